"""Raw triaxial curves as instruments export them: failure = the peak of the deviator stress q.

The curves come as one long table (with a ``test_id`` column), one file per
test, a folder of such files or a glob. Usual export headers are understood
(``Axial Strain (%)``, ``Deviator Stress (kPa)``, ``Radial Pressure (kPa)``,
``Volumetric Strain (%)``, ``Axial Force (kN)``), with a metadata block and a
units row (see capred.io.table). Where only the axial force is given,
q = F / A with the area of a right cylinder that deforms at constant volume
change, A = A0 (1 - eps_v)/(1 - eps_a) (A0/(1 - eps_a) without eps_v),
A0 = pi D0^2/4; the initial diameter D0 (and height H0) come from the tests
table (columns ``D0``, ``H0``) or from the file's metadata. The test id is a
metadata key (``Test ID``, ``Test``, ``Sample``) or else the file name.
"""
from __future__ import annotations

import glob
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, Problem
from ..io.grid import SPREADSHEET_SUFFIXES, source_path
from ..io.table import Column, Table, _key, read_table
from ..units import parse_quantity

SCHEMA = [
    Column("test_id", "text", None, "test identifier", ("id", "test", "sample_id", "sample")),
    Column("axial_strain", "dimensionless", "-", "axial strain",
           ("eps_a", "eps1", "epsilon_1", "axial_strain_pct", "ea", "strain")),
    Column("q", "pressure", "kPa", "q", ("deviator", "q_kpa", "deviatoric_stress", "deviator_stress",
                                         "deviatoric_stress_q", "deviator_stress_q")),
    Column("vol_strain", "dimensionless", "-", "volumetric strain",
           ("eps_v", "epsilon_v", "volumetric_strain", "volume_strain", "ev")),
    Column("axial_force", "force", "kN", "axial force", ("force", "axial_load", "load", "deviator_force")),
    Column("radial_pressure", "pressure", "kPa", "radial (cell) pressure",
           ("cell_pressure", "confining_pressure", "radial_stress", "sigma3", "radial_pressure_kpa")),
]
_ID_KEYS = ("test_id", "test", "sample", "sample_id", "specimen", "test_name")
_D0_KEYS = ("initial_diameter", "diameter", "d0", "sample_diameter", "specimen_diameter")
_H0_KEYS = ("initial_height", "height", "h0", "sample_height", "specimen_height")
_KEY_UNIT = re.compile(r"^(?P<name>.*?)\s*[\[(]\s*(?P<unit>[^\])]+?)\s*[\])]\s*$")


@dataclass
class TriaxialCurves:
    peaks: dict[str, tuple[float, float]] = field(default_factory=dict)  # test id -> (q_peak [Pa], eps_a at peak)
    tables: list[Table] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)


def curve_files(spec) -> list:
    """The files a --curves value names: a file, a folder (its .csv, .xlsx, .ods files) or a glob."""
    path = source_path(spec)
    if hasattr(path, "to_csv"):
        return [spec]
    text = str(path)
    p = Path(text)
    if p.is_dir():
        files = sorted(f for f in p.iterdir() if f.suffix.lower() in (".csv", ".txt", ".tsv") + SPREADSHEET_SUFFIXES)
        if not files:
            raise InputError(Problem(text, None, None, "the folder holds no .csv, .xlsx or .ods curve files"))
        return files
    if any(ch in text for ch in "*?[") and not p.exists():
        files = [Path(f) for f in sorted(glob.glob(text, recursive=True))]
        if not files:
            raise InputError(Problem(text, None, None, "no file matches this pattern"))
        return files
    return [spec]


def _meta(metadata: dict[str, str], keys) -> tuple[str, str] | None:
    """(value, unit in the key) of the first metadata key among ``keys`` (spelling-insensitive)."""
    for key, value in metadata.items():
        m = _KEY_UNIT.match(key)
        name, unit = (m.group("name"), m.group("unit")) if m else (key, "")
        if _key(name) in keys:
            return value, unit
    return None


def _length(value: str, unit: str) -> float | None:
    try:
        return parse_quantity(value.strip(), unit or "mm", "length")
    except Exception:
        return None


def read_curves(spec, tests: Table | None = None) -> TriaxialCurves:
    """Peak q and the axial strain at the peak of every test's curve."""
    out = TriaxialCurves()
    d0_col = {str(t): d for t, d in zip(tests.columns.get("test_id", []), tests.get("D0"))} if tests is not None else {}
    for f in curve_files(spec):
        table = read_table(f, SCHEMA)
        out.tables.append(table)
        out.warnings += table.warnings
        has_q, has_force = "q" in table.columns, "axial_force" in table.columns
        if not (has_q or has_force):
            table.missing_column("q", " (or 'axial_force' with the initial diameter D0)")
        if table.missing:
            out.problems += table.problems
            continue
        if "test_id" in table.columns:
            ids = table.columns["test_id"]
        else:
            found = _meta(table.metadata, _ID_KEYS)
            tid = found[0] if found and found[0] else Path(str(source_path(f))).stem
            ids = np.array([tid] * len(table), dtype=object)
        eps = table.get("axial_strain")
        for tid in dict.fromkeys(ids):
            sel = np.flatnonzero(ids == tid)
            q = table.get("q")[sel].copy()
            if not np.isfinite(q).any() and has_force:
                D0 = d0_col.get(str(tid), np.nan)
                if not np.isfinite(D0):
                    found = _meta(table.metadata, _D0_KEYS)
                    D0 = _length(*found) if found else None
                if D0 is None or not np.isfinite(D0) or D0 <= 0:
                    table.add_problem(int(sel[0]), "axial_force", f"test '{tid}': q from the axial force needs the "
                                      "initial diameter: a column 'D0' in the tests table or a metadata line "
                                      "'Initial diameter (mm): ...'")
                    continue
                ea = eps[sel]
                ev = table.get("vol_strain")[sel]
                area = np.pi * D0**2 / 4 * np.where(np.isfinite(ev), 1.0 - ev, 1.0) / (1.0 - ea)
                q = table.columns["axial_force"][sel] / area
                out.notes.append(f"test '{tid}': q = F/A with A = A0 (1 - eps_v)/(1 - eps_a), D0 = {D0 * 1e3:.4g} mm")
            ok = np.isfinite(q)
            if not ok.any():
                table.add_problem(int(sel[0]), "q" if has_q else "axial_force", f"test '{tid}' has no q values")
                continue
            k = sel[ok][int(np.argmax(q[ok]))]
            if str(tid) in out.peaks:
                table.add_problem(int(sel[0]), "test_id", f"a second curve for test '{tid}'")
                continue
            out.peaks[str(tid)] = (float(np.max(q[ok])), float(eps[k]))
        out.problems += table.problems
    return out
