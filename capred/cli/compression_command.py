"""`capred compression`: an oedometer or isotropic compression test reduced to its lines and yield stress."""

from __future__ import annotations

import typer

from .common import Invocation, SampleOpt, command
from .declare import option, si_values

CO = "capred.spec.compression:CompressionOptions"


def register(app: typer.Typer) -> None:
    """Register `capred compression` on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(
        app,
        "compression",
        data="CSV, .xlsx or .ods files of a compression test, one row per reading: sigma_eff (sigma_v or p') "
        "[kPa] and e, or height [mm] with --solids-height; optional stage (loading, unloading, reloading)",
    )(compression)


def compression(
    test: option(CO, "test", metavar="oedometer|isotropic") = None,
    solids_height: option(CO, "solids_height", note="when the file gives the specimen height") = None,
    reference_stress: option(CO, "reference_stress", note="where e_N is read") = None,
    sample: SampleOpt = False,
) -> Invocation:
    """Compression and swelling indices and the yield stress of an oedometer or isotropic compression test.

    Compression index C_c (lambda = C_c/ln 10), swelling index C_s (kappa), e_N at a reference stress and the yield
    stress: a smooth bilinear curve fitted to the first loading gives C_c and the bilinear yield stress, and on it the
    pre-consolidation stress by Casagrande (1936) and Pacheco Silva (1970); unloading stages give C_s, reloading stages
    C_r; each with SE and 95 % interval. compression.json feeds `skempton-b --compression` and `pt-volume
    --compression-w/--compression-a`.

    Example: capred compression oedometer.csv --out results/oedometer

    \f

    Parameters
    ----------
    test : str, optional
        oedometer or isotropic.
    solids_height : str, optional
        Height of the solids H_s [mm] (e = H/H_s - 1).
    reference_stress : str, optional
        Stress where e_N is read [kPa].
    sample : bool, optional
        Run the bundled synthetic oedometer test.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.compression import CompressionOptions

    given = si_values(CO, test=test, solids_height=solids_height, reference_stress=reference_stress)
    return Invocation("compression", CompressionOptions(**given))
