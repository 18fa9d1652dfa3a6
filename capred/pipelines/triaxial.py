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

from ..errors import FitError, OptionError
from ..fitting.linear import LineFit, fit_line
from ..io.table import Column, Table, read_table
from ..physics import triaxial as tx
from ..references import cite
from ..result import InputFile, Options, Result, TableSpec, input_file, num

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


@dataclass(frozen=True)
class TriaxialOptions(Options):
    """Options of `capred triaxial-bounds`.

    ``c_eff`` [Pa] (or a string with a unit) and ``phi_eff`` [deg] replace the
    fit of the saturated tests; ``curves`` is a long table of raw curves
    (test_id, axial_strain, q) whose peaks give q_f.
    """

    QUANTITIES = {"c_eff": "c_eff", "phi_eff": "phi_eff"}

    c_eff: float | None = None  # Pa
    phi_eff: float | None = None  # deg
    confidence: float = 0.95
    curves: str | Path | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if (self.c_eff is None) != (self.phi_eff is None):
            raise OptionError("give both --c-eff and --phi-eff, or neither")


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
    """q at failure (from q_f, sigma1 or the curves) per test; problems collected in ``table``."""
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
    strain = np.full(n, np.nan)
    table.check_unique("test_id")
    for i in range(n):
        tid = table.columns["test_id"][i]
        if np.isnan(q[i]) and np.isfinite(s1[i]):
            q[i] = s1[i] - s3[i]
            if q[i] <= 0:
                table.add_problem(i, "sigma1", f"sigma1 = {table.value_text('sigma1', i)} is not above sigma3: q_f <= 0")
        if np.isnan(q[i]) and curves and tid in curves:
            q[i], strain[i] = curves[tid]
            if q[i] <= 0:
                table.add_problem(i, "test_id", f"the curve of '{tid}' peaks at q = {q[i] / 1e3:.4g} kPa <= 0")
        if np.isnan(q[i]) and not any(p.line == int(table.lines[i]) for p in table.problems):
            table.add_problem(i, "q_f" if "q_f" in table.columns else None,
                              "no failure deviator: give 'q_f' or 'sigma1'" + (" or a curve" if curves else ""))
        if np.isnan(s3[i]) and not any(p.line == int(table.lines[i]) for p in table.problems):
            table.add_problem(i, "sigma3", "sigma3 is blank")
    if curves:
        unknown = sorted(set(curves) - set(table.columns["test_id"]))
        if unknown:
            table.notes.append(f"curves for tests not in the table ignored: {', '.join(unknown)}")
    return table, {"q": q, "strain": strain}


def run_triaxial_bounds(source, options: TriaxialOptions | None = None,
                        curves: str | Path | None = None) -> TriaxialResult:
    """Envelope, bounds and group analysis of a triaxial table (see module docstring).

    ``source`` is a CSV path or a DataFrame; ``curves`` (or ``options.curves``)
    a long CSV of raw curves.

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

        raw_curves = read_curves(curves, table)
        table.problems += raw_curves.problems  # reported with the table's own, in one round
        table.notes += raw_curves.notes
        table.warnings += raw_curves.warnings
    table, d = load_triaxial_table(table, raw_curves.peaks if raw_curves else None)
    table.raise_if_problems()

    cond = table.columns["condition"]
    sat = cond == "saturated"
    unsat = ~sat
    s3 = table.columns["sigma3"]
    q = d["q"]
    s1 = s3 + q
    s2 = table.get("sigma2").copy()
    s2[np.isnan(s2)] = s3[np.isnan(s2)]
    p0 = table.get("p0").copy()
    p0[np.isnan(p0)] = s3[np.isnan(p0)]
    s0 = table.get("s0")
    for i in np.flatnonzero(np.isfinite(s2)):
        if not s3[i] <= s2[i] <= s1[i]:
            table.add_problem(i, "sigma2", "sigma2 must lie between sigma3 and sigma1")

    notes = list(table.notes)
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
    }
    inputs = [input_file(source, table)] + ([input_file(t.path, t) for t in raw_curves.tables] if raw_curves else [])
    return TriaxialResult(table.path, env, tests, bounds, q_sat, _group_analysis(tests, env), notes, opt, inputs,
                          opt.warnings + table.warnings)


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
