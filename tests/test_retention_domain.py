"""Retention models in their natural domain (issue 30, item 4; issue 28, item 7): on every public data set and both
branches of the bundled sample, each model's fit reaches the optimum of a 200-start global search over its own
domain, read from tests/data/retention/reference_optima.csv (computed once by make_reference_optima.py in the
same folder: scipy's least_squares on all parameters from 200 random starts in the model's bounds, seed 0)."""

import csv
import sys

import numpy as np
import pytest
from conftest import RETENTION_DATA

from capred.fitting.retention_models import MODELS, fit_model

sys.path.insert(0, str(RETENTION_DATA))
import make_reference_optima as ref  # noqa: E402

#: capred's SSE may exceed the global search's by at most 0.1 % (the issue's tolerance)
REL = 1e-3
#: ... or by less than n (1e-5)²: the data are printed to 1e-4 (m³/m³ or -), and two fits whose RMS differs by a
#: tenth of that cannot be told apart (the noise-free RETC set fits to RSS ~4e-10, where 0.1 % is 4e-13)
FLOOR = 1e-5

DATA = {name: (s, y) for name, s, y in ref.datasets()}
with open(RETENTION_DATA / "reference_optima.csv", encoding="utf-8") as f:
    REFERENCE = {(r["data"], r["model"]): float(r["rss"]) for r in csv.DictReader(f)}


def test_the_reference_covers_every_data_set_and_model():
    assert set(REFERENCE) == {(d, m) for d in DATA for m in MODELS}


@pytest.mark.parametrize("data,model", sorted(REFERENCE))
def test_sse_within_a_tenth_of_a_percent_of_the_global_search(data, model):
    s, y = DATA[data]
    f = fit_model(model, s, y)
    assert f.rss <= REFERENCE[data, model] * (1 + REL) + s.size * FLOOR**2, (f.rss, REFERENCE[data, model])


def test_fredlund_xing_reaches_n_below_one():
    """Fredlund & Xing (1994) require n > 0 only: on Beit Netofa clay (van Genuchten 1980) the optimum of the
    form without C(s) has n ≈ 0.36, which the former bound n ≥ 1.005 excluded."""
    s, y = DATA["swrc_vg1980_beit_netofa_clay"]
    f = fit_model("fx_no_c", s, y)
    assert 0.1 < f.params_si["n"] < 1 and "n" not in f.at_bounds()
    assert f.rss <= REFERENCE["swrc_vg1980_beit_netofa_clay", "fx_no_c"] * (1 + REL)
    old = fit_model("fx_no_c", s, y, fixed={"n": 1.005})  # the old domain's edge, where its optimum lay
    assert old.rss > 1.01 * f.rss
    assert np.isfinite(f.stderr_si["n"])
