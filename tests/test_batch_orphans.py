"""Nothing left behind (issue 32.5): a batch's worker processes die with it, also after `kill -9`, and a
symlinked --out leaves no hidden work folder or link."""

import os
import shutil
import signal
import subprocess
import sys
import time

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app


def _children(pid: int) -> set[int]:
    out: set[int] = set()
    try:
        for tid in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{tid}/children") as fh:
                out |= {int(x) for x in fh.read().split()}
    except OSError:
        pass
    return out


def _alive(pid: int) -> bool:
    """True while ``pid`` runs (a zombie, dead and waiting for its reaper, is not alive)."""
    try:
        with open(f"/proc/{pid}/status") as fh:
            state = next(line for line in fh if line.startswith("State:"))
    except (OSError, StopIteration):
        return False
    return "Z" not in state.split()[1]


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_workers_die_within_5_s_of_kill_9_of_the_batch(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(8):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    from conftest import ROOT

    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    cmd = [sys.executable, "-m", "capred", "shear", str(runs / "*.csv"), "--workers", "2", "--no-plots"]
    cmd += ["--bootstrap", "40000", "--out", str(tmp_path / "out")]  # long jobs: the workers are busy when killed
    parent = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers: set[int] = set()
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and len(workers) < 2 and parent.poll() is None:
            workers = {c for c in _children(parent.pid) if _alive(c)}
            time.sleep(0.05)
        assert len(workers) >= 2, "the batch never started its workers"
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait()
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.05)
        orphans = [w for w in workers if _alive(w)]
        assert not orphans, f"workers still running 5 s after kill -9 of their batch: {orphans}"
    finally:
        if parent.poll() is None:
            parent.kill()
        for w in workers:  # the orphans a failing run leaves: ended here, by their ids
            if _alive(w):
                os.kill(w, signal.SIGKILL)


def test_a_worker_whose_parent_is_gone_ends(monkeypatch):
    """die_with_parent in a process whose parent is not the one named ends it at once (the parent died before
    the death signal was armed)."""
    from capred import batch

    code = "import os, capred.batch as b; b.die_with_parent(os.getppid() + 1); print('alive')"
    res = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    assert res.returncode == 1 and "alive" not in res.stdout
    assert batch.PR_SET_PDEATHSIG == 1  # linux/prctl.h


def test_a_symlinked_out_leaves_nothing_but_the_run(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / "link").symlink_to(real)
    args = ["shear", "--sample", "--no-plots", "--bootstrap", "0", "--out", str(tmp_path / "link")]
    for _ in range(2):  # a first run, then a run that replaces it
        res = CliRunner().invoke(app, args)
        assert res.exit_code == 0, res.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "real"]  # no hidden .capred-tmp-* left
    assert (tmp_path / "link").is_symlink() and os.readlink(tmp_path / "link") == str(real)
    assert "results.csv" in {p.name for p in real.iterdir()}
    assert not [p for p in real.iterdir() if p.name.startswith(".")]
