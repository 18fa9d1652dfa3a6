"""`capred prism`, `capred skempton-b`, `capred rumpf`: closed-form calculators, from options or a table of cases."""

from typing import Annotated

import typer

from .common import Invocation, command, quantity


def register(app: typer.Typer) -> None:
    command(app, "prism", data="Optional CSV of cases: break_tension, friction_angle", plots=False)(prism)
    command(app, "skempton-b", data="Optional CSV of cases: S_r (or B), and any of kappa, e0, p0, u0, pa0")(skempton_b)
    command(
        app,
        "rumpf",
        data="Optional CSV of cases (shape_factor, void_ratio, S_r, diameter, surface_tension, contact_angle)",
        plots=False,
    )(rumpf)


def _number(value: float | None, name: str, option: str) -> float | None:
    return quantity(None if value is None else repr(float(value)), "", name, option)


def prism(
    break_tension: Annotated[
        str | None,
        typer.Option(help="Break tension sigma_b of the prism [kPa]; any pressure unit, g/cm^2 read as gram-force."),
    ] = None,
    friction_angle: Annotated[float | None, typer.Option(help="Friction angle rho of the sand [deg].")] = None,
    gamma_w: Annotated[str, typer.Option(help="Unit weight of water [kN/m^3].")] = "9.81",
) -> Invocation:
    """Bernatzik's (1948) prism test: maximal capillary pressure
    P_kmax = sigma_b (1 - sin rho)/(2 sin rho) and capillary rise h_c = P_kmax/gamma_w.

    Example: capred prism --break-tension "115 g/cm^2" --friction-angle 36
    """
    from ..pipelines.calculators import PrismOptions

    opts = PrismOptions(
        quantity(break_tension, "kPa", "break_tension", "--break-tension"),
        quantity(None if friction_angle is None else str(friction_angle), "deg", "friction_angle", "--friction-angle"),
        quantity(gamma_w, "kN/m^3", "gamma_w", "--gamma-w"),
    )
    return Invocation("prism", opts)


def skempton_b(
    S_R: Annotated[float | None, typer.Option("--S-R", "--sr", help="Degree of saturation S_R [-]: compute B.")] = None,
    b: Annotated[float | None, typer.Option("--b", help="Measured B [-]: compute S_R.")] = None,
    kappa_elastic: Annotated[
        float, typer.Option("--kappa-elastic", "--kappa", help="Slope kappa of the elastic line in e-ln p' [-].")
    ] = 0.006,
    e0: Annotated[float, typer.Option(help="Initial void ratio.")] = 0.8,
    p0: Annotated[str, typer.Option(help="Mean total stress [kPa].")] = "100",
    u0: Annotated[str, typer.Option(help="Initial pore pressure [kPa].")] = "30",
    pa0: Annotated[str, typer.Option(help="Absolute initial air pressure [kPa].")] = "130",
    se: Annotated[
        str | None,
        typer.Option("--se", help="Air-entry suction s_e [kPa] (Brooks-Corey): simulation with suction equilibrium."),
    ] = None,
    bc_lambda: Annotated[
        float | None,
        typer.Option(
            "--bc-lambda",
            "--bc-alpha",
            help="Brooks-Corey pore-size index lambda (alpha in Morvan et al. 2016), with --se.",
        ),
    ] = None,
    model: Annotated[
        str,
        typer.Option(
            metavar="elastic|elastoplastic",
            help="Skeleton model: elastic (eq. 10, or with suction equilibrium); "
            "elastoplastic (section 4) is not available, see the README.",
        ),
    ] = "elastic",
    a_ini: Annotated[
        str | None,
        typer.Option(
            "--a-ini",
            help="Initial position A_ini of the bounding "
            "surface [kPa] (Morvan et al. 2016, Table 3), with --model "
            "elastoplastic.",
        ),
    ] = None,
    retention: Annotated[
        str | None,
        typer.Option(
            help="fits.json of capred retention (any model): s_e and lambda of Brooks-Corey from it (another "
            "model is converted to Brooks-Corey, the misfit reported); instead of --se and --bc-lambda."
        ),
    ] = None,
) -> Invocation:
    """Skempton's B against degree of saturation (Morvan et al. 2016, eq. 10):
    B = 1/(1 + p'0 e0 (1 - S_r)/(kappa P_a0)) with p'0 = p0 - u0, or its inverse
    S_r from a measured B; with --se and --bc-lambda, the simulation with suction
    equilibrium (p'0 = p0 - u_a0 + s S_r). Defaults are those of Morvan et al.
    (2016), Table 1.

    Example: capred skempton-b --S-R 0.9 --kappa-elastic 0.06
    """
    from ..pipelines.calculators import SkemptonOptions

    opts = SkemptonOptions(
        _number(S_R, "S_R", "--S-R"),
        _number(b, "B", "--b"),
        _number(kappa_elastic, "kappa_elastic", "--kappa-elastic"),
        _number(e0, "e0", "--e0"),
        quantity(p0, "kPa", "p0", "--p0"),
        quantity(u0, "kPa", "u0", "--u0"),
        quantity(pa0, "kPa", "pa0", "--pa0"),
        quantity(se, "kPa", "air_entry", "--se"),
        _number(bc_lambda, "bc_lambda", "--bc-lambda"),
        model=model,
        a_ini=quantity(a_ini, "kPa", "p0", "--a-ini"),
        retention=retention,
    )
    return Invocation("skempton-b", opts, extra_inputs=[retention] if retention else [])


def rumpf(
    shape_factor: Annotated[float | None, typer.Option(help="Particle shape factor phi [-].")] = None,
    void_ratio: Annotated[float | None, typer.Option(help="Void ratio e [-].")] = None,
    S_R: Annotated[float | None, typer.Option("--S-R", "--sr", help="Degree of saturation S_R [-].")] = None,
    diameter: Annotated[str | None, typer.Option(help="Apparent particle diameter d_p [mm].")] = None,
    surface_tension: Annotated[str, typer.Option(help="Surface tension gamma [N/m].")] = "0.0728",
    contact_angle: Annotated[float, typer.Option(help="Contact angle [deg].")] = 0.0,
) -> Invocation:
    """Rumpf's capillary pressure p_cap = -(6/phi)(S_r/e)(gamma/d_p) cos(theta)
    (Prunier et al. 2024, eq. 19); negative means tension.

    Example: capred rumpf --shape-factor 1 --void-ratio 0.5 --S-R 0.3 --diameter 0.2
    """
    from ..pipelines.calculators import RumpfOptions

    opts = RumpfOptions(
        _number(shape_factor, "shape_factor", "--shape-factor"),
        _number(void_ratio, "void_ratio", "--void-ratio"),
        _number(S_R, "S_R", "--S-R"),
        quantity(diameter, "mm", "diameter", "--diameter"),
        quantity(surface_tension, "N/m", "surface_tension", "--surface-tension"),
        quantity(repr(float(contact_angle)), "deg", "contact_angle", "--contact-angle"),
    )
    return Invocation("rumpf", opts)
