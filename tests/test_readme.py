"""The README is a landing page whose commands and Python example run as written (issues 6 and 43).

It starts with the two set-up commands; every ``capred`` line of its bash blocks runs through the real entry
point; its Python example runs and writes a report; the values printed beside the calculator examples are what
the commands compute; and it stays a landing page: at most 250 lines, linking into the documentation.
"""

import re
import shlex
import shutil

import pytest
from conftest import ROOT
from typer.testing import CliRunner

import capred
from capred.cli import app

README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"```(\w+)\n(.*?)```", README, flags=re.S)
SETUP = [
    "python3 -m venv .venv && .venv/bin/pip install . && .venv/bin/capred shear --sample --out capred-report",
    'python3 -m venv .venv && .venv/bin/pip install ".[test]" && .venv/bin/python -m pytest -q',
]


def _capred_lines():
    for lang, body in BLOCKS:
        if lang != "bash":
            continue
        for line in body.splitlines():
            line = line.split("  #")[0].strip()
            if "capred " in line:
                yield line[line.index("capred ") + len("capred ") :]


@pytest.fixture
def lab(tmp_path, monkeypatch):
    """A folder holding the files the README's examples name."""
    for name, sample in (("tests.csv", "shear"), ("triaxial.csv", "triaxial-bounds"), ("column.csv", "retention")):
        shutil.copy(capred.sample_path(sample), tmp_path / name)
    for folder, sample, name in (
        ("runs", "shear", "sand_1.csv"),
        ("triaxial", "triaxial-bounds", "gavet.csv"),
        ("column", "retention", "c1.csv"),
    ):
        (tmp_path / folder).mkdir()
        shutil.copy(capred.sample_path(sample), tmp_path / folder / name)
    manifests = [body for lang, body in BLOCKS if lang == "text" and body.startswith("command,input,options")]
    if manifests:
        (tmp_path / "season.csv").write_text(manifests[0])
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_readme_has_the_two_setup_commands_first():
    # exactly the two commands of every earlier README: they must keep working on a fresh machine
    first = BLOCKS[0][1].strip().splitlines()
    assert first == SETUP
    assert README.index("```bash") < README.index("\n## ")


def test_readme_is_a_landing_page():
    lines = README.splitlines()
    assert len(lines) <= 250
    assert sum(line.startswith("![") for line in lines) == 1  # one figure
    figure = re.search(r"!\[[^]]*\]\(([^)]+)\)", README).group(1)
    assert (ROOT / figure).is_file()
    # the command table names every command
    from capred.reductions import REDUCTIONS

    table = "\n".join(line for line in lines if line.startswith("| `capred "))
    for name in REDUCTIONS:
        first_word = name.split()[0]
        assert f"capred {first_word}" in table or f"`{first_word}`" in table, name


def test_readme_links_resolve():
    for target in re.findall(r"\]\(([^)#]+)\)", README):
        if "://" in target:
            continue
        assert (ROOT / target).exists(), target


@pytest.mark.parametrize("line", list(_capred_lines()))
def test_readme_command_runs(line, lab):
    res = CliRunner().invoke(app, shlex.split(line))
    assert res.exit_code == 0, (line, res.output)


def test_readme_python_example_runs(lab):
    code = next(body for lang, body in BLOCKS if lang == "python")
    exec(compile(code, "README.md", "exec"), {})
    assert (lab / "report" / "results.csv").exists()


EXAMPLES = re.findall(r"^capred (.+?)\s+# \{([^}]*)\}: ([0-9.]+)", README, flags=re.M)


def test_readme_has_example_values():
    assert len(EXAMPLES) >= 3


@pytest.mark.parametrize("args,keys,value", EXAMPLES)
def test_readme_example_values_hold(args, keys, value, lab):
    """The values the README prints beside its examples, to the digits it prints them."""
    import json

    res = CliRunner().invoke(app, [*shlex.split(args), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    key = keys.split(",")[-1].strip()
    decimals = len(value.split(".")[1]) if "." in value else 0
    # printed value = computed value rounded to the printed digits: half a unit of the last digit
    assert doc[key] == pytest.approx(float(value), abs=0.5 * 10**-decimals + 1e-12)
