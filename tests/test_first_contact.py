"""First contact (issue 29.9): the README explains the sample's warning, git ignores the README's report folder,
the test run stays short, and `--help` groups the options and lists the input columns of every command."""

import re
import tomllib

import pytest
from conftest import ROOT
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.cli.help import INPUT_FILE_SECTION, INPUT_PANEL, OUTPUT_PANEL, input_description, schema_of
from capred.reductions import REDUCTIONS

README = (ROOT / "README.md").read_text(encoding="utf-8")
runner = CliRunner()


def test_readme_explains_the_sample_warning_in_its_first_lines():
    """The sample's first run warns that most wet tests lie outside the pendular regime: the README says what
    that means right under the setup commands (its first 20 lines), where a new user looks."""
    doc = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)).to_json()
    assert any("pendular regime" in w for w in doc["warnings"])  # the warning the sentence explains
    head = "\n".join(README.splitlines()[:20])
    assert "pendular regime" in head and "metrics_pendular" in head


def test_gitignore_covers_the_readme_report_folder():
    folder = re.search(r"--out (\S+)", README.splitlines()[3]).group(1)  # the first setup command
    ignored = (ROOT / ".gitignore").read_text(encoding="utf-8").split()
    assert f"{folder.rstrip('/')}/" in ignored


def test_expected_warnings_are_filtered_in_the_pytest_configuration():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["pytest"]["ini_options"]
    assert "ignore::capred.errors.CapredWarning" in config["filterwarnings"]


def test_capred_warnings_are_still_seen_by_pytest_warns():
    """The filter hides the summary lines only: a test that expects a warning still gets it."""
    with pytest.warns(capred.CapredWarning, match="pendular"):
        capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))


@pytest.mark.parametrize("command", sorted(REDUCTIONS))
def test_help_groups_options_and_lists_input_columns(command):
    res = runner.invoke(app, [*command.split(), "--help"], terminal_width=100)
    assert res.exit_code == 0, res.output
    text = res.stdout
    sections = re.findall(r"^(\S[^\n]*):$", text, flags=re.M)
    assert {f"{command.split()[-1]} options", OUTPUT_PANEL} <= set(sections), sections
    assert "Options" not in sections  # no ungrouped remainder
    schema = schema_of(command)
    described = input_description(command)  # an input that is not a table (a fits.json, a lab store)
    if REDUCTIONS[command].source == "required":
        assert schema or described, f"{command}: no input columns found, nor a description of its input"
    if described and not schema:  # said in the columns' place, whole (click wraps it: compare word by word)
        assert INPUT_FILE_SECTION in sections, sections
        assert " ".join(described.split()) in " ".join(text.split()), command
    if REDUCTIONS[command].source != "none":
        assert INPUT_PANEL in sections
    for column in schema:  # each column with its unit, as the glossary of the schema says
        unit = f" [{column.unit}]" if column.unit and column.unit != "-" else ""
        assert re.search(rf"^\s+{re.escape(column.name + unit)}\s", text, flags=re.M), (command, column.name)
