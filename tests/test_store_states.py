"""A lab store that cannot take a run is refused before the run's folder is written (capred.lab_store.Recorder).

Each state is one that a store can reach in a lab (a link left dangling, a file made immutable, a table dropped
by another program, a page damaged): the command exits 1 with one message naming the store, no traceback, no
output folder, and the store's bytes unchanged.
"""

import os
import shutil
import sqlite3
import subprocess
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred import lab_store
from capred.cli import app
from capred.errors import InputError

runner = CliRunner()
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")
G = 9.81


def _shear_file(path, phi_deg=35.0, seed=0):
    rng = np.random.default_rng(seed)
    rows = ["date: 2026-03-01", "test_id,material,condition,added_mass [g],cap_mass [g],box_area [cm^2],tau_max [kPa]"]
    for i, m in enumerate((0.0, 200.0, 400.0, 700.0, 1000.0)):
        sigma = (120.0 + m) * 1e-3 * G / 36e-4 / 1e3
        tau = sigma * np.tan(np.radians(phi_deg)) + rng.normal(0.0, 0.01)
        rows.append(f"T{i},Toyoura sand,dry,{m},120.0,36.0,{tau:.4f}")
    path.write_text("\n".join(rows) + "\n")


def _run(tmp_path, store, out="o", extra=()):
    return runner.invoke(
        app,
        ["shear", str(tmp_path / "a.csv"), "--bootstrap", "0", "--no-plots", "--no-html", "--out",
         str(tmp_path / out), "--store", str(store), *extra],
    )  # fmt: skip


def _good_store(tmp_path):
    """A store holding one run of a.csv (recorded through the command line)."""
    _shear_file(tmp_path / "a.csv")
    store = tmp_path / "lab.sqlite"
    res = _run(tmp_path, store, out="first")
    assert res.exit_code == 0, res.output
    return store


def _bytes(path):
    return {p: open(p, "rb").read() for p in (str(path), f"{path}-wal") if os.path.isfile(p)}


def _drop_table(store):
    con = sqlite3.connect(store)
    con.execute("DROP TABLE records")
    con.commit()
    con.close()


def _drop_column(store):
    con = sqlite3.connect(store)
    con.execute("ALTER TABLE runs DROP COLUMN out_dir")
    con.commit()
    con.close()


def _version(store):
    con = sqlite3.connect(store)
    con.execute("PRAGMA user_version = 1")  # says schema 1 while its tables are schema 2
    con.commit()
    con.close()


def _trigger(store):
    con = sqlite3.connect(store)
    con.execute("CREATE TABLE log (x)")
    con.execute("CREATE TRIGGER spy AFTER INSERT ON runs BEGIN INSERT INTO log VALUES (new.id); END")
    con.commit()
    con.close()


def _shm_folder(store):
    con = sqlite3.connect(store)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    for side in ("-wal", "-shm"):
        if os.path.exists(f"{store}{side}"):
            os.remove(f"{store}{side}")
    os.mkdir(f"{store}-shm")


STATES = {
    "dropped table": (_drop_table, "no table 'records'"),
    "dropped column": (_drop_column, "lost the column out_dir"),
    "schema version mismatch": (_version, "schema version 1"),
    "foreign trigger": (_trigger, "triggers capred did not create (spy)"),
    "-shm a folder": (_shm_folder, "lab.sqlite-shm is a folder"),
}


@pytest.mark.parametrize("state", list(STATES))
def test_store_that_cannot_take_the_run_is_refused_before_writing(tmp_path, state):
    store = _good_store(tmp_path)
    make, message = STATES[state]
    make(store)
    before = _bytes(store)
    res = _run(tmp_path, store)
    assert res.exit_code == 1, res.output
    assert "Traceback" not in res.output and message in res.stderr and str(store) in res.stderr
    assert not (tmp_path / "o").exists()  # nothing written
    assert _bytes(store) == before


def test_dangling_link_loop_and_fifo_are_refused_without_opening(tmp_path):
    _shear_file(tmp_path / "a.csv")
    dangling = tmp_path / "dangling.sqlite"
    dangling.symlink_to(tmp_path / "nowhere" / "lab.sqlite")
    loop = tmp_path / "loop.sqlite"
    loop.symlink_to(loop)
    fifo = tmp_path / "fifo.sqlite"
    os.mkfifo(fifo)
    for store, message in ((dangling, "does not exist"), (loop, "loops"), (fifo, "FIFO")):
        # a FIFO opened for reading waits for a writer forever: refused by stat alone (the test would hang)
        res = _run(tmp_path, store)
        assert res.exit_code == 1 and message in res.stderr and "Traceback" not in res.output, res.output
        assert not (tmp_path / "o").exists()
    with pytest.raises(InputError, match="FIFO"):
        capred.history(fifo)
    assert not (tmp_path / "nowhere").exists()


def test_immutable_store_is_refused_before_writing(tmp_path):
    store = _good_store(tmp_path)
    con = sqlite3.connect(store)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    if shutil.which("chattr") is None or subprocess.run(["chattr", "+i", str(store)]).returncode != 0:
        pytest.skip("chattr +i is not available here (needs root on a file system with attributes)")
    try:
        before = store.read_bytes()
        res = _run(tmp_path, store)
        assert res.exit_code == 1 and "cannot be written" in res.stderr and "Traceback" not in res.output, res.output
        assert not (tmp_path / "o").exists()
        assert store.read_bytes() == before
    finally:
        subprocess.run(["chattr", "-i", str(store)])


@pytest.mark.skipif(sys.platform == "win32" or os.geteuid() == 0, reason="root writes into a read-only folder")
def test_read_only_folder_new_store_is_refused_before_writing(tmp_path):
    _shear_file(tmp_path / "a.csv")
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        res = _run(tmp_path, ro / "lab.sqlite")
        assert res.exit_code == 1 and "cannot be created" in res.stderr, res.output
        assert not (tmp_path / "o").exists()
    finally:
        ro.chmod(0o755)


def _damage_last_run(store):
    """Overwrite bytes inside the last run's stored text (the page's structure intact, its content not)."""
    con = sqlite3.connect(store)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    data = store.read_bytes()
    assert data.count(b'"sha256"') >= 2  # in the run's inputs and its JSON document
    store.write_bytes(data.replace(b'"sha256"', b"\x1b[2J\xff\xfe\xfd\xfc"))  # ESC, then bytes that are not UTF-8


def test_damaged_page_is_reported_and_never_appended_to(tmp_path):
    store = _good_store(tmp_path)
    _damage_last_run(store)
    before = store.read_bytes()
    res = _run(tmp_path, store, extra=("--gamma-w", "9.8"))  # another run: it would be appended
    assert res.exit_code == 1 and "damaged" in res.stderr and "Traceback" not in res.output, res.output
    assert not (tmp_path / "o").exists()
    res = runner.invoke(app, ["history", str(store), "--quantity", "phi_deg"])
    assert res.exit_code == 1 and "damaged" in res.stderr, res.output
    assert "\x1b" not in res.output and "Traceback" not in res.output
    assert store.read_bytes() == before


def test_store_failing_at_commit_puts_the_earlier_folder_back(tmp_path, monkeypatch):
    """The run is recorded once its folder is in place; a store failing then puts the earlier run's folder back."""
    store = _good_store(tmp_path)
    first = sorted(p.name for p in (tmp_path / "first").iterdir())
    csv_before = (
        (tmp_path / "first" / "shear_results.csv").read_bytes()
        if (tmp_path / "first" / "shear_results.csv").exists()
        else None
    )

    def fail(self, result, out_dir=None):
        raise InputError(lab_store.Problem(str(self.path), None, None, "disk full while recording"))

    monkeypatch.setattr(lab_store.Recorder, "record", fail)
    res = _run(tmp_path, store, out="first", extra=("--gamma-w", "9.8"))
    assert res.exit_code == 1 and "disk full while recording" in res.stderr
    assert sorted(p.name for p in (tmp_path / "first").iterdir()) == first
    if csv_before is not None:
        assert (tmp_path / "first" / "shear_results.csv").read_bytes() == csv_before
    assert not [p for p in tmp_path.iterdir() if ".capred-" in p.name]  # no work folder left
    monkeypatch.undo()
    assert len(capred.history(store)["run"].unique()) == 1  # nothing recorded for the failed run


def test_control_characters_from_the_store_never_reach_a_figure_raw(tmp_path):
    """Another program wrote U+202E and ESC into the store's material and unit: the SVG is well-formed XML and
    the terminal gets no raw ESC (the text is neutralised before matplotlib sees it)."""
    import xml.etree.ElementTree as ET

    store = _good_store(tmp_path)
    res = _run(tmp_path, store, out="second", extra=("--gamma-w", "9.8"))
    assert res.exit_code == 0, res.output
    con = sqlite3.connect(store)
    con.execute("UPDATE records SET unit = 'deg\u202e>gap', material = 'sand\u202e\x1b[2J' WHERE quantity = 'phi_deg'")
    con.commit()
    con.close()
    out = tmp_path / "h"
    res = runner.invoke(
        app, ["history", str(store), "--quantity", "phi_deg", "--format", "svg", "--out", str(out), "--reference",
              "35", "--spread", "1"],
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    assert "\x1b" not in res.output and "\u202e" not in res.output
    svgs = list(out.rglob("*.svg"))
    assert svgs
    for svg in svgs:
        text = svg.read_text(encoding="utf-8")
        ET.fromstring(text)  # well-formed
        assert "\u202e" not in text and "\x1b" not in text
        assert "U+202E" in text  # shown, not dropped


def test_truncated_store_is_refused_by_its_header(tmp_path):
    """A store cut short (a copy interrupted): its header's page count x page size exceeds the file's bytes."""
    store = _good_store(tmp_path)
    con = sqlite3.connect(store)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    for side in ("-wal", "-shm"):
        if os.path.exists(f"{store}{side}"):
            os.remove(f"{store}{side}")
    data = store.read_bytes()
    page = int.from_bytes(data[16:18], "big")
    assert int.from_bytes(data[28:32], "big") * page == len(data)  # the header counts the file's pages
    store.write_bytes(data[: len(data) - page])
    res = _run(tmp_path, store)
    assert res.exit_code == 1 and "truncated" in res.stderr and "Traceback" not in res.output, res.output
    assert not (tmp_path / "o").exists()


def test_a_write_ahead_log_that_vanishes_while_the_store_is_examined(tmp_path, monkeypatch):
    """Another writer's last connection deletes lab.sqlite-wal when it closes, at any moment: a log seen to exist
    and gone when its size is read is a log without frames (in a season batch of two workers, each asking whether
    its run is already recorded, this once crashed a run with FileNotFoundError)."""
    from pathlib import Path

    store = _good_store(tmp_path)
    wal = f"{store}-wal"
    real_exists, real_stat = Path.exists, Path.stat

    def exists(self, *a, **k):
        return True if str(self) == wal else real_exists(self, *a, **k)

    def stat(self, *a, **k):
        if str(self) == wal:
            raise FileNotFoundError(2, "No such file or directory", wal)
        return real_stat(self, *a, **k)

    monkeypatch.setattr(Path, "exists", exists)
    monkeypatch.setattr(Path, "stat", stat)
    assert lab_store._inspect(store) is not None
