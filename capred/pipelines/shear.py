"""`capred shear`: hanging-column direct-shear tests to a model comparison.

Reads one table (one row per test), derives sigma_N, suction and S_R, fits the
dry envelope per material, predicts every wet test with the effective-stress
models of the registry (by default the four of Evenepoel's thesis) and scores
them.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import nomenclature as nom
from ..errors import FitError, OptionError
from ..fitting.comparison import compared
from ..fitting.linear import LineFit, breusch_pagan, fit_envelope
from ..io import Table, read_table
from ..physics import effective_stress_models as esm
from ..physics import shear as ph
from ..progress import steps
from ..references import cite
from ..result import (
    InputFile,
    Result,
    Rows,
    input_file,
    json_list,
    num,
    output,
    record_json,
    record_row,
    user_units,
)
from ..spec.shear import SCHEMA, ModelParams, ShearOptions  # noqa: F401 (declared in spec; re-exported here)
from .shear_fits import envelope_fits, line_of
from .shear_records import EnvelopeNumbers, ModelPrediction

#: input columns repeated in results.csv as read (in their documented units), before the derived columns
#: the per-test quantities derived from the raw inputs, as the JSON rows and results.csv give them (glossary names)
DERIVED_OUTPUTS = ("sigma_N", "suction", "S_R", "tau_max", "chi1", "chi2")
RAW_INPUTS = ("z1", "z2", "V_v", "added_mass", "cap_mass", "box_area", "R", "F_max", "e", "height", "rho_d", "G_s")
#: the documented unit of each input column (from its schema entry: one place for it)
_SCHEMA_UNITS = {c.name: c.unit for c in SCHEMA}


def model_params_from_retention(path: str | Path, branch: str | None = None, limits=None, **overrides) -> ModelParams:
    """Retention parameters from a `capred retention` fits.json; options in ``overrides`` win.

    The fits of one branch are read (``branch``; default drying, else the file's main branch). Van Genuchten's
    α, n, m and S_res come from its van Genuchten fit, Brooks-Corey's air-entry suction from its Brooks-Corey fit;
    where the branch has no such fit, its best fit (lowest AICc) is converted to that model over the suction
    range of its data (:func:`capred.pipelines.retention_convert.run_retention_convert`), and a note names the
    conversion, its misfit (RMSE, largest deviation) and the branch.

    Parameters
    ----------
    path : str or Path
        A fits.json written by `capred retention` (or `capred retention-convert`).
    branch : str, optional
        ``"drying"`` or ``"wetting"`` (``--retention-branch``): which branch's fits (default: drying, else the
        file's main branch).
    limits : capred.io.ReadLimits, optional
        The run's reading limits (``--max-megabytes``; default 256 MiB): the file's largest size.
    **overrides
        ModelParams fields given as options (SI: vg_alpha [1/Pa], air_entry [Pa]); None values are ignored.

    Returns
    -------
    ModelParams
        s_res, vg_alpha [1/Pa], vg_n, vg_m, air_entry [Pa] and the best fit's S_R(s) relation, from the van
        Genuchten and Brooks-Corey fits (another model converted to them); ``retention_notes`` says which branch
        and which conversion gave them.

    Raises
    ------
    OptionError
        Where ``path`` cannot be read as a fits.json, or has no branch ``branch``.

    References
    ----------
    van Genuchten, M. Th. (1980). Soil Sci. Soc. Am. J. 44, 892-898, doi:10.2136/sssaj1980.03615995004400050002x;
    Brooks, R. H., Corey, A. T. (1964). Hydraulic properties of porous media. Hydrology Paper 3, Colorado State
    University.
    """
    import json

    from ..io import read_json

    try:
        js = read_json(path, "--retention", limits)  # bounded: --max-megabytes, MAX_JSON_DEPTH
        branches = js.get("branches") or {js.get("main_branch") or "drying": {"fits": js["fits"]}}
        if not isinstance(branches, dict):
            raise TypeError("'branches' is not an object")
    except FileNotFoundError:  # the file is missing: say so, not that it is the wrong kind of file
        from ..errors import MissingFileError

        raise MissingFileError(str(path), "file not found (--retention)") from None
    except json.JSONDecodeError as exc:
        raise OptionError(
            f"--retention {path}: not a fits.json written by capred retention (not JSON: {exc.msg}, line {exc.lineno})"
        ) from None
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        raise OptionError(f"--retention {path}: not a fits.json written by capred retention ({exc})") from None
    if branch is not None and branch not in branches:
        raise OptionError(
            f"--retention-branch {branch}: {path} has no branch '{branch}' (it has {', '.join(branches) or 'none'})"
        )
    b = branch or ("drying" if "drying" in branches else js.get("main_branch") or next(iter(branches), "drying"))
    try:
        fits = branches[b]["fits"]
        if not isinstance(fits, dict):
            raise TypeError("'fits' is not an object")
    except (KeyError, TypeError) as exc:
        raise OptionError(f"--retention {path}: not a fits.json written by capred retention ({exc})") from None
    others = [o for o in branches if o != b]
    how = "given by --retention-branch" if branch is not None else "the default"
    notes: list[tuple[tuple[str, ...], str, bool]] = [
        (
            (),
            f"--retention {path}: the fits of branch '{b}' used ({how})"
            + (f"; the file also has {', '.join(others)}: --retention-branch picks it" if others else ""),
            False,
        )
    ]
    p: dict = {}
    given = {k for k, v in overrides.items() if v is not None}

    def take(to: str, label: str, fields: tuple[str, ...]) -> dict | None:
        """The branch's ``to`` fit, or its best fit converted to ``to`` (with a note); None when impossible."""
        own = fits.get(to) or (fits.get("vg_m_free") if to == "vg" else None)
        used = tuple(f for f in fields if f not in given)
        if own or not fits:
            return own
        from .retention_convert import ConvertOptions, run_retention_convert

        try:
            res = run_retention_convert(js, ConvertOptions(to=to, branch=b))
        except (FitError, OptionError) as exc:
            note = f"--retention {path}: branch '{b}' has no {label} fit and its fit could not be converted: {exc}"
            notes.append((used, note, False))
            return None
        m, src = res.misfit, res.source_fit
        unit = " m³/m³" if src.quantity == "theta" else ""
        conv = res.to_json()["fits"][to]
        shown = ", ".join(f"{k} = {conv[k]:.4g}" for k in conv.get("parameters", ()) if isinstance(conv.get(k), float))
        notes.append(
            (
                used,
                f"--retention {path}: the {src.model} fit of branch '{b}' converted to {label} ({shown}) by least "
                f"squares over its data's suctions, {m['suction_range_kPa'][0]:.4g} to {m['suction_range_kPa'][1]:.4g}"
                f" kPa: misfit in {src.quantity} RMSE {m['rmse']:.3g}{unit}, largest deviation "
                f"{m['max_deviation']:.3g}{unit} at {m['at_suction_kPa']:.4g} kPa (as capred retention-convert)",
                False,
            )
        )
        notes.extend((used, f"--retention {path}, branch '{b}': {w}", True) for w in res.converted.warnings)
        return conv

    vg = take("vg", "van Genuchten", ("s_res", "vg_alpha", "vg_n", "vg_m"))
    if vg:
        ys, yr = (vg.get("S_s"), vg.get("S_res")) if "S_s" in vg else (vg.get("theta_s"), vg.get("theta_r"))
        if ys:
            p["s_res"] = yr / ys if "theta_s" in vg else yr
        p.update(vg_alpha=vg["alpha_per_kPa"] / 1e3, vg_n=vg["n"], vg_m=vg.get("m"))
    bc = take("bc", "Brooks-Corey", ("air_entry",) if "s_res" in p else ("air_entry", "s_res"))
    if bc:
        p["air_entry"] = bc["s_e_kPa"] * 1e3
        if "s_res" not in p:
            p["s_res"] = bc["S_res"] if "S_res" in bc else bc["theta_r"] / bc["theta_s"]
    # the best fit (lowest AICc) of any model gives the S_R(s) relation of the shear figures
    scored = [
        (f.get("aicc") if f.get("aicc") is not None else np.inf, m)
        for m, f in fits.items()
        if isinstance(f, dict) and "params_si" in f
    ]
    if scored:
        best = min(scored)[1]
        p["retention_model"] = (best, tuple(sorted(fits[best]["params_si"].items())), js.get("quantity", "S_R"))
    supplied = tuple(k for k in p if k != "retention_model" and overrides.get(k) is None)
    p.update({k: v for k, v in overrides.items() if v is not None})
    params = ModelParams(**p)
    object.__setattr__(params, "_retention_notes", tuple(notes))  # frozen: set once, as Options sets _warnings
    object.__setattr__(params, "_retention_fields", supplied)  # the model parameters the file gave
    return params


@user_units
@dataclass(frozen=True, eq=False)
class ModelMetrics:
    """How well one effective-stress model predicts the measured peak shear strength of a set of wet tests.

    Attributes
    ----------
    n : int
        Number of tests with a prediction [-].
    rmse_kPa : float
        Root-mean-square error of τ_pred − τ_max [kPa] (JSON ``rmse_kPa``, metrics.csv ``rmse [kPa]``).
    bias_kPa : float
        Mean of τ_pred − τ_max [kPa] (JSON ``bias_kPa``, metrics.csv ``bias [kPa]``).
    r2 : float
        Coefficient of determination 1 − SS_res/SS_tot [-] (NaN where undefined).
    rmse, bias
        The same in Pa (the fields, as the pipeline stores them): deprecated names, kept for one release with a
        DeprecationWarning; ``.si.rmse`` reads them without one.
    """

    n: int = output("n", "n")
    rmse: float = output("rmse_kPa", "rmse", "kPa", 1e-3)
    bias: float = output("bias_kPa", "bias", "kPa", 1e-3)
    r2: float = output("r2", "r2")


@dataclass(repr=False)
class ShearResult(Result):
    """Everything `capred shear` computes. SI inside; ``to_json`` gives kPa."""

    command = "shear"

    source: str
    options: ShearOptions
    tests: dict[str, np.ndarray]
    fits: dict  # material -> EnvelopeFit (fit.params["c_kPa"], fit.summary(); the SI LineFit is fit.line)
    metrics: dict[str, dict[str, ModelMetrics]]
    metrics_overall: dict[str, ModelMetrics]
    best_model: dict[str, str | None]
    best_model_overall: str | None
    notes: list[str] = field(default_factory=list)
    per_material: dict[str, dict] = field(default_factory=dict)  # what models report per material (phi_b_deg)
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    metrics_pendular: dict[str, dict[str, ModelMetrics]] = field(default_factory=dict)
    metrics_pendular_overall: dict[str, ModelMetrics] = field(default_factory=dict)
    laws: dict = field(default_factory=dict)  # model -> material -> FittedLaw
    ranking: dict = field(default_factory=dict)  # material -> RankingUncertainty
    model_inputs: object = None  # esm.ModelInputs of every test (with the fitted laws)
    curves: object = None  # ShearCurves when raw curves were given
    predictions: dict = field(default_factory=dict)  # model -> ModelPrediction (every test)
    saturated_fits: dict = field(default_factory=dict)  # material -> LineFit of its saturated tests
    back: object = None  # BackAnalysis of the wet tests
    #: material -> Breusch-Pagan tests of the dry fit and of each model's wet residuals, and the error model used
    heteroscedasticity: dict = field(default_factory=dict)

    @property
    def level(self) -> str:
        """The confidence level in percent, as output names carry it ("95")."""
        return f"{self.options.confidence * 100:g}"

    @property
    def models(self) -> tuple[str, ...]:
        """The effective-stress models compared (``options.models``), in display order."""
        return self.options.models

    @property
    def best_model_pendular(self) -> dict[str, str | None]:
        """Per material, the model with the lowest RMSE on its pendular wet tests (None: nothing to compare)."""
        return {m: best_of(v) for m, v in self.metrics_pendular.items()}

    @property
    def best_model_pendular_overall(self) -> str | None:
        """The model with the lowest RMSE on every pendular wet test (None: nothing to compare)."""
        return best_of(self.metrics_pendular_overall)

    @property
    def materials(self) -> list[str]:
        """The materials of the run, in the order of their dry fits."""
        return list(self.fits)

    def flags(self, i: int) -> list[str]:
        """The warning flags of one test (e.g. a dry test flagged as an outlier).

        Parameters
        ----------
        i : int
            Row of the test (0-based).

        Returns
        -------
        list of str
            Its flags (empty when none).
        """
        text = self._flag_texts()[i]
        return text.split(";") if text else []

    def tables(self) -> dict:
        """Output tables: ``results`` (one row per test) and ``summary`` (one row per material and model).

        Returns
        -------
        dict of str to pandas.DataFrame
        """
        cached = self.__dict__.get("_tables")
        if cached is None:
            import pandas as pd

            cached = self.__dict__["_tables"] = {
                "results": pd.DataFrame(self._results_columns(), copy=False),
                "summary": summary_table(self),
                "metrics": metrics_table(self),
            }
        return cached

    def csv_tables(self) -> dict:
        """The tables as CSV files take them: results as plain columns (no DataFrame is built); made once.

        Returns
        -------
        dict
            File stem -> a DataFrame or plain columns, under ``name [unit]`` headers.
        """
        cached = self.__dict__.get("_tables") or self.__dict__.get("_csv_tables")
        if cached is None:
            cached = self.__dict__["_csv_tables"] = {
                "results": self._results_columns(),
                "summary": summary_table(self, frame=False),
                "metrics": metrics_table(self, frame=False),
            }
            if self.laws:
                cached["laws"] = laws_table(self)
        return cached

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: per material the dry envelope's numbers and what the models report.

        The envelope's numbers through their declarations (:class:`EnvelopeNumbers`, the ones the JSON's materials block
        writes), and what the models report per material (``phi_b_deg``) where the glossary declares the key; an
        undeclared key is not recorded and is named in a CapredWarning (its unit is never guessed).

        Parameters
        ----------
        material : str, optional
            Not used: a shear run names its materials itself.

        Returns
        -------
        list of capred.records.StoreRow
        """
        import warnings

        from ..errors import CapredWarning
        from ..lab_store import declared_units
        from ..records import record_store_rows, store_row

        rows, units = [], declared_units()
        for m, fit in self.fits.items():
            rows += record_store_rows(envelope_numbers(fit), m)
            for k, v in self.per_material.get(m, {}).items():
                if isinstance(v, str):
                    continue
                if k not in units:
                    warnings.warn(
                        f"material '{m}': '{k}' has no declared unit; the lab store does not record it",
                        CapredWarning,
                        stacklevel=2,
                    )
                    continue
                row = store_row(m, k, num(v), units[k][1])
                if row is not None:
                    rows.append(row)
        return rows

    def season_rows(self) -> list[dict]:
        """Rows of a batch's season.csv: one per material.

        With c and phi [kPa, deg] and their standard errors, the numbers of dry and wet tests, the best model and its
        RMSE [kPa] and the number of flagged tests.

        Returns
        -------
        list of dict
            ``name [unit]`` -> value.
        """
        rows = []
        flags = np.array([bool(f) for f in self._flag_texts()])
        for m, fit in self.fits.items():
            e = envelope_numbers(fit)  # the JSON's declared numbers, under their glossary CSV headers
            best = self.best_model.get(m)
            met = self.metrics.get(m, {}).get(best) if best else None
            rows.append(
                {
                    "material": m,
                    **{nom.column(name, se): num(getattr(e, name + se)) for name in ("c", "phi") for se in ("", "_se")},
                    "n_dry": e.n,
                    "n_wet": int(np.sum((self.tests["material"] == m) & (self.tests["condition"] == "wet"))),
                    "best_model": best,
                    "best_rmse [kPa]": num(met.rmse_kPa) if met else None,
                    "flagged_tests": int(np.sum(flags & (self.tests["material"] == m))),
                }
            )
        return rows

    def method_notes(self) -> tuple[list[str], list[str]]:
        """The models of the run, one sentence each, and their references.

        Returns
        -------
        (list of str, list of str)
            The paragraphs (the models, the dry fit), and the keys of the models' references.
        """
        entries = [esm.REGISTRY[m] for m in self.models]
        text = "Models compared: " + " ".join(e.method for e in entries if e.method)
        return [text, self._dry_method()], [e.reference for e in entries]

    def _dry_method(self) -> str:
        """The methods sentence of the dry envelope: error model (what auto chose), loss, outlier test."""
        o = self.options
        used = {m: line_of(f).errors for m, f in self.fits.items()}
        chosen = ", ".join(f"{m}: {e}" for m, e in used.items())
        errors = {
            "either": "no particular error model: every interval is the wider of those of a constant scatter and "
            "of a scatter proportional to the strength (the least-squares line, its covariance the larger of the "
            "two models' in every direction, a new test's scatter max(s², s_p²(τ/τ_ref)²)), so it holds under both",
            "constant": "the same scatter for every test",
            "proportional": "a scatter proportional to the strength (weighted least squares with the variance "
            "function s²(τ/τ_ref)², iterated; prediction and σ_cap intervals widen with the strength)",
            "auto": "the error model chosen per material by a Breusch-Pagan test (Koenker's form) of the "
            "least-squares residuals against σ_N: proportional when p < 0.05, else constant "
            f"({chosen})",
        }[o.errors]
        loss = {
            "ols": "least squares",
            "huber": "Huber's loss (k = 1.345 s, MAD scale) with sandwich standard errors",
            "tukey": "Tukey's biweight (c = 4.685 s, MAD scale) with sandwich standard errors",
        }[o.dry_loss]
        origin = "through the origin (c = 0)" if o.dry_fit == "origin" else "with c and φ free"
        return (
            f"Dry envelope τ = c + σ_N tan φ fitted per material {origin} by {loss}, assuming {errors}. "
            "A dry test is flagged as an outlier when its externally studentized residual exceeds the Bonferroni "
            "5 % limit t(1 − 0.025/n, n − p − 1)."
        )

    def retention_relation(self, material: str):
        """The S_R(s) relation along which model curves are drawn (None: markers per test only).

        Parameters
        ----------
        material : str
            A material of the run.

        Returns
        -------
        RetentionRelation or None
            The relation (computed once per material).
        """
        from .shear_analysis import retention_relation

        cache = self.__dict__.setdefault("_relations", {})
        if material not in cache:
            sel = (self.tests["material"] == material) & (self.tests["condition"] == "wet")
            cache[material] = retention_relation(
                self.options.model_params, self.tests["suction"][sel], self.tests["S_R"][sel]
            )
        return cache[material]

    def model_curves(self, material: str, sigma_N: float, points: int = 120):
        """Each model's strength along the material's water-retention relation at one normal stress.

        Parameters
        ----------
        material : str
            A material of the run.
        sigma_N : float
            Total normal stress [Pa].
        points : int
            Points along the relation.

        Returns
        -------
        S_R : ndarray
            Degrees of saturation [-] (empty when the material has no retention relation).
        tau : dict of str to ndarray
            Predicted shear strength of each model [Pa].
        """
        from .shear_analysis import model_curves

        relation = self.retention_relation(material)
        if relation is None:
            return np.empty(0), {}
        return model_curves(self, material, relation, sigma_N, points)

    def test_ids(self, rows) -> list[str]:
        """The test_id of each of ``rows`` (row numbers), as read.

        Parameters
        ----------
        rows : array_like of int
            Row numbers (0-based).

        Returns
        -------
        list of str
            The test ids.
        """
        return [str(x) for x in self.tests["test_id"][np.asarray(rows, dtype=int)]]

    def _test_rows(self, start: int, stop: int) -> list[dict]:
        """JSON rows of tests start..stop-1 (kPa)."""
        from ..result import record_json_columns

        t = self.tests
        sl = slice(start, stop)
        # each derived quantity under its glossary JSON key (sigma_N_kPa, S_R), in its glossary unit
        # (divided by SI per output unit, 1000 Pa per kPa: a value typed in kPa reads back as typed)
        derived = {nom.json_key(k): json_list(t[k][sl] / (1 / nom.QUANTITIES[k].factor)) for k in DERIVED_OUTPUTS}
        flags = self._flag_texts()[sl]
        ids, mats, conds, lines = (t[k][sl].tolist() for k in ("test_id", "material", "condition", "line"))
        curve = (
            {
                "displacement_at_peak_mm": json_list(t["displacement_at_peak"][sl] * 1e3),
                "tau_residual_kPa": json_list(t["tau_residual"][sl] / 1e3),
                "dilatancy_angle_deg": json_list(t["dilatancy_angle"][sl]),
            }
            if "displacement_at_peak" in t
            else {}
        )
        columns = {
            **curve,
            "test_id": list(map(str, ids)),
            "material": list(map(str, mats)),
            "condition": list(map(str, conds)),
            "line": list(map(int, lines)),
            **derived,
            **record_json_columns(self.predictions, start, stop, self.level),
            **record_json_columns({None: self.back}, start, stop, self.level),
            "flags": [f.split(";") if f else [] for f in flags],
        }
        keys = tuple(columns)
        return [dict(zip(keys, vals)) for vals in zip(*columns.values())]

    def _results_columns(self) -> dict:
        """The columns of results.csv (name -> array); the arrays as they are, no copies."""
        from ..result import record_columns

        t = self.tests
        cols: dict[str, object] = {
            "test_id": t["test_id"],
            "material": t["material"],
            "condition": t["condition"],
            "line": t["line"],
        }
        for name in RAW_INPUTS:  # the raw inputs as read, in their documented units
            if f"in_{name}" in t:
                cols[f"{name} [{_SCHEMA_UNITS[name]}]"] = t[f"in_{name}"]
        for name in DERIVED_OUTPUTS:
            cols[nom.column(name)] = nom.to_output(name, t[name])
        cols.update(record_columns(self.predictions, self.level))
        cols.update(record_columns({None: self.back}, self.level))
        if "displacement_at_peak" in t:
            cols["displacement_at_peak [mm]"] = t["displacement_at_peak"] * 1e3
            cols["tau_residual [kPa]"] = t["tau_residual"] / 1e3
            cols["dilatancy_angle [deg]"] = t["dilatancy_angle"]
        cols["flags"] = np.asarray(self._flag_texts(), dtype=object)
        return cols

    def _flag_texts(self) -> list[str]:
        cached = self.__dict__.get("_flags")
        if cached is not None:
            return cached
        code, names = self._flag_codes()
        cached = self.__dict__["_flags"] = list(names[code])
        return cached

    def _flag_codes(self) -> tuple[np.ndarray, np.ndarray]:
        """(code of each test, text of each code): bit k of a code is the k-th flag (';'-joined in the text)."""
        wet = self.tests["condition"] == "wet"
        S = self.tests["S_R"]
        parts = [
            ("outside_pendular", wet & (S > self.options.pendular_limit)),
            ("chi1_gt_1", wet & (S > ph.CHI1_UNITY_SR)),
        ]
        outlier = np.zeros(S.shape, bool)
        for fit in self.fits.values():
            diag = line_of(fit).diagnostics or {}
            if "rows" in diag:
                outlier[diag["rows"][np.asarray(diag["outlier"], bool)]] = True
        parts.append(("dry_outlier", outlier))
        for model in self.models:
            flag = esm.REGISTRY[model].no_prediction
            if flag is not None:
                parts.append((flag.name, wet & ~np.isfinite(self.predictions[model].si.tau)))
        code = sum(mask.astype(int) << k for k, (_, mask) in enumerate(parts))
        names = np.array(
            [";".join(n for k, (n, _) in enumerate(parts) if c >> k & 1) for c in range(1 << len(parts))], dtype=object
        )
        return code, names

    def model_selection(self) -> dict:
        """Per material: each model's k, n, RSS, AICc, BIC, delta AICc and Akaike weight on its wet tests.

        Returns
        -------
        dict
            Material -> model -> its criteria (RSS in Pa²).
        """
        from ..fitting.chi_laws import akaike_weights, information_criteria

        cached = self.__dict__.get("_model_selection")
        if cached is not None:
            return cached
        out = self.__dict__["_model_selection"] = {}
        t = self.tests
        for mat in self.materials:
            sel = (t["material"] == mat) & (t["condition"] == "wet")
            if not sel.any():
                continue
            rows = {}
            for m in self.models:
                r = self.predictions[m].si.tau[sel] - t["tau_max"][sel]  # the residual column, also in a long run
                r = r[np.isfinite(r)]
                law = self.laws.get(m, {}).get(mat)
                p = len(law.values) - len(law.fixed) if law is not None else 0
                p += esm.REGISTRY[m].wet_parameters  # e.g. Fredlund's tan(phi_b), fitted on the wet tests
                ic = information_criteria(float(r @ r), int(r.size), p)
                rows[m] = {
                    "k": p + 1,
                    "n": int(r.size),
                    "rss_kPa2": num(float(r @ r) / 1e6),
                    "aicc": num(ic["aicc"]),
                    "bic": num(ic["bic"]),
                }
                if ic["aicc"] is None:  # say why, rather than a bare blank
                    rows[m]["aicc_note"] = (
                        f"AICc undefined: n - k - 1 = {r.size - (p + 1) - 1} <= 0 (too few wet tests for k = {p + 1})"
                        if r.size - (p + 1) - 1 <= 0
                        else "AICc undefined: zero residual sum of squares"
                    )
            # weights among the models scored on the same wet tests; the others listed apart (issue 41.2)
            inside, apart = compared(self.metrics.get(mat, {}))
            weights = akaike_weights({m: rows[m]["aicc"] for m in inside if m in rows})
            for m, (delta, w) in weights.items():
                rows[m]["delta_aicc"], rows[m]["weight"] = num(delta), num(w)
            for m, lack in apart.items():
                if m in rows:
                    rows[m]["delta_aicc"] = rows[m]["weight"] = None
                    rows[m]["missing"] = lack
                    rows[m]["aicc_note"] = (
                        f"not compared: no prediction for {lack} of the {lack + rows[m]['n']} wet tests the others "
                        "are scored on (AICc weights compare models on the same tests only)"
                    )
            out[mat] = rows
        return out

    def summary_rows(self) -> list[dict]:
        """Long table of fits and metrics for the summary CSV.

        Returns
        -------
        list of dict
            One row per material for its dry fit, then one per material and model.
        """
        rows = []
        for mat, fit in self.fits.items():
            rows.append({"material": mat, "model": "dry_fit", **_fit_dict(fit)})
            for m, met in self.metrics[mat].items():
                rows.append({"material": mat, "model": m, **_metric_dict(met), "best": m == self.best_model[mat]})
        for m, met in self.metrics_overall.items():
            rows.append({"material": "(all)", "model": m, **_metric_dict(met), "best": m == self.best_model_overall})
        return rows

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        Source, per material its envelope (and saturated envelope), models, tests, the metrics (all wet tests and
        pendular ones, per material and overall), the best models, the bootstrap ranking, the fitted laws and the
        back-analysis.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        n = len(self.tests["line"])
        tests = Rows(n, self._test_rows)
        return {
            "source": self.source,
            "materials": {
                m: {
                    **_fit_dict(f),
                    **({"saturated_envelope": _fit_dict(self.saturated_fits[m])} if m in self.saturated_fits else {}),
                    **{k: (v if isinstance(v, str) else num(v)) for k, v in self.per_material.get(m, {}).items()},
                }
                for m, f in self.fits.items()
            },
            "models": list(self.models),
            "tests": tests if lazy else tests.tolist(),
            "metrics": {mat: {m: _metric_dict(v) for m, v in d.items()} for mat, d in self.metrics.items()},
            # models left out of the ranking, weights and bootstrap: {material: {model: wet tests it lacks}}
            "not_compared": {mat: compared(d)[1] for mat, d in self.metrics.items() if compared(d)[1]},
            "metrics_overall": {m: _metric_dict(v) for m, v in self.metrics_overall.items()},
            "best_model": self.best_model,
            "best_model_overall": self.best_model_overall,
            "metrics_pendular": {
                mat: {m: _metric_dict(v) for m, v in d.items()} for mat, d in self.metrics_pendular.items()
            },
            "metrics_pendular_overall": {m: _metric_dict(v) for m, v in self.metrics_pendular_overall.items()},
            "best_model_pendular": self.best_model_pendular,
            "best_model_pendular_overall": self.best_model_pendular_overall,
            "best_model_probability": {m: r.probability for m, r in self.ranking.items()},
            "bootstrap": {m: _ranking_dict(r) for m, r in self.ranking.items()},
            "fitted": {
                mat: {
                    model: _law_dict(model, law)
                    for model, by_mat in self.laws.items()
                    for mm, law in by_mat.items()
                    if mm == mat
                }
                for mat in self.materials
                if any(mat in v for v in self.laws.values())
            },
            "model_selection": self.model_selection(),
            "heteroscedasticity": _json_ready(self.heteroscedasticity),
            "dry_fit": self.options.dry_fit,
            "errors": self.options.errors,
            "dry_loss": self.options.dry_loss,
            "constants": {
                "gamma_w_kN_per_m3": self.options.gamma_w / 1e3,
                "surface_tension_N_per_m": self.options.surface_tension,
                "g_m_per_s2": self.options.g,
                "pendular_limit": self.options.pendular_limit,
                "confidence": self.options.confidence,
            },
            "references": {m: cite(esm.REGISTRY[m].reference) for m in self.models},
        }


def laws_table(result) -> dict:
    """The fitted χ laws as a CSV table: one row per law and material.

    Each parameter with its standard error and 95 % interval under ``name [unit]`` headers (the JSON's ``fitted`` block,
    in its units).

    Parameters
    ----------
    result : ShearResult
        A run with fitted laws (``--models chi_power``, ``khalili_fit`` ...).

    Returns
    -------
    dict
        Column header -> list of values (blank where a law has no such parameter; a fixed parameter has no
        standard error or interval).
    """
    from ..result import csv_header

    rows = []
    for model, by_mat in result.laws.items():
        for mat, law in by_mat.items():
            row = {"model": model, "material": mat}
            for name, p in law.params.items():
                head = csv_header(name)
                base, unit = (head[: head.index(" [")], head[head.index("[") + 1 : -1]) if "[" in head else (name, "-")
                row[f"{base} [{unit}]"] = num(p.value)
                row[f"{base}_se [{unit}]"] = num(p.stderr)
                row[f"{base}_low95 [{unit}]"] = num(p.ci95[0])
                row[f"{base}_high95 [{unit}]"] = num(p.ci95[1])
            row.update({"fixed": ";".join(law.fixed), "n": law.n, "dof": law.dof, "converged": law.converged})
            rows.append(row)
    meta = ("fixed", "n", "dof", "converged")
    keys = [k for k in dict.fromkeys(k for r in rows for k in r) if k not in meta] + list(meta)
    return {k: [r.get(k) for r in rows] for k in keys}


def _law_dict(model: str, law) -> dict:
    from ..fitting.chi_laws import information_criteria

    scale = {"s_b": ("s_b_kPa", 1e-3)}
    params = {scale.get(k, (k, 1.0))[0]: num(v * scale.get(k, (k, 1.0))[1]) for k, v in law.values.items()}
    se = {
        scale.get(k, (k, 1.0))[0]: (None if v is None else num(v * scale.get(k, (k, 1.0))[1]))
        for k, v in law.se.items()
    }
    ic = information_criteria(law.rss, law.n, len(law.values) - len(law.fixed))
    ci = {
        scale.get(k, (k, 1.0))[0]: (
            None if v is None else [num(v[0] * scale.get(k, (k, 1.0))[1]), num(v[1] * scale.get(k, (k, 1.0))[1])]
        )
        for k, v in law.ci95.items()
    }
    return {
        "params": params,
        "se": se,
        "ci95": ci,
        "dof": law.dof,
        "fixed": list(law.fixed),
        "rss_kPa2": num(law.rss / 1e6),
        "aicc": num(ic["aicc"]),
        "bic": num(ic["bic"]),
        "n": law.n,
        "converged": law.converged,
        # parameters the tests cannot determine: their se and ci95 are null (never a zero-width interval)
        "not_identifiable": [scale.get(k, (k, 1.0))[0] for k in law.unidentified],
    }


def _ranking_dict(r) -> dict:
    def kpa(pair):
        return None if pair is None else [num(pair[0] / 1e3), num(pair[1] / 1e3)]

    from ..fitting.comparison import difference_resolution

    res = difference_resolution(r.difference_ci)
    return {
        "replicates": r.replicates,
        "replicates_requested": r.requested,
        "seed": r.seed,
        "best_model_probability": r.probability,
        "rmse_ci95_kPa": {m: kpa(v) for m, v in r.rmse_ci.items()},
        "best": r.best,
        "runner_up": r.runner_up,
        "rmse_difference_ci95_kPa": kpa(r.difference_ci),
        "rmse_difference_resolution_kPa": None if res is None else num(res / 1e3),
    }


def envelope_numbers(fit) -> EnvelopeNumbers:
    """The numbers of a fitted envelope in their output units (kPa, deg), as declared by EnvelopeNumbers.

    Parameters
    ----------
    fit : capred.fitting.linear.LineFit or an envelope fit holding one
        The fitted straight envelope tau = c + sigma_N tan(phi) (SI units; :func:`capred.pipelines.shear_fits.line_of`).

    Returns
    -------
    EnvelopeNumbers
        c [kPa], phi [deg], tan(phi), their standard errors and 95 % intervals, R², n and the fit's error model.
    """
    fit = line_of(fit)
    slope = np.float64(fit.slope)  # numpy arithmetic: an absurd input overflows to inf (null in JSON), no exception
    phi = np.degrees(np.arctan(slope))
    # delta method: d(phi)/d(tan phi) = 1 / (1 + tan^2 phi)
    with np.errstate(over="ignore", invalid="ignore"):
        phi_se = np.degrees(fit.slope_se / (1.0 + slope**2))
    lo, hi = fit.slope_ci
    c_lo, c_hi = fit.intercept_ci
    kpa = 1 / nom.QUANTITIES["c"].factor  # Pa per kPa
    return EnvelopeNumbers(
        c=fit.intercept / kpa,
        phi=phi,
        tan_phi=fit.slope,
        c_se=fit.intercept_se / kpa,
        phi_se=phi_se,
        tan_phi_se=fit.slope_se,
        c_ci=(c_lo / kpa, c_hi / kpa),
        phi_ci=(np.degrees(np.arctan(lo)), np.degrees(np.arctan(hi))),
        r2=fit.r2,
        n=fit.n,
        errors=fit.errors,
        loss=fit.loss,
        scatter=np.sqrt(fit.residual_variance) / kpa if fit.dof > 0 else math.nan,
        outliers=_outliers(fit),
    )


def _fit_dict(fit) -> dict:
    """The JSON object of a fitted envelope: :func:`envelope_numbers` through its declarations (record_json)."""
    return record_json(envelope_numbers(fit))


def _outliers(fit: LineFit) -> list[dict]:
    """The dry tests flagged as outliers: file line, externally studentized residual, Cook's distance."""
    diag = fit.diagnostics or {}
    out = []
    for k in np.flatnonzero(np.asarray(diag.get("outlier", []), bool)):
        out.append(
            {
                "line": int(diag["lines"][k]) if "lines" in diag else None,
                "test_id": str(diag["test_ids"][k]) if "test_ids" in diag else None,
                "studentized_residual": num(diag["studentized"][k]),
                "cooks_distance": num(diag["cooks"][k]),
                "threshold": num(diag["threshold"]),
            }
        )
    return out


def _json_ready(v):
    """Plain JSON values of a nested dict of test results (numpy scalars as numbers, NaN as None)."""
    if isinstance(v, dict):
        return {str(k): _json_ready(x) for k, x in v.items()}
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, float, np.integer, np.floating)):
        return num(v)
    return v


def _metric_dict(m: ModelMetrics) -> dict:
    return record_json(m)


def model_metrics(predicted, measured) -> ModelMetrics:
    """RMSE, bias (mean of predicted - measured) and R^2 = 1 - SS_res/SS_tot.

    Tests without a prediction (NaN, e.g. no concave bridge for exact_neck) are
    left out; ``n`` counts the tests used.

    Parameters
    ----------
    predicted : array_like
        Predicted shear strength per test [Pa] (NaN: no prediction).
    measured : array_like
        Measured shear strength per test [Pa].

    Returns
    -------
    ModelMetrics
        n [-], rmse [Pa], bias [Pa] and r2 [-] (NaN where undefined).
    """
    p = np.asarray(predicted, dtype=float)
    y = np.asarray(measured, dtype=float)
    keep = np.isfinite(p)
    p, y = p[keep], y[keep]
    r = p - y
    tss = float(np.sum((y - y.mean()) ** 2)) if y.size else 0.0
    r2 = 1.0 - float(r @ r) / tss if tss > 0 else float("nan")
    if y.size == 0:
        return ModelMetrics(0, float("nan"), float("nan"), float("nan"))
    return ModelMetrics(int(y.size), float(np.sqrt(np.mean(r**2))), float(np.mean(r)), r2)


def best_of(metrics: dict[str, ModelMetrics]) -> str | None:
    """Model with the lowest RMSE among those `compared` on the same tests.

    None when there is nothing to compare.

    Parameters
    ----------
    metrics : dict
        Model name -> ModelMetrics.

    Returns
    -------
    str or None
        The model's name.
    """
    inside, _ = compared(metrics)
    scored = {m: metrics[m].si.rmse for m in inside if np.isfinite(metrics[m].si.rmse)}
    return min(scored, key=scored.get) if scored else None


#: options that fill a column's blanks (column -> ShearOptions field)
ROW_DEFAULT_OPTIONS = {"box_area": "box_area", "V_v": "void_volume", "cap_mass": "cap_mass", "R": "radius"}


def unused_row_options(table: Table, opt: ShearOptions) -> list[str]:
    """Warnings for the options given to fill a column's blanks where every row has its own value.

    The option changes nothing, and a user who gave it should know (report.html lists it among the options in force).

    Parameters
    ----------
    table : Table
        The whole shear table read.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    list of str
        One warning per such option.
    """
    out = []
    for column, name in ROW_DEFAULT_OPTIONS.items():
        if getattr(opt, name) is None or column not in table.columns or not len(table):
            continue
        if not np.isnan(table.get(column)).any():
            out.append(
                f"{opt.option_name(name)} is not used: every row gives its own '{column}' (the option fills "
                "only blank cells)"
            )
    return out


def filled_column(table: Table, name: str, option: float | None) -> np.ndarray:
    """Column values with blanks (or an absent column) filled from an option.

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    name : str
        The column.
    option : float or None
        The option's value (SI) filling blanks; None fills nothing.

    Returns
    -------
    ndarray
        The column (SI), NaN where blank and no option is given.

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    v = table.get(name).copy()
    if option is not None:
        v[np.isnan(v)] = option
    return v


def _void_volume(table: Table, opt: ShearOptions, box: np.ndarray) -> np.ndarray:
    """V_v per row [m^3]: the column (or --void-volume), else from a void ratio and the sample height.

    A h e/(1 + e) from a void ratio e and the sample height, with e = G_s rho_w / rho_d - 1 from a dry density.
    """
    from .sample_state import table_state

    table_state(table, opt.rho_w, ("e", "rho_d", "G_s"))  # e, rho_d and G_s of a row must agree (phase relations)
    v_v = filled_column(table, "V_v", opt.void_volume)
    e = table.get("e").copy()
    from_density = np.isnan(e) & np.isfinite(table.get("rho_d"))
    e[from_density] = (table.get("G_s") * opt.rho_w / table.get("rho_d"))[from_density] - 1.0
    for i in np.flatnonzero(from_density & ~np.isfinite(e)):
        table.add_problem(i, "rho_d", "a dry density needs 'G_s' (specific gravity of the solids) to give e")
    for i in np.flatnonzero(from_density & (e <= 0)):
        table.add_problem(i, "rho_d", f"e = G_s rho_w/rho_d - 1 = {e[i]:.4g} is not positive: check rho_d and G_s")
    height = table.get("height")
    from_e = np.isnan(v_v) & np.isfinite(e)
    with np.errstate(invalid="ignore"):
        v_v[from_e] = (box * height * e / (1.0 + e))[from_e]
    for i in np.flatnonzero(from_e & np.isnan(v_v)):
        table.add_problem(
            i,
            "e" if "e" in table.columns else "rho_d",
            "V_v from the void ratio needs the sample 'height' and the box area",
        )
    return v_v


@dataclass
class _DerivedColumns:
    """The per-test arrays :func:`derive_tests` builds [SI], with the inputs its check of missing values names."""

    wet: np.ndarray
    cap: np.ndarray
    added: np.ndarray
    box: np.ndarray
    radius: np.ndarray
    sigma_N: np.ndarray
    tau: np.ndarray
    suction: np.ndarray
    S_R: np.ndarray
    from_burette: np.ndarray


def _report_missing(table: Table, opt: ShearOptions, cols: _DerivedColumns, with_curves: bool) -> None:
    """A problem for every value that cannot be derived, and for a burette's S_R outside [0, 1].

    Unless its cause is already reported: a bad cell on the line, an absent column.
    """
    n = len(table)
    bad_lines = {p.line for p in table.problems}

    def missing(i: int, what: str, column: str | None) -> None:
        """A value that cannot be derived.

        Reported unless its cause is already (a bad cell on the line, an absent column).
        """
        if table.missing or int(table.lines[i]) in bad_lines:
            return
        table.add_problem(i, column, what)

    wet, cap, added, box, sigma_N, tau, suction, S_R = (
        cols.wet,
        cols.cap,
        cols.added,
        cols.box,
        cols.sigma_N,
        cols.tau,
        cols.suction,
        cols.S_R,
    )
    # only rows with something missing or out of range need a look (the rest are fine)
    # R is required only by the models that read it (issue 41.5): Own 2's chi2 and the exact bridge
    by_radius = [esm.REGISTRY[m].label for m in opt.models if esm.REGISTRY[m].uses_radius]
    no_radius = np.isnan(cols.radius) if by_radius else np.zeros(n, bool)
    look = (
        np.isnan(sigma_N)
        | np.isnan(tau)
        | (wet & (np.isnan(suction) | np.isnan(S_R) | no_radius | (cols.from_burette & ((S_R < 0) | (S_R > 1)))))
    )
    for i in np.flatnonzero(look):
        if np.isnan(sigma_N[i]):
            parts = [
                c for c, v in (("added_mass", added[i]), ("cap_mass", cap[i]), ("box_area", box[i])) if np.isnan(v)
            ]
            col = parts[0] if parts and parts[0] in table.columns else None
            missing(
                i,
                "no normal stress: give 'sigma_N', or 'added_mass' with 'cap_mass' and 'box_area' "
                f"(missing here: {', '.join(parts)}; cap mass and box area may come from "
                "--cap-mass and --box-area)",
                col,
            )
        if np.isnan(tau[i]):
            col = "tau_max" if "tau_max" in table.columns else None
            missing(
                i,
                "no shear strength: give 'tau_max', or 'F_max' with 'box_area'"
                + (", or a curve for this test" if with_curves else ""),
                col,
            )
        if not wet[i]:
            continue
        if np.isnan(suction[i]):
            col = "z1" if "z1" in table.columns else None
            missing(i, "wet test without suction: give 'suction' or the head 'z1'", col)
        if np.isnan(S_R[i]):
            col = "z2" if "z2" in table.columns else None
            missing(i, "wet test without S_R: give 'S_R', or 'z2' with 'V_v' (or --void-volume)", col)
        elif cols.from_burette[i] and not 0.0 <= S_R[i] <= 1.0:
            table.add_problem(
                i,
                "z2",
                f"S_R = (V_v - z2)/V_v = {S_R[i]:.4g} lies outside [0, 1]: "
                f"z2 = {table.value_text('z2', i)} exceeds V_v",
            )
        if no_radius[i]:
            col = "R" if "R" in table.columns else None
            missing(
                i,
                f"wet test without particle radius: give 'R' or --radius (needed by {', '.join(by_radius)})",
                col,
            )


def derive_tests(
    table: Table, opt: ShearOptions, box: np.ndarray, tau_curve: np.ndarray | None = None
) -> dict[str, np.ndarray]:
    """sigma_N, suction, S_R and tau_max per row; problems go into ``table``.

    ``tau_curve`` is the peak of each test's raw curve (NaN where it has none); it wins over tau_max.

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    opt : ShearOptions
        The run's options.
    box : ndarray
        Box area of each test [m^2].
    tau_curve : ndarray, optional
        Peak shear stress of each test's raw curve [Pa].

    Returns
    -------
    dict of str to ndarray
        The derived per-test arrays (SI).

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    n = len(table)
    cond = table.columns.get("condition", np.array([""] * n, dtype=object))
    wet = cond == "wet"
    cap = filled_column(table, "cap_mass", opt.cap_mass)
    added = table.get("added_mass")
    radius = filled_column(table, "R", opt.radius)
    v_v = _void_volume(table, opt, box)

    sigma_N = table.get("sigma_N").copy()
    from_masses = np.isnan(sigma_N)
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is the bound's error below, not numpy's
        sigma_N[from_masses] = ph.normal_stress(cap + added, box, opt.g)[from_masses]
    _bound_derived(table, sigma_N, from_masses, "sigma_N", ("added_mass", "cap_mass", "box_area"))

    tau = table.get("tau_max").copy()
    from_force = np.isnan(tau)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        tau[from_force] = (table.get("F_max") / box)[from_force]
    _bound_derived(table, tau, from_force, "tau_max", ("F_max", "box_area"))
    if tau_curve is not None:
        has_curve = np.isfinite(tau_curve)
        tau[has_curve] = tau_curve[has_curve]

    suction = table.get("suction").copy()
    from_head = np.isnan(suction)
    z1 = table.get("z1")
    suction[from_head] = ph.suction_from_head(z1, opt.gamma_w)[from_head]
    z_max = ph.cavitation_head(opt.gamma_w, opt.ambient_pressure)
    for i in np.flatnonzero(wet & from_head & (z1 > z_max)):
        table.add_problem(
            i,
            "z1",
            f"a hanging-column head of {z1[i]:.4g} m is impossible: above "
            f"{z_max:.3g} m the water at the sample would fall below its vapour pressure "
            f"(20 °C, ambient {opt.ambient_pressure / 1e3:.5g} kPa) and cavitate; if the "
            "suction was measured another way, give it in a 'suction' column",
        )

    S_R = table.get("S_R").copy()
    from_burette = np.isnan(S_R)
    z2 = table.get("z2")
    S_R[from_burette] = ph.degree_of_saturation(z2, v_v)[from_burette]

    columns = _DerivedColumns(wet, cap, added, box, radius, sigma_N, tau, suction, S_R, from_burette)
    _report_missing(table, opt, columns, tau_curve is not None)
    suction = np.where(wet, suction, 0.0)
    S_R = np.where(wet, S_R, np.where(cond == "saturated", 1.0, 0.0))  # a saturated test: S_R = 1, no suction
    return {"sigma_N": sigma_N, "suction": suction, "S_R": S_R, "tau_max": tau, "R": radius}


def load_shear_table(source, with_curves: bool = False) -> Table:
    """The tests table with its required columns checked (problems collected, not raised).

    Parameters
    ----------
    source : str or Path or DataFrame
        The direct-shear tests table.
    with_curves : bool, optional
        Raw curves are given: tau or sigma_N may come from them.

    Returns
    -------
    Table
        The table read, its problems in ``table.problems``.
    """
    table = read_table(source, SCHEMA)
    check_shear_table(table, with_curves)
    return table


def check_shear_table(table: Table, with_curves: bool = False, unique: bool = True) -> None:
    """The checks of load_shear_table on a table read (``unique``: also blank and repeated test ids).

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    with_curves : bool, optional
        The table comes with raw curves.
    unique : bool, optional
        Also check blank and repeated test ids.

    Returns
    -------
    None

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    for name in ("test_id", "condition"):
        if name not in table.columns:
            table.missing_column(name)
    if "tau_max" not in table.columns and "F_max" not in table.columns and not with_curves:
        table.missing_column("tau_max", " (or 'F_max', or raw curves with --curves)")
    if "sigma_N" not in table.columns and "added_mass" not in table.columns:
        table.missing_column("added_mass", " (or 'sigma_N')")
    if "condition" in table.columns and np.any(table.columns["condition"] == "wet"):
        if "suction" not in table.columns and "z1" not in table.columns:
            table.missing_column("z1", " (or 'suction'), needed by the wet tests")
        if "S_R" not in table.columns and "z2" not in table.columns:
            table.missing_column("z2", " (or 'S_R'), needed by the wet tests")
    if "material" not in table.columns:
        table.columns["material"] = np.array(["(all)"] * len(table), dtype=object)
        table.notes.append("no 'material' column: all tests treated as one material")
    if unique and "test_id" in table.columns:
        table.check_unique("test_id")


def run_table(source, opt: ShearOptions, table: Table | None = None) -> ShearResult:
    """`capred shear` on a table held whole: derive, fit the dry envelopes, predict and score every model.

    What :func:`capred.pipelines.shear_run.run_shear` does with a table of one block, or with raw curves;
    raises InputError (every problem in the file, each with line and column), OptionError or FitError.

    Parameters
    ----------
    source : str or Path or DataFrame
        The direct-shear tests (one row per test), as the user gave them.
    opt : ShearOptions
        Constants, per-test defaults, models and fitting choices (SI).
    table : capred.io.Table or None, optional
        The table already read from ``source`` (its one block); None: read here (with ``opt.curves``).

    Returns
    -------
    ShearResult
        The dry envelopes, each model's predictions and scores, the ranking and the back-analysis.

    References
    ----------
    .. [1] Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular
       materials. Master thesis, Vrije Universiteit Brussel.
    """
    if table is None:
        table = load_shear_table(source, opt.curves is not None)
    else:
        check_shear_table(table)
    table.warnings += unused_row_options(table, opt)
    box = filled_column(table, "box_area", opt.box_area)
    curves = None
    if opt.curves is not None:
        from .shear_curves import pick_peaks

        # --ignore-column applies to every file the command reads; a name no file has is warned about once
        curves = pick_peaks(opt.curves, table, box, opt.area_correction, getattr(source, "ignore_columns", ()))
        table.forget_ignores(curves.table.ignores_used)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):  # NaN and overflow are reported below
        d = derive_tests(table, opt, box, curves.tau_peak if curves else None)
    if curves is not None and opt.area_correction != "none":
        # sigma_N on the corrected area at the peak, as tau (ASTM D3080 / BS 1377-7 practice)
        d["sigma_N"] = d["sigma_N"] * curves.area_ratio_at_peak
        table.notes.append(
            f"--area-correction {opt.area_correction}: tau and sigma_N of the tests with a curve are "
            "taken on the corrected contact area at the peak (ASTM D3080, BS 1377-7)"
        )
    if curves is not None:
        table.problems += curves.problems
    table.raise_if_problems()  # every problem of the file (and of the curves) at once
    if "condition" in table.columns and not np.any(table.columns["condition"] == "wet"):
        table.notes.append("no wet tests in the file: the dry envelope alone (no effective-stress model is compared)")

    materials = list(dict.fromkeys(table.columns["material"]))
    mat = table.columns["material"]
    cond = table.columns["condition"]
    wet = cond == "wet"
    fits = fit_dry_envelopes(table, d, mat, cond, materials, opt)
    saturated_fits = fit_saturated_envelopes(table, d, mat, cond, materials, opt)
    table.raise_if_problems()

    read = {f"in_{name}": documented_column(table, name) for name in RAW_INPUTS if name in table.columns}
    tests: dict[str, np.ndarray] = {
        "test_id": table.columns["test_id"],
        "material": mat,
        "condition": cond,
        "line": table.lines,
        **read,
        **d,
        "chi1": np.where(wet, ph.chi1(d["S_R"]), 0.0),
        "chi2": np.where(wet, ph.chi2(d["S_R"], d["R"], opt.surface_tension), 0.0),
    }
    predictions, back, per_material, laws, model_inputs = _predict(tests, wet, mat, fits, opt, saturated_fits)
    scored = score_models(d, wet, mat, fits, laws, predictions, opt)
    metrics, overall = scored["metrics"], scored["overall"]
    if curves is not None:
        tests.update(curves.per_test())
    warnings = list(opt.warnings) + table.warnings + (curves.warnings if curves else []) + scored["warnings"]
    result = ShearResult(
        source=table.path,
        options=opt,
        tests=tests,
        fits=envelope_fits(fits, table.path),
        metrics=metrics,
        metrics_overall=overall,
        best_model={m: best_of(v) for m, v in metrics.items()},
        best_model_overall=best_of(overall),
        notes=opt.notes + table.notes,
        per_material=per_material,
        inputs=[input_file(source, table)] + ([input_file(opt.curves, curves.table)] if curves else []),
        warnings=warnings,
        metrics_pendular=scored["pendular"],
        metrics_pendular_overall=scored["overall_pendular"],
        laws=laws,
        model_inputs=model_inputs,
        curves=curves,
        predictions=predictions,
        back=back,
        saturated_fits=saturated_fits,
        heteroscedasticity=scored["heteroscedasticity"],
    )
    if opt.bootstrap > 0:
        result.ranking = bootstrap_materials(result, wet, mat, cond, opt)
    return result


def score_models(d: dict, wet, mat, fits, laws, predictions, opt: ShearOptions) -> dict:
    """Metrics of every model per material and overall, on all wet tests and on the pendular ones; warnings.

    Parameters
    ----------
    d : dict of str to ndarray
        The derived per-test arrays (`derive_tests`).
    wet, mat : ndarray
        Per test: whether it is a wet test, and its material.
    fits : dict of str to LineFit
        Each material's dry envelope.
    laws : dict
        The fitted chi laws per model and material.
    predictions : dict of str to ModelPrediction
        Each model's predictions.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    dict
        ``metrics``, ``metrics_pendular``, ``heteroscedasticity`` and ``warnings``.

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    pend = wet & (d["S_R"] <= opt.pendular_limit)
    of_material = {m: mat == m for m in fits}

    def scores(sel):
        out = {}
        for m in fits:
            rows = np.flatnonzero(of_material[m] & sel)
            if rows.size:
                out[m] = {mod: model_metrics(predictions[mod].si.tau[rows], d["tau_max"][rows]) for mod in opt.models}
        return out

    metrics, metrics_pend = scores(wet), scores(pend)
    for m in fits:
        metrics.setdefault(m, {})
    hetero = _heteroscedasticity(d, wet, of_material, fits, predictions, opt)
    overall = (
        {mod: model_metrics(predictions[mod].si.tau[wet], d["tau_max"][wet]) for mod in opt.models} if wet.any() else {}
    )
    overall_pend = (
        {mod: model_metrics(predictions[mod].si.tau[pend], d["tau_max"][pend]) for mod in opt.models}
        if pend.any()
        else {}
    )
    return {
        "metrics": metrics,
        "pendular": metrics_pend,
        "overall": overall,
        "overall_pendular": overall_pend,
        "warnings": run_warnings(wet, pend, mat, fits, laws, predictions, opt) + _scatter_warnings(fits, hetero),
        "heteroscedasticity": hetero,
    }


def _heteroscedasticity(d: dict, wet, of_material: dict, fits, predictions, opt: ShearOptions) -> dict:
    """Per material: the Breusch-Pagan tests of the residuals against sigma_N, and the error model used.

    Of the dry fit's least-squares residuals and of each model's wet residuals (capred.fitting.linear.breusch_pagan).
    """
    out = {}
    for m, fit in fits.items():
        rows = np.flatnonzero(of_material[m] & wet)
        models = {}
        for mod in opt.models:
            r = predictions[mod].si.tau[rows] - d["tau_max"][rows]
            ok = np.isfinite(r)
            scale = float(np.max(np.abs(d["tau_max"][rows]), initial=0.0))
            models[mod] = breusch_pagan(d["sigma_N"][rows][ok], r[ok], scale)
        out[m] = {
            "dry_fit": fit.heteroscedasticity,
            "errors": fit.errors,
            "errors_option": opt.errors,
            "models": models,
        }
    return out


def _scatter_warnings(fits, hetero: dict) -> list[str]:
    """Scatter growing with stress (dry fit, models) and outlying dry tests, one line each."""
    out = []
    for m, fit in fits.items():
        bp = fit.heteroscedasticity or {}
        if bp.get("significant"):
            used = (
                "the intervals use proportional errors (weighted least squares)"
                if fit.errors == "proportional"
                else "the intervals hold under constant and under proportional scatter (--errors either)"
                if fit.errors == "either"
                else "the intervals assume a constant scatter (--errors constant): use --errors proportional"
            )
            out.append(
                f"material '{m}': the scatter of the dry tests grows with sigma_N (Breusch-Pagan "
                f"LM = {bp['statistic']:.3g}, p = {bp['p_value']:.3g}); {used}"
            )
        grows = [mod for mod, t in hetero.get(m, {}).get("models", {}).items() if t.get("significant")]
        if grows:
            out.append(
                f"material '{m}': the wet residuals of {', '.join(grows)} grow with sigma_N (Breusch-Pagan p < 0.05): "
                "scatter growing with stress, or a model that misses a trend"
            )
        diag = fit.diagnostics or {}
        for k in np.flatnonzero(diag.get("outlier", [])):
            line = int(diag["lines"][k]) if "lines" in diag else None
            where = f"the dry test on line {line}" if line is not None else f"dry test {k + 1}"
            if "test_ids" in diag:
                where = f"the dry test '{diag['test_ids'][k]}'" + (f" (line {line})" if line is not None else "")
            cure = (
                f"--dry-loss {fit.loss} bounds its weight"
                if fit.loss != "ols"
                else "it drives the envelope and its intervals: check it, or fit with --dry-loss huber"
            )
            out.append(
                f"material '{m}': {where} is an outlier of the dry envelope (externally studentized residual "
                f"{diag['studentized'][k]:.3g}, beyond ±{diag['threshold']:.3g}, the Bonferroni 5 % limit); {cure}"
            )
    return out


def documented_column(table: Table, name: str) -> np.ndarray:
    """A column in its documented unit: the numbers as typed when the file uses that unit, else converted.

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    name : str
        The column.

    Returns
    -------
    ndarray

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    from ..units import conversion

    q = nom.QUANTITIES.get(name)
    if q is None:
        return table.columns[name]
    try:
        same = conversion(table.units.get(name, q.unit), q.kind)[0] == conversion(q.unit, q.kind)[0]
    except Exception:
        same = False
    return table.as_read[name] if same and name in table.as_read else table.columns[name] * q.factor


def run_warnings(wet, pend, mat, fits, laws, predictions, opt) -> list[str]:
    """The run's warnings on its wet tests, fits and predictions (implausible values, models left out).

    Parameters
    ----------
    wet, pend, mat : ndarray
        Per test: whether it is wet, whether pendular, and its material.
    fits : dict of str to LineFit
        Each material's dry envelope.
    laws : dict
        The fitted chi laws per model and material.
    predictions : dict of str to ModelPrediction
        Each model's predictions.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    list of str

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    out = []
    n_wet, n_pend = int(wet.sum()), int(pend.sum())
    if n_wet and n_wet - n_pend > n_wet / 2:
        out.append(
            f"{n_wet - n_pend} of {n_wet} wet tests lie outside the pendular regime (S_R > "
            f"{opt.pendular_limit:g}) for which the chi approximations were derived; see metrics_pendular "
            f"({n_pend} tests)"
        )
    for m, fit in fits.items():
        k = int(np.sum(wet & (mat == m)))
        if 0 < k < 5:
            out.append(f"material '{m}': the model ranking rests on {k} wet tests (fewer than 5)")
        phi = float(np.degrees(np.arctan(fit.slope)))
        if not 15.0 <= phi <= 60.0:
            out.append(
                f"material '{m}': the dry fit gives phi = {phi:.3g}°, outside the usual 15-60° of soils; "
                "check the normal stresses and their units"
            )
        if fit.intercept < 0:
            out.append(
                f"material '{m}': the dry fit gives c = {fit.intercept / 1e3:.4g} kPa < 0 "
                "(try --dry-fit origin for a cohesionless soil)"
            )
        if fit.r2 < 0.9:
            out.append(f"material '{m}': the dry fit has R² = {fit.r2:.3g} < 0.9")
        if fit.n < 5:
            out.append(f"material '{m}': the dry envelope rests on {fit.n} dry tests (fewer than 5)")
    for model, by_mat in laws.items():
        for m, law in by_mat.items():
            for text in law.identifiability:
                out.append(f"material '{m}': fitted {model}: {text}")
            for name in law.at_bound:
                out.append(
                    f"material '{m}': fitted {model} parameter '{name}' = {law.values[name]:.6g} lies at its bound"
                )
    for model in opt.models:
        flag = esm.REGISTRY[model].no_prediction
        k = int(np.sum(wet & ~np.isfinite(predictions[model].si.tau))) if flag else 0
        if k:
            out.append(
                f"{model}: {k} wet tests {flag.meaning} (flag {flag.name}) and are left out of its metrics; it is "
                "not ranked against models scored on every wet test (listed apart, with the count it lacks)"
            )
    return out


def bootstrap_materials(result: ShearResult, wet, mat, cond, opt: ShearOptions) -> dict:
    """Ranking uncertainty per material (see capred.pipelines.shear_analysis.bootstrap_ranking).

    Parameters
    ----------
    result : ShearResult
        The run (its inputs, fits, laws and ranking).
    wet, mat : ndarray
        Per test: whether it is a wet test, and its material.
    cond : ndarray
        Condition of each test.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    dict of str to RankingUncertainty

    References
    ----------
    Efron & Tibshirani (1993), doi:10.1007/978-1-4899-4541-9, ch. 9.
    """
    from . import shear_analysis as sa

    t = result.tests
    out = {}
    d = result.model_inputs
    for m in steps(list(result.fits), "ranking bootstrap, material by material"):
        sel = wet & (mat == m)
        if not sel.any():
            continue
        dry = (mat == m) & (cond == "dry")
        inside, _ = compared(result.metrics[m])  # only models scored on the same wet tests (issue 41.2)
        ranked = sorted(
            (k for k in inside if np.isfinite(result.metrics[m][k].si.rmse)),
            key=lambda k: result.metrics[m][k].si.rmse,
        )
        out[m] = sa.bootstrap_ranking(
            d,
            t["sigma_N"][dry],
            t["tau_max"][dry],
            [k for k in opt.models if k in inside],
            opt.model_params,
            d.fitted,
            ranked,
            opt.bootstrap,
            opt.seed,
            opt.dry_fit == "origin",
            rows=sel,
            errors=line_of(result.fits[m]).errors,  # the run's error model and loss (issue 41.4)
            loss=line_of(result.fits[m]).loss,
            scale=line_of(result.fits[m]).scale,
            adaptive=True,  # stop once the printed numbers are resolved, at most opt.bootstrap (issue 44.2)
        )
    return out


def fit_dry_envelopes(table, d: dict, mat, cond, materials, opt: ShearOptions) -> dict[str, LineFit]:
    """Per material, the dry envelope tau = c + sigma_N tan(phi).

    Through the origin with ``dry_fit='origin'``; a material without dry tests, or whose fit is impossible, is a problem
    of its first row in ``table``.

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    d : dict of str to ndarray
        The derived per-test arrays.
    mat, cond : ndarray
        Material and condition of each test.
    materials : list of str
        The materials.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    dict of str to LineFit

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    fits: dict[str, LineFit] = {}
    for m in materials:
        of_m = mat == m
        dry = of_m & (cond == "dry")
        first = int(np.argmax(of_m))
        if not dry.any():
            table.add_problem(
                first, "condition", f"material '{m}' has no dry test: its envelope c, phi cannot be fitted"
            )
            continue
        try:
            fits[m] = fit_envelope(
                d["sigma_N"][dry], d["tau_max"][dry], opt.confidence, opt.dry_fit == "origin", opt.errors, opt.dry_loss
            )
        except FitError as exc:
            table.add_problem(first, "condition", f"material '{m}': dry fit impossible: {exc}")
            continue
        rows = np.flatnonzero(dry)  # where each dry point lies in the table (flags, warnings)
        fits[m].diagnostics.update(rows=rows, lines=np.asarray(table.lines)[rows])
        ids = getattr(table, "columns", {}).get("test_id")
        if ids is not None:  # an outlier is named by the id the lab gave it, not only by its line
            fits[m].diagnostics["test_ids"] = np.asarray(ids, dtype=object)[rows]
    return fits


def fit_saturated_envelopes(table: Table, d: dict, mat, cond, materials, opt: ShearOptions) -> dict[str, LineFit]:
    """Per material, the envelope tau = c_W + sigma_N tan(phi_W) of its saturated tests.

    Clay reconstituted from slurry and sheared saturated, drained: sigma'_W = sigma_N; the tau^W envelope of Pedrotti &
    Tarantino (submitted), eq. 13; problems go into ``table``.

    Parameters
    ----------
    table : Table
        The shear table read (its problems are collected there).
    d : dict of str to ndarray
        The derived per-test arrays.
    mat, cond : ndarray
        Material and condition of each test.
    materials : list of str
        The materials.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    dict of str to LineFit

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 13.
    """
    out: dict[str, LineFit] = {}
    for m in materials:
        sat = (mat == m) & (cond == "saturated")
        if not sat.any():
            continue
        try:  # the same error model and loss as the dry envelope (tested, flagged, reported alike)
            out[m] = fit_envelope(d["sigma_N"][sat], d["tau_max"][sat], opt.confidence, False, opt.errors, opt.dry_loss)
            rows = np.flatnonzero(sat)
            out[m].diagnostics.update(rows=rows, lines=np.asarray(table.lines)[rows])
        except FitError as exc:
            table.add_problem(
                int(np.flatnonzero(sat)[0]),
                "condition",
                f"material '{m}': the envelope of the saturated tests cannot be fitted: {exc}",
            )
    return out


def _predict(tests: dict, wet, mat, fits: dict[str, LineFit], opt: ShearOptions, saturated_fits=None):
    """Per test and model: sigma'_N, tau_pred and its bands, the predicted capillary stress.

    sigma'_N is NaN where a model predicts tau directly; and the back-analysed capillary stress of the wet tests.

    Returns the ModelPrediction of each model, the BackAnalysis, what models report per material (Fredlund's
    phi_b), the fitted chi laws and the ModelInputs.
    """
    from . import shear_analysis as sa

    d = model_inputs_of(tests, wet, mat, fits, opt, saturated_fits)
    laws = sa.fit_laws(d, opt.models, list(fits), opt.model_params, fits=fits)
    d = dataclasses.replace(
        d, fitted={model: {m: law.values for m, law in by_mat.items()} for model, by_mat in laws.items()}
    )
    predictions, back = predict_models(tests, wet, d, fits, laws, opt)
    return predictions, back, values_by_material(d, wet, mat, fits, opt), laws, d


def model_inputs_of(tests: dict, wet, mat, fits: dict[str, LineFit], opt: ShearOptions, saturated_fits=None):
    """The esm.ModelInputs of every test: its state and its material's dry (and saturated) envelope.

    Parameters
    ----------
    tests : dict of str to ndarray
        The derived per-test arrays.
    wet, mat : ndarray
        Per test: whether it is a wet test, and its material.
    fits : dict of str to LineFit
        Each material's dry envelope.
    opt : ShearOptions
        The run's options.
    saturated_fits : dict of str to LineFit, optional
        Each material's saturated envelope.

    Returns
    -------
    ModelInputs

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    names = list(fits)
    saturated_fits = saturated_fits or {}
    if len(mat) > 10_000:  # a long table: by material code (a Python list of a million floats is ~30 MB)
        which = _codes(mat, names)
        pad = lambda v: np.append(np.asarray(v, dtype=float), np.nan)[which]  # noqa: E731
        c, tan_phi = pad([fits[m].intercept for m in names]), pad([fits[m].slope for m in names])
        # no saturated envelope at all: None, which every model reads as NaN everywhere (16 bytes a test less)
        c_sat = (
            pad([saturated_fits[m].intercept if m in saturated_fits else np.nan for m in names])
            if saturated_fits
            else None
        )
        tan_phi_sat = (
            pad([saturated_fits[m].slope if m in saturated_fits else np.nan for m in names]) if saturated_fits else None
        )
    else:
        c = np.array([fits[m].intercept for m in mat])
        tan_phi = np.array([fits[m].slope for m in mat])
        c_sat = np.array([saturated_fits[m].intercept if m in saturated_fits else np.nan for m in mat])
        tan_phi_sat = np.array([saturated_fits[m].slope if m in saturated_fits else np.nan for m in mat])
    return esm.ModelInputs(
        tests["sigma_N"],
        tests["suction"],
        tests["S_R"],
        tests["R"],
        tests["tau_max"],
        wet,
        mat,
        c,
        tan_phi,
        opt.surface_tension,
        opt.model_params,
        c_sat=c_sat,
        tan_phi_sat=tan_phi_sat,
    )


def _codes(values, names: list) -> np.ndarray:
    """Index of each value in ``names`` (len(names) where absent), without a Python object per row."""
    out = np.full(len(values), len(names), dtype=np.int16)
    for k, name in enumerate(names):
        out[values == name] = k
    return out


def predict_models(tests: dict, wet, d, fits: dict[str, LineFit], laws: dict, opt: ShearOptions):
    """Each model's ModelPrediction and the BackAnalysis of the tests of ``d`` (rows of ``tests``).

    Parameters
    ----------
    tests : dict of str to ndarray
        The derived per-test arrays.
    wet : ndarray of bool
        Which tests are wet.
    d : ModelInputs
        The tests predicted.
    fits : dict of str to LineFit
        Each material's dry envelope.
    laws : dict
        The fitted chi laws per model and material.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    (dict of str to ModelPrediction, BackAnalysis)

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    from . import shear_analysis as sa

    c, tan_phi = d.c, d.tan_phi
    cov, s2, t = sa.fit_covariances(fits, d.material)
    dof = sa.fit_dof(fits, d.material)
    predictions = {}

    def scatter(level):  # the variance of one test of expected strength ``level`` (grows with it: --errors)
        return _scatter_variance(fits, d.material, level)

    for model in opt.models:
        eff, tau = esm.predict(model, d)
        # mean band: the dry envelope's (and a fitted law's) uncertainty; prediction interval: plus one test's scatter
        b = sa.tau_bands(model, d, cov, s2, dof, laws, opt.confidence, scatter=scatter)
        predictions[model] = ModelPrediction(
            model,
            sigma_eff=eff,
            tau=tau,
            residual=tau - tests["tau_max"],
            tau_mean_ci=(b.mean_low, b.mean_high),
            tau_prediction_interval=(b.pred_low, b.pred_high),
            sigma_cap=np.where(wet, (tau - c) / tan_phi - tests["sigma_N"], np.nan),
        )
    s2_test = scatter(tests["tau_max"])  # the wet test's own scatter, at its measured strength
    back = sa.back_analysis_intervals(
        tests["tau_max"], tests["sigma_N"], tests["suction"], c, tan_phi, cov, s2_test, dof, opt.confidence, wet=wet
    )
    return predictions, back


def _scatter_variance(fits: dict[str, LineFit], material, level) -> np.ndarray:
    """Per test: s^2 v(level) of its material's dry fit (`LineFit.scatter_variance`) [Pa^2]."""
    level = np.asarray(level, dtype=float)
    out = np.full(level.shape, np.nan)
    for m, f in fits.items():
        sel = material == m
        out[sel] = f.scatter_variance(level[sel])
    return out


def values_by_material(d, wet, mat, fits: dict[str, LineFit], opt: ShearOptions) -> dict[str, dict]:
    """What a model reports per material beside the dry fit (Fredlund's phi_b), from its wet tests.

    Parameters
    ----------
    d : ModelInputs
        The tests.
    wet, mat : ndarray
        Per test: whether it is a wet test, and its material.
    fits : dict of str to LineFit
        Each material's dry envelope.
    opt : ShearOptions
        The run's options.

    Returns
    -------
    dict of str to dict

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    extra: dict[str, dict] = {}  # per material: what a model reports beside the dry fit (Fredlund's phi_b)
    for model in opt.models:
        per_material = esm.REGISTRY[model].material_values
        if per_material is None:
            continue
        for m in fits:
            sel = wet & (mat == m)
            if sel.any():
                extra.setdefault(m, {}).update(per_material(d.subset(sel)))
    return extra


def summary_table(result: ShearResult, frame: bool = True):
    """summary.csv: one row per material, its dry envelope (``name [unit]`` headers).

    A DataFrame, or with ``frame=False`` plain columns that write the same CSV without pandas. The models' scores are
    metrics.csv (`metrics_table`): one kind of record per table.

    Parameters
    ----------
    result : ShearResult
    frame : bool, optional
        A DataFrame (True) or plain columns.

    Returns
    -------
    DataFrame or dict

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    rows = []
    for mat, fit in result.fits.items():
        f = _fit_dict(fit)
        line = line_of(fit)
        envelope = {}  # the JSON's numbers under their glossary CSV headers (c [kPa], c_se [kPa], ...)
        for name in ("c", "phi", "tan_phi", "r2"):
            envelope[nom.column(name)] = f[nom.json_key(name)]
            if name != "r2":
                envelope[nom.column(name, "_se")] = f[nom.json_key(name, "_se")]
            if name in ("c", "phi"):
                low, high = f[nom.json_key(name, "_ci95")]
                envelope.update({nom.column(name, "_ci95_low"): low, nom.column(name, "_ci95_high"): high})
        rows.append(
            {
                "material": mat,
                "n_dry [-]": f["n"],
                **envelope,
                "dry_fit": "origin" if line.through_origin else "free",
                "errors": getattr(line, "errors", "constant"),
                "dry_loss": getattr(line, "loss", "ols"),
            }
        )
    return _rows_table(rows, frame)


def metrics_table(result: ShearResult, frame: bool = True):
    """metrics.csv: one row per material (and "(all)") and model: n, RMSE, bias, R² and the best flag.

    Parameters
    ----------
    result : ShearResult
    frame : bool, optional
        A DataFrame (True) or plain columns.

    Returns
    -------
    DataFrame or dict

    References
    ----------
    Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular materials,
    master thesis, Vrije Universiteit Brussel (the reduction of `capred shear`).
    """
    rows = []
    for mat, by_model in list(result.metrics.items()) + [("(all)", result.metrics_overall)]:
        best = result.best_model_overall if mat == "(all)" else result.best_model.get(mat)
        for m, met in by_model.items():
            rows.append({"material": mat, "model": m, **record_row(met), "best": m == best})
    return _rows_table(rows, frame)


def _rows_table(rows: list[dict], frame: bool):
    if not frame:
        from ..result import columns_of_rows

        return columns_of_rows(rows)
    import pandas as pd

    return pd.DataFrame(rows)


__all__ = ["SCHEMA", "ModelParams", "ShearOptions", "ShearResult", "run_table"]


def _bound_derived(table, values, derived, name: str, sources: tuple[str, ...]) -> None:
    """A stress derived from a row's masses or force gets the magnitude bound of a measured one.

    capred.nomenclature MAGNITUDES: over it, or not finite from finite inputs (an overflow), the row's problem names the
    value and the columns it came from; the value becomes NaN so nothing downstream computes with it.
    """
    from ..nomenclature import magnitude_problem

    for i in np.flatnonzero(derived & ~np.isnan(values)):
        v = float(values[i])
        why = magnitude_problem(name, v) if np.isfinite(v) else f"|{name}| overflows (beyond 1.8e308 Pa)"
        if why is None:
            continue
        given = [c for c in sources if c in table.columns]
        shown = ", ".join(f"{c} = {table.value_text(c, i)}" for c in given)
        table.add_problem(i, given[0] if given else None, f"{name} derived from {shown}: {why}")
        values[i] = np.nan
