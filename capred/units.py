"""Unit handling at the edges of capred, backed by pint.

Inside capred every quantity is in SI base units (Pa, m, kg, N, m^3, rad for
angles passed to trigonometry). Columns and options may carry any unit pint
understands; this module converts them to SI and checks their dimension.

Older literature (Bernatzik 1948) writes pressures in g/cm^2 or kg/cm^2,
meaning gram-force and kilogram-force per cm^2. Where a pressure is expected and
a mass per area is given, the value is multiplied by standard gravity
(9.80665 m/s^2) and the conversion is reported back to the caller.
"""

from __future__ import annotations

import re
from functools import lru_cache

import numpy as np

from .errors import UnitError

# Quantity kinds capred knows, with the SI unit every value is converted to.
SI_UNIT = {
    "pressure": "Pa",
    "length": "m",
    "mass": "kg",
    "area": "m**2",
    "volume": "m**3",
    "force": "N",
    "surface_tension": "N/m",
    "unit_weight": "N/m**3",
    "acceleration": "m/s**2",
    "dimensionless": "dimensionless",
    "angle": "deg",  # angles stay in degrees at the interface; physics converts
    "per_pressure": "1/Pa",
    "density": "kg/m**3",
}

_STANDARD_GRAVITY = 9.80665  # m/s^2, the definition of gram-force / kilogram-force


@lru_cache(maxsize=1)
def registry():
    """The one pint UnitRegistry of the process, built on first use (it is slow to create).

    Returns
    -------
    pint.UnitRegistry
        The registry, its parsed definitions cached on disk where the cache folder can be written.
    """
    import pint

    try:  # parsed definitions cached on disk: 20 ms instead of 350 ms per process
        return pint.UnitRegistry(cache_folder=":auto:")
    except OSError:
        return pint.UnitRegistry()


#: the longest unit string capred reads (a longer one is not a unit a lab writes)
MAX_UNIT_LENGTH = 64
_UNIT_CHARS = re.compile(r"[A-Za-z0-9µμ°Ω%*/^(). _-]*")
#: superscript digits and signs as labs type them in Excel ('cm³', 'kN/m³', 'm⁻¹'): read as '^' powers
_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")
_SUPERSCRIPT_RUN = re.compile(r"[⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+")
_PRODUCT_SIGNS = str.maketrans({"·": "*", "⋅": "*", "×": "*", "∙": "*"})
_WATER_HEAD = re.compile(r"^\s*(?P<len>[a-zµμ]*m)\s*(?:_?H2O|water|of water|wc)\s*$", re.I)


def ascii_unit(unit: str) -> str:
    """A unit as typed with superscripts and product signs, in plain text.

    ``'cm³'`` -> ``'cm^3'``, ``'kN·m⁻³'`` -> ``'kN*m^-3'``. Other text is returned unchanged.

    Parameters
    ----------
    unit : str
        A unit as typed.

    Returns
    -------
    str
    """
    if unit.isascii():
        return unit
    unit = _SUPERSCRIPT_RUN.sub(lambda m: "^" + m.group(0).translate(_SUPERSCRIPT), unit)
    return unit.translate(_PRODUCT_SIGNS)


def check_unit_text(unit: str) -> None:
    """Refuse a unit string before pint sees it: too long, odd characters, unbalanced parentheses.

    Raises UnitError saying what is wrong; returns None for an acceptable unit text.

    Parameters
    ----------
    unit : str
        The unit text, e.g. "kN/m^3".
    """
    if len(unit) > MAX_UNIT_LENGTH:
        raise UnitError(f"unit '{unit[:20]}...' is longer than {MAX_UNIT_LENGTH} characters")
    if not _UNIT_CHARS.fullmatch(unit):
        bad = sorted({ch for ch in unit if not _UNIT_CHARS.fullmatch(ch)})
        raise UnitError(
            f"unknown unit '{unit}': it holds {' '.join(repr(b) for b in bad)} (a unit is made of "
            "unit names, numbers, * / ^ ( ) and spaces)"
        )
    depth = 0
    for ch in unit:
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth < 0:
            break
    if depth != 0:
        raise UnitError(f"unknown unit '{unit}': its parentheses do not match")


def _normalise(unit: str, kind: str | None = None) -> str:
    u = unit.strip()
    if u in {"-", "", "1", "–"}:
        return "dimensionless"
    if u == "%":
        return "percent"
    water = _WATER_HEAD.match(u)
    if water:  # a head of water: a length where a length is expected, else the pressure of that column
        length = water.group("len").replace("μ", "µ")
        return length if kind == "length" else f"{length}_H2O"
    u = u.replace("μ", "µ")
    # 'cm3', 'mm2' -> 'cm**3', 'mm**2' (but leave 'cmH2O' alone)
    u = re.sub(r"([A-Za-zµ])([23])(?![A-Za-z0-9])", r"\1**\2", u)
    return u.replace("^", "**")


#: exact SI factors of the most common units, so that reading a plain lab file needs no pint registry
_COMMON = {
    ("m", "length"): 1.0,
    ("mm", "length"): 1e-3,
    ("cm", "length"): 1e-2,
    ("um", "length"): 1e-6,
    ("µm", "length"): 1e-6,
    ("Pa", "pressure"): 1.0,
    ("kPa", "pressure"): 1e3,
    ("MPa", "pressure"): 1e6,
    ("N", "force"): 1.0,
    ("mN", "force"): 1e-3,
    ("kN", "force"): 1e3,
    ("N/m", "surface_tension"): 1.0,
    ("mN/m", "surface_tension"): 1e-3,
    ("m^3", "volume"): 1.0,
    ("mm^3", "volume"): 1e-9,
    ("cm^3", "volume"): 1e-6,
    ("m^2", "area"): 1.0,
    ("mm^2", "area"): 1e-6,
    ("cm^2", "area"): 1e-4,
    ("deg", "angle"): 1.0,
    ("kg", "mass"): 1.0,
    ("g", "mass"): 1e-3,
    ("N/m^3", "unit_weight"): 1.0,
    ("kN/m^3", "unit_weight"): 1e3,
    ("kg/m^3", "density"): 1.0,
    ("g/cm^3", "density"): 1e3,
    ("Mg/m^3", "density"): 1e3,
    ("m/s^2", "acceleration"): 1.0,
    ("dimensionless", "dimensionless"): 1.0,
    ("-", "dimensionless"): 1.0,
    ("%", "dimensionless"): 0.01,
}


@lru_cache(maxsize=256)
def conversion(unit: str, kind: str) -> tuple[float, str | None]:
    """Factor that turns a value in ``unit`` into SI for a quantity of ``kind``.

    Parameters
    ----------
    unit : str
        The unit as a file or an option writes it (``"kPa"``, ``"g/cm^3"``, ``"kN·m⁻³"``).
    kind : str
        The kind of quantity, a key of ``SI_UNIT`` (its SI unit is the target).

    Returns
    -------
    factor : float
        SI value = factor × value in ``unit``.
    note : str or None
        Said when a mass per area was read as a force per area (g/cm^2 as gram-force per cm^2), else None.

    Raises
    ------
    UnitError
        For an unknown unit, or one of the wrong dimension.
    """
    if (unit, kind) in _COMMON:  # the usual lab units need no unit registry (it takes 0.2 s to build)
        return _COMMON[unit, kind], None
    if not unit.isascii():  # 'cm³', 'kN/m³', 'kN·m⁻³' as Excel users type them
        plain = ascii_unit(unit)
        if plain != unit:
            try:
                return conversion(plain, kind)
            except UnitError as exc:  # the message names the unit as the user wrote it
                raise UnitError(str(exc).replace(f"'{plain}'", f"'{unit}'")) from None
    ureg = registry()
    target = ureg.Unit(SI_UNIT[kind])
    check_unit_text(unit)
    try:
        q = ureg.Quantity(1.0, _normalise(unit, kind))
        factor = float(q.magnitude)
        if not np.isfinite(factor) or factor == 0:
            raise ValueError("not a finite, non-zero scale")
    except Exception as exc:  # pint raises many kinds (and ZeroDivisionError for '1/0'): all mean "not a unit"
        raise UnitError(f"unknown unit '{unit}'") from exc
    note = None
    if kind == "pressure" and q.dimensionality == ureg.Unit("kg/m**2").dimensionality:
        q = q * ureg.Quantity(_STANDARD_GRAVITY, "m/s**2")
        note = f"'{unit}' read as {unit.replace('kg', 'kgf').replace('g/', 'gf/')} (force per area, g = 9.80665 m/s^2)"
    if q.dimensionality != target.dimensionality:
        raise UnitError(f"unit '{unit}' is not a unit of {kind.replace('_', ' ')} (expected e.g. {_example(kind)})")
    try:
        return float(q.to(target).magnitude), note
    except Exception as exc:  # pragma: no cover - dimensions were checked above
        raise UnitError(f"unit '{unit}' cannot be converted to {SI_UNIT[kind]}") from exc


def _example(kind: str) -> str:
    return {
        "pressure": "kPa, Pa, MPa, g/cm^2",
        "length": "mm, cm, m, um",
        "mass": "g, kg",
        "area": "cm^2, mm^2, m^2",
        "volume": "cm^3, mm^3, mL",
        "force": "N, mN, kN",
        "surface_tension": "N/m, mN/m",
        "unit_weight": "kN/m^3",
        "acceleration": "m/s^2",
        "dimensionless": "-, %",
        "angle": "deg, rad",
        "per_pressure": "1/kPa",
        "density": "kg/m^3, g/cm^3, Mg/m^3",
    }[kind]


def parse_quantity(text: str, default_unit: str, kind: str, notes: list[str] | None = None) -> float:
    """Read an option such as ``"115 g/cm^2"`` or ``"0.5"`` (in ``default_unit``) to SI.

    A note on how the unit was read (g/cm^2 as gram-force) is appended to ``notes``.

    Parameters
    ----------
    text : str
        A number, optionally followed by a unit.
    default_unit : str
        Unit of a bare number.
    kind : str
        The dimension expected, a key of ``SI_UNIT`` (e.g. "pressure"); another dimension raises UnitError.
    notes : list of str or None, optional
        Receives a note on an ambiguous unit.

    Returns
    -------
    float
        The value in SI units.
    """
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*", str(text))
    if not m:
        raise UnitError(f"'{text}' is not a number with an optional unit")
    unit = m.group(2) or default_unit
    factor, note = conversion(unit, kind)
    if note and notes is not None:
        notes.append(note)
    return float(m.group(1)) * factor


def to_si(value, name: str, where: str | None = None, notes: list[str] | None = None) -> float:
    """An API option of quantity ``name`` (a key of capred.nomenclature.QUANTITIES) in SI.

    ``value`` may be a plain number, taken in the SI unit the docstring of the
    option documents (N/m^3 for a unit weight, Pa for a pressure, m for a
    length), a string with a unit (``"10 kN/m^3"``), or a pint Quantity. A value
    of the wrong dimension, not a number, or outside the physical range of the
    quantity raises OptionError naming ``where`` (the option).

    Parameters
    ----------
    value : float, str or pint.Quantity
        The option's value.
    name : str
        The quantity, a key of ``capred.nomenclature.QUANTITIES``.
    where : str or None, optional
        The option as messages name it (default: ``name``).
    notes : list of str or None, optional
        Receives a note on an ambiguous unit.

    Returns
    -------
    float
        The value in SI units.
    """
    import numbers

    from .errors import OptionError
    from .nomenclature import QUANTITIES, range_problem

    q = QUANTITIES[name]
    label = where or name
    if isinstance(value, bool):
        raise OptionError(f"{label}: expected a number with an optional unit, got {value!r}")
    if isinstance(value, numbers.Real):
        si = float(value)
    elif isinstance(value, str):
        try:
            si = parse_quantity(value, SI_UNIT[q.kind].replace("**", "^"), q.kind, notes)
        except UnitError as exc:
            raise OptionError(f"{label}: {exc}") from None
    elif hasattr(value, "magnitude") and hasattr(value, "units"):  # a pint Quantity
        try:
            si = float(value.magnitude) * conversion(str(value.units), q.kind)[0]
        except (UnitError, TypeError, ValueError) as exc:
            raise OptionError(f"{label}: {exc}") from None
    else:
        raise OptionError(
            f"{label}: expected a number, a string such as '10 kN/m^3' or a pint Quantity, got {type(value).__name__}"
        )
    if si != si or si in (float("inf"), float("-inf")):
        raise OptionError(f"{label}: {value!r} is not a finite number")
    problem = range_problem(name, si)
    if problem:
        raise OptionError(f"{label}: {problem}")
    return si
