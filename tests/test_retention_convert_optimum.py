"""`retention-convert` reaches the optimum (issue 41, item 5): on each pair of
tests/data/retention/reference_conversions.csv the conversion's objective (the mean over ln s of the squared
difference between the two curves, conversion_objective) is within 0.1 % of an independent 30-start search's
(computed once by make_reference_conversions.py in that folder). Before the fix, kosugi -> vg_m_free on Beit Netofa
clay ended 0.8 % above it."""

import csv
import sys

import pytest
from conftest import RETENTION_DATA

from capred.pipelines.retention_convert import conversion_objective, convert_fit

sys.path.insert(0, str(RETENTION_DATA))
import make_reference_conversions as ref  # noqa: E402

#: the objective may exceed the reference by 0.1 % (the tolerance of tests/test_retention_domain.py) ...
REL = 1e-3
#: ... or by less than (3e-8)²: a conversion fits an exact curve, not rounded data, so the floor is the
#: optimisers' resolution (both stop at relative changes of 1e-14 of objectives of 1e-9 and more), far below the
#: 0.8 % of 3.6e-9 that the fix removed on Beit Netofa clay
FLOOR = 3e-8

with open(RETENTION_DATA / "reference_conversions.csv", encoding="utf-8") as f:
    REFERENCE = {(r["data"], r["source"], r["target"]): float(r["objective"]) for r in csv.DictReader(f)}


def test_the_reference_covers_the_cases():
    assert set(REFERENCE) == set(ref.CASES)


@pytest.mark.parametrize("data,source,target", sorted(REFERENCE))
def test_conversion_reaches_the_reference_optimum(data, source, target):
    src = ref.source(data, source)
    new, _ = convert_fit(src, target)
    j = conversion_objective(src, target, new.params_si)
    assert j <= REFERENCE[data, source, target] * (1 + REL) + FLOOR**2, (j, REFERENCE[data, source, target])
