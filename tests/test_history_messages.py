"""What `capred history` and `--store` tell a user: why a chart has no runs, lists that are cut, a run recorded
before, and a run that writes no files (so is not recorded)."""

import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app

runner = CliRunner()
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")
QUICK = ["--no-plots", "--no-html"]


def _ok(args):
    res = runner.invoke(app, [str(a) for a in args])
    assert res.exit_code == 0, res.output
    return res


def test_of_command_without_the_material_names_what_its_runs_hold(tmp_path):
    store = tmp_path / "S.db"
    _ok(["shear", "--sample", "--bootstrap", "0", *QUICK, "--store", store, "--out", tmp_path / "o1"])
    _ok(["triaxial-bounds", "--sample", *QUICK, "--store", store, "--out", tmp_path / "o2"])
    res = runner.invoke(
        app,
        ["history", str(store), "--quantity", "c_kPa", "--material", "steel_2mm", "--of-command", "triaxial-bounds"],
    )
    assert res.exit_code == 1
    err = res.stderr
    # the sample's triaxial-bounds runs record c_kPa without a material; its shear runs name two materials
    assert "no `triaxial-bounds` run records 'c_kPa' of material 'steel_2mm'" in err
    assert "the `triaxial-bounds` runs record it only without a material (leave out --material" in err
    assert "the whole store holds the materials: sand_208-417um, steel_2mm" in err
    assert "it holds: \n" not in err and "it holds: " not in err  # no empty list any more
    res = runner.invoke(app, ["history", str(store), "--quantity", "c_kPa", "--of-command", "retention"])
    assert res.exit_code == 1
    assert "no `retention` run is recorded in this store; it holds runs of: shear, triaxial-bounds" in res.stderr
    res = runner.invoke(app, ["history", str(store), "--quantity", "tan_phi", "--of-command", "triaxial-bounds"])
    assert res.exit_code == 1 and "no `triaxial-bounds` run records quantity 'tan_phi'" in res.stderr
    assert "the whole store holds: " in res.stderr and "tan_phi" in res.stderr.split("the whole store holds: ")[1]


def test_long_lists_are_counted_with_the_way_to_list_them_all(tmp_path):
    n = 33  # materials: 30 are named, the 3 others counted
    rows = ["test_id,material,condition,V_v [cm^3],added_mass [g],cap_mass [g],box_area [cm^2],tau_max [kPa]"]
    for k in range(n):
        for i, (m, tau) in enumerate(((0.0, 0.25), (200.0, 0.6), (400.0, 0.95))):
            rows.append(f"T{k:02d}{i},mat{k:02d},dry,30.5,{m},120.0,36.0,{tau + 0.001 * k:.4f}")
    (tmp_path / "many.csv").write_text("\n".join(rows) + "\n")
    store = tmp_path / "S.db"
    _ok(["shear", tmp_path / "many.csv", "--bootstrap", "0", *QUICK, "--store", store, "--out", tmp_path / "o"])
    res = runner.invoke(app, ["history", str(store), "--quantity", "phi_deg"])
    assert res.exit_code == 1
    err = res.stderr.replace("\n", "")
    assert "--material is needed" in err and "mat29" in err and "mat30" not in err
    assert "and 3 more (list them all: python -c " in err
    # the command it names lists all 33
    cmd = err.split("list them all: python -c ")[1].rsplit(")", 1)[0]
    out = subprocess.run([sys.executable, "-c", cmd.strip('"')], capture_output=True, text=True, check=True).stdout
    assert out.split() == [f"mat{k:02d}" for k in range(n)]


def test_a_run_recorded_before_is_said_so(tmp_path):
    store = tmp_path / "S.db"
    _ok(["retention", "--sample", *QUICK, "--store", store, "--out", tmp_path / "o1"])
    res = _ok(["retention", "--sample", *QUICK, "--store", store, "--out", tmp_path / "o2", "--json"])
    note = f"already recorded in {store} as run 1 (same inputs and options); not recorded again"
    assert any(note in x for x in json.loads(res.stdout)["notes"])
    # the run's own document (retention: fits.json) carries the note too
    assert any(note in x for x in json.loads((tmp_path / "o2" / "fits.json").read_text())["notes"])
    res = _ok(["retention", "--sample", *QUICK, "--store", store, "--out", tmp_path / "o3"])
    assert f"note: {note}" in res.stdout
    assert capred.history(store)["run"].nunique() == 1


def test_a_run_that_writes_no_files_says_it_is_not_recorded(tmp_path):
    store = tmp_path / "P.db"
    args = ["prism", "--break-tension", "115 g/cm^2", "--friction-angle", "36", "--store", store]
    res = _ok(args)
    assert "this run was not recorded in the store: --store" in res.stdout
    assert "`capred prism` writes them only with --out (it prints by default); give --out FOLDER" in res.stdout
    assert not store.exists()
    res = _ok([*args, "--json"])
    assert any("was not recorded in the store" in w for w in json.loads(res.stdout)["warnings"])
    # with --out the run is recorded, and nothing is said about it
    res = _ok([*args, "--out", tmp_path / "o"])
    assert "not recorded" not in res.stdout and capred.history(store)["run"].nunique() == 1
    # a command that writes files by default, with --json and no --out
    res = _ok(["shear", "--sample", "--bootstrap", "0", "--json", "--store", tmp_path / "S.db"])
    assert any("with --json and no --out it writes none" in w for w in json.loads(res.stdout)["warnings"])
    assert not (tmp_path / "S.db").exists()
