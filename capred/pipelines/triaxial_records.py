"""Typed records of `capred triaxial-bounds`: the tests, their bounds, the effective envelope and the groups.

Every numeric field names its glossary entry (capred.nomenclature.QUANTITIES) once, with :func:`quantity`;
from it follow

- the Python attribute (the field's name) and its value, in the unit of the JSON and console (kPa, deg, -),
- the JSON key: the name plus ``_kPa`` / ``_deg`` (nothing for a dimensionless number), ``_se`` before the
  unit for a standard error, ``_ci95`` for a 95 % interval ``[low, high]``,
- the CSV header ``name [unit]`` (``name_ci95_low [unit]`` / ``_high`` for an interval),
- the console and HTML header ``symbol [unit]`` (capred.nomenclature.label).

Text fields (identifiers, methods, notes) are declared with :func:`text`. The JSON keys are those of capred
0.x: nothing changed meaning. The CSV headers all have the ``name [unit]`` form (README, "Renamed").
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..nomenclature import QUANTITIES
from ..parameters import Parameter, Parameters, deprecated, fit_report
from ..physics import triaxial as tx
from ..references import cite
from ..result import num

if TYPE_CHECKING:
    from ..fitting.linear import LineFit

#: Pa per kPa: the records hold the user's units, the physics SI
KPA = 1e3
#: how the envelope of a run without saturated tests is named, wherever it is shown
EXTENDED_MC_METHOD = (
    "extended Mohr-Coulomb envelope at s -> 0 (Fredlund et al. 1978) fitted to the unsaturated failure states, "
    "their initial suction s0 taken as the suction at failure"
)

#: JSON key suffix of each output unit
_SUFFIX = {"kPa": "_kPa", "deg": "_deg", "-": "", "mm": "_mm"}


def quantity(
    name: str, *, se: bool = False, ci: bool = False, optional: bool = False, many: bool = False, init: bool = True
):
    """A record field holding glossary quantity ``name`` in its output unit.

    Parameters
    ----------
    name : str
        Key of capred.nomenclature.QUANTITIES.
    se, ci : bool
        The field is the standard error (``name_se``) or the 95 % interval (``name_ci95``, a pair) of it.
    optional : bool
        Left out of the JSON when None (keys that exist only when computed).
    many : bool
        A list of values per record (e.g. the Lode angles of a group's tests): its JSON key and CSV header
        take the field's name (``lode_angles_deg``) with the quantity's unit.
    init : bool
        The field is an argument of the record's constructor.

    Returns
    -------
    dataclasses.Field
        The field, default None, its declaration in ``metadata``.
    """
    if name not in QUANTITIES:
        raise KeyError(f"{name!r} is not in the glossary (capred.nomenclature.QUANTITIES)")
    meta = {"quantity": name, "se": se, "ci": ci, "optional": optional, "many": many}
    return field(default=None, metadata=meta, init=init)


def text(json: str | None = None, *, optional: bool = False, kind: str = "text", init: bool = True):
    """A record field of text (or ``kind`` "int", "bool", "number", "list", "record", "records").

    ``json`` overrides its JSON key (the field's name by default).

    Parameters
    ----------
    json : str, optional
        JSON key (default: the field's name).
    optional : bool, optional
        Left out of the JSON when None.
    kind : str, optional
        ``text``, ``int``, ``bool``, ``number``, ``list``, ``record`` or ``records``.
    init : bool, optional
        The field is an argument of the record's constructor.

    Returns
    -------
    dataclasses.Field
        The field, default None.
    """
    return field(default=None, metadata={"text": kind, "json": json, "optional": optional}, init=init)


def json_key(f: dataclasses.Field) -> str:
    """The JSON key of a record field (see the module docstring).

    Parameters
    ----------
    f : dataclasses.Field
        A field of a record.

    Returns
    -------
    str
        Its JSON key (a quantity's name with its unit's suffix, e.g. ``_kPa``).
    """
    m = f.metadata
    if "quantity" not in m:
        return m.get("json") or f.name
    base = (f.name if m["many"] else m["quantity"]) + ("_se" if m["se"] else "") + ("_ci95" if m["ci"] else "")
    return base + _SUFFIX.get(QUANTITIES[m["quantity"]].unit, "")


def csv_headers(f: dataclasses.Field, prefix: str = "") -> tuple[str, ...]:
    """The CSV header(s) of a record field: ``name [unit]`` (two for an interval), the name for text.

    Parameters
    ----------
    f : dataclasses.Field
        A field of a record.
    prefix : str, optional
        Put before the name (a nested record's ``name.``).

    Returns
    -------
    tuple of str
        The header(s).
    """
    m = f.metadata
    if "quantity" not in m:
        return (prefix + (m.get("json") or f.name),)
    unit = QUANTITIES[m["quantity"]].unit
    base = prefix + (f.name if m["many"] else m["quantity"]) + ("_se" if m["se"] else "")
    if m["ci"]:
        return (f"{base}_ci95_low [{unit}]", f"{base}_ci95_high [{unit}]")
    return (f"{base} [{unit}]",)


def _plain(value, kind: str | None):
    if value is None:
        return None
    if kind == "int":
        return int(value)
    if kind == "bool":
        return bool(value)
    if kind == "list":
        return [None if x is None or x == "" else x for x in value]
    if kind == "text":
        return None if value == "" else str(value)
    if kind == "number":
        return num(value)
    return value


def _number(value, m) -> object:
    if value is None:
        return None
    if m["ci"]:
        return None if value is None else [num(value[0]), num(value[1])]
    if m["many"]:
        return [num(x) for x in value]
    return num(value)


def to_json(record) -> dict:
    """A scalar record (envelope, group, one test's bound) as its JSON object, keys in declaration order.

    Parameters
    ----------
    record : dataclass
        A record of this module.

    Returns
    -------
    dict
        JSON key -> value (numbers in the glossary's units; None left out of optional fields).
    """
    out = {}
    for f in dataclasses.fields(record):
        if not f.metadata:
            continue
        v = getattr(record, f.name)
        if f.metadata.get("optional") and v is None:
            continue
        if "quantity" in f.metadata:
            out[json_key(f)] = _number(v, f.metadata)
        elif dataclasses.is_dataclass(v):
            out[json_key(f)] = to_json(v)
        elif f.metadata["text"] == "records":
            out[json_key(f)] = [to_json(x) for x in v]
        else:
            out[json_key(f)] = _plain(v, f.metadata["text"])
    return out


def store_rows(record, material=None, intervals=None) -> list:
    """The lab store's rows of a scalar record: each glossary quantity field with its JSON key, value and unit.

    Value or standard error, its JSON key as :func:`to_json` writes it (:func:`json_key`), the glossary unit; a value's
    95 % interval is its ``ci`` field or ``intervals[key]``. Text fields are not recorded; a value that is not a finite
    number is left out.

    Parameters
    ----------
    record : dataclass
        A record of this module (the envelope).
    material : str, optional
        The material of the rows.
    intervals : dict, optional
        JSON key -> (low, high), for values whose interval the record does not hold.

    Returns
    -------
    list of capred.records.StoreRow
    """
    from ..records import store_row

    fields = [f for f in dataclasses.fields(record) if "quantity" in f.metadata and not f.metadata["many"]]
    found = dict(intervals or {})
    for f in fields:
        if f.metadata["ci"]:
            value = getattr(record, f.name)
            twin = [g for g in fields if g.metadata["quantity"] == f.metadata["quantity"] and not g.metadata["se"]]
            if value is not None and twin:
                found.setdefault(json_key(twin[0]), value)
    rows = []
    for f in fields:
        if f.metadata["ci"]:
            continue
        key, unit = json_key(f), QUANTITIES[f.metadata["quantity"]].unit
        ci = None if f.metadata["se"] else found.get(key)
        row = store_row(material, key, num(getattr(record, f.name)), unit, ci)
        if row is not None:
            rows.append(row)
    return rows


def row_json(record, i: int) -> dict:
    """Row ``i`` of a per-test record (arrays over the tests) as its JSON object.

    Parameters
    ----------
    record : dataclass
        A per-test record.
    i : int
        Row of the test (0-based).

    Returns
    -------
    dict
        JSON key -> value.
    """
    out = {}
    for f in dataclasses.fields(record):
        if not f.metadata:
            continue
        v = getattr(record, f.name)[i]
        out[json_key(f)] = num(v) if "quantity" in f.metadata else _plain(v, f.metadata["text"])
    return out


def row_csv(record, prefix: str = "") -> dict:
    """A record's CSV columns ``{header: value}`` (a scalar record: one row; a per-test record: arrays).

    Parameters
    ----------
    record : dataclass
        A record of this module.
    prefix : str, optional
        Put before each header (a nested record's ``name.``).

    Returns
    -------
    dict
        ``name [unit]`` header -> value (or array of values).
    """
    out = {}
    for f in dataclasses.fields(record):
        if not f.metadata:
            continue
        v = getattr(record, f.name)
        heads = csv_headers(f, prefix)
        if f.metadata.get("ci"):
            lo, hi = (None, None) if v is None else v
            out[heads[0]], out[heads[1]] = num(lo) if lo is not None else None, num(hi) if hi is not None else None
        elif dataclasses.is_dataclass(v):
            out.update(row_csv(v, prefix + f.name + "."))
        elif isinstance(v, np.ndarray):  # a per-test record's column
            text_col = "quantity" not in f.metadata and v.dtype.kind not in "biuf"
            out[heads[0]] = np.array([None if x == "" else x for x in v], dtype=object) if text_col else v
        elif isinstance(v, (list, tuple)):
            out[heads[0]] = ";".join("" if x is None else (x if isinstance(x, str) else repr(x)) for x in v)
        else:
            out[heads[0]] = _plain(v, f.metadata.get("text")) if "text" in f.metadata else v
    return out


@dataclass(frozen=True)
class TestStates:
    """Every test's failure state, one array per field over the tests of the table, in output units.

    Stresses are net of the pore pressure (σ − u_b saturated, σ − u_a unsaturated; compression positive).

    Attributes
    ----------
    test_id, condition, group, branch, pair : ndarray of str
        Identifier, ``saturated`` / ``unsaturated``, group (``""``: none), loading branch (compression,
        extension, general) and paired saturated test (``""``: none).
    line : ndarray of int
        Line of the test in its input file.
    sigma3, sigma2, sigma1, p, q : ndarray
        Principal stresses, mean stress and deviator at failure [kPa].
    p0, s0 : ndarray
        Initial mean stress (net) and initial suction [kPa] (NaN when not given).
    sigma3_total, back_pressure, u_a, radial_pressure : ndarray
        The cell pressure as given and the pressures it was reduced with [kPa] (NaN when unknown).
    membrane_correction : ndarray
        Membrane correction subtracted from q [kPa] (NaN without one; ASTM D4767).
    lode_angle : ndarray
        Lode angle [deg]: 0 in compression, 60 in extension (round-off of exact tests snapped).
    strain_at_failure : ndarray
        Axial strain at failure [-] (NaN when unknown).
    q_sat : ndarray
        Drained saturated strength at the test's p0 [kPa] (NaN on saturated tests).
    skempton_A : ndarray
        Skempton's A at failure, (Δu − B Δσ3)/(B (Δσ1 − Δσ3)) over the shear stage of the test's curve [-]
        (NaN without a curve that logs the pore pressure; Skempton 1954).
    suction, S_R, void_ratio : ndarray
        Matric suction [kPa], degree of saturation [-] and void ratio [-] at failure, as the test's export logs
        them (``Matric Suction``, ``Degree of Saturation``, ``Voids ratio``; NaN where it does not).
    """

    test_id: np.ndarray = text()
    condition: np.ndarray = text()
    group: np.ndarray = text()
    line: np.ndarray = text(kind="int")
    sigma3: np.ndarray = quantity("sigma3")
    sigma2: np.ndarray = quantity("sigma2")
    sigma1: np.ndarray = quantity("sigma1")
    p: np.ndarray = quantity("p")
    q: np.ndarray = quantity("q")
    p0: np.ndarray = quantity("p0")
    s0: np.ndarray = quantity("s0")
    sigma3_total: np.ndarray = quantity("sigma3_total")
    back_pressure: np.ndarray = quantity("back_pressure")
    u_a: np.ndarray = quantity("u_a")
    radial_pressure: np.ndarray = quantity("radial_pressure")
    membrane_correction: np.ndarray = quantity("membrane_correction")
    lode_angle: np.ndarray = quantity("lode_angle")
    branch: np.ndarray = text()
    pair: np.ndarray = text()
    strain_at_failure: np.ndarray = quantity("strain_at_failure")
    q_sat: np.ndarray = quantity("q_sat")
    skempton_A: np.ndarray = quantity("skempton_A")
    suction: np.ndarray = quantity("suction")
    S_R: np.ndarray = quantity("S_R")
    void_ratio: np.ndarray = quantity("void_ratio")

    def __len__(self) -> int:
        return len(self.test_id)


@dataclass(frozen=True)
class BoundStates:
    """One bound's capillary tensor at failure and its effective image point, arrays over the tests [kPa].

    NaN on saturated tests and where the bound does not apply (true-triaxial tests; EDTP without s0).

    Attributes
    ----------
    sigma1_cap, sigma2_cap, sigma3_cap, p_cap, q_cap : ndarray
        Capillary components, mean and deviator [kPa] (compression positive: tensile is negative).
    p_prime, q_prime : ndarray
        Image point on the effective envelope [kPa].
    gain : ndarray
        q'/q'_sat [-].
    positive_component : ndarray of bool
        A component is > 0 (compressive), against eq. 18/20 of Prunier et al. (2024).
    """

    sigma1_cap: np.ndarray = quantity("sigma1_cap")
    sigma2_cap: np.ndarray = quantity("sigma2_cap")
    sigma3_cap: np.ndarray = quantity("sigma3_cap")
    p_cap: np.ndarray = quantity("p_cap")
    q_cap: np.ndarray = quantity("q_cap")
    p_prime: np.ndarray = quantity("p_prime")
    q_prime: np.ndarray = quantity("q_prime")
    gain: np.ndarray = quantity("gain")
    positive_component: np.ndarray = text(kind="bool")

    def applies(self, i: int) -> bool:
        """True when the bound was computed for test ``i``.

        Parameters
        ----------
        i : int
            Row of the test (0-based).

        Returns
        -------
        bool
        """
        return bool(np.isfinite(self.sigma1_cap[i]))


@dataclass(frozen=True)
class Lower48:
    """Eq. 48 closed with σ1,cap = 0 (kept under the JSON key ``eq48_lower``) [kPa]."""

    C_fictive: float = quantity("C_fictive")
    sigma1_cap: float = quantity("sigma1_cap")
    sigma3_cap: float = quantity("sigma3_cap")


@dataclass(frozen=True)
class Closure:
    """One closure of eq. 48 for a group without paired saturated tests (Prunier et al. 2024, Appendix 1).

    Attributes
    ----------
    name : str
        ``sigma1_cap_zero`` (the lower bound's σ1,cap = 0, eq. 24) or ``spherical`` (eq. 37).
    label : str
        What the closure assumes, in words.
    chosen : bool
        True for the closure capred reports as its one choice (``sigma1_cap_zero``).
    sigma1_cap, sigma2_cap, sigma3_cap, p_cap : float
        The tensor under this closure [kPa].
    """

    name: str = text()
    label: str = text()
    chosen: bool = text(kind="bool")
    sigma1_cap: float = quantity("sigma1_cap")
    sigma2_cap: float = quantity("sigma2_cap")
    sigma3_cap: float = quantity("sigma3_cap")
    p_cap: float = quantity("p_cap")


@dataclass(frozen=True)
class Range:
    """Admissible range of one component [kPa]: ``lower`` and ``upper`` (JSON keys)."""

    lower: float = text(kind="number")
    upper: float = text(kind="number")


@dataclass(frozen=True)
class Admissible:
    """Per component, the range of tensors eq. 37 admits between the paper's closures [kPa]."""

    sigma1_cap: Range = text("sigma1_cap_kPa")
    sigma2_cap: Range = text("sigma2_cap_kPa")
    sigma3_cap: Range = text("sigma3_cap_kPa")
    p_cap: Range = text("p_cap_kPa")


@dataclass(frozen=True)
class GroupRecord:
    """Appendix 1 of Prunier et al. (2024) for one group of unsaturated tests sharing one capillary tensor.

    Values in kPa and degrees; None where not computed. The tensor (``sigma1_cap`` ...) is given only where
    the paper determines it: eq. 48 with the paired saturated tests, or eq. 50. Without pairs it is None and
    ``admissible`` holds each component's range with the ``closures`` that bound it.

    Attributes
    ----------
    group : str
        The group's name.
    tests, pairs : list of str
        Its tests and their paired saturated tests (None: no pair).
    n : int
        Number of tests.
    branch : str
        compression, extension, general (true triaxial) or mixed.
    lode_angles, lode_spread, lode_tol : list, float, float
        Lode angles of its tests, their spread and the tolerance of eq. 49 [deg].
    eq49_holds : bool
        One Lode angle within the tolerance.
    method, needs : str
        How the tensor was obtained; what is missing to obtain it.
    sigma1_cap, sigma2_cap, sigma3_cap : float
        The shared tensor [kPa]; ``*_se`` standard errors, ``*_ci95`` 95 % intervals (t, n − 1 dof).
    p_cap, q_cap : float
        Its mean and deviator [kPa].
    dof : int
        Degrees of freedom of the standard errors.
    C, C_se, C_fictive, C_fictive_se, Ci, Ci_fictive : float
        Cohesions of eq. 48/50 [kPa].
    phi_i, phi_apparent_se : float
        Intermediate friction angle (eq. 50) and the SE of the apparent one [deg].
    apparent_M, apparent_k, C_apparent, phi_apparent, phi_difference, eq37_sigma_cap : float
        The group's apparent (total) envelope and the spherical tensor of eq. 37.
    eq48_lower : Lower48
        Eq. 48 closed with σ1,cap = 0.
    closures : list of Closure
        Without pairs: the closures the paper allows, the chosen one marked.
    admissible : Admissible
        Without pairs: each component's admissible range (``lower``, ``upper``).
    fictive_sigma1, fictive_sigma3 : list of float
        The fictive states σ'' of eq. 44 [kPa].
    error, apparent_error, warning : str
        Why the group or its apparent envelope could not be analysed; a warning.
    """

    group: str = text()
    tests: list = text(kind="list")
    n: int = text(kind="int")
    branch: str = text()
    lode_angles: list = quantity("lode_angle", many=True)
    lode_spread: float = quantity("lode_spread")
    lode_tol: float = quantity("lode_tol")
    eq49_holds: bool = text(kind="bool")
    pairs: list = text(kind="list")
    method: str = text()
    needs: str = text()
    sigma1_cap: float = quantity("sigma1_cap")
    sigma1_cap_se: float = quantity("sigma1_cap", se=True)
    sigma1_cap_ci95: tuple = quantity("sigma1_cap", ci=True)
    sigma2_cap: float = quantity("sigma2_cap")
    sigma2_cap_se: float = quantity("sigma2_cap", se=True)
    sigma2_cap_ci95: tuple = quantity("sigma2_cap", ci=True)
    sigma3_cap: float = quantity("sigma3_cap")
    sigma3_cap_se: float = quantity("sigma3_cap", se=True)
    sigma3_cap_ci95: tuple = quantity("sigma3_cap", ci=True)
    p_cap: float = quantity("p_cap")
    q_cap: float = quantity("q_cap")
    dof: int = text(kind="int")
    C: float = quantity("C")
    C_se: float = quantity("C", se=True)
    C_fictive: float = quantity("C_fictive")
    C_fictive_se: float = quantity("C_fictive", se=True)
    Ci: float = quantity("Ci")
    Ci_fictive: float = quantity("Ci_fictive")
    phi_i: float = quantity("phi_i")
    phi_apparent_se: float = quantity("phi_apparent", se=True)
    apparent_M: float = quantity("apparent_M", optional=True)
    apparent_k: float = quantity("apparent_k", optional=True)
    C_apparent: float = quantity("C_apparent", optional=True)
    phi_apparent: float = quantity("phi_apparent", optional=True)
    phi_difference: float = quantity("phi_difference", optional=True)
    eq37_sigma_cap: float = quantity("eq37_sigma_cap", optional=True)
    eq48_lower: Lower48 = text(optional=True, kind="record")
    closures: list = text(optional=True, kind="records")
    admissible: Admissible = text(optional=True, kind="record")
    fictive_sigma1: list = quantity("fictive_sigma1", many=True, optional=True)
    fictive_sigma3: list = quantity("fictive_sigma3", many=True, optional=True)
    error: str = text(optional=True)
    apparent_error: str = text(optional=True)
    warning: str = text(optional=True)

    def __getitem__(self, key: str):
        """Deprecated: a group was a dict of its JSON object in capred 0.x; use the attributes."""
        import warnings

        warnings.warn(
            f"group[{key!r}] is deprecated (groups are GroupRecord records); use the attribute "
            "(e.g. group.sigma1_cap) or to_json()['groups']",
            DeprecationWarning,
            stacklevel=2,
        )
        return to_json(self)[key]

    def get(self, key: str, default=None):
        """Deprecated: dict-style access of capred 0.x (see ``__getitem__``).

        Parameters
        ----------
        key : str
            A key of capred 0.x's group dict.
        default : object, optional
            Returned where ``key`` is unknown.

        Returns
        -------
        object
            The value.
        """
        try:
            return self[key]
        except KeyError:
            return default

    @property
    def determined(self) -> bool:
        """True when the paper determines the tensor (eq. 48 with pairs, or eq. 50)."""
        return self.sigma1_cap is not None

    #: the fitted quantities of a group (attribute, its standard error's attribute or None), in report order
    FITTED = (
        ("sigma1_cap", "sigma1_cap_se"),
        ("sigma2_cap", "sigma2_cap_se"),
        ("sigma3_cap", "sigma3_cap_se"),
        ("C", "C_se"),
        ("C_fictive", "C_fictive_se"),
        ("phi_apparent", "phi_apparent_se"),
        ("Ci", None),
        ("Ci_fictive", None),
        ("phi_i", None),
    )

    @property
    def params(self):
        """The group's fitted quantities by JSON name, with standard error and 95 % interval, in kPa and deg.

        ``params["sigma1_cap_kPa"]``, ``["sigma2_cap_kPa"]``, ``["sigma3_cap_kPa"]`` (the shared capillary
        tensor, eq. 48 or 50), ``["C_kPa"]`` and ``["C_fictive_kPa"]`` (cohesions of the group's lines),
        ``["phi_apparent_deg"]`` (the free line's friction angle), and for eq. 50 ``["Ci_kPa"]``,
        ``["Ci_fictive_kPa"]``, ``["phi_i_deg"]`` (no standard error). Only the quantities the group has: a
        group without pairs has no tensor (see ``admissible``). Intervals are value ± t(0.975, dof) SE: dof =
        n − 1 for the tensor and the cohesions (means of per-test values; the JSON's ``*_ci95_kPa``), n − 2 for
        ``phi_apparent_deg`` (a free straight line).

        Returns
        -------
        capred.parameters.Parameters
            By JSON name; no correlations (the group's fits give none).

        References
        ----------
        Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.
        doi:10.1080/19648189.2024.2314099, Appendix 1, eq. 48-50.
        """
        import math

        from scipy.stats import t as student

        from ..parameters import Parameter, Parameters

        by_name = {f.name: f for f in dataclasses.fields(self)}
        # the tensor and the cohesions are means of per-test values (dof n - 1); the apparent angle comes from a
        # free straight line (slope and intercept: dof n - 2)
        dofs = {"phi_apparent": None if self.n is None else self.n - 2}
        out = []
        for name, se_name in self.FITTED:
            value = getattr(self, name)
            if value is None or not np.isfinite(value):
                continue
            f = by_name[name]
            q = QUANTITIES[f.metadata["quantity"]]
            se = getattr(self, se_name) if se_name else None
            se = math.nan if se is None else float(se)
            ci = getattr(self, name + "_ci95", None)
            dof = dofs.get(name, self.dof)
            if ci is None and dof is not None and dof >= 1 and math.isfinite(se):
                h = float(student.ppf(0.975, dof)) * se
                ci = (value - h, value + h)
            ci = (math.nan, math.nan) if ci is None else ci
            out.append(Parameter(json_key(f), float(value), se, tuple(float(x) for x in ci), q.unit, q.description))
        return Parameters(tuple(out))

    def summary(self) -> str:
        """A plain-text report of the group: its fitted quantities with SE and 95 % CI, n, dof, and what is missing.

        Returns
        -------
        str
            capred.parameters.fit_report of ``params``, titled with the group and its method.
        """
        from ..parameters import fit_report

        stats = {k: v for k, v in (("n", self.n), ("dof", self.dof), ("branch", self.branch)) if v is not None}
        notes = [x for x in (self.error, self.apparent_error, self.warning) if x]
        if not self.determined and self.needs:
            notes.append(f"tensor not determined: {self.needs}")
        return fit_report(f"Capillary tensor of group {self.group}, {self.method}", self.params, stats, notes)


def group_csv(g: GroupRecord) -> dict:
    """A group as one flat CSV row.

    Lists joined by ';', intervals and ranges as _low/_high (_lower/_upper) columns, the closures' tensors as
    ``<closure>.<component> [kPa]``.

    Parameters
    ----------
    g : GroupRecord
        A group of tests sharing one capillary tensor.

    Returns
    -------
    dict
        Header -> value.
    """
    row = {}
    for f in dataclasses.fields(g):
        v = getattr(g, f.name)
        if f.metadata.get("optional") and v is None:
            continue
        if f.name == "closures":
            for c in v:
                row.update({f"{c.name}.{k}": x for k, x in row_csv(c).items() if k not in ("name", "label", "chosen")})
        elif f.name == "admissible":
            for comp in ("sigma1_cap", "sigma2_cap", "sigma3_cap", "p_cap"):
                r = getattr(v, comp)
                row[f"{comp}_lower [kPa]"], row[f"{comp}_upper [kPa]"] = r.lower, r.upper
        elif dataclasses.is_dataclass(v):
            row.update(row_csv(v, f.name + "."))
        else:
            heads = csv_headers(f)
            if f.metadata.get("ci"):
                row[heads[0]], row[heads[1]] = (None, None) if v is None else v
            elif isinstance(v, (list, tuple)):
                row[heads[0]] = ";".join("" if x is None else (x if isinstance(x, str) else repr(x)) for x in v)
            else:
                row[heads[0]] = v
    return row


@dataclass(frozen=True)
class Curve:
    """One test's shear-stage curve as read (deviator corrected for the membrane where asked) and its peak.

    Attributes
    ----------
    test_id : str
        The test.
    axial_strain, vol_strain : ndarray
        Axial strain ε1 and volumetric strain εv of every reading [-] (compression positive; NaN where absent).
    q : ndarray
        Deviator stress of every reading [kPa].
    peak : int
        Index of the reading taken as failure (the largest q).
    """

    test_id: str
    axial_strain: np.ndarray
    q: np.ndarray
    vol_strain: np.ndarray
    peak: int


@dataclass(frozen=True, kw_only=True)
class Envelope:
    """The effective (saturated drained) Mohr-Coulomb envelope c', φ' of a run, in the user's units.

    A typed record: each field names its glossary entry; the JSON
    object ``envelope`` and the console table follow. ``params["c_kPa"]`` and ``params["phi_deg"]`` are the
    fitted parameters with standard error and 95 % interval (capred.parameters); ``summary()`` reports them.

    Attributes
    ----------
    c_kPa, c_se_kPa : float
        Effective cohesion c' and its standard error [kPa] (SE None when given as options).
    phi_deg, phi_se_deg : float
        Effective friction angle φ' and its standard error [deg].
    M, k_kPa : float
        Slope [-] and intercept [kPa] of the envelope in the q-p plane, triaxial compression (eq. 25-26).
    M_extension, k_extension_kPa : float
        The same in triaxial extension, M = 6 sin φ'/(3 + sin φ') [-], [kPa].
    source : str
        ``"fit"`` (least squares of σ'1 on σ'3 of the saturated tests), ``"options"``, or
        ``"extended_mc"`` (no saturated test: the extended Mohr-Coulomb fit of the unsaturated tests at s -> 0,
        their s0 taken as the suction at failure; capred.pipelines.triaxial_materials.zero_suction_envelope).
    n : int or None
        Saturated tests fitted.
    r2 : float or None
        R² of the fit [-].
    method : str
        How the envelope was obtained, with its reference.
    fit : LineFit or None
        The straight line σ'1 = K_p σ'3 + b in SI (Pa), for whoever needs its covariance.
    c_phi_correlation : float
        Correlation of c' and φ' (delta method) [-] (NaN when given as options).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.
       doi:10.1080/19648189.2024.2314099, eq. 25-26.
    """

    c_kPa: float = quantity("c")
    phi_deg: float = quantity("phi")
    M: float = quantity("M", init=False)
    k_kPa: float = quantity("k", init=False)
    M_extension: float = quantity("M_extension", init=False)
    k_extension_kPa: float = quantity("k_extension", init=False)
    c_se_kPa: float | None = quantity("c", se=True)
    phi_se_deg: float | None = quantity("phi", se=True)
    source: str = text()
    n: int | None = text(kind="int")
    r2: float | None = quantity("r2")
    method: str = text(init=False)
    fit: LineFit | None = None  # capred.fitting.linear.LineFit
    c_phi_correlation: float = float("nan")

    def __post_init__(self) -> None:
        c, phi = self.c_kPa * KPA, self.phi_deg
        for attr, branch in (("", "compression"), ("_extension", "extension")):
            M, k = tx.envelope_qp(c, phi, branch)
            object.__setattr__(self, "M" + attr, float(M))
            object.__setattr__(self, "k" + attr + "_kPa", float(k) / KPA)
        object.__setattr__(
            self,
            "method",
            f"least squares of sigma'_1 on sigma'_3 ({cite('prunier2024', 'eq. 25')})"
            if self.fit
            else EXTENDED_MC_METHOD
            if self.source == "extended_mc"
            else "given as options",
        )

    @property
    def params(self) -> Parameters:
        """c_kPa and phi_deg with standard error and 95 % interval (t, n − 2 dof) [kPa], [deg]."""
        from ..fitting.linear import t_quantile

        fixed = self.fit is None and self.source != "extended_mc"
        dof = (self.n or 0) - (3 if self.source == "extended_mc" else 2)  # c', phi', phi_b fitted
        t = float(t_quantile(0.975, dof)) if dof > 0 else float("nan")
        out = []
        for name, v, se, unit, q in (
            ("c_kPa", self.c_kPa, self.c_se_kPa, "kPa", "c_eff"),
            ("phi_deg", self.phi_deg, self.phi_se_deg, "deg", "phi_eff"),
        ):
            se = float("nan") if se is None else float(se)
            ci = (v - t * se, v + t * se)
            out.append(Parameter(name, float(v), se, ci, unit, QUANTITIES[q].description, fixed))
        corr = {} if fixed else {("c_kPa", "phi_deg"): self.c_phi_correlation}
        return Parameters(tuple(out), corr)

    def summary(self) -> str:
        """A plain-text report of the envelope: c', φ' with SE and 95 % CI, their correlation, n, R².

        Returns
        -------
        str
            capred.parameters.fit_report of the envelope's parameters.
        """
        fitted = self.fit is not None or self.source == "extended_mc"
        dof = (self.n or 0) - (3 if self.source == "extended_mc" else 2)
        stats = {"n": self.n, "dof": dof, "R²": self.r2} if fitted else {}
        warn = [f"c' = {self.c_kPa:.4g} kPa < 0: a negative cohesion has no physical meaning"] if self.c_kPa < 0 else []
        return fit_report(f"Effective envelope, {self.method}", self.params, stats, warn)

    # --- the names of capred 0.x, in Pa (one release, with a DeprecationWarning) ---------------------
    @property
    def c(self) -> float:
        """Deprecated: effective cohesion [Pa]; use ``params["c_kPa"]`` (kPa)."""
        return deprecated("Envelope.c [Pa]", 'Envelope.params["c_kPa"] (or .c_kPa)', self.c_kPa * KPA)

    @property
    def c_se(self) -> float | None:
        """Deprecated: standard error of c' [Pa]; use ``params["c_kPa"].stderr`` (kPa)."""
        v = None if self.c_se_kPa is None else self.c_se_kPa * KPA
        return deprecated("Envelope.c_se [Pa]", 'Envelope.params["c_kPa"].stderr (or .c_se_kPa)', v)

    @property
    def phi(self) -> float:
        """Deprecated: effective friction angle [deg]; use ``params["phi_deg"]``."""
        return deprecated("Envelope.phi", 'Envelope.params["phi_deg"] (or .phi_deg)', self.phi_deg)

    @property
    def phi_se(self) -> float | None:
        """Deprecated: standard error of φ' [deg]; use ``params["phi_deg"].stderr``."""
        return deprecated("Envelope.phi_se", 'Envelope.params["phi_deg"].stderr (or .phi_se_deg)', self.phi_se_deg)

    @property
    def k(self) -> float:
        """Deprecated: intercept in the q-p plane [Pa]; use ``k_kPa``."""
        return deprecated("Envelope.k [Pa]", "Envelope.k_kPa", self.k_kPa * KPA)

    @property
    def k_extension(self) -> float:
        """Deprecated: intercept in the q-p plane in extension [Pa]; use ``k_extension_kPa``."""
        return deprecated("Envelope.k_extension [Pa]", "Envelope.k_extension_kPa", self.k_extension_kPa * KPA)
