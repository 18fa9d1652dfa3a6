"""`capred triaxial`: unsaturated strength from triaxial failure states, per material (issue 40)."""

from __future__ import annotations

import typer

from .common import Invocation, command
from .declare import model_parameter_values, option, registry_names, si_values

TRIAX = "capred.spec.triaxial_strength:TriaxialStrengthOptions"
PARAMS = "capred.spec.shear:ModelParams"


def register(app: typer.Typer) -> None:
    """Register `capred triaxial` on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(
        app,
        "triaxial",
        data="CSV, .xlsx or .ods files of triaxial failure states, one row per test: test_id, material, net "
        "sigma3, q_f (or sigma1), suction [kPa], and S_r or a sample state it follows from",
    )(triaxial)


def _models_help() -> str:
    return (
        f"Models to compare, comma separated: {', '.join(registry_names('effective_stress_models'))}; 'thesis' "
        "for the thesis's four, 'all' (default) for every model the inputs allow (the registry of capred shear)."
    )


def triaxial(
    models: option(TRIAX, "models", help=_models_help, shown="all") = None,
    c_eff: option(TRIAX, "c_eff", note="instead of the extended Mohr-Coulomb envelope at s -> 0") = None,
    phi_eff: option(TRIAX, "phi_eff", note="with --c-eff") = None,
    errors: option(
        TRIAX,
        "errors",
        metavar="either|proportional|constant|auto",
        help="Scatter of a test in the extended Mohr-Coulomb fit: either (default: intervals that hold whether it "
        "is constant or proportional to the strength), proportional, constant (ordinary least squares) or auto "
        "(Breusch-Pagan).",
    ) = None,
    bootstrap: option(TRIAX, "bootstrap", help="Replicates of the ranking bootstrap per material (0: none).") = None,
    seed: option(TRIAX, "seed", help="Seed of the ranking bootstrap.") = None,
    s_res: option(PARAMS, "s_res", note="(Vanapalli et al. 1996)") = None,
    vanapalli_kappa: option(PARAMS, "vanapalli_kappa", note="(Vanapalli et al. 1996)") = None,
    air_entry: option(PARAMS, "air_entry", note="(Khalili & Khabbaz 1998)") = None,
    vg_alpha: option(PARAMS, "vg_alpha", note="(Lu & Likos 2006)") = None,
    vg_n: option(PARAMS, "vg_n", note="(Lu & Likos 2006)") = None,
    **model_options,
) -> Invocation:
    """Unsaturated strength from triaxial failure states, per material.

    The extended Mohr-Coulomb envelope c', phi', phi_b (Fredlund et al. 1978), the comparison of the effective-stress
    models of capred shear on q_f, the back-analysed capillary stress and chi of each test, fitted chi laws, and Prunier
    et al.'s bounds on the envelope at s -> 0 (named; --c-eff/--phi-eff override it).

    Example: capred triaxial failure_states.csv --out triaxial

    \f

    Parameters
    ----------
    models : str, optional
        Models, comma separated.
    c_eff, phi_eff : str, optional
        The effective envelope [kPa, deg] instead of the fit at s -> 0.
    errors : str, optional
        either, proportional, constant or auto.
    bootstrap, seed : int, optional
        Ranking bootstrap.
    s_res, vanapalli_kappa, air_entry, vg_alpha, vg_n : optional
        Parameters of the models beyond the thesis's four.
    **model_options
        The parameters registered models declare for themselves (``--my-kappa``), as `capred shear` takes them.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.shear import ModelParams
    from ..pipelines.triaxial_strength import TriaxialStrengthOptions

    params = si_values(
        PARAMS, s_res=s_res, vanapalli_kappa=vanapalli_kappa, air_entry=air_entry, vg_alpha=vg_alpha, vg_n=vg_n
    )
    own = model_parameter_values(model_options)
    mp = ModelParams(**params, **({"extra": own} if own else {}))
    given = si_values(TRIAX, models=models, c_eff=c_eff, phi_eff=phi_eff, errors=errors, bootstrap=bootstrap, seed=seed)
    return Invocation("triaxial", TriaxialStrengthOptions(**given, model_params=mp))
