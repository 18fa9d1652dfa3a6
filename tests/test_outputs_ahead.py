"""A run whose outputs would be too large is refused before anything is computed (issue 46): its input's data
lines x the cells its outputs take per row (``Reduction.row_cells``) sized against the writer's bound."""

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.io.blocks import data_lines
from capred.reductions import REDUCTIONS
from capred.report.outputs import output_cells

runner = CliRunner()


@pytest.mark.parametrize(
    ("text", "lines"),
    [
        ("a,b\n1,2\n", 2),
        ("a,b\n1,2", 2),  # no line end after the last line
        ("a,b\r\n1,2\r\n\r\n", 2),  # CRLF: the empty piece between CR and LF holds nothing
        ("a,b\r1,2\r", 2),  # lone CRs end lines too
        ("\n\n,,\n;;\n \t\n", 0),  # blank lines and rows of delimiters only hold no data
        ("\n" * 50 + "x", 1),
        ("\r" * 50, 0),
    ],
)
@pytest.mark.parametrize("block", [1, 2, 3, None])  # a line cut between blocks is counted once
def test_data_lines_counts_what_holds_data(tmp_path, text, lines, block):
    path = tmp_path / "t.csv"
    path.write_bytes(text.encode())
    assert data_lines(path, block) == lines


def _width(table) -> int:
    return len(table) if isinstance(table, dict) else table.shape[1]


@pytest.mark.parametrize(
    ("command", "options", "table"),
    [
        ("shear", {"bootstrap": 0}, "results"),
        ("shear", {"bootstrap": 0, "models": ("bishop",)}, "results"),
        ("triaxial", {"bootstrap": 0}, "results"),
        ("triaxial", {"bootstrap": 0, "models": "bishop"}, "results"),
        ("triaxial", {"bootstrap": 0, "models": "bishop,own1,no_suction"}, "results"),
        ("triaxial-bounds", {}, "results"),
        ("retention", {}, "points"),
        ("retention", {"models": ("vg",)}, "points"),
        ("bridge solve", {}, "solve"),
        ("bridge compare", {}, "compare"),
        ("bridge rupture", {}, "rupture"),
        ("compression", {}, "results"),
    ],
)
def test_declared_cells_per_row_are_the_per_row_tables_columns(command, options, table):
    """Each declaration is exact on the sample: its per-row table's columns with these options (a file that lacks
    an optional input column writes fewer: the estimate is an upper bound)."""
    red = REDUCTIONS[command]
    opts = red.options(**options)
    tables = red.run(capred.sample_path(red.sample), opts).csv_tables()
    if getattr(opts, "models", None) == "all":  # triaxial's default: the models that lack a parameter are skipped
        assert output_cells(command, opts) >= _width(tables[table])
    else:
        assert output_cells(command, opts) == _width(tables[table])


def test_a_tiny_output_bound_refuses_before_the_reduction(tmp_path, monkeypatch):
    """$CAPRED_MAX_OUTPUT_MEGABYTES of 0.01 (10 kiB): the shear sample's 52 tests x 59 cells x 40 B = 123 kB are
    refused from its lines alone; the reduction is never called and nothing is written."""
    import capred.pipelines.shear_run as shear

    def not_called(*args, **kwargs):
        raise AssertionError("the reduction ran")

    monkeypatch.setattr(shear, "run_shear", not_called)
    monkeypatch.setenv("CAPRED_MAX_OUTPUT_MEGABYTES", "0.01")
    out = tmp_path / "o"
    res = runner.invoke(app, ["shear", str(capred.sample_path("shear")), "--no-plots", "--out", str(out)])
    assert res.exit_code == 1, res.output
    assert "would take about" in res.output and "CAPRED_MAX_OUTPUT_MEGABYTES" in res.output
    assert "table cells" in res.output and "the reduction ran" not in res.output
    assert not out.exists() and not list(tmp_path.iterdir())


def test_the_batch_runner_sizes_each_file_before_its_reduction(tmp_path, monkeypatch):
    import capred.pipelines.shear_run as shear
    from capred import batch

    monkeypatch.setattr(shear, "run_shear", lambda *a, **k: pytest.fail("the reduction ran"))
    monkeypatch.setenv("CAPRED_MAX_OUTPUT_MEGABYTES", "0.01")
    job = batch.Job("shear", capred.sample_path("shear"), tmp_path / "o", capred.ShearOptions(bootstrap=0), False)
    with pytest.raises(capred.OutputError, match="would take about"):
        batch.run_job(job)
    assert not (tmp_path / "o").exists()


def test_a_run_within_the_bound_is_written(tmp_path, monkeypatch):
    monkeypatch.setenv("CAPRED_MAX_OUTPUT_MEGABYTES", "1")  # 1 MiB: the sample's 123 kB of tables fit
    out = tmp_path / "o"
    res = runner.invoke(
        app,
        ["shear", str(capred.sample_path("shear")), "--bootstrap", "0", "--no-plots", "--no-html", "--out", str(out)],
    )
    assert res.exit_code == 0, res.output
    assert (out / "results.csv").exists()
