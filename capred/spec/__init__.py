"""The declarations of capred: what every command reads, which options it takes and how each is checked.

This layer says *what* capred's commands are, never how they compute: each command's input schema
(:class:`capred.spec.columns.Column` lists, ``capred.spec.<command>.SCHEMA``), its Options dataclass (each
dimensional field a glossary quantity, each simple value check a declarative constraint of
:mod:`capred.spec.options`), the constants those declarations need as defaults, and every registry's metadata
(effective-stress models, retention models, bridge laws, chi laws: names, labels, references, required options)
with its numerical callables named as ``"module:function"`` (:mod:`capred.spec.callables` resolves them on first
use). The command line and its ``--help`` are built from these declarations at run time (capred.cli.declare,
capred.cli.help): nothing about an option or a column is generated into the package or cached on disk, and a
model or option declared at run time shows at once.

The rule of the layer: a module of ``capred.spec`` imports only the standard library and the capred modules that
are themselves free of numpy, pandas, pint, scipy, matplotlib and typer (``capred.spec.*``,
``capred.nomenclature``, ``capred.errors``, ``capred.references``, ``capred.text_safety``), so that
``capred --help`` and ``capred COMMAND --help`` load no numerical library. What a declaration needs from the
numerical layers at run time (reading a unit with pint, a registry's callable) is imported inside the method
that needs it (tests/test_spec_layer.py imports every module of the layer in a fresh interpreter and checks).
"""

from .callables import resolve  # noqa: F401  (one resolver of "module:function" references)
