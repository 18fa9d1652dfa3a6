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
from ..result import InputFile, Options, Result, input_file, num
from ..units import parse_quantity

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column(
        "condition", "text", None, "test condition", ("state", "saturation_state"), choices=("saturated", "unsaturated")
    ),
    Column(
        "sigma3", "pressure", "kPa", "sigma3", ("s3", "confining_pressure", "sigma_3", "cell_pressure"), "nonnegative"
    ),
    Column("q_f", "pressure", "kPa", "q_f", ("q", "qf", "q_max", "deviator", "q_peak"), "positive"),
    Column("sigma1", "pressure", "kPa", "sigma1", ("s1", "sigma_1"), "nonnegative"),
    Column("sigma2", "pressure", "kPa", "sigma2", ("s2", "sigma_2"), "nonnegative"),
    Column("p0", "pressure", "kPa", "p0", ("p_0", "initial_pressure"), "nonnegative"),
    Column("s0", "pressure", "kPa", "s0", ("s_0", "initial_suction", "suction"), "nonnegative"),
    Column("group", "text", None, "group", ("tensor_group",)),
    Column("D0", "length", "mm", "initial diameter", ("initial_diameter", "diameter", "d_0"), "positive"),
    Column("H0", "length", "mm", "initial height", ("initial_height", "height", "h_0"), "positive"),
    Column(
        "back_pressure",
        "pressure",
        "kPa",
        "back pressure u_b (pore-water pressure)",
        ("backpressure", "u_b", "bp", "back_pressure_kpa"),
    ),
    Column(
        "u_a", "pressure", "kPa", "pore-air pressure (axis translation)", ("pore_air_pressure", "air_pressure", "ua")
    ),
    Column(
        "branch",
        "text",
        None,
        "loading branch (compression or extension; blank: from sigma2)",
        ("loading", "triaxial_branch", "compression_extension"),
    ),
    Column(
        "pair",
        "text",
        None,
        "paired saturated test",
        ("saturated_pair", "paired_test", "sat_pair", "pair_id", "saturated_test"),
    ),
    Column(
        "strain_at_failure",
        "dimensionless",
        "-",
        "axial strain at failure",
        ("eps_f", "axial_strain_f", "axial_strain_at_failure", "strain_f"),
    ),
]

CURVE_SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
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
        """Slope of the envelope in the (p, q) plane, triaxial compression [-]."""
        return float(tx.envelope_qp(self.c, self.phi)[0])

    @property
    def k(self) -> float:
        """Intercept of the envelope in the (p, q) plane, triaxial compression [Pa]."""
        return float(tx.envelope_qp(self.c, self.phi)[1])

    @property
    def M_extension(self) -> float:
        """Slope in the (p, q) plane in triaxial extension, 6 sin phi'/(3 + sin phi') [-]."""
        return float(tx.envelope_qp(self.c, self.phi, "extension")[0])

    @property
    def k_extension(self) -> float:
        """Intercept in the (p, q) plane in triaxial extension [Pa]."""
        return float(tx.envelope_qp(self.c, self.phi, "extension")[1])


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

    QUANTITIES = {"c_eff": "c_eff", "phi_eff": "phi_eff", **{k: k for k in _MEMBRANE if k in _GLOSSARY}}

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
            raise OptionError(
                "give both --membrane-thickness and --membrane-modulus for the membrane correction, or neither"
            )

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
            "sigma1_cap_kPa": _kpa(b.sigma1_cap[i]),
            "sigma2_cap_kPa": _kpa((b.sigma3_cap if b.sigma2_cap is None else b.sigma2_cap)[i]),
            "sigma3_cap_kPa": _kpa(b.sigma3_cap[i]),
            "p_cap_kPa": _kpa(b.p_cap[i]),
            "q_cap_kPa": _kpa(b.q_cap[i]),
            "p_prime_kPa": _kpa(b.p_prime[i]),
            "q_prime_kPa": _kpa(b.q_prime[i]),
            "gain": num(gain),
            "positive_component": bool(b.positive[i]),
        }

    def payload(self, lazy: bool = False) -> dict:
        e = self.envelope
        t = self.tests
        tests = []
        for i in range(len(t["test_id"])):
            row = {
                "test_id": str(t["test_id"][i]),
                "condition": str(t["condition"][i]),
                "group": t["group"][i] or None,
                "line": int(t["line"][i]),
                "sigma3_kPa": _kpa(t["sigma3"][i]),
                "sigma2_kPa": _kpa(t["sigma2"][i]),
                "sigma1_kPa": _kpa(t["sigma1"][i]),
                "p_kPa": _kpa(t["p"][i]),
                "q_kPa": _kpa(t["q"][i]),
                "p0_kPa": _kpa(t["p0"][i]),
                "s0_kPa": _kpa(t["s0"][i]),
                "sigma3_total_kPa": _kpa(t["sigma3_total"][i]),
                "back_pressure_kPa": _kpa(t["back_pressure"][i]),
                "u_a_kPa": _kpa(t["u_a"][i]),
                "radial_pressure_kPa": _kpa(t["radial_pressure"][i]),
                "membrane_correction_kPa": _kpa(t["membrane"][i]),
                "lode_angle_deg": num(t["lode"][i]),
                "branch": str(t["branch"][i]),
                "pair": t["pair"][i] or None,
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
                "c_kPa": _kpa(e.c),
                "phi_deg": num(e.phi),
                "M": num(e.M),
                "k_kPa": _kpa(e.k),
                "M_extension": num(e.M_extension),
                "k_extension_kPa": _kpa(e.k_extension),
                "c_se_kPa": _kpa(e.c_se) if e.c_se is not None else None,
                "phi_se_deg": num(e.phi_se) if e.phi_se is not None else None,
                "source": e.source,
                "n": e.fit.n if e.fit else None,
                "r2": num(e.fit.r2) if e.fit else None,
                "method": (
                    f"least squares of sigma'_1 on sigma'_3 ({cite('prunier2024', 'eq. 25')})"
                    if e.fit
                    else "given as options"
                ),
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

                cached["groups"] = pd.json_normalize([_group_row(g) for g in self.to_json()["groups"]])
            self.__dict__["_tables"] = cached
        return cached

    def season_rows(self) -> list[dict]:
        e = self.envelope
        n_flag = sum(1 for i in range(len(self.tests["test_id"])) if self.flags(i))
        return [
            {
                "material": "(envelope)",
                "c [kPa]": num(e.c / 1e3),
                "c_se [kPa]": num(e.c_se / 1e3) if e.c_se is not None else None,
                "phi [deg]": num(e.phi),
                "phi_se [deg]": num(e.phi_se),
                "n_dry": e.fit.n if e.fit else None,
                "n_wet": int(self.unsaturated.sum()),
                "best_model": None,
                "best_rmse [kPa]": None,
                "flagged_tests": n_flag,
            }
        ]

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


def _group_row(g: dict) -> dict:
    """A group's JSON record as one flat CSV row: lists joined by ';', 95 % intervals as _low/_high columns."""
    row = {}
    for k, v in g.items():
        if k.endswith("_ci95_kPa"):
            base = k[: -len("_ci95_kPa")]
            row[f"{base}_ci95_low_kPa"], row[f"{base}_ci95_high_kPa"] = v if v else (None, None)
        elif isinstance(v, list):
            row[k] = ";".join("" if x is None else (x if isinstance(x, str) else repr(x)) for x in v)
        else:
            row[k] = v
    return row


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
                table.add_problem(
                    i, "sigma1", f"sigma1 = {table.value_text('sigma1', i)} is not above sigma3: q_f <= 0"
                )
        if np.isnan(q[i]) and curves and tid in curves:
            q[i], strain[i] = curves[tid]
            from_curve[i] = True
            if q[i] <= 0:
                table.add_problem(i, "test_id", f"the curve of '{tid}' peaks at q = {q[i] / 1e3:.4g} kPa <= 0")
        if np.isnan(q[i]) and not any(p.line == int(table.lines[i]) for p in table.problems):
            table.add_problem(
                i,
                "q_f" if "q_f" in table.columns else None,
                "no failure deviator: give 'q_f' or 'sigma1'" + (" or a curve" if curves else ""),
            )
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


def pore_pressures(table: Table, at_peak: dict[str, dict[str, float]], q, ext=None) -> dict:
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
    if ext is None:
        ext = np.zeros(n, bool)
    exp = {
        k: np.array([at_peak.get(t, {}).get(k, np.nan) for t in tids])
        for k in ("radial_pressure", "back_pressure", "pore_pressure", "air_pressure")
    }
    u = np.zeros(n)
    notes, warnings = [], []
    filled_s3, from_export, already = [], [], []
    for i in range(n):
        tid = tids[i]
        if sat[i]:
            if np.isfinite(ua_col[i]):
                table.add_problem(
                    i,
                    "u_a",
                    "u_a is for unsaturated tests (net stress sigma - u_a); the pore "
                    "pressure of a saturated test is its back_pressure",
                )
            u_tab = ub_col[i]
            u_exp = exp["pore_pressure"][i] if np.isfinite(exp["pore_pressure"][i]) else exp["back_pressure"][i]
        else:
            u_tab = ua_col[i]
            u_exp = exp["air_pressure"][i]
            u_w = ub_col[i] if np.isfinite(ub_col[i]) else exp["back_pressure"][i]
            if np.isfinite(ub_col[i]) and not (np.isfinite(ua_col[i]) or np.isfinite(u_exp)):
                table.add_problem(
                    i,
                    "back_pressure",
                    "an unsaturated test's back pressure is the pore-water "
                    "pressure of axis translation: give the pore-air pressure 'u_a' too (the "
                    "stresses are net of u_a)",
                )
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
            elif (
                np.isfinite(u_known)
                and abs(u_known) > pressure_tolerance(radial)
                and abs(cell - (radial - u_known)) <= pressure_tolerance(radial)
            ):
                total = False
                already.append(tid)
                if np.isfinite(u_tab):
                    warnings.append(
                        f"test '{tid}': {name} = {cell / 1e3:.4g} kPa equals the export's radial "
                        f"pressure {radial / 1e3:.4g} kPa minus the pore pressure {u_known / 1e3:.4g} kPa: "
                        "the table's stresses are already effective; the pore pressure of the table "
                        "is not subtracted again"
                    )
            else:
                warnings.append(
                    f"test '{tid}': {name} = {cell / 1e3:.4g} kPa in the table but the export's radial "
                    f"pressure at failure is {radial / 1e3:.4g} kPa (tolerance "
                    f"{pressure_tolerance(radial) / 1e3:.3g} kPa, ASTM D4767); the table's value is used"
                )
        if total:
            if np.isfinite(u_tab):
                u[i] = u_tab
            elif np.isfinite(u_exp):
                u[i] = u_exp
                from_export.append(tid)
    if filled_s3:
        notes.append(f"sigma3 taken from the export's radial pressure at failure: {', '.join(filled_s3)}")
    if from_export:
        notes.append(
            f"pore pressure taken from the export at failure (sigma' = sigma - u_w saturated, "
            f"sigma - u_a unsaturated): {', '.join(from_export)}"
        )
    if already:
        notes.append(
            f"sigma3 already effective (= radial pressure - pore pressure of the export): {', '.join(already)}"
        )
    ub = np.where(sat, np.where(np.isfinite(ub_col), ub_col, np.where(u != 0, u, np.nan)), ub_col)
    ua = np.where(~sat, np.where(np.isfinite(ua_col), ua_col, np.where(u != 0, u, np.nan)), np.nan)
    return {
        "u": u,
        "u_b": ub,
        "u_a": ua,
        "radial": exp["radial_pressure"],
        "sigma3": s3,
        "s0": s0,
        "notes": notes,
        "warnings": warnings,
    }


def run_triaxial_bounds(
    source, options: TriaxialOptions | None = None, curves: str | Path | None = None
) -> TriaxialResult:
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
            need = [
                w
                for w, ok in (("'strain_at_failure'", np.isfinite(d["strain"][i])), ("'D0'", np.isfinite(D0[i])))
                if not ok
            ]
            if need:
                table.add_problem(
                    i,
                    "test_id",
                    f"the membrane correction of '{tid}' needs {' and '.join(need)} (or its raw curve with --curves)",
                )
                continue
            dq[i] = float(membrane_correction(d["strain"][i], D0[i], *opt.membrane))
        q = q - np.where(d["from_curve"], 0.0, dq)  # a curve's readings were corrected before its peak
        for i in np.flatnonzero(q <= 0):
            table.add_problem(int(i), "test_id", f"after the membrane correction ({dq[i] / 1e3:.4g} kPa) q_f <= 0")
        t_m, E_m = opt.membrane
        notes.append(
            f"membrane correction of the deviator (ASTM D4767-11): Δq = 4 E_m t_m ε_a / D0 with "
            f"t_m = {t_m * 1e3:.4g} mm, E_m = {E_m / 1e3:.4g} kPa; D0 for the diameter after consolidation"
        )
    else:
        notes.append(
            "no membrane correction of the deviator (give --membrane-thickness and --membrane-modulus "
            "to apply ASTM D4767-11's)"
        )

    branch_col = (
        np.array([str(x).strip().lower() for x in table.columns["branch"]], dtype=object)
        if "branch" in table.columns
        else np.array([""] * len(table), dtype=object)
    )
    for i in np.flatnonzero(~np.isin(branch_col, ("", "compression", "extension"))):
        table.add_problem(
            int(i),
            "branch",
            f"'{table.value_text('branch', int(i))}' is not one of 'compression' "
            "or 'extension' (or blank: the branch follows from sigma2)",
        )
    s2_raw = table.get("sigma2")
    ext_raw = (branch_col == "extension") | (np.abs(s2_raw - (table.columns["sigma3"] + q)) <= 1e-9 * np.abs(s2_raw))
    pp = pore_pressures(table, raw_curves.at_peak if raw_curves else {}, q, ext_raw)
    notes += pp["notes"]
    warnings += pp["warnings"]
    u = pp["u"]
    for i in np.flatnonzero(np.isnan(pp["sigma3"])):
        table.add_problem(int(i), "sigma3", "sigma3 is blank")
    table.raise_if_problems()
    s3_total = pp["sigma3"]
    s3 = s3_total - u
    s1 = s3 + q
    s2 = s2_raw - u
    s2 = np.where(np.isnan(s2), np.where(branch_col == "extension", s1, s3), s2)
    lode = np.asarray(tx.lode_angle_deg(s1, s2, s3), float)
    branch = np.atleast_1d(tx.lode_branch(s1, s2, s3)).astype(object)
    for i in np.flatnonzero((branch_col != "") & (branch != branch_col)):
        table.add_problem(
            int(i),
            "branch",
            f"branch '{branch_col[i]}' but sigma2 = {s2_raw[i] / 1e3:.4g} kPa gives a "
            f"Lode angle of {lode[i]:.3g} deg ({branch[i]}; compression is 0, extension 60, within "
            f"{tx.LODE_TOL_DEG:g} deg)",
        )
    axi = branch != "general"
    phys_branch = np.where(axi, branch, "compression")
    p0 = table.get("p0") - u
    p0[np.isnan(p0)] = s3[np.isnan(p0)]
    s0 = pp["s0"]
    for i in np.flatnonzero(s3 < 0):
        kind = "effective" if sat[i] else "net"
        table.add_problem(
            int(i),
            "sigma3",
            f"the {kind} confining stress sigma3 - {'u_b' if sat[i] else 'u_a'} = {s3[i] / 1e3:.4g} kPa is negative",
        )
    for i in np.flatnonzero(np.isfinite(s2_raw)):
        if not s3[i] * (1 - 1e-12) <= s2[i] <= s1[i] * (1 + 1e-12):
            table.add_problem(i, "sigma2", "sigma2 must lie between sigma3 and sigma1")
    if np.any(u != 0):
        notes.append(
            "stresses net of the pore pressure: sigma' = sigma - u_b (saturated tests, Terzaghi), "
            "sigma - u_a (unsaturated tests, axis translation); sigma3_total_kPa keeps the cell pressure"
        )

    if opt.c_eff is not None:
        env = Envelope(opt.c_eff, opt.phi_eff, None, None, "options")
        if sat.any():
            notes.append("envelope taken from --c-eff/--phi-eff; the saturated tests are only plotted")
    elif sat.sum() == 0:
        table.add_problem(
            None,
            "condition",
            "no saturated test and no envelope given: add saturated drained tests or pass --c-eff and --phi-eff",
        )
        table.raise_if_problems()
    else:
        try:
            env = fit_envelope(s3[sat], s1[sat], opt.confidence)
        except FitError as exc:
            first = int(np.flatnonzero(sat)[0])
            table.add_problem(
                first,
                "condition",
                f"effective envelope from the saturated tests: {exc} (or pass --c-eff and --phi-eff)",
            )
    groups = table.get("group") if "group" in table.columns else np.array([""] * len(table), dtype=object)
    pairs = table.columns["pair"] if "pair" in table.columns else np.array([""] * len(table), dtype=object)
    for g in set(groups) - {""}:
        members = np.flatnonzero(groups == g)
        if len(members) < 2:
            table.add_problem(int(members[0]), "group", f"group '{g}' has one test: a shared tensor needs at least two")
        elif sat[members].any():
            table.add_problem(
                int(members[sat[members]][0]),
                "group",
                f"group '{g}' holds a saturated test; groups are for unsaturated tests",
            )
        elif 0 < sum(bool(x) for x in pairs[members]) < len(members):
            table.add_problem(
                int(members[0]),
                "pair",
                f"group '{g}': give a paired saturated test for every test of the group, or for none",
            )
    ids = {str(x): i for i, x in enumerate(table.columns["test_id"])}
    for i in np.flatnonzero(pairs != ""):
        j = ids.get(str(pairs[i]))
        if sat[i]:
            table.add_problem(
                int(i),
                "pair",
                "a pair is the saturated test paired with an unsaturated one; give it on the unsaturated test's row",
            )
        elif j is None:
            table.add_problem(int(i), "pair", f"no test '{pairs[i]}' in the table")
        elif not sat[j]:
            table.add_problem(int(i), "pair", f"'{pairs[i]}' is not a saturated test")
    table.raise_if_problems()
    if env.c < 0:
        hint = (
            "; if sigma3 is the cell pressure of back-pressured tests, give their 'back_pressure' "
            "(sigma' = sigma - u_b)"
            if not np.any(u[sat] != 0)
            else ""
        )
        warnings.append(
            f"c' = {env.c / 1e3:.4g} kPa < 0 from the saturated tests: a negative cohesion has no "
            f"physical meaning and the bounds below rest on it{hint}"
        )

    nan = np.full(len(table), np.nan)
    bounds = {}
    s0_or_0 = np.where(np.isnan(s0), 0.0, s0)
    for name, b in (
        ("spherical", tx.spherical_bound(s1, s3, env.c, env.phi, phys_branch)),
        ("lower", tx.lower_bound(s1, s3, env.c, env.phi, phys_branch)),
        ("edtp", tx.edtp_bound(s1, s3, p0, s0_or_0, env.c, env.phi, phys_branch)),
    ):
        keep = unsat & axi if name != "edtp" else unsat & axi & np.isfinite(s0)
        bounds[name] = tx.Bound(
            *(
                np.where(keep, getattr(b, f), nan)
                for f in ("sigma1_cap", "sigma3_cap", "p_prime", "q_prime", "sigma2_cap")
            )
        )
    if (unsat & axi & np.isnan(s0)).any():
        notes.append("EDTP bound skipped where s0 (initial suction) is not given")
    if (unsat & ~axi).any():
        notes.append(
            "bounds (section 4 of Prunier et al. 2024) are for axisymmetric tests: none for the "
            f"true-triaxial tests {', '.join(str(x) for x in table.columns['test_id'][unsat & ~axi])}; "
            "a group of them at one Lode angle gets eq. 50"
        )
    if (branch == "extension").any():
        notes.append(
            "extension tests (sigma2 = sigma1) use the extension form of the criterion, "
            "M = 6 sin phi'/(3 + sin phi'), in the bounds, q'_sat and the figures"
        )
    q_sat = tx.drained_strength(p0, env.c, env.phi, phys_branch)
    tests = {
        "test_id": table.columns["test_id"],
        "condition": cond,
        "group": groups,
        "line": table.lines,
        "sigma1": s1,
        "sigma2": s2,
        "sigma3": s3,
        "p": tx.mean_stress(s1, s3, s2),
        "q": q,
        "p0": p0,
        "s0": s0,
        "strain_f": d["strain"],
        "lode": lode,
        "branch": branch,
        "pair": pairs,
        "sigma3_total": s3_total,
        "back_pressure": pp["u_b"],
        "u_a": pp["u_a"],
        "radial_pressure": pp["radial"],
        "membrane": np.where(dq != 0, dq, np.nan) if opt.membrane is not None else nan,
    }
    inputs = [input_file(source, table)] + ([input_file(t.path, t) for t in raw_curves.tables] if raw_curves else [])
    group_records = _group_analysis(tests, env)
    for g in group_records:
        notes += [f"group {g['group']}: {g[k]}" for k in ("needs", "warning") if g.get(k)]
    return TriaxialResult(table.path, env, tests, bounds, q_sat, group_records, notes, opt, inputs, warnings)


def _ci95(value: float, se: float, dof: int) -> list | None:
    """[low, high] [kPa] of value +- t(0.975, dof) se (values in Pa), None without a finite se."""
    from scipy.stats import t as student

    if dof < 1 or not np.isfinite(se):
        return None
    h = float(student.ppf(0.975, dof)) * se
    return [_kpa(value - h), _kpa(value + h)]


def _tensor_json(gt: tx.GroupTensor) -> dict:
    """The keys of a group's capillary tensor (eq. 48 or 50) in a group's JSON record."""
    out = {}
    for k in ("sigma1_cap", "sigma2_cap", "sigma3_cap"):
        v, se = getattr(gt, k), getattr(gt, k + "_se")
        out[f"{k}_kPa"], out[f"{k}_se_kPa"], out[f"{k}_ci95_kPa"] = _kpa(v), _kpa(se), _ci95(v, se, gt.dof)
    out.update(
        {
            "p_cap_kPa": _kpa(gt.p_cap),
            "q_cap_kPa": _kpa(gt.q_cap),
            "dof": gt.dof,
            "C_kPa": _kpa(gt.C_apparent),
            "C_se_kPa": _kpa(gt.C_apparent_se),
            "C_fictive_kPa": _kpa(gt.C_fictive),
            "C_fictive_se_kPa": _kpa(gt.C_fictive_se),
            "Ci_kPa": _kpa(gt.Ci_apparent),
            "Ci_fictive_kPa": _kpa(gt.Ci_fictive),
            "phi_i_deg": num(gt.phi_i_deg),
            "phi_apparent_se_deg": num(gt.phi_apparent_se_deg),
        }
    )
    return out


_TENSOR_KEYS = tuple(_tensor_json(tx.GroupTensor(2, 1, "compression", *([np.nan] * 10))))


def _group_analysis(t: dict, env: Envelope) -> list[dict]:
    """Appendix 1 of Prunier et al. (2024) for every group of unsaturated tests sharing one tensor.

    Every group gets the free regression sigma1 = K sigma3 + b through its
    failure states (apparent C, phi; eq. 35 and 43 ask phi = phi') and eq. 37
    (spherical tensor). With each test's paired saturated test (column
    ``pair``) an axisymmetric group gets eq. 48 with the fictive state sigma''
    (eq. 44-47) and a true-triaxial group at one Lode angle (eq. 49, within
    ``tx.LODE_TOL_DEG``) eq. 50, by the least squares the paper recommends
    (section 7.3), with standard errors and 95 % intervals (t, n - 1 dof).
    Without pairs eq. 48 is closed with sigma1_cap = 0 (the lower bound,
    eq. 24) and eq. 50 is not available; ``needs`` says what is missing.
    """
    out = []
    index = {str(x): i for i, x in enumerate(t["test_id"])}
    for g in [g for g in dict.fromkeys(t["group"]) if g]:
        sel = np.flatnonzero(t["group"] == g)
        s1, s2, s3 = t["sigma1"][sel], t["sigma2"][sel], t["sigma3"][sel]
        lode = t["lode"][sel]
        branches = sorted(set(t["branch"][sel]))
        res: dict = {
            "group": g,
            "tests": [str(x) for x in t["test_id"][sel]],
            "n": int(sel.size),
            "branch": branches[0] if len(branches) == 1 else "mixed",
            "lode_angles_deg": [num(x) for x in lode],
            "lode_spread_deg": num(np.ptp(lode)),
            "lode_tol_deg": tx.LODE_TOL_DEG,
            "eq49_holds": bool(np.ptp(lode) <= tx.LODE_TOL_DEG),
            "pairs": [t["pair"][i] or None for i in sel],
            "method": None,
            "needs": None,
            **dict.fromkeys(_TENSOR_KEYS),
        }
        if len(branches) > 1:
            res["error"] = (
                f"the group mixes {' and '.join(branches)} tests: one tensor is shared by tests of "
                "one branch (and one Lode angle, eq. 49)"
            )
            out.append(res)
            continue
        branch = branches[0]
        if np.ptp(s3) > 0:
            kp, b = np.polyfit(s3, s1, 1)
            if kp > 1.0:
                C, phi = tx.envelope_from_principal_fit(kp, b)
                M_app, k_app = tx.envelope_qp(C, phi, "extension" if branch == "extension" else "compression")
                res.update({"apparent_M": num(M_app), "apparent_k_kPa": _kpa(k_app)})
                c2 = tx.fictive_cohesion_lower(C, env.c, env.phi)
                a1, a3 = tx.axisymmetric_group_cap(C, c2, env.c, env.phi)
                res.update(
                    {
                        "C_apparent_kPa": _kpa(C),
                        "phi_apparent_deg": num(phi),
                        "phi_difference_deg": num(phi - env.phi),
                        "eq37_sigma_cap_kPa": _kpa(tx.spherical_group_cap(C, env.c, env.phi)),
                        "eq48_lower": {
                            "C_fictive_kPa": _kpa(c2),
                            "sigma1_cap_kPa": _kpa(a1),
                            "sigma3_cap_kPa": _kpa(a3),
                        },
                    }
                )
            else:
                res["apparent_error"] = f"apparent K_p = {kp:.3g} <= 1: no apparent friction angle"
        else:
            res["apparent_error"] = "all tests of the group share one sigma3: no apparent envelope (eq. 37)"
        paired = all(t["pair"][i] for i in sel)
        p_idx = np.array([index[t["pair"][i]] for i in sel]) if paired else None
        if paired:  # the fictive state sigma'' (eq. 44): the unsaturated circle's centre, the saturated radius
            f1, f3 = tx.fictive_state(s1, s3, t["sigma1"][p_idx], t["sigma3"][p_idx])
            res.update({"fictive_sigma1_kPa": [_kpa(x) for x in f1], "fictive_sigma3_kPa": [_kpa(x) for x in f3]})
        if branch == "general" and not res["eq49_holds"]:
            res["error"] = (
                f"the Lode angles of the group spread over {np.ptp(lode):.3g} deg > "
                f"{tx.LODE_TOL_DEG:g} deg: eq. 50 needs one Lode angle (eq. 49)"
            )
        elif branch == "general" and paired:
            gt = tx.true_triaxial_group_tensor(
                s1, s2, s3, t["sigma1"][p_idx], t["sigma2"][p_idx], t["sigma3"][p_idx], env.c, env.phi
            )
            res["method"] = "eq. 50 (fictive state of the paired saturated tests, constant Lode angle)"
            res.update(_tensor_json(gt))
            off = np.abs(t["lode"][p_idx] - np.mean(lode)) > tx.LODE_TOL_DEG
            if off.any():
                res["warning"] = "paired saturated tests at another Lode angle than the group: " + ", ".join(
                    str(t["test_id"][i]) for i in p_idx[off]
                )
        elif branch == "general":
            res["needs"] = (
                "eq. 50 needs, for each test, its paired saturated true-triaxial test at the same Lode "
                "angle (column 'pair' naming its test_id): the fictive state sigma'' takes its radii"
            )
        elif paired:
            gt = tx.axisymmetric_group_tensor(
                s1, s3, t["sigma1"][p_idx], t["sigma3"][p_idx], env.c, env.phi, branch=branch
            )
            res["method"] = "eq. 48 (fictive state sigma'' of the paired saturated tests, eq. 44-47)"
            res.update(_tensor_json(gt))
        else:
            res["needs"] = (
                "eq. 48 with the fictive state sigma'' (eq. 44-47) needs, for each test, the saturated "
                "test that reaches the same effective state at failure (column 'pair' naming its "
                "test_id); without it eq. 48 is closed with sigma1_cap = 0 (the lower bound, eq. 24)"
            )
            if "eq48_lower" in res:
                e = res["eq48_lower"]
                res["method"] = "eq. 48 closed with sigma1_cap = 0 (no paired saturated tests)"
                # in extension the major direction is radial: sigma2_cap = sigma1_cap
                res.update(
                    {
                        "sigma1_cap_kPa": e["sigma1_cap_kPa"],
                        "sigma3_cap_kPa": e["sigma3_cap_kPa"],
                        "sigma2_cap_kPa": e["sigma1_cap_kPa"] if branch == "extension" else e["sigma3_cap_kPa"],
                        "C_kPa": res["C_apparent_kPa"],
                        "C_fictive_kPa": e["C_fictive_kPa"],
                    }
                )
                caps = [res[k] * 1e3 for k in ("sigma1_cap_kPa", "sigma2_cap_kPa", "sigma3_cap_kPa")]
                res["p_cap_kPa"] = _kpa(sum(caps) / 3)
                res["q_cap_kPa"] = _kpa(caps[0] - caps[2])
        out.append(res)
    return out
