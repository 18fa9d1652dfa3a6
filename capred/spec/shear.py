"""`capred shear`: what it reads (``SCHEMA``) and its options (``ShearOptions``, ``ModelParams``).

Numpy-free (see :mod:`capred.spec`): the effective-stress models are those of the registry
capred.spec.effective_stress.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import OptionError
from ..nomenclature import QUANTITIES, Quantity
from . import effective_stress as esm
from .columns import Column
from .constants import ERROR_MODELS, GAMMA_W, LOSSES, PENDULAR_LIMIT, SURFACE_TENSION, G
from .options import Options, Probability, StrOptions, Whole

SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column("material", "text", None, "material name", ("soil", "material_name")),
    Column("condition", "text", None, "test condition", ("state", "dry_wet"), choices=("dry", "wet", "saturated")),
    Column("z1", "length", "cm", "suction head z1", ("suction_head", "head", "z_1"), quantity="z1"),
    Column("z2", "volume", "cm^3", "air volume z2", ("air_volume", "burette", "z_2", "V_a"), quantity="z2"),
    Column("V_v", "volume", "cm^3", "void volume V_v", ("Vv", "void_volume"), quantity="V_v"),
    Column("added_mass", "mass", "g", "added mass", ("added_weight", "m_added", "weight"), quantity="added_mass"),
    Column("cap_mass", "mass", "g", "cap mass", ("m_cap", "top_cap_mass", "cap_weight"), quantity="cap_mass"),
    Column("box_area", "area", "cm^2", "box area", ("A_box", "area", "shear_area"), quantity="box_area"),
    Column("R", "length", "mm", "particle radius R", ("radius", "particle_radius", "r_particle"), quantity="R"),
    Column(
        "tau_max",
        "pressure",
        "kPa",
        "tau_max",
        ("tau", "taumax", "shear_strength", "peak_shear_stress"),
        quantity="tau_max",
    ),
    Column("F_max", "force", "N", "F_max", ("fmax", "peak_force", "max_force"), quantity="F_max"),
    Column("sigma_N", "pressure", "kPa", "sigma_N", ("sigma_n", "normal_stress", "sigman"), quantity="sigma_N"),
    Column("suction", "pressure", "kPa", "suction", ("delta_u", "matric_suction", "ua_uw"), quantity="suction"),
    Column("S_R", "dimensionless", "-", "S_R", ("Sr", "degree_of_saturation", "saturation"), quantity="S_R"),
    Column("e", "dimensionless", "-", "void ratio e", ("void_ratio", "e0"), quantity="void_ratio"),
    Column("height", "length", "mm", "sample height", ("h", "sample_height", "H0", "H"), quantity="height"),
    Column("rho_d", "density", "kg/m^3", "dry density", ("dry_density", "rhod"), quantity="rho_d"),
    Column("G_s", "dimensionless", "-", "specific gravity of the solids", ("Gs", "specific_gravity"), quantity="G_s"),
]


@dataclass(frozen=True)
class ModelParameter:
    """A parameter an effective-stress model declares for itself, in its registry entry (``parameters``).

    From this declaration alone `capred shear` takes the option ``--<name>`` (a number in the quantity's output
    unit, or with a unit of its own; its help shows the unit and range), the Python API takes
    ``ModelParams(extra={name: value})``, and the model reads the value in SI as ``d.params.<name>``.

    Attributes
    ----------
    name : str
        The parameter's keyword, e.g. ``"my_kappa"`` (``--my-kappa``); its glossary entry is registered under
        this name (capred.nomenclature.QUANTITIES) when the registry is read.
    quantity : capred.nomenclature.Quantity
        Symbol, output unit, factor, SI kind, description and hard limits, as a glossary entry has them.
    default : float, optional
        The SI value when the option is not given; None (the default): not given, and a model that lists the
        parameter in its ``requires`` is refused without it.
    """

    name: str
    quantity: Quantity
    default: float | None = None

    @property
    def option(self) -> str:
        """The command-line option, ``--my-kappa``."""
        return "--" + self.name.replace("_", "-")


def model_parameters() -> dict[str, ModelParameter]:
    """The parameters the registered effective-stress models declare for themselves (an entry's ``parameters``).

    Read now: a model registered by a script is included. Each one's glossary entry is registered under its name
    (capred.nomenclature.QUANTITIES), so that it is read and range checked as every option is.

    Returns
    -------
    dict
        Parameter name -> ModelParameter, in registry order (the first model declaring a name wins).
    """
    out: dict[str, ModelParameter] = {}
    for entry in esm.REGISTRY.values():
        for p in entry.parameters:
            QUANTITIES.setdefault(p.name, p.quantity)
            out.setdefault(p.name, p)
    return out


@dataclass(frozen=True)
class ModelParams(Options):
    """Parameters of the models beyond the thesis's four (SI; None = not given).

    Retention parameters come from `capred retention` output (--retention) or options.
    ``air_entry`` [Pa] and ``vg_alpha`` [1/Pa] also take a unit: ``air_entry="5 kPa"``.
    """

    QUANTITIES = {
        "air_entry": "air_entry",
        "vg_alpha": "vg_alpha",
        "contact_angle": "contact_angle",
        "s_res": "S_res",
        "vanapalli_kappa": "vanapalli_kappa",
        "vg_n": "vg_n",
        "vg_m": "vg_m",
        "eta": "khalili_eta",
    }
    OPTION_NAMES = {"s_res": "--s-res", "eta": "--eta"}

    s_res: float | None = None  # residual S_R (Vanapalli)
    vanapalli_kappa: float = 1.0
    air_entry: float | None = None  # Pa (Khalili-Khabbaz)
    vg_alpha: float | None = None  # 1/Pa (Lu-Likos)
    vg_n: float | None = None
    vg_m: float | None = None
    water_envelope: tuple[float, float] | None = None  # (c [Pa], phi [deg]) of the saturated soil (P-T)
    retention_model: tuple | None = None  # (model name, SI parameters, quantity) of a capred retention fit
    contact_angle: float = 0.0  # deg, of the exact bridge (exact_neck)
    eta: float = 0.55  # exponent of khalili_fit (fixed unless fit_eta)
    fit_eta: bool = False
    #: the parameters registered models declare for themselves (ModelParameter): name -> value (SI after
    #: construction); in the options record only when one is given
    extra: dict = field(default_factory=dict, metadata={"omit_when_empty": True})

    def __post_init__(self) -> None:
        super().__post_init__()  # a bad value is quoted as given (capred.spec.options.as_given)
        if self.extra:
            object.__setattr__(self, "extra", self._read_extra(dict(self.extra)))

    def _read_extra(self, extra: dict) -> dict:
        """The models' own parameters in SI, each read and range checked with its declared quantity."""
        from ..units import to_si  # pint: at run time only

        declared = model_parameters()
        unknown = sorted(set(extra) - set(declared))
        if unknown:
            raise OptionError(
                f"extra: no registered model declares {', '.join(unknown)} (declared: {', '.join(declared) or 'none'})"
            )
        out = {}
        for name, value in extra.items():
            if value is not None:
                out[name] = to_si(value, name, f"{name} ({declared[name].option})", self._notes)
        return out

    def __getattr__(self, name: str):
        """A parameter a registered model declares for itself (``d.params.my_kappa``).

        The value given, else its declared default.
        """
        if name.startswith("_"):
            raise AttributeError(name)
        p = model_parameters().get(name)
        if p is None:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        return self.__dict__.get("extra", {}).get(name, p.default)

    @property
    def retention_notes(self) -> tuple:
        """What --retention FIT.json gave: ``(fields, text, is_warning)`` per note.

        The branch read, each conversion to another model with its misfit; shown by ShearOptions where a model compared
        uses one of the fields (or always, with no fields). Not an option (set by :func:`model_params_from_retention`,
        as ``warnings`` is by the options' checks): the options record does not repeat it.
        """
        return tuple(getattr(self, "_retention_notes", ()))

    def missing(self, model: str) -> str:
        """What ``model`` needs and is not given (its registry ``requires``), e.g. ``"--s-res"``; "" when nothing.

        Parameters
        ----------
        model : str
            An effective-stress model of the registry.

        Returns
        -------
        str
            The missing options, joined by " and ".
        """
        return " and ".join(opt for name, opt in esm.REGISTRY[model].requires if getattr(self, name) is None)

    def require(self, model: str) -> None:
        """Refuse a model that lacks a parameter it needs.

        Parameters
        ----------
        model : str
            An effective-stress model of the registry.

        Raises
        ------
        OptionError
            Naming the missing options (see :meth:`missing`).
        """
        missing = self.missing(model)
        if missing:
            needs = {name for name, _ in esm.REGISTRY[model].requires}
            why = "".join(f"; {note}" for fields, note, _ in self.retention_notes if needs & set(fields))
            raise OptionError(
                f"model '{model}' needs {missing} (or --retention FIT.json written by capred retention){why}"
            )


@dataclass(frozen=True)
class ShearOptions(Options):
    """Constants and per-test defaults.

    Every dimensional option takes a number in the SI unit noted beside it, a
    string with a unit (``gamma_w="10 kN/m^3"``) or a pint Quantity; it holds
    SI after construction. Per-test values (box area, cap mass, R, V_v) given
    as options fill the rows where the column is absent or blank; a value in
    the file wins.
    """

    QUANTITIES = {
        "gamma_w": "gamma_w",
        "surface_tension": "surface_tension",
        "g": "g",
        "pendular_limit": "pendular_limit",
        "box_area": "box_area",
        "cap_mass": "cap_mass",
        "radius": "R",
        "void_volume": "V_v",
        "ambient_pressure": "ambient_pressure",
        "rho_w": "rho_w",
    }
    CONSTRAINTS = {
        "area_correction": StrOptions(("none", "square", "circular")),
        "dry_fit": StrOptions(("free", "origin"), text="be 'free' or 'origin'"),
        "errors": StrOptions(ERROR_MODELS, text="be " + ", ".join(ERROR_MODELS)),
        "dry_loss": StrOptions(LOSSES, text="be " + ", ".join(LOSSES)),
        "bootstrap": Whole(min=0),
        "seed": Whole(min=0),
        "confidence": Probability(),
    }

    gamma_w: float = GAMMA_W  # N/m^3
    surface_tension: float = SURFACE_TENSION  # N/m
    g: float = G  # m/s^2
    pendular_limit: float = PENDULAR_LIMIT  # -
    confidence: float = 0.95
    box_area: float | None = None  # m^2
    cap_mass: float | None = None  # kg
    radius: float | None = None  # m
    void_volume: float | None = None  # m^3
    models: tuple[str, ...] = esm.THESIS_MODELS
    model_params: ModelParams = field(default_factory=ModelParams)
    ambient_pressure: float = 101325.0  # Pa: the hanging column cavitates above (p_a - p_v)/gamma_w
    rho_w: float = 1000.0  # kg/m^3, for e = G_s rho_w/rho_d - 1
    curves: object = None  # raw direct-shear curves (path or DataFrame): peaks give tau_max
    area_correction: str = "none"  # of the curves: none (nominal area, ASTM D3080), square or circular
    dry_fit: str = "free"  # "free" (c and phi) or "origin" (c = 0, cohesionless soil)
    #: error model of the dry envelope: either (the default: every interval at least as wide as both the constant
    #: and the proportional model give, so valid under both), constant, proportional (sd proportional to the
    #: strength) or auto (proportional when the Breusch-Pagan test of the least-squares residuals against sigma_N
    #: has p < 0.05; covers only 84-87 % with scatter proportional to the strength on 6 dry tests)
    errors: str = "either"
    dry_loss: str = "ols"  # loss of the dry fit: ols, huber or tukey (robust, sandwich standard errors)
    bootstrap: int = 2000  # most replicates of the ranking bootstrap (0: none); adaptive: it stops when resolved
    seed: int = 0  # of the bootstrap: the same seed gives the same probabilities

    def __post_init__(self) -> None:
        super().__post_init__()  # a bad value is quoted as given (capred.spec.options.as_given)
        try:
            models = esm.resolve_models(self.models)
        except (ValueError, TypeError) as exc:
            raise OptionError(f"models (--models): {exc}") from None
        skipped = {}
        if esm.asks_for_all(self.models):  # 'all': every model the inputs allow; the others named, with their needs
            skipped = {m: need for m in models if (need := self.model_params.missing(m))}
            models = tuple(m for m in models if m not in skipped)
        object.__setattr__(self, "models", models)
        object.__setattr__(self, "_skipped", skipped)
        for m in models:
            self.model_params.require(m)

    @property
    def skipped_models(self) -> dict[str, str]:
        """Models that ``models="all"`` left out: {model: what it needs} (e.g. ``"--s-res"``)."""
        return dict(getattr(self, "_skipped", {}))

    @property
    def notes(self) -> list[str]:
        """One line per model ``all`` skipped, naming what it needs, and what --retention gave.

        The branch read, and each conversion to another model with its misfit, where a model compared uses it.
        """
        out = [
            f"--models all: model '{m}' skipped: it needs {need} (or --retention FIT.json written by capred retention)"
            for m, need in self.skipped_models.items()
        ]
        return out + self._from_retention(warnings=False)

    def _from_retention(self, warnings: bool) -> list[str]:
        """The notes (or warnings) of --retention that concern the models compared, each naming the models."""
        out = []
        supplied = set(getattr(self.model_params, "_retention_fields", ()))
        used = any({name for name, _ in esm.REGISTRY[m].requires} & supplied for m in self.models)
        for fields, note, is_warning in self.model_params.retention_notes:
            users = [m for m in self.models if {name for name, _ in esm.REGISTRY[m].requires} & set(fields)]
            if is_warning != warnings:
                continue
            if not fields:
                out.append(note)
            elif users:
                out.append(f"{note}; used by {', '.join(users)}")
        if out and not warnings and not used:
            out[0] += (
                "; no model compared takes its parameters (see --models): it gives the figures' S_R(s) relation, "
                "along which the model curves are drawn"
            )
        return out

    @property
    def warnings(self) -> list[str]:
        """Implausible option values, the model parameters' warnings and those of the retention parameters."""
        return super().warnings + self.model_params.warnings + self._from_retention(warnings=True)


__all__ = ["SCHEMA", "ModelParameter", "ModelParams", "ShearOptions", "model_parameters"]
