"""Speed targets of `capred shear` (issue 2), measured in fresh subprocesses.

1. `capred --help` against `python -c "import typer"` (target <= 1.3x).
2. `capred shear --sample` (with PNGs) against the bare imports it needs plus
   one savefig of a 2x2 figure (target <= 1.5x).

Run: python benchmarks/bench_shear.py [repeats]
"""
from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def timed(cmd: list[str], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


BARE = """
import numpy, pandas, scipy.special, pint, rich, typer
from matplotlib.figure import Figure
fig = Figure(figsize=(11, 9))
axes = fig.subplots(2, 2)
for ax in axes.flat:
    ax.plot([0, 1], [0, 1], "o-")
fig.savefig(r"{out}/bare.png", dpi=150)
"""


def main(repeats: int = 7) -> None:
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        typer_t = timed([py, "-c", "import typer"], repeats)
        help_t = timed([py, "-m", "capred", "--help"], repeats)
        bare_t = timed([py, "-c", BARE.format(out=tmp)], repeats)
        shear_t = timed([py, "-m", "capred", "shear", "--sample", "--out", f"{tmp}/o"], repeats)
        # the sample holds two materials (two report sheets); time one material alone too
        from capred.samples import sample_path

        lines = sample_path("shear").read_text().splitlines()
        one = [ln for ln in lines if not ln.startswith("SA-")]
        single = Path(tmp) / "steel_only.csv"
        single.write_text("\n".join(one) + "\n")
        one_t = timed([py, "-m", "capred", "shear", str(single), "--out", f"{tmp}/o1"], repeats)
    print(f"import typer              {typer_t * 1e3:7.0f} ms")
    print(f"capred --help             {help_t * 1e3:7.0f} ms   ratio {help_t / typer_t:.2f} (target <= 1.3)")
    print(f"bare imports + savefig    {bare_t * 1e3:7.0f} ms")
    print(f"capred shear --sample     {shear_t * 1e3:7.0f} ms   ratio {shear_t / bare_t:.2f} (2 report sheets)")
    print(f"capred shear, 1 material  {one_t * 1e3:7.0f} ms   ratio {one_t / bare_t:.2f} (1 sheet; target <= 1.5)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
