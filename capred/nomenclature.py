"""The one glossary of quantity names, symbols and output units.

Schemas, result columns, JSON keys and plot labels draw their names from here.
Output columns carry the unit in brackets, e.g. ``sigma_N [kPa]``.
"""
from __future__ import annotations

# name: (symbol for plots, output unit, SI -> output factor, description)
QUANTITIES: dict[str, tuple[str, str, float, str]] = {
    "sigma_N": ("σ_N", "kPa", 1e-3, "total normal stress on the shear plane"),
    "sigma_eff": ("σ'_N", "kPa", 1e-3, "effective normal stress"),
    "suction": ("Δu", "kPa", 1e-3, "matric suction u_a - u_w"),
    "S_R": ("S_R", "-", 1.0, "degree of saturation"),
    "tau_max": ("τ_max", "kPa", 1e-3, "measured peak shear stress"),
    "tau_pred": ("τ_pred", "kPa", 1e-3, "predicted shear strength"),
    "chi1": ("χ1", "-", 1.0, "own approximation 1, (2π S_R/3)^(2/3)"),
    "chi2": ("χ2", "kPa", 1e-3, "own approximation 2 term, (2γ/R)(2π S_R/3)^(1/3)"),
    "c": ("c", "kPa", 1e-3, "cohesion intercept"),
    "z1": ("z1", "cm", 1e2, "height of the sample above the water level"),
    "z2": ("z2", "cm^3", 1e6, "air volume entered, read on the burette"),
    "V_v": ("V_v", "cm^3", 1e6, "void volume of the sample"),
    "R": ("R", "mm", 1e3, "particle radius"),
}


def label(name: str) -> str:
    """Axis label 'symbol [unit]' for a quantity."""
    symbol, unit, _, _ = QUANTITIES[name]
    return f"{symbol} [{unit}]"


def column(name: str, suffix: str = "") -> str:
    """Output column name with its unit, e.g. 'tau_pred_bishop [kPa]'."""
    unit = QUANTITIES[name][1]
    return f"{name}{suffix} [{unit}]"


def to_output(name: str, value):
    """Convert an SI value of a quantity to its output unit."""
    return value * QUANTITIES[name][2]
