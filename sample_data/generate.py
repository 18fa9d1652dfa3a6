"""Regenerate the synthetic sample files: ``python -m capred.sample_data.generate [DIR]``.

Deterministic (fixed seed). The procedure is described in README.md here.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

G = 9.81  # m/s^2
GAMMA_W = 9810.0  # N/m^3
SURFACE_TENSION = 0.0728  # N/m
BOX_AREA_CM2 = 36.0  # 60 mm x 60 mm shear box
CAP_MASS_G = 120.0
ADDED_WET_G = (0.0, 77.47)  # the thesis's added weights for the wet tests
ADDED_DRY_G = (0.0, 77.47, 200.0, 400.0, 700.0, 1000.0)

# material: (dry c [kPa], tan phi, R [mm], V_v [cm^3], heads z1 [cm],
#            van Genuchten retention alpha [1/cm], n, residual S_R)
MATERIALS = {
    "steel_2mm": (0.3452, 0.7146, 1.0, 27.0, (2, 4, 6, 8, 10, 14, 20), 0.20, 5.0, 0.02),
    "sand_208-417um": (0.0721, 0.7955, 0.156, 30.5, (10, 20, 30, 40, 50, 60, 80), 0.028, 6.0, 0.04),
}


def retention(z1_cm, alpha, n, s_res):
    """S_R from a van Genuchten curve in head (m = 1 - 1/n)."""
    se = (1.0 + (alpha * z1_cm) ** n) ** -(1.0 - 1.0 / n)
    return s_res + (1.0 - s_res) * se


def make_shear(rng) -> str:
    lines = [
        "# capred sample: SYNTHETIC hanging-column direct-shear tests (not measured data).",
        "# Made by sample_data/generate.py, seed 20261121; see sample_data/README.md.",
        "test_id,material,condition,z1 [cm],z2 [cm^3],V_v [cm^3],added_mass [g],cap_mass [g],"
        "box_area [cm^2],R [mm],tau_max [kPa]",
    ]
    area = BOX_AREA_CM2 * 1e-4
    for mat, (c, tan_phi, r_mm, v_v, heads, alpha, n, s_res) in MATERIALS.items():
        tag = mat.split("_")[0][:2].upper()
        k = 0
        for added in ADDED_DRY_G:
            for _ in range(2):
                k += 1
                sigma = (CAP_MASS_G + added) * 1e-3 * G / area / 1e3
                tau = c + sigma * tan_phi + rng.normal(0.0, 0.02 + 0.02 * sigma * tan_phi)
                lines.append(f"{tag}-D{k:02d},{mat},dry,,,{v_v},{added},{CAP_MASS_G},{BOX_AREA_CM2},{r_mm},{tau:.3f}")
        k = 0
        for added in ADDED_WET_G:
            for z1 in heads:
                k += 1
                s_r = retention(z1, alpha, n, s_res)
                z2 = round(v_v * (1.0 - s_r), 1)  # burette read to 0.1 cm^3
                s_r = (v_v - z2) / v_v
                suction = GAMMA_W * z1 * 1e-2
                x = (2.0 * np.pi * s_r / 3.0) ** (1.0 / 3.0)
                # "truth" = Own 2 (thesis conclusion: chi = (2 pi S_R/3)^(2/3) beats S_R)
                sigma = (CAP_MASS_G + added) * 1e-3 * G / area
                sigma_eff = sigma + x**2 * suction + 2 * SURFACE_TENSION / (r_mm * 1e-3) * x
                tau = (c * 1e3 + sigma_eff * tan_phi) / 1e3
                tau += rng.normal(0.0, 0.03 + 0.04 * tau)
                lines.append(
                    f"{tag}-W{k:02d},{mat},wet,{z1},{z2},{v_v},{added},{CAP_MASS_G},{BOX_AREA_CM2},{r_mm},{tau:.3f}"
                )
    return "\n".join(lines) + "\n"


# Gavet silt (Prunier et al. 2024): envelope and failure deviators reconstructed from the
# paper's Tables 2 and 3 (see README.md here and tests/test_triaxial_published.py).
GAVET_C_KPA, GAVET_PHI_DEG = 2.795, 31.523
GAVET_UNSAT_Q_KPA = {0.0: 150.2, 100.0: 317.6, 150.0: 396.7}
GAVET_SAT_P0_KPA = (30.0, 50.0, 100.0, 150.0)
GAVET_S0_KPA = 55.0


def _drained_q(p0, c, phi_deg):
    s = np.sin(np.radians(phi_deg))
    kp = (1 + s) / (1 - s)
    return (kp - 1) * p0 + 2 * c * np.sqrt(kp)


def make_triaxial() -> str:
    lines = [
        "# capred sample: Gavet silt triaxial tests RECONSTRUCTED from Prunier et al. (2024), Tables 2-3.",
        "# The paper gives failure points only in figures; see sample_data/README.md for how these were made.",
        "test_id,condition,sigma3 [kPa],q_f [kPa],p0 [kPa],s0 [kPa]",
    ]
    for p0 in GAVET_SAT_P0_KPA:
        q = _drained_q(p0, GAVET_C_KPA, GAVET_PHI_DEG)
        lines.append(f"SAT-{p0:g},saturated,{p0:g},{q:.1f},{p0:g},")
    for p0, q in GAVET_UNSAT_Q_KPA.items():
        lines.append(f"UNSAT-{p0:g},unsaturated,{p0:g},{q:.1f},{p0:g},{GAVET_S0_KPA:g}")
    return "\n".join(lines) + "\n"


def make_triaxial_curves(rng) -> str:
    """Synthetic q(eps_a) curves peaking at the reconstructed failure deviators."""
    lines = [
        "# capred sample: SYNTHETIC stress-strain curves (hyperbolic rise, softening after the peak).",
        "test_id,axial_strain [%],q [kPa],vol_strain [%]",
    ]
    for p0, q_f in GAVET_UNSAT_Q_KPA.items():
        eps_f = 2.0 + p0 / 100.0  # % axial strain at the peak
        for eps in np.round(np.arange(0.0, 2.0 * eps_f + 1e-9, 0.25), 2):
            x = eps / eps_f
            q = q_f * (2 * x / (1 + x * x)) if x <= 1 else q_f * (1 - 0.25 * (x - 1))
            q += rng.normal(0.0, 0.002 * q_f) if 0 < eps != eps_f else 0.0
            ev = -0.3 * eps + 0.04 * eps**2
            lines.append(f"UNSAT-{p0:g},{eps:.2f},{q:.2f},{ev:.3f}")
    return "\n".join(lines) + "\n"


def make_retention(rng) -> str:
    """Hanging-column retention of the sand: drying then wetting branch (hysteresis)."""
    lines = [
        "# capred sample: SYNTHETIC hanging-column retention data for sand 208-417 um (drying, then wetting).",
        "# Made by sample_data/generate.py; see sample_data/README.md.",
        "z1 [cm],z2 [cm^3],V_v [cm^3],branch",
    ]
    v_v = 30.5
    branches = (
        ("drying", (2, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 60, 70, 80, 100, 120), 0.028, 6.0),
        ("wetting", (120, 100, 80, 60, 50, 40, 35, 30, 25, 20, 15, 10, 5), 0.045, 5.0),
    )
    for name, heads, alpha, n in branches:
        for z1 in heads:
            s_r = retention(z1, alpha, n, 0.04)
            s_r = min(1.0, max(0.0, s_r + rng.normal(0.0, 0.01)))
            lines.append(f"{z1},{round(v_v * (1.0 - s_r), 1)},{v_v},{name}")
    return "\n".join(lines) + "\n"


def main(folder: str | None = None) -> None:
    out = Path(folder) if folder else Path(__file__).parent
    rng = np.random.default_rng(20261121)
    (out / "shear_tests.csv").write_text(make_shear(rng))
    (out / "triaxial_tests.csv").write_text(make_triaxial())
    (out / "triaxial_curves.csv").write_text(make_triaxial_curves(rng))
    (out / "retention.csv").write_text(make_retention(rng))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
