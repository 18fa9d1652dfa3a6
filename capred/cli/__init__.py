"""Command-line interface: thin commands over capred's reductions.

Only typer is imported at start-up; a command imports its pipeline when it
runs, so `capred --help` and `capred COMMAND --help` stay fast.
"""

from pathlib import Path
from typing import Annotated

import typer

from ..errors import CapredError
from . import (
    bridge_commands,
    calculator_commands,
    compression_command,
    data_commands,
    pt_volume_command,
    retention_convert_command,
    triaxial_strength_command,
)
from .common import BUILDERS, JsonOpt, WorkersOpt, fail, physics_refusal, run_batch
from .generated import register_generated
from .help import HelpGroup

app = typer.Typer(
    name="capred",
    help="Capillary effective stress and strength from unsaturated-soil lab tests.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # plain help text: rendering help through rich would double `capred --help` start-up time
    rich_markup_mode=None,
    cls=HelpGroup,  # help wrapped between words, never at a hyphen
)


def _version(value: bool):
    if value:
        from .. import __version__

        typer.echo(f"capred {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Show the version and exit.")
    ] = False,
):
    """The capred command line: unsaturated-soil lab readings to effective stresses, strength and figures.

    capred turns raw unsaturated-soil lab readings into effective stresses, strength parameters, model comparisons and
    report figures.
    """


data_commands.register(app)
bridge_commands.register(app)
calculator_commands.register(app)
pt_volume_command.register(app)
compression_command.register(app)
retention_convert_command.register(app)
triaxial_strength_command.register(app)
# every other registered command: a CLI built from its Options (capred/cli/generated.py)
register_generated(app, BUILDERS)


@app.command(short_help="A season's runs from a CSV or TOML manifest.")
def batch(
    manifest: Annotated[
        Path,
        typer.Argument(
            help="CSV (command,input,options) or TOML ([[run]] command, input, options) listing the runs.",
            show_default=False,
        ),
    ],
    out: Annotated[Path | None, typer.Option("--out", "-o", help="Root output folder [default: ./capred_out].")] = None,
    json_out: JsonOpt = False,
    workers: WorkersOpt = None,
    store: Annotated[
        Path | None,
        typer.Option("--store", help="Record every run in this lab store (SQLite; see `capred history`)."),
    ] = None,
):
    """Run a season's worth of reductions listed in a manifest.

    One line per run, with the command (shear, triaxial-bounds, retention, prism, skempton-b, rumpf, bridge solve,
    bridge compare), the input file or glob, and that command's options as on the command line. Every file gets its own
    folder under --out; bad files are reported and the others still complete; index.csv lists every output; the exit
    code is 1 if anything failed.

    Example: capred batch season.csv --out results   (season.csv: command,input,options /
    shear,runs/*.csv,--gamma-w 10 --no-plots)

    \f

    Parameters
    ----------
    manifest : Path
        CSV (command,input,options) or TOML ([[run]]) listing the runs.
    out : Path, optional
        Root output folder (default ./capred_out).
    json_out : bool, optional
        Print one JSON document on stdout instead of tables.
    workers : int, optional
        Worker processes (default: one per core, at most one per file).
    store : Path, optional
        Lab store (SQLite) that records every run.
    """
    try:
        jobs = _manifest_jobs(manifest, out, json_out)
    except CapredError as exc:
        fail(exc)
    if store is not None:  # a line's own --store wins
        import dataclasses

        from .common import OutputOptions

        for job in jobs:
            o = job.output or OutputOptions()
            job.output = o if o.store is not None else dataclasses.replace(o, store=str(store))
    root = (out or Path.cwd() / "capred_out") if (out is not None or not json_out) else None
    try:
        run_batch(jobs, root, json_out, workers, extra_inputs=[manifest])
    except CapredError as exc:
        fail(exc)


from .help import group_help  # noqa: E402 - after every command is registered

group_help(app)


def _manifest_jobs(manifest: Path, out, json_out: bool):
    """Jobs of every manifest line, each line parsed exactly as the command line would parse it."""
    import shlex

    import typer.main

    from .. import batch as batch_mod
    from ..errors import InputError, Problem
    from ..io import read_manifest
    from ..reductions import REDUCTIONS
    from .common import file_command_lines

    group = typer.main.get_command(app)
    problems: list = []
    invocations = []
    runnable = [c for c in BUILDERS if REDUCTIONS[c].source != "none"]  # the commands that read files
    for line, command, pattern, options in read_manifest(manifest):
        cmd = _subcommand(group, command) if command in runnable else None
        if cmd is None:
            problems.append(Problem(str(manifest), line, "command", f"'{command}' is not one of {', '.join(runnable)}"))
            continue
        target = pattern if Path(pattern).is_absolute() else str(manifest.parent / pattern)
        try:
            argv = [target, *(shlex.split(options) if isinstance(options, str) else options)]
        except ValueError as exc:  # unbalanced quotes in the options
            problems.append(Problem(str(manifest), line, "options", str(exc)))
            continue
        try:
            typed = ["capred", *command.split(), *argv]  # before click consumes argv
            ctx = cmd.make_context(command, argv)
            invocations.append((BUILDERS[command](**ctx.params), cmd, typed))
        except CapredError as exc:
            problems.append(Problem(str(manifest), line, None, str(exc)))
        except Exception as exc:  # usage errors: bad option names or values in the manifest
            if isinstance(exc, ValueError) and physics_refusal(exc) is not None:  # a value the physics refuses
                problems.append(Problem(str(manifest), line, None, str(exc)))
                continue
            if type(exc).__module__.split(".")[0] not in ("click", "typer"):
                raise
            message = exc.format_message() if hasattr(exc, "format_message") else str(exc)
            problems.append(Problem(str(manifest), line, "options", message))
    if problems:
        raise InputError(problems)
    write = out is not None or not json_out
    root = out or Path.cwd() / "capred_out"
    flat = [(inv, src) for inv, _, _ in invocations for src in inv.sources]
    dirs = batch_mod.output_dirs([inv.command for inv, _ in flat], [src for _, src in flat], root)
    lines, k = [], 0  # each file's own command line (provenance.json, report.html): its line's options
    for inv, cmd, argv in invocations:
        n = len(inv.sources)
        lines += file_command_lines(inv.command, inv.sources, dirs[k : k + n] if write else [None] * n, argv, cmd)
        k += n
    return [
        batch_mod.Job(
            inv.command,
            src,
            d if write else None,
            inv.options,
            inv.plots,
            keep_json=json_out,
            output=inv.output,
            command_line=line,
        )
        for (inv, src), d, line in zip(flat, dirs, lines)
    ]


def _subcommand(group, name: str):
    cmd = group
    for part in name.split():
        cmd = getattr(cmd, "commands", {}).get(part)
        if cmd is None:
            return None
    return cmd


def _fast_help() -> None:
    """Let `capred COMMAND --help` skip building typer's value adapters (and importing pydantic).

    Typer >= 0.2x coerces every parameter through a pydantic adapter, also the
    unset `--help` flag of the parent command; a bool flag that is unset is
    simply False. If typer's internals differ, nothing is changed.
    """
    try:
        from typer.core import _TyperParameter
    except ImportError:  # pragma: no cover - other typer versions
        return
    original = getattr(_TyperParameter, "process_value", None)
    if original is None or getattr(original, "_capred", False):
        return

    def process_value(self, ctx, value):
        desc = getattr(self, "type_descriptor", None)
        if value is None and not self.default and desc is not None and getattr(desc, "annotation", None) is bool:
            value = False
        return original(self, ctx, value)

    process_value._capred = True
    _TyperParameter.process_value = process_value


def main() -> None:
    """The console entry point `capred`: OpenBLAS on one thread unless the user chose, then the application."""
    import os

    # OpenBLAS on one thread unless the user chose: capred's matrix products are small (a bootstrap's counts times
    # sums), and OpenBLAS's spinning threads only cost CPU on them (~0.3 s of the README's first command, with
    # no wall time saved); capred runs its own work on both cores where it pays (figures, batches, bridges)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    _fast_help()
    from .lazy_group import lazy_command

    # the commands are built when used: `capred --help` builds none, `capred shear ...` builds shear alone
    lazy_command(app)(prog_name="capred")


__all__ = ["app", "main"]
