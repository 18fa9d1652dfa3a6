"""`capred triaxial-bounds`: bounds of the capillary stress tensor at failure (Prunier et al. 2024).

Saturated drained tests give the effective envelope c', phi'; every
unsaturated test's total failure state is projected on it under three
hypotheses (spherical tensor, lower bound, EDTP upper bound), and groups of
unsaturated tests that share one tensor get the Appendix 1 analysis.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import CapredError, FitError, OptionError
from ..fitting.linear import LineFit, fit_line
from ..io.table import Column, Table, read_table
from ..nomenclature import QUANTITIES as _GLOSSARY
from ..physics import triaxial as tx
from ..references import cite
from ..result import InputFile, Options, Result, TableSpec, input_file, num
from ..units import parse_quantity

SCHEMA = [
    Column("test_id", "text", None, "test identifier", ("id", "test", "sample_id")),
    Column("condition", "text", None, "test condition", ("state", "saturation_state"),
           choices=("saturated", "unsaturated")),
    Column("sigma3", "pressure", "kPa", "sigma3", ("s3", "confining_pressure", "sigma_3", "cell_pressure"), "nonnegative"),
    Column("q_f", "pressure", "kPa", "q_f", ("q", "qf", "q_max", "deviator", "q_peak"), "positive"),
    Column("sigma1", "pressure", "kPa", "sigma1", ("s1", "sigma_1"), "nonnegative"),
    Column("sigma2", "pressure", "kPa", "sigma2", ("s2", "sigma_2"), "nonnegative"),
    Column("p0", "pressure", "kPa", "p0", ("p_0", "initial_pressure"), "nonnegative"),
    Column("s0", "pressure", "kPa", "s0", ("s_0", "initial_suction", "suction"), "nonnegative"),
    Column("group", "text", None, "group", ("tensor_group",)),
    Column("D0", "length", "mm", "initial diameter", ("initial_diameter", "diameter", "d_0"), "positive"),
    Column("H0", "length", "mm", "initial height", ("initial_height", "height", "h_0"), "positive"),
    Column("back_pressure", "pressure", "kPa", "back pressure u_b (pore-water pressure)",
           ("backpressure", "u_b", "bp", "back_pressure_kpa")),
    Column("u_a", "pressure", "kPa", "pore-air pressure (axis translation)",
           ("pore_air_pressure", "air_pressure", "ua")),
    Column("strain_at_failure", "dimensionless", "-", "axial strain at failure",
           ("eps_f", "axial_strain_f", "axial_strain_at_failure", "strain_f")),
]

CURVE_SCHEMA = [
    Column("test_id", "text", None, "test identifier", ("id", "test", "sample_id")),
    Column("axial_strain", "dimensionless", "-", "axial strain", ("eps_a", "eps1", "epsilon_1", "axial_strain_pct")),
    Column("q", "pressure", "kPa", "q", ("deviator", "q_kpa", "deviatoric_stress")),
    Column("vol_strain", "dimensionless", "-", "volumetric strain", ("eps_v", "epsilon_v")),
]

BOUNDS = ("spherical", "lower", "edtp")


@dataclass
class Envelope:
    c: float  # Pa
    phi: float  # deg
    c_se: float | None
    phi_se: float | None
    source: str  # "fit" or "options"
    fit: LineFit | None = None

    @property
    def M(self) -> float:
        return float(tx.envelope_qp(self.c, self.phi)[0])

    @property
    def k(self) -> float:
        return float(tx.envelope_qp(self.c, self.phi)[1])


def fit_envelope(sigma3_eff, sigma1_eff, confidence=0.95) -> Envelope:
    """c', phi' from saturated failure states by least squares of sigma'_1 on sigma'_3.

    Eq. (25) of Prunier et al. (2024) is linear in the principal-stress plane:
    sigma'_1 = K_p sigma'_3 + 2c' sqrt(K_p). The confining stress is the
    controlled variable and sigma'_1 the measured one, so ordinary least
    squares has its error in the right variable (a fit of q on p would put the
    measured q on both axes, since p = sigma3 + q/3). This is the exact
    Mohr-Coulomb criterion, i.e. the line tangent to the Mohr circles.
    Standard errors of c', phi' follow by the delta method.
    """
    f = fit_line(sigma3_eff, sigma1_eff, confidence)
    kp, b = f.slope, f.intercept
    if kp <= 1.0:
        raise FitError(f"saturated failure states give K_p = {kp:.3g} <= 1: no positive friction angle")
    c, phi = tx.envelope_from_principal_fit(kp, b)
    # delta method: phi = asin((K-1)/(K+1)), c = b/(2 sqrt K)
    dphi_dk = np.degrees(1.0 / ((kp + 1.0) * np.sqrt(kp)))
    dc_db, dc_dk = 1.0 / (2.0 * np.sqrt(kp)), -b / (4.0 * kp**1.5)
    cov = f.covariance  # [[var b, cov], [cov, var K]]
    phi_se = abs(dphi_dk) * np.sqrt(cov[1, 1])
    c_var = dc_db**2 * cov[0, 0] + dc_dk**2 * cov[1, 1] + 2 * dc_db * dc_dk * cov[0, 1]
    return Envelope(float(c), float(phi), float(np.sqrt(max(c_var, 0.0))), float(phi_se), "fit", f)


#: membrane options and their SI unit; their glossary names are used once capred.nomenclature has them
_MEMBRANE = {"membrane_thickness": ("m", "length"), "membrane_modulus": ("Pa", "pressure")}


@dataclass(frozen=True)
class TriaxialOptions(Options):
    """Options of `capred triaxial-bounds`.

    Attributes
    ----------
    c_eff : float or str, optional
        Effective cohesion c' [Pa] (or a string with a unit); with ``phi_eff``
        it replaces the fit of the saturated tests.
    phi_eff : float, optional
        Effective friction angle phi' [deg].
    confidence : float
        Confidence level of the envelope fit's intervals.
    curves : path, optional
        Raw curves (a long table with test_id, a file, a folder or a glob of
        instrument exports) whose peaks give q_f.
    membrane_thickness : float or str, optional
        Membrane thickness t_m [m] (CLI in mm); with ``membrane_modulus`` the
        deviator is corrected for the membrane (ASTM D4767); off by default.
    membrane_modulus : float or str, optional
        Young's modulus of the membrane E_m [Pa] (CLI in kPa; latex about
        1400 kPa).
    """

    QUANTITIES = {"c_eff": "c_eff", "phi_eff": "phi_eff",
                  **{k: k for k in _MEMBRANE if k in _GLOSSARY}}

    c_eff: float | None = None  # Pa
    phi_eff: float | None = None  # deg
    confidence: float = 0.95
    curves: str | Path | None = None
    membrane_thickness: float | None = None  # m
    membrane_modulus: float | None = None  # Pa

    def __post_init__(self) -> None:
        super().__post_init__()
        if (self.c_eff is None) != (self.phi_eff is None):
            raise OptionError("give both --c-eff and --phi-eff, or neither")
        for name, (unit, kind) in _MEMBRANE.items():
            value = getattr(self, name)
            if value is None or name in self.QUANTITIES:
                continue
            try:
                si = float(value) if isinstance(value, (int, float)) else parse_quantity(str(value), unit, kind)
            except (CapredError, ValueError) as exc:
                raise OptionError(f"{self.option_name(name)}: {exc}") from None
            if not np.isfinite(si) or si <= 0:
                raise OptionError(f"{self.option_name(name)}: must be > 0 (got {value!r})")
            object.__setattr__(self, name, si)
        if (self.membrane_thickness is None) != (self.membrane_modulus is None):
            raise OptionError("give both --membrane-thickness and --membrane-modulus for the membrane correction, "
                              "or neither")

    @property
    def membrane(self) -> tuple[float, float] | None:
        """(thickness [m], modulus [Pa]) of the membrane, or None (no correction)."""
        if self.membrane_thickness is None:
            return None
        return self.membrane_thickness, self.membrane_modulus


@dataclass(repr=False)
class TriaxialResult(Result):
    command = "triaxial-bounds"

    source: str
    envelope: Envelope
    tests: dict[str, np.ndarray]
    bounds: dict[str, tx.Bound]  # for all rows (NaN on saturated rows / missing s0)
    q_sat: np.ndarray
    groups: list[dict]
    notes: list[str] = field(default_factory=list)
    options: TriaxialOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def unsaturated(self) -> np.ndarray:
        return self.tests["condition"] == "unsaturated"

    def flags(self, i: int) -> list[str]:
        out = []
        for name in BOUNDS:
            b = self.bounds[name]
            if np.isfinite(b.sigma1_cap[i]) and b.positive[i]:
                out.append(f"{name}_positive_component")
        if self.unsaturated[i] and self.bounds["spherical"].p_prime[i] < 0:
            out.append("spherical_negative_p_prime")
        return out

    def _bound_json(self, name: str, i: int) -> dict | None:
        b = self.bounds[name]
        if not np.isfinite(b.sigma1_cap[i]):
            return None
        gain = b.q_prime[i] / self.q_sat[i]
        return {
            "sigma1_cap_kPa": _kpa(b.sigma1_cap[i]), "sigma3_cap_kPa": _kpa(b.sigma3_cap[i]),
            "p_cap_kPa": _kpa(b.p_cap[i]), "q_cap_kPa": _kpa(b.q_cap[i]),
            "p_prime_kPa": _kpa(b.p_prime[i]), "q_prime_kPa": _kpa(b.q_prime[i]),
            "gain": num(gain), "positive_component": bool(b.positive[i]),
        }

    def payload(self, lazy: bool = False) -> dict:
        e = self.envelope
        t = self.tests
        tests = []
        for i in range(len(t["test_id"])):
            row = {
                "test_id": str(t["test_id"][i]), "condition": str(t["condition"][i]),
                "group": t["group"][i] or None, "line": int(t["line"][i]),
                "sigma3_kPa": _kpa(t["sigma3"][i]), "sigma2_kPa": _kpa(t["sigma2"][i]),
                "sigma1_kPa": _kpa(t["sigma1"][i]),
                "p_kPa": _kpa(t["p"][i]), "q_kPa": _kpa(t["q"][i]),
                "p0_kPa": _kpa(t["p0"][i]), "s0_kPa": _kpa(t["s0"][i]),
                "sigma3_total_kPa": _kpa(t["sigma3_total"][i]), "back_pressure_kPa": _kpa(t["back_pressure"][i]),
                "u_a_kPa": _kpa(t["u_a"][i]), "radial_pressure_kPa": _kpa(t["radial_pressure"][i]),
                "membrane_correction_kPa": _kpa(t["membrane"][i]),
                "lode_angle_deg": num(t["lode"][i]),
                "strain_at_failure": num(t["strain_f"][i]),
                "q_sat_kPa": _kpa(self.q_sat[i]) if self.unsaturated[i] else None,
            }
            for name in BOUNDS:
                row[name] = self._bound_json(name, i) if self.unsaturated[i] else None
            row["flags"] = self.flags(i)
            tests.append(row)
        return {
            "source": self.source,
            "envelope": {
                "c_kPa": _kpa(e.c), "phi_deg": num(e.phi), "M": num(e.M), "k_kPa": _kpa(e.k),
                "c_se_kPa": _kpa(e.c_se) if e.c_se is not None else None,
                "phi_se_deg": num(e.phi_se) if e.phi_se is not None else None,
                "source": e.source, "n": e.fit.n if e.fit else None,
                "r2": num(e.fit.r2) if e.fit else None,
                "method": (f"least squares of sigma'_1 on sigma'_3 ({cite('prunier2024', 'eq. 25')})"
                           if e.fit else "given as options"),
            },
            "tests": tests,
            "groups": self.groups,
        }

    def tables(self) -> dict:
        """results (one row per test, bounds side by side) and, with groups, groups."""
        cached = self.__dict__.get("_tables")
        if cached is None:
            cached = {"results": self._results_table()}
            if self.groups:
                import pandas as pd

                rows = [{**g, "tests": ";".join(g["tests"]), "lode_angles_deg": ";".join(
                    "" if x is None else repr(x) for x in g.get("lode_angles_deg", []))} for g in self.groups]
                cached["groups"] = pd.json_normalize(rows)
            self.__dict__["_tables"] = cached
        return cached

    def season_rows(self) -> list[dict]:
        e = self.envelope
        n_flag = sum(1 for i in range(len(self.tests["test_id"])) if self.flags(i))
        return [{"material": "(envelope)", "c [kPa]": num(e.c / 1e3), "c_se [kPa]": num(e.c_se / 1e3)
                 if e.c_se is not None else None, "phi [deg]": num(e.phi), "phi_se [deg]": num(e.phi_se),
                 "n_dry": e.fit.n if e.fit else None, "n_wet": int(self.unsaturated.sum()), "best_model": None,
                 "best_rmse [kPa]": None, "flagged_tests": n_flag}]

    def _results_table(self):
        import pandas as pd

        js = self.to_json()
        rows = []
        for t in js["tests"]:
            r = {k: v for k, v in t.items() if k not in BOUNDS and k != "flags"}
            r = {(k.replace("_kPa", " [kPa]").replace("_deg", " [deg]")): v for k, v in r.items()}
            for name in BOUNDS:
                for key, v in (t[name] or {}).items():
                    r[f"{name}_{key.replace('_kPa', '')}" + (" [kPa]" if key.endswith("_kPa") else "")] = v
            r["flags"] = ";".join(t["flags"])
            rows.append(r)
        return pd.DataFrame(rows)


def _kpa(x) -> float | None:
    return num(float(x) / 1e3)


def load_triaxial_table(table: Table, curves: dict[str, tuple[float, float]] | None) -> tuple[Table, dict]:
    """q at failure (from q_f, sigma1 or the curves) per test; problems collected in ``table``.

    Returns the table and a dict with ``q`` [Pa], ``strain`` (axial strain at
    failure [-], from the curve or the column ``strain_at_failure``) and
    ``from_curve`` (True where the curve gave q).
    """
    for name in ("test_id", "condition", "sigma3"):
        if name not in table.columns:
            table.missing_column(name)
    if "q_f" not in table.columns and "sigma1" not in table.columns and not curves:
        table.missing_column("q_f", " (or 'sigma1', or raw curves with --curves)")
    table.raise_if_problems()
    n = len(table)
    s3 = table.columns["sigma3"]
    q = table.get("q_f").copy()
    s1 = table.get("sigma1")
    strain = table.get("strain_at_failure").copy()
    from_curve = np.zeros(n, bool)
    table.check_unique("test_id")
    for i in range(n):
        tid = table.columns["test_id"][i]
        if np.isnan(q[i]) and np.isfinite(s1[i]) and np.isfinite(s3[i]):
            q[i] = s1[i] - s3[i]
            if q[i] <= 0:
                table.add_problem(i, "sigma1", f"sigma1 = {table.value_text('sigma1', i)} is not above sigma3: q_f <= 0")
        if np.isnan(q[i]) and curves and tid in curves:
            q[i], strain[i] = curves[tid]
            from_curve[i] = True
            if q[i] <= 0:
                table.add_problem(i, "test_id", f"the curve of '{tid}' peaks at q = {q[i] / 1e3:.4g} kPa <= 0")
        if np.isnan(q[i]) and not any(p.line == int(table.lines[i]) for p in table.problems):
            table.add_problem(i, "q_f" if "q_f" in table.columns else None,
                              "no failure deviator: give 'q_f' or 'sigma1'" + (" or a curve" if curves else ""))
    if curves:
        unknown = sorted(set(curves) - set(table.columns["test_id"]))
        if unknown:
            table.notes.append(f"curves for tests not in the table ignored: {', '.join(unknown)}")
    return table, {"q": q, "strain": strain, "from_curve": from_curve}


def pressure_tolerance(pressure):
    """Tolerance [Pa] of a cell or back pressure: 2 kPa below 200 kPa, 1 % above.

    The accuracy ASTM D4767-11 (section 5, pressure-control devices;
    doi:10.1520/D4767-11) asks of the devices that apply the chamber and back
    pressures; two readings of one pressure that differ by more are two
    different pressures.
    """
    return np.maximum(2e3, 0.01 * np.abs(pressure))


def pore_pressures(table: Table, at_peak: dict[str, dict[str, float]], q) -> dict:
    """The pore pressure to subtract from each test's stresses and whether the table's stresses are total.

    Saturated tests: sigma' = sigma - u_w with u_w the ``back_pressure``
    column, else the export's pore pressure at the peak, else its back
    pressure (Terzaghi). Unsaturated tests under axis translation: the net
    stress sigma - u_a with u_a the ``u_a`` column, else the export's pore-air
    pressure (Fredlund & Morgenstern 1977 stress state variables). The table's
    sigma3 is compared with the export's radial pressure at the peak
    (sigma1 in extension, where the cell pressure is the major stress) within
    :func:`pressure_tolerance`: equal -> total stresses (the pore pressure is
    subtracted); equal to radial - u -> already effective (not subtracted
    again); otherwise a warning. Problems are added to ``table``.

    Returns
    -------
    dict
        ``u`` [Pa] subtracted per test, ``u_b``, ``u_a`` [Pa] (NaN where
        unknown), ``radial`` [Pa] (the export's, NaN without one),
        ``sigma3`` [Pa] (the table's, blank cells filled from the export),
        ``s0`` [Pa] (blank cells filled with u_a - u_b), ``notes``,
        ``warnings``.
    """
    n = len(table)
    tids = [str(t) for t in table.columns["test_id"]]
    sat = table.columns["condition"] == "saturated"
    s3 = table.columns["sigma3"].copy()
    s0 = table.get("s0").copy()
    ub_col, ua_col = table.get("back_pressure").copy(), table.get("u_a").copy()
    ext = (table.get("sigma2") == s3 + q) if "sigma2" in table.columns else np.zeros(n, bool)
    exp = {k: np.array([at_peak.get(t, {}).get(k, np.nan) for t in tids]) for k in
           ("radial_pressure", "back_pressure", "pore_pressure", "air_pressure")}
    u = np.zeros(n)
    notes, warnings = [], []
    filled_s3, from_export, already = [], [], []
    for i in range(n):
        tid = tids[i]
        if sat[i]:
            if np.isfinite(ua_col[i]):
                table.add_problem(i, "u_a", "u_a is for unsaturated tests (net stress sigma - u_a); the pore "
                                            "pressure of a saturated test is its back_pressure")
            u_tab = ub_col[i]
            u_exp = exp["pore_pressure"][i] if np.isfinite(exp["pore_pressure"][i]) else exp["back_pressure"][i]
        else:
            u_tab = ua_col[i]
            u_exp = exp["air_pressure"][i]
            u_w = ub_col[i] if np.isfinite(ub_col[i]) else exp["back_pressure"][i]
            if np.isfinite(ub_col[i]) and not (np.isfinite(ua_col[i]) or np.isfinite(u_exp)):
                table.add_problem(i, "back_pressure", "an unsaturated test's back pressure is the pore-water "
                                  "pressure of axis translation: give the pore-air pressure 'u_a' too (the "
                                  "stresses are net of u_a)")
            u_a = u_tab if np.isfinite(u_tab) else u_exp
            if np.isnan(s0[i]) and np.isfinite(u_a) and np.isfinite(u_w):
                s0[i] = u_a - u_w
                notes.append(f"test '{tid}': s0 = u_a - u_w = {s0[i] / 1e3:.4g} kPa (axis translation)")
        radial = exp["radial_pressure"][i]
        if np.isnan(s3[i]) and np.isfinite(radial) and not ext[i]:
            s3[i] = radial
            filled_s3.append(tid)
        total = np.isfinite(u_tab)
        if np.isfinite(radial) and np.isfinite(s3[i]):
            cell = s3[i] + q[i] if ext[i] else s3[i]
            u_known = u_tab if np.isfinite(u_tab) else u_exp
            name = "sigma1" if ext[i] else "sigma3"
            if abs(cell - radial) <= pressure_tolerance(radial):
                total = True
            elif np.isfinite(u_known) and abs(u_known) > pressure_tolerance(radial) and \
                    abs(cell - (radial - u_known)) <= pressure_tolerance(radial):
                total = False
                already.append(tid)
                if np.isfinite(u_tab):
                    warnings.append(f"test '{tid}': {name} = {cell / 1e3:.4g} kPa equals the export's radial "
                                    f"pressure {radial / 1e3:.4g} kPa minus the pore pressure {u_known / 1e3:.4g} kPa: "
                                    "the table's stresses are already effective; the pore pressure of the table "
                                    "is not subtracted again")
            else:
                warnings.append(f"test '{tid}': {name} = {cell / 1e3:.4g} kPa in the table but the export's radial "
                                f"pressure at failure is {radial / 1e3:.4g} kPa (tolerance "
                                f"{pressure_tolerance(radial) / 1e3:.3g} kPa, ASTM D4767); the table's value is used")
        if total:
            if np.isfinite(u_tab):
                u[i] = u_tab
            elif np.isfinite(u_exp):
                u[i] = u_exp
                from_export.append(tid)
    if filled_s3:
        notes.append(f"sigma3 taken from the export's radial pressure at failure: {', '.join(filled_s3)}")
    if from_export:
        notes.append(f"pore pressure taken from the export at failure (sigma' = sigma - u_w saturated, "
                     f"sigma - u_a unsaturated): {', '.join(from_export)}")
    if already:
        notes.append(f"sigma3 already effective (= radial pressure - pore pressure of the export): "
                     f"{', '.join(already)}")
    ub = np.where(sat, np.where(np.isfinite(ub_col), ub_col, np.where(u != 0, u, np.nan)), ub_col)
    ua = np.where(~sat, np.where(np.isfinite(ua_col), ua_col, np.where(u != 0, u, np.nan)), np.nan)
    return {"u": u, "u_b": ub, "u_a": ua, "radial": exp["radial_pressure"], "sigma3": s3, "s0": s0,
            "notes": notes, "warnings": warnings}


def run_triaxial_bounds(source, options: TriaxialOptions | None = None,
                        curves: str | Path | None = None) -> TriaxialResult:
    """Envelope, bounds and group analysis of a triaxial table (see module docstring).

    ``source`` is a CSV path or a DataFrame; ``curves`` (or ``options.curves``)
    a long CSV of raw curves. Stresses in the table are total unless a pore
    pressure says otherwise: ``back_pressure`` (saturated tests,
    sigma' = sigma - u_b) and ``u_a`` (unsaturated tests, net stress
    sigma - u_a) are subtracted from sigma3, sigma1, sigma2 and p0.

    Example
    -------
    >>> r = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))  # doctest: +SKIP
    >>> r.to_json()["tests"][4]["spherical"]["p_cap_kPa"]                     # doctest: +SKIP
    """
    opt = options or TriaxialOptions()
    if curves is not None:
        opt = dataclasses.replace(opt, curves=curves)
    curves = opt.curves
    table = read_table(source, SCHEMA)
    raw_curves = None
    if curves is not None:
        from .triaxial_curves import read_curves

        raw_curves = read_curves(curves, table, opt.membrane)
        table.problems += raw_curves.problems  # reported with the table's own, in one round
        table.notes += raw_curves.notes
        table.warnings += raw_curves.warnings
    table, d = load_triaxial_table(table, raw_curves.peaks if raw_curves else None)
    table.raise_if_problems()
    notes = list(table.notes)
    warnings = list(opt.warnings) + list(table.warnings)

    cond = table.columns["condition"]
    sat = cond == "saturated"
    unsat = ~sat
    q = d["q"].copy()
    # membrane correction of the deviator (the curves' readings are corrected before their peak)
    dq = np.zeros(len(table))
    if opt.membrane is not None:
        from .triaxial_curves import membrane_correction

        at = raw_curves.at_peak if raw_curves else {}
        D0 = table.get("D0")
        for i in range(len(table)):
            tid = str(table.columns["test_id"][i])
            if d["from_curve"][i]:
                dq[i] = at[tid]["membrane"]
                continue
            need = [w for w, ok in (("'strain_at_failure'", np.isfinite(d["strain"][i])),
                                    ("'D0'", np.isfinite(D0[i]))) if not ok]
            if need:
                table.add_problem(i, "test_id", f"the membrane correction of '{tid}' needs {' and '.join(need)} "
                                                "(or its raw curve with --curves)")
                continue
            dq[i] = float(membrane_correction(d["strain"][i], D0[i], *opt.membrane))
        q = q - np.where(d["from_curve"], 0.0, dq)  # a curve's readings were corrected before its peak
        for i in np.flatnonzero(q <= 0):
            table.add_problem(int(i), "test_id", f"after the membrane correction ({dq[i] / 1e3:.4g} kPa) q_f <= 0")
        t_m, E_m = opt.membrane
        notes.append(f"membrane correction of the deviator (ASTM D4767-11): Δq = 4 E_m t_m ε_a / D0 with "
                     f"t_m = {t_m * 1e3:.4g} mm, E_m = {E_m / 1e3:.4g} kPa; D0 for the diameter after consolidation")
    else:
        notes.append("no membrane correction of the deviator (give --membrane-thickness and --membrane-modulus "
                     "to apply ASTM D4767-11's)")

    pp = pore_pressures(table, raw_curves.at_peak if raw_curves else {}, q)
    notes += pp["notes"]
    warnings += pp["warnings"]
    u = pp["u"]
    for i in np.flatnonzero(np.isnan(pp["sigma3"])):
        table.add_problem(int(i), "sigma3", "sigma3 is blank")
    table.raise_if_problems()
    s3_total = pp["sigma3"]
    s3 = s3_total - u
    s1 = s3 + q
    s2 = table.get("sigma2") - u
    s2[np.isnan(s2)] = s3[np.isnan(s2)]
    p0 = table.get("p0") - u
    p0[np.isnan(p0)] = s3[np.isnan(p0)]
    s0 = pp["s0"]
    for i in np.flatnonzero(s3 < 0):
        kind = "effective" if sat[i] else "net"
        table.add_problem(int(i), "sigma3", f"the {kind} confining stress sigma3 - "
                          f"{'u_b' if sat[i] else 'u_a'} = {s3[i] / 1e3:.4g} kPa is negative")
    for i in np.flatnonzero(np.isfinite(table.get("sigma2"))):
        if not s3[i] <= s2[i] <= s1[i]:
            table.add_problem(i, "sigma2", "sigma2 must lie between sigma3 and sigma1")
    if np.any(u != 0):
        notes.append("stresses net of the pore pressure: sigma' = sigma - u_b (saturated tests, Terzaghi), "
                     "sigma - u_a (unsaturated tests, axis translation); sigma3_total_kPa keeps the cell pressure")

    if opt.c_eff is not None:
        env = Envelope(opt.c_eff, opt.phi_eff, None, None, "options")
        if sat.any():
            notes.append("envelope taken from --c-eff/--phi-eff; the saturated tests are only plotted")
    elif sat.sum() == 0:
        table.add_problem(None, "condition", "no saturated test and no envelope given: add saturated drained tests "
                                             "or pass --c-eff and --phi-eff")
        table.raise_if_problems()
    else:
        try:
            env = fit_envelope(s3[sat], s1[sat], opt.confidence)
        except FitError as exc:
            first = int(np.flatnonzero(sat)[0])
            table.add_problem(first, "condition", f"effective envelope from the saturated tests: {exc} "
                                                  "(or pass --c-eff and --phi-eff)")
    groups = table.get("group") if "group" in table.columns else np.array([""] * len(table), dtype=object)
    for g in set(groups) - {""}:
        members = np.flatnonzero(groups == g)
        if len(members) < 2:
            table.add_problem(int(members[0]), "group", f"group '{g}' has one test: a shared tensor needs at least two")
        elif sat[members].any():
            table.add_problem(int(members[sat[members]][0]), "group",
                              f"group '{g}' holds a saturated test; groups are for unsaturated tests")
    table.raise_if_problems()
    if env.c < 0:
        hint = ("; if sigma3 is the cell pressure of back-pressured tests, give their 'back_pressure' "
                "(sigma' = sigma - u_b)" if not np.any(u[sat] != 0) else "")
        warnings.append(f"c' = {env.c / 1e3:.4g} kPa < 0 from the saturated tests: a negative cohesion has no "
                        f"physical meaning and the bounds below rest on it{hint}")

    nan = np.full(len(table), np.nan)
    bounds = {}
    for name, b in (("spherical", tx.spherical_bound(s1, s3, env.c, env.phi)),
                    ("lower", tx.lower_bound(s1, s3, env.c, env.phi)),
                    ("edtp", tx.edtp_bound(s1, s3, p0, np.where(np.isnan(s0), 0.0, s0), env.c, env.phi))):
        keep = unsat if name != "edtp" else unsat & np.isfinite(s0)
        bounds[name] = tx.Bound(*(np.where(keep, getattr(b, f), nan)
                                  for f in ("sigma1_cap", "sigma3_cap", "p_prime", "q_prime")))
    if (unsat & np.isnan(s0)).any():
        notes.append("EDTP bound skipped where s0 (initial suction) is not given")
    q_sat = tx.drained_strength(p0, env.c, env.phi)
    tests = {
        "test_id": table.columns["test_id"], "condition": cond, "group": groups, "line": table.lines,
        "sigma1": s1, "sigma2": s2, "sigma3": s3, "p": tx.mean_stress(s1, s3, s2), "q": q,
        "p0": p0, "s0": s0, "strain_f": d["strain"], "lode": tx.lode_angle(s1, s2, s3),
        "sigma3_total": s3_total, "back_pressure": pp["u_b"], "u_a": pp["u_a"], "radial_pressure": pp["radial"],
        "membrane": np.where(dq != 0, dq, np.nan) if opt.membrane is not None else nan,
    }
    inputs = [input_file(source, table)] + ([input_file(t.path, t) for t in raw_curves.tables] if raw_curves else [])
    return TriaxialResult(table.path, env, tests, bounds, q_sat, _group_analysis(tests, env), notes, opt, inputs,
                          warnings)


def _group_analysis(t: dict, env: Envelope) -> list[dict]:
    """Appendix 1 of Prunier et al. (2024) for every group of unsaturated tests sharing one tensor."""
    out = []
    for g in [g for g in dict.fromkeys(t["group"]) if g]:
        sel = t["group"] == g
        s1, s2, s3 = t["sigma1"][sel], t["sigma2"][sel], t["sigma3"][sel]
        res: dict = {"group": g, "tests": [str(x) for x in t["test_id"][sel]], "n": int(sel.sum())}
        if np.ptp(s3) <= 0:
            res["error"] = "all tests of the group share one sigma3: no apparent envelope"
            out.append(res)
            continue
        kp, b = np.polyfit(s3, s1, 1)
        if kp <= 1.0:
            res["error"] = f"apparent K_p = {kp:.3g} <= 1: no apparent friction angle"
            out.append(res)
            continue
        C, phi = tx.envelope_from_principal_fit(kp, b)
        Q = tx.lode_ratio(s1, s2, s3)
        c2 = tx.fictive_cohesion_lower(C, env.c, env.phi)
        a1, a3 = tx.axisymmetric_group_cap(C, c2, env.c, env.phi)
        res.update({
            "C_apparent_kPa": _kpa(C), "phi_apparent_deg": num(phi),
            "phi_difference_deg": num(phi - env.phi),
            "eq37_sigma_cap_kPa": _kpa(tx.spherical_group_cap(C, env.c, env.phi)),
            "eq48_lower": {"C_fictive_kPa": _kpa(c2), "sigma1_cap_kPa": _kpa(a1), "sigma3_cap_kPa": _kpa(a3)},
            "lode_angles_deg": [num(x) for x in t["lode"][sel]],
            "eq49_holds": bool(np.ptp(Q) <= 1e-3),
        })
        out.append(res)
    return out
