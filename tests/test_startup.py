"""Start-up stays cheap (issue 31, item 5): `capred --help` and `capred COMMAND --help` import no numerical library,
the commands are built only when used (capred.cli.lazy_group) with help and errors the same as typer's own
group, and the snapshot of the input columns that help reads (capred/cli/help_columns.py) is current.

Not timed: what is imported and what is built are counted (benchmarks/bench_startup.py measures the time).
"""

import json
import os
import subprocess
import sys

import pytest
import typer.testing
from conftest import ROOT
from typer.testing import CliRunner

from capred.cli import app, help_columns
from capred.cli import help as cli_help
from capred.cli.lazy_group import LazyGroup, lazy_command
from capred.reductions import REDUCTIONS

HEAVY_ALL = ("numpy", "pandas", "matplotlib", "scipy", "rich", "jinja2", "pint")


def _typer_own() -> set[str]:
    """The heavy packages `import typer` loads by itself (typer before 0.20 imports rich): not capred's doing."""
    code = "import json, sys, typer; print(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return set(json.loads(p.stdout)) & set(HEAVY_ALL)


#: what capred's help must not import beyond typer itself
HEAVY = tuple(m for m in HEAVY_ALL if m not in _typer_own())

#: runs `capred ARGS` as the console script does and prints which heavy packages were imported
PROBE = """
import json, sys
sys.argv = ["capred"] + sys.argv[1:]
from capred.cli import main
try:
    main()
except SystemExit:
    pass
heavy = sorted({m.split(".")[0] for m in sys.modules} & set(json.loads(sys.stdin.read())))
print("HEAVY=" + json.dumps(heavy))
"""


def _heavy_imports(*args: str) -> list[str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.run(
        [sys.executable, "-c", PROBE, *args], input=json.dumps(HEAVY), capture_output=True, text=True, env=env
    )
    assert "HEAVY=" in p.stdout, p.stderr
    return json.loads(p.stdout.split("HEAVY=")[-1])


@pytest.mark.parametrize("args", [["--help"], ["shear", "--help"], ["bridge", "solve", "--help"], ["--version"]])
def test_help_imports_no_numerical_library(args):
    """Neither the command list nor a command's help (with its input columns) imports numpy, pandas, matplotlib,
    scipy, rich, jinja2 or pint: the columns come from the snapshot, the commands are built from typer alone."""
    assert _heavy_imports(*args) == []


def test_every_command_help_imports_no_numerical_library():
    """The same for the help of every other command (one process for all: `capred X --help` exits, so the probe
    runs them one after another in one interpreter)."""
    script = (
        "import json, sys\n"
        "from capred.cli import main\n"
        "names, heavy = json.loads(sys.argv[1]), set(json.loads(sys.argv[2]))\n"
        "for cmd in names:\n"
        "    sys.argv = ['capred', *cmd.split(), '--help']\n"
        "    try:\n"
        "        main()\n"
        "    except SystemExit:\n"
        "        pass\n"
        "print('HEAVY=' + json.dumps(sorted({m.split('.')[0] for m in sys.modules} & heavy)))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    names = [*REDUCTIONS, "batch", "bridge"]
    p = subprocess.run(
        [sys.executable, "-c", script, json.dumps(names), json.dumps(HEAVY)], capture_output=True, text=True, env=env
    )
    assert "HEAVY=" in p.stdout, p.stderr
    assert json.loads(p.stdout.split("HEAVY=")[-1]) == []
    assert p.stdout.count("Usage: capred") == len(names)  # every help was written


def _invoke(args, group=None):
    """typer's test runner on ``app`` with typer's own group, or with ``group`` (the lazy one) in its place."""
    if group is None:
        return CliRunner().invoke(app, args, prog_name="capred")
    saved = typer.testing._get_command  # the runner builds typer's group: give it the lazy one instead
    typer.testing._get_command = lambda _app: group
    try:
        return CliRunner().invoke(app, args, prog_name="capred")
    finally:
        typer.testing._get_command = saved


def _both(args):
    """(exit code, output) of ``args`` through typer's own group and through the lazy group."""
    full, lazy = _invoke(args), _invoke(args, lazy_command(app))
    return (full.exit_code, full.output), (lazy.exit_code, lazy.output)


@pytest.mark.parametrize(
    "args",
    [["--help"], [], ["bridge", "--help"], ["bridge"], ["nosuch"], ["shea"], ["bridge", "nosuch"], ["--version"]]
    + [[*name.split(), "--help"] for name in [*REDUCTIONS, "batch"]],
    ids=lambda a: " ".join(a) or "(none)",
)
def test_lazy_group_writes_what_typer_writes(args):
    """Help, usage errors and suggestions are the same, to the character, whether the commands are built at once
    (typer's group) or when used (the lazy group that `capred` runs)."""
    full, lazy = _both(args)
    assert lazy == full


def test_command_list_builds_no_command_and_a_command_builds_itself_alone():
    group = lazy_command(app)
    assert isinstance(group, LazyGroup)
    names = list(group.commands)
    assert set(group.builders) == set(names)  # nothing built yet
    result = _invoke(["--help"], group)
    assert result.exit_code == 0 and set(group.builders) == set(names)  # the list came from the stand-ins
    result = _invoke(["skempton-b", "--help"], group)
    assert result.exit_code == 0 and set(names) - set(group.builders) == {"skempton-b"}
    result = _invoke(["bridge", "solve", "--help"], group)
    assert result.exit_code == 0
    bridge = group.commands["bridge"]
    assert isinstance(bridge, LazyGroup) and set(bridge.commands) - set(bridge.builders) == {"solve"}


def test_a_command_runs_through_the_lazy_group(tmp_path):
    """`capred skempton-b --sample --json` through the lazy group prints the same JSON document as through
    typer's own group (B is a pure function of S_r: the same numbers to the digit)."""
    args = ["skempton-b", "--json", *REDUCTIONS["skempton-b"].example_args()[1:]]
    full, lazy = _both(args)
    assert full[0] == 0, full[1]
    assert lazy == full


def test_the_column_snapshot_is_current():
    """Every command that reads a file has its entry; each entry's digest is that of its source files as they
    are, and its lines are those of the schema. When this fails, rewrite the snapshot:
    python -c 'import capred.cli.help as h; h.write_snapshot()'"""
    readers = sorted(n for n, r in REDUCTIONS.items() if r.source != "none")
    assert sorted(help_columns.COLUMNS) == readers
    for name in readers:
        entry = help_columns.COLUMNS[name]
        assert cli_help.source_digest(entry["files"]) == entry["digest"], f"{name}: snapshot out of date"
        assert [list(x) for x in cli_help.column_lines(cli_help.schema_of(name))] == entry["lines"], name


def test_a_changed_source_file_makes_help_read_the_schema(monkeypatch):
    """Where the digest no longer matches (a source file of the schema changed), help imports the schema
    instead of showing the snapshot's (possibly stale) columns."""
    entry = dict(help_columns.COLUMNS["shear"], digest="0" * 40, lines=[["stale", "stale"]])
    monkeypatch.setitem(help_columns.COLUMNS, "shear", entry)
    lines = cli_help.column_help("shear")
    assert lines and ("stale", "stale") not in lines
    assert lines == cli_help.column_lines(cli_help.schema_of("shear"))


def test_digest_of_a_missing_file_is_none():
    assert cli_help.source_digest(["no_such_module.py"]) is None
