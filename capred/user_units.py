"""Records that hold SI values and offer each in its output unit (``rec.tau_kPa``).

Derived from the field's one :func:`capred.records.output` declaration; the old SI names warn for one release (README,
"Renamed in this release").
"""

from __future__ import annotations

import dataclasses

from .nomenclature import unit_suffix
from .records import scale_value


class _RenamedField:
    """The old attribute of a field stored in SI.

    Every read warns (capred.parameters.deprecated) and gives the SI value.

    A data descriptor: the dataclass's ``__init__`` stores through it (into the instance's ``__dict__``, under
    the field's name). capred's own code never reads through it: :func:`capred.records.field_value`,
    ``rec.si`` and ``rec.replace`` read the instance's ``__dict__`` (``dataclasses.replace`` reads every field by
    its attribute, so it warns for each old name: a record of :func:`user_units` is copied with ``rec.replace``).
    """

    def __init__(self, name: str, new: str, unit: str):
        self.name, self.new, self.unit = name, new, unit

    def __get__(self, obj, cls=None):
        if obj is None:
            return self
        from .parameters import deprecated

        value = obj.__dict__.get(self.name)

        owner = type(obj).__name__
        si = {"kPa": "Pa", "MPa": "Pa", "mm": "m", "1/kPa": "1/Pa", "kPa^2": "Pa^2"}.get(self.unit, "SI")
        return deprecated(f"{owner}.{self.name} [{si}]", f"{owner}.{self.new} [{self.unit}]", value)

    def __set__(self, obj, value):
        obj.__dict__[self.name] = value


class SIValues:
    """The SI values of a record's fields, read without deprecation warnings: ``rec.si.tau`` [Pa].

    For code that hands a record's values to capred.physics (which works in SI). A lab script reads the
    attributes in the JSON's units (``rec.tau_kPa``).

    Parameters
    ----------
    record : dataclass instance
        A record decorated with :func:`user_units`.
    """

    def __init__(self, record):
        object.__setattr__(self, "_record", record)

    def __getattr__(self, name: str):
        try:
            return vars(self._record)[name]
        except KeyError:
            raise AttributeError(f"{type(self._record).__name__} has no field {name!r}") from None

    def __repr__(self) -> str:
        return f"<SI values of {type(self._record).__name__}: {', '.join(vars(self._record))}>"


def user_units(cls):
    """Class decorator: a record whose fields hold SI values offers each one in its output unit.

    For every output field with a unit and a scale (``output("sigma_cap_kPa", ..., "kPa", 1e-3)``) the record
    gains the attribute ``<field>_<unit>`` (``sigma_cap_kPa``) in the unit of the JSON and console, derived from
    the one declaration; the field's own name keeps its SI value for one release and raises a
    DeprecationWarning naming the new attribute (README, "Renamed in this release"). ``rec.si.<field>`` reads
    the SI value without a warning (for code that calls capred.physics). Apply above ``@dataclass``.

    Parameters
    ----------
    cls : type
        A dataclass whose fields were declared with :func:`output`.

    Returns
    -------
    type
        ``cls``, with the new attributes, a ``si`` view, a silent ``replace`` and a short ``repr``.
    """
    renamed = {}
    for f in dataclasses.fields(cls):
        spec = f.metadata.get("output")
        if spec is None or spec.scale == 1.0 or not spec.unit:
            continue
        new = f"{f.name}_{unit_suffix(spec.unit)}"
        renamed[f.name] = new
        setattr(cls, f.name, _RenamedField(f.name, new, spec.unit))

        def getter(self, _name=f.name, _scale=spec.scale):
            return scale_value(self.__dict__.get(_name), _scale)

        getter.__doc__ = f"``{f.name}`` in [{spec.unit}], the unit of the JSON and console (None if not computed)."
        setattr(cls, new, property(getter, doc=getter.__doc__))
    cls.RENAMED = renamed

    def si(self):
        return SIValues(self)

    def replace(self, **changes):
        return type(self)(**{f.name: self.__dict__.get(f.name) for f in dataclasses.fields(self) if f.init} | changes)

    replace.__doc__ = (
        "A copy with ``changes`` (SI values, as the constructor takes them), every other field's stored value "
        "kept: ``dataclasses.replace`` without the old names' deprecation warnings."
    )
    cls.replace = replace

    si.__doc__ = "The fields' SI values, read without deprecation warnings (:class:`capred.user_units.SIValues`)."
    cls.si = property(si, doc=si.__doc__)

    def __repr__(self):
        head = [f"{k}={v!r}" for k, v in vars(self).items() if isinstance(v, str)]
        shown = []
        for k, v in vars(self).items():
            if v is None or isinstance(v, str):
                continue
            if isinstance(v, (int, float)):  # a scalar: its value in the output unit
                shown.append(f"{renamed.get(k, k)}={getattr(self, renamed.get(k, k))!r}")
            else:
                shown.append(renamed.get(k, k))
        return f"{cls.__name__}({', '.join(head + shown)})"

    cls.__repr__ = __repr__
    return cls
