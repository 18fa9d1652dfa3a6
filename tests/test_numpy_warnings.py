"""Numpy RuntimeWarnings never reach the console (issue 39, part 7): every command's sample, and the edge inputs
that leaked one, run with RuntimeWarning turned into an error (``python -W error::RuntimeWarning`` as a user's
console would show them). Where a leak was found its source now computes the right limit; the values are checked
against the closed form."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.physics import calculators as calc
from capred.physics import retention as rp
from capred.reductions import REDUCTIONS

runner = CliRunner()
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

#: what a command needs beyond --sample to run
EXTRA = {"retention-convert": ["--to", "bc"], "history": ["--quantity", "phi_deg"]}
SAMPLED = [name for name, r in REDUCTIONS.items() if r.sample]


def _run(args, tmp_path):
    res = runner.invoke(app, [*args, "--no-plots", "--json", "--out", str(tmp_path / "out")])
    if res.exception is not None and not isinstance(res.exception, SystemExit):
        raise res.exception  # a RuntimeWarning turned error surfaces here with its traceback
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


@pytest.mark.parametrize("command", SAMPLED)
def test_every_sample_runs_without_a_runtime_warning(command, tmp_path):
    _run([*command.split(), "--sample", *EXTRA.get(command, [])], tmp_path)


def test_bridge_curve_runs_without_a_runtime_warning(tmp_path):
    _run(["bridge", "curve", "--points", "200"], tmp_path)


def test_skempton_b_of_zero_b_and_zero_saturation(tmp_path):
    # B = 0 lies below any B of these parameters (the dry soil's is > 0): no S_r, said in a note (was 1/0)
    doc = _run(["skempton-b", "--b", "0"], tmp_path)
    assert any("below what these parameters give for dry soil" in n for n in doc["notes"])
    # S_r = 0 under suction equilibrium: s S_r = s_e S_r^(1 - 1/lambda) -> inf for lambda < 1, so B -> 0 (was
    # inf * 0 = NaN with a warning)
    doc = _run(["skempton-b", "--sr", "0", "--se", "20", "--bc-lambda", "0.8"], tmp_path)
    assert json.dumps(doc).count('"B": 0.0') >= 1
    # the limits, from the closed form (Morvan et al. 2016, eq. 10-13): lambda = 1 gives s S_r = s_e exactly
    B = calc.skempton_b_suction(0.0, 100e3, 30e3, 0.8, 0.006, 130e3, 20e3, 1.0)
    assert B == pytest.approx(calc.skempton_b(0.0, 100e3 - 30e3 + 20e3, 0.8, 0.006, 130e3), rel=1e-15)
    assert calc.skempton_b_suction(0.0, 100e3, 30e3, 0.8, 0.006, 130e3, 20e3, 0.8) == 0.0
    assert calc.skempton_b_suction(0.0, 100e3, 30e3, 0.8, 0.006, 130e3, 20e3, 1.5) == pytest.approx(
        calc.skempton_b(0.0, 70e3, 0.8, 0.006, 130e3), rel=1e-15
    )
    assert calc.saturation_from_b(0.0, 70e3, 0.8, 0.006, 130e3) == -np.inf


def test_shear_bootstrap_replicate_without_suction(tmp_path):
    # four wet tests, two of them without suction: some bootstrap replicates draw no test with s > 0, whose
    # Khalili refit has no bounds (it was log(-inf))
    data = tmp_path / "shear.csv"
    data.write_text(
        "test_id,material,condition,sigma_N,tau_max,z1,z2,V_v,R\n"
        "t1,s,dry,10,5,,,,1\nt2,s,dry,20,10,,,,1\nt3,s,dry,30,15.2,,,,1\n"
        "w1,s,wet,10,6,10,10,10,1\nw2,s,wet,10,6,50,0,10,1\nw3,s,wet,20,11,0,5,10,1\nw4,s,wet,20,11,30,9.999,10,1\n"
    )
    doc = _run(["shear", str(data), "--models", "all"], tmp_path)
    assert "s" in doc["materials"]


def test_van_genuchten_and_fredlund_xing_beyond_the_float_range():
    # (alpha s)^n overflows: S_e = (alpha s)^(-n m) to 1e-308 relative; before, inf gave S_e = 0 (wrong for small m)
    assert rp.vg_effective_saturation(1e200, 1.0, 2.0, 0.001) == pytest.approx(1e200 ** (-0.002), rel=1e-12)
    se = rp.vg_effective_saturation(np.array([0.0, 1.0, 1e200]), 1.0, 2.0)
    assert se[:2] == pytest.approx([1.0, 2**-0.5], rel=1e-15) and se[2] == pytest.approx(1e-200, rel=1e-12)
    # Fredlund & Xing: ln(e + (s/a)^n) = n ln(s/a) once (s/a)^n overflows
    assert rp.fx_shape(1e200, 1.0, 2.0, 1.0) == pytest.approx(1 / (2 * np.log(1e200)), rel=1e-12)
    assert rp.fx_shape(np.array([0.0, 2.0]), 1.0, 2.0, 1.0) == pytest.approx([1.0, 1 / np.log(np.e + 4.0)], rel=1e-15)


def test_retention_fit_whose_search_overflows(tmp_path):
    # the RETC loam points: the durner search visits (alpha s)^n beyond the float range (was an overflow warning)
    from pathlib import Path

    src = Path(__file__).parent / "data" / "retention" / "swrc_retc_loam_synthetic.csv"
    doc = _run(["retention", str(src), "--model", "vg,durner"], tmp_path)
    assert doc["fits"]
