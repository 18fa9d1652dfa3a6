"""`capred bridge solve` on a file of several blocks: the same bridges as one whole table, written whole."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.io.table import read_table
from capred.pipelines import bridge as pb
from capred.pipelines import bridge_solve as bs
from capred.pipelines.bridge_blocks import BridgeBlocks


def _cases(path, n=3000, bad_line=None):
    """Random steel-sphere bridges: suction-controlled rows and volume-controlled ones, some beyond rupture."""
    rng = np.random.default_rng(7)
    lines = ["R [mm],contact_angle [deg],gap [mm],suction [kPa],V_w [mm3]"]
    for i in range(n):
        R, th, gap = rng.uniform(0.2, 2.0), rng.uniform(0, 50), rng.uniform(0, 0.05)
        if i % 3:
            lines.append(f"{R:.5f},{th:.3f},{gap * R:.6f},{10 ** rng.uniform(-1, 1.5):.5f},")
        else:
            lines.append(f"{R:.5f},{th:.3f},{gap * R:.6f},,{rng.uniform(1e-4, 1e-2) * R**3:.6g}")
    if bad_line is not None:
        cells = lines[bad_line - 1].split(",")
        cells[1] = "95"
        lines[bad_line - 1] = ",".join(cells)
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def small_blocks(monkeypatch):
    monkeypatch.setattr("capred.io.blocks.BLOCK_BYTES", 20_000)  # ~400 rows per block: 8 blocks


def test_blocks_give_the_bridges_of_the_whole_table(tmp_path, small_blocks):
    f = _cases(tmp_path / "cases.csv")
    res = pb.solve_bridges(f)
    assert isinstance(res, BridgeBlocks) and res.status.size == 3000
    whole = pb.solve_bridges(read_table(f, pb.SOLVE_SCHEMA))
    assert list(res.columns()) == list(whole.columns())  # the same numeric columns either way
    a, b = res._all(), whole._cols()
    assert list(a) == list(b)
    np.testing.assert_array_equal(res.status, whole.status)
    np.testing.assert_array_equal(a["note"], b["note"])
    for k in a:
        if a[k].dtype != object:
            # the same rows through the same solver; a batch's iteration count follows its slowest row, so a row
            # may take one more Newton polish in one batch than in another: 1e-12 relative, far below 1e-9 (the
            # verification tolerance of every bridge)
            np.testing.assert_allclose(a[k], b[k], rtol=1e-12, atol=0, equal_nan=True, err_msg=k)
    assert res.rows_range(1990, 2010) == pb.json_rows({k: v[1990:2010] for k, v in a.items()})


def test_cli_writes_every_row_once(tmp_path, small_blocks):
    f = _cases(tmp_path / "cases.csv")
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["bridge", "solve", str(f), "--out", str(out), "--no-html"])
    code, text = res.exit_code, res.output
    assert code == 0, text
    rows = (out / "solve.csv").read_text().splitlines()
    assert len(rows) == 3001 and rows[0].startswith("r0 [mm],")  # one header, then every row once, in order
    doc = json.loads((out / "solve.json").read_text())
    assert len(doc["bridges"]) == 3000
    whole = pb.solve_bridges(read_table(f, pb.SOLVE_SCHEMA))
    assert [r["status"] for r in doc["bridges"]] == [pb.STATUS[k] for k in whole.status]


def test_a_bad_row_in_a_later_block_stops_the_run(tmp_path, small_blocks):
    f = _cases(tmp_path / "cases.csv", bad_line=2500)
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["bridge", "solve", str(f), "--out", str(out), "--no-html"])
    code, text = res.exit_code, res.output
    assert code != 0 and "line 2500" in text and "contact_angle" in text and "Traceback" not in text
    assert not out.exists()  # nothing written


def test_no_numpy_warning_where_the_gap_is_flat_in_suction():
    """225 volume- and suction-controlled rows (found by a new-user review) where the constant-volume Newton step
    meets a zero derivative of the gap in suction: such a row is simply not on the arc (no RuntimeWarning)."""
    import warnings
    from pathlib import Path

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = pb.solve_bridges(Path(__file__).parent / "data" / "bridge" / "gap_flat_in_suction.csv")
    assert res.status.size == 225 and np.any(res.status == 0)


def test_one_helper_process_serves_every_block(tmp_path, small_blocks, monkeypatch):
    """Blocks of a long file share one forked helper (the second half of each block): one fork for the run,
    and the bridges, bit for bit, of one process."""
    import os

    f = _cases(tmp_path / "cases.csv")
    one = pb.solve_bridges(f)._all()
    forks = []
    real_fork = os.fork

    def fork():
        pid = real_fork()
        if pid:
            forks.append(pid)
        return pid

    monkeypatch.setattr(os, "fork", fork)
    monkeypatch.setenv("CAPRED_PROCESSES", "2")  # two processes whatever the machine's load
    monkeypatch.setattr(bs, "_PARALLEL_ROWS", 100)  # every block of ~400 rows in two processes
    two = pb.solve_bridges(f)._all()
    assert len(forks) == 1  # one helper for the 8 blocks
    assert bs._HELPERS == []  # closed with the run
    for k, v in one.items():
        np.testing.assert_array_equal(two[k], v)  # exact: each row solved by the same operations
