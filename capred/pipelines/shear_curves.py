"""Raw direct-shear curves: the peak strength, residual strength and dilatancy of each test.

A curves table is long: one row per reading, ``test_id``, the horizontal
``displacement`` [mm], and the shear force ``F`` [N] or the shear stress
``tau`` [kPa]; optionally the ``vertical_displacement`` [mm] (positive up,
i.e. dilation). tau = F / A_c with the area correction of the box:

- ``none``: the nominal area A (as ASTM D3080 reports),
- ``square`` box of side L = sqrt(A): A_c = L (L - delta),
- ``circular`` box of diameter D: A_c = (D^2/2)(acos(delta/D) - (delta/D) sqrt(1 - (delta/D)^2)).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..io import Column, Table, read_table

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column(
        "displacement",
        "length",
        "mm",
        "horizontal displacement",
        ("horizontal_displacement", "shear_displacement", "dx", "delta", "disp"),
    ),
    Column("F", "force", "N", "shear force", ("shear_force", "force", "horizontal_force")),
    Column("tau", "pressure", "kPa", "shear stress", ("shear_stress", "tau_kpa")),
    Column(
        "vertical_displacement",
        "length",
        "mm",
        "vertical displacement",
        ("dy", "vertical", "dv", "normal_displacement", "vertical_disp"),
    ),
]


def corrected_area(area, displacement, kind: str = "none"):
    """Contact area of a shear box after a horizontal displacement delta [m^2].

    Parameters
    ----------
    area : float or array_like
        Nominal box area A [m^2].
    displacement : float or array_like
        Horizontal displacement delta [m], >= 0 (its magnitude is taken).
    kind : str, optional
        ``"none"`` (A), ``"square"`` (A_c = L (L - delta), L = sqrt(A)) or ``"circular"``
        (A_c = (D^2/2)(acos(delta/D) - (delta/D) sqrt(1 - (delta/D)^2)), D = sqrt(4A/pi)).

    Returns
    -------
    numpy.ndarray
        The contact area A_c [m^2], broadcast over ``area`` and ``displacement``.
    """
    A = np.asarray(area, float)
    d = np.abs(np.asarray(displacement, float))
    if kind == "none":
        return A + 0.0 * d
    if kind == "square":
        L = np.sqrt(A)
        return L * (L - d)
    D = np.sqrt(4.0 * A / np.pi)
    x = np.clip(d / D, 0.0, 1.0)
    return 0.5 * D**2 * (np.arccos(x) - x * np.sqrt(1.0 - x**2))


@dataclass
class ShearCurves:
    """Peaks picked from the raw curves, per test of the tests table (NaN where a test has no curve)."""

    table: Table
    tau_peak: np.ndarray  # Pa
    displacement_at_peak: np.ndarray  # m
    tau_residual: np.ndarray  # Pa
    dilatancy_angle: np.ndarray  # deg
    curves: dict[str, tuple[np.ndarray, np.ndarray, int]]  # test_id -> (displacement [m], tau [Pa], peak index)
    problems: list = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: test_id -> vertical displacement [m] (positive up: dilation) at the readings of ``curves``, where given
    vertical: dict[str, np.ndarray] = field(default_factory=dict)
    #: per test: nominal over corrected area at the peak, A / A_c(delta_peak) [-] (1 without area correction)
    area_ratio_at_peak: np.ndarray | None = None

    def per_test(self) -> dict[str, np.ndarray]:
        """The per-test outputs of the curves beside the tests table.

        Returns
        -------
        dict
            ``displacement_at_peak`` [m], ``tau_residual`` [Pa], ``dilatancy_angle`` [deg] -> array per test.
        """
        return {
            "displacement_at_peak": self.displacement_at_peak,
            "tau_residual": self.tau_residual,
            "dilatancy_angle": self.dilatancy_angle,
        }


def pick_peaks(
    source, tests: Table, box_area: np.ndarray, area_correction: str = "none", ignore_columns=()
) -> ShearCurves:
    """Peak tau of every test's curve, its displacement, the residual tau and the dilatancy angle at the peak.

    The residual tau is the mean over the last 10 % of the displacement; the dilatancy angle (atan of dv/dh) needs
    vertical displacements.

    Parameters
    ----------
    source : str or Path or DataFrame
        Long table of raw curves: test_id, displacement, F or tau (optional vertical displacement).
    tests : Table
        The tests table the curves belong to.
    box_area : ndarray
        Nominal box area of each test [m^2].
    area_correction : str, optional
        ``none``, ``square`` or ``circular`` (see :func:`corrected_area`).
    ignore_columns : sequence of str, optional
        Columns to leave out (the command's --ignore-column list: it applies to every file the command reads;
        the names this file lacks are not warned about here, see capred.io.Table.forget_ignores).

    Returns
    -------
    ShearCurves
        Per test: tau at peak [Pa], displacement at peak [m], residual tau [Pa], dilatancy angle [deg]; the
        problems of the file collected, not raised.
    """
    table = read_table(source, SCHEMA, ignore_columns=ignore_columns)
    table.forget_ignores()  # the tests table warns about a name no file has
    for name in ("test_id", "displacement"):
        if name not in table.columns:
            table.missing_column(name)
    if "F" not in table.columns and "tau" not in table.columns:
        table.missing_column("F", " (or 'tau')")
    n = len(tests)
    out = ShearCurves(
        table,
        *(np.full(n, np.nan) for _ in range(4)),
        {},
        table.problems,
        list(table.warnings),
        area_ratio_at_peak=np.ones(n),
    )
    if table.missing or "test_id" not in tests.columns:
        return out
    ids = tests.columns["test_id"]
    row_of = {str(t): i for i, t in enumerate(ids)}
    cid = table.columns["test_id"]
    disp = table.columns["displacement"]
    for tid in dict.fromkeys(cid):
        sel = np.flatnonzero(cid == tid)
        if str(tid) not in row_of:
            out.warnings.append(f"curve of test '{tid}' ignored: no such test in the tests table")
            continue
        i = row_of[str(tid)]
        d = disp[sel]
        if "tau" in table.columns and np.isfinite(table.columns["tau"][sel]).any():
            tau = table.columns["tau"][sel]
        else:
            F = table.get("F")[sel]
            if not np.isfinite(box_area[i]):
                table.add_problem(
                    int(sel[0]),
                    "F",
                    f"test '{tid}': a force curve needs the box area ('box_area' in the tests table or --box-area)",
                )
                continue
            area = corrected_area(box_area[i], d, area_correction)
            with np.errstate(divide="ignore", invalid="ignore"):
                tau = np.where(area > 0, F / area, np.nan)
        ok = np.isfinite(tau) & np.isfinite(d)
        if not ok.any():
            table.add_problem(int(sel[0]), "test_id", f"test '{tid}': the curve has no readings")
            continue
        d, tau = d[ok], tau[ok]
        vert = table.get("vertical_displacement")[sel][ok]
        k = int(np.argmax(tau))
        out.tau_peak[i] = tau[k]
        out.displacement_at_peak[i] = d[k]
        span = d.max() - d.min()
        out.tau_residual[i] = float(np.mean(tau[d >= d.max() - 0.1 * span])) if span > 0 else tau[-1]
        if np.isfinite(vert).sum() >= 3 and np.ptp(d) > 0:
            order = np.argsort(d, kind="stable")
            slope = np.gradient(vert[order], d[order])  # dv/dh along the curve
            at_peak = int(np.flatnonzero(order == k)[0])
            out.dilatancy_angle[i] = float(np.degrees(np.arctan(slope[at_peak])))
        out.curves[str(tid)] = (d, tau, k)
        if np.isfinite(vert).any():
            out.vertical[str(tid)] = vert
        if np.isfinite(box_area[i]):
            # the normal force acts on the same corrected area as the shear force (ASTM D3080, BS 1377-7)
            out.area_ratio_at_peak[i] = float(box_area[i] / corrected_area(box_area[i], d[k], area_correction))
        given = tests.get("tau_max")[i]
        if np.isfinite(given) and abs(given - tau[k]) > 0.01 * abs(tau[k]):
            out.warnings.append(
                f"test '{tid}': tau_max {given / 1e3:.4g} kPa in the tests table differs by more "
                f"than 1 % from the peak of its curve, {tau[k] / 1e3:.4g} kPa (the curve is used)"
            )
    return out
