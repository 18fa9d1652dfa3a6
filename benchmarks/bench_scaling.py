"""How the cost grows: exponents in rows, distinct dry stresses, files and workers (issue 31, item 2).

For each axis the CPU time of the whole process tree is measured at sizes a factor apart (the minimum of
``repeats`` runs: the least disturbed by other load on a shared machine) and the growth exponent k of
cost ~ size^k is printed, between every two neighbouring sizes and over the top half of the range (where a
fixed start-up no longer hides the growth). An exponent above 1.15 (local or top half) is flagged: a cost
that grows faster than the data (a cliff) is a bug, whatever the machine; on an axis that must cost nothing
(distinct dry stresses at fixed rows) any local exponent above 0.3 is. Exit status 1 when one is flagged.

Axes (data shaped as labs have it, ``common.lab_shear_rows`` / ``lab_retention_rows``):

- ``shear-rows``:     ``run_shear`` (default bootstrap, R = 2000) on 1k .. 64k rows (``--full``: to 1M),
                      every dry test at its own normal stress
- ``shear-distinct``: the same at 20,000 rows, dry stresses 6, 60, 600, half the dry tests (each stress
                      twice), all distinct: the exponent must be about 0 (issue 31.1: it was quadratic)
- ``retention-rows``: ``run_retention`` (default models) on 1k .. 100k readings at scattered suctions
- ``bridge-rows``:    ``physics.bridge.solve_for_suction`` on 1k .. 100k bridges (``--full``: to 1M)
- ``batch-files``:    ``capred batch`` over 10 .. 100 sample-sized shear files (``--full``: 1,000),
                      ``--no-plots`` (``--figures``: every default output), one worker
- ``batch-workers``:  the same 40 files on 1 .. all cores: CPU exponent (work added by more workers: ~0)
                      and the wall speed-up
- ``shear-files``:    ``capred shear FILES --no-plots`` as a user types it (no manifest, the CLI's default
                      workers) over 10 .. 100 sample-sized files (``--full``: 1,000); prints the CPU per file
                      beyond the start-up (issue 44, item 1: a per-file cost that does not depend on the data)
                      and flags it above ``PER_FILE_MS``

Prints the machine (CPU model), its core count and the load average before and after.

Run from the repository root: python benchmarks/bench_scaling.py [--full] [--figures] [--repeats N] [axis ...]
"""

from __future__ import annotations

import os

# one BLAS thread, as the command line runs (capred.cli): spinning BLAS threads would count as CPU time here
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import math  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import lab_retention_rows, lab_shear_rows, machine_line, timed  # noqa: E402

FLAG = 1.15
#: axes whose cost must not grow at all, and the exponent above which they are flagged (any neighbouring pair)
FLAT = {"shear-distinct": 0.3}
#: CPU per sample-sized file of `capred shear FILES --no-plots` beyond the start-up above which ``shear-files`` is
#: flagged [ms]: 18-21 ms measured on this project's AMD EPYC pair at 30ddff3 (issue 44); 10 s of wall time for
#: 1,000 files on 2 cores leaves at most ~19 ms per file
PER_FILE_MS = 25.0
ROOT = Path(__file__).resolve().parents[1]


def exponents(sizes, costs) -> tuple[list[float], float]:
    """Local exponents log(c2/c1)/log(n2/n1) between neighbours, and the least-squares slope over the top
    half of the sizes (at least the last two)."""
    local = [
        math.log(c2 / c1) / math.log(n2 / n1)
        for (n1, c1), (n2, c2) in zip(zip(sizes, costs), zip(sizes[1:], costs[1:]))
    ]
    top = max(2, (len(sizes) + 1) // 2)
    x = [math.log(n) for n in sizes[-top:]]
    y = [math.log(c) for c in costs[-top:]]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    slope = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
    return local, slope


def best(fn, repeats: int) -> float:
    """The least CPU time [s] of ``repeats`` runs of ``fn``."""
    return min(timed(fn)[1].cpu for _ in range(repeats))


def shear_cost(path, repeats: int) -> float:
    import capred

    def go():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            capred.run_shear(path, capred.ShearOptions())

    return best(go, repeats)


def axis_shear_rows(tmp: Path, full: bool, repeats: int):
    sizes = [1_000, 4_000, 16_000, 64_000] + ([256_000, 1_000_000] if full else [])
    costs = []
    for n in sizes:
        p = tmp / f"shear_{n}.csv"
        lab_shear_rows(p, n)
        costs.append(shear_cost(p, repeats if n <= 64_000 else 1))
    return sizes, costs


def axis_shear_distinct(tmp: Path, full: bool, repeats: int, rows: int = 20_000):
    half = _dry_per_material(rows) // 2  # every stress tested twice: the case the dense indicator met in full
    sizes = [6, 60, 600, half, None]
    costs, shown = [], []
    for k in sizes:
        p = tmp / f"shear_d{k}.csv"
        lab_shear_rows(p, rows, distinct_dry=k)
        costs.append(shear_cost(p, repeats))
        shown.append(k or _dry_per_material(rows))
    return shown, costs


def _dry_per_material(rows: int) -> int:
    """Dry tests per material among ``rows`` rows of the sample's pattern (every one distinct)."""
    import capred

    lines = [ln for ln in capred.sample_path("shear").read_text().splitlines() if ln and not ln.startswith("#")][1:]
    dry = [ln for ln in lines if ",dry," in ln]
    return max(1, rows * len(dry) // len(lines) // 2)


def axis_retention_rows(tmp: Path, full: bool, repeats: int):
    import capred

    sizes = [1_000, 10_000, 100_000]
    costs = []
    for n in sizes:
        p = tmp / f"ret_{n}.csv"
        lab_retention_rows(p, n)

        def go(p=p):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                capred.run_retention(p)

        costs.append(best(go, repeats))
    return sizes, costs


def axis_bridge_rows(tmp: Path, full: bool, repeats: int):
    import numpy as np

    from capred.physics import bridge as br

    sizes = [1_000, 10_000, 100_000] + ([1_000_000] if full else [])
    costs = []
    for n in sizes:
        rng = np.random.default_rng(0)
        R = rng.uniform(0.1, 2.0, n)
        th = np.radians(rng.uniform(0.0, 60.0, n))
        s = 10 ** rng.uniform(-1, 1.5, n) * 1e3 * R * 1e-3 / 0.0728
        D = rng.uniform(0.0, 0.05, n)
        costs.append(best(lambda: br.solve_for_suction(th, s, D, np.ones(n)), repeats if n <= 100_000 else 1))
    return sizes, costs


def _batch(tmp: Path, n: int, workers: int, figures: bool) -> tuple[float, float]:
    """(CPU, wall) [s] of `capred batch` over ``n`` copies of the shear sample."""
    import capred

    runs = tmp / f"runs_{n}"
    if not runs.exists():
        runs.mkdir()
        for k in range(n):
            shutil.copy(capred.sample_path("shear"), runs / f"s{k:05d}.csv")
    manifest = tmp / f"m_{n}.csv"
    manifest.write_text(f"command,input,options\nshear,{runs}/*.csv,{'' if figures else '--no-plots'}\n")
    out = tmp / "out"
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, "-m", "capred", "batch", str(manifest), "--out", str(out), "--workers", str(workers)]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    _, t = timed(lambda: subprocess.run(cmd, check=True, capture_output=True, env=env))
    return t.cpu, t.wall


def axis_batch_files(tmp: Path, full: bool, repeats: int, figures: bool = False):
    sizes = [10, 30, 100] + ([300, 1_000] if full else [])
    costs = [min(_batch(tmp, n, 1, figures)[0] for _ in range(repeats if n <= 100 else 1)) for n in sizes]
    return sizes, costs


def axis_shear_files(tmp: Path, full: bool, repeats: int, figures: bool = False):
    """CPU [s] of `capred shear FILES --no-plots` (default workers) over 10 .. 100 (1,000) sample files."""
    import capred

    sizes = [10, 30, 100] + ([300, 1_000] if full else [])
    costs, walls = [], []
    for n in sizes:
        runs = tmp / f"runs_{n}"
        if not runs.exists():
            runs.mkdir()
            for k in range(n):
                shutil.copy(capred.sample_path("shear"), runs / f"s{k:05d}.csv")
        files = [str(p) for p in sorted(runs.glob("*.csv"))]
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        best_cpu, best_wall = math.inf, math.inf
        for _ in range(repeats if n <= 100 else 1):
            out = tmp / "out_files"
            shutil.rmtree(out, ignore_errors=True)
            cmd = [sys.executable, "-m", "capred", "shear", *files, *([] if figures else ["--no-plots"])]
            _, t = timed(lambda: subprocess.run([*cmd, "--out", str(out)], check=True, capture_output=True, env=env))
            best_cpu, best_wall = min(best_cpu, t.cpu), min(best_wall, t.wall)
        costs.append(best_cpu)
        walls.append(best_wall)
    per_file = (costs[-1] - costs[0]) / (sizes[-1] - sizes[0]) * 1e3
    for n, c, w in zip(sizes, costs, walls):
        print(f"    {n:5d} files: CPU {c:7.2f} s  wall {w:7.2f} s")
    flag = per_file > PER_FILE_MS and not figures
    print(
        f"    CPU per file beyond the start-up {per_file:.1f} ms (flagged above {PER_FILE_MS:.0f} ms)"
        + ("   <-- above" if flag else "")
    )
    if flag:
        _PER_FILE_FLAGS.append("shear-files (CPU per file)")
    return sizes, costs


_PER_FILE_FLAGS: list[str] = []


def axis_batch_workers(tmp: Path, full: bool, repeats: int, figures: bool = False, files: int = 40):
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover
        cores = os.cpu_count() or 1
    sizes = sorted({1, 2, 4, 8, 16, cores} & set(range(1, cores + 1)))
    cpu, wall = [], []
    for w in sizes:
        runs = [_batch(tmp, files, w, figures) for _ in range(repeats)]
        cpu.append(min(r[0] for r in runs))
        wall.append(min(r[1] for r in runs))
    for w, c, t in zip(sizes, cpu, wall):
        print(f"    {w:3d} workers: CPU {c:7.2f} s  wall {t:7.2f} s  speed-up {wall[0] / t:5.2f}x")
    return sizes, cpu


AXES = {
    "shear-rows": axis_shear_rows,
    "shear-distinct": axis_shear_distinct,
    "retention-rows": axis_retention_rows,
    "bridge-rows": axis_bridge_rows,
    "batch-files": axis_batch_files,
    "batch-workers": axis_batch_workers,
    "shear-files": axis_shear_files,
}


def main(argv: list[str]) -> int:
    full = "--full" in argv
    figures = "--figures" in argv
    repeats = int(argv[argv.index("--repeats") + 1]) if "--repeats" in argv else 3
    names = [a for a in argv if a in AXES] or list(AXES)
    print(f"capred scaling on {machine_line()}")
    flagged = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            fn = AXES[name]
            kw = {"figures": figures} if name.startswith("batch") or name == "shear-files" else {}
            sizes, costs = fn(Path(tmp), full, repeats, **kw)
            local, slope = exponents(sizes, costs)
            cells = "  ".join(f"{n:,}: {c:.3f} s" for n, c in zip(sizes, costs))
            print(f"{name:15s} {cells}")
            limit = FLAT.get(name, FLAG)
            flag = max(local + [slope]) > limit
            print(
                f"{'':15s} exponents {' '.join(f'{e:+.2f}' for e in local)}; top half {slope:+.2f}"
                + (f"   <-- above {limit}" if flag else "")
            )
            if flag:
                flagged.append(name)
    flagged += _PER_FILE_FLAGS
    print(f"after: {machine_line()}; " + (f"FLAGGED: {', '.join(flagged)}" if flagged else "no exponent flagged"))
    return 1 if flagged else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
