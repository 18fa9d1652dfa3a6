"""Console summaries of every command, as TableSpecs for capred.report.render."""
from __future__ import annotations

from ..physics.effective_stress_models import MODEL_LABELS
from ..references import cite
from ..result import TableSpec
from .render import fmt, row_table


def _spec(title: str, headers: list[str], left: int = 1) -> TableSpec:
    return TableSpec(title, [(h, "left" if j < left else "right") for j, h in enumerate(headers)])


def shear_tables(result) -> list[TableSpec]:
    """Dry fits per material, then model metrics with the best model marked."""
    js = result.json_lazy()
    phi_b = any("phi_b_deg" in f for f in js["materials"].values())
    fits = _spec("Dry envelope τ = c + σ_N tan φ", ["material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ",
                                                    "R²"] + (["φ_b [°]"] if phi_b else []))
    for mat, f in js["materials"].items():
        fits.rows.append([mat, fmt(f["n"]), fmt(f["c_kPa"]), fmt(f["c_se_kPa"]), fmt(f["phi_deg"]),
                          fmt(f["phi_se_deg"]), fmt(f["tan_phi"]), fmt(f["r2"]),
                          *([fmt(f.get("phi_b_deg"))] if phi_b else [])])
    met = _spec("Wet tests: model comparison (residual = predicted − measured)",
                ["material", "model", "n", "RMSE [kPa]", "bias [kPa]", "R²", ""], left=2)
    groups = list(js["metrics"].items())
    if js["metrics_overall"] and len(groups) > 1:
        groups.append(("(all)", js["metrics_overall"]))
    for mat, models in groups:
        best = js["best_model_overall"] if mat == "(all)" else js["best_model"].get(mat)
        for k, (m, v) in enumerate(models.items()):
            if m == best:
                met.bold_rows.add(len(met.rows))
            if k == len(models) - 1:
                met.sections.add(len(met.rows))
            met.rows.append([mat if k == 0 else "", MODEL_LABELS[m], fmt(v["n"]), fmt(v["rmse_kPa"]),
                             fmt(v["bias_kPa"], sign=True), fmt(v["r2"]), "best" if m == best else ""])
    return [fits, met]


def triaxial_tables(result) -> list[TableSpec]:
    """Envelope, then one row per unsaturated test and bound, then groups."""
    js = result.to_json()
    e = js["envelope"]
    env = _spec("Effective envelope (saturated drained tests)",
                ["source", "n", "c' [kPa]", "± se", "φ' [°]", "± se", "M", "k [kPa]"])
    env.rows.append([e["source"], fmt(e["n"]), fmt(e["c_kPa"]), fmt(e["c_se_kPa"]), fmt(e["phi_deg"]),
                     fmt(e["phi_se_deg"]), fmt(e["M"]), fmt(e["k_kPa"])])
    names = {"lower": "LB", "spherical": "UB q=q'", "edtp": "UB EDTP"}
    tb = _spec("Capillary stress tensor at failure [kPa], compression +; gain = q'/q'_sat",
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
        g = _spec(f"Groups sharing one capillary tensor ({cite('prunier2024', 'Appendix 1')})",
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


def retention_tables(result) -> list[TableSpec]:
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
        t = _spec(f"{title} fits — branches: {js['branch_source']}",
                  ["branch", "model", ys, yr, *(c for c, _ in cols), "R²", "AIC"], left=2)
        for b, m, v in present:
            t.rows.append([b, m, fmt(v[ys]), fmt(v[yr]), *(fmt(v[k]) for _, k in cols), fmt(v["r2"]), fmt(v["aic"])])
        out.append(t)
    return out


def calc_tables(result) -> list[TableSpec]:
    """Inputs and results of a calculator, one row per case (at most 20 shown)."""
    rows = result.rows()
    return [row_table(f"{result.title}", rows, list(rows[0]), "results.csv")]


def bridge_solve_tables(result) -> list[TableSpec]:
    keys = ["case", "r0_mm", "F_cap_mN", "V_w_mm3", "filling_angle_deg", "suction_kPa", "S_R", "sigma_prime_kPa",
            "status"]
    rows = result.rows()
    counts: dict[str, int] = {}
    for s in result.table()["status"]:
        counts[s] = counts.get(s, 0) + 1
    summary = _spec("Bridges solved", ["status", "rows"])
    summary.rows = [[k, str(v)] for k, v in counts.items()]
    present = [k for k in keys if rows and k in rows[0]]
    return [summary, row_table("Exact capillary bridges", rows, present, "solve.csv")]


def bridge_compare_tables(result) -> list[TableSpec]:
    keys = ["case", "F_measured_mN", "F_exact_mN", "F_toroidal_mN", "F_willett_mN", "F_israelachvili_mN", "status"]
    rows = result.rows()
    present = [k for k in keys if rows and k in rows[0]]
    return [row_table("Measured against predicted capillary force [mN]", rows, present, "compare.csv")]


def bridge_curve_tables(result) -> list[TableSpec]:
    err = result.to_json()["rms_relative_error_vs_exact"]
    lim = result.pendular_limit
    t = _spec("RMS relative error of σ' against the exact bridge", ["model", f"S_R < {lim:g}", f"S_R >= {lim:g}"])
    for m in ("israelachvili", "bishop", "own1", "own2"):
        t.rows.append([m, *(f"{err[r][m]:.1%}" if err[r][m] is not None else "—" for r in ("inside", "outside"))])
    return [t]
