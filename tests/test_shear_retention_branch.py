"""`shear --retention FIT.json` (issue 34.1): which branch, which conversion, and why a model cannot run.

A fits.json of `capred retention` holds a fit per branch (drying, wetting); the χ laws take van Genuchten
(Lu & Likos 2006; S_res for Vanapalli et al. 1996) or Brooks-Corey's air entry (Khalili & Khabbaz 1998). The
parameters come from the chosen branch; another model is converted as `capred retention-convert` does.
"""

import json

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import OptionError
from capred.pipelines.shear import model_params_from_retention

runner = CliRunner()


@pytest.fixture(scope="module")
def kosugi_fits(tmp_path_factory):
    out = tmp_path_factory.mktemp("r")
    res = runner.invoke(app, ["retention", "--sample", "--model", "kosugi", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    return out / "fits.json"


@pytest.mark.parametrize("branch", ["drying", "wetting"])
def test_parameters_are_those_retention_convert_gives_for_the_branch(kosugi_fits, branch):
    """The same least squares as retention-convert on the same fit: the same α, n, m, S_res and s_e (to the last
    digit: one computation), and the note names the branch and the misfit."""
    mp = model_params_from_retention(kosugi_fits, branch)
    vg = capred.convert_retention(kosugi_fits, to="vg", branch=branch).converted.params
    bc = capred.convert_retention(kosugi_fits, to="bc", branch=branch).converted.params
    assert mp.vg_alpha == pytest.approx(vg["alpha_per_kPa"].value / 1e3, rel=1e-12)
    assert mp.vg_n == pytest.approx(vg["n"].value, rel=1e-12)
    assert mp.s_res == pytest.approx(vg["S_res"].value, rel=1e-12)
    assert mp.air_entry == pytest.approx(bc["s_e_kPa"].value * 1e3, rel=1e-12)
    texts = [t for _, t, _ in mp.retention_notes]
    assert any(f"kosugi fit of branch '{branch}' converted to van Genuchten" in t and "RMSE" in t for t in texts)
    # the drying and wetting curves differ (hysteresis: the wetting curve lies at lower suctions), so do α
    other = model_params_from_retention(kosugi_fits, "wetting" if branch == "drying" else "drying")
    assert other.vg_alpha != pytest.approx(mp.vg_alpha, rel=0.05)


def test_default_branch_is_drying_and_options_win(kosugi_fits):
    mp = model_params_from_retention(kosugi_fits, vg_n=3.0)
    assert mp.vg_n == 3.0  # the option wins over the converted value
    assert mp.vg_alpha == pytest.approx(model_params_from_retention(kosugi_fits, "drying").vg_alpha, rel=1e-12)
    assert "branch 'drying' used (the default)" in mp.retention_notes[0][1]
    with pytest.raises(OptionError, match="has no branch 'scanning'"):
        model_params_from_retention(kosugi_fits, "scanning")


def test_a_fit_that_cannot_be_converted_says_why_the_model_is_refused(kosugi_fits, tmp_path):
    """A fits.json of an older capred has no suction range: a conversion cannot be made (it holds only over the
    data's suctions). Before, shear said 'needs --vg-alpha (or --retention FIT.json ...)' to a user who gave one."""
    doc = json.loads(kosugi_fits.read_text(encoding="utf-8"))
    for fits in [doc["fits"], *(b["fits"] for b in doc["branches"].values())]:
        for f in fits.values():
            f.pop("suction_range_kPa", None)
            f.pop("suction_points_kPa", None)
    old = tmp_path / "old_fits.json"
    old.write_text(json.dumps(doc), encoding="utf-8")
    res = runner.invoke(
        app,
        ["shear", "--sample", "--models", "lu_likos", "--retention", str(old), "--bootstrap", "0", "--no-plots"]
        + ["--out", str(tmp_path / "o")],
    )
    assert res.exit_code != 0 and "Traceback" not in res.output
    assert "needs --vg-alpha and --vg-n" in res.output and "could not be converted" in res.output, res.output
    assert "suction range" in res.output, res.output
