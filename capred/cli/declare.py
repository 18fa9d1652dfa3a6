"""Each option of a hand-written command declared once: by its Options field and the glossary.

A command's builder names the Options class and the field; the help text, the unit, the valid range and the
default shown in ``--help`` come from the field (its default, its numpydoc ``Attributes`` text) and, for a
dimensional field, from its glossary entry (``Options.QUANTITIES`` -> ``capred.nomenclature.QUANTITIES``:
description, symbol, output unit, hard limits). The CLI adds only what is about the command line: the
option's spelling and old aliases, and a note where the option needs one ("the thesis uses 10").

`capred --help` must not import numpy, and every Options class lives in a numerical module; so what the
Options, the glossary and the registries say is read once into ``capred/cli/declared.py`` (a generated
snapshot, checked by ``tests/test_cli_declared.py``: regenerate it with ``python -m capred.cli.declare``).
At run time nothing comes from the snapshot: the parsed values go to the live Options.

Values stay numbers: a bare number is read once (in the glossary's output unit, the unit ``--help`` shows)
and handed to the Options in SI; a value typed with a unit ("36 cm^2") goes to the Options as typed, which
read it once.
"""

from __future__ import annotations

import re
from functools import lru_cache
from typing import Annotated

import typer

#: the Options classes whose fields the hand-written commands declare (module:class)
OPTIONS_CLASSES = (
    "capred.pipelines.shear:ShearOptions",
    "capred.pipelines.shear:ModelParams",
    "capred.pipelines.triaxial:TriaxialOptions",
    "capred.pipelines.retention:RetentionOptions",
    "capred.pipelines.retention_convert:ConvertOptions",
    "capred.pipelines.calculators:PrismOptions",
    "capred.pipelines.calculators:SkemptonOptions",
    "capred.pipelines.calculators:RumpfOptions",
    "capred.pipelines.calculators:ShearBandOptions",
    "capred.pipelines.pt_volume:PTVolumeOptions",
    "capred.pipelines.bridge:CurveOptions",
    "capred.pipelines.bridge_solve:BridgeOptions",
    "capred.pipelines.yade_files:YadeOptions",
    "capred.pipelines.bridge_laws:LawsOptions",
    "capred.pipelines.history:HistoryOptions",
    "capred.pipelines.compression:CompressionOptions",
    "capred.pipelines.triaxial_strength:TriaxialStrengthOptions",
)

#: the registries whose entries the help lists: name -> (module:mapping, attribute giving an entry's help,
#: flags naming subsets of the entries: ``thesis`` -> the entries whose ``thesis`` is true)
REGISTRIES = {
    "effective_stress_models": ("capred.physics.effective_stress_models:REGISTRY", "label", ("thesis", "fitted")),
    "retention_models": ("capred.fitting.retention_models:MODELS", "help", ()),
    "bridge_laws": ("capred.physics.bridge_laws:LAWS", "label", ()),
}

_NUMBER = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*")


#: the layout of the snapshot (a snapshot of another layout is read afresh from the Options)
LAYOUT = 2


def _snapshot(fresh: bool = False) -> dict:
    """The snapshot of capred/cli/declared.py; where it is missing, of another layout or lacks an entry
    (``fresh``), what the Options, glossary and registries say now (slower: imports every pipeline; the CLI
    still starts, and ``python -m capred.cli.declare`` can rewrite the snapshot)."""
    if not fresh:
        try:
            from .declared import SNAPSHOT
        except ImportError:
            SNAPSHOT = {}
        if SNAPSHOT.get("layout") == LAYOUT:
            return SNAPSHOT
    return _live()


@lru_cache(maxsize=1)
def _live() -> dict:
    return facts()


def field_facts(options: str, field: str) -> dict:
    """What the snapshot holds on one Options field (see `facts`).

    Parameters
    ----------
    options : str
        The Options class as ``"module:Class"``.
    field : str
        The field's name.

    Returns
    -------
    dict
        ``quantity``, ``unit``, ``text``, ``range``, ``default``, ``option``.
    """
    try:
        return _snapshot()["options"][options][field]
    except KeyError:  # a field the snapshot does not know yet: read the Options now
        return _snapshot(fresh=True)["options"][options][field]


def registry_names(name: str, subset: str | None = None) -> list[str]:
    """The entries of a registry, in its order (from the snapshot, so that `--help` imports no numerical module).

    Parameters
    ----------
    name : str
        A key of `REGISTRIES`.
    subset : str, optional
        One of the registry's flags (``thesis``): only the entries with that attribute true.

    Returns
    -------
    list of str
    """
    entry = _snapshot()["registries"].get(name) or _snapshot(fresh=True)["registries"][name]
    return entry[subset or "names"].split(", ")


def registry_help(name: str) -> list[str]:
    """One line per entry of a registry, ``"name: its help"`` (from the snapshot).

    Parameters
    ----------
    name : str
        A key of `REGISTRIES`.

    Returns
    -------
    list of str
    """
    entry = _snapshot()["registries"].get(name) or _snapshot(fresh=True)["registries"][name]
    return list(entry["help"])


def option(options: str, field: str, *flags: str, note: str = "", help: str | None = None, **kw):
    """The annotation of one command-line option declared by an Options field.

    Parameters
    ----------
    options : str
        The Options class as ``"module:Class"`` (one of `OPTIONS_CLASSES`).
    field : str
        The field; the option is spelt as the Options' ``OPTION_NAMES`` say (default ``--field-name``) unless
        ``flags`` spell it (first the name, then old aliases).
    *flags : str
        The option's spellings, e.g. ``"--S-R", "--sr"``.
    note : str, optional
        What the help adds about the command line (appended after the field's own text).
    help : str, optional
        The option's description in the command line's words (default: the glossary's description and symbol
        for a dimensional field, else the field's ``Attributes`` text); a dimensional field's unit and range
        are the glossary's all the same (a glossary entry shared by two fields, as ``a_ini`` shares ``p0``'s).
    **kw
        Further ``typer.Option`` arguments (``metavar``, ``min`` ...); ``shown`` spells the default where the
        Options' value does not read as typed (``1,2,plane`` for ``(1.0, 2.0, inf)``).

    Returns
    -------
    typing.Annotated
        ``str | None`` for a dimensional field (a number in the unit shown, or a number with its own unit),
        else the field's type; the default shown is the Options default (the signature's default is None:
        the Options fill it in).
    """
    f = field_facts(options, field)
    text = help or f["text"]
    if not text:
        raise ValueError(f"{options}.{field}: no help text (document the field or pass help=)")
    if f["quantity"] is not None:
        bracket = "; ".join(x for x in (f["unit"], f["range"]) if x)
        text = f"{text} [{bracket}]" if bracket else text
    text = text.rstrip(".")
    if note:
        text = f"{text} {note}" if note[0] == "(" else f"{text}{note}" if note[0] in ":," else f"{text}; {note}"
    text = text if text.endswith((".", "?", "!")) else text + "."
    names = flags or (f["option"],)  # the Options' OPTION_NAMES, else --field-name
    if f["type"] == "bool":
        if not flags:
            names = (f"{names[0]}/--no-{names[0][2:]}",)
        return Annotated[bool, typer.Option(*names, help=text, **kw)]
    shown = kw.pop("shown", None)
    if f["default"] and "show_default" not in kw:  # the Options default (the signature's default is None)
        text = f"{text}  [default: {shown}]" if shown else f"{text}  {f['default']}"
    kw.setdefault("show_default", False)
    if f["quantity"] is not None:
        kw.setdefault("metavar", "NUMBER")
        return Annotated[str | None, typer.Option(*names, help=text, **kw)]
    typ = {"int": int, "float": float}.get(f["type"], str)
    return Annotated[typ | None, typer.Option(*names, help=text, **kw)]


def _shown(value) -> str:
    if isinstance(value, (list, tuple)):
        return ",".join(_shown(v) for v in value)
    if isinstance(value, float):
        return f"{value:.12g}"
    return str(value)


def si_values(options: str, **given) -> dict:
    """The options given on the command line, ready for the Options class: None (not given) left out, so
    that the Options' own default applies; a bare number of a dimensional field read once, in the unit
    ``--help`` shows, to SI (range checked here with the glossary's wording); a value with a unit passed
    as typed (the Options read it, and note how, e.g. g/cm^2 as gram-force).

    Parameters
    ----------
    options : str
        The Options class as ``"module:Class"``.
    **given
        Field name -> parsed value.

    Returns
    -------
    dict
        Field name -> value for the Options class.

    Raises
    ------
    OptionError
        A bare number outside the quantity's physical range.
    """
    out = {}
    for name, value in given.items():
        if value is None:
            continue
        f = field_facts(options, name)
        out[name] = value if f["quantity"] is None else read_number(value, f["quantity"], f"{name} ({f['option']})")
    return out


def read_number(value, quantity: str, where: str):
    """One option of a dimensional field as the command line gives it: a bare number is read once, in the
    glossary's output unit (the unit ``--help`` shows), to SI and range checked; text with a unit of its own
    is returned as typed (the Options read it once).

    Parameters
    ----------
    value : str or float
        The option as parsed.
    quantity : str
        Its glossary entry, a key of ``capred.nomenclature.QUANTITIES``.
    where : str
        The option as messages name it, e.g. ``"gamma_w (--gamma-w)"``.

    Returns
    -------
    float or str
        The SI value [SI unit of the quantity's kind], or the text with its unit.

    Raises
    ------
    OptionError
        A bare number outside the quantity's physical range (the glossary's wording).
    """
    from ..errors import OptionError
    from ..nomenclature import QUANTITIES, range_problem

    if isinstance(value, str) and not _NUMBER.fullmatch(value):
        return value
    if isinstance(value, bool) or not isinstance(value, (str, int, float)):
        return value
    q = QUANTITIES[quantity]
    si = float(value) * _factor(q.unit, q.kind)
    problem = range_problem(quantity, si)
    if problem:
        raise OptionError(f"{where}: {problem}")
    return si


def unit_and_range(quantity: str) -> str:
    """The bracket of an option's help: the glossary's output unit and hard limits, e.g. ``"[kPa; > 0]"``.

    Parameters
    ----------
    quantity : str
        A key of ``capred.nomenclature.QUANTITIES``.

    Returns
    -------
    str
        ``""`` for a dimensionless quantity without limits.
    """
    from ..nomenclature import QUANTITIES

    q = QUANTITIES[quantity]
    inside = "; ".join(x for x in ("" if q.unit == "-" else q.unit, _range_text(q)) if x)
    return f"[{inside}]" if inside else ""


def _factor(unit: str, kind: str) -> float:
    """SI value of one ``unit`` (the glossary's output unit)."""
    if unit in ("-", ""):
        return 1.0
    from ..units import conversion

    return conversion(unit, kind)[0]


# --- the snapshot ----------------------------------------------------------------------------------------------


def _range_text(q) -> str:
    """A glossary entry's hard limits in its output unit: ``> 0``, ``0 to 1``, ``0 to 90, both excluded``."""
    lo = None if q.lower is None else q.lower * q.factor
    hi = None if q.upper is None else q.upper * q.factor
    if lo is not None and hi is not None:
        ends = [f"{v:g}" for v, o in ((lo, q.lower_open), (hi, q.upper_open)) if o]
        return f"{lo:g} to {hi:g}" + (f", {' and '.join(ends)} excluded" if ends else "")
    if lo is not None:
        return f"{'>' if q.lower_open else '>='} {lo:g}"
    if hi is not None:
        return f"{'<' if q.upper_open else '<='} {hi:g}"
    return ""


def facts() -> dict:
    """What the Options classes, the glossary and the registries say about the command-line options, read
    from them now (imports every pipeline): the content of ``capred/cli/declared.py``.

    Returns
    -------
    dict
        ``{"options": {class: {field: {...}}}, "registries": {name: [(entry, help), ...]}}``; a field holds
        ``quantity`` (its glossary name or None), ``unit`` (the glossary's output unit, "" for none or "-"),
        ``range`` (its hard limits in that unit), ``text`` (the Options ``Attributes`` text, else the glossary
        description and symbol), ``default`` (the Options default as ``--help`` shows it, in that unit:
        ``"[default: 9.81]"``), ``type`` and ``option`` (its command-line spelling in messages).
    """
    import dataclasses
    import typing
    from importlib import import_module

    from ..nomenclature import QUANTITIES
    from .generated import attribute_help, base_type

    options: dict = {}
    for path in OPTIONS_CLASSES:
        module, name = path.split(":")
        cls = getattr(import_module(module), name)
        hints = typing.get_type_hints(cls)
        docs = _attribute_help(cls, attribute_help)
        dims = getattr(cls, "QUANTITIES", {}) or {}
        names = getattr(cls, "OPTION_NAMES", {}) or {}
        fields = {}
        for f in dataclasses.fields(cls):
            if f.name.startswith("_") or not f.init:
                continue
            default = f.default if f.default is not dataclasses.MISSING else None
            typ, _ = base_type(hints.get(f.name, str))
            kind = {bool: "bool", int: "int", float: "float", tuple: "tuple", list: "tuple"}.get(typ, "str")
            entry = {
                "quantity": dims.get(f.name),
                "unit": "",
                "range": "",
                "text": docs.get(f.name, ""),
                "default": None if default is None else f"[default: {_shown(default)}]",
                "type": kind,
                "option": names.get(f.name, "--" + f.name.replace("_", "-")),
            }
            if f.name in dims:
                q = QUANTITIES[dims[f.name]]
                entry["unit"] = "" if q.unit == "-" else q.unit
                entry["range"] = _range_text(q)
                entry["text"] = _glossary_text(q)
                if isinstance(default, (int, float)) and not isinstance(default, bool):  # in the glossary's unit
                    entry["default"] = f"[default: {_shown(float(f'{default * q.factor:.12g}'))}]"
                entry["type"] = "float"
            fields[f.name] = entry
        options[path] = fields
    registries = {}  # names joined, never one name alone: the names live in their registry's module only
    for key, (path, attr, subsets) in REGISTRIES.items():
        module, name = path.split(":")
        reg = getattr(import_module(module), name)
        helps = [str(getattr(v, attr, "")) if attr else "" for v in reg.values()]
        registries[key] = {
            "names": ", ".join(reg),
            "help": [h if h.startswith(f"{k}:") else f"{k}: {h}" if h else k for k, h in zip(reg, helps)],
            **{flag: ", ".join(k for k, v in reg.items() if getattr(v, flag, None)) for flag in subsets},
        }
    return {"layout": LAYOUT, "options": options, "registries": registries}


def _glossary_text(q) -> str:
    """An option's text from its glossary entry: the description, capitalised (not "van Genuchten"), then the
    symbol unless the description already names it."""
    text = q.description if q.description.startswith("van ") else q.description[0].upper() + q.description[1:]
    return text if re.search(rf"(^|\W){re.escape(q.symbol)}(\W|$)", text) else f"{text} {q.symbol}"


def _attribute_help(cls, reader) -> dict[str, str]:
    """A class's ``Attributes`` texts with the SI units in brackets dropped (the option shows the glossary's
    unit) and the reST literal quotes."""
    out = {}
    for name, text in reader(cls).items():
        out[name] = re.sub(r"\s*\[[^\]]*\]", "", text).replace("``", "").strip()
    return out


def _literal(value, indent: int = 0) -> str:
    """Python source of a snapshot value as ``ruff format`` leaves it: every dict and list one item a line
    with a trailing comma (kept as written), strings in double quotes."""
    import json

    pad, inner = " " * indent, " " * (indent + 4)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = "".join(f"{inner}{json.dumps(k)}: {_literal(v, indent + 4)},\n" for k, v in value.items())
        return "{\n" + items + pad + "}"
    if isinstance(value, (list, tuple)):
        if not value:
            return "[]"
        return "[\n" + "".join(f"{inner}{_literal(v, indent + 4)},\n" for v in value) + pad + "]"
    if isinstance(value, str):
        text = json.dumps(value, ensure_ascii=False)
        if value.count('"') > value.count("'"):  # ruff's choice: the quote that needs fewer escapes
            return "'" + text[1:-1].replace('\\"', '"').replace("'", "\\'") + "'"
        return text
    return repr(value)


def render(snapshot: dict) -> str:
    """The text of ``capred/cli/declared.py`` holding ``snapshot`` (stable under ``ruff format``).

    Parameters
    ----------
    snapshot : dict
        As `facts` returns it.

    Returns
    -------
    str
    """
    return (
        '"""Generated by ``python -m capred.cli.declare`` from the Options classes, the glossary and the registries:\n'
        'do not edit (tests/test_cli_declared.py fails when it is out of date)."""\n\n'
        f"SNAPSHOT = {_literal(snapshot)}\n"
    )


def main() -> None:
    """Rewrite ``capred/cli/declared.py`` from the Options classes, the glossary and the registries."""
    from pathlib import Path

    target = Path(__file__).with_name("declared.py")
    target.write_text(render(facts()), encoding="utf-8")
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
