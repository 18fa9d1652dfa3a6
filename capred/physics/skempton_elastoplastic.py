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
of the constitutive matrix of eq. 14. This module runs the loops for any
``A11`` supplied as a callable (:class:`Compliance`). The paper takes ``A11``
from the bounding-surface model of its reference [16] (Morvan, Wong & Branque
2010, Int. J. Numer. Anal. Meth. Geomech. 34:1512-1537; parameters lambda_0,
Gamma, rho, M, A_ini of Table 3). Those equations are not restated in the 2016
paper and could not be found in the material available to capred, so the only
compliance shipped is the elastic one the paper does define, eq. 5:
``A11 = kappa / ((1 + e) p')``. With it the scheme reproduces eq. 10 with the
suction-equilibrium effective stress of section 3 (``skempton_b_suction`` in
:mod:`capred.physics.calculators`), which the tests check.

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

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..errors import OptionError
from .retention import bc_suction

__all__ = [
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
    void ratio ``void_ratio`` [-]; returns ``A11`` [1/Pa], > 0. A model with
    internal state (a bounding surface) keeps it itself.
    """

    def __call__(self, p_eff: float, void_ratio: float) -> float: ...


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
class ElasticCompliance:
    """:class:`Compliance` of eq. 5 of [1]: ``A11 = kappa_elastic / ((1 + e) p')``.

    Attributes
    ----------
    kappa_elastic : float
        Slope of the elastic line in ``e - ln p'`` [-].
    """

    kappa_elastic: float

    def __call__(self, p_eff: float, void_ratio: float) -> float:
        return float(elastic_compliance(p_eff, void_ratio, self.kappa_elastic))


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
    """

    S_R: np.ndarray
    suction: np.ndarray
    p_eff: np.ndarray
    void_ratio: np.ndarray
    A11: np.ndarray
    B: np.ndarray


def _undrained_b(compliance: Compliance, p_eff, e, S_R, pa0, dp, n_dp):
    """Second loop of [1]: ``n_dp`` sub-increments of ``dp / n_dp``; returns the secant B.

    Per sub-increment (eqs. 22-23): ``d eps = A11 dp V_a / (V_a + A11 P_a V)``,
    ``du_a = P_a V d eps / V_a`` (written so that ``V_a = 0`` gives
    ``d eps = 0, du_a = dp``); then Boyle's law updates ``P_a`` and ``V_a``, the
    skeleton volume ``V`` shrinks by ``V d eps`` (water and grains
    incompressible, eq. 19), and ``p'`` changes by ``dp - du_a`` (eq. 18 at
    ``ds = 0``: suction and chi constant during the increment).
    """
    V = 1.0 + e  # per unit volume of grains
    Va = e * (1.0 - S_R)
    pa = pa0
    h = dp / n_dp
    for _ in range(n_dp):
        a11 = compliance(p_eff, V - 1.0)
        den = Va + a11 * pa * V
        deps = a11 * h * Va / den
        du = a11 * pa * V * h / den
        pa += du
        Va -= V * deps
        V -= V * deps
        p_eff += h - du
    return (pa - pa0) / dp


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
) -> IncrementalBPath:
    r"""The two incremental loops of Morvan et al. (2016), section 4: B along a drying path.

    Loop 1 dries the sample from ``S_R = 1`` (suction ``s_e``, ``p' = p0 - u0 + s_e``)
    down to ``S_R_min`` in steps of ``S_R_step``, at constant total stress and
    air pressure (``dp = du_a = 0``), with

    .. math::

        s = s_e S_R^{-1/\lambda}, \qquad dp' = S_R (1 - \lambda)\, ds,
        \qquad d\varepsilon_p = A_{11}\, dp', \qquad de = -(1 + e)\, d\varepsilon_p

    (eqs. 17-18; ``ds`` exact along the Brooks-Corey curve, ``S_R`` at the mid-step;
    the drying strains use ``A11`` only, i.e. ``A13 = 0`` as for the elastic
    law of eq. 5). Loop 2, at each recorded state, applies the undrained
    isotropic increment ``dp`` in ``n_dp`` sub-increments (eqs. 19-24) on a copy
    of the state: the increment is a B check, not part of the drying history.

    Parameters
    ----------
    S_R_min : float
        Lowest degree of saturation of the path [-], in (0, 1].
    compliance : Compliance, optional
        ``A11(p_eff [Pa], void_ratio [-]) -> [1/Pa]``. Default: the elastic
        compliance of eq. 5 with ``kappa_elastic`` (:class:`ElasticCompliance`). The
        bounding-surface compliance of Morvan, Wong & Branque (2010) that the
        paper uses is not available in capred.
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

    Returns
    -------
    IncrementalBPath
        The states and B, ordered by decreasing ``S_R``.

    Raises
    ------
    OptionError
        ``S_R_min`` outside (0, 1], a recording point outside ``[S_R_min, 1]``,
        or a non-positive ``dp``, ``n_dp`` or ``S_R_step``.

    References
    ----------
    [1] Morvan et al. (2016), section 4, eqs. 13, 17-24; Table 3 (defaults).
    [3] Brooks & Corey (1964), retention curve ``S_R = (s_e / s)^lambda``.
    """
    if compliance is None:
        compliance = ElasticCompliance(kappa_elastic)
    if not 0.0 < S_R_min <= 1.0:
        raise OptionError(f"S_R_min must be in (0, 1], got {S_R_min}")
    if dp <= 0 or n_dp < 1 or S_R_step <= 0:
        raise OptionError("dp, n_dp and S_R_step must be positive")
    n = max(1, int(np.ceil((1.0 - S_R_min) / S_R_step - 1e-9)))
    grid = np.linspace(1.0, S_R_min, n + 1)
    if at is None:
        stops = grid
    else:
        stops = np.unique(np.asarray(at, float).ravel())[::-1]
        if stops.size and (stops[0] > 1.0 or stops[-1] < S_R_min):
            raise OptionError(f"recording points must lie in [{S_R_min}, 1]")
        near = np.abs(grid[:, None] - stops[None, :]).min(axis=1) < 1e-9  # grid points a stop replaces
        grid = np.unique(np.concatenate([grid[~near], stops]))[::-1]

    out = {k: [] for k in ("S_R", "suction", "p_eff", "void_ratio", "A11", "B")}
    p_eff = p0 - u0 + air_entry  # eq. 13 at S_R = 1, s = s_e
    e = e0
    j = 0  # next recording point
    for i, sr in enumerate(grid):
        if i > 0:
            s_prev = bc_suction(grid[i - 1], air_entry, bc_lambda)
            s_now = bc_suction(sr, air_entry, bc_lambda)
            dpe = 0.5 * (grid[i - 1] + sr) * (1.0 - bc_lambda) * (s_now - s_prev)  # eq. 18
            e -= (1.0 + e) * compliance(p_eff + 0.5 * dpe, e) * dpe
            p_eff += dpe
        if j < stops.size and sr == stops[j]:
            out["S_R"].append(sr)
            out["suction"].append(float(bc_suction(sr, air_entry, bc_lambda)))
            out["p_eff"].append(p_eff)
            out["void_ratio"].append(e)
            out["A11"].append(compliance(p_eff, e))
            out["B"].append(_undrained_b(compliance, p_eff, e, sr, pa0, dp, n_dp))
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
    compliance, kappa_elastic, p0, u0, e0, pa0, air_entry, bc_lambda, dp, n_dp, S_R_step
        As in :func:`skempton_b_incremental_path` (SI units, Pa).

    Returns
    -------
    ndarray or float
        B [-], same shape as ``S_R``.

    Raises
    ------
    OptionError
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
        raise OptionError("S_R must lie in (0, 1]")
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
    )
    B = np.interp(S.ravel(), path.S_R[::-1], path.B[::-1]).reshape(S.shape)  # exact: every S_R is a path point
    return B if B.ndim else float(B)
