"""Console (and HTML) tables of `capred shear`."""

from __future__ import annotations

import numpy as np

from ..nomenclature import QUANTITIES
from ..physics.effective_stress_models import MODEL_LABELS
from ..records import num
from ..table_spec import TableSpec
from .render import MAX_ROWS, fmt, row_table, spec


def _outlier_labels(line) -> list[str]:
    """The dry outliers of a fit as the lab names them: test id with its line ("D8 (line 13)"), or the line alone.

    Parameters
    ----------
    line : capred.fitting.linear.LineFit
        The SI fit of a dry envelope (its ``diagnostics`` flag the outliers).

    Returns
    -------
    list of str
    """
    diag = line.diagnostics or {}
    out = []
    for k in np.flatnonzero(np.asarray(diag.get("outlier", []), bool)):
        where = f"line {int(diag['lines'][k])}" if "lines" in diag else ""
        if "test_ids" not in diag:
            out.append(where or "?")
        else:
            tid = str(diag["test_ids"][k])
            out.append(f"{tid} ({where})" if where else tid)
    return out


def shear_tables(result) -> list[TableSpec]:
    """The console tables of a ``capred shear`` run.

    Dry fits; model metrics on all wet tests and on the pendular ones; how sure the ranking is; model selection; the
    back-analysed capillary stress of the wet tests.

    Every value comes from the run's typed records, in the units of the JSON: the envelopes'
    ``fit.params`` (``c_kPa``, ``phi_deg``, ``tan_phi``), the ``ModelMetrics`` (``rmse_kPa``, ``bias_kPa``), the
    fitted laws' ``law.params``, the back-analysis (``sigma_cap_kPa``), the bootstrap rankings.

    Parameters
    ----------
    result : capred.pipelines.shear.ShearResult
        A ``capred shear`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    opt = result.options
    phi_b = any("phi_b_deg" in result.per_material.get(m, {}) for m in result.fits)
    origin = opt.dry_fit == "origin"
    loss = opt.dry_loss
    fits = spec(
        "Dry envelope τ = c + σ_N tan φ"
        + (" (through the origin, c = 0)" if origin else "")
        + (f", {loss} loss" if loss != "ols" else "")
        + "; scatter: either (valid for constant or proportional), constant or proportional to τ (--errors), "
        "BP p: Breusch-Pagan test of growing scatter",
        ["material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ", "R²", "scatter", "BP p", "outliers"]
        + (["φ_b [°]"] if phi_b else []),
    )
    for mat, fit in result.fits.items():
        p, line = fit.params, fit.line
        bp = ((result.heteroscedasticity.get(mat) or {}).get("dry_fit") or {}).get("p_value")
        fits.rows.append(
            [
                mat,
                fmt(int(line.n)),
                fmt(p["c_kPa"].value),
                fmt(p["c_kPa"].stderr),
                fmt(p["phi_deg"].value),
                fmt(p["phi_deg"].stderr),
                fmt(p["tan_phi"].value),
                fmt(line.r2),
                getattr(line, "errors", "constant"),
                fmt(bp),
                ", ".join(_outlier_labels(line)) or "none",
                *([fmt(result.per_material.get(mat, {}).get("phi_b_deg"))] if phi_b else []),
            ]
        )
    n_wet = int(np.sum(result.tests["condition"] == "wet"))
    if n_wet == 0:  # a file of dry tests: the envelope alone, no empty wet-test tables (the notes say why)
        return [fits]
    out = [
        fits,
        _metrics_table(
            "Wet tests: model comparison (residual = predicted − measured)",
            result.metrics,
            result.metrics_overall,
            result.best_model,
            result.best_model_overall,
        ),
    ]
    if result.metrics_pendular:
        out.append(
            _metrics_table(
                f"Pendular wet tests only (S_R ≤ {opt.pendular_limit:g})",
                result.metrics_pendular,
                result.metrics_pendular_overall,
                result.best_model_pendular,
                result.best_model_pendular_overall,
            )
        )
    if result.ranking:
        kpa = QUANTITIES["tau_pred"].factor  # the ranking's RMSE differences are SI [Pa]
        boot = spec(
            "How sure is the ranking? (paired bootstrap of wet and dry tests; ΔRMSE = runner-up − best)",
            ["material", "best model", "best in % of resamples", "runner-up", "ΔRMSE 95 % CI [kPa]", "replicates"],
        )
        for mat, b in result.ranking.items():
            best = b.best
            p = num(b.probability.get(best)) if best else None
            diff = b.difference_ci
            used = fmt(b.replicates) if b.requested in (None, b.replicates) else f"{b.replicates} of {b.requested}"
            boot.rows.append(
                [
                    mat,
                    MODEL_LABELS.get(best, "—"),
                    "—" if p is None else f"{p:.0%}",
                    MODEL_LABELS.get(b.runner_up, "—"),
                    "—" if diff is None else _difference_text(diff, kpa),
                    used,
                ]
            )
        out.append(boot)
    sel = result.model_selection()
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
    if result.laws:
        f = spec("Fitted χ laws (dry c, φ held)", ["material", "model", "parameter", "value", "± se", "n"], left=3)
        for mat in result.materials:
            for m, by_material in result.laws.items():
                law = by_material.get(mat)
                if law is None:
                    continue
                from ..fitting.chi_laws import LAW_PARAMETERS

                lost = {LAW_PARAMETERS.get(k, (k,))[0] for k in law.unidentified}
                for name, par in law.params.items():
                    if not par.fixed:
                        se = "not identifiable" if name in lost else fmt(par.stderr)
                        f.rows.append([mat, MODEL_LABELS[m], name, fmt(par.value), se, fmt(law.n)])
        if f.rows:
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
            "suction [kPa]": t["suction"][i] * QUANTITIES["suction"].factor,  # tests hold SI [Pa]
            "σ_cap [kPa]": b.sigma_cap_kPa[i],
            "± se": b.sigma_cap_se_kPa[i],
            "χ_back": b.chi_back[i],
            "± se ": b.chi_back_se[i],
        }


def _difference_text(diff, kpa: float) -> str:
    """The ΔRMSE interval [kPa] at its printed resolution.

    `difference_resolution`: the adaptive bootstrap stops once the Monte-Carlo error of each end is below it.
    """
    import math

    from ..fitting.comparison import difference_resolution

    lo, hi = num(diff[0] * kpa), num(diff[1] * kpa)
    res = difference_resolution((lo, hi)) if lo is not None and hi is not None else None
    if res is None:
        return f"{fmt(lo)} to {fmt(hi)}"
    places = max(0, -int(math.floor(math.log10(res))))
    return f"{round(lo / res) * res:.{places}f} to {round(hi / res) * res:.{places}f}"


def _metrics_table(title, metrics, overall, best_of_material, best_overall) -> TableSpec:
    """One model-comparison table: per material (and "(all)") each model's ModelMetrics, the best in bold."""
    met = spec(title, ["material", "model", "n", "RMSE [kPa]", "bias [kPa]", "R²", "lowest RMSE"], left=2)
    groups = list(metrics.items())
    if overall and len(groups) > 1:
        groups.append(("(all)", overall))
    from ..fitting.comparison import compared

    for mat, models in groups:
        best = best_overall if mat == "(all)" else best_of_material.get(mat)
        _, apart = compared(models)
        for k, (m, v) in enumerate(models.items()):
            if m == best:
                met.bold_rows.add(len(met.rows))
            if k == len(models) - 1:
                met.sections.add(len(met.rows))
            met.rows.append(
                [
                    mat if k == 0 else "",
                    MODEL_LABELS[m],
                    fmt(v.n),
                    fmt(v.rmse_kPa),
                    fmt(v.bias_kPa, sign=True),
                    fmt(v.r2),
                    "best" if m == best else f"not ranked: lacks {apart[m]}" if m in apart else "",
                ]
            )
    return met
