"""The README command's floor (benchmarks/bench_one_path.py, issue 31) draws the same sheets the command writes.

The floor is what any such run must pay: the same two report sheets drawn and saved with plain matplotlib. If
the command came to write other sheets, or the floor stopped drawing some, the benchmark's ratio would compare
different work; this test fails then.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

pytestmark = pytest.mark.slow


def test_the_floor_draws_the_sheets_the_readme_command_writes(tmp_path):
    import bench_one_path as bench
    from PIL import Image

    pickled = tmp_path / "result.pickle"
    bench.write_sample_result(pickled)
    floor = tmp_path / "floor"
    floor.mkdir()
    script = bench.FLOOR_SHEETS.format(pickle=pickled, out=floor)
    subprocess.run([sys.executable, "-c", script], check=True, cwd=tmp_path, capture_output=True)
    run = tmp_path / "run"
    subprocess.run(
        [sys.executable, "-m", "capred", "shear", "--sample", "--out", str(run)],
        check=True,
        cwd=tmp_path,
        capture_output=True,
    )
    written = sorted(p.name for p in run.glob("*.png"))
    assert written == ["report_sand_208-417um.png", "report_steel_2mm.png"]
    assert sorted(p.name for p in floor.glob("*.png")) == written
    for name in written:  # the same page width at 300 dpi (180 mm: 2126 px), so the same pixels to fill
        w_floor, _ = Image.open(floor / name).size
        w_run, _ = Image.open(run / name).size
        assert abs(w_floor - w_run) <= 1
