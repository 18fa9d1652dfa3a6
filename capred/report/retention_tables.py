"""Console (and HTML) tables of `capred retention`, read from the run's typed records.

Per branch two narrow tables that fit an 80-column terminal without folding: the model comparison (every
model's name, R², RMSE, AICc, ΔAICc and Akaike weight, best first) and the parameters in long form (one row
per model and parameter: value, standard error, 95 % interval, unit). A long parameter list never widens a
row, so no number is cut and no column squeezed to nothing.
"""

from __future__ import annotations

import math

from ..table_spec import TableSpec
from .render import fmt, spec


def _num(x):
    return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x


def _order(records):
    return sorted(records, key=lambda r: (not math.isfinite(r.delta_aicc), _num(r.delta_aicc) or 0.0))


def model_table(branch: str, records, how: str) -> TableSpec:
    """Model comparison of one branch: model, k, R², RMSE, AICc, ΔAICc, Akaike weight (best first).

    Parameters
    ----------
    branch : str
        The branch name.
    records : list of RetentionFitRecord
        The fits of that branch.
    how : str
        How branches were told apart (shown in the title).

    Returns
    -------
    TableSpec
    """
    t = spec(f"Retention models, branch {branch} ({how})", ["model", "k", "R²", "RMSE", "AICc", "ΔAICc", "weight"])
    for r in _order(records):
        t.rows.append(
            [
                r.model,
                str(r.n_free),
                fmt(_num(r.r2)),
                fmt(_num(r.rmse)),
                fmt(_num(r.aicc)) if math.isfinite(r.aicc) else "— (n−k−1≤0)",
                fmt(_num(r.delta_aicc)),
                fmt(_num(r.weight)),
            ]
        )
    return t


def parameter_table(title: str, records) -> TableSpec:
    """Parameters of fits in long form.

    A bold row naming the model, then one row per parameter with its value, ± standard error, 95 % interval and unit
    (narrow enough for an 80-column terminal).

    Parameters
    ----------
    title : str
        Table title.
    records : list of RetentionFitRecord
        The fits (models in the order given).

    Returns
    -------
    TableSpec
    """
    t = spec(title, ["model / parameter", "value", "± se", "95 % CI", "unit"])
    for i, r in enumerate(records):
        t.bold_rows.add(len(t.rows))
        t.rows.append([r.model, "", "", "", ""])
        for p in r.params.values():
            if p.fixed:
                se, ci = "(fixed)", ""
            else:
                se = fmt(_num(p.stderr), 2)
                ci = "—" if not math.isfinite(p.ci95[0]) else f"{fmt(p.ci95[0], 3)} to {fmt(p.ci95[1], 3)}"
            t.rows.append(["  " + p.name, fmt(p.value), se, ci, p.unit])
        if i < len(records) - 1:
            t.sections.add(len(t.rows) - 1)
    return t


def retention_tables(result) -> list[TableSpec]:
    """Per branch: the model comparison and the parameters (± se, 95 % CI); the joint hysteresis fit.

    Parameters
    ----------
    result : capred.pipelines.retention.RetentionResult
        A ``capred retention`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    out = []
    for b in result.fits:
        recs = result.fit_records(b)
        out.append(model_table(b, recs, result.branch_source))
        out.append(parameter_table(f"Retention parameters, branch {b}", _order(recs)))
    if result.hysteresis is not None:
        rec = result.fit_record("both", "kool_parker")
        t = parameter_table("Hysteresis, Kool & Parker (1987): joint fit of both branches", [rec])
        ratio = result.hysteresis.params_si["alpha_w"] / result.hysteresis.params_si["alpha_d"]
        t.rows.append(["  α_w/α_d", fmt(ratio), "", "", "-"])
        t.rows.append(["  AICc joint", fmt(_num(rec.aicc)), "", "", "-"])
        t.rows.append(["  AICc independent", fmt(_num(result.independent_aicc())), "", "", "-"])
        out.append(t)
    scans = getattr(result, "scanning", [])
    if scans:
        t = spec(
            "Scanning curves, Parker & Lenhard (1987) scaling of the main curves",
            ["direction", "readings", "reversal [kPa]", "closure [kPa]", "main", "RMSE", "R²"],
        )
        for c in scans:
            closure = fmt(c.s_closure * 1e-3) if math.isfinite(c.s_closure) else "dry end"
            t.rows.append(
                [
                    c.direction,
                    f"{c.index[0] + 1}-{c.index[-1] + 1}",
                    fmt(c.s_reversal * 1e-3),
                    closure,
                    c.main_model,
                    fmt(_num(c.rmse)),
                    fmt(_num(c.r2)),
                ]
            )
        out.append(t)
    return out


def convert_tables(result) -> list[TableSpec]:
    """`capred retention-convert`: the conversion (from, to, misfit) and the parameters of both curves.

    Parameters
    ----------
    result : capred.pipelines.retention_convert.RetentionConvertResult
        A ``capred retention-convert`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    src, new, m = result.source_fit, result.converted, result.misfit
    unit = "m³/m³" if result.quantity == "theta" else "-"  # S_R and w (by mass) are both [-]
    t = spec(f"Conversion of {result.source}", ["", "value", "unit"])
    t.rows += [
        ["from", src.model, ""],
        ["to", new.model, ""],
        ["suction range", f"{fmt(m['suction_range_kPa'][0])} to {fmt(m['suction_range_kPa'][1])}", "kPa"],
        ["points", str(m["n_points"]), ""],
        ["RMSE", fmt(m["rmse"]), unit],
        ["largest deviation", fmt(m["max_deviation"]), unit],
        ["at suction", fmt(m["at_suction_kPa"]), "kPa"],
    ]
    b = next(iter(result.fits))
    recs = [result.fit_record(b, new.model)]
    out = [t, parameter_table("Converted parameters (standard errors do not apply)", recs)]
    src_table = spec(f"Source: {src.label}", ["parameter", "value", "unit"])
    for p in src.params.values():
        src_table.rows.append([p.name, fmt(p.value), p.unit])
    out.append(src_table)
    return out
