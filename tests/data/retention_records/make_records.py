"""Write the synthetic retention records of this folder from known models (see SOURCES.md).

- evaporation.csv: an evaporation (HYPROP-type) record, a smooth van Genuchten drying curve read every few minutes
  (head 2 to 800 cm, 120 readings) with Gaussian scatter of 0.002 m³/m³ in θ and five dips of 0.03 cm in head (a
  tensiometer's noise): one drying branch.
- scanning_loops.csv: main drying to 30 kPa, a first-order scanning wetting curve to 3 kPa, a second-order scanning
  drying curve back to 30 kPa (closing there), the main drying curve on to 1000 kPa, the main wetting curve back
  to 0.1 kPa; main curves of Kool & Parker (1987) (θ_r 0.05, θ_s 0.45, n 2, α_d 0.1 1/kPa, α_w 0.2 1/kPa), the
  scanning curves by Parker & Lenhard's (1987) scaling (capred.physics.retention.scanning_water), scatter 0.003.
  scanning_loops_labelled.csv: the same readings with the branch each was generated on (drying, scanning,
  wetting) in a 'branch' column.
- entrapped_air.csv: a drying branch (θ_s 0.47) and a wetting branch that returns to θ_s 0.32 only (entrapped
  air), van Genuchten with θ_r 0.05, n 2.2, α_d 0.05 1/kPa, α_w 0.1 1/kPa, scatter 0.003.

Run from the repository root: python tests/data/retention_records/make_records.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2]))

from capred.physics import retention as rp  # noqa: E402

CM = 98.1  # Pa per cm of water head (the γ_w of capred: 9.81 kN/m³)

#: the scanning-loop record's main curves (SI: Pa, 1/Pa)
LOOP = dict(y_r=0.05, y_s=0.45, n=2.0, alpha_d=1e-4, alpha_w=2e-4)
#: the evaporation record's curve
EVAPORATION = dict(y_r=0.06, y_s=0.41, alpha=1 / (40 * CM), n=1.9)


def evaporation(seed: int = 1):
    """Head [cm] and θ of the evaporation record (readings in time order)."""
    rng = np.random.default_rng(seed)
    h = np.geomspace(2.0, 800.0, 120)
    p = EVAPORATION
    theta = rp.vg_water(h * CM, p["y_r"], p["y_s"], p["alpha"], p["n"]) + rng.normal(0, 0.002, h.size)
    for i in (20, 40, 60, 80, 100):  # the suction dips by a few hundredths of a cm
        h[i] = h[i - 1] - 0.03
    return h, theta


def scanning_loops(seed: int = 2):
    """Suction [kPa], θ and the true branch of each reading of the scanning-loop record."""
    p = LOOP
    rng = np.random.default_rng(seed)

    def main_drying(s):
        return rp.vg_water(s, p["y_r"], p["y_s"], p["alpha_d"], p["n"])

    def main_wetting(s):
        return rp.vg_water(s, p["y_r"], p["y_s"], p["alpha_w"], p["n"])

    s1 = np.geomspace(100, 30e3, 20)
    s2 = np.geomspace(30e3, 3e3, 10)[1:]
    y2 = rp.scanning_water(s2, main_wetting, 30e3, main_drying(30e3), 0.0, p["y_s"])
    s3 = np.geomspace(3e3, 30e3, 10)[1:]
    y3 = rp.scanning_water(s3, main_drying, 3e3, y2[-1], 30e3, main_drying(30e3))
    s4 = np.geomspace(30e3, 1e6, 15)[1:]
    s5 = np.geomspace(1e6, 100, 30)[1:]
    s = np.concatenate([s1, s2, s3, s4, s5])
    y = np.concatenate([main_drying(s1), y2, y3, main_drying(s4), main_wetting(s5)])
    label = ["drying"] * 20 + ["scanning"] * 18 + ["drying"] * 14 + ["wetting"] * 29
    return s / 1e3, y + rng.normal(0, 0.003, s.size), label


def entrapped_air(seed: int = 3):
    """Suction [kPa], θ and branch of the entrapped-air record."""
    rng = np.random.default_rng(seed)
    sd = np.geomspace(200, 1e6, 25)
    sw = sd[::-1]
    yd = rp.vg_water(sd, 0.05, 0.47, 5e-5, 2.2)
    yw = rp.vg_water(sw, 0.05, 0.32, 1e-4, 2.2)
    s = np.concatenate([sd, sw])
    y = np.concatenate([yd, yw]) + rng.normal(0, 0.003, s.size)
    return s / 1e3, y, ["drying"] * sd.size + ["wetting"] * sw.size


def main():
    h, theta = evaporation()
    with open(HERE / "evaporation.csv", "w", encoding="utf-8") as f:
        f.write("head [cm],theta [-]\n")
        f.writelines(f"{a:.4f},{b:.5f}\n" for a, b in zip(h, theta))
    s, y, label = scanning_loops()
    with open(HERE / "scanning_loops.csv", "w", encoding="utf-8") as f:
        f.write("suction [kPa],theta [-]\n")
        f.writelines(f"{a:.6g},{b:.5f}\n" for a, b in zip(s, y))
    with open(HERE / "scanning_loops_labelled.csv", "w", encoding="utf-8") as f:
        f.write("suction [kPa],theta [-],branch\n")
        f.writelines(f"{a:.6g},{b:.5f},{c}\n" for a, b, c in zip(s, y, label))
    s, y, label = entrapped_air()
    with open(HERE / "entrapped_air.csv", "w", encoding="utf-8") as f:
        f.write("suction [kPa],theta [-],branch\n")
        f.writelines(f"{a:.6g},{b:.5f},{c}\n" for a, b, c in zip(s, y, label))


if __name__ == "__main__":
    main()
