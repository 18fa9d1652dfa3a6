"""`capred prism`, `capred skempton-b`, `capred rumpf`: closed-form calculators, from options or a table of cases."""

from __future__ import annotations

import typer

from .common import Invocation, command
from .declare import option, si_values

PRISM = "capred.spec.calculators:PrismOptions"
SKEMPTON = "capred.spec.calculators:SkemptonOptions"
RUMPF = "capred.spec.calculators:RumpfOptions"
SHEAR_BAND = "capred.spec.calculators:ShearBandOptions"
HISTORY = "capred.spec.history:HistoryOptions"


def register(app: typer.Typer) -> None:
    """Register the commands of prism, skempton-b, rumpf and history on the application.

    Parameters
    ----------
    app : typer.Typer
        The capred application.
    """
    command(app, "prism", data="Optional CSV of cases: break_tension, friction_angle")(prism)
    command(app, "skempton-b", data="Optional CSV of cases: S_r (or B), and any of kappa, e0, p0, u0, pa0")(skempton_b)
    command(
        app,
        "rumpf",
        data="Optional CSV of cases (shape_factor, void_ratio, S_r, diameter, surface_tension, contact_angle)",
        plots=False,
    )(rumpf)
    command(
        app,
        "shear-band",
        data="Optional CSV of cases: phi, dilatancy_angle (or dilatancy_rate), shear_band_angle (measured)",
        plots=False,
    )(shear_band)
    command(app, "history", data="The lab's store (SQLite), written by any command with --store or CAPRED_STORE")(
        history
    )


def prism(
    break_tension: option(PRISM, "break_tension", note="any pressure unit, g/cm^2 read as gram-force") = None,
    friction_angle: option(PRISM, "friction_angle") = None,
    gamma_w: option(PRISM, "gamma_w") = None,
) -> Invocation:
    """Bernatzik's (1948) prism test: maximal capillary pressure and capillary rise.

    P_kmax = sigma_b (1 - sin rho)/(2 sin rho) and h_c = P_kmax/gamma_w.

    Example: capred prism --break-tension "115 g/cm^2" --friction-angle 36

    \f

    Parameters
    ----------
    break_tension : str, optional
        Break tension sigma_b [kPa], as typed: a number in the unit given, or with a unit of its own (g/cm^2 read as
        gram-force).
    friction_angle : float, optional
        Friction angle rho [deg].
    gamma_w : str, optional
        Unit weight of water [kN/m^3].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.calculators import PrismOptions

    opts = PrismOptions(**si_values(PRISM, break_tension=break_tension, friction_angle=friction_angle, gamma_w=gamma_w))
    return Invocation("prism", opts)


def skempton_b(
    S_R: option(SKEMPTON, "S_R", "--S-R", "--sr", note=": compute B") = None,
    b: option(SKEMPTON, "b", "--b", help="Measured B", note=": compute S_R") = None,
    kappa_elastic: option(SKEMPTON, "kappa_elastic", "--kappa-elastic", "--kappa") = None,
    e0: option(SKEMPTON, "e0") = None,
    p0: option(SKEMPTON, "p0") = None,
    u0: option(SKEMPTON, "u0") = None,
    pa0: option(SKEMPTON, "pa0") = None,
    se: option(SKEMPTON, "s_e", "--se", note=": simulation with suction equilibrium") = None,
    bc_lambda: option(
        SKEMPTON, "bc_lambda", "--bc-lambda", "--bc-alpha", note="(alpha in Morvan et al. 2016), with --se"
    ) = None,
    model: option(
        SKEMPTON,
        "model",
        metavar="elastic|bounding-surface|elastoplastic",
        help="Skeleton model: elastic (eq. 10, or with --se/--bc-lambda suction equilibrium, section 3); "
        "bounding-surface (section 4 by capred's Cam-clay bounding-surface reconstruction, not the BDNS "
        "model of the paper's ref. [16]; Table 3 defaults); elastoplastic is refused, with the reason.",
    ) = None,
    a_ini: option(
        SKEMPTON,
        "a_ini",
        "--a-ini",
        help="Initial distance A_ini of the bounding surface's apex above p'0",
        note="(Morvan et al. 2016, Table 3: 0 normally consolidated, 10 over-consolidated), with --model "
        "bounding-surface. Default 0",
    ) = None,
    interpolation_h: option(
        SKEMPTON,
        "interpolation_h",
        "--interpolation-h",
        help="Dafalias-type interpolation constant h [-] of the reconstruction; required with --a-ini > 0 "
        "(no published value: h = 336 meets the paper's Fig. 6 value 0.04 with --air-pressure gauge).",
    ) = None,
    air_pressure: option(
        SKEMPTON,
        "air_pressure",
        "--air-pressure",
        metavar="absolute|gauge",
        help="With --model bounding-surface: absolute (Boyle's law on pa0, p' = p0 - u0 + s S_r) or gauge "
        "(u0 in Boyle's law, p' = p0 + s S_r: the convention under which the paper's Fig. 6 values come "
        "out; Boyle's law needs absolute pressure, so this warns).",
    ) = None,
    lambda0: option(
        SKEMPTON,
        "lambda0",
        "--lambda0",
        help="Slope lambda0 of the normal compression line",
        note="(Table 3: 0.2), with --model bounding-surface",
    ) = None,
    retention: option(
        SKEMPTON,
        "retention",
        help="fits.json of capred retention (any model): s_e and lambda of Brooks-Corey from it (another "
        "model is converted to Brooks-Corey, the misfit reported); instead of --se and --bc-lambda.",
    ) = None,
    curve: option(
        SKEMPTON,
        "curve",
        "--curve",
        help="B against S_r (0.5-1) for the models asked instead of cases: eq. 10; with --se/--bc-lambda "
        "suction equilibrium; with --model bounding-surface NC and (with --a-ini) OC; as Morvan et al. "
        "(2016) Fig. 1-3, 5, 6. Give --out for the figure.",
    ) = False,
    compression: option(
        SKEMPTON,
        "compression",
        "--compression",
        help="compression.json of capred compression: kappa and e0 (and lambda0 with --model bounding-surface) "
        "from it, instead of --kappa-elastic and --e0.",
    ) = None,
    compare: option(
        SKEMPTON,
        "compare",
        "--compare",
        help="With --curve: classical B(S_r) relations drawn beside eq. 10 on the same skeleton, comma separated: "
        "skempton1954, hilf_lade, schuurman1966, or all (Morvan et al. 2016's comparison).",
    ) = None,
) -> Invocation:
    """Skempton's B against degree of saturation (Morvan et al. 2016, eq. 10).

    B = 1/(1 + p'0 e0 (1 - S_r)/(kappa P_a0)) with p'0 = p0 - u0, or its inverse S_r from a measured B; with --se and
    --bc-lambda, the simulation with suction equilibrium (p'0 = p0 - u_a0 + s S_r). Defaults are those of Morvan et al.
    (2016), Table 1. With --model bounding-surface, the two incremental loops of section 4 with capred's Cam-clay
    bounding-surface reconstruction (not the BDNS model of the paper's ref. [16], whose equations are not published in a
    source we could reach); Table 3 fills s_e = 20 kPa, lambda = 0.8, lambda0 = 0.2, A_ini = 0.

    Example: capred skempton-b --S-R 0.9 --kappa-elastic 0.06

    Example: capred skempton-b --S-R 0.9 --model bounding-surface --a-ini 10 --interpolation-h 336

    Example: capred skempton-b --curve --model bounding-surface --a-ini 10 --interpolation-h 336 --out fig6

    \f

    Parameters
    ----------
    S_R : float, optional
        Degree of saturation [-]: compute B.
    b : float, optional
        Measured B [-]: compute S_R.
    kappa_elastic : float, optional
        Slope of the elastic line in e-ln p' [-].
    e0 : float, optional
        Initial void ratio [-].
    p0, u0, pa0 : str, optional
        Mean total stress, initial pore pressure, absolute initial air pressure [kPa].
    se : str, optional
        Air-entry suction s_e of Brooks-Corey [kPa].
    bc_lambda : float, optional
        Brooks-Corey pore-size index [-].
    model : str, optional
        elastic, bounding-surface or elastoplastic (refused).
    a_ini : str, optional
        Initial distance of the bounding surface's apex above p'0 [kPa].
    interpolation_h : float, optional
        Interpolation constant h of the reconstruction [-].
    air_pressure : str, optional
        absolute or gauge (bounding-surface).
    lambda0 : float, optional
        Slope of the normal compression line [-].
    retention : Path, optional
        A fits.json of `capred retention` instead of --se and --bc-lambda.
    curve : bool, optional
        B against S_r for every model asked instead of cases.
    compression : Path, optional
        A compression.json of `capred compression` instead of --kappa-elastic and --e0.
    compare : str, optional
        Classical relations beside eq. 10 with --curve (comma separated, or all).

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.calculators import SkemptonOptions

    given = si_values(
        SKEMPTON,
        S_R=S_R,
        b=b,
        kappa_elastic=kappa_elastic,
        e0=e0,
        p0=p0,
        u0=u0,
        pa0=pa0,
        s_e=se,
        bc_lambda=bc_lambda,
        a_ini=a_ini,
        lambda0=lambda0,
        model=model,
        interpolation_h=interpolation_h,
        air_pressure=air_pressure,
        retention=retention,
        curve=curve,
        compression=compression,
    )
    if compression is not None and (kappa_elastic is not None or e0 is not None):
        from ..errors import OptionError

        raise OptionError("give --compression or --kappa-elastic/--e0, not both")
    if compare:
        given["compare"] = tuple(c.strip() for c in str(compare).split(",") if c.strip())
    opts = SkemptonOptions(**given)
    extra = [p for p in (retention, compression) if p]
    return Invocation("skempton-b", opts, extra_inputs=extra)


def rumpf(
    shape_factor: option(RUMPF, "shape_factor") = None,
    void_ratio: option(RUMPF, "void_ratio") = None,
    S_R: option(RUMPF, "S_R", "--S-R", "--sr") = None,
    diameter: option(RUMPF, "diameter") = None,
    surface_tension: option(RUMPF, "surface_tension") = None,
    contact_angle: option(RUMPF, "contact_angle") = None,
) -> Invocation:
    """Rumpf's capillary pressure (Prunier et al. 2024, eq. 19); negative means tension.

    p_cap = -(6/phi)(S_r/e)(gamma/d_p) cos(theta).

    Example: capred rumpf --shape-factor 1 --void-ratio 0.5 --S-R 0.3 --diameter 0.2

    \f

    Parameters
    ----------
    shape_factor : float, optional
        Particle shape factor phi [-].
    void_ratio : float, optional
        Void ratio e [-].
    S_R : float, optional
        Degree of saturation [-].
    diameter : str, optional
        Apparent particle diameter d_p [mm].
    surface_tension : str, optional
        Surface tension gamma [N/m].
    contact_angle : float, optional
        Contact angle [deg].

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.calculators import RumpfOptions

    opts = RumpfOptions(
        **si_values(
            RUMPF,
            shape_factor=shape_factor,
            void_ratio=void_ratio,
            S_R=S_R,
            diameter=diameter,
            surface_tension=surface_tension,
            contact_angle=contact_angle,
        )
    )
    return Invocation("rumpf", opts)


def history(
    material: option(
        HISTORY, "material", help="Material as the runs name it (needed when the store holds several)."
    ) = None,
    quantity: option(
        HISTORY, "quantity", help="Quantity: a key of the runs' JSON, e.g. phi_deg, c_kPa (shear)."
    ) = None,
    baseline: option(HISTORY, "baseline", help="First runs that set the centre line and the 3-sigma limits.") = None,
    reference: option(
        HISTORY, "reference", help="Reference value of the quantity (its unit), instead of the baseline."
    ) = None,
    spread: option(
        HISTORY, "spread", help="Standard deviation of the reference value (its unit), with --reference."
    ) = None,
    of_command: option(HISTORY, "command", "--of-command", help="Only the runs of this command (e.g. shear).") = None,
) -> Invocation:
    """A lab's history: one quantity of one material per recorded run, on an individuals chart.

    Each run's value with its 95 % interval, on an individuals chart with moving range (centre line and 3-sigma limits
    from the first 8 runs, sigma = mean moving range / 1.128, or from --reference and --spread); runs beyond the limits
    are flagged. Record runs with --store lab.sqlite on any command (or CAPRED_STORE).

    Example: capred history lab.sqlite --material "Toyoura sand" --quantity phi_deg --out chart

    \f

    Parameters
    ----------
    material : str, optional
        Material as the runs name it.
    quantity : str, optional
        A key of the runs' JSON, e.g. phi_deg.
    baseline : int, optional
        Number of first runs that set the centre line and limits [-].
    reference : float, optional
        Reference value of the quantity (its unit), instead of the baseline.
    spread : float, optional
        Standard deviation of the reference value (its unit).
    of_command : str, optional
        Only the runs of this command.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.history import HistoryOptions

    given = si_values(
        HISTORY,
        material=material,
        quantity=quantity,
        baseline=baseline,
        reference=reference,
        spread=spread,
        command=of_command,
    )
    return Invocation("history", HistoryOptions(**given))


def shear_band(
    phi_eff: option(SHEAR_BAND, "phi_eff", "--phi-eff", "--phi", note="(or --triaxial)") = None,
    dilatancy_angle: option(SHEAR_BAND, "dilatancy_angle") = None,
    dilatancy_rate: option(
        SHEAR_BAND, "dilatancy_rate", help="Rate of dilation at failure -d eps_v/d eps_1 [-]"
    ) = None,
    measured: option(SHEAR_BAND, "measured", help="Measured angle of the band to the major principal plane") = None,
    triaxial: option(
        SHEAR_BAND, "triaxial", help="summary.json of capred triaxial-bounds: phi' of its envelope."
    ) = None,
) -> Invocation:
    """Shear-band angles to the major principal plane, beside a measured angle.

    Coulomb 45 + phi'/2, Roscoe (1970) 45 + psi/2 and Arthur et al. (1977) 45 + (phi' + psi)/4 (Prunier et al. 2024,
    Fig. 14: about 70 and 60 deg).

    Example: capred shear-band --triaxial results/summary.json --dilatancy-angle 8 --measured 60

    \f

    Parameters
    ----------
    phi_eff : str, optional
        Effective friction angle [deg].
    dilatancy_angle : str, optional
        Dilatancy angle [deg].
    dilatancy_rate : float, optional
        -d eps_v/d eps_1 at failure [-].
    measured : str, optional
        Measured angle [deg].
    triaxial : Path, optional
        A triaxial-bounds summary.json.

    Returns
    -------
    Invocation
        The command's options record, run by :func:`capred.cli.common.execute` with the options every command shares.
    """
    from ..pipelines.calculators import ShearBandOptions

    given = si_values(
        SHEAR_BAND,
        phi_eff=phi_eff,
        dilatancy_angle=dilatancy_angle,
        dilatancy_rate=dilatancy_rate,
        measured=measured,
        triaxial=None if triaxial is None else str(triaxial),
    )
    return Invocation("shear-band", ShearBandOptions(**given), extra_inputs=[triaxial] if triaxial else [])
