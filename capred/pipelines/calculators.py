"""`capred prism`, `capred skempton-b`, `capred rumpf`: closed-form calculators.

Each takes one case from options, or many from a CSV (one case per row,
units in headers as for `capred shear`); a value in the file wins over the
option, an option fills absent columns and blank cells.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, OptionError, Problem
from ..io import Column, read_table
from ..nomenclature import renamed_keywords
from ..physics import calculators as calc
from ..physics.shear import GAMMA_W, SURFACE_TENSION
from ..references import cite
from ..result import InputFile, Options, Result, input_file
from ..spec.calculators import (  # noqa: F401 (declared in spec; re-exported here)
    ELASTOPLASTIC_REFUSAL,
    SKEMPTON_MODELS,
    TABLE3,
    PrismOptions,
    RumpfOptions,
    ShearBandOptions,
    SkemptonOptions,
)
from .calculator_records import Cases, PrismCases, RumpfCases, ShearBandCases, SkemptonCases, SkemptonCurves

CASE = Column("case", "text", None, "case label")  # aliases: nomenclature.COLUMN_ALIASES


@dataclass(repr=False)
class CalcResult(Result):
    """Result of a calculator: its cases as a typed record (capred.pipelines.calculator_records), output units.

    ``cases.P_kmax`` (prism), ``cases.B`` (skempton-b), ``cases.p_cap`` (rumpf) ...: one array per field over the
    cases, in the units of the JSON and console; ``values`` and ``outputs`` give the inputs and the results as
    ``{JSON key: array}``.
    """

    calculator: str  # the command: prism, skempton-b or rumpf
    cases: Cases  # the typed per-case record: inputs and results, output units
    source: str | None
    notes: list[str] = field(default_factory=list)
    labels: list[str] | None = None
    options: Options | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    title: str = ""
    #: what the figure of the run is drawn from (skempton-b: the cases by parameter set and the options), or None
    figure_data: dict | None = None
    #: skempton-b: the skeleton model's name as every output gives it, and its inputs (JSON units)
    model: str | None = None
    model_inputs: dict | None = None

    json_name = "results.json"

    @property
    def command(self) -> str:
        """The command's name: the calculator's (``prism``, ``skempton-b``, ``rumpf``, ``shear-band``)."""
        return self.calculator

    def figure_curves(self) -> dict:
        """skempton-b: every curve its figure sheet draws, computed from ``figure_data`` when asked for.

        capred.pipelines.skempton_figure.figure_curves computes them; capred.report draws them.

        Returns
        -------
        dict
        """
        from .skempton_figure import figure_curves

        return figure_curves(self.figure_data)

    @property
    def values(self) -> dict[str, np.ndarray]:
        """The cases' inputs, ``{JSON key: array}`` in output units (from ``cases``)."""
        return self.cases.json_columns(outputs=False)

    @property
    def outputs(self) -> dict[str, np.ndarray]:
        """The cases' results, ``{JSON key: array}`` in output units (from ``cases``)."""
        return self.cases.json_columns(outputs=True)

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Per case: its label (if any), inputs and results in output units.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        cached = self.__dict__.get("_rows")
        if cached is None:
            cached = self.__dict__["_rows"] = self.cases.json_rows(self.labels)
        return cached

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the cases.

        A single case's results also at the top; the skeleton model and its inputs where one applies.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        rows = self.rows()
        out = {"source": self.source, "cases": rows}
        if len(rows) == 1:
            out = {**{k: rows[0][k] for k in self.outputs}, **out}
        if self.model is not None:
            out = {"model": self.model, "model_inputs": self.model_inputs or {}, **out}
        return out

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: a single case's results, each in its glossary unit (``Cases.store_rows``).

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        return self.cases.store_rows(material)

    def method_notes(self) -> tuple[list[str], list[str]]:
        """The skeleton model of a `skempton-b` run, for the methods section of report.html.

        Returns
        -------
        (list of str, list of str)
            The paragraph on the bounding-surface reconstruction and its references; empty for other runs.
        """
        if self.model is None or "bounding-surface" not in self.model:
            return [], []
        return [
            f"Elasto-plastic B by the two incremental loops of Morvan et al. (2016), section 4, with the {self.model}: "
            "for an isotropic state the image point is the apex p_π of the bounding surface, so Γ, ρ and M drop "
            "out; A11 = κ/((1+e)p') + (λ0 − κ)/((1+e)p') / (1 + h δ/p'), δ = p_π − p', with Cam-clay apex "
            "hardening dp_π/p_π = (1+e) dε_v^p/(λ0 − κ) and p_π0 = p'0 + A_ini. The constant h has no published "
            "value. Morvan et al.'s Fig. 6 values (0.4 and 0.04 at S_r = 0.9) come out only with the gauge air "
            "pressure in Boyle's law and p' = p0 + s S_r (h = 336 chosen to meet 0.04)."
        ], ["morvan2016", "morvan_wong_branque2010"]

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame.

        ``results``: one row per case, led by the model where one applies.

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        cols = {**({"case": list(self.labels)} if self.labels else {}), **self.cases.csv_columns()}
        frame = pd.DataFrame(cols)
        if self.model is not None:
            frame.insert(0, "model", self.model)
        return {"results": frame}


def _labels(values: dict) -> list[str] | None:
    case = values.pop("case", None)
    return [str(c) for c in case] if case is not None else None


def _inputs(source, schema: list[Column], options: dict[str, float | None], optional: tuple[str, ...] = ()):
    """Per-case SI arrays from a CSV and/or options, and notes (e.g. g/cm^2 read as gf/cm^2).

    Names in ``optional`` may stay NaN (absent from both the file and the options).
    """
    notes: list[str] = []
    if source is None:
        missing = [c.name for c in schema if options.get(c.name) is None and c.name not in optional]
        if missing:
            raise OptionError("missing " + ", ".join(f"--{m.replace('_', '-')}" for m in missing))
        values = {k: np.array([np.nan if v is None else v], dtype=float) for k, v in options.items()}
        return values, notes, None
    table = read_table(source, [*schema, CASE])
    values = {}
    for col in schema:
        v = table.get(col.name).copy()
        opt = options.get(col.name)
        if opt is not None:
            v[np.isnan(v)] = opt
        for i in np.flatnonzero(np.isnan(v) if col.name not in optional else []):
            table.add_problem(
                i,
                col.name if col.name in table.columns else None,
                f"no value for '{col.name}' (column or --{col.name.replace('_', '-')})",
            )
        values[col.name] = v
    table.raise_if_problems()
    if "case" in table.columns:
        values["case"] = table.columns["case"]
    values["_table"] = table  # taken out by _labels: it carries the warnings and the metadata block
    return values, table.notes, table.path


def _finish(command: str, title: str, cases: Cases, src, notes, labels, opt, source, table=None, figure_data=None):
    return CalcResult(
        command,
        cases,
        src,
        notes,
        labels,
        opt,
        [input_file(source, table)] if source is not None else [],
        opt.warnings + (table.warnings if table is not None else []),
        title,
        figure_data,
    )


PRISM = [
    Column("break_tension", "pressure", "kPa", "break tension sigma_b", ("sigma_b", "break_stress"), "positive"),
    Column("friction_angle", "angle", "deg", "friction angle rho", ("rho", "phi"), "positive"),
]


def reduce_prism(source, opt: PrismOptions) -> CalcResult:
    """Bernatzik (1948): maximal capillary pressure and capillary rise of a sand prism.

    Parameters
    ----------
    source : str or Path or DataFrame or None
        Optional table of cases (break_tension, friction_angle).
    opt : PrismOptions
        Break tension [Pa], friction angle [deg] and unit weight of water [N/m^3] for cases without them.

    Returns
    -------
    CalcResult
        Per case P_kmax [kPa] and the capillary rise h_c.

    Raises
    ------
    OptionError
        Where a friction angle is not between 0 and 90 deg.

    References
    ----------
    .. [1] Bernatzik, W. (1948). The determination of the capillary rise in sand by means of prism pressure
       tests. Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, paper II b 6.
    """
    v, notes, src = _inputs(source, PRISM, {"break_tension": opt.break_tension, "friction_angle": opt.friction_angle})
    table = v.pop("_table", None)
    labels = _labels(v)
    if np.any((v["friction_angle"] <= 0) | (v["friction_angle"] >= 90)):
        raise OptionError("the friction angle must lie between 0 and 90 deg")
    p = calc.prism_capillary_pressure(v["break_tension"], v["friction_angle"])
    cases = PrismCases(
        break_tension=v["break_tension"] / 1e3,
        friction_angle=v["friction_angle"],
        P_kmax=p / 1e3,
        capillary_rise=calc.capillary_rise(p, opt.gamma_w) * 100.0,
        P_kmax_over_sigma_b=p / v["break_tension"],
    )
    figure = dict(  # the Mohr diagram, drawn from the record (kPa, deg)
        break_tension_kPa=cases.break_tension,
        friction_angle_deg=cases.friction_angle,
        P_kmax_kPa=cases.P_kmax,
        labels=labels,
    )
    return _finish(
        "prism",
        f"Prism test ({cite('bernatzik1948')})",
        cases,
        src,
        notes,
        labels,
        opt,
        source,
        table,
        figure,
    )


def run_prism(source=None, break_tension=None, friction_angle=None, gamma_w=GAMMA_W) -> CalcResult:
    """Bernatzik (1948): P_kmax = sigma_b (1 - sin rho)/(2 sin rho) and h_c = P_kmax/gamma_w, per case.

    Cases come from ``source`` (CSV path or DataFrame) and/or the options
    (``break_tension`` [Pa or a string with a unit], ``friction_angle`` [deg]).

    Parameters
    ----------
    source : str or Path or DataFrame, optional
        Table of cases (break_tension, friction_angle).
    break_tension : float or str, optional
        Break tension sigma_b of the prism [Pa] (a string may carry a unit, e.g. "115 g/cm^2").
    friction_angle : float, optional
        Friction angle rho of the sand [deg].
    gamma_w : float or str, optional
        Unit weight of water [N/m^3].

    Returns
    -------
    CalcResult
        Per case P_kmax [kPa] and the capillary rise h_c.

    References
    ----------
    .. [1] Bernatzik, W. (1948). The determination of the capillary rise in sand by means of prism pressure
       tests. Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, paper II b 6.
    """
    return reduce_prism(source, PrismOptions(break_tension, friction_angle, gamma_w))


SKEMPTON = [
    Column("kappa", "dimensionless", "-", "kappa", (), "positive"),
    Column("e0", "dimensionless", "-", "e0", ("e_0", "void_ratio"), "positive"),
    Column("p0", "pressure", "kPa", "p0", ("p_0",), "nonnegative"),
    Column("u0", "pressure", "kPa", "u0", ("u_0", "ua0"), None),
    Column("pa0", "pressure", "kPa", "pa0", ("p_a0", "P_a0"), "positive"),
]


def _p_eff_message(p0: float, u0: float) -> str:
    """The error of a non-positive p0 - u0 with the values as read [kPa].

    A p0 below 1 kPa is most likely kPa typed as a script's plain number, which is in Pa.
    """
    text = f"p0 - u0 (initial mean effective stress) must be > 0; read p0 = {p0 / 1e3:g} kPa, u0 = {u0 / 1e3:g} kPa"
    if p0 < 1e3:
        text += " (a plain number given to run_skempton_b is in Pa: write p0='100 kPa' or 100e3)"
    return text


@renamed_keywords(sr="S_R", kappa="kappa_elastic", bc_alpha="bc_lambda")
def run_skempton_b(
    source=None,
    S_R=None,
    b=None,
    kappa_elastic=0.006,
    e0=0.8,
    p0=100e3,
    u0=30e3,
    pa0=130e3,
    s_e=None,
    bc_lambda=None,
    model="elastic",
    a_ini=None,
    interpolation_h=None,
    air_pressure="absolute",
    lambda0=None,
    retention=None,
    curve=False,
    compression=None,
    compare=(),
) -> CalcResult:
    """Morvan et al. (2016): B from the degree of saturation ``S_R`` [-] (eq. 10), or S_R from a measured B.

    ``kappa_elastic`` is the slope of the elastic line in e-ln p' [-]. With ``s_e`` [Pa] and ``bc_lambda``
    (the Brooks-Corey index, alpha in Morvan et al.), B is computed with suction equilibrium (section 3);
    its inverse is solved numerically. ``model="bounding-surface"`` runs the two incremental loops of
    section 4 with capred's Cam-clay bounding-surface reconstruction (not the BDNS model of the paper's
    ref. [16]): ``a_ini`` [Pa] (0: normally consolidated), ``interpolation_h`` [-] (required when
    ``a_ini > 0``), ``lambda0`` [-] and ``air_pressure`` (``absolute``, or ``gauge`` to meet the paper's
    Fig. 6); Table 3 gives the defaults. ``curve=True`` gives B against S_r (0.5 to 1) for every model the
    options ask for (see :func:`skempton_curves`) instead of cases. ``model="elastoplastic"`` raises
    OptionError with the reason. The
    former keywords ``sr``, ``kappa`` and ``bc_alpha`` still work for one release, with a DeprecationWarning.
    ``retention``: a fits.json of `capred retention` (any model) instead of ``s_e`` and ``bc_lambda``: a
    Brooks-Corey fit as it is, another model converted to Brooks-Corey (capred.convert_retention), the misfit
    in the notes.

    Parameters
    ----------
    source : str or Path or DataFrame, optional
        Table of cases (S_r or B, and any of kappa, e0, p0, u0, pa0).
    S_R : float, optional
        Degree of saturation [-]: compute B.
    b : float, optional
        Measured B [-]: compute S_R.
    kappa_elastic : float, optional
        Slope of the elastic line in e-ln p' [-].
    e0 : float, optional
        Initial void ratio [-].
    p0, u0, pa0 : float or str, optional
        Mean total stress, initial pore pressure and absolute initial air pressure [Pa].
    s_e : float or str, optional
        Air-entry suction of Brooks-Corey [Pa] (suction equilibrium, with ``bc_lambda``).
    bc_lambda : float, optional
        Brooks-Corey pore-size index [-].
    model : str, optional
        ``elastic``, ``bounding-surface`` or ``elastoplastic`` (refused).
    a_ini : float or str, optional
        Initial distance of the bounding surface's apex above p'0 [Pa].
    interpolation_h : float, optional
        Interpolation constant h of the reconstruction [-].
    air_pressure : str, optional
        ``absolute`` or ``gauge``.
    lambda0 : float, optional
        Slope of the normal compression line [-].
    retention : str or Path, optional
        A fits.json of `capred retention`.
    curve : bool, optional
        Give B against S_r for every model asked instead of the cases.
    compression : str or Path, optional
        A compression.json of `capred compression`: κ, e0 (and λ0 with bounding-surface) from it.
    compare : tuple of str, optional
        With ``curve``: classical relations drawn beside eq. 10 (keys of ``SKEMPTON_RELATIONS``, or "all").

    Returns
    -------
    CalcResult
        B or S_R per case (or the curves), with the skeleton model and its inputs.

    References
    ----------
    Morvan, Vernay & Breul (2016), Study of the variation of B with Sr, E-UNSAT 2016, E3S Web of Conferences;
    eqs. 10, 13-24, Tables 1 and 3.
    """
    return reduce_skempton_b(
        source,
        SkemptonOptions(
            S_R,
            b,
            kappa_elastic,
            e0,
            p0,
            u0,
            pa0,
            s_e,
            bc_lambda,
            model,
            a_ini,
            interpolation_h,
            air_pressure,
            lambda0,
            retention,
            curve,
            compression,
            compare,
        ),
    )


def reduce_skempton_b(source, opt: SkemptonOptions) -> CalcResult:
    """B or S_r per case (see run_skempton_b), with the figure of the B-S_r relation.

    The title, the tables and the JSON name the skeleton model and its inputs.

    Parameters
    ----------
    source : str or Path or DataFrame or None
        Optional table of cases.
    opt : SkemptonOptions
        The options of :func:`run_skempton_b` (pressures in Pa).

    Returns
    -------
    CalcResult
        B or S_R per case, with the figure data of the B-S_r relation.

    References
    ----------
    .. [1] Morvan, M., Vernay, M., Breul, P. (2016). Study of the variation of B with Sr. E-UNSAT 2016,
       E3S Web of Conferences; eqs. 10, 13-24.
    """
    fit_notes, fit_warnings = [], []
    if opt.compression is not None:
        opt, fit_notes, fit_warnings = _with_compression(opt, getattr(source, "limits", None))
    if opt.retention is not None:  # any retention fit: Brooks-Corey as it is, another model converted to it
        from .retention_convert import brooks_corey_for_skempton

        if opt.s_e is not None or opt.bc_lambda is not None:
            raise OptionError("give --retention or --se with --bc-lambda, not both")
        s_e, lam, more_notes, more_warnings = brooks_corey_for_skempton(
            opt.retention, limits=getattr(source, "limits", None)
        )
        fit_notes, fit_warnings = fit_notes + more_notes, fit_warnings + more_warnings
        opt = dataclasses.replace(opt, s_e=s_e, bc_lambda=lam)
    kw = dict(kappa=opt.kappa_elastic, e0=opt.e0, p0=opt.p0, u0=opt.u0, pa0=opt.pa0)  # keys: the figure's
    if opt.curve:
        res = skempton_curves(source, opt)
        res.warnings += fit_warnings
        res.notes = list(res.notes) + fit_notes
        return res
    if opt.compare:
        raise OptionError("--compare draws the classical relations beside eq. 10 on a curve: give it with --curve")
    bounding = None
    s_e, bc_lambda = opt.s_e, opt.bc_lambda
    if opt.model == "bounding-surface":
        s_e = TABLE3["s_e"] if s_e is None else s_e
        bc_lambda = TABLE3["bc_lambda"] if bc_lambda is None else bc_lambda
        bounding = dict(
            lambda0=opt.lambda0_or_default,
            a_ini=opt.a_ini_or_default,
            interpolation_h=opt.interpolation_h,
            air_pressure=opt.air_pressure,
        )
    res = _skempton(source, opt.S_R, opt.b, s_e=s_e, bc_lambda=bc_lambda, bounding=bounding, **kw)
    S = np.asarray(res.values.get("S_r", res.outputs.get("S_r")), float)
    B = np.asarray(res.values.get("B", res.outputs.get("B")), float)
    n = S.size
    params = [
        np.broadcast_to(
            np.asarray(res.values.get(k, kw[k.replace("_kPa", "")]), float) * (1e3 if k.endswith("_kPa") else 1.0), n
        )
        for k in ("kappa", "e0", "p0_kPa", "u0_kPa", "pa0_kPa")
    ]
    cases: dict = {}
    for i in range(n):
        key = tuple(float(p[i]) for p in params)
        cases.setdefault(key, ([], []))
        cases[key][0].append(S[i])
        cases[key][1].append(B[i])
    if bounding is not None:
        filled = [
            text
            for given, text in (
                (opt.s_e, f"s_e = {s_e / 1e3:g} kPa"),
                (opt.bc_lambda, f"λ = {bc_lambda:g}"),
                (opt.lambda0, f"λ0 = {bounding['lambda0']:g}"),
                (opt.a_ini, "A_ini = 0 (normally consolidated)"),
            )
            if given is None
        ]
        if filled:
            res.notes.append(f"Morvan et al. (2016), Table 3 values used where no option gave one: {', '.join(filled)}")
    res.figure_data = dict(cases=cases, s_e=s_e, bc_lambda=bc_lambda, bounding=bounding, **kw)
    res.title, res.model, res.model_inputs = skempton_model_description(opt.model, s_e, bc_lambda, bounding)
    res.options, res.warnings = opt, opt.warnings + res.warnings
    res.warnings += fit_warnings
    res.notes = list(res.notes) + fit_notes
    return res


def _with_compression(opt: SkemptonOptions, limits=None) -> tuple[SkemptonOptions, list[str], list[str]]:
    """κ and e0 (and λ0 with bounding-surface) from a compression.json, with its notes and warnings.

    Read within ``limits`` (--max-megabytes); an error when the options give them too.
    """
    from .compression import load_compression_fit

    fields = {f.name: f.default for f in dataclasses.fields(SkemptonOptions)}
    clash = [
        name for name, key in (("--kappa-elastic", "kappa_elastic"), ("--e0", "e0")) if getattr(opt, key) != fields[key]
    ]
    if opt.model == "bounding-surface" and opt.lambda0 is not None:
        clash.append("--lambda0")
    if clash:
        raise OptionError(f"give --compression or {', '.join(clash)}, not both")
    lines = load_compression_fit(opt.compression, limits)
    if lines.url_slope is None:
        raise OptionError(f"--compression {lines.source}: the test has no unloading stage, so no κ for skempton-b")
    new = {"kappa_elastic": lines.url_slope, "e0": lines.e0}
    text = f"κ = {lines.url_slope:.4g} and e0 = {lines.e0:.4g}"
    if opt.model == "bounding-surface":
        new["lambda0"] = lines.ncl_slope
        text += f" and λ0 = {lines.ncl_slope:.4g}"
    warnings = []
    if lines.test == "oedometer":
        # Morvan et al.'s eq. 10 takes kappa in e - ln p'; an oedometer's lines are in e - ln sigma'_v, parallel to
        # those in p' only while K0 stays constant, which it does not on unloading (K0 grows as sigma'_v falls)
        warnings.append(
            f"--compression {lines.source} is an oedometer test: its κ is the slope in e - ln σ'_v, and Morvan et "
            "al.'s eq. 10 takes it in e - ln p'; the two agree only while K0 is constant (not on unloading, where "
            "K0 grows); an isotropic test (capred compression --test isotropic) gives κ in p' directly"
        )
    return dataclasses.replace(opt, **new), [f"{text} from the compression test {lines.source}"], warnings


#: degrees of saturation of `skempton-b --curve` (the range of Morvan et al.'s 2016 figures)
CURVE_S_R = np.round(np.linspace(0.5, 1.0, 101), 10)


def skempton_curves(source, opt: SkemptonOptions) -> CalcResult:
    """B against S_r (0.5 to 1, step 0.005) for every model the options ask for, as Morvan et al. (2016) draw it.

    Always eq. 10 (their Fig. 1-3); with ``s_e`` and ``bc_lambda``, or with ``model="bounding-surface"``
    (Table 3's s_e and lambda), the elastic B with suction equilibrium (section 3, Fig. 5); with
    ``model="bounding-surface"``, the Cam-clay bounding-surface reconstruction normally consolidated
    (A_ini = 0) and, with ``a_ini > 0``, over-consolidated (section 4, Fig. 6).

    Parameters
    ----------
    source : None
        A curve is drawn from the options alone (a file of cases is refused).
    opt : SkemptonOptions
        With ``curve=True``; ``S_R`` and ``b`` must be None.

    Returns
    -------
    CalcResult
        One row per S_r; one output column per model (``B_eq10``, ``B_suction``, ``B_bounding_NC``,
        ``B_bounding_OC``).

    References
    ----------
    Morvan et al. (2016), eqs. 10, 13-24; Fig. 1-3, 5, 6; Tables 1 and 3.
    """
    from ..physics.skempton_elastoplastic import BOUNDING_SURFACE_NAME

    if source is not None or opt.S_R is not None or opt.b is not None:
        raise OptionError("--curve draws B against S_r from the options: give no data file, --S-R or --b with it")
    S = CURVE_S_R
    k, e0, p0, u0, pa0 = opt.kappa_elastic, opt.e0, opt.p0, opt.u0, opt.pa0
    if p0 - u0 <= 0:
        raise OptionError(_p_eff_message(p0, u0))
    bs = opt.model == "bounding-surface"
    s_e = opt.s_e if opt.s_e is not None or not bs else TABLE3["s_e"]
    bc_lambda = opt.bc_lambda if opt.bc_lambda is not None or not bs else TABLE3["bc_lambda"]
    if (s_e is None) != (bc_lambda is None):
        raise OptionError("give both --se and --bc-lambda for the suction-equilibrium simulation, or neither")
    outputs = {"B_eq10": calc.skempton_b(S, p0 - u0, e0, k, pa0)}
    names = [f"B_eq10: elastic skeleton ({cite('morvan2016', 'eq. 10')})"]
    for key in opt.compare:  # the classical relations on the same skeleton (the paper's comparison)
        rel = calc.SKEMPTON_RELATIONS[key]
        outputs[f"B_{key}"] = rel.b(S, p0 - u0, e0, k, pa0)
        names.append(f"B_{key}: {rel.label} ({cite(rel.reference)}): {rel.equation}")
    if s_e is not None:
        outputs["B_suction"] = calc.skempton_b_suction(S, p0, u0, e0, k, pa0, s_e, bc_lambda)
        names.append(
            f"B_suction: elastic skeleton with suction equilibrium, s_e = {s_e / 1e3:g} kPa, λ = {bc_lambda:g}"
        )
    bounding = None
    if bs:
        bounding = dict(
            lambda0=opt.lambda0_or_default,
            a_ini=opt.a_ini_or_default,
            interpolation_h=opt.interpolation_h,
            air_pressure=opt.air_pressure,
        )
        states = [("NC", 0.0)] + ([("OC", bounding["a_ini"])] if bounding["a_ini"] > 0 else [])
        for label, a in states:
            b = {**bounding, "a_ini": a}
            outputs[f"B_bounding_{label}"] = _bounding_b(S, k, e0, p0, u0, pa0, s_e, bc_lambda, b)
            names.append(
                f"B_bounding_{label}: {BOUNDING_SURFACE_NAME}, A_ini = {a / 1e3:g} kPa"
                + (f", h = {bounding['interpolation_h']:g}" if a > 0 else "")
                + f", {bounding['air_pressure']} air pressure"
            )
    _, model, inputs = skempton_model_description(opt.model, s_e, bc_lambda, bounding)
    res = CalcResult(
        "skempton-b",
        SkemptonCurves(S_R=S.copy(), **outputs),
        None,
        ["curves: " + "; ".join(names)],
        None,
        opt,
        [],
        list(opt.warnings),
        "Skempton's B against S_r: " + ", ".join(outputs) + f" ({cite('morvan2016', 'Fig. 1-3, 5, 6')})",
        dict(
            curves={"S_r": S, **outputs},
            curve_names=names,
            kappa=k,
            e0=e0,
            p0=p0,
            u0=u0,
            pa0=pa0,
            s_e=s_e,
            bc_lambda=bc_lambda,
            bounding=bounding,
        ),
        model,
        inputs,
    )
    return res


def skempton_model_description(model: str, s_e, bc_lambda, bounding: dict | None) -> tuple[str, str, dict]:
    """(title, model name, model inputs in JSON units) of a `skempton-b` run: what every output says it computed.

    Parameters
    ----------
    model : str
        ``elastic`` or ``bounding-surface``.
    s_e : float or None
        Brooks-Corey air-entry suction [Pa] (suction equilibrium; Table 3's 20 kPa with bounding-surface).
    bc_lambda : float or None
        Brooks-Corey pore-size index [-] (alpha in Morvan et al. 2016).
    bounding : dict or None
        ``lambda0`` [-], ``a_ini`` [Pa], ``interpolation_h`` [-] or None, ``air_pressure``.

    Returns
    -------
    (str, str, dict)
        The title, the model's name, and its inputs by JSON key in JSON units.

    References
    ----------
    Morvan et al. (2016), eq. 10 (elastic), section 3 (suction equilibrium), section 4 (elasto-plastic).
    """
    from ..physics.skempton_elastoplastic import BOUNDING_SURFACE_NAME

    if model == "bounding-surface":
        h = bounding["interpolation_h"]
        inputs = {
            "s_e_kPa": s_e / 1e3,
            "bc_lambda": bc_lambda,
            "lambda0": bounding["lambda0"],
            "a_ini_kPa": bounding["a_ini"] / 1e3,
            "interpolation_h": h,
            "air_pressure": bounding["air_pressure"],
        }
        state = "normally consolidated" if bounding["a_ini"] == 0 else "over-consolidated"
        text = (
            f"{state}, A_ini = {bounding['a_ini'] / 1e3:g} kPa, h = {'-' if h is None else f'{h:g}'}, "
            f"λ0 = {bounding['lambda0']:g}, s_e = {s_e / 1e3:g} kPa, λ = {bc_lambda:g}, "
            f"{bounding['air_pressure']} air pressure"
        )
        title = f"Skempton's B, {BOUNDING_SURFACE_NAME}: {text} ({cite('morvan2016', 'section 4')})"
        return title, BOUNDING_SURFACE_NAME, inputs
    if s_e is not None:
        name = f"elastic skeleton with suction equilibrium ({cite('morvan2016', 'section 3')})"
        title = f"Skempton's B, {name}: s_e = {s_e / 1e3:g} kPa, λ = {bc_lambda:g}"
        return title, name, {"s_e_kPa": s_e / 1e3, "bc_lambda": bc_lambda}
    name = f"elastic skeleton ({cite('morvan2016', 'eq. 10')})"
    return f"Skempton's B, {name}", name, {}


def _bounding_b(S, k, e, p, u, pa, s_e, bc_lambda, bounding) -> float:
    """B at S_r (or, with S None, the whole path) by the two loops of Morvan et al. (2016) section 4."""
    from ..physics import skempton_elastoplastic as sep

    kw = dict(
        kappa_elastic=k,
        p0=p,
        u0=u,
        e0=e,
        pa0=pa,
        air_entry=s_e,
        bc_lambda=bc_lambda,
        air_pressure=bounding["air_pressure"],
    )
    try:  # the physics refuses a value (S_r outside (0, 1], ...) with a ValueError: the user's message
        kw["compliance"] = sep.BoundingSurfaceCompliance(
            k, bounding["lambda0"], bounding["a_ini"], bounding["interpolation_h"]
        )
        if S is None:
            return sep.skempton_b_incremental_path(0.01, **kw)
        return sep.skempton_b_incremental(S, **kw)
    except ValueError as exc:
        raise OptionError(str(exc)) from None


def _saturation_from_b(v: dict, cases: list, p_eff, s_e, bc_lambda, bounding, notes: list[str]):
    """S_r of every case from its measured B, and the warnings on several roots.

    On the bounding-surface drying path (its root nearest saturation), with the suction-equilibrium model (Brent's root
    in (0, 1]), or in closed form. A B not reached on the drying path is noted (S_r NaN).
    """
    root_warnings: list[str] = []
    if bounding is not None:

        def solve(row, bi, *c):
            path = _bounding_b(None, *c, s_e, bc_lambda, bounding)
            roots = b_roots(path.S_R, path.B, bi)
            where = f"row {row + 1}: " if len(cases) > 1 else ""
            if not roots:
                notes.append(
                    f"{where}B = {bi:g} is not reached on the drying path from S_r = 1 to {path.S_R.min():g} "
                    f"(B spans {np.nanmin(path.B):.4g} to {np.nanmax(path.B):.4g} there): no S_r"
                )
                return np.nan
            if len(roots) > 1:
                root_warnings.append(
                    f"{where}B = {bi:g} is reached at {len(roots)} degrees of saturation on the drying path "
                    f"(S_r = {', '.join(f'{r:.4f}' for r in roots)}): B is not monotonic in S_r along it; "
                    f"S_r = {roots[0]:.4f}, the root nearest saturation, is given"
                )
            return roots[0]

        from ..progress import steps

        rows = list(enumerate(zip(v["B"], cases)))
        S = np.array([solve(i, bi, *c) for i, (bi, c) in steps(rows, "S_r (rows)")])
    elif s_e is not None and bc_lambda is not None:  # the suction-equilibrium simulation
        from scipy.optimize import brentq

        def solve(bi, k, e, p, u, pa):
            f = lambda s: calc.skempton_b_suction(s, p, u, e, k, pa, s_e, bc_lambda) - bi  # noqa: E731
            lo, hi = 1e-9, 1.0
            return brentq(f, lo, hi, xtol=1e-14) if f(lo) * f(hi) < 0 else np.nan

        S = np.array([solve(*args) for args in zip(v["B"], *zip(*cases))])
    else:
        S = calc.saturation_from_b(v["B"], p_eff, v["e0"], v["kappa"], v["pa0"])
    return S, root_warnings


def _skempton(source, S_R, b, kappa, e0, p0, u0, pa0, s_e, bc_lambda, bounding=None) -> CalcResult:
    """B or S_R per case; the dict keys are the CSV columns and JSON keys (``S_r``, ``kappa``), unchanged."""
    schema = SKEMPTON + [
        Column("S_r", "dimensionless", "-", "S_r", ("Sr", "S_R"), "fraction"),
        Column("B", "dimensionless", "-", "B", ("skempton_b",), "fraction"),
    ]
    given = {"kappa": kappa, "e0": e0, "p0": p0, "u0": u0, "pa0": pa0, "S_r": S_R, "B": b}
    if source is None and (S_R is None) == (b is None):
        raise OptionError("give exactly one of --S-R (or --sr) and --b")
    v, notes, src = _inputs(source, schema, given, optional=("S_r", "B"))
    table = v.pop("_table", None)
    labels = _labels(v)
    forward = bool(np.all(np.isfinite(v["S_r"])))
    if not forward and not np.all(np.isfinite(v["B"])):
        raise InputError(
            Problem(str(src), None, None, "every row needs 'S_r' (to compute B) or every row 'B' (to compute S_r)")
        )
    v.pop("B" if forward else "S_r")
    suction = s_e is not None and bc_lambda is not None
    if (s_e is None) != (bc_lambda is None):
        raise OptionError("give both --se and --bc-lambda for the suction-equilibrium simulation, or neither")
    p_eff = v["p0"] - v["u0"]
    if np.any(p_eff <= 0):
        i = int(np.flatnonzero(p_eff <= 0)[0])
        raise OptionError(_p_eff_message(v["p0"][i], v["u0"][i]))
    if bounding is not None and np.any(v["kappa"] >= bounding["lambda0"]):
        raise OptionError(f"kappa must be below lambda0 = {bounding['lambda0']:g} (--lambda0) in every case")
    ins = {k: (x / 1e3 if k in ("p0", "u0", "pa0") else x) for k, x in v.items() if k not in ("S_r", "B", "kappa")}
    ins["kappa_elastic"] = v["kappa"]
    if bounding is not None and bounding["air_pressure"] == "gauge":
        del ins["pa0"]  # Boyle's law on the gauge u0: the absolute initial air pressure is not used, not shown
    if suction:  # the model's inputs in every row: the table and the CSV say what was computed
        n = v["kappa"].size
        ins["s_e"], ins["bc_lambda"] = np.full(n, s_e / 1e3), np.full(n, float(bc_lambda))
    cases = list(zip(v["kappa"], v["e0"], v["p0"], v["u0"], v["pa0"]))
    if forward:
        if bounding is not None:
            from ..progress import steps  # two incremental loops per row: seconds a row, a bar for many

            rows = list(zip(v["S_r"], cases))
            B = np.array([_bounding_b(sr, *c, s_e, bc_lambda, bounding) for sr, c in steps(rows, "B (rows)")])
        elif suction:
            B = calc.skempton_b_suction(v["S_r"], v["p0"], v["u0"], v["e0"], v["kappa"], v["pa0"], s_e, bc_lambda)
        else:
            B = calc.skempton_b(v["S_r"], p_eff, v["e0"], v["kappa"], v["pa0"])
        return CalcResult(
            "skempton-b",
            SkemptonCases(S_R=v["S_r"], B=B, solved="B", **ins),
            src,
            notes,
            labels,
            title=_B_TITLE,
            warnings=table.warnings if table is not None else [],
            inputs=[input_file(source, table)] if source is not None else [],
        )
    S, root_warnings = _saturation_from_b(v, cases, p_eff, s_e, bc_lambda, bounding, notes)
    if bounding is None and np.any(~np.isfinite(S) | (S < 0)):
        notes.append("some B values are below what these parameters give for dry soil: S_r is outside [0, 1] there")
    return CalcResult(
        "skempton-b",
        SkemptonCases(B=v["B"], S_R=S, solved="S_R", **ins),
        src,
        notes,
        labels,
        title=_B_TITLE,
        warnings=(list(table.warnings) if table is not None else []) + (root_warnings if bounding is not None else []),
        inputs=[input_file(source, table)] if source is not None else [],
    )


_B_TITLE = f"Skempton's B and the degree of saturation ({cite('morvan2016', 'eq. 10')})"


def b_roots(S_R, B, b) -> list[float]:
    """Every degree of saturation where a path's B(S_r) equals ``b``, nearest saturation first.

    Each crossing of ``b`` between two neighbouring points of the path (or a point equal to it) gives one root,
    placed by linear interpolation between them (the path's step, 1e-3 in S_r, bounds its error).

    Parameters
    ----------
    S_R : array_like
        Degrees of saturation of the path [-], in any order.
    B : array_like
        B at each [-].
    b : float
        The measured B [-].

    Returns
    -------
    list of float
        The roots, in decreasing S_r (empty when ``b`` is not reached).

    References
    ----------
    .. [1] Morvan, M., Vernay, M., Breul, P. (2016). E-UNSAT 2016, section 4: B along a drying path.
    """
    S = np.asarray(S_R, float)
    Bv = np.asarray(B, float)
    order = np.argsort(-S)
    S, d = S[order], Bv[order] - b
    roots = [float(S[i]) for i in np.flatnonzero(d == 0.0)]
    for i in np.flatnonzero(d[:-1] * d[1:] < 0):
        roots.append(float(S[i] + (S[i + 1] - S[i]) * d[i] / (d[i] - d[i + 1])))
    return sorted(set(roots), reverse=True)


RUMPF = [
    Column("shape_factor", "dimensionless", "-", "shape factor phi", ("phi", "shape"), "positive"),
    Column("void_ratio", "dimensionless", "-", "void ratio e", ("e",), "positive"),
    Column("S_r", "dimensionless", "-", "S_r", ("Sr", "S_R"), "fraction"),
    Column("diameter", "length", "mm", "particle diameter d_p", ("d_p", "d", "particle_diameter"), "positive"),
    Column("surface_tension", "surface_tension", "N/m", "surface tension", ("gamma",), "positive"),
    Column("contact_angle", "angle", "deg", "contact angle", ("theta",), "nonnegative"),
]


@renamed_keywords(sr="S_R")
def run_rumpf(
    source=None,
    shape_factor=None,
    void_ratio=None,
    S_R=None,
    diameter=None,
    surface_tension=SURFACE_TENSION,
    contact_angle=0.0,
) -> CalcResult:
    """Rumpf's capillary pressure (Prunier et al. 2024, eq. 19).

    p_cap = -(6/phi)(S_R/e)(gamma/d_p) cos(contact_angle), ``contact_angle`` in degrees. The former keyword ``sr`` still
    works for one release, with a DeprecationWarning.

    Parameters
    ----------
    source : str or Path or DataFrame, optional
        Table of cases (shape_factor, void_ratio, S_r, diameter, surface_tension, contact_angle).
    shape_factor : float, optional
        Shape factor phi of the grains [-].
    void_ratio : float, optional
        Void ratio e [-].
    S_R : float, optional
        Degree of saturation [-].
    diameter : float or str, optional
        Grain diameter d_p [m].
    surface_tension : float or str, optional
        Surface tension gamma [N/m].
    contact_angle : float, optional
        Contact angle [deg].

    Returns
    -------
    CalcResult
        Per case p_cap [kPa] (negative: tensile).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J., Darve, F. (2024). A method to evaluate the capillary stress
       tensor at failure in unsaturated soils. Eur. J. Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099,
       eq. 19.
    """
    return reduce_rumpf(source, RumpfOptions(shape_factor, void_ratio, S_R, diameter, surface_tension, contact_angle))


def reduce_rumpf(source, opt: RumpfOptions) -> CalcResult:
    """p_cap per case (see run_rumpf).

    Parameters
    ----------
    source : str or Path or DataFrame or None
        Optional table of cases.
    opt : RumpfOptions
        Shape factor [-], void ratio [-], S_R [-], diameter [m], surface tension [N/m], contact angle [deg].

    Returns
    -------
    CalcResult
        Per case p_cap [kPa].

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J., Darve, F. (2024). A method to evaluate the capillary stress
       tensor at failure in unsaturated soils. Eur. J. Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099,
       eq. 19.
    """
    v, notes, src = _inputs(
        source,
        RUMPF,
        {
            "shape_factor": opt.shape_factor,
            "void_ratio": opt.void_ratio,
            "S_r": opt.S_R,
            "diameter": opt.diameter,
            "surface_tension": opt.surface_tension,
            "contact_angle": opt.contact_angle,
        },
    )
    table = v.pop("_table", None)
    labels = _labels(v)
    if np.any(v["contact_angle"] >= 90):
        raise OptionError("the contact angle must be below 90 deg")
    p = calc.rumpf_capillary_pressure(
        v["shape_factor"], v["void_ratio"], v["S_r"], v["diameter"], v["surface_tension"], v["contact_angle"]
    )
    cases = RumpfCases(
        shape_factor=v["shape_factor"],
        void_ratio=v["void_ratio"],
        S_R=v["S_r"],
        diameter=v["diameter"] * 1e3,
        surface_tension=v["surface_tension"],
        contact_angle=v["contact_angle"],
        p_cap=p / 1e3,
    )
    return _finish(
        "rumpf",
        f"Rumpf's capillary pressure ({cite('prunier2024', 'eq. 19')})",
        cases,
        src,
        notes,
        labels,
        opt,
        source,
        table,
    )


__all__ = [
    "run_prism",
    "run_skempton_b",
    "run_rumpf",
    "CalcResult",
    "PrismOptions",
    "SkemptonOptions",
    "RumpfOptions",
    "InputError",
    "Problem",
]


SHEAR_BAND = [
    Column("phi_eff", "angle", "deg", "effective friction angle phi'", ("phi", "friction_angle", "phi_deg"), None),
    Column("dilatancy_angle", "angle", "deg", "dilatancy angle psi", ("psi", "psi_deg"), None),
    Column("dilatancy_rate", "dimensionless", "-", "-d eps_v/d eps_1 at failure", ("dilation_rate",), None),
    Column(
        "shear_band_angle",
        "angle",
        "deg",
        "measured angle of the band to the major principal plane",
        ("band_angle", "measured_angle", "shear_band"),
        None,
    ),
]


def _phi_from_triaxial(path, limits=None) -> float:
    """φ' [deg] of the envelope in a summary.json of `capred triaxial-bounds` or of `capred triaxial`.

    One material; several are named with their φ', for --phi-eff. Read within ``limits`` (--max-megabytes) and
    capred.io.MAX_JSON_DEPTH.
    """
    from ..io import read_json

    where = str(path)
    try:
        doc = read_json(path, "--triaxial", limits)
        if isinstance(doc, dict) and doc.get("command") == "triaxial" and isinstance(doc.get("materials"), dict):
            phis = {m: float(v["envelope"]["phi_deg"]) for m, v in doc["materials"].items()}
            if len(phis) != 1:
                listed = ", ".join(f"'{m}' {phi:.4g} deg" for m, phi in phis.items())
                raise InputError(
                    Problem(
                        where, None, None, f"holds {len(phis)} materials ({listed}): give --phi-eff with the one meant"
                    )
                )
            return next(iter(phis.values()))
        phi = float(doc["envelope"]["phi_deg"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError(
            Problem(
                where, None, None, f"not a summary.json of capred triaxial-bounds or triaxial with an envelope ({exc})"
            )
        ) from None
    return phi


def reduce_shear_band(source, opt: ShearBandOptions) -> CalcResult:
    """The classical shear-band angles (Coulomb, Roscoe, Arthur) per case, beside the measured one.

    Parameters
    ----------
    source : str or Path or DataFrame or None
        Optional table of cases (phi, dilatancy_angle or dilatancy_rate, shear_band_angle, case).
    opt : ShearBandOptions
        φ' (or a triaxial-bounds summary.json), ψ or the dilatancy rate, the measured angle [deg].

    Returns
    -------
    CalcResult
        Per case: the angles [deg] and their differences to the measured one.

    References
    ----------
    .. [1] Roscoe (1970); Arthur et al. (1977); Prunier et al. (2024), Fig. 14.
    """
    from ..physics import shear_band as sb

    phi_eff = opt.phi_eff
    notes_extra = []
    if opt.triaxial is not None:
        phi_eff = _phi_from_triaxial(opt.triaxial, getattr(source, "limits", None))
        notes_extra.append(f"φ' = {phi_eff:.4g} deg from the envelope of {opt.triaxial}")
    v, notes, src = _inputs(
        source,
        SHEAR_BAND,
        {
            "phi_eff": phi_eff,
            "dilatancy_angle": opt.dilatancy_angle,
            "dilatancy_rate": opt.dilatancy_rate,
            "shear_band_angle": opt.measured,
        },
        optional=("dilatancy_angle", "dilatancy_rate", "shear_band_angle"),
    )
    table = v.pop("_table", None)
    labels = _labels(v)
    psi = v["dilatancy_angle"].copy()
    from_rate = np.isnan(psi) & np.isfinite(v["dilatancy_rate"])
    psi[from_rate] = sb.dilatancy_angle_triaxial(v["dilatancy_rate"][from_rate])
    if from_rate.any():
        notes_extra.append("ψ from the dilatancy rate d = −dε_v/dε_1: sin ψ = d/(2 + d)")
    if np.all(np.isnan(psi)):
        notes_extra.append("no dilatancy angle: Roscoe's and Arthur's angles need ψ (--dilatancy-angle or -rate)")
    measured = v["shear_band_angle"]
    coulomb, roscoe = sb.coulomb_angle(v["phi_eff"]), sb.roscoe_angle(psi)
    arthur = sb.arthur_angle(v["phi_eff"], psi)
    has_m = bool(np.any(np.isfinite(measured)))
    cases = ShearBandCases(
        phi_eff=v["phi_eff"],
        dilatancy_angle=psi if np.any(np.isfinite(psi)) else None,
        measured=measured if has_m else None,
        coulomb=coulomb,
        roscoe=roscoe,
        arthur=arthur,
        coulomb_minus_measured=coulomb - measured if has_m else None,
        roscoe_minus_measured=roscoe - measured if has_m else None,
        arthur_minus_measured=arthur - measured if has_m else None,
    )
    return _finish(
        "shear-band",
        f"Shear-band angles: Coulomb 45 + φ'/2, {cite('roscoe1970')} 45 + ψ/2, {cite('arthur1977')} 45 + (φ' + ψ)/4",
        cases,
        src,
        list(notes) + notes_extra,
        labels,
        opt,
        source,
        table,
    )
