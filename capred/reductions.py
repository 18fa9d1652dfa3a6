"""Every command of capred as a reduction: ``run(source, options) -> Result``.

The functions are named as "module:function" and imported only when a
reduction runs, so that `capred --help` loads no numerical library.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import import_module


@dataclass(frozen=True)
class Reduction:
    """One command of capred: what it runs and with which options, its sample, outputs and methods text.

    The callables are named as ``"module:function"`` strings, imported only when the command runs, so that
    ``--help`` imports no numpy. Each field is described where it is declared.
    """

    name: str  # the command as typed: "shear", "bridge solve"
    run_path: str  # "module:function" taking (source, options)
    options_path: str  # "module:class" of its options
    source: str  # "required", "optional" (cases from options or a file) or "none"
    sample: str | None  # key of capred.samples.SAMPLES
    out_prefix: str  # default output folder: ./capred_out/<prefix>_<input stem>
    method: tuple[str, ...] = ()  # paragraphs of the methods section of report.html
    references: tuple[str, ...] = ()  # keys of capred.references.REFERENCES cited there
    #: write files without --out (into ./capred_out/...); a calculator only prints unless --out is given
    files_by_default: bool = True
    summary: str = ""  # one line of `capred --help`
    #: options of a quick run, for a command without a sample (tests, docs): ``{"points": 50}``
    example: tuple = ()
    #: what the input is, for a command whose input is not a table of columns (`--help` shows it in their place)
    input_description: str = ""
    #: what its input table is called in "this looks like ..." hints, for a command whose table has a schema of
    #: its own (capred.cli.common)
    table_kind: str = ""
    #: the cells its outputs take per input row: (the columns of its per-row table, the columns it adds per model
    #: compared in ``options.models``), by which a long file's outputs are sized before anything is computed
    #: (capred.report.outputs.check_outputs_ahead; tests/test_outputs_ahead.py checks them on the samples);
    #: (0, 0): sized only once computed
    row_cells: tuple[int, int] = (0, 0)
    #: what the second count of ``row_cells`` is per: "models" (each model in ``options.models``) or
    #: "bridge_laws" (each law of the law registry, a law registered at run time included)
    row_cells_per: str = "models"

    def run(self, source, options):
        """Run the command: call its run function (``run_path``, imported on first use).

        Parameters
        ----------
        source : str, pathlib.Path, pandas.DataFrame or None
            The input table.
        options : object
            The command's options object.

        Returns
        -------
        capred.result.Result
        """
        module, name = self.run_path.split(":")
        return getattr(import_module(module), name)(source, options)

    def example_args(self) -> list[str]:
        """The CLI arguments of a quick run: ``--sample``, or the ``example`` options spelled as flags.

        Returns
        -------
        list of str
            E.g. ``["bridge", "curve", "--points", "50"]``.
        """
        args = self.name.split() + (["--sample"] if self.sample is not None else [])
        for key, value in self.example:
            args.append("--" + key.replace("_", "-"))
            if value is not True:  # a flag takes no value
                args.append(",".join(map(str, value)) if isinstance(value, tuple) else str(value))
        return args

    def options(self, **kw):
        """The command's options object (``options_path``, imported on first use) built from keywords.

        Parameters
        ----------
        **kw
            Options by keyword.

        Returns
        -------
        object
            The options object (a capred.result.Options).
        """
        module, name = self.options_path.split(":")
        return getattr(import_module(module), name)(**kw)


#: where the options and input schemas are declared (numpy-free: `--help` reads them)
_S = "capred.spec."
_P = "capred.pipelines."
REDUCTIONS: dict[str, Reduction] = {
    r.name: r
    for r in (
        Reduction(
            "shear",
            _P + "shear_run:run_shear",
            _S + "shear:ShearOptions",
            "required",
            "shear",
            "shear",
            method=(
                "Suction Δu = γ_w z1 from the hanging-column head, degree of saturation S_R = (V_v − z2)/V_v "
                'from the burette, normal stress σ_N = (m_cap + m_added) g/A (Evenepoel, VUB thesis, "Apply '
                'suction").',
                "Per material, the dry envelope τ = c + σ_N tan φ is fitted (by least squares unless --dry-loss "
                "says otherwise, see below) with standard errors and Student-t 95 % intervals. Every wet test is predicted with the dry c, φ and σ'_N "
                "= σ_N + χ Δu of each model: χ = S_R (Bishop 1959), χ1 = (2π S_R/3)^(2/3) and χ1 Δu + "
                "(2γ/R)(2π S_R/3)^(1/3) (Evenepoel's Own 1 and Own 2), and the others chosen with --models. "
                "Scores: RMSE, bias and R² of predicted − measured, on all wet tests and on the pendular "
                "ones.",
                "The capillary stress each wet test carried is back-analysed as σ_cap = (τ_max − c)/tan φ − "
                "σ_N with its standard uncertainty by the delta method; χ_back = σ_cap/Δu. The ranking's "
                "uncertainty comes from a paired bootstrap over the wet tests that refits the dry envelope in "
                "every replicate.",
            ),
            references=("evenepoel", "bishop1959"),
            summary="Direct shear with hanging-column suction: dry envelope, effective-stress models, σ_cap.",
            table_kind="a direct-shear table",
            row_cells=(27, 8),
        ),
        Reduction(
            "triaxial-bounds",
            _P + "triaxial:run_triaxial_bounds",
            _S + "triaxial:TriaxialOptions",
            "required",
            "triaxial-bounds",
            "triaxial",
            method=(
                "The effective envelope c', φ' is fitted to the saturated drained tests by least squares of "
                "σ'1 on σ'3, σ'1 = K_p σ'3 + 2c'√K_p (Prunier et al. 2024, eq. 25). For every unsaturated "
                "test the total failure state is projected on it under three hypotheses: a spherical "
                "capillary tensor (q = q'), the lower bound σ1,cap = 0, and the EDTP upper bound from the "
                "initial suction s0; the strength gain is q'/q'_sat. Groups sharing one tensor get the "
                "analysis of Appendix 1 (eqs. 37, 48, 49).",
            ),
            references=("prunier2024",),
            summary="Capillary stress tensor at failure from triaxial tests: bounds and groups.",
            table_kind="a triaxial table (one row per test)",
            row_cells=(53, 0),
        ),
        Reduction(
            "triaxial",
            _P + "triaxial_strength:run_triaxial_strength",
            _S + "triaxial_strength:TriaxialStrengthOptions",
            "required",
            "triaxial",
            "triaxial_strength",
            method=(
                "Per material (never pooled), the extended Mohr-Coulomb envelope q_f = (K_p − 1) σ3 + 2√K_p (c' + "
                "s tan φ_b) (Fredlund et al. 1978, in its triaxial form; net stresses) is fitted to the unsaturated "
                "failure states with standard errors, 95 % intervals and correlations. Its trace at s → 0 is the "
                "effective envelope c', φ' (named as such; --c-eff/--phi-eff override it). Every effective-stress "
                "model of `capred shear` predicts q_f = a + b (σ3 + χ s) on that envelope, with the same scores, "
                "AICc weights, fitted χ laws, back-analysed σ_cap and ranking bootstrap; Prunier et al.'s spherical "
                "and lower bounds of each test's capillary tensor carry the envelope's uncertainty.",
            ),
            references=("fredlund1978", "prunier2024", "bishop1959"),
            summary="Unsaturated strength from triaxial failure states: extended Mohr-Coulomb, models, bounds.",
            example=(("bootstrap", 0),),
            table_kind="a table of triaxial failure states",
            row_cells=(25, 1),
        ),
        Reduction(
            "retention",
            _P + "retention:run_retention",
            _S + "retention:RetentionOptions",
            "required",
            "retention",
            "retention",
            method=(
                "Water retention curves are fitted per branch (drying, wetting) by least squares on θ or S_R: "
                "van Genuchten (1980) with m = 1 − 1/n and with m free, and Brooks & Corey (1964) with the "
                "air-entry suction profiled exactly. Standard errors from the Jacobian; R², AIC and BIC.",
            ),
            references=("vangenuchten1980", "brooks_corey1964"),
            summary="Water retention curves per branch: fits at the optimum, model selection.",
            table_kind="a retention table",
            row_cells=(4, 1),
        ),
        Reduction(
            "retention-convert",
            _P + "retention_convert:run_retention_convert",
            _S + "retention_convert:ConvertOptions",
            "required",
            "retention-convert",
            "retention_convert",
            method=(
                "A fitted retention curve is expressed in another model: the target's parameters are those that "
                "best reproduce the fitted curve (least squares on S_R or θ, at the global optimum inside the "
                "target's bounds) at the suctions of the original data and at a dense logarithmic grid between "
                "the smallest and largest of them; the RMSE and the largest deviation say how closely the target "
                "follows it. A closed-form correspondence (e.g. Lenhard et al. 1989 for Brooks-Corey and van "
                "Genuchten) holds only in the limits; the fit holds over the data's range.",
            ),
            references=("lenhard1989",),
            summary="A retention fit expressed in another model (fits.json --to MODEL), with the misfit.",
            example=(("to", "bc"),),
            input_description=(
                "FIT.json: the fits.json written by `capred retention` (or by `capred retention-convert`): per "
                "branch (drying, wetting), each model's fitted parameters and the suctions of the data they were "
                "fitted to. --branch and --model choose the fit to convert (default: drying, lowest AICc)."
            ),
        ),
        Reduction(
            "prism",
            _P + "calculators:reduce_prism",
            _S + "calculators:PrismOptions",
            "optional",
            "prism",
            "prism",
            method=(
                "P_kmax = σ_b (1 − sin ρ)/(2 sin ρ) and h_c = P_kmax/γ_w from the break tension of a sand "
                "prism and the friction angle of the sand (Bernatzik 1948).",
            ),
            references=("bernatzik1948",),
            files_by_default=False,
            summary="Capillary pressure and rise from the break tension of a sand prism.",
        ),
        Reduction(
            "skempton-b",
            _P + "calculators:reduce_skempton_b",
            _S + "calculators:SkemptonOptions",
            "optional",
            "skempton-b",
            "skempton",
            method=(
                "B = 1/(1 + p'0 e0 (1 − S_r)/(κ P_a0)) with p'0 = p0 − u0 (Morvan et al. 2016, eq. 10), or "
                "its inverse; with suction equilibrium p'0 = p0 − u_a0 + s S_r and s from Brooks-Corey.",
            ),
            references=("morvan2016", "skempton1954", "brooks_corey1964"),
            files_by_default=False,
            summary="Skempton's B from S_r, or S_r from a measured B.",
        ),
        Reduction(
            "rumpf",
            _P + "calculators:reduce_rumpf",
            _S + "calculators:RumpfOptions",
            "optional",
            "rumpf",
            "rumpf",
            method=("p_cap = −(6/φ)(S_r/e)(γ/d_p) cos θ (Prunier et al. 2024, eq. 19, after Rumpf).",),
            references=("prunier2024",),
            files_by_default=False,
            summary="Rumpf's capillary pressure from S_r, void ratio and grain size.",
        ),
        Reduction(
            "shear-band",
            _P + "calculators:reduce_shear_band",
            _S + "calculators:ShearBandOptions",
            "optional",
            None,
            "shear_band",
            method=(
                "Shear-band angles to the major principal plane from the effective friction angle φ' (given, or "
                "from the envelope of a triaxial-bounds summary.json) and the dilatancy angle ψ (given, or from "
                "the dilatancy rate d = −dε_v/dε_1 at failure, sin ψ = d/(2 + d)): Coulomb 45 + φ'/2, Roscoe "
                "(1970) 45 + ψ/2, Arthur et al. (1977) 45 + (φ' + ψ)/4, beside a measured angle (Prunier et al. "
                "2024, Fig. 14: about 70 and 60 deg).",
            ),
            references=("roscoe1970", "arthur1977", "prunier2024"),
            files_by_default=False,
            summary="Shear-band angles (Coulomb, Roscoe, Arthur) beside a measured one.",
            example=(("phi_eff", 31.5), ("dilatancy_angle", 10), ("measured", 60)),
        ),
        Reduction(
            "bridge solve",
            _P + "bridge:solve_bridges",
            _S + "bridge:BridgeOptions",
            "required",
            "bridge-solve",
            "bridge",
            method=(
                "Exact pendular bridges between two equal spheres from the axisymmetric Young-Laplace "
                "equation, its first integral evaluated by Gauss-Legendre quadrature; F_cap = π r0² Δu + 2π "
                "r0 γ, S_R = 3V_w/(2πR³), σ' = F_cap/(πR²) (Evenepoel's unit cell; Lian et al. 1993).",
            ),
            references=("evenepoel", "lian1993"),
            summary="Exact capillary bridges from a table of cases.",
            row_cells=(16, 0),
        ),
        Reduction(
            "bridge compare",
            _P + "bridge:compare_measured",
            _S + "bridge:BridgeOptions",
            "required",
            "bridge-compare",
            "bridge_compare",
            method=(
                "Measured capillary forces of micro-tests beside the exact bridge of the same R, gap, contact "
                "angle and volume, the toroidal approximation, Willett et al. (2000) and Israelachvili's 2πRγ "
                "cos θ, and beside every closed-form law of `capred bridge laws` (its registry), each with "
                "Derjaguin's effective radius for unequal pairs and a plane, and NaN where a law does not apply "
                "to the pair's geometry.",
            ),
            references=("willett2000", "israelachvili", "lian1993"),
            summary="Measured capillary forces beside the exact bridge and approximations.",
            row_cells=(13, 2),
            row_cells_per="bridge_laws",
        ),
        Reduction(
            "bridge rupture",
            _P + "bridge:rupture_distances",
            _S + "bridge:BridgeOptions",
            "required",
            "bridge-rupture",
            "bridge_rupture",
            method=(
                "Each bridge of water volume V_w is pulled apart at constant volume: the rupture distance is the "
                "widest gap at which a stable Young-Laplace bridge of that volume still exists between the two "
                "bodies, found on the exact bridges, beside Lian et al.'s (1993) estimate "
                "D_rupt = (1 + θ/2) V^(1/3) (θ in rad, lengths over R).",
            ),
            references=("lian1993",),
            summary="Rupture distance of bridges at constant volume.",
            row_cells=(14, 0),
        ),
        Reduction(
            "bridge laws",
            _P + "bridge_laws:compare_laws",
            _S + "bridge:LawsOptions",
            "optional",
            "bridge-laws",
            "bridge_laws",
            method=(
                "The closed-form capillary forces of DEM codes (Willett et al. 2000, simple and full; Rabinovich "
                "et al. 2005; Lambert et al. 2008; Soulié et al. 2006; Mikami et al. 1998; Weigert & Ripperger 1999) against the exact "
                "Young-Laplace bridge at equal contact angle, volume and gap, the exact bridge on the stable branch "
                "at constant volume; forces in units of 2πRγ, relative errors per region of gap × volume × angle "
                "× geometry.",
            ),
            references=("willett2000", "lian1993"),
            summary="Closed-form capillary-force laws of DEM codes against the exact bridge.",
        ),
        Reduction(
            "bridge yade-files",
            _P + "yade_files:reduce_yade_files",
            _S + "bridge:YadeOptions",
            "none",
            None,
            "yade_files",
            method=(
                "One file per radius ratio R2/R1 in the layout YADE's capillary law reads (Duriez & Wan 2017): "
                "per distance d* = D/R2, by rising suction uc* = Δu R2/γ, the exact stable Young-Laplace bridge's "
                "volume, force F/(2πγR2), filling angles and the integrals of its normal; nothing is interpolated.",
            ),
            references=("duriez_wan2017",),
            summary="Capillary files for YADE's capillary law.",
            example=(("ratios", (1, 2)), ("distances", 4), ("suctions", 5)),
        ),
        Reduction(
            "bridge curve",
            _P + "bridge:reduce_curve",
            _S + "bridge:CurveOptions",
            "none",
            None,
            "bridge_curve",
            method=(
                "σ' = F_cap/(πR²) against S_R = 3V_w/(2πR³) for two spheres in contact, from exact bridges, "
                "beside Israelachvili, Bishop (S_R Δu) and Evenepoel's Own 1 and Own 2.",
            ),
            references=("evenepoel", "israelachvili", "bishop1959"),
            summary="The thesis's σ'-S_R comparison for spheres in contact.",
            example=(("points", 50),),
        ),
        Reduction(
            "pt-volume",
            _P + "pt_volume:run_pt_volume",
            _S + "pt_volume:PTVolumeOptions",
            "required",
            "pt-volume",
            "pt_volume",
            method=(
                "Volume change along a path of total stress σ, pore pressures u_w, u_a and degree of saturation "
                "S_r with the model of Pedrotti & Tarantino (submitted): the water-saturated pores carry "
                "σ'_W = (σ − u_w) S_r and the air-saturated pores σ'_A = (σ − u_a)(1 − S_r) (eq. 1-2, with u_w "
                "and u_a as in their section 5.1). Pores that keep their fluid move on the url (eq. 6-7) or ncl "
                "(eq. 10) of clay reconstituted from slurry (W: λ_W, κ_W) or compressed from dry powder (A: "
                "λ_A, κ_A); pores that change fluid move from the equivalent pre-consolidation stress σ* onto "
                "the lines of their new fluid (eq. 8-9). The sample's void ratio couples the parts through S_r "
                "(eq. 5, read as e = e^W e^A/(e^W (1 − S_r) + e^A S_r), the form that returns e^W at S_r = 1 "
                "and e^A at S_r = 0).",
                "capred keeps the books of solids and voids of each part instead of adding the class changes "
                "with the weights ΔS_r/S_r and −ΔS_r/(1 − S_r) of eq. 3-4 (which it reports as w_AW, w_WA): "
                "the pores that change fluid are taken pro rata from the part they leave, in the amount that "
                "makes the model's S_r equal the path's. Both parts start on their ncl at the first point "
                "(the end of compaction, point A of Fig. 13) unless initial yield stresses are given; steps "
                "are split into sub-steps (|ΔS_r| ≤ 0.002, |Δ ln σ'| ≤ 0.02 by default).",
            ),
            references=("pedrotti_tarantino_submitted",),
            summary="Void ratio along a stress path with two effective stresses.",
            table_kind="a stress path for pt-volume",
            example=(("example_kaolin", True),),
        ),
        Reduction(
            "compression",
            _P + "compression:run_compression",
            _S + "compression:CompressionOptions",
            "required",
            "compression",
            "compression",
            method=(
                "The first loading of an oedometer or isotropic compression test is fitted (least squares, five "
                "parameters, Jacobian covariance) with a smooth bilinear curve in e-log10 σ': a recompression and a "
                "virgin line joined by a bend of width w decades. C_c is the virgin line's slope (λ = C_c/ln 10), "
                "e_N its void ratio at the reference stress, σ'_y the meeting point of the two lines; on the fitted "
                "curve the pre-consolidation stress is constructed after Casagrande (1936: largest curvature, "
                "bisector of the horizontal and the tangent, virgin line) and Pacheco Silva (1970: virgin line at "
                "e0, down to the curve, across to the virgin line). Unloading stages give C_s (κ = C_s/ln 10) and "
                "reloading stages C_r, each a straight line in e-log10 σ' with one slope and an intercept per "
                "stage. Standard errors by the delta method, 95 % intervals by Student's t (stresses: symmetric in "
                "log σ').",
            ),
            references=("casagrande1936", "pacheco_silva1970", "schofield_wroth1968"),
            summary="Oedometer or isotropic compression: λ (C_c), κ (C_s), e_N and the yield stress.",
            table_kind="a compression test (one row per reading)",
            row_cells=(6, 0),
        ),
        Reduction(
            "history",
            _P + "history:reduce_history",
            _S + "history:HistoryOptions",
            "required",
            "history",
            "history",
            method=(
                "Individuals chart with moving range (Montgomery 2013, section 6.4): MR_i = |x_i − x_(i−1)|; "
                "centre line and σ = mean(MR)/1.128 from the first runs (8 by default) or from a reference "
                "value and spread; limits centre ± 3σ, moving-range limit 3.267·mean(MR); runs beyond are flagged.",
            ),
            summary="A lab's recorded runs (--store): one quantity per run on a control chart.",
            example=(("quantity", "phi_deg"),),
            input_description=(
                "STORE: a lab store (one SQLite file) that any command fills with --store STORE or CAPRED_STORE: "
                "per recorded run its date, inputs and options, and one record per material and quantity (a key of "
                "the run's JSON such as phi_deg, with its 95 % interval and unit). It is opened read-only."
            ),
        ),
    )
}


def run(command: str, source=None, options=None, **option_values):
    """Run any command from a script: ``capred.run("shear", "tests.csv", gamma_w="10 kN/m^3")``.

    Parameters
    ----------
    command : str
        A command's name, a key of ``REDUCTIONS`` (e.g. "shear", "bridge solve").
    source : str, pathlib.Path, pandas.DataFrame or None, optional
        The input table (None for a command without one).
    options : object or None, optional
        The command's options object; None: built from ``option_values``.
    **option_values
        Options by keyword, when ``options`` is None.

    Returns
    -------
    capred.result.Result
        The command's result.
    """
    red = REDUCTIONS[command]
    if options is None:
        options = red.options(**option_values)
    return red.run(source, options)
