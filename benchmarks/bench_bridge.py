"""Bridge solvers in process, one core, as ratios measured in one run (issues 3, 13 and 20).

1. Direct bridges (beta, theta, s*) -> gap, volume, force against scipy's
   solve_ivp (DOP853) one bridge at a time, at equal accuracy.
2. Volume-controlled against suction-controlled solves of the same bridges
   (`solve_for_volume` on (V*, gap*) against `solve_for_suction` on
   (s*, gap*), every row with a bridge), at contact and at a gap, for equal
   spheres and for mixed partners (unequal spheres and planes): target
   <= 3x. Rows with no bridge (beyond rupture) are timed apart: most are
   settled in bulk, the rest take the scan of the arc.
3. The suction-controlled solver against solve_ivp charged only for the rows
   that have a bridge.

Every comparison is interleaved (A, B, A, B, ...; median of the repeats) and
reports CPU and wall time; everything runs in this one process (one core), so
CPU seconds compare core for core.

Run: python benchmarks/bench_bridge.py [n_rows] [repeats]
"""

from __future__ import annotations

import sys

import numpy as np
from common import interleaved, ratio_line, timed
from scipy.integrate import solve_ivp

from capred.physics import bridge as br


def ivp_bridge(beta, theta, s, rtol=1e-10):
    """The same bridge by integrating the Young-Laplace ODE from the contact line to the neck (DOP853): gap,
    volume and force in units of R and gamma."""

    def rhs(_, u):
        return [-np.cos(u[2]), -np.sin(u[2]), -(s + np.cos(u[2]) / u[1]), np.pi * u[1] ** 2 * np.cos(u[2])]

    def neck(_, u):
        return u[2]

    neck.terminal, neck.direction = True, -1
    sol = solve_ivp(
        rhs,
        (0, 50),
        [0.0, np.sin(beta), 0.5 * np.pi - beta - theta, 0.0],
        method="DOP853",
        rtol=rtol,
        atol=rtol * 1e-3,
        events=neck,
    )
    x, y, _, v = sol.y_events[0][0]
    h = 1 - np.cos(beta)
    return 2 * (-x + np.cos(beta) - 1), 2 * (v - np.pi * h * h * (3 - h) / 3), 2 * y + s * y * y


def cli_cases(n: int, seed: int = 0):
    """theta [rad], s* and gap* of `bench_bridge_cli.py`'s rows: R 0.1-2 mm, theta 0-60 deg, suction 0.1-30 kPa,
    gaps up to 0.05 R (gamma = 0.0728 N/m)."""
    rng = np.random.default_rng(seed)
    R = rng.uniform(0.1, 2.0, n)
    th = np.radians(rng.uniform(0.0, 60.0, n))
    s = 10 ** rng.uniform(-1, 1.5, n) * 1e3 * R * 1e-3 / 0.0728
    return th, s, rng.uniform(0.0, 0.05, n), rng


def bridge_rows(n: int, partners: str, where: str, seed: int = 0):
    """Rows (theta, s*, gap*, rho, V*) that all have a bridge: the suction-controlled rows of `cli_cases` at
    contact or at their gap, the volume of each bridge found."""
    th, s, D, rng = cli_cases(n, seed)
    rho = np.ones(n)
    if partners == "mixed":
        u = rng.uniform(size=n)
        rho = np.where(u < 0.3, np.inf, 10 ** rng.uniform(-0.5, 1.0, n))
    if where == "contact":
        D = np.zeros(n)
    b, st = br.solve_for_suction(th, s, D, rho)
    ok = st == 0
    V = br.bridge(b[ok], th[ok], s[ok], rho[ok]).volume
    return th[ok], s[ok], D[ok], rho[ok], V


def main(n: int = 20_000, repeats: int = 5) -> None:
    print(f"capred bridge solvers, {n:,} rows, {repeats} interleaved repeats (medians), one process\n")

    # 1. direct bridges against solve_ivp at equal accuracy
    rng = np.random.default_rng(0)
    th = np.radians(rng.uniform(0, 60, n))
    s = 10 ** rng.uniform(-1, 3, n)
    beta = rng.uniform(0.02, 0.98, n) * (0.5 * np.pi - th)
    m = 200
    mine = br.geometry(beta[:m], th[:m], s[:m])[2]
    t = interleaved(
        {
            "capred": lambda: br.geometry(beta, th, s),
            "solve_ivp": lambda: [ivp_bridge(beta[i], th[i], s[i], 1e-12) for i in range(m)],
        },
        repeats,
    )
    err = np.max(np.abs(np.array([ivp_bridge(beta[i], th[i], s[i], 1e-12)[2] for i in range(m)]) / mine - 1))
    print(
        f"direct bridges: capred {n / t['capred'].cpu:,.0f}/s CPU ({n / t['capred'].wall:,.0f}/s wall); "
        f"solve_ivp rtol 1e-12 {m / t['solve_ivp'].cpu:,.0f}/s CPU (max force difference {err:.1e})"
    )
    print("  " + ratio_line("capred over solve_ivp per bridge, CPU", t["solve_ivp"].cpu / m, t["capred"].cpu / n))

    # 2. volume-controlled against suction-controlled, the same bridges
    print("\nvolume-controlled (V*, gap*) against suction-controlled (s*, gap*) solves of the same bridges")
    for partners in ("equal", "mixed"):
        for where in ("contact", "gap"):
            th, s, D, rho, V = bridge_rows(n, partners, where)
            k = th.size
            out, _ = timed(lambda: br.solve_for_volume(th, V, D, rho))
            agree = np.max(np.abs(out[1] / s - 1)[out[2] == 0])  # over the rows the volume solver verified
            t = interleaved(
                {
                    "suction": lambda: br.solve_for_suction(th, s, D, rho),
                    "volume": lambda: br.solve_for_volume(th, V, D, rho),
                },
                repeats,
            )
            print(
                f"  {partners:5s} partners at {where:7s} ({k:,} rows, {np.mean(out[2] == 0):.2%} ok, "
                f"max |s_V / s - 1| {agree:.1e}): suction {k / t['suction'].cpu:,.0f} rows/s CPU "
                f"({k / t['suction'].wall:,.0f} wall), volume {k / t['volume'].cpu:,.0f} rows/s CPU "
                f"({k / t['volume'].wall:,.0f} wall)"
            )
            print(
                "    "
                + ratio_line("volume over suction, CPU", t["volume"].cpu, t["suction"].cpu, "<= 3x")
                + "; "
                + ratio_line("wall", t["volume"].wall, t["suction"].wall)
            )
    th, s, D, rho, V = bridge_rows(2000, "equal", "gap")
    far = 3.0 * br.lian_rupture_gap(th, V) + D  # beyond the rupture distance of each volume
    out, tb = timed(lambda: br.solve_for_volume(th, V, far, rho))
    print(
        f"  rows beyond rupture (no bridge, status {sorted(set(out[2].tolist()))}): "
        f"{th.size / tb.cpu:,.0f} rows/s CPU (most settled in bulk, the rest by the scan of the arc; not part of the target)"
    )

    # 3. the suction-controlled solver against solve_ivp charged only for the rows that have a bridge
    th, s, D, _ = cli_cases(n)
    b, st = br.solve_for_suction(th, s, D)
    ok = np.flatnonzero(st == 0)
    sample = ok[:200]
    t = interleaved(
        {
            "capred": lambda: br.solve_for_suction(th, s, D),
            "solve_ivp": lambda: [ivp_bridge(b[i], th[i], s[i], 1e-12) for i in sample],
        },
        repeats,
    )
    per_bridge = t["solve_ivp"].cpu / sample.size
    print(
        f"\nsuction-controlled solve: {n:,} rows ({ok.size / n:.0%} with a bridge) in {t['capred'].cpu:.3f} s CPU; "
        f"solve_ivp {per_bridge * 1e3:.3f} ms CPU per bridge"
    )
    print(
        "  "
        + ratio_line(
            "solve_ivp for the rows with a bridge over capred for every row, CPU", per_bridge * ok.size, t["capred"].cpu
        )
    )


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
