"""Sphinx configuration of capred's documentation.

Build (from the repository root, in a venv with ``pip install ".[docs]"``)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

The pages under ``docs/generated/`` (command-line reference, registries, glossary, bibliography, validation) and
the example gallery (``docs/examples/plot_*.py`` -> ``docs/auto_examples/``) are made at every build.
"""

import os
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))  # document (and run the gallery on) the checked-out capred
sys.path.insert(0, str(DOCS))
os.environ.setdefault("MPLBACKEND", "Agg")

import generate  # noqa: E402

import capred  # noqa: E402

generate.write_all()

project = "capred"
author = "capred developers"
copyright = "2026, capred developers"
version = release = capred.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinx_gallery.gen_gallery",
    "sphinxcontrib.bibtex",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "generated/*.bib", "examples/README.txt", "**/README.md", "auto_examples/*.ipynb"]
templates_path = ["_templates"]
# "--models" stays two hyphens (options, help texts), quotes stay as written
smartquotes = False
html_static_path = ["_static"]

# MyST: the Markdown moved from the README builds as it was written
myst_enable_extensions = ["colon_fence", "deflist", "dollarmath"]
myst_heading_anchors = 3
# a page of the user guide may jump a heading level (### under #): not an error of the site
# numpydoc-style "References" sections list [1], [2] ... without citing each in the text (pvlib does the same)
suppress_warnings = ["myst.header", "ref.footnote"]

# autodoc / autosummary / napoleon (numpydoc-style docstrings)
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": False, "show-inheritance": False}
autodoc_typehints = "none"  # the numpydoc sections state types and units
autodoc_member_order = "bysource"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_ivar = True  # Attributes sections as fields: no duplicate descriptions of dataclass fields
napoleon_use_rtype = False
nitpicky = False

# sphinxcontrib-bibtex: the bibliography generated from capred.references
bibtex_bibfiles = ["generated/references.bib"]
bibtex_default_style = "plain"
bibtex_reference_style = "author_year"

# sphinx-gallery: every example executed at every build, on the bundled samples and public data sets
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "show_memory": False,
    "plot_gallery": "True",
}

html_theme = "pydata_sphinx_theme"
html_title = f"capred {release}"
html_theme_options = {
    "show_toc_level": 2,
    "navigation_with_keys": False,
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
    "secondary_sidebar_items": ["page-toc"],
}
html_show_sourcelink = False
html_css_files = ["capred.css"]
# top-level pages have no section to navigate: their tables get the sidebar's width
html_sidebars = {
    "index": [],
    "getting_started": [],
    "whatsnew": [],
    "changelog": [],
    "contributing": [],
    "generated/validation": [],
}
html_last_updated_fmt = None


_ABSOLUTE = re.compile(r"(?<![\\`|])\|(?=[^\s|`])([^|`\n]*?[^\s|`\\])\|(?![\w|])")


def _field_lines(obj) -> list[str]:
    """An ``Attributes`` section for an Options or Result dataclass whose docstring has none.

    Options fields read their meaning, unit, range, default and option from the snapshot the command line uses
    (``capred.cli.declare.field_facts``); Result fields give their type.
    """
    from dataclasses import fields, is_dataclass

    from capred.result import Options, Result

    if not (isinstance(obj, type) and is_dataclass(obj) and issubclass(obj, Options | Result)):
        return []
    out = ["", "Attributes", "----------"]
    for f in fields(obj):
        if f.name.startswith("_"):
            continue
        kind = f.type if isinstance(f.type, str) else getattr(f.type, "__name__", "")
        out.append(f"{f.name} : {kind}".replace("*", "\\*"))
        text = ""
        if issubclass(obj, Options):
            try:
                from capred.cli.declare import field_facts

                facts = field_facts(f"{obj.__module__}:{obj.__name__}", f.name)
            except Exception:  # a field the command line does not offer
                facts = {}
            unit = facts.get("unit") or ""
            bits = [
                facts.get("text") or "",
                f"[{unit}]" if unit else "",
                facts.get("range") or "",
                facts.get("default") or "",
            ]
            text = " ".join(b for b in bits if b).replace("*", "\\*")
        out.append("    " + (text or "See the class description."))
    return out


def _plain_docstrings(app, what, name, obj, options, lines):
    """Docstrings written for a terminal read as such on the site.

    A module docstring (the long physics notes with ASCII formulas) is shown as preformatted text, as written;
    ``|x|`` (an absolute value) is not a reStructuredText substitution.
    """
    if what == "module" and lines:
        lines[:] = ["::", ""] + ["    " + line for line in lines] + [""]
        return
    if what == "class" and not any(line.strip() == "Attributes" for line in lines):
        lines.extend(_field_lines(obj))
    for i, line in enumerate(lines):
        lines[i] = _ABSOLUTE.sub(r"\\|\1\\|", line)


_LINK = re.compile(r"(?<!!)\[([^\]`<>]+)\]\(((?:\.\./)+[^)#\s]+)\)")


def _repository_links(app, docname, source):
    """A Markdown link from a page to a file of the repository outside docs/ (``tests/data/real/SOURCES.md``)
    becomes a download of that file, so that it resolves on the site as it does on the repository."""
    page = (DOCS / docname).parent

    def link(m):
        target = (page / m.group(2)).resolve()
        if DOCS in target.parents or not target.is_file() or ROOT not in target.parents:
            return m.group(0)
        return f"{{download}}`{m.group(1)} <{m.group(2)}>`"

    source[0] = _LINK.sub(link, source[0])


def setup(app):
    app.connect("autodoc-process-docstring", _plain_docstrings, priority=400)  # before napoleon (500)
    app.connect("source-read", _repository_links)
