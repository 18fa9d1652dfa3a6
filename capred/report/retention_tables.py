"""Console (and HTML) tables of `capred retention`."""

from __future__ import annotations

from ..result import TableSpec
from .render import fmt, spec


def retention_tables(result) -> list[TableSpec]:
    """Per branch: every model's parameters (± se), R², RMSE, AICc, ΔAICc and Akaike weight; hysteresis."""
    js = result.to_json()
    out = []
    for b, d in js["branches"].items():
        t = spec(
            f"Retention fits, branch {b} ({js['branch_source']})",
            ["model", "parameters (± se)", "R²", "RMSE", "AICc", "ΔAICc", "weight"],
            left=2,
        )
        sel = d["model_selection"]
        order = sorted(d["fits"], key=lambda m: (sel[m]["delta_aicc"] is None, sel[m]["delta_aicc"] or 0.0))
        for m in order:
            v = d["fits"][m]
            parts = []
            for rn in v["parameters"]:
                se = v.get(f"{rn}_se")
                parts.append(
                    f"{rn} {fmt(v[rn])}"
                    + (f" ± {fmt(se, 2)}" if se is not None else (" (fixed)" if rn in v["fixed"] else ""))
                )
            t.rows.append(
                [
                    m,
                    "; ".join(parts),
                    fmt(v["r2"]),
                    fmt(v["rmse"]),
                    fmt(v["aicc"]),
                    fmt(sel[m]["delta_aicc"]),
                    fmt(sel[m]["weight"]),
                ]
            )
        out.append(t)
    h = js.get("hysteresis")
    if h:
        t = spec("Hysteresis, Kool & Parker (1987): joint fit of both branches", ["parameter", "value", "± se"])
        for k, v in h["params"].items():
            t.rows.append([k, fmt(v), fmt(h["se"].get(k))])
        t.rows.append(["α_w/α_d", fmt(h["alpha_ratio"]), ""])
        t.rows.append(["AICc joint / independent", f"{fmt(h['aicc'])} / {fmt(h['independent_aicc'])}", ""])
        out.append(t)
    return out
