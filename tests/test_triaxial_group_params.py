"""Triaxial groups as fits (issue 28, item 2): ``group.params[NAME]`` and ``group.summary()`` as shear's envelopes.

NAME is exactly the JSON key of the group (``sigma1_cap_kPa``, ``C_kPa``, ``phi_apparent_deg`` ...), values in
the JSON's units; the 95 % intervals hold their level in simulation.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.stats import t as student

import capred
import capred.physics.triaxial as tx
from capred.parameters import Parameters
from capred.pipelines.triaxial import _tensor_fields
from capred.pipelines.triaxial_records import GroupRecord

KPA = 1e3


@pytest.fixture(scope="module")
def groups():
    r = capred.run_triaxial_bounds(capred.sample_path("triaxial-groups"))
    doc = json.loads(json.dumps(r.to_json()))
    return {g.group: g for g in r.groups}, {g["group"]: g for g in doc["groups"]}


def test_params_equal_the_json(groups):
    """Every parameter's value, SE and interval are the JSON's numbers under the same name (tolerance 0: the
    same floats)."""
    recs, js = groups
    for name, g in recs.items():
        for p in g.params.values():
            assert p.value == js[name][p.name], (name, p.name)
            base, unit = p.name.rsplit("_", 1)
            se_key = f"{base}_se_{unit}"
            if se_key in js[name] and js[name][se_key] is not None:
                assert p.stderr == js[name][se_key]
            ci_key = f"{base}_ci95_{unit}"
            if ci_key in js[name]:
                assert list(p.ci95) == js[name][ci_key]


def test_sample_tensors_by_name(groups):
    """The sample's known tensors (its header: group A (-10, -40, -40) kPa, group T (-10, -25, -40) kPa, to 12
    decimals in the file: 1e-9 kPa), through the names a user types."""
    recs, _ = groups
    a, t = recs["A"].params, recs["T"].params
    assert isinstance(a, Parameters)
    assert [a[k].value for k in ("sigma1_cap_kPa", "sigma2_cap_kPa", "sigma3_cap_kPa")] == pytest.approx(
        [-10, -40, -40], abs=1e-9
    )
    assert [t[k].value for k in ("sigma1_cap_kPa", "sigma2_cap_kPa", "sigma3_cap_kPa")] == pytest.approx(
        [-10, -25, -40], abs=1e-9
    )
    assert a["sigma1_cap_kPa"].unit == "kPa" and a["phi_apparent_deg"].unit == "deg"
    # the apparent angle of the sample's unsaturated circles is phi' = 31.523 deg (its header)
    assert a["phi_apparent_deg"].value == pytest.approx(31.523, abs=1e-9)
    assert "Ci_kPa" in t and "phi_i_deg" in t and "Ci_kPa" not in a  # eq. 50 only
    # a group without pairs: no tensor, its apparent cohesion without SE
    e = recs["E"].params
    assert "sigma1_cap_kPa" not in e and np.isnan(e["C_kPa"].stderr)


def test_summary(groups):
    recs, _ = groups
    text = recs["A"].summary()
    assert text.startswith("[[Capillary tensor of group A, eq. 48")
    assert "sigma1_cap_kPa" in text and "C_fictive_kPa" in text and "dof            = 2" in text
    e = recs["E"].summary()
    assert "tensor not determined" in e and "column 'pair'" in e


def _noisy_group(rng, sd_kpa, n=5):
    """A compression group of ``n`` tests sharing (-10, -40, -40) kPa on c' = 2.795 kPa, phi' = 31.523 deg, its
    sigma1 measured with a normal error of sd ``sd_kpa``."""
    c, phi = 2.795e3, 31.523
    kp = (1 + np.sin(np.radians(phi))) / (1 - np.sin(np.radians(phi)))
    s3_eff = np.linspace(50e3, 250e3, n)
    s1_eff = kp * s3_eff + 2 * c * np.sqrt(kp)
    cap1, cap3 = -10e3, -40e3
    s1, s3 = s1_eff + cap1, s3_eff + cap3
    s1 = s1 + rng.normal(0, sd_kpa * KPA, n)
    gt = tx.axisymmetric_group_tensor(s1, s3, s1_eff, s3_eff, c, phi)
    return GroupRecord(group="sim", n=n, phi_apparent=float(gt.phi_apparent_deg), **_tensor_fields(gt)), (
        cap1 / KPA,
        cap3 / KPA,
        phi,
    )


@pytest.mark.slow  # a coverage simulation of 2,000 groups (~9 s): the slow set; test_interval_by_hand stays everyday
def test_interval_coverage():
    """2,000 seeded groups of 5 tests: the 95 % intervals of sigma1_cap, sigma3_cap and C cover the truth 95 % of
    the time (t intervals of means of per-test values, normal errors: exact). Binomial sd of a rate over 2,000
    draws is 0.0049; the tolerance 0.02 is 4 sd. phi_apparent's delta-method interval (slope of a free line
    through 5 points) is checked to 0.03."""
    rng = np.random.default_rng(2028)
    hits = {"sigma1_cap_kPa": 0, "sigma3_cap_kPa": 0, "C_kPa": 0, "phi_apparent_deg": 0}
    c_true = None
    N = 2000
    for _ in range(N):
        g, (cap1, cap3, phi) = _noisy_group(rng, sd_kpa=4.0)
        if c_true is None:  # C of the noiseless group: the mean per-test cohesion of the unsaturated circles
            g0, _ = _noisy_group(np.random.default_rng(0), sd_kpa=0.0)
            c_true = g0.params["C_kPa"].value
        p = g.params
        truth = {"sigma1_cap_kPa": cap1, "sigma3_cap_kPa": cap3, "C_kPa": c_true, "phi_apparent_deg": phi}
        for k in hits:
            lo, hi = p[k].ci95
            hits[k] += lo <= truth[k] <= hi
    for k, h in hits.items():
        tol = 0.03 if k == "phi_apparent_deg" else 0.02
        assert abs(h / N - 0.95) < tol, (k, h / N)


def test_interval_by_hand():
    """C's interval is C ± t(0.975, n − 1) SE: t(0.975, 4) = 2.776445 (tables)."""
    g, _ = _noisy_group(np.random.default_rng(7), sd_kpa=4.0)
    p = g.params["C_kPa"]
    assert student.ppf(0.975, 4) == pytest.approx(2.776445, abs=1e-6)
    assert p.ci95[1] - p.value == pytest.approx(2.776445 * p.stderr, rel=1e-6)
