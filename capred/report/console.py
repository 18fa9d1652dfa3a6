"""Console summaries with rich."""
from __future__ import annotations

from rich.markup import escape
from rich.table import Table

from ..physics.shear import MODEL_LABELS


def _f(x, fmt=".4g"):
    return "—" if x is None else format(x, fmt)


def shear_tables(result) -> list[Table]:
    """Dry fits per material, then model metrics with the best model marked."""
    js = result.to_json()
    fits = Table(title="Dry envelope τ = c + σ_N tan φ", title_justify="left")
    phi_b = any("phi_b_deg" in f for f in js["materials"].values())
    for col in ("material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ", "R²") + (("φ_b [°]",) if phi_b else ()):
        fits.add_column(escape(col), justify="left" if col == "material" else "right")
    for mat, f in js["materials"].items():
        fits.add_row(mat, str(f["n"]), _f(f["c_kPa"]), _f(f["c_se_kPa"], ".2g"), _f(f["phi_deg"], ".2f"),
                     _f(f["phi_se_deg"], ".2f"), _f(f["tan_phi"]), _f(f["r2"]),
                     *((_f(f.get("phi_b_deg"), ".2f"),) if phi_b else ()))

    met = Table(title="Wet tests: model comparison (residual = predicted − measured)", title_justify="left")

    for col in ("material", "model", "n", "RMSE [kPa]", "bias [kPa]", "R²", ""):
        met.add_column(escape(col), justify="left" if col in ("material", "model") else "right")
    groups = list(js["metrics"].items())
    if js["metrics_overall"] and len(groups) > 1:
        groups.append(("(all)", js["metrics_overall"]))
    for mat, models in groups:
        best = js["best_model_overall"] if mat == "(all)" else js["best_model"].get(mat)
        for k, (m, v) in enumerate(models.items()):
            mark = "[bold green]best[/]" if m == best else ""
            style = "bold" if m == best else None
            met.add_row(mat if k == 0 else "", MODEL_LABELS[m], str(v["n"]), _f(v["rmse_kPa"], ".3g"),
                        _f(v["bias_kPa"], "+.3g"), _f(v["r2"], ".3f"), mark, style=style,
                        end_section=k == len(models) - 1)
    return [fits, met]


def triaxial_tables(result) -> list[Table]:
    """Envelope, then one row per unsaturated test and bound."""
    js = result.to_json()
    e = js["envelope"]
    env = Table(title="Effective envelope (saturated drained tests)", title_justify="left")
    for col in ("source", "n", "c' [kPa]", "± se", "φ' [°]", "± se", "M", "k [kPa]"):
        env.add_column(escape(col), justify="right")
    env.add_row(e["source"], _f(e["n"]) if e["n"] else "—", _f(e["c_kPa"]), _f(e["c_se_kPa"], ".2g"),
                _f(e["phi_deg"], ".2f"), _f(e["phi_se_deg"], ".2f"), _f(e["M"]), _f(e["k_kPa"]))
    names = {"lower": "LB", "spherical": "UB q=q'", "edtp": "UB EDTP"}
    tb = Table(title=escape("Capillary stress tensor at failure [kPa], compression +; gain = q'/q'_sat"),
               title_justify="left")
    for col in ("test (σ3, q)", "bound", "σ1_cap", "σ3_cap", "p_cap", "q_cap", "p'", "q'", "gain"):
        tb.add_column(escape(col), justify="left" if col.startswith(("test", "bound")) else "right")
    rows = [t for t in js["tests"] if t["condition"] == "unsaturated"]
    for t in rows:
        present = [n for n in ("lower", "spherical", "edtp") if t[n]]
        head = [t["test_id"], f"({_f(t['sigma3_kPa'], '.4g')}, {_f(t['q_kPa'], '.4g')})"]
        for k, name in enumerate(present):
            b = t[name]
            label = names[name] + (" [red]σ_cap>0[/]" if b["positive_component"] else "")
            tb.add_row(head[k] if k < 2 else "", label, _f(b["sigma1_cap_kPa"], ".1f"),
                       _f(b["sigma3_cap_kPa"], ".1f"), _f(b["p_cap_kPa"], ".1f"), _f(b["q_cap_kPa"], ".1f"),
                       _f(b["p_prime_kPa"], ".1f"), _f(b["q_prime_kPa"], ".1f"), _f(b["gain"], ".3g"),
                       end_section=k == len(present) - 1)
    out = [env, tb]
    if js["groups"]:
        g = Table(title="Groups sharing one capillary tensor (seed 002, Appendix 1)", title_justify="left")
        for col in ("group", "n", "C [kPa]", "φ [°]", "φ − φ' [°]", "eq. 37 σ_cap", "eq. 48 (LB) σ1_cap, σ3_cap", "eq. 49"):
            g.add_column(escape(col), justify="right")
        for r in js["groups"]:
            if "error" in r:
                g.add_row(r["group"], str(r["n"]), r["error"], "", "", "", "", "")
                continue
            e48 = r["eq48_lower"]
            g.add_row(r["group"], str(r["n"]), _f(r["C_apparent_kPa"]), _f(r["phi_apparent_deg"], ".2f"),
                      _f(r["phi_difference_deg"], "+.2f"), _f(r["eq37_sigma_cap_kPa"], ".3g"),
                      f"{_f(e48['sigma1_cap_kPa'], '.3g')}, {_f(e48['sigma3_cap_kPa'], '.3g')}",
                      "holds" if r["eq49_holds"] else "fails")
        out.append(g)
    return out


def retention_tables(result) -> list[Table]:
    """One table for the van Genuchten fits, one for Brooks-Corey."""
    js = result.to_json()
    ys, yr = result.names
    specs = (("van Genuchten", ("vg", "vg_m_free"), (("α [1/kPa]", "alpha_per_kPa"), ("n", "n"), ("m", "m"))),
             ("Brooks-Corey", ("bc",), (("s_e [kPa]", "s_e_kPa"), ("λ", "lambda"))))
    out = []
    for title, models, cols in specs:
        present = [(b, m, d["fits"][m]) for b, d in js["branches"].items() for m in models if m in d["fits"]]
        if not present:
            continue
        t = Table(title=f"{title} fits — branches: {js['branch_source']}", title_justify="left")
        for col in ("branch", "model", ys, yr, *(c for c, _ in cols), "R²", "AIC"):
            t.add_column(escape(col), justify="left" if col in ("branch", "model") else "right")
        for b, m, v in present:
            t.add_row(b, m, _f(v[ys]), _f(v[yr]), *(_f(v[k]) for _, k in cols), _f(v["r2"], ".4f"),
                      _f(v["aic"], ".1f"))
        out.append(t)
    return out


def calc_table(result) -> Table:
    """Inputs and results of a calculator, one row per case."""
    rows = result.rows()
    t = Table(title=f"capred {result.command}", title_justify="left")
    for k in rows[0]:
        t.add_column(escape(k), justify="right", style="bold" if k in result.outputs else None)
    for r in rows:
        t.add_row(*(v if isinstance(v, str) else _f(v) for v in r.values()))
    return t
