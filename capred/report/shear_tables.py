"""Console (and HTML) tables of `capred shear`."""

from __future__ import annotations

import numpy as np

from ..physics.effective_stress_models import MODEL_LABELS
from ..result import TableSpec
from .render import MAX_ROWS, fmt, row_table, spec


def _outlier_label(outlier: dict) -> str:
    """A dry outlier as the lab names it: its test id with its line ("D8 (line 13)"), or its line alone."""
    line = f"line {outlier['line']}" if outlier.get("line") is not None else ""
    if outlier.get("test_id") is None:
        return line or "?"
    return f"{outlier['test_id']} ({line})" if line else str(outlier["test_id"])


def shear_tables(result) -> list[TableSpec]:
    """Dry fits; model metrics on all wet tests and on the pendular ones; how sure the ranking is;
    model selection; the back-analysed capillary stress of the wet tests.

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.

    Returns
    -------
    list of capred.result.TableSpec
    """
    js = result.json_lazy()
    phi_b = any("phi_b_deg" in f for f in js["materials"].values())
    origin = js["dry_fit"] == "origin"
    loss = js.get("dry_loss", "ols")
    fits = spec(
        "Dry envelope τ = c + σ_N tan φ"
        + (" (through the origin, c = 0)" if origin else "")
        + (f", {loss} loss" if loss != "ols" else "")
        + "; scatter: constant or proportional to τ (--errors), BP p: Breusch-Pagan test of growing scatter",
        ["material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ", "R²", "scatter", "BP p", "outliers"]
        + (["φ_b [°]"] if phi_b else []),
    )
    hetero = js.get("heteroscedasticity", {})
    for mat, f in js["materials"].items():
        fits.rows.append(
            [
                mat,
                fmt(f["n"]),
                fmt(f["c_kPa"]),
                fmt(f["c_se_kPa"]),
                fmt(f["phi_deg"]),
                fmt(f["phi_se_deg"]),
                fmt(f["tan_phi"]),
                fmt(f["r2"]),
                f.get("errors", "constant"),
                fmt(((hetero.get(mat) or {}).get("dry_fit") or {}).get("p_value")),
                ", ".join(_outlier_label(o) for o in f.get("outliers", [])) or "none",
                *([fmt(f.get("phi_b_deg"))] if phi_b else []),
            ]
        )
    n_wet = int(np.sum(result.tests["condition"] == "wet"))
    if n_wet == 0:  # a file of dry tests: the envelope alone, no empty wet-test tables (the notes say why)
        return [fits]
    out = [
        fits,
        _metrics_table(
            "Wet tests: model comparison (residual = predicted − measured)",
            js["metrics"],
            js["metrics_overall"],
            js["best_model"],
            js["best_model_overall"],
        ),
    ]
    if js["metrics_pendular"]:
        lim = result.options.pendular_limit
        out.append(
            _metrics_table(
                f"Pendular wet tests only (S_R ≤ {lim:g})",
                js["metrics_pendular"],
                js["metrics_pendular_overall"],
                js["best_model_pendular"],
                js["best_model_pendular_overall"],
            )
        )
    if js["bootstrap"]:
        boot = spec(
            "How sure is the ranking? (paired bootstrap of wet and dry tests; ΔRMSE = runner-up − best)",
            ["material", "best model", "best in % of resamples", "runner-up", "ΔRMSE 95 % CI [kPa]", "replicates"],
        )
        for mat, b in js["bootstrap"].items():
            best = b["best"]
            p = b["best_model_probability"].get(best) if best else None
            diff = b["rmse_difference_ci95_kPa"]
            boot.rows.append(
                [
                    mat,
                    MODEL_LABELS.get(best, "—"),
                    "—" if p is None else f"{p:.0%}",
                    MODEL_LABELS.get(b["runner_up"], "—"),
                    "—" if diff is None else f"{fmt(diff[0])} to {fmt(diff[1])}",
                    fmt(b["replicates"]),
                ]
            )
        out.append(boot)
    sel = js["model_selection"]
    if sel and len(result.models) > 1:
        t = spec(
            "Model selection on the wet tests (Gaussian errors; k counts fitted parameters and the variance)",
            ["material", "model", "k", "n", "AICc", "ΔAICc", "weight"],
            left=2,
        )
        for mat, rows in sel.items():
            for k, (m, v) in enumerate(
                sorted(rows.items(), key=lambda kv: (kv[1]["delta_aicc"] is None, kv[1]["delta_aicc"] or 0.0))
            ):
                if k == len(rows) - 1:
                    t.sections.add(len(t.rows))
                t.rows.append(
                    [
                        mat if k == 0 else "",
                        MODEL_LABELS[m],
                        fmt(v["k"]),
                        fmt(v["n"]),
                        fmt(v["aicc"]),
                        fmt(v["delta_aicc"]),
                        fmt(v["weight"]),
                    ]
                )
        out.append(t)
    if js["fitted"]:
        f = spec("Fitted χ laws (dry c, φ held)", ["material", "model", "parameter", "value", "± se", "n"], left=3)
        for mat, models in js["fitted"].items():
            for m, v in models.items():
                for name, value in v["params"].items():
                    if name in v["fixed"]:
                        continue
                    f.rows.append([mat, MODEL_LABELS[m], name, fmt(value), fmt(v["se"].get(name)), fmt(v["n"])])
        out.append(f)
    import itertools

    rows = list(itertools.islice(_wet_rows(result), MAX_ROWS))
    table = row_table(
        "Capillary stress carried by each wet test, σ_cap = (τ − c)/tan φ − σ_N [kPa]",
        rows,
        ["test_id", "material", "S_R", "suction [kPa]", "σ_cap [kPa]", "± se", "χ_back", "± se "],
        "results.csv",
    )
    if n_wet > MAX_ROWS:
        table.total_rows, table.full_table = n_wet, "results.csv"
    out.append(table)
    return out


def _wet_rows(result, limit: int = MAX_ROWS):
    """The first ``limit`` wet tests' rows of the capillary-stress table (a long run keeps just these in memory)."""
    t = result.tests
    rows = np.flatnonzero(t["condition"] == "wet")[:limit]
    b = result.back
    for i, tid in zip(rows.tolist(), result.test_ids(rows)):
        yield {
            "test_id": tid,
            "material": str(t["material"][i]),
            "S_R": t["S_R"][i],
            "suction [kPa]": t["suction"][i] / 1e3,
            "σ_cap [kPa]": b.sigma_cap_kPa[i],
            "± se": b.sigma_cap_se_kPa[i],
            "χ_back": b.chi_back[i],
            "± se ": b.chi_back_se[i],
        }


def _metrics_table(title, metrics, overall, best_of_material, best_overall) -> TableSpec:
    met = spec(title, ["material", "model", "n", "RMSE [kPa]", "bias [kPa]", "R²", "lowest RMSE"], left=2)
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
            met.rows.append(
                [
                    mat if k == 0 else "",
                    MODEL_LABELS[m],
                    fmt(v["n"]),
                    fmt(v["rmse_kPa"]),
                    fmt(v["bias_kPa"], sign=True),
                    fmt(v["r2"]),
                    "best" if m == best else "",
                ]
            )
    return met
