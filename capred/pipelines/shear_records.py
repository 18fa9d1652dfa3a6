"""Typed records of `capred shear`: one per concept, each field with its unit, meaning and output names.

Arrays run over the tests of the run (dry tests included: NaN where a value
concerns wet tests only). JSON keys and results.csv columns come from each
field's ``output`` metadata through the one mapping of capred.result
(``record_columns``, ``record_json_columns``), and so do the Python
attributes a user reads (``capred.result.user_units``): a stress is
``tau_kPa``, ``sigma_cap_kPa`` ... [kPa], as in the JSON and console. The
pipeline stores SI values; the field's own name (``tau`` [Pa]) keeps them
for one release with a DeprecationWarning, and ``rec.si.tau`` reads them
silently for code that calls capred.physics.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..result import output, user_units


@user_units
@dataclass(frozen=True, eq=False)
class ModelPrediction:
    """One effective-stress model's prediction of every test.

    Attributes
    ----------
    model : str
        Name of the model (a key of capred.physics.effective_stress_models.REGISTRY).
    sigma_eff_kPa : ndarray
        Effective normal stress σ'_N [kPa] (NaN for a model that predicts τ directly).
    tau_kPa : ndarray
        Predicted peak shear strength τ_pred [kPa] (dry tests: the dry envelope); JSON ``tau_pred_kPa``.
    residual_kPa : ndarray
        τ_pred − τ_max [kPa].
    tau_mean_ci_kPa : (ndarray, ndarray)
        Confidence band of the mean prediction at the test's state [kPa]: where the model's τ lies given the
        uncertainty of the dry envelope (and of a fitted χ law's parameters).
    tau_prediction_interval_kPa : (ndarray, ndarray)
        Prediction interval of a new test at the same state [kPa]: the mean band widened by the scatter of a
        single test (the dry fit's residual variance), so it covers new tests at the stated level.
    sigma_cap_kPa : ndarray
        Capillary stress the model ascribes to each wet test, (τ_pred − c)/tan φ − σ_N [kPa].
    sigma_eff, tau, residual, tau_mean_ci, tau_prediction_interval, sigma_cap
        The same in Pa (the fields, as the pipeline stores them): deprecated names, kept for one release with a
        DeprecationWarning; ``.si.tau`` reads them without one.
    """

    model: str
    sigma_eff: np.ndarray = output(None, "sigma_eff_{model}", "kPa", 1e-3)
    tau: np.ndarray = output("tau_pred_kPa", "tau_pred_{model}", "kPa", 1e-3)
    residual: np.ndarray = output("residual_kPa", "residual_{model}", "kPa", 1e-3)
    tau_prediction_interval: tuple = output(
        "tau_pred_pi{level}_kPa",
        ("tau_pred_{model}_low{level}", "tau_pred_{model}_high{level}"),
        "kPa",
        1e-3,
        pair=True,
    )
    tau_mean_ci: tuple = output(
        "tau_mean_ci{level}_kPa",
        ("tau_mean_{model}_low{level}", "tau_mean_{model}_high{level}"),
        "kPa",
        1e-3,
        pair=True,
    )
    sigma_cap: np.ndarray = output("sigma_cap_pred_kPa", "sigma_cap_pred_{model}", "kPa", 1e-3)


@user_units
@dataclass(frozen=True, eq=False)
class BackAnalysis:
    """The capillary stress each wet test carried, back-analysed from the dry envelope.

    σ_cap = (τ_max − c)/tan φ − σ_N and χ_back = σ_cap/Δu, with standard uncertainties by the delta method
    (the dry fit's covariance of c and tan φ and one test's scatter) and intervals with the Student t
    quantile of the dry fit's degrees of freedom.

    Attributes
    ----------
    sigma_cap_kPa, sigma_cap_se_kPa : ndarray
        Back-analysed capillary stress and its standard uncertainty [kPa] (NaN on dry tests).
    sigma_cap_ci_kPa : (ndarray, ndarray)
        Its confidence interval [kPa] (``confidence`` of the run, 95 % by default).
    sigma_cap, sigma_cap_se, sigma_cap_ci
        The same in Pa (the fields, as the pipeline stores them): deprecated names, kept for one release with a
        DeprecationWarning; ``.si.sigma_cap`` reads them without one.
    chi_back, chi_back_se : ndarray
        χ_back = σ_cap/Δu and its standard uncertainty [-] (NaN where Δu = 0).
    chi_back_ci : (ndarray, ndarray)
        Its confidence interval [-].
    dof : ndarray
        Degrees of freedom of the dry fit behind each test's interval [-].
    """

    sigma_cap: np.ndarray = output("sigma_cap_kPa", "sigma_cap", "kPa", 1e-3)
    sigma_cap_se: np.ndarray = output("sigma_cap_se_kPa", "sigma_cap_se", "kPa", 1e-3)
    sigma_cap_ci: tuple = output(
        "sigma_cap_ci{level}_kPa", ("sigma_cap_low{level}", "sigma_cap_high{level}"), "kPa", 1e-3, pair=True
    )
    chi_back: np.ndarray = output("chi_back", "chi_back")
    chi_back_se: np.ndarray = output("chi_back_se", "chi_back_se")
    chi_back_ci: tuple = output("chi_back_ci{level}", ("chi_back_low{level}", "chi_back_high{level}"), pair=True)
    dof: np.ndarray = output("dof", "dof")


class Sampled:
    """Values of a per-test array kept at some rows only (a long run's figures and console tables need no more).

    ``a[rows]`` gives the values at ``rows`` (integer indices, or one index) when every one of them was kept;
    any other row raises IndexError. A long `capred shear` run (capred.pipelines.shear, block by block) keeps
    its per-test outputs in a spool on disk and these samples in memory.

    Parameters
    ----------
    rows : ndarray of int
        The rows kept, increasing.
    values : ndarray
        The values at those rows.
    n : int
        Length of the whole array (the number of tests).
    """

    def __init__(self, rows: np.ndarray, values: np.ndarray, n: int):
        self.rows, self.values, self.n = rows, values, n

    def __len__(self) -> int:
        return self.n

    def __repr__(self) -> str:
        return (
            f"Sampled({self.rows.size} of {self.n} tests kept, e.g. {self.values[:3].tolist()}; every test's "
            "value is in results.csv or result.table())"
        )

    @property
    def shape(self) -> tuple[int]:
        """``(n,)``: the shape of the whole per-test array the samples come from."""
        return (self.n,)

    def scaled(self, factor: float) -> Sampled:
        """The same rows with every value times ``factor`` (Pa -> kPa: 1e-3).

        Parameters
        ----------
        factor : float
            The factor.

        Returns
        -------
        Sampled
            A new sample of the same rows.
        """
        return Sampled(self.rows, self.values * factor, self.n)

    def __array__(self, dtype=None, copy=None):
        raise TypeError(
            "a long run keeps this per-test array at sampled rows only (Sampled.rows, Sampled.values); "
            "every test's value is in results.csv, or in result.table()"
        )

    def __getitem__(self, index):
        idx = np.asarray(index)
        if idx.dtype == bool or idx.dtype.kind not in "iu":
            raise IndexError(
                "a long run keeps this per-test array at sampled rows only: index it with row numbers "
                "(the whole column is in results.csv)"
            )
        pos = np.searchsorted(self.rows, idx)
        pos_ok = np.minimum(pos, max(self.rows.size - 1, 0))
        if self.rows.size == 0 or np.any(self.rows[pos_ok] != idx):
            raise IndexError("rows not kept in memory by a long run (the whole column is in results.csv)")
        return self.values[pos_ok]


def _glossary(name: str, suffix: str = "", **kw):
    """An :func:`output` declaration of a glossary quantity: its JSON key and unit (capred.nomenclature)."""
    from .. import nomenclature as nom

    q = nom.QUANTITIES[name]
    return output(nom.json_key(name, suffix), unit=q.unit if q.unit not in ("", "-") else "", **kw)


@dataclass(frozen=True, eq=False)
class EnvelopeNumbers:
    """The numbers of a fitted straight envelope tau = c + sigma_N tan(phi) as the JSON's materials block gives them.

    The lab store records them so: each field one declaration, its JSON key and unit the glossary's.

    The values are held in the output units (kPa, deg), computed once from the fit by
    ``capred.pipelines.shear.envelope_numbers``.

    Attributes
    ----------
    c, c_se : float
        Cohesion intercept and its standard error [kPa].
    phi, phi_se : float
        Friction angle and its standard error (delta method) [deg].
    tan_phi, tan_phi_se : float
        Slope and its standard error [-].
    c_ci, phi_ci : tuple of float
        95 % intervals of c [kPa] and phi [deg].
    r2 : float
        Coefficient of determination [-].
    n : int
        Number of tests fitted (a count: not recorded in the lab store).
    errors, loss : str
        Error model and loss of the fit.
    scatter : float
        Residual standard deviation [kPa] (NaN without degrees of freedom).
    outliers : list of dict
        The tests flagged as outliers.
    """

    c: float = _glossary("c")
    phi: float = _glossary("phi")
    tan_phi: float = _glossary("tan_phi")
    c_se: float = _glossary("c", "_se")
    phi_se: float = _glossary("phi", "_se")
    tan_phi_se: float = _glossary("tan_phi", "_se")
    c_ci: tuple = _glossary("c", "_ci95", pair=True, of="c")
    phi_ci: tuple = _glossary("phi", "_ci95", pair=True, of="phi")
    r2: float = _glossary("r2")
    n: int = output("n", store=False)
    errors: str = output("errors", store=False)
    loss: str = output("dry_loss", store=False)
    scatter: float = _glossary("scatter")
    outliers: list = output("outliers", store=False)
