"""`capred shear`, `capred triaxial-bounds`, `capred retention`: reductions of lab data tables."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from .common import Invocation, MaxMbOpt, ThousandsOpt, command
from .declare import model_parameter_values, option, registry_help, registry_names, si_values

SHEAR = "capred.spec.shear:ShearOptions"
PARAMS = "capred.spec.shear:ModelParams"
TRIAXIAL = "capred.spec.triaxial:TriaxialOptions"
RETENTION = "capred.spec.retention:RetentionOptions"


def _models_help() -> str:
    """--models of shear: every model of the effective-stress registry, its named sets and its fitted laws."""
    return (
        f"Models to compare, comma separated: {', '.join(registry_names('effective_stress_models'))}; "
        f"'thesis' for the thesis's {', '.join(registry_names('effective_stress_models', 'thesis'))}, 'all' for "
        f"every one. Fitted per material: {', '.join(registry_names('effective_stress_models', 'fitted'))}."
    )


def _retention_models_help() -> str:
    """--model of retention: every model of the retention registry with its one-line help."""
    return "Models, comma separated, or all: " + "; ".join(registry_help("retention_models")) + "."


def register(app: typer.Typer) -> None:
    """Register the commands of shear, triaxial-bounds and retention on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(app, "shear", data="CSV, .xlsx or .ods files of direct-shear tests (one row per test)")(shear)
    command(app, "triaxial-bounds", data="CSV, .xlsx or .ods files of triaxial tests (one row per test)")(
        triaxial_bounds
    )
    command(
        app,
        "retention",
        data="CSV, .xlsx or .ods files of retention readings: suction, head or pF, and "
        "S_R, theta, w with rho_d, or z2 + V_v",
    )(retention)


def shear(
    thousands: ThousandsOpt = None,
    max_megabytes: MaxMbOpt = None,
    curves: Annotated[
        Path | None,
        typer.Option(
            help="Raw shear curves (CSV, .xlsx or .ods), long format: "
            "test_id, displacement [mm], F [N] or tau [kPa], optionally "
            "vertical_displacement [mm]; the peak gives tau_max."
        ),
    ] = None,
    area_correction: option(
        SHEAR,
        "area_correction",
        metavar="none|square|circular",
        help="Area of the curves' shear stress: none (nominal, as ASTM D3080 reports), square or circular box.",
    ) = None,
    ambient_pressure: option(
        SHEAR, "ambient_pressure", note="a hanging-column head above (p_a - p_vapour)/gamma_w, about 10.1 m, is refused"
    ) = None,
    rho_w: option(SHEAR, "rho_w", note="for e = G_s rho_w/rho_d - 1") = None,
    gamma_w: option(SHEAR, "gamma_w", note="the thesis uses 10") = None,
    surface_tension: option(SHEAR, "surface_tension") = None,
    gravity: option(SHEAR, "g") = None,
    pendular_limit: option(
        SHEAR, "pendular_limit", note="above it a wet test is flagged outside the pendular regime"
    ) = None,
    box_area: option(SHEAR, "box_area", note="for rows without 'box_area'") = None,
    cap_mass: option(SHEAR, "cap_mass", note="for rows without 'cap_mass'") = None,
    radius: option(SHEAR, "radius", note="for rows without 'R'") = None,
    void_volume: option(SHEAR, "void_volume", note="for rows without 'V_v'") = None,
    models: option(SHEAR, "models", help=_models_help, shown="thesis") = None,
    retention: Annotated[
        Path | None,
        typer.Option(
            help="fits.json from capred retention: S_res, s_e and van Genuchten parameters for the extra models."
        ),
    ] = None,
    retention_branch: Annotated[
        str | None,
        typer.Option(
            metavar="drying|wetting",
            help="Branch of --retention's fits (default: drying, else the file's main branch); the note says which.",
        ),
    ] = None,
    s_res: option(PARAMS, "s_res", note="(Vanapalli et al. 1996)") = None,
    vanapalli_kappa: option(PARAMS, "vanapalli_kappa", note="(Vanapalli et al. 1996)") = None,
    air_entry: option(PARAMS, "air_entry", note="(Khalili & Khabbaz 1998)") = None,
    vg_alpha: option(PARAMS, "vg_alpha", note="(Lu & Likos 2006)") = None,
    vg_n: option(PARAMS, "vg_n", note="(Lu & Likos 2006); m = 1 - 1/n unless --vg-m") = None,
    vg_m: option(PARAMS, "vg_m", note="(Lu & Likos 2006)") = None,
    water_envelope: Annotated[
        str | None,
        typer.Option(
            help="'c,phi' [kPa, deg] of the water-saturated soil (Pedrotti & Tarantino); default: the dry envelope."
        ),
    ] = None,
    contact_angle: option(PARAMS, "contact_angle", note="of the exact bridge (exact_neck)") = None,
    fit_eta: option(
        PARAMS, "fit_eta", "--fit-eta", help="khalili_fit: fit the exponent eta too (else eta = 0.55)"
    ) = False,
    dry_fit: option(
        SHEAR,
        "dry_fit",
        metavar="free|origin",
        help="Dry envelope: 'free' (c and phi) or 'origin' (c = 0, cohesionless soil).",
    ) = None,
    errors: option(
        SHEAR,
        "errors",
        metavar="either|constant|proportional|auto",
        help="Scatter of a test: either (default: intervals valid whether the scatter is constant or proportional "
        "to the strength), constant, proportional to its strength (weighted least squares), or auto "
        "(proportional when the Breusch-Pagan test of the dry residuals against sigma_N has p < 0.05).",
    ) = None,
    dry_loss: option(
        SHEAR,
        "dry_loss",
        metavar="ols|huber|tukey",
        help="Loss of the dry fit: ols (least squares), huber or tukey (robust to an outlier, sandwich errors).",
    ) = None,
    bootstrap: option(
        SHEAR,
        "bootstrap",
        help="Most replicates of the paired bootstrap of the model ranking (0: none); it stops earlier, in rounds "
        "of 250, once the printed probabilities and ΔRMSE ends are resolved.",
    ) = None,
    seed: option(SHEAR, "seed", help="Seed of the bootstrap: the same seed gives the same probabilities.") = None,
    **model_options,
) -> Invocation:
    """Direct-shear tests with hanging-column suction (Evenepoel, VUB thesis).

    Dry envelope per material, the effective-stress models (No suction, Bishop, Own 1, Own 2 by default) on every wet
    test, their scores (all wet tests and pendular ones), how sure the ranking is (bootstrap), the capillary stress each
    wet test carried (back-analysed from the dry envelope) and report sheets per material.

    Values in the file win over the options; options fill absent columns and
    blank cells. Any option may carry a unit: --box-area "36 cm^2".

    Example: capred shear tests.csv --out report --gamma-w 10

    \f

    Parameters
    ----------
    thousands : str, optional
        Thousands separator of the curves file.
    max_megabytes : int, optional
        Largest input read [MiB]: the table, the curves file and --retention's JSON (default 256).
    curves : Path, optional
        Raw shear curves, long format.
    area_correction : str, optional
        none, square or circular.
    ambient_pressure : str, optional
        Ambient air pressure [kPa].
    rho_w : str, optional
        Density of water [kg/m^3].
    gamma_w : str, optional
        Unit weight of water [kN/m^3].
    surface_tension : str, optional
        Surface tension of water [N/m].
    gravity : str, optional
        Gravitational acceleration [m/s^2].
    pendular_limit : float, optional
        S_R above which a wet test is outside the pendular regime [-].
    box_area, cap_mass, radius, void_volume : str, optional
        Defaults of rows without them: box area [cm^2], cap mass [g], R [mm], V_v [cm^3].
    models : str, optional
        Effective-stress models, comma-separated, or a named set.
    retention : Path, optional
        fits.json of `capred retention` for the extra models.
    retention_branch : str, optional
        drying or wetting: the branch of --retention's fits.
    s_res : float, optional
        Residual S_R [-].
    vanapalli_kappa : float, optional
        Fitting exponent kappa of Vanapalli et al. (1996) [-].
    air_entry : str, optional
        Air-entry suction s_e [kPa].
    vg_alpha : str, optional
        van Genuchten alpha [1/kPa].
    vg_n, vg_m : float, optional
        van Genuchten n and m [-].
    water_envelope : str, optional
        'c,phi' [kPa, deg] of the water-saturated soil.
    contact_angle : float, optional
        Contact angle of the exact bridge [deg].
    fit_eta : bool, optional
        Fit Khalili's exponent eta too.
    dry_fit : str, optional
        free or origin.
    errors : str, optional
        either (default), constant, proportional or auto.
    dry_loss : str, optional
        ols, huber or tukey.
    bootstrap : int, optional
        Replicates of the bootstrap of the model ranking [-].
    seed : int, optional
        Seed of the bootstrap.
    **model_options
        The parameters registered models declare for themselves (capred.spec.shear.ModelParameter), one option
        each (``--my-kappa``), read from the registry when the command is built.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.shear import ModelParams, ShearOptions, model_params_from_retention

    params = si_values(
        PARAMS,
        s_res=s_res,
        vanapalli_kappa=vanapalli_kappa,
        air_entry=air_entry,
        vg_alpha=vg_alpha,
        vg_n=vg_n,
        vg_m=vg_m,
        contact_angle=contact_angle,
        fit_eta=fit_eta,
    )
    envelope = _envelope_pair(water_envelope)
    if envelope is not None:
        params["water_envelope"] = envelope
    own = model_parameter_values(model_options)
    if own:
        params["extra"] = own
    if retention_branch is not None and retention is None:
        from ..errors import OptionError

        raise OptionError("--retention-branch needs --retention FIT.json")
    from ..io import ReadLimits

    # --retention's JSON and the curves file read within --max-megabytes, as the table is
    limits = None if max_megabytes is None else ReadLimits(max_bytes=max_megabytes * 2**20)
    mp = (
        model_params_from_retention(retention, retention_branch, limits, **params)
        if retention is not None
        else ModelParams(**params)
    )
    given = si_values(
        SHEAR,
        gamma_w=gamma_w,
        surface_tension=surface_tension,
        g=gravity,
        pendular_limit=pendular_limit,
        box_area=box_area,
        cap_mass=cap_mass,
        radius=radius,
        void_volume=void_volume,
        dry_fit=dry_fit,
        errors=errors,
        dry_loss=dry_loss,
        bootstrap=bootstrap,
        seed=seed,
        ambient_pressure=ambient_pressure,
        rho_w=rho_w,
        area_correction=area_correction,
    )
    if models is not None:
        given["models"] = _model_list(models)
    opts = ShearOptions(**given, model_params=mp, curves=_curves_source(curves, thousands, limits))
    return Invocation("shear", opts, extra_inputs=[p for p in (retention, curves) if p])


def triaxial_bounds(
    curves: option(TRIAXIAL, "curves", note="for tests without q_f or sigma1") = None,
    c_eff: option(TRIAXIAL, "c_eff", note="instead of fitting saturated tests") = None,
    phi_eff: option(TRIAXIAL, "phi_eff", note="with --c-eff") = None,
    membrane_thickness: option(
        TRIAXIAL,
        "membrane_thickness",
        note="with --membrane-modulus the deviator is corrected for the membrane (ASTM D4767: 4 E_m t_m eps_a / D0). "
        "Off by default",
    ) = None,
    membrane_modulus: option(
        TRIAXIAL, "membrane_modulus", note="(latex: about 1400 kPa), with --membrane-thickness"
    ) = None,
    extension_path: option(TRIAXIAL, "extension_path") = None,
    material: option(TRIAXIAL, "material", note="one material of the table's material column per run") = None,
) -> Invocation:
    """Bounds of the capillary stress tensor at failure from triaxial tests (Prunier et al. 2024).

    Effective envelope from saturated drained tests, then for every unsaturated test the spherical upper bound (q = q'),
    the lower bound (sigma1_cap = 0) and the EDTP upper bound (needs s0), with the strength gain q'/q'_sat; groups
    sharing one tensor get the Appendix 1 analysis.

    Example: capred triaxial-bounds tests.csv --out bounds

    \f

    Parameters
    ----------
    curves : Path, optional
        Long CSV of raw curves (test_id, axial_strain, q).
    c_eff : str, optional
        Effective cohesion c' [kPa], instead of fitting saturated tests.
    phi_eff : float, optional
        Effective friction angle phi' [deg].
    membrane_thickness : str, optional
        Membrane thickness t_m [mm].
    membrane_modulus : str, optional
        Young's modulus of the membrane E_m [kPa].
    extension_path : str, optional
        axial-unloading or radial-loading.
    material : str, optional
        The material analysed (a table with several materials needs it).

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.triaxial import TriaxialOptions

    opts = TriaxialOptions(
        **si_values(
            TRIAXIAL,
            c_eff=c_eff,
            phi_eff=phi_eff,
            curves=curves,
            membrane_thickness=membrane_thickness,
            membrane_modulus=membrane_modulus,
            extension_path=extension_path,
            material=material,
        )
    )
    return Invocation("triaxial-bounds", opts, extra_inputs=[curves] if curves else [])


def retention(
    model: option(RETENTION, "models", "--model", help=_retention_models_help) = None,
    hysteresis: option(
        RETENTION,
        "hysteresis",
        metavar="kool-parker",
        help="kool-parker: fit the drying and wetting branches jointly (shared theta_s, theta_r, n; alpha_d, alpha_w).",
    ) = None,
    rho_w: option(RETENTION, "rho_w", note="for theta = w rho_d/rho_w") = None,
    branches: option(RETENTION, "branches", metavar="auto|single") = None,
    reversal_relative: option(RETENTION, "reversal_relative") = None,
    reversal_range: option(RETENTION, "reversal_range") = None,
    fix: Annotated[
        list[str] | None,
        typer.Option(help="Fix a parameter, e.g. --fix theta_s=0.25 (alpha in 1/kPa, s_e in kPa); repeatable."),
    ] = None,
    gamma_w: option(RETENTION, "gamma_w", note="to turn heads into suction") = None,
) -> Invocation:
    """Fit water retention curves for every branch (drying, wetting), with a model-selection table.

    van Genuchten (1980) (m = 1 - 1/n, m free), Brooks & Corey (1964), Kosugi (1996), Fredlund & Xing (1994) (with and
    without C), Durner (1994), with standard errors, 95 % intervals, correlations, R^2, RMSE, AIC, AICc, BIC;
    --hysteresis kool-parker fits both branches jointly. Suction as a pressure, a head or pF; water as theta, S_R, or w
    with rho_d, or w alone (a w(s) fit); an optional 'weight' column. Branches come from a 'branch' column (drying,
    wetting, scanning) or, without one, from the order of readings (rising suction = drying; reversals below the noise
    tolerance ignored; readings that start at a reversal inside the measured range are scanning, kept out of the main
    fits and compared with Parker & Lenhard's scanning curves); --branches single fits one curve.

    Example: capred retention column.csv --model vg,bc,kosugi --fix theta_r=0

    \f

    Parameters
    ----------
    model : str, optional
        Models, comma separated, or all.
    hysteresis : str, optional
        kool-parker, or None.
    rho_w : str, optional
        Density of water [kg/m^3].
    branches : str, optional
        auto or single.
    reversal_relative, reversal_range : float, optional
        Noise tolerance of a reversal: fraction of the reading, of the measured range [-].
    fix : list of str, optional
        NAME=VALUE of fixed parameters (kPa, 1/kPa).
    gamma_w : str, optional
        Unit weight of water [kN/m^3].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..errors import OptionError
    from ..fitting.retention_models import MODELS
    from ..pipelines.retention import RetentionOptions, parse_fixed

    given = si_values(
        RETENTION,
        gamma_w=gamma_w,
        rho_w=rho_w,
        hysteresis=hysteresis,
        branches=branches.strip().lower() if branches else None,
        reversal_relative=reversal_relative,
        reversal_range=reversal_range,
    )
    if model is not None:
        names = [m.strip().lower() for m in model.split(",") if m.strip()]
        if names == ["all"]:
            names = list(MODELS)
        bad = [m for m in names if m not in MODELS]
        if bad or not names:
            raise OptionError(
                f"--model: unknown model '{bad[0] if bad else model}'; choose from {', '.join(MODELS)} or all"
            )
        given["models"] = tuple(dict.fromkeys(names))
    opts = RetentionOptions(fixed=parse_fixed(fix or []), **given)
    return Invocation("retention", opts)


def _curves_source(path: Path | None, thousands, limits=None):
    if path is None or (thousands is None and limits is None):
        return path
    from ..io import TableSource

    return TableSource(path, None, thousands, limits=limits)


def _model_list(text: str) -> tuple[str, ...]:
    from ..errors import OptionError
    from ..physics.effective_stress_models import asks_for_all, resolve_models

    try:
        resolved = resolve_models(text)
    except ValueError as exc:
        raise OptionError(f"--models: {exc}") from None
    return text if asks_for_all(text) else resolved  # 'all' reaches ShearOptions, which skips what it cannot run


def _envelope_pair(text: str | None):
    from ..errors import OptionError

    if text is None:
        return None
    try:
        c, phi = (float(x) for x in text.split(","))
    except ValueError:
        raise OptionError(f"--water-envelope '{text}': expected 'c,phi' in kPa and degrees") from None
    if not (c >= 0 and 0 < phi < 90):
        raise OptionError(f"--water-envelope '{text}': need c >= 0 kPa and 0 < phi < 90 deg")
    return c * 1e3, phi
