"""Exact bridges per second (issue 3), on one core, against scipy's solve_ivp one case at a time.

Run: python benchmarks/bench_bridge.py [n_cases]
Pin to one core with `taskset -c 0` for the one-core figure.
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time

import numpy as np
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
    sol = solve_ivp(rhs, (0, 50), [0.0, np.sin(beta), 0.5 * np.pi - beta - theta, 0.0], method="DOP853",
                    rtol=rtol, atol=rtol * 1e-3, events=neck)
    x, y, _, v = sol.y_events[0][0]
    h = 1 - np.cos(beta)
    return 2 * (-x + np.cos(beta) - 1), 2 * (v - np.pi * h * h * (3 - h) / 3), 2 * y + s * y * y


def main(n: int = 100_000) -> None:
    rng = np.random.default_rng(0)
    th = np.radians(rng.uniform(0, 60, n))
    s = 10 ** rng.uniform(-1, 3, n)
    beta = rng.uniform(0.02, 0.98, n) * (0.5 * np.pi - th)
    br.geometry(beta[:100], th[:100], s[:100])  # warm up

    t0 = time.perf_counter()
    gap, vol, F, _ = br.geometry(beta, th, s)
    t_direct = time.perf_counter() - t0

    m = 300
    t0 = time.perf_counter()
    ref = np.array([ivp_bridge(beta[i], th[i], s[i]) for i in range(m)])
    t_ivp = (time.perf_counter() - t0) / m
    err = np.max(np.abs(ref[:, 2] / F[:m] - 1))

    D = np.clip(gap, 0, None) * rng.uniform(0, 1, n)
    t0 = time.perf_counter()
    b2, st = br.solve_for_suction(th, s, D)
    t_suction = time.perf_counter() - t0

    k = 5000
    t0 = time.perf_counter()
    _, _, st_v = br.solve_for_volume(th[:k], np.abs(vol[:k]), np.clip(gap[:k], 0, None))
    t_volume = (time.perf_counter() - t0) / k

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "capred", "bridge", "curve", "--points", "2000", "--out", tmp],
                       check=True, capture_output=True)
        t_curve_cli = time.perf_counter() - t0
    from capred.pipelines.bridge import bridge_curve

    t0 = time.perf_counter()
    bridge_curve(points=2000)
    t_curve = time.perf_counter() - t0

    print(f"direct bridges (beta, theta, s*) -> gap, V, F:   {n / t_direct:12,.0f} per s")
    print(f"same with solve_ivp (DOP853, one by one):        {1 / t_ivp:12,.0f} per s   "
          f"ratio {t_ivp * n / t_direct:,.0f}x; max rel. force difference {err:.1e}")
    print(f"suction-controlled solve (gap, s*) -> bridge:    {n / t_suction:12,.0f} per s   "
          f"({np.mean(st == 0):.0%} with a bridge); ratio vs solve_ivp direct {t_ivp * n / t_suction:,.0f}x")
    print(f"volume-controlled solve (gap, V*) -> bridge:     {1 / t_volume:12,.0f} per s")
    print(f"bridge curve, 2000 points: {t_curve:.2f} s in-process, {t_curve_cli:.2f} s through the CLI (with PNG)")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 100_000)
