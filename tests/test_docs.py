"""The documentation site covers capred as it is (issue 43).

Every command has a user-guide page and a section of the command-line reference with its real ``--help``;
every registry entry is named in the hand-written user guide and has a row in the generated registries page;
every quantity of the glossary and every reference of the bibliography reach their generated pages; the
validation page is computed from the tests' own case lists and every row lies within its tolerance; the
Sphinx configuration builds with the extensions the ``docs`` extra installs. (The site itself is built with
warnings as errors by .ci/run.)
"""

import re
import sys
import tomllib

import pytest
from conftest import ROOT

DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS))
import generate  # noqa: E402

GUIDE = {p.name: p.read_text(encoding="utf-8") for p in (DOCS / "user_guide").glob("*.md")}
HAND = "\n".join(
    p.read_text(encoding="utf-8")
    for p in DOCS.rglob("*.md")
    if not {"generated", "auto_examples", "_build"} & set(p.relative_to(DOCS).parts)
)


@pytest.fixture(scope="module")
def cli_page():
    return generate.cli_page()


@pytest.mark.parametrize("name", generate.command_names())
def test_every_command_has_a_user_guide_page(name):
    pages = [page for page, text in GUIDE.items() if f"capred {name}" in text and text.startswith("# ")]
    assert pages, f"no page of docs/user_guide names `capred {name}`"


@pytest.mark.parametrize("name", generate.command_names())
def test_every_command_is_in_the_cli_reference(name, cli_page):
    section = cli_page.split(f"## `capred {name}`\n", 1)
    assert len(section) == 2, name
    assert f"Usage: capred {name} [OPTIONS]" in section[1].split("\n## ", 1)[0]


def test_help_text_is_the_command_lines():
    # the reference shows what a user's terminal shows, without colour codes
    text = generate.help_text(["shear"])
    assert "\x1b[" not in text and "--models" in text and "--bootstrap" in text


REGISTRY_ENTRIES = [(title, key) for title, (_, entries) in generate.registries().items() for key in entries]


@pytest.mark.parametrize("title,key", REGISTRY_ENTRIES)
def test_every_registry_entry_is_documented(title, key):
    entries = generate.registries()[title][1]
    entry = entries[key]
    label = getattr(entry, "label", None) or ""
    if title == "Commands":
        assert f"capred {key}" in HAND, key
    else:
        assert f"`{key}`" in HAND or (label and label in HAND), f"{title}: {key} is named in no hand-written page"


def test_registries_page_has_a_row_per_entry():
    page = generate.registries_page()
    for title, key in REGISTRY_ENTRIES:
        assert f"| `{key}` |" in page, (title, key)


def test_glossary_page_has_every_quantity():
    from capred.nomenclature import QUANTITIES

    page = generate.glossary_page().split("\n## ")[0]  # the quantities' table, before the id spellings
    rows = [line for line in page.splitlines() if line.startswith("| `")]
    assert len(rows) == len(QUANTITIES)
    for name, q in QUANTITIES.items():
        assert f"| `{name}` | {q.symbol} | {q.unit} |" in page.replace("\\|", "|"), name


def test_bibliography_has_every_reference():
    from capred.references import REFERENCES

    bib = generate.bibtex()
    keys = re.findall(r"^@misc\{([^,]+),", bib, flags=re.M)
    assert keys == list(REFERENCES)
    assert bib.count("{") == bib.count("}")  # balanced: pybtex reads every entry
    assert "doi = {10.1080/19648189.2024.2314099}" in bib  # Prunier et al. (2024)


def test_validation_rows_are_the_tests_cases_and_within_tolerance():
    prunier = generate.prunier_rows()
    sys.path.insert(0, str(ROOT / "tests"))
    import test_triaxial_published as tp

    assert [(r["quantity"], r["published"]) for r in prunier] == [(c[0], c[2]) for c in tp.CASES]
    for r in prunier:  # the same tolerance the test applies
        assert abs(r["capred"] - r["published"]) <= r["tolerance"], r
    page = generate.validation_page()
    assert "**no**" not in page
    assert page.count("| yes |") >= len(prunier) + 2 * 5 + 9  # Prunier, van Genuchten (α, n of 5 soils), YADE


def test_validation_page_takes_the_real_data_rows_when_present(monkeypatch):
    row = {
        "dataset": "a data set",
        "source": "a paper, Table 1",
        "quantity": "phi_deg",
        "published": 31.0,
        "capred": 31.2,
        "difference": 0.2,
        "tolerance": 0.5,
    }
    monkeypatch.setitem(generate.VALIDATIONS, "Real laboratory data", (lambda: [row], "text"))
    monkeypatch.setitem(generate.VALIDATIONS, "Capillary bridges: YADE's capillary-file generator", (list, ""))
    page = generate.validation_page()
    assert "| a data set | a paper, Table 1 | phi_deg | 31 | 31.2 | 0.2 | 0.5 | yes |" in page
    # tests/real_cases.py's rows: difference and tolerance as text, NaN where the source has no value, and
    # whether the row holds
    other = {**row, "published": float("nan"), "difference": "-1.2 %", "tolerance": "2 %", "passed": False}
    monkeypatch.setitem(generate.VALIDATIONS, "Real laboratory data", (lambda: [other], "text"))
    page = generate.validation_page()
    assert "| a data set | a paper, Table 1 | phi_deg | — | 31.2 | -1.2 % | 2 % | **no** |" in page


def test_user_guide_glob_picks_up_new_pages():
    index = (DOCS / "user_guide.md").read_text(encoding="utf-8")
    assert ":glob:" in index and "user_guide/*" in index


def test_docs_extra_installs_the_configured_extensions():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    docs = {re.split(r"[<>=!~ ]", d)[0].lower() for d in extras["docs"]}
    conf = (DOCS / "conf.py").read_text(encoding="utf-8")
    needs = {
        "myst_parser": "myst-parser",
        "sphinx_gallery": "sphinx-gallery",
        "sphinxcontrib.bibtex": "sphinxcontrib-bibtex",
        "pydata_sphinx_theme": "pydata-sphinx-theme",
    }
    for module, package in needs.items():
        assert module in conf and package in docs, package
    assert "sphinx" in docs


def test_gallery_has_at_least_eight_examples_each_drawing_a_figure():
    examples = sorted((DOCS / "examples").glob("plot_*.py"))
    assert len(examples) >= 8
    for path in examples:
        text = path.read_text(encoding="utf-8")
        assert text.startswith('"""') and "plt.show()" in text, path.name
