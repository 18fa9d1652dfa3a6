"""End-to-end speed and memory of `capred bridge solve` (issue 13), as ratios measured in one run.

1. `capred bridge solve` on 100,000 suction-controlled rows (CSV in, CSV and
   JSON out, no figures, only the first 20 rows on the console) against one
   scipy `solve_ivp` integration (DOP853) per bridge at its known filling
   angle, timed on a sample of the same rows in this process and scaled to
   100,000: target >= 50x. The reference integrates at rtol 1e-12, the
   accuracy capred's quadrature delivers (the force difference is printed);
   the ratio at rtol 1e-10 is printed too.
2. The solver alone (`physics.bridge.solve_for_suction`) on one core: target
   >= 100,000 bridges/s (run under `taskset -c 0` for the one-core figure).
3. Peak memory of the CLI: RSS on 100,000 rows against 10,000 rows (flat in
   the row count: rows are read, solved and written in blocks).

Run from the repository root with capred installed:
    python benchmarks/bench_bridge_cli.py [rows] [ivp_sample]
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from bench_bridge import ivp_bridge  # one solve_ivp integration per bridge (this folder)

from capred.physics import bridge as br

RUN = """
import resource, sys
sys.argv = ["capred"] + sys.argv[1:]
from capred.cli import main
code = 0
try:
    main()
except SystemExit as exc:
    code = exc.code or 0
print("MAXRSS_KB", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)
sys.exit(code)
"""


def cases(n: int, seed: int = 0):
    """Random steel-sphere and sand-grain bridges: R 0.1-2 mm, theta 0-60 deg, suction 0.1-30 kPa, gaps up to
    0.05 mm (a third beyond rupture)."""
    rng = np.random.default_rng(seed)
    R = rng.uniform(0.1, 2.0, n)
    th = rng.uniform(0.0, 60.0, n)
    s = 10 ** rng.uniform(-1, 1.5, n)
    D = rng.uniform(0.0, 0.05, n) * R
    return R, th, D, s


def write_csv(path: Path, n: int) -> None:
    R, th, D, s = cases(n)
    with open(path, "w") as fh:
        fh.write("R [mm],contact_angle [deg],gap [mm],suction [kPa]\n")
        fh.writelines(f"{a!r},{b!r},{c!r},{d!r}\n" for a, b, c, d in zip(*(x.tolist() for x in (R, th, D, s))))


def cli(csv: Path, out: Path) -> tuple[float, int]:
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-c", RUN, "bridge", "solve", str(csv), "--out", str(out), "--no-html"],
                       capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        raise SystemExit(p.stderr)
    rss = int(p.stderr.split("MAXRSS_KB")[-1].split()[0])
    return dt, rss


def main(n: int = 100_000, sample: int = 400) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        big, small = tmp / "big.csv", tmp / "small.csv"
        write_csv(big, n)
        write_csv(small, n // 10)
        cli(small, tmp / "warm")  # warm the file cache and the bytecode
        runs = [cli(big, tmp / f"out_big{k}") for k in range(3)]
        t_cli, rss_big = sorted(runs)[1]  # the median of three runs
        _, rss_small = cli(small, tmp / "out_small")

    R, th, D, s = cases(n)
    gamma = 0.0728
    th_r, s_star, D_star = np.radians(th), s * 1e3 * R * 1e-3 / gamma, D / R
    t0 = time.perf_counter()
    beta, status = br.solve_for_suction(th_r, s_star, D_star)
    t_solver = time.perf_counter() - t0

    ok = np.flatnonzero(status == 0)[:sample]
    mine = br.bridge(beta[ok], th_r[ok], s_star[ok])
    t_ivp, err = {1e-12: [], 1e-10: []}, {}
    for _ in range(3):  # interleaved blocks, the median per tolerance: the machine's load varies
        for rtol in t_ivp:
            t0 = time.perf_counter()
            ref = np.array([ivp_bridge(beta[i], th_r[i], s_star[i], rtol) for i in ok])
            t_ivp[rtol].append((time.perf_counter() - t0) / ok.size)
            err[rtol] = np.max(np.abs(ref[:, 2] / mine.force - 1))
    t_ivp = {k: sorted(v)[1] for k, v in t_ivp.items()}

    print(f"capred bridge solve, {n:,} rows through the CLI: {t_cli:.2f} s ({n / t_cli:,.0f} bridges/s)")
    for rtol in t_ivp:
        print(f"solve_ivp at the known filling angle, rtol {rtol:g}: {t_ivp[rtol] * 1e3:.3f} ms per bridge -> "
              f"{t_ivp[rtol] * n:.1f} s for {n:,} (max force difference {err[rtol]:.1e}); "
              f"ratio end to end {t_ivp[rtol] * n / t_cli:.1f}x (target >= 50x)")
    print(f"solver alone: {n / t_solver:,.0f} bridges/s (target >= 100,000/s on one core)")
    print(f"peak RSS: {rss_small / 1024:.0f} MB for {n // 10:,} rows, {rss_big / 1024:.0f} MB for {n:,} rows "
          f"({(rss_big - rss_small) * 1024 / (n - n // 10):.0f} B/row)")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
