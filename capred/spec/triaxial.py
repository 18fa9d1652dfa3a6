"""`capred triaxial-bounds`: what it reads (``SCHEMA``) and its options (``TriaxialOptions``).

Numpy-free (see :mod:`capred.spec`): a membrane option with a unit is read by pint at run time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import CapredError, OptionError
from ..nomenclature import QUANTITIES as _GLOSSARY
from .columns import Column
from .options import Options, Probability, StrOptions

#: the drained path of an extension test from its isotropic state -> its slope dq/dp in the q-p plane [-]
#: (capred.physics.triaxial reads it from here)
EXTENSION_PATHS = {"axial-unloading": -3.0, "radial-loading": 1.5}

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column("material", "text", None, "material name (one per run: --material)", ("soil", "material_name")),
    Column(
        "condition", "text", None, "test condition", ("state", "saturation_state"), choices=("saturated", "unsaturated")
    ),
    Column(
        "sigma3", "pressure", "kPa", "sigma3", ("s3", "confining_pressure", "sigma_3", "cell_pressure"), "nonnegative"
    ),
    Column("q_f", "pressure", "kPa", "q_f", ("q", "qf", "q_max", "deviator", "q_peak"), "positive"),
    Column("sigma1", "pressure", "kPa", "sigma1", ("s1", "sigma_1"), "nonnegative"),
    Column("sigma2", "pressure", "kPa", "sigma2", ("s2", "sigma_2"), "nonnegative"),
    Column("p0", "pressure", "kPa", "p0", ("p_0", "initial_pressure"), "nonnegative"),
    Column("s0", "pressure", "kPa", "s0", ("s_0", "initial_suction", "suction"), "nonnegative"),
    Column("group", "text", None, "group", ("tensor_group",)),
    Column("D0", "length", "mm", "initial diameter", ("initial_diameter", "diameter", "d_0"), "positive"),
    Column("H0", "length", "mm", "initial height", ("initial_height", "height", "h_0"), "positive"),
    Column(
        "back_pressure",
        "pressure",
        "kPa",
        "back pressure u_b (pore-water pressure)",
        ("backpressure", "u_b", "bp", "back_pressure_kpa"),
    ),
    Column(
        "u_a", "pressure", "kPa", "pore-air pressure (axis translation)", ("pore_air_pressure", "air_pressure", "ua")
    ),
    Column(
        "branch",
        "text",
        None,
        "loading branch (compression or extension; blank: from sigma2)",
        ("loading", "triaxial_branch", "compression_extension"),
    ),
    Column(
        "pair",
        "text",
        None,
        "paired saturated test",
        ("saturated_pair", "paired_test", "sat_pair", "pair_id", "saturated_test"),
    ),
    Column(
        "strain_at_failure",
        "dimensionless",
        "-",
        "axial strain at failure",
        ("eps_f", "axial_strain_f", "axial_strain_at_failure", "strain_f"),
    ),
    Column("B", "dimensionless", "-", "Skempton's B of the test", ("b_value", "skempton_b"), "coefficient"),
    Column("D_c", "length", "mm", "diameter after consolidation", ("consolidated_diameter", "d_c"), "positive"),
    Column("H_c", "length", "mm", "height after consolidation", ("consolidated_height", "h_c"), "positive"),
    Column(
        "dV_c",
        "volume",
        "cm^3",
        "volume decrease during consolidation",
        ("consolidation_volume_change", "volume_change_consolidation", "delta_v_c"),
    ),
]


#: membrane options and their SI unit; their glossary names are used once capred.nomenclature has them
_MEMBRANE = {"membrane_thickness": ("m", "length"), "membrane_modulus": ("Pa", "pressure")}


@dataclass(frozen=True)
class TriaxialOptions(Options):
    """Options of `capred triaxial-bounds`.

    Attributes
    ----------
    c_eff : float or str, optional
        Effective cohesion c' [Pa] (or a string with a unit); with ``phi_eff``
        it replaces the fit of the saturated tests.
    phi_eff : float, optional
        Effective friction angle phi' [deg].
    confidence : float
        Confidence level of the envelope fit's intervals.
    curves : path, optional
        Raw curves (a long table with test_id, a file, a folder or a glob of
        instrument exports) whose peaks give q_f.
    membrane_thickness : float or str, optional
        Membrane thickness t_m [m] (CLI in mm); with ``membrane_modulus`` the
        deviator is corrected for the membrane (ASTM D4767); off by default.
    membrane_modulus : float or str, optional
        Young's modulus of the membrane E_m [Pa] (CLI in kPa; latex about
        1400 kPa).
    extension_path : str
        The drained path of an extension test from its isotropic state, for
        its saturated reference strength q'_sat and its EDTP bound:
        ``"axial-unloading"`` (the axial stress falls at constant cell
        pressure, slope -3 in the q-p plane; the default) or
        ``"radial-loading"`` (the cell pressure rises at constant axial
        stress, slope 3/2) (capred.physics.triaxial.EXTENSION_PATHS).
    material : str, optional
        The material analysed, from the table's ``material`` column (needed
        when it holds several: materials are never pooled).
    """

    QUANTITIES = {"c_eff": "c_eff", "phi_eff": "phi_eff", **{k: k for k in _MEMBRANE if k in _GLOSSARY}}
    CONSTRAINTS = {
        "extension_path": StrOptions(EXTENSION_PATHS, text="be one of " + ", ".join(EXTENSION_PATHS)),
        "confidence": Probability(text="lie between 0 and 1, both excluded", hint="0.95 for 95 %"),
    }

    c_eff: float | None = None  # Pa
    phi_eff: float | None = None  # deg
    confidence: float = 0.95
    curves: str | Path | None = None
    membrane_thickness: float | None = None  # m
    membrane_modulus: float | None = None  # Pa
    extension_path: str = "axial-unloading"
    material: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "_given", {"c_eff": self.c_eff, "phi_eff": self.phi_eff})  # as the caller typed
        super().__post_init__()
        if (self.c_eff is None) != (self.phi_eff is None):
            given = "c_eff" if self.phi_eff is None else "phi_eff"
            raise OptionError(
                f"give both --c-eff and --phi-eff (Python: c_eff and phi_eff), or neither; you gave "
                f"{given}={self._given[given]!r} alone"
            )
        for name, (unit, kind) in _MEMBRANE.items():
            value = getattr(self, name)
            if value is None or name in self.QUANTITIES:
                continue
            from ..units import parse_quantity  # pint: at run time only

            try:
                si = float(value) if isinstance(value, (int, float)) else parse_quantity(str(value), unit, kind)
            except (CapredError, ValueError) as exc:
                raise OptionError(f"{self.option_name(name)}: {exc}") from None
            if not math.isfinite(si) or si <= 0:
                raise OptionError(f"{self.option_name(name)}: must be > 0 (got {value!r})")
            object.__setattr__(self, name, si)
        if (self.membrane_thickness is None) != (self.membrane_modulus is None):
            raise OptionError(
                "give both --membrane-thickness and --membrane-modulus for the membrane correction, or neither"
            )

    @property
    def extension_slope(self) -> float:
        """Slope dq/dp of the extension path in the q-p plane [-] (-3 or 3/2)."""
        return EXTENSION_PATHS[self.extension_path]

    @property
    def membrane(self) -> tuple[float, float] | None:
        """(thickness [m], modulus [Pa]) of the membrane, or None (no correction)."""
        if self.membrane_thickness is None:
            return None
        return self.membrane_thickness, self.membrane_modulus


__all__ = ["EXTENSION_PATHS", "SCHEMA", "TriaxialOptions"]
