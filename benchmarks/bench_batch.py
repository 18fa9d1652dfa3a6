"""`capred batch MANIFEST` itself, timed as a whole process tree: CPU and wall, interleaved repeats.

What it claims (issue 20, item 3): 1,000 sample files through `capred batch`
with default options and --no-plots in <= 10 s of wall time on a 2-core
machine. On a machine other work is loading, wall time is not the machine's:
the benchmark measures CPU seconds of the whole tree (the batch and its
workers) and the wall time, and estimates the wall time of an idle machine as
CPU / min(cores, workers) plus the serial start-up.

Variants, each one manifest line over N copies of sample_data/shear_tests.csv,
run in turn (A B C D, A B C D, ...) so that a change of load hits each alike:

- ``default``:     --no-plots                       (the target's command)
- ``boot0``:       --no-plots --bootstrap 0          (the reduction without the bootstrap)
- ``boot0-nohtml``: --no-plots --bootstrap 0 --no-html (tables and JSON only)
- ``startup``:     one file, --no-plots --bootstrap 0 (the least a run costs)

Each variant is also run over one file: cpu(1) and cpu(N) give its fixed CPU (start-up and what its first file
loads) and its CPU per file, cpu(k) = fixed + k x per file; the idle wall time of 1,000 files is extrapolated as
fixed + 1,000 x per file / workers. With N = 1000 the measured wall time is printed beside it.
- ``every-output``: no option at all: every default output (tables, JSON, the report sheets as 300-dpi PNGs,
  report.html), the season of issue 31 (item 3: 1,000 files in <= 4 minutes of wall time on 2 cores; issue 44,
  item 3: <= 3 minutes)
- ``shear-glob``:  not a manifest: ``capred shear runs/*.csv --no-plots`` as a user types it (the shell's list of
  files, the CLI's default workers): issue 44, item 1 (1,000 files in <= 10 s of wall time on 2 cores)

``--only a,b`` runs those variants alone (``startup`` is always run: the fixed cost). ``--baseline COMMIT``
also runs each variant from that commit (a temporary git worktree on PYTHONPATH), interleaved with the
others: the before/after of a change in one session, under the same load.

Every run's CPU time (the whole process tree) and wall time are printed, with the CPU model and the load
average before and after: on a shared machine compare CPU (and the ratios to the baseline, taken under the same
load); the wall time of an idle machine is estimated from CPU as above.

Run: python benchmarks/bench_batch.py [n_files=200] [repeats=3] [--workers W] [--only every-output]
[--baseline COMMIT]
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

VARIANTS = {
    "default": "--no-plots",
    "boot0": "--no-plots --bootstrap 0",
    "boot0-nohtml": "--no-plots --bootstrap 0 --no-html",
    "every-output": "",
    "shear-glob": None,  # `capred shear FILES --no-plots`, no manifest
}
#: the claim each variant is held to: (seconds of wall time for 1,000 files on an idle machine, what it is)
CLAIMS = {
    "default": (10.0, "1,000 files with default options and --no-plots (issue 20)"),
    "every-output": (180.0, "1,000 files with every default output (issue 31: 240 s; issue 44: 180 s)"),
    "shear-glob": (10.0, "`capred shear 1000 files --no-plots` (issue 44)"),
}
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from common import installed_env, machine_line  # noqa: E402


def timed(args: list[str], env: dict | None = None, cwd: Path | None = None) -> tuple[float, float]:
    """(wall seconds, CPU seconds of the child and every process it waited for)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "capred", *args], capture_output=True, text=True, env=env, cwd=cwd)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"capred {' '.join(args)} failed:\n{proc.stderr[-2000:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def copies(folder: Path, n: int) -> Path:
    """A folder of ``n`` copies of the shear sample (made once)."""
    from capred.samples import sample_path

    runs = folder / f"runs_{n}"
    if not runs.exists():
        runs.mkdir(parents=True)
        src = sample_path("shear")
        for k in range(n):
            shutil.copy(src, runs / f"s{k:05d}.csv")
    return runs


def manifest(folder: Path, name: str, n: int, options: str | None) -> list[str]:
    """The arguments of a run over ``n`` copies of the shear sample (``--out`` is added by the caller): a
    manifest of one line with ``options``, or (``options`` None) ``capred shear FILES --no-plots`` with the
    files listed as a shell expands ``runs/*.csv``."""
    runs = copies(folder, n)
    if options is None:
        return ["shear", *(str(p) for p in sorted(runs.glob("*.csv"))), "--no-plots"]
    path = folder / f"{name}.csv"
    path.write_text(f"command,input,options\nshear,{runs}/*.csv,{options}\n")
    return ["batch", str(path)]


def fixed_cost(one: float, many: float, n: int) -> tuple[float, float]:
    """(fixed CPU s, CPU s per file) of a variant from its runs over one file (``one``) and ``n`` files
    (``many``): cpu(k) = fixed + k per_file. The fixed cost is the variant's own (what its first file loads:
    the bootstrap's and the report's code, not only the start-up of a bare run), so it is not spread over the
    files when the claim is extrapolated to 1,000 of them."""
    per_file = (many - one) / max(n - 1, 1)
    return one - per_file, per_file


def cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover
        return os.cpu_count() or 1


def cli_default_workers(n: int) -> int:
    """The worker count `capred batch` uses without --workers (its default: a number, or None for one per core)."""
    import inspect

    from capred.batch import default_workers
    from capred.cli import batch

    default = inspect.signature(batch).parameters["workers"].default
    return default_workers(n) if default is None else int(default)


def main(
    n: int = 200,
    repeats: int = 3,
    workers: int | None = None,
    only: list[str] | None = None,
    baseline: str | None = None,
) -> None:
    extra = ["--workers", str(workers)] if workers else []
    variants = {k: v for k, v in VARIANTS.items() if not only or k in only}
    if not variants:
        raise SystemExit(f"--only names none of {', '.join(VARIANTS)}")
    loads = []
    print(f"machine: {machine_line()}")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        plans = {name: manifest(tmp, name, n, opts) for name, opts in variants.items()}
        plans["startup"] = manifest(tmp, "startup", 1, VARIANTS["boot0"])
        for name, opts in variants.items():  # each variant over one file: its own fixed cost (`fixed_cost`)
            plans[f"{name}:1"] = manifest(tmp, f"{name}_1", 1, opts)
        envs = {name: None for name in plans}
        base = tmp / "baseline"
        if baseline:
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), baseline],
                check=True,
                capture_output=True,
            )
            env = {**installed_env(tmp / "pycache-base"), "PYTHONPATH": str(base)}
            for name in list(plans):
                plans[f"{name}@base"] = plans[name]
                envs[f"{name}@base"] = env
        mine = {**installed_env(tmp / "pycache"), "PYTHONPATH": str(ROOT)}
        times: dict[str, list[tuple[float, float]]] = {k: [] for k in plans}
        try:
            for r in range(repeats):  # interleaved: each variant once per round
                for name, path in plans.items():
                    # a new folder for every run, all removed at the end: ext4 scans its inode bitmaps for a while
                    # after many files are deleted (recently_deleted, find_inode_bit), which charged a run ~16 %
                    # more system time when the previous run's folder had just been removed
                    out = tmp / f"out_{name.replace('@', '_')}_{r}"
                    times[name].append(timed([*path, "--out", str(out), *extra], envs[name] or mine, tmp))
                    loads.append(os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan"))
        finally:
            if baseline:
                subprocess.run(
                    ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base)], capture_output=True
                )
    c = cores()
    w = min(c, workers or cli_default_workers(n), n)  # the processes that share the files
    med = {k: sorted(v)[len(v) // 2] for k, v in ((k, [x[0] for x in t]) for k, t in times.items())}
    cpu = {k: sorted(x[1] for x in t)[len(t) // 2] for k, t in times.items()}
    print(f"machine after: {machine_line()}")
    print(
        f"capred batch over {n} copies of the shear sample; {repeats} interleaved repeats (medians); "
        f"{c} cores, {w} workers ({'--workers' if workers else 'the CLI default'}); "
        f"load average (1 min) after each run {min(loads):.1f} to {max(loads):.1f}"
    )
    print(
        f"{'variant':20s} {'wall s':>8s} {'CPU s':>8s} {'CPU ms/file':>12s} {'fixed CPU s':>12s} "
        f"{'idle wall s':>12s} {'1000 files, idle wall s':>24s}"
    )
    for tag in ("", "@base") if baseline else ("",):
        for name in variants:
            key = name + tag
            fixed, per_file = fixed_cost(cpu[f"{name}:1{tag}"], cpu[key], n)
            idle = fixed + per_file * n / w  # start-up is serial; the files spread over the workers
            at_1000 = fixed + per_file * 1000 / w
            print(
                f"{key:20s} {med[key]:8.2f} {cpu[key]:8.2f} {per_file * 1e3:12.1f} {fixed:12.2f} {idle:12.2f} "
                f"{at_1000:24.1f}"
            )
        print(
            f"{'startup' + tag:20s} {med['startup' + tag]:8.2f} {cpu['startup' + tag]:8.2f}   (one file, "
            "--bootstrap 0: the least a run costs)"
        )
    for name in variants:
        if baseline:
            print(
                f"{name}: this tree / {baseline}: CPU {cpu[name] / cpu[name + '@base']:.2f}x, "
                f"wall {med[name] / med[name + '@base']:.2f}x"
            )
        if name in CLAIMS:
            limit, what = CLAIMS[name]
            fixed, per_file = fixed_cost(cpu[f"{name}:1"], cpu[name], n)
            target = fixed + per_file * 1000 / w
            print(
                f"claim: {what} in {target:.1f} s wall on an idle {c}-core machine, extrapolated from {n} files "
                f"(target <= {limit:.0f} s): {'met' if target <= limit else 'NOT met'}"
            )
            if n == 1000:
                print(
                    f"claim: {what}: measured {med[name]:.1f} s wall at load {min(loads):.1f}-{max(loads):.1f} "
                    f"(target <= {limit:.0f} s): {'met' if med[name] <= limit else 'NOT met'}"
                )


if __name__ == "__main__":
    argv = sys.argv[1:]
    flags: dict[str, str | None] = {"--workers": None, "--only": None, "--baseline": None}
    for flag in flags:
        if flag in argv:
            k = argv.index(flag)
            flags[flag] = argv[k + 1]
            del argv[k : k + 2]
    main(
        *(int(a) for a in argv[:2]),
        workers=int(flags["--workers"]) if flags["--workers"] else None,
        only=flags["--only"].split(",") if flags["--only"] else None,
        baseline=flags["--baseline"],
    )
