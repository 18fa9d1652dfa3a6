"""A command's CLI built from its Options: each option declared once, by its Options field and the glossary.

A reduction (capred/reductions.py) whose command has no hand-written builder gets one here: every public
field of its Options dataclass becomes an option ``--field-name`` with

- its help from the Options docstring's numpydoc ``Attributes`` section,
- its unit and range from the glossary (``Options.QUANTITIES`` names the glossary entry of a dimensional
  field): the option takes a number in the glossary's output unit (kPa, kN/m^3, mm ...), read once to SI
  (capred.cli.declare.read_number, as the hand-written commands read theirs), or a number with a unit of
  its own, which the Options read once,
- its type and default from the field (bool fields are ``--flag/--no-flag``; tuples are comma separated).

So a new command is its Reduction entry (with its Options and records) and its presenter: nothing in cli/.
"""

from __future__ import annotations

import dataclasses
import inspect
import re
import typing
from typing import Annotated

import typer

from .common import Invocation, command
from .declare import attribute_help, base_type, metavar, read_number, unit_and_range


def option_parameters(options_cls) -> list[tuple[str, inspect.Parameter, object]]:
    """The typer parameters of an Options class: ``(field name, parameter, converter)`` per public field.

    Parameters
    ----------
    options_cls : type
        The Options dataclass of a reduction.

    Returns
    -------
    list of tuple
        The field's name, its ``inspect.Parameter`` (annotated with ``typer.Option``) and a function that turns
        the parsed value into the Options' value (SI for a dimensional field).
    """
    from ..nomenclature import QUANTITIES

    hints = typing.get_type_hints(options_cls)
    helps = attribute_help(options_cls)
    dims = getattr(options_cls, "QUANTITIES", {}) or {}
    out = []
    for f in dataclasses.fields(options_cls):
        if f.name.startswith("_") or not f.init:
            continue
        default = f.default if f.default is not dataclasses.MISSING else None
        if f.default is dataclasses.MISSING and f.default_factory is not dataclasses.MISSING:
            default = f.default_factory()
        typ, _ = base_type(hints.get(f.name, str))
        flag = "--" + f.name.replace("_", "-")
        text = helps.get(f.name, f.name.replace("_", " "))
        convert = _identity
        if f.name in dims:  # a number in the glossary's unit (or with a unit of its own), read once
            q = QUANTITIES[dims[f.name]]
            text = re.sub(r"\s*\[[^\]]*\]", "", text).rstrip(".") + " " + unit_and_range(dims[f.name])
            if default is not None:
                text += f".  [default: {float(default) * q.factor:.12g}]"
            annotation = Annotated[
                str | None, typer.Option(flag, help=text, metavar=metavar("float"), show_default=False)
            ]
            default, convert = None, _reader(dims[f.name], f"{f.name} ({flag})")
        elif typ is bool:
            annotation = Annotated[bool, typer.Option(f"{flag}/--no-{f.name.replace('_', '-')}", help=text)]
        elif typ in (tuple, list):
            shown = None if default is None else ",".join(map(str, default))
            numbers = bool(default) and all(isinstance(v, (int, float)) for v in default)
            annotation = Annotated[
                str | None, typer.Option(flag, help=text + " (comma separated)", metavar=metavar("tuple", numbers))
            ]
            default, convert = shown, _split
        elif typ in (int, float):
            annotation = Annotated[typ | None, typer.Option(flag, help=text)]
        else:
            annotation = Annotated[str | None, typer.Option(flag, help=text)]
        param = inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=default, annotation=annotation)
        out.append((f.name, param, convert))
    return out


def _identity(value):
    return value


def _reader(quantity: str, where: str):
    """The converter of a dimensional option: the same reading as the hand-written commands'."""
    return lambda value: None if value is None else read_number(value, quantity, where)


def _split(text):
    if text is None:
        return None
    items = [t.strip() for t in str(text).split(",") if t.strip()]
    try:
        return tuple(float(t) for t in items)
    except ValueError:
        return tuple(items)


def register_generated(app: typer.Typer, builders: dict) -> list[str]:
    """Give every registered reduction without a hand-written builder a CLI built from its Options.

    Parameters
    ----------
    app : typer.Typer
        The application (a command of a group, "bridge laws", goes to that group when it exists).
    builders : dict
        The command name -> builder registry of capred.cli.common (commands already there are left alone).

    Returns
    -------
    list of str
        The commands registered here.
    """
    from ..reductions import REDUCTIONS

    done = []
    for name, red in REDUCTIONS.items():
        if name in builders or " " in name:  # hand-written, or a subcommand of a group with its own app
            continue
        command(app, name, data=_data_help(red))(generated_builder(red))
        done.append(name)
    return done


def _data_help(red) -> str | None:
    if red.source == "none":
        return None
    return red.input_description or f"Input files of `capred {red.name}`"


def generated_builder(red):
    """The builder of one reduction: keyword arguments from its Options' fields, returning an Invocation.

    Parameters
    ----------
    red : capred.reductions.Reduction
        The command.

    Returns
    -------
    callable
        ``builder(**parsed) -> Invocation`` with a signature typer reads.
    """
    from importlib import import_module

    module, cls_name = red.options_path.split(":")
    options_cls = getattr(import_module(module), cls_name)
    params = option_parameters(options_cls)

    def builder(**parsed) -> Invocation:
        values = {name: convert(parsed[name]) for name, _, convert in params if parsed.get(name) is not None}
        return Invocation(red.name, options_cls(**values))

    builder.__signature__ = inspect.Signature([p for _, p, _ in params], return_annotation=Invocation)
    builder.__name__ = red.name.replace("-", "_")
    builder.__doc__ = red.summary or red.name
    return builder
