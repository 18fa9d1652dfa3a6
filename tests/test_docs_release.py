"""Release metadata agree with each other and with the package (issue 43).

The version lives in one place, ``capred.__version__``, which pyproject.toml reads; CITATION.cff and
.zenodo.json state the same version, date, title, licence, authors and keywords; the changelog and the
documentation's "What's new" have a section for it; paper.md cites only keys that paper.bib holds.
"""

import json
import re
import tomllib

from conftest import ROOT

import capred


def _cff() -> dict:
    """The top-level scalar fields, keywords and author names of CITATION.cff (a YAML subset, no parser needed)."""
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    top = text.split("\nreferences:")[0]
    fields = dict(re.findall(r'^([a-z-]+): "?([^"\n]*)"?$', top, flags=re.M))
    block = lambda name: re.search(rf"^{name}:\n((?:  .*\n)+)", top + "\n", flags=re.M).group(1)  # noqa: E731
    fields["keywords"] = re.findall(r"^  - (.+)$", block("keywords"), flags=re.M)
    fields["authors"] = re.findall(r'name: "?([^"\n]+)"?', block("authors"))
    return fields


def test_version_in_one_place():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in project["project"] and "version" in project["project"]["dynamic"]
    assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "capred.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+", capred.__version__)


def test_citation_and_zenodo_agree():
    cff = _cff()
    zen = json.loads((ROOT / ".zenodo.json").read_text(encoding="utf-8"))
    assert cff["version"] == zen["version"] == capred.__version__
    assert cff["date-released"] == zen["publication_date"]
    assert cff["title"] == zen["title"]
    assert cff["license"] == zen["license"] == "MIT"
    assert cff["abstract"] == zen["description"]
    assert cff["keywords"] == zen["keywords"]
    assert cff["authors"] == [c["name"] for c in zen["creators"]]


def test_changelog_and_whatsnew_have_the_version():
    version = re.escape(capred.__version__)
    assert re.search(rf"^## {version}\b", (ROOT / "CHANGELOG.md").read_text(encoding="utf-8"), flags=re.M)
    assert re.search(rf"^## {version}\b", (ROOT / "docs" / "whatsnew.md").read_text(encoding="utf-8"), flags=re.M)


def test_paper_cites_only_what_paper_bib_holds():
    paper = (ROOT / "paper.md").read_text(encoding="utf-8")
    bib = (ROOT / "paper.bib").read_text(encoding="utf-8")
    keys = set(re.findall(r"^@\w+\{([^,]+),", bib, flags=re.M))
    cited = set(re.findall(r"@([A-Za-z][\w:-]*\w)", paper.split("\n---\n", 1)[1]))
    assert cited and cited <= keys, cited - keys
    front = paper.split("\n---\n", 1)[0]
    for field in ("title:", "tags:", "authors:", "date:", "bibliography: paper.bib"):
        assert field in front, field
    for section in ("# Summary", "# Statement of need", "# Validation"):
        assert section in paper, section


def test_every_package_of_capred_is_installed():
    """A wheel holds only the packages pyproject.toml lists: every folder of capred/ with an __init__.py must be one
    of them (capred.spec was once left out, and only a non-editable install showed it)."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    listed = set(project["tool"]["setuptools"]["packages"])
    on_disk = {
        ".".join(p.parent.relative_to(ROOT).parts)
        for p in (ROOT / "capred").rglob("__init__.py")
        if "__pycache__" not in p.parts
    }
    assert on_disk - listed == set()
