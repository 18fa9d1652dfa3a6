"""`capred bridge solve` on 1, 2, ... processes (issue 31 item 4): speed-up of the whole command and of the
solver alone, CPU and wall, with the load average before and after each run.

The rows are the random suction-controlled bridges of bench_bridge_cli.py (R 0.1-2 mm, theta 0-60 deg, suction
0.1-30 kPa, gaps up to 0.05 mm; about a third beyond rupture). Each number of processes is asked for with
``--workers k`` and ``CAPRED_PROCESSES=k`` (the command: the latter also keeps the JSON writer in the run's one
process at k = 1, so that one process does all the work) or ``workers=k`` (the solver alone:
capred.pipelines.bridge_solve._in_parallel on the rows already read); runs are interleaved (1, 2, ..., 1, 2, ...)
and the medians reported. Every run's outputs are checked equal to those of one process (CSV and JSON byte for
byte, but for the option ``workers`` the JSON echoes; solver: to the bit).

Pass ``--command-only`` as a fourth argument to leave out the solver alone.

A shared machine spoils the measure: a speed-up needs idle cores, so compare the load average printed with
the number of cores (a load above cores - k leaves fewer than k cores to the run).

Run from the repository root with capred importable:
    python benchmarks/bench_bridge_cores.py [rows] [workers, comma-separated] [repeats]
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import numpy as np
from common import installed_env, interleaved, run, timed

from capred.pipelines import bridge_solve as bs

GAMMA = 0.0728  # N/m, capred's default surface tension


def cases(n: int, seed: int = 0):
    """The rows of bench_bridge_cli.py (copied here: this benchmark needs numpy only, no scipy)."""
    rng = np.random.default_rng(seed)
    R = rng.uniform(0.1, 2.0, n)
    th = rng.uniform(0.0, 60.0, n)
    s = 10 ** rng.uniform(-1, 1.5, n)
    D = rng.uniform(0.0, 0.05, n) * R
    return R, th, D, s


def dimensionless(R, th, D, s):
    """theta [rad], s* = Delta_u R / gamma and gap* = D / R of rows in mm, deg, kPa."""
    return np.radians(th), s * 1e3 * R * 1e-3 / GAMMA, D / R


def suction_file(path: Path, R, th, D, s) -> None:
    with open(path, "w") as fh:
        fh.write("R [mm],contact_angle [deg],gap [mm],suction [kPa]\n")
        fh.writelines(",".join(map(repr, row)) + "\n" for row in zip(R.tolist(), th.tolist(), D.tolist(), s.tolist()))


def main(n: int = 1_000_000, workers: str = "1,2", repeats: int = 1, solver_too: bool = True) -> None:
    ks = [int(k) for k in workers.split(",")]
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    R, th, D, s = cases(n)
    th_r, s_star, D_star = dimensionless(R, th, D, s)
    rho = np.ones(n)
    print(f"{n:,} suction-controlled rows; {cores} cores; load average {os.getloadavg()[0]:.2f} at the start")

    if solver_too:
        _solver_alone(ks, repeats, th_r, s_star, D_star, rho)
    _command(ks, repeats, R, th, D, s)
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


def _solver_alone(ks, repeats, th_r, s_star, D_star, rho) -> None:
    """The solver alone, on the rows already in memory."""
    ref = None
    solver = {}
    for k in ks:
        solver[f"{k}"] = lambda k=k: bs._in_parallel(bs._suction_rows, th_r, s_star, D_star, rho, th_r, workers=k)
    times = {}
    for _ in range(repeats):
        for k in ks:
            loads = os.getloadavg()[0]
            out, t = timed(solver[f"{k}"])
            if ref is None:
                ref = out
            assert all(np.array_equal(a, b, equal_nan=True) for a, b in zip(out, ref)), "results differ"
            times.setdefault(k, []).append((t, loads, os.getloadavg()[0]))
    base = np.median([t.wall for t, _, _ in times[ks[0]]])
    print("solver alone (capred.pipelines.bridge_solve._in_parallel; identical results to the bit):")
    for k in ks:
        wall = np.median([t.wall for t, _, _ in times[k]])
        cpu = np.median([t.cpu for t, _, _ in times[k]])
        la = ", ".join(f"{a:.1f}->{b:.1f}" for _, a, b in times[k])
        print(f"  {k:>2} process(es): {wall:7.2f} s wall, {cpu:7.2f} s CPU; speed-up {base / wall:5.2f}x (load {la})")


def _same_json(a: bytes, b: bytes) -> bool:
    """The same JSON documents but for the option ``workers`` (the number each run was given)."""
    import json

    if a[a.index(b'"source":') :] != b[b.index(b'"source":') :]:
        return False
    head_a, head_b = (x[: x.index(b'"source":')].rstrip(b",") + b"}" for x in (a, b))
    da, db = json.loads(head_a), json.loads(head_b)
    da["options"].pop("workers"), db["options"].pop("workers")
    return da == db


def _command(ks, repeats, R, th, D, s) -> None:
    """The whole command: CSV in, CSV and JSON out (no HTML), --workers k with CAPRED_PROCESSES=k."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        csv = tmp / "cases.csv"
        suction_file(csv, R, th, D, s)
        env = installed_env(tmp / "pycache")

        def cli(k):
            cmd = [sys.executable, "-m", "capred", "bridge", "solve", str(csv), "--out", str(tmp / f"o{k}")]
            return run([*cmd, "--no-html", "--workers", str(k)], env={**env, "CAPRED_PROCESSES": str(k)})[0]

        cli(ks[0])  # warm the file cache and the bytecode
        loads = [os.getloadavg()[0]]
        t = interleaved({f"{k}": (lambda k=k: cli(k)) for k in ks}, repeats)
        loads.append(os.getloadavg()[0])
        first = (tmp / f"o{ks[0]}" / "solve.csv").read_bytes()
        first_json = (tmp / f"o{ks[0]}" / "solve.json").read_bytes()
        for k in ks[1:]:
            assert (tmp / f"o{k}" / "solve.csv").read_bytes() == first, "CSV outputs differ"
            assert _same_json((tmp / f"o{k}" / "solve.json").read_bytes(), first_json), "JSON outputs differ"
        print(
            "capred bridge solve (CSV in, CSV and JSON out, no HTML; outputs byte-identical; "
            f"load {loads[0]:.1f} -> {loads[1]:.1f}):"
        )
        base = t[str(ks[0])]
        for k in ks:
            m = t[f"{k}"]
            print(
                f"  --workers {k:>2}: {m.wall:7.2f} s wall, {m.cpu:7.2f} s CPU; speed-up {base.wall / m.wall:5.2f}x; "
                f"CPU {m.cpu / base.cpu:4.2f}x one process's; walls {', '.join(f'{r.wall:.2f}' for r in m.repeats)}"
            )


if __name__ == "__main__":
    args = sys.argv[1:4]
    main(
        int(args[0]) if args else 1_000_000,
        args[1] if len(args) > 1 else "1,2",
        int(args[2]) if len(args) > 2 else 1,
        "--command-only" not in sys.argv,
    )
