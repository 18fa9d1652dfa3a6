"""Pages of the documentation generated from capred's own registries, at every build.

``python docs/generate.py`` writes them into ``docs/generated/`` (git-ignored); ``docs/conf.py`` calls
:func:`write_all` before Sphinx reads the sources, so the site can never disagree with the code:

- ``cli.md``: every command of ``capred.reductions.REDUCTIONS`` (and ``capred batch``) with its summary, its
  methods text, its references and its ``--help`` exactly as the command line prints it;
- ``registries.md``: the registries (commands, effective-stress models, fitted χ laws, retention models,
  closed-form bridge laws) as tables;
- ``glossary.md``: ``capred.nomenclature.QUANTITIES`` and ``COLUMN_ALIASES``;
- ``references.bib``: ``capred.references.REFERENCES`` as BibTeX for sphinxcontrib-bibtex;
- ``validation.md``: capred's values against published ones, computed now by the same code and from the same
  case lists the tests use (``tests/test_triaxial_published.py``, ``tests/test_retention_published.py``,
  ``tests/test_bridge_pairs.py`` and, when it exists, ``tests/real_cases.py``).
"""

from __future__ import annotations

import importlib
import os
import re
import sys
from dataclasses import fields, is_dataclass
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
OUT = DOCS / "generated"


def _cell(text) -> str:
    """A Markdown table cell: one line, pipes escaped."""
    text = "" if text is None else str(text)
    return " ".join(text.split()).replace("|", "\\|")


def _table(header: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def _anchor(name: str) -> str:
    return "cli-" + name.replace(" ", "-")


def _write(name: str, text: str) -> Path:
    OUT.mkdir(parents=True, exist_ok=True)
    path = OUT / name
    if not path.exists() or path.read_text(encoding="utf-8") != text:  # unchanged pages keep their time stamp
        path.write_text(text, encoding="utf-8")
    return path


# --------------------------------------------------------------------------------------------------------------
# command-line reference
# --------------------------------------------------------------------------------------------------------------


def help_text(args: list[str]) -> str:
    """The ``--help`` of a command as a terminal of 80 columns prints it, without colours.

    Parameters
    ----------
    args : list of str
        The command words, e.g. ``["bridge", "solve"]``.

    Returns
    -------
    str
    """
    from typer.testing import CliRunner

    from capred.cli import app

    env = {"COLUMNS": "80", "NO_COLOR": "1", "TERM": "dumb", "_TYPER_FORCE_DISABLE_TERMINAL": "1"}
    res = CliRunner().invoke(app, [*args, "--help"], env=env)
    if res.exit_code != 0:
        raise RuntimeError(f"capred {' '.join(args)} --help failed: {res.output}")
    text = re.sub(r"\x1b\[[0-9;]*m", "", res.output)
    return "\n".join(line.rstrip() for line in text.splitlines()).strip("\n")


def command_names() -> list[str]:
    """Every command of the command line: the reductions and ``batch``.

    Returns
    -------
    list of str
    """
    from capred.reductions import REDUCTIONS

    return [*REDUCTIONS, "batch"]


def cli_page() -> str:
    """The command-line reference page (MyST Markdown).

    Returns
    -------
    str
    """
    from capred.reductions import REDUCTIONS
    from capred.references import REFERENCES, cite

    out = [
        "# Command-line reference\n",
        "Generated at every build from `capred.reductions.REDUCTIONS`: each command's summary, the methods text "
        "its `report.html` prints, its references and its `--help` as the command line prints it.\n",
        "```text\n" + help_text([]) + "\n```\n",
    ]
    for name in command_names():
        out.append(f"({_anchor(name)})=\n## `capred {name}`\n")
        red = REDUCTIONS.get(name)
        if red is not None:
            out.append(red.summary + "\n")
            if red.method:
                out.append("**Methods** (as report.html states them):\n")
                out += [p + "\n" for p in red.method]
            if red.references:
                refs = "; ".join(cite(k) for k in red.references if k in REFERENCES)
                out.append(f"**References:** {refs}.\n")
            out.append(f"**Quick run:** `capred {' '.join(red.example_args())}`\n")
        out.append("```text\n" + help_text(name.split()) + "\n```\n")
    return "\n".join(out)


# --------------------------------------------------------------------------------------------------------------
# registries
# --------------------------------------------------------------------------------------------------------------


def _short(value) -> str:
    if callable(value):
        return ""
    if isinstance(value, tuple | list):
        return ", ".join(_short(v) if not isinstance(v, tuple) else "/".join(map(str, v)) for v in value)
    return str(value)


def registries() -> dict[str, tuple[str, dict]]:
    """The registries the documentation renders: title -> (module path, registry).

    Returns
    -------
    dict
    """
    from capred.fitting import chi_laws, retention_models
    from capred.physics import bridge_laws, effective_stress_models
    from capred.reductions import REDUCTIONS

    return {
        "Commands": ("capred.reductions.REDUCTIONS", REDUCTIONS),
        "Effective-stress models (`capred shear --models`)": (
            "capred.physics.effective_stress_models.REGISTRY",
            effective_stress_models.REGISTRY,
        ),
        "Fitted χ laws": ("capred.fitting.chi_laws.LAWS", chi_laws.LAWS),
        "Retention models (`capred retention --model`)": (
            "capred.fitting.retention_models.MODELS",
            retention_models.MODELS,
        ),
        "Closed-form capillary bridge laws (`capred bridge laws`)": (
            "capred.physics.bridge_laws.LAWS",
            bridge_laws.LAWS,
        ),
    }


#: the columns of a registry whose automatic choice would be less useful
COLUMNS = {"capred.reductions.REDUCTIONS": ["summary", "source", "sample", "references"]}


def _entry_columns(entries) -> list[str]:
    """The text fields worth a column: strings and tuples of strings, not functions or long texts."""
    first = next(iter(entries.values()))
    if not is_dataclass(first):
        return []
    keep = []
    for f in fields(first):
        values = [getattr(e, f.name) for e in entries.values()]
        if any(callable(v) or isinstance(v, dict) for v in values):
            continue
        text = [_short(v) for v in values]
        if f.name in ("name", "method", "help") or max(map(len, text), default=0) > 160:
            continue
        if any(text):
            keep.append(f.name)
    return keep[:6]


def registries_page() -> str:
    """Every registry as a table (one row per entry).

    Returns
    -------
    str
    """
    out = [
        "# Registries\n",
        "A model, a law or a command is one entry of a registry; these tables are generated from the registries "
        "at every build (see {doc}`../contributing` for how to add an entry).\n",
    ]
    for title, (path, entries) in registries().items():
        cols = COLUMNS.get(path) or _entry_columns(entries)
        rows = [[f"`{key}`", *[_short(getattr(e, c, "")) for c in cols]] for key, e in entries.items()]
        if not cols:  # a χ law holds only functions: describe it by the effective-stress entry that offers it
            from capred.physics.effective_stress_models import REGISTRY

            cols = ["label", "fitted", "reference"]
            rows = [[f"`{key}`", *[_short(getattr(REGISTRY.get(key), c, "")) for c in cols]] for key in entries]
        out.append(f"## {title}\n\n`{path}`: {len(entries)} entries.\n")
        out.append(_table(["name", *cols], rows))
    return "\n".join(out)


# --------------------------------------------------------------------------------------------------------------
# options and results of every command
# --------------------------------------------------------------------------------------------------------------


def _class(path: str):
    module, name = path.split(":")
    return getattr(importlib.import_module(module), name)


def _result_class(red):
    """The Result class a command's run function returns (its return annotation)."""
    import inspect
    import typing

    run = _class(red.run_path)
    run = getattr(run, "__wrapped__", run)
    try:
        hint = typing.get_type_hints(run).get("return")
    except Exception:  # an annotation that does not resolve: read the string
        hint = inspect.signature(run).return_annotation
        hint = getattr(importlib.import_module(run.__module__), str(hint), None) if isinstance(hint, str) else hint
    return hint if isinstance(hint, type) else None


def _offers(help_shown: str, option: str | None) -> bool:
    return bool(option) and re.search(rf"(^|[\s,]){re.escape(option)}(?![\w-])", help_shown, re.M) is not None


def records_page() -> str:
    """Every command's Options (each field with its option, unit, range, default and meaning) and Result fields.

    Returns
    -------
    str
    """
    from capred.cli.declare import field_facts
    from capred.cli.generated import attribute_help
    from capred.reductions import REDUCTIONS

    out = [
        "# Options and results of every command\n",
        "Generated at every build from each command's Options and Result dataclasses (and the glossary that gives "
        "each option its unit and range). A dimensional option takes a number in SI, a string with a unit "
        '(`gamma_w="10 kN/m^3"`) or a pint Quantity; the units below are those of the command line. The classes '
        "themselves: {doc}`../api/index`.\n",
    ]
    seen: set[str] = set()
    for name, red in REDUCTIONS.items():
        out.append(f"## `capred {name}`\n")
        opts = _class(red.options_path)
        qual = f"{opts.__module__}.{opts.__qualname__}"
        if qual in seen:
            out.append(f"Options: `{qual}` (above).\n")
        else:
            seen.add(qual)
            shown = help_text(name.split())  # an option is named only where the command line offers it so
            rows = []
            for f in fields(opts):
                if f.name.startswith("_"):
                    continue
                try:
                    facts = field_facts(red.options_path, f.name)
                except Exception:  # a field the command line does not offer
                    facts = {}
                rows.append(
                    [
                        f"`{f.name}`",
                        f"`{facts['option']}`" if _offers(shown, facts.get("option")) else "",
                        facts.get("unit", ""),
                        facts.get("range", ""),
                        (facts.get("default") or "").removeprefix("[default: ").removesuffix("]"),
                        facts.get("text", ""),
                    ]
                )
            out.append(f"Options: `{qual}`\n")
            out.append(_table(["field", "option", "unit", "range", "default", "meaning"], rows))
        res = _result_class(red)
        if res is not None and is_dataclass(res):
            rqual = f"{res.__module__}.{res.__qualname__}"
            if rqual in seen:
                out.append(f"Result: `{rqual}` (above).\n")
                continue
            seen.add(rqual)
            doc = (res.__doc__ or "").strip().split("\n\n")[0]
            helps = attribute_help(res)
            rows = [
                [
                    f"`{f.name}`",
                    f"`{f.type}`" if isinstance(f.type, str) else getattr(f.type, "__name__", ""),
                    helps.get(f.name, ""),
                ]
                for f in fields(res)
                if not f.name.startswith("_")
            ]
            out.append(f"Result: `{rqual}`: {_cell(doc)}\n")
            out.append(_table(["attribute", "type", "meaning"], rows))
    return "\n".join(out)


# --------------------------------------------------------------------------------------------------------------
# glossary
# --------------------------------------------------------------------------------------------------------------


def _limit(q) -> str:
    lo = "" if q.lower is None else f"{q.lower * q.factor:g} {'<' if q.lower_open else '≤'} "
    hi = "" if q.upper is None else f" {'<' if q.upper_open else '≤'} {q.upper * q.factor:g}"
    return f"{lo}x{hi}" if lo or hi else ""


def glossary_page() -> str:
    """The glossary: every quantity of ``capred.nomenclature`` with symbol, unit, meaning and valid range.

    Returns
    -------
    str
    """
    from capred import nomenclature as nm

    rows = [
        [f"`{name}`", q.symbol, q.unit, q.description, _limit(q)]
        for name, q in sorted(nm.QUANTITIES.items(), key=lambda kv: kv[0].lower())
    ]
    spellings = [[f"`{name}`", ", ".join(f"`{a}`" for a in aliases)] for name, aliases in nm.COLUMN_ALIASES.items()]
    return (
        "# Glossary\n\n"
        "One name per concept, as `capred.nomenclature` defines it: options, input columns, JSON keys, CSV "
        "headers (`name [unit]`) and plot labels all use these names. *Range* is the physically possible range "
        "in the output unit (outside it a value is an error). Generated from `capred.nomenclature.QUANTITIES` "
        "at every build.\n\n"
        + _table(["name", "symbol", "unit", "meaning", "range"], rows)
        + "\n## Spellings of the id columns\n\n"
        "Headers are matched ignoring case, spaces, `-`, `.` and `/`; the id columns also accept these spellings "
        "(`capred.nomenclature.COLUMN_ALIASES`):\n\n" + _table(["column", "also read as"], spellings)
    )


# --------------------------------------------------------------------------------------------------------------
# bibliography
# --------------------------------------------------------------------------------------------------------------


def _bib_authors(authors: str) -> str:
    text = authors.replace(" et al.", " and others").replace(" & ", " and ")
    if " " in text and " and " not in text and not text.startswith("van "):
        return "{" + text + "}"  # a body (ASTM International), not a person
    return text


def _bib_escape(text: str) -> str:
    return text.replace("&", r"\&").replace("%", r"\%").replace("#", r"\#")


def bibtex() -> str:
    """``capred.references.REFERENCES`` as BibTeX (one ``@misc`` per entry, keyed as in capred).

    Returns
    -------
    str
    """
    from capred.references import REFERENCES

    out = []
    for key, ref in REFERENCES.items():
        items = [f"  author = {{{_bib_authors(ref.authors)}}}", f"  title = {{{{{_bib_escape(ref.title)}}}}}"]
        items.append(f"  year = {{{ref.year if ref.year else 'n.d.'}}}")
        items.append(f"  note = {{{_bib_escape(ref.source)}}}")
        if ref.doi:
            items.append(f"  doi = {{{ref.doi}}}")
        out.append(f"@misc{{{key},\n" + ",\n".join(items) + "\n}\n")
    return "\n".join(out)


# --------------------------------------------------------------------------------------------------------------
# validation
# --------------------------------------------------------------------------------------------------------------


def _tests_module(name: str):
    """Import a module of tests/ (with tests/ on the path, as pytest has it); None if it does not exist."""
    tests = str(ROOT / "tests")
    if tests not in sys.path:
        sys.path.insert(0, tests)
    if not (ROOT / "tests" / f"{name}.py").exists():
        return None
    return importlib.import_module(name)


def _fmt(x) -> str:
    if isinstance(x, float):
        return "—" if x != x else f"{x:.5g}"  # NaN: the source gives no value
    return str(x)


def prunier_rows() -> list[dict]:
    """Prunier et al. (2024) Tables 2 and 3 against ``capred triaxial-bounds`` on the reconstructed Gavet silt.

    Returns
    -------
    list of dict
        Keys ``dataset, source, quantity, published, capred, difference, tolerance``.
    """
    import capred
    from capred.pipelines.triaxial import run_triaxial_bounds

    mod = _tests_module("test_triaxial_published")
    js = run_triaxial_bounds(capred.sample_path("triaxial-bounds")).to_json()
    tests = {t["p0_kPa"]: t for t in js["tests"] if t["condition"] == "unsaturated"}
    rows = []
    for quantity, p0, published, tol, source in mod.CASES:
        bound, key = quantity.split(".")
        value = tests[p0][bound][key]
        rows.append(
            {
                "dataset": f"Gavet silt, p0 = {p0} kPa",
                "source": f"Prunier et al. (2024), {source}",
                "quantity": quantity,
                "published": published,
                "capred": value,
                "difference": value - published,
                "tolerance": tol,
            }
        )
    return rows


def vg1980_rows() -> list[dict]:
    """van Genuchten (1980) Table 1: α and n fitted by ``capred retention`` with θ_s, θ_r fixed as published.

    Returns
    -------
    list of dict
    """
    from capred.pipelines.retention import RetentionOptions, run_retention

    mod = _tests_module("test_retention_published")
    rows = []
    for name, ts, tr, alpha, n in mod.VG1980:
        opts = RetentionOptions(models=("vg",), fixed={"theta_s": ts, "theta_r": tr})
        vg = run_retention(mod.RETENTION_DATA / name, opts).to_json()["fits"]["vg"]
        label = name.removeprefix("swrc_vg1980_").removesuffix(".csv").replace("_", " ")
        for quantity, published, rel in (("alpha_per_cm", alpha, 0.08), ("n", n, 0.04)):
            rows.append(
                {
                    "dataset": label,
                    "source": "van Genuchten (1980), Table 1",
                    "quantity": quantity,
                    "published": published,
                    "capred": vg[quantity],
                    "difference": vg[quantity] - published,
                    "tolerance": f"{rel:.0%} relative",
                }
            )
    return rows


def duriez_rows() -> list[dict]:
    """YADE's capillary-file generator (Duriez): widest gap bridged at zero suction, against capred's bridge.

    Returns
    -------
    list of dict
    """
    from capred.pipelines.yade_files import capillary_file

    mod = _tests_module("test_bridge_pairs")
    rows = []
    for ratio, published in mod.DURIEZ_MAX_D.items():
        value = capillary_file(ratio, 0.0, n_dist=6, n_suct=12).d_max  # the test's grid
        rows.append(
            {
                "dataset": f"R2/R1 = {ratio:g}, θ = 0",
                "source": "YADE writesCapFile.m (Duriez), comments",
                "quantity": "d*_max = D/R2",
                "published": published,
                "capred": value,
                "difference": value - published,
                "tolerance": "0.2% relative",
            }
        )
    return rows


def real_rows() -> list[dict]:
    """The rows of ``tests/real_cases.py`` (real laboratory data sets), if that module exists.

    Returns
    -------
    list of dict
    """
    mod = _tests_module("real_cases")
    return [] if mod is None else list(mod.validation_rows())


VALIDATIONS = {
    "Capillary stress bounds at failure: Prunier et al. (2024)": (
        prunier_rows,
        "`capred triaxial-bounds` on the Gavet silt tests reconstructed from the paper (the bundled sample "
        "`triaxial-bounds`; `tests/test_triaxial_published.py` explains the reconstruction and why two lower-"
        "bound ratios are checked to 0.02).",
    ),
    "Retention fits: van Genuchten (1980), Table 1": (
        vg1980_rows,
        "`capred retention --model vg` with θ_s and θ_r fixed at the published values, on the data digitised "
        "from the paper (`tests/data/retention/`, sources in its README).",
    ),
    "Capillary bridges: YADE's capillary-file generator": (
        duriez_rows,
        "The widest gap a bridge spans at zero suction, d* = D/R2, from `capred bridge yade-files` against "
        "Duriez's finite-difference estimates in the comments of YADE's generator.",
    ),
    "Real laboratory data": (
        real_rows,
        "Public laboratory data sets (`tests/data/real/`, sources in its SOURCES.md), from `tests/real_cases.py`.",
    ),
}


def validation_page() -> str:
    """The "Validated against" page: every table computed now, by the code the tests run.

    Returns
    -------
    str
    """
    out = [
        "# Validated against\n",
        "Every number on this page was computed while these pages were built, by the same code and from the "
        "same case lists as the test suite (`pytest` fails when a row leaves its tolerance); nothing here is "
        "typed by hand. *difference* = capred − published.\n",
    ]
    header = ["dataset", "source", "quantity", "published", "capred", "difference", "tolerance", "within"]
    for title, (rows_of, text) in VALIDATIONS.items():
        rows = rows_of()
        if not rows:
            continue
        out.append(f"## {title}\n\n{text}\n")
        table = []
        for r in rows:
            tol, diff = r.get("tolerance"), r.get("difference")
            within = ""
            if isinstance(r.get("passed"), bool):  # a row that says itself whether it holds (tests/real_cases.py)
                within = "yes" if r["passed"] else "**no**"
            elif isinstance(tol, int | float) and isinstance(diff, int | float):
                within = "yes" if abs(diff) <= tol else "**no**"
            elif isinstance(tol, str) and tol.endswith("relative") and isinstance(diff, int | float):
                rel = float(tol.split("%")[0]) / 100
                within = "yes" if abs(diff) <= rel * abs(float(r["published"])) else "**no**"
            table.append([_fmt(r.get(k, "")) for k in header[:-1]] + [within])
        out.append(_table(header, table))
    return "\n".join(out)


# --------------------------------------------------------------------------------------------------------------


def write_all() -> list[Path]:
    """Write every generated page into ``docs/generated/``.

    Returns
    -------
    list of pathlib.Path
    """
    os.environ.setdefault("MPLBACKEND", "Agg")
    return [
        _write("cli.md", cli_page()),
        _write("registries.md", registries_page()),
        _write("glossary.md", glossary_page()),
        _write("records.md", records_page()),
        _write("references.bib", bibtex()),
        _write("validation.md", validation_page()),
    ]


if __name__ == "__main__":
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    for p in write_all():
        print(p.relative_to(ROOT))
