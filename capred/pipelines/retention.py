"""`capred retention`: water-retention models fitted per branch, with uncertainties and model selection,
and hysteresis fitted jointly (Kool & Parker 1987)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..errors import FitError, OptionError
from ..fitting.chi_laws import akaike_weights
from ..fitting.nonlinear import NonlinearFit
from ..fitting.retention_models import MODELS as FITTERS
from ..fitting.retention_models import confidence_band, fit_hysteresis, fit_model
from ..io.table import Column, read_table
from ..physics.shear import GAMMA_W
from ..references import cite
from ..result import InputFile, Options, Result, input_file, num

SCHEMA = [
    Column("suction", "pressure", "kPa", "suction", ("s", "matric_suction", "delta_u", "ua_uw"), "nonnegative"),
    Column(
        "head",
        "length",
        "cm",
        "suction head",
        ("h", "suction_head", "pressure_head", "z1", "matric_head"),
        "nonnegative",
    ),
    Column("pF", "dimensionless", "-", "pF (log10 of the head in cm of water)", ("pf", "p_f"), None),
    Column("S_R", "dimensionless", "-", "S_R", ("Sr", "degree_of_saturation", "saturation"), "fraction"),
    Column(
        "theta",
        "dimensionless",
        "-",
        "theta",
        ("theta_vol", "vwc", "water_content_vol", "theta_vol_m3_per_m3", "volumetric_water_content"),
        "fraction",
    ),
    Column(
        "w",
        "dimensionless",
        "-",
        "gravimetric water content w",
        ("gravimetric_water_content", "w_grav", "water_content"),
        "nonnegative",
    ),
    Column("rho_d", "density", "kg/m^3", "dry density", ("dry_density", "rhod"), "positive"),
    Column("z2", "volume", "cm^3", "air volume z2", ("air_volume", "burette", "V_a"), "nonnegative"),
    Column("V_v", "volume", "cm^3", "void volume V_v", ("Vv", "void_volume"), "positive"),
    Column("weight", "dimensionless", "-", "weight", ("weights", "w_fit"), "positive"),
    Column("branch", "text", None, "branch", ("path",), choices=("drying", "wetting")),
]

#: the models of `--model all`, in display order

# internal parameter -> (report name, factor SI -> report unit); water quantities named by the data kind
_REPORT = {
    "alpha": ("alpha_per_kPa", 1e3),
    "alpha1": ("alpha1_per_kPa", 1e3),
    "alpha2": ("alpha2_per_kPa", 1e3),
    "alpha_d": ("alpha_d_per_kPa", 1e3),
    "alpha_w": ("alpha_w_per_kPa", 1e3),
    "s_e": ("s_e_kPa", 1e-3),
    "s_m": ("s_m_kPa", 1e-3),
    "a": ("a_kPa", 1e-3),
    "s_r": ("s_r_kPa", 1e-3),
    "lam": ("lambda", 1.0),
    "n": ("n", 1.0),
    "m": ("m", 1.0),
    "n1": ("n1", 1.0),
    "n2": ("n2", 1.0),
    "w1": ("w1", 1.0),
    "sigma": ("sigma", 1.0),
}
# the same as a head of water [cm] (SWRC Fit and RETC report these)
_HEAD = {
    "alpha": "alpha_per_cm",
    "s_e": "h_b_cm",
    "s_m": "h_m_cm",
    "a": "a_cm",
    "s_r": "h_r_cm",
    "alpha1": "alpha1_per_cm",
    "alpha2": "alpha2_per_cm",
    "alpha_d": "alpha_d_per_cm",
    "alpha_w": "alpha_w_per_cm",
}


def _names(quantity: str) -> dict[str, str]:
    return {"y_s": "theta_s" if quantity == "theta" else "S_s", "y_r": "theta_r" if quantity == "theta" else "S_res"}


def report_name(internal: str, quantity: str) -> str:
    return _names(quantity).get(internal) or _report(internal)[0]


def _report(internal: str) -> tuple[str, float]:
    """(report name, factor SI -> report unit) of a parameter: from the table above, else from the unit its
    registry entry gives (Pa -> '<name>_kPa', 1/Pa -> '<name>_per_kPa', dimensionless as it is)."""
    if internal in _REPORT:
        return _REPORT[internal]
    unit = next((p.unit for m in FITTERS.values() for p in m.parameters if p.name == internal), "-")
    return {"Pa": (f"{internal}_kPa", 1e-3), "1/Pa": (f"{internal}_per_kPa", 1e3)}.get(unit, (internal, 1.0))


def _to_internal(name: str) -> tuple[str, float]:
    """Report name -> (internal name, factor report unit -> SI)."""
    for k, v in {"theta_s": "y_s", "S_s": "y_s", "theta_r": "y_r", "S_res": "y_r"}.items():
        if name == k:
            return v, 1.0
    for internal, (rep, f) in _REPORT.items():
        if name in (rep, internal) and internal not in ("alpha_d", "alpha_w"):
            return internal, 1.0 / f
    raise KeyError(name)


@dataclass(frozen=True)
class RetentionOptions(Options):
    """Options of `capred retention`: models to fit (names, or 'all'), fixed parameters (report names and
    units: kPa, 1/kPa), the unit weight of water ``gamma_w`` [N/m^3, or a string with a unit] and its
    density ``rho_w`` [kg/m^3] (for w rho_d/rho_w), and ``hysteresis`` ("kool-parker" or None)."""

    QUANTITIES = {"gamma_w": "gamma_w", "rho_w": "rho_w"}

    models: tuple[str, ...] = ("vg", "vg_m_free", "bc")
    fixed: dict[str, float] = field(default_factory=dict)
    gamma_w: float = GAMMA_W
    rho_w: float = 1000.0
    hysteresis: str | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        models = (self.models,) if isinstance(self.models, str) else tuple(self.models)
        if models == ("all",):
            models = tuple(FITTERS)
        unknown = [m for m in models if m not in FITTERS]
        if unknown or not models:
            raise OptionError(
                f"unknown model {unknown[0] if unknown else ''!r}; choose from {', '.join(FITTERS)} or all"
            )
        object.__setattr__(self, "models", models)
        for name in self.fixed:
            try:
                _to_internal(name)
            except KeyError:
                raise OptionError(f"fixed: unknown parameter '{name}'") from None
        if self.hysteresis not in (None, "kool-parker"):
            raise OptionError(f"--hysteresis must be kool-parker (got '{self.hysteresis}')")


@dataclass(repr=False)
class RetentionResult(Result):
    command = "retention"
    json_name = "fits.json"

    source: str
    quantity: str  # "theta" or "S_R"
    suction: np.ndarray  # Pa
    water: np.ndarray
    branch: np.ndarray
    branch_source: str
    fits: dict[str, dict[str, NonlinearFit]]  # branch -> model -> fit
    options: RetentionOptions
    notes: list[str] = field(default_factory=list)
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    hysteresis: NonlinearFit | None = None

    @property
    def names(self) -> tuple[str, str]:
        return ("theta_s", "theta_r") if self.quantity == "theta" else ("S_s", "S_res")

    def fit_json(self, f: NonlinearFit, model: str) -> dict:
        cm = self.options.gamma_w * 0.01  # Pa per cm of water head
        out: dict = {}
        for k, v in f.params.items():
            name = report_name(k, self.quantity)
            scale = _report(k)[1] if k not in ("y_s", "y_r") else 1.0
            se = f.stderr.get(k)
            ci = f.ci95(k)
            out[name] = num(v * scale)
            out[f"{name}_se"] = None if se is None or not np.isfinite(se) else num(se * scale)
            out[f"{name}_ci95"] = None if ci is None else [num(ci[0] * scale), num(ci[1] * scale)]
            if k in _HEAD:
                out[_HEAD[k]] = num(v * cm if k.startswith("alpha") else v / cm)
        if model in ("vg", "hysteresis") and "n" in f.params:
            out["m"] = num(1 - 1 / f.params["n"])
        out.update(
            {
                "r2": num(f.r2),
                "rmse": num(f.rmse),
                "aic": num(f.aic),
                "aicc": num(f.aicc),
                "bic": num(f.bic),
                "rss": num(f.rss),
                "n_points": f.n,
                "n_free": f.nfree,
                "converged": f.converged,
                "fixed": [report_name(k, self.quantity) for k in f.fixed],
                "at_bounds": [report_name(k, self.quantity) for k in f.at_bounds()],
                "correlation": {
                    report_name(a, self.quantity): {report_name(b, self.quantity): num(v) for b, v in row.items()}
                    for a, row in f.correlation().items()
                },
                "params_si": {k: num(v) for k, v in f.params.items()},
                "parameters": [report_name(k, self.quantity) for k in f.params],
                "held": [report_name(k, self.quantity) for k in getattr(f, "held", ())],
                "notes": list(getattr(f, "notes", [])),
                "model": FITTERS[model].label if model in FITTERS else model,
                "reference": cite(FITTERS[model].reference if model in FITTERS else "kool_parker1987"),
            }
        )
        return out

    def model_selection(self, branch: str) -> dict:
        fits = self.fits.get(branch, {})
        weights = akaike_weights({m: f.aicc for m, f in fits.items()})
        return {
            m: {"aicc": num(fits[m].aicc), "delta_aicc": num(d), "weight": num(w), "k": fits[m].nfree}
            for m, (d, w) in weights.items()
        }

    def payload(self, lazy: bool = False) -> dict:
        branches = {
            b: {
                "n_points": int(np.sum(self.branch == b)),
                "fits": {m: self.fit_json(f, m) for m, f in fits.items()},
                "model_selection": self.model_selection(b),
            }
            for b, fits in self.fits.items()
        }
        main = "drying" if "drying" in branches else next(iter(branches), None)
        out = {
            "source": self.source,
            "quantity": self.quantity,
            "branch_source": self.branch_source,
            "main_branch": main,
            "fits": branches[main]["fits"] if main else {},
            "branches": branches,
            "model_selection": branches[main]["model_selection"] if main else {},
        }
        if self.hysteresis is not None:
            h = self.hysteresis
            js = self.fit_json(h, "hysteresis")
            ind = [self.fits[b]["vg"] for b in ("drying", "wetting") if "vg" in self.fits.get(b, {})]
            ind_aicc = None
            if len(ind) == 2:
                n = sum(f.n for f in ind)
                k = sum(f.nfree for f in ind)
                rss = sum(f.rss for f in ind)
                ind_aicc = n * np.log(rss / n) + 2 * k + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else np.nan)
            keys = [report_name(k, self.quantity) for k in h.params]
            out["hysteresis"] = {
                "model": "kool-parker",
                "params": {k: js[k] for k in keys},
                "se": {k: js[f"{k}_se"] for k in keys},
                "alpha_ratio": num(h.params["alpha_w"] / h.params["alpha_d"]),
                "rss": js["rss"],
                "r2": js["r2"],
                "aicc": js["aicc"],
                "independent_aicc": num(ind_aicc),
                "reference": cite("kool_parker1987"),
            }
        return out

    def season_rows(self) -> list[dict]:
        """One row per branch for a batch's season.csv: the best model (lowest AICc) and its parameters."""
        rows = []
        for b, fits in self.fits.items():
            if not fits:
                continue
            sel = self.model_selection(b)
            best = min(sel, key=lambda m: (sel[m]["aicc"] is None, sel[m]["aicc"] or 0.0))
            js = self.fit_json(fits[best], best)
            params = {name: js.get(name) for name in js["parameters"]}
            rows.append(
                {
                    "branch": b,
                    "best_model": best,
                    "n_points": fits[best].n,
                    "r2": js["r2"],
                    "rmse": js["rmse"],
                    "aicc": js["aicc"],
                    **params,
                }
            )
        return rows

    def tables(self) -> dict:
        """fits: one row per branch and model (parameters with their standard errors)."""
        cached = self.__dict__.get("_tables")
        if cached is None:
            cached = self.__dict__["_tables"] = {"fits": self._fits_table()}
        return cached

    def _fits_table(self):
        import pandas as pd

        rows = []
        for b, d in self.payload()["branches"].items():
            for m, v in d["fits"].items():
                rows.append(
                    {"branch": b, "model": m, **{k: x for k, x in v.items() if k not in ("correlation", "params_si")}}
                )
        return pd.DataFrame(rows)

    def curve(self, branch: str, model: str, s):
        return FITTERS[model].water(s, **self.fits[branch][model].params)

    def band(self, branch: str, model: str, s):
        return confidence_band(model, self.fits[branch][model], s)


def parse_fixed(items: list[str]) -> dict[str, float]:
    """'theta_s=0.25' -> {'theta_s': 0.25}; values in the report units (kPa, 1/kPa)."""
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        try:
            _to_internal(name)
        except KeyError:
            known = ", ".join(["theta_s", "theta_r", "S_s", "S_res", *sorted({v[0] for v in _REPORT.values()})])
            raise OptionError(f"--fix '{item}': expected NAME=VALUE with NAME one of {known}") from None
        if not sep:
            raise OptionError(f"--fix '{item}': expected NAME=VALUE")
        try:
            out[name] = float(value)
        except ValueError:
            raise OptionError(f"--fix '{item}': '{value}' is not a number") from None
    return out


def _infer_branches(s: np.ndarray) -> np.ndarray:
    """Drying where suction rises from one reading to the next, wetting where it falls.

    Each reading takes the direction of the step that leads to it (the first
    reading that of the step after it); repeated suctions keep the current branch.
    """
    out = np.empty(len(s), dtype=object)
    steps = np.diff(s)
    first = next((d for d in steps if d != 0), 1.0)
    current = "drying" if first > 0 else "wetting"
    out[0] = current
    for i, d in enumerate(steps, start=1):
        if d > 0:
            current = "drying"
        elif d < 0:
            current = "wetting"
        out[i] = current
    return out


def _suction(table, opt) -> np.ndarray:
    """Suction [Pa] from a suction column, a head (any length unit or cm of water) or pF (10^pF cm of water)."""
    s = table.get("suction").copy()
    from_head = np.isnan(s)
    s[from_head] = (opt.gamma_w * table.get("head"))[from_head]
    from_pf = np.isnan(s)
    s[from_pf] = (opt.gamma_w * 0.01 * 10.0 ** table.get("pF"))[from_pf]
    return s


def run_retention(source, options: RetentionOptions | None = None) -> RetentionResult:
    """Fit the chosen retention models to every branch of a retention table (CSV path, spreadsheet or DataFrame)."""
    opt = options or RetentionOptions()
    table = read_table(source, SCHEMA)
    if not any(c in table.columns for c in ("suction", "head", "pF")):
        table.missing_column("suction", " (or 'head' / 'z1', or 'pF')")
    if not any(c in table.columns for c in ("S_R", "theta", "z2", "w")):
        table.missing_column("S_R", " (or 'theta', or 'w' with 'rho_d', or 'z2' with 'V_v')")
    if "z2" in table.columns and "V_v" not in table.columns and "S_R" not in table.columns:
        table.missing_column("V_v", " (needed with 'z2')")
    if "w" in table.columns and "rho_d" not in table.columns and "theta" not in table.columns:
        table.missing_column("rho_d", " (needed with the gravimetric 'w': theta = w rho_d/rho_w)")
    table.raise_if_problems()
    s = _suction(table, opt)
    positive = s[s > 0]
    with np.errstate(over="ignore", divide="ignore"):
        span = positive.max() / positive.min() if positive.size else 1.0
    if positive.size and not (np.isfinite(span) and 1e-30 < positive.min() and positive.max() < 1e30):
        raise FitError(
            f"{table.path}: suctions from {positive.min():.3g} to {positive.max():.3g} Pa cannot be "
            "fitted: check the units of the file and --gamma-w"
        )
    if "theta" in table.columns or "w" in table.columns:
        quantity = "theta"
        y = table.get("theta").copy()
        grav = np.isnan(y)
        y[grav] = (table.get("w") * table.get("rho_d") / opt.rho_w)[grav]
    else:
        quantity = "S_R"
        y = table.get("S_R").copy()
        burette = np.isnan(y)
        y[burette] = ((table.get("V_v") - table.get("z2")) / table.get("V_v"))[burette]
        for i in np.flatnonzero(burette & np.isfinite(y) & ((y < 0) | (y > 1))):
            table.add_problem(i, "z2", f"S_R = (V_v - z2)/V_v = {y[i]:.4g} lies outside [0, 1]")
    for i in np.flatnonzero(np.isnan(s)):
        table.add_problem(i, next((c for c in ("suction", "head", "pF") if c in table.columns), None), "no suction")
    for i in np.flatnonzero(np.isnan(y)):
        table.add_problem(i, None, f"no {quantity} value")
    weights = table.get("weight", 1.0).copy()
    weights[np.isnan(weights)] = 1.0
    table.raise_if_problems()

    if "branch" in table.columns and all(table.columns["branch"]):
        branch, how = table.columns["branch"], "column 'branch'"
    else:
        branch, how = _infer_branches(s), "inferred from the order of readings (rising suction = drying)"
    fixed_internal = {}
    for name, v in opt.fixed.items():
        key, factor = _to_internal(name)
        fixed_internal[key] = v * factor
    warnings = list(opt.warnings) + table.warnings
    fits: dict[str, dict[str, NonlinearFit]] = {}
    for b in dict.fromkeys(branch):
        sel = branch == b
        fits[b] = {}
        for m in opt.models:
            fx = {k: v for k, v in fixed_internal.items() if k in FITTERS[m].names}
            n_free = len(FITTERS[m].names) - len(fx)
            if sel.sum() <= n_free:
                warnings.append(
                    f"branch '{b}': {int(sel.sum())} readings for the {n_free} free parameters of {m}: not fitted"
                )
                continue
            try:
                f = dataclasses.replace(fit_model(m, s[sel], y[sel], fx, weights[sel]), quantity=quantity)
            except FitError as exc:
                warnings.append(f"branch '{b}', model {m}: not fitted ({exc})")
                continue
            fits[b][m] = f
            for k in f.at_bounds():
                scale = _report(k)[1] if k not in ("y_s", "y_r") else 1.0
                warnings.append(
                    f"branch '{b}', model {m}: {report_name(k, quantity)} = {f.params[k] * scale:.6g} lies at its bound"
                )
    if not any(fits.values()):
        raise FitError(f"{table.path}: no model could be fitted to any branch ({'; '.join(warnings[-3:])})")
    fits = {b: f for b, f in fits.items() if f}
    hyst = None
    if opt.hysteresis == "kool-parker":
        d, w = branch == "drying", branch == "wetting"
        if not (d.any() and w.any()):
            raise OptionError("--hysteresis kool-parker needs a drying and a wetting branch")
        hyst = fit_hysteresis(
            s[d],
            y[d],
            s[w],
            y[w],
            {k: v for k, v in fixed_internal.items() if k in ("y_r", "y_s", "n")},
            np.concatenate([weights[d], weights[w]]),
        )
        if "vg" not in opt.models:
            for b in ("drying", "wetting"):
                sel = branch == b
                fits.setdefault(b, {})["vg"] = dataclasses.replace(
                    fit_model("vg", s[sel], y[sel], {}, weights[sel]), quantity=quantity
                )
    return RetentionResult(
        table.path,
        quantity,
        s,
        y,
        branch,
        how,
        fits,
        opt,
        list(table.notes),
        [input_file(source, table)],
        warnings,
        hyst,
    )
