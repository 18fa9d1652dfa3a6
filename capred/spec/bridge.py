"""The liquid-bridge commands: what they read and the options of every `capred bridge` command.

What `capred bridge solve`, `compare`, `rupture` and `laws` read, and ``BridgeOptions``, ``CurveOptions``,
``YadeOptions``, ``LawsOptions``.

Numpy-free (see :mod:`capred.spec`). The law registry is capred.spec.bridge_laws.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import OptionError
from ..nomenclature import StableJsonKeys, renamed_keywords
from .columns import Column
from .constants import PENDULAR_LIMIT, SURFACE_TENSION
from .options import Interval, Options, StrOptions, Whole

#: the words a radius-ratio column or option reads as a plane (R2 = inf)
_PLANE = (("plane", math.inf), ("inf", math.inf), ("infinity", math.inf), ("\u221e", math.inf))


CASE = Column("case", "text", None, "case label")  # aliases: nomenclature.COLUMN_ALIASES


RADIUS = Column("R", "length", "mm", "particle radius R", ("radius", "particle_radius", "R1"), "positive", quantity="R")


RADIUS2 = Column(
    "R2",
    "length",
    "mm",
    "radius R2 of the second particle ('plane' or 'inf': a plane; absent: equal spheres)",
    ("radius2", "second_radius"),
    "positive",
    words=_PLANE,
)


GAMMA = Column("gamma", "surface_tension", "N/m", "surface tension", ("surface_tension",), "positive")


ANGLE = Column("contact_angle", "angle", "deg", "contact angle", ("theta", "wetting_angle"), "nonnegative")


ANGLE2 = Column(
    "contact_angle2",
    "angle",
    "deg",
    "contact angle on the second particle (sphere R2 or plane; absent or blank: --contact-angle2, else contact_angle)",
    ("theta2", "wetting_angle2", "contact_angle_2"),
    "nonnegative",
)


VOLUME = Column("V_w", "volume", "mm^3", "water volume V_w", ("volume", "V", "Vw"), "positive")


SOLVE_SCHEMA = [
    CASE,
    RADIUS,
    RADIUS2,
    GAMMA,
    ANGLE,
    ANGLE2,
    Column("gap", "length", "mm", "gap D", ("D", "separation", "distance"), "nonnegative"),
    Column("suction", "pressure", "kPa", "suction", ("delta_u", "ua_uw"), "nonnegative"),
    VOLUME,
    Column("F_cap", "force", "mN", "measured force F_cap", ("F", "force", "F_measured"), "nonnegative"),
    Column("filling_angle", "angle", "deg", "measured filling angle", ("beta", "half_filling_angle"), "nonnegative"),
]


@dataclass(frozen=True)
class BridgeOptions(Options):
    """Options of `capred bridge solve`, `compare` and `rupture`.

    Attributes
    ----------
    surface_tension : float
        Surface tension [N/m, or a string with a unit] of rows without a ``gamma`` value.
    contact_angle2 : float, optional
        Contact angle on the second particle [deg] of rows without a ``contact_angle2`` value; None (the
        default): the row's ``contact_angle`` (one angle on both particles).
    workers : int, optional
        Processes that solve the rows (``--workers``); None: ``CAPRED_PROCESSES`` when set, else the cores this
        process may use that the load leaves idle. On a long file each process also reads and parses its blocks
        and writes their CSV and JSON text (capred.pipelines.bridge_blocks). The results are the same, to the
        bit, for any number.
    branch : str
        Volume-controlled rows: ``stable`` (default), the bridge continuous with the bridge at contact; ``thin``,
        the second bridge of the same volume and gap on the thin-neck side of the volume's minimum along the
        arc (unstable at constant volume; near rupture only).
    """

    QUANTITIES = {"surface_tension": "surface_tension", "contact_angle2": "contact_angle"}
    CONSTRAINTS = {"branch": StrOptions(("stable", "thin")), "workers": Whole(min=1)}

    surface_tension: float = SURFACE_TENSION
    contact_angle2: float | None = None
    workers: int | None = None
    branch: str = "stable"

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.contact_angle2 is not None and not 0 <= self.contact_angle2 < 90:
            raise OptionError(
                f"contact_angle2 (--contact-angle2): pendular bridges need a contact angle in [0, 90) deg "
                f"(got {self.contact_angle2:g} deg)"
            )


#: `bridge compare` reads the cases as `bridge solve` does (its --help lists these columns)
COMPARE_SCHEMA = SOLVE_SCHEMA


@renamed_keywords(sr_max="S_R_max")
@dataclass(frozen=True)
class CurveOptions(StableJsonKeys, Options):
    """Options of `capred bridge curve`.

    Radius R [m], surface tension [N/m] (or strings with units), contact angle [deg], number of S_R values, largest S_R
    (``S_R_max``; the keyword ``sr_max`` still works with a DeprecationWarning, and the JSON keeps the key ``sr_max``),
    pendular limit.
    """

    QUANTITIES = {
        "radius": "R",
        "surface_tension": "surface_tension",
        "contact_angle": "contact_angle",
        "pendular_limit": "pendular_limit",
    }
    OPTION_NAMES = {"S_R_max": "--S-R-max"}
    JSON_NAMES = {"S_R_max": "sr_max"}
    CONSTRAINTS = {"points": Whole(min=2), "S_R_max": Interval(1e-4, 1, closed="right")}

    radius: float = 1e-3
    surface_tension: float = SURFACE_TENSION
    contact_angle: float = 0.0
    points: int = 2000
    S_R_max: float = 0.3
    pendular_limit: float = PENDULAR_LIMIT


RUPTURE_SCHEMA = [CASE, RADIUS, RADIUS2, GAMMA, ANGLE, ANGLE2, VOLUME]


DEFAULT_RATIOS = (1.0, 1.1, 1.25, 1.5, 1.75, 2.0, 3.0, 4.0, 5.0, 10.0)


@dataclass(frozen=True)
class YadeOptions(Options):
    """Options of `capred bridge yade-files`.

    Radius ratios R2/R1 >= 1, contact angle [deg], number of distances and of suctions per file.
    """

    QUANTITIES = {"contact_angle": "contact_angle"}  # the glossary's range: [0, 90) deg
    CONSTRAINTS = {"distances": Whole(min=2), "suctions": Whole(min=3)}

    ratios: tuple[float, ...] = DEFAULT_RATIOS
    contact_angle: float = 0.0
    distances: int = 80
    suctions: int = 350

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "ratios", tuple(float(r) for r in self.ratios))
        if not self.ratios or any(not math.isfinite(r) or r < 1 for r in self.ratios):
            raise OptionError(
                "--ratios: radius ratios R2/R1 must be finite numbers >= 1 (the larger over the smaller radius)"
            )
        if len(set(self.ratios)) != len(self.ratios):
            raise OptionError("--ratios: each ratio once")


LAWS_SCHEMA = [
    Column("D_over_R", "dimensionless", "-", "gap D / R", ("gap_over_R", "D/R", "gap_R"), "nonnegative"),
    Column("V_over_R3", "dimensionless", "-", "bridge volume V / R^3", ("V/R3", "volume_over_R3"), "positive"),
    Column("contact_angle", "angle", "deg", "contact angle", ("theta",), "nonnegative"),
    Column(
        "R2_over_R",
        "dimensionless",
        "-",
        "R2 / R ('plane': a sphere and a plane; absent: equal spheres)",
        ("ratio", "R2/R"),
        "positive",
        words=_PLANE,
    ),
]


def _parse_list(text, name: str, words=()) -> tuple[float, ...]:
    if isinstance(text, (tuple, list)):
        return tuple(float(x) for x in text)
    out = []
    for part in str(text).split(","):
        p = part.strip().lower()
        if not p:
            continue
        value = dict(words).get(p)
        if value is None:
            try:
                value = float(p)
            except ValueError:
                raise OptionError(f"{name}: '{part.strip()}' is not a number (a comma-separated list)") from None
        out.append(value)
    if not out:
        raise OptionError(f"{name}: give at least one value")
    return tuple(out)


@dataclass(frozen=True)
class LawsOptions(Options):
    """Options of `capred bridge laws`: the default grid (used without a grid file) and the tolerance.

    Attributes
    ----------
    gaps : tuple of float
        D / R [-] (``--gaps``, comma-separated).
    volumes : tuple of float
        V / R^3 [-] (``--volumes``).
    angles : tuple of float
        Contact angles [deg] (``--angles``), in [0, 90).
    ratios : tuple of float
        R2 / R [-] (``--ratios``; ``plane`` for a sphere and a plane).
    tolerance : float
        Largest relative error [-] at which a law counts as within (``--tolerance``, default 0.05).
    """

    CONSTRAINTS = {"tolerance": Interval(0, 1, closed="neither", text="be a fraction in (0, 1)")}

    gaps: tuple = (0.0, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2)
    volumes: tuple = (1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1)
    angles: tuple = (0.0, 20.0, 40.0)
    ratios: tuple = (1.0, 2.0, math.inf)
    tolerance: float = 0.05

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "gaps", _parse_list(self.gaps, "gaps (--gaps)"))
        object.__setattr__(self, "volumes", _parse_list(self.volumes, "volumes (--volumes)"))
        object.__setattr__(self, "angles", _parse_list(self.angles, "angles (--angles)"))
        object.__setattr__(self, "ratios", _parse_list(self.ratios, "ratios (--ratios)", _PLANE))
        if any(g < 0 for g in self.gaps):
            raise OptionError("gaps (--gaps): D/R must be >= 0")
        if any(v <= 0 for v in self.volumes):
            raise OptionError("volumes (--volumes): V/R^3 must be > 0")
        if any(not 0 <= a < 90 for a in self.angles):
            raise OptionError("angles (--angles): contact angles must lie in [0, 90) deg")
        if any(r <= 0 for r in self.ratios):
            raise OptionError("ratios (--ratios): R2/R must be > 0 (or 'plane')")


__all__ = [
    "ANGLE",
    "ANGLE2",
    "CASE",
    "COMPARE_SCHEMA",
    "DEFAULT_RATIOS",
    "GAMMA",
    "LAWS_SCHEMA",
    "RADIUS",
    "RADIUS2",
    "RUPTURE_SCHEMA",
    "SOLVE_SCHEMA",
    "VOLUME",
    "BridgeOptions",
    "CurveOptions",
    "LawsOptions",
    "YadeOptions",
]
