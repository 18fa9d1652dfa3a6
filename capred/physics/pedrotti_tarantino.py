r"""Volume change of unsaturated clay with two effective stresses (Pedrotti & Tarantino).

Compacted clay is pictured as a water-saturated part (the micro-pores, filled
with water) and an air-saturated part (the macro-pores, filled with air). Each
part has its own effective stress [1, eq. 1-2],

.. math::

    \sigma'_W = (\sigma - u_w)\,S_r, \qquad \sigma'_A = (\sigma - u_a)\,(1 - S_r),

and its own compressibility lines in the e-ln σ' plane: the water-saturated
pores follow the normal-compression and unloading-reloading lines (ncl, url)
of the clay reconstituted from slurry (slopes λ_W, κ_W), the air-saturated
pores those of the clay compressed from dry powder (λ_A, κ_A) [1, section 4.1,
hypotheses 2-3]. Pores that change fluid (air to water on wetting, water to
air on drying) jump from their void ratio onto the other part's lines through
an equivalent pre-consolidation stress σ* [1, eq. 8-9]. The void ratio of the
whole sample couples the two parts through S_r [1, eq. 5].

SI units: stresses in Pa, void ratios and S_r dimensionless. Compression
positive; pore pressures are gauge pressures (u_w < u_a under suction).

Choices where the paper is open (each documented again where it is made)
------------------------------------------------------------------------
1. **Stresses.** Section 4.1 of [1] typesets eq. 1-2 with one pore pressure u;
   section 5.1 writes σ'_W = (σ − u_w) S_R and σ'_A = (σ − u_A)(1 − S_R).
   capred uses the latter: the air-saturated part feels the air pressure.
2. **Coupling, eq. 5.** As typeset in the submitted manuscript,
   e = (e^W + e^A)/(e^W (1 − S_r) + e^A S_r) does not return e^W at S_r = 1
   (nor e = e^W when e^W = e^A). Splitting the solids between the two parts,
   with e^W and e^A the void ratios of the parts and S_r the water-filled
   share of the voids, gives 1/e = S_r/e^W + (1 − S_r)/e^A, i.e.
   e = e^W e^A / (e^W (1 − S_r) + e^A S_r), which meets both limits; capred
   uses this form (:func:`coupled_void_ratio`).
3. **Combination of the classes, eq. 3-4.** The paper adds the void-ratio
   changes of the classes with weights ΔS_r/S_r and (−ΔS_r)/(1 − S_r). Read
   literally this does not conserve pore volume when the pores that change
   fluid enter with a void ratio (e^A or e^W) different from that of the part
   they join. The simulator instead keeps the books of solids and voids: each
   part is a set of pore packets (solid fraction, yield stress); the pores
   that change fluid are taken pro rata from every packet of the part they
   leave (hypothesis 4), carry that part's mean void ratio into the transition
   law eq. 8-9, and their amount is the one that makes the model's S_r equal
   the S_r of the path. The weights of eq. 3-4 are recovered as the share of
   the new part's voids that changed fluid (``w_AW``, ``w_WA`` of the record;
   ΔS_r/S_r to first order). Eq. 3-4 as printed are available as
   :func:`water_saturated_increment` and :func:`air_saturated_increment`.
4. **Which pores change fluid.** The direction is that of S_r(path) − S_r
   after the two parts deformed at constant fluid content; it is the sign of
   ΔS_r whenever the two parts deform alike.
5. **Transition law.** Eq. 8 (water to air: rebound on the air url, κ_A) and
   eq. 9 (air to water: collapse onto the water ncl, λ_W) are the two cases
   met in the paper's paths. In general the pores land on the ncl of their new
   fluid when its effective stress reaches σ* (λ) and on the url through σ*
   otherwise (κ) — :func:`transition_void_ratio_change`.
6. **Initial state.** At the first point of the path both parts lie on their
   ncl (the end of compaction, point A of Fig. 13 of [1]) unless larger past
   yield stresses are given.
7. **Lines.** ncl: e = e_ncl − λ ln(σ'/σ_ref) with σ_ref = 1 kPa by default
   (the paper gives the specific volume "at 1 kPa"); a url is the line of
   slope κ through the yield point on the ncl.

The paper prints no parameter values (its λ, κ and intercepts come from
oedometer tests in Pedrotti & Tarantino (2018/2019) and Pedrotti (2016)), so
:class:`PTVolumeParameters` has no defaults.

References
----------
[1] Pedrotti, M., Tarantino, A., "Effective stresses for unsaturated states
    stemming from clay microstructure", submitted to Geomechanics for Energy
    and the Environment: eq. 1-2 (effective stresses), 3-4 (combination of
    the pore classes), 5 (coupling), 6-7 and 10 (url and ncl of the pores
    that keep their fluid), 8-9 (pores that change fluid), Fig. 13-17.
[2] Pedrotti, M., Tarantino, A. (2019), "A conceptual constitutive model
    unifying slurried (saturated), compacted (unsaturated) and dry states",
    Géotechnique 69(3):217-233 (online 2018): the model's derivation.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

__all__ = [
    "PTVolumeParameters",
    "PTVolumePath",
    "EXAMPLE_KAOLIN",
    "PATH_COLUMNS",
    "water_saturated_effective_stress",
    "air_saturated_effective_stress",
    "ncl_void_ratio",
    "compression_void_ratio",
    "url_void_ratio_change",
    "ncl_void_ratio_change",
    "equivalent_preconsolidation_stress",
    "transition_void_ratio_change",
    "water_saturated_increment",
    "air_saturated_increment",
    "coupled_void_ratio",
    "path_problems",
    "simulate_volume_path",
]

from ..spec.constants import PATH_COLUMNS  # noqa: E402 (declared once in spec: the schema takes it)


# --------------------------------------------------------------------------------------------
# eq. 1-2: the two effective stresses
# --------------------------------------------------------------------------------------------
def water_saturated_effective_stress(sigma, u_w, S_R):
    r"""Effective stress of the water-saturated part, σ'_W = (σ − u_w) S_r [Pa].

    .. math:: \sigma'_W = (\sigma - u_w)\,S_r

    Parameters
    ----------
    sigma : array_like
        Total stress σ [Pa], compression positive (the mean stress when the
        lines are isotropic ones).
    u_w : array_like
        Pore-water pressure [Pa] (gauge; negative under suction).
    S_R : array_like
        Degree of saturation [-], in [0, 1].

    Returns
    -------
    ndarray
        σ'_W [Pa], broadcast shape of the inputs.

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 1, with u = u_w as in their section 5.1.
    """
    return (np.asarray(sigma, float) - np.asarray(u_w, float)) * np.asarray(S_R, float)


def air_saturated_effective_stress(sigma, u_a, S_R):
    r"""Effective stress of the air-saturated part, σ'_A = (σ − u_a)(1 − S_r) [Pa].

    .. math:: \sigma'_A = (\sigma - u_a)\,(1 - S_r)

    Parameters
    ----------
    sigma : array_like
        Total stress σ [Pa], compression positive.
    u_a : array_like
        Pore-air pressure [Pa] (gauge; 0 for atmospheric air).
    S_R : array_like
        Degree of saturation [-], in [0, 1].

    Returns
    -------
    ndarray
        σ'_A [Pa], broadcast shape of the inputs.

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 2, with u = u_a as in their section 5.1
    (section 4.1 typesets a single u).
    """
    return (np.asarray(sigma, float) - np.asarray(u_a, float)) * (1.0 - np.asarray(S_R, float))


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PTVolumeParameters:
    """Compressibility lines of the clay reconstituted from slurry (W) and compressed from dry powder (A).

    ncl: e = e_ncl − λ ln(σ'/σ_ref); url: slope κ through the yield point on the ncl.
    The slopes are natural-log slopes in the e-ln σ' plane (λ = C_c / ln 10).
    The lines and the path's σ must refer to the same stress measure (mean or
    vertical): Pedrotti & Tarantino converted oedometer lines to mean stress
    with K0 = 0.77.

    Attributes
    ----------
    lambda_W : float
        Slope of the ncl of the clay reconstituted from slurry [-], > 0 (λ_w of [1]).
    kappa_W : float
        Slope of its url [-], 0 < κ_W < λ_W (κ_w of [1]).
    e_ncl_W : float
        Void ratio on the slurry ncl at ``reference_stress`` [-], > 0.
    lambda_A : float
        Slope of the ncl of the clay compressed from dry powder [-], > 0 (λ_A of [1]).
    kappa_A : float
        Slope of its url [-], 0 < κ_A < λ_A (κ_A of [1]).
    e_ncl_A : float
        Void ratio on the dry-powder ncl at ``reference_stress`` [-], > 0.
    reference_stress : float
        σ_ref [Pa] where the intercepts are read, > 0; default 1 kPa (the
        paper's "specific volume at 1 kPa").

    Raises
    ------
    ValueError
        When a value lies outside its range (every problem in one message).

    References
    ----------
    [1] Pedrotti & Tarantino (submitted), section 4.1 (hypotheses 2-3), eq. 6-10.
    """

    lambda_W: float
    kappa_W: float
    e_ncl_W: float
    lambda_A: float
    kappa_A: float
    e_ncl_A: float
    reference_stress: float = 1.0e3

    def __post_init__(self):
        problems = []
        for f in fields(self):
            v = getattr(self, f.name)
            if not isinstance(v, (int, float, np.floating, np.integer)) or not np.isfinite(v):
                problems.append(f"{f.name} must be a finite number (got {v!r})")
        if problems:
            raise ValueError("; ".join(problems))
        for part in ("W", "A"):
            lam, kap, e0 = (getattr(self, f"{n}_{part}") for n in ("lambda", "kappa", "e_ncl"))
            if not lam > 0:
                problems.append(f"lambda_{part} must be > 0 (got {lam:g})")
            if not 0 < kap < lam:
                problems.append(f"kappa_{part} must lie in (0, lambda_{part}) = (0, {lam:g}) (got {kap:g})")
            if not e0 > 0:
                problems.append(f"e_ncl_{part} must be > 0 (got {e0:g})")
        if not self.reference_stress > 0:
            problems.append(f"reference_stress must be > 0 Pa (got {self.reference_stress:g})")
        if problems:
            raise ValueError("Pedrotti-Tarantino parameters: " + "; ".join(problems))

    def line(self, part: str) -> tuple[float, float, float]:
        """(λ, κ, e_ncl) of part ``"W"`` (slurry) or ``"A"`` (dry powder).

        Parameters
        ----------
        part : {"W", "A"}
            The clay part; another value raises ValueError.

        Returns
        -------
        tuple of float
            Compression index λ [-], swelling index κ [-] and void ratio of the ncl at the reference stress [-].
        """
        if part not in ("W", "A"):
            raise ValueError(f"part must be 'W' or 'A', not {part!r}")
        return getattr(self, f"lambda_{part}"), getattr(self, f"kappa_{part}"), getattr(self, f"e_ncl_{part}")

    def ncl(self, part: str, sigma_eff):
        """Void ratio on the ncl of part ``"W"`` or ``"A"`` at effective stress ``sigma_eff`` [Pa].

        Parameters
        ----------
        part : {"W", "A"}
            The clay part.
        sigma_eff : float or array_like
            Effective stress of the part [Pa], > 0.

        Returns
        -------
        numpy.ndarray
            Void ratio [-] ``e_ncl - λ ln(σ'/σ_ref)`` (``ncl_void_ratio``).

        References
        ----------
        Pedrotti & Tarantino (submitted), eq. 10 integrated: (Δe)_ncl = −λ Δ(ln σ').
        """
        lam, _, e0 = self.line(part)
        return ncl_void_ratio(sigma_eff, lam, e0, self.reference_stress)


#: Illustrative values for a kaolin, NOT from the paper (it prints none): slopes of the order
#: reported for Speswhite kaolin from slurry, and intercepts chosen so that a sample compacted
#: to about 340 kPa mean stress at S_r = 0.55 and 800 kPa suction has e close to 1.2, like the
#: samples of Sivakumar & Wheeler (2000) modelled in the paper. For sample runs and figures only.
EXAMPLE_KAOLIN = PTVolumeParameters(
    lambda_W=0.18, kappa_W=0.03, e_ncl_W=2.23, lambda_A=0.13, kappa_A=0.01, e_ncl_A=2.06
)


# --------------------------------------------------------------------------------------------
# the lines and the laws of the pore classes (eq. 6-10)
# --------------------------------------------------------------------------------------------
def ncl_void_ratio(sigma_eff, ncl_slope, e_ncl, reference_stress=1.0e3):
    """Void ratio on a normal-compression line, e = e_ncl − λ ln(σ'/σ_ref) [-].

    Parameters
    ----------
    sigma_eff : array_like
        Effective stress σ' [Pa], > 0.
    ncl_slope : float
        Slope λ of the ncl [-] (λ_W or λ_A).
    e_ncl : float
        Void ratio on the ncl at ``reference_stress`` [-].
    reference_stress : float
        σ_ref [Pa]; default 1 kPa.

    Returns
    -------
    ndarray
        e [-].

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 10 integrated: (Δe)_ncl = −λ Δ(ln σ').
    """
    return e_ncl - ncl_slope * np.log(np.asarray(sigma_eff, float) / reference_stress)


def compression_void_ratio(sigma_eff, yield_stress, ncl_slope, url_slope, e_ncl, reference_stress=1.0e3):
    r"""Void ratio of pores with past yield stress σ_y at effective stress σ' [-] (ncl/url model).

    .. math::

        \sigma_c = \max(\sigma_y, \sigma'), \qquad
        e = e_{ncl} - \lambda \ln(\sigma_c/\sigma_{ref}) - \kappa \ln(\sigma'/\sigma_c)

    On the ncl (σ' ≥ σ_y) this is eq. 10 of [1]; below it, the url of eq. 6-7.

    Parameters
    ----------
    sigma_eff : array_like
        Effective stress σ' [Pa], > 0.
    yield_stress : array_like
        Largest effective stress σ_y the pores have carried on their ncl [Pa], > 0.
    ncl_slope, url_slope : float
        Slopes λ of the ncl and κ of the url [-].
    e_ncl : float
        Void ratio on the ncl at ``reference_stress`` [-].
    reference_stress : float
        σ_ref [Pa].

    Returns
    -------
    ndarray
        e [-].

    References
    ----------
    [1] Pedrotti & Tarantino (submitted), eq. 6-7 (url) and 10 (ncl).
    """
    s = np.asarray(sigma_eff, float)
    sc = np.maximum(np.asarray(yield_stress, float), s)
    return e_ncl - ncl_slope * np.log(sc / reference_stress) - url_slope * np.log(s / sc)


def url_void_ratio_change(url_slope, sigma_before, sigma_after):
    """(Δe)_url = −κ Δ(ln σ') of pores that keep their fluid, below their yield stress [-].

    Parameters
    ----------
    url_slope : float
        url slope κ [-]: κ_A for air-saturated pores (eq. 6), κ_W for water-saturated ones (eq. 7).
    sigma_before, sigma_after : array_like
        Effective stress of the pores' part before and after the increment [Pa], > 0.

    Returns
    -------
    ndarray
        Δe [-] (positive on unloading).

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 6 (Δe^AA) and eq. 7 (Δe^WW).
    """
    return -url_slope * np.log(np.asarray(sigma_after, float) / np.asarray(sigma_before, float))


def ncl_void_ratio_change(ncl_slope, sigma_before, sigma_after):
    """(Δe)_ncl = −λ Δ(ln σ') of pores compressed on their ncl [-].

    Parameters
    ----------
    ncl_slope : float
        ncl slope λ [-] (λ_W for water-saturated pores).
    sigma_before, sigma_after : array_like
        Effective stress before and after [Pa], > 0, both on the ncl.

    Returns
    -------
    ndarray
        Δe [-].

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 10.
    """
    return -ncl_slope * np.log(np.asarray(sigma_after, float) / np.asarray(sigma_before, float))


def equivalent_preconsolidation_stress(void_ratio, ncl_slope, e_ncl, reference_stress=1.0e3):
    r"""σ* [Pa]: the effective stress at which an ncl passes through a given void ratio.

    .. math:: \sigma^* = \sigma_{ref}\,\exp\left((e_{ncl} - e)/\lambda\right)

    Pores that change fluid keep, at that instant, the void ratio e they had;
    σ* places them on the lines of their new fluid [1, Fig. 14-15].

    Parameters
    ----------
    void_ratio : array_like
        Void ratio of the pores just before they change fluid [-].
    ncl_slope, e_ncl : float
        Slope λ and intercept of the ncl of the new fluid [-].
    reference_stress : float
        σ_ref [Pa].

    Returns
    -------
    ndarray
        σ* [Pa] (σ*_A of eq. 8 on the dry-powder ncl, σ'*_W of eq. 9 on the slurry ncl).

    References
    ----------
    [1] Pedrotti & Tarantino (submitted), definitions before eq. 8 and eq. 9.
    """
    return reference_stress * np.exp((e_ncl - np.asarray(void_ratio, float)) / ncl_slope)


def transition_void_ratio_change(sigma_eff, sigma_star, ncl_slope, url_slope):
    r"""Δe of pores that change fluid: from σ* onto the lines of the new fluid [-].

    .. math::

        \Delta e = -\lambda \ln(\sigma'/\sigma^*) \;\; (\sigma' \ge \sigma^*), \qquad
        \Delta e = -\kappa \ln(\sigma'/\sigma^*) \;\; (\sigma' < \sigma^*)

    The first branch is eq. 9 (air to water, collapse onto the slurry ncl,
    λ_W); the second is eq. 8 (water to air, rebound on the dry-powder url,
    κ_A). capred applies whichever branch the stresses call for, to either
    transition (the paper shows each in one case only).

    Parameters
    ----------
    sigma_eff : array_like
        Effective stress of the new fluid's part after the increment [Pa], > 0.
    sigma_star : array_like
        Equivalent pre-consolidation stress [Pa] (:func:`equivalent_preconsolidation_stress`).
    ncl_slope, url_slope : float
        ncl slope λ and url slope κ of the new fluid [-].

    Returns
    -------
    ndarray
        Δe^AW (new fluid water) or Δe^WA (new fluid air) [-].

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 8 and eq. 9.
    """
    r = np.log(np.asarray(sigma_eff, float) / np.asarray(sigma_star, float))
    return -np.where(r >= 0.0, ncl_slope, url_slope) * r


# --------------------------------------------------------------------------------------------
# eq. 3-5 as printed (eq. 5 corrected)
# --------------------------------------------------------------------------------------------
def water_saturated_increment(de_WW, de_AW, S_R, dS_R):
    """Eq. 3 as printed: Δe^W = Δe^WW (1 − ΔS_r/S_r) + Δe^AW ΔS_r/S_r [-].

    Only wetting (ΔS_r > 0) brings air-saturated pores into the water-saturated
    part; for ΔS_r ≤ 0 the weight is 0 and Δe^W = Δe^WW. S_r is taken at the end
    of the increment, so the weight ΔS_r/S_r is the share of the water-saturated
    voids that were air-saturated before and lies in [0, 1].

    Parameters
    ----------
    de_WW : array_like
        Void-ratio change of the pores that stay water-saturated [-] (eq. 7 or 10).
    de_AW : array_like
        Void-ratio change of the pores going from air to water [-] (eq. 9).
    S_R : array_like
        Degree of saturation at the end of the increment [-], in (0, 1].
    dS_R : array_like
        Change of degree of saturation over the increment [-].

    Returns
    -------
    ndarray
        Δe^W [-].

    Notes
    -----
    A literal sum of void-ratio changes: it does not account for the AW pores
    entering with the void ratio of the air-saturated part.
    :func:`simulate_volume_path` keeps the books of voids instead (module notes, item 3).

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 3.
    """
    w = np.clip(np.asarray(dS_R, float), 0.0, None) / np.asarray(S_R, float)
    return np.asarray(de_WW, float) * (1.0 - w) + np.asarray(de_AW, float) * w


def air_saturated_increment(de_AA, de_WA, S_R, dS_R):
    """Eq. 4 as printed: Δe^A = Δe^AA (1 − (−ΔS_r)/(1 − S_r)) + Δe^WA (−ΔS_r)/(1 − S_r) [-].

    Only drying (ΔS_r < 0) brings water-saturated pores into the air-saturated
    part; for ΔS_r ≥ 0 the weight is 0. S_r is taken at the end of the increment.

    Parameters
    ----------
    de_AA : array_like
        Void-ratio change of the pores that stay air-saturated [-] (eq. 6).
    de_WA : array_like
        Void-ratio change of the pores going from water to air [-] (eq. 8).
    S_R : array_like
        Degree of saturation at the end of the increment [-], in [0, 1).
    dS_R : array_like
        Change of degree of saturation over the increment [-].

    Returns
    -------
    ndarray
        Δe^A [-].

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 4.
    """
    w = np.clip(-np.asarray(dS_R, float), 0.0, None) / (1.0 - np.asarray(S_R, float))
    return np.asarray(de_AA, float) * (1.0 - w) + np.asarray(de_WA, float) * w


def coupled_void_ratio(e_W, e_A, S_R):
    r"""Void ratio of the sample from those of its two parts, e = e^W e^A / (e^W (1 − S_r) + e^A S_r) [-].

    .. math:: \frac{1}{e} = \frac{S_r}{e^W} + \frac{1 - S_r}{e^A}

    With solids M_W, M_A (M_W + M_A = 1) in the water- and air-saturated parts,
    e = M_W e^W + M_A e^A and S_r = M_W e^W / e; eliminating M_W gives the
    expression above. It returns e^W at S_r = 1 and e^A at S_r = 0.

    Parameters
    ----------
    e_W : array_like
        Void ratio of the water-saturated part [-], > 0.
    e_A : array_like
        Void ratio of the air-saturated part [-], > 0.
    S_R : array_like
        Degree of saturation [-], in [0, 1].

    Returns
    -------
    ndarray
        e [-].

    Notes
    -----
    The submitted manuscript prints e = (e^W + e^A)/(e^W (1 − S_r) + e^A S_r),
    which gives 1 + e^W/e^A at S_r = 1 and 2 when e^W = e^A; capred reads the
    numerator as the product e^W e^A, the form that follows from the solids
    partition above.

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 5 (derived in Pedrotti & Tarantino, 2019, Géotechnique 69(3)).
    """
    e_W = np.asarray(e_W, float)
    e_A = np.asarray(e_A, float)
    S = np.asarray(S_R, float)
    return e_W * e_A / (e_W * (1.0 - S) + e_A * S)


# --------------------------------------------------------------------------------------------
# the path simulator
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PTVolumePath:
    """A simulated path of the Pedrotti & Tarantino volume-change model; arrays of one value per path point.

    Increments (``de_*``, ``w_*``, ``sigma_star_*``) belong to the step that ends
    at the point; they are NaN at the first point and where the class is absent.

    Attributes
    ----------
    sigma, u_w, u_a : ndarray
        The path: total stress, pore-water and pore-air pressure [Pa].
    S_R : ndarray
        Degree of saturation of the path [-].
    sigma_W, sigma_A : ndarray
        Effective stresses σ'_W = (σ − u_w) S_r and σ'_A = (σ − u_a)(1 − S_r) [Pa] (eq. 1-2).
    e : ndarray
        Void ratio of the sample [-] (eq. 5 holds: ``coupled_void_ratio(e_W, e_A, S_r) == e``).
    e_W, e_A : ndarray
        Void ratio of the water-saturated and air-saturated parts [-]; NaN where the part is empty.
    solid_fraction_W : ndarray
        Share of the solids in the water-saturated part [-] (= S_r e / e^W).
    ncl_fraction_W, ncl_fraction_A : ndarray
        Share of each part's solids lying on its ncl [-] (1: normally consolidated; 0: all on urls).
    de_WW, de_AA : ndarray
        Mean void-ratio change of the pores that kept their fluid [-] (eq. 6, 7, 10).
    de_AW, de_WA : ndarray
        Void-ratio change of the pores that changed fluid in the step, air to water (eq. 9) and water to
        air (eq. 8), from their part's void ratio to the new fluid's lines [-]; a solids-weighted mean
        over the sub-steps.
    w_AW, w_WA : ndarray
        Voids that entered the water-saturated (air-saturated) part in the step, at their entry void
        ratio, over that part's voids at the point [-]: the weights ΔS_r/S_r of eq. 3 and
        (−ΔS_r)/(1 − S_r) of eq. 4, to first order; 0 when no pore changed fluid.
    sigma_star_W, sigma_star_A : ndarray
        Equivalent pre-consolidation stresses σ'*_W (eq. 9) and σ*_A (eq. 8) of the step [Pa].
    loading_W, loading_A : ndarray of bool
        The step increased σ'_W (σ'_A); False at the first point.
    yielding_W, yielding_A : ndarray of bool
        Some pores of the part lie on its ncl at the end of the step (virgin compression or collapse).
    params : PTVolumeParameters
        The lines used.
    substeps : ndarray of int
        Sub-steps used for each step between two points (length n − 1).
    """

    sigma: np.ndarray
    u_w: np.ndarray
    u_a: np.ndarray
    S_R: np.ndarray
    sigma_W: np.ndarray
    sigma_A: np.ndarray
    e: np.ndarray
    e_W: np.ndarray
    e_A: np.ndarray
    solid_fraction_W: np.ndarray
    ncl_fraction_W: np.ndarray
    ncl_fraction_A: np.ndarray
    de_WW: np.ndarray
    de_AA: np.ndarray
    de_AW: np.ndarray
    de_WA: np.ndarray
    w_AW: np.ndarray
    w_WA: np.ndarray
    sigma_star_W: np.ndarray
    sigma_star_A: np.ndarray
    loading_W: np.ndarray
    loading_A: np.ndarray
    yielding_W: np.ndarray
    yielding_A: np.ndarray
    params: PTVolumeParameters = field(repr=False)
    substeps: np.ndarray = field(default_factory=lambda: np.zeros(0, int))

    #: unit (SI) of each array attribute; the output layer converts Pa to kPa
    UNITS = {
        "sigma": "Pa",
        "u_w": "Pa",
        "u_a": "Pa",
        "S_R": "-",
        "sigma_W": "Pa",
        "sigma_A": "Pa",
        "e": "-",
        "e_W": "-",
        "e_A": "-",
        "solid_fraction_W": "-",
        "ncl_fraction_W": "-",
        "ncl_fraction_A": "-",
        "de_WW": "-",
        "de_AA": "-",
        "de_AW": "-",
        "de_WA": "-",
        "w_AW": "-",
        "w_WA": "-",
        "sigma_star_W": "Pa",
        "sigma_star_A": "Pa",
        "loading_W": "bool",
        "loading_A": "bool",
        "yielding_W": "bool",
        "yielding_A": "bool",
    }


def path_problems(sigma, u_w, u_a, S_R) -> list[tuple[int, str, str]]:
    r"""Every reason a path cannot be simulated, as (point index, column, message); empty when fine.

    Checks: equal lengths (≥ 1 point), finite values, S_r in [0, 1], σ − u_w > 0
    where S_r > 0 and σ − u_a > 0 where S_r < 1, at the point or at a
    neighbouring one (each part's effective stress must be positive for ln σ'
    to exist, also on the sub-steps between points):

    .. math::

        \sigma'_W = (\sigma - u_w)\,S_r > 0 \;\text{where}\; S_r > 0, \qquad
        \sigma'_A = (\sigma - u_a)\,(1 - S_r) > 0 \;\text{where}\; S_r < 1

    Parameters
    ----------
    sigma, u_w, u_a : array_like
        Total stress, pore-water and pore-air pressure [Pa].
    S_R : array_like
        Degree of saturation [-].

    Returns
    -------
    list of (int, str, str)
        (0-based point index or -1 for the whole path, column name, message), for the
        pipeline to turn into file/line problems. The column names are those of a path
        file (``PATH_COLUMNS``: ``sigma``, ``u_w``, ``u_a``, ``S_r``).

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 1-2 (the two effective stresses) and eq. 6-10 (lines in
    e-ln σ', which need σ' > 0).
    """
    cols = {"sigma": sigma, "u_w": u_w, "u_a": u_a, "S_r": S_R}
    arrs = {k: np.atleast_1d(np.asarray(v, float)) for k, v in cols.items()}
    n = {k: a.size for k, a in arrs.items()}
    if len(set(n.values())) != 1:
        return [
            (
                -1,
                "",
                "sigma, u_w, u_a and S_r must have the same length (got "
                + ", ".join(f"{k}: {v}" for k, v in n.items())
                + ")",
            )
        ]
    if arrs["sigma"].size == 0:
        return [(-1, "", "the path is empty")]
    out: list[tuple[int, str, str]] = []
    for k, a in arrs.items():
        for i in np.flatnonzero(~np.isfinite(a)):
            out.append((int(i), k, f"{k} must be a finite number"))
    s, uw, ua, S = arrs["sigma"], arrs["u_w"], arrs["u_a"], arrs["S_r"]
    # a part that exists at a point or at a neighbouring point (sub-steps interpolate between them)
    wet, dry = S > 0, S < 1
    wet_near = wet | np.r_[wet[1:], False] | np.r_[False, wet[:-1]]
    dry_near = dry | np.r_[dry[1:], False] | np.r_[False, dry[:-1]]
    with np.errstate(invalid="ignore"):
        for i in np.flatnonzero((S < 0) | (S > 1)):
            out.append((int(i), "S_r", f"degree of saturation must lie between 0 and 1 (got {S[i]:.6g})"))
        for i in np.flatnonzero(wet_near & ~(s - uw > 0)):
            out.append(
                (
                    int(i),
                    "u_w",
                    "sigma - u_w must be > 0 where S_r > 0 (here or at a neighbouring "
                    "point): the water-saturated part "
                    f"needs a positive effective stress (got {(s[i] - uw[i]) * 1e-3:.6g} kPa)",
                )
            )
        for i in np.flatnonzero(dry_near & ~(s - ua > 0)):
            out.append(
                (
                    int(i),
                    "u_a",
                    "sigma - u_a must be > 0 where S_r < 1 (here or at a neighbouring "
                    "point): the air-saturated part "
                    f"needs a positive effective stress (got {(s[i] - ua[i]) * 1e-3:.6g} kPa)",
                )
            )
    return sorted(out)


class _Part:
    """The pore packets of one part: solid fraction m and ln of the yield stress, per packet."""

    def __init__(self, lam, kap, e_ncl, ln_ref):
        self.lam, self.kap, self.e_ncl, self.ln_ref = lam, kap, e_ncl, ln_ref
        self.m = np.zeros(0)
        self.lny = np.zeros(0)

    @property
    def mass(self) -> float:
        return float(self.m.sum())

    def void_ratios(self, ln_s, lny=None):
        lny = self.lny if lny is None else lny
        lnc = np.maximum(lny, ln_s)
        return self.e_ncl - self.lam * (lnc - self.ln_ref) - self.kap * (ln_s - lnc)

    def mean_void_ratio(self, ln_s) -> float:
        M = self.mass
        return float(self.m @ self.void_ratios(ln_s)) / M if M > 0 else float("nan")

    def add(self, m, lny):
        if m <= 0:
            return
        hit = np.flatnonzero(np.abs(self.lny - lny) <= 1e-12)
        if hit.size:
            self.m[hit[0]] += m
        else:
            self.m = np.append(self.m, m)
            self.lny = np.append(self.lny, lny)

    def scale(self, factor):
        self.m = self.m * factor
        keep = self.m > 1e-15
        self.m, self.lny = self.m[keep], self.lny[keep]

    def empty(self):
        self.m = np.zeros(0)
        self.lny = np.zeros(0)

    def ncl_fraction(self, ln_s) -> float:
        M = self.mass
        return float(self.m[self.lny <= ln_s + 1e-12].sum()) / M if M > 0 else float("nan")


def simulate_volume_path(
    sigma,
    u_w,
    u_a,
    S_R,
    *,
    params: PTVolumeParameters,
    initial_yield_W=None,
    initial_yield_A=None,
    substeps: int | None = None,
) -> PTVolumePath:
    r"""Void ratio along a path of total stress, pore pressures and S_r (Pedrotti & Tarantino, eq. 1-10).

    At each step the two effective stresses follow from eq. 1-2. The pores
    that keep their fluid move on the ncl/url of their part: slurry lines for
    the water-saturated pores (eq. 7, 10), dry-powder lines for the
    air-saturated ones (eq. 6). The pores that change fluid leave their part
    with its mean void ratio at the start of the step, get the equivalent
    pre-consolidation stress σ* of that void ratio on the new fluid's ncl and
    move to the new fluid's effective stress by eq. 8-9. Their amount (taken
    pro rata from every packet of the part they leave, hypothesis 4) is the one
    that makes the water-saturated share of the voids equal the path's S_r,
    solved in closed form. The void ratio of the sample then satisfies eq. 5,

    .. math:: e = \frac{e^W e^A}{e^W (1 - S_r) + e^A S_r}.

    For an A→W transfer of a fraction x of the air-saturated solids (V: void
    volumes per unit solids after the step at constant fluid content, e_T the
    void ratio of the transferred pores after eq. 9),

    .. math:: x = \frac{S_r V_A - (1 - S_r) V_W}{(1 - S_r) M_A e_T + S_r V_A},

    and symmetrically for W→A. See the module notes for the choices the paper
    leaves open (stresses, eq. 5, the combination eq. 3-4, the transition law).

    Parameters
    ----------
    sigma : array_like
        Total stress at each point of the path [Pa], compression positive (the
        stress measure of the lines: mean stress for isotropic lines).
    u_w : array_like
        Pore-water pressure [Pa] (gauge; −suction when u_a = 0).
    u_a : array_like
        Pore-air pressure [Pa] (gauge).
    S_R : array_like
        Degree of saturation [-], in [0, 1] (measured or prescribed; an input).
    params : PTVolumeParameters
        ncl/url slopes and intercepts of slurry (W) and dry-powder (A) clay.
    initial_yield_W, initial_yield_A : float, optional
        Largest σ'_W (σ'_A) the water-(air-)saturated part carried before the
        first point [Pa]; default (and floor): the first point's own stress,
        i.e. both parts start on their ncl (end of compaction).
    substeps : int, optional
        Each step between two points is split into this many equal sub-steps
        of (σ, u_w, u_a, S_r); results are reported at the points. The
        transfer uses the void ratio at the start of a (sub-)step, so the
        scheme is first order in the step size. Default (None): per step,
        enough sub-steps that |ΔS_r| ≤ 0.002 and |Δ ln σ'_W|, |Δ ln σ'_A| ≤ 0.02
        in each (at most 2000); 1 takes the path exactly as given (the paper's
        Fig. 14-15 draw single steps).

    Returns
    -------
    PTVolumePath
        Arrays with one value per point (see its attributes).

    Raises
    ------
    ValueError
        A path that cannot be simulated (:func:`path_problems`) or substeps < 1.

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 1-2, 3-5, 6-10, Fig. 13-17; the model of
    Pedrotti & Tarantino (2019), Géotechnique 69(3):217-233.
    """
    problems = path_problems(sigma, u_w, u_a, S_R)
    if problems:
        raise ValueError(
            "path: " + "; ".join((f"point {i + 1}, {c}: " if i >= 0 else "") + m for i, c, m in problems[:20])
        )
    if substeps is not None and not (isinstance(substeps, (int, np.integer)) and substeps >= 1):
        raise ValueError(f"substeps must be None or an integer >= 1 (got {substeps!r})")
    sigma, u_w, u_a, S_R = (np.atleast_1d(np.asarray(x, float)) for x in (sigma, u_w, u_a, S_R))
    n = sigma.size
    p = params
    ln_ref = np.log(p.reference_stress)
    W = _Part(*p.line("W"), ln_ref)
    A = _Part(*p.line("A"), ln_ref)

    sW_path = water_saturated_effective_stress(sigma, u_w, S_R)
    sA_path = air_saturated_effective_stress(sigma, u_a, S_R)

    def ln_or_nan(x):
        return np.log(x) if x > 0 else np.nan

    # --- initial state: both parts on (or below) their ncl; solids split by eq. 5
    S0 = S_R[0]
    lnW0, lnA0 = ln_or_nan(sW_path[0]), ln_or_nan(sA_path[0])
    if S0 > 0:
        yW = lnW0 if initial_yield_W is None else max(lnW0, np.log(initial_yield_W))
        eW0 = float(W.void_ratios(lnW0, np.array([yW]))[0])
    if S0 < 1:
        yA = lnA0 if initial_yield_A is None else max(lnA0, np.log(initial_yield_A))
        eA0 = float(A.void_ratios(lnA0, np.array([yA]))[0])
    if S0 >= 1:
        W.add(1.0, yW)
    elif S0 <= 0:
        A.add(1.0, yA)
    else:
        e0 = float(coupled_void_ratio(eW0, eA0, S0))
        mW = S0 * e0 / eW0
        W.add(mW, yW)
        A.add(1.0 - mW, yA)

    nan = np.full(n, np.nan)
    rec = {
        k: nan.copy()
        for k in (
            "e",
            "e_W",
            "e_A",
            "solid_fraction_W",
            "ncl_fraction_W",
            "ncl_fraction_A",
            "de_WW",
            "de_AA",
            "de_AW",
            "de_WA",
            "w_AW",
            "w_WA",
            "sigma_star_W",
            "sigma_star_A",
        )
    }
    flags = {k: np.zeros(n, bool) for k in ("loading_W", "loading_A", "yielding_W", "yielding_A")}

    def record(i, lnW, lnA):
        MW, MA = W.mass, A.mass
        VW = float(W.m @ W.void_ratios(lnW)) if MW > 0 else 0.0
        VA = float(A.m @ A.void_ratios(lnA)) if MA > 0 else 0.0
        rec["e"][i] = (VW + VA) / (MW + MA)
        rec["e_W"][i] = VW / MW if MW > 0 else np.nan
        rec["e_A"][i] = VA / MA if MA > 0 else np.nan
        rec["solid_fraction_W"][i] = MW / (MW + MA)
        rec["ncl_fraction_W"][i] = W.ncl_fraction(lnW) if MW > 0 else np.nan
        rec["ncl_fraction_A"][i] = A.ncl_fraction(lnA) if MA > 0 else np.nan
        flags["yielding_W"][i] = MW > 0 and rec["ncl_fraction_W"][i] > 0
        flags["yielding_A"][i] = MA > 0 and rec["ncl_fraction_A"][i] > 0

    record(0, lnW0, lnA0)
    n_sub = _substeps(sW_path, sA_path, S_R) if substeps is None else np.full(max(n - 1, 0), int(substeps))
    for k in range(1, n):
        nk = int(n_sub[k - 1])
        acc = {key: [] for key in ("de_WW", "de_AA", "sigma_star_W", "sigma_star_A")}
        moved = {"AW": [0.0, 0.0, 0.0], "WA": [0.0, 0.0, 0.0]}  # solids, solids * de, voids on entry
        for j in range(1, nk + 1):
            t0, t1 = (j - 1) / nk, j / nk
            s0, s1 = (sigma[k - 1] + t * (sigma[k] - sigma[k - 1]) for t in (t0, t1))
            uw0, uw1 = (u_w[k - 1] + t * (u_w[k] - u_w[k - 1]) for t in (t0, t1))
            ua0, ua1 = (u_a[k - 1] + t * (u_a[k] - u_a[k - 1]) for t in (t0, t1))
            S_a, S = (S_R[k - 1] + t * (S_R[k] - S_R[k - 1]) for t in (t0, t1))
            lnW_a = ln_or_nan(float(water_saturated_effective_stress(s0, uw0, S_a)))
            lnA_a = ln_or_nan(float(air_saturated_effective_stress(s0, ua0, S_a)))
            lnW = ln_or_nan(float(water_saturated_effective_stress(s1, uw1, S)))
            lnA = ln_or_nan(float(air_saturated_effective_stress(s1, ua1, S)))
            out = _step(W, A, lnW_a, lnA_a, lnW, lnA, S, p)
            for key in acc:
                if np.isfinite(out[key]):
                    acc[key].append(out[key])
            for c in ("AW", "WA"):
                if out[f"moved_{c}"] > 0:
                    moved[c][0] += out[f"moved_{c}"]
                    moved[c][1] += out[f"moved_{c}"] * out[f"de_{c}"]
                    moved[c][2] += out[f"moved_{c}"] * out[f"e_T_{c}"]
        for key, vals in acc.items():
            if vals:
                # pores that kept their fluid: their changes add up over the sub-steps;
                # sigma*: that of the last sub-step that had a transfer
                rec[key][k] = vals[-1] if key.startswith("sigma_star") else float(np.sum(vals))
        lnWk, lnAk = ln_or_nan(sW_path[k]), ln_or_nan(sA_path[k])
        VW = float(W.m @ W.void_ratios(lnWk)) if W.mass > 0 else 0.0
        VA = float(A.m @ A.void_ratios(lnAk)) if A.mass > 0 else 0.0
        for c, V in (("AW", VW), ("WA", VA)):
            m_c, mde_c, v_c = moved[c]
            # pores that changed fluid: solids-weighted mean change on entry (eq. 8-9);
            # weight of eq. 3-4: their entry voids over the receiving part's voids at the point
            rec[f"de_{c}"][k] = mde_c / m_c if m_c > 0 else np.nan
            rec[f"w_{c}"][k] = v_c / V if m_c > 0 and V > 0 else 0.0
        flags["loading_W"][k] = bool(sW_path[k] > sW_path[k - 1])
        flags["loading_A"][k] = bool(sA_path[k] > sA_path[k - 1])
        record(k, lnWk, lnAk)

    return PTVolumePath(
        sigma=sigma,
        u_w=u_w,
        u_a=u_a,
        S_R=S_R,
        sigma_W=sW_path,
        sigma_A=sA_path,
        **rec,
        **flags,
        params=p,
        substeps=n_sub,
    )


def _substeps(sW, sA, S, dS_max=0.002, dln_max=0.02, cap=2000) -> np.ndarray:
    """Sub-steps per path step: |ΔS_r| <= dS_max and |Δ ln σ'| <= dln_max of each existing part."""

    def dln(s):
        with np.errstate(divide="ignore", invalid="ignore"):
            d = np.abs(np.diff(np.log(np.where(s > 0, s, np.nan))))
        return np.where(np.isfinite(d), d, 0.0)

    need = np.maximum.reduce(
        [np.abs(np.diff(S)) / dS_max, dln(sW) / dln_max, dln(sA) / dln_max, np.ones(max(S.size - 1, 0))]
    )
    return np.minimum(np.ceil(need), cap).astype(int)


def _step(W: _Part, A: _Part, lnW_a, lnA_a, lnW, lnA, S, p: PTVolumeParameters) -> dict:
    """One (sub-)step: mechanics of the pores that keep their fluid, then the fluid transfer.

    ``lnW_a``/``lnA_a``: ln σ' at the start, ``lnW``/``lnA`` at the end (NaN where σ' = 0).
    Mutates W and A; returns the class changes of the step.
    """
    out = dict(
        de_WW=np.nan,
        de_AA=np.nan,
        de_AW=np.nan,
        de_WA=np.nan,
        moved_AW=0.0,
        moved_WA=0.0,
        e_T_AW=np.nan,
        e_T_WA=np.nan,
        sigma_star_W=np.nan,
        sigma_star_A=np.nan,
    )
    MW, MA = W.mass, A.mass
    eW_old = W.mean_void_ratio(lnW_a) if MW > 0 else np.nan
    eA_old = A.mean_void_ratio(lnA_a) if MA > 0 else np.nan
    lamW, kapW, eW_ncl = p.line("W")
    lamA, kapA, eA_ncl = p.line("A")

    # direction and amount of the transfer
    if S >= 1.0:
        x, y = (1.0 if MA > 0 else 0.0), 0.0
    elif S <= 0.0:
        x, y = 0.0, (1.0 if MW > 0 else 0.0)
    else:
        VWp = float(W.m @ W.void_ratios(lnW)) if MW > 0 else 0.0
        VAp = float(A.m @ A.void_ratios(lnA)) if MA > 0 else 0.0
        D = S * VAp - (1.0 - S) * VWp
        x = y = 0.0
        if D > 1e-14 * (VWp + VAp) and MA > 0:
            ln_star = np.log(p.reference_stress) + (eW_ncl - eA_old) / lamW
            eT = eA_old + float(transition_void_ratio_change(np.exp(lnW), np.exp(ln_star), lamW, kapW))
            x = min(1.0, D / ((1.0 - S) * MA * eT + S * VAp))
        elif D < -1e-14 * (VWp + VAp) and MW > 0:
            ln_star = np.log(p.reference_stress) + (eA_ncl - eW_old) / lamA
            eT = eW_old + float(transition_void_ratio_change(np.exp(lnA), np.exp(ln_star), lamA, kapA))
            y = min(1.0, -D / ((1.0 - S) * VWp + S * MW * eT))

    # pores that keep their fluid (eq. 6, 7, 10): packets update their yield stress
    if MW > 0 and y < 1.0:
        out["de_WW"] = W.mean_void_ratio(lnW) - eW_old
    if MA > 0 and x < 1.0:
        out["de_AA"] = A.mean_void_ratio(lnA) - eA_old

    if x > 0:  # air -> water (eq. 9)
        ln_star = np.log(p.reference_stress) + (eW_ncl - eA_old) / lamW
        moved = x * MA
        A.scale(1.0 - x) if x < 1.0 else A.empty()
        W.add(moved, max(ln_star, lnW))
        eT = float(W.void_ratios(lnW, np.array([max(ln_star, lnW)]))[0])
        out["de_AW"] = eT - eA_old
        out["sigma_star_W"] = float(np.exp(ln_star))
        out["moved_AW"], out["e_T_AW"] = moved, eT
    if y > 0:  # water -> air (eq. 8)
        ln_star = np.log(p.reference_stress) + (eA_ncl - eW_old) / lamA
        moved = y * MW
        W.scale(1.0 - y) if y < 1.0 else W.empty()
        A.add(moved, max(ln_star, lnA))
        eT = float(A.void_ratios(lnA, np.array([max(ln_star, lnA)]))[0])
        out["de_WA"] = eT - eW_old
        out["sigma_star_A"] = float(np.exp(ln_star))
        out["moved_WA"], out["e_T_WA"] = moved, eT
    # yield stresses of the packets that kept their fluid: raised to the current stress
    if W.mass > 0 and np.isfinite(lnW):
        W.lny = np.maximum(W.lny, lnW)
        _merge(W)
    if A.mass > 0 and np.isfinite(lnA):
        A.lny = np.maximum(A.lny, lnA)
        _merge(A)
    return out


def _merge(part: _Part):
    """Merge packets with the same yield stress (those on the ncl, mainly)."""
    if part.lny.size < 2:
        return
    order = np.argsort(part.lny)
    lny, m = part.lny[order], part.m[order]
    new = np.concatenate(([True], np.diff(lny) > 1e-12))
    idx = np.cumsum(new) - 1
    part.m = np.bincount(idx, weights=m)
    part.lny = lny[new]
