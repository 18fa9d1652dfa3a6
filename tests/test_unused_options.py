"""An option that fills a column's blank cells changes nothing when every row has its own value: capred says so
(console, JSON warnings, Python warnings) instead of listing it silently among the options in force."""

import json

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.errors import CapredWarning
from capred.pipelines.shear import model_params_from_retention


def test_box_area_given_where_every_row_has_its_own_is_said_unused(tmp_path):
    out = tmp_path / "o"
    res = CliRunner().invoke(app, ["shear", "--sample", "--box-area", "50", "--out", str(out), "--no-plots"])
    assert res.exit_code == 0, res.output
    said = "box_area (--box-area) is not used: every row gives its own 'box_area'"
    assert said in " ".join(res.output.split())
    assert any(said in w for w in json.loads((out / "summary.json").read_text())["warnings"])
    with pytest.warns(CapredWarning, match="is not used"):
        capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(box_area="50 cm^2", bootstrap=0))


def test_a_blank_cell_filled_by_the_option_is_no_warning(tmp_path):
    rows = capred.sample_path("shear").read_text(encoding="utf-8").splitlines()
    header = [h.strip() for h in rows[[i for i, r in enumerate(rows) if not r.startswith("#")][0]].split(",")]
    col = next(i for i, h in enumerate(header) if h.split(" [")[0] == "box_area")
    first = [i for i, r in enumerate(rows) if not r.startswith("#")][0]
    cells = rows[first + 1].split(",")
    cells[col] = ""  # one blank: the option fills it
    rows[first + 1] = ",".join(cells)
    f = tmp_path / "one_blank.csv"
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    r = capred.run_shear(f, capred.ShearOptions(box_area="36 cm^2", bootstrap=0))
    assert not any("is not used" in w for w in r.warnings)


def test_retention_whose_parameters_no_model_takes_says_what_it_is_used_for(tmp_path):
    fits = tmp_path / "r"
    res = CliRunner().invoke(app, ["retention", "--sample", "--out", str(fits), "--no-plots", "--no-html"])
    assert res.exit_code == 0, res.output
    said = "no model compared takes its parameters"
    # the default models (thesis set) take no retention parameters: the file only gives the figures' S_R(s)
    params = model_params_from_retention(fits / "fits.json")
    r = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, model_params=params))
    assert any(said in n for n in r.options.notes)
    # vanapalli takes van Genuchten's parameters from it: nothing to say
    r = capred.run_shear(
        capred.sample_path("shear"),
        capred.ShearOptions(bootstrap=0, model_params=params, models="bishop,vanapalli"),
    )
    assert not any(said in n for n in r.options.notes)
