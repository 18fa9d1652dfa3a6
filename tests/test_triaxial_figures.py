"""Figures of `capred triaxial-bounds` drawn from capred's own numbers, each citing the figure of Prunier et al.
(2024) it follows (issue 33.2): q-eps1 and epsv-eps1 with the picked peaks (their Fig. 10, 15), and the rest."""

import re

import numpy as np
import pandas as pd
import pytest

import capred


def _with_curves():
    tests = pd.read_csv(capred.sample_path("triaxial-bounds"), comment="#")
    tests.loc[tests["condition"] == "unsaturated", "q_f [kPa]"] = np.nan  # the curves give the peaks
    return capred.run_triaxial_bounds(tests, curves=capred.sample_path("triaxial-curves"))


def test_curves_kept_for_the_figures_are_the_ones_that_gave_q_f():
    r = _with_curves()
    assert sorted(r.curves) == ["UNSAT-0", "UNSAT-100", "UNSAT-150"]
    for tid, c in r.curves.items():
        i = list(r.states.test_id).index(tid)
        # the peak of the curve is the test's failure state, as read (no membrane correction here); kPa -> Pa ->
        # kPa costs one rounding: 1e-15 relative
        assert c.q[c.peak] == np.nanmax(c.q) == pytest.approx(r.states.q[i], rel=1e-15)
        assert c.axial_strain[c.peak] == r.states.strain_at_failure[i]
    # without --curves there are none, and no curve panels
    assert capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds")).curves == {}


@pytest.mark.slow
def test_every_panel_cites_the_figure_it_follows_and_marks_the_peaks():
    r = _with_curves()
    fig = r.plot("report")
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert "Prunier et al. 2024, Fig." in fig._suptitle.get_text()
    for t in titles:
        assert re.search(r"\(Fig\. \d", t), t  # each panel names the paper's figure
    (q_ax,) = [ax for ax in fig.axes if ax.get_title().startswith(r"$q$-$\varepsilon_1$")]
    # the peak markers sit at (strain at failure [%], q_f [kPa]) of each curve test
    points = {
        (round(float(x[0]), 9), round(float(y[0]), 9))
        for ln in q_ax.get_lines()
        for x, y in [ln.get_data()]
        if len(x) == 1
    }
    for tid in r.curves:
        i = list(r.states.test_id).index(tid)
        assert (round(r.states.strain_at_failure[i] * 100, 9), round(r.states.q[i], 9)) in points
    groups = capred.run_triaxial_bounds(capred.sample_path("triaxial-groups")).plot("report")
    for ax in groups.axes:
        if ax.get_title():
            assert re.search(r"\(Fig\. \d|range without pairs", ax.get_title()), ax.get_title()


def test_curves_of_tests_with_q_f_are_compared_with_it_and_drawn_for_reference(tmp_path):
    """A curve whose test has q_f in the table is not used for failure (the table wins); the note names it and
    compares the curve's peak with q_f. Here UNSAT-0's q_f is blanked (its curve gives failure) and UNSAT-100's
    set to 300 kPa against its curve's peak of 317.6 kPa: (317.6 - 300)/300 = +5.9 %, by hand."""
    from capred.pipelines.triaxial import run_triaxial_bounds
    from capred.report.sheets import sheet_figure
    from capred.report.triaxial_figures import sheet_triaxial

    text = capred.sample_path("triaxial-bounds").read_text(encoding="utf-8")
    text = text.replace("UNSAT-0,unsaturated,0,150.2,", "UNSAT-0,unsaturated,0,,").replace(
        "UNSAT-100,unsaturated,100,317.6,", "UNSAT-100,unsaturated,100,300,"
    )
    tests = tmp_path / "tests.csv"
    tests.write_text(text, encoding="utf-8")
    r = run_triaxial_bounds(tests, curves=capred.sample_path("triaxial-curves"))
    assert sorted(r.curves) == ["UNSAT-0"] and sorted(r.reference_curves) == ["UNSAT-100", "UNSAT-150"]
    note = next(n for n in r.notes if n.startswith("--curves:"))
    assert "UNSAT-100, UNSAT-150 not used for failure: these tests have q_f" in note, note
    assert "'UNSAT-100', peak 317.6 kPa against q_f 300 kPa (+5.9 %)" in note, note
    # the failure of UNSAT-0 is its curve's peak (150.2 kPa, the sample's q_f it was made from)
    assert r.states.q[list(r.states.test_id).index("UNSAT-0")] == pytest.approx(150.2, abs=0.05)
    titles = [ax.get_title() for ax in sheet_figure(sheet_triaxial(r)).axes]
    assert sum("for reference" in t for t in titles) == 2, titles  # q-eps1 and epsv-eps1
    assert any("picked peaks" in t for t in titles), titles  # UNSAT-0's curve, used for failure
    # no reference panels when every curve gave its test's failure
    text = text.replace("UNSAT-100,unsaturated,100,300,", "UNSAT-100,unsaturated,100,,").replace(
        "UNSAT-150,unsaturated,150,396.7,", "UNSAT-150,unsaturated,150,,"
    )
    tests.write_text(text, encoding="utf-8")
    r = run_triaxial_bounds(tests, curves=capred.sample_path("triaxial-curves"))
    assert r.reference_curves == {} and not any(n.startswith("--curves:") for n in r.notes)
