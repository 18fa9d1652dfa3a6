"""triaxial-bounds and the material column: one material per run, never pooled (issue 40)."""

import pytest
from numpy.testing import assert_allclose
from typer.testing import CliRunner

from capred.cli import app
from capred.errors import InputError, OptionError
from capred.pipelines.triaxial import TriaxialOptions, run_triaxial_bounds

runner = CliRunner()
A = "s1,A,saturated,30,75.7,,\ns2,A,saturated,50,119.6,,\ns3,A,saturated,100,229.1,,\nu1,A,unsaturated,100,300,55,100\n"
B = "t1,B,saturated,30,60,,\nt2,B,saturated,100,200,,\nt3,B,saturated,150,290,,\n"
HEAD = "test_id,material,condition,sigma3,q_f,s0,p0\n"


def test_several_materials_are_refused_not_pooled(write_csv):
    path = write_csv(HEAD + A + B)
    with pytest.raises(InputError, match=r"2 materials .*'A' \(4 tests\), 'B' \(3 tests\).*--material"):
        run_triaxial_bounds(path)
    out = path.parent / "out"
    res = runner.invoke(app, ["triaxial-bounds", str(path), "--out", str(out), "--no-plots"])
    assert res.exit_code == 1 and "never pools" in res.output and not out.exists()


def test_material_option_equals_a_table_of_that_material_alone(write_csv):
    both = write_csv(HEAD + A + B, "both.csv")
    alone = write_csv(HEAD + A, "alone.csv")
    env = run_triaxial_bounds(both, TriaxialOptions(material="A")).envelope
    ref = run_triaxial_bounds(alone).envelope
    # the same four rows fitted by the same code: identical to rounding
    assert_allclose([env.c_kPa, env.phi_deg], [ref.c_kPa, ref.phi_deg], rtol=1e-12)
    b = run_triaxial_bounds(both, TriaxialOptions(material="B")).envelope
    assert abs(b.phi_deg - env.phi_deg) > 1  # B's own envelope, not A's nor a pooled one


def test_unknown_material_and_line_numbers(write_csv):
    both = write_csv(HEAD + A + B)
    with pytest.raises(OptionError, match="its materials: A, B"):
        run_triaxial_bounds(both, TriaxialOptions(material="C"))
    bad = write_csv(HEAD + A + "t1,B,saturated,30,-60,,\nt2,B,saturated,100,200,,\n", "bad.csv")
    with pytest.raises(InputError, match="line 6"):  # the file's own line, after selecting B
        run_triaxial_bounds(bad, TriaxialOptions(material="B"))


UNSAT = (
    "test_id,condition,sigma3,q_f,s0,p0\n"
    "u1,unsaturated,50,260,50,50\nu2,unsaturated,100,360,50,100\nu3,unsaturated,200,560,50,200\n"
    "u4,unsaturated,50,330,150,50\nu5,unsaturated,100,430,150,100\nu6,unsaturated,200,640,150,200\n"
)


def test_no_saturated_test_uses_the_named_envelope_at_zero_suction(write_csv):
    """Issue 40: without saturated tests, triaxial-bounds takes c', phi' of the extended Mohr-Coulomb fit at s -> 0."""
    import math

    import numpy as np

    from capred.fitting.extended_mc import fit_extended_mc

    path = write_csv(UNSAT)
    res = run_triaxial_bounds(path)
    env = res.envelope
    assert env.source == "extended_mc" and "s -> 0" in env.method
    assert any("no saturated test" in n for n in res.notes)
    fit = fit_extended_mc([50e3, 100e3, 200e3] * 2, [50e3] * 3 + [150e3] * 3, [260e3, 360e3, 560e3, 330e3, 430e3, 640e3],
                          "compression", "proportional")  # fmt: skip
    c, phi, _ = fit.envelope
    assert_allclose([env.c_kPa, env.phi_deg], [c / 1e3, phi], rtol=1e-12)  # the same fit, two entry points
    # with its uncertainty: Student-t interval with n - 3 dof
    assert env.params["phi_deg"].stderr > 0 and np.isfinite(env.params["c_kPa"].ci95[0])
    # the lower bound uses that envelope: sigma3_cap = sigma3 + 2c'cos/(1+sin) - sigma1 (1-sin)/(1+sin) (eq. 27)
    sn = math.sin(math.radians(phi))
    s3, s1 = 50e3, 310e3
    lb = s3 + 2 * c * math.cos(math.radians(phi)) / (1 + sn) - s1 * (1 - sn) / (1 + sn)
    row = res.to_json()["tests"][0]
    assert_allclose(row["lower"]["sigma3_cap_kPa"], lb / 1e3, rtol=1e-9)


def test_no_saturated_test_and_one_suction_is_a_clear_error(write_csv):
    path = write_csv("test_id,condition,sigma3,q_f,s0\nu1,unsaturated,50,260,50\nu2,unsaturated,100,360,50\n")
    with pytest.raises(InputError, match="no saturated test.*--c-eff"):
        run_triaxial_bounds(path)
