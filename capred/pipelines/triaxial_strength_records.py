"""The records of `capred triaxial`: one material's findings and the run's result, with their tables and JSON.

Separate from the computation (capred.pipelines.triaxial_strength) as shear_records is from shear: the one place
where JSON keys and CSV columns of the command are spelled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import nomenclature as nom
from ..fitting.extended_mc import ExtendedMCFit
from ..physics import effective_stress_models as esm
from ..result import Result, num

KPA = 1e3


@dataclass(frozen=True)
class MaterialStrength:
    """Everything `capred triaxial` found for one material (SI inside; JSON in kPa and deg).

    Attributes
    ----------
    material : str
    form : str
        ``"compression"`` or ``"extension"``.
    rows : numpy.ndarray
        Indices of the material's tests in the input table.
    fit : ExtendedMCFit
        The extended Mohr-Coulomb fit of its failure states.
    envelope_source : str
        What the effective envelope is: the extended fit at s -> 0 (named) or the options.
    c_eff, phi_eff : float
        The envelope used by the models and the bounds [Pa], [deg].
    envelope_cov : numpy.ndarray
        2 x 2 covariance of (c' [Pa], φ' [deg]) (zeros for an envelope given as options).
    line_cov : numpy.ndarray
        2 x 2 covariance of (a [Pa], b [-]) of q_f = a + b σ'3.
    models : tuple of str
        Models scored.
    skipped : dict
        Model -> why it was not scored.
    predictions : dict
        Model -> q_f predicted per test [Pa].
    metrics : dict
        Model -> ModelMetrics (capred.pipelines.shear) on the tests with suction.
    information : dict
        Model -> {"k", "aicc", "delta_aicc", "weight"}.
    laws : dict
        Model -> FittedLaw (chi laws fitted on this material).
    back : dict
        ``sigma_cap``, ``sigma_cap_se`` [Pa], ``chi_back``, ``chi_back_se`` [-] per test.
    bounds : dict
        ``spherical_p_cap``, ``lower_p_cap``, ``lower_sigma3_cap`` [Pa] and their ``_se`` per test.
    ranking : object or None
        capred.pipelines.shear_analysis.RankingUncertainty of the bootstrap.
    best : str or None
        Lowest RMSE.
    """

    material: str
    form: str
    rows: np.ndarray
    fit: ExtendedMCFit
    envelope_source: str
    c_eff: float
    phi_eff: float
    envelope_cov: np.ndarray
    line_cov: np.ndarray
    models: tuple
    skipped: dict
    predictions: dict
    metrics: dict
    information: dict
    laws: dict
    back: dict
    bounds: dict
    ranking: object
    best: str | None
    #: model -> its own envelope refitted under it (``c_eff`` [Pa], ``phi_eff`` [deg], ``rmse`` [Pa], ``k``,
    #: ``aicc``, ``delta_aicc``, ``weight``): `own_envelopes`
    own: dict = field(default_factory=dict)


@dataclass(repr=False)
class TriaxialStrengthResult(Result):
    """Result of `capred triaxial`, per material.

    The extended Mohr-Coulomb fit, the model comparison, the back-analysed capillary stress and the bounds on the named
    envelope.

    Attributes
    ----------
    source : str
        The input table's path (``"<DataFrame>"`` for a DataFrame).
    tests : dict
        Per test (input order): ``test_id``, ``material``, ``branch``, ``sigma3``, ``q_f``, ``suction`` [Pa] and
        the completed sample state (``S_R``, ``rho_d``, ``e``, ``w`` ...).
    materials : dict
        Material -> MaterialStrength.
    options : TriaxialStrengthOptions
    inputs : list of InputFile
    notes, warnings : list of str
    """

    command = "triaxial"
    source: str
    tests: dict
    materials: dict
    options: object  # TriaxialStrengthOptions
    inputs: list
    notes: list
    warnings: list

    # --- per material -------------------------------------------------------------------------------------
    def fits(self) -> dict[str, ExtendedMCFit]:
        """Material -> its extended Mohr-Coulomb fit (``fit.params[NAME]``, ``fit.summary()``).

        Returns
        -------
        dict of str to capred.fitting.extended_mc.ExtendedMCFit
            One fit per material.
        """
        return {m: r.fit for m, r in self.materials.items()}

    def best_model(self) -> dict[str, str | None]:
        """Material -> the model of lowest RMSE on its tests with suction.

        Returns
        -------
        dict of str to str or None
            The model's name per material (None where no model could be scored).
        """
        return {m: r.best for m, r in self.materials.items()}

    # --- tables -------------------------------------------------------------------------------------------
    def test_rows(self) -> list[dict]:
        """One dict per test: inputs, completed state, back-analysis, bounds and every model's q_f [kPa].

        Returns
        -------
        list of dict
            One dict per test, stresses in kPa.
        """
        t = self.tests
        out: list[dict] = [{} for _ in t["test_id"]]
        for m, r in self.materials.items():
            pi_low, pi_high = r.fit.prediction_interval(
                r.fit.x, r.fit.s
            )  # a new test at each test's state, at --confidence
            for j, i in enumerate(r.rows):
                row = {
                    "test_id": t["test_id"][i],
                    "material": m,
                    "branch": r.form,
                    "sigma3_kPa": num(t["sigma3"][i] / KPA),
                    "q_f_kPa": num(t["q_f"][i] / KPA),
                    "suction_kPa": num(t["suction"][i] / KPA),
                    **{k: num(t[k][i]) for k in _STATE_KEYS},
                    "q_fit_kPa": num(r.fit.fitted[j] / KPA),
                    "q_fit_pi_low_kPa": num(pi_low[j] / KPA),
                    "q_fit_pi_high_kPa": num(pi_high[j] / KPA),
                    "sigma_cap_kPa": num(r.back["sigma_cap"][j] / KPA),
                    "sigma_cap_se_kPa": num(r.back["sigma_cap_se"][j] / KPA),
                    "chi_back": num(r.back["chi_back"][j]),
                    "chi_back_se": num(r.back["chi_back_se"][j]),
                    "spherical_p_cap_kPa": num(r.bounds["spherical_p_cap"][j] / KPA),
                    "spherical_p_cap_se_kPa": num(r.bounds["spherical_p_cap_se"][j] / KPA),
                    "lower_sigma3_cap_kPa": num(r.bounds["lower_sigma3_cap"][j] / KPA),
                    "lower_sigma3_cap_se_kPa": num(r.bounds["lower_sigma3_cap_se"][j] / KPA),
                    "lower_p_cap_kPa": num(r.bounds["lower_p_cap"][j] / KPA),
                    **{f"q_pred_{mod}_kPa": num(r.predictions[mod][j] / KPA) for mod in r.models},
                    "flags": ";".join(self.flags(m, j)),
                }
                out[i] = row
        return out

    def flags(self, material: str, j: int) -> list[str]:
        """The flags of the j-th test of ``material``.

        Beyond the pendular regime, χ_back outside [0, 1], a positive capillary pressure; none for a test without suction
        (a saturated test has no capillary stress to flag).

        Parameters
        ----------
        material : str
            The material.
        j : int
            The test's index among the material's tests (from 0).

        Returns
        -------
        list of str
            The flags' names (empty when none applies).
        """
        r = self.materials[material]
        i = r.rows[j]
        out = []
        if not r.fit.s[j] > 0:
            return out
        S = self.tests["S_R"][i]
        if np.isfinite(S) and S > 3 / (2 * np.pi):  # Own 1's chi1 = (2 pi S_R/3)^(2/3) exceeds 1 (SPEC 2)
            out.append("chi1_above_1")
        chi = r.back["chi_back"][j]
        if np.isfinite(chi) and (chi < 0 or chi > 1):
            out.append("chi_back_outside_0_1")
        if r.bounds["spherical_p_cap"][j] > 0:
            out.append("positive_capillary_pressure")
        return out

    def material_rows(self) -> list[dict]:
        """One dict per material: the extended Mohr-Coulomb parameters, the envelope used and the best model.

        Returns
        -------
        list of dict
            One dict per material, c' in kPa and the angles in degrees.
        """
        rows = []
        for m, r in self.materials.items():
            p = r.fit.params
            row = {"material": m, "branch": r.form, "n": r.fit.n, "errors": r.fit.errors}
            for name in ("c_eff_kPa", "phi_eff_deg", "phi_b_deg"):
                row[name] = num(p[name].value)
                row[name.rsplit("_", 1)[0] + "_se_" + name.rsplit("_", 1)[1]] = num(p[name].stderr)
                row[name.rsplit("_", 1)[0] + "_ci95_low_" + name.rsplit("_", 1)[1]] = num(p[name].ci95[0])
                row[name.rsplit("_", 1)[0] + "_ci95_high_" + name.rsplit("_", 1)[1]] = num(p[name].ci95[1])
            row["r2"] = num(r.fit.r2)
            row["rmse_fit_kPa"] = num(math.sqrt(r.fit.rss / r.fit.n) / KPA)
            row["envelope"] = r.envelope_source
            row["envelope_c_kPa"] = num(r.c_eff / KPA)
            row["envelope_phi_deg"] = num(r.phi_eff)
            row["best_model"] = r.best
            rows.append(row)
        return rows

    def metric_rows(self) -> list[dict]:
        """One dict per material and model: n, RMSE, bias, R², AICc, Akaike weight, bootstrap share.

        Returns
        -------
        list of dict
            One dict per material and model, RMSE and bias in kPa.
        """
        rows = []
        for m, r in self.materials.items():
            for mod in r.models:
                mm, info = r.metrics[mod], r.information[mod]
                rk = r.ranking
                rows.append(
                    {
                        "material": m,
                        "model": mod,
                        "label": esm.REGISTRY[mod].label,
                        "n": mm.n,
                        "rmse_kPa": num(mm.si.rmse / KPA),
                        "bias_kPa": num(mm.si.bias / KPA),
                        "r2": num(mm.r2),
                        "k": info["k"],
                        "aicc": num(info["aicc"]),
                        "delta_aicc": num(info["delta_aicc"]),
                        "akaike_weight": num(info["weight"]),
                        "p_best": None if rk is None else num(rk.probability.get(mod)),
                        **_own_columns(r.own.get(mod)),
                        "rmse_ci95_low_kPa": None
                        if rk is None or mod not in rk.rmse_ci
                        else num(rk.rmse_ci[mod][0] / KPA),
                        "rmse_ci95_high_kPa": None
                        if rk is None or mod not in rk.rmse_ci
                        else num(rk.rmse_ci[mod][1] / KPA),
                    }
                )
        return rows

    def law_rows(self) -> list[dict]:
        """One dict per fitted chi law and material: its parameters with SE and 95 % interval.

        Returns
        -------
        list of dict
            One dict per law, material and parameter.
        """
        rows = []
        for m, r in self.materials.items():
            for mod, law in r.laws.items():
                for name, par in law.params.items():
                    rows.append(
                        {
                            "material": m,
                            "model": mod,
                            "parameter": name,
                            "value": num(par.value),
                            "se": num(par.stderr),
                            "ci95_low": num(par.ci95[0]),
                            "ci95_high": num(par.ci95[1]),
                            "unit": par.unit,
                        }
                    )
        return rows

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        ``materials`` (fit, envelope, models, laws, ranking), ``metrics`` and ``tests``.

        Parameters
        ----------
        lazy : bool, optional
            Allow :class:`capred.result.Rows` in place of long lists (default False: plain lists).

        Returns
        -------
        dict
            JSON key -> value.
        """
        mats = {}
        for m, r in self.materials.items():
            p = r.fit.params
            mats[m] = {
                "branch": r.form,
                "extended_mohr_coulomb": {
                    "n": r.fit.n,
                    "dof": r.fit.dof,
                    "errors": r.fit.errors,
                    "heteroscedasticity": {k: _plain(v) for k, v in r.fit.heteroscedasticity.items()},
                    "r2": num(r.fit.r2),
                    "params": {
                        n: {"value": num(v.value), "se": num(v.stderr), "ci95": [num(v.ci95[0]), num(v.ci95[1])]}
                        for n, v in p.items()
                    },
                    "correlation": {f"{a}/{b}": num(c) for (a, b), c in p.correlation.items()},
                    "warnings": list(r.fit.warnings),
                },
                "envelope": {
                    "source": r.envelope_source,
                    **{nom.json_key(q): num(v) for q, (v, _) in _envelope(r).items()},
                    **{nom.json_key(q, "_se"): num(se) for q, (_, se) in _envelope(r).items()},
                },
                "best_model": r.best,
                "own_envelopes": {
                    mod: {
                        "c_kPa": num(v["c_eff"] / KPA),
                        "phi_deg": num(v["phi_eff"]),
                        "rmse_kPa": num(v["rmse"] / KPA),
                        "k": v["k"],
                        "delta_aicc": num(v.get("delta_aicc")),
                        "akaike_weight": num(v.get("weight")),
                    }
                    for mod, v in r.own.items()
                },
                "skipped_models": dict(r.skipped),
                "laws": {
                    mod: {
                        n: {"value": num(v.value), "se": num(v.stderr), "unit": v.unit} for n, v in law.params.items()
                    }
                    for mod, law in r.laws.items()
                },
                "ranking": None
                if r.ranking is None
                else {
                    "replicates": r.ranking.replicates,
                    "seed": r.ranking.seed,
                    "probability_best": {k: num(v) for k, v in r.ranking.probability.items()},
                },
            }
        return {"source": self.source, "materials": mats, "metrics": self.metric_rows(), "tests": self.test_rows()}

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows, per material: the effective envelope and the extended Mohr-Coulomb fit.

        The envelope's ``c_kPa``, ``phi_deg`` and their standard errors (glossary units, as the JSON's ``envelope``),
        the fit's parameters (``c_eff_kPa``, ``phi_eff_deg``, ``phi_b_deg``, ``tan_phi_b``: capred.parameters.Parameter,
        with their 95 % intervals and standard errors) and its ``r2``.

        Parameters
        ----------
        material : str, optional
            Not used: a triaxial run names its materials itself.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import parameter_store_rows, store_row

        rows = []
        for m, r in self.materials.items():
            for q, (value, se) in _envelope(r).items():
                unit = nom.QUANTITIES[q].unit
                rows += [
                    store_row(m, nom.json_key(q), num(value), unit),
                    store_row(m, nom.json_key(q, "_se"), num(se), unit),
                ]
            rows += parameter_store_rows(r.fit.params.values(), m)
            rows.append(store_row(m, nom.json_key("r2"), num(r.fit.r2), nom.QUANTITIES["r2"].unit))
        return [row for row in rows if row is not None]

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame.

        Returns
        -------
        dict of str to pandas.DataFrame
            ``results`` (per test), ``materials``, ``metrics`` and ``laws``.
        """
        import pandas as pd

        return {
            "results": pd.DataFrame(self.test_rows()),
            "materials": pd.DataFrame(self.material_rows()),
            "metrics": pd.DataFrame(self.metric_rows()),
            "laws": pd.DataFrame(
                self.law_rows(),
                columns=["material", "model", "parameter", "value", "se", "ci95_low", "ci95_high", "unit"],
            ),
        }

    def method_notes(self) -> tuple[list[str], list[str]]:
        """What the run adds to the methods text: the envelope of each material, named.

        Returns
        -------
        tuple of (list of str, list of str)
            The paragraphs, and the keys of the references they cite (capred.references.REFERENCES).
        """
        return [f"{m}: {r.envelope_source}." for m, r in self.materials.items()], ["fredlund1978", "prunier2024"]


def _own_columns(own: dict | None) -> dict:
    """The metrics.csv columns of a model's own envelope (None where the model has none)."""
    own = own or {}
    return {
        "own_c_eff_kPa": num(own.get("c_eff", math.nan) / KPA),
        "own_phi_eff_deg": num(own.get("phi_eff")),
        "own_rmse_kPa": num(own.get("rmse", math.nan) / KPA),
        "own_delta_aicc": num(own.get("delta_aicc")),
        "own_akaike_weight": num(own.get("weight")),
    }


#: the completed sample state repeated per test (dimensionless; G_s carries the densities)
_STATE_KEYS = ("S_R", "w", "e", "n", "theta", "G_s")


def _plain(v):
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, float, np.floating, np.integer)):
        return num(v)
    return v


# --- reading ----------------------------------------------------------------------------------------------------


def _envelope(r) -> dict:
    """Glossary name -> (value, standard error) of a material's effective envelope: c' [kPa], phi' [deg]."""
    return {
        "c": (r.c_eff / KPA, math.sqrt(max(r.envelope_cov[0, 0], 0.0)) / KPA),
        "phi": (r.phi_eff, math.sqrt(max(r.envelope_cov[1, 1], 0.0))),
    }
