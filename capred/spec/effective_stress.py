"""The effective-stress and strength models of `capred shear`: their one registry, declared without numerics.

A model is one entry of ``REGISTRY``: name, label, the parameters it needs, its style, methods text and
reference, and the functions giving σ'_N (or τ directly) named as ``"module:function"`` (the numerical functions
live in `capred.physics.effective_stress_models`, imported only when a model is run). Adding a model is adding
one entry; a script may give its functions as callables::

    REGISTRY["half_bishop"] = EffectiveStressModel(
        "half_bishop", "Half Bishop", (), "bishop1959", sigma_eff=lambda d: d.sigma_N + 0.5 * d.S_R * d.suction
    )

Importing this module imports no numpy (``capred --help`` reads it).

References
----------
.. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular materials,
   master thesis, Vrije Universiteit Brussel (no DOI): the thesis's four models.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from .callables import CallableField

__all__ = [
    "MODEL_LABELS",
    "REGISTRY",
    "THESIS_MODELS",
    "EffectiveStressModel",
    "Flag",
    "UnitCellCurve",
    "asks_for_all",
    "bridge_curve_models",
    "resolve_models",
]


@dataclass(frozen=True)
class Flag:
    """A per-test flag: its name in results.csv and what it means (completes "N wet tests ...")."""

    name: str
    meaning: str


@dataclass(frozen=True)
class UnitCellCurve:
    """How a model is drawn on the σ'-S_R curve of `capred bridge curve` (two equal spheres in contact).

    The model's capillary stress on that unit cell is its own ``sigma_eff`` at σ_N = 0
    (`capred.physics.effective_stress_models.unit_cell_capillary_stress`), compared there with the exact
    pendular bridge.

    Attributes
    ----------
    label : str
        Legend label of the curve (mathtext), naming the model and its capillary term.
    line : dict
        Matplotlib line width and dash (``lw``, ``ls``); the colour is the model's ``style``.
    """

    label: str
    line: dict


@dataclass(frozen=True)
class EffectiveStressModel:
    """One entry of the registry: everything capred knows about a model.

    The callable fields (``sigma_eff``, ``tau``, ``material_values``, ``chi_of_saturation``) are declared as
    ``"module:function"`` strings or given as callables; reading one gives the callable (its module imported
    on first use, see `capred.spec.callables.resolve`).

    Attributes
    ----------
    name : str
        Name as typed in ``--models`` and used in JSON keys and columns.
    label : str
        Short label of tables and legends (mathtext allowed).
    requires : tuple of (str, str)
        (ModelParams field, command-line option) of each parameter the model needs.
    reference : str
        Key of capred.references.REFERENCES.
    sigma_eff, tau : callable
        ``sigma_eff(ModelInputs)`` gives σ'_N [Pa]; a model that predicts the strength directly gives ``tau``
        [Pa] instead (its σ'_N is then NaN).
    thesis : bool
        One of the four models of Evenepoel's thesis (the default set).
    fitted : tuple of str
        Parameters fitted per material on the wet tests (capred.fitting.chi_laws).
    wet_parameters : int
        Parameters fitted on the wet tests outside a χ law (Fredlund's tan φ_b): counted in AICc and BIC.
    material_values : callable, optional
        ``material_values(ModelInputs of one material's wet tests) -> {json key: value}``: what the model
        reports per material beside the dry envelope.
    no_prediction : Flag, optional
        The flag of wet tests the model cannot predict (NaN), left out of its metrics.
    along_retention : bool
        Drawn as a curve along the material's water-retention relation (False: markers per test only).
    style : dict
        Colour (an Okabe-Ito colour name: black, orange, sky, green, yellow, blue, vermillion, purple, grey)
        and marker of every figure.
    method : str
        One sentence for the methods section of report.html (the equation of the model).
    chi_of_saturation : callable, optional
        ``chi(S_R, params, fitted)`` for a model whose χ depends on S_R alone (drawn against the
        back-analysed χ); ``params`` is the run's ModelParams, ``fitted`` the material's fitted law parameters
        (or None).
    bridge_curve : UnitCellCurve, optional
        Drawn beside the exact bridge on `capred bridge curve` (σ' against S_R of the unit cell), with its
        error against the exact bridge in curve.json (Evenepoel's comparison: Bishop, Own 1, Own 2).
    uses_radius : bool
        The model reads the particle radius R of a wet test (`capred shear` then requires it; other models
        run without it).
    parameters : tuple of capred.spec.shear.ModelParameter
        Parameters the model declares for itself: each becomes the option ``--<name>`` of `capred shear` and
        `capred triaxial` (its unit and range from the declaration), ``ModelParams(extra={name: value})`` in
        the API and ``d.params.<name>`` in the model; list it in ``requires`` to refuse a run without it.
    """

    name: str
    label: str
    requires: tuple[tuple[str, str], ...]
    reference: str
    sigma_eff: object = field(default=CallableField(), repr=False)
    tau: object = field(default=CallableField(), repr=False)
    thesis: bool = False
    fitted: tuple[str, ...] = ()
    wet_parameters: int = 0
    material_values: object = field(default=CallableField(), repr=False)
    no_prediction: Flag | None = None
    along_retention: bool = True
    style: dict = field(default_factory=lambda: {"color": "black", "marker": "o"})
    method: str = ""
    chi_of_saturation: object = field(default=CallableField(), repr=False)
    bridge_curve: UnitCellCurve | None = None
    uses_radius: bool = False
    parameters: tuple = ()


#: where the registry's numerical functions live
_F = "capred.physics.effective_stress_models:"

#: what both Pedrotti-Tarantino entries quote of the paper (eq. 1 and 11-14)
_PT_EQUATIONS = (
    "Pedrotti & Tarantino: eq. 1 σ'_W = (σ − u_w) S_R; eq. 11 T = τA = T^W + T^A; eq. 12 τ^W = T^W/A^W, "
    "τ^A = T^A/A^A; eq. 13 τ = τ^W A^W/A + τ^A A^A/A; eq. 14 τ = τ^W S_R + τ^A (1 − S_R) with A^W/A = S_R; "
    "τ^W on the envelope of the saturated (reconstituted) soil, τ^A on that of the dry one."
)

REGISTRY: dict[str, EffectiveStressModel] = {
    m.name: m
    for m in (
        EffectiveStressModel(
            "no_suction",
            "No suction",
            (),
            "evenepoel",
            _F + "_no_suction",
            thesis=True,
            style={"color": "grey", "marker": "s"},
            method="No suction: σ'_N = σ_N, the dry envelope alone.",
        ),
        EffectiveStressModel(
            "bishop",
            "Bishop",
            (),
            "bishop1959",
            _F + "_bishop",
            thesis=True,
            style={"color": "blue", "marker": "o"},
            method="Bishop: σ'_N = σ_N + S_R Δu (χ = S_R).",
            chi_of_saturation=_F + "_bishop_chi",
            bridge_curve=UnitCellCurve(r"Bishop $S_R\,\Delta u$", {"lw": 1.2, "ls": "-."}),
        ),
        EffectiveStressModel(
            "own1",
            "Own 1",
            (),
            "evenepoel",
            _F + "_own1",
            thesis=True,
            style={"color": "orange", "marker": "^"},
            method="Own 1: σ'_N = σ_N + χ1 Δu with χ1 = (2π S_R/3)^(2/3).",
            chi_of_saturation=_F + "_own1_chi",
            bridge_curve=UnitCellCurve(r"Own 1 $\chi_1\,\Delta u$", {"lw": 1.2, "ls": ":"}),
        ),
        EffectiveStressModel(
            "own2",
            "Own 2",
            (),
            "evenepoel",
            _F + "_own2",
            thesis=True,
            uses_radius=True,
            style={"color": "green", "marker": "D"},
            method="Own 2: σ'_N = σ_N + χ1 Δu + (2γ/R)(2π S_R/3)^(1/3).",
            bridge_curve=UnitCellCurve(r"Own 2 $\chi_1\,\Delta u + \chi_2$", {"lw": 1.4, "ls": "-"}),
        ),
        EffectiveStressModel(
            "vanapalli",
            "Vanapalli",
            (("s_res", "--s-res"),),
            "vanapalli1996",
            _F + "_vanapalli",
            style={"color": "purple", "marker": "v"},
            method="Vanapalli: χ = S_e^κ with S_e = (S_R − S_res)/(1 − S_res), κ from --vanapalli-kappa.",
            chi_of_saturation=_F + "_vanapalli_chi",
        ),
        EffectiveStressModel(
            "khalili",
            "Khalili-Khabbaz",
            (("air_entry", "--air-entry"),),
            "khalili_khabbaz1998",
            _F + "_khalili",
            style={"color": "vermillion", "marker": "<"},
            method="Khalili-Khabbaz: χ = (Δu/s_b)^−0.55 above the air-entry suction s_b, 1 below.",
        ),
        EffectiveStressModel(
            "lu_likos",
            "Lu-Likos",
            (("vg_alpha", "--vg-alpha"), ("vg_n", "--vg-n")),
            "lu_likos2006",
            _F + "_lu_likos",
            style={"color": "sky", "marker": ">"},
            method="Lu-Likos: χ = S_e of van Genuchten's curve at the test's suction (suction stress).",
        ),
        EffectiveStressModel(
            "fredlund",
            "Fredlund φ_b",
            (),
            "fredlund1978",
            _F + "_fredlund",
            wet_parameters=1,
            material_values=_F + "_fredlund_values",
            along_retention=False,
            style={"color": "black", "marker": "p"},
            method="Fredlund: τ = c + σ_N tan φ + Δu tan φ_b, tan φ_b fitted per material on the wet tests.",
        ),
        EffectiveStressModel(
            "pedrotti_tarantino",
            "Pedrotti-Tarantino",
            (),
            "pedrotti_tarantino_submitted",
            tau=_F + "_pedrotti_tarantino",
            style={"color": "sky", "marker": "h"},
            material_values=_F + "_water_envelope_values",
            method=_PT_EQUATIONS + " Read as printed: τ^W is evaluated at σ'_W = (σ − u_w) S_R and τ^A at "
            "σ'_A = (σ − u_a)(1 − S_R) (\"τ^W is controlled by ... σ'_W\", after eq. 14), so friction is "
            "weighted by S_R².",
        ),
        EffectiveStressModel(
            "pedrotti_tarantino_wet_area",
            "Pedrotti-Tarantino (wet area)",
            (),
            "pedrotti_tarantino_submitted",
            tau=_F + "_pedrotti_tarantino_wet_area",
            style={"color": "yellow", "marker": "H"},
            material_values=_F + "_water_envelope_values",
            method=_PT_EQUATIONS + " Read consistently in area: τ^W = T^W/A^W is a stress on the wet area, "
            "where the wet part's normal stress is σ'_W/S_R = σ − u_w (eq. 1 is a force per total area), so "
            "τ = S_R τ^W(σ − u_w) + (1 − S_R) τ^A(σ − u_a).",
        ),
        EffectiveStressModel(
            "chi_power",
            "χ = S_e^κ (fitted)",
            (),
            "vanapalli1996",
            _F + "_chi_power",
            fitted=("kappa",),
            style={"color": "purple", "marker": "P"},
            method="χ = S_e^κ with κ fitted per material on the wet tests.",
            chi_of_saturation=_F + "_chi_power_chi",
        ),
        EffectiveStressModel(
            "khalili_fit",
            "Khalili-Khabbaz (fitted)",
            (),
            "khalili_khabbaz1998",
            _F + "_khalili_fit",
            fitted=("s_b", "eta"),
            style={"color": "vermillion", "marker": "X"},
            method="Khalili-Khabbaz with the air-entry suction s_b (and optionally η) fitted per "
            "material on the wet tests.",
        ),
        EffectiveStressModel(
            "exact_neck",
            "Exact bridge",
            (),
            "evenepoel",
            _F + "_exact_neck",
            no_prediction=Flag("no_concave_bridge", "hold more water than the last concave bridge at contact"),
            uses_radius=True,
            style={"color": "black", "marker": "*"},
            method="Exact bridge: σ'_N = σ_N + F_cap/(πR²) of the exact pendular bridge between two "
            "spheres in contact holding the test's water at its suction.",
        ),
    )
}

#: The thesis's four models in display order (the default of `capred shear --models`).
THESIS_MODELS = tuple(m for m, e in REGISTRY.items() if e.thesis)


def bridge_curve_models() -> tuple[str, ...]:
    """The models drawn on `capred bridge curve`, in registry order: those whose entry has a ``bridge_curve``.

    No equation: a lookup in ``REGISTRY`` at each call (an entry added later is drawn too).

    Returns
    -------
    tuple of str
        Registry names (Bishop, Own 1 and Own 2 of Evenepoel's comparison).

    References
    ----------
    .. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular
       materials, master thesis, Vrije Universiteit Brussel (no DOI): σ' against S_R of the unit cell.
    """
    return tuple(name for name, e in REGISTRY.items() if e.bridge_curve is not None)


class _Labels(Mapping):
    """model name -> label, read from the registry at each access (an entry added later is labelled too)."""

    def __getitem__(self, name: str) -> str:
        return REGISTRY[name].label

    def __iter__(self):
        return iter(REGISTRY)

    def __len__(self) -> int:
        return len(REGISTRY)


MODEL_LABELS = _Labels()


def resolve_models(names) -> tuple[str, ...]:
    """Model names as a user gives them: a comma-separated string or a sequence.

    ``thesis`` stands for the thesis's four and ``all`` for every model of the registry; duplicates dropped, order kept.

    No equation: a lookup in ``REGISTRY`` (names are lower-cased, ``-`` read as ``_``).

    Parameters
    ----------
    names : str or sequence of str
        E.g. ``"thesis,vanapalli"`` or ``["bishop", "own1"]``.

    Returns
    -------
    tuple of str
        Registry names, in the order given.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the choices) or an empty selection.

    References
    ----------
    .. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular
       materials, master thesis, Vrije Universiteit Brussel (no DOI): the four models of ``thesis``.
    """
    items = names.split(",") if isinstance(names, str) else list(names)
    out: list[str] = []
    for name in (str(t).strip().lower().replace("-", "_") for t in items if str(t).strip()):
        for m in {"thesis": THESIS_MODELS, "all": tuple(REGISTRY)}.get(name, (name,)):
            if m not in REGISTRY:
                raise ValueError(f"unknown model '{m}'; choose from {', '.join(REGISTRY)}, thesis or all")
            if m not in out:
                out.append(m)
    if not out:
        raise ValueError("no model named")
    return tuple(out)


def asks_for_all(names) -> bool:
    """True when a ``--models`` selection contains ``all`` (run every model the inputs allow).

    Parameters
    ----------
    names : str or sequence of str
        As for `resolve_models`.

    Returns
    -------
    bool

    References
    ----------
    .. [1] capred issue 29.6 (no paper: a selection rule): ``all`` runs every model the inputs allow.
    """
    items = names.split(",") if isinstance(names, str) else list(names)
    return any(str(t).strip().lower() == "all" for t in items)
