"""`capred pt-volume`: the volume-change model of Pedrotti & Tarantino along a path read from a table."""

from typing import Annotated

import typer

from .common import Invocation, SampleOpt, command, quantity


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


def _line(value: float | None, name: str, option: str) -> str | None:
    return quantity(None if value is None else repr(float(value)), "", name, option)


def pt_volume(
    lambda_w: Annotated[
        float | None,
        typer.Option(
            "--lambda-w", help="Slope lambda_W of the ncl of the clay reconstituted from slurry, in e-ln sigma' [-]."
        ),
    ] = None,
    kappa_w: Annotated[float | None, typer.Option("--kappa-w", help="Slope kappa_W of its url [-].")] = None,
    e_ncl_w: Annotated[
        float | None, typer.Option("--e-ncl-w", help="Void ratio on the slurry ncl at --reference-stress [-].")
    ] = None,
    lambda_a: Annotated[
        float | None,
        typer.Option("--lambda-a", help="Slope lambda_A of the ncl of the clay compressed from dry powder [-]."),
    ] = None,
    kappa_a: Annotated[float | None, typer.Option("--kappa-a", help="Slope kappa_A of its url [-].")] = None,
    e_ncl_a: Annotated[
        float | None, typer.Option("--e-ncl-a", help="Void ratio on the dry-powder ncl at --reference-stress [-].")
    ] = None,
    reference_stress: Annotated[str, typer.Option(help="Stress at which the ncl void ratios are read [kPa].")] = "1",
    example_kaolin: Annotated[
        bool,
        typer.Option(
            "--example-kaolin",
            help="Take the lines not given from "
            "EXAMPLE_KAOLIN: illustrative kaolin values, NOT from the paper "
            "(said in a warning).",
        ),
    ] = False,
    initial_yield_w: Annotated[
        str | None,
        typer.Option(
            "--initial-yield-w",
            help="Largest sigma'_W carried before the first point [kPa]; default: the first point's (on the ncl).",
        ),
    ] = None,
    initial_yield_a: Annotated[
        str | None,
        typer.Option(
            "--initial-yield-a",
            help="Largest sigma'_A carried before the first point [kPa]; default: the first point's (on the ncl).",
        ),
    ] = None,
    substeps: Annotated[
        int | None,
        typer.Option(
            help="Sub-steps per step between two points [default: "
            "automatic, |dS_r| <= 0.002 and |d ln sigma'| <= 0.02]; 1 takes "
            "the path as given."
        ),
    ] = None,
    sample: SampleOpt = False,
) -> Invocation:
    """Void ratio along a path of total stress, pore pressures and degree of
    saturation with the volume-change model of Pedrotti & Tarantino
    (submitted, eq. 1-10): sigma'_W = (sigma - u_w) S_r for the water-saturated
    pores on the lines of clay reconstituted from slurry, sigma'_A =
    (sigma - u_a)(1 - S_r) for the air-saturated pores on the lines of clay
    compressed from dry powder, pores changing fluid through the equivalent
    pre-consolidation stress, e of the sample from eq. 5. Needs the six line
    parameters (--lambda-w --kappa-w --e-ncl-w --lambda-a --kappa-a --e-ncl-a)
    or --example-kaolin; --sample runs the bundled illustrative path with
    EXAMPLE_KAOLIN unless lines are given.

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
    sample : bool, optional
        Run the bundled illustrative path.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.pt_volume import PTVolumeOptions

    lines = {
        "lambda_W": _line(lambda_w, "lambda_W", "--lambda-w"),
        "kappa_W": _line(kappa_w, "kappa_W", "--kappa-w"),
        "e_ncl_W": _line(e_ncl_w, "e_ncl_W", "--e-ncl-w"),
        "lambda_A": _line(lambda_a, "lambda_A", "--lambda-a"),
        "kappa_A": _line(kappa_a, "kappa_A", "--kappa-a"),
        "e_ncl_A": _line(e_ncl_a, "e_ncl_A", "--e-ncl-a"),
    }
    # the bundled path is drawn for EXAMPLE_KAOLIN (its header says so): --sample alone runs with it
    example = example_kaolin or (sample and all(v is None for v in lines.values()))
    opts = PTVolumeOptions(
        **lines,
        reference_stress=quantity(reference_stress, "kPa", "reference_stress", "--reference-stress"),
        example_kaolin=example,
        initial_yield_W=quantity(initial_yield_w, "kPa", "initial_yield_W", "--initial-yield-w"),
        initial_yield_A=quantity(initial_yield_a, "kPa", "initial_yield_A", "--initial-yield-a"),
        substeps=substeps,
    )
    return Invocation("pt-volume", opts)
