"""Write triaxial_failure_states.csv, the synthetic sample of `capred triaxial` (numpy default_rng(20261129)).

Three residual-soil-like materials, no saturated test, 8-14 tests each at net cell pressures of 25-300 kPa and
suctions of 20-400 kPa; strength from Bishop's effective stress with chi = S_r on an envelope c', phi' per
material, S_r falling with suction (van Genuchten-like), a scatter of 5 % of q_f (growing with stress). The
sample state is given as rho_d, G_s and w: S_r, e, n follow by the phase relations (capred.physics.phase).
Illustrative numbers, not measurements.
"""

import math
from pathlib import Path

import numpy as np

SOILS = {  # c' [kPa], phi' [deg], G_s, rho_d [kg/m^3], van Genuchten alpha [1/kPa], n, tests
    "granite residual": (6.0, 34.0, 2.65, 1650.0, 0.05, 1.6, 14),
    "volcanic residual": (12.0, 30.0, 2.72, 1450.0, 0.02, 1.4, 10),
    "mudstone residual": (18.0, 25.0, 2.70, 1550.0, 0.008, 1.3, 8),
}


def main() -> None:
    rng = np.random.default_rng(20261129)
    lines = ["test_id,material,sigma3 [kPa],q_f [kPa],suction [kPa],rho_d [kg/m^3],G_s,w"]
    for k, (name, (c, phi, gs, rho_d, alpha, n, count)) in enumerate(SOILS.items()):
        kp = (1 + math.sin(math.radians(phi))) / (1 - math.sin(math.radians(phi)))
        e = gs * 1000.0 / rho_d - 1
        for j in range(count):
            s3 = float(rng.choice([25, 50, 100, 200, 300]))
            s = float(rng.choice([20, 50, 100, 200, 400]))
            sr = (1 + (alpha * s) ** n) ** (-(1 - 1 / n))
            q = (kp - 1) * (s3 + sr * s) + 2 * math.sqrt(kp) * c
            q *= 1 + 0.05 * rng.normal()
            w = sr * e / gs
            lines.append(f"{'GVM'[k]}{j + 1:02d},{name},{s3:g},{q:.1f},{s:g},{rho_d:g},{gs:g},{w:.4f}")
    Path(__file__).with_name("triaxial_failure_states.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
