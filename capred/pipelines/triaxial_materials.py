"""What `capred triaxial-bounds` shares with `capred triaxial` (issue 40).

The ``material`` column (one material per analysis, never pooled) and the envelope at s -> 0 of the unsaturated tests
when there is no saturated test.

`capred triaxial` analyses every material of its table separately. `capred triaxial-bounds` fits ONE effective
envelope per run, so a table with several materials runs one of them at a time (``--material NAME``); without it,
a table of several materials is refused with the list of materials, rather than pooled into one envelope.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from ..errors import FitError, InputError, OptionError, Problem
from ..io import Table
from .triaxial_records import KPA, Envelope


def materials_of(table: Table) -> dict[str, int]:
    """{material: number of tests} in table order (blank cells count as "" ); {} without a material column.

    Parameters
    ----------
    table : capred.io.Table

    Returns
    -------
    dict of str to int
    """
    if not table.has("material"):
        return {}
    out: dict[str, int] = {}
    for v in table.columns["material"]:
        out[str(v)] = out.get(str(v), 0) + 1
    return out


class _Picked(Sequence):
    """The cells ``cells[idx]`` of a column's text, each read when a message quotes it.

    A long file's cells are cut out of its text on demand (capred.io.plain_tail).
    """

    def __init__(self, cells, idx: np.ndarray):
        self.cells, self.idx = cells, idx

    def __len__(self) -> int:
        return len(self.idx)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self.cells[int(k)] for k in self.idx[i]]
        return self.cells[int(self.idx[i])]


def subset_rows(table: Table, keep: np.ndarray) -> Table:
    """The same table restricted to the rows ``keep`` (a boolean mask); file lines and raw cells kept.

    Parameters
    ----------
    table : capred.io.Table
    keep : numpy.ndarray of bool

    Returns
    -------
    capred.io.Table
    """
    keep = np.asarray(keep, bool)
    idx = np.flatnonzero(keep)
    return dataclasses.replace(
        table,
        columns={k: np.asarray(v)[keep] for k, v in table.columns.items()},
        raw={k: _Picked(v, idx) for k, v in table.raw.items()},
        lines=np.asarray(table.lines)[keep],
        as_read={k: np.asarray(v)[keep] for k, v in table.as_read.items()},
        notes=list(table.notes),
        problems=list(table.problems),
        warnings=list(table.warnings),
    )


def one_material(table: Table, material: str | None) -> tuple[Table, str | None]:
    """The rows of one material of a triaxial table, for an analysis that fits one envelope.

    Parameters
    ----------
    table : capred.io.Table
        As read (``material`` column optional).
    material : str or None
        The material asked for (``--material``); None: the table must hold a single material.

    Returns
    -------
    (Table, str or None)
        The rows of that material and its name (None when the table has no material column).

    Raises
    ------
    InputError
        Several materials and none chosen (the message lists them with their number of tests).
    OptionError
        ``material`` given for a table without a material column, or not among its materials.
    """
    found = materials_of(table)
    if not found:
        if material is not None:
            raise OptionError(f"--material {material!r}: {table.path} has no material column")
        return table, None
    if material is None:
        named = [m for m in found if m]
        if len(found) == 1 or (len(named) <= 1 and "" not in found):
            return table, next(iter(found))
        listed = ", ".join(f"'{m}' ({n} tests)" if m else f"blank ({n} tests)" for m, n in found.items())
        raise InputError(
            Problem(
                table.path,
                table.header_line,
                table.headers.get("material", "material"),
                f"{len(found)} materials in one table ({listed}): triaxial-bounds fits one effective envelope per "
                "run and never pools materials; run it once per material with --material NAME, or use "
                "`capred triaxial`, which analyses every material separately",
                table.sheet,
            )
        )
    if material not in found:
        raise OptionError(f"--material {material!r} is not in {table.path}; its materials: {', '.join(found)}")
    return subset_rows(table, np.asarray(table.columns["material"], dtype=object) == material), material


def zero_suction_envelope(sigma3, sigma1, s0, branch, confidence: float = 0.95):
    """The effective envelope of a triaxial-bounds run without saturated tests: the extended fit at s -> 0.

    q_f = (K_p - 1) σ3 + 2 √K_p (c' + s tan φ_b) (compression; the extension form with the cell pressure as the
    major stress), fitted with proportional errors (`capred.fitting.extended_mc`), s0 standing for the suction at
    failure (Prunier et al.'s drained tests at constant water content do not measure it).

    Parameters
    ----------
    sigma3, sigma1 : ndarray
        Minor and major net principal stresses at failure of the unsaturated tests [Pa].
    s0 : ndarray
        Their initial suction [Pa].
    branch : ndarray of str
        ``"compression"`` or ``"extension"`` per test (one branch for all).
    confidence : float
        Level of the intervals.

    Returns
    -------
    capred.pipelines.triaxial.Envelope
        ``source="extended_mc"``, with standard errors and the c'-φ' correlation (delta method).

    Raises
    ------
    FitError
        s0 missing, several branches, or failure states that do not determine the plane (one suction only,
        fewer than 4 tests).

    References
    ----------
    .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). Can. Geotech. J. 15(3):313-321,
       doi:10.1139/t78-029.
    """
    from ..fitting.extended_mc import fit_extended_mc

    s0 = np.asarray(s0, float)
    if not np.all(np.isfinite(s0)):
        raise FitError(f"{int(np.sum(~np.isfinite(s0)))} unsaturated test(s) without s0")
    forms = set(np.asarray(branch, dtype=object).tolist())
    if len(forms) != 1 or not forms <= {"compression", "extension"}:
        raise FitError(f"one branch, compression or extension, is needed (got {', '.join(map(str, sorted(forms)))})")
    form = forms.pop()
    sigma3, sigma1 = np.asarray(sigma3, float), np.asarray(sigma1, float)
    x = sigma3 if form == "compression" else sigma1
    fit = fit_extended_mc(x, s0, sigma1 - sigma3, form, "proportional", confidence)
    c, phi, _ = fit.envelope
    cov = fit.derived_covariance()[:2, :2]
    c_se, phi_se = float(np.sqrt(max(cov[0, 0], 0.0))), float(np.sqrt(max(cov[1, 1], 0.0)))
    corr = float(cov[0, 1] / (c_se * phi_se)) if c_se > 0 and phi_se > 0 else float("nan")
    return Envelope(
        c_kPa=c / KPA,
        phi_deg=phi,
        c_se_kPa=c_se / KPA,
        phi_se_deg=phi_se,
        source="extended_mc",
        n=fit.n,
        r2=float(fit.r2),
        c_phi_correlation=corr,
    )
