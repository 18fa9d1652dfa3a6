"""Console summaries of every command, as TableSpecs for capred.report.render."""
from __future__ import annotations

from ..physics.effective_stress_models import MODEL_LABELS
from ..references import cite
from ..result import TableSpec
import numpy as np

from .render import MAX_ROWS, fmt, row_table


def _spec(title: str, headers: list[str], left: int = 1) -> TableSpec:
    return TableSpec(title, [(h, "left" if j < left else "right") for j, h in enumerate(headers)])


def shear_tables(result) -> list[TableSpec]:
    """Dry fits; model metrics on all wet tests and on the pendular ones; how sure the ranking is;
    model selection; the back-analysed capillary stress of the wet tests."""
    js = result.json_lazy()
    phi_b = any("phi_b_deg" in f for f in js["materials"].values())
    origin = js["dry_fit"] == "origin"
    fits = _spec("Dry envelope τ = c + σ_N tan φ" + (" (through the origin, c = 0)" if origin else ""),
                 ["material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ", "R²"] + (["φ_b [°]"] if phi_b else []))
    for mat, f in js["materials"].items():
        fits.rows.append([mat, fmt(f["n"]), fmt(f["c_kPa"]), fmt(f["c_se_kPa"]), fmt(f["phi_deg"]),
                          fmt(f["phi_se_deg"]), fmt(f["tan_phi"]), fmt(f["r2"]),
                          *([fmt(f.get("phi_b_deg"))] if phi_b else [])])
    out = [fits, _metrics_table("Wet tests: model comparison (residual = predicted − measured)",
                                js["metrics"], js["metrics_overall"], js["best_model"], js["best_model_overall"])]
    if js["metrics_pendular"]:
        lim = result.options.pendular_limit
        out.append(_metrics_table(f"Pendular wet tests only (S_R ≤ {lim:g})", js["metrics_pendular"],
                                  js["metrics_pendular_overall"], js["best_model_pendular"],
                                  js["best_model_pendular_overall"]))
    if js["bootstrap"]:
        boot = _spec("How sure is the ranking? (paired bootstrap of wet and dry tests)",
                     ["material", "best model", "best in", "runner-up", "RMSE difference 95 % CI [kPa]",
                      "replicates"])
        for mat, b in js["bootstrap"].items():
            best = b["best"]
            p = b["best_model_probability"].get(best) if best else None
            diff = b["rmse_difference_ci95_kPa"]
            boot.rows.append([mat, MODEL_LABELS.get(best, "—"), "—" if p is None else f"{p:.0%} of resamples",
                              MODEL_LABELS.get(b["runner_up"], "—"),
                              "—" if diff is None else f"{fmt(diff[0])} to {fmt(diff[1])}", fmt(b["replicates"])])
        out.append(boot)
    sel = js["model_selection"]
    if sel and len(result.models) > 1:
        t = _spec("Model selection on the wet tests (Gaussian errors; k counts fitted parameters and the variance)",
                  ["material", "model", "k", "n", "AICc", "ΔAICc", "weight"], left=2)
        for mat, rows in sel.items():
            for k, (m, v) in enumerate(sorted(rows.items(), key=lambda kv: (kv[1]["delta_aicc"] is None,
                                                                            kv[1]["delta_aicc"] or 0.0))):
                if k == len(rows) - 1:
                    t.sections.add(len(t.rows))
                t.rows.append([mat if k == 0 else "", MODEL_LABELS[m], fmt(v["k"]), fmt(v["n"]), fmt(v["aicc"]),
                               fmt(v["delta_aicc"]), fmt(v["weight"])])
        out.append(t)
    if js["fitted"]:
        f = _spec("Fitted χ laws (dry c, φ held)", ["material", "model", "parameter", "value", "± se", "n"], left=3)
        for mat, models in js["fitted"].items():
            for m, v in models.items():
                for name, value in v["params"].items():
                    if name in v["fixed"]:
                        continue
                    f.rows.append([mat, MODEL_LABELS[m], name, fmt(value), fmt(v["se"].get(name)), fmt(v["n"])])
        out.append(f)
    import itertools

    n_wet = int(np.sum(result.tests["condition"] == "wet"))
    rows = list(itertools.islice(_wet_rows(result), MAX_ROWS))
    table = row_table("Capillary stress carried by each wet test, σ_cap = (τ − c)/tan φ − σ_N [kPa]", rows,
                      ["test_id", "material", "S_R", "suction [kPa]", "σ_cap [kPa]", "± se", "χ_back", "± se "],
                      "results.csv")
    if n_wet > MAX_ROWS:
        table.total_rows, table.full_table = n_wet, "results.csv"
    out.append(table)
    return out


def _wet_rows(result):
    t = result.tests
    for i in range(len(t["test_id"])):
        if t["condition"][i] != "wet":
            continue
        yield {"test_id": str(t["test_id"][i]), "material": str(t["material"][i]), "S_R": t["S_R"][i],
               "suction [kPa]": t["suction"][i] / 1e3, "σ_cap [kPa]": t["sigma_cap"][i] / 1e3,
               "± se": t["sigma_cap_se"][i] / 1e3, "χ_back": t["chi_back"][i], "± se ": t["chi_back_se"][i]}


def _metrics_table(title, metrics, overall, best_of_material, best_overall) -> TableSpec:
    met = _spec(title, ["material", "model", "n", "RMSE [kPa]", "bias [kPa]", "R²", ""], left=2)
    groups = list(metrics.items())
    if overall and len(groups) > 1:
        groups.append(("(all)", overall))
    for mat, models in groups:
        best = best_overall if mat == "(all)" else best_of_material.get(mat)
        for k, (m, v) in enumerate(models.items()):
            if m == best:
                met.bold_rows.add(len(met.rows))
            if k == len(models) - 1:
                met.sections.add(len(met.rows))
            met.rows.append([mat if k == 0 else "", MODEL_LABELS[m], fmt(v["n"]), fmt(v["rmse_kPa"]),
                             fmt(v["bias_kPa"], sign=True), fmt(v["r2"]), "best" if m == best else ""])
    return met


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
    """Per branch: every model's parameters (± se), R², RMSE, AICc, ΔAICc and Akaike weight; hysteresis."""
    js = result.to_json()
    out = []
    for b, d in js["branches"].items():
        t = _spec(f"Retention fits, branch {b} ({js['branch_source']})",
                  ["model", "parameters (± se)", "R²", "RMSE", "AICc", "ΔAICc", "weight"], left=2)
        sel = d["model_selection"]
        order = sorted(d["fits"], key=lambda m: (sel[m]["delta_aicc"] is None, sel[m]["delta_aicc"] or 0.0))
        for m in order:
            v = d["fits"][m]
            parts = []
            for rn in v["parameters"]:
                se = v.get(f"{rn}_se")
                parts.append(f"{rn} {fmt(v[rn])}" + (f" ± {fmt(se, 2)}" if se is not None else
                                                     (" (fixed)" if rn in v["fixed"] else "")))
            t.rows.append([m, "; ".join(parts), fmt(v["r2"]), fmt(v["rmse"]), fmt(v["aicc"]),
                           fmt(sel[m]["delta_aicc"]), fmt(sel[m]["weight"])])
        out.append(t)
    h = js.get("hysteresis")
    if h:
        t = _spec("Hysteresis, Kool & Parker (1987): joint fit of both branches", ["parameter", "value", "± se"])
        for k, v in h["params"].items():
            t.rows.append([k, fmt(v), fmt(h["se"].get(k))])
        t.rows.append(["α_w/α_d", fmt(h["alpha_ratio"]), ""])
        t.rows.append(["AICc joint / independent", f"{fmt(h['aicc'])} / {fmt(h['independent_aicc'])}", ""])
        out.append(t)
    return out


def calc_tables(result) -> list[TableSpec]:
    """Inputs and results of a calculator, one row per case (at most 20 shown)."""
    rows = result.rows()
    return [row_table(f"{result.title}", rows, list(rows[0]), "results.csv")]


def bridge_solve_tables(result) -> list[TableSpec]:
    keys = ["case", "r0_mm", "F_cap_mN", "V_w_mm3", "filling_angle_deg", "filling_angle2_deg", "suction_kPa", "S_R",
            "sigma_prime_kPa", "status"]
    rows = result.rows_range(0, MAX_ROWS)
    codes, counts = np.unique(result.status, return_counts=True)
    summary = _spec("Bridges solved", ["status", "rows"])
    summary.rows = [[result.status_text(k), str(v)] for k, v in zip(codes, counts)]
    present = [k for k in keys if rows and k in rows[0]]
    if "filling_angle2_deg" in present and np.all(result.inputs_si["ratio"] == 1):
        present.remove("filling_angle2_deg")  # equal spheres: the same angle twice
    return [summary, row_table("Exact capillary bridges", rows, present, "solve.csv", total=result.status.size)]


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
