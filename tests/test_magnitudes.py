"""Physically impossible magnitudes are errors, implausible ones warnings (issue 32, item 7); the bounds live in
the glossary (capred.nomenclature.MAGNITUDES), one per quantity, each with its reason."""

import warnings

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import InputError
from capred.nomenclature import MAGNITUDES, QUANTITIES, magnitude_of, magnitude_problem, magnitude_warning

runner = CliRunner()
HEAD = "test_id,material,condition,sigma_N [kPa],tau_max [kPa]\n"
ROWS = "b,m,dry,20,11.5\nc,m,dry,30,17.4\nd,m,dry,40,23.0\n"


def test_every_bound_is_a_glossary_quantity_with_a_reason():
    for name, m in MAGNITUDES.items():
        assert name in QUANTITIES and m.why and 0 < m.warn < m.error


def test_stress_bounds_are_50_mpa_and_1_gpa():
    assert magnitude_problem("tau_max", 0.99e9) is None and magnitude_problem("tau_max", 1.01e9)
    assert magnitude_warning("tau_max", 49e6) is None and magnitude_warning("tau_max", 51e6)
    assert magnitude_warning("tau_max", 2e9) is None  # impossible, not implausible: said once, as an error
    assert magnitude_problem("sigma3", -2e9)  # a magnitude: negative too
    assert magnitude_of("s0", "pressure") is MAGNITUDES["suction"]  # a suction column: its own bound
    assert magnitude_of("back_pressure", "pressure") is MAGNITUDES["sigma_N"]  # any other pressure: a stress


def test_tau_max_1e300_is_an_error_not_a_cohesion_of_minus_1e299(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text(HEAD + "a,m,dry,10,1e300\n" + ROWS)
    with pytest.raises(InputError) as err:
        capred.run_shear(p)
    (prob,) = err.value.problems
    assert prob.line == 2 and "tau_max" in prob.column and "physically impossible" in prob.message
    res = runner.invoke(app, ["shear", str(p), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code != 0 and "physically impossible" in res.output and "Traceback" not in res.output
    assert not (tmp_path / "o").exists()


def test_an_implausible_stress_is_one_warning_per_column(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text(HEAD + "a,m,dry,60000,5\ne,m,dry,70000,6\n" + ROWS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = capred.run_shear(p)
    told = [w for w in r.warnings if "implausible for a soil test" in w]
    assert len(told) == 1 and "2 values, the first on line 2" in told[0] and "sigma_N" in told[0]


def test_triaxial_table_without_quantities_is_checked_by_kind(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("test_id,condition,sigma3,q_f\ns1,saturated,30,75.7\ns2,saturated,5e9,119.6\n")
    with pytest.raises(InputError, match="physically impossible"):
        capred.run_triaxial_bounds(p)
