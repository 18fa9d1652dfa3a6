"""Generate compression_oedometer.csv: a synthetic oedometer test with known lines and yield stress.

Run ``python sample_data/generate_compression.py``. Deterministic (numpy ``default_rng(20261129)``); the truth is
documented in docs/user_guide/compression.md:

- first loading on the smooth bilinear curve of capred.physics.compression with e_y = 0.95, C_r = 0.04,
  C_c = 0.40 (lambda = 0.1737), sigma'_y = 120 kPa, bend width w = 0.12 decades;
- unloading from 800 kPa to 50 kPa and reloading to 800 kPa on a straight line C_s = 0.05 (kappa = 0.0217);
- a last loading step to 1600 kPa on the virgin line;
- Gaussian scatter of standard deviation 0.002 in e, rounded to 4 decimals.
"""

from pathlib import Path

import numpy as np

E_Y, C_R, C_C, SIGMA_Y, W, C_S, SD = 0.95, 0.04, 0.40, 120.0, 0.12, 0.05, 0.002


def curve(sigma):
    t = np.log10(np.asarray(sigma, float) / SIGMA_Y)
    return E_Y - C_R * t - (C_C - C_R) * W * np.logaddexp(0.0, np.log(10.0) * t / W) / np.log(10.0)


def main() -> None:
    rng = np.random.default_rng(20261129)
    first = [10, 20, 40, 60, 80, 100, 120, 150, 200, 300, 400, 800]
    rows = [(s, "loading", curve(s)) for s in first]
    e_r = float(curve(800.0))
    for s in (400, 200, 100, 50):
        rows.append((s, "unloading", e_r + C_S * np.log10(800.0 / s)))
    for s in (100, 200, 400, 800):
        rows.append((s, "reloading", e_r + C_S * np.log10(800.0 / s)))
    rows.append((1600, "loading", E_Y - C_C * np.log10(1600.0 / SIGMA_Y)))
    out = [
        "# synthetic oedometer test (capred sample_data/generate_compression.py); truth in docs/user_guide/compression.md",
        "step,stage,sigma_v [kPa],e",
    ]
    for i, (s, stage, e) in enumerate(rows):
        out.append(f"{i},{stage},{s:g},{e + rng.normal(0.0, SD):.4f}")
    Path(__file__).with_name("compression_oedometer.csv").write_text("\n".join(out) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
