"""Skempton's B by the incremental scheme of Morvan et al. (2016), section 4 (eqs. 14-24).

Morvan, Vernay & Breul (2016) compute B against the degree of saturation with
two nested incremental loops:

1. a drying loop in ``S_R``: suction follows the Brooks-Corey curve (eq. 17)
   and the Bishop-type effective stress ``p' = p - u_a + s S_R`` (eq. 13)
   changes by ``dp' = dp - du_a + S_R (1 - lambda) ds`` (eq. 18);
2. at each ``S_R`` an undrained isotropic increment ``dp``: suction and ``chi``
   held constant (``du_a = du_w``), air compressed by Boyle's law (eqs. 19, 22),
   giving ``d eps_p = A11 dp / (1 + A11 P_a V_0 / V_a)`` (eq. 23) and
   ``du_a = du_w = (P_a V_0 / V_a) d eps_p`` (eq. 24).

Both loops need only ``A11 = d eps_p / dp'`` (at ``dq = ds = 0``), the first entry
of the constitutive matrix of eq. 14 (and ``A13``, its suction entry, in the
drying loop). This module runs the loops for any skeleton model: a plain
callable ``A11(p', e)`` (:class:`Compliance`) or a :class:`SkeletonCompliance`
carrying its state (the bounding surface's apex ``p_pi``, an ``A13`` slot).
The paper takes ``A11`` from the bounding-surface model of its reference [16]
(Morvan, Wong & Branque 2010, Int. J. Numer. Anal. Meth. Geomech. 34:1512-1537;
parameters lambda_0, Gamma, rho, M, A_ini of Table 3). Those equations are not
restated in the 2016 paper and could not be found in any source capred could
reach, so two compliances are shipped:

- :class:`ElasticCompliance`, eq. 5, ``A11 = kappa / ((1 + e) p')``, with which the
  scheme reproduces eq. 10 with the suction-equilibrium effective stress of
  section 3 (``skempton_b_suction`` in :mod:`capred.physics.calculators`);
- :class:`BoundingSurfaceCompliance`, a *Cam-clay bounding-surface
  reconstruction* (not the BDNS model of ref. [16]): for an isotropic state the
  radial image point is the apex, so Gamma, rho and M drop out and B depends on
  kappa, lambda_0, A_ini and the interpolation constant ``h`` only. At
  ``S_R = 0.9`` with Table 3 it gives 0.097 (elastic) and 0.783 (normally
  consolidated) with Boyle's law on the absolute air pressure; the paper's
  Fig. 6 values (0.4 and 0.04) come out only with the gauge air pressure in
  Boyle's law and ``p' = p0 + s S_R`` (0.386, and 0.040 at ``h = 336``, a value
  of ``h`` chosen to meet 0.04). With absolute pressure, the over-consolidated
  B cannot fall below the elastic bound 0.097, so the paper's 0.04 is out of
  reach there.

SI units throughout: pressures in Pa (``pa0`` absolute, ``p0`` and ``u0``
gauge), compliances in 1/Pa.

References
----------
[1] M. Morvan, M. Vernay, P. Breul (2016), "Study of the variation of B with
    Sr", E-UNSAT 2016, E3S Web of Conferences; eqs. 5, 8, 13, 14-24, Table 3.
[2] M. Morvan, H. Wong, D. Branque (2010), "An unsaturated soil model with
    minimal number of parameters based on bounding surface plasticity",
    Int. J. Numer. Anal. Meth. Geomech. 34:1512-1537 (reference [16] of [1];
    its equations are not implemented here).
[3] R. H. Brooks, A. T. Corey (1964), Hydraulic properties of porous media,
    Hydrology Paper 3, Colorado State University.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from .retention import bc_suction

__all__ = [
    "AIR_PRESSURE_CONVENTIONS",
    "BOUNDING_SURFACE_NAME",
    "BoundingSurfaceCompliance",
    "SkeletonCompliance",
    "SkeletonState",
    "Compliance",
    "ElasticCompliance",
    "IncrementalBPath",
    "air_volume_ratio",
    "compliance_from_skempton_b",
    "elastic_compliance",
    "skempton_b_from_compliance",
    "skempton_b_incremental",
    "skempton_b_incremental_path",
]


class Compliance(Protocol):
    """Isotropic compliance ``A11 = d eps_p / dp'`` [1/Pa] of eq. 14 of [1].

    Called with the current mean effective stress ``p_eff`` [Pa] (eq. 13) and
    void ratio ``void_ratio`` [-]; returns ``A11`` [1/Pa], > 0. A plain callable
    of this form is an elastic-like skeleton (no surface, no hardening); a
    model with a bounding surface is a :class:`SkeletonCompliance`, which
    carries the state it needs (the apex ``p_pi``, an ``A13`` slot).
    """

    def __call__(self, p_eff: float, void_ratio: float) -> float:
        """Isotropic compliance ``A11`` [1/Pa] at a state, the :class:`Compliance` call of eq. 14 of [1].

        Parameters
        ----------
        p_eff : float
            Mean effective stress p' [Pa] (eq. 13).
        void_ratio : float
            Void ratio e [-].

        Returns
        -------
        float
            ``A11 = d eps_p / dp'`` [1/Pa], > 0.
        """
        ...


@dataclass
class SkeletonState:
    """State of the skeleton carried by the loops of [1], section 4.

    Attributes
    ----------
    p_eff : float
        Mean effective stress ``p'`` [Pa] (eq. 13).
    void_ratio : float
        Void ratio ``e`` [-].
    p_pi : float
        Apex of the bounding surface on the isotropic axis [Pa]; ``inf`` for a
        skeleton without a surface.
    """

    p_eff: float
    void_ratio: float
    p_pi: float = math.inf


class SkeletonCompliance:
    """Base of a skeleton model with state: ``A11`` (total and plastic part), ``A13`` and apex hardening.

    The loops of [1] call ``a11(state, loading)``, ``a11_plastic(state, loading)``,
    ``a13(state)`` (``d eps_p / ds`` at constant ``p'``, [1/Pa]) and
    ``harden(state, deps_plastic)``. This base is elastic-free and plastic-free:
    subclasses override what they need. Calling an instance with
    ``(p_eff, void_ratio)`` gives ``A11`` of a state on its own surface (the
    :class:`Compliance` form).

    References
    ----------
    [1] Morvan et al. (2016), eq. 14 (the matrix whose entries A11 and A13 these are).
    """

    def initial_apex(self, p_eff0: float) -> float:
        """Apex ``p_pi`` [Pa] at the start of the drying path, where ``p' = p_eff0`` [Pa].

        Parameters
        ----------
        p_eff0 : float
            Mean effective stress at the start [Pa].

        Returns
        -------
        float
            ``inf`` here (no yield surface); subclasses with a surface override it.
        """
        return math.inf

    def a11(self, state: SkeletonState, loading: bool = True) -> float:
        """Total ``A11 = d eps_p / dp'`` [1/Pa] at ``state``; ``loading``: ``dp' > 0``.

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa], void ratio [-] and apex ``p_pi`` [Pa].
        loading : bool, optional
            True when ``dp' > 0`` (default).

        Returns
        -------
        float
            ``A11`` [1/Pa] (eq. 14 of Morvan et al. 2016).
        """
        raise NotImplementedError

    def a11_plastic(self, state: SkeletonState, loading: bool = True) -> float:
        """Plastic part of ``A11`` [1/Pa]; 0 for an elastic skeleton.

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa], void ratio [-] and apex ``p_pi`` [Pa].
        loading : bool, optional
            True when ``dp' > 0`` (default).

        Returns
        -------
        float
            Plastic compliance [1/Pa].
        """
        return 0.0

    def a13(self, state: SkeletonState) -> float:
        """``A13 = d eps_p / ds`` at constant ``p'`` [1/Pa]; 0 (suction acts through ``p'`` alone, eq. 13).

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa], void ratio [-] and apex ``p_pi`` [Pa].

        Returns
        -------
        float
            ``A13`` [1/Pa].
        """
        return 0.0

    def harden(self, state: SkeletonState, deps_plastic: float) -> float:
        """Apex after a plastic volumetric strain ``deps_plastic`` [-] (compression positive) [Pa].

        Parameters
        ----------
        state : SkeletonState
            State before the step.
        deps_plastic : float
            Plastic volumetric strain increment [-], compression positive.

        Returns
        -------
        float
            The apex ``p_pi`` [Pa]; unchanged here (no hardening).
        """
        return state.p_pi

    def __call__(self, p_eff: float, void_ratio: float) -> float:
        """Isotropic compliance ``A11`` [1/Pa] at a state, the :class:`Compliance` call of eq. 14 of [1].

        Parameters
        ----------
        p_eff : float
            Mean effective stress p' [Pa] (eq. 13).
        void_ratio : float
            Void ratio e [-].

        Returns
        -------
        float
            ``A11 = d eps_p / dp'`` [1/Pa], > 0.

        Notes
        -----
        The skeleton's own apex at ``p_eff`` (``initial_apex``) is taken as the state, with the loading branch.
        """
        return self.a11(SkeletonState(p_eff, void_ratio, self.initial_apex(p_eff)))


class _CallableCompliance(SkeletonCompliance):
    """A plain ``A11(p_eff, void_ratio)`` callable as a :class:`SkeletonCompliance` (no surface)."""

    def __init__(self, fn):
        self.fn = fn

    def a11(self, state, loading=True):
        return float(self.fn(state.p_eff, state.void_ratio))


def _as_model(compliance) -> SkeletonCompliance:
    return compliance if isinstance(compliance, SkeletonCompliance) else _CallableCompliance(compliance)


def air_volume_ratio(S_R, void_ratio):
    """Air volume over total volume, ``V_a / V_0`` [-] (eq. 8 of [1]).

    Parameters
    ----------
    S_R : array_like
        Degree of saturation [-], in [0, 1].
    void_ratio : array_like
        Void ratio ``e`` [-].

    Returns
    -------
    ndarray
        ``V_a / V_0 = e (1 - S_R) / (1 + e)`` [-].

    References
    ----------
    [1] Morvan et al. (2016), eq. 8.
    """
    e = np.asarray(void_ratio, float)
    return e * (1.0 - np.asarray(S_R, float)) / (1.0 + e)


def elastic_compliance(p_eff, void_ratio, kappa_elastic):
    """Elastic isotropic compliance ``A11 = kappa_elastic / ((1 + e) p')`` [1/Pa] (eq. 5 of [1]).

    Parameters
    ----------
    p_eff : array_like
        Mean effective stress ``p'`` [Pa], > 0 (eq. 13 of [1]).
    void_ratio : array_like
        Void ratio ``e`` [-].
    kappa_elastic : float
        Slope of the elastic line in the ``e - ln p'`` plane [-].

    Returns
    -------
    ndarray
        ``d eps_p / dp'`` [1/Pa].

    References
    ----------
    [1] Morvan et al. (2016), eq. 5.
    """
    return kappa_elastic / ((1.0 + np.asarray(void_ratio, float)) * np.asarray(p_eff, float))


@dataclass(frozen=True)
class ElasticCompliance(SkeletonCompliance):
    """:class:`Compliance` of eq. 5 of [1]: ``A11 = kappa_elastic / ((1 + e) p')``.

    Attributes
    ----------
    kappa_elastic : float
        Slope of the elastic line in ``e - ln p'`` [-].
    """

    kappa_elastic: float

    def a11(self, state: SkeletonState, loading: bool = True) -> float:
        """Elastic ``A11 = kappa_elastic / ((1 + e) p')`` [1/Pa] at ``state`` (eq. 5 of Morvan et al. 2016).

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa] and void ratio [-].
        loading : bool, optional
            Ignored: the same on loading and unloading.

        Returns
        -------
        float
            ``A11`` [1/Pa].
        """
        return float(elastic_compliance(state.p_eff, state.void_ratio, self.kappa_elastic))

    def __call__(self, p_eff: float, void_ratio: float) -> float:
        """Isotropic compliance ``A11`` [1/Pa] at a state, the :class:`Compliance` call of eq. 14 of [1].

        Parameters
        ----------
        p_eff : float
            Mean effective stress p' [Pa] (eq. 13).
        void_ratio : float
            Void ratio e [-].

        Returns
        -------
        float
            ``A11 = d eps_p / dp'`` [1/Pa], > 0.

        Notes
        -----
        The elastic ``kappa_elastic / ((1 + e) p')`` of eq. 5 of Morvan et al. (2016).
        """
        return float(elastic_compliance(p_eff, void_ratio, self.kappa_elastic))


#: How the bounding-surface compliance is named in every output: a reconstruction, not the paper's model.
BOUNDING_SURFACE_NAME = (
    "Cam-clay bounding-surface reconstruction (not the BDNS model of ref. [16], whose equations are not "
    "published in a source we could reach)"
)


@dataclass(frozen=True)
class BoundingSurfaceCompliance(SkeletonCompliance):
    r"""Cam-clay bounding-surface reconstruction of the isotropic compliance of [1], section 4 (not BDNS [2]).

    For an isotropic state (``q = 0``) with the image point found by radial
    projection from the origin, the image is the apex ``p_pi`` of the bounding
    surface, so the surface's shape (Gamma, rho, M of Table 3) drops out and

    .. math::

        A_{11} = rac{\kappa}{(1+e) p'}
               + rac{\lambda_0 - \kappa}{(1+e) p'}\,
                 rac{1}{1 + h\, \delta / (p_\pi - \delta)},
        \qquad \delta = p_\pi - p' \ge 0,

    on loading (``dp' > 0``; elastic on unloading), with Cam-clay apex
    hardening ``dp_pi / p_pi = (1 + e) d eps_p^p / (lambda_0 - kappa)`` and
    ``p_pi0 = p'_0 + A_ini``. ``A_ini = 0`` is a normally consolidated sample
    (``delta = 0``: the full Cam-clay compliance ``lambda_0 / ((1+e) p')``);
    ``h -> inf`` makes an over-consolidated sample elastic (eq. 5). This is the
    reconstruction of capred's SPEC (section 6b), *not* the BDNS model of
    Morvan, Wong & Branque (2010), whose equations capred does not have.

    Attributes
    ----------
    kappa_elastic : float
        Slope of the elastic line in ``e - ln p'`` [-] (Table 3: 0.006).
    lambda0 : float
        Slope of the normal compression line (plastic isotropic modulus) [-] (Table 3: 0.2).
    a_ini : float
        Initial distance of the apex from the state, ``p_pi0 - p'_0`` [Pa] (Table 3: 0 or 10 kPa).
    interpolation_h : float or None
        Dafalias-type interpolation constant ``h`` [-], > 0; needed when ``a_ini > 0``. ``None``
        (allowed for ``a_ini = 0`` only): the sharp Cam-clay surface, elastic inside it (``h -> inf``).

    References
    ----------
    [1] Morvan et al. (2016), section 4, eq. 14, Table 3.
    [2] Morvan, Wong & Branque (2010), IJNAMG 34:1512-1537 (BDNS; not implemented).
    [4] Y. F. Dafalias, L. R. Herrmann (1982), "Bounding surface formulation of soil plasticity",
        in Soil Mechanics - Transient and Cyclic Loads, Wiley, 253-282 (the interpolation rule).
    [5] K. H. Roscoe, J. B. Burland (1968), "On the generalized stress-strain behaviour of wet clay",
        Engineering Plasticity, Cambridge University Press, 535-609 (Cam-clay hardening).
    """

    kappa_elastic: float = 0.006
    lambda0: float = 0.2
    a_ini: float = 0.0
    interpolation_h: float | None = None

    def __post_init__(self) -> None:
        if not 0.0 < self.kappa_elastic < self.lambda0:
            raise ValueError(f"need 0 < kappa ({self.kappa_elastic}) < lambda0 ({self.lambda0})")
        if not (self.a_ini >= 0.0 and math.isfinite(self.a_ini)):
            raise ValueError(f"A_ini must be >= 0 (got {self.a_ini / 1e3:g} kPa)")
        if self.a_ini > 0 and self.interpolation_h is None:
            raise ValueError(
                "--interpolation-h is required with --a-ini > 0: the Dafalias-type constant h of the "
                "reconstruction has no published value (h = 336 meets the paper's Fig. 6 value 0.04 under the "
                "gauge convention)"
            )
        if self.interpolation_h is not None and not self.interpolation_h > 0:
            raise ValueError(f"--interpolation-h must be > 0 (got {self.interpolation_h})")

    def initial_apex(self, p_eff0: float) -> float:
        """Apex ``p_pi0 = p'_0 + A_ini`` [Pa] of the bounding surface at the start of the drying path.

        Parameters
        ----------
        p_eff0 : float
            Mean effective stress at the start [Pa].

        Returns
        -------
        float
            ``p_pi0`` [Pa].
        """
        return p_eff0 + self.a_ini

    def a11_plastic(self, state: SkeletonState, loading: bool = True) -> float:
        """Plastic part of ``A11`` [1/Pa]: ``(lambda0 - kappa) / ((1 + e) p') / (1 + h delta / p')``, ``delta = p_pi - p'``.

        Zero on unloading and, without ``h``, inside the surface (the sharp Cam-clay surface).

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa], void ratio [-] and apex ``p_pi`` [Pa].
        loading : bool, optional
            True when ``dp' > 0`` (default).

        Returns
        -------
        float
            Plastic compliance [1/Pa].
        """
        if not loading:
            return 0.0
        p = state.p_eff
        delta = max(state.p_pi - p, 0.0)
        if delta <= 1e-9 * state.p_pi:  # on the surface (rounding of the hardening step)
            ratio = 0.0
        elif self.interpolation_h is None:  # no interpolation: the sharp Cam-clay surface, elastic inside
            return 0.0
        else:
            ratio = self.interpolation_h * delta / p  # h delta / (p_pi - delta), p_pi - delta = p'
        return (self.lambda0 - self.kappa_elastic) / ((1.0 + state.void_ratio) * p) / (1.0 + ratio)

    def a11(self, state: SkeletonState, loading: bool = True) -> float:
        """Total ``A11`` [1/Pa]: elastic ``kappa / ((1 + e) p')`` plus :meth:`a11_plastic`.

        Parameters
        ----------
        state : SkeletonState
            Current ``p'`` [Pa], void ratio [-] and apex ``p_pi`` [Pa].
        loading : bool, optional
            True when ``dp' > 0`` (default).

        Returns
        -------
        float
            ``A11`` [1/Pa].
        """
        elastic = self.kappa_elastic / ((1.0 + state.void_ratio) * state.p_eff)
        return elastic + self.a11_plastic(state, loading)

    def harden(self, state: SkeletonState, deps_plastic: float) -> float:
        """Apex after a plastic step: ``p_pi (1 + (1 + e) deps_plastic / (lambda0 - kappa))`` [Pa] (explicit Cam-clay hardening).

        Parameters
        ----------
        state : SkeletonState
            State before the step.
        deps_plastic : float
            Plastic volumetric strain increment [-], compression positive.

        Returns
        -------
        float
            The new apex ``p_pi`` [Pa].
        """
        # explicit step of dp_pi / p_pi = (1 + e) d eps^p / (lambda0 - kappa): on the surface it moves the apex by
        # exactly the step's dp', so a normally consolidated state stays on its surface up to rounding
        return state.p_pi * (1.0 + (1.0 + state.void_ratio) * deps_plastic / (self.lambda0 - self.kappa_elastic))


def skempton_b_from_compliance(A11, S_R, void_ratio, pa):
    r"""Skempton's B from the isotropic compliance, undrained with Boyle's law (eqs. 22-24 of [1]).

    .. math::

        B = \frac{du_w}{dp} = \frac{X A_{11}}{1 + X A_{11}},
        \qquad X = \frac{P_a V_0}{V_a} = \frac{P_a (1 + e)}{e (1 - S_R)}

    written as ``A11 P_a (1+e) / (e (1-S_R) + A11 P_a (1+e))`` so that
    ``S_R = 1`` gives ``B = 1`` without a division by zero. Suction constant
    during the increment (``du_a = du_w``), water and grains incompressible.

    Parameters
    ----------
    A11 : array_like
        Isotropic compliance ``d eps_p / dp'`` [1/Pa], >= 0.
    S_R : array_like
        Degree of saturation [-].
    void_ratio : array_like
        Void ratio ``e`` [-].
    pa : array_like
        Absolute air pressure ``P_a`` [Pa].

    Returns
    -------
    ndarray
        B [-], same broadcast shape as the inputs.

    Notes
    -----
    With the elastic ``A11`` of eq. 5 this is eq. 10 of [1].

    References
    ----------
    [1] Morvan et al. (2016), eqs. 22-24 (and eq. 8 for ``V_a``).
    """
    e = np.asarray(void_ratio, float)
    k = np.asarray(A11, float) * np.asarray(pa, float) * (1.0 + e)
    return k / (e * (1.0 - np.asarray(S_R, float)) + k)


def compliance_from_skempton_b(B, S_R, void_ratio, pa):
    """Inverse of eq. 24 of [1]: the compliance ``A11`` [1/Pa] a measured or published B implies.

    ``A11 = B e (1 - S_R) / ((1 - B) P_a (1 + e))``, for ``0 <= B < 1``.

    Parameters
    ----------
    B : array_like
        Skempton's B [-], in [0, 1).
    S_R : array_like
        Degree of saturation [-].
    void_ratio : array_like
        Void ratio ``e`` [-].
    pa : array_like
        Absolute air pressure ``P_a`` [Pa].

    Returns
    -------
    ndarray
        ``A11`` [1/Pa].

    References
    ----------
    [1] Morvan et al. (2016), eq. 24.
    """
    B = np.asarray(B, float)
    e = np.asarray(void_ratio, float)
    return B * e * (1.0 - np.asarray(S_R, float)) / ((1.0 - B) * np.asarray(pa, float) * (1.0 + e))


@dataclass(frozen=True)
class IncrementalBPath:
    """States of the drying loop of [1] and the B found at each (section 4, eqs. 14-24).

    Every attribute is a 1-D array over the points of the path, ordered by
    decreasing ``S_R`` (the drying direction, from ``S_R = 1``).

    Attributes
    ----------
    S_R : ndarray
        Degree of saturation [-].
    suction : ndarray
        Brooks-Corey suction ``s = s_e S_R^(-1/lambda)`` [Pa] (eq. 17).
    p_eff : ndarray
        Mean effective stress ``p'`` [Pa], integrated from eq. 18 (equal to
        eq. 13, ``p0 - u0 + s S_R``, up to the integration error).
    void_ratio : ndarray
        Void ratio ``e`` [-] after the drying strains ``d eps_p = A11 dp'``.
    A11 : ndarray
        Compliance at the state [1/Pa].
    B : ndarray
        Skempton's B of the undrained increment ``dp`` applied at the state [-]
        (secant ``du_w / dp``, eqs. 22-24).
    p_pi : ndarray
        Apex of the bounding surface [Pa] (``inf`` for a skeleton without one).
    """

    S_R: np.ndarray
    suction: np.ndarray
    p_eff: np.ndarray
    void_ratio: np.ndarray
    A11: np.ndarray
    B: np.ndarray
    #: apex of the bounding surface [Pa] (``inf`` without a surface)
    p_pi: np.ndarray | None = None


def _undrained_b(model: SkeletonCompliance, state: SkeletonState, S_R, pa0, dp, n_dp):
    """Second loop of [1]: ``n_dp`` sub-increments of ``dp / n_dp`` on a copy of ``state``; the secant B.

    Per sub-increment (eqs. 22-23): ``d eps = A11 dp V_a / (V_a + A11 P_a V)``,
    ``du_a = P_a V d eps / V_a`` (written so that ``V_a = 0`` gives
    ``d eps = 0, du_a = dp``); then Boyle's law updates ``P_a`` and ``V_a``, the
    skeleton volume ``V`` shrinks by ``V d eps`` (water and grains
    incompressible, eq. 19), ``p'`` changes by ``dp - du_a`` (eq. 18 at
    ``ds = 0``: suction and chi constant during the increment) and the apex
    hardens with the plastic part ``A11^p (dp - du_a)``.
    """
    V = 1.0 + state.void_ratio  # per unit volume of grains
    Va = state.void_ratio * (1.0 - S_R)
    pa = pa0
    p_eff, p_pi = state.p_eff, state.p_pi
    h = dp / n_dp
    for _ in range(n_dp):
        st = SkeletonState(p_eff, V - 1.0, p_pi)
        a11 = model.a11(st, True)
        den = Va + a11 * pa * V
        deps = a11 * h * Va / den
        du = a11 * pa * V * h / den
        p_pi = max(model.harden(st, model.a11_plastic(st, True) * (h - du)), p_eff + h - du)
        pa += du
        Va -= V * deps
        V -= V * deps
        p_eff += h - du
    return (pa - pa0) / dp


AIR_PRESSURE_CONVENTIONS = ("absolute", "gauge")


def skempton_b_incremental_path(
    S_R_min=0.5,
    *,
    compliance: Compliance | Callable[[float, float], float] | None = None,
    kappa_elastic=0.006,
    p0=100e3,
    u0=30e3,
    e0=0.8,
    pa0=130e3,
    air_entry=20e3,
    bc_lambda=0.8,
    dp=1e3,
    n_dp=10,
    S_R_step=1e-3,
    at=None,
    air_pressure="absolute",
) -> IncrementalBPath:
    r"""The two incremental loops of Morvan et al. (2016), section 4: B along a drying path.

    Loop 1 dries the sample from ``S_R = 1`` (suction ``s_e``, ``p' = p0 - u0 + s_e``)
    down to ``S_R_min`` in steps of ``S_R_step``, at constant total stress and
    air pressure (``dp = du_a = 0``), with

    .. math::

        s = s_e S_R^{-1/\lambda}, \qquad dp' = S_R (1 - \lambda)\, ds,
        \qquad d\varepsilon_p = A_{11}\, dp', \qquad de = -(1 + e)\, d\varepsilon_p

    (eqs. 17-18; ``ds`` exact along the Brooks-Corey curve, ``S_R`` and ``p'`` at the
    mid-step; the drying strains are ``A11 dp' + A13 ds``, with ``A13 = 0`` for both
    shipped models; the apex hardens with the plastic part of ``A11 dp'``). Loop 2, at each recorded state, applies the undrained
    isotropic increment ``dp`` in ``n_dp`` sub-increments (eqs. 19-24) on a copy
    of the state: the increment is a B check, not part of the drying history.

    Parameters
    ----------
    S_R_min : float
        Lowest degree of saturation of the path [-], in (0, 1].
    compliance : Compliance, optional
        ``A11(p_eff [Pa], void_ratio [-]) -> [1/Pa]``, or a :class:`SkeletonCompliance`
        with state (:class:`BoundingSurfaceCompliance`). Default: the elastic
        compliance of eq. 5 with ``kappa_elastic`` (:class:`ElasticCompliance`).
    kappa_elastic : float
        Slope of the elastic line in ``e - ln p'`` [-] (Table 3: 0.006).
    p0 : float
        Mean total stress [Pa] (Table 3: 100 kPa).
    u0 : float
        Initial (gauge) air pressure [Pa]; 30 kPa as in Table 1, so that
        ``pa0 = 130 kPa`` absolute with a 100 kPa atmosphere.
    e0 : float
        Void ratio at ``S_R = 1`` [-] (Table 3: 0.8).
    pa0 : float
        Absolute air pressure [Pa] (Table 3: 130 kPa).
    air_entry : float
        Brooks-Corey air-entry suction ``s_e`` [Pa] (Table 3: 20 kPa).
    bc_lambda : float
        Brooks-Corey exponent [-], alpha in the paper (Table 3: 0.8).
    dp : float
        Undrained isotropic total-stress increment of loop 2 [Pa], > 0. The
        paper does not give its value; B is the secant ``du_w / dp`` and tends
        to eq. 24 as ``dp -> 0`` (1 kPa changes B by < 1 % at Table 3 values).
    n_dp : int
        Sub-increments of ``dp``.
    S_R_step : float
        Step of ``S_R`` in loop 1 [-].
    at : array_like, optional
        Degrees of saturation at which to record the state (each in
        ``[S_R_min, 1]``); default: every step of loop 1.
    air_pressure : {"absolute", "gauge"}
        ``absolute`` (default): Boyle's law on the absolute air pressure ``pa0``
        and ``p' = p0 - u0 + s S_R`` (eq. 13). ``gauge``: the gauge air pressure
        ``u0`` in Boyle's law and ``p' = p0 + s S_R``, the convention under
        which the paper's Fig. 6 values (0.4 and 0.04 at ``S_R = 0.9``) come out
        with :class:`BoundingSurfaceCompliance`; Boyle's law needs the absolute
        pressure, so this is for comparison with the paper only.

    Returns
    -------
    IncrementalBPath
        The states and B, ordered by decreasing ``S_R``.

    Raises
    ------
    ValueError
        ``S_R_min`` outside (0, 1], a recording point outside ``[S_R_min, 1]``,
        or a non-positive ``dp``, ``n_dp`` or ``S_R_step``.

    References
    ----------
    [1] Morvan et al. (2016), section 4, eqs. 13, 17-24; Table 3 (defaults).
    [3] Brooks & Corey (1964), retention curve ``S_R = (s_e / s)^lambda``.
    """
    model = _as_model(ElasticCompliance(kappa_elastic) if compliance is None else compliance)
    if air_pressure not in AIR_PRESSURE_CONVENTIONS:
        raise ValueError(f"air_pressure must be absolute or gauge (got '{air_pressure}')")
    if air_pressure == "gauge":
        pa0, u0 = u0, 0.0
    if not pa0 > 0:
        raise ValueError(f"the air pressure in Boyle's law must be > 0 (got {pa0 / 1e3:g} kPa)")
    if not 0.0 < S_R_min <= 1.0:
        raise ValueError(f"S_R_min must be in (0, 1], got {S_R_min}")
    if dp <= 0 or n_dp < 1 or S_R_step <= 0:
        raise ValueError("dp, n_dp and S_R_step must be positive")
    n = max(1, int(np.ceil((1.0 - S_R_min) / S_R_step - 1e-9)))
    grid = np.linspace(1.0, S_R_min, n + 1)
    if at is None:
        stops = grid
    else:
        stops = np.unique(np.asarray(at, float).ravel())[::-1]
        if stops.size and (stops[0] > 1.0 or stops[-1] < S_R_min):
            raise ValueError(f"recording points must lie in [{S_R_min}, 1]")
        near = np.abs(grid[:, None] - stops[None, :]).min(axis=1) < 1e-9  # grid points a stop replaces
        grid = np.unique(np.concatenate([grid[~near], stops]))[::-1]

    out = {k: [] for k in ("S_R", "suction", "p_eff", "void_ratio", "A11", "B", "p_pi")}
    p_eff = p0 - u0 + air_entry  # eq. 13 at S_R = 1, s = s_e
    if not p_eff > 0:
        raise ValueError(f"the initial mean effective stress p0 - u0 + s_e must be > 0 (got {p_eff / 1e3:g} kPa)")
    state = SkeletonState(p_eff, e0, model.initial_apex(p_eff))
    j = 0  # next recording point
    for i, sr in enumerate(grid):
        if i > 0:
            s_prev = bc_suction(grid[i - 1], air_entry, bc_lambda)
            s_now = bc_suction(sr, air_entry, bc_lambda)
            ds = s_now - s_prev
            dpe = 0.5 * (grid[i - 1] + sr) * (1.0 - bc_lambda) * ds  # eq. 18
            mid = SkeletonState(state.p_eff + 0.5 * dpe, state.void_ratio, state.p_pi)
            loading = dpe > 0
            deps = model.a11(mid, loading) * dpe + model.a13(mid) * ds  # eq. 14, first row, dq = 0
            p_pi = model.harden(mid, model.a11_plastic(mid, loading) * dpe)
            e = state.void_ratio - (1.0 + state.void_ratio) * deps
            state = SkeletonState(state.p_eff + dpe, e, max(p_pi, state.p_eff + dpe))
        if j < stops.size and sr == stops[j]:
            out["S_R"].append(sr)
            out["suction"].append(float(bc_suction(sr, air_entry, bc_lambda)))
            out["p_eff"].append(state.p_eff)
            out["void_ratio"].append(state.void_ratio)
            out["A11"].append(model.a11(state, True))
            out["B"].append(_undrained_b(model, state, sr, pa0, dp, n_dp))
            out["p_pi"].append(state.p_pi)
            j += 1
    return IncrementalBPath(**{k: np.asarray(v, float) for k, v in out.items()})


def skempton_b_incremental(
    S_R,
    *,
    compliance: Compliance | Callable[[float, float], float] | None = None,
    kappa_elastic=0.006,
    p0=100e3,
    u0=30e3,
    e0=0.8,
    pa0=130e3,
    air_entry=20e3,
    bc_lambda=0.8,
    dp=1e3,
    n_dp=10,
    S_R_step=1e-3,
    air_pressure="absolute",
):
    r"""Skempton's B at each ``S_R`` by the two incremental loops of Morvan et al. (2016), eqs. 14-24.

    One drying path from ``S_R = 1`` down to ``min(S_R)`` (loop 1) and, at each
    requested ``S_R``, an undrained isotropic increment ``dp`` (loop 2);
    see :func:`skempton_b_incremental_path` for the scheme and parameters.

    .. math::

        B = \frac{du_w}{dp}
          = \frac{(P_a V_0/V_a)\, A_{11}}{1 + (P_a V_0/V_a)\, A_{11}}
        \quad (\text{eq. 24, as } dp \to 0)

    Parameters
    ----------
    S_R : array_like
        Degrees of saturation [-], each in (0, 1].
    compliance, kappa_elastic, p0, u0, e0, pa0, air_entry, bc_lambda, dp, n_dp, S_R_step, air_pressure
        As in :func:`skempton_b_incremental_path` (SI units, Pa).

    Returns
    -------
    ndarray or float
        B [-], same shape as ``S_R``.

    Raises
    ------
    ValueError
        A degree of saturation outside (0, 1], or an invalid step (see
        :func:`skempton_b_incremental_path`).

    Notes
    -----
    With the default elastic compliance (eq. 5) the result agrees with eq. 10
    evaluated at the effective stress of eq. 13, ``p' = p0 - u0 + s S_R``
    (``skempton_b_suction``), up to the small drying change of ``e`` and the
    finite ``dp``. The elasto-plastic B of the paper (Fig. 6: 0.4 and 0.04
    at ``S_R = 0.9``) needs the bounding-surface compliance of Morvan, Wong &
    Branque (2010), which capred does not have.

    References
    ----------
    [1] Morvan et al. (2016), section 4, eqs. 14-24; Table 3.
    """
    S = np.asarray(S_R, float)
    if S.size == 0:
        return S.copy()
    if np.any(~np.isfinite(S)) or np.any(S <= 0.0) or np.any(S > 1.0):
        raise ValueError("S_R must lie in (0, 1]")
    path = skempton_b_incremental_path(
        float(S.min()),
        compliance=compliance,
        kappa_elastic=kappa_elastic,
        p0=p0,
        u0=u0,
        e0=e0,
        pa0=pa0,
        air_entry=air_entry,
        bc_lambda=bc_lambda,
        dp=dp,
        n_dp=n_dp,
        S_R_step=S_R_step,
        at=S,
        air_pressure=air_pressure,
    )
    B = np.interp(S.ravel(), path.S_R[::-1], path.B[::-1]).reshape(S.shape)  # exact: every S_R is a path point
    return B if B.ndim else float(B)
