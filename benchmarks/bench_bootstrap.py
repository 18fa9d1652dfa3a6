"""Cost of the ranking bootstrap in `capred shear` (issue 20, target: <= 1.5x the run without it).

Times ``capred shear --sample --no-plots --no-html --bootstrap N`` against the same command with
``--bootstrap 0``, each in a fresh process, the two interleaved repeat by repeat (so drifts of the
machine load hit both alike). CPU is the user + system time of the child process tree
(``resource.RUSAGE_CHILDREN``); wall is ``time.perf_counter``. Medians are compared.

Run: python benchmarks/bench_bootstrap.py [N=2000] [repeats=7] [extra capred shear options...]
e.g. python benchmarks/bench_bootstrap.py 2000 7 --models thesis,chi_power,khalili_fit

``--mc [seeds=50]`` instead measures the Monte-Carlo error of the probabilities the bootstrap reports, in
this process: for each material of the bundled sample and each replicate count R, the standard deviation
over ``seeds`` seeds of every model's probability of being best, beside the binomial sqrt(p(1 - p)/R)
(Efron & Tibshirani 1993, doi:10.1007/978-1-4899-4541-9, ch. 6) and the CPU time of one call.
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


def monte_carlo_error(seeds: int = 50, counts=(250, 500, 1000, 2000, 4000)) -> dict:
    """{(material, R): (max SD over the models of P(best), its binomial value, ms of CPU per call)}."""
    import numpy as np

    import capred.pipelines.shear as shear
    import capred.pipelines.shear_analysis as sa
    from capred.batch import single_threaded_blas
    from capred.samples import sample_path

    calls = []
    original = sa.bootstrap_ranking

    def record(*a, **k):
        calls.append((a, k))
        return original(*a, **k)

    sa.bootstrap_ranking = record
    try:
        shear.run_table(sample_path("shear"), shear.ShearOptions())
    finally:
        sa.bootstrap_ranking = original
    out = {}
    with single_threaded_blas():
        for a, k in calls:
            material = str(a[0].material[0])
            for R in counts:
                t0 = time.process_time()
                probs = [original(*a[:7], R, seed, *a[9:], **k).probability for seed in range(seeds)]
                ms = (time.process_time() - t0) / seeds * 1e3
                models = list(probs[0])
                table = np.array([[p[m] for m in models] for p in probs])
                sd = table.std(axis=0, ddof=1)
                worst = int(np.argmax(sd))
                p = table[:, worst].mean()
                out[(material, R)] = (float(sd[worst]), float(np.sqrt(p * (1 - p) / R)), ms)
                print(
                    f"{material:12s} R={R:5d}  SD of P(best) {sd[worst]:.4f} ({models[worst]}, mean {p:.3f}; "
                    f"binomial {np.sqrt(p * (1 - p) / R):.4f}; worst case p = 0.5: {np.sqrt(0.25 / R):.4f})  "
                    f"{ms:.2f} ms CPU per call"
                )
    return out


if __name__ == "__main__":
    args = sys.argv[1:]
    if args and args[0] == "--mc":
        monte_carlo_error(int(args[1]) if len(args) > 1 else 50)
        raise SystemExit(0)
    n = int(args[0]) if args else 2000
    reps = int(args[1]) if len(args) > 1 else 7
    main(n, reps, args[2:])
