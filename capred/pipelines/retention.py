"""`capred retention`: fit van Genuchten and Brooks-Corey curves per branch."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import FitError, OptionError
from ..fitting.nonlinear import NonlinearFit
from ..fitting.retention import fit_brooks_corey, fit_van_genuchten
from ..io.table import Column, read_table
from ..physics import retention as rp
from ..physics.shear import GAMMA_W
from ..references import cite
from ..result import InputFile, Options, Result, TableSpec, input_file, num

SCHEMA = [
    Column("suction", "pressure", "kPa", "suction", ("s", "matric_suction", "delta_u", "ua_uw"), "nonnegative"),
    Column("head", "length", "cm", "suction head", ("h", "suction_head", "pressure_head", "z1", "matric_head"), "nonnegative"),
    Column("S_R", "dimensionless", "-", "S_R", ("Sr", "degree_of_saturation", "saturation"), "fraction"),
    Column("theta", "dimensionless", "-", "theta", ("theta_vol", "vwc", "water_content_vol", "theta_vol_m3_per_m3",
                                                     "volumetric_water_content"), "fraction"),
    Column("z2", "volume", "cm^3", "air volume z2", ("air_volume", "burette", "V_a"), "nonnegative"),
    Column("V_v", "volume", "cm^3", "void volume V_v", ("Vv", "void_volume"), "positive"),
    Column("branch", "text", None, "branch", ("path",), choices=("drying", "wetting")),
]

MODELS = {"vg": "van Genuchten, m = 1 - 1/n", "vg_m_free": "van Genuchten, m free", "bc": "Brooks-Corey"}
REFERENCE = {"vg": "vangenuchten1980", "vg_m_free": "vangenuchten1980", "bc": "brooks_corey1964"}


@dataclass(frozen=True)
class RetentionOptions(Options):
    """Options of `capred retention`: models to fit, fixed parameters (report names and
    units: kPa, 1/kPa) and the unit weight of water ``gamma_w`` [N/m^3, or a string with a unit]."""

    QUANTITIES = {"gamma_w": "gamma_w"}

    models: tuple[str, ...] = ("vg", "vg_m_free", "bc")
    fixed: dict[str, float] = field(default_factory=dict)
    gamma_w: float = GAMMA_W

    def __post_init__(self) -> None:
        super().__post_init__()
        models = (self.models,) if isinstance(self.models, str) else tuple(self.models)
        unknown = [m for m in models if m not in MODELS]
        if unknown or not models:
            raise OptionError(f"unknown model {unknown[0] if unknown else ''!r}; choose from {', '.join(MODELS)}")
        object.__setattr__(self, "models", models)
        for name in self.fixed:
            if name not in _TO_INTERNAL:
                raise OptionError(f"fixed: unknown parameter '{name}'; choose from {', '.join(_TO_INTERNAL)}")


@dataclass
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

    @property
    def names(self) -> tuple[str, str]:
        return ("theta_s", "theta_r") if self.quantity == "theta" else ("S_s", "S_res")

    def fit_json(self, f: NonlinearFit, model: str) -> dict:
        ys, yr = self.names
        p, e = f.params, f.stderr
        cm = self.options.gamma_w * 0.01  # Pa per cm of water head

        def se(k, scale=1.0):
            return None if e.get(k) is None or not np.isfinite(e[k]) else num(e[k] * scale)

        out = {ys: num(p["y_s"]), yr: num(p["y_r"]), f"{ys}_se": se("y_s"), f"{yr}_se": se("y_r")}
        if model.startswith("vg"):
            out.update({"alpha_per_kPa": num(p["alpha"] * 1e3), "alpha_per_kPa_se": se("alpha", 1e3),
                        "alpha_per_cm": num(p["alpha"] * cm), "n": num(p["n"]), "n_se": se("n"),
                        "m": num(p.get("m", 1 - 1 / p["n"])), "m_se": se("m")})
        else:
            out.update({"s_e_kPa": num(p["s_e"] / 1e3), "s_e_kPa_se": se("s_e", 1e-3),
                        "h_b_cm": num(p["s_e"] / cm), "lambda": num(p["lam"]), "lambda_se": se("lam")})
        out.update({"r2": num(f.r2), "aic": num(f.aic), "bic": num(f.bic), "rss": num(f.rss), "n_points": f.n,
                    "fixed": [_report_name(k, self.quantity) for k in f.fixed], "converged": f.converged,
                    "model": MODELS[model], "reference": cite(REFERENCE[model])})
        return out

    def payload(self, lazy: bool = False) -> dict:
        branches = {b: {"n_points": int(np.sum(self.branch == b)),
                        "fits": {m: self.fit_json(f, m) for m, f in fits.items()}}
                    for b, fits in self.fits.items()}
        main = "drying" if "drying" in branches else next(iter(branches))
        return {"source": self.source, "quantity": self.quantity, "branch_source": self.branch_source,
                "main_branch": main, "fits": branches[main]["fits"], "branches": branches}

    def tables(self) -> dict:
        """fits: one row per branch and model."""
        cached = self.__dict__.get("_tables")
        if cached is None:
            cached = self.__dict__["_tables"] = {"fits": self._fits_table()}
        return cached

    def figures(self) -> dict:
        from ..report.retention_figures import sheet_retention

        return {"retention": sheet_retention(self)}

    def console_tables(self) -> list[TableSpec]:
        from ..report.console import retention_tables

        return retention_tables(self)

    def _fits_table(self):
        import pandas as pd

        rows = []
        for b, d in self.to_json()["branches"].items():
            for m, v in d["fits"].items():
                rows.append({"branch": b, "model": m, **{k: (";".join(x) if isinstance(x, list) else x)
                                                         for k, x in v.items()}})
        return pd.DataFrame(rows)

    def curve(self, branch: str, model: str, s):
        p = self.fits[branch][model].params
        if model.startswith("vg"):
            return rp.vg_water(s, p["y_r"], p["y_s"], p["alpha"], p["n"], p.get("m"))
        return rp.bc_water(s, p["y_r"], p["y_s"], p["s_e"], p["lam"])


_TO_INTERNAL = {  # report name -> (internal name, factor from report unit to SI)
    "theta_s": ("y_s", 1.0), "theta_r": ("y_r", 1.0), "S_s": ("y_s", 1.0), "S_res": ("y_r", 1.0),
    "alpha_per_kPa": ("alpha", 1e-3), "alpha": ("alpha", 1e-3), "n": ("n", 1.0), "m": ("m", 1.0),
    "s_e_kPa": ("s_e", 1e3), "s_e": ("s_e", 1e3), "lambda": ("lam", 1.0),
}


def _report_name(internal: str, quantity: str) -> str:
    names = {"y_s": "theta_s" if quantity == "theta" else "S_s", "y_r": "theta_r" if quantity == "theta" else "S_res",
             "alpha": "alpha_per_kPa", "n": "n", "m": "m", "s_e": "s_e_kPa", "lam": "lambda"}
    return names[internal]


def parse_fixed(items: list[str]) -> dict[str, float]:
    """'theta_s=0.25' -> {'theta_s': 0.25}; values in the report units (kPa, 1/kPa)."""
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or name not in _TO_INTERNAL:
            raise OptionError(f"--fix '{item}': expected NAME=VALUE with NAME one of {', '.join(_TO_INTERNAL)}")
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
    current = "drying"
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


def run_retention(source, options: RetentionOptions | None = None) -> RetentionResult:
    """Fit the chosen retention models to every branch of a retention table (CSV path or DataFrame)."""
    opt = options or RetentionOptions()
    table = read_table(source, SCHEMA)
    if "suction" not in table.columns and "head" not in table.columns:
        table.missing_column("suction", " (or 'head' / 'z1')")
    has_water = "S_R" in table.columns or "theta" in table.columns or "z2" in table.columns
    if not has_water:
        table.missing_column("S_R", " (or 'theta', or 'z2' with 'V_v')")
    if "z2" in table.columns and "V_v" not in table.columns and "S_R" not in table.columns:
        table.missing_column("V_v", " (needed with 'z2')")
    table.raise_if_problems()
    s = table.get("suction").copy()
    from_head = np.isnan(s)
    s[from_head] = (opt.gamma_w * table.get("head"))[from_head]
    if "theta" in table.columns:
        quantity, y = "theta", table.columns["theta"].copy()
    else:
        quantity = "S_R"
        y = table.get("S_R").copy()
        burette = np.isnan(y)
        y[burette] = ((table.get("V_v") - table.get("z2")) / table.get("V_v"))[burette]
        for i in np.flatnonzero(burette & np.isfinite(y) & ((y < 0) | (y > 1))):
            table.add_problem(i, "z2", f"S_R = (V_v - z2)/V_v = {y[i]:.4g} lies outside [0, 1]")
    for i in np.flatnonzero(np.isnan(s)):
        table.add_problem(i, "suction" if "suction" in table.columns else "head", "no suction")
    for i in np.flatnonzero(np.isnan(y)):
        table.add_problem(i, None, f"no {quantity} value")
    table.raise_if_problems()

    if "branch" in table.columns and all(table.columns["branch"]):
        branch, how = table.columns["branch"], "column 'branch'"
    else:
        branch, how = _infer_branches(s), "inferred from the order of readings (rising suction = drying)"
    fixed_internal = {}
    for name, v in opt.fixed.items():
        key, factor = _TO_INTERNAL[name]
        fixed_internal[key] = v * factor
    fits: dict[str, dict[str, NonlinearFit]] = {}
    for b in dict.fromkeys(branch):
        sel = branch == b
        fits[b] = {}
        for m in opt.models:
            fx = {k: v for k, v in fixed_internal.items()
                  if k in (("y_r", "y_s", "alpha", "n") + (("m",) if m == "vg_m_free" else ())
                           if m.startswith("vg") else ("y_r", "y_s", "s_e", "lam"))}
            try:
                if m == "bc":
                    fits[b][m] = fit_brooks_corey(s[sel], y[sel], fx)
                else:
                    fits[b][m] = fit_van_genuchten(s[sel], y[sel], fx, m_free=(m == "vg_m_free"))
            except FitError as exc:
                raise FitError(f"{table.path}: branch '{b}', model {m}: {exc}") from None
    return RetentionResult(table.path, quantity, s, y, branch, how, fits, opt, list(table.notes),
                           [input_file(source, table)], opt.warnings + table.warnings)
