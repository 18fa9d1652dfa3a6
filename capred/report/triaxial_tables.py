"""Console (and HTML) tables of `capred triaxial-bounds`."""

from __future__ import annotations

from ..references import cite
from ..result import TableSpec
from .render import fmt, magnitude, spec

_BRANCH = {"compression": "comp.", "extension": "ext.", "general": "true tx."}


def _pm(value, se, scale: float | None = None) -> str:
    """'value ± se' (se omitted when unknown; 0 when the value is 0 within rounding of ``scale``)."""
    if value is None:
        return "—"
    return fmt(value, scale=scale) if se is None else f"{fmt(value, scale=scale)} ± {fmt(se, 2)}"


def triaxial_tables(result) -> list[TableSpec]:
    """Envelope, then one row per unsaturated test and bound, then groups (apparent envelope and shared tensor)."""
    js = result.to_json()
    e = js["envelope"]
    env = spec(
        "Effective envelope (saturated drained tests)",
        ["source", "n", "c' [kPa]", "± se", "φ' [°]", "± se", "M", "k [kPa]"],
    )
    env.rows.append(
        [
            e["source"],
            fmt(e["n"]),
            fmt(e["c_kPa"]),
            fmt(e["c_se_kPa"]),
            fmt(e["phi_deg"]),
            fmt(e["phi_se_deg"]),
            fmt(e["M"]),
            fmt(e["k_kPa"]),
        ]
    )
    names = {"lower": "LB", "spherical": "UB q=q'", "edtp": "UB EDTP"}
    tb = spec(
        "Capillary stress tensor at failure [kPa], compression +; gain = q'/q'_sat; "
        "θ = Lode angle (0 compression, 60 extension); bound 'none': not axisymmetric (see groups)",
        [
            "test",
            "bound",
            "branch",
            "θ [°]",
            "σ3 [kPa]",
            "q [kPa]",
            "σ1,cap",
            "σ2,cap",
            "σ3,cap",
            "p_cap",
            "q_cap",
            "p'",
            "q'",
            "gain",
            "σ_cap > 0",
        ],
        left=3,
    )
    tb.label_columns = 2  # test and bound name each row when the table is folded
    for t in (t for t in js["tests"] if t["condition"] == "unsaturated"):
        present = [n for n in ("lower", "spherical", "edtp") if t[n]]
        head = [
            _BRANCH.get(t["branch"], t["branch"]),
            fmt(t["lode_angle_deg"], 3),
            fmt(t["sigma3_kPa"]),
            fmt(t["q_kPa"]),
        ]
        if not present:
            tb.sections.add(len(tb.rows))
            tb.rows.append([t["test_id"], "none", *head, *[""] * 9])
            continue
        for k, name in enumerate(present):
            b = t[name]
            if k == len(present) - 1:
                tb.sections.add(len(tb.rows))
            stresses = [
                b[f"{c}_kPa"]
                for c in ("sigma1_cap", "sigma2_cap", "sigma3_cap", "p_cap", "q_cap", "p_prime", "q_prime")
            ]
            # 0 within rounding of the stresses the row was computed from (the test's and the bound's)
            scale = magnitude([*stresses, t["sigma3_kPa"], t["q_kPa"]])
            tb.rows.append(
                [
                    t["test_id"] if k == 0 else "",
                    names[name],
                    *(head if k == 0 else [""] * 4),
                    *(fmt(v, scale=scale) for v in stresses),
                    fmt(b["gain"]),
                    "yes" if b["positive_component"] else "",
                ]
            )
    out = [env, tb]
    if js["groups"]:
        g = spec(
            f"Groups: apparent envelope ({cite('prunier2024', 'Appendix 1, eq. 35-37, 43')})",
            ["group", "n", "branch", "C [kPa]", "φ [°]", "φ − φ' [°]", "eq. 37 σ_cap", "θ spread [°]", "eq. 49"],
        )
        tensor = spec(
            f"Groups: shared capillary tensor [kPa] ± se (n − 1 dof; 95 % intervals in the JSON) "
            f"({cite('prunier2024', 'eq. 44-50')})",
            ["group", "method", "σ1,cap", "σ2,cap", "σ3,cap", "p_cap", "C [kPa]", "C'' [kPa]"],
            left=2,
        )
        for r in js["groups"]:
            apparent = [
                fmt(r.get("C_apparent_kPa")),
                fmt(r.get("phi_apparent_deg")),
                fmt(r.get("phi_difference_deg"), sign=True),
                fmt(r.get("eq37_sigma_cap_kPa")),
            ]
            if "C_apparent_kPa" not in r:
                apparent = [r.get("apparent_error", "—"), "", "", ""]
            g.rows.append(
                [
                    r["group"],
                    fmt(r["n"]),
                    _BRANCH.get(r["branch"], r["branch"]),
                    *apparent,
                    fmt(r["lode_spread_deg"], 2),
                    "holds" if r["eq49_holds"] else "fails",
                ]
            )
            if "error" in r:
                tensor.rows.append([r["group"], r["error"], *[""] * 6])
                continue
            method = (r["method"] or "— (see notes)").split(" (")[0]
            if r["method"] and "closed" in r["method"]:
                method = "eq. 48, σ1,cap = 0 closure"
            caps = [abs(r[f"sigma{k}_cap_kPa"]) for k in (1, 2, 3) if r[f"sigma{k}_cap_kPa"] is not None]
            scale = max(caps + [abs(r.get("C_kPa") or 0.0)]) or None  # the magnitudes the tensor came from
            tensor.rows.append(
                [
                    r["group"],
                    method,
                    *(_pm(r[f"sigma{k}_cap_kPa"], r[f"sigma{k}_cap_se_kPa"], scale) for k in (1, 2, 3)),
                    fmt(r["p_cap_kPa"]),
                    fmt(r["C_kPa"]),
                    fmt(r["C_fictive_kPa"]),
                ]
            )
        out += [g, tensor]
    return out
