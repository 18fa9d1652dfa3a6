"""End-to-end speed and memory of `capred bridge solve` (issues 13 and 20), as ratios measured in one run.

1. `capred bridge solve` on n suction-controlled rows (CSV in, CSV and JSON
   out, no figures, no HTML) against one scipy `solve_ivp` integration
   (DOP853, rtol 1e-12: the accuracy of capred's quadrature, the force
   difference is printed) per bridge at its known filling angle. The peer is
   charged only for the rows that have a bridge (about a third of the rows
   are beyond rupture and cost it nothing), and the comparison is core for
   core: CPU seconds of capred's whole process tree (it solves large files
   in two processes) against CPU seconds of solve_ivp. Target >= 50x. The
   wall-clock ratio against the peer spread over as many processes as
   capred uses is printed too.
2. Volume-controlled rows against suction-controlled rows of the same
   bridges through the CLI (rows given V_w against rows given the suction),
   at contact and at a gap, CPU of the process tree: target <= 3x.
3. Peak memory of the CLI: RSS on n rows against n / 10 rows.

All timings are interleaved (A, B, A, B, ...; medians of the repeats).

capred runs with its bytecode cached, as an installed package has it (pip
compiles on install): a warm-up run writes it to a temporary
PYTHONPYCACHEPREFIX, also where the environment sets PYTHONDONTWRITEBYTECODE
(which would make every run compile capred's modules again, about 0.2 s CPU).
Set CAPRED_BENCH_COMPILE=1 to keep the environment's setting.

capred forks its helper processes (the second half of each block's solve, the
JSON writer) only when a core is free (capred.io.writers.second_core_free:
the load average leaves one idle); the load average is printed. Set
CAPRED_PROCESSES=2 (or 1) to force two processes (or one) whatever the load.

Run from the repository root with capred installed:
    python benchmarks/bench_bridge_cli.py [rows] [repeats] [ivp_sample]
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import numpy as np
from bench_bridge import ivp_bridge  # one solve_ivp integration per bridge (this folder)
from common import installed_env, interleaved, ratio_line, run

from capred.physics import bridge as br

GAMMA = 0.0728  # N/m, capred's default surface tension

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
    0.05 mm (about a third beyond rupture)."""
    rng = np.random.default_rng(seed)
    R = rng.uniform(0.1, 2.0, n)
    th = rng.uniform(0.0, 60.0, n)
    s = 10 ** rng.uniform(-1, 1.5, n)
    D = rng.uniform(0.0, 0.05, n) * R
    return R, th, D, s


def dimensionless(R, th, D, s):
    """theta [rad], s* = Delta_u R / gamma and gap* = D / R of rows in mm, deg, kPa."""
    return np.radians(th), s * 1e3 * R * 1e-3 / GAMMA, D / R


def write_csv(path: Path, columns: dict[str, np.ndarray]) -> None:
    with open(path, "w") as fh:
        fh.write(",".join(columns) + "\n")
        fh.writelines(",".join(map(repr, row)) + "\n" for row in zip(*(c.tolist() for c in columns.values())))


def suction_file(path: Path, R, th, D, s) -> None:
    write_csv(path, {"R [mm]": R, "contact_angle [deg]": th, "gap [mm]": D, "suction [kPa]": s})


#: environment of the CLI runs (see the module docstring): set by main
ENV: dict | None = None


def cli(csv: Path, out: Path):
    """One `capred bridge solve` run: (Timing of its process tree, peak RSS [kB])."""
    p, t = run([sys.executable, "-c", RUN, "bridge", "solve", str(csv), "--out", str(out), "--no-html"], env=ENV)
    return t, int(p.stderr.split("MAXRSS_KB")[-1].split()[0])


def main(n: int = 100_000, repeats: int = 3, sample: int = 300) -> None:
    # capred uses up to two processes on a long file (the JSON writer, and the solver on blocks of 40,000 rows or
    # more: capred.pipelines.bridge_solve._PARALLEL_ROWS); the wall-clock peer is spread over as many (its best case)
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    forced = os.environ.get("CAPRED_PROCESSES", "").strip()
    procs = int(forced) if forced.isdigit() and int(forced) > 0 else (2 if n >= 40_000 and cores >= 2 else 1)
    R, th, D, s = cases(n)
    th_r, s_star, D_star = dimensionless(R, th, D, s)
    beta, status = br.solve_for_suction(th_r, s_star, D_star)
    ok = np.flatnonzero(status == 0)
    pick = ok[:sample]
    mine = br.bridge(beta[pick], th_r[pick], s_star[pick])
    err = np.max(np.abs(np.array([ivp_bridge(beta[i], th_r[i], s_star[i], 1e-12)[2] for i in pick]) / mine.force - 1))

    global ENV
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        ENV = installed_env(tmp / "pycache")
        print(
            "bytecode: "
            + (
                "compiled by every run (CAPRED_BENCH_COMPILE=1)"
                if ENV is None
                else "cached by the warm-up run (PYTHONPYCACHEPREFIX)"
            )
            + f"; load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; CAPRED_PROCESSES="
            + os.environ.get("CAPRED_PROCESSES", "(unset: capred decides by the load)")
        )
        big, small = tmp / "big.csv", tmp / "small.csv"
        suction_file(big, R, th, D, s)
        suction_file(small, *(x[: n // 10] for x in (R, th, D, s)))
        cli(small, tmp / "warm")  # warm the file cache and the bytecode
        t = interleaved(
            {
                "capred": lambda: cli(big, tmp / "out_big"),
                "solve_ivp": lambda: [ivp_bridge(beta[i], th_r[i], s_star[i], 1e-12) for i in pick],
            },
            repeats,
        )
        rss_big = cli(big, tmp / "out_big")[1]
        rss_small = cli(small, tmp / "out_small")[1]

        cpu_ivp = t["solve_ivp"].cpu / pick.size * ok.size  # charged for the rows with a bridge only
        wall_ivp = t["solve_ivp"].wall / pick.size * ok.size / procs  # spread over as many processes as capred
        print(
            f"capred bridge solve, {n:,} suction-controlled rows ({ok.size:,} with a bridge), {procs} process(es): "
            f"{t['capred'].cpu:.2f} s CPU, {t['capred'].wall:.2f} s wall "
            f"({ok.size / t['capred'].cpu:,.0f} bridges per CPU second)"
        )
        print(
            f"solve_ivp (DOP853, rtol 1e-12, max force difference {err:.1e}): "
            f"{t['solve_ivp'].cpu / pick.size * 1e3:.3f} ms CPU per bridge -> {cpu_ivp:.1f} s CPU for the "
            f"{ok.size:,} bridges"
        )
        print(
            "  "
            + ratio_line("solve_ivp over capred, CPU (core for core, bridges only)", cpu_ivp, t["capred"].cpu, ">= 50x")
        )
        print("  " + ratio_line(f"wall, the peer on {procs} process(es)", wall_ivp, t["capred"].wall))

        # volume-controlled against suction-controlled rows of the same bridges, through the CLI
        for where in ("contact", "gap"):
            Dw = np.zeros(n) if where == "contact" else D_star
            b, st = br.solve_for_suction(th_r, s_star, Dw)
            k = np.flatnonzero(st == 0)
            V = br.bridge(b[k], th_r[k], s_star[k]).volume * R[k] ** 3  # mm^3
            fs, fv = tmp / f"s_{where}.csv", tmp / f"v_{where}.csv"
            suction_file(fs, R[k], th[k], Dw[k] * R[k], s[k])
            write_csv(fv, {"R [mm]": R[k], "contact_angle [deg]": th[k], "gap [mm]": Dw[k] * R[k], "V_w [mm^3]": V})
            tv = interleaved({"suction": lambda: cli(fs, tmp / "os"), "volume": lambda: cli(fv, tmp / "ov")}, repeats)
            print(
                f"bridge solve at {where}, {k.size:,} bridges: suction rows {tv['suction'].cpu:.2f} s CPU "
                f"({tv['suction'].wall:.2f} wall), volume rows {tv['volume'].cpu:.2f} s CPU "
                f"({tv['volume'].wall:.2f} wall)"
            )
            print(
                "  "
                + ratio_line("volume over suction, CPU", tv["volume"].cpu, tv["suction"].cpu, "<= 3x")
                + "; "
                + ratio_line("wall", tv["volume"].wall, tv["suction"].wall)
            )
    print(
        f"peak RSS: {rss_small / 1024:.0f} MB for {n // 10:,} rows, {rss_big / 1024:.0f} MB for {n:,} rows "
        f"({(rss_big - rss_small) * 1024 / (n - n // 10):.0f} B/row)"
    )


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:4]))
