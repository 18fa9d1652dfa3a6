"""`capred retention-convert`: a fitted retention curve expressed in another retention model.

The parameters of the target model are those that best reproduce the fitted curve over the suction range of
the data it was fitted to: least squares on the fitted water quantity (S_R or θ) over ln s between the
smallest and largest of the data's suctions (Gauss-Legendre quadrature, split at a kink of the target such
as Brooks-Corey's air entry, so that it is continuous), solved by capred's global retention fit
(:func:`capred.fitting.retention_models.fit_model`) and polished across the kink. The misfit (RMSE and
largest deviation at the data's own suctions and a logarithmic grid between, in the unit of the water
quantity) says how well the target model can follow the curve; the converted fit is a fit like
any other (callable, ``params`` by JSON name, a fits.json of the same shape as `capred retention` writes).

It also serves the commands that need a given model: `skempton-b --retention FIT.json` takes Brooks-Corey's
air-entry suction and index (:func:`brooks_corey_for_skempton`).
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..errors import FitError, OptionError
from ..fitting.retention_models import MODELS, RetentionFit, fit_model, json_name, power_law_model
from ..physics.shear import GAMMA_W
from ..result import input_file, num
from ..spec.retention_convert import GRID_POINTS, ConvertOptions  # noqa: F401 (declared in spec; re-exported here)
from .retention import RetentionResult

#: start-grid minima refined by a conversion (fit_model's n_starts; its default, 3 or 8, left some conversions up
#: to 0.8 % above the optimum of an independent 200-start search: issue 41; 40 reach it on every pair of
#: tests/data/retention/reference_conversions.csv, and the curve of 100-200 nodes keeps it well under a second)
CONVERT_STARTS = 40
#: a conversion whose largest deviation exceeds this (in S_R, or θ/θ_s) is flagged: the curves differ visibly
#: on a retention plot (0.02 is about the scatter of a careful hanging-column or pressure-plate series)
MISFIT_WARNING = 0.02


@dataclass(repr=False)
class RetentionConvertResult(RetentionResult):
    """Result of `capred retention-convert`: the converted fit (``fits[branch][to]``), the source fit and the misfit.

    ``suction`` and ``water`` hold the points the conversion was fitted to (the source curve).
    """

    command = "retention-convert"
    json_name = "fits.json"

    source_fit: RetentionFit | None = None
    misfit: dict = field(default_factory=dict)

    @property
    def converted(self) -> RetentionFit:
        """The converted fit."""
        return next(iter(next(iter(self.fits.values())).values()))

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: those of ``capred retention`` plus ``conversion``.

        ``conversion``: source and target models, the source parameters (report units and SI) and the misfit.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        out = super().payload(lazy)
        src = self.source_fit
        out["conversion"] = {
            "from_model": src.model,
            "to_model": self.converted.model,
            "from_params": {p.name: num(p.value) for p in src.params.values()},
            "from_params_si": {k: num(v) for k, v in src.params_si.items()},
            **{k: num(v) if isinstance(v, float) else v for k, v in self.misfit.items()},
        }
        return out

    def tables(self) -> dict:
        """Output tables: fits and parameters of the converted fit (as `capred retention`), and points.

        Points: the source curve and the converted one at the conversion's points.

        Returns
        -------
        dict of str to pandas.DataFrame
            ``fits``, ``parameters`` and ``points``.
        """
        t = dict(super().tables())
        pts = t["points"]
        t["points"] = pts.rename(columns={c: c.replace(f"_{self.converted.model} [", "_converted [") for c in pts})
        return t

    def csv_tables(self) -> dict:
        """The CSV tables of :meth:`tables` as column mappings (written without pandas).

        Returns
        -------
        dict
            File stem -> {``"name [unit]"``: array}.
        """
        t = dict(super().csv_tables())
        tag = f"_{self.converted.model} ["
        t["points"] = {c.replace(tag, "_converted ["): v for c, v in t["points"].items()}
        return t

    def season_rows(self) -> list[dict]:
        """Rows of a batch's season.csv: none (a conversion is not a measurement).

        Returns
        -------
        list
            Empty.
        """
        return []


def _real(value, what: str) -> float:
    """A JSON number as a float: not a boolean, not a string, finite; else an OptionError naming ``what``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise OptionError(f"{what} must be a number (got {json.dumps(value)[:40]})")
    x = float(value)
    if not np.isfinite(x):
        raise OptionError(f"{what} must be finite (got {x})")
    return x


def _optional_real(f: dict, key: str, where: str) -> float:
    v = f.get(key)
    return float("nan") if v is None else _real(v, f"{where}: '{key}'")


def check_domain(model: str, si: dict, quantity: str, where: str) -> None:
    """Every parameter of a fitted model inside the model's natural domain.

    The registry's ``domain`` of each parameter: a parameter on a logarithmic scale exceeds its offset, n > 1 where m =
    1 − 1/n, α > 0 ...; Durner's w1 in [0, 1]; 0 ≤ y_r < y_s; S_res < 1 for a fit on S_R.

    Parameters
    ----------
    model : str
        Registry key.
    si : dict
        Parameters by internal name, in SI units.
    quantity : str
        ``S_R``, ``theta`` or ``w``.
    where : str
        The file and fit, for the message.

    Raises
    ------
    OptionError
        The first parameter outside its domain, with the domain and its paper.
    """
    entry = MODELS[model]
    for p in entry.parameters:
        v = _real(si[p.name], f"{where}: params_si '{p.name}'")
        off = p.log_offset
        ok = True
        if off is not None:
            ok = v > off
        elif p.kind == "absolute":
            ok = p.lower <= v <= p.upper
        elif p.kind == "residual":
            ok = v >= 0 and (quantity != "S_R" or v < 1)
        elif p.kind == "saturated":
            ok = v > 0
        if not ok:
            name = json_name(p.name, quantity)[0]
            raise OptionError(
                f"{where}: {name} = {v:.6g} lies outside the {entry.label} model's domain ({p.domain or p.range_text})"
            )
    if "y_r" in si and not si["y_r"] < si["y_s"]:
        raise OptionError(
            f"{where}: {json_name('y_r', quantity)[0]} = {si['y_r']:.6g} is not below "
            f"{json_name('y_s', quantity)[0]} = {si['y_s']:.6g} ({Y_DOMAIN})"
        )


#: the order of residual and saturated water content (van Genuchten 1980, eq. 21)
Y_DOMAIN = "0 ≤ θ_r < θ_s, van Genuchten 1980, eq. 21"


def _fit_from_json(doc: dict, where: str, model: str | None, branch: str | None) -> RetentionFit:
    """The RetentionFit a fits.json describes (its SI parameters, quantity and suction points), each value checked.

    Parameters inside the model's domain, counts and statistics numbers, the suction range positive and finite.
    """
    try:
        branches = doc.get("branches") or {doc.get("main_branch") or "drying": {"fits": doc["fits"]}}
        b = branch or doc.get("main_branch") or next(iter(branches))
        if b not in branches:
            raise OptionError(f"{where}: no branch '{b}' (the file has {', '.join(map(str, branches))})")
        fits = branches[b]["fits"]
        if not fits:
            raise OptionError(f"{where}: branch '{b}' holds no fit")

        def aicc(m):
            v = fits[m].get("aicc") if isinstance(fits[m], dict) else None
            return v if isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) else np.inf

        if model is None:
            model = min(fits, key=aicc)
        if model not in fits:
            raise OptionError(f"{where}: branch '{b}' has no {model} fit (it has {', '.join(map(str, fits))})")
        f = fits[model]
        raw = f["params_si"]
        if not isinstance(raw, dict):
            raise TypeError("params_si is not an object")
    except (KeyError, TypeError, AttributeError, ValueError) as exc:
        raise OptionError(f"{where}: not a fits.json written by capred retention ({exc})") from None
    key = next((k for k, e in MODELS.items() if e.label == f.get("model")), model)
    if key not in MODELS or set(raw) != set(MODELS[key].names):
        raise OptionError(f"{where}: the {model} fit is not one of capred's retention models")
    quantity = doc.get("quantity", "S_R")
    if quantity not in ("S_R", "theta", "w"):
        raise OptionError(f"{where}: 'quantity' must be S_R, theta or w (got {json.dumps(quantity)[:40]})")
    here = f"{where} (branch '{b}', {model})"
    si = {k: _real(v, f"{here}: params_si '{k}'") for k, v in raw.items()}
    check_domain(key, si, quantity, here)
    points = f.get("suction_points_kPa") or f.get("suction_range_kPa")
    if not points:
        raise FitError(
            f"{where}: the {model} fit of branch '{b}' has no suction range (suction_range_kPa): it was written by "
            "an older capred, and a conversion holds only over the suctions of the data; run capred retention "
            "on the data again"
        )
    name = "suction_points_kPa" if f.get("suction_points_kPa") else "suction_range_kPa"
    if not isinstance(points, list) or len(points) < 2:
        raise OptionError(f"{here}: '{name}' must be a list of at least two suctions in kPa")
    kpa = np.array([_real(x, f"{here}: '{name}'") for x in points])
    if not (np.all(kpa > 0) and kpa.max() > kpa.min() and kpa.max() * 1e3 < 1e15):
        raise OptionError(
            f"{here}: '{name}' must hold positive suctions below 1e12 kPa, not all equal "
            f"(got {kpa.min():.6g} to {kpa.max():.6g} kPa)"
        )
    n_points = f.get("n_points")
    if n_points is not None:
        n_points = _real(n_points, f"{here}: 'n_points'")
        if n_points < 1 or n_points != int(n_points):
            raise OptionError(f"{here}: 'n_points' must be a whole number of readings (got {n_points:g})")
    conv = f.get("converged", True)
    if not isinstance(conv, bool):
        raise OptionError(f"{here}: 'converged' must be true or false (got {json.dumps(conv)[:40]})")
    fit = RetentionFit(
        params=si,
        stderr={},
        fixed=(),
        n=int(n_points) if n_points is not None else kpa.size,
        rss=_optional_real(f, "rss", here),
        r2=_optional_real(f, "r2", here),
        aic=_optional_real(f, "aic", here),
        bic=_optional_real(f, "bic", here),
        converged=conv,
        model=key,
        quantity=quantity,
        suction_points=tuple(float(x) * 1e3 for x in np.sort(kpa)),
    )
    lo, hi = fit.suction_range
    with np.errstate(all="ignore"):
        ends = MODELS[key].effective_saturation(np.array([lo, hi]), si)
    if not np.all(np.isfinite(ends)) or abs(ends[0] - ends[1]) < 1e-6:
        raise OptionError(
            f"{here}: the curve is flat over its suction range ({lo * 1e-3:.4g} to {hi * 1e-3:.4g} kPa: effective "
            f"saturation {ends[0]:.6g} to {ends[1]:.6g}); its parameters put the whole change of water content "
            "outside the data's suctions, and no other model can be fitted to a constant"
        )
    fit.extra["branch"] = b
    return fit


def load_retention_fit(fit, model: str | None = None, branch: str | None = None) -> tuple[RetentionFit, str, list]:
    """A retention fit from what a user holds: a RetentionFit, a RetentionResult, a fits.json path or its dict.

    Parameters
    ----------
    fit : RetentionFit, RetentionResult, str, pathlib.Path or dict
        The fit; a result or a file gives the fit of ``model`` on ``branch`` (default: the lowest AICc of the
        main branch); a table of readings (CSV, .xlsx, .ods) is fitted first with `capred retention`'s defaults.
    model, branch : str, optional
        Which fit of a result or file.

    Returns
    -------
    (RetentionFit, str, list)
        The fit, where it came from (a path or a description), and the input files read.

    Raises
    ------
    FitError
        The fit carries no suction range (a fits.json of an older capred).
    OptionError
        Not a fit, or no such model or branch.
    """
    if isinstance(fit, RetentionFit):
        if fit.suction_range is None:
            raise FitError(
                f"the {fit.model} fit has no suction range (suction_points): a conversion holds only over the "
                "suctions of the data it was fitted to; fit it with capred.run_retention or fit_model"
            )
        return fit, f"{fit.model} fit", []
    if isinstance(fit, RetentionResult):
        return load_retention_fit(fit.to_json(), model, branch)[0], fit.source, list(fit.inputs)
    if isinstance(fit, dict):
        return _fit_from_json(fit, "the fit", model, branch), "the fit", []
    if fit is None:
        raise OptionError("no fit given: a fits.json written by capred retention, or a table of retention readings")
    from ..io import source_path

    where = source_path(fit)
    if not isinstance(where, (str, Path)) or Path(where).suffix.lower() != ".json":  # readings: fitted first
        from .retention import run_retention

        return load_retention_fit(run_retention(fit), model, branch)
    path = Path(where)
    limits = getattr(fit, "limits", None)
    doc = read_fit_json(path, limits.max_bytes if limits is not None else MAX_JSON_BYTES)
    return _fit_from_json(doc, str(path), model, branch), str(path), [input_file(str(path))]


#: the largest fits.json read [bytes] unless --max-megabytes says otherwise: a fits.json of every model on both
#: branches of 10,000 readings holds under 1 MiB (at most 200 suction points a fit)
MAX_JSON_BYTES = 16 * 2**20


def read_fit_json(path, max_bytes: int = MAX_JSON_BYTES) -> dict:
    """A fits.json read safely: a regular file, at most ``max_bytes``, parsed by orjson.

    NaN and Infinity are not JSON; nested at most `capred.io.json_input.MAX_JSON_DEPTH` levels deep.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    max_bytes : int
        Largest size read [bytes].

    Returns
    -------
    dict
        The document.

    Raises
    ------
    MissingFileError
        No such file.
    OptionError
        Not a regular file, too large, not JSON, or not an object.
    """
    import stat

    import orjson

    from ..errors import MissingFileError

    path = Path(path)
    try:
        st = path.stat()
    except FileNotFoundError:
        raise MissingFileError(str(path)) from None
    except OSError as exc:
        raise OptionError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    if not stat.S_ISREG(st.st_mode):
        raise OptionError(f"{path}: not a regular file (a fits.json written by capred retention is one)")
    if st.st_size > max_bytes:
        raise OptionError(
            f"{path}: {st.st_size / 2**20:.1f} MiB, more than the {max_bytes / 2**20:g} MiB a fits.json is read up "
            "to (a fits.json of capred retention holds well under 1 MiB; raise the limit with --max-megabytes)"
        )
    try:
        with open(path, "rb") as f:
            raw = f.read(max_bytes + 1)
        doc = orjson.loads(raw)
    except OSError as exc:
        raise OptionError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    except orjson.JSONDecodeError as exc:
        raise OptionError(f"{path}: not a fits.json written by capred retention (not valid JSON: {exc})") from None
    from ..io import MAX_JSON_DEPTH, json_depth

    # capred's own depth rule, whatever the orjson version (older ones parse any depth)
    if json_depth(doc) > MAX_JSON_DEPTH:
        raise OptionError(
            f"{path}: not a fits.json written by capred retention (not valid JSON for capred: nested deeper than "
            f"{MAX_JSON_DEPTH} levels)"
        )
    if not isinstance(doc, dict):
        raise OptionError(f"{path}: not a fits.json written by capred retention (not a JSON object)")
    return doc


def conversion_points(fit: RetentionFit, points: int = GRID_POINTS) -> np.ndarray:
    """The suctions [Pa] a conversion is fitted at: the fit's own and ``points`` log-spaced between its extremes.

    Parameters
    ----------
    fit : RetentionFit
        The source fit (its suction points and range [Pa]).
    points : int, optional
        Number of log-spaced suctions added [-].

    Returns
    -------
    ndarray
        Sorted unique suctions [Pa].
    """
    lo, hi = fit.suction_range
    return np.unique(np.concatenate([np.asarray(fit.suction_points, float), np.geomspace(lo, hi, points)]))


@lru_cache(maxsize=8)
def _gauss_legendre(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [-1, 1] (computed once per size: an eigenvalue problem)."""
    return np.polynomial.legendre.leggauss(points)


def log_quadrature(lo: float, hi: float, points: int, breaks=()) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights of the mean over ln s of [lo, hi].

    ``points`` nodes in each piece between the ``breaks`` that lie inside.

    Parameters
    ----------
    lo, hi : float
        The suction range [Pa], 0 < lo < hi.
    points : int
        Nodes per piece [-].
    breaks : sequence of float, optional
        Suctions [Pa] where the integrand has a kink (Brooks-Corey's air entry): each piece is smooth, so the
        rule integrates it to the order of a smooth function, and the integral is smooth in the break.

    Returns
    -------
    (ndarray, ndarray)
        Nodes s_j [Pa] and weights w_j [-] (sum 1): Σ w_j g(s_j) ≈ (1/ln(hi/lo)) ∫ g(s) d ln s.

    References
    ----------
    Abramowitz, M. & Stegun, I. A. (1964). Handbook of Mathematical Functions, eq. 25.4.29 (Gauss-Legendre).
    """
    x, w = _gauss_legendre(int(points))
    a, b = np.log(lo), np.log(hi)
    edges = [a, *sorted(np.log(t) for t in breaks if lo < t < hi), b]
    nodes, weights = [], []
    for e0, e1 in zip(edges[:-1], edges[1:]):
        half = 0.5 * (e1 - e0)
        nodes.append(np.exp(e0 + half * (x + 1.0)))
        weights.append(w * half / (b - a))
    return np.concatenate(nodes), np.concatenate(weights)


def convert_fit(fit: RetentionFit, to: str, points: int = GRID_POINTS, fixed: dict | None = None):
    """The ``to`` model that best reproduces a fitted curve over its data's suction range.

    Least squares in the logarithm of suction over the data's range: the target's parameters minimise the mean
    of (y_to(s) − y_fit(s))² over ln s from the smallest to the largest suction of the data (S_R or θ), by
    Gauss-Legendre quadrature (:func:`log_quadrature`, ``points`` nodes), at the global optimum inside the
    target's bounds (:func:`capred.fitting.retention_models.fit_model` at the nodes, with their weights). A
    target with a kink (Brooks-Corey's air entry s_e) is then polished with the quadrature split at the kink,
    so that the objective is smooth in it and the air entry is a continuous function of the source curve, not
    one of the nodes. The misfit is reported at the data's own suctions and a log grid between
    (:func:`conversion_points`).

    Parameters
    ----------
    fit : RetentionFit
        The source fit (with ``suction_points``).
    to : str
        Target model.
    points : int
        Quadrature nodes (per piece) and grid points of the misfit between the extremes of the data's suctions.
    fixed : dict, optional
        Target parameters held (internal names, SI), e.g. ``{"y_r": 0, "y_s": 1}``.

    Returns
    -------
    (RetentionFit, dict)
        The converted fit (standard errors not applicable: None) and the misfit: ``rmse`` and
        ``max_deviation`` [unit of the water quantity], ``at_suction_kPa`` where the deviation is largest,
        ``n_points``, ``suction_range_kPa``.

    References
    ----------
    Lenhard, R. J., Parker, J. C., Mishra, S. (1989). On the correspondence between Brooks-Corey and van
    Genuchten models. J. Irrig. Drain. Eng. 115(4):744-751, doi:10.1061/(ASCE)0733-9437(1989)115:4(744)
    (a closed-form correspondence; capred fits the target curve instead, over the data's range).
    """
    lo, hi = fit.suction_range
    fixed = dict(fixed or {})
    nodes, w = log_quadrature(lo, hi, points)
    y_nodes = fit.water(nodes)
    s = conversion_points(fit, points)
    y = fit.water(s)
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(y_nodes))):
        raise FitError(f"the {fit.model} curve is not finite over its suction range: nothing to convert")
    new = fit_model(to, nodes, y_nodes, fixed, w * nodes.size, n_starts=CONVERT_STARTS)
    kinks = [p.name for p in MODELS[to].parameters if p.kinks_at_data and p.name not in fixed]
    if kinks:
        new = _polish_across_kinks(new, fit, to, kinks, fixed, (lo, hi), int(points))
    d = new.water(s) - y
    i = int(np.argmax(np.abs(d)))
    misfit = {
        "rmse": float(np.sqrt(np.mean(d**2))),
        "max_deviation": float(np.abs(d[i])),
        "at_suction_kPa": float(s[i] * 1e-3),
        "n_points": int(s.size),
        "suction_range_kPa": [float(s[0] * 1e-3), float(s[-1] * 1e-3)],
    }
    unit = "m³/m³" if fit.quantity == "theta" else ""
    note = (
        f"converted from the {fit.model} fit by least squares over ln s from {lo * 1e-3:.4g} to {hi * 1e-3:.4g} kPa "
        f"(the data's range; Gauss-Legendre, {points} nodes): at the data's suctions and a log grid "
        f"({s.size} suctions) RMSE {misfit['rmse']:.3g}{unit and ' '}{unit}, largest deviation "
        f"{misfit['max_deviation']:.3g}{unit and ' '}{unit} at {s[i] * 1e-3:.4g} kPa; standard errors do not apply "
        "to a converted curve"
    )
    scale = fit.params_si.get("y_s", 1.0) if fit.quantity in ("theta", "w") else 1.0  # θ/θ_s, w/w_s ~ S_R
    warns = []
    if misfit["max_deviation"] / scale > MISFIT_WARNING:
        warns.append(
            f"{to} cannot follow the {fit.model} curve closely: largest deviation {misfit['max_deviation']:.3g}"
            f"{unit and ' '}{unit} at {s[i] * 1e-3:.4g} kPa (above {MISFIT_WARNING:g} in S_R)"
        )
    for k in new.at_bounds():
        name, factor, unit_k = json_name(k, fit.quantity)
        warns.append(
            f"{name} = {new.params_si[k] * factor:.6g}{'' if unit_k in ('-', '') else ' ' + unit_k} lies at its "
            f"bound: the {to} curve closest to the {fit.model} curve wants it beyond the model's range"
        )
    new = dataclasses.replace(
        new,
        quantity=fit.quantity,
        stderr={k: None for k in new.params_si},
        covariance=None,
        aic=float("nan"),
        bic=float("nan"),
        notes=[note],
        warnings=warns,
        suction_points=fit.suction_points,
    )
    return new, misfit


def conversion_objective(fit: RetentionFit, to: str, params: dict, points: int = GRID_POINTS) -> float:
    """What a conversion minimises: the mean over ln s of (y_to(s) − y_fit(s))² over the data's suction range.

    By Gauss-Legendre quadrature split at the target's kinks (:func:`log_quadrature`).

    Parameters
    ----------
    fit : RetentionFit
        The source fit (its suction range).
    to : str
        Target model.
    params : dict
        The target's parameters (internal names, SI).
    points : int, optional
        Nodes per piece.

    Returns
    -------
    float
        The objective [unit of the water quantity, squared].
    """
    lo, hi = fit.suction_range
    model = MODELS[to]
    kinks = [params[p.name] for p in model.parameters if p.kinks_at_data]
    nodes, w = log_quadrature(lo, hi, points, kinks)
    with np.errstate(all="ignore"):
        d = model.water(nodes, **params) - fit.water(nodes)
    return float(np.sum(w * d**2))


def _polish_across_kinks(new: RetentionFit, src: RetentionFit, to: str, kinks, fixed, span, points) -> RetentionFit:
    """The global fit ``new`` polished with the quadrature split at the target's kinks (its air entry).

    By bounded least squares from ``new``: the residuals are smooth in every parameter there, so the kink moves freely.
    """
    from scipy.optimize import least_squares

    model = MODELS[to]
    free = [k for k in model.names if k not in fixed]
    lo_b = np.array([new.bounds[k][0] for k in free])
    hi_b = np.array([new.bounds[k][1] for k in free])

    def residuals(x):
        p = {**fixed, **dict(zip(free, x))}
        nodes, w = log_quadrature(*span, points, [p[k] for k in kinks])
        return np.sqrt(w) * (model.water(nodes, **p) - src.water(nodes))

    x0 = np.clip([new.params_si[k] for k in free], lo_b, hi_b)
    scale = np.where(np.abs(x0) > 0, np.abs(x0), 1.0)
    sol = least_squares(residuals, x0, bounds=(lo_b, hi_b), x_scale=scale, xtol=1e-12, ftol=1e-14, gtol=1e-14)
    if not np.sum(sol.fun**2) < np.sum(residuals(x0) ** 2):  # the global fit stands
        return new
    # least_squares keeps strictly inside the bounds: a parameter within 1e-12 of its scale of a bound is on it
    x = np.where(sol.x - lo_b <= 1e-12 * scale, lo_b, np.where(hi_b - sol.x <= 1e-12 * scale, hi_b, sol.x))
    found = {**fixed, **dict(zip(free, x))}
    params = {k: float(found[k]) for k in model.names}
    nodes, w = log_quadrature(*span, points, [params[k] for k in kinks])
    y_src = src.water(nodes)
    rss = float(np.sum(w * (model.water(nodes, **params) - y_src) ** 2)) * nodes.size
    ybar = float(np.sum(w * y_src))
    tss = float(np.sum(w * (y_src - ybar) ** 2)) * nodes.size
    return dataclasses.replace(
        new, params=params, rss=rss, r2=1.0 - rss / tss if tss > 0 else float("nan"), n=int(nodes.size)
    )


def convert_retention(fit, to: str, model: str | None = None, branch: str | None = None, points: int = GRID_POINTS):
    """Express a retention fit in another model: ``capred.convert_retention(fit, to="bc")``.

    Parameters
    ----------
    fit : RetentionFit, RetentionResult, str, pathlib.Path or dict
        A fit (``result.fits["drying"]["vg"]``), a result, or a fits.json written by `capred retention`.
    to : str
        Target model (``vg``, ``vg_m_free``, ``bc``, ``kosugi``, ``fx``, ``fx_no_c``, ``durner``).
    model, branch : str, optional
        Which fit of a result or file (default: the lowest AICc of the main branch).
    points : int
        Grid points between the data's smallest and largest suction.

    Returns
    -------
    RetentionConvertResult
        ``.converted`` is the new fit (callable, ``params`` by JSON name); ``.misfit`` the RMSE and largest
        deviation; ``to_json()`` a fits.json of the same shape as `capred retention` writes, with a
        ``conversion`` block.

    References
    ----------
    See :func:`convert_fit`.
    """
    return run_retention_convert(fit, ConvertOptions(to=to, model=model, branch=branch, points=points))


def run_retention_convert(source, options: ConvertOptions | None = None) -> RetentionConvertResult:
    """The reduction of `capred retention-convert FIT.json --to MODEL` (see :func:`convert_retention`).

    Parameters
    ----------
    source : str or Path
        A fits.json of `capred retention` (or a table of readings, fitted first).
    options : ConvertOptions, optional
        Target model, which fit and branch to convert, grid points, unit weight of water [N/m^3].

    Returns
    -------
    RetentionConvertResult
        The converted fit, the source fit and the misfit.
    """
    opt = options or ConvertOptions()
    src, where, inputs = load_retention_fit(source, opt.model, opt.branch)
    new, misfit = convert_fit(src, opt.to, int(opt.points))
    s = conversion_points(src, int(opt.points))
    branch = src.extra.get("branch") or opt.branch or "drying"
    warnings = list(opt.warnings) + [f"branch '{branch}', model {opt.to}: {w}" for w in new.warnings]
    return RetentionConvertResult(
        where,
        src.quantity,
        s,
        src.water(s),
        np.full(s.size, branch, dtype=object),
        f"converted from the {src.model} fit",
        {branch: {opt.to: new}},
        opt,
        list(new.notes),
        inputs,
        warnings,
        source_fit=src,
        misfit=misfit,
    )


def brooks_corey_for_skempton(path, gamma_w: float = GAMMA_W, limits=None) -> tuple[float, float, list[str], list[str]]:
    """Brooks-Corey s_e [Pa] and λ [-] of Morvan et al.'s suction equilibrium, s = s_e S_r^(−1/λ), from a fits.json.

    A Brooks-Corey fit is taken as it is; any other model is converted to Brooks-Corey on S_R with S_res = 0
    and S_s = 1 (the form the relation takes), and the misfit is reported.

    Parameters
    ----------
    path : str or pathlib.Path
        fits.json written by `capred retention` (or `capred retention-convert`).
    gamma_w : float
        Unit weight of water [N/m^3].
    limits : capred.io.ReadLimits, optional
        The run's reading limits: ``max_bytes`` (--max-megabytes) bounds the file (default 16 MiB).

    Returns
    -------
    (float, float, list of str, list of str)
        s_e [Pa], λ [-], notes, warnings.

    References
    ----------
    Morvan, M., Wong, H., Branque, D. (2016), E-UNSAT 2016, E3S Web of Conferences, eq. 13 (s from Brooks-Corey);
    Brooks, R. H., Corey, A. T. (1964). Hydraulic properties of porous media. Hydrology Paper 3, Colorado State
    University.
    """
    from ..io import TableSource

    src, where, _ = load_retention_fit(path if limits is None else TableSource(path, limits=limits))
    target = power_law_model()
    air, index = target.power_law
    where = f"{where}{_chosen(path, src.model, MAX_JSON_BYTES if limits is None else limits.max_bytes)}"
    if src.model == target.name:
        p = src.params_si
        notes = [
            f"--retention {where}: {target.label} fit taken as it is: s_e = {p[air] * 1e-3:.4g} kPa, λ = {p[index]:.4g}"
        ]
        warns = []
        s_res = p["y_r"] / p["y_s"] if src.quantity in ("theta", "w") else p["y_r"]
        if s_res > 0.01 or (src.quantity == "S_R" and abs(p["y_s"] - 1) > 0.01):
            warns.append(
                f"--retention {where}: the {target.label} fit has S_res = {s_res:.3g}"
                + (f", S_s = {p['y_s']:.3g}" if src.quantity == "S_R" else "")
                + "; Morvan et al.'s s = s_e S_r^(-1/λ) takes S_r itself (S_res = 0, S_s = 1)"
            )
        return p[air], p[index], notes, warns
    # the curve in S_R: θ/θ_s for a θ fit, w/w_s for a w fit (S_R = w G_s/e at the specimen's constant e)
    sr = _as_saturation(src) if src.quantity in ("theta", "w") else src
    new, misfit = convert_fit(sr, target.name, fixed={"y_r": 0.0, "y_s": 1.0})
    p = new.params_si
    notes = [
        f"--retention {where}: the {src.model} fit converted to {target.label} with S_res = 0, S_s = 1 "
        f"(Morvan et al.'s s = s_e S_r^(-1/λ)): s_e = {p[air] * 1e-3:.4g} kPa, λ = {p[index]:.4g}; misfit in S_R: "
        f"RMSE {misfit['rmse']:.3g}, largest deviation {misfit['max_deviation']:.3g} at "
        f"{misfit['at_suction_kPa']:.4g} kPa"
    ]
    return p[air], p[index], notes, [f"--retention {where}: {w}" for w in new.warnings]


def _chosen(path, model: str, max_bytes: int = MAX_JSON_BYTES) -> str:
    """Which fit of a fits.json was taken, for the notes; empty for anything but a fits.json.

    Its branch, and that it has the branch's lowest AICc where the branch holds several.
    """
    try:
        doc = read_fit_json(path, max_bytes)
    except (OptionError, OSError, TypeError, ValueError):
        return ""
    branches = doc.get("branches") or {}
    b = doc.get("main_branch") or next(iter(branches), None)
    fits = (branches.get(b) or {}).get("fits") or doc.get("fits") or {}
    parts = [f"branch '{b}'"] if b else []
    parts.append(f"its lowest-AICc fit of {len(fits)}: {model}" if len(fits) > 1 else model)
    return f" ({', '.join(parts)})"


class _SaturationView(RetentionFit):
    """A θ fit seen as S_R = θ/θ_s (the source of a conversion on S_R)."""

    def water(self, suction):
        return RetentionFit.water(self, suction) / self.params_si["y_s"]


def _as_saturation(fit: RetentionFit) -> RetentionFit:
    view = _SaturationView(
        **{f.name: getattr(fit, f.name) for f in dataclasses.fields(fit) if f.name != "params"},
        params=dict(fit.params_si),
    )
    view.quantity = "S_R"
    return view


def converted_fit_json(doc: dict, to: str) -> dict | None:
    """The fits.json entry of a file's best fit (main branch) converted to ``to``, or None.

    For readers that need one model (`shear --retention`: van Genuchten for Lu & Likos, Brooks-Corey's air entry for
    Khalili); None when the file cannot be converted (no suction range: a file of an older capred), so that the reader
    goes on without it.

    Parameters
    ----------
    doc : dict
        A fits.json document.
    to : str
        Target model.

    Returns
    -------
    dict or None
        The converted fit's JSON (parameters by JSON name, ``params_si``, ``notes`` with the misfit).
    """
    try:
        res = run_retention_convert(doc, ConvertOptions(to=to))
    except (FitError, OptionError):
        return None
    return res.to_json()["fits"][to]
