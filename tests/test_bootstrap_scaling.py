"""The bootstrap's cost does not depend on how many distinct normal stresses the dry tests have (issue 31.1).

Labs that weigh to 0.01 g, or pool a season's tests, give every dry test its own normal stress. The dry
resampling used to check each resample's refittability through a dense (dry tests x distinct stresses)
indicator matrix: memory and time quadratic in the dry tests. It now checks the group codes of the drawn
tests (min != max per resample). These tests count memory (tracemalloc), not time, so a loaded machine
cannot fail them.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from capred.fitting.linear import fit_line
from capred.physics import effective_stress_models as esm
from capred.pipelines import shear_analysis as sa
from capred.pipelines.shear import ModelParams

C, TAN_PHI = 300.0, 0.7  # Pa, -
N_DRY = 4000  # dry tests: 2,000 distinct stresses means every stress tested twice
MODELS = ["no_suction", "bishop", "own1"]


def _material(distinct: int, seed: int = 0, n_dry: int = N_DRY):
    """``n_dry`` dry tests at ``distinct`` normal stresses spread over 1-3 kPa, and 10 wet tests."""
    rng = np.random.default_rng(seed)
    levels = np.linspace(1e3, 3e3, distinct)
    dry_x = levels[np.arange(n_dry) % distinct]
    dry_y = C + TAN_PHI * dry_x + rng.normal(0, 10.0, n_dry)
    fit = fit_line(dry_x, dry_y)
    sigma = np.array([1, 2, 3, 1, 2, 3, 1, 2, 3, 2.0]) * 1e3
    S_R = np.linspace(0.05, 0.9, 10)
    suction = np.linspace(4e3, 0.6e3, 10)
    tau = C + TAN_PHI * (sigma + S_R * suction) + rng.normal(0, 10.0, 10)
    d = esm.ModelInputs(
        sigma,
        suction,
        S_R,
        np.full(10, 1e-3),
        tau,
        np.ones(10, bool),
        np.array(["m"] * 10, dtype=object),
        np.full(10, fit.intercept),
        np.full(10, fit.slope),
        0.0728,
        ModelParams(),
    )
    return d, dry_x, dry_y


def _peak(distinct: int) -> int:
    """Peak bytes traced while bootstrapping (100 replicates) a material with ``distinct`` dry stresses."""
    d, dry_x, dry_y = _material(distinct)
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        out = sa.bootstrap_ranking(d, dry_x, dry_y, MODELS, ModelParams(), {}, ["own1", "bishop"], 100, 1, False)
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        tracemalloc.stop()
    assert out.replicates == 100
    return peak


def test_bootstrap_working_set_does_not_grow_with_distinct_dry_stresses():
    """6 -> 2,000 distinct stresses at the same 4,000 dry tests: the working set stays within 1.5x (the
    issue's bound). The dense indicator this replaces was 4,000 x 2,000 floats (64 MB) against a block of
    counts of 2 MB: ~30x; the group codes add 32 KB whatever the number of stresses."""
    few, many = _peak(6), _peak(2000)
    assert many <= 1.5 * few, (few, many)


@pytest.mark.parametrize("through_origin", [False, True])
def test_group_codes_decide_refittability_as_the_counts_do(through_origin):
    """A resample fits a line iff it holds two distinct stresses (through the origin: one not 0). Checked
    against the definition on the counts, with ties and zeros so that many resamples are redrawn."""
    dry_x = np.array([0.0, 0.0, 0.0, 1e3, 1e3, 2e3]) if through_origin else np.array([1e3, 1e3, 1e3, 1e3, 1e3, 2e3])
    rng = np.random.default_rng(5)
    U, _, valid = sa._draw(rng, dry_x, 4, 2000, through_origin)
    assert valid.all()  # a redraw always finds one within 100 tries here (P(fail) = (5/6)^(6*100) ~ 0)
    for u in U:
        held = dry_x[u > 0]
        assert np.any(held != 0) if through_origin else np.unique(held).size >= 2, u
        assert u.sum() == dry_x.size  # a resample is nd draws
