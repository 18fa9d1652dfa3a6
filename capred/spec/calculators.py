"""The calculators' options: `capred prism`, `capred skempton-b`, `capred rumpf`, `capred shear-band`.

Numpy-free (see :mod:`capred.spec`): the bounding-surface check and the classical relations of skempton-b are
imported when options are built, at run time.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import OptionError
from ..nomenclature import StableJsonKeys, renamed_keywords
from .constants import GAMMA_W, SURFACE_TENSION
from .options import Options, StrOptions


@dataclass(frozen=True)
class PrismOptions(Options):
    """Break tension sigma_b [Pa], friction angle rho [deg], unit weight of water [N/m^3] (or strings with units)."""

    QUANTITIES = {"break_tension": "break_tension", "friction_angle": "friction_angle", "gamma_w": "gamma_w"}

    break_tension: float | None = None
    friction_angle: float | None = None
    gamma_w: float = GAMMA_W


#: the skeleton models of `capred skempton-b --model` (Morvan et al. 2016, sections 2-4)
SKEMPTON_MODELS = ("elastic", "bounding-surface", "elastoplastic")


#: Morvan et al. (2016), Table 3: the defaults of --model bounding-surface where no option gives a value
TABLE3 = {"s_e": 20e3, "bc_lambda": 0.8, "lambda0": 0.2, "a_ini": 0.0}


ELASTOPLASTIC_REFUSAL = (
    "--model elastoplastic: the elasto-plastic B of Morvan et al. (2016), section 4, needs the bounding-surface "
    "model of Morvan, Wong & Branque (2010), whose equations capred does not have. A reconstruction cannot stand "
    "in for it silently: with Boyle's law on the absolute air pressure (130 kPa, Table 3) every skeleton is at "
    "least as compliant as the elastic one, so B at S_r = 0.9 cannot fall below the elastic bound 0.097, and the "
    "paper's over-consolidated value 0.04 is below it (it comes out only with the gauge pressure, 30 kPa, in "
    "Boyle's law). Use --model bounding-surface for capred's stated Cam-clay reconstruction (--a-ini, "
    "--interpolation-h, --air-pressure absolute|gauge), or the elastic B (eq. 10, or with --se and --bc-lambda "
    "the elastic B with suction equilibrium)"
)


@renamed_keywords(sr="S_R", kappa="kappa_elastic")
@dataclass(frozen=True)
class SkemptonOptions(StableJsonKeys, Options):
    """Options of `capred skempton-b` (defaults: Morvan et al. 2016, Table 1); pressures in Pa or with a unit.

    ``S_R`` is the degree of saturation [-] (compute B) and ``b`` a measured B [-] (compute S_R);
    ``kappa_elastic`` the slope of the elastic line in e-ln p' [-]; ``bc_lambda`` the Brooks-Corey pore-size
    index (Morvan et al. call it alpha). ``model`` is ``elastic`` (eq. 10, or section 3 with ``s_e`` and
    ``bc_lambda``) or ``bounding-surface`` (section 4 by capred's Cam-clay bounding-surface reconstruction, not
    the BDNS model of the paper's ref. [16]: ``a_ini`` [Pa], ``interpolation_h`` [-] required when
    ``a_ini > 0``, ``lambda0`` [-], ``air_pressure`` ``absolute`` or ``gauge``; Table 3 fills ``s_e``,
    ``bc_lambda``, ``lambda0`` and ``a_ini = 0``). ``elastoplastic`` is refused with the reason. The keywords
    ``sr`` and ``kappa`` still work (DeprecationWarning); the JSON keeps the option keys ``sr`` and ``kappa``.
    """

    QUANTITIES = {
        "S_R": "S_R",
        "b": "B",
        "kappa_elastic": "kappa_elastic",
        "e0": "e0",
        "p0": "p0",
        "u0": "u0",
        "pa0": "pa0",
        "s_e": "air_entry",
        "bc_lambda": "bc_lambda",
        "a_ini": "p0",
        "lambda0": "kappa_elastic",
    }
    OPTION_NAMES = {"S_R": "--S-R", "kappa_elastic": "--kappa-elastic", "s_e": "--se"}
    JSON_NAMES = {"S_R": "sr", "kappa_elastic": "kappa"}
    CONSTRAINTS = {
        "model": StrOptions(SKEMPTON_MODELS, text="be one of " + ", ".join(SKEMPTON_MODELS)),
        "air_pressure": StrOptions(("absolute", "gauge")),
    }

    S_R: float | None = None
    b: float | None = None
    kappa_elastic: float = 0.006
    e0: float = 0.8
    p0: float = 100e3
    u0: float = 30e3
    pa0: float = 130e3
    s_e: float | None = None
    bc_lambda: float | None = None
    model: str = "elastic"
    a_ini: float | str | None = None  # Pa, initial distance of the bounding surface's apex (bounding-surface only)
    interpolation_h: float | None = None  # Dafalias-type constant h of the reconstruction (bounding-surface only)
    air_pressure: str = "absolute"  # Boyle's law on absolute or gauge air pressure (bounding-surface only)
    lambda0: float | None = None  # slope of the normal compression line (bounding-surface only; Table 3: 0.2)
    retention: str | Path | None = None  # a fits.json of capred retention: s_e and the Brooks-Corey index from it
    curve: bool = False  # B against S_r over 0.5-1 for every model the options ask for, instead of cases
    #: a compression.json of capred compression: kappa, e0 (and lambda0 with bounding-surface) from it
    compression: str | Path | None = None
    #: the classical relations drawn beside eq. 10 with --curve (SKEMPTON_RELATIONS keys; "all" for every one)
    compare: tuple = ()

    def __post_init__(self) -> None:
        super().__post_init__()
        compare = (self.compare,) if isinstance(self.compare, str) else tuple(self.compare or ())
        if compare == ("all",):
            compare = tuple(_relations())
        unknown = [c for c in compare if c not in _relations()]
        if unknown:
            raise OptionError(
                f"--compare: unknown relation(s) {', '.join(map(str, unknown))}; there are: "
                + ", ".join(_relations())
                + ", all"
            )
        object.__setattr__(self, "compare", compare)
        if self.model == "elastoplastic":
            raise OptionError(ELASTOPLASTIC_REFUSAL)
        if self.model != "bounding-surface":
            given = [
                name
                for name, v in (
                    ("--a-ini", self.a_ini),
                    ("--interpolation-h", self.interpolation_h),
                    ("--lambda0", self.lambda0),
                )
                if v is not None
            ] + (["--air-pressure gauge"] if self.air_pressure == "gauge" else [])
            if given:
                raise OptionError(f"{', '.join(given)} go(es) with --model bounding-surface")
            return
        from ..physics.skempton_elastoplastic import BoundingSurfaceCompliance

        try:  # checks kappa < lambda0, A_ini >= 0 and h where it is needed; the physics' text is the option's
            BoundingSurfaceCompliance(
                self.kappa_elastic, self.lambda0_or_default, self.a_ini_or_default, self.interpolation_h
            )
        except ValueError as exc:
            raise OptionError(str(exc)) from None
        if self.air_pressure == "gauge":
            self._warnings.append(
                "--air-pressure gauge: Boyle's law needs the absolute air pressure; the gauge pressure u0 in Boyle's "
                "law with p' = p0 + s S_r is the convention under which Morvan et al.'s (2016) Fig. 6 values come "
                "out, for comparison with the paper only (pa0 is not used)"
            )

    @property
    def lambda0_or_default(self) -> float:
        """Slope ``lambda0`` of the normal compression line [-]: the option, else Morvan et al.'s (2016) Table 3."""
        return TABLE3["lambda0"] if self.lambda0 is None else self.lambda0

    @property
    def a_ini_or_default(self) -> float:
        """Initial apex distance ``a_ini = p_pi0 - p'_0`` [Pa]: the option, else Table 3 of Morvan et al. (2016) (0)."""
        return TABLE3["a_ini"] if self.a_ini is None else self.a_ini


@renamed_keywords(sr="S_R")
@dataclass(frozen=True)
class RumpfOptions(StableJsonKeys, Options):
    """Options of `capred rumpf`.

    Degree of saturation ``S_R`` [-], diameter [m], surface tension [N/m] (or strings with units), contact angle [deg].
    The keyword ``sr`` still works (DeprecationWarning); the JSON keeps the option key ``sr``.
    """

    QUANTITIES = {
        "shape_factor": "shape_factor",
        "void_ratio": "void_ratio",
        "S_R": "S_R",
        "diameter": "diameter",
        "surface_tension": "surface_tension",
        "contact_angle": "contact_angle",
    }
    OPTION_NAMES = {"S_R": "--S-R"}
    JSON_NAMES = {"S_R": "sr"}

    shape_factor: float | None = None
    void_ratio: float | None = None
    S_R: float | None = None
    diameter: float | None = None
    surface_tension: float = SURFACE_TENSION
    contact_angle: float = 0.0


@dataclass(frozen=True)
class ShearBandOptions(Options):
    """Options of `capred shear-band`.

    Attributes
    ----------
    phi_eff : float, optional
        Effective friction angle φ' [deg] (or ``triaxial``).
    dilatancy_angle : float, optional
        Dilatancy angle ψ [deg].
    dilatancy_rate : float, optional
        −dε_v/dε_1 at failure [-], instead of ψ (sin ψ = d/(2 + d)).
    measured : float, optional
        Measured angle of the band to the major principal plane [deg].
    triaxial : str, optional
        summary.json of `capred triaxial-bounds` or of `capred triaxial` (one material): φ' of its envelope.
    """

    QUANTITIES = {"phi_eff": "phi_eff", "dilatancy_angle": "dilatancy_angle", "measured": "shear_band_angle"}

    phi_eff: float | None = None
    dilatancy_angle: float | None = None
    dilatancy_rate: float | None = None
    measured: float | None = None
    triaxial: str | Path | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.dilatancy_angle is not None and self.dilatancy_rate is not None:
            raise OptionError("give --dilatancy-angle or --dilatancy-rate, not both")
        if self.phi_eff is not None and self.triaxial is not None:
            raise OptionError("give --phi-eff or --triaxial (the envelope's phi'), not both")


def _relations() -> dict:
    """The classical relations of B and S_r that ``--compare`` draws (capred.physics.calculators)."""
    from ..physics.calculators import SKEMPTON_RELATIONS

    return SKEMPTON_RELATIONS


__all__ = [
    "ELASTOPLASTIC_REFUSAL",
    "SKEMPTON_MODELS",
    "TABLE3",
    "PrismOptions",
    "RumpfOptions",
    "ShearBandOptions",
    "SkemptonOptions",
]
