"""Calculators as typed records (issue 28, item 1): one field declaration gives attribute, JSON key, CSV header
and console header; the JSON keys are capred 0.x's, the CSV headers all ``name [unit]``."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from numpy.testing import assert_array_equal
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.pipelines.calculator_records import PrismCases, RumpfCases, SkemptonCases, json_key
from capred.report.calculator_tables import calc_tables

#: the JSON keys of every case, as capred 0.x wrote them (a public interface: unchanged)
JSON_KEYS = {
    "prism": [
        "case",
        "break_tension_kPa",
        "friction_angle_deg",
        "P_kmax_kPa",
        "capillary_rise_cm",
        "P_kmax_over_sigma_b",
    ],
    "skempton-b": ["S_r", "kappa", "e0", "p0_kPa", "u0_kPa", "pa0_kPa", "B"],
    "rumpf": [
        "case",
        "shape_factor",
        "void_ratio",
        "S_r",
        "diameter_mm",
        "surface_tension_N_per_m",
        "contact_angle_deg",
        "p_cap_kPa",
    ],
}
CSV_HEADERS = {
    "prism": [
        "case",
        "break_tension [kPa]",
        "friction_angle [deg]",
        "P_kmax [kPa]",
        "capillary_rise [cm]",
        "P_kmax_over_sigma_b [-]",
    ],  # fmt: skip
    "skempton-b": ["model", "S_r [-]", "kappa [-]", "e0 [-]", "p0 [kPa]", "u0 [kPa]", "pa0 [kPa]", "B [-]"],
    "rumpf": [
        "case",
        "shape_factor [-]",
        "void_ratio [-]",
        "S_r [-]",
        "diameter [mm]",
        "surface_tension [N/m]",
        "contact_angle [deg]",
        "p_cap [kPa]",
    ],  # fmt: skip
}
RUN = {"prism": capred.run_prism, "skempton-b": capred.run_skempton_b, "rumpf": capred.run_rumpf}


@pytest.fixture(scope="module", params=sorted(RUN))
def run(request):
    name = request.param
    return name, RUN[name](capred.sample_path(name))


def test_json_keys_unchanged(run):
    name, r = run
    assert list(r.to_json()["cases"][0]) == JSON_KEYS[name]


def test_csv_headers_name_unit(run):
    name, r = run
    assert list(r.tables()["results"].columns) == CSV_HEADERS[name]


def test_attributes_equal_the_json(run):
    """Each record attribute equals the JSON's numbers under the derived key (the same floats: tolerance 0)."""
    name, r = run
    cases = r.to_json()["cases"]
    for f in r.cases.columns():
        got = np.asarray(getattr(r.cases, f.name), float)
        want = np.array([np.nan if c[json_key(f)] is None else c[json_key(f)] for c in cases])
        assert_array_equal(got, want, err_msg=f.name)


def test_console_headers_from_the_glossary(run):
    """The console (and report.html) shows symbol [unit] of each field's glossary entry."""
    name, r = run
    heads = [h for h, _ in calc_tables(r)[0].columns]
    expected = {
        "prism": ["case", "σ_b [kPa]", "ρ [deg]", "P_kmax [kPa]", "h_c [cm]", "P_kmax/σ_b [-]"],
        "skempton-b": ["S_R [-]", "κ [-]", "e0 [-]", "p0 [kPa]", "u0 [kPa]", "P_a0 [kPa]", "B [-]"],
        "rumpf": ["case", "φ_s [-]", "e [-]", "S_R [-]", "d_p [mm]", "γ [N/m]", "θ_c [deg]", "p_cap [kPa]"],
    }[name]
    assert heads == expected


def test_prism_by_hand():
    """Bernatzik (1948): P_kmax = σ_b (1 − sin ρ)/(2 sin ρ); h_c = P_kmax/γ_w. σ_b = 10 kPa, ρ = 30 deg:
    P_kmax = 10 (1 − 0.5)/(2 · 0.5) = 5 kPa; h_c = 5000/9810 m = 50.968 cm (rounding only: 1e-12)."""
    r = capred.run_prism(break_tension="10 kPa", friction_angle=30)
    assert isinstance(r.cases, PrismCases)
    assert r.cases.P_kmax[0] == pytest.approx(5.0, rel=1e-12)
    assert r.cases.capillary_rise[0] == pytest.approx(5000 / 9810 * 100, rel=1e-12)
    assert r.cases.P_kmax_over_sigma_b[0] == pytest.approx(0.5, rel=1e-12)
    assert r.outputs["P_kmax_kPa"][0] == r.cases.P_kmax[0]  # the JSON-keyed view of the same record


def test_skempton_inverse_puts_the_solved_field_last():
    """B given, S_r computed: B leads and S_r closes the row, as capred 0.x ordered it."""
    fwd = capred.run_skempton_b(S_R=0.95, kappa_elastic=0.006, e0=0.8, p0="100 kPa", u0="30 kPa", pa0="130 kPa")
    B = float(fwd.cases.B[0])
    inv = capred.run_skempton_b(b=B, kappa_elastic=0.006, e0=0.8, p0="100 kPa", u0="30 kPa", pa0="130 kPa")
    assert isinstance(inv.cases, SkemptonCases) and inv.cases.solved == "S_R"
    assert list(inv.to_json()["cases"][0]) == ["B", "kappa", "e0", "p0_kPa", "u0_kPa", "pa0_kPa", "S_r"]
    assert inv.cases.S_R[0] == pytest.approx(0.95, rel=1e-9)  # the inverse of eq. 10 (brentq-free closed form)
    assert list(inv.outputs) == ["S_r"] and list(inv.values)[0] == "B"


def test_own_files_read_back_new_and_old_headers(tmp_path):
    """capred reads its results.csv back as cases (``S_r [-]``) and a file with capred 0.x's headers (``S_r``)."""
    out = tmp_path / "o"
    assert CliRunner().invoke(app, ["rumpf", "--sample", "--no-plots", "--out", str(out)]).exit_code == 0
    again = capred.run_rumpf(out / "results.csv")
    first = capred.run_rumpf(capred.sample_path("rumpf"))
    assert_array_equal(again.cases.p_cap, first.cases.p_cap)
    old = pd.read_csv(out / "results.csv").rename(columns={"shape_factor [-]": "shape_factor", "S_r [-]": "S_r",
                                                          "void_ratio [-]": "void_ratio"})  # fmt: skip
    old.to_csv(tmp_path / "old.csv", index=False)
    assert_array_equal(capred.run_rumpf(tmp_path / "old.csv").cases.p_cap, first.cases.p_cap)


def test_rumpf_record_types():
    r = capred.run_rumpf(shape_factor=1.0, void_ratio=0.5, S_R=0.5, diameter="0.1 mm", surface_tension=0.0728)
    assert isinstance(r.cases, RumpfCases) and len(r.cases) == 1
    assert r.cases.diameter[0] == pytest.approx(0.1, rel=1e-12) and math.isfinite(r.cases.p_cap[0])
