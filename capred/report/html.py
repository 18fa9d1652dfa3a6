"""report.html: one self-contained document per run (no network; figures inline as SVG; prints to A4).

Built with a jinja2 template (templates/report.html.j2) with autoescaping, so
user text (material names, test ids) is shown literally.
"""
from __future__ import annotations

import sys
from datetime import datetime, timezone

from ..references import bibliography
from .render import fmt

#: the per-row table of the report shows at most this many rows (all are in the CSV)
MAX_REPORT_ROWS = 500

FLAG_MEANING = {
    "outside_pendular": "S_R above the pendular limit, for which the χ approximations were derived",
    "chi1_gt_1": "S_R > 3/(2π): χ1 = (2π S_R/3)^(2/3) exceeds 1",
    "no_concave_bridge": "more water than the last concave bridge at contact: no exact_neck prediction",
    "lower_positive_component": "lower bound with a positive (compressive) capillary component",
    "spherical_positive_component": "spherical bound with a positive capillary component",
    "edtp_positive_component": "EDTP bound with a positive capillary component",
    "spherical_negative_p_prime": "spherical bound gives p' < 0",
}

METHODS = {
    "shear": (
        ["Suction Δu = γ_w z1 from the hanging-column head, degree of saturation S_R = (V_v − z2)/V_v from the "
         "burette, normal stress σ_N = (m_cap + m_added) g/A (Evenepoel, VUB thesis, \"Apply suction\").",
         "Per material, the dry envelope τ = c + σ_N tan φ is fitted by least squares with standard errors and "
         "Student-t 95 % intervals. Every wet test is predicted with the dry c, φ and σ'_N = σ_N + χ Δu of each "
         "model: χ = S_R (Bishop 1959), χ1 = (2π S_R/3)^(2/3) and χ1 Δu + (2γ/R)(2π S_R/3)^(1/3) (Evenepoel's "
         "Own 1 and Own 2), and the others chosen with --models. Scores: RMSE, bias and R² of predicted − measured, "
         "on all wet tests and on the pendular ones.",
         "The capillary stress each wet test carried is back-analysed as σ_cap = (τ_max − c)/tan φ − σ_N with its "
         "standard uncertainty by the delta method; χ_back = σ_cap/Δu. The ranking's uncertainty comes from a "
         "paired bootstrap over the wet tests that refits the dry envelope in every replicate."],
        ["evenepoel", "bishop1959", "vanapalli1996", "khalili_khabbaz1998", "lu_likos2006", "fredlund1978",
         "pedrotti_tarantino"]),
    "triaxial-bounds": (
        ["The effective envelope c', φ' is fitted to the saturated drained tests by least squares of σ'1 on σ'3, "
         "σ'1 = K_p σ'3 + 2c'√K_p (Prunier et al. 2024, eq. 25). For every unsaturated test the total failure state "
         "is projected on it under three hypotheses: a spherical capillary tensor (q = q'), the lower bound "
         "σ1,cap = 0, and the EDTP upper bound from the initial suction s0; the strength gain is q'/q'_sat. Groups "
         "sharing one tensor get the analysis of Appendix 1 (eqs. 37, 48, 49)."],
        ["prunier2024"]),
    "retention": (
        ["Water retention curves are fitted per branch (drying, wetting) by least squares on θ or S_R: van "
         "Genuchten (1980) with m = 1 − 1/n and with m free, and Brooks & Corey (1964) with the air-entry suction "
         "profiled exactly. Standard errors from the Jacobian; R², AIC and BIC."],
        ["vangenuchten1980", "brooks_corey1964"]),
    "prism": (["P_kmax = σ_b (1 − sin ρ)/(2 sin ρ) and h_c = P_kmax/γ_w from the break tension of a sand prism and "
               "the friction angle of the sand (Bernatzik 1948)."], ["bernatzik1948"]),
    "skempton-b": (["B = 1/(1 + p'0 e0 (1 − S_r)/(κ P_a0)) with p'0 = p0 − u0 (Morvan et al. 2016, eq. 10), or its "
                    "inverse; with suction equilibrium p'0 = p0 − u_a0 + s S_r and s from Brooks-Corey."],
                   ["morvan2016", "skempton1954", "brooks_corey1964"]),
    "rumpf": (["p_cap = −(6/φ)(S_r/e)(γ/d_p) cos θ (Prunier et al. 2024, eq. 19, after Rumpf)."], ["prunier2024"]),
    "bridge solve": (["Exact pendular bridges between two equal spheres from the axisymmetric Young-Laplace equation, "
                      "its first integral evaluated by Gauss-Legendre quadrature; F_cap = π r0² Δu + 2π r0 γ, "
                      "S_R = 3V_w/(2πR³), σ' = F_cap/(πR²) (Evenepoel's unit cell; Lian et al. 1993)."],
                     ["evenepoel", "lian1993"]),
    "bridge compare": (["Measured capillary forces of micro-tests beside the exact bridge of the same R, gap, contact "
                        "angle and volume, the toroidal approximation, Willett et al. (2000) and Israelachvili's "
                        "2πRγ cos θ."], ["willett2000", "israelachvili", "lian1993"]),
    "bridge curve": (["σ' = F_cap/(πR²) against S_R = 3V_w/(2πR³) for two spheres in contact, from exact bridges, "
                      "beside Israelachvili, Bishop (S_R Δu) and Evenepoel's Own 1 and Own 2."],
                     ["evenepoel", "israelachvili", "bishop1959"]),
}


def _options(doc: dict) -> list[tuple[str, str, str]]:
    units = doc.get("option_units", {})
    out = []
    for name, value in doc["options"].items():
        if isinstance(value, dict):
            for k, v in value.items():
                out.append((f"{name}.{k}", _text(v), ""))
        else:
            out.append((name, _text(value), units.get(name, "")))
    return out


def _text(v) -> str:
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, (list, tuple)):
        return ", ".join(_text(x) for x in v)
    return "—" if v is None else str(v)


def _flags(result) -> list[tuple[str, int, str]]:
    try:
        frame = result.table()
    except Exception:  # pragma: no cover - every result has a table
        return []
    if "flags" not in frame.columns:
        return []
    counts: dict[str, int] = {}
    for text, k in frame["flags"].value_counts().items():  # distinct flag combinations, counted once each
        for f in (text.split(";") if isinstance(text, str) and text else []):
            counts[f] = counts.get(f, 0) + int(k)
    return [(k, v, FLAG_MEANING.get(k, "")) for k, v in counts.items()]


def _per_row(result) -> dict:
    frame = result.table()
    rows = []
    for values in frame.head(MAX_REPORT_ROWS).itertuples(index=False):
        rows.append([fmt(v) if isinstance(v, float) else ("" if v is None else str(v)) for v in values])
    name = next(iter(result.tables()))
    return {"columns": [str(c) for c in frame.columns], "rows": rows, "total": len(frame), "file": f"{name}.csv"}


def render_html(result, figures: dict, plots: bool) -> str:
    """The report of one run as an HTML string (figures: {sheet: {"svg", "caption", "panels"}})."""
    from importlib.resources import files

    import jinja2

    from .presenters import console_tables

    template = jinja2.Environment(autoescape=True, undefined=jinja2.StrictUndefined).from_string(
        files("capred.report").joinpath("templates/report.html.j2").read_text(encoding="utf-8"))
    doc = result.header()
    paragraphs, refs = METHODS.get(result.command, ([], []))
    names = ", ".join(i["path"].replace("\\", "/").rsplit("/", 1)[-1] for i in doc["inputs"]) or "options"
    return template.render(
        title=f"capred {result.command}: {names}",
        doc=doc,
        created=datetime.now(timezone.utc).replace(microsecond=0).isoformat(),
        command_line=" ".join(["capred", *sys.argv[1:]]) if sys.argv and "capred" in sys.argv[0] else
        f"capred {result.command}",
        options=_options(doc),
        warnings=doc["warnings"],
        notes=doc["notes"],
        flags=_flags(result),
        tables=console_tables(result),
        figures=list(figures.items()),
        plots=plots,
        methods=paragraphs,
        references=bibliography(refs),
        per_row=_per_row(result),
    )


_SEASON = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>capred season</title>
<style>@page { size: A4 landscape; margin: 12mm; } body { font-family: "DejaVu Sans", Arial, sans-serif;
font-size: 9pt; margin: 1.5em; } table { border-collapse: collapse; } th, td { border-bottom: 1px solid #ccc;
padding: 2px 6px; text-align: right; } th { background: #eee; } td.l, th.l { text-align: left; }</style></head>
<body><h1>capred season: {{ n }} runs</h1>
<table><tr>{% for c in columns %}<th class="l">{{ c }}</th>{% endfor %}</tr>
{% for row in rows %}<tr>{% for c, v in row %}<td class="{{ 'l' if c in ('input', 'command', 'status', 'material',
'best_model') else '' }}">{% if c == 'report' and v %}<a href="{{ v }}">report</a>{% else %}{{ v }}{% endif %}</td>
{% endfor %}</tr>{% endfor %}</table></body></html>
"""


def render_season(frame) -> str:
    """The season table of a batch as one HTML page linking each run's report.html."""
    import jinja2

    rows = [[(c, fmt(v) if isinstance(v, float) else ("" if v is None else str(v))) for c, v in zip(frame.columns, r)]
            for r in frame.itertuples(index=False)]
    return jinja2.Environment(autoescape=True).from_string(_SEASON).render(
        n=int(frame["input"].nunique()) if len(frame) else 0, columns=list(frame.columns), rows=rows)
