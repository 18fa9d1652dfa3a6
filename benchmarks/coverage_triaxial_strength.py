"""Coverage of the intervals of `capred triaxial` by simulation: the tables of docs/user_guide/triaxial_strength.md.

Run: python benchmarks/coverage_triaxial_strength.py (about 30 s). Fixed seeds: the same numbers on every run.
1000 simulated materials per row, 6-20 tests each, sigma3 and s uniform in 20-400 kPa, c' = 10 kPa, phi' = 30 deg,
phi_b = 18 deg (triaxial compression); 30 new tests per material for q_f, split by thirds of the sigma3 range.
"""

import math

import numpy as np

from capred.fitting.extended_mc import coefficients, fit_extended_mc
from capred.pipelines.triaxial_strength import bounds_on_envelope

A, B, D = coefficients("compression", 10e3, 30.0, math.tan(math.radians(18)))
SCATTER = {"6 % of q_f": lambda mu: 0.06 * mu, "2 kPa + 4 % of q_f": lambda mu: 2e3 + 0.04 * mu}
SCATTER["15 kPa"] = lambda mu: np.full(np.shape(mu), 15e3)


def parameters_and_new_tests(errors, sd, reps=1000, seed=1):
    rng = np.random.default_rng(seed)
    hits, newc, newn, chosen = np.zeros(3), np.zeros(3), np.zeros(3), 0
    for _ in range(reps):
        n = rng.integers(6, 21)
        x, s = rng.uniform(20e3, 400e3, n), rng.uniform(20e3, 400e3, n)
        mu = A + B * x + D * s
        f = fit_extended_mc(x, s, mu + rng.normal(size=n) * sd(mu), "compression", errors)
        chosen += f.errors == "proportional"
        p = f.params
        for k, (name, true) in enumerate((("c_eff_kPa", 10), ("phi_eff_deg", 30), ("phi_b_deg", 18))):
            hits[k] += p[name].ci95[0] <= true <= p[name].ci95[1]
        x0, s0 = rng.uniform(20e3, 400e3, 30), rng.uniform(20e3, 400e3, 30)
        mu0 = A + B * x0 + D * s0
        y0 = mu0 + rng.normal(size=30) * sd(mu0)
        lo, hi = f.prediction_interval(x0, s0)
        third = np.minimum(((x0 - 20e3) / (380e3 / 3)).astype(int), 2)
        for k in range(3):
            newn[k] += np.sum(third == k)
            newc[k] += np.sum(((lo <= y0) & (y0 <= hi))[third == k])
    return hits / reps, newc / newn, chosen / reps


def bounds(reps=1000, seed=4):
    """Coverage of the spherical and lower bounds' intervals (t SE) of three fixed failure states."""
    rng = np.random.default_rng(seed)
    x0, q0 = np.array([50e3, 200e3, 380e3]), np.array([400e3, 900e3, 1500e3])
    true = bounds_on_envelope("compression", x0, q0, 10e3, 30.0, np.zeros((2, 2)))
    hit = np.zeros((2, 3))
    for _ in range(reps):
        n = rng.integers(6, 21)
        x, s = rng.uniform(20e3, 400e3, n), rng.uniform(20e3, 400e3, n)
        mu = A + B * x + D * s
        f = fit_extended_mc(x, s, mu + rng.normal(size=n) * 0.06 * mu, "compression", "either")
        c, phi, _ = f.envelope
        got = bounds_on_envelope("compression", x0, q0, c, phi, f.derived_covariance()[:2, :2])
        for k, name in enumerate(("spherical_p_cap", "lower_sigma3_cap")):
            hit[k] += np.abs(got[name] - true[name]) <= f.t * got[name + "_se"]
    return hit / reps


def sigma_cap(reps=1000, seed=9):
    """Coverage of sigma_cap +/- t SE of 5 new tests per material (shear_analysis.back_analysis on the s -> 0
    line of the extended fit), where the strength is the plane: true sigma_cap = d s / b."""
    from capred.pipelines import shear_analysis as sa

    rng = np.random.default_rng(seed)
    hit = tot = 0
    for _ in range(reps):
        n = rng.integers(6, 21)
        x, s = rng.uniform(20e3, 400e3, n), rng.uniform(20e3, 400e3, n)
        mu = A + B * x + D * s
        f = fit_extended_mc(x, s, mu + rng.normal(size=n) * 0.06 * mu, "compression", "either")
        a, b, cov = f.zero_suction_line()
        x0, s0 = rng.uniform(20e3, 400e3, 5), rng.uniform(20e3, 400e3, 5)
        mu0 = A + B * x0 + D * s0
        y0 = mu0 + rng.normal(size=5) * 0.06 * mu0
        cap, se, _, _ = sa.back_analysis(
            y0, x0, s0, np.full(5, a), np.full(5, b), np.broadcast_to(cov, (5, 2, 2)), f.new_test_variance(x0, s0)
        )
        hit += int(np.sum(np.abs(cap - D * s0 / B) <= f.t * se))
        tot += 5
    return hit / tot


if __name__ == "__main__":
    print("| scatter of a test | --errors | c' | φ' | φ_b | q_f, low third | q_f, middle third | q_f, high third |")
    print("|---|---|---|---|---|---|---|---|")
    for label, sd in SCATTER.items():
        for errors in ("either", "proportional", "constant", "auto"):
            h, nw, ch = parameters_and_new_tests(errors, sd)
            extra = f" (proportional chosen in {100 * ch:.0f} %)" if errors == "auto" else ""
            print(f"| {label} | {errors}{extra} | " + " | ".join(f"{100 * v:.1f}" for v in (*h, *nw)) + " |")
    print("bounds (spherical, lower) at sigma3 = 50, 200, 380 kPa:", np.round(100 * bounds(), 1).tolist())
    print(f"sigma_cap of a new test: {100 * sigma_cap():.1f}")
