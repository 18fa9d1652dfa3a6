"""capred shear end to end: CliRunner, a real subprocess, and every bad input."""

import json
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import file_hash
from typer.testing import CliRunner

from capred.cli import app

runner = CliRunner()

GOOD = (
    "test_id,material,condition,z1,z2,V_v,added_mass,cap_mass,box_area,R,tau_max\n"
    "d1,sand,dry,,,30,0,120,36,0.156,0.30\n"
    "d2,sand,dry,,,30,200,120,36,0.156,0.75\n"
    "d3,sand,dry,,,30,400,120,36,0.156,1.15\n"
    "w1,sand,wet,20,1.5,30,0,120,36,0.156,2.5\n"
)


def test_shear_sample_writes_report_folder(tmp_path):
    out = tmp_path / "rep"
    res = runner.invoke(app, ["shear", "--sample", "--out", str(out)])
    assert res.exit_code == 0, res.output
    names = {p.name for p in out.iterdir()}
    assert {
        "results.csv",
        "summary.csv",
        "summary.json",
        "provenance.json",
        "report_steel_2mm.png",
        "report_sand_208-417um.png",
    } <= names
    assert "Dry envelope" in res.output and "best" in res.output
    prov = json.loads((out / "provenance.json").read_text())
    assert prov["inputs"][0]["sha256"] and prov["capred_version"]


def test_shear_json_has_the_documented_keys(tmp_path):
    res = runner.invoke(app, ["shear", "--sample", "--json", "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    js = json.loads(res.stdout)
    m = js["materials"]["steel_2mm"]
    assert set(m) >= {"c_kPa", "phi_deg", "tan_phi", "c_se_kPa", "phi_se_deg", "r2", "n"}
    t = js["tests"][0]
    assert set(t) >= {
        "test_id",
        "material",
        "condition",
        "sigma_N_kPa",
        "suction_kPa",
        "S_R",
        "tau_max_kPa",
        "tau_pred_kPa",
        "flags",
    }
    assert set(t["tau_pred_kPa"]) == {"no_suction", "bishop", "own1", "own2"}
    assert set(js["metrics"]["sand_208-417um"]["own2"]) >= {"rmse_kPa", "bias_kPa", "r2"}
    assert js["best_model"]["steel_2mm"] in {"no_suction", "bishop", "own1", "own2"}
    assert not list((tmp_path / "o").glob("*.png"))


@pytest.mark.slow
def test_shear_rerun_is_byte_identical(tmp_path, write_csv):
    data = write_csv(GOOD)
    for k in ("a", "b"):
        assert runner.invoke(app, ["shear", str(data), "--out", str(tmp_path / k)]).exit_code == 0
    for name in ("results.csv", "summary.csv", "summary.json", "report_sand.png"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name


@pytest.mark.slow
def test_shear_through_installed_entry_point(tmp_path):
    exe = Path(sys.executable).with_name("capred")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "capred"]
    res = subprocess.run(
        cmd + ["shear", "--sample", "--json", "--out", str(tmp_path / "o")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["best_model"]


def test_python_m_capred_help():
    res = subprocess.run([sys.executable, "-m", "capred", "--help"], capture_output=True, text=True, timeout=60)
    assert res.returncode == 0 and "shear" in res.stdout


def test_help_does_not_import_heavy_modules():
    code = (
        "import sys\nfrom typer.testing import CliRunner\nfrom capred.cli import app\n"
        "CliRunner().invoke(app, ['--help'])\nCliRunner().invoke(app, ['shear', '--help'])\n"
        "print(sorted(m for m in ('pandas', 'scipy', 'matplotlib', 'pint') if m in sys.modules))"
    )
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert res.stdout.strip() == "[]", res.stdout + res.stderr


def _commands(group, prefix=()):
    import typer.main

    click_group = typer.main.get_command(group)
    stack = [(prefix, click_group)]
    while stack:
        path, cmd = stack.pop()
        for name, sub in getattr(cmd, "commands", {}).items():
            yield (*path, name), sub
            stack.append(((*path, name), sub))


def test_every_command_has_help_text_with_example():
    cmds = list(_commands(app))
    assert cmds
    for path, cmd in cmds:
        assert cmd.help and len(cmd.help.strip()) > 20, path
        if not getattr(cmd, "commands", None):
            assert "Example" in cmd.help, path


HEADER = "test_id,material,condition,z1,z2,V_v,added_mass,cap_mass,box_area,R,tau_max\n"
BAD_CASES = {
    "misspelt_column": (
        "test_id,material,condition,z1,z2,V_v,added_mas,cap_mass,box_area,R,tau_max\n"
        "d1,s,dry,,,30,0,120,36,0.156,0.3\n",
        ["line 1", "added_mass", "did you mean 'added_mas'"],
    ),
    "text_in_number": (
        HEADER + "d1,s,dry,,,30,0,120,36,0.156,abc\n",
        ["line 2", "column 'tau_max'", "'abc' is not a number"],
    ),
    "empty_file": ("", ["empty"]),
    "header_only": (HEADER, ["no data rows"]),
    "no_dry_test": (HEADER + "w1,s,wet,20,1.5,30,0,120,36,0.156,2.5\n", ["line 2", "no dry test"]),
    "z2_exceeds_void_volume": (
        GOOD + "w2,sand,wet,20,31,30,0,120,36,0.156,2.5\n",
        ["line 6", "column 'z2'", "outside [0, 1]"],
    ),
    "S_R_above_one": (
        "test_id,condition,sigma_N,suction,S_R,tau_max\nd1,dry,1,,,1\nd2,dry,2,,,2\nd3,dry,3,,,3.1\nw1,wet,1,2,1.2,2\n",
        ["line 5", "column 'S_R'", "between 0 and 1"],
    ),
    "negative_mass": (HEADER + "d1,s,dry,,,30,-5,120,36,0.156,0.3\n", ["line 2", "column 'added_mass'", "negative"]),
    "negative_head": (GOOD + "w2,sand,wet,-20,1.5,30,0,120,36,0.156,2.5\n", ["line 6", "column 'z1'", "negative"]),
    "unknown_unit": (
        HEADER.replace("tau_max", "tau_max [blorps]") + "d1,s,dry,,,30,0,120,36,0.156,0.3\n",
        ["line 1", "column 'tau_max [blorps]'", "unknown unit 'blorps'"],
    ),
    "wrong_dimension": (
        HEADER.replace("z1,", "z1 [kPa],") + "d1,s,dry,,,30,0,120,36,0.156,0.3\n",
        ["line 1", "column 'z1 [kPa]'", "not a unit of length"],
    ),
    "duplicate_test_id": (
        GOOD + "d2,sand,dry,,,30,600,120,36,0.156,1.6\n",
        ["line 6", "duplicate test_id 'd2'", "first on line 3"],
    ),
    "unknown_condition": (GOOD.replace("w1,sand,wet", "w1,sand,moist"), ["line 5", "'moist' is not one of"]),
    "hook_case": ("test_id,z1\nA,not-a-number\n", ["'not-a-number' is not a number"]),
}


@pytest.mark.parametrize("case", sorted(BAD_CASES))
def test_shear_bad_input_clean_error(case, tmp_path, write_csv):
    text, expected = BAD_CASES[case]
    data = write_csv(text, "bad.csv")
    before = file_hash(data)
    out = tmp_path / "out"
    res = runner.invoke(app, ["shear", str(data), "--out", str(out)])
    assert res.exit_code == 1
    assert res.exception is None or isinstance(res.exception, SystemExit)
    err = res.stderr
    assert err.startswith("Error:") and "bad.csv" in err and "Traceback" not in err
    for piece in expected:
        assert piece in err, (piece, err)
    assert not out.exists()
    assert file_hash(data) == before


def test_shear_collects_all_problems_in_a_file(write_csv):
    data = write_csv(HEADER + "d1,s,dry,,,30,-5,120,36,0.156,x\nd1,s,dry,,,30,0,120,36,0.156,0.3\n", "bad.csv")
    res = runner.invoke(app, ["shear", str(data)])
    assert res.exit_code == 1
    assert "problems in the input" in res.stderr
    assert "'x' is not a number" in res.stderr and "must not be negative" in res.stderr


def test_shear_bad_option_unit():
    res = runner.invoke(app, ["shear", "--sample", "--box-area", "36 kPa"])
    assert res.exit_code == 1 and "--box-area" in res.stderr and "not a unit of area" in res.stderr


def test_shear_missing_file():
    res = runner.invoke(app, ["shear", "nope.csv"])
    assert res.exit_code == 1 and "nope.csv: file not found" in res.stderr


def test_shear_requires_R_only_for_the_models_that_read_it(tmp_path, write_csv):
    """Issue 41.5: wet tests without R run with models that do not use it (Bishop, Own 1); Own 2 and the exact
    bridge still need it, and the message names them."""
    no_r = GOOD.replace(",R,", ",").replace(",0.156,", ",")
    data = write_csv(no_r, "nor.csv")
    ok = runner.invoke(app, ["shear", str(data), "--models", "bishop,own1", "--out", str(tmp_path / "a"), "--json"])
    assert ok.exit_code == 0, ok.stderr
    assert json.loads(ok.stdout)["metrics"]["sand"]["bishop"]["n"] == 1
    bad = runner.invoke(app, ["shear", str(data), "--models", "bishop,own2,exact_neck", "--out", str(tmp_path / "b")])
    assert bad.exit_code == 1 and "needed by Own 2, Exact bridge" in bad.stderr and "line 5" in bad.stderr
    assert not (tmp_path / "b").exists()
