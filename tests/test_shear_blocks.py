"""`capred shear` on a long table, block by block (issue 20): the same files as the whole-table run.

The block size of capred.io.blocks is made small (monkeypatched) so that a table of a few thousand tests is
read in several blocks; results.csv, summary.csv and the JSON document must then be byte for byte those of the
same table read whole, and the figures' and console tables' inputs the same numbers.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

import capred.io.blocks as blocks_module
import capred.pipelines.shear_long as shear_long_module
from capred.io.writers import encode_csv, encode_json
from capred.pipelines.shear import ShearOptions, ShearResult
from capred.pipelines.shear_long import ShearBlocks
from capred.pipelines.shear_run import run_shear
from capred.samples import sample_path


def _rows(path, n: int, seed: int = 20) -> None:
    """``n`` tests: the bundled sample repeated, ids made unique, tau_max perturbed by a seeded 2 % noise."""
    lines = [ln for ln in sample_path("shear").read_text().splitlines() if ln and not ln.startswith("#")]
    header, rows = lines[0], lines[1:]
    tau = header.split(",").index("tau_max [kPa]")
    noise = 1.0 + 0.02 * np.random.default_rng(seed).standard_normal(n)
    out = [header]
    for k in range(n):
        cells = rows[k % len(rows)].split(",")
        cells[0] = f"{cells[0]}-{k // len(rows)}"
        cells[tau] = f"{float(cells[tau]) * noise[k]:.4f}"
        out.append(",".join(cells))
    path.write_text("\n".join(out) + "\n", encoding="utf-8")


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """(whole-table result, block-by-block result) of the same 2,600 tests (50 repeats of the 52 of the sample)."""
    path = tmp_path_factory.mktemp("blocks") / "long.csv"
    _rows(path, 2600)
    opt = ShearOptions(bootstrap=40)
    whole = run_shear(path, opt)
    mp = pytest.MonkeyPatch()
    mp.setattr(blocks_module, "BLOCK_BYTES", 30_000)  # ~450 rows a block: 6 blocks of the ~180 kB file
    mp.setattr(shear_long_module, "_SPOOL_ROWS", 200)  # and each spooled in pieces of 200 tests
    try:
        long = run_shear(path, opt)
    finally:
        mp.undo()
    return whole, long


def test_read_in_blocks(pair):
    whole, long = pair
    assert type(whole) is ShearResult
    assert isinstance(long, ShearBlocks)
    assert len(long.starts) - 1 >= 4  # several blocks, so that every seam is crossed
    assert long.row_count() == 2600 and "2600 rows" in repr(long)


def test_same_files(pair):
    """results.csv, summary.csv and the JSON document: byte for byte the whole-table run's."""
    whole, long = pair
    for name in ("results", "summary"):
        assert encode_csv(long.csv_tables()[name]) == encode_csv(whole.csv_tables()[name]), name
    assert encode_json(long.to_json()) == encode_json(whole.to_json())


def test_rows_across_seams(pair):
    """JSON rows and results.csv columns of a range across block seams, as the whole run gives them."""
    whole, long = pair
    seam = int(long.starts[2])
    assert long._test_rows(seam - 3, seam + 2) == whole._test_rows(seam - 3, seam + 2)
    cols = long.csv_tables()["results"].columns(seam - 3, seam + 2)
    for key, v in whole._results_columns().items():
        assert_array_equal(cols[key], np.asarray(v)[seam - 3 : seam + 2], err_msg=key)


def test_figure_and_table_inputs(pair):
    """The per-test values the figures and the console tables read, where the long run keeps them."""
    from capred.report.presenters import console_tables

    whole, long = pair
    assert [t.rows for t in console_tables(long)] == [t.rows for t in console_tables(whole)]
    rows = long.back.si.sigma_cap.rows
    assert rows.size > 0
    for m in whole.models:
        # the same numbers: the same computation on a slice of the tests (exact)
        assert_allclose(long.predictions[m].si.tau[rows], whole.predictions[m].si.tau[rows], rtol=0, atol=0)
        assert_allclose(
            long.predictions[m].si.tau_prediction_interval[1][rows],
            whole.predictions[m].si.tau_prediction_interval[1][rows],
            rtol=0,
            atol=0,
        )
    assert_allclose(long.back.chi_back[rows], whole.back.chi_back[rows], rtol=0, atol=0)
    assert long.test_ids(rows[:3]) == [str(x) for x in whole.tests["test_id"][rows[:3]]]
    with pytest.raises(IndexError):
        long.back.si.sigma_cap[np.setdiff1d(np.arange(2600), rows)[:1]]  # a row not kept
    # whole columns read back from the spools on demand
    assert_array_equal(long.tests["test_id"], whole.tests["test_id"])
    assert_array_equal(long.tests["chi2"], whole.tests["chi2"])
    assert long.season_rows() == whole.season_rows()


def test_repeated_id_across_blocks(tmp_path, monkeypatch):
    """A test id repeated in another block is reported with the line of its first occurrence."""
    from capred.errors import InputError

    path = tmp_path / "dup.csv"
    _rows(path, 1300)
    lines = path.read_text(encoding="utf-8").split("\n")
    first = lines[5].split(",")[0]
    cells = lines[1200].split(",")
    cells[0] = first
    lines[1200] = ",".join(cells)
    path.write_text("\n".join(lines), encoding="utf-8")
    monkeypatch.setattr(blocks_module, "BLOCK_BYTES", 30_000)
    with pytest.raises(InputError) as err:
        run_shear(path, ShearOptions(bootstrap=0))
    text = str(err.value)
    # the header is line 1, so lines[k] is file line k + 1
    assert f"duplicate test_id '{first}' (first on line 6)" in text
    assert "line 1201" in text


def test_problems_of_every_block_are_reported_at_once(tmp_path, monkeypatch):
    """As for a short table, a long one's problems are all reported in one pass: a negative void volume in
    one block, a letter in a number in another and a test id repeated across two more (block path: 30 kB
    blocks of ~400 tests)."""
    from capred.errors import InputError

    path = tmp_path / "bad.csv"
    _rows(path, 2600)
    lines = path.read_text(encoding="utf-8").split("\n")
    header = lines[0].split(",")
    vv, tau = header.index("V_v [cm^3]"), header.index("tau_max [kPa]")
    cells = lines[500].split(",")
    cells[vv] = "-3.0"
    lines[500] = ",".join(cells)
    cells = lines[1500].split(",")
    cells[tau] = "1.2abc"
    lines[1500] = ",".join(cells)
    cells = lines[2400].split(",")
    cells[0] = lines[1000].split(",")[0]
    lines[2400] = ",".join(cells)
    path.write_text("\n".join(lines), encoding="utf-8")
    monkeypatch.setattr(blocks_module, "BLOCK_BYTES", 30_000)
    with pytest.raises(InputError) as err:
        run_shear(path, ShearOptions(bootstrap=0))
    where = {(p.line, p.column) for p in err.value.problems}
    assert {(501, "V_v [cm^3]"), (1501, "tau_max [kPa]")} <= where
    assert any(p.line == 2401 and "duplicate test_id" in p.message for p in err.value.problems)


def test_sampled():
    """Sampled gives the kept values at kept rows, and refuses any other row, a mask or a whole-array use."""
    from capred.pipelines.shear_records import Sampled

    a = Sampled(np.array([2, 5, 9]), np.array([20.0, 50.0, 90.0]), 12)
    assert_array_equal(a[np.array([9, 2])], [90.0, 20.0])
    assert a[5] == 50.0 and len(a) == 12
    for bad in (np.array([3]), np.array([12]), np.zeros(12, dtype=bool)):
        with pytest.raises(IndexError):
            a[bad]
    with pytest.raises(TypeError):
        np.asarray(a)
