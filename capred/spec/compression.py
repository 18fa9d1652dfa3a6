"""`capred compression`: what it reads (``SCHEMA``) and its options (``CompressionOptions``).

Numpy-free (see :mod:`capred.spec`).
"""

from __future__ import annotations

from dataclasses import dataclass

from .columns import Column
from .options import Options, StrOptions

SCHEMA = [
    Column("step", "dimensionless", "-", "reading number", ("reading", "point"), None, decisive=False),
    Column(
        "stage",
        "text",
        None,
        "loading, unloading or reloading (default: from the stress history)",
        ("branch", "stage_label"),
    ),
    Column(
        "sigma_eff",
        "pressure",
        "kPa",
        "effective stress: vertical (oedometer) or mean p' (isotropic)",
        ("sigma_v", "sigma_v_eff", "effective_stress", "vertical_stress", "p_eff", "p_prime", "sigma", "p"),
        "positive",
    ),
    Column("e", "dimensionless", "-", "void ratio", ("void_ratio",), "positive"),
    Column("height", "length", "mm", "specimen height (with --solids-height)", ("H", "specimen_height"), "positive"),
]


TESTS = ("oedometer", "isotropic")


@dataclass(frozen=True)
class CompressionOptions(Options):
    """Options of `capred compression`.

    Attributes
    ----------
    test : str
        ``oedometer`` (σ'_v, one-dimensional) or ``isotropic`` (p'); names the stress in the outputs.
    solids_height : float, optional
        Height of the solids H_s [m] when the file gives the specimen height: e = H/H_s − 1.
    reference_stress : float
        Stress at which e_N on the normal compression line is read [Pa]; default 1 kPa.
    """

    QUANTITIES = {"solids_height": "solids_height", "reference_stress": "reference_stress"}
    CONSTRAINTS = {"test": StrOptions(TESTS)}

    test: str = "oedometer"
    solids_height: float | None = None
    reference_stress: float = 1.0e3


__all__ = ["SCHEMA", "TESTS", "CompressionOptions"]
