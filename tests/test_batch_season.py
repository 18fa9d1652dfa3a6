"""A season's files (issues 29.3, 28.4, 32.5): season.csv one row per run with what every command shares,
each command's details in season_<command>.csv and a section of season.html, `name [unit]` headers, paths
relative to the batch root, every batch file listed in index.csv and protected by its recorded hash."""

import json
import re
import shutil
from pathlib import Path

import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app

runner = CliRunner()
#: a CSV header of a number: `name [unit]` ([-] for a dimensionless number or a count)
UNIT_HEADER = re.compile(r"^\S+ \[[^\]]+\]$")


@pytest.fixture(scope="module")
def season(tmp_path_factory):
    """A batch of a good and a bad shear file and the retention sample, run once for the module."""
    tmp = tmp_path_factory.mktemp("season")
    runs = tmp / "runs"
    runs.mkdir()
    shutil.copy(capred.sample_path("shear"), runs / "good.csv")
    (runs / "bad.csv").write_text("test_id,material\nT1,sand\n")  # no condition, no tau_max: a failed run
    (tmp / "col").mkdir()
    shutil.copy(capred.sample_path("retention"), tmp / "col" / "column.csv")
    manifest = tmp / "m.csv"
    manifest.write_text(
        "command,input,options\nshear,runs/*.csv,--no-plots --bootstrap 0\nretention,col/column.csv,--no-plots\n"
    )
    out = tmp / "out"
    res = runner.invoke(app, ["batch", str(manifest), "--out", str(out)])
    assert res.exit_code == 1  # one file failed
    return out, manifest, res


def _csv(path: Path) -> pd.DataFrame:
    return pd.read_csv(path, dtype=str, keep_default_na=False)


def test_a_failed_file_shows_its_reason_in_season_csv(season):
    out, _, _ = season
    table = _csv(out / "season.csv")
    bad = table[table["input"] == "../runs/bad.csv"].iloc[0]
    assert bad["status"] == "failed"
    assert "missing column 'condition'" in bad["reason"] and "\n" not in bad["reason"]
    good = table[table["input"] == "../runs/good.csv"].iloc[0]
    assert good["status"] == "ok" and good["reason"] == ""


def test_season_csv_is_one_row_per_run_with_labels_not_ids(season):
    out, _, _ = season
    table = _csv(out / "season.csv")
    assert len(table) == 3  # three runs, whatever their materials or branches
    assert list(table.columns[:6]) == ["command", "input", "status", "reason", "material", "headline"]
    good = table[table["input"] == "../runs/good.csv"].iloc[0]
    assert good["material"] == "steel_2mm; sand_208-417um"
    # the headline quotes the run's own dry envelope of steel (4 significant digits) and the best model's label
    steel = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)).fits["steel_2mm"].params
    c, phi = steel["c_kPa"].value, steel["phi_deg"].value
    assert f"steel_2mm: c {c:.4g} kPa, phi {phi:.4g} deg, best model: Own 2" in good["headline"]
    retention = table[table["command"] == "retention"].iloc[0]
    assert "best model: van Genuchten" in retention["headline"] and "vg" not in retention["headline"].split()
    for text in table["headline"]:
        assert not re.search(r"\b(own1|own2|vg|bc|vg_m_free)\b", text)


def test_each_command_has_its_details_file_and_section(season):
    out, _, _ = season
    shear = _csv(out / "season_shear.csv")
    assert set(shear["material"]) == {"steel_2mm", "sand_208-417um"} and set(shear["best_model"]) == {"Own 2"}
    assert set(shear["input"]) == {"../runs/good.csv"}  # the failed file has no details
    retention = _csv(out / "season_retention.csv")
    assert list(retention["branch"]) == ["drying", "wetting"]
    page = (out / "season.html").read_text(encoding="utf-8")
    assert 'id="season-shear"' in page and 'id="season-retention"' in page
    assert "missing column &#39;condition&#39;" in page  # the reason on the page too


def test_every_csv_header_of_the_batch_root_has_a_unit_or_is_text(season):
    out, _, _ = season
    text_columns = {"command", "input", "status", "reason", "material", "headline", "options", "report", "branch"}
    text_columns |= {"best_model", "message", "output"}
    for path in sorted(out.glob("*.csv")):
        for head in _csv(path).columns:
            assert head in text_columns or UNIT_HEADER.match(head), (path.name, head)


def test_paths_are_relative_to_the_batch_root(season):
    out, _, _ = season
    for name in ("season.csv", "index.csv"):
        table = _csv(out / name)
        for value in table["input"]:
            assert not value or (not Path(value).is_absolute() and (out / value).resolve().is_file()), value
    index = _csv(out / "index.csv")
    for value in index["output"]:
        assert not value or (not Path(value).is_absolute() and (out / value).exists()), value


def test_index_lists_every_batch_file_and_provenance_protects_them(season):
    out, _, _ = season
    index = _csv(out / "index.csv")
    listed = set(index.loc[index["command"] == "batch", "output"])
    root_files = {p.name for p in out.iterdir() if p.is_file()}
    assert root_files == listed  # every file of the root, in one place
    prov = json.loads((out / "provenance.json").read_text())
    assert set(prov["batch_files"]) == root_files - {"provenance.json"}


@pytest.mark.parametrize("name", ["index.csv", "season_shear.csv", "season.csv"])
def test_an_edited_batch_file_is_refused_not_replaced(season, name, tmp_path):
    out, manifest, _ = season
    copy = tmp_path / "out"
    shutil.copytree(out, copy)
    edited = (copy / name).read_text() + "my note\n"  # a user's edit of a file capred wrote
    (copy / name).write_text(edited)
    res = runner.invoke(app, ["batch", str(manifest), "--out", str(copy)])
    assert res.exit_code == 1 and name in res.stderr and "Traceback" not in res.output
    assert (copy / name).read_text() == edited


def test_season_page_prints_every_column_on_a4_landscape():
    """A command whose details are wider than A4 landscape: split into column groups that each fit the
    printable 277 mm (7 pt text), the input repeated in each; every column in exactly one group."""
    from capred.batch import season_columns
    from capred.report import html

    rows = [{"input": "runs/a.csv", "material": "sand", **{f"p{k} [kPa]": 1234.5678 + k for k in range(40)}}]
    table = season_columns(rows)
    names = list(table)
    cells = html._season_cells(table, names)
    groups = html._season_groups(names, cells)
    assert len(groups) > 1
    for g in groups:
        assert g[:2] == [0, 1]
        width = sum(
            max([len(w) for w in names[j].split()] + [len(x) for x in cells[j]]) * html.SEASON_CHAR_MM + html.CELL_MM
            for j in g
        )
        assert width <= html.SEASON_WIDTH_MM
    assert sorted(j for g in groups for j in g[2:]) == list(range(2, len(names)))
    page = html.render_season(season_columns([{"command": "shear", "input": "a", "status": "ok"}]), {"shear": table})
    assert page.count("<table>") == 1 + len(groups)
    assert "size: A4 landscape" in page and "max-width: 1240px" in page
