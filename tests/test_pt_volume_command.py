"""`capred pt-volume` end to end: files written, values equal to the physics, the limits S_r = 1 and 0, errors.

Reference values are the model's closed forms at points where they hold exactly
(both parts on their ncl at the first point; a saturated path on the slurry
ncl/url; a dry path on the dry-powder lines), worked from Pedrotti &
Tarantino (submitted), eq. 1-2, 5, 6-7 and 10; the rest is compared with
capred.physics.pedrotti_tarantino.simulate_volume_path called directly.
"""

import json
from math import log

import pandas as pd
import pytest
from numpy.testing import assert_allclose
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import OptionError
from capred.physics import pedrotti_tarantino as pt
from capred.pipelines.pt_volume import PTVolumeOptions, run_pt_volume

runner = CliRunner()
KPA = 1e3
KAOLIN = pt.EXAMPLE_KAOLIN
# round lines for hand arithmetic (as in test_pedrotti_tarantino): slurry lambda 0.2, kappa 0.02, e = 2.0 at
# 1 kPa; dry powder lambda 0.1, kappa 0.01, e = 1.8 at 1 kPa
HAND = [
    "--lambda-w",
    "0.2",
    "--kappa-w",
    "0.02",
    "--e-ncl-w",
    "2.0",
    "--lambda-a",
    "0.1",
    "--kappa-a",
    "0.01",
    "--e-ncl-a",
    "1.8",
]
HAND_P = pt.PTVolumeParameters(lambda_W=0.2, kappa_W=0.02, e_ncl_W=2.0, lambda_A=0.1, kappa_A=0.01, e_ncl_A=1.8)


def _sample_arrays():
    d = pd.read_csv(capred.sample_path("pt-volume"), comment="#")
    return (
        d["sigma [kPa]"].to_numpy() * KPA,
        d["u_w [kPa]"].to_numpy() * KPA,
        d["u_a [kPa]"].to_numpy() * KPA,
        d["S_r"].to_numpy(),
    )


def _json(args):
    res = runner.invoke(app, ["pt-volume", *args, "--json", "--no-plots"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_pt_volume_sample_writes_files_equal_to_the_physics(tmp_path):
    out = tmp_path / "o"
    res = runner.invoke(app, ["pt-volume", "--sample", "--out", str(out)])
    assert res.exit_code == 0, res.output
    names = {p.name for p in out.iterdir()}
    assert {"results.csv", "results.json", "stages.csv", "pt_volume.png", "provenance.json", "report.html"} <= names
    assert (out / "pt_volume.png").stat().st_size > 10_000  # the sheet of three panels was drawn
    # --sample alone runs with EXAMPLE_KAOLIN and says that the lines are illustrative
    assert "EXAMPLE_KAOLIN" in res.output and "illustrative" in res.output
    assert "Stages" in res.output and "Path points" in res.output

    ref = pt.simulate_volume_path(*_sample_arrays(), params=KAOLIN)
    t = pd.read_csv(out / "results.csv")
    assert len(t) == 21
    # the CSV keeps every digit (shortest round-trip repr), so the kPa values differ from Pa/1000 by rounding only
    for col, attr, scale in (
        ("sigma_W [kPa]", "sigma_W", 1e-3),
        ("sigma_A [kPa]", "sigma_A", 1e-3),
        ("e [-]", "e", 1.0),
        ("e_W [-]", "e_W", 1.0),
        ("e_A [-]", "e_A", 1.0),
        ("de_WW [-]", "de_WW", 1.0),
        ("de_AA [-]", "de_AA", 1.0),
        ("de_AW [-]", "de_AW", 1.0),
        ("de_WA [-]", "de_WA", 1.0),
        ("w_AW [-]", "w_AW", 1.0),
        ("w_WA [-]", "w_WA", 1.0),
        ("sigma_star_W [kPa]", "sigma_star_W", 1e-3),
        ("ncl_fraction_W [-]", "ncl_fraction_W", 1.0),
        ("solid_fraction_W [-]", "solid_fraction_W", 1.0),
    ):
        # atol 1e-15: the increments de are differences of void ratios near 1, where numpy's libm differs by a
        # few ulps between releases (3e-13 relative to an increment of 3e-4 with numpy 2.0, the floor)
        assert_allclose(
            t[col].to_numpy(float), getattr(ref, attr) * scale, rtol=1e-14, atol=1e-15, equal_nan=True, err_msg=col
        )
    for flag in ("loading_W", "loading_A", "yielding_W", "yielding_A"):
        assert t[flag].tolist() == getattr(ref, flag).tolist()
    # the sample's file lines: 5 comment lines, the header on line 6, points from line 7
    assert t["line"].tolist() == list(range(7, 28))
    assert t["stage"].tolist()[:2] == ["A", "A-B"] and t["stage"].iloc[-1] == "D"
    # wetting B-C moves air-saturated pores into the water-saturated part, unloading A-B the reverse (Fig. 14-15)
    assert set(t["fluid_change"].iloc[8:15]) == {"air_to_water"}
    assert set(t["fluid_change"].iloc[1:8]) == {"water_to_air"}
    stages = pd.read_csv(out / "stages.csv")
    assert stages["stage"].tolist() == ["A", "A-B", "B", "B-C", "C", "C-D", "D"]
    # the changes over the runs add up to the change over the path (exact up to float round-off)
    assert_allclose(stages["de [-]"].sum(), ref.e[-1] - ref.e[0], rtol=0, atol=1e-14)


def test_pt_volume_sample_json_equals_api_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    doc = _json(["--sample"])
    api = run_pt_volume(capred.sample_path("pt-volume"), PTVolumeOptions(example_kaolin=True))
    assert doc == api.to_json()
    assert list(tmp_path.iterdir()) == []  # --json without --out writes no file


def test_pt_volume_first_point_by_hand_and_json_equals_api(tmp_path):
    path = capred.sample_path("pt-volume")
    doc = _json([str(path), *HAND])
    api = run_pt_volume(
        str(path), PTVolumeOptions(lambda_W=0.2, kappa_W=0.02, e_ncl_W=2.0, lambda_A=0.1, kappa_A=0.01, e_ncl_A=1.8)
    )
    assert doc == api.to_json()
    assert doc["command"] == "pt-volume" and doc["parameters"]["illustrative"] == []
    assert not any("EXAMPLE_KAOLIN" in w for w in doc["warnings"])
    p0 = doc["points"][0]
    # eq. 1-2 at point A: sigma'_W = (339 + 800) 0.55 = 626.45 kPa, sigma'_A = 339 (1 - 0.55) = 152.55 kPa
    assert_allclose([p0["sigma_W_kPa"], p0["sigma_A_kPa"]], [626.45, 152.55], rtol=1e-14)
    # both parts on their ncl (eq. 10 integrated), coupled by eq. 5: e = eW eA / (eW (1 - S_r) + eA S_r)
    eW, eA = 2.0 - 0.2 * log(626.45), 1.8 - 0.1 * log(152.55)
    assert_allclose([p0["e_W"], p0["e_A"]], [eW, eA], rtol=1e-13)  # log() of a kPa value vs Pa/1 kPa: round-off
    assert_allclose(p0["e"], eW * eA / (eW * 0.45 + eA * 0.55), rtol=1e-13)
    assert p0["yielding_W"] and p0["yielding_A"] and p0["step"] == 0 and p0["stage"] == "A" and p0["line"] == 7
    # the whole path equals the physics function's
    ref = pt.simulate_volume_path(*_sample_arrays(), params=HAND_P)
    assert_allclose([r["e"] for r in doc["points"]], ref.e, rtol=1e-15)
    assert doc["substeps"] == ref.substeps.tolist()


def test_pt_volume_saturated_limit_follows_slurry_lines(write_csv):
    # S_r = 1, u_w = u_a = 0: sigma'_W = sigma (Terzaghi), the A part is empty, e = e^W (eq. 5 at S_r = 1)
    data = write_csv(
        "step,stage,sigma [MPa],u_w,u_a,S_r\n0,A,0.1,0,0,1\n1,load,0.2,0,0,1\n2,load,0.4,0,0,1\n3,unload,0.2,0,0,1\n"
    )
    doc = _json([str(data), *HAND])
    e = [r["e"] for r in doc["points"]]
    # ncl e = 2.0 - 0.2 ln(sigma'/1 kPa) up to 400 kPa, then the url: + kappa_W ln(400/200) (eq. 7)
    expected = [2.0 - 0.2 * log(100), 2.0 - 0.2 * log(200), 2.0 - 0.2 * log(400), 2.0 - 0.2 * log(400) + 0.02 * log(2)]
    assert_allclose(e, expected, rtol=1e-13)  # closed forms; log round-off only
    assert_allclose([r["e_W"] for r in doc["points"]], expected, rtol=1e-13)
    assert all(r["e_A"] is None for r in doc["points"])  # no air-saturated part
    assert [s["stage"] for s in doc["stages"]] == ["A", "load", "unload"]


def test_pt_volume_dry_limit_follows_dry_powder_lines_with_suction_column(write_csv):
    # S_r = 0 and no u_a column (atmospheric air, said in a note); suction instead of u_w
    data = write_csv("sigma,suction,S_r\n50,10000,0\n100,10000,0\n25,10000,0\n")
    doc = _json([str(data), *HAND])
    expected = [1.8 - 0.1 * log(50), 1.8 - 0.1 * log(100), 1.8 - 0.1 * log(100) + 0.01 * log(4)]  # eq. 10, eq. 6
    assert_allclose([r["e"] for r in doc["points"]], expected, rtol=1e-13)
    assert_allclose([r["u_w_kPa"] for r in doc["points"]], [-10000.0] * 3, rtol=0)  # u_w = u_a - suction
    assert any("u_a = 0" in n for n in doc["notes"])
    assert [r["step"] for r in doc["points"]] == [0, 1, 2]  # no step column: numbered from 0


def test_pt_volume_initial_yield_and_substeps_reach_the_physics():
    path = str(capred.sample_path("pt-volume"))
    doc = _json([path, *HAND, "--initial-yield-w", "1000", "--substeps", "1"])
    p0 = doc["points"][0]
    # over-consolidated W part: url through the yield point at 1000 kPa,
    # e = 2.0 - 0.2 ln 1000 - 0.02 ln(626.45/1000) (eq. 7 below the ncl)
    assert_allclose(p0["e_W"], 2.0 - 0.2 * log(1000) - 0.02 * log(626.45 / 1000), rtol=1e-13)
    assert p0["ncl_fraction_W"] == 0.0 and not p0["yielding_W"]
    ref = pt.simulate_volume_path(*_sample_arrays(), params=HAND_P, initial_yield_W=1000 * KPA, substeps=1)
    assert_allclose([r["e"] for r in doc["points"]], ref.e, rtol=1e-15)
    assert doc["substeps"] == [1] * 20


def test_pt_volume_example_kaolin_with_one_line_overridden():
    doc = _json([str(capred.sample_path("pt-volume")), "--example-kaolin", "--lambda-w", "0.2"])
    assert doc["parameters"]["lambda_W"] == 0.2 and doc["parameters"]["kappa_W"] == KAOLIN.kappa_W
    assert "lambda_W" not in doc["parameters"]["illustrative"]
    assert any("EXAMPLE_KAOLIN" in w and "illustrative" in w for w in doc["warnings"])


def test_pt_volume_bad_rows_are_clean_errors_with_their_line(write_csv):
    # comment on line 1, header on line 2: the third point is on line 5
    data = write_csv("# my path\nsigma,u_w,u_a,S_r\n100,-50,0,0.6\n120,-50,0,0.6\n140,-50,0,1.2\n")
    res = runner.invoke(app, ["pt-volume", str(data), *HAND, "--no-plots", "--out", str(data.parent / "o")])
    assert res.exit_code == 1
    assert "Traceback" not in res.output
    assert "line 5, column 'S_r'" in res.stderr and "between 0 and 1" in res.stderr
    assert not (data.parent / "o").exists()  # nothing half-written
    # sigma - u_a <= 0 where the air-saturated part exists: sigma'_A would not be positive (eq. 2)
    data = write_csv("sigma,u_w,u_a,S_r\n100,-50,0,0.6\n100,-50,120,0.6\n", "air.csv")
    res = runner.invoke(app, ["pt-volume", str(data), *HAND, "--json"])
    assert res.exit_code == 1
    errors = json.loads(res.stdout)["errors"]
    assert [(e["line"], e["column"]) for e in errors] == [(3, "u_a")]
    assert "sigma - u_a must be > 0" in errors[0]["message"]
    # a blank cell and a missing column
    data = write_csv("sigma,u_w,S_r\n100,,0.6\n", "blank.csv")
    res = runner.invoke(app, ["pt-volume", str(data), *HAND, "--json"])
    assert res.exit_code == 1 and json.loads(res.stdout)["errors"][0]["line"] == 2
    data = write_csv("sigma,u_w,Sat\n100,-50,0.6\n", "nosr.csv")
    res = runner.invoke(app, ["pt-volume", str(data), *HAND, "--no-plots", "--out", str(data.parent / "o2")])
    assert res.exit_code == 1 and "missing column 'S_r'" in res.stderr


def test_pt_volume_missing_or_bad_lines_are_clean_errors(tmp_path):
    path = str(capred.sample_path("pt-volume"))
    res = runner.invoke(app, ["pt-volume", path, "--lambda-w", "0.18", "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "Traceback" not in res.output
    for option in ("--kappa-w", "--e-ncl-w", "--lambda-a", "--kappa-a", "--e-ncl-a", "--example-kaolin"):
        assert option in res.stderr
    assert "--lambda-w," not in res.stderr  # the one given is not listed as missing
    assert not (tmp_path / "o").exists()
    # kappa must lie below lambda (the url is flatter than the ncl)
    bad = [*HAND[:2], "--kappa-w", "0.3", *HAND[4:]]
    res = runner.invoke(app, ["pt-volume", path, *bad, "--json"])
    assert res.exit_code == 1 and "kappa_W must lie in (0, lambda_W)" in res.stderr
    with pytest.raises(OptionError, match="--kappa-a"):
        run_pt_volume(path, PTVolumeOptions(lambda_W=0.2, kappa_W=0.02, e_ncl_W=2.0, lambda_A=0.1, e_ncl_A=1.8))
    with pytest.raises(OptionError, match="substeps"):
        PTVolumeOptions(example_kaolin=True, substeps=0)
