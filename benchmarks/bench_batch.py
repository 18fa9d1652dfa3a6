"""Batch speed and memory (issue 6), measured through the installed command line.

1. 1,000 direct-shear files without plots (target <= 10 s).
2. Files with plots, --workers 1 against --workers 2 (target >= 1.7x).
3. Peak memory (max RSS of the child) for 100 and 1,000 files: should stay flat.

Run: python benchmarks/bench_batch.py [n_files] [n_plot_files]
"""
from __future__ import annotations

import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(args: list[str]) -> tuple[float, float]:
    """(wall seconds, peak RSS in MB of this child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "capred", *args], check=False, capture_output=True)
    dt = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    return dt, max(after, before) / 1024.0


def make_files(folder: Path, n: int) -> list[str]:
    from capred.samples import sample_path

    folder.mkdir(parents=True, exist_ok=True)
    src = sample_path("shear")
    for k in range(n):
        shutil.copy(src, folder / f"run_{k:05d}.csv")
    return [str(folder / "*.csv")]


def main(n: int = 1000, n_plots: int = 24) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        small = make_files(tmp / "small", 100)
        big = make_files(tmp / "big", n)
        t_small, m_small = run(["shear", *small, "--no-plots", "--out", str(tmp / "o_small")])
        t_big, m_big = run(["shear", *big, "--no-plots", "--out", str(tmp / "o_big")])
        plots = make_files(tmp / "plots", n_plots)
        t1, _ = run(["shear", *plots, "--workers", "1", "--out", str(tmp / "o_w1")])
        t2, _ = run(["shear", *plots, "--workers", "2", "--out", str(tmp / "o_w2")])
    print(f"{n} files, no plots:        {t_big:6.2f} s  ({t_big / n * 1e3:.1f} ms per file; target <= 10 s)")
    print(f"peak RSS 100 / {n} files:   {m_small:6.0f} / {m_big:.0f} MB (flat if close)")
    print(f"{n_plots} files with plots, 1 worker: {t1:6.2f} s")
    print(f"{n_plots} files with plots, 2 workers: {t2:6.2f} s  speed-up {t1 / t2:.2f}x (target >= 1.7x)")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
