"""Fitted parameters as a user reads them: one record per parameter, in the units of the JSON and console.

Every fit capred exposes (a dry envelope, a retention model, a χ law, an effective envelope) offers
``fit.params[NAME]`` where NAME is exactly the parameter's JSON name (``c_kPa``, ``phi_deg``,
``theta_r``, ``alpha_per_kPa``, ``n`` ...) and ``fit.summary()``, a plain-text report in the spirit of
lmfit's ``fit_report()``. SI values stay inside ``capred.physics`` and ``capred.fitting``; this module is
where they meet the user's units, once.

It also holds the one rule for renamed attributes (:func:`deprecated`): an old Python name keeps its old
value and unit for one release and warns with its replacement.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field

#: correlations whose absolute value exceeds this are listed by :func:`fit_report` (lmfit's default 0.1 is
#: chatty for two-parameter envelopes; 0.9 flags the pairs a lab should look at)
CORRELATION_SHOWN = 0.9


@dataclass(frozen=True)
class Parameter:
    """One fitted parameter in the user's unit.

    Attributes
    ----------
    name : str
        The JSON name, e.g. ``"c_kPa"``, ``"alpha_per_kPa"``, ``"n"``.
    value : float
        Best estimate [``unit``].
    stderr : float
        Standard error [``unit``] (NaN when the fit gives none, e.g. a parameter fixed by the user).
    ci95 : tuple of float
        Lower and upper limit of its 95 % confidence interval [``unit``] (NaN, NaN when not available).
    unit : str
        Unit of ``value``, ``stderr`` and ``ci95`` (``"-"`` for a dimensionless number).
    description : str
        What the parameter is, from the glossary.
    fixed : bool
        True when the value was imposed rather than fitted (e.g. c = 0 through the origin).
    """

    name: str
    value: float
    stderr: float = math.nan
    ci95: tuple[float, float] = (math.nan, math.nan)
    unit: str = "-"
    description: str = ""
    fixed: bool = False

    @property
    def relative_stderr(self) -> float:
        """Relative standard error, stderr / |value| [-] (inf when the value is 0 and the error is not)."""
        if self.value == 0:
            return 0.0 if self.stderr == 0 else math.inf
        return abs(self.stderr / self.value)

    def __float__(self) -> float:
        return float(self.value)

    # A Parameter reads as its value in arithmetic, comparisons and numpy (as lmfit's Parameter does), so a lab
    # script written against a plain float keeps working where the unit did not change.
    def __array__(self, dtype=None, copy=None):
        import numpy as np

        return np.asarray(self.value, dtype=dtype)

    def __add__(self, other):
        return self.value + other

    def __radd__(self, other):
        return other + self.value

    def __sub__(self, other):
        return self.value - other

    def __rsub__(self, other):
        return other - self.value

    def __mul__(self, other):
        return self.value * other

    def __rmul__(self, other):
        return other * self.value

    def __truediv__(self, other):
        return self.value / other

    def __rtruediv__(self, other):
        return other / self.value

    def __pow__(self, other):
        return self.value**other

    def __rpow__(self, other):
        return other**self.value

    def __neg__(self):
        return -self.value

    def __abs__(self):
        return abs(self.value)

    def __lt__(self, other):
        return self.value < other

    def __le__(self, other):
        return self.value <= other

    def __gt__(self, other):
        return self.value > other

    def __ge__(self, other):
        return self.value >= other

    def __repr__(self) -> str:
        return f"<Parameter {self.name} = {_fmt(self.value)} ± {_fmt(self.stderr)} {self.unit}>"


@dataclass(frozen=True)
class Parameters(Mapping):
    """The parameters of one fit, by JSON name, in fit order; ``correlation`` maps (name, name) pairs.

    Attributes
    ----------
    items_ : tuple of Parameter
        The parameters in the order of the fit.
    correlation : dict
        ``{(a, b): r}`` for every fitted pair (a before b) [-].
    """

    items_: tuple[Parameter, ...]
    correlation: dict = field(default_factory=dict)

    def __getitem__(self, name: str) -> Parameter:
        for p in self.items_:
            if p.name == name:
                return p
        raise KeyError(f"no parameter {name!r}; this fit has {', '.join(p.name for p in self.items_)}")

    def __iter__(self) -> Iterator[str]:
        return (p.name for p in self.items_)

    def __len__(self) -> int:
        return len(self.items_)

    def valuesdict(self) -> dict[str, float]:
        """The values by name, as lmfit's method of the same name.

        Returns
        -------
        dict of str to float
            ``{name: value}`` as plain floats, in the record's units.
        """
        return {p.name: float(p.value) for p in self.items_}

    def __repr__(self) -> str:
        return "Parameters(" + ", ".join(f"{p.name}={_fmt(p.value)}" for p in self.items_) + ")"


def correlation_from_covariance(names, covariance) -> dict:
    """``{(a, b): r_ab}`` of every pair of ``names`` from a covariance matrix (any consistent units).

    Pairs involving a parameter with zero or undefined variance are left out.

    Parameters
    ----------
    names : sequence of str
        Parameter names, in the order of the matrix's rows.
    covariance : array_like, shape (n, n)
        Covariance matrix.

    Returns
    -------
    dict
        ``(a, b)`` (``a`` before ``b`` in ``names``) -> correlation coefficient [-].
    """
    import numpy as np

    cov = np.asarray(covariance, dtype=float)
    out = {}
    for i, a in enumerate(names):
        for j in range(i + 1, len(names)):
            d = cov[i, i] * cov[j, j]
            if np.isfinite(d) and d > 0:
                out[(a, names[j])] = float(cov[i, j] / math.sqrt(d))
    return out


def fit_report(title: str, params: Parameters, statistics: Mapping | None = None, warnings_=()) -> str:
    """A plain-text report of one fit: parameters with SE and 95 % CI, strong correlations, statistics, warnings.

    Parameters
    ----------
    title : str
        First line, e.g. ``"van Genuchten fit of drying (retention.csv)"``.
    params : Parameters
        The fitted parameters.
    statistics : mapping, optional
        ``{label: value}`` shown under "Fit statistics" (n, dof, R², AICc ...), in the order given.
    warnings_ : sequence of str
        Lines shown under "Warnings".

    Returns
    -------
    str
        The report, lines of at most ~80 characters for the numbers.
    """
    lines = [f"[[{title}]]"]
    if statistics:
        lines.append("[[Fit statistics]]")
        for k, v in statistics.items():
            lines.append(f"    {k:<14} = {_fmt(v)}")
    lines.append("[[Parameters]]  value ± standard error  (95 % confidence interval)  unit")
    width = max((len(p.name) for p in params.items_), default=4)
    for p in params.items_:
        if p.fixed:
            lines.append(f"    {p.name:<{width}} = {_fmt(p.value)} (fixed) {p.unit}")
            continue
        rel = f" ({100 * p.relative_stderr:.1f} %)" if math.isfinite(p.relative_stderr) and p.value else ""
        lines.append(
            f"    {p.name:<{width}} = {_fmt(p.value)} ± {_fmt(p.stderr)}{rel}  "
            f"({_fmt(p.ci95[0])}, {_fmt(p.ci95[1])})  {p.unit}"
        )
    strong = [(k, r) for k, r in params.correlation.items() if abs(r) > CORRELATION_SHOWN]
    if strong:
        lines.append(f"[[Correlations]] (|r| > {CORRELATION_SHOWN})")
        for (a, b), r in sorted(strong, key=lambda kr: -abs(kr[1])):
            lines.append(f"    C({a}, {b}) = {r:+.4f}")
    if warnings_:
        lines.append("[[Warnings]]")
        lines.extend(f"    {w}" for w in warnings_)
    return "\n".join(lines)


def _fmt(v) -> str:
    try:
        v = float(v)
    except (TypeError, ValueError):
        return str(v)
    if math.isnan(v):
        return "—"
    return f"{v:.6g}"


def deprecated(old: str, new: str, value):
    """Return ``value`` (in the OLD name's unit) and warn that ``old`` is replaced by ``new``.

    The one rule for renamed Python attributes (README, "Renamed"): an old name keeps its old value and unit
    for one release and raises a DeprecationWarning naming its replacement, so that a lab script never reads
    kPa where it read Pa without being told.

    Parameters
    ----------
    old : str
        The deprecated attribute, e.g. "fit.c".
    new : str
        Its replacement, e.g. "fit.params['c']".
    value : object
        The old attribute's value.

    Returns
    -------
    object
        ``value``, unchanged.
    """
    warnings.warn(
        f"{old} is deprecated and will be removed in the next release; use {new} (in the units of the JSON)",
        DeprecationWarning,
        stacklevel=3,
    )
    return value


def non_finite_options(options) -> list[str]:
    """The fields of an Options record holding NaN or an infinity that their default does not hold.

    Alone or in a tuple or list of values: an option is a number a user typed, and ``nan`` or ``inf`` parse as floats
    but are no value of any quantity.

    Parameters
    ----------
    options : dataclass instance
        A command's Options (``ShearOptions``, ``LawsOptions`` ...).

    Returns
    -------
    list of str
        ``"--field-name = nan"`` for each such field, in field order (empty: every number is finite).
    """
    import dataclasses

    if not dataclasses.is_dataclass(options) or isinstance(options, type):
        return []

    def bad(value) -> list:
        if isinstance(value, bool):
            return []
        if isinstance(value, float):
            return [] if math.isfinite(value) else [value]
        if isinstance(value, (tuple, list)):
            return [v for item in value for v in bad(item)]
        return []

    out = []
    for f in dataclasses.fields(options):
        if f.name.startswith("_") or not f.init:  # not an option a user sets
            continue
        value = getattr(options, f.name, None)
        values = bad(value)
        if not values:
            continue
        default = f.default if f.default is not dataclasses.MISSING else None
        if repr(value) == repr(default):  # the default itself, not set by the user
            continue
        allowed = {v for v in bad(default) if not math.isnan(v)}  # what the default holds (inf: 'plane', no bound)
        values = [v for v in values if v not in allowed]
        if not values:
            continue
        shown = ", ".join(repr(v) for v in values[:3])
        out.append(f"--{f.name.replace('_', '-')} = {shown}")
    return out
