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
    for col in ("material", "n", "c [kPa]", "± se", "φ [°]", "± se", "tan φ", "R²"):
        fits.add_column(escape(col), justify="left" if col == "material" else "right")
    for mat, f in js["materials"].items():
        fits.add_row(mat, str(f["n"]), _f(f["c_kPa"]), _f(f["c_se_kPa"], ".2g"), _f(f["phi_deg"], ".2f"),
                     _f(f["phi_se_deg"], ".2f"), _f(f["tan_phi"]), _f(f["r2"]))

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
