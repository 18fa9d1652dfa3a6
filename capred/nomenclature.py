"""The one glossary of quantity names, symbols, units and valid ranges of capred.

Schemas, options, result columns, JSON keys and plot labels draw their names
from here. One name per concept: ``contact_angle`` (never ``theta``, which is
the volumetric water content), ``lode_angle``, ``bc_lambda`` (the Brooks-Corey
pore-size index, called alpha by Morvan et al. and lambda by Brooks & Corey).
Output columns carry their unit in brackets, e.g. ``sigma_N [kPa]``.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Quantity:
    """One quantity of the glossary: its symbol, output unit and scale, kind and physical limits.

    Attributes
    ----------
    symbol : str
        The symbol of plots and console headers (``"σ_N"``).
    unit : str
        The output unit (``"kPa"``).
    factor : float
        SI value × factor = value in the output unit.
    kind : str
        A key of ``capred.units.SI_UNIT`` (``"pressure"``): the SI unit of the value computed with.
    description : str
        What the quantity is, in words.
    lower, upper : float or None
        Hard limits in SI: a value outside is physically impossible (None: no limit).
    lower_open, upper_open : bool
        True when the limit itself is excluded (x > lower, x < upper).
    """

    symbol: str  # for plots and console headers
    unit: str  # output unit
    factor: float  # SI value * factor = value in the output unit
    kind: str  # a key of capred.units.SI_UNIT
    description: str
    lower: float | None = None  # hard limits in SI: outside is physically impossible
    upper: float | None = None
    lower_open: bool = False  # True: the lower limit itself is excluded (x > lower)
    upper_open: bool = False  # True: the upper limit itself is excluded (x < upper)


QUANTITIES: dict[str, Quantity] = {
    # direct shear (Evenepoel)
    "sigma_N": Quantity("σ_N", "kPa", 1e-3, "pressure", "total normal stress on the shear plane", 0.0),
    "sigma_eff": Quantity("σ'_N", "kPa", 1e-3, "pressure", "effective normal stress"),
    "suction": Quantity("Δu", "kPa", 1e-3, "pressure", "matric suction u_a − u_w", 0.0),
    "S_R": Quantity("S_R", "-", 1.0, "dimensionless", "degree of saturation", 0.0, 1.0),
    "tau_max": Quantity("τ_max", "kPa", 1e-3, "pressure", "measured peak shear stress", 0.0),
    "tau_pred": Quantity("τ_pred", "kPa", 1e-3, "pressure", "predicted shear strength"),
    "chi1": Quantity("χ1", "-", 1.0, "dimensionless", "own approximation 1, (2π S_R/3)^(2/3)"),
    "chi2": Quantity("χ2", "kPa", 1e-3, "pressure", "own approximation 2 term, (2γ/R)(2π S_R/3)^(1/3)"),
    "c": Quantity("c", "kPa", 1e-3, "pressure", "cohesion intercept"),
    "phi": Quantity("φ", "deg", 1.0, "angle", "friction angle", 0.0, 90.0, True, True),
    "tan_phi": Quantity("tan φ", "-", 1.0, "dimensionless", "slope of the envelope τ = c + σ_N tan φ"),
    "scatter": Quantity("s", "kPa", 1e-3, "pressure", "residual standard deviation about a fitted envelope", 0.0),
    "r2": Quantity("R²", "-", 1.0, "dimensionless", "coefficient of determination of a fit"),
    "z1": Quantity("z1", "cm", 1e2, "length", "height of the sample above the water level", 0.0),
    "z2": Quantity("z2", "cm^3", 1e6, "volume", "air volume entered, read on the burette", 0.0),
    "V_v": Quantity("V_v", "cm^3", 1e6, "volume", "void volume of the sample", 0.0, None, True),
    "R": Quantity("R", "mm", 1e3, "length", "particle radius", 0.0, None, True),
    "box_area": Quantity("A", "cm^2", 1e4, "area", "shear box area", 0.0, None, True),
    "cap_mass": Quantity("m_cap", "g", 1e3, "mass", "mass of the top cap", 0.0),
    "added_mass": Quantity("m_added", "g", 1e3, "mass", "added weights on the top cap", 0.0),
    "F_max": Quantity("F_max", "N", 1.0, "force", "peak shear force", 0.0),
    "pendular_limit": Quantity(
        "S_R,pend", "-", 1.0, "dimensionless", "upper S_R of the pendular regime", 0.0, 1.0, True
    ),
    "height": Quantity("H", "mm", 1e3, "length", "sample height", 0.0, None, True),
    "rho_d": Quantity("ρ_d", "kg/m^3", 1.0, "density", "dry density", 0.0, None, True),
    "G_s": Quantity("G_s", "-", 1.0, "dimensionless", "specific gravity of the solids", 0.0, None, True),
    "rho_w": Quantity("ρ_w", "kg/m^3", 1.0, "density", "density of water", 0.0, None, True),
    "ambient_pressure": Quantity("p_a", "kPa", 1e-3, "pressure", "ambient (atmospheric) pressure", 0.0, None, True),
    # constants
    "gamma_w": Quantity("γ_w", "kN/m^3", 1e-3, "unit_weight", "unit weight of water", 0.0, None, True),
    "surface_tension": Quantity("γ", "N/m", 1.0, "surface_tension", "surface tension of water", 0.0, None, True),
    "g": Quantity("g", "m/s^2", 1.0, "acceleration", "gravitational acceleration", 0.0, None, True),
    # retention
    "theta": Quantity("θ", "-", 1.0, "dimensionless", "volumetric water content", 0.0, 1.0),
    "head": Quantity("h", "cm", 1e2, "length", "suction head", 0.0),
    "air_entry": Quantity("s_e", "kPa", 1e-3, "pressure", "air-entry suction (Brooks-Corey)", 0.0, None, True),
    "vg_alpha": Quantity("α", "1/kPa", 1e3, "per_pressure", "van Genuchten α", 0.0, None, True),
    "bc_lambda": Quantity("λ", "-", 1.0, "dimensionless", "Brooks-Corey pore-size index", 0.0, None, True),
    "vg_n": Quantity("n", "-", 1.0, "dimensionless", "van Genuchten n", 1.0, None, True),
    "vg_m": Quantity("m", "-", 1.0, "dimensionless", "van Genuchten m", 0.0, 1.0, True),
    "S_res": Quantity("S_res", "-", 1.0, "dimensionless", "residual degree of saturation", 0.0, 1.0, False, True),
    "w_s": Quantity("w_s", "-", 1.0, "dimensionless", "saturated water content by mass of a w(s) fit", 0.0),
    "w_r": Quantity("w_r", "-", 1.0, "dimensionless", "residual water content by mass of a w(s) fit", 0.0),
    "vanapalli_kappa": Quantity("κ", "-", 1.0, "dimensionless", "exponent κ of χ = S_e^κ (Vanapalli)", 0.0, None, True),
    "khalili_eta": Quantity(
        "η", "-", 1.0, "dimensionless", "exponent η of χ = (s/s_b)^−η (Khalili-Khabbaz)", 0.0, None, True
    ),
    # triaxial (Prunier et al. 2024)
    "sigma1": Quantity("σ1", "kPa", 1e-3, "pressure", "major principal total stress at failure"),
    "sigma3": Quantity("σ3", "kPa", 1e-3, "pressure", "confining (minor principal) total stress", 0.0),
    "q_f": Quantity("q_f", "kPa", 1e-3, "pressure", "deviator stress at failure"),
    "c_eff": Quantity("c'", "kPa", 1e-3, "pressure", "effective cohesion", 0.0),
    "membrane_thickness": Quantity("t_m", "mm", 1e3, "length", "membrane thickness", 0.0, None, True),
    "membrane_modulus": Quantity("E_m", "kPa", 1e-3, "pressure", "Young's modulus of the membrane", 0.0, None, True),
    "phi_eff": Quantity("φ'", "deg", 1.0, "angle", "effective friction angle", 0.0, 90.0, True, True),
    "lode_angle": Quantity("θ_L", "deg", 1.0, "angle", "Lode angle"),
    # bridges
    "contact_angle": Quantity("θ_c", "deg", 1.0, "angle", "contact angle", 0.0, 90.0, False, True),
    "gap": Quantity("D", "mm", 1e3, "length", "gap between the particles", 0.0),
    "V_w": Quantity("V_w", "mm^3", 1e9, "volume", "water volume of a bridge", 0.0, None, True),
    "F_cap": Quantity("F_cap", "mN", 1e3, "force", "capillary force", 0.0),
    "filling_angle": Quantity("β", "deg", 1.0, "angle", "half-filling angle", 0.0, 90.0),
    "r0": Quantity("r0", "mm", 1e3, "length", "neck radius of a bridge"),
    # calculators
    "break_tension": Quantity("σ_b", "kPa", 1e-3, "pressure", "break tension of a sand prism", 0.0, None, True),
    "friction_angle": Quantity("ρ", "deg", 1.0, "angle", "friction angle of the sand", 0.0, 90.0, True, True),
    "P_kmax": Quantity("P_kmax", "kPa", 1e-3, "pressure", "maximal capillary pressure of a sand prism (Bernatzik)"),
    "capillary_rise": Quantity("h_c", "cm", 1e2, "length", "capillary rise P_kmax/γ_w"),
    "P_kmax_over_sigma_b": Quantity("P_kmax/σ_b", "-", 1.0, "dimensionless", "P_kmax over the break tension"),
    "kappa": Quantity("κ", "-", 1.0, "dimensionless", "slope of the elastic line in e-ln p'", 0.0, None, True),
    # the Python name of that slope (``kappa`` stays the CSV column and JSON key of `capred skempton-b`)
    "kappa_elastic": Quantity("κ", "-", 1.0, "dimensionless", "slope of the elastic line in e-ln p'", 0.0, None, True),
    "e0": Quantity("e0", "-", 1.0, "dimensionless", "initial void ratio", 0.0, None, True),
    "p0": Quantity("p0", "kPa", 1e-3, "pressure", "mean total stress", 0.0),
    "u0": Quantity("u0", "kPa", 1e-3, "pressure", "initial pore pressure"),
    "pa0": Quantity("P_a0", "kPa", 1e-3, "pressure", "absolute initial air pressure", 0.0, None, True),
    "B": Quantity("B", "-", 1.0, "dimensionless", "Skempton's pore-pressure coefficient B", 0.0, 1.0),
    "shape_factor": Quantity("φ_s", "-", 1.0, "dimensionless", "particle shape factor", 0.0, None, True),
    "void_ratio": Quantity("e", "-", 1.0, "dimensionless", "void ratio", 0.0, None, True),
    "diameter": Quantity("d_p", "mm", 1e3, "length", "apparent particle diameter", 0.0, None, True),
    # volume change of clay with two effective stresses (Pedrotti & Tarantino)
    "sigma": Quantity("σ", "kPa", 1e-3, "pressure", "total (mean) stress, compression positive"),
    "u_w": Quantity("u_w", "kPa", 1e-3, "pressure", "pore-water pressure (gauge)"),
    "u_a": Quantity("u_a", "kPa", 1e-3, "pressure", "pore-air pressure (gauge)"),
    "sigma_W": Quantity(
        "σ'_W", "kPa", 1e-3, "pressure", "effective stress of the water-saturated part, (σ − u_w) S_r", 0.0
    ),
    "sigma_A": Quantity(
        "σ'_A", "kPa", 1e-3, "pressure", "effective stress of the air-saturated part, (σ − u_a)(1 − S_r)", 0.0
    ),
    "lambda_W": Quantity(
        "λ_W",
        "-",
        1.0,
        "dimensionless",
        "slope of the ncl of clay reconstituted from slurry in e-ln σ'",
        0.0,
        None,
        True,
    ),
    "kappa_W": Quantity(
        "κ_W",
        "-",
        1.0,
        "dimensionless",
        "slope of the url of clay reconstituted from slurry in e-ln σ'",
        0.0,
        None,
        True,
    ),
    "e_ncl_W": Quantity(
        "e_ncl,W", "-", 1.0, "dimensionless", "void ratio on the slurry ncl at the reference stress", 0.0, None, True
    ),
    "lambda_A": Quantity(
        "λ_A",
        "-",
        1.0,
        "dimensionless",
        "slope of the ncl of clay compressed from dry powder in e-ln σ'",
        0.0,
        None,
        True,
    ),
    "kappa_A": Quantity(
        "κ_A",
        "-",
        1.0,
        "dimensionless",
        "slope of the url of clay compressed from dry powder in e-ln σ'",
        0.0,
        None,
        True,
    ),
    "e_ncl_A": Quantity(
        "e_ncl,A",
        "-",
        1.0,
        "dimensionless",
        "void ratio on the dry-powder ncl at the reference stress",
        0.0,
        None,
        True,
    ),
    "reference_stress": Quantity(
        "σ_ref", "kPa", 1e-3, "pressure", "stress at which the ncl intercepts are read", 0.0, None, True
    ),
    "initial_yield_W": Quantity(
        "σ'_y,W", "kPa", 1e-3, "pressure", "largest σ'_W carried before the path", 0.0, None, True
    ),
    "initial_yield_A": Quantity(
        "σ'_y,A", "kPa", 1e-3, "pressure", "largest σ'_A carried before the path", 0.0, None, True
    ),
    # the slopes of one line, W or A, as the functions of capred.physics.pedrotti_tarantino take them
    "ncl_slope": Quantity(
        "λ", "-", 1.0, "dimensionless", "slope of a normal-compression line in e-ln σ' (λ_W or λ_A)", 0.0, None, True
    ),
    "url_slope": Quantity(
        "κ", "-", 1.0, "dimensionless", "slope of an unloading-reloading line in e-ln σ' (κ_W or κ_A)", 0.0, None, True
    ),
    # compression tests (capred compression)
    "solids_height": Quantity("H_s", "mm", 1e3, "length", "height of the solids of a specimen, V_s/A", 0.0, None, True),
    "compression_index": Quantity("C_c", "-", 1.0, "dimensionless", "slope of the virgin line in e-log10 σ'", 0.0),
    "swelling_index": Quantity("C_s", "-", 1.0, "dimensionless", "slope of an unloading line in e-log10 σ'", 0.0),
    # shear-band orientation (capred shear-band)
    "dilatancy_angle": Quantity("ψ", "deg", 1.0, "angle", "dilatancy angle", -90.0, 90.0, True, True),
    "dilatancy_rate": Quantity("−dε_v/dε_1", "-", 1.0, "dimensionless", "rate of dilation at failure, −dε_v/dε_1"),
    "shear_band_angle": Quantity(
        "θ_b", "deg", 1.0, "angle", "angle between a shear band and the major principal plane", 0.0, 90.0
    ),
    "preconsolidation_stress": Quantity(
        "σ'_p", "kPa", 1e-3, "pressure", "pre-consolidation (yield) stress of a compression test", 0.0, None, True
    ),
    # unsaturated strength from triaxial failure states (`capred triaxial`, issue 40)
    "phi_b": Quantity("φ_b", "deg", 1.0, "angle", "angle of the strength gain with suction (Fredlund)", 0.0, 90.0),
    "sigma_cap": Quantity("σ_cap", "kPa", 1e-3, "pressure", "back-analysed capillary stress σ'3 − σ3 of a test"),
    "chi_back": Quantity("χ_back", "-", 1.0, "dimensionless", "back-analysed Bishop χ = σ_cap/s of a test"),
    "rho_s": Quantity("ρ_s", "kg/m^3", 1.0, "density", "density of the solids", 0.0, None, True),
    "porosity": Quantity("n", "-", 1.0, "dimensionless", "porosity e/(1 + e)", 0.0, 1.0, True, True),
    "water_content": Quantity("w", "-", 1.0, "dimensionless", "gravimetric water content", 0.0),
}


@dataclass(frozen=True)
class Magnitude:
    """How large the magnitude |x| of a quantity can be in a soil test (SI).

    ``error``: above is physically impossible for the material or the apparatus (an error: usually a unit slip
    or a corrupt cell); ``warn``: above is implausible for a soil test (a warning: the run goes on, and says so).
    ``why`` justifies both bounds. ``floor``: a non-zero magnitude below it is physically impossible too (a
    particle smaller than a molecule), justified by ``floor_why``.
    """

    warn: float
    error: float
    why: str
    floor: float = 0.0
    floor_why: str = ""


#: stresses and pressures in a soil test (total, effective, deviator, shear, cohesion, pore pressures)
# soil-testing cells and shear boxes work below a few MPa; high-pressure triaxial cells reach about 50-70 MPa, so a
# stress above 50 MPa is implausible for a soil test. 1 GPa is above the crushing strength of the grains themselves
# (uniaxial strength of quartzite about 0.2-0.4 GPa) and the working range of the steel platens: no soil test reaches it.
STRESS_MAGNITUDE = Magnitude(50e6, 1e9, "no soil test reaches 1 GPa, above the crushing strength of its grains")
#: the suction of a soil: up to about 1 GPa at oven-dryness (Fredlund & Xing 1994, doi:10.1139/t94-061: 10^6 kPa
#: at zero water content); Kelvin's law, psi = -(RT/v_w) ln(RH), gives 0.93 GPa at a relative humidity of 0.1 % (20 °C) and 10 GPa only
#: below RH = 10^-30
SUCTION_MAGNITUDE = Magnitude(1e9, 10e9, "a soil's suction is at most about 1 GPa, when oven-dry")
#: a particle's radius: cobbles reach 100 mm (200 mm across, ISO 14688-1:2017, table 1), no laboratory apparatus holds
#: a grain of 10 m radius
#: and 1 nm: below it a "particle" is a molecule and a capillary bridge has no meniscus (a water molecule: 0.3 nm)
PARTICLE_MAGNITUDE = Magnitude(
    0.1,
    10.0,
    "no laboratory test holds a grain of 10 m radius",
    1e-9,
    "below 1 nm a particle is a molecule, and a capillary bridge has no meniscus",
)
#: magnitude bounds by glossary name; input columns of kind "pressure" without an entry use STRESS_MAGNITUDE
MAGNITUDES: dict[str, Magnitude] = {
    **{
        name: STRESS_MAGNITUDE
        for name in (
            "sigma_N",
            "sigma_eff",
            "tau_max",
            "tau_pred",
            "c",
            "chi2",
            "sigma1",
            "sigma3",
            "q_f",
            "c_eff",
            "p0",
            "u0",
            "sigma",
            "u_w",
            "u_a",
            "sigma_W",
            "sigma_A",
            "break_tension",
            "air_entry",
            "reference_stress",
            "initial_yield_W",
            "initial_yield_A",
        )
    },
    "suction": SUCTION_MAGNITUDE,
    "R": PARTICLE_MAGNITUDE,
}
#: the default bound of a kind of quantity (capred.units kinds) where the name has none of its own
MAGNITUDES_BY_KIND: dict[str, Magnitude] = {"pressure": STRESS_MAGNITUDE}


def magnitude_of(name: str | None, kind: str | None = None) -> Magnitude | None:
    """The magnitude bounds of quantity ``name`` (else of its ``kind``), or None where none is set.

    Parameters
    ----------
    name : str or None
        Glossary name (or input column name) of the quantity.
    kind : str or None
        Kind of quantity (a key of ``capred.units.SI_UNIT``), used when ``name`` has no entry.

    Returns
    -------
    Magnitude or None
        The bounds [SI], see :data:`MAGNITUDES`.
    """
    if name in MAGNITUDES:
        return MAGNITUDES[name]
    if name in ("s0", "s", "matric_suction"):  # a column of suction under another name
        return SUCTION_MAGNITUDE
    return MAGNITUDES_BY_KIND.get(kind) if kind else None


def _magnitude_words(name: str, value: float, bound: float, unit: str, factor: float) -> str:
    return f"|{name}| = {abs(value) * factor:.4g} {unit} is above {bound * factor:g} {unit}"


def magnitude_problem(name: str, value: float, kind: str | None = None, unit: str | None = None) -> str | None:
    """Why an SI value is physically impossible by its magnitude (None when it is not).

    Parameters
    ----------
    name : str
        Glossary name (or column name) of the quantity.
    value : float
        The value [SI].
    kind, unit : str, optional
        Kind of quantity, for names without bounds of their own; the unit the message uses (default: the
        glossary's, else kPa for pressures).

    Returns
    -------
    str or None
        The message, with the bound and its justification.
    """
    m = magnitude_of(name, kind)
    tiny = m is not None and 0 < abs(value) < m.floor
    if m is None or not (abs(value) > m.error or tiny):
        return None
    q = QUANTITIES.get(name)
    unit, factor = (q.unit, q.factor) if q is not None and unit is None else (unit or "kPa", 1e-3)
    if tiny:
        return (
            f"|{name}| = {abs(value) * factor:.4g} {unit} is below {m.floor * factor:g} {unit}: physically "
            f"impossible ({m.floor_why})"
        )
    return f"{_magnitude_words(name, value, m.error, unit, factor)}: physically impossible ({m.why})"


def magnitude_warning(name: str, value: float, kind: str | None = None, unit: str | None = None) -> str | None:
    """A warning when an SI value is implausibly large for a soil test (None when plausible or impossible).

    Parameters
    ----------
    name : str
        Glossary name (or column name) of the quantity.
    value : float
        The value [SI].
    kind, unit : str, optional
        As for :func:`magnitude_problem`.

    Returns
    -------
    str or None
        The warning.
    """
    m = magnitude_of(name, kind)
    if m is None or not (m.warn < abs(value) <= m.error):
        return None
    q = QUANTITIES.get(name)
    unit, factor = (q.unit, q.factor) if q is not None and unit is None else (unit or "kPa", 1e-3)
    return f"{_magnitude_words(name, value, m.warn, unit, factor)}: implausible for a soil test; check its unit"


#: The spellings users type for an input column, by canonical column name: the one column vocabulary of every
#: reader (:class:`capred.io.table.Column` adds them to its own aliases, so a column named ``test_id`` reads
#: ``Test no``, ``Test No.``, ``sample`` or ``Sample ID`` in every command). Spellings are compared with case,
#: spaces, '-', '.' and '/' ignored (``Test No.`` is ``test_no``).
COLUMN_ALIASES: dict[str, tuple[str, ...]] = {
    # a test is named by whoever ran it: a number, a sample or a specimen label
    "test_id": (
        "id",
        "test",
        "test_no",
        "test_nr",
        "test_number",
        "test_name",
        "sample",
        "sample_id",
        "sample_no",
        "sample_name",
        "specimen",
        "specimen_id",
    ),
    # a case of a calculator or of a bridge table: a label, often a test or sample id
    "case": ("case_id", "name", "label", "test_id", "id", "sample_id", "test_no", "sample"),
}


#: Words of other languages for the values of text columns, with the glossary's word and the language: named in
#: the hint of an error (capred reads the English words only, so that no value is guessed).
VALUE_TRANSLATIONS: dict[str, dict[str, tuple[str, str]]] = {
    "condition": {
        "droog": ("dry", "Dutch"),
        "nat": ("wet", "Dutch"),
        "vochtig": ("wet", "Dutch"),
        "verzadigd": ("saturated", "Dutch"),
        "sec": ("dry", "French"),
        "sèche": ("dry", "French"),
        "seche": ("dry", "French"),
        "humide": ("wet", "French"),
        "saturé": ("saturated", "French"),
        "sature": ("saturated", "French"),
        "trocken": ("dry", "German"),
        "nass": ("wet", "German"),
        "feucht": ("wet", "German"),
        "gesättigt": ("saturated", "German"),
        "gesaettigt": ("saturated", "German"),
        "seco": ("dry", "Spanish or Portuguese"),
        "húmedo": ("wet", "Spanish"),
        "humedo": ("wet", "Spanish"),
        "mojado": ("wet", "Spanish"),
        "saturado": ("saturated", "Spanish or Portuguese"),
        "molhado": ("wet", "Portuguese"),
        "úmido": ("wet", "Portuguese"),
        "secco": ("dry", "Italian"),
        "umido": ("wet", "Italian"),
        "bagnato": ("wet", "Italian"),
        "saturo": ("saturated", "Italian"),
        "suchy": ("dry", "Polish"),
        "mokry": ("wet", "Polish"),
        # the words of other commands and papers for the same tests
        "unsaturated": ("wet", "another word"),
        "partially saturated": ("wet", "another word"),
        "moist": ("wet", "another word"),
        "oven-dry": ("dry", "another word"),
    },
    # retention branches as the literature names them
    "branch": {
        "desorption": ("drying", "another word"),
        "drainage": ("drying", "another word"),
        "adsorption": ("wetting", "another word"),
        "absorption": ("wetting", "another word"),
        "imbibition": ("wetting", "another word"),
        "sorption": ("wetting", "another word"),
    },
}


def column_aliases(name: str) -> tuple[str, ...]:
    """The spellings a reader accepts for the input column ``name`` besides the name itself.

    Parameters
    ----------
    name : str
        Canonical column name (``test_id``, ``case``, ...).

    Returns
    -------
    tuple of str
        The aliases of :data:`COLUMN_ALIASES`, empty when the glossary lists none.
    """
    return COLUMN_ALIASES.get(name, ())


# triaxial outputs (Prunier et al. 2024): the fields of capred.pipelines.triaxial_records name these entries;
# their JSON keys (name + _kPa/_deg), CSV headers (name [unit]) and console headers (symbol [unit]) follow
QUANTITIES.update(
    {
        "sigma2": Quantity("σ2", "kPa", 1e-3, "pressure", "intermediate principal stress at failure"),
        "p": Quantity("p", "kPa", 1e-3, "pressure", "mean stress at failure, (σ1 + σ2 + σ3)/3"),
        "q": Quantity("q", "kPa", 1e-3, "pressure", "deviator stress at failure, σ1 − σ3"),
        "s0": Quantity("s0", "kPa", 1e-3, "pressure", "initial matric suction of a triaxial test"),
        "sigma3_total": Quantity("σ3,tot", "kPa", 1e-3, "pressure", "cell pressure as given (total σ3)"),
        "back_pressure": Quantity("u_b", "kPa", 1e-3, "pressure", "back pressure (pore-water pressure)"),
        "radial_pressure": Quantity("σ_r", "kPa", 1e-3, "pressure", "radial pressure of the export at failure"),
        "membrane_correction": Quantity("Δq_m", "kPa", 1e-3, "pressure", "membrane correction of the deviator"),
        "strain_at_failure": Quantity("ε_f", "-", 1.0, "dimensionless", "axial strain at failure"),
        "q_sat": Quantity("q'_sat", "kPa", 1e-3, "pressure", "drained saturated strength at the same p0"),
        "sigma1_cap": Quantity("σ1,cap", "kPa", 1e-3, "pressure", "capillary stress, major principal direction"),
        "sigma2_cap": Quantity("σ2,cap", "kPa", 1e-3, "pressure", "capillary stress, intermediate direction"),
        "sigma3_cap": Quantity("σ3,cap", "kPa", 1e-3, "pressure", "capillary stress, minor principal direction"),
        "p_cap": Quantity("p_cap", "kPa", 1e-3, "pressure", "mean capillary stress"),
        "q_cap": Quantity("q_cap", "kPa", 1e-3, "pressure", "capillary deviator σ1,cap − σ3,cap"),
        "p_prime": Quantity("p'", "kPa", 1e-3, "pressure", "mean effective stress of the image point"),
        "q_prime": Quantity("q'", "kPa", 1e-3, "pressure", "effective deviator of the image point"),
        "gain": Quantity("q'/q'_sat", "-", 1.0, "dimensionless", "strength gain over the saturated strength"),
        "M": Quantity("M", "-", 1.0, "dimensionless", "slope of the envelope in the q-p plane (compression)"),
        "k": Quantity("k", "kPa", 1e-3, "pressure", "intercept of the envelope in the q-p plane (compression)"),
        "M_extension": Quantity("M_e", "-", 1.0, "dimensionless", "slope of the envelope in the q-p plane (extension)"),
        "k_extension": Quantity("k_e", "kPa", 1e-3, "pressure", "intercept of the envelope (extension)"),
        "C": Quantity("C", "kPa", 1e-3, "pressure", "cohesion of the line through a group's circles"),
        "C_apparent": Quantity("C", "kPa", 1e-3, "pressure", "apparent (total-stress) cohesion of a group"),
        "C_fictive": Quantity("C''", "kPa", 1e-3, "pressure", "cohesion of the line through the fictive circles"),
        "Ci": Quantity("C_i", "kPa", 1e-3, "pressure", "intermediate cohesion of a true-triaxial group (eq. 50)"),
        "Ci_fictive": Quantity("C''_i", "kPa", 1e-3, "pressure", "intermediate fictive cohesion (eq. 50)"),
        "phi_i": Quantity("φ_i", "deg", 1.0, "angle", "intermediate friction angle (eq. 50)"),
        "phi_apparent": Quantity("φ", "deg", 1.0, "angle", "apparent friction angle of a group"),
        "phi_difference": Quantity("φ − φ'", "deg", 1.0, "angle", "apparent minus effective friction angle"),
        "eq37_sigma_cap": Quantity("σ_cap,37", "kPa", 1e-3, "pressure", "spherical group tensor of eq. 37"),
        "apparent_M": Quantity("M_app", "-", 1.0, "dimensionless", "slope of a group's apparent envelope"),
        "apparent_k": Quantity("k_app", "kPa", 1e-3, "pressure", "intercept of a group's apparent envelope"),
        "lode_spread": Quantity("Δθ_L", "deg", 1.0, "angle", "spread of a group's Lode angles"),
        "lode_tol": Quantity("tol θ_L", "deg", 1.0, "angle", "Lode angle tolerance of one branch"),
        "fictive_sigma1": Quantity("σ''1", "kPa", 1e-3, "pressure", "major stress of the fictive state (eq. 44)"),
        "fictive_sigma3": Quantity("σ''3", "kPa", 1e-3, "pressure", "minor stress of the fictive state (eq. 44)"),
        "skempton_A": Quantity("A", "-", 1.0, "dimensionless", "Skempton's pore-pressure coefficient A at failure"),
    }
)


def renamed_keywords(**old_to_new: str):
    """Decorator: a function or an options class also takes the old keyword of a renamed parameter.

    ``@renamed_keywords(sr="S_R")`` on ``f(S_R=None)`` makes ``f(sr=0.9)`` work as ``f(S_R=0.9)`` with a
    DeprecationWarning naming the new keyword; giving both raises TypeError. The signature seen by
    :func:`inspect.signature` (and by help and tab completion) is the new one. On a class, its
    ``__init__`` is wrapped.

    Parameters
    ----------
    **old_to_new : str
        Old keyword -> new keyword.

    Returns
    -------
    callable
        The decorator.
    """
    import functools
    import inspect
    import warnings

    def convert(where: str, kwargs: dict) -> dict:
        for old, new in old_to_new.items():
            if old in kwargs:
                if new in kwargs:
                    raise TypeError(f"{where}() got both '{old}' and its new name '{new}'")
                warnings.warn(
                    f"{where}(): the keyword '{old}' is deprecated, use '{new}' (capred's glossary)",
                    DeprecationWarning,
                    stacklevel=3,
                )
                kwargs[new] = kwargs.pop(old)
        return kwargs

    def decorate(obj):
        if inspect.isclass(obj):
            init = obj.__init__

            @functools.wraps(init)
            def __init__(self, *args, **kwargs):
                init(self, *args, **convert(obj.__name__, kwargs))

            obj.__init__ = __init__
            return obj

        @functools.wraps(obj)
        def wrapper(*args, **kwargs):
            return obj(*args, **convert(obj.__name__, kwargs))

        return wrapper

    return decorate


class StableJsonKeys:
    """Mixin of an options dataclass whose fields were renamed to the glossary.

    ``record()`` (the JSON ``options`` and ``option_units``) keeps the keys users have, ``JSON_NAMES`` mapping field ->
    key.

    Put it before ``capred.result.Options`` among the bases.
    """

    JSON_NAMES: dict[str, str] = {}

    def record(self) -> tuple[dict, dict]:
        """(values, units) of the options as the base class gives them, each key renamed by ``JSON_NAMES``.

        Returns
        -------
        tuple of dict
            Option JSON name -> SI value, and -> SI unit.
        """
        values, units = super().record()

        def keyed(d: dict) -> dict:
            return {self.JSON_NAMES.get(k, k): v for k, v in d.items()}

        return keyed(values), keyed(units)


def label(name: str) -> str:
    """Axis label 'symbol [unit]' for a quantity.

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES``.

    Returns
    -------
    str
        E.g. ``'τ [kPa]'``.
    """
    q = QUANTITIES[name]
    return f"{q.symbol} [{q.unit}]"


def column(name: str, suffix: str = "") -> str:
    """Output column name with its unit, e.g. 'tau_pred_bishop [kPa]'.

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES``.
    suffix : str, optional
        Appended to the name before the unit, e.g. "_pred_bishop".

    Returns
    -------
    str
    """
    return f"{name}{suffix} [{QUANTITIES[name].unit}]"


def unit_suffix(unit: str) -> str:
    """The Python-name form of an output unit: ``kPa`` -> ``kPa``, ``1/kPa`` -> ``per_kPa``, ``cm^3`` -> ``cm3``.

    Parameters
    ----------
    unit : str
        An output unit as headers show it.

    Returns
    -------
    str
        The suffix of a JSON key or attribute that holds a value in that unit (``tau_kPa``).
    """
    s = unit.replace("1/", "per_").replace("/", "_per_").replace("^", "").replace(" ", "")
    return s.replace("%", "pct").replace("°", "deg")


def json_key(name: str, suffix: str = "") -> str:
    """JSON key of a quantity: its name, ``suffix`` and its output unit (``sigma_N_kPa``; ``S_R``: dimensionless).

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES``.
    suffix : str, optional
        Appended to the name before the unit, e.g. ``"_se"`` (``c_se_kPa``).

    Returns
    -------
    str
    """
    unit = QUANTITIES[name].unit
    return f"{name}{suffix}" if unit in ("", "-") else f"{name}{suffix}_{unit_suffix(unit)}"


def to_output(name: str, value):
    """Convert an SI value of a quantity to its output unit.

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES``.
    value : float or array_like
        Value in SI units.

    Returns
    -------
    float or numpy.ndarray
        ``value`` times the quantity's factor, in its output unit (e.g. Pa -> kPa).
    """
    return value * QUANTITIES[name].factor


def range_problem(name: str, value: float) -> str | None:
    """Why an SI value lies outside the physical range of quantity ``name`` (None when inside).

    The one wording of range errors, for file columns and options alike.

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES``.
    value : float
        Value in SI units.

    Returns
    -------
    str or None
        The message, the value shown in the output unit.
    """
    q = QUANTITIES[name]
    lo_bad = q.lower is not None and (value <= q.lower if q.lower_open else value < q.lower)
    hi_bad = q.upper is not None and (value >= q.upper if q.upper_open else value > q.upper)
    if not (lo_bad or hi_bad):
        return magnitude_problem(name, value)
    unit = "" if q.unit == "-" else f" {q.unit}"
    got = f"(got {value * q.factor:.6g}{unit})"
    if q.lower is not None and q.upper is not None:
        lo, hi = q.lower * q.factor, q.upper * q.factor
        if not (q.lower_open or q.upper_open):
            return f"{q.description} must lie between {lo:g} and {hi:g}{unit} {got}"
        excluded = " and ".join(f"{v:g}" for v, is_open in ((lo, q.lower_open), (hi, q.upper_open)) if is_open)
        return f"{q.description} must lie between {lo:g} and {hi:g}{unit}, {excluded} excluded {got}"
    bound = (q.lower if lo_bad else q.upper) * q.factor
    if lo_bad and bound == 0 and not q.lower_open:
        return f"{q.description} must not be negative {got}"
    rel = {(True, True): ">", (True, False): ">=", (False, True): "<", (False, False): "<="}[
        (lo_bad, q.lower_open if lo_bad else q.upper_open)
    ]
    return f"{q.description} must be {rel} {bound:g}{unit} {got}"


#: Plausible ranges (SI) of constants: a value outside is accepted with a warning,
#: which usually means a number given in another unit than the documented one.
PLAUSIBLE: dict[str, tuple[float, float]] = {
    "gamma_w": (9.0e3, 10.5e3),
    "surface_tension": (0.02, 0.08),
    "g": (9.7, 9.9),
}


def plausibility_warning(name: str, value: float, where: str | None = None) -> str | None:
    """A warning when an SI value lies outside the plausible range of a constant (None when plausible).

    Parameters
    ----------
    name : str
        A key of ``QUANTITIES`` (constants without a plausible range: never a warning).
    value : float
        Value in SI units.
    where : str or None, optional
        How the message names the value (default: ``name``).

    Returns
    -------
    str or None
        The warning text, the value shown in the output unit.
    """
    if name not in PLAUSIBLE:
        return None
    lo, hi = PLAUSIBLE[name]
    if lo <= value <= hi:
        return None
    q = QUANTITIES[name]
    return (
        f"{where or name} = {value * q.factor:.6g} {q.unit} lies outside the usual "
        f"{lo * q.factor:g}-{hi * q.factor:g} {q.unit} for {q.description}; check its unit"
    )
