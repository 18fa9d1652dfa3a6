"""skempton-b's figure (issue 42): the pipeline computes every curve (capred.pipelines.skempton_figure), the
report only draws them (capred.report.calculator_figures imports no physics)."""

import ast
from pathlib import Path

import numpy as np
import pytest

import capred
from capred.physics import calculators as calc
from capred.pipelines.calculators import run_skempton_b


def test_each_case_lies_on_its_own_curve():
    """Every computed case's (S_r, B) lies on the eq. 10 curve of its parameter set (Morvan et al. 2016): the
    curve, interpolated linearly on its 400-point grid (step 1.25e-3 in S_r), meets the case's B within 1e-3
    (B's slope in S_r stays below 1 per 0.001 on the sample's cases, so the interpolation error is far smaller)."""
    res = run_skempton_b(capred.sample_path("skempton-b"))
    drawn = res.figure_curves()
    assert drawn["cases"] and sum(len(c["points"][0]) for c in drawn["cases"]) == len(res.to_json()["cases"])
    for case in drawn["cases"]:
        S_pts, B_pts = (np.asarray(v, float) for v in case["points"])
        inside = (S_pts >= 0.5) & (S_pts <= 1.0)
        assert inside.any()
        on_curve = np.interp(S_pts[inside], drawn["S_r"], case["B_eq10"])
        assert on_curve == pytest.approx(B_pts[inside], abs=1e-3)


def test_parameter_studies_are_eq_10():
    """The κ study is eq. 10 at the options' e0, p0 − u0 and pa0 [Pa]."""
    res = run_skempton_b(capred.sample_path("skempton-b"), e0=0.7, p0=150e3, u0=20e3, pa0=120e3)
    drawn = res.figure_curves()
    for kappa, B in drawn["studies"]["kappa"].items():
        expected = calc.skempton_b(drawn["S_r"], 150e3 - 20e3, 0.7, kappa, 120e3)
        np.testing.assert_allclose(B, expected, rtol=1e-12)  # one formula, same inputs


def test_the_report_draws_without_physics():
    tree = ast.parse(Path(capred.__file__).with_name("report").joinpath("calculator_figures.py").read_text("utf-8"))
    imported = {n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert not [m for m in imported if "physics" in m]
