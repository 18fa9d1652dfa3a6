"""`capred compression`: an oedometer or isotropic compression test reduced to its lines and yield stress.

Reads one row per reading: the effective stress (``sigma_eff``: vertical in an oedometer, mean p' in an isotropic
cell) and the void ratio ``e``, or the specimen ``height`` with the height of solids (``--solids-height``:
e = H/H_s - 1); an optional ``stage`` column (loading, unloading, reloading; otherwise taken from the stress
history). The first loading is fitted with a smooth bilinear curve (capred.physics.compression): the compression
index C_c (lambda = C_c/ln 10), the bilinear yield stress, and on the fitted curve the pre-consolidation stress
by Casagrande (1936) and by Pacheco Silva (1970); unloading stages give C_s (kappa = C_s/ln 10); reloading
stages C_r. Every value has its standard error and 95 % interval. The JSON (compression.json) feeds
`pt-volume --compression-w/--compression-a` and `skempton-b --compression`.

References
----------
Casagrande (1936); Pacheco Silva (1970); Schofield & Wroth (1968) for lambda and kappa in e - ln p'.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, OptionError, Problem
from ..io import read_json, read_table
from ..physics import compression as cp
from ..result import InputFile, Result, input_file, num, output
from ..spec.compression import SCHEMA, TESTS, CompressionOptions  # noqa: F401 (declared in spec; re-exported here)
from .row_records import RowRecord, plain

STAGES = ("loading", "unloading", "reloading")
_STAGE_WORDS = {"load": "loading", "l": "loading", "unload": "unloading", "u": "unloading", "reload": "reloading"}
_STAGE_WORDS.update({"r": "reloading", **{s: s for s in STAGES}})


@dataclass(frozen=True)
class CompressionReadings(RowRecord):
    """The readings, one row each (results.csv, the JSON's ``readings``).

    Attributes
    ----------
    line : ndarray of int
        Line in the file.
    stage : list of str
        loading, unloading or reloading.
    sigma : ndarray
        Effective stress [kPa].
    e : ndarray
        Void ratio [-].
    first_loading : ndarray of bool
        Reading of the first loading (fitted by the smooth bilinear curve).
    e_fitted : ndarray
        e of the fitted first-loading curve at the reading (NaN off the first loading) [-].
    """

    line: np.ndarray = plain("line")
    stage: list = plain("stage")
    sigma: np.ndarray = output("sigma_eff_kPa", "sigma_eff", "kPa")
    e: np.ndarray = output("e", "e", "")
    first_loading: np.ndarray = plain("first_loading")
    e_fitted: np.ndarray = output("e_fitted", "e_fitted", "")


@dataclass(frozen=True)
class Estimate:
    """One estimated quantity with its uncertainty.

    Attributes
    ----------
    name : str
        JSON key (``lambda``, ``kappa``, ``C_c``, ``sigma_p_casagrande_kPa`` ...).
    symbol : str
        As printed (λ, κ, C_c, σ'_p ...).
    value, se : float
        Estimate and standard error, in ``unit``.
    low, high : float
        95 % interval, in ``unit``.
    unit : str
        "" or "kPa".
    method : str
        How it was obtained.
    """

    name: str
    symbol: str
    value: float
    se: float
    low: float
    high: float
    unit: str
    method: str

    def as_json(self) -> dict:
        """The estimate as the JSON writes it.

        Returns
        -------
        dict
            ``value``, ``se``, ``ci95`` (a pair) in ``unit``, NaN as None; ``unit`` and ``method``.
        """
        return {
            "value": num(self.value),
            "se": num(self.se),
            "ci95": [num(self.low), num(self.high)],
            "unit": self.unit,
            "method": self.method,
        }


def _t95(dof: int) -> float:
    from scipy.stats import t

    return float(t.ppf(0.975, dof)) if dof > 0 else float("nan")


@dataclass(repr=False)
class CompressionResult(Result):
    """Result of `capred compression`.

    Attributes
    ----------
    source : str
        The input file.
    readings : CompressionReadings
        The readings with their stage and the fitted curve.
    fit : capred.physics.compression.FirstLoadingFit
        The smooth bilinear curve of the first loading.
    unloading : capred.physics.compression.LineFit or None
        C_s of the unloading stages (common slope, one intercept per stage).
    reloading : capred.physics.compression.LineFit or None
        C_r of the reloading stages.
    estimates : list of Estimate
        Every reported quantity (λ, κ, C_c, C_s, C_r, e_N, σ'_y, σ'_p by Casagrande and Pacheco Silva).
    e0 : float
        Initial void ratio (the first reading) [-].
    """

    command = "compression"
    json_name = "compression.json"

    source: str
    readings: CompressionReadings
    fit: cp.FirstLoadingFit
    unloading: cp.LineFit | None
    reloading: cp.LineFit | None
    estimates: list
    e0: float
    options: CompressionOptions
    notes: list[str] = field(default_factory=list)
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def estimate(self, name: str) -> Estimate | None:
        """The estimate of one quantity by its JSON key, or None.

        Parameters
        ----------
        name : str
            The JSON key (``"C_c"``, ``"kappa"``, ``"sigma_p_casagrande_kPa"``).

        Returns
        -------
        Estimate or None
        """
        return next((x for x in self.estimates if x.name == name), None)

    @property
    def stress_symbol(self) -> str:
        """The symbol of the effective stress of the test: σ'_v (oedometer) or p' (isotropic)."""
        return "σ'_v" if self.options.test == "oedometer" else "p'"

    def lines(self) -> dict:
        """What other commands take: lambda, kappa (None without unloading), e_ncl at the reference stress, e0.

        Returns
        -------
        dict
            ``lambda``, ``kappa``, ``e_ncl``, ``reference_stress_kPa``, ``e0``.
        """
        kappa = self.estimate("kappa")
        return {
            "lambda": num(self.estimate("lambda").value),
            "kappa": None if kappa is None else num(kappa.value),
            "e_ncl": num(self.estimate("e_N").value),
            "reference_stress_kPa": num(self.options.reference_stress / 1e3),
            "e0": num(self.e0),
        }

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the initial void ratio (glossary ``e0``) and every estimate.

        Each estimate (C_c, λ, e_N, the yield stresses, C_s, ...) is stored under its JSON name with its 95 %
        interval and its standard error (``name_se``), in its declared unit (``-`` when dimensionless), so that
        `capred history --quantity C_c` charts it.

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import quantity_store_row, store_row

        rows = [quantity_store_row(material, "e0", self.e0)]
        for x in self.estimates:
            unit = x.unit or "-"
            rows.append(store_row(material, x.name, x.value, unit, (x.low, x.high)))
            rows.append(store_row(material, f"{x.name}_se", x.se, unit))
        return [r for r in rows if r is not None]

    def payload(self, lazy: bool = False) -> dict:
        """The command's keys of compression.json: test, e0, the estimates, the lines and the readings.

        Parameters
        ----------
        lazy : bool, optional
            Allow :class:`capred.spool.Rows` in place of long lists (unused: the lists are short).

        Returns
        -------
        dict
            JSON key -> value.
        """
        f = self.fit
        return {
            "source": self.source,
            "test": self.options.test,
            "e0": num(self.e0),
            "estimates": {x.name: x.as_json() for x in self.estimates},
            "lines": self.lines(),
            "first_loading_curve": {
                "e_y": num(f.e_y),
                "C_r": num(f.C_r),
                "C_c": num(f.C_c),
                "sigma_y_kPa": num(10**f.log_sigma_y / 1e3),
                "bend_width_decades": num(f.w),
                "n": f.n,
                "rms_residual": num(np.sqrt(f.rss / f.n)),
            },
            "readings": self.readings.json_rows(),
        }

    def tables(self) -> dict:
        """results: one row per reading; estimates: one row per quantity.

        Returns
        -------
        dict of str to pandas.DataFrame
            ``results``: one row per reading; ``estimates``: one row per quantity.
        """
        import pandas as pd

        est = pd.DataFrame(
            {
                "quantity": [x.name for x in self.estimates],
                "value": [x.value for x in self.estimates],
                "se": [x.se for x in self.estimates],
                "ci95_low": [x.low for x in self.estimates],
                "ci95_high": [x.high for x in self.estimates],
                "unit": [x.unit for x in self.estimates],
                "method": [x.method for x in self.estimates],
            }
        )
        return {"results": pd.DataFrame(self.readings.csv_columns()), "estimates": est}

    def method_notes(self) -> tuple[list[str], list[str]]:
        """The test, its e0 and the stress e_N is read at, for the methods text.

        Returns
        -------
        (list of str, list of str)
            The paragraph, and the keys of Casagrande (1936) and Pacheco Silva (1970).
        """
        return [
            f"Test: {self.options.test} ({self.stress_symbol}); e0 = {self.e0:.4g}; e_N read at "
            f"{self.options.reference_stress / 1e3:g} kPa."
        ], ["casagrande1936", "pacheco_silva1970"]


def _stages(table, sigma) -> list[str]:
    if "stage" not in table.columns:
        return cp.stage_labels(sigma)
    out = []
    for i, s in enumerate(table.columns["stage"]):
        word = _STAGE_WORDS.get(str(s).strip().lower())
        if word is None:
            table.add_problem(i, "stage", f"stage {s!r} is not loading, unloading or reloading")
            word = "loading"
        out.append(word)
    return out


def _first_loading(stages: list[str]) -> np.ndarray:
    """The readings of the first run of loading readings (up to the first unloading)."""
    out = np.zeros(len(stages), bool)
    started = False
    for i, s in enumerate(stages):
        if s == "loading":
            out[i], started = True, True
        elif started:
            break
    return out


def _pooled_line(sigma, e, groups) -> cp.LineFit | None:
    """One slope over several stages, each with its own intercept (OLS)."""
    keep = [g for g in groups if g.sum() >= 2]
    if not keep:
        return None
    x = np.log10(sigma)
    n = int(sum(g.sum() for g in keep))
    X = np.zeros((n, len(keep) + 1))
    y = np.empty(n)
    row = 0
    for j, g in enumerate(keep):
        k = int(g.sum())
        X[row : row + k, j] = 1.0
        X[row : row + k, -1] = x[g]
        y[row : row + k] = e[g]
        row += k
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    dof = n - X.shape[1]
    se = np.nan
    if dof > 0:
        r = y - X @ coef
        cov = np.linalg.pinv(X.T @ X) * float(r @ r) / dof
        se = float(np.sqrt(cov[-1, -1]))
    return cp.LineFit(float(-coef[-1]), se, float(coef[0]), n), dof


def run_compression(source, options: CompressionOptions | None = None) -> CompressionResult:
    """Reduce a compression test: C_c/λ, C_s/κ, C_r, e_N, and the yield stress (bilinear, Casagrande, Pacheco Silva).

    Parameters
    ----------
    source : str, Path, DataFrame or TableSource
        One row per reading: ``sigma_eff`` [kPa unless the header says], ``e`` or ``height`` [mm] (with
        ``solids_height``), optional ``stage`` and ``step``.
    options : CompressionOptions
        The test, the height of solids and the reference stress of e_N.

    Returns
    -------
    CompressionResult

    Raises
    ------
    InputError
        Missing columns, values out of range, fewer than 6 readings on the first loading.

    References
    ----------
    Casagrande (1936); Pacheco Silva (1970); Schofield & Wroth (1968).
    """
    opt = options if options is not None else CompressionOptions()
    table = read_table(source, SCHEMA)
    notes = list(table.notes)
    warnings = list(opt.warnings) + list(table.warnings)
    if "sigma_eff" not in table.columns:
        table.missing_column("sigma_eff")
    if "e" not in table.columns and "height" not in table.columns:
        table.missing_column("e", " (or 'height' with --solids-height)")
    table.raise_if_problems()
    sigma = table.get("sigma_eff").copy()
    if "e" in table.columns:
        e = table.get("e").copy()
        if "height" in table.columns:
            notes.append("both 'e' and 'height' given: e is used, height is not")
    else:
        if opt.solids_height is None:
            raise OptionError(
                f"{table.path}: the file gives the specimen height, not e: give the height of solids "
                "(--solids-height, mm) so that e = H/H_s - 1"
            )
        H = table.get("height")
        e = H / opt.solids_height - 1.0
        for i in np.flatnonzero(e <= 0):
            table.add_problem(i, "height", f"height {H[i] * 1e3:g} mm is not above the solids' height")
        notes.append(f"e = H/H_s − 1 with H_s = {opt.solids_height * 1e3:g} mm")
    for name, v in (("sigma_eff", sigma), ("e" if "e" in table.columns else "height", e)):
        for i in np.flatnonzero(np.isnan(v)):
            table.add_problem(i, name, f"no value for '{name}'")
    table.raise_if_problems()
    stages = _stages(table, sigma)
    table.raise_if_problems()
    first = _first_loading(stages)
    if first.sum() < 6:
        table.add_problem(
            None,
            "sigma_eff",
            f"{int(first.sum())} readings on the first loading; the smooth bilinear curve has 5 parameters and "
            "needs at least 6 (its standard errors need more than 5)",
        )
        table.raise_if_problems()
    xs = np.log10(sigma[first])
    if np.any(np.diff(xs) <= 0):
        warnings.append("the first loading's stresses are not increasing in the order read: fitted as sorted")
    order = np.argsort(sigma[first], kind="stable")
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        fit = cp.fit_first_loading(sigma[first][order], e[first][order])
    if fit.w_at_bound:
        warnings.append(
            f"the bend of the first-loading curve ended at its bound (w = {fit.w:.3g} decades): too few readings "
            "around the yield stress to describe it; the yield stresses depend on that bound"
        )
    sy = 10**fit.log_sigma_y
    lo, hi = float(sigma[first].min()), float(sigma[first].max())
    if not lo < sy < hi:
        warnings.append(
            f"the bilinear yield stress {sy / 1e3:.4g} kPa lies outside the first loading's stresses "
            f"({lo / 1e3:g}-{hi / 1e3:g} kPa): the test does not show both lines, so C_c, σ'_y and the "
            "constructions are extrapolated"
        )
    if not fit.C_c > max(fit.C_r, 0.0):
        warnings.append(
            f"the first loading shows no virgin line steeper than its recompression (C_c = {fit.C_c:.4g}, "
            f"C_r = {fit.C_r:.4g}): the sample has not yielded, or the stages are mislabelled"
        )
    e0 = float(e[0])
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):  # NaN/inf become None
        est = _estimates(fit, e0, opt, sigma, e, stages, first)
    unloading, reloading = est.pop("_unloading"), est.pop("_reloading")
    if unloading is None:
        notes.append("no unloading stage: κ (C_s) is not estimated")
    elif not unloading.index < fit.C_c:
        warnings.append(
            f"C_s = {unloading.index:.4g} is not below C_c = {fit.C_c:.4g}: an unloading line as steep as the "
            "virgin line is not physical (pt-volume and skempton-b's bounding surface need κ < λ)"
        )
    e_fit = np.full(sigma.size, np.nan)
    e_fit[first] = fit.e_at(sigma[first])
    readings = CompressionReadings(
        line=np.asarray(table.lines, int),
        stage=list(stages),
        sigma=sigma / 1e3,
        e=e,
        first_loading=first,
        e_fitted=e_fit,
    )
    res = CompressionResult(
        table.path,
        readings,
        fit,
        unloading,
        reloading,
        est["list"],
        e0,
        opt,
        notes,
        [input_file(source, table)],
        warnings,
    )
    return res


def _estimates(fit, e0, opt, sigma, e, stages, first) -> dict:
    """Every estimate with its SE (delta method on the fit's covariance) and 95 % interval (Student t)."""
    p, cov = fit.params, fit.cov
    t5 = _t95(fit.n - 5)
    out: list[Estimate] = []

    def add(name, symbol, f, unit="", method="", log=False):
        value = f(p)
        g = cp.gradient(f, p)
        se = float(np.sqrt(max(g @ cov @ g, 0.0)))
        if log:  # a stress: the interval is symmetric in log10 sigma (value and se given in kPa)
            out.append(
                Estimate(
                    name,
                    symbol,
                    10**value / 1e3,
                    10**value / 1e3 * cp.LN10 * se,
                    10 ** (value - t5 * se) / 1e3,
                    10 ** (value + t5 * se) / 1e3,
                    "kPa",
                    method,
                )
            )
        else:
            out.append(Estimate(name, symbol, value, se, value - t5 * se, value + t5 * se, unit, method))

    curve = "smooth bilinear fit of the first loading"
    add("C_c", "C_c", lambda q: q[2], method=curve + ": slope of its virgin asymptote in e-log10 σ'")
    add("lambda", "λ", lambda q: q[2] / cp.LN10, method="C_c / ln 10 (slope in e-ln σ')")
    ref = np.log10(opt.reference_stress)
    add("e_N", "e_N", lambda q: q[0] - q[2] * (ref - q[3]), method=f"e on the virgin line at {10**ref / 1e3:g} kPa")
    add("sigma_y_kPa", "σ'_y", lambda q: q[3], method="intersection of the two asymptotes (bilinear)", log=True)
    add(
        "sigma_p_casagrande_kPa",
        "σ'_p (Casagrande)",
        lambda q: q[3] + cp.casagrande_t(q[0], q[1], q[2], q[4]),
        method="Casagrande (1936) on the fitted curve",
        log=True,
    )
    add(
        "sigma_p_pacheco_silva_kPa",
        "σ'_p (Pacheco Silva)",
        lambda q: q[3] + cp.pacheco_silva_t(e0, q[0], q[1], q[2], q[4]),
        method=f"Pacheco Silva (1970) on the fitted curve, e0 = {e0:.4g}",
        log=True,
    )
    add("C_r_first", "C_r (first loading)", lambda q: q[1], method=curve + ": slope of its recompression asymptote")

    st = np.asarray(stages)

    def runs(label):
        groups, i = [], 0
        while i < st.size:
            if st[i] == label:
                j = i
                while j + 1 < st.size and st[j + 1] == label:
                    j += 1
                g = np.zeros(st.size, bool)
                # a stage starts at its reversal point: the reading before it belongs to both branches
                g[max(i - 1, 0) : j + 1] = True
                groups.append(g)
                i = j + 1
            else:
                i += 1
        return groups

    lines = {}
    for label, name, symbol in (("unloading", "C_s", "C_s"), ("reloading", "C_r", "C_r")):
        got = _pooled_line(sigma, e, runs(label))
        if got is None:
            lines[label] = None
            continue
        lf, dof = got
        lines[label] = lf
        t = _t95(dof)
        what = f"straight line in e-log10 σ' over the {label} stages (one slope, an intercept per stage)"
        out.append(Estimate(name, symbol, lf.index, lf.se, lf.index - t * lf.se, lf.index + t * lf.se, "", what))
        if label == "unloading":
            k, s = lf.index / cp.LN10, lf.se / cp.LN10
            out.append(Estimate("kappa", "κ", k, s, k - t * s, k + t * s, "", "C_s / ln 10 (slope in e-ln σ')"))
    return {"list": out, "_unloading": lines["unloading"], "_reloading": lines["reloading"]}


# --- the fit as other commands take it --------------------------------------------------------------------------
@dataclass(frozen=True)
class CompressionLines:
    """The lines of a compression fit as `pt-volume` and `skempton-b` take them.

    Attributes
    ----------
    ncl_slope, url_slope : float or None
        λ and κ: slopes of the normal compression and unloading lines in e - ln σ' [-] (κ None without
        unloading).
    e_ncl : float
        e on the normal compression line at ``reference_stress`` [-].
    reference_stress : float
        [Pa].
    e0 : float
        Initial void ratio of the specimen [-].
    source : str
        The file it was read from.
    test : str
        ``oedometer`` (lines in e - ln σ'_v) or ``isotropic`` (in e - ln p').
    """

    ncl_slope: float
    url_slope: float | None
    e_ncl: float
    reference_stress: float
    e0: float
    source: str
    test: str = "oedometer"

    def e_ncl_at(self, stress: float) -> float:
        """Void ratio on the normal compression line at another reference stress, e_ncl − λ ln(σ/σ_ref).

        Parameters
        ----------
        stress : float
            The reference stress σ [Pa], > 0.

        Returns
        -------
        float
            The void ratio e [-].
        """
        return float(self.e_ncl - self.ncl_slope * np.log(stress / self.reference_stress))


def load_compression_fit(fit, limits=None) -> CompressionLines:
    """The lines of a `capred compression` run: its compression.json, or a CompressionResult.

    Parameters
    ----------
    fit : str, Path or CompressionResult
        The JSON written by `capred compression`, or its result.
    limits : capred.io.ReadLimits, optional
        The run's reading limits (``--max-megabytes``; default 256 MiB): the file's largest size.

    Returns
    -------
    CompressionLines

    Raises
    ------
    InputError
        The file cannot be read (larger than the limit, nested deeper than capred.io.MAX_JSON_DEPTH) or is not
        a compression.json.
    """
    if isinstance(fit, CompressionResult):
        doc, where = fit.to_json(), fit.source
    else:
        where = str(fit)
        try:
            doc = read_json(fit, "compression.json", limits)  # bounded in size and nesting
        except (OSError, UnicodeDecodeError, ValueError) as exc:
            raise InputError(
                Problem(where, None, None, f"cannot read it as the JSON of capred compression ({exc})")
            ) from None
    lines = doc.get("lines") if isinstance(doc, dict) else None
    if not isinstance(lines, dict) or doc.get("command") != "compression":
        raise InputError(Problem(where, None, None, "not a compression.json written by capred compression"))
    try:
        lam, e_ncl = float(lines["lambda"]), float(lines["e_ncl"])
        ref, e0 = float(lines["reference_stress_kPa"]) * 1e3, float(lines["e0"])
    except (KeyError, TypeError, ValueError):
        raise InputError(
            Problem(where, None, None, "its 'lines' lack lambda, e_ncl, reference_stress_kPa or e0")
        ) from None
    kappa = lines.get("kappa")
    test = doc.get("test") if doc.get("test") in TESTS else "oedometer"
    return CompressionLines(lam, None if kappa is None else float(kappa), e_ncl, ref, e0, where, test)


__all__ = [
    "run_compression",
    "CompressionOptions",
    "CompressionResult",
    "CompressionReadings",
    "Estimate",
    "CompressionLines",
    "load_compression_fit",
    "SCHEMA",
]
