"""`capred bridge curve | solve | compare | rupture | laws | yade-files`: exact capillary bridges.

Between two spheres or a sphere and a plane.
"""

from __future__ import annotations

from typing import Annotated

import typer

from .common import Invocation, command
from .declare import option, si_values
from .help import HelpGroup

#: points of a `bridge laws` grid given by options solved without --yes (the default grid: 504)
MAX_GRID_POINTS = 5000

CURVE = "capred.spec.bridge:CurveOptions"
BRIDGE = "capred.spec.bridge:BridgeOptions"
YADE = "capred.spec.bridge:YadeOptions"
LAWS = "capred.spec.bridge:LawsOptions"


def register(app: typer.Typer) -> None:
    """Register the commands of `capred bridge` (curve, solve, compare, rupture, yade-files, laws) on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    bridge_app = typer.Typer(
        help="Exact capillary bridges between two spheres or a sphere and a plane "
        "(Young-Laplace): solve, rupture, the thesis's analytical comparison, checks "
        "against microscopic tests and YADE capillary files.",
        short_help="Exact capillary bridges (Young-Laplace): solve, rupture, laws, YADE files.",
        no_args_is_help=True,
        rich_markup_mode=None,
        cls=HelpGroup,  # help wrapped between words, never at a hyphen
    )
    app.add_typer(bridge_app, name="bridge")
    command(bridge_app, "curve", "bridge curve")(curve)
    command(
        bridge_app,
        "solve",
        "bridge solve",
        data="CSV, one bridge per row: R (and R2: a radius or 'plane'), gamma, contact_angle (and contact_angle2), "
        "gap, and suction or V_w",
        plots=False,
    )(solve)
    command(
        bridge_app,
        "rupture",
        "bridge rupture",
        data="CSV, one case per row: R, contact_angle, V_w (and R2: a radius or 'plane')",
    )(rupture)
    command(bridge_app, "yade-files", "bridge yade-files", plots=False)(yade_files)
    command(
        bridge_app,
        "laws",
        "bridge laws",
        data="CSV grid, one point per row: D_over_R, V_over_R3, contact_angle (and R2_over_R: a ratio or 'plane'); "
        "without it, the grid of the options",
    )(laws)
    command(
        bridge_app,
        "compare",
        "bridge compare",
        data="CSV of microscopic tests: R (and R2), contact_angle, gap, V_w, measured F_cap (and filling_angle)",
    )(compare)


def curve(
    radius: option(CURVE, "radius", note="(2 mm steel spheres: 1)") = None,
    surface_tension: option(CURVE, "surface_tension") = None,
    contact_angle: option(CURVE, "contact_angle") = None,
    points: option(CURVE, "points", help="Number of S_R values.") = None,
    S_R_max: option(
        CURVE,
        "S_R_max",
        "--S-R-max",
        "--sr-max",
        help="Largest S_R of the sweep (bridges stop where suction reaches 0).",
    ) = None,
    pendular_limit: option(CURVE, "pendular_limit", note="the bound of the pendular regime panel") = None,
) -> Invocation:
    """Evenepoel's analytical comparison: sigma' = F_cap/(pi R^2) against S_R = 3 V_w/(2 pi R^3).

    For two spheres in contact, from exact bridges, beside Israelachvili, Bishop, Own 1 and Own 2; one panel inside the
    pendular regime and one over the whole concave range.

    Example: capred bridge curve --radius 1 --contact-angle 0 --points 2000

    \f

    Parameters
    ----------
    radius : str, optional
        Particle radius R [mm], as typed: a number in the unit given, or with a unit of its own.
    surface_tension : str, optional
        Surface tension gamma [N/m].
    contact_angle : float, optional
        Contact angle [deg].
    points : int, optional
        Number of S_R values [-].
    S_R_max : float, optional
        Largest S_R of the sweep [-].
    pendular_limit : float, optional
        S_R bound of the pendular regime panel [-].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.bridge import CurveOptions

    opts = CurveOptions(
        **si_values(
            CURVE,
            radius=radius,
            surface_tension=surface_tension,
            contact_angle=contact_angle,
            points=points,
            S_R_max=S_R_max,
            pendular_limit=pendular_limit,
        )
    )
    return Invocation("bridge curve", opts)


def solve(
    surface_tension: option(BRIDGE, "surface_tension", note="of rows without 'gamma'") = None,
    contact_angle2: option(
        BRIDGE,
        "contact_angle2",
        "--contact-angle2",
        note="on the second particle (sphere R2 or plane) of rows without a 'contact_angle2' value "
        "[default: the row's contact_angle]",
    ) = None,
    workers: option(
        BRIDGE,
        "workers",
        help="Processes that solve the rows (results identical for any number) [default: CAPRED_PROCESSES, "
        "else the cores this run may use that the load leaves idle]; with several files, worker processes "
        "of the batch.",
    ) = None,
    branch: option(
        BRIDGE,
        "branch",
        "--branch",
        metavar="stable|thin",
        help="Rows given V_w: stable (the bridge continuous with the bridge at contact) or thin (the second, "
        "thin-neck bridge of the same volume and gap, near rupture, unstable at constant volume). Rows that have "
        "a second bridge say so in their note.",
    ) = None,
) -> Invocation:
    """Exact bridge per row between spheres of radii R and R2 (or a sphere and a plane).

    Neck radius r0, F_cap = F_L + F_T, V_w, filling angles on both particles, liquid-gas area and its n(x)n integrals
    (nn11, nn33), S_R = 3V_w/(2 pi R^3) and sigma' = F_cap/(pi R^2). Each particle may have its own contact angle
    (columns contact_angle and contact_angle2). Every bridge is verified to reproduce its gap and volume (or suction) to
    1e-9; a row without one (beyond rupture, too much water) gets a status, not an error.

    Example: capred bridge solve cases.csv --json

    \f

    Parameters
    ----------
    surface_tension : str, optional
        Surface tension gamma [N/m] of rows without 'gamma'.
    contact_angle2 : float, optional
        Contact angle on the second particle [deg] of rows without one.
    workers : int, optional
        Processes that solve the rows [-].
    branch : str, optional
        stable or thin (rows given V_w).

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.bridge import BridgeOptions

    opts = BridgeOptions(
        **si_values(
            BRIDGE, surface_tension=surface_tension, contact_angle2=contact_angle2, workers=workers, branch=branch
        )
    )
    return Invocation("bridge solve", opts)


def compare(
    surface_tension: option(BRIDGE, "surface_tension", note="of rows without 'gamma'") = None,
) -> Invocation:
    """Microscopic tests against theory: the measured force of each sphere pair beside the models, with residuals.

    The exact bridge of the same R, gap, contact angle and V_w, the toroidal approximation, Willett et al. (2000),
    Israelachvili and each closed-form law of `capred bridge laws`.

    Example: capred bridge compare micro_tests.csv --out micro

    \f

    Parameters
    ----------
    surface_tension : str, optional
        Surface tension gamma [N/m] of rows without 'gamma'.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.bridge import BridgeOptions

    opts = BridgeOptions(**si_values(BRIDGE, surface_tension=surface_tension))
    return Invocation("bridge compare", opts)


def rupture(
    surface_tension: option(
        BRIDGE, "surface_tension", note="of rows without 'gamma' (for the suction and force at rupture)"
    ) = None,
) -> Invocation:
    """Rupture distance at constant volume, beside Lian et al.'s (1993) estimate.

    The widest gap a bridge of volume V_w spans between particles of radii R and R2 (or a sphere and a plane), beside
    the estimate D = (1 + theta/2) V^(1/3), with the bridge at rupture; figure of both against V^(1/3).

    Example: capred bridge rupture volumes.csv --out rupture

    \f

    Parameters
    ----------
    surface_tension : str, optional
        Surface tension gamma [N/m] of rows without 'gamma'.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.bridge import BridgeOptions

    opts = BridgeOptions(**si_values(BRIDGE, surface_tension=surface_tension))
    return Invocation("bridge rupture", opts)


def yade_files(
    ratios: option(YADE, "ratios", help="Radius ratios R2/R1 >= 1, comma-separated (YADE opens these ten).") = None,
    contact_angle: option(YADE, "contact_angle", "--contact-angle", "--theta") = None,
    distances: option(
        YADE, "distances", help="Distances per file, 0 to the largest gap bridged at zero suction."
    ) = None,
    suctions: option(
        YADE,
        "suctions",
        help="Suctions per distance: 0, then geometric from uc* = 0.002 to a mean filling angle of 1 deg at contact.",
    ) = None,
) -> Invocation:
    """Capillary files for YADE's Law2_ScGeom_CapillaryPhys_Capillarity.

    One file M(r=<ratio>) per radius ratio, in YADE's layout and dimensionless variables, every row an exact stable
    bridge (with delta1, delta2, nn11, nn33). Run YADE from the output folder (or copy the M(r=...) files next to your
    script).

    Example: capred bridge yade-files --contact-angle 0 --out capillary_files

    \f

    Parameters
    ----------
    ratios : str, optional
        Radius ratios R2/R1 >= 1, comma-separated [-].
    contact_angle : float, optional
        Contact angle [deg].
    distances : int, optional
        Distances per file [-].
    suctions : int, optional
        Suctions per distance [-].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..errors import OptionError
    from ..pipelines.yade_files import YadeOptions

    given = si_values(YADE, contact_angle=contact_angle, distances=distances, suctions=suctions)
    if ratios is not None:
        try:
            given["ratios"] = tuple(float(x) for x in ratios.split(",") if x.strip())
        except ValueError:
            raise OptionError(f"--ratios: '{ratios}' is not a comma-separated list of numbers") from None
    return Invocation("bridge yade-files", YadeOptions(**given))


def laws(
    gaps: option(LAWS, "gaps", help="Gaps D/R of the default grid, comma-separated.") = None,
    volumes: option(LAWS, "volumes", help="Volumes V/R^3 of the default grid, comma-separated.") = None,
    angles: option(LAWS, "angles", help="Contact angles [deg] of the default grid, comma-separated.") = None,
    ratios: option(
        LAWS,
        "ratios",
        help="R2/R of the default grid, comma-separated ('plane': a sphere and a plane).",
        shown="1,2,plane",
    ) = None,
    tolerance: option(
        LAWS, "tolerance", help="Relative error under which a law counts as within, everywhere in a region."
    ) = None,
    yes: Annotated[
        bool,
        typer.Option("--yes", help=f"Solve a grid of more than {MAX_GRID_POINTS:,} points given by options."),
    ] = False,
) -> Invocation:
    """Which closed-form capillary force a DEM code should use.

    Each law of the registry ({laws}) against the exact Young-Laplace bridge at the same contact angle, volume and gap
    (the stable bridge at constant volume), forces in units of 2 pi R gamma; per region of gap x volume x angle x
    geometry each law's median and largest relative error and which laws stay within the tolerance; error maps, one
    panel per law.

    Example: capred bridge laws --sample --out laws

    \f

    Parameters
    ----------
    gaps : str, optional
        Gaps D/R of the grid, comma-separated [-].
    volumes : str, optional
        Volumes V/R^3 of the grid, comma-separated [-].
    angles : str, optional
        Contact angles of the grid, comma-separated [deg].
    ratios : str, optional
        R2/R of the grid, comma-separated ('plane': a sphere and a plane) [-].
    tolerance : float, optional
        Relative error under which a law counts as within [-].
    yes : bool, optional
        Solve a grid of more than MAX_GRID_POINTS points (a stated bound on the work an option asks for).

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..errors import OptionError
    from ..pipelines.bridge_laws import LawsOptions

    given = si_values(LAWS, gaps=gaps, volumes=volumes, angles=angles, ratios=ratios, tolerance=tolerance)
    opts = LawsOptions(**given)
    n = len(opts.gaps) * len(opts.volumes) * len(opts.angles) * len(opts.ratios)
    if n > MAX_GRID_POINTS and not yes:
        raise OptionError(
            f"the grid holds {n:,} points ({len(opts.gaps)} gaps x {len(opts.volumes)} volumes x {len(opts.angles)} "
            f"angles x {len(opts.ratios)} ratios), more than {MAX_GRID_POINTS:,}: each is an exact bridge solved "
            "(minutes for a grid this size); confirm with --yes, or give the points in a file (D_over_R, "
            "V_over_R3, contact_angle, R2_over_R)"
        )
    return Invocation("bridge laws", opts)
