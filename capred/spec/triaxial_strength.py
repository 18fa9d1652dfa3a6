"""`capred triaxial`: what it reads (``SCHEMA``) and its options (``TriaxialStrengthOptions``).

Numpy-free (see :mod:`capred.spec`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import OptionError
from . import effective_stress as esm
from .columns import Column
from .constants import ERROR_MODELS, SURFACE_TENSION
from .options import Options, Probability, StrOptions, Whole
from .shear import ModelParams

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),
    Column("material", "text", None, "material name", ("soil", "material_name")),
    Column(
        "branch",
        "text",
        None,
        "loading branch (compression or extension; blank: compression)",
        ("loading", "triaxial_branch"),
        choices=("compression", "extension"),
    ),
    Column(
        "sigma3",
        "pressure",
        "kPa",
        "net cell pressure sigma3 - u_a",
        ("net_sigma3", "sigma3_net", "s3", "confining_pressure", "cell_pressure", "net_confining_pressure"),
        quantity="sigma3",
    ),
    Column(
        "q_f", "pressure", "kPa", "deviator at failure q_f", ("q", "qf", "q_max", "deviator", "q_peak"), quantity="q_f"
    ),
    Column("sigma1", "pressure", "kPa", "net axial stress at failure", ("s1", "sigma_1"), "nonnegative"),
    Column(
        "suction", "pressure", "kPa", "matric suction u_a - u_w", ("s", "matric_suction", "ua_uw"), quantity="suction"
    ),
    Column("S_R", "dimensionless", "-", "degree of saturation", ("Sr", "S_r", "degree_of_saturation"), quantity="S_R"),
    Column("w", "dimensionless", "-", "gravimetric water content", ("water_content", "w0"), quantity="water_content"),
    Column("rho_d", "density", "kg/m^3", "dry density", ("dry_density", "rhod"), quantity="rho_d"),
    Column("rho_s", "density", "kg/m^3", "density of the solids", ("solid_density", "rhos"), quantity="rho_s"),
    Column("G_s", "dimensionless", "-", "specific gravity of the solids", ("Gs", "specific_gravity"), quantity="G_s"),
    Column("e", "dimensionless", "-", "void ratio", ("void_ratio", "e0"), quantity="void_ratio"),
    Column("n", "dimensionless", "-", "porosity", ("porosity",), quantity="porosity"),
    Column("theta", "dimensionless", "-", "volumetric water content", ("vwc",), quantity="theta"),
    Column("R", "length", "mm", "particle radius R", ("radius", "particle_radius"), quantity="R"),
]


#: the default model selection: every model of the registry the inputs allow
DEFAULT_MODELS = "all"


@dataclass(frozen=True)
class TriaxialStrengthOptions(Options):
    """Options of `capred triaxial`.

    Attributes
    ----------
    models : str
        Effective-stress models compared, comma separated (the registry of `capred shear`), ``thesis`` for the
        thesis's four or ``all`` for every model the inputs allow (the default).
    c_eff : float, optional
        Effective cohesion c' [Pa]; with ``phi_eff`` it replaces the envelope at s -> 0 of the extended
        Mohr-Coulomb fit.
    phi_eff : float, optional
        Effective friction angle φ' [deg], with ``c_eff``.
    errors : str
        Scatter of a test's strength in the extended Mohr-Coulomb fit: ``either`` (the default, as `capred shear`:
        intervals that hold whether the scatter is constant or grows with the strength, with no choice made),
        ``proportional`` (to the strength), ``constant`` (ordinary least squares) or ``auto`` (Breusch-Pagan).
    confidence : float
        Level of the intervals [-].
    bootstrap : int
        Replicates of the ranking bootstrap per material (0: none).
    seed : int
        Seed of the bootstrap.
    model_params : ModelParams
        Parameters of the models beyond the thesis's four (as `capred shear`).
    surface_tension : float
        γ [N/m], of Own 2 and the exact bridge.
    """

    QUANTITIES = {"c_eff": "c_eff", "phi_eff": "phi_eff", "surface_tension": "surface_tension"}
    CONSTRAINTS = {
        "errors": StrOptions(ERROR_MODELS, text="be one of " + ", ".join(ERROR_MODELS)),
        "confidence": Probability(text="lie between 0 and 1, both excluded"),
        "bootstrap": Whole(min=0),
        "seed": Whole(min=0),
    }

    models: str = DEFAULT_MODELS
    c_eff: float | None = None  # Pa
    phi_eff: float | None = None  # deg
    errors: str = "either"
    confidence: float = 0.95
    bootstrap: int = 200
    seed: int = 12345
    model_params: ModelParams = field(default_factory=ModelParams)
    surface_tension: float = SURFACE_TENSION

    def __post_init__(self) -> None:
        super().__post_init__()
        if (self.c_eff is None) != (self.phi_eff is None):
            raise OptionError("give both --c-eff and --phi-eff (Python: c_eff and phi_eff), or neither")
        try:
            esm.resolve_models(self.models)
        except ValueError as exc:
            raise OptionError(f"models (--models): {exc}") from None

    @property
    def envelope_given(self) -> bool:
        """True when --c-eff/--phi-eff replace the envelope at s -> 0."""
        return self.c_eff is not None


__all__ = ["DEFAULT_MODELS", "SCHEMA", "TriaxialStrengthOptions"]
