"""One column vocabulary (issue 28, item 3): the spellings of a test id live once in the glossary
(capred.nomenclature.COLUMN_ALIASES) and every reader of every command accepts them."""

import json
import warnings

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.io.table import Column
from capred.nomenclature import COLUMN_ALIASES, column_aliases

runner = CliRunner()
SPELLINGS = ("Test no", "Test No.", "sample", "Sample ID")


def _renamed(sample: str, old: str, new: str, tmp_path) -> str:
    """The bundled sample with its id column renamed to ``new`` (only the header cell changes)."""
    lines = capred.sample_path(sample).read_text().splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.split(",")[0] == old)
    lines[k] = ",".join([new, *lines[k].split(",")[1:]])
    p = tmp_path / f"{sample}.csv"
    p.write_text("\n".join(lines) + "\n")
    return str(p)


def test_glossary_aliases_reach_every_column_named_test_id():
    col = Column("test_id", "text", None, "test identifier", ("my_own",))
    assert col.aliases[0] == "my_own"  # a schema's own spellings come first
    assert set(column_aliases("test_id")) <= set(col.aliases)
    assert {"test_no", "sample", "sample_id"} <= set(COLUMN_ALIASES["test_id"])


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_triaxial_bounds_cli_reads_a_test_no_column(spelling, tmp_path):
    src = _renamed("triaxial-bounds", "test_id", spelling, tmp_path)
    res = runner.invoke(app, ["triaxial-bounds", src, "--json", "--no-plots", "--out", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    ref = runner.invoke(app, ["triaxial-bounds", "--sample", "--json", "--no-plots", "--out", str(tmp_path / "ref")])
    a = json.loads((tmp_path / "out" / "summary.json").read_text())
    b = json.loads((tmp_path / "ref" / "summary.json").read_text())
    assert ref.exit_code == 0
    # the same tests by the same ids, whatever the header says
    assert [t["test_id"] for t in a["tests"]] == [t["test_id"] for t in b["tests"]]


@pytest.mark.parametrize("spelling", SPELLINGS)
@pytest.mark.parametrize(
    ("sample", "run", "ids"),
    [
        ("shear", "run_shear", lambda r: r.tests["test_id"].tolist()),
        ("prism", "run_prism", lambda r: list(r.labels)),
    ],
)
def test_every_reader_of_a_test_id_accepts_the_spellings(sample, run, ids, spelling, tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fn = getattr(capred, run)
        got = ids(fn(_renamed(sample, "test_id", spelling, tmp_path)))
        ref = ids(fn(str(capred.sample_path(sample))))
    assert got == ref and len(got) > 0


@pytest.mark.parametrize("spelling", SPELLINGS)
def test_triaxial_curves_accept_the_spellings(spelling, tmp_path):
    """Raw curves (a long table of readings) name their test by the same vocabulary."""
    from capred.pipelines.triaxial_curves import read_curves

    got = read_curves(_renamed("triaxial-curves", "test_id", spelling, tmp_path))
    ref = read_curves(str(capred.sample_path("triaxial-curves")))
    assert sorted(got.peaks) == sorted(ref.peaks) and len(ref.peaks) > 0 and not got.problems
