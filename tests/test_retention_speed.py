"""capred retention's whole-process cost (issue 31.5): what a run does not load, and that the shortcuts change
no number and no byte. Not timed: the benchmark is benchmarks/bench_retention.py --process."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import capred
from capred.fitting.linear import t_quantile
from capred.fitting.nonlinear import LARGE_DOF, t_quantile_large_dof
from capred.io.writers import write_csv_file
from capred.pipelines.retention import RetentionOptions, run_retention
from capred.result import with_csv_headers

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("p", [0.975, 0.995, 0.025])
def test_t_quantile_series_matches_scipy_above_the_closed_form(p):
    """Abramowitz & Stegun (1964) eq. 26.7.5 with four terms: the first term left out is O(ν^-5), about 1e-12 of
    t at ν = 201 and p = 0.975 (and smaller beyond); scipy's stdtrit is good to ~2e-16."""
    from scipy.special import stdtrit

    for nu in (LARGE_DOF + 1, 250, 1_000, 10_000, 1_000_000):
        assert t_quantile_large_dof(p, nu) == pytest.approx(float(stdtrit(nu, p)), rel=1e-11)


def test_t_quantile_series_meets_the_closed_form_at_the_switch():
    """At ν = 200 capred's closed form (A&S 26.7.3-4, exact to ~1e-15) and the series differ by the series'
    truncation only: the 95 % quantile does not jump where the fit switches from one to the other."""
    closed = t_quantile(0.975, LARGE_DOF)
    assert t_quantile_large_dof(0.975, LARGE_DOF) == pytest.approx(closed, rel=2e-12)
    assert 1.9599639 < t_quantile_large_dof(0.975, 1e12) < 1.9599640  # the normal quantile 1.95996398 in the limit


def _lab_rows(path: Path, n: int) -> None:
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from common import lab_retention_rows
    finally:
        sys.path.pop(0)
    lab_retention_rows(path, n)


def test_a_large_run_loads_neither_scipy_nor_pandas(tmp_path):
    """The CLI on 2,000 readings with tables and JSON: scipy (its t quantile) and pandas (its DataFrames) are
    not imported, ~0.6 s of CPU of a run that fits in ~0.3 s."""
    data = tmp_path / "r.csv"
    _lab_rows(data, 2_000)
    code = (
        "import sys, runpy\n"
        f"sys.argv = ['capred', 'retention', {str(data)!r}, '--out', {str(tmp_path / 'out')!r}, '--no-plots', "
        "'--no-html']\n"
        "try:\n    runpy.run_module('capred', run_name='__main__')\nexcept SystemExit as e:\n    assert not e.code, e\n"
        "print('LOADED', sorted(m for m in ('scipy', 'pandas') if m in sys.modules))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}  # matplotlib keeps its font cache (HOME)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "LOADED []" in out.stdout
    assert (tmp_path / "out" / "points.csv").stat().st_size > 0


@pytest.mark.parametrize(
    "options",
    [RetentionOptions(), RetentionOptions(models="all", hysteresis="kool-parker", fixed={"S_res": 0.0})],
    ids=["default", "all_models_hysteresis_fixed"],
)
def test_csv_tables_write_the_bytes_of_the_dataframes(options):
    """csv_tables (no pandas) and tables() (DataFrames) give the same bytes in both CSV dialects, table by table."""
    r = run_retention(capred.sample_path("retention"), options)
    fast, frames = r.csv_tables(), r.tables()
    assert list(fast) == list(frames) == ["fits", "parameters", "points"]
    for stem, frame in frames.items():
        for dialect in ("standard", "excel-eu"):
            a, b = io.BytesIO(), io.BytesIO()
            write_csv_file(a, fast[stem], dialect)
            write_csv_file(b, with_csv_headers(frame), dialect)
            assert a.getvalue() == b.getvalue(), (stem, dialect)
    assert np.asarray(fast["points"]["suction [kPa]"]).size == r.suction.size


def test_the_default_figure_builds_no_mathtext_parser(tmp_path, monkeypatch):
    """The retention sheet's texts are plain (legend equations in Unicode, axis labels, tick labels as numbers):
    matplotlib's mathtext parser, ~0.1 s of CPU to build and 10-50 ms per label, is never made. Counted by
    wrapping its constructor in this process, which has not drawn mathtext yet (a fresh process)."""
    code = (
        "import sys\n"
        "import matplotlib._mathtext as mt\n"
        "built = []\n"
        "init = mt.Parser.__init__\n"
        "mt.Parser.__init__ = lambda self, *a, **k: (built.append(1), init(self, *a, **k))[1]\n"
        "import capred\n"
        f"r = capred.run_retention(capred.sample_path('retention'), capred.RetentionOptions(models='all'))\n"
        f"capred.write_outputs(r, {str(tmp_path / 'out')!r})\n"
        "print('PARSERS', len(built))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}  # matplotlib keeps its font cache (HOME)
    out = subprocess.run(
        [sys.executable, "-W", "ignore", "-c", code], capture_output=True, text=True, env=env, timeout=300
    )
    assert out.returncode == 0, out.stderr
    assert "PARSERS 0" in out.stdout
    assert (tmp_path / "out" / "retention.png").stat().st_size > 10_000
