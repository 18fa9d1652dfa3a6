"""What makes a batch fast without changing a byte: one BLAS thread per worker, report.html and season.html
tables built column by column exactly as the template loops built them, the bootstrap's affine check in three
predictions (issue 20, item 3)."""

from __future__ import annotations

import jinja2
import numpy as np
import pytest
from numpy.testing import assert_allclose

from capred import batch
from capred.physics import effective_stress_models as esm
from capred.pipelines import shear_analysis as sa
from capred.pipelines.shear import ModelParams
from capred.report import html as report_html
from capred.report.render import fmt
from capred.result import TableSpec


def test_single_threaded_blas_sets_one_thread_and_restores_the_count():
    import scipy.linalg  # noqa: F401  (scipy's own OpenBLAS loaded too)

    controls = batch._openblas_controls()
    if not controls:
        pytest.skip("no OpenBLAS found in this process (not Linux, or another BLAS)")
    before = [get() for _, get in controls]
    with batch.single_threaded_blas():
        assert [get() for _, get in controls] == [1] * len(controls)
    assert [get() for _, get in controls] == before


def test_float_cells_print_as_fmt_prints_each_value():
    values = np.array([np.nan, np.inf, -np.inf, -0.0, 0.0, 1e-300, 123456.7, 0.1 + 0.2, -2.5e-7, 42.0])
    cells = report_html._float_cells(np.stack([values, values[::-1]]))
    assert cells == [[fmt(float(v)) for v in values], [fmt(float(v)) for v in values[::-1]]]
    # by hand: 4 significant digits, '—' where not finite
    assert cells[0][:3] == ["—"] * 3 and cells[0][6] == "1.235e+05" and cells[0][7] == "0.3" and cells[0][9] == "42"
    many = np.random.default_rng(1).standard_cauchy(20_000) * 10.0 ** np.random.default_rng(2).integers(-12, 12, 20_000)
    assert report_html._float_cells(many[None, :])[0] == [fmt(float(v)) for v in many]


#: the summary-table rows of report.html as its template built them, cell by cell (before the rows were built
#: in Python): the reference for byte-identical output
_SUMMARY_LOOP = jinja2.Environment(autoescape=True).from_string(
    """{% for row in rows %}
  <tr>{% for cell in row %}<td class="{{ 'l' if columns[loop.index0][1] == 'left' else '' }}">{{ cell }}</td>"""
    """{% endfor %}</tr>
  {% endfor %}"""
)


def test_summary_rows_are_the_bytes_of_the_template_loop():
    spec = TableSpec("t", [("material", "left"), ("c [kPa]", "right"), ("note", "left")])
    spec.rows = [["sand <b>&", "1.2", 'say "hi"'], ["o'clay", "—", ""], ["x", "3", "a > b"]]
    for group in ([0, 1, 2], [0, 2]):
        columns = [spec.columns[j] for j in group]
        want = _SUMMARY_LOOP.render(rows=[[r[j] for j in group] for r in spec.rows], columns=columns)
        got = report_html._summary_rows(spec.rows, [c[1] == "left" for c in columns], group)
        assert str(got) == want


def test_season_html_cells_are_escaped_and_a_missing_value_is_blank():
    """season.html from the season table's columns (capred.batch.season_columns): user text escaped as the
    template escaped it, a count a run has not blank (not '<NA>', not 12.0), a missing float blank too (not
    '—'), text columns left-aligned, the report a link."""
    from capred.batch import season_columns

    rows = [
        {
            "input": "a<1>.csv",
            "command": "shear",
            "status": "ok",
            "material": 'sand "x"',
            "c [kPa]": 1.23456,
            "n_dry": 4,
            "report": "shear_a/report.html",
        },
        {"input": "b&'c'.csv", "command": "retention", "status": "ok", "branch": "drying", "n_dry": None, "report": ""},
    ]
    page = report_html.render_season(season_columns(rows))
    assert (
        '<tr><td class="l">a&lt;1&gt;.csv</td>\n<td class="l">shear</td>\n<td class="l ok">ok</td>\n'
        '<td class="l">sand &#34;x&#34;</td>\n<td class="">1.235</td>\n<td class="">4</td>\n'
        '<td class=""><a href="shear_a/report.html">report</a></td>\n<td class="l"></td>\n</tr>'
    ) in page
    assert (
        '<tr><td class="l">b&amp;&#39;c&#39;.csv</td>\n<td class="l">retention</td>\n<td class="l ok">ok</td>\n'
        '<td class="l"></td>\n<td class=""></td>\n<td class=""></td>\n<td class=""></td>\n'
        '<td class="l">drying</td>\n</tr>'
    ) in page


def _wet(n: int = 7) -> esm.ModelInputs:
    rng = np.random.default_rng(3)
    sigma = rng.uniform(5e3, 40e3, n)
    suction = rng.uniform(0.5e3, 6e3, n)
    S_R = rng.uniform(0.05, 0.3, n)
    tau = 1e3 + 0.6 * (sigma + S_R * suction) + rng.normal(0, 100.0, n)
    return esm.ModelInputs(
        sigma,
        suction,
        S_R,
        np.full(n, 1e-3),
        tau,
        np.ones(n, bool),
        np.array(["m"] * n, dtype=object),
        np.full(n, 1e3),
        np.full(n, 0.6),
        0.0728,
        ModelParams(),
    )


def test_pointwise_affine_gives_bishops_derivatives_by_hand():
    """Bishop: tau = c + (sigma_N + S_R s) tan phi, so d tau/dc = 1 and d tau/d tan phi = sigma_N + S_R s; the
    finite differences of an affine function are exact to rounding (1e-9 relative: steps of 10 % of c and
    tan phi on values of ~1e4 Pa)."""
    d = _wet()
    e0, beta, gamma = sa._pointwise_affine("bishop", d)
    assert_allclose(beta, 1.0, rtol=1e-9)
    assert_allclose(gamma, d.sigma_N + d.S_R * d.suction, rtol=1e-9)
    assert_allclose(e0, 1e3 + 0.6 * (d.sigma_N + d.S_R * d.suction) - d.tau_max, rtol=1e-9, atol=1e-9)


def test_pointwise_affine_refuses_a_model_fitted_on_the_set():
    """Fredlund's tan phi_b is fitted on the set's own strengths: a half of the tests gets another fit, so
    the model is scored replicate by replicate (None)."""
    d = _wet()
    assert sa._pointwise_affine("fredlund", d) is None


def test_all_close_is_allclose_with_equal_nan():
    a = np.array([1.0, np.nan, np.inf, -np.inf, 5.0])
    for b, atol in (
        (a.copy(), 0.0),
        (a + np.array([1e-10, 0, 0, 0, -1e-10]), 1e-9),
        (a + np.array([1e-8, 0, 0, 0, 0]), 1e-9),
        (np.array([1.0, 2.0, np.inf, np.inf, 5.0]), 1.0),
    ):
        assert sa._all_close(a, b, atol) == np.allclose(a, b, rtol=0.0, atol=atol, equal_nan=True)
