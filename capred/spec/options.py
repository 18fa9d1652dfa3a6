"""The base of every command's options, and the declarative checks of their values.

An Options class is a frozen dataclass whose fields are the command's options. Two class attributes declare how
a field is read and checked, so that the class holds no hand-written check of a plain value:

- ``QUANTITIES`` maps a dimensional field to its glossary entry (``capred.nomenclature.QUANTITIES``): it takes a
  number in SI, a string with a unit (``"10 kN/m^3"``) or a pint Quantity, holds SI after construction, and is
  range checked with the glossary's limits and wording;
- ``CONSTRAINTS`` maps any other field to a constraint (`Interval`, `Whole`, `StrOptions`, `Probability`, in the
  spirit of scikit-learn's ``_parameter_constraints``): the base ``__post_init__`` refuses a value that breaks it
  with ``"field (--option) must <rule> (got <value>)"``. NaN and ±inf break every numeric constraint.

The command line reads the same declarations (capred.cli.declare): an option's help, unit, range and default
come from here, at run time.

Numpy-free (see :mod:`capred.spec`): pint is imported when a dimensional value is read, at run time only.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from pathlib import Path

from ..errors import OptionError

# --- constraints -----------------------------------------------------------------------------------------------


class Constraint:
    """A rule an option's value must follow; ``text`` completes "FIELD (--option) must ..." in messages.

    None (an option not given) passes every constraint.
    """

    text = "be valid"
    #: what the message adds after the value given, e.g. ``"0.95 for 95 %"``
    hint = ""

    def accepts(self, value) -> bool:  # pragma: no cover - every constraint defines it
        """Whether ``value`` follows the rule.

        Parameters
        ----------
        value : object
            The field's value (not None).

        Returns
        -------
        bool
        """
        raise NotImplementedError

    def problem(self, where: str, value) -> str | None:
        """The message for ``value``, or None when it follows the rule.

        Parameters
        ----------
        where : str
            The option as messages name it, e.g. ``"seed (--seed)"``.
        value : object
            The field's value.

        Returns
        -------
        str or None
            ``"seed (--seed) must be a whole number >= 0 (got -1)"``.
        """
        if value is None or self.accepts(value):
            return None
        return f"{where} must {self.text} (got {value!r}{'; ' + self.hint if self.hint else ''})"

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.text!r})"


def _real(value) -> bool:
    """A finite real number (not a bool, not NaN, not ±inf)."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)


class Interval(Constraint):
    """A finite real number within ``low`` .. ``high`` (None: unbounded on that side, still finite).

    Parameters
    ----------
    low, high : float or None
        The ends.
    closed : {"both", "left", "right", "neither"}
        Which ends belong to the interval.
    text : str, optional
        The rule in the command's words (default: ``"be > 0"``, ``"lie in (0, 1]"`` ...).
    """

    def __init__(self, low=None, high=None, closed: str = "both", text: str | None = None):
        if closed not in ("both", "left", "right", "neither"):
            raise ValueError(f"closed must be both, left, right or neither (got {closed!r})")
        self.low, self.high, self.closed = low, high, closed
        self.text = text or self._text()

    def _text(self) -> str:
        lo_in, hi_in = self.closed in ("both", "left"), self.closed in ("both", "right")
        if self.low is not None and self.high is not None:
            return f"lie in {'[' if lo_in else '('}{self.low:g}, {self.high:g}{']' if hi_in else ')'}"
        if self.low is not None:
            return f"be {'>=' if lo_in else '>'} {self.low:g}"
        if self.high is not None:
            return f"be {'<=' if hi_in else '<'} {self.high:g}"
        return "be a finite number"

    def range_text(self) -> str:
        """The interval as ``--help`` shows it: ``"> 0"``, ``"0 to 1, both excluded"``.

        Returns
        -------
        str
            Empty for an interval without limits.
        """
        lo_in, hi_in = self.closed in ("both", "left"), self.closed in ("both", "right")
        if self.low is not None and self.high is not None:
            ends = [f"{v:g}" for v, inside in ((self.low, lo_in), (self.high, hi_in)) if not inside]
            return f"{self.low:g} to {self.high:g}" + (f", {' and '.join(ends)} excluded" if ends else "")
        if self.low is not None:
            return f"{'>=' if lo_in else '>'} {self.low:g}"
        if self.high is not None:
            return f"{'<=' if hi_in else '<'} {self.high:g}"
        return ""

    def accepts(self, value) -> bool:
        """Whether ``value`` is a finite real number inside the interval.

        Parameters
        ----------
        value : object
            The field's value (not None).

        Returns
        -------
        bool
        """
        if not _real(value):
            return False
        lo_in, hi_in = self.closed in ("both", "left"), self.closed in ("both", "right")
        if self.low is not None and not (value >= self.low if lo_in else value > self.low):
            return False
        return self.high is None or (value <= self.high if hi_in else value < self.high)


class Probability(Interval):
    """A probability or confidence level: a finite number strictly between 0 and 1.

    Parameters
    ----------
    text : str, optional
        The rule in the command's words (default ``"lie strictly between 0 and 1, e.g. 0.95"``).
    hint : str, optional
        What the message adds after the value given (``"0.95 for 95 %"``).
    """

    def __init__(self, text: str | None = None, hint: str = ""):
        super().__init__(0.0, 1.0, closed="neither", text=text or "lie strictly between 0 and 1, e.g. 0.95")
        self.hint = hint


class Whole(Constraint):
    """A whole number (a Python ``int``, not a bool) within ``min`` .. ``max`` (both included).

    Parameters
    ----------
    min, max : int or None
        The smallest and largest value allowed (None: no limit).
    text : str, optional
        The rule in the command's words (default ``"be a whole number >= 0"``).
    """

    def __init__(self, min: int | None = None, max: int | None = None, text: str | None = None):
        self.min, self.max = min, max
        limits = " and ".join(
            x for x in (f">= {min}" if min is not None else "", f"<= {max}" if max is not None else "") if x
        )
        self.text = text or ("be a whole number" + (f" {limits}" if limits else ""))

    def range_text(self) -> str:
        """The limits as ``--help`` shows them: ``">= 0"``.

        Returns
        -------
        str
            Empty without limits.
        """
        parts = [f">= {self.min}" if self.min is not None else "", f"<= {self.max}" if self.max is not None else ""]
        return " and ".join(p for p in parts if p)

    def accepts(self, value) -> bool:
        """Whether ``value`` is a whole number (an ``int``, not a bool) within the limits.

        Parameters
        ----------
        value : object
            The field's value (not None).

        Returns
        -------
        bool
        """
        if isinstance(value, bool) or not isinstance(value, int):
            return False
        return (self.min is None or value >= self.min) and (self.max is None or value <= self.max)


class StrOptions(Constraint):
    """One of a set of words.

    Parameters
    ----------
    options : iterable of str
        The words allowed, in the order messages list them.
    text : str, optional
        The rule in the command's words (default ``"be a, b or c"``).
    """

    def __init__(self, options, text: str | None = None):
        self.options = tuple(options)
        words = list(self.options)
        self.text = text or ("be " + (", ".join(words[:-1]) + " or " + words[-1] if len(words) > 1 else words[0]))

    def accepts(self, value) -> bool:
        """Whether ``value`` is one of the words allowed.

        Parameters
        ----------
        value : object
            The field's value (not None).

        Returns
        -------
        bool
        """
        return isinstance(value, str) and value in self.options


class Flag(Constraint):
    """True or False (a Python bool: not 0, 1 or a word)."""

    text = "be True or False"

    def accepts(self, value) -> bool:
        """Whether ``value`` is a bool.

        Parameters
        ----------
        value : object
            The field's value (not None).

        Returns
        -------
        bool
        """
        return isinstance(value, bool)


# --- the Options base ------------------------------------------------------------------------------------------


class Options:
    """Base of every command's options dataclass.

    ``QUANTITIES`` maps a dimensional field to its nomenclature name. Such a
    field accepts a number in SI, a string with a unit (``"10 kN/m^3"``) or a
    pint Quantity, and holds SI after construction. Values are range checked;
    implausible constants give warnings (``self.warnings``). ``CONSTRAINTS``
    maps a field to a `Constraint` checked after the quantities are read.
    """

    QUANTITIES: dict[str, str] = {}
    #: command-line spelling of a field where it is not --field-name
    OPTION_NAMES: dict[str, str] = {}
    #: field -> Constraint its value must follow (checked by ``__post_init__``, shown by ``--help``)
    CONSTRAINTS: dict[str, Constraint] = {}

    def option_name(self, field_name: str) -> str:
        """An option's name for messages: the Python keyword and the command-line option.

        Parameters
        ----------
        field_name : str
            The field of the options class, e.g. "gamma_w".

        Returns
        -------
        str
            E.g. ``"gamma_w (--gamma-w)"``.
        """
        cli = self.OPTION_NAMES.get(field_name, "--" + field_name.replace("_", "-"))
        return f"{field_name} ({cli})"

    def __post_init__(self) -> None:
        warnings: list[str] = []
        notes: list[str] = []
        if self.QUANTITIES:
            from ..nomenclature import plausibility_warning
            from ..units import to_si  # pint: at run time only

            for name, quantity in self.QUANTITIES.items():
                value = getattr(self, name)
                if value is None:
                    continue
                where = self.option_name(name)
                try:
                    si = to_si(value, quantity, where, notes)
                except OptionError as exc:  # quote the value as the API caller gave it, not its SI reading
                    err = OptionError(as_given(str(exc), name, value, quantity))
                    err.as_given = True  # quoted: a subclass's own quoting leaves it as it is
                    raise err from None
                object.__setattr__(self, name, si)
                w = plausibility_warning(quantity, si, where)
                if w:
                    warnings.append(w)
        object.__setattr__(self, "_warnings", warnings)
        object.__setattr__(self, "_notes", notes)
        self.check_constraints()

    def check_constraints(self) -> None:
        """Refuse a field whose value breaks its declared constraint (``CONSTRAINTS``).

        Raises
        ------
        OptionError
            ``"field (--option) must ... (got ...)"``, for the first field in declaration order.
        """
        for name, rule in self.CONSTRAINTS.items():
            problem = rule.problem(self.option_name(name), getattr(self, name))
            if problem:
                raise OptionError(problem)

    @property
    def warnings(self) -> list[str]:
        """Implausible option values (e.g. a unit weight of water of 10 N/m^3)."""
        return list(getattr(self, "_warnings", []))

    @property
    def unit_notes(self) -> list[str]:
        """How option units were read (e.g. g/cm^2 as gram-force per cm^2)."""
        return list(getattr(self, "_notes", []))

    def record(self) -> tuple[dict, dict]:
        """The options as the JSON records them.

        Returns
        -------
        values : dict
            Every option by field name, with its SI value.
        units : dict
            The SI unit of each dimensional option (``"Pa"``, ``"N/m"``).
        """
        from ..nomenclature import QUANTITIES
        from ..units import SI_UNIT

        values, units = {}, {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name.startswith("_") or (f.metadata.get("omit_when_empty") and not v):
                continue
            values[f.name] = _plain(v)
            if f.name in self.QUANTITIES:
                units[f.name] = SI_UNIT[QUANTITIES[self.QUANTITIES[f.name]].kind].replace("**", "^")
        return values, units


def as_given(message: str, name: str, value, quantity: str) -> str:
    """An option's error message with its value quoted as the caller gave it (issue 28).

    The glossary's range check shows the SI reading in the output unit: ``box_area=-3`` (a plain number, read in
    m^2) reads "(got -30000 cm^2)", a value the caller never typed. The message keeps that reading beside the
    value as given, says which unit a plain number is read in and how to give one; a string is quoted as typed
    (with its reading where its unit is not the output unit).

    Parameters
    ----------
    message : str
        The message of capred.units.to_si, starting with the option's name.
    name : str
        The options field (the API keyword), e.g. "box_area".
    value : object
        The value as given.
    quantity : str
        Its glossary entry (a key of capred.nomenclature.QUANTITIES).

    Returns
    -------
    str
        E.g. ``"box_area (--box-area): shear box area must be > 0 cm^2 (got box_area=-3, a plain number read in
        m^2, that is -30000 cm^2; give a unit, e.g. box_area='-3 cm^2')"``.
    """
    import re

    from ..nomenclature import QUANTITIES
    from ..units import SI_UNIT

    q = QUANTITIES[quantity]
    m = re.search(r" \(got ([^()]*)\)$", message)
    reading = m.group(1) if m else None
    base = message[: m.start()] if m else message
    that = f", that is {reading}" if reading else ""
    if isinstance(value, str):
        if reading is not None and reading.replace(" ", "") == value.strip().replace(" ", ""):
            that = ""  # the reading is the value as typed
        return f"{base} (got {name}={value!r}{that})"
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        si = SI_UNIT[q.kind].replace("**", "^")
        if not math.isfinite(value) or q.unit in ("-", "", si):
            return f"{base} (got {name}={value!r})"
        return (
            f"{base} (got {name}={value!r}, a plain number read in {si}{that}; give a unit, "
            f"e.g. {name}='{value!r} {q.unit}')"
        )
    return f"{base} (got {value}{that})"  # a pint Quantity, as it prints


def _plain(v):
    """A JSON-ready copy of an option value (tuples as lists, dataclasses as dicts, paths as text)."""
    if dataclasses.is_dataclass(v):  # a field declared omit_when_empty appears only when it holds something
        return {
            f.name: _plain(getattr(v, f.name))
            for f in dataclasses.fields(v)
            if getattr(v, f.name) or not f.metadata.get("omit_when_empty")
        }
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, Path):
        return str(v)
    if isinstance(v, float) and not math.isfinite(v):
        return None  # as every JSON file writes it (null): the API's document equals the file's
    return v


__all__ = ["Constraint", "Flag", "Interval", "Options", "Probability", "StrOptions", "Whole", "as_given"]
