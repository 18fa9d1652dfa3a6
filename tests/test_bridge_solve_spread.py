"""`capred bridge solve` on several processes, reading and writing included (issue 31, item 4): each process
reads, parses and solves whole blocks of the file and writes their CSV and JSON text; the files are the same, byte
for byte, as those of one process, and a bad row still stops the run with nothing written."""

import json
import os

import numpy as np
import pytest
from test_blocks_bridge import _cases
from typer.testing import CliRunner

from capred.cli import app
from capred.pipelines import bridge as pb
from capred.pipelines import bridge_blocks as bb
from capred.pipelines import bridge_solve as bs


@pytest.fixture
def small_blocks(monkeypatch):
    monkeypatch.setattr("capred.io.blocks.BLOCK_BYTES", 20_000)  # 5 blocks of the 3,000 rows


@pytest.fixture
def forks(monkeypatch):
    """The pids of the processes forked while the test runs."""
    seen = []
    real_fork = os.fork

    def fork():
        pid = real_fork()
        if pid:
            seen.append(pid)
        return pid

    monkeypatch.setattr(os, "fork", fork)
    return seen


def _run(tmp_path, f, workers, *extra):
    out = tmp_path / f"out{workers}{''.join(extra)}"
    res = CliRunner().invoke(
        app, ["bridge", "solve", str(f), "--out", str(out), "--no-html", "--workers", str(workers), *extra]
    )
    assert res.exit_code == 0, res.output
    return out, res.output


def _without_workers(doc: bytes) -> dict:
    d = json.loads(doc)
    d["options"].pop("workers")  # the option as given: 1, 2 or 3
    return d


@pytest.mark.parametrize("workers", [2, 3])
def test_files_are_those_of_one_process_byte_for_byte(tmp_path, small_blocks, forks, workers):
    f = _cases(tmp_path / "cases.csv")
    one, text_one = _run(tmp_path, f, 1)
    assert forks == []  # one process: nothing forked
    many, text_many = _run(tmp_path, f, workers)
    # workers - 1 readers-solvers, then workers - 1 writers of the CSV and JSON text (and the JSON writer's own
    # process where the machine's load leaves a core idle)
    assert len(forks) >= 2 * (workers - 1)
    assert (many / "solve.csv").read_bytes() == (one / "solve.csv").read_bytes()
    a, b = (one / "solve.json").read_bytes(), (many / "solve.json").read_bytes()
    # the same bytes from the rows on; before them only the option --workers differs
    assert a[a.index(b'"source":') :] == b[b.index(b'"source":') :]
    assert _without_workers(a) == _without_workers(b)
    assert len(json.loads(b)["bridges"]) == 3000
    assert text_many.replace(str(many), "OUT") == text_one.replace(str(one), "OUT")  # the same console summary


def test_the_result_is_that_of_one_process_to_the_bit(tmp_path, small_blocks, monkeypatch):
    f = _cases(tmp_path / "cases.csv")
    monkeypatch.setenv("CAPRED_PROCESSES", "1")
    one = pb.solve_bridges(f)
    monkeypatch.setenv("CAPRED_PROCESSES", "3")
    three = pb.solve_bridges(f)
    # blocks of a third of the usual size at 3 processes (at least 4 a process, at most 4 times as many as usual)
    assert isinstance(three, bb.BridgeBlocks) and three.processes == 3 and three.n_blocks == 12
    assert not bs.ONE_PROCESS and bb._Worker.live_fds == []  # the run's state is cleared
    np.testing.assert_array_equal(three.status, one.status)
    a, b = one._all(), three._all()
    assert list(a) == list(b)
    for k in a:
        np.testing.assert_array_equal(b[k], a[k], err_msg=k)  # exact: the same blocks, solved alike
    assert three.notes == one.notes and three.warnings == one.warnings and three.inputs == one.inputs
    np.testing.assert_array_equal(three.inputs_si["ratio"], one.inputs_si["ratio"])
    assert three.rows_range(1990, 2010) == one.rows_range(1990, 2010)


def test_the_excel_dialect_is_written_from_the_columns(tmp_path, small_blocks):
    """The text written ahead is the standard dialect's; an excel-eu CSV is written from the columns, the same
    bytes as one process writes."""
    f = _cases(tmp_path / "cases.csv")
    one, _ = _run(tmp_path, f, 1, "--csv-dialect", "excel-eu")
    two, _ = _run(tmp_path, f, 2, "--csv-dialect", "excel-eu")
    assert (two / "solve.csv").read_bytes() == (one / "solve.csv").read_bytes()
    assert (two / "solve.csv").read_bytes().startswith("\ufeff".encode())


@pytest.mark.parametrize("bad_line", [300, 1500, 2500])
def test_a_bad_row_in_any_block_stops_the_run_with_its_line(tmp_path, small_blocks, bad_line):
    """Whichever process reads the bad row (line 300: the first block, this process; 1500 and 2500: later blocks,
    a worker's or this process's), the run stops with the message one process gives, and writes nothing."""
    f = _cases(tmp_path / "cases.csv", bad_line=bad_line)
    msgs = []
    for workers in (1, 2, 3):
        out = tmp_path / f"out{workers}"
        res = CliRunner().invoke(
            app, ["bridge", "solve", str(f), "--out", str(out), "--no-html", "--workers", str(workers)]
        )
        assert res.exit_code != 0 and f"line {bad_line}" in res.output and "Traceback" not in res.output
        assert not out.exists()
        msgs.append(res.output)
    assert msgs[1] == msgs[0] and msgs[2] == msgs[0]
    assert bb._Worker.live_fds == [] and not bs.ONE_PROCESS


def test_a_short_file_stays_in_one_process(tmp_path, forks):
    """A file of one block is solved as one table, as before (no worker for a single block)."""
    f = _cases(tmp_path / "cases.csv", n=200)
    res = pb.solve_bridges(f, pb.BridgeOptions(workers=4))
    assert isinstance(res, bs.BridgeResult) and res.status.size == 200


def test_the_json_document_on_stdout_is_that_of_one_process(tmp_path, small_blocks):
    """`--json` without `--out` prints the document: the rows come from the text written ahead, the same bytes."""
    f = _cases(tmp_path / "cases.csv")
    docs = []
    for workers in (1, 2):
        res = CliRunner().invoke(app, ["bridge", "solve", str(f), "--json", "--workers", str(workers)])
        assert res.exit_code == 0, res.output
        docs.append(res.stdout.encode())
    assert docs[0][docs[0].index(b'"source":') :] == docs[1][docs[1].index(b'"source":') :]
    assert _without_workers(docs[0]) == _without_workers(docs[1])


@pytest.mark.parametrize("workers", [1, 2])
def test_report_html_of_a_long_file_shows_its_first_rows(tmp_path, small_blocks, workers):
    """A file read block by block keeps its rows in a spool: report.html shows the first rows of the spool under
    the CSV's headers, as of a short file (it raised AttributeError on 'HeadedSpool.columns')."""
    f = _cases(tmp_path / "cases.csv")
    out = tmp_path / f"html{workers}"
    res = CliRunner().invoke(app, ["bridge", "solve", str(f), "--out", str(out), "--workers", str(workers)])
    assert res.exit_code == 0, res.output
    html = (out / "report.html").read_text(encoding="utf-8")
    first = (out / "solve.csv").read_text(encoding="utf-8").splitlines()[0].split(",")
    assert all(h.replace("^", "") in html.replace("<sup>", "").replace("</sup>", "") or "[" in h for h in first[:3])
    assert html.count("<tr>") > 20  # rows of the table, not an empty section
