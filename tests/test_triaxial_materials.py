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
