"""`capred bridge solve | curve | compare | rupture`: exact capillary bridges.

Between two spheres of radii R and R2, or a sphere and a plane.

The contact angle is ``contact_angle`` everywhere (input column ``contact_angle``,
also accepted as ``theta``); ``contact_angle2`` (optional) is the second particle's, equal to the first by default.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..io import Table
from ..nomenclature import renamed_keywords
from ..physics import bridge as br
from ..physics import bridge_laws as bl
from ..physics import effective_stress_models as esm
from ..physics import shear as ph
from ..records import per_case_store_rows
from ..result import InputFile, Result, input_file, num
from ..spec.bridge import COMPARE_SCHEMA, RUPTURE_SCHEMA, CurveOptions  # noqa: F401 (declared in spec; re-exported here)
from . import bridge_blocks
from .bridge_records import CompareRecord, RuptureRecord
from .bridge_solve import (  # noqa: F401  (re-exported: the names users and tests import from here)
    ANGLE,
    ANGLE2,
    CASE,
    GAMMA,
    RADIUS,
    RADIUS2,
    SOLVE_SCHEMA,
    STATUS,
    VERIFY_RTOL,
    VOLUME,
    BridgeOptions,
    BridgeResult,
    ColumnRows,
    frame_records,
    json_rows,
    read_cases,
    solve_arrays,
    solve_table,
    with_csv_headers,
)


def solve_bridges(source, options: BridgeOptions | None = None) -> BridgeResult:
    """One bridge per row of a table (CSV path, DataFrame or a Table read).

    The table gives R (and R2), gamma, contact_angle (and contact_angle2), gap and suction or V_w.

    A long plain CSV is read, solved and kept block by block (:mod:`capred.pipelines.bridge_blocks`); a Table
    already read is solved at once (:func:`capred.pipelines.bridge_solve.solve_table`).

    Parameters
    ----------
    source : str or Path or DataFrame or Table
        The cases: R [mm], optional R2 [mm] or 'plane', gamma [N/m], contact_angle (and contact_angle2) [deg],
        gap [mm] and suction [kPa] or V_w [mm^3] (units in the headers win).
    options : BridgeOptions, optional
        Surface tension and second contact angle for rows without them (default: water, the row's angle).

    Returns
    -------
    BridgeResult
        One bridge (or a status saying why none) per row.

    References
    ----------
    .. [1] Lian, G., Thornton, C., Adams, M. J. (1993). A theoretical study of the liquid bridge forces
       between two rigid spherical bodies. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    opt = options or BridgeOptions()
    if isinstance(source, Table):
        return solve_table(source, opt)
    return bridge_blocks.solve_in_blocks(source, opt)


@dataclass(repr=False)
class CurveResult(Result):
    """Evenepoel's analytical comparison: sigma' against S_R for two spheres in contact."""

    command = "bridge curve"
    json_name = "curve.json"

    R: float  # m
    gamma: float  # N/m
    contact_angle_rad: float  # contact angle [rad]; JSON and tables give contact_angle_deg
    S_R: np.ndarray
    suction: np.ndarray  # Pa
    sigma_exact: np.ndarray  # Pa
    pendular_limit: float
    options: CurveOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def models(self) -> dict[str, np.ndarray]:
        """Capillary stress of every model at the curve's S_R.

        The exact bridges, Israelachvili (2 gamma cos(theta) / R) and each effective-stress model whose registry entry
        is drawn on this curve (``bridge_curve``: Bishop S_R s, Own 1 chi1 s and Own 2 chi1 s + chi2), in registry
        order.

        Returns
        -------
        dict
            Model name -> sigma' [Pa], one value per S_R.
        """
        S, s = self.S_R, self.suction
        return {
            "exact": self.sigma_exact,
            "israelachvili": np.full_like(S, 2.0 * self.gamma * np.cos(self.contact_angle_rad) / self.R),
            **{m: esm.unit_cell_capillary_stress(m, S, s, self.R, self.gamma) for m in esm.bridge_curve_models()},
        }

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        The table ``curve``: S_R, suction, sigma' of each model.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        return frame_records(self.tables()["curve"])

    def summary(self) -> dict:
        """Relative RMS error of each model against the exact bridges, inside and outside the pendular regime.

        Inside: S_R below ``pendular_limit``; outside: above it.

        Returns
        -------
        dict
            ``{"rms_relative_error_vs_exact": {"inside": {model: error}, "outside": {...}}}`` [-], the exact
            bridges left out (None where a regime has no point).
        """
        m = self.models()
        out = {}
        for regime, sel in (("inside", self.S_R < self.pendular_limit), ("outside", self.S_R >= self.pendular_limit)):
            ex = m["exact"][sel]
            out[regime] = {
                k: num(np.sqrt(np.mean(((v[sel] - ex) / ex) ** 2))) if sel.any() else None
                for k, v in m.items()
                if k != "exact"
            }
        return {"rms_relative_error_vs_exact": out}

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the sphere radius, surface tension, contact angle and pendular limit of the curve.

        Each under its JSON key in its glossary unit (capred.records.quantity_store_row).

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import quantity_store_row

        rows = [
            quantity_store_row(material, "R", self.R * 1e3),
            quantity_store_row(material, "surface_tension", self.gamma, key="gamma_N_per_m"),
            quantity_store_row(material, "contact_angle", float(np.degrees(self.contact_angle_rad))),
            quantity_store_row(material, "pendular_limit", self.pendular_limit),
        ]
        return [r for r in rows if r is not None]

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        R_mm, gamma_N_per_m, contact_angle_deg, the error summary and the curve rows.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        return {
            "R_mm": self.R * 1e3,
            "gamma_N_per_m": self.gamma,
            "contact_angle_deg": float(np.degrees(self.contact_angle_rad)),
            "pendular_limit": self.pendular_limit,
            **self.summary(),
            "curve": self.rows(),
        }

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``curve``: S_R, suction [kPa] and sigma' [kPa] of each model).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        cached = self.__dict__.get("_tables")
        if cached is None:
            cols = {
                "S_R": self.S_R,
                "suction_kPa": self.suction / 1e3,
                **{f"sigma_prime_{k}_kPa": v / 1e3 for k, v in self.models().items()},
            }
            cached = self.__dict__["_tables"] = {"curve": pd.DataFrame(cols)}
        return cached

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``curve``), under ``name [unit]`` headers.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        return {"curve": with_csv_headers(self.tables()["curve"])}


@renamed_keywords(theta_deg="contact_angle_deg", sr_max="S_R_max")
def bridge_curve(
    R=1e-3,
    gamma=ph.SURFACE_TENSION,
    contact_angle_deg: float = 0.0,
    points: int = 2000,
    pendular_limit: float = ph.PENDULAR_LIMIT,
    S_R_max: float = 0.3,
) -> CurveResult:
    """Exact sigma' = F/(pi R^2) against S_R = 3 V/(2 pi R^3) for spheres in contact (gap 0).

    ``R`` [m] and ``gamma`` [N/m] also take strings with units; ``contact_angle_deg``
    is the contact angle [deg]. S_R is swept evenly from 1e-4 to ``S_R_max``;
    points beyond the last concave bridge (suction down to zero) are left out.
    The former keywords ``theta_deg`` and ``sr_max`` still work for one release, with a DeprecationWarning.

    Parameters
    ----------
    R : float or str, optional
        Particle radius [m] (a string may carry a unit, e.g. "1 mm").
    gamma : float or str, optional
        Surface tension [N/m].
    contact_angle_deg : float, optional
        Contact angle [deg].
    points : int, optional
        Number of S_R values of the sweep [-].
    pendular_limit : float, optional
        S_R bound of the pendular regime, for the error summary per regime [-].
    S_R_max : float, optional
        Largest S_R of the sweep [-].

    Returns
    -------
    CurveResult
        S_R, suction [Pa] and exact sigma' [Pa], with the models beside it.
    """
    return reduce_curve(None, CurveOptions(R, gamma, contact_angle_deg, points, S_R_max, pendular_limit))


def reduce_curve(source, opt: CurveOptions) -> CurveResult:
    """The sweep of bridge_curve for an options record (``source`` is unused: the curve needs no file).

    Parameters
    ----------
    source : None
        Unused.
    opt : CurveOptions
        Radius [m], surface tension [N/m], contact angle [deg], points, S_R_max and pendular limit [-].

    Returns
    -------
    CurveResult
        The concave bridges of the sweep.
    """
    R, gamma, points, S_R_max = opt.radius, opt.surface_tension, opt.points, opt.S_R_max
    th = np.radians(opt.contact_angle)
    S = np.linspace(1e-4, S_R_max, points)
    beta, s_star, status = br.solve_for_volume(th, 2 * np.pi * S / 3, 0.0)
    ok = status == 0
    _, vol, f, _ = br.geometry(beta[ok], th, s_star[ok])
    return CurveResult(
        R,
        gamma,
        th,
        3 * vol / (2 * np.pi),
        s_star[ok] * gamma / R,
        f * gamma / R,
        opt.pendular_limit,
        opt,
        [],
        opt.warnings,
    )


@dataclass(repr=False)
class CompareResult(Result):
    """Measured capillary forces of micro-tests beside the exact bridge and three approximations."""

    command = "bridge compare"
    json_name = "compare.json"

    bridges: BridgeResult
    measured_force: np.ndarray  # N
    measured_beta: np.ndarray  # rad, NaN where not measured
    volume_in: np.ndarray  # m^3, as given

    @property
    def options(self):
        """The options of the exact bridges solved (``bridges.options``)."""
        return self.bridges.options

    @property
    def inputs(self):
        """The input files of the run (``bridges.inputs``)."""
        return self.bridges.inputs

    @property
    def warnings(self):
        """The warnings of the exact bridges solved (``bridges.warnings``)."""
        return self.bridges.warnings

    @property
    def notes(self):
        """The notes of the exact bridges solved (``bridges.notes``)."""
        return self.bridges.notes

    def record(self) -> CompareRecord:
        """The comparison as a typed record.

        Per micro-test the measured force, each model's force and residual [mN], the filling angles [deg] and the exact
        bridge's status.

        Returns
        -------
        CompareRecord
            One value per micro-test in output units (NaN where a model gives no bridge).

        References
        ----------
        .. [1] Willett, C. D., Adams, M. J., Johnson, S. A., Seville, J. P. K. (2000). Capillary bridges
           between two spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
        """
        cached = self.__dict__.get("_record")
        if cached is not None:
            return cached
        b = self.bridges
        i_ = b.inputs_si
        R, g, th, D, rho = i_["R"], i_["gamma"], i_["contact_angle_rad"], i_["gap"], i_["ratio"]
        th2 = i_.get("contact_angle2_rad", th)
        ok = b.status == 0
        equal = (rho == 1) & (th2 == th)  # the toroidal approximation: equal spheres, one contact angle
        # two contact angles in the closed forms: cos(theta) -> (cos theta1 + cos theta2) / 2, their Derjaguin
        # limit F = pi R* gamma (cos theta1 + cos theta2) (Willett et al. 2000, doi:10.1021/la000657y)
        th_mean = np.where(th2 == th, th, np.arccos(0.5 * (np.cos(th) + np.cos(th2))))
        # Derjaguin's effective radius for unequal pairs: R* = 2 R R2 / (R + R2) (R for equal spheres, 2 R on a plane)
        r_eff = np.where(np.isinf(rho), 2.0 * R, 2.0 * R * rho / (1.0 + np.where(np.isinf(rho), 0.0, rho)))
        models = {
            "exact": (b.force, ok),
            "toroidal": (br.toroidal(b.beta, th, D / R)[2] * np.pi * g * R, ok & equal),
            "willett": (br.willett_force(r_eff, g, th_mean, self.volume_in, D), np.ones_like(ok)),
            "israelachvili": (br.israelachvili_force(r_eff, g, th_mean), np.ones_like(ok)),
        }
        cols: dict = {}
        for m, (F, good) in models.items():
            cols[f"F_{m}"] = np.where(good, F * 1e3, np.nan)
            cols[f"residual_{m}"] = np.where(good, (F - self.measured_force) * 1e3, np.nan)
        # every closed-form law of the one law registry (`bridge laws` reads the same), in its dimensionless form
        # F / (2 pi R1 gamma) of (theta, V/R1^3, D/R1, R2/R1); NaN where a law does not apply to the geometry
        laws = {}
        for name in bl.LAWS:
            F = bl.law_force(name, th_mean, self.volume_in / R**3, D / R, rho) * 2.0 * np.pi * R * g
            laws[name] = (F * 1e3, (F - self.measured_force) * 1e3)
        cached = self.__dict__["_record"] = CompareRecord(
            case=b.labels or None,
            F_measured=self.measured_force * 1e3,
            filling_angle_measured=np.degrees(self.measured_beta),
            filling_angle_exact=np.where(ok, np.degrees(b.beta), np.nan),
            status=[STATUS[int(k)] for k in b.status],
            laws=laws,
            **cols,
        )
        return cached

    def _frame(self):
        import pandas as pd

        cached = self.__dict__.get("_table")
        if cached is None:
            cached = self.__dict__["_table"] = pd.DataFrame(self.record().columns())
        return cached

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Per micro-test: measured and modelled forces and residuals [mN], filling angles [deg], status.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        cached = self.__dict__.get("_rows")
        if cached is None:
            cached = self.__dict__["_rows"] = self.record().json_rows()
        return cached

    store_rows = per_case_store_rows  # bridges per case: nothing to chart across runs

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the comparison rows.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        return {"source": self.bridges.source, "comparison": self.rows()}

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``compare``: one row per micro-test).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        return {"compare": self._frame()}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``compare``), under ``name [unit]`` headers.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        import pandas as pd

        return {"compare": pd.DataFrame(self.record().csv_columns())}


def compare_measured(source, options: BridgeOptions | None = None) -> CompareResult:
    """Micro-tests: the exact bridge of each measured (R, R2, gap, contact angle, V_w) beside the measured force.

    With the toroidal approximation (equal spheres), Willett et al. (2000) and Israelachvili (with Derjaguin's effective
    radius 2 R R2 / (R + R2) for unequal pairs and a plane), and every closed-form law of the law registry
    (`capred.spec.bridge_laws.LAWS`, the laws of ``capred bridge laws``).

    Parameters
    ----------
    source : str or Path or DataFrame or Table
        The micro-tests: R, R2, gap [mm], contact_angle [deg], V_w [mm^3] and the measured F_cap [mN].
    options : BridgeOptions, optional
        Surface tension [N/m] for rows without gamma.

    Returns
    -------
    CompareResult
        The exact bridges and the measured forces; ``rows()`` gives the comparison with residuals [mN].

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A., Seville, J. P. K. (2000). Capillary bridges
       between two spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
    """
    opt = options or BridgeOptions()
    table, gamma, ratio, th2 = read_cases(source, ("R", "contact_angle", "gap", "V_w"), (), opt)
    if "F_cap" not in table.columns:
        table.missing_column("F_cap")
    table.raise_if_problems()
    R, th, D, V = (
        table.columns["R"],
        np.radians(table.columns["contact_angle"]),
        table.columns["gap"],
        table.columns["V_w"],
    )
    res = solve_arrays(
        table.path,
        R,
        gamma,
        th,
        D,
        ratio,
        np.full(R.size, np.nan),
        V,
        list(table.columns["case"]) if "case" in table.columns else None,
        table.notes,
        th2,
    )
    res.options, res.inputs, res.warnings = opt, [input_file(source, table)], opt.warnings + table.warnings
    return CompareResult(res, table.columns["F_cap"], np.radians(table.get("filling_angle")), V)


@dataclass(repr=False)
class RuptureResult(Result):
    """Rupture distance at constant volume per case, beside Lian et al.'s (1993) estimate."""

    command = "bridge rupture"
    json_name = "rupture.json"

    source: str
    #: per case, SI: R and R2/R ratio [m, -], gamma [N/m], contact_angle_rad [rad], V_w [m^3]
    inputs_si: dict[str, np.ndarray]
    gap: np.ndarray  # m, the rupture distance
    beta: np.ndarray  # filling angle on particle 1 at rupture [rad]
    suction: np.ndarray  # Pa
    shape: br.Bridge  # the bridge at rupture, dimensionless
    status: np.ndarray
    labels: list[str] | None = None
    notes: list[str] = field(default_factory=list)
    options: BridgeOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def record(self) -> RuptureRecord:
        """The rupture distances as a typed record.

        Per case the inputs, the exact rupture distance beside Lian et al.'s (1993) estimate, and the bridge at rupture.

        Returns
        -------
        RuptureRecord
            One value per case in output units (mm, deg, mm^3, kPa, mN; NaN where no rupture was found).

        References
        ----------
        .. [1] Lian, G., Thornton, C., Adams, M. J. (1993). A theoretical study of the liquid bridge forces
           between two rigid spherical bodies. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
        """
        cached = self.__dict__.get("_record")
        if cached is not None:
            return cached
        i_ = self.inputs_si
        R, g, th, V, rho = i_["R"], i_["gamma"], i_["contact_angle_rad"], i_["V_w"], i_["ratio"]
        ok = self.status == 0

        def out(x):
            return np.where(ok, x, np.nan)

        lian = br.lian_rupture_gap(th, V / R**3) * R
        cached = self.__dict__["_record"] = RuptureRecord(
            case=self.labels or None,
            R=R * 1e3,
            R2=np.where(np.isinf(rho), np.inf, rho * R * 1e3),
            contact_angle=np.degrees(th),
            V_w=V * 1e9,
            D_rupture=out(self.gap * 1e3),
            D_rupture_lian=lian * 1e3,
            ratio_to_lian=out(self.gap / lian),
            filling_angle=out(np.degrees(self.beta)),
            filling_angle2=out(np.degrees(self.shape.delta2)),
            suction=out(self.suction / 1e3),
            F_cap=out(self.shape.force * np.pi * g * R * 1e3),
            r0=out(self.shape.neck * R * 1e3),
            status=[STATUS[int(k)] for k in self.status],
        )
        return cached

    def _frame(self):
        import pandas as pd

        cached = self.__dict__.get("_table")
        if cached is None:
            cached = self.__dict__["_table"] = pd.DataFrame(self.record().columns())
        return cached

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Per case: rupture distance and the bridge at rupture; a plane's R2_mm is 'plane'.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        cached = self.__dict__.get("_rows")
        if cached is None:
            cached = self.__dict__["_rows"] = self.record().json_rows()  # a plane's R2_mm is the word
        return cached

    store_rows = per_case_store_rows  # bridges per case: nothing to chart across runs

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the rupture rows.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        return {"source": self.source, "rupture": self.rows()}

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``rupture``: one row per case).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        return {"rupture": self._frame()}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``rupture``), under ``name [unit]`` headers.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        import pandas as pd

        return {"rupture": pd.DataFrame(self.record().csv_columns())}


def rupture_distances(source, options: BridgeOptions | None = None) -> RuptureResult:
    """Rupture distance of each (R, R2, contact_angle, V_w) row, with the bridge at rupture.

    The widest gap a bridge of that volume spans (Lian et al. 1993; pulled apart at constant volume).

    Parameters
    ----------
    source : str or Path or DataFrame or Table
        The cases: R, R2 [mm] (or 'plane'), contact_angle [deg] and V_w [mm^3].
    options : BridgeOptions, optional
        Surface tension [N/m] for rows without gamma, and the second contact angle.

    Returns
    -------
    RuptureResult
        Per row the rupture distance [mm], beside Lian et al.'s estimate, and the bridge at rupture.

    References
    ----------
    .. [1] Lian, G., Thornton, C., Adams, M. J. (1993). A theoretical study of the liquid bridge forces
       between two rigid spherical bodies. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    opt = options or BridgeOptions()
    table, gamma, ratio, th2 = read_cases(source, ("R", "contact_angle", "V_w"), (), opt, RUPTURE_SCHEMA)
    table.raise_if_problems()
    R, th, V = table.columns["R"], np.radians(table.columns["contact_angle"]), table.columns["V_w"]
    D, beta, s, status = br.rupture_gap(th, V / R**3, ratio, th2)
    shape = br.bridge(beta, th, np.where(np.isfinite(s), s, 0.0), ratio, th2)
    res = RuptureResult(
        table.path,
        {"R": R, "gamma": gamma, "contact_angle_rad": th, "V_w": V, "ratio": ratio, "contact_angle2_rad": th2},
        D * R,
        beta,
        s * gamma / R,
        shape,
        status,
        list(table.columns["case"]) if "case" in table.columns else None,
        list(table.notes),
    )
    res.options, res.inputs, res.warnings = opt, [input_file(source, table)], opt.warnings + table.warnings
    return res


def comparison_rows(res: CompareResult) -> list[dict]:
    """Measured force against exact, toroidal, Willett and Israelachvili (mN) with residuals.

    Parameters
    ----------
    res : CompareResult
        The result of :func:`compare_measured`.

    Returns
    -------
    list of dict
        One row per micro-test, as ``res.rows()``.
    """
    return res.rows()


__all__ = [
    "solve_bridges",
    "bridge_curve",
    "compare_measured",
    "rupture_distances",
    "RuptureResult",
    "comparison_rows",
    "BridgeResult",
    "CurveResult",
    "CompareResult",
    "BridgeOptions",
    "CurveOptions",
    "InputError",
]
