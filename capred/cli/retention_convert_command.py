"""`capred retention-convert FIT.json --to MODEL`: a retention fit expressed in another model."""

from __future__ import annotations

from typing import Annotated

import typer

from .common import Invocation, command
from .declare import option, registry_names, si_values

CONVERT = "capred.spec.retention_convert:ConvertOptions"


def register(app: typer.Typer) -> None:
    """Add `capred retention-convert` to the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(
        app,
        "retention-convert",
        data="fits.json written by capred retention (or a table of retention readings, fitted first)",
    )(retention_convert)


def retention_convert(
    to: Annotated[
        str,
        typer.Option(
            "--to", help="Target model: " + ", ".join(registry_names("retention_models")) + ".", show_default=False
        ),
    ],
    model: option(CONVERT, "model") = None,
    branch: option(CONVERT, "branch") = None,
    points: option(CONVERT, "points") = None,
    gamma_w: option(CONVERT, "gamma_w", note="(heads in cm in the JSON)") = None,
) -> Invocation:
    """Express a retention fit in another model.

    The parameters of --to that best reproduce the fitted curve (least squares on S_R or theta at the data's own
    suctions and a dense grid between), with the misfit (RMSE, largest deviation) and a figure of both curves. The
    output fits.json has the shape of capred retention's, so --retention of shear and skempton-b reads it.

    Example: capred retention-convert capred_out/retention_column/fits.json --to bc

    \f

    Parameters
    ----------
    to : str
        Target model.
    model : str, optional
        Which fit of FIT.json to convert.
    branch : str, optional
        Which branch of FIT.json.
    points : int, optional
        Points of the logarithmic suction grid [-].
    gamma_w : str, optional
        Unit weight of water [kN/m^3].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.retention_convert import ConvertOptions

    opts = ConvertOptions(
        to=to.strip().lower(),
        **si_values(
            CONVERT, model=model.strip().lower() if model else None, branch=branch, gamma_w=gamma_w, points=points
        ),
    )
    return Invocation("retention-convert", opts)
