"""`capred prism`, `capred skempton-b`, `capred rumpf`: closed-form calculators.

Each takes one case from options, or many from a CSV (one case per row,
units in headers as for `capred shear`); a value in the file wins over the
option, an option fills absent columns and blank cells.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, OptionError, Problem
from ..io.table import Column, read_table
from ..physics import calculators as calc
from ..physics.shear import GAMMA_W, SURFACE_TENSION


CASE = Column("case", "text", None, "case label", ("test_id", "id", "name", "sample_id"))


@dataclass
class CalcResult:
    command: str
    inputs: dict[str, np.ndarray]  # output units
    outputs: dict[str, np.ndarray]  # output units, keys carry the unit
    source: str | None
    notes: list[str] = field(default_factory=list)
    labels: list[str] | None = None

    def rows(self) -> list[dict]:
        n = len(next(iter(self.outputs.values())))
        return [{**({"case": self.labels[i]} if self.labels else {}),
                 **{k: _num(v[i]) for k, v in self.inputs.items()},
                 **{k: _num(v[i]) for k, v in self.outputs.items()}} for i in range(n)]

    def to_json(self) -> dict:
        rows = self.rows()
        out = {"cases": rows, "notes": self.notes}
        if len(rows) == 1:
            out = {**{k: rows[0][k] for k in self.outputs}, **out}
        return out

    def table(self):
        import pandas as pd

        return pd.DataFrame(self.rows())


def _num(x):
    x = float(x)
    return round(x, 10) if np.isfinite(x) else None


def _labels(values: dict) -> list[str] | None:
    case = values.pop("case", None)
    return [str(c) for c in case] if case is not None else None


def _inputs(source, schema: list[Column], options: dict[str, float | None], optional: tuple[str, ...] = ()):
    """Per-case SI arrays from a CSV and/or options, and notes (e.g. g/cm^2 read as gf/cm^2).

    Names in ``optional`` may stay NaN (absent from both the file and the options).
    """
    notes: list[str] = []
    if source is None:
        missing = [c.name for c in schema if options.get(c.name) is None and c.name not in optional]
        if missing:
            raise OptionError("missing " + ", ".join(f"--{m.replace('_', '-')}" for m in missing))
        values = {k: np.array([np.nan if v is None else v], dtype=float) for k, v in options.items()}
        return values, notes, None
    table = read_table(source, [*schema, CASE])
    values = {}
    for col in schema:
        v = table.get(col.name).copy()
        opt = options.get(col.name)
        if opt is not None:
            v[np.isnan(v)] = opt
        for i in np.flatnonzero(np.isnan(v) if col.name not in optional else []):
            table.add_problem(i, col.name if col.name in table.columns else None,
                              f"no value for '{col.name}' (column or --{col.name.replace('_', '-')})")
        values[col.name] = v
    table.raise_if_problems()
    if "case" in table.columns:
        values["case"] = table.columns["case"]
    return values, table.notes, table.path


PRISM = [
    Column("break_tension", "pressure", "kPa", "break tension sigma_b", ("sigma_b", "break_stress"), "positive"),
    Column("friction_angle", "angle", "deg", "friction angle rho", ("rho", "phi"), "positive"),
]


def run_prism(source=None, break_tension: float | None = None, friction_angle: float | None = None,
              gamma_w: float = GAMMA_W) -> CalcResult:
    """Bernatzik (seed 001): maximal capillary pressure and capillary rise of a sand prism."""
    v, notes, src = _inputs(source, PRISM, {"break_tension": break_tension, "friction_angle": friction_angle})
    labels = _labels(v)
    if np.any((v["friction_angle"] <= 0) | (v["friction_angle"] >= 90)):
        raise OptionError("the friction angle must lie between 0 and 90 deg")
    p = calc.prism_capillary_pressure(v["break_tension"], v["friction_angle"])
    return CalcResult("prism", {"break_tension_kPa": v["break_tension"] / 1e3, "friction_angle_deg": v["friction_angle"]},
                      {"P_kmax_kPa": p / 1e3, "capillary_rise_cm": calc.capillary_rise(p, gamma_w) * 100.0,
                       "P_kmax_over_sigma_b": p / v["break_tension"]}, src, notes, labels)


SKEMPTON = [
    Column("kappa", "dimensionless", "-", "kappa", (), "positive"),
    Column("e0", "dimensionless", "-", "e0", ("e_0", "void_ratio"), "positive"),
    Column("p0", "pressure", "kPa", "p0", ("p_0",), "nonnegative"),
    Column("u0", "pressure", "kPa", "u0", ("u_0", "ua0"), None),
    Column("pa0", "pressure", "kPa", "pa0", ("p_a0", "P_a0"), "positive"),
]


def run_skempton_b(source=None, sr: float | None = None, b: float | None = None, kappa=0.006, e0=0.8,
                   p0=100e3, u0=30e3, pa0=130e3, s_e: float | None = None, bc_alpha: float | None = None) -> CalcResult:
    """Morvan et al. (seed 004): B from S_r (eq. 10), or S_r from a measured B.

    With ``s_e`` and ``bc_alpha`` (Brooks-Corey), B is computed with suction
    equilibrium (section 3); its inverse is solved numerically.
    """
    schema = SKEMPTON + [Column("S_r", "dimensionless", "-", "S_r", ("Sr", "S_R"), "fraction"),
                         Column("B", "dimensionless", "-", "B", ("skempton_b",), "fraction")]
    given = {"kappa": kappa, "e0": e0, "p0": p0, "u0": u0, "pa0": pa0, "S_r": sr, "B": b}
    if source is None and (sr is None) == (b is None):
        raise OptionError("give exactly one of --sr and --b")
    v, notes, src = _inputs(source, schema, given, optional=("S_r", "B"))
    labels = _labels(v)
    forward = bool(np.all(np.isfinite(v["S_r"])))
    if not forward and not np.all(np.isfinite(v["B"])):
        raise InputError(Problem(str(src), None, None, "every row needs 'S_r' (to compute B) or every row 'B' "
                                                          "(to compute S_r)"))
    v.pop("B" if forward else "S_r")
    suction = s_e is not None and bc_alpha is not None
    if (s_e is None) != (bc_alpha is None):
        raise OptionError("give both --se and --bc-alpha for the suction-equilibrium simulation, or neither")
    p_eff = v["p0"] - v["u0"]
    if np.any(p_eff <= 0):
        raise OptionError("p0 - u0 (initial mean effective stress) must be > 0")
    ins = {k + "_kPa" if k in ("p0", "u0", "pa0") else k: (x / 1e3 if k in ("p0", "u0", "pa0") else x)
           for k, x in v.items() if k not in ("S_r", "B")}
    if forward:
        if suction:
            B = calc.skempton_b_suction(v["S_r"], v["p0"], v["u0"], v["e0"], v["kappa"], v["pa0"], s_e, bc_alpha)
        else:
            B = calc.skempton_b(v["S_r"], p_eff, v["e0"], v["kappa"], v["pa0"])
        return CalcResult("skempton-b", {"S_r": v["S_r"], **ins}, {"B": B}, src, notes, labels)
    if suction:
        from scipy.optimize import brentq

        def solve(bi, k, e, p, u, pa):
            f = lambda s: calc.skempton_b_suction(s, p, u, e, k, pa, s_e, bc_alpha) - bi  # noqa: E731
            lo, hi = 1e-9, 1.0
            return brentq(f, lo, hi, xtol=1e-14) if f(lo) * f(hi) < 0 else np.nan

        S = np.array([solve(*args) for args in zip(v["B"], v["kappa"], v["e0"], v["p0"], v["u0"], v["pa0"])])
    else:
        S = calc.saturation_from_b(v["B"], p_eff, v["e0"], v["kappa"], v["pa0"])
    if np.any(~np.isfinite(S) | (S < 0)):
        notes.append("some B values are below what these parameters give for dry soil: S_r is outside [0, 1] there")
    return CalcResult("skempton-b", {"B": v["B"], **ins}, {"S_r": S}, src, notes, labels)


RUMPF = [
    Column("shape_factor", "dimensionless", "-", "shape factor phi", ("phi", "shape"), "positive"),
    Column("void_ratio", "dimensionless", "-", "void ratio e", ("e",), "positive"),
    Column("S_r", "dimensionless", "-", "S_r", ("Sr", "S_R"), "fraction"),
    Column("diameter", "length", "mm", "particle diameter d_p", ("d_p", "d", "particle_diameter"), "positive"),
    Column("surface_tension", "surface_tension", "N/m", "surface tension", ("gamma",), "positive"),
    Column("contact_angle", "angle", "deg", "contact angle", ("theta",), "nonnegative"),
]


def run_rumpf(source=None, shape_factor=None, void_ratio=None, sr=None, diameter=None,
              surface_tension=SURFACE_TENSION, contact_angle=0.0) -> CalcResult:
    """Rumpf's capillary pressure p_cap = -(6/phi)(S_r/e)(gamma/d_p) cos theta (seed 002, eq. 19)."""
    v, notes, src = _inputs(source, RUMPF, {"shape_factor": shape_factor, "void_ratio": void_ratio, "S_r": sr,
                                            "diameter": diameter, "surface_tension": surface_tension,
                                            "contact_angle": contact_angle})
    labels = _labels(v)
    if np.any(v["contact_angle"] >= 90):
        raise OptionError("the contact angle must be below 90 deg")
    p = calc.rumpf_capillary_pressure(v["shape_factor"], v["void_ratio"], v["S_r"], v["diameter"],
                                      v["surface_tension"], v["contact_angle"])
    ins = {"shape_factor": v["shape_factor"], "void_ratio": v["void_ratio"], "S_r": v["S_r"],
           "diameter_mm": v["diameter"] * 1e3, "surface_tension_N_per_m": v["surface_tension"],
           "contact_angle_deg": v["contact_angle"]}
    return CalcResult("rumpf", ins, {"p_cap_kPa": p / 1e3}, src, notes, labels)


def write_calc_outputs(result: CalcResult, out_dir, figure=None, command_options=None) -> list[Path]:
    from ..io import writers

    out = Path(out_dir)
    written = [writers.write_csv(out / "results.csv", result.table()),
               writers.write_json(out / "results.json", result.to_json())]
    if figure is not None:
        written.append(writers.write_png(out / f"{result.command}.png", figure))
    written.append(writers.write_json(out / "provenance.json", writers.provenance(
        result.command, [result.source] if result.source else [], command_options or {}, written)))
    return written


__all__ = ["run_prism", "run_skempton_b", "run_rumpf", "write_calc_outputs", "CalcResult", "InputError", "Problem"]
