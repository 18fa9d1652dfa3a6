"""Effective-stress and strength models of `capred shear`, and their one registry (SI units).

A model is one entry of ``REGISTRY``, declared in `capred.spec.effective_stress` (name, label, the
parameters it needs, its reference and the names of its functions here); this module holds the functions
giving sigma'_N (or tau directly) and re-exports the registry. Adding a model is adding one entry.

References
----------
[1] Evenepoel, master thesis, Vrije Universiteit Brussel: "Own approximation".
[8] Vanapalli et al. (1996), Can. Geotech. J. 33:379-392, doi:10.1139/t96-060.
[9] Khalili & Khabbaz (1998), Géotechnique 48:681-687, doi:10.1680/geot.1998.48.5.681.
[10] Lu & Likos (2006), J. Geotech. Geoenviron. Eng. 132:131-142,
    doi:10.1061/(ASCE)1090-0241(2006)132:2(131).
[11] Fredlund et al. (1978), Can. Geotech. J. 15:313-321, doi:10.1139/t78-029.
[12] Pedrotti & Tarantino, "Effective stresses for unsaturated states stemming
    from clay microstructure" (submitted), eq. [1], [2], [14].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..spec.effective_stress import (  # noqa: F401  (the registry and its lookups, declared without numerics)
    MODEL_LABELS,
    REGISTRY,
    THESIS_MODELS,
    EffectiveStressModel,
    Flag,
    UnitCellCurve,
    asks_for_all,
    bridge_curve_models,
    resolve_models,
)
from . import shear as ph
from .retention import vg_effective_saturation


def chi_vanapalli(S_R, S_res=0.0, vanapalli_kappa=1.0):
    r"""Bishop's χ as the normalised degree of saturation raised to κ (Vanapalli et al. 1996).

    .. math::

        \chi = S_e^{\kappa}, \qquad S_e = \frac{S_R - S_{res}}{1 - S_{res}} \in [0, 1]

    Vanapalli et al. write :math:`\tau = c' + (\sigma - u_a)\tan\phi' + s\,\Theta^{\kappa}\tan\phi'`
    with :math:`\Theta` the normalised volumetric water content; at constant void ratio
    :math:`\Theta = S_e`, and κ = 1 is their second form (the normalised water content itself). The fitted law ``chi_power``
    (:mod:`capred.fitting.chi_laws`) is this χ with κ fitted per material.

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-].
    S_res : float or array_like, default 0
        Residual degree of saturation [-], in [0, 1).
    vanapalli_kappa : float or array_like, default 1
        Exponent κ [-], > 0 (glossary ``vanapalli_kappa``; the JSON parameter of ``chi_power`` is ``kappa``).

    Returns
    -------
    numpy.ndarray
        χ [-], in [0, 1]; 0 at and below ``S_res``.

    References
    ----------
    .. [1] Vanapalli, S. K., Fredlund, D. G., Pufahl, D. E. & Clifton, A. W. (1996). Model for the
       prediction of shear strength with respect to soil suction. Can. Geotech. J. 33(3):379-392.
       doi:10.1139/t96-060: the prediction equation with :math:`\Theta^\kappa` (equation number not
       checked against the paper, which capred does not hold).
    """
    S_e = np.clip((np.asarray(S_R, float) - S_res) / (1.0 - S_res), 0.0, 1.0)
    return S_e**vanapalli_kappa


def chi_khalili(suction, air_entry, eta=0.55):
    r"""Bishop's χ of Khalili & Khabbaz (1998): a power of the suction above the air-entry value.

    .. math::

        \chi = \left(\frac{s}{s_b}\right)^{-\eta} \;\; (s > s_b), \qquad \chi = 1 \;\; (s \le s_b)

    Parameters
    ----------
    suction : array_like
        Matric suction s [Pa], >= 0.
    air_entry : float or array_like
        Air-entry (or air-expulsion) suction :math:`s_b` [Pa], > 0.
    eta : float or array_like, default 0.55
        Exponent η [-]; Khalili & Khabbaz found 0.55 for many soils.

    Returns
    -------
    numpy.ndarray
        χ [-], in (0, 1].

    References
    ----------
    .. [1] Khalili, N. & Khabbaz, M. H. (1998). A unique relationship for chi for the determination of the
       shear strength of unsaturated soils. Géotechnique 48(5):681-687. doi:10.1680/geot.1998.48.5.681,
       the χ-(s/s_b) relation and its best-fit exponent η = 0.55 (equation number not checked).
    """
    s = np.asarray(suction, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(s > air_entry, (np.where(s > 0, s, 1.0) / air_entry) ** -eta, 1.0)


def exact_neck_capillary_stress(S_R, suction, R, surface_tension, contact_angle=0.0):
    r"""Capillary stress of the exact pendular bridge of a two-sphere unit cell [Pa], and where it exists.

    .. math::

        \sigma_{cap} = \frac{\pi r_0^2\,\Delta u + 2\pi r_0\,\gamma}{\pi R^2}, \qquad
        V_w = \frac{2\pi R^3 S_R}{3}

    with :math:`r_0` the neck radius of the exact Young-Laplace bridge between two equal spheres of
    radius R in contact that holds the unit-cell water volume :math:`V_w` (Evenepoel, VUB thesis,
    "Shape"), and Δu the measured suction. As S_R -> 0 it tends to Israelachvili's
    :math:`2\gamma\cos\theta_c/R`.

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-].
    suction : array_like
        Measured matric suction Δu [Pa].
    R : array_like
        Particle radius [m].
    surface_tension : float
        γ [N/m].
    contact_angle : float, default 0
        Contact angle :math:`\theta_c` [deg], in [0, 90).

    Returns
    -------
    sigma_cap : numpy.ndarray
        Capillary stress [Pa]; NaN where S_R exceeds the last concave bridge (or is 0).
    ok : numpy.ndarray of bool
        Where the bridge exists.

    References
    ----------
    .. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular
       materials, master thesis, Vrije Universiteit Brussel (no DOI): the unit cell, section "Shape".
    .. [2] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two
       rigid spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452 (the bridge and
       its force through the neck).
    """
    from . import bridge as br

    S, s, R = (np.asarray(x, float) for x in np.broadcast_arrays(S_R, suction, R))
    th = np.radians(contact_angle)
    beta, s_star, status = br.solve_for_volume(np.full(S.size, th), (2.0 * np.pi * S / 3.0).ravel(), 0.0)
    ok = (status == 0).reshape(S.shape)
    y0 = br.geometry(beta, th, np.where(status == 0, s_star, 0.0))[3].reshape(S.shape)
    r0 = y0 * R
    with np.errstate(invalid="ignore"):
        cap = (np.pi * r0**2 * s + 2.0 * np.pi * r0 * surface_tension) / (np.pi * R**2)
    return np.where(ok, cap, np.nan), ok


def chi_lu_likos(suction, vg_alpha, vg_n, vg_m=None):
    r"""Bishop's χ as the effective saturation of van Genuchten's curve (Lu & Likos 2006).

    .. math::

        \chi = S_e(s) = \left[1 + (\alpha s)^n\right]^{-m}, \qquad -\sigma^s = S_e\, s

    (the suction stress :math:`\sigma^s` of Lu & Likos with van Genuchten's S_e).

    Parameters
    ----------
    suction : array_like
        Matric suction s [Pa], >= 0.
    vg_alpha : float or array_like
        van Genuchten :math:`\alpha` [1/Pa], > 0.
    vg_n : float or array_like
        van Genuchten n [-], > 1.
    vg_m : float or array_like, optional
        van Genuchten m [-]; ``1 - 1/vg_n`` when None.

    Returns
    -------
    numpy.ndarray
        χ [-], in [0, 1].

    References
    ----------
    .. [1] Lu, N. & Likos, W. J. (2006). Suction stress characteristic curve for unsaturated soil.
       J. Geotech. Geoenviron. Eng. 132(2):131-142. doi:10.1061/(ASCE)1090-0241(2006)132:2(131): the
       suction stress -σ^s = S_e s (equation number not checked).
    .. [2] van Genuchten, M. Th. (1980). A closed-form equation for predicting the hydraulic conductivity of
       unsaturated soils. Soil Sci. Soc. Am. J. 44:892-898. doi:10.2136/sssaj1980.03615995004400050002x,
       eq. 3.
    """
    return vg_effective_saturation(suction, vg_alpha, vg_n, vg_m)


def fit_tan_phi_b(suction, excess_strength):
    r"""The tan φ_b of Fredlund et al. (1978) by least squares through the origin.

    .. math::

        \tau = c' + \sigma_N \tan\phi' + s \tan\phi_b, \qquad
        \tan\phi_b = \frac{\sum_i s_i\,r_i}{\sum_i s_i^2}, \quad r_i = \tau_i - (c' + \sigma_{N,i}\tan\phi')

    Parameters
    ----------
    suction : array_like
        Matric suction s of the wet tests [Pa].
    excess_strength : array_like
        :math:`r_i`, measured strength above the dry envelope of the wet tests [Pa].

    Returns
    -------
    float
        tan φ_b [-]; NaN when every suction is 0.

    References
    ----------
    .. [1] Fredlund, D. G., Morgenstern, N. R. & Widger, R. A. (1978). The shear strength of unsaturated
       soils. Can. Geotech. J. 15(3):313-321. doi:10.1139/t78-029: the planar envelope in (σ − u_a,
       u_a − u_w) (equation number not checked).
    """
    s = np.asarray(suction, float)
    r = np.asarray(excess_strength, float)
    ss = float(s @ s)
    return float(s @ r) / ss if ss > 0 else float("nan")


def pedrotti_tarantino_strength(sigma_N, suction, S_R, c_w, tan_phi_w, c_a, tan_phi_a):
    r"""Shear strength of Pedrotti & Tarantino: the two pore classes each on its own envelope.

    .. math::

        \tau = S_R\,\tau^W + (1 - S_R)\,\tau^A, \qquad
        \tau^W = c_W + \sigma'_W \tan\phi_W, \quad \tau^A = c_A + \sigma'_A \tan\phi_A,

        \sigma'_W = (\sigma - u_w)\,S_R, \qquad \sigma'_A = (\sigma - u_a)(1 - S_R)

    with :math:`\sigma - u_w = \sigma_N + s` and :math:`\sigma - u_a = \sigma_N` when the air is at
    atmospheric pressure. The W envelope is that of the water-saturated (reconstituted) soil, the A
    envelope that of the dry one.

    Parameters
    ----------
    sigma_N : array_like
        Total normal stress σ_N [Pa].
    suction : array_like
        Matric suction s = u_a − u_w [Pa].
    S_R : array_like
        Degree of saturation [-].
    c_w, tan_phi_w : float or array_like
        Cohesion [Pa] and friction coefficient [-] of the water-saturated soil.
    c_a, tan_phi_a : float or array_like
        Cohesion [Pa] and friction coefficient [-] of the dry soil.

    Returns
    -------
    numpy.ndarray
        τ [Pa].

    References
    ----------
    .. [1] Pedrotti, M. & Tarantino, A. Effective stresses for unsaturated states stemming from clay
       microstructure. Submitted to Geomechanics for Energy and the Environment (no DOI yet), eq. 1, 2
       and 14.
    """
    S_R = np.asarray(S_R, float)
    sigma_N = np.asarray(sigma_N, float)
    tau_w = c_w + (sigma_N + np.asarray(suction, float)) * S_R * tan_phi_w
    tau_a = c_a + sigma_N * (1.0 - S_R) * tan_phi_a
    return S_R * tau_w + (1.0 - S_R) * tau_a


def pedrotti_tarantino_wet_area_strength(sigma_N, suction, S_R, c_w, tan_phi_w, c_a, tan_phi_a):
    r"""Shear strength of Pedrotti & Tarantino read consistently in area: each envelope at the stress on its own area.

    .. math::

                au = S_R\,	au^W(\sigma - u_w) + (1 - S_R)\,	au^A(\sigma - u_a), \qquad
                au^W(x) = c_W + x 	an\phi_W, \quad 	au^A(x) = c_A + x 	an\phi_A

    Their eq. 11-13 define τ^W = T^W/A^W, a shear stress on the wet area A^W, and eq. 14 weights it by
    A^W/A = S_R. The effective stress of the wet part, σ'_W = (σ − u_w) S_R (their eq. 1), is its normal force
    per TOTAL area; per wet area it is σ'_W / S_R = σ − u_w (and σ'_A / (1 − S_R) = σ − u_a for the dry part).
    Reading τ^W at σ − u_w keeps both stresses on the same area; the printed reading
    (`pedrotti_tarantino_strength`) evaluates τ^W at σ'_W itself, which weights friction by S_R².

    Parameters
    ----------
    sigma_N : array_like
        Total normal stress σ_N = σ − u_a (air at atmospheric pressure) [Pa].
    suction : array_like
        Matric suction s = u_a − u_w [Pa].
    S_R : array_like
        Degree of saturation [-].
    c_w, tan_phi_w : float or array_like
        Cohesion [Pa] and friction coefficient [-] of the water-saturated (reconstituted) soil.
    c_a, tan_phi_a : float or array_like
        Cohesion [Pa] and friction coefficient [-] of the dry soil.

    Returns
    -------
    numpy.ndarray
        τ [Pa].

    References
    ----------
    .. [1] Pedrotti, M. & Tarantino, A. Effective stresses for unsaturated states stemming from clay
       microstructure. Submitted to Geomechanics for Energy and the Environment (no DOI yet), eq. 1, 2, 11-14.
    """
    S_R = np.asarray(S_R, float)
    sigma_N = np.asarray(sigma_N, float)
    tau_w = c_w + (sigma_N + np.asarray(suction, float)) * tan_phi_w
    tau_a = c_a + sigma_N * tan_phi_a
    return S_R * tau_w + (1.0 - S_R) * tau_a


@dataclass(frozen=True)
class ModelInputs:
    """What a model may use, per test (arrays, SI): the dry envelope of each test's material included."""

    sigma_N: np.ndarray
    suction: np.ndarray
    S_R: np.ndarray
    R: np.ndarray
    tau_max: np.ndarray
    wet: np.ndarray
    material: np.ndarray
    c: np.ndarray
    tan_phi: np.ndarray
    surface_tension: float
    params: object  # capred.pipelines.shear.ModelParams
    fitted: dict = field(default_factory=dict)  # model -> material -> fitted parameters (SI)
    cache: dict = field(default_factory=dict)  # per-test arrays that do not depend on the dry fit
    #: per test, the envelope of its material's saturated tests (c [Pa], tan phi [-]); NaN where it has none
    c_sat: np.ndarray | None = None
    tan_phi_sat: np.ndarray | None = None

    @classmethod
    def of_unit_cell(cls, sigma_N, suction, S_R, R, surface_tension) -> ModelInputs:
        """Inputs of wet tests known only by their stresses and the unit cell (no strength, material or run).

        Parameters
        ----------
        sigma_N : array_like
            Total normal stress [Pa].
        suction : array_like
            Matric suction Δu [Pa].
        S_R : array_like
            Degree of saturation [-].
        R : array_like
            Particle radius [m] (NaN where no model needs it).
        surface_tension : float
            γ [N/m].

        Returns
        -------
        ModelInputs
            The arrays broadcast together, every test wet; strength, dry envelope and material NaN, no run
            parameters (``params`` None): enough for a model whose σ'_N depends on these quantities alone.
        """
        sigma_N, suction, S_R, R = np.broadcast_arrays(
            *(np.asarray(v, dtype=float) for v in (sigma_N, suction, S_R, R))
        )
        nan = np.full(sigma_N.shape, np.nan)
        return cls(sigma_N, suction, S_R, R, nan, np.ones(sigma_N.shape, bool), nan, nan, nan, surface_tension, None)

    def subset(self, mask) -> ModelInputs:
        """The same inputs for the tests selected by ``mask`` (a boolean mask or indices).

        Parameters
        ----------
        mask : array_like of bool or int
            Which tests to keep.

        Returns
        -------
        ModelInputs
            Per-test arrays (and cached arrays) subset; constants and fitted parameters shared.
        """
        arrays = {
            k: getattr(self, k)[mask]
            for k in ("sigma_N", "suction", "S_R", "R", "tau_max", "wet", "material", "c", "tan_phi")
        }
        sat = {k: getattr(self, k)[mask] for k in ("c_sat", "tan_phi_sat") if getattr(self, k) is not None}
        return ModelInputs(
            **arrays,
            surface_tension=self.surface_tension,
            params=self.params,
            fitted=self.fitted,
            cache={k: v[mask] for k, v in self.cache.items()},
            **sat,
        )

    def cached(self, key: str, compute) -> np.ndarray:
        """A per-test array computed once (e.g. exact bridges), kept through ``subset``.

        Parameters
        ----------
        key : str
            Name of the array in the cache.
        compute : callable
            ``compute()`` returns the per-test array; called only when ``key`` is not cached yet.

        Returns
        -------
        numpy.ndarray
            The per-test array (SI units of what ``compute`` returns).
        """
        if key not in self.cache:
            self.cache[key] = compute()
        return self.cache[key]

    def per_test(self, model: str, name: str) -> np.ndarray:
        """A fitted parameter of ``model`` for every test (from its material's fit; NaN where not fitted).

        Parameters
        ----------
        model : str
            A model's registry name.
        name : str
            The parameter's internal name (SI units).

        Returns
        -------
        numpy.ndarray
            One value per test [SI unit of the parameter].
        """
        fits = self.fitted.get(model, {})
        return np.array([fits[m][name] if m in fits else np.nan for m in self.material], dtype=float)


def _tan_phi_b(d: ModelInputs) -> np.ndarray:
    """tan(phi_b) of each test, fitted per material on its wet tests [11]."""
    tb = np.zeros(d.sigma_N.size)
    for m in dict.fromkeys(d.material):
        sel = d.wet & (d.material == m)
        if sel.any():
            excess = d.tau_max[sel] - ph.mohr_coulomb_strength(d.c[sel], d.tan_phi[sel], d.sigma_N[sel])
            tb[d.material == m] = fit_tan_phi_b(d.suction[sel], excess)
    return tb


def _fredlund(d: ModelInputs) -> np.ndarray:
    """sigma'_N equivalent of tau = c + sigma_N tan phi + s tan phi_b, tan phi_b fitted per material [11]."""
    return d.sigma_N + d.suction * _tan_phi_b(d) / d.tan_phi


def _water_envelope(d: ModelInputs):
    """(c_W [Pa], tan phi_W, source) of each test [12, eq. 13].

    Its material's saturated tests where the run has them, else --water-envelope, else the dry envelope (a stand-in the
    result names).
    """
    env = d.params.water_envelope
    c_w, tan_w = (
        (d.c, d.tan_phi)
        if env is None
        else (np.full(d.c.shape, env[0]), np.full(d.c.shape, np.tan(np.radians(env[1]))))
    )
    if d.c_sat is None:
        return c_w, tan_w, np.full(d.c.shape, "dry envelope" if env is None else "--water-envelope")
    own = np.isfinite(d.c_sat)
    source = np.where(own, "saturated tests", "dry envelope" if env is None else "--water-envelope")
    return np.where(own, d.c_sat, c_w), np.where(own, d.tan_phi_sat, tan_w), source


def _pedrotti_tarantino(d: ModelInputs) -> np.ndarray:
    c_w, tan_w, _ = _water_envelope(d)
    return pedrotti_tarantino_strength(d.sigma_N, d.suction, d.S_R, c_w, tan_w, d.c, d.tan_phi)


def _pedrotti_tarantino_wet_area(d: ModelInputs) -> np.ndarray:
    c_w, tan_w, _ = _water_envelope(d)
    return pedrotti_tarantino_wet_area_strength(d.sigma_N, d.suction, d.S_R, c_w, tan_w, d.c, d.tan_phi)


def _no_suction(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + 0.0 * d.suction


def _bishop(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + np.asarray(d.S_R, dtype=float) * d.suction


def _own1(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + ph.chi1(d.S_R) * d.suction


def _own2(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + ph.chi1(d.S_R) * d.suction + ph.chi2(d.S_R, d.R, d.surface_tension)


def _bishop_chi(S, p, f) -> np.ndarray:
    return np.asarray(S, float)


def _own1_chi(S, p, f) -> np.ndarray:
    return ph.chi1(S)


def _vanapalli(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + chi_vanapalli(d.S_R, d.params.s_res, d.params.vanapalli_kappa) * d.suction


def _vanapalli_chi(S, p, f) -> np.ndarray:
    return chi_vanapalli(S, p.s_res, p.vanapalli_kappa)


def _khalili(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + chi_khalili(d.suction, d.params.air_entry) * d.suction


def _lu_likos(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + chi_lu_likos(d.suction, d.params.vg_alpha, d.params.vg_n, d.params.vg_m) * d.suction


def _fredlund_values(d: ModelInputs) -> dict:
    return {"phi_b_deg": float(np.degrees(np.arctan(_tan_phi_b(d)[0])))}


def _water_envelope_values(d: ModelInputs) -> dict:
    return {"water_envelope": str(_water_envelope(d)[2][0])}


def _chi_power(d: ModelInputs) -> np.ndarray:
    return d.sigma_N + chi_vanapalli(d.S_R, d.params.s_res or 0.0, d.per_test("chi_power", "kappa")) * d.suction


def _chi_power_chi(S, p, f) -> np.ndarray:
    return np.full(np.shape(S), np.nan) if f is None else chi_vanapalli(S, p.s_res or 0.0, f["kappa"])


def _khalili_fit(d: ModelInputs) -> np.ndarray:
    s_b, eta = d.per_test("khalili_fit", "s_b"), d.per_test("khalili_fit", "eta")
    return d.sigma_N + chi_khalili(d.suction, s_b, eta) * d.suction


def _exact_neck(d: ModelInputs) -> np.ndarray:
    def compute():
        return exact_neck_capillary_stress(d.S_R, d.suction, d.R, d.surface_tension, d.params.contact_angle)[0]

    return d.sigma_N + d.cached("exact_neck", compute)


def unit_cell_capillary_stress(model: str, S_R, suction, R, surface_tension=ph.SURFACE_TENSION) -> np.ndarray:
    r"""Capillary stress σ'_N − σ_N of a model on the unit cell of two equal spheres in contact [Pa].

    .. math::

        \sigma_{cap}(S_R, \Delta u) = \sigma'_N(\sigma_N = 0, \Delta u, S_R, R, \gamma)

    the model's own ``sigma_eff`` of its registry entry at zero total stress (e.g. :math:`S_R\,\Delta u`
    for Bishop, :math:`\chi_1\Delta u + \chi_2` for Own 2), the quantity Evenepoel compares with
    the exact bridge's :math:`F_{cap}/(\pi R^2)`.

    Parameters
    ----------
    model : str
        A name of ``REGISTRY`` whose σ'_N depends on S_R, Δu, R and γ alone (see `bridge_curve_models`).
    S_R : array_like
        Degree of saturation [-].
    suction : array_like
        Matric suction Δu [Pa].
    R : array_like
        Particle radius [m], > 0.
    surface_tension : float, optional
        γ [N/m] (water at 20 °C by default).

    Returns
    -------
    numpy.ndarray
        σ_cap [Pa], broadcast over the inputs.

    Raises
    ------
    ValueError
        For a model that predicts τ directly, needs run parameters or fits per material.

    References
    ----------
    .. [1] Evenepoel, Micro-mechanical characterization of the capillary effective stress in granular
       materials, master thesis, Vrije Universiteit Brussel (no DOI): sections "Own approximation" and "Shape".
    """
    e = REGISTRY[model]
    if e.sigma_eff is None or e.requires or e.fitted or e.wet_parameters:
        raise ValueError(f"model '{model}' needs more than S_R, suction, R and surface tension")
    return e.sigma_eff(ModelInputs.of_unit_cell(0.0, suction, S_R, R, surface_tension))


def predict(model: str, d: ModelInputs) -> tuple[np.ndarray, np.ndarray]:
    r"""(σ'_N, τ_pred) of every test under ``model``; dry tests keep σ_N and the dry envelope.

    .. math::

        \tau_{pred} = c + \sigma'_N \tan\phi, \qquad \sigma'_N = \sigma_N + \chi\,\Delta u \;\;
        \text{(wet tests; } \sigma'_N = \sigma_N \text{ for dry ones)}

    with χ Δu (or σ'_N itself) from the model's registry entry (Bishop 1959, eq. of the effective
    stress); a model that predicts the strength directly (``tau`` in its entry) gives τ_pred and a NaN
    σ'_N on the wet tests.

    Parameters
    ----------
    model : str
        A name of ``REGISTRY``.
    d : ModelInputs
        The tests and the dry envelope of each (SI).

    Returns
    -------
    sigma_eff : numpy.ndarray
        σ'_N [Pa]; NaN on the wet tests of a model that predicts τ directly.
    tau_pred : numpy.ndarray
        Predicted shear strength [Pa].

    References
    ----------
    .. [1] Bishop, A. W. (1959). The principle of effective stress. Teknisk Ukeblad 106(39):859-863 (no DOI).
    .. [2] Evenepoel, master thesis, Vrije Universiteit Brussel (no DOI): σ'_N on the dry envelope.
    """
    e = REGISTRY[model]
    dry_tau = ph.mohr_coulomb_strength(d.c, d.tan_phi, d.sigma_N)
    if e.tau is not None:
        return np.where(d.wet, np.nan, d.sigma_N), np.where(d.wet, e.tau(d), dry_tau)
    with np.errstate(invalid="ignore"):
        eff = np.where(d.wet, e.sigma_eff(d), d.sigma_N)
    return eff, ph.mohr_coulomb_strength(d.c, d.tan_phi, eff)


def effective_normal_stress(model, sigma_N, suction, S_R, R=np.nan, surface_tension=ph.SURFACE_TENSION):
    r"""Effective normal stress :math:`\sigma'_N` under one of the thesis's four models.

    Parameters
    ----------
    model : str
        One of the thesis's models, ``capred.physics.effective_stress_models.THESIS_MODELS`` (see Notes).
    sigma_N : numeric
        Total normal stress [Pa].
    suction : numeric
        Matric suction :math:`\Delta u` [Pa].
    S_R : numeric
        Degree of saturation [-].
    R : numeric, optional
        Particle radius [m]; needed by ``own2`` only.
    surface_tension : float, default :data:`capred.physics.shear.SURFACE_TENSION`
        Surface tension :math:`\gamma` [N/m]; ``own2`` only.

    Returns
    -------
    numeric
        :math:`\sigma'_N` [Pa].

    Raises
    ------
    ValueError
        For an unknown ``model``.

    Notes
    -----
    .. math::

       \sigma'_N = \sigma_N \ \text{(no_suction)},\quad
       \sigma_N + S_R\Delta u \ \text{(bishop)},\quad
       \sigma_N + \chi_1\Delta u \ \text{(own1)},\quad
       \sigma_N + \chi_1\Delta u + \chi_2 \ \text{(own2)}

    with :math:`\chi_1`, :math:`\chi_2` of :func:`capred.physics.shear.chi1`, :func:`capred.physics.shear.chi2`.

    References
    ----------
    .. [1] Evenepoel, R. (n.d.). Micro-mechanical characterization of the
       capillary effective stress in granular materials. Master thesis, Vrije
       Universiteit Brussel (no DOI), section "Shear strength" (table of
       the four models).
    """
    if model not in THESIS_MODELS:
        raise ValueError(f"unknown model '{model}'; choose from {', '.join(THESIS_MODELS)}")
    return REGISTRY[model].sigma_eff(ModelInputs.of_unit_cell(sigma_N, suction, S_R, R, surface_tension))
