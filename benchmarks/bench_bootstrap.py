"""Cost of the ranking bootstrap in `capred shear` (issue 20, target: <= 1.5x the run without it).

Times ``capred shear --sample --no-plots --no-html --bootstrap N`` against the same command with
``--bootstrap 0``, each in a fresh process, the two interleaved repeat by repeat (so drifts of the
machine load hit both alike). CPU is the user + system time of the child process tree
(``resource.RUSAGE_CHILDREN``); wall is ``time.perf_counter``. Medians are compared.

Run: python benchmarks/bench_bootstrap.py [N=2000] [repeats=7] [extra capred shear options...]
e.g. python benchmarks/bench_bootstrap.py 2000 7 --models thesis,chi_power,khalili_fit
"""
from __future__ import annotations

import resource
import statistics
import subprocess
import sys
import tempfile
import time


def run(cmd: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one subprocess (CPU of its whole process tree)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def main(replicates: int = 2000, repeats: int = 7, extra: list[str] | None = None) -> dict:
    py = sys.executable
    extra = extra or []
    times: dict[str, list[tuple[float, float]]] = {"without": [], "with": []}
    with tempfile.TemporaryDirectory() as tmp:
        base = [py, "-m", "capred", "shear", "--sample", "--no-plots", "--no-html", *extra]
        run(base + ["--bootstrap", "0", "--out", f"{tmp}/warm"])  # warm the file cache once, untimed
        for k in range(repeats):
            times["without"].append(run(base + ["--bootstrap", "0", "--out", f"{tmp}/a{k}"]))
            times["with"].append(run(base + ["--bootstrap", str(replicates), "--out", f"{tmp}/b{k}"]))
    med = {key: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for key, v in times.items()}
    (w0, c0), (w1, c1) = med["without"], med["with"]
    print(f"capred shear --sample --no-plots --no-html {' '.join(extra)}  ({repeats} interleaved repeats, medians)")
    print(f"  --bootstrap 0        wall {w0 * 1e3:7.0f} ms   CPU {c0 * 1e3:7.0f} ms")
    print(f"  --bootstrap {replicates:<8d} wall {w1 * 1e3:7.0f} ms   CPU {c1 * 1e3:7.0f} ms")
    print(f"  ratio                wall {w1 / w0:7.2f}      CPU {c1 / c0:7.2f}      (target <= 1.5)")
    return {"wall_ratio": w1 / w0, "cpu_ratio": c1 / c0, "medians": med}


if __name__ == "__main__":
    args = sys.argv[1:]
    n = int(args[0]) if args else 2000
    reps = int(args[1]) if len(args) > 1 else 7
    main(n, reps, args[2:])
