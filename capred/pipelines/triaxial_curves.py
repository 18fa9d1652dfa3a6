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

The pressures an export logs beside the curve (``Radial Pressure``, ``Back
Pressure``, ``Pore Pressure``, ``Pore Air Pressure``) are kept at the peak:
the tests table's sigma3 is checked against the radial pressure, and the
pore pressures turn total stresses into effective (saturated) or net
(unsaturated, axis translation) ones. With a membrane (thickness t_m,
modulus E_m) the deviator of every reading is corrected before the peak is
taken (:func:`membrane_correction`).
"""

from __future__ import annotations

import glob
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, Problem
from ..io import SPREADSHEET_SUFFIXES, Column, Table, header_key, read_table, source_path
from ..nomenclature import column_aliases
from ..units import parse_quantity
from .triaxial_records import Curve

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column(
        "axial_strain",
        "dimensionless",
        "-",
        "axial strain",
        ("eps_a", "eps1", "epsilon_1", "axial_strain_pct", "ea", "strain"),
    ),
    Column(
        "q",
        "pressure",
        "kPa",
        "q",
        ("deviator", "q_kpa", "deviatoric_stress", "deviator_stress", "deviatoric_stress_q", "deviator_stress_q"),
    ),
    Column(
        "vol_strain",
        "dimensionless",
        "-",
        "volumetric strain",
        ("eps_v", "epsilon_v", "volumetric_strain", "volume_strain", "ev"),
    ),
    Column("axial_force", "force", "kN", "axial force", ("force", "axial_load", "load", "deviator_force")),
    Column(
        "radial_pressure",
        "pressure",
        "kPa",
        "radial (cell) pressure",
        ("cell_pressure", "confining_pressure", "radial_stress", "sigma3", "radial_pressure_kpa"),
    ),
    Column("back_pressure", "pressure", "kPa", "back pressure", ("backpressure", "u_b", "back_pressure_kpa")),
    Column(
        "pore_pressure",
        "pressure",
        "kPa",
        "pore (water) pressure",
        ("pore_water_pressure", "u_w", "pwp", "base_pore_pressure", "pore_pressure_kpa"),
    ),
    Column("air_pressure", "pressure", "kPa", "pore-air pressure", ("pore_air_pressure", "u_a", "air_pressure_kpa")),
]
#: Standard columns of a GDS-style triaxial export (GDSLAB data files) that capred does not need: they are known,
#: read as text and never warned about as "not used". This is the one list; a column capred uses (axial strain,
#: deviator stress, axial force, radial, back and pore pressures, volumetric strain, stage number) is in SCHEMA.
EXPORT_COLUMNS = (
    "Time since start of test",
    "Time since start of stage",
    "Date and time",
    "Radial Volume",
    "Back Volume",
    "Base Volume",
    "Base Pressure",
    "Load Cell",
    "Axial Displacement",
    "Axial Displacement 2",
    "Av Diameter Change",
    "Radial Strain",
    "Axial Stress",
    "Eff. Axial Stress",
    "Eff. Radial Stress",
    "Total Stress Ratio",
    "Eff. Stress Ratio",
    "Current Area",
    "Shear Strain",
    "Cambridge p",
    "Eff. Cambridge p'",
    "Max Shear Stress t",
    "Mean Stress s",
    "Eff. Mean Stress s'",
    "Mean Stress s/Eff. Axial Stress 2",
    "Volume Change",
    "Local Axial 1",
    "Local Axial 2",
    "Local Radial",
    "Lower Chamber Pressure",
    "Lower Chamber Volume",
    "Excess PWP",
    "PWP Ratio",
    "L/C Pressure",
    "L/C Volume",
    "Back Differential Pressure",
    "Pore Air Volume",
    "Atmospheric Pressure",
    "Temperature",
    "Mid Plane PWP",
    "Back to Cell Differential",
    "Total Volume Change",
    "Undefined Tx 1",
    "Undefined Tx 2",
    "Undefined Tx 3",
    "Lower Chamber Displacement",
    "Lower Chamber Axial Load",
    "Specimen Air Volume",
    "Specimen Water Volume",
    "kRT constant",
    "Permeability IN",
    "Permeability OUT",
)
SCHEMA += [
    Column("stage", "text", None, "stage number of the export", ("stage_number", "stage_no", "stage_nr")),
    # GDSLAB's running ratio of the pore-pressure change to the cell-pressure change since the stage began: B only
    # at the end of a B check (read there, see b_check); in the shear stage a number without meaning
    Column("B", "dimensionless", "-", "Skempton's pore-pressure coefficient B", ("b_value", "skempton_b")),
    # the state of an unsaturated specimen as the export logs it (GDSLAB's unsaturated module)
    Column("suction", "pressure", "kPa", "matric suction u_a - u_w", ("matric_suction",)),
    Column("S_R", "dimensionless", "-", "degree of saturation", ("degree_of_saturation", "s_r", "saturation_degree")),
    Column("void_ratio", "dimensionless", "-", "void ratio", ("voids_ratio", "e")),
]
# known and not used: their absence changes nothing, so a near miss of one is no reason to stop a run
SCHEMA += [
    Column(header_key(name), "text", None, f"{name} (instrument export; not used)", (), decisive=False)
    for name in EXPORT_COLUMNS
]

#: the pressures read at the peak of a curve (an export's columns)
PEAK_PRESSURES = ("radial_pressure", "back_pressure", "pore_pressure", "air_pressure")
#: the state of an unsaturated specimen an export logs, kept at the start of the shear stage and at the peak
EXPORT_STATE = ("suction", "S_R", "void_ratio")
_ID_KEYS = tuple(header_key(k) for k in ("test_id", *column_aliases("test_id")))
_D0_KEYS = ("initial_diameter", "diameter", "d0", "sample_diameter", "specimen_diameter")
_H0_KEYS = ("initial_height", "height", "h0", "sample_height", "specimen_height")
_KEY_UNIT = re.compile(r"^(?P<name>.*?)\s*[\[(]\s*(?P<unit>[^\])]+?)\s*[\])]\s*$")


def pressure_tolerance(pressure):
    """Tolerance [Pa] of a cell or back pressure: 2 kPa below 200 kPa, 1 % above.

    The accuracy ASTM D4767-11 (section 5, pressure-control devices;
    doi:10.1520/D4767-11) asks of the devices that apply the chamber and back
    pressures; two readings of one pressure that differ by more are two
    different pressures.

    Parameters
    ----------
    pressure : float or array_like
        Cell or back pressure [Pa].

    Returns
    -------
    float or ndarray
        Tolerance [Pa], same shape.
    """
    return np.maximum(2e3, 0.01 * np.abs(pressure))


def membrane_correction(axial_strain, diameter, membrane_thickness, membrane_modulus):
    r"""Deviator stress carried by a rubber membrane in triaxial compression.

    Parameters
    ----------
    axial_strain : numeric
        Axial strain :math:`\varepsilon_1` [-] (compression positive).
    diameter : numeric
        Specimen diameter :math:`D_c` after consolidation [m] (capred takes
        the initial diameter D0).
    membrane_thickness : float
        Membrane thickness :math:`t_m` [m].
    membrane_modulus : float
        Young's modulus of the membrane :math:`E_m` [Pa] (about 1400 kPa for
        latex).

    Returns
    -------
    numeric
        :math:`\Delta(\sigma_1 - \sigma_3)` [Pa], to subtract from the
        measured deviator.

    Notes
    -----
    The membrane as a thin cylindrical shell shortened with the specimen
    (the theory of Henkel & Gilbert 1952), the correction of ASTM D4767-11
    (membrane correction of the deviator stress):

    .. math::

       \Delta(\sigma_1 - \sigma_3) = \frac{4 E_m t_m \varepsilon_1}{D_c}

    BS 1377-8:1990 gives a correction of the same kind as a chart (a 0.2 mm
    membrane on a 38 mm specimen, scaled by thickness and diameter); capred
    applies the formula. It holds while the specimen shortens as a cylinder
    (no barrelling beyond the strain of the chart's break).

    References
    ----------
    .. [1] ASTM D4767-11 (2011). Standard Test Method for Consolidated
       Undrained Triaxial Compression Test for Cohesive Soils. ASTM
       International. doi:10.1520/D4767-11 (membrane correction).
    .. [2] Henkel, D. J. & Gilbert, G. D. (1952). The effect of the rubber
       membrane on the measured triaxial compression strength of clay
       samples. Geotechnique 3(1), 20-29.
    """
    return 4.0 * membrane_modulus * membrane_thickness * np.asarray(axial_strain, float) / np.asarray(diameter, float)


@dataclass
class TriaxialCurves:
    """What the curves of a triaxial export give the triaxial commands: each test's peak and state there.

    Each field is described where it is declared: the peak (q and axial strain) and the pressures at it per test
    id, the curve tables, and the problems, notes and warnings of the reading.
    """

    peaks: dict[str, tuple[float, float]] = field(default_factory=dict)  # test id -> (q_peak [Pa], eps_a at peak)
    #: test id -> pressures at the peak [Pa] (keys of PEAK_PRESSURES, NaN where the export has none),
    #: "membrane" (the correction at the peak [Pa]) and "D0" [m]
    at_peak: dict[str, dict[str, float]] = field(default_factory=dict)
    tables: list[Table] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: test id -> its shear-stage readings in kPa and strains [-] (capred.pipelines.triaxial_records.Curve)
    curves: dict = field(default_factory=dict)
    #: header keys of the ignore_columns names some curve file had (capred.io.Table.forget_ignores)
    ignores_used: set = field(default_factory=set)


def curve_files(spec) -> list:
    """The files a --curves value names: a file, a folder (its .csv, .xlsx, .ods files) or a glob.

    Parameters
    ----------
    spec : str or Path or DataFrame
        The value of --curves (a DataFrame is returned as it is).

    Returns
    -------
    list
        The files, sorted.

    Raises
    ------
    InputError
        Where a folder or glob names no curve file.
    """
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
        if header_key(name) in keys:
            return value, unit
    return None


def _length(value: str, unit: str) -> float | None:
    try:
        return parse_quantity(value.strip(), unit or "mm", "length")
    except Exception:
        return None


def _shear_stage(table: Table, sel: np.ndarray, tid: str, notes: list[str]) -> np.ndarray:
    """The rows of ``sel`` in the shear stage of an export with a ``Stage Number`` column.

    An export logs every stage of a test (saturation, B check, consolidation, shear) in one file. The shear
    stage is the one in which the deviator rises most (its largest q, or axial force, minus its first): the
    other stages hold q near constant. Blank stage cells belong to no stage and are left out.
    """
    stage = np.array([str(x).strip() for x in table.columns["stage"][sel]], dtype=object)
    names = [x for x in dict.fromkeys(stage) if x not in ("", "nan", "None")]
    if len(names) <= 1:
        return sel[stage != ""] if names else sel
    load = table.get("q") if "q" in table.columns else table.get("axial_force")

    def rise(name: str) -> float:
        v = load[sel[stage == name]]
        v = v[np.isfinite(v)]
        return float(v.max() - v[0]) if v.size else -np.inf

    best = max(names, key=lambda n: (rise(n), names.index(n)))  # ties: the later stage
    notes.append(
        f"test '{tid}': stage {best} of stages {', '.join(names)} taken as the shear stage "
        "(the deviator rises most in it; column 'Stage Number')"
    )
    return sel[stage == best]


def b_check(table: Table, rows: np.ndarray, shear: np.ndarray, tid: str) -> dict:
    """Skempton's B of a test from the B-check stage of its export, and how it was found.

    A B check closes the drainage and raises the cell pressure: B = Δu/Δσ3 over the stage (Skempton 1954),
    first reading to last. The B-check stage is the last stage before the shear stage in which the cell
    pressure rises and the pore pressure rises with it (both by more than the pressure tolerance of ASTM
    D4767, pressure_tolerance) while the back pressure holds: a saturation ramp
    moves the back pressure with the cell, and a consolidation ends with the excess pore pressure gone. The
    export's running ``B Value`` column is not read as B (in the shear stage it is Δu over the cell's creep);
    where it logs a value at the end of the B check that differs from Δu/Δσ3 by more than 0.02, a warning
    names both.

    Parameters
    ----------
    table : Table
        The export (columns stage, radial_pressure, pore_pressure, optional back_pressure and B) [Pa].
    rows : ndarray of int
        The test's rows, every stage.
    shear : ndarray of int
        The rows of its shear stage.
    tid : str
        The test id (for messages).

    Returns
    -------
    dict
        ``B`` [-] (NaN: none found or outside (0, 1]), ``source`` ("b_check", "none" or "invalid"), ``note``
        and ``warning`` (str or None).

    References
    ----------
    .. [1] Skempton, A. W. (1954). The pore-pressure coefficients A and B. Geotechnique 4(4), 143-147.
       doi:10.1680/geot.1954.4.4.143
    .. [2] ASTM D4767-11, section 8.2 (B check of saturation). doi:10.1520/D4767-11
    """
    out = {"B": float("nan"), "source": "none", "note": None, "warning": None}
    if "stage" not in table.columns or "pore_pressure" not in table.columns or "radial_pressure" not in table.columns:
        return out
    stage = np.array([str(x).strip() for x in table.columns["stage"][rows]], dtype=object)
    start = int(shear[0]) if len(shear) else int(rows[-1]) + 1
    cell, pore, back = (table.get(k)[rows] for k in ("radial_pressure", "pore_pressure", "back_pressure"))
    found = None
    for name in dict.fromkeys(stage[rows < start]):
        if name in ("", "nan", "None"):
            continue
        k = np.flatnonzero((stage == name) & (rows < start))
        c, u, b = cell[k][np.isfinite(cell[k])], pore[k][np.isfinite(pore[k])], back[k][np.isfinite(back[k])]
        if c.size < 2 or u.size < 2:
            continue
        ds3, du = c[-1] - c[0], u[-1] - u[0]
        holds = b.size < 2 or abs(b[-1] - b[0]) <= pressure_tolerance(b[-1])
        if ds3 > pressure_tolerance(c[-1]) and du > pressure_tolerance(u[-1]) and holds:
            found = (name, k, ds3, du)
    if found is None:
        return out
    name, k, ds3, du = found
    B = du / ds3
    what = f"stage {name}: Δu = {du / 1e3:.4g} kPa over Δσ3 = {ds3 / 1e3:.4g} kPa"
    logged = table.get("B")[rows[k]]
    logged = logged[np.isfinite(logged)]
    if logged.size and abs(logged[-1] - B) > 0.02:
        out["warning"] = (
            f"test '{tid}': the B check ({what}) gives B = {B:.3g} but the export's B Value at its end is "
            f"{logged[-1]:.4g}; capred uses Δu/Δσ3 = {B:.3g} (Skempton 1954)"
        )
    if not 0 < B <= 1:
        out.update(source="invalid")
        out["warning"] = (
            f"test '{tid}': the B check of the export ({what}) gives B = {B:.3g}, outside (0, 1]: Skempton's A is "
            "not computed for this test; give its B in the tests table (column 'B') to compute it"
        )
        return out
    out.update(B=float(B), source="b_check", note=f"test '{tid}': Skempton's B = {B:.3g} from the B check ({what})")
    return out


#: The physical domain of each export state: an export's value outside it is not a measurement of the specimen
#: (GDSLAB writes -u_w as "Matric Suction", 0 as "Voids ratio" and a negative "Degree of Saturation" when the
#: specimen's phase data were never entered) and is not taken.
EXPORT_STATE_DOMAIN = {
    "suction": (lambda v: v >= 0.0, "a matric suction is not negative"),
    "S_R": (lambda v: (v >= 0.0) & (v <= 1.0), "a degree of saturation lies in [0, 1]"),
    "void_ratio": (lambda v: v > 0.0, "a void ratio is positive"),
}


def _strains_in_percent(table: Table, notes: list[str]) -> None:
    """Read a strain column without a unit in per cent when its readings are impossible as fractions.

    A strain above 1 (100 %) in compression is impossible, so a unitless strain column that exceeds it is in per
    cent, as GDSLAB and most triaxial software write strains; it is converted in place, with a note. A column
    whose unit says [-] and that exceeds 1 is an error naming it.
    """
    for name in ("axial_strain", "vol_strain"):
        if name not in table.columns:
            continue
        values = table.columns[name]
        finite = values[np.isfinite(values)]
        if not finite.size or np.max(np.abs(finite)) <= 1.0:
            continue
        largest = float(finite[np.argmax(np.abs(finite))])
        header = table.headers[name]
        if name in table.unit_given:
            table.add_problem(
                None,
                name,
                f"column '{header}' reaches {largest:.4g} in {table.units[name]!r}: a strain above 1 (100 %) "
                f"is impossible; if the column is in per cent, write its unit ('{header} (%)')",
            )
            continue
        table.columns[name] = values / 100.0
        notes.append(
            f"column '{header}' has no unit and reaches {largest:.4g}, impossible as a fraction (above 100 %): "
            f"read in per cent, as GDSLAB and most triaxial software write strains (write '{header} (%)' to say so)"
        )


def export_states(table: Table, at_peak: dict) -> tuple[dict[str, np.ndarray], list[str], list[str]]:
    """Matric suction, degree of saturation and void ratio at failure of every test, from its export.

    The tests table's own column (``suction``, ``S_R``, ``void_ratio``, where its schema has one) wins; a blank
    is filled with the export's value at the peak of the curve, and a note says which were taken. An export's
    value outside its physical domain (:data:`EXPORT_STATE_DOMAIN`) is not taken, and a warning says so.

    Parameters
    ----------
    table : Table
        The tests table (test_id).
    at_peak : dict
        Test id -> the export's values at the peak (read_curves' ``at_peak``: suction [Pa], S_R and
        void_ratio [-]).

    Returns
    -------
    values : dict of str to ndarray
        ``suction`` [Pa], ``S_R`` [-], ``void_ratio`` [-] per test (NaN where neither gives one).
    notes : list of str
    warnings : list of str
    """
    tids = [str(t) for t in table.columns["test_id"]]
    out, notes, warnings = {}, [], []
    for name, words in zip(EXPORT_STATE, ("matric suction", "degree of saturation", "void ratio")):
        v = table.get(name).copy()
        exp = np.array([at_peak.get(t, {}).get(name, np.nan) for t in tids])
        inside, rule = EXPORT_STATE_DOMAIN[name]
        with np.errstate(invalid="ignore"):
            bad = np.isnan(v) & np.isfinite(exp) & ~inside(exp)
        for i in np.flatnonzero(bad):
            shown = exp[i] / 1e3 if name == "suction" else exp[i]
            unit = " kPa" if name == "suction" else ""
            warnings.append(
                f"test '{tids[i]}': the export's {words} at failure is {shown:.4g}{unit}, outside its physical "
                f"domain ({rule}): not a measurement of the specimen, not taken"
            )
        took = np.isnan(v) & np.isfinite(exp) & ~bad
        v[took] = exp[took]
        out[name] = v
        if took.any():
            notes.append(f"{words} at failure taken from the export: {', '.join(np.array(tids)[took])}")
    return out, notes, warnings


def _initial_diameter(table: Table, tid, d0_col: dict) -> float:
    """D0 [m] of a test: the tests table's, else the curve file's metadata; NaN where unknown or not > 0."""
    D0 = d0_col.get(str(tid), np.nan)
    if not np.isfinite(D0):
        found = _meta(table.metadata, _D0_KEYS)
        D0 = _length(*found) if found else None
    return np.nan if D0 is None or not np.isfinite(D0) or D0 <= 0 else float(D0)


def _state_at_peak(
    table: Table,
    tid,
    every: np.ndarray,
    sel: np.ndarray,
    k: int,
    q: np.ndarray,
    ok: np.ndarray,
    dq,
    D0: float,
    out: TriaxialCurves,
) -> dict:
    """The export's pressures at the peak reading ``k`` and their changes over the shear stage [Pa].

    With the B check, the specimen's state at the start of the shear and at the peak, the membrane correction there [Pa]
    and D0 [m].

    The B check's note and warning are added to ``out``.
    """
    state = {name: float(table.get(name)[k]) for name in PEAK_PRESSURES}
    # changes over the stage, first reading to the peak, for Skempton's A (Skempton 1954)
    first = int(sel[0])
    state["du"] = float(table.get("pore_pressure")[k] - table.get("pore_pressure")[first])
    u_stage = table.get("pore_pressure")[sel]
    u_stage = u_stage[np.isfinite(u_stage)]  # how far the pore pressure moved in the stage: ~0 when drained
    state["du_range"] = float(np.ptp(u_stage)) if u_stage.size else float("nan")
    state["dsigma3"] = float(table.get("radial_pressure")[k] - table.get("radial_pressure")[first])
    state["dq"] = float(np.max(q[ok]) - q[0]) if np.isfinite(q[0]) else float("nan")
    b = b_check(table, every, sel, str(tid))  # never the shear stage's running B Value
    state["B"], state["B_source"] = b["B"], b["source"]
    out.notes += [b["note"]] if b["note"] else []
    out.warnings += [b["warning"]] if b["warning"] else []
    for name in EXPORT_STATE:  # an unsaturated specimen's state: at the start of the shear and at the peak
        v = table.get(name)[sel]
        ok_v = np.flatnonzero(np.isfinite(v))
        state[name + "_initial"] = float(v[ok_v[0]]) if ok_v.size else float("nan")
        state[name] = float(table.get(name)[k])
    state["membrane"] = float(dq[int(np.flatnonzero(sel == k)[0])])
    state["D0"] = D0
    return state


def _read_test_curve(
    table: Table,
    out: TriaxialCurves,
    tid,
    every: np.ndarray,
    sel: np.ndarray,
    D0: float,
    membrane: tuple[float, float] | None,
    consolidated: dict | None,
) -> None:
    """One test's curve (readings ``sel`` of its shear stage, ``every`` of the file), added to ``out``.

    q from the axial force where the file has no q, the membrane correction, then its peak, curve and state at the peak.

    Problems are added to ``table`` (the test is then left out).
    """
    has_q, has_force = "q" in table.columns, "axial_force" in table.columns
    eps = table.get("axial_strain")
    q = table.get("q")[sel].copy()
    if not np.isfinite(q).any() and has_force:
        if not np.isfinite(D0):
            table.add_problem(
                int(sel[0]),
                "axial_force",
                f"test '{tid}': q from the axial force needs the "
                "initial diameter: a column 'D0' in the tests table or a metadata line "
                "'Initial diameter (mm): ...'",
            )
            return
        ea = eps[sel]
        ev = table.get("vol_strain")[sel]
        area = np.pi * D0**2 / 4 * np.where(np.isfinite(ev), 1.0 - ev, 1.0) / (1.0 - ea)
        q = table.columns["axial_force"][sel] / area
        out.notes.append(f"test '{tid}': q = F/A with A = A0 (1 - eps_v)/(1 - eps_a), D0 = {D0 * 1e3:.4g} mm")
    dq = np.zeros(len(sel))
    if membrane is not None:
        if not np.isfinite(D0):
            table.add_problem(
                int(sel[0]),
                "axial_strain" if "axial_strain" in table.columns else None,
                f"test '{tid}': the membrane correction needs the diameter: a column 'D0' in "
                "the tests table or a metadata line 'Initial diameter (mm): ...'",
            )
            return
        if "axial_strain" not in table.columns:
            table.add_problem(
                int(sel[0]),
                None,
                f"test '{tid}': the membrane correction needs the axial "
                "strain of every reading (column 'axial_strain')",
            )
            return
        dc = (consolidated or {}).get(str(tid), np.nan)
        dc_known = dc is not None and np.isfinite(dc) and dc > 0
        diameter_source = "D_c" if dc_known else "D0"
        dq = membrane_correction(np.where(np.isfinite(eps[sel]), eps[sel], 0.0), dc if dc_known else D0, *membrane)
        q = q - dq
    ok = np.isfinite(q)
    if not ok.any():
        table.add_problem(int(sel[0]), "q" if has_q else "axial_force", f"test '{tid}' has no q values")
        return
    k = sel[ok][int(np.argmax(q[ok]))]
    if str(tid) in out.peaks:
        table.add_problem(int(sel[0]), "test_id", f"a second curve for test '{tid}'")
        return
    out.peaks[str(tid)] = (float(np.max(q[ok])), float(eps[k]))
    out.curves[str(tid)] = Curve(
        str(tid),
        eps[sel].copy(),
        q / 1e3,
        table.get("vol_strain")[sel].copy(),
        int(np.flatnonzero(sel == k)[0]),
    )
    state = _state_at_peak(table, tid, every, sel, k, q, ok, dq, D0, out)
    if membrane is not None:
        state["diameter_source"] = diameter_source
    out.at_peak[str(tid)] = state


def read_curves(
    spec,
    tests: Table | None = None,
    membrane: tuple[float, float] | None = None,
    consolidated: dict | None = None,
    ignore_columns=(),
) -> TriaxialCurves:
    """Peak q and the axial strain at the peak of every test's curve.

    ``membrane`` = (thickness [m], modulus [Pa]) corrects every reading's q
    by :func:`membrane_correction` before the peak is taken, with the
    diameter after consolidation ``consolidated[test_id]`` [m] (from the tests
    table: capred.pipelines.triaxial.consolidated_diameter) where known, else
    the initial D0 of the tests table or of the file's metadata (``at_peak``
    records which: ``diameter_source`` "D_c" or "D0").

    Parameters
    ----------
    spec : str or Path or DataFrame
        The curves: a file, a folder or a glob (see :func:`curve_files`).
    tests : Table, optional
        The tests table (its D0 per test).
    membrane : tuple of float, optional
        (thickness [m], Young's modulus [Pa]) of the membrane; None: no correction.
    consolidated : dict, optional
        Test id -> diameter after consolidation [m].
    ignore_columns : sequence of str, optional
        Columns to leave out of every curve file (CLI ``--ignore-column``, the command's list); a name no curve
        file has is not warned about here (``ignores_used`` tells the caller which ones some file had).

    Returns
    -------
    TriaxialCurves
        Per test the peak (q [Pa], axial strain [-]), the pressures at the peak [Pa] and the readings.

    References
    ----------
    .. [1] ASTM D4767-11, Standard test method for consolidated undrained triaxial compression test for
       cohesive soils. doi:10.1520/D4767-11
    """
    out = TriaxialCurves()
    d0_col = {str(t): d for t, d in zip(tests.columns.get("test_id", []), tests.get("D0"))} if tests is not None else {}
    for f in curve_files(spec):
        table = read_table(f, SCHEMA, ignore_columns=ignore_columns)
        out.ignores_used |= table.ignores_used
        table.forget_ignores()  # the command's first file warns about a name no file has
        out.tables.append(table)
        out.warnings += table.warnings
        out.notes += table.notes  # what the reading says (a column ignored as asked, a note under the data)
        if not ("q" in table.columns or "axial_force" in table.columns):
            table.missing_column("q", " (or 'axial_force' with the initial diameter D0)")
        _strains_in_percent(table, out.notes)
        if table.missing or table.problems:
            out.problems += table.problems
            continue
        if "test_id" in table.columns:
            ids = table.columns["test_id"]
        else:
            found = _meta(table.metadata, _ID_KEYS)
            tid = found[0] if found and found[0] else Path(str(source_path(f))).stem
            ids = np.array([tid] * len(table), dtype=object)
        for tid in dict.fromkeys(ids):
            every = sel = np.flatnonzero(ids == tid)
            if "stage" in table.columns:
                sel = _shear_stage(table, sel, str(tid), out.notes)
            D0 = _initial_diameter(table, tid, d0_col)
            _read_test_curve(table, out, tid, every, sel, D0, membrane, consolidated)
        out.problems += table.problems
    return out
