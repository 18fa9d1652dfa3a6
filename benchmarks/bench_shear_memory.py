"""Peak memory of `capred shear` on n tests against n/10 (issue 20: within 1.5x), and the peak per test.

Each run is one `python -m capred shear FILE --out DIR` process, started from this small process; its
peak resident set size is the ``ru_maxrss`` that ``os.wait4`` reports for it (on Linux the largest of the
process and the children it waited for: the forked JSON writer, the figure processes). Three contestants
per size: every default output (figures, report.html, the 2,000-replicate bootstrap), ``--no-plots``
(report.html without figures) and ``--no-plots --bootstrap 0`` (without the ranking bootstrap of
capred.pipelines.shear_analysis, whose working set grows with the wet tests of a material).

The rows repeat sample_data/shear_tests.csv with unique test ids and 2 % noise on tau_max
(``bench_shear.make_rows``). Printed: the peaks, their ratio against the 1.5x target, and the peak
per test at n, (peak(n) - peak(n/10)) / (0.9 n), the memory each further test costs.

``--lab``: rows shaped as a lab's season (``common.lab_shear_rows``: every dry test at its own stress);
``--only=defaults`` (repeatable): only those contestants.

Run from the repository root: python benchmarks/bench_shear_memory.py [rows=1000000] [--lab] [--only=NAME]
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import ratio_line  # noqa: E402

CONTESTANTS = {
    "defaults": (),
    "--no-plots": ("--no-plots",),
    "--no-plots --bootstrap 0": ("--no-plots", "--bootstrap", "0"),
}


def peak_mb(data: Path, out: Path, args: tuple[str, ...]) -> tuple[float, float]:
    """(peak RSS [MB], wall time [s]) of one `capred shear` process."""
    t = time.perf_counter()
    p = subprocess.Popen(
        [sys.executable, "-m", "capred", "shear", str(data), "--out", str(out), *args],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    err = p.stderr.read()
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise SystemExit(f"capred shear {data} failed:\n{err.decode(errors='replace')}")
    return usage.ru_maxrss / 1024, time.perf_counter() - t  # ru_maxrss in kB on Linux


def main(n: int = 1_000_000, lab: bool = False, only: tuple[str, ...] = ()) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        small, big = tmp / "small.csv", tmp / "big.csv"
        # the rows are made in a process of their own: a child's ru_maxrss counts the pages it shared with this
        # process between fork and exec, so this one must stay small
        here = str(Path(__file__).resolve().parent)
        for path, rows in ((small, n // 10), (big, n)):
            subprocess.run(
                [
                    sys.executable,
                    "-c",
                    f"import sys; sys.path.insert(0, {here!r}); from bench_shear import make_rows; "
                    f"from common import lab_shear_rows; from pathlib import Path; "
                    f"{'lab_shear_rows' if lab else 'make_rows'}(Path({str(path)!r}), {rows})",
                ],
                check=True,
            )
        peak_mb(small, tmp / "warm", ("--no-plots", "--bootstrap", "0"))  # file cache and bytecode warm
        print(f"load {os.getloadavg()}, {'lab-shaped rows (common.lab_shear_rows)' if lab else 'the sample repeated'}")
        for name, args in CONTESTANTS.items():
            if only and name not in only:
                continue
            lo, t_lo = peak_mb(small, tmp / "o_small", args)
            hi, t_hi = peak_mb(big, tmp / "o_big", args)
            print(
                f"{name}: {n // 10:,} tests {lo:.0f} MB ({t_lo:.0f} s), {n:,} tests {hi:.0f} MB ({t_hi:.0f} s); "
                f"peak per test {hi * 2**20 / n:.0f} B, each further test {(hi - lo) * 2**20 / (0.9 * n):.0f} B"
            )
            print("  " + ratio_line(f"peak at {n:,} / at {n // 10:,}", hi, lo, "<= 1.5x"))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    only = tuple(a[len("--only=") :] for a in sys.argv[1:] if a.startswith("--only="))
    main(int(args[0]) if args else 1_000_000, "--lab" in sys.argv, only)
