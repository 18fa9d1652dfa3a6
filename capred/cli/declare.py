"""Each option of a hand-written command declared once: by its Options field (capred.spec) and the glossary.

A command's builder names the Options class and the field; the help text, the unit, the valid range and the
default shown in ``--help`` come from the field (its default, its numpydoc ``Attributes`` text, its declared
constraint) and, for a dimensional field, from its glossary entry (``Options.QUANTITIES`` ->
``capred.nomenclature.QUANTITIES``: description, symbol, output unit, hard limits). The CLI adds only what is
about the command line: the option's spelling and old aliases, and a note where the option needs one ("the
thesis uses 10").

Everything is read at run time from the declarations themselves: the Options classes live in capred.spec, which
imports no numpy (so `capred --help` stays cheap), and the registries' names and help are read from their
capred.spec modules when the help is shown, so a model registered by a script before the command runs shows in
its ``--help``. Nothing is generated or cached on disk.

Values stay numbers: a bare number is read once (in the glossary's output unit, the unit ``--help`` shows)
and handed to the Options in SI; a value typed with a unit ("36 cm^2") goes to the Options as typed, which
read it once.
"""

from __future__ import annotations

import inspect
import re
import typing
from functools import cache
from typing import Annotated

import typer

#: the registries whose entries the help lists: name -> (module:mapping, attribute giving an entry's help,
#: flags naming subsets of the entries: ``thesis`` -> the entries whose ``thesis`` is true); every one is a
#: numpy-free declaration of capred.spec, read when the help is shown
REGISTRIES = {
    "effective_stress_models": ("capred.spec.effective_stress:REGISTRY", "label", ("thesis", "fitted")),
    "retention_models": ("capred.spec.retention_models:MODELS", "help", ()),
    "bridge_laws": ("capred.spec.bridge_laws:LAWS", "label", ()),
}

_NUMBER = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*")

#: the one vocabulary of values in ``--help``: the kind of an option's value -> how it is shown (`metavar`)
METAVARS = {
    "float": "NUMBER",  # a number, with a unit of its own where the option is dimensional
    "int": "INTEGER",
    "path": "PATH",  # an option's file or folder (a Path, or a path given as text: --retention, --out)
    "files": "FILE",  # the data files a command reads (its argument: "FILE...")
    "str": "TEXT",
    "tuple": "NAME[,NAME...]",  # a comma-separated list (of words, or of numbers: NUMBER[,NUMBER...])
}


def _load(path: str):
    """The object a ``"module:name"`` path names (a capred.spec module: no numerical library)."""
    from importlib import import_module

    module, name = path.split(":")
    return getattr(import_module(module), name)


def field_facts(options: str, field: str) -> dict:
    """What an Options field declares about its command-line option (read from the class now).

    Parameters
    ----------
    options : str
        The Options class as ``"module:Class"`` (a capred.spec module).
    field : str
        The field's name.

    Returns
    -------
    dict
        ``quantity`` (its glossary name or None), ``unit`` (the glossary's output unit, "" for none or "-"),
        ``range`` (its hard limits in that unit, or its constraint's), ``text`` (the Options ``Attributes`` text,
        else the glossary description and symbol), ``default`` (the Options default as ``--help`` shows it, in
        that unit: ``"[default: 9.81]"``), ``type`` and ``option`` (its command-line spelling in messages).
    """
    return class_facts(_load(options))[field]


def registry_entries(name: str) -> dict:
    """A registry's entries as they stand now (a model registered by a script included).

    Parameters
    ----------
    name : str
        A key of `REGISTRIES`.

    Returns
    -------
    dict
        Entry name -> entry, in the registry's order.
    """
    return _load(REGISTRIES[name][0])


def registry_names(name: str, subset: str | None = None) -> list[str]:
    """The entries of a registry, in its order (read now from its capred.spec module).

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
    reg = registry_entries(name)
    return [k for k, v in reg.items() if subset is None or getattr(v, subset, None)]


def registry_help(name: str) -> list[str]:
    """One line per entry of a registry, ``"name: its help"`` (read now from its capred.spec module).

    Parameters
    ----------
    name : str
        A key of `REGISTRIES`.

    Returns
    -------
    list of str
    """
    attr = REGISTRIES[name][1]
    out = []
    for k, v in registry_entries(name).items():
        h = str(getattr(v, attr, "") or "")
        out.append(h if h.startswith(f"{k}:") else f"{k}: {h}" if h else k)
    return out


#: help text rendered when the help is shown: text as written -> a function giving it afresh (see `live_help`)
LIVE_HELP: dict = {}


def live_help(text: str) -> str:
    """An option's help as it reads now.

    The text of an option whose help was given as a function (``option(..., help=callable)``, e.g. the registry's
    models) is rendered again, so that an entry registered since the command was declared shows; any other text is
    returned as it is.

    Parameters
    ----------
    text : str
        The help text of a click parameter.

    Returns
    -------
    str
    """
    render = LIVE_HELP.get(text)
    if render is None:
        return text
    fresh = render()
    LIVE_HELP[fresh] = render
    return fresh


#: ``{name}`` in a command's help text -> a function giving what stands there when the help is shown
#: (capred.cli.help fills them in): a registry's entries as they stand then, without importing it at start-up
HELP_FIELDS = {"laws": lambda: "; ".join(registry_help("bridge_laws"))}


def fill_help_fields(text: str) -> str:
    """A command's help with its ``{name}`` fields (`HELP_FIELDS`) filled in now.

    Parameters
    ----------
    text : str
        The help as declared (the builder's docstring).

    Returns
    -------
    str
    """
    for name, render in HELP_FIELDS.items():
        if "{" + name + "}" in text:
            text = text.replace("{" + name + "}", render())
    return text


def model_parameter_options() -> list:
    """The command-line options of the parameters registered effective-stress models declare for themselves.

    Read from the registry now (capred.spec.shear.ModelParameter): ``--my-kappa`` of a model a script registered, with
    the unit, range and description its declaration gives.

    Returns
    -------
    list of inspect.Parameter
        Keyword-only parameters named after the parameters, annotated with their ``typer.Option`` (a number in
        the declared output unit, or with a unit of its own; default None: not given).
    """
    from ..spec.shear import model_parameters

    out = []
    for name, p in model_parameters().items():
        q = p.quantity
        bracket = "; ".join(x for x in ("" if q.unit == "-" else q.unit, _range_text(q)) if x)
        models = [k for k, e in registry_entries("effective_stress_models").items() if p in e.parameters]
        text = f"{_glossary_text(q)}{f' [{bracket}]' if bracket else ''}; of model {', '.join(models)}."
        if p.default is not None:
            text += f"  [default: {_shown(float(f'{p.default * q.factor:.12g}'))}]"
        annotation = Annotated[
            str | None,
            typer.Option(p.option, help=text, metavar=metavar("float"), show_default=False, rich_help_panel=None),
        ]
        out.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=annotation))
    return out


def model_parameter_values(given: dict) -> dict:
    """The models' own parameters given on the command line, for ``ModelParams(extra=...)``.

    None (not given) left out, a bare number read once in the declared output unit to SI (range checked), a value with a
    unit passed as typed.

    Parameters
    ----------
    given : dict
        Parameter name -> parsed value (the builder's ``**model_options``).

    Returns
    -------
    dict
    """
    from ..spec.shear import model_parameters

    declared = model_parameters()
    return {
        name: read_number(value, name, f"{name} ({declared[name].option})")
        for name, value in given.items()
        if value is not None and name in declared
    }


def metavar(kind: str, numbers: bool = False) -> str:
    """How ``--help`` shows the value of an option of one kind (`METAVARS`): one vocabulary for every option.

    Parameters
    ----------
    kind : str
        ``"float"``, ``"int"``, ``"path"``, ``"files"``, ``"str"`` or ``"tuple"`` (`class_facts`' ``type``).
    numbers : bool, optional
        For a ``tuple``: its items are numbers (``NUMBER[,NUMBER...]``).

    Returns
    -------
    str
    """
    if kind == "tuple" and numbers:
        return "NUMBER[,NUMBER...]"
    return METAVARS.get(kind, METAVARS["str"])


def param_metavar(param) -> str | None:
    """The metavar of a click parameter declared without one (a shared option, the files argument), by its type.

    The same vocabulary as the declared options (`metavar`): ``int`` -> INTEGER, ``float`` -> NUMBER, ``Path`` ->
    PATH (FILE for the data files a command reads, its argument), ``str`` -> TEXT; a repeatable option or an
    argument of several values shows one item (the help says "repeat"; the argument adds "...").

    Parameters
    ----------
    param : click.Parameter
        A typer option or argument.

    Returns
    -------
    str or None
        None for a flag, a choice (its words show) or a parameter that names its own metavar.
    """
    from pathlib import Path

    if getattr(param, "metavar", None) is not None or getattr(param, "is_flag", False):
        return None
    desc = getattr(param, "type_descriptor", None)
    if desc is None:  # typer on the click package (its floor, 0.16): the click type names the kind of value
        kind = str(getattr(getattr(param, "type", None), "name", "text"))
        if kind in ("boolean", "choice"):
            return None
        if kind == "path":
            return metavar("files" if param.param_type_name == "argument" else "path")
        return metavar("int" if kind.startswith("integer") else "float" if kind.startswith("float") else "str")
    if desc.is_choice:
        return None
    typ, _ = base_type(desc.annotation)
    if typ is list:
        (typ,) = typing.get_args(desc.annotation) or (str,)
    if typ is bool:
        return None
    if isinstance(typ, type) and issubclass(typ, Path):
        return metavar("files" if param.param_type_name == "argument" else "path")
    return metavar({int: "int", float: "float"}.get(typ, "str"))


def whole_or_as_given(value):
    """An integer option as typed, read as an int where it is one, else left for its constraint to refuse.

    ``"12"`` -> 12; ``"1.5"`` -> 1.5 and ``"many"`` -> "many", which the field's declared constraint (`Whole`)
    refuses in its own words (``"bootstrap (--bootstrap) must be a whole number >= 0 (got 1.5)"``), as it refuses
    ``-1``: one message style and exit status for every option error.

    Parameters
    ----------
    value : str, int or None
        The option as parsed.

    Returns
    -------
    int, float, str or None
    """
    if not isinstance(value, str):
        return value
    text = value.strip()
    if re.fullmatch(r"[-+]?\d+", text):
        return int(text)
    return float(text) if _NUMBER.fullmatch(text) else value


def option(options: str, field: str, *flags: str, note: str = "", help: str | None = None, **kw):
    """The annotation of one command-line option declared by an Options field.

    Parameters
    ----------
    options : str
        The Options class as ``"module:Class"`` (a capred.spec module).
    field : str
        The field; the option is spelt as the Options' ``OPTION_NAMES`` say (default ``--field-name``) unless
        ``flags`` spell it (first the name, then old aliases).
    *flags : str
        The option's spellings, e.g. ``"--S-R", "--sr"``.
    note : str, optional
        What the help adds about the command line (appended after the field's own text).
    help : str or callable, optional
        The option's description in the command line's words, or a function giving it (called again each time
        the help is shown: a registry's entries as they stand then) (default: the glossary's description and symbol
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
    names = flags or (f["option"],)  # the Options' OPTION_NAMES, else --field-name
    shown = kw.pop("shown", None)
    with_default = f["type"] != "bool" and bool(f["default"]) and "show_default" not in kw

    def render() -> str:
        text = (help() if callable(help) else help) or f["text"]
        if not text:
            raise ValueError(f"{options}.{field}: no help text (document the field or pass help=)")
        if f["quantity"] is not None or f["range"]:  # the glossary's unit and range, or the declared constraint's
            bracket = "; ".join(x for x in (f["unit"], f["range"]) if x)
            text = f"{text.rstrip('.')} [{bracket}]" if bracket else text
        text = text.rstrip(".")
        if note:
            text = f"{text} {note}" if note[0] == "(" else f"{text}{note}" if note[0] in ":," else f"{text}; {note}"
        text = text if text.endswith((".", "?", "!")) else text + "."
        if with_default:  # the Options default (the signature's default is None)
            text = f"{text}  [default: {shown}]" if shown else f"{text}  {f['default']}"
        return text

    text = render()
    if callable(help):  # rendered again when the help is shown (capred.cli.help reads LIVE_HELP)
        LIVE_HELP[text] = render
    if f["type"] == "bool":
        if not flags:
            names = (f"{names[0]}/--no-{names[0][2:]}",)
        return Annotated[bool, typer.Option(*names, help=text, **kw)]
    kw.setdefault("show_default", False)
    kw.setdefault("metavar", metavar(f["type"], f["numbers"]))
    if f["quantity"] is not None:
        return Annotated[str | None, typer.Option(*names, help=text, **kw)]
    # an integer is read as text (`whole_or_as_given` in `si_values`) so that its constraint words what is wrong
    typ = float if f["type"] == "float" else str
    return Annotated[typ | None, typer.Option(*names, help=text, **kw)]


def _shown(value) -> str:
    if isinstance(value, (list, tuple)):
        return ",".join(_shown(v) for v in value)
    if isinstance(value, float):
        return f"{value:.12g}"
    return str(value)


def si_values(options: str, **given) -> dict:
    """The options given on the command line, ready for the Options class.

    None (not given) left out, so that the Options' own default applies; a bare number of a dimensional field read once,
    in the unit ``--help`` shows, to SI (range checked here with the glossary's wording); a value with a unit passed as
    typed (the Options read it, and note how, e.g. g/cm^2 as gram-force).

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
        if f["quantity"] is not None:
            out[name] = read_number(value, f["quantity"], f"{name} ({f['option']})")
        else:
            out[name] = whole_or_as_given(value) if f["type"] == "int" else value
    return out


def read_number(value, quantity: str, where: str):
    """One option of a dimensional field as the command line gives it.

    A bare number is read once, in the glossary's output unit (the unit ``--help`` shows), to SI and range checked; text
    with a unit of its own is returned as typed (the Options read it once).

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


# --- what an Options class declares ---------------------------------------------------------------------------


def attribute_help(cls) -> dict[str, str]:
    """The numpydoc ``Attributes`` section of a class docstring, as ``{name: first sentence of its text}``.

    Parameters
    ----------
    cls : type
        A documented dataclass (an Options class).

    Returns
    -------
    dict
        Field name -> its description (one line).
    """
    doc = inspect.cleandoc(cls.__doc__ or "")
    m = re.search(r"^Attributes\n-+\n(.*?)(?:\n\n[A-Z][A-Za-z ]+\n-+\n|\Z)", doc, re.S | re.M)
    out: dict[str, str] = {}
    if not m:
        return out
    names: list[str] = []
    for line in m.group(1).splitlines():
        head = re.match(r"^([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)\s*(?::.*)?$", line)
        if head and not line.startswith(" "):  # "name : type" or "a, b : type" (one text for each)
            names = [n.strip() for n in head.group(1).split(",")]
            out.update(dict.fromkeys(names, ""))
        elif names and line.strip():
            for name in names:
                out[name] = (out[name] + " " + line.strip()).strip()
    return out


def base_type(annotation):
    """The Python type of an Options field's annotation, and whether it may be None.

    Parameters
    ----------
    annotation : object
        A field annotation such as ``float | None`` or ``tuple``.

    Returns
    -------
    tuple
        ``(type, optional)``: the type without ``None`` (``str`` for a union of several types), and whether
        ``None`` is allowed.
    """
    args = typing.get_args(annotation)
    optional = type(None) in args
    if args and typing.get_origin(annotation) in (typing.Union, getattr(__import__("types"), "UnionType", None)):
        rest = [a for a in args if a is not type(None)]
        from pathlib import Path

        if len(rest) == 2 and set(rest) == {str, Path}:  # a file given as a path or as text
            annotation = Path
        else:
            annotation = rest[0] if len(rest) == 1 else str
    origin = typing.get_origin(annotation) or annotation
    return origin, optional


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


@cache
def class_facts(cls) -> dict:
    """What one Options class declares about each of its command-line options (see `field_facts`).

    Parameters
    ----------
    cls : type
        An Options dataclass (capred.spec).

    Returns
    -------
    dict
        Field name -> ``{"quantity", "unit", "range", "text", "default", "type", "option"}``.
    """
    import dataclasses
    from pathlib import Path

    from ..nomenclature import QUANTITIES

    hints = typing.get_type_hints(cls)
    docs = _attribute_help(cls)
    dims = getattr(cls, "QUANTITIES", {}) or {}
    names = getattr(cls, "OPTION_NAMES", {}) or {}
    rules = getattr(cls, "CONSTRAINTS", {}) or {}
    fields = {}
    for f in dataclasses.fields(cls):
        if f.name.startswith("_") or not f.init:
            continue
        default = f.default if f.default is not dataclasses.MISSING else None
        typ, _ = base_type(hints.get(f.name, str))
        kind = {bool: "bool", int: "int", float: "float", tuple: "tuple", list: "tuple", Path: "path"}.get(typ, "str")
        rule = rules.get(f.name)
        entry = {
            "quantity": dims.get(f.name),
            "unit": "",
            "range": rule.range_text() if hasattr(rule, "range_text") else "",
            "text": docs.get(f.name, ""),
            "default": None if default is None else f"[default: {_shown(default)}]",
            "type": kind,
            "option": names.get(f.name, "--" + f.name.replace("_", "-")),
            "numbers": isinstance(default, tuple)
            and bool(default)
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in default),
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
    return fields


def _glossary_text(q) -> str:
    """An option's text from its glossary entry.

    The description, capitalised (not "van Genuchten"), then the symbol unless the description already names it.
    """
    text = q.description if q.description.startswith("van ") else q.description[0].upper() + q.description[1:]
    return text if re.search(rf"(^|\W){re.escape(q.symbol)}(\W|$)", text) else f"{text} {q.symbol}"


def _attribute_help(cls) -> dict[str, str]:
    """A class's ``Attributes`` texts, cleaned for the command line.

    The SI units in brackets are dropped (the option shows the glossary's unit), and so are the reST literal quotes.
    """
    out = {}
    for name, text in attribute_help(cls).items():
        out[name] = re.sub(r"\s*\[[^\]]*\]", "", text).replace("``", "").strip()
    return out
