"""`capred triaxial`: unsaturated strength from triaxial failure states, per material, through shear's models.

One row per test: the net cell pressure sigma3 (sigma3 - u_a), the deviator at failure q_f (or sigma1), the
matric suction, and the sample state (S_r, or any consistent subset of rho_d, rho_s/G_s, e, n, w, theta from
which capred.physics.phase completes it). Per material (a ``material`` column splits the run; never pooled):

1. the extended Mohr-Coulomb envelope c', phi', phi_b (Fredlund et al. 1978) in its triaxial form
   (`capred.fitting.extended_mc`);
2. the effective envelope at s -> 0 of that fit (no saturated test needed), or --c-eff/--phi-eff;
3. every model of the ONE effective-stress registry of `capred shear`
   (`capred.physics.effective_stress_models.REGISTRY`) predicts q_f through its sigma'_3 = sigma3 + chi s:
   with the envelope written q_f = a + b sigma'_3 (a = 2 sqrt(Kp) c', b = Kp - 1 in compression;
   a = 2 c'/sqrt(Kp), b = 1 - 1/Kp in extension, with sigma3 the major radial stress) a model is exactly
   shear's tau = c + tan(phi) sigma'_N with (c, tan phi, sigma_N, tau) -> (a, b, sigma3, q_f), so shear's
   `predict`, fitted chi laws (`shear_analysis.fit_laws`), back-analysis (`shear_analysis.back_analysis`),
   metrics (`shear.model_metrics`), AICc weights (`chi_laws.akaike_weights`) and ranking summary are reused
   as they are;
4. Prunier et al. (2024)'s spherical upper and lower bounds of the capillary tensor of each test on the named
   envelope, with their standard errors from the envelope's covariance (delta method).

References
----------
.. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). Can. Geotech. J. 15(3):313-321,
   doi:10.1139/t78-029.
.. [2] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.,
   doi:10.1080/19648189.2024.2314099, eq. 15-27.
.. [3] Bishop, A. W. (1959). The principle of effective stress. Teknisk Ukeblad 106(39):859-863.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import FitError, InputError, OptionError, Problem
from ..fitting import chi_laws
from ..fitting.extended_mc import ExtendedMCFit, coefficients, envelope_of, fit_extended_mc
from ..io import read_table
from ..physics import effective_stress_models as esm
from ..physics import triaxial as tx
from ..result import input_file
from ..spec.triaxial_strength import DEFAULT_MODELS, SCHEMA, TriaxialStrengthOptions  # noqa: F401 (declared in spec; re-exported here)
from .shear import model_metrics
from .triaxial_strength_records import MaterialStrength, TriaxialStrengthResult

__all__ = ["TriaxialStrengthOptions", "TriaxialStrengthResult", "MaterialStrength", "run_triaxial_strength"]

KPA = 1e3


#: the sample-state columns completed by capred.physics.phase (capred.pipelines.sample_state)
_STATE_COLUMNS = ("rho_d", "rho_s", "G_s", "e", "n", "w", "S_R", "theta")


def load_table(source):
    """Read and check a triaxial failure-state table (every problem collected, then raised once).

    Parameters
    ----------
    source : str, path, DataFrame or capred.io.grid.TableSource
        The table: a CSV, .xlsx or .ods file, or a DataFrame.

    Returns
    -------
    capred.io.Table
        The table read against ``SCHEMA``, with q_f completed from sigma1 where only sigma1 is given.

    Raises
    ------
    InputError
        Naming every missing column and bad cell (file, sheet, line, column).
    """
    table = read_table(source, SCHEMA)
    for name in ("test_id", "sigma3", "suction"):
        if not table.has(name):
            table.missing_column(name, " (needed for every failure state)")
    if not table.has("q_f") and not table.has("sigma1"):
        table.missing_column("q_f", " (or sigma1: q_f = |sigma1 - sigma3|)")
    table.raise_if_problems()
    table.check_unique("test_id")
    q = table.get("q_f")
    if table.has("sigma1"):
        from_s1 = np.abs(table.get("sigma1") - table.get("sigma3"))
        q = np.where(np.isfinite(q), q, from_s1)
    for i in range(len(table)):
        for name in ("sigma3", "suction"):
            if not np.isfinite(table.get(name)[i]):
                table.add_problem(i, name, f"{name} is blank")
        if not np.isfinite(q[i]):
            table.add_problem(i, "q_f" if table.has("q_f") else "sigma1", "no deviator at failure (q_f or sigma1)")
        elif q[i] <= 0:
            table.add_problem(i, "q_f", "the deviator at failure must be > 0")
    table.raise_if_problems()
    return table, np.abs(q)


def complete_states(table) -> dict[str, np.ndarray]:
    """The sample state of every test completed by the phase relations.

    Parameters
    ----------
    table : capred.io.Table
        The failure-state table, as :func:`load_table` returns it.

    Returns
    -------
    dict of str to numpy.ndarray
        rho_d, rho_s, G_s, e, n, w, S_R and theta per test (SI units), NaN where the table does not give it.

    Raises
    ------
    InputError
        One error naming each bad row.
    """
    from .sample_state import table_state

    state = table_state(table)
    table.raise_if_problems()
    n = len(table)
    return {col: state.get(col, np.full(n, np.nan)) for col in _STATE_COLUMNS}


# --- the run ----------------------------------------------------------------------------------------------------


def run_triaxial_strength(source, options: TriaxialStrengthOptions | None = None) -> TriaxialStrengthResult:
    """Unsaturated strength from triaxial failure states, per material (see the module docstring).

    Parameters
    ----------
    source : str, pathlib.Path or pandas.DataFrame
        The table of failure states.
    options : TriaxialStrengthOptions, optional

    Returns
    -------
    TriaxialStrengthResult

    Raises
    ------
    InputError
        Bad cells, inconsistent sample states, or a material mixing compression and extension.
    FitError
        A material whose failure states do not determine the extended envelope (fewer than 4 tests, one suction).
    """
    opt = options or TriaxialStrengthOptions()
    table, q = load_table(source)
    state = complete_states(table)
    n = len(table)
    material = (
        np.array([v or "(no material)" for v in table.columns["material"]], dtype=object)
        if table.has("material")
        else np.full(n, "(all tests)", dtype=object)
    )
    branch = (
        np.array([v or "compression" for v in table.columns["branch"]], dtype=object)
        if table.has("branch")
        else np.full(n, "compression", dtype=object)
    )
    tests = {
        "test_id": np.asarray(table.columns["test_id"], dtype=object),
        "material": material,
        "branch": branch,
        "sigma3": table.get("sigma3"),
        "q_f": q,
        "suction": table.get("suction"),
        "R": table.get("R"),
        **state,
    }
    problems = []
    for m in dict.fromkeys(material):
        forms = set(branch[material == m])
        if len(forms) > 1:
            i = int(np.flatnonzero((material == m) & (branch == "extension"))[0])
            problems.append(
                Problem(
                    table.path,
                    int(table.lines[i]),
                    table.headers.get("branch", "branch"),
                    f"material '{m}' mixes compression and extension tests: give each branch its own material name "
                    "(their envelopes are fitted separately)",
                    table.sheet,
                )
            )
    if problems:
        raise InputError(problems)
    notes: list[str] = []
    warnings: list[str] = list(opt.warnings) + list(table.warnings)
    if not table.has("material"):
        notes.append("no material column: every test is one material")
    models = esm.resolve_models(opt.models)
    all_asked = esm.asks_for_all(opt.models)
    materials = {}
    from ..progress import steps

    for m in steps(list(dict.fromkeys(material)), "materials: extended envelope, models, bootstrap"):
        rows = np.flatnonzero(material == m)
        try:
            materials[m] = _material(m, rows, tests, opt, models, all_asked)
        except FitError as exc:
            raise FitError(f"{table.path}, material '{m}': {exc}") from None
        if not opt.envelope_given and not np.any(tests["suction"][rows] == 0):
            notes.append(
                f"{m}: no saturated (zero-suction) test; the effective envelope c', φ' is the extended Mohr-Coulomb "
                "fit at s -> 0 (Fredlund et al. 1978), an extrapolation to the suction axis, with its uncertainty "
                "carried into the bounds; --c-eff/--phi-eff override it"
            )
        warnings.extend(f"{m}: {w}" for w in materials[m].fit.warnings)
        for mod, why in materials[m].skipped.items():  # named in --models but not scored: a warning, else a note
            (notes if all_asked else warnings).append(f"{m}: model '{mod}' not scored: {why}")
        dry = int(np.sum(tests["suction"][rows] == 0))
        if dry:
            notes.append(
                f"{m}: {dry} test(s) at zero suction enter the extended envelope but not the model scores (every "
                "model gives them the envelope itself)"
            )
    return TriaxialStrengthResult(
        source=table.path,
        tests=tests,
        materials=materials,
        options=opt,
        inputs=[input_file(source, table)],
        notes=notes,
        warnings=list(dict.fromkeys(warnings)),
    )


def _line(form: str, c_eff: float, phi_eff: float) -> tuple[float, float]:
    a, b, _ = coefficients(form, c_eff, phi_eff)
    return float(a), float(b)


def _inputs(tests, rows, a, b, opt, m) -> esm.ModelInputs:
    k = rows.size
    return esm.ModelInputs(
        sigma_N=tests["sigma3"][rows],
        suction=tests["suction"][rows],
        S_R=tests["S_R"][rows],
        R=tests["R"][rows],
        tau_max=tests["q_f"][rows],
        wet=tests["suction"][rows] > 0,
        material=np.full(k, m, dtype=object),
        c=np.full(k, a),
        tan_phi=np.full(k, b),
        surface_tension=opt.surface_tension,
        params=opt.model_params,
    )


def _usable(model: str, d: esm.ModelInputs, opt) -> str:
    """Why ``model`` cannot be scored on these tests ("" when it can).

    A missing parameter, or no finite prediction (a fitted law is judged after its fit, in `_material`).
    """
    missing = opt.model_params.missing(model)
    if missing:
        return f"needs {missing}"
    if esm.REGISTRY[model].fitted:
        return ""
    with np.errstate(all="ignore"):
        pred = esm.predict(model, d)[1]
    return "" if np.any(np.isfinite(pred[d.wet])) else _no_prediction(d)


def _no_prediction(d: esm.ModelInputs) -> str:
    need = "S_R (or a sample state it follows from)" if not np.any(np.isfinite(d.S_R[d.wet])) else "R"
    return f"no prediction on these tests (needs {need})"


def _material(m, rows, tests, opt, models, all_asked) -> MaterialStrength:
    form = str(tests["branch"][rows[0]])
    x, s, y = tests["sigma3"][rows], tests["suction"][rows], tests["q_f"][rows]
    fit = fit_extended_mc(x, s, y, form, opt.errors, opt.confidence)
    if opt.envelope_given:
        c_eff, phi_eff = float(opt.c_eff), float(opt.phi_eff)
        env_cov = np.zeros((2, 2))
        a, b = _line(form, c_eff, phi_eff)
        line_cov = np.zeros((2, 2))
        source = f"given as options (--c-eff {c_eff / KPA:g} kPa, --phi-eff {phi_eff:g} deg)"
    else:
        a, b, line_cov = fit.zero_suction_line()
        c_eff, phi_eff, _ = fit.envelope
        env_cov = fit.derived_covariance()[:2, :2]
        n_sat = int(np.sum(s == 0))
        tests_text = (
            f"{fit.n - n_sat} unsaturated tests, no saturated test needed"
            if n_sat == 0
            else f"{fit.n - n_sat} unsaturated and {n_sat} saturated tests"
        )
        source = (
            "extended Mohr-Coulomb envelope at s -> 0 (Fredlund et al. 1978) fitted to the failure states "
            f"({tests_text})"
        )
    d = _inputs(tests, rows, a, b, opt, m)
    skipped, scored = {}, []
    for mod in models:
        why = _usable(mod, d, opt)
        if why and not all_asked and why.startswith("needs"):  # named in --models without its parameter, as shear
            raise OptionError(f"model '{mod}' (--models) {why}")
        if why:
            skipped[mod] = why
        else:
            scored.append(mod)
    from . import shear_analysis as sa

    laws = {}
    for mod in [mod for mod in scored if esm.REGISTRY[mod].fitted]:
        try:
            with np.errstate(all="ignore"):
                law = sa.fit_laws(d, [mod], [m], opt.model_params).get(mod, {}).get(m)
        except (ValueError, FitError, np.linalg.LinAlgError) as exc:  # e.g. no S_R to fit chi = S_e^kappa on
            law = None
            why = f"its law could not be fitted ({exc})" if np.any(np.isfinite(d.S_R[d.wet])) else _no_prediction(d)
        else:
            why = "fewer than 2 tests with suction"
        if law is None or not all(np.isfinite(v) for v in law.values.values()):
            scored.remove(mod)
            skipped[mod] = why if law is None else _no_prediction(d)
        else:
            laws[mod] = law
    d = dataclasses.replace(d, fitted={mod: {m: law.values} for mod, law in laws.items()})
    for mod in [mod for mod in scored if esm.REGISTRY[mod].fitted]:
        with np.errstate(all="ignore"):
            if not np.any(np.isfinite(esm.predict(mod, d)[1][d.wet])):
                scored.remove(mod)
                laws.pop(mod, None)
                skipped[mod] = _no_prediction(d)
    d = dataclasses.replace(d, fitted={mod: {m: law.values} for mod, law in laws.items()})
    wet = d.wet
    predictions, metrics, info_in = {}, {}, {}
    for mod in list(scored):
        with np.errstate(all="ignore"):
            pred = esm.predict(mod, d)[1]
        # two models that predict the same q_f on every test (Pedrotti-Tarantino's wet-area reading is Bishop's
        # chi = S_r when no saturated test gives a water envelope of its own) are one hypothesis on these data:
        # ranked once, so that it does not take two shares of the Akaike weights
        same = next(
            (o for o, p in predictions.items() if np.allclose(pred, p, rtol=1e-12, atol=0.0, equal_nan=True)), None
        )
        if same is not None:
            scored.remove(mod)
            skipped[mod] = f"predicts what '{same}' predicts on every test of this material: ranked once, as '{same}'"
            continue
        predictions[mod] = pred
    for mod in scored:
        metrics[mod] = model_metrics(predictions[mod][wet], y[wet])
        e = esm.REGISTRY[mod]
        k = len(e.fitted) + e.wet_parameters
        rss = float(np.nansum((predictions[mod][wet] - y[wet]) ** 2))
        info_in[mod] = (k, chi_laws.information_criteria(rss, metrics[mod].n, k)["aicc"])
    weights = chi_laws.akaike_weights({mod: v[1] for mod, v in info_in.items()})
    information = {
        mod: {"k": info_in[mod][0], "aicc": info_in[mod][1], "delta_aicc": weights[mod][0], "weight": weights[mod][1]}
        for mod in scored
    }
    ranked = sorted([mod for mod in scored if np.isfinite(metrics[mod].si.rmse)], key=lambda mod: metrics[mod].si.rmse)
    best = ranked[0] if ranked else None
    # back-analysis: the capillary stress sigma'_3 - sigma3 the envelope needs to carry the measured q_f
    cov = np.broadcast_to(line_cov, (rows.size, 2, 2))
    s2 = fit.new_test_variance(x, s)
    cap, cap_se, chi, chi_se = sa.back_analysis(y, x, s, d.c, d.tan_phi, cov, s2)
    bounds = bounds_on_envelope(form, x, y, c_eff, phi_eff, env_cov)
    ranking = _bootstrap(m, rows, tests, opt, scored, ranked, laws, form) if opt.bootstrap and len(ranked) > 1 else None
    return MaterialStrength(
        m, form, rows, fit, source, c_eff, phi_eff, env_cov, line_cov, tuple(scored), skipped, predictions,
        metrics, information, laws, {"sigma_cap": cap, "sigma_cap_se": cap_se, "chi_back": chi, "chi_back_se": chi_se},
        bounds, ranking, best, own_envelopes(d, scored, form, y, fit.weights),
    )  # fmt: skip


def own_envelopes(d: esm.ModelInputs, models, form: str, y, weights=None) -> dict:
    r"""Each model's own envelope: (c', φ') refitted to the material's failure states UNDER that model.

    With no saturated test the shared envelope (the extended fit at s -> 0) is the planar envelope's intercept:
    a model whose σ'_3 is not planar in s (Bishop with S_r falling with suction) is then scored on an envelope
    fitted under another hypothesis. Refitting (a, b) of q = a + b σ'_3 under each model removes that bias. A
    registry model's prediction is affine in (a, b) (checked here per model; the fitted χ laws are left out):

    .. math:: q_i = f_{0,i} + a\,f_{a,i} + b\,f_{b,i}

    so the refit is least squares on all the material's tests, weighted as the extended fit was (``weights``:
    ones for constant errors, 1/q̂² for proportional ones; the model's own σ'_3 against the same
    scatter); RMSE on the tests with suction, and AICc with k = 2 + the model's wet parameters.

    Parameters
    ----------
    d : ModelInputs
        The material's tests (``c``, ``tan_phi`` the shared envelope's a, b).
    models : sequence of str
        Scored models.
    form : str
        ``"compression"`` or ``"extension"``.
    y : ndarray
        Measured q_f [Pa].
    weights : ndarray, optional
        Least-squares weights per test (default ones).

    Returns
    -------
    dict
        model -> {c_eff [Pa], phi_eff [deg], rmse [Pa], k, aicc, delta_aicc, weight}; models that are not affine
        (fitted laws) are left out.

    References
    ----------
    .. [1] Draper & Smith (1998), doi:10.1002/9781118625590 (least squares); Burnham & Anderson (2002),
       doi:10.1007/b97636 (AICc).
    """
    out, aicc = {}, {}
    n = y.size
    wet = d.wet
    for mod in models:
        e = esm.REGISTRY[mod]
        if e.fitted:
            continue

        def at(a, b, mod=mod):
            with np.errstate(all="ignore"):
                return esm.predict(mod, dataclasses.replace(d, c=np.full(n, a), tan_phi=np.full(n, b)))[1]

        # probes about the shared envelope (a0, b0): f = f0 + (a - a0) fa + (b - b0) fb where the model is affine
        a0, b0 = float(d.c[0]), float(d.tan_phi[0])
        ha, hb = max(abs(a0), 1.0), max(abs(b0), 1e-3)
        f0 = at(a0, b0)
        fa, fb = (at(a0 + ha, b0) - f0) / ha, (at(a0, b0 + hb) - f0) / hb
        keep = np.isfinite(f0) & np.isfinite(fa) & np.isfinite(fb)
        check = at(a0 - 0.5 * ha, b0 + 0.5 * hb)
        if keep.sum() < 3 or not np.allclose(
            check[keep], (f0 - 0.5 * ha * fa + 0.5 * hb * fb)[keep], rtol=1e-7, atol=1e-6 * float(np.max(np.abs(y)))
        ):
            continue
        sw = np.sqrt(np.ones(n) if weights is None else np.asarray(weights, float))[keep]
        X = np.column_stack([fa, fb])[keep] * sw[:, None]
        (da, db), *_ = np.linalg.lstsq(X, (y - f0)[keep] * sw, rcond=None)
        a, b = a0 + da, b0 + db
        c_eff, phi, _ = envelope_of(form, a, b)
        pred = f0 + da * fa + db * fb
        sel = wet & keep
        rmse = math.sqrt(float(np.mean((pred[sel] - y[sel]) ** 2))) if sel.any() else math.nan
        k = 2 + e.wet_parameters
        aicc[mod] = chi_laws.information_criteria(float(np.sum((pred[sel] - y[sel]) ** 2)), int(sel.sum()), k)["aicc"]
        out[mod] = {"c_eff": float(c_eff), "phi_eff": float(phi), "rmse": rmse, "k": k, "aicc": aicc[mod]}
    for mod, (delta, weight) in chi_laws.akaike_weights(aicc).items():
        out[mod]["delta_aicc"], out[mod]["weight"] = delta, weight
    return out


def _principal(form, x, q):
    """(sigma1, sigma3) major and minor net stresses of each test: the cell pressure x is minor in compression."""
    return (x + q, x) if form == "compression" else (x, x - q)


def bounds_on_envelope(form, x, q, c_eff, phi_eff, env_cov) -> dict:
    """Prunier et al. (2024) spherical and lower bounds of each test on an envelope, with SEs by the delta method.

    Parameters
    ----------
    form : {"compression", "extension"}
    x : ndarray
        Net cell pressure [Pa] (minor principal stress in compression, major in extension).
    q : ndarray
        Deviator at failure [Pa].
    c_eff, phi_eff : float
        The envelope [Pa], [deg].
    env_cov : (2, 2) ndarray
        Covariance of (c' [Pa], φ' [deg]); zeros for an envelope taken as exact.

    Returns
    -------
    dict
        ``spherical_p_cap``, ``lower_p_cap``, ``lower_sigma3_cap`` [Pa] and their ``_se`` [Pa] per test; the SE is
        that of the envelope alone (the failure state taken as measured). Coverage of ±t SE by simulation:
        95-96 % (benchmarks/coverage_triaxial_strength.py).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.
       doi:10.1080/19648189.2024.2314099, eq. 15-17 (spherical) and 20-27 (lower bound).
    """
    s1, s3 = _principal(form, x, q)

    def values(c, phi):
        sph = tx.spherical_bound(s1, s3, c, phi, form)
        low = tx.lower_bound(s1, s3, c, phi, form)
        return np.stack([sph.p_cap, low.p_cap, low.sigma3_cap])

    base = values(c_eff, phi_eff)
    grads = []
    for k, (c, phi) in enumerate(((c_eff, phi_eff),) * 2):
        h = 1e-6 * max(abs(c), 1.0) if k == 0 else 1e-6 * max(abs(phi), 1.0)
        up = values(c + h, phi) if k == 0 else values(c, phi + h)
        dn = values(c - h, phi) if k == 0 else values(c, phi - h)
        grads.append((up - dn) / (2 * h))
    gc, gp = grads
    var = gc**2 * env_cov[0, 0] + 2 * gc * gp * env_cov[0, 1] + gp**2 * env_cov[1, 1]
    se = np.sqrt(np.maximum(var, 0.0))
    names = ("spherical_p_cap", "lower_p_cap", "lower_sigma3_cap")
    return {**{n: base[k] for k, n in enumerate(names)}, **{n + "_se": se[k] for k, n in enumerate(names)}}


def _bootstrap(m, rows, tests, opt, scored, ranked, laws, form):
    """Paired bootstrap of the ranking of the models.

    Resample the material's tests, refit the extended envelope (its s -> 0 line, or the given one), refit the chi laws
    (warm start), score every model by RMSE on the resampled tests with suction; summarised as `capred shear` does
    (shear_analysis.summarise_ranking).
    """
    from . import shear_analysis as sa

    rng = np.random.default_rng(opt.seed)
    k = rows.size
    scores = np.full((opt.bootstrap, len(scored)), np.nan)
    for r in range(opt.bootstrap):
        pick = rows[rng.integers(0, k, k)]
        x, s, y = tests["sigma3"][pick], tests["suction"][pick], tests["q_f"][pick]
        try:
            if opt.envelope_given:
                a, b = _line(form, float(opt.c_eff), float(opt.phi_eff))
            else:
                a, b, _ = fit_extended_mc(x, s, y, form, opt.errors, opt.confidence).zero_suction_line()
        except FitError:
            continue
        d = _inputs(tests, pick, a, b, opt, m)
        fitted = {}
        with np.errstate(all="ignore"):
            for mod, law in laws.items():
                try:
                    fitted[mod] = {m: chi_laws.LAWS[mod].fit(d.subset(d.wet), opt.model_params, law.values).values}
                except Exception:  # a replicate where the law does not converge: that model unscored there
                    pass
            d = dataclasses.replace(d, fitted=fitted)
            for j, mod in enumerate(scored):
                if esm.REGISTRY[mod].fitted and mod not in fitted:
                    continue
                pred = esm.predict(mod, d)[1][d.wet]
                keep = np.isfinite(pred)
                if keep.any():
                    scores[r, j] = math.sqrt(float(np.mean((pred[keep] - d.tau_max[d.wet][keep]) ** 2)))
    return sa.summarise_ranking(scores, list(scored), ranked, opt.seed)


def envelope_from_fit(fit: ExtendedMCFit) -> tuple[float, float]:
    """The envelope of an extended fit at s -> 0 (the one a run without saturated tests uses).

    Parameters
    ----------
    fit : capred.fitting.extended_mc.ExtendedMCFit
        The extended Mohr-Coulomb fit of one material.

    Returns
    -------
    c_eff : float
        Effective cohesion c' [Pa].
    phi_eff : float
        Effective friction angle φ' [deg].
    """
    c, phi, _ = envelope_of(fit.form, *fit.coef)
    return float(c), float(phi)
