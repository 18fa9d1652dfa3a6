"""Run one data command on one file, or many files (optionally in worker processes).

A job is (command, input path, output folder, keyword arguments of the
pipeline, plots). Running it never raises for bad input: the outcome carries
the message, so one bad file never costs the others.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import CapredError


def _shear(source, out_dir, plots, options, command_options):
    from .shear import run_shear, write_shear_outputs

    r = run_shear(source, options)
    return r, write_shear_outputs(r, out_dir, plots=plots, command_options=command_options)


def _triaxial(source, out_dir, plots, options, curves=None, command_options=None):
    from .triaxial import run_triaxial_bounds, write_triaxial_outputs

    r = run_triaxial_bounds(source, options, curves=curves)
    inputs = [source] + ([curves] if curves else [])
    return r, write_triaxial_outputs(r, out_dir, plots=plots, inputs=inputs, command_options=command_options)


def _retention(source, out_dir, plots, options, command_options):
    from .retention import run_retention, write_retention_outputs

    r = run_retention(source, options)
    return r, write_retention_outputs(r, out_dir, plots=plots, command_options=command_options)


RUNNERS = {"shear": _shear, "triaxial-bounds": _triaxial, "retention": _retention}


@dataclass
class Job:
    command: str
    source: Path
    out_dir: Path
    kwargs: dict = field(default_factory=dict)
    plots: bool = True
    keep_json: bool = False


@dataclass
class Outcome:
    command: str
    source: str
    out_dir: str
    ok: bool
    message: str = ""
    outputs: list[str] = field(default_factory=list)
    seconds: float = 0.0
    result_json: dict | None = None


def run(job: Job):
    """(result, written files) of one job; raises CapredError on bad input."""
    return RUNNERS[job.command](job.source, job.out_dir, job.plots, **job.kwargs)


def run_safely(job: Job) -> Outcome:
    """Outcome of one job; a CapredError becomes a failed outcome with its message."""
    t0 = time.perf_counter()
    try:
        result, written = run(job)
    except CapredError as exc:
        return Outcome(job.command, str(job.source), str(job.out_dir), False, str(exc),
                       seconds=time.perf_counter() - t0)
    return Outcome(job.command, str(job.source), str(job.out_dir), True, "", [str(p) for p in written],
                   time.perf_counter() - t0, result.to_json() if job.keep_json else None)


def run_all(jobs: list[Job], workers: int = 1, on_done=None) -> list[Outcome]:
    """Run every job (in ``workers`` processes when > 1), in input order; ``on_done(outcome)`` after each."""
    outcomes: list[Outcome] = []
    if workers <= 1 or len(jobs) <= 1:
        for job in jobs:
            outcomes.append(run_safely(job))
            if on_done:
                on_done(outcomes[-1])
        return outcomes
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=workers) as pool:
        for outcome in pool.map(run_safely, jobs, chunksize=max(1, min(16, len(jobs) // (4 * workers)))):
            outcomes.append(outcome)
            if on_done:
                on_done(outcome)
    return outcomes


def output_dirs(commands: list[str], sources: list[Path], root: Path) -> list[Path]:
    """One folder per input under ``root``: <command>_<stem>, made unique with parent names if needed."""
    prefixes = [c.split("-")[0] for c in commands]
    names = [f"{prefix}_{p.stem}" for prefix, p in zip(prefixes, sources)]
    for i, p in enumerate(sources):
        if names.count(names[i]) > 1:
            names[i] = f"{prefixes[i]}_{p.parent.name}_{p.stem}"
    seen: dict[str, int] = {}
    out = []
    for n in names:
        k = seen.get(n, 0)
        seen[n] = k + 1
        out.append(root / (n if k == 0 else f"{n}_{k + 1}"))
    return out


def write_index(root: Path, outcomes: list[Outcome]) -> Path:
    """index.csv: every input with its outcome and every output file written."""
    import csv
    import io

    from ..io.writers import write_text

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["command", "input", "status", "message", "output"])
    for o in outcomes:
        if o.ok:
            for f in o.outputs:
                w.writerow([o.command, o.source, "ok", "", f])
        else:
            w.writerow([o.command, o.source, "failed", o.message.replace("\n", " | "), ""])
    return write_text(root / "index.csv", buf.getvalue())
