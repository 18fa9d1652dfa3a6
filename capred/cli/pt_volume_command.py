"""`capred pt-volume`: the volume-change model of Pedrotti & Tarantino along a path read from a table."""

from __future__ import annotations

from pathlib import Path

import typer

from .common import Invocation, SampleOpt, command
from .declare import option, si_values

PT = "capred.spec.pt_volume:PTVolumeOptions"


def register(app: typer.Typer) -> None:
    """Register the commands of `capred pt-volume` on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(
        app,
        "pt-volume",
        data="CSV, .xlsx or .ods files of a path, one row per point: sigma, u_w (or "
        "suction), u_a, S_r [kPa, -]; optional step and stage",
    )(pt_volume)


def pt_volume(
    lambda_w: option(PT, "lambda_W") = None,
    kappa_w: option(PT, "kappa_W") = None,
    e_ncl_w: option(PT, "e_ncl_W", note="(--reference-stress)") = None,
    lambda_a: option(PT, "lambda_A") = None,
    kappa_a: option(PT, "kappa_A") = None,
    e_ncl_a: option(PT, "e_ncl_A", note="(--reference-stress)") = None,
    reference_stress: option(PT, "reference_stress") = None,
    example_kaolin: option(PT, "example_kaolin", "--example-kaolin") = False,
    initial_yield_w: option(PT, "initial_yield_W", note="default: the first point's (on the ncl)") = None,
    initial_yield_a: option(PT, "initial_yield_A", note="default: the first point's (on the ncl)") = None,
    substeps: option(PT, "substeps", note="1 takes the path as given") = None,
    compression_w: option(
        PT,
        "compression_W",
        "--compression-w",
        help="compression.json of capred compression on the clay from slurry: lambda_W, kappa_W, e_ncl_W from it.",
    ) = None,
    compression_a: option(
        PT,
        "compression_A",
        "--compression-a",
        help="compression.json of capred compression on the clay from dry powder: lambda_A, kappa_A, e_ncl_A.",
    ) = None,
    sample: SampleOpt = False,
) -> Invocation:
    """Void ratio along a path of total stress, pore pressures and degree of saturation.

    With the volume-change model of Pedrotti & Tarantino (submitted, eq. 1-10): sigma'_W = (sigma - u_w) S_r for the
    water-saturated pores on the lines of clay reconstituted from slurry, sigma'_A = (sigma - u_a)(1 - S_r) for the
    air-saturated pores on the lines of clay compressed from dry powder, pores changing fluid through the equivalent
    pre-consolidation stress, e of the sample from eq. 5. Needs the six line parameters (--lambda-w --kappa-w --e-ncl-w
    --lambda-a --kappa-a --e-ncl-a) or --example-kaolin; --sample runs the bundled illustrative path with EXAMPLE_KAOLIN
    unless lines are given.

    Example: capred pt-volume path.csv --lambda-w 0.18 --kappa-w 0.03 --e-ncl-w 2.23 --lambda-a 0.13 --kappa-a 0.01 --e-ncl-a 2.06

    \f

    Parameters
    ----------
    lambda_w, kappa_w, e_ncl_w : float, optional
        Slopes of the ncl and url and ncl void ratio of the clay reconstituted from slurry [-].
    lambda_a, kappa_a, e_ncl_a : float, optional
        The same for the clay compressed from dry powder [-].
    reference_stress : str, optional
        Stress at which the ncl void ratios are read [kPa].
    example_kaolin : bool, optional
        Take the lines not given from EXAMPLE_KAOLIN (illustrative).
    initial_yield_w, initial_yield_a : str, optional
        Largest sigma'_W, sigma'_A carried before the first point [kPa].
    substeps : int, optional
        Sub-steps per step [-] (default automatic).
    compression_w, compression_a : Path, optional
        compression.json files of `capred compression` giving the W or A lines.
    sample : bool, optional
        Run the bundled illustrative path.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.pt_volume import PTVolumeOptions

    lines = si_values(
        PT,
        lambda_W=lambda_w,
        kappa_W=kappa_w,
        e_ncl_W=e_ncl_w,
        lambda_A=lambda_a,
        kappa_A=kappa_a,
        e_ncl_A=e_ncl_a,
    )
    # the bundled path is drawn for EXAMPLE_KAOLIN (its header says so): --sample alone runs with it
    example = example_kaolin or (sample and not lines and not (compression_w or compression_a))
    given = si_values(
        PT,
        reference_stress=reference_stress,
        initial_yield_W=initial_yield_w,
        initial_yield_A=initial_yield_a,
        substeps=substeps,
    )
    fits = {"compression_W": compression_w, "compression_A": compression_a}
    fits = {k: str(v) for k, v in fits.items() if v is not None}
    opts = PTVolumeOptions(**lines, **given, **fits, example_kaolin=example)
    return Invocation("pt-volume", opts, extra_inputs=[Path(v) for v in fits.values()])
