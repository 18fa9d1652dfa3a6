"""`capred bridge solve | curve | compare`: exact capillary bridges between equal spheres."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, OptionError
from ..io.table import Column, read_table
from ..physics import bridge as br
from ..physics import shear as ph

# 1: the gap is too wide for this suction or volume; 3: so much water that the bridge would be
# convex (water above air pressure), outside the pendular model
STATUS = {0: "ok", 1: "no bridge: beyond rupture", 2: "invalid input", 3: "no concave bridge: too much water"}

SOLVE_SCHEMA = [
    Column("case", "text", None, "case label", ("test_id", "id", "name")),
    Column("R", "length", "mm", "particle radius R", ("radius", "particle_radius"), "positive"),
    Column("gamma", "surface_tension", "N/m", "surface tension", ("surface_tension",), "positive"),
    Column("theta", "angle", "deg", "contact angle", ("contact_angle",), "nonnegative"),
    Column("gap", "length", "mm", "gap D", ("D", "separation", "distance"), "nonnegative"),
    Column("suction", "pressure", "kPa", "suction", ("delta_u", "ua_uw"), "positive"),
    Column("V_w", "volume", "mm^3", "water volume V_w", ("volume", "V", "Vw"), "positive"),
    Column("F_cap", "force", "mN", "measured force F_cap", ("F", "force", "F_measured"), "nonnegative"),
    Column("filling_angle", "angle", "deg", "measured filling angle", ("beta", "half_filling_angle"), "nonnegative"),
]


@dataclass
class BridgeResult:
    """Bridges, one per case, SI inside; ``to_json`` in mm, mN, kPa."""

    source: str
    inputs: dict[str, np.ndarray]
    beta: np.ndarray
    suction: np.ndarray  # Pa
    volume: np.ndarray  # m^3
    force: np.ndarray  # N
    neck: np.ndarray  # m
    status: np.ndarray
    note: list[str]
    labels: list[str] | None = None
    notes: list[str] = field(default_factory=list)

    def rows(self) -> list[dict]:
        R, g = self.inputs["R"], self.inputs["gamma"]
        out = []
        for i in range(self.beta.size):
            ok = self.status[i] == 0
            F_L = np.pi * self.neck[i] ** 2 * self.suction[i]
            F_T = 2 * np.pi * self.neck[i] * g[i]
            row = {"case": self.labels[i]} if self.labels else {}
            row.update({
                "r0_mm": _n(self.neck[i] * 1e3, ok), "F_cap_mN": _n(self.force[i] * 1e3, ok),
                "F_L_mN": _n(F_L * 1e3, ok), "F_T_mN": _n(F_T * 1e3, ok),
                "V_w_mm3": _n(self.volume[i] * 1e9, ok), "filling_angle_deg": _n(np.degrees(self.beta[i]), ok),
                "suction_kPa": _n(self.suction[i] / 1e3, ok),
                "S_R": _n(3 * self.volume[i] / (2 * np.pi * R[i] ** 3), ok),
                "sigma_prime_kPa": _n(self.force[i] / (np.pi * R[i] ** 2) / 1e3, ok),
                "status": STATUS[int(self.status[i])],
            })
            if self.note[i]:
                row["note"] = self.note[i]
            out.append(row)
        return out

    def to_json(self) -> dict:
        return {"source": self.source, "bridges": self.rows(), "notes": self.notes}

    def table(self):
        import pandas as pd

        return pd.DataFrame(self.rows())


def _n(x, ok=True):
    x = float(x)
    return round(x, 12) if ok and np.isfinite(x) else None


def _read_cases(source, required_one_of: tuple[str, ...]):
    table = read_table(source, SOLVE_SCHEMA)
    for name in ("R", "theta", "gap"):
        if name not in table.columns:
            table.missing_column(name)
    if not any(n in table.columns for n in required_one_of):
        table.missing_column(required_one_of[0], "".join(f" (or '{n}')" for n in required_one_of[1:]))
    table.raise_if_problems()
    gamma = table.get("gamma").copy()
    gamma[np.isnan(gamma)] = ph.SURFACE_TENSION
    for i in np.flatnonzero(table.columns["theta"] >= 90):
        table.add_problem(i, "theta", f"contact angle {table.value_text('theta', i)} deg: pendular bridges need "
                                      "theta < 90 deg")
    for name in ("R", "theta", "gap"):
        for i in np.flatnonzero(np.isnan(table.columns[name])):
            table.add_problem(i, name, f"blank {name}")
    return table, gamma


def solve_bridges(source) -> BridgeResult:
    """One bridge per row of a CSV: R, gamma, theta, gap and either suction or V_w."""
    table, gamma = _read_cases(source, ("suction", "V_w"))
    s_in, v_in = table.get("suction"), table.get("V_w")
    for i in np.flatnonzero(np.isnan(s_in) & np.isnan(v_in)):
        table.add_problem(i, "suction" if "suction" in table.columns else "V_w", "give suction or V_w")
    for i in np.flatnonzero(np.isfinite(s_in) & np.isfinite(v_in)):
        table.add_problem(i, "V_w", "give suction or V_w, not both")
    table.raise_if_problems()
    R, th, D = table.columns["R"], np.radians(table.columns["theta"]), table.columns["gap"]
    n = len(table)
    beta, s_star, status = np.full(n, np.nan), np.full(n, np.nan), np.full(n, 2)
    by_s = np.flatnonzero(np.isfinite(s_in))
    by_v = np.flatnonzero(np.isfinite(v_in))
    note = [""] * n
    if by_s.size:
        s_star[by_s] = s_in[by_s] * R[by_s] / gamma[by_s]
        beta[by_s], status[by_s] = br.solve_for_suction(th[by_s], s_star[by_s], D[by_s] / R[by_s])
        for i in by_s[(status[by_s] == 0) & (D[by_s] > 0)]:
            note[i] = "two bridges fit this gap and suction; the stable one (larger filling angle) is given"
    if by_v.size:
        beta[by_v], s_star[by_v], status[by_v] = br.solve_for_volume(th[by_v], v_in[by_v] / R[by_v] ** 3,
                                                                     D[by_v] / R[by_v])
    return _result(table.path, R, gamma, th, D, beta, s_star, status, note,
                   list(table.columns["case"]) if "case" in table.columns else None, table.notes)


def _result(source, R, gamma, th, D, beta, s_star, status, note, labels=None, notes=None) -> BridgeResult:
    gap_s, vol_s, f_s, y0 = br.geometry(beta, th, s_star)
    return BridgeResult(source, {"R": R, "gamma": gamma, "theta": th, "gap": D}, beta, s_star * gamma / R,
                        vol_s * R**3, f_s * np.pi * gamma * R, y0 * R, status, note, labels, list(notes or []))


@dataclass
class CurveResult:
    """The thesis's analytical comparison: sigma' against S_R at contact (seed 000)."""

    R: float
    gamma: float
    theta: float  # rad
    S_R: np.ndarray
    suction: np.ndarray  # Pa
    sigma_exact: np.ndarray  # Pa
    pendular_limit: float

    def models(self) -> dict[str, np.ndarray]:
        S, s = self.S_R, self.suction
        return {
            "exact": self.sigma_exact,
            "israelachvili": np.full_like(S, 2.0 * self.gamma * np.cos(self.theta) / self.R),
            "bishop": S * s,
            "own1": ph.chi1(S) * s,
            "own2": ph.chi1(S) * s + ph.chi2(S, self.R, self.gamma),
        }

    def rows(self) -> list[dict]:
        m = self.models()
        return [{"S_R": _n(self.S_R[i]), "suction_kPa": _n(self.suction[i] / 1e3),
                 **{f"sigma_prime_{k}_kPa": _n(v[i] / 1e3) for k, v in m.items()}} for i in range(self.S_R.size)]

    def summary(self) -> dict:
        m = self.models()
        out = {}
        for regime, sel in (("inside", self.S_R < self.pendular_limit), ("outside", self.S_R >= self.pendular_limit)):
            ex = m["exact"][sel]
            out[regime] = {k: _n(np.sqrt(np.mean(((v[sel] - ex) / ex) ** 2))) if sel.any() else None
                           for k, v in m.items() if k != "exact"}
        return {"rms_relative_error_vs_exact": out}

    def to_json(self) -> dict:
        return {"R_mm": self.R * 1e3, "gamma_N_per_m": self.gamma, "theta_deg": float(np.degrees(self.theta)),
                "pendular_limit": self.pendular_limit, **self.summary(), "curve": self.rows()}

    def table(self):
        import pandas as pd

        return pd.DataFrame(self.rows())


def bridge_curve(R: float = 1e-3, gamma: float = ph.SURFACE_TENSION, theta_deg: float = 0.0, points: int = 2000,
                 pendular_limit: float = ph.PENDULAR_LIMIT, sr_max: float = 0.3) -> CurveResult:
    """Exact sigma' = F/(pi R^2) against S_R = 3 V/(2 pi R^3) for spheres in contact (gap 0).

    S_R is swept evenly from 1e-4 to ``sr_max``; points beyond the last
    concave bridge (suction down to zero) are left out.
    """
    if not R > 0 or not gamma > 0:
        raise OptionError("R and gamma must be > 0")
    if not 0 <= theta_deg < 90:
        raise OptionError("the contact angle must lie in [0, 90) deg")
    if points < 2 or not 1e-4 < sr_max <= 1:
        raise OptionError("need --points >= 2 and 0.0001 < --sr-max <= 1")
    th = np.radians(theta_deg)
    S = np.linspace(1e-4, sr_max, points)
    beta, s_star, status = br.solve_for_volume(th, 2 * np.pi * S / 3, 0.0)
    ok = status == 0
    _, vol, f, _ = br.geometry(beta[ok], th, s_star[ok])
    return CurveResult(R, gamma, th, 3 * vol / (2 * np.pi), s_star[ok] * gamma / R, f * gamma / R, pendular_limit)


def compare_measured(source) -> BridgeResult:
    """Microscopic tests: exact bridge for each measured (R, gap, theta, V_w), beside the measured force."""
    table, gamma = _read_cases(source, ("V_w",))
    if "F_cap" not in table.columns:
        table.missing_column("F_cap")
    table.raise_if_problems()
    for i in np.flatnonzero(np.isnan(table.columns["V_w"])):
        table.add_problem(i, "V_w", "blank V_w")
    table.raise_if_problems()
    R, th, D, V = table.columns["R"], np.radians(table.columns["theta"]), table.columns["gap"], table.columns["V_w"]
    beta, s_star, status = br.solve_for_volume(th, V / R**3, D / R)
    res = _result(table.path, R, gamma, th, D, beta, s_star, status, [""] * len(table),
                  list(table.columns["case"]) if "case" in table.columns else None, table.notes)
    res.inputs.update(V_w=V, F_measured=table.columns["F_cap"], beta_measured=np.radians(table.get("filling_angle")))
    return res


def comparison_rows(res: BridgeResult) -> list[dict]:
    """Measured force against exact, toroidal, Willett and Israelachvili (mN) with residuals."""
    i_ = res.inputs
    R, g, th, D, V = i_["R"], i_["gamma"], i_["theta"], i_["gap"], i_["V_w"]
    tor = br.toroidal(res.beta, th, D / R)[2] * np.pi * g * R
    models = {"exact": res.force, "toroidal": tor, "willett": br.willett_force(R, g, th, V, D),
              "israelachvili": br.israelachvili_force(R, g, th)}
    rows = []
    for k in range(R.size):
        ok = res.status[k] == 0
        row = {"case": res.labels[k]} if res.labels else {}
        row["F_measured_mN"] = _n(i_["F_measured"][k] * 1e3)
        for m, F in models.items():
            good = ok or m == "israelachvili" or m == "willett"
            row[f"F_{m}_mN"] = _n(F[k] * 1e3, good)
            row[f"residual_{m}_mN"] = _n((F[k] - i_["F_measured"][k]) * 1e3, good)
        row["filling_angle_measured_deg"] = _n(np.degrees(i_["beta_measured"][k]))
        row["filling_angle_exact_deg"] = _n(np.degrees(res.beta[k]), ok)
        row["status"] = STATUS[int(res.status[k])]
        rows.append(row)
    return rows


__all__ = ["solve_bridges", "bridge_curve", "compare_measured", "comparison_rows", "BridgeResult", "CurveResult",
           "InputError"]


def write_bridge_outputs(command: str, table_rows: list[dict], js: dict, out_dir, figure=None,
                         inputs=None, options=None) -> list[Path]:
    """bridges.csv / curve.csv / compare.csv, the JSON, an optional PNG and provenance.json."""
    import pandas as pd

    from ..io import writers

    out = Path(out_dir)
    name = command.split()[-1]
    written = [writers.write_csv(out / f"{name}.csv", pd.DataFrame(table_rows)),
               writers.write_json(out / f"{name}.json", js)]
    if figure is not None:
        written.append(writers.write_png(out / f"{name}.png", figure))
    written.append(writers.write_json(out / "provenance.json",
                                      writers.provenance(command, inputs or [], options or {}, written)))
    return written
