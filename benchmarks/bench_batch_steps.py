"""Where a sample-sized shear file's CPU goes in a batch without figures: each step's CPU per file, in one process.

`bench_batch.py` times whole batches (the process tree, start-up and workers included); this one runs N copies
of the shear sample through the batch's own job runner (`capred.batch.run_safely`, the default options,
``--no-plots``) in one warm process, one after the other, and charges each step's CPU time (user and system)
to it: the reduction (`run_shear`) and its bootstrap, dry fits, predictions and scores; the outputs
(`write_outputs`) and their report.html, per-row table, summary.json and CSV files. The first file is run
before timing (what it loads on first use is the start-up, not a file's cost).

With ``--baseline COMMIT`` the same is run from that commit (a temporary git worktree on PYTHONPATH), the two
alternating, ``repeats`` times each; each step's figure is the least over the repeats (on a shared machine
other work only adds time), with the ratio this tree / baseline. Every run writes into a new folder: removing
many files just before a run charges it the file system's clean-up (see bench_batch.py).

Run: python benchmarks/bench_batch_steps.py [n_files=100] [repeats=3] [--baseline COMMIT]
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from common import installed_env, machine_line  # noqa: E402

#: the steps timed: (module, function) — each charged its CPU time, calls within it included
STEPS = [
    ("capred.pipelines.shear", "run_shear"),
    ("capred.pipelines.shear", "bootstrap_materials"),
    ("capred.pipelines.shear", "fit_dry_envelopes"),
    ("capred.pipelines.shear", "predict_models"),
    ("capred.pipelines.shear", "score_models"),
    ("capred.report.outputs", "write_outputs"),
    ("capred.report.html", "render_html"),
    ("capred.report.html", "_per_row"),
    ("capred.io.writers", "stream_json"),
    ("capred.io.writers", "write_csv_file"),
]


def child(n: int, folder: str) -> None:
    """Run in a fresh process: time the steps over ``n`` files, print one JSON line {step: ms per file}."""
    import importlib
    import shutil
    import time
    from collections import defaultdict

    acc: dict[str, float] = defaultdict(float)

    def wrap(modname: str, fname: str) -> None:
        mod = importlib.import_module(modname)
        f = getattr(mod, fname, None)
        if f is None:  # a step another version does not have
            return

        def timed(*a, **k):
            t = time.process_time()
            try:
                return f(*a, **k)
            finally:
                acc[fname] += time.process_time() - t

        setattr(mod, fname, timed)

    for modname, fname in STEPS:
        wrap(modname, fname)
    from capred import batch
    from capred.cli.common import OutputOptions
    from capred.pipelines.shear import ShearOptions
    from capred.samples import sample_path

    src = Path(folder) / "in"
    src.mkdir()
    runs = []
    for k in range(n + 1):
        runs.append(src / f"s{k:05d}.csv")
        shutil.copy(sample_path("shear"), runs[-1])
    out = Path(folder) / "out"
    dirs = batch.output_dirs(["shear"] * len(runs), runs, out)
    out.mkdir()
    jobs = [batch.Job("shear", s, d, ShearOptions(), False, output=OutputOptions()) for s, d in zip(runs, dirs)]
    batch._warm(jobs)
    with batch.single_threaded_blas():  # as a batch runs
        first = batch.run_safely(jobs[0])
        assert first.ok, first.message
        acc.clear()
        t0 = time.process_time()
        for job in jobs[1:]:
            outcome = batch.run_safely(job)
            assert outcome.ok, outcome.message
        total = time.process_time() - t0
    print(json.dumps({"whole file": total / n * 1e3, **{k: v / n * 1e3 for k, v in acc.items()}}))


def run_child(n: int, pythonpath: Path, env_base: dict) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        proc = subprocess.run(
            [sys.executable, __file__, "--child", str(n), tmp],
            capture_output=True,
            text=True,
            env={**env_base, "PYTHONPATH": str(pythonpath)},
        )
    if proc.returncode != 0:
        raise SystemExit(proc.stderr[-2000:])
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(n: int = 100, repeats: int = 3, baseline: str | None = None) -> None:
    print(f"machine: {machine_line()}")
    loads = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        trees = {"this tree": ROOT}
        if baseline:
            base = tmp / "baseline"
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), baseline],
                check=True,
                capture_output=True,
            )
            trees[baseline] = base
        best: dict[str, dict[str, float]] = {k: {} for k in trees}
        try:
            for _ in range(repeats):
                for name, path in trees.items():
                    env = installed_env(tmp / f"pycache-{name.replace(' ', '_')}")
                    for step, ms in run_child(n, path, env).items():
                        best[name][step] = min(best[name].get(step, float("inf")), ms)
                    loads.append(os.getloadavg()[0])
        finally:
            if baseline:
                subprocess.run(
                    ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(tmp / "baseline")],
                    capture_output=True,
                )
    print(f"machine after: {machine_line()}")
    print(
        f"{n} copies of the shear sample, default options, --no-plots, one process; least of {repeats} runs; "
        f"load average (1 min) after each run {min(loads):.1f} to {max(loads):.1f}"
    )
    names = list(trees)
    print(f"{'step (CPU ms per file)':28s}" + "".join(f"{k:>14s}" for k in names) + ("   ratio" if baseline else ""))
    for step in ["whole file"] + [f for _, f in STEPS if f in best[names[0]]]:
        row = [best[k].get(step, float("nan")) for k in names]
        ratio = f"   {row[0] / row[1]:.2f}x" if baseline and row[1] == row[1] else ""
        print(f"{step:28s}" + "".join(f"{v:14.2f}" for v in row) + ratio)


if __name__ == "__main__":
    argv = sys.argv[1:]
    if argv and argv[0] == "--child":
        child(int(argv[1]), argv[2])
        raise SystemExit(0)
    base = None
    if "--baseline" in argv:
        k = argv.index("--baseline")
        base = argv[k + 1]
        del argv[k : k + 2]
    main(*(int(a) for a in argv[:2]), baseline=base)
