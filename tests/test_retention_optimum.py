"""Retention fits reach the global optimum (issue 23, item 4): capred against an independent multi-start fit.

The reference (`multistart`) shares nothing with capred's search: scipy's least_squares on *all* parameters
(no variable projection, natural coordinates, x_scale='jac') from random starts drawn inside capred's own
bounds (log-uniform on log-scaled parameters); the lowest end point wins. capred passes when its RSS is
not above the reference's by more than 1e-6 relative (the reference itself converges only to ~1e-9
relative, and an RSS 1e-6 above the optimum moves no parameter by more than ~0.1 % of its standard error).
The reference may stop higher than capred (a random search has no guarantee); that is allowed.
"""

import numpy as np
import pandas as pd
import pytest
from conftest import RETENTION_DATA
from numpy.testing import assert_allclose
from scipy.optimize import least_squares

from capred.fitting.retention_models import MODELS, RetentionFit, bounds_for, fit_model
from capred.physics import retention as rp
from capred.references import REFERENCES

CM = 98.1  # Pa per cm of water (gamma_w = 9.81 kN/m^3)
ROOT = RETENTION_DATA.parents[2]
REL = 1e-6  # see the module docstring


def multistart(name, s, y, n_starts=30, seed=0):
    """Independent reference: lowest RSS of least_squares on all parameters from random starts in the bounds."""
    model = MODELS[name]
    names = model.names
    b = bounds_for(s, y, name)
    lo = np.array([b[k][0] for k in names])
    hi = np.array([b[k][1] for k in names])
    logp = model.log_params
    rng = np.random.default_rng(seed)

    def resid(v):
        r = model.water(s, **dict(zip(names, v))) - y
        return np.where(np.isfinite(r), r, 1e3)

    best = np.inf
    for _ in range(n_starts):
        x0 = [
            o + np.exp(rng.uniform(np.log(a - o), np.log(c - o)))
            if (o := logp.get(k)) is not None
            else rng.uniform(a, c)
            for k, a, c in zip(names, lo, hi)
        ]
        x0 = np.clip(x0, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo))
        r = least_squares(resid, x0, bounds=(lo, hi), x_scale="jac", ftol=1e-13, xtol=1e-13, gtol=1e-13, max_nfev=3000)
        best = min(best, 2 * r.cost)
    return best


def _public(name):
    d = pd.read_csv(RETENTION_DATA / f"{name}.csv")
    return d.iloc[:, 0].to_numpy(float) * CM, d.iloc[:, 1].to_numpy(float)


def _sample(branch):
    d = pd.read_csv(ROOT / "sample_data" / "retention.csv", comment="#")
    d = d[d["branch"] == branch]
    return d["z1 [cm]"].to_numpy(float) * CM, ((d["V_v [cm^3]"] - d["z2 [cm^3]"]) / d["V_v [cm^3]"]).to_numpy(float)


def _sand(seed):
    """A hanging-column sand: 14 heads in 2-60 cm, a steep van Genuchten curve (n = 6) plus noise 0.02."""
    rng = np.random.default_rng(seed)
    s = np.sort(rng.uniform(2, 60, 14)) * CM
    return s, np.clip(rp.vg_water(s, 0.05, 0.95, 1 / (12 * CM), 6.0) + rng.normal(0, 0.02, s.size), 0, 1)


PUBLIC = sorted(p.stem for p in RETENTION_DATA.glob("swrc_*.csv"))


def _check(name, s, y, n_starts=30):
    f = fit_model(name, s, y)
    ref = multistart(name, s, y, n_starts)
    assert f.rss <= ref * (1 + REL), (name, f.rss, ref)
    return f, ref


# cases where the previous starts stopped above the optimum (measured with the previous code, see the note)
HARD = [
    # Brooks-Corey: the old 40 x 40 grid + one local fit stayed in the wrong interval between data suctions
    ("bc", 13, 0.0056306),  # old: h_b 8.95 cm, RSS 0.0058624 (+4.1 %); optimum h_b 6.70 cm
    ("bc", 53, 0.0030570),  # old: h_b 14.1 cm, RSS 0.0042641 (+39 %); optimum h_b 7.90 cm
    # Durner: the old starts ended with the second pore system outside the data (a unimodal fit)
    pytest.param("durner", 25, 0.00076692, marks=pytest.mark.slow),  # old RSS 0.0023107 (+201 %)
]


@pytest.mark.parametrize("name,seed,rss", HARD)
def test_optimum_hard_synthetic_cases(name, seed, rss):
    s, y = _sand(seed)
    f, ref = _check(name, s, y)
    assert_allclose(f.rss, rss, rtol=1e-4)  # the optimum found when the case was built (5 printed digits)


@pytest.mark.parametrize(
    "data,name",
    [
        ("swrc_vg1980_touchet_silt_loam_ge3", "bc"),  # optimum s_e in the interval left of the grid's best point
        pytest.param("swrc_vg1980_hygiene_sandstone", "durner", marks=pytest.mark.slow),  # two systems, one alpha
        pytest.param("swrc_vg1980_silt_loam_ge3", "fx", marks=pytest.mark.slow),  # s_r inside the data range
        ("swrc_toyoura_sand_swrcfit", "fx_no_c"),  # flat (m, n, theta_r) ridge
        pytest.param("swrc_toyoura_sand_swrcfit", "vg_m_free", marks=pytest.mark.slow),
    ],
)
def test_optimum_public_sets_hard(data, name):
    _check(name, *_public(data))


@pytest.mark.parametrize(
    "name", [m if m in ("vg", "bc", "kosugi") else pytest.param(m, marks=pytest.mark.slow) for m in MODELS]
)
@pytest.mark.parametrize("branch", ["drying", "wetting"])
def test_optimum_bundled_sample(branch, name):
    _check(name, *_sample(branch), n_starts=20)


# every public set and model against a 200-start global search: tests/test_retention_domain.py, which reads the
# reference optima from tests/data/retention/reference_optima.csv instead of searching on every run (issue 28.7)


def test_brooks_corey_air_entry_is_interior():
    """Seed 13: the optimum h_b lies strictly between two data suctions (a smooth interior minimum)."""
    s, y = _sand(13)
    f = fit_model("bc", s, y)
    knots = np.unique(s)
    i = np.searchsorted(knots, f.params_si["s_e"])
    assert knots[i - 1] < f.params_si["s_e"] < knots[i]
    assert_allclose(f.params_si["s_e"] / CM, 6.697, rtol=1e-3)  # 4 printed digits


def test_bound_warning_in_the_parameters_own_scale():
    """Kosugi's s_m = 7.9 kPa in 1e-4 ... 1.5e7 kPa is interior on a log scale (the linear test flagged it)."""
    f = RetentionFit(
        params={"y_r": 0.1, "y_s": 0.4, "s_m": 7947.0, "sigma": 0.5},
        stderr={},
        fixed=(),
        n=20,
        rss=1.0,
        r2=0.9,
        aic=0.0,
        bic=0.0,
        converged=True,
        free=("y_r", "y_s", "s_m", "sigma"),
        bounds={"y_r": (0.0, 0.4), "y_s": (0.1, 1.0), "s_m": (0.1, 1.5e10), "sigma": (1e-3, 10.0)},
        log_params=MODELS["kosugi"].log_params,
        model="kosugi",
    )
    assert f.at_bounds() == []
    f.params_si["s_m"] = 0.1 * (1 + 1e-9)  # on its bound to 1e-9 of the log range
    f.params_si["y_r"] = 0.0
    assert f.at_bounds() == ["y_r", "s_m"]


def test_residual_at_its_bound_keeps_the_other_standard_errors():
    """theta_r at 0: the other SEs are those of the fit with theta_r fixed at 0, and a note says so."""
    s = np.geomspace(1e3, 1e5, 20)
    rng = np.random.default_rng(3)
    y = rp.vg_water(s, 0.0, 0.40, 1 / 5000, 2.0) - 0.02 * (s / 1e5) + rng.normal(0, 0.003, s.size)
    f = fit_model("vg", s, y)
    assert f.params_si["y_r"] == 0.0 and f.held == ("y_r",) and f.stderr_si["y_r"] is None
    assert any("y_r ended on its lower bound" in n for n in f.notes)
    g = fit_model("vg", s, y, fixed={"y_r": 0.0})
    for k in ("y_s", "alpha", "n"):
        assert np.isfinite(f.stderr_si[k]) and f.stderr_si[k] > 0
        # the same Jacobian columns and dof: equal to the precision of the central differences
        assert_allclose(f.stderr_si[k], g.stderr_si[k], rtol=1e-5)
    assert f.t == pytest.approx(g.t)


@pytest.mark.parametrize(
    "name,truth",
    [
        ("vg", dict(y_r=0.05, y_s=0.40, alpha=1 / 4000, n=2.5)),
        ("vg_m_free", dict(y_r=0.02, y_s=0.45, alpha=1 / 2000, n=2.5, m=0.4)),
        ("bc", dict(y_r=0.05, y_s=0.40, s_e=3000.0, lam=1.2)),
        ("kosugi", dict(y_r=0.03, y_s=0.38, s_m=4000.0, sigma=0.8)),
        ("fx", dict(y_s=0.40, a=2000.0, n=3.0, m=1.2, s_r=5e5)),
        ("fx_no_c", dict(y_r=0.03, y_s=0.40, a=2000.0, n=3.0, m=1.2)),
        ("durner", dict(y_r=0.05, y_s=0.42, w1=0.6, alpha1=1 / 300, n1=6.0, alpha2=1 / 30000, n2=1.6)),
    ],
)
def test_fitted_curve_is_callable_and_invertible(name, truth):
    s = np.geomspace(100, 1e6, 30)
    f = fit_model(name, s, MODELS[name].water(s, **truth))
    grid = np.geomspace(300, 3e5, 7)
    grid = grid[MODELS[name].effective_saturation(grid, truth) < 1 - 1e-9]  # Brooks-Corey: S_e = 1 below s_e
    assert_allclose(f(grid), MODELS[name].water(grid, **f.params_si), rtol=1e-15)  # the same function
    # noise-free data: the fitted curve is the true one (the fit converges to ~1e-7 relative)
    assert_allclose(f.water(grid), MODELS[name].water(grid, **truth), rtol=1e-6)
    # inverse: closed form (vg, kosugi, bc) or bisection on ln s to 2^-64 of the bracket
    assert_allclose(f.suction(f.water(grid)), grid, rtol=1e-7)
    assert np.isnan(f.suction(np.array([f.params_si["y_s"] + 0.01]))[0])  # wetter than saturated: no suction


def test_brooks_corey_inverse_at_saturation_is_the_air_entry():
    f = fit_model("bc", *(lambda s: (s, rp.bc_water(s, 0.1, 0.9, 5000.0, 0.8)))(np.geomspace(500, 2e5, 30)))
    assert_allclose(f.suction(np.array([0.9])), [5000.0], rtol=1e-6)  # S_e = 1 at s = s_e (fitted to 1e-6)


def test_registry_entries_are_complete():
    for name, m in MODELS.items():
        assert m.name == name and m.label and "=" in m.equation and m.help.startswith(f"{name}:")
        assert "$" not in m.equation  # plain text: the legend needs no mathtext parser
        assert all(k in REFERENCES for k in m.references) and m.reference == m.references[0]
        assert "=" in m.method and m.style.get("ls") is not None
        for p in m.parameters:
            assert p.unit in ("Pa", "1/Pa", "-", "y") and p.description and p.range_text
            # the natural domain with its paper (issue 30, item 4): one of the entry's references, or van Genuchten's
            cited = [REFERENCES[k].authors.split(" ")[0] for k in m.references] + ["van Genuchten"]
            assert p.domain and any(a in p.domain for a in cited), (name, p.name)
            assert p.symbol.startswith("$")
        assert m.names == tuple(p.name for p in m.parameters)
