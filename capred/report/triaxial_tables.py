"""Console (and HTML) tables of `capred triaxial-bounds`."""
from __future__ import annotations

from ..references import cite
from ..result import TableSpec
from .render import fmt, spec

def triaxial_tables(result) -> list[TableSpec]:
    """Envelope, then one row per unsaturated test and bound, then groups."""
    js = result.to_json()
    e = js["envelope"]
    env = spec("Effective envelope (saturated drained tests)",
                ["source", "n", "c' [kPa]", "± se", "φ' [°]", "± se", "M", "k [kPa]"])
    env.rows.append([e["source"], fmt(e["n"]), fmt(e["c_kPa"]), fmt(e["c_se_kPa"]), fmt(e["phi_deg"]),
                     fmt(e["phi_se_deg"]), fmt(e["M"]), fmt(e["k_kPa"])])
    names = {"lower": "LB", "spherical": "UB q=q'", "edtp": "UB EDTP"}
    tb = spec("Capillary stress tensor at failure [kPa], compression +; gain = q'/q'_sat",
               ["test", "σ3 [kPa]", "q [kPa]", "bound", "σ1,cap", "σ3,cap", "p_cap", "q_cap", "p'", "q'", "gain",
                "σ_cap > 0"], left=1)
    tb.columns[3] = ("bound", "left")
    for t in (t for t in js["tests"] if t["condition"] == "unsaturated"):
        present = [n for n in ("lower", "spherical", "edtp") if t[n]]
        for k, name in enumerate(present):
            b = t[name]
            head = [t["test_id"], fmt(t["sigma3_kPa"]), fmt(t["q_kPa"])] if k == 0 else ["", "", ""]
            if k == len(present) - 1:
                tb.sections.add(len(tb.rows))
            tb.rows.append([*head, names[name], fmt(b["sigma1_cap_kPa"]), fmt(b["sigma3_cap_kPa"]),
                            fmt(b["p_cap_kPa"]), fmt(b["q_cap_kPa"]), fmt(b["p_prime_kPa"]), fmt(b["q_prime_kPa"]),
                            fmt(b["gain"]), "yes" if b["positive_component"] else ""])
    out = [env, tb]
    if js["groups"]:
        g = spec(f"Groups sharing one capillary tensor ({cite('prunier2024', 'Appendix 1')})",
                  ["group", "n", "C [kPa]", "φ [°]", "φ − φ' [°]", "eq. 37 σ_cap", "eq. 48 σ1,cap", "eq. 48 σ3,cap",
                   "eq. 49"])
        for r in js["groups"]:
            if "error" in r:
                g.rows.append([r["group"], fmt(r["n"]), r["error"], "", "", "", "", "", ""])
                continue
            e48 = r["eq48_lower"]
            g.rows.append([r["group"], fmt(r["n"]), fmt(r["C_apparent_kPa"]), fmt(r["phi_apparent_deg"]),
                           fmt(r["phi_difference_deg"], sign=True), fmt(r["eq37_sigma_cap_kPa"]),
                           fmt(e48["sigma1_cap_kPa"]), fmt(e48["sigma3_cap_kPa"]),
                           "holds" if r["eq49_holds"] else "fails"])
        out.append(g)
    return out
