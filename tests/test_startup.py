"""Start-up stays cheap (issue 31, item 5): `capred --help` and `capred COMMAND --help` import no numerical library,
the commands are built only when used (capred.cli.lazy_group) with help and errors the same as typer's own
group, and a command's help is read from the declarations themselves (capred.spec) at run time, so that a model
a script registers shows in it.

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

from capred.cli import app
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
    scipy, rich, jinja2 or pint: the columns and options come from capred.spec, the commands from typer alone."""
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


def test_help_columns_are_the_schema_the_command_reads():
    """Every command that reads a table shows the columns of the very schema its pipeline reads with (the
    pipeline module re-exports the spec's list: one declaration)."""
    from importlib import import_module

    for name, red in REDUCTIONS.items():
        schema = cli_help.schema_of(name)
        if red.source == "none":
            assert schema == []
            continue
        pipeline = import_module(red.run_path.split(":")[0])
        last = name.split()[-1].replace("-", "_").upper()
        own = getattr(pipeline, f"{last}_SCHEMA", None) or getattr(pipeline, "SCHEMA", None) or []
        assert schema is own or schema == own == [], name
        assert cli_help.column_help(name) == cli_help.column_lines(schema)


#: a lab script: registers its own effective-stress model, then runs `capred shear --help` in the same process
REGISTERING_SCRIPT = """
import json, sys
import capred.spec.effective_stress as es
es.REGISTRY["half_bishop"] = es.EffectiveStressModel(
    "half_bishop", "Half Bishop", (), "bishop1959", lambda d: d.sigma_N + 0.5 * d.S_R * d.suction
)
sys.argv = ["capred", "shear", "--help"]
from capred.cli import main
try:
    main()
except SystemExit:
    pass
print("HEAVY=" + json.dumps(sorted({m.split(".")[0] for m in sys.modules} & set(json.loads(sys.argv_heavy)))))
"""


def test_a_model_registered_by_a_script_shows_in_shear_help_without_numpy():
    """Issue 42: the README's `half_bishop`, registered from a script, is listed by `capred shear --help`, which
    still imports no numerical library (the registry's declaration is numpy-free)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    script = REGISTERING_SCRIPT.replace("sys.argv_heavy", repr(json.dumps(HEAVY)))
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env)
    assert "HEAVY=" in p.stdout, p.stderr
    text = " ".join(p.stdout.split())
    assert "own2, vanapalli" in text and ", half_bishop;" in text  # in the --models list, in registry order
    assert json.loads(p.stdout.split("HEAVY=")[-1]) == []


def test_the_command_list_reads_no_options_declaration():
    """`capred --help` lists the commands without evaluating any command's options: the option annotations are
    evaluated when typer builds the command asked for (capred.cli.common._Callback), so no capred.spec module
    is imported for the list."""
    code = (
        "import io, json, sys, contextlib\n"
        "sys.argv = ['capred', '--help']\n"
        "from capred.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n        main()\n    except SystemExit:\n        pass\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith('capred.spec'))))"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    assert json.loads(p.stdout) == []
