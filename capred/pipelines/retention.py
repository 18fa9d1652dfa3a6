"""`capred retention`: water-retention models fitted per branch, with uncertainties and model selection.

And hysteresis fitted jointly (Kool & Parker 1987).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..errors import FitError, OptionError
from ..fitting.chi_laws import akaike_weights
from ..fitting.nonlinear import NonlinearFit
from ..fitting.retention_models import (
    JSON_NAMES,
    confidence_band,
    fit_hysteresis,
    fit_model,
    hysteresis_model,
    identifiability_warnings,
    json_name,
)
from ..fitting.retention_models import MODELS as FITTERS
from ..io import Table, read_table
from ..parameters import Parameters
from ..references import cite
from ..result import InputFile, Result, columns_of_rows, csv_header, input_file, num, with_csv_headers
from ..spec.retention import SCHEMA, RetentionOptions, to_internal  # noqa: F401 (declared in spec; re-exported here)
from .retention_branches import (
    infer_branches,
    reversal_points,
    single_direction,
)

# the same as a head of water [cm] (SWRC Fit and RETC report these)
_HEAD = {
    "alpha": "alpha_per_cm",
    "s_e": "h_b_cm",
    "s_m": "h_m_cm",
    "a": "a_cm",
    "s_r": "h_r_cm",
    "alpha1": "alpha1_per_cm",
    "alpha2": "alpha2_per_cm",
    "alpha_d": "alpha_d_per_cm",
    "alpha_w": "alpha_w_per_cm",
}


def report_name(internal: str, quantity: str) -> str:
    """The JSON name of an internal retention parameter.

    ``alpha`` -> ``alpha_per_kPa``, ``y_r`` -> ``theta_r`` or ``S_res``.

    Parameters
    ----------
    internal : str
        The parameter's internal name (``alpha``, ``n``, ``y_s``, ``y_r``, ...).
    quantity : str
        What the fit is of: ``theta`` or ``S_R``.

    Returns
    -------
    str
        The JSON name.
    """
    return json_name(internal, quantity)[0]


#: a branch is fitted with a model only when it holds at least the model's free parameters plus this many readings
#: (issue 39: with k + 1 readings a curve of k parameters passes through them all; three more leave a residual
#: with three degrees of freedom, and AICc needs n − k − 1 > 0)
MIN_EXTRA_READINGS = 3
#: a fit whose R² falls below this gets a warning: the curve misses the readings by more than their scatter
#: around a retention curve of any of the registry's shapes (the public sets of tests/data/retention fit with
#: R² ≥ 0.98)
R2_WARNING = 0.95
#: ΔAICc of the joint hysteresis model against the separate branches above which it is rejected (Burnham &
#: Anderson 2002, section 2.6: ΔAICc > 10 means essentially no support)
HYSTERESIS_DELTA_AICC = 10.0


# --- typed records: one per fit and one per reading; JSON keys and CSV headers follow from these declarations


def _y_unit(quantity: str) -> str:
    return "m³/m³" if quantity == "theta" else "-"


#: fields of a RetentionFitRecord as they appear in the outputs: (attribute, JSON key, CSV column, unit);
#: unit "y" is the unit of the fitted water quantity (m³/m³ for θ, - for S_R), None a text column
FIT_OUTPUTS: tuple[tuple[str, str, str, str | None], ...] = (
    ("branch", "branch", "branch", None),
    ("model", "model_name", "model", None),
    ("n_points", "n_points", "n_points", "-"),
    ("n_free", "n_free", "n_free", "-"),
    ("r2", "r2", "R²", "-"),
    ("rmse", "rmse", "RMSE", "y"),
    ("rss", "rss", "RSS", "y²"),
    ("aic", "aic", "AIC", "-"),
    ("aicc", "aicc", "AICc", "-"),
    ("bic", "bic", "BIC", "-"),
    ("delta_aicc", "delta_aicc", "ΔAICc", "-"),
    ("weight", "weight", "Akaike weight", "-"),
    ("converged", "converged", "converged", None),
)
#: the fit statistics of FIT_OUTPUTS that a fit's JSON object (and the lab store) gives
_STATS = ("r2", "rmse", "aic", "aicc", "bic", "rss")
#: columns of one parameter in parameters.csv: (attribute of capred.parameters.Parameter, CSV column)
PARAMETER_COLUMNS = (("value", "value"), ("stderr", "standard error"), ("ci95", "95 % CI"))


@dataclass(frozen=True)
class RetentionFitRecord:
    """One retention model fitted to one branch, in the user's units (the JSON's).

    Attributes
    ----------
    branch : str
        ``"drying"`` or ``"wetting"`` (``"both"`` for the joint hysteresis fit).
    model : str
        Registry key (``vg``, ``bc`` ...; ``kool_parker`` for the hysteresis fit).
    label : str
        Display name of the model.
    quantity : str
        ``"theta"`` (θ [m³/m³]) or ``"S_R"`` [-]: the fitted water quantity.
    params : capred.parameters.Parameters
        Fitted parameters by JSON name (``theta_r``, ``alpha_per_kPa``, ``n`` ...), value, stderr, ci95, unit.
    n_points, n_free : int
        Readings fitted and free parameters k [-].
    r2 : float
        Weighted coefficient of determination [-].
    rmse : float
        Root mean square residual [unit of the water quantity].
    rss : float
        Weighted residual sum of squares [unit squared].
    aic, aicc, bic : float
        Akaike (with the small-sample correction: AICc) and Bayesian information criteria [-]; AICc is NaN when
        n − k − 1 ≤ 0 (a warning says so).
    delta_aicc, weight : float
        AICc minus the branch's lowest, and the Akaike weight exp(−Δ/2)/Σ [-] (Burnham & Anderson 2002).
    converged : bool
        The optimiser met its tolerances.
    at_bounds, fixed, held : tuple of str
        JSON names of parameters on a bound, fixed by the user, held at a bound for the standard errors.
    warnings : tuple of str
        Warnings on this fit (bounds, identifiability, AICc).
    notes : tuple of str
        Notes on this fit.
    reference : str
        The model's paper.
    """

    branch: str
    model: str
    label: str
    quantity: str
    params: Parameters
    n_points: int
    n_free: int
    r2: float
    rmse: float
    rss: float
    aic: float
    aicc: float
    bic: float
    delta_aicc: float
    weight: float
    converged: bool
    at_bounds: tuple = ()
    fixed: tuple = ()
    held: tuple = ()
    warnings: tuple = ()
    notes: tuple = ()
    reference: str = ""

    def row(self) -> dict:
        """The record as one row of fits.csv: ``{"name [unit]": value}`` (text columns without a unit).

        Returns
        -------
        dict
            ``{"name [unit]": value}``.
        """
        out = {}
        for attr, _, column, unit in FIT_OUTPUTS:
            if unit is None:
                out[column] = getattr(self, attr)
            else:
                u = unit.replace("y", _y_unit(self.quantity)) if "y" in unit else unit
                u = "(m³/m³)²" if u == "m³/m³²" else ("-" if u == "-²" else u)
                out[f"{column} [{u}]"] = getattr(self, attr)
        return out

    def parameter_rows(self) -> list[dict]:
        """One row of parameters.csv per parameter.

        Branch, model, parameter, value, standard error, 95 % CI, and the unit of those three (one table holds
        parameters of several units: the unit is a column).

        Returns
        -------
        list of dict
        """
        rows = []
        for p in self.params.values():
            r = {"branch": self.branch, "model": self.model, "parameter": p.name}
            r["value"] = p.value
            r["standard error"] = p.stderr
            r["95 % CI low"], r["95 % CI high"] = p.ci95
            r["unit"] = p.unit
            r["fixed"] = p.fixed
            rows.append(r)
        return rows


@dataclass(frozen=True)
class RetentionPoints:
    """The readings of a retention run and each fitted curve at them (arrays over readings).

    Attributes
    ----------
    suction : ndarray
        Suction s [Pa] (output in kPa).
    water : ndarray
        θ [m³/m³] or S_R [-] as read.
    branch : ndarray of str
        The branch of each reading.
    weight : ndarray
        Weight of each reading in the least squares [-].
    fitted : dict[str, ndarray]
        ``{model: fitted value at each reading}`` (NaN where the model was not fitted to the reading's branch).
    quantity : str
        ``"theta"`` or ``"S_R"``.
    """

    suction: np.ndarray
    water: np.ndarray
    branch: np.ndarray
    weight: np.ndarray
    fitted: dict
    quantity: str

    def columns(self) -> dict:
        """``{"name [unit]": array}`` of points.csv.

        Returns
        -------
        dict of str to numpy.ndarray
            Branch, suction [kPa], the water quantity and each model's fitted value.
        """
        y, unit = {"theta": ("theta", "m³/m³"), "w": ("w", "-")}.get(self.quantity, ("S_R", "-"))
        out = {"branch": np.asarray(self.branch, dtype=object), "suction [kPa]": self.suction * 1e-3}
        out[f"{y} [{unit}]"] = self.water
        out["weight [-]"] = self.weight
        for m, v in self.fitted.items():
            out[f"{y}_{m} [{unit}]"] = v
        return out


@dataclass(repr=False)
class RetentionResult(Result):
    """Result of `capred retention`: fits per branch and model, readings, hysteresis.

    ``fits[branch][model]`` is a :class:`capred.fitting.retention_models.RetentionFit` (callable; ``.params`` by
    JSON name in the JSON's units, ``.summary()``); :meth:`fit_records` and :meth:`points` are the typed
    records the tables, CSV files and console read. ``unfitted`` maps a branch too short to fit to the reason;
    ``direction`` (+1/-1 per reading) and ``turning`` (indices of the reversals inferred, empty when the branches
    came from a column or ``--branches single``) come from
    :func:`capred.pipelines.retention_branches.infer_branches`; ``scanning`` lists the :class:`ScanningCurve`
    of the readings labelled ``scanning``.
    """

    command = "retention"
    json_name = "fits.json"

    source: str
    quantity: str  # "theta" or "S_R"
    suction: np.ndarray  # Pa
    water: np.ndarray
    branch: np.ndarray
    branch_source: str
    fits: dict[str, dict[str, NonlinearFit]]  # branch -> model -> fit
    options: RetentionOptions
    notes: list[str] = field(default_factory=list)
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    hysteresis: NonlinearFit | None = None
    weights: np.ndarray | None = None
    unfitted: dict = field(default_factory=dict)
    direction: np.ndarray | None = None
    turning: tuple = ()
    scanning: list = field(default_factory=list)

    @property
    def names(self) -> tuple[str, str]:
        """The names of the saturated and residual values of the fitted quantity (``("theta_s", "theta_r")``, ...)."""
        return {"theta": ("theta_s", "theta_r"), "w": ("w_s", "w_r")}.get(self.quantity, ("S_s", "S_res"))

    def fit_record(self, branch: str, model: str) -> RetentionFitRecord:
        """The typed record of one fit (``branch`` ``"both"`` and ``model`` ``"kool_parker"``: the hysteresis).

        Parameters
        ----------
        branch : str
            ``drying`` or ``wetting`` (a key of ``fits``).
        model : str
            The model's name (``vg``, ``vg_m_free``, ``bc``, ``kosugi``, ``fx``, ``fx_no_c``, ``durner``).
            ``kool_parker`` (with any ``branch``) gives the joint hysteresis fit.

        Returns
        -------
        RetentionFitRecord
            Parameters in JSON units with their errors, statistics and Akaike weight.
        """
        if model == "kool_parker":
            f, sel = self.hysteresis, {"kool_parker": (float("nan"), float("nan"))}
        else:
            f = self.fits[branch][model]
            sel = akaike_weights({m: g.aicc for m, g in self.fits[branch].items()})
        d, w = sel[model]

        def names(keys):
            return tuple(json_name(k, self.quantity)[0] for k in keys)

        return RetentionFitRecord(
            branch,
            model,
            f.label,
            self.quantity,
            f.params,
            f.n,
            f.nfree,
            float(f.r2),
            float(f.rmse),
            float(f.rss),
            float(f.aic),
            float(f.aicc),
            float(f.bic),
            float(d) if d is not None else float("nan"),
            float(w) if w is not None else float("nan"),
            bool(f.converged),
            names(f.at_bounds()),
            names(f.fixed),
            names(getattr(f, "held", ())),
            tuple(getattr(f, "warnings", ())),
            tuple(getattr(f, "notes", ())),
            cite(FITTERS[model].reference if model in FITTERS else "kool_parker1987"),
        )

    def fit_records(self, branch: str | None = None) -> list[RetentionFitRecord]:
        """Every fit's record, branch by branch, models in the order fitted (one branch with ``branch``).

        Parameters
        ----------
        branch : str, optional
            Only this branch (default: all).

        Returns
        -------
        list of RetentionFitRecord
            The records, in order.
        """
        return [self.fit_record(b, m) for b, fits in self.fits.items() if branch in (None, b) for m in fits]

    def points(self) -> RetentionPoints:
        """The readings and each model's fitted value at them.

        Returns
        -------
        RetentionPoints
        """
        fitted = {}
        for b, fits in self.fits.items():
            sel = self.branch == b
            for m, f in fits.items():
                col = fitted.setdefault(m, np.full(self.suction.size, np.nan))
                col[sel] = f.water(self.suction[sel])
        if self.scanning:
            col = fitted.setdefault("scanning", np.full(self.suction.size, np.nan))
            for c in self.scanning:
                col[c.index] = c.predicted
        w = self.weights if self.weights is not None else np.ones(self.suction.size)
        return RetentionPoints(self.suction, self.water, self.branch, w, fitted, self.quantity)

    def quantity_units(self) -> dict[str, str]:
        """JSON key -> unit of each number in a fit's object (:meth:`fit_json`), from the declarations.

        Each parameter's unit (capred.parameters.Parameter, also of its ``_se``), its head form (cm of water), the fit
        statistics (``FIT_OUTPUTS``, "y" being the fitted quantity's unit).

        Returns
        -------
        dict
            Key -> unit ("-" when dimensionless).
        """
        y = _y_unit(self.quantity)
        of_y = {"y": y, "y²": "-" if y == "-" else f"({y})²"}
        out = {key: of_y.get(unit, unit) for _, key, _, unit in FIT_OUTPUTS if unit is not None}
        fits = [f for branch in self.fits.values() for f in branch.values()] + [self.hysteresis or None]
        for f in filter(None, fits):
            for k, p in zip(f.params_si, f.params.values()):
                out[p.name] = out[f"{p.name}_se"] = p.unit
                if k in _HEAD:
                    out[_HEAD[k]] = "1/cm" if k.startswith("alpha") else "cm"
        return out

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: per branch, every fitted model's numbers as ``<model>.<key>``.

        The branch is labelled ``material (branch)`` where the inputs name a material; each number from the declaration
        :meth:`fit_json` writes it by: a parameter's JSON name, value, standard error, 95 % interval and unit
        (capred.parameters.Parameter), its head form (cm of water), the values the model derives (``m``, unit from the
        retention JSON names) and the fit statistics (``FIT_OUTPUTS``; the counts n_points and n_free are not recorded).
        A derived value that no declaration gives a unit is not recorded and is named in a CapredWarning.

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        import warnings

        from ..errors import CapredWarning
        from ..fitting.retention_models import JSON_NAMES
        from ..records import parameter_store_rows, store_row

        units = self.quantity_units()
        derived_units = {key: unit for key, _, unit in JSON_NAMES.values()}
        rows = []
        for branch, fits in self.fits.items():
            label = f"{material} ({branch})" if material else str(branch)
            for model, f in fits.items():
                prefix = f"{model}."
                si, heads = f.params_si, self._head_forms(f)
                for k, p in zip(si, f.params.values()):  # each parameter, then its head form (as fit_json)
                    rows += parameter_store_rows([p], label, prefix)
                    if k in _HEAD:
                        rows += filter(
                            None, [store_row(label, prefix + _HEAD[k], num(heads[_HEAD[k]]), units[_HEAD[k]])]
                        )
                found = []
                entry = FITTERS.get(model)
                for name, value in entry.derived if entry is not None else ():
                    if name not in derived_units:
                        warnings.warn(
                            f"retention model '{model}': '{name}' has no declared unit; the lab store does not "
                            "record it",
                            CapredWarning,
                            stacklevel=2,
                        )
                        continue
                    found.append((name, value(si), derived_units[name]))
                found += [(key, getattr(f, key), units[key]) for key in _STATS]  # their units: FIT_OUTPUTS
                for key, value, unit in found:
                    row = store_row(label, prefix + key, num(value), unit)
                    if row is not None:
                        rows.append(row)
        return rows

    def _head_forms(self, f: NonlinearFit) -> dict:
        """JSON key -> value of a fit's suction parameters as heads of water (``alpha_per_cm``, ``h_b_cm``)."""
        cm = self.options.gamma_w * 0.01  # Pa per cm of water head
        si = f.params_si
        return {_HEAD[k]: si[k] * cm if k.startswith("alpha") else si[k] / cm for k in si if k in _HEAD}

    def fit_json(self, f: NonlinearFit, model: str) -> dict:
        """The JSON of one fit.

        Each parameter by JSON name with ``_se`` and ``_ci95``, its head form (cm), statistics, correlations, SI values,
        warnings.

        Parameters
        ----------
        f : NonlinearFit
            One fit of this result.
        model : str
            Its model name (``hysteresis`` or ``kool_parker`` for the joint fit).

        Returns
        -------
        dict
            JSON key -> value (kPa, 1/kPa, cm of head, -).
        """
        si = f.params_si
        heads = self._head_forms(f)
        out: dict = {}
        for k, p in zip(si, f.params.values()):
            out[p.name] = num(p.value)
            out[f"{p.name}_se"] = num(p.stderr) if np.isfinite(p.stderr) else None
            out[f"{p.name}_ci95"] = None if not np.isfinite(p.ci95[0]) else [num(p.ci95[0]), num(p.ci95[1])]
            if k in _HEAD:
                out[_HEAD[k]] = num(heads[_HEAD[k]])
        entry = FITTERS.get(model) or (hysteresis_model() if f is self.hysteresis else None)
        for name, value in entry.derived if entry is not None else ():
            out[name] = num(value(si))
        out.update(
            {
                "r2": num(f.r2),
                "rmse": num(f.rmse),
                "aic": num(f.aic),
                "aicc": num(f.aicc),
                "bic": num(f.bic),
                "rss": num(f.rss),
                "n_points": f.n,
                "n_free": f.nfree,
                "converged": f.converged,
                "fixed": [report_name(k, self.quantity) for k in f.fixed],
                "at_bounds": [report_name(k, self.quantity) for k in f.at_bounds()],
                "correlation": {
                    report_name(a, self.quantity): {report_name(b, self.quantity): num(v) for b, v in row.items()}
                    for a, row in f.correlation().items()
                },
                "params_si": {k: num(v) for k, v in si.items()},
                "parameters": [report_name(k, self.quantity) for k in si],
                "units": {p.name: p.unit for p in f.params.values()},
                "held": [report_name(k, self.quantity) for k in getattr(f, "held", ())],
                "notes": list(getattr(f, "notes", [])),
                "warnings": list(getattr(f, "warnings", [])),
                "model": f.label,
                "reference": cite(FITTERS[model].reference if model in FITTERS else "kool_parker1987"),
            }
        )
        if getattr(f, "suction_range", None) is not None:
            out["suction_range_kPa"] = [num(f.suction_range[0] * 1e-3), num(f.suction_range[1] * 1e-3)]
            out["suction_points_kPa"] = [num(x * 1e-3) for x in f.suction_points]
        return out

    def model_selection(self, branch: str) -> dict:
        """AICc, its difference to the best and the Akaike weight of every model fitted to one branch.

        Parameters
        ----------
        branch : str
            ``drying`` or ``wetting``.

        Returns
        -------
        dict
            Model -> {``aicc``, ``delta_aicc``, ``weight``, ``k``} ({} for a branch without fits).
        """
        fits = self.fits.get(branch, {})
        weights = akaike_weights({m: f.aicc for m, f in fits.items()})
        return {
            m: {"aicc": num(fits[m].aicc), "delta_aicc": num(d), "weight": num(w), "k": fits[m].nfree}
            for m, (d, w) in weights.items()
        }

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        Source, quantity, branch source, main branch and its fits, every branch with its fits and model selection, the
        hysteresis fit if any.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        branches = {
            b: {
                "n_points": int(np.sum(self.branch == b)),
                "fits": {m: self.fit_json(f, m) for m, f in fits.items()},
                "model_selection": self.model_selection(b),
            }
            for b, fits in self.fits.items()
        }
        main = "drying" if "drying" in branches else next(iter(branches), None)
        out = {
            "source": self.source,
            "quantity": self.quantity,
            "branch_source": self.branch_source,
            "main_branch": main,
            "fits": branches[main]["fits"] if main else {},
            "branches": branches,
            "model_selection": branches[main]["model_selection"] if main else {},
        }
        if self.turning:
            out["reversals_kPa"] = [num(self.suction[i] * 1e-3) for i in self.turning]
        if self.unfitted:
            out["unfitted_branches"] = {
                b: {"n_points": int(np.sum(self.branch == b)), "reason": why} for b, why in self.unfitted.items()
            }
        if (self.branch == "scanning").any():
            out["scanning"] = {
                "n_points": int(np.sum(self.branch == "scanning")),
                "curves": [c.json() for c in self.scanning],
            }
        if self.hysteresis is not None:
            h = self.hysteresis
            js = self.fit_json(h, "hysteresis")
            ind_aicc = self.independent_aicc()
            keys = list(h.params)
            out["hysteresis"] = {
                "model": "kool-parker",
                "params": {k: js[k] for k in keys},
                "se": {k: js[f"{k}_se"] for k in keys},
                "units": {k: h.params[k].unit for k in keys},
                "alpha_ratio": num(h.params_si["alpha_w"] / h.params_si["alpha_d"]),
                "rss": js["rss"],
                "r2": js["r2"],
                "aicc": js["aicc"],
                "independent_aicc": num(ind_aicc),
                "reference": cite("kool_parker1987"),
            }
        return out

    def independent_aicc(self) -> float | None:
        """AICc of the hysteresis fit's model fitted to each branch on its own.

        The model is van Genuchten, ``hysteresis_base`` in the registry; to compare with the joint hysteresis fit.

        Returns
        -------
        float or None
            None without its fit of both branches, NaN where n − k − 1 ≤ 0.
        """
        base = hysteresis_model().name
        ind = [self.fits[b][base] for b in ("drying", "wetting") if base in self.fits.get(b, {})]
        if len(ind) != 2:
            return None
        n = sum(f.n for f in ind)
        k = sum(f.nfree for f in ind)
        rss = sum(f.rss for f in ind)
        return float(n * np.log(rss / n) + 2 * k + (2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else np.nan))

    def season_rows(self) -> list[dict]:
        """One row per branch for a batch's season.csv: the best model (lowest AICc) and its parameters.

        Headers follow the rule of fits.csv and parameters.csv: ``name [unit]`` with the unit of the record
        (RMSE and θ_r, θ_s in m³/m³ for θ data, - for S_R; a JSON suffix read as its unit: ``alpha [1/kPa]``).

        Returns
        -------
        list of dict
            ``name [unit]`` (text columns: name) -> value.
        """
        rows = []
        for b, fits in self.fits.items():
            if not fits:
                continue
            recs = self.fit_records(b)
            best = min(recs, key=lambda r: (not np.isfinite(r.aicc), r.aicc if np.isfinite(r.aicc) else 0.0))
            row = {"branch": b, "best_model": best.model, "n_points [-]": best.n_points}
            row["r2 [-]"] = num(best.r2)
            row[f"rmse [{_y_unit(self.quantity)}]"] = num(best.rmse)
            row["aicc [-]"] = num(best.aicc)
            for p in best.params.values():
                head = csv_header(p.name)
                row[head if "[" in head else f"{p.name} [{p.unit}]"] = num(p.value)
            rows.append(row)
        return rows

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame.

        ``fits``: one row per branch and model (statistics); ``parameters``: one row per fitted parameter (value,
        standard error, 95 % CI and unit); ``points``: one row per reading with each model's fitted value.

        Returns
        -------
        dict of str to pandas.DataFrame
        """
        cached = self.__dict__.get("_tables")
        if cached is None:
            import pandas as pd

            recs = self.fit_records()
            if self.hysteresis is not None:
                recs = recs + [self.fit_record("both", "kool_parker")]
            cached = self.__dict__["_tables"] = {
                "fits": pd.DataFrame([r.row() for r in recs]),
                "parameters": pd.DataFrame([row for r in recs for row in r.parameter_rows()]),
                "points": pd.DataFrame(self.points().columns()),
            }
        return cached

    def csv_tables(self) -> dict:
        """The tables of :meth:`tables` as column mappings (name -> array), written without importing pandas.

        The same bytes in every CSV file (pandas costs a third of a second of a run's start-up).

        Returns
        -------
        dict
            File stem -> {``"name [unit]"``: array}.
        """
        recs = self.fit_records()
        if self.hysteresis is not None:
            recs = recs + [self.fit_record("both", "kool_parker")]
        tables = {
            "fits": columns_of_rows([r.row() for r in recs]),
            "parameters": columns_of_rows([row for r in recs for row in r.parameter_rows()]),
            "points": self.points().columns(),
        }
        return {stem: with_csv_headers(t) for stem, t in tables.items()}

    def curve(self, branch: str, model: str, s):
        """The fitted curve of one branch and model at suctions ``s`` [Pa] (θ [m³/m³] or S_R [-]).

        Parameters
        ----------
        branch : str
            ``drying`` or ``wetting`` (a key of ``fits``).
        model : str
            The model's name (``vg``, ``vg_m_free``, ``bc``, ``kosugi``, ``fx``, ``fx_no_c``, ``durner``).
        s : array_like
            Suction [Pa].

        Returns
        -------
        ndarray
            The fitted water content at ``s``.
        """
        return self.fits[branch][model].water(s)

    def band(self, branch: str, model: str, s):
        """95 % confidence band (lower, upper) of one fitted curve at ``s`` [Pa].

        Parameters
        ----------
        branch : str
            ``drying`` or ``wetting`` (a key of ``fits``).
        model : str
            The model's name (``vg``, ``vg_m_free``, ``bc``, ``kosugi``, ``fx``, ``fx_no_c``, ``durner``).
        s : array_like
            Suction [Pa].

        Returns
        -------
        tuple of ndarray
            (lower, upper), in the fit's quantity.
        """
        return confidence_band(model, self.fits[branch][model], s)


@dataclass(frozen=True)
class ScanningCurve:
    """One scanning curve of a record.

    The readings of a ``scanning`` run and the curve the main curves predict through its reversal point (Parker &
    Lenhard 1987 scaling, :func:`capred.physics.retention.scanning_water`).

    Attributes
    ----------
    direction : str
        ``drying`` or ``wetting``: the direction of the scanning curve.
    index : ndarray of int
        The readings on it (0-based rows).
    s_reversal, y_reversal : float
        Its reversal point: suction [Pa] and water quantity (the reading where the direction turned).
    s_closure, y_closure : float
        Where its loop closes: the previous reversal of the other kind, or the wet end (s = 0) / dry end
        (s = inf) [Pa].
    main_model : str
        The fit of the main curve scaled (``kool_parker`` or a registry model).
    predicted : ndarray
        The scanning curve at the readings.
    rmse, r2 : float
        Agreement of the predicted curve with the readings [unit of the water quantity], [-].
    main : callable
        The main curve scaled, ``main(s) -> y``.
    """

    direction: str
    index: np.ndarray
    s_reversal: float
    y_reversal: float
    s_closure: float
    y_closure: float
    main_model: str
    predicted: np.ndarray
    rmse: float
    r2: float
    main: object = field(default=None, repr=False, compare=False)

    def curve(self, s):
        """The scanning curve at suctions ``s`` [Pa] (Parker & Lenhard 1987 scaling of the main curve).

        Parameters
        ----------
        s : array_like
            Suction [Pa].

        Returns
        -------
        ndarray
            The water quantity on the scanning curve.
        """
        from ..physics.retention import scanning_water

        return scanning_water(s, self.main, self.s_reversal, self.y_reversal, self.s_closure, self.y_closure)

    def json(self) -> dict:
        """The curve in fits.json.

        Direction, readings (1-based), reversal and closure points [kPa] (null at the dry end, s → ∞; ``closes_at`` says
        where), model, RMSE, R².

        Returns
        -------
        dict
        """
        return {
            "direction": self.direction,
            "readings": [int(i) + 1 for i in self.index],
            "reversal_kPa": num(self.s_reversal * 1e-3),
            "reversal_water": num(self.y_reversal),
            "closure_kPa": num(self.s_closure * 1e-3) if np.isfinite(self.s_closure) else None,
            "closes_at": "dry end"
            if not np.isfinite(self.s_closure)
            else "wet end"
            if self.s_closure == 0
            else ("previous reversal"),
            "closure_water": num(self.y_closure),
            "main_model": self.main_model,
            "rmse": num(self.rmse),
            "r2": num(self.r2),
            "method": "Parker & Lenhard (1987) scaling of the main curve through the reversal and closure points",
            "reference": cite("parker_lenhard1987"),
        }


def _main_curves(fits: dict, hyst) -> tuple[str, dict] | None:
    """(model, {direction: y(s)}) of the main curves a scanning curve scales.

    The joint Kool & Parker fit when run, else the model with the lowest summed AICc among those fitted to both main
    branches, else the best of one.
    """
    from ..physics import retention as rp

    if hyst is not None:
        p = hyst.params_si
        return "kool_parker", {
            "drying": lambda x: rp.vg_water(x, p["y_r"], p["y_s"], p["alpha_d"], p["n"]),
            "wetting": lambda x: rp.vg_water(x, p["y_r"], p["y_s"], p["alpha_w"], p["n"]),
        }
    both = [m for m in fits.get("drying", {}) if m in fits.get("wetting", {})]
    score = {m: fits["drying"][m].aicc + fits["wetting"][m].aicc for m in both}
    finite = [m for m in both if np.isfinite(score[m])]
    if finite or both:
        m = min(finite, key=score.get) if finite else both[0]
        return m, {b: fits[b][m].water for b in ("drying", "wetting")}
    for b in ("drying", "wetting"):
        if fits.get(b):
            m = min(fits[b], key=lambda k: fits[b][k].aicc if np.isfinite(fits[b][k].aicc) else np.inf)
            return m, {b: fits[b][m].water}
    return None


def scanning_curves(s, y, branch, direction, turning, fits, hyst=None) -> tuple[list[ScanningCurve], list[str]]:
    """The scanning curves of a record.

    Each run of ``scanning`` readings compared with the curve the main curves predict through its reversal point (Parker
    & Lenhard 1987).

    Parameters
    ----------
    s, y : ndarray
        Suction [Pa] and water quantity of every reading, in time order.
    branch : ndarray of str
        Label of each reading (``scanning`` marks the scanning readings).
    direction : ndarray of int
        +1 (suction rising) or -1 per reading.
    turning : sequence of int
        The reversal points (indices).
    fits : dict
        Main-curve fits by branch and model.
    hyst : RetentionFit, optional
        The joint Kool & Parker fit, scaled in preference.

    Returns
    -------
    (list of ScanningCurve, list of str)
        The curves and warnings.

    References
    ----------
    Parker, J. C., Lenhard, R. J. (1987). Water Resour. Res. 23(12):2187-2196, doi:10.1029/WR023i012p02187.
    """
    from ..physics.retention import scanning_water

    scan = np.flatnonzero(branch == "scanning")
    if not scan.size:
        return [], []
    main = _main_curves(fits, hyst)
    runs, cur = [], [int(scan[0])]
    for i in scan[1:]:
        if i == cur[-1] + 1 and direction[i] == direction[cur[-1]]:
            cur.append(int(i))
        else:
            runs.append(cur)
            cur = [int(i)]
    runs.append(cur)
    reversals = reversal_points(direction, turning)
    out, warns = [], []
    for run in runs:
        idx = np.array(run)
        d = int(direction[idx[0]])
        name = "drying" if d > 0 else "wetting"
        r = idx[0] - 1 if idx[0] > 0 else idx[0]
        where = f"scanning {name} curve, readings {idx[0] + 1}-{idx[-1] + 1}"
        if main is None or name not in main[1]:
            warns.append(f"{where}: no main {name} curve fitted, so no scanning curve is predicted")
            continue
        model, curves = main
        m = curves[name]
        # the loop closes at the latest earlier reversal of the other kind beyond the reversal point
        kind = 1 if d > 0 else -1
        prev = [i for i, k in reversals if i < r and k == kind and (s[i] - s[r]) * d > 0]
        if prev:
            s_c, y_c = float(s[prev[-1]]), float(y[prev[-1]])
        else:
            s_c = np.inf if d > 0 else 0.0
            y_c = float(np.asarray(m(np.asarray(1e15 if d > 0 else 0.0))))
        pred = scanning_water(s[idx], m, float(s[r]), float(y[r]), s_c, y_c)
        res = y[idx] - pred
        rmse = float(np.sqrt(np.mean(res**2))) if np.all(np.isfinite(res)) else float("nan")
        tss = float(np.sum((y[idx] - y[idx].mean()) ** 2))
        r2 = 1.0 - float(np.sum(res**2)) / tss if tss > 0 and np.isfinite(rmse) else float("nan")
        out.append(ScanningCurve(name, idx, float(s[r]), float(y[r]), s_c, y_c, model, pred, rmse, r2, m))
        if not np.all(np.isfinite(pred)):
            warns.append(
                f"{where}: the main {name} curve ({model}) is flat between the reversal at {s[r] * 1e-3:.4g} kPa and "
                "the closure of the loop, so it cannot be scaled through both: no scanning curve is predicted"
            )
        if idx.size >= 3 and np.isfinite(r2) and r2 < R2_WARNING:
            warns.append(
                f"{where}: the scanning curve scaled from the main {name} curve ({model}) through the reversal at "
                f"{s[r] * 1e-3:.4g} kPa gives R² = {r2:.3f} < {R2_WARNING:g} (RMSE {rmse:.3g}): the readings do not "
                "follow Parker & Lenhard's scaling of the main curves (air entrapment, or a mislabelled branch)"
            )
    return out, warns


def _hysteresis_rejected(hyst, fits: dict, quantity: str) -> list[str]:
    """A warning when the joint Kool & Parker model is rejected against the separate branches (ΔAICc > 10).

    It says which shared parameter the branches disagree on (a wetting θ_s below the drying one: entrapped air).
    """
    base = hysteresis_model().name
    ind = [fits[b][base] for b in ("drying", "wetting") if base in fits.get(b, {})]
    if len(ind) != 2:
        return []
    n = sum(f.n for f in ind)
    k = sum(f.nfree for f in ind)
    if not n - k - 1 > 0 or not np.isfinite(hyst.aicc):
        return []
    rss = sum(f.rss for f in ind)
    independent = float(n * np.log(rss / n) + 2 * k + 2 * k * (k + 1) / (n - k - 1))
    delta = float(hyst.aicc) - independent
    if not delta > HYSTERESIS_DELTA_AICC:
        return []
    d, w = (f.params_si for f in ind)
    parts = []
    for key in ("y_s", "y_r", "n"):
        name = json_name(key, quantity)[0]
        parts.append(f"{name} {d[key]:.3g} drying, {w[key]:.3g} wetting")
    hint = ""
    if w["y_s"] < d["y_s"] - 0.05 * max(abs(d["y_s"]), 1e-12):
        hint = (
            f"; a wetting {json_name('y_s', quantity)[0]} below the drying one is the mark of entrapped air "
            "(the wetting branch does not return to the drying branch's saturated water content)"
        )
    return [
        f"hysteresis (Kool & Parker): the joint model (θ_s, θ_r, n shared by both branches, α apart) is rejected "
        f"against separate drying and wetting fits of {base}: ΔAICc = {delta:.3g} > {HYSTERESIS_DELTA_AICC:g} "
        f"(Burnham & Anderson 2002: no support); the branches differ in more than α ({'; '.join(parts)}){hint}; "
        "use the separate branch fits"
    ]


def parse_fixed(items: list[str]) -> dict[str, float]:
    """'theta_s=0.25' -> {'theta_s': 0.25}; values in the report units (kPa, 1/kPa).

    Parameters
    ----------
    items : list of str
        The values of --fix, each ``NAME=VALUE``.

    Returns
    -------
    dict
        Report name -> value [kPa, 1/kPa or -].

    Raises
    ------
    OptionError
        On an unknown name or a value that is not a number.
    """
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        try:
            to_internal(name)
        except KeyError:
            known = ", ".join(["theta_s", "theta_r", "S_s", "S_res", *sorted({v[0] for v in JSON_NAMES.values()})])
            raise OptionError(f"--fix '{item}': expected NAME=VALUE with NAME one of {known}") from None
        if not sep:
            raise OptionError(f"--fix '{item}': expected NAME=VALUE")
        try:
            out[name] = float(value)
        except ValueError:
            raise OptionError(f"--fix '{item}': '{value}' is not a number") from None
    return out


def _suction(table, opt) -> np.ndarray:
    """Suction [Pa] from a suction column, a head (any length unit or cm of water) or pF (10^pF cm of water)."""
    s = table.get("suction").copy()
    from_head = np.isnan(s)
    s[from_head] = (opt.gamma_w * table.get("head"))[from_head]
    from_pf = np.isnan(s)
    s[from_pf] = (opt.gamma_w * 0.01 * 10.0 ** table.get("pF"))[from_pf]
    return s


@dataclass
class _Readings:
    """A retention table read and checked: suction [Pa], the water quantity fitted and its readings, weights."""

    table: Table
    s: np.ndarray
    y: np.ndarray
    quantity: str
    weights: np.ndarray


def _water_readings(table: Table, opt: RetentionOptions) -> tuple[str, np.ndarray]:
    """The water quantity fitted ('theta', 'w' or 'S_R') and its readings.

    A burette's S_R outside [0, 1] is a problem of the table.
    """
    if "theta" in table.columns or ("w" in table.columns and "rho_d" in table.columns):
        y = table.get("theta").copy()
        grav = np.isnan(y)
        y[grav] = (table.get("w") * table.get("rho_d") / opt.rho_w)[grav]
        return "theta", y
    if "w" in table.columns:  # w(s) at the specimen's (constant) dry density: the same curve shape, w_s, w_r
        return "w", table.get("w").copy()
    y = table.get("S_R").copy()
    burette = np.isnan(y)
    y[burette] = ((table.get("V_v") - table.get("z2")) / table.get("V_v"))[burette]
    for i in np.flatnonzero(burette & np.isfinite(y) & ((y < 0) | (y > 1))):
        table.add_problem(i, "z2", f"S_R = (V_v - z2)/V_v = {y[i]:.4g} lies outside [0, 1]")
    return "S_R", y


def _read_readings(source, opt: RetentionOptions) -> _Readings:
    """Read a retention table: its suctions, water readings and weights, every problem raised at once."""
    table = read_table(source, SCHEMA)
    if not any(c in table.columns for c in ("suction", "head", "pF")):
        table.missing_column("suction", " (or 'head' / 'z1', or 'pF')")
    if not any(c in table.columns for c in ("S_R", "theta", "z2", "w")):
        table.missing_column("S_R", " (or 'theta', or 'w' with 'rho_d', or 'z2' with 'V_v')")
    if "z2" in table.columns and "V_v" not in table.columns and "S_R" not in table.columns:
        table.missing_column("V_v", " (needed with 'z2')")
    from .sample_state import table_state

    table_state(table, opt.rho_w, ("w", "rho_d", "theta", "S_R"))  # a row's w, rho_d, theta must agree
    table.raise_if_problems()
    s = _suction(table, opt)
    positive = s[s > 0]
    with np.errstate(over="ignore", divide="ignore"):
        span = positive.max() / positive.min() if positive.size else 1.0
    if positive.size and not (np.isfinite(span) and 1e-30 < positive.min() and positive.max() < 1e30):
        raise FitError(
            f"{table.path}: suctions from {positive.min():.3g} to {positive.max():.3g} Pa cannot be "
            "fitted: check the units of the file and --gamma-w"
        )
    quantity, y = _water_readings(table, opt)
    for i in np.flatnonzero(np.isnan(s)):
        table.add_problem(i, next((c for c in ("suction", "head", "pF") if c in table.columns), None), "no suction")
    for i in np.flatnonzero(np.isnan(y)):
        table.add_problem(i, None, f"no {quantity} value")
    weights = table.get("weight", 1.0).copy()
    weights[np.isnan(weights)] = 1.0
    table.raise_if_problems()
    return _Readings(table, s, y, quantity, weights)


def _branch_labels(table: Table, s: np.ndarray, opt: RetentionOptions, notes: list[str]):
    """The branch of every reading, how it was found, and the branches inferred from the order of readings."""
    found = infer_branches(s, opt.reversal_relative, opt.reversal_range)
    if opt.branches == "single":
        one = single_direction(s, opt.reversal_relative, opt.reversal_range)
        branch = np.full(s.size, one, dtype=object)
        how = f"--branches single: every reading on one {one} curve"
        if "branch" in table.columns:
            notes.append("--branches single: the 'branch' column is not used")
    elif "branch" in table.columns and all(table.columns["branch"]):
        branch, how = np.asarray(table.columns["branch"], dtype=object), "column 'branch'"
    else:
        branch = found.label
        rel, rng = found.tolerance
        how = (
            "inferred from the order of readings (rising suction = drying; reversals below "
            f"max({100 * rel:g} % of the reading, {100 * rng:g} % of the range) ignored)"
        )
        if found.against:
            notes.append(
                f"{found.against} readings step against their branch's direction by less than the noise tolerance "
                f"(max({100 * rel:g} % of the reading, {100 * rng:g} % of the measured range)): they stay in it "
                "(--reversal-relative, --reversal-range, or a 'branch' column decide otherwise)"
            )
        if found.turning:
            notes.append(
                "branches inferred: reversals at "
                + ", ".join(f"{s[i] * 1e-3:.4g} kPa (reading {i + 1})" for i in found.turning)
                + "; check them, or give a 'branch' column"
            )
    n_scan = int(np.sum(branch == "scanning"))
    if n_scan:
        notes.append(
            f"{n_scan} readings on scanning curves (they start at a reversal inside the measured range): kept out "
            "of the main-curve fits, shown in the outputs and figures, and compared with the scanning curves the "
            "main curves predict (Parker & Lenhard 1987 scaling)"
        )
    return branch, how, found


def _fit_branch(
    b: str, sel: np.ndarray, r: _Readings, opt: RetentionOptions, fixed_internal: dict, warnings: list[str]
) -> tuple[dict[str, NonlinearFit], list[str]]:
    """Every model of ``opt.models`` fitted to the readings ``sel`` of branch ``b``, and the models skipped.

    Skipped for want of readings; warnings (not fitted, identifiability, parameters at a bound) appended.
    """
    s, y, weights, quantity = r.s, r.y, r.weights, r.quantity
    fits: dict[str, NonlinearFit] = {}
    skipped = []
    for m in opt.models:
        fx = {k: v for k, v in fixed_internal.items() if k in FITTERS[m].names}
        n_free = len(FITTERS[m].names) - len(fx)
        if sel.sum() < n_free + MIN_EXTRA_READINGS:
            skipped.append(f"{m} ({n_free} free parameters)")
            continue
        try:
            f = dataclasses.replace(fit_model(m, s[sel], y[sel], fx, weights[sel]), quantity=quantity)
        except FitError as exc:
            warnings.append(f"branch '{b}', model {m}: not fitted ({exc})")
            continue
        f.warnings = identifiability_warnings(f)  # named by the data kind (theta_r or S_res)
        warnings.extend(f"branch '{b}', model {m}: {w}" for w in f.warnings)
        fits[m] = f
        for k in f.at_bounds():
            name, scale, _ = json_name(k, quantity)
            warnings.append(f"branch '{b}', model {m}: {name} = {f.params_si[k] * scale:.6g} lies at its bound")
    return fits, skipped


def _fit_branches(
    r: _Readings, branch: np.ndarray, opt: RetentionOptions, fixed_internal: dict, warnings: list[str]
) -> tuple[dict[str, dict[str, NonlinearFit]], dict[str, str]]:
    """The fits of every main branch (scanning readings left out), and why a branch went unfitted by a model."""
    fits: dict[str, dict[str, NonlinearFit]] = {}
    unfitted: dict[str, str] = {}
    for b in dict.fromkeys(branch):
        if b == "scanning":
            continue
        sel = branch == b
        fits[b], skipped = _fit_branch(b, sel, r, opt, fixed_internal, warnings)
        if skipped:
            unfitted[b] = (
                f"{int(sel.sum())} readings: fewer than the parameters plus {MIN_EXTRA_READINGS} of "
                + ", ".join(skipped)
            )
            warnings.append(
                f"branch '{b}': not fitted with {', '.join(skipped)}: {int(sel.sum())} readings, fewer than the "
                f"model's free parameters plus {MIN_EXTRA_READINGS} (its readings are kept in the outputs; "
                "if they are noise in a longer branch, widen --reversal-relative or give a 'branch' column)"
            )
        poor = [(m, f.r2) for m, f in fits[b].items() if np.isfinite(f.r2) and f.r2 < R2_WARNING]
        if poor:
            warnings.append(
                f"branch '{b}': R² below {R2_WARNING:g} for "
                + ", ".join(f"{m} ({r2:.3f})" for m, r2 in poor)
                + ": the curve does not follow the readings; readings of another branch (a scanning loop, a "
                "mislabelled reversal) or a shape the model cannot take; check the branches (a 'branch' column "
                "with 'scanning') or the data"
            )
    return fits, unfitted


def _kool_parker_fit(
    r: _Readings, branch: np.ndarray, opt: RetentionOptions, fixed_internal: dict, fits: dict, warnings: list[str]
):
    """The joint drying-wetting fit of Kool & Parker (1987) (None unless --hysteresis kool-parker).

    Each branch is also fitted alone with the base model when ``opt.models`` lacks it (added to ``fits``), to
    compare with the joint fit.
    """
    if opt.hysteresis != "kool-parker":
        return None
    s, y, weights, quantity = r.s, r.y, r.weights, r.quantity
    d, w = branch == "drying", branch == "wetting"
    if not (d.any() and w.any()):
        raise OptionError("--hysteresis kool-parker needs a drying and a wetting branch")
    hyst = fit_hysteresis(
        s[d],
        y[d],
        s[w],
        y[w],
        {k: v for k, v in fixed_internal.items() if k in ("y_r", "y_s", "n")},
        np.concatenate([weights[d], weights[w]]),
    )
    base = hysteresis_model().name  # each branch on its own too, to compare with the joint fit
    if base not in opt.models:
        for b in ("drying", "wetting"):
            sel = branch == b
            fits.setdefault(b, {})[base] = dataclasses.replace(
                fit_model(base, s[sel], y[sel], {}, weights[sel]), quantity=quantity
            )
    hyst = dataclasses.replace(hyst, quantity=quantity)
    hyst.warnings = identifiability_warnings(hyst)
    warnings.extend(f"hysteresis (Kool & Parker): {w}" for w in hyst.warnings)
    warnings.extend(_hysteresis_rejected(hyst, fits, quantity))
    return hyst


def run_retention(source, options: RetentionOptions | None = None) -> RetentionResult:
    """Fit the chosen retention models to every branch of a retention table (CSV path, spreadsheet or DataFrame).

    Parameters
    ----------
    source : str or Path or DataFrame
        Retention readings: suction (or head, pF) and water (S_R, theta, or w with rho_d), optional branch and
        weight columns.
    options : RetentionOptions, optional
        Models, fixed parameters, unit weight [N/m^3] and density [kg/m^3] of water, hysteresis.

    Returns
    -------
    RetentionResult
        Every fit per branch with standard errors, 95 % intervals, statistics and model selection.

    References
    ----------
    .. [1] van Genuchten, M. Th. (1980). Soil Sci. Soc. Am. J. 44, 892-898. doi:10.2136/sssaj1980.03615995004400050002x
    .. [2] Brooks, R. H., Corey, A. T. (1964). Hydraulic properties of porous media. Hydrology Paper 3,
       Colorado State University.
    .. [3] Kosugi, K. (1996). Water Resour. Res. 32(9), 2697-2703. doi:10.1029/96WR01776
    .. [4] Fredlund, D. G., Xing, A. (1994). Can. Geotech. J. 31(4), 521-532. doi:10.1139/t94-061
    .. [5] Durner, W. (1994). Water Resour. Res. 30(2), 211-223. doi:10.1029/93WR02676
    .. [6] Kool, J. B., Parker, J. C. (1987). Water Resour. Res. 23(1), 105-114. doi:10.1029/WR023i001p00105
    """
    opt = options or RetentionOptions()
    r = _read_readings(source, opt)
    table, s, y, quantity = r.table, r.s, r.y, r.quantity
    notes = list(table.notes)
    if quantity == "w":
        notes.append(
            "water content by mass w without dry density: w(s) fitted (w_s, w_r), the shape of the retention "
            "curve at the specimen's dry density; give 'rho_d' to fit theta = w rho_d/rho_w"
        )
    branch, how, found = _branch_labels(table, s, opt, notes)
    fixed_internal = {}
    for name, v in opt.fixed.items():
        key, factor = to_internal(name)
        fixed_internal[key] = v * factor
    warnings = list(opt.warnings) + table.warnings
    fits, unfitted = _fit_branches(r, branch, opt, fixed_internal, warnings)
    if not any(fits.values()):
        raise FitError(f"{table.path}: no model could be fitted to any branch ({'; '.join(warnings[-3:])})")
    fits = {b: f for b, f in fits.items() if f}
    hyst = _kool_parker_fit(r, branch, opt, fixed_internal, fits, warnings)
    scans, scan_warnings = scanning_curves(s, y, branch, found.direction, found.turning, fits, hyst)
    warnings.extend(scan_warnings)
    return RetentionResult(
        table.path,
        quantity,
        s,
        y,
        branch,
        how,
        fits,
        opt,
        notes,
        [input_file(source, table)],
        warnings,
        hyst,
        r.weights,
        unfitted,
        found.direction,
        found.turning if how.startswith("inferred") else (),
        scans,
    )
