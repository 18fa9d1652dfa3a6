"""Pendular liquid bridge between two spheres, or a sphere and a plane, in zero gravity.

Sources: Lian, Thornton & Adams (1993), J. Colloid Interface Sci. 161, 138-147,
doi:10.1006/jcis.1993.1452 (first integral, rupture distance); Evenepoel (VUB
thesis) for the unit cell; Duriez & Wan (2017), doi:10.1007/s11440-016-0500-6
and Prunier et al. (2024) for the interface tensor and YADE's capillary files.

Dimensionless core: lengths in units of the radius R1 of the first particle,
suction s* = Delta_u R1 / gamma, force F* = F / (pi gamma R1), volume
V* = V / R1^3, areas in R1^2. The second particle has radius rho = R2 / R1
(``inf`` for a plane). Both particles have the contact angle theta (``contact_angle_rad``
in the public functions, radians; ``contact_angle`` [deg] in the pipelines and the CLI).

The meridian y(x) (x along the line of centres) obeys the axisymmetric
Young-Laplace equation Delta_u / gamma = kappa_meridional - cos(psi) / y
(psi: angle of the tangent with the axis). Its first integral is the axial
force, the same through every section:
    F* = 2 y cos(psi) + s* y^2,
so cos(psi) = c(y) = (F* - s* y^2) / (2 y) and the neck (psi = 0) has
y0 = F* / (1 + sqrt(1 + s* F*)). At the contact line on a sphere of radius
R_i with filling angle delta_i, y = R_i sin(delta_i) and c = sin(delta_i +
theta); on a plane, c = sin(theta). With
    1 - c = (y - y0) A / (2 y),  1 + c = B / (2 y),
    A = 2 + s* (y + y0),  B = 2 y + F* - s* y^2,
every integral along the meridian from the neck to a contact (x-length,
volume under it, interface area, int n(x)n dS) has only an inverse
square-root singularity at the neck; the substitution y = y0 cosh(tau)
removes it and also resolves thin necks, and 16 Gauss-Legendre nodes give
about 1e-13 relative.

The neck lies between the particles when delta_i + theta < 90 deg on both;
when delta_i + theta > 90 deg on one of them the meridian widens from that
contact to the other and the neck (a virtual one, on the continuation of the
meridian) lies behind it: the bridge is then the difference of the two
neck-to-contact pieces. The force identity F = pi r0^2 Delta_u + 2 pi r0 gamma
holds with that r0 too.

Only bridges with s* >= 0 (water at or below air pressure: concave,
pendular) are treated.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

from ..nomenclature import renamed_keywords

_NODES = 16
_u, _w = leggauss(_NODES)
_U = 0.5 * (_u + 1.0)
_W = 0.5 * _w
_u8, _w8 = leggauss(8)  # a coarse rule for bracketing scans, where only the sign of gap - D matters
_U8, _W8 = 0.5 * (_u8 + 1.0), 0.5 * _w8
_USQ, _U8SQ = _U * _U, _U8 * _U8  # node positions of the t^2 substitution of _length
_CHUNK = 2048  # cases per vectorised block: its chunk x nodes arrays (256 kB) stay in the cache and in the heap
HALF_PI = 0.5 * np.pi
#: every bridge called ok reproduces its gap and volume (or suction) to this relative tolerance
VERIFY_RTOL = 1e-9


@dataclass
class Bridge:
    r"""A set of bridges, dimensionless (lengths in R1, forces in pi gamma R1); NaN where there is no concave bridge.

    Attributes
    ----------
    gap : numpy.ndarray
        D / R1 [-].
    volume : numpy.ndarray
        V / R1^3 [-].
    force : numpy.ndarray
        F / (pi gamma R1) [-], :math:`F^* = 2 y_0 + s^* y_0^2`.
    neck : numpy.ndarray
        r0 / R1 [-] (a virtual neck behind a contact when delta + theta > 90 deg there).
    delta2 : numpy.ndarray
        Filling angle on particle 2 [rad]; 0 on a plane.
    area : numpy.ndarray
        Liquid-gas interface area / R1^2 [-].
    nn11, nn33 : numpy.ndarray
        Transverse (= nn22) and axial components of :math:`\int n \otimes n\, dS`
        over the interface / R1^2 [-]; area = 2 nn11 + nn33.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    .. [2] Duriez, J. & Wan, R. (2017). Contact angle mechanical influence in wet granular soils. Acta Geotech.
       12, 67-83. doi:10.1007/s11440-016-0500-6 (the interface tensor).
    """

    gap: np.ndarray
    volume: np.ndarray
    force: np.ndarray
    neck: np.ndarray
    delta2: np.ndarray
    area: np.ndarray
    nn11: np.ndarray
    nn33: np.ndarray


_FIELDS = ("gap", "volume", "force", "neck", "delta2", "area", "nn11", "nn33")


def _arr(*xs):
    return [np.asarray(x, dtype=float) for x in np.broadcast_arrays(*xs)]


def _blocks(beta, theta, suction, ratio, fields, theta2=None, **how):
    """``fields`` outputs of :func:`_pair` over broadcast inputs, block by block (memory bounded by a block).

    A case with any non-finite output is NaN throughout, with no warning. ``theta2``: the contact angle on particle 2
    (None: ``theta``).
    """
    beta, theta, suction, ratio, theta2 = _arr(beta, theta, suction, ratio, theta if theta2 is None else theta2)
    cols = [a.ravel() for a in (beta, theta, suction, ratio, theta2)]
    out = np.full((fields, cols[0].size), np.nan)
    with np.errstate(all="ignore"):
        for start in range(0, cols[0].size, _CHUNK):
            sl = slice(start, start + _CHUNK)
            vals = np.array(_pair(*(c[sl] for c in cols), **how)[:fields])
            out[:, sl] = np.where(np.all(np.isfinite(vals), axis=0), vals, np.nan)
    return out.reshape((fields, *beta.shape))


def bridge(beta, contact_angle_rad, suction, ratio=1.0, contact_angle2_rad=None) -> Bridge:
    r"""Exact pendular bridge from its filling angle, contact angle and suction (zero gravity).

    Parameters
    ----------
    beta : float or array_like
        Filling angle on particle 1 [rad], > 0.
    contact_angle_rad : float or array_like
        Contact angle θ [rad], in [0, pi/2).
    suction : float or array_like
        Dimensionless suction s* = Delta_u R1 / gamma [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle θ2 on particle 2 (sphere or plane) [rad], in [0, pi/2); default: ``contact_angle_rad``
        (θ is then particle 1's alone). Inputs broadcast against each other.

    Returns
    -------
    Bridge
        gap* = D / R1, volume* = V / R1^3, force* = F / (pi gamma R1), neck*
        = r0 / R1, delta2 [rad], area* and the interface tensor nn11*, nn33*
        [R1^2], each of the broadcast shape; NaN where no concave bridge has
        these inputs (beta + theta too large, or no filling angle on particle
        2 can carry the force: the smaller particle would be engulfed).

    Notes
    -----
    The meridian y(x) obeys the axisymmetric Young-Laplace equation, whose first
    integral is the axial force, the same through every section [1]_:

    .. math::

        F^* = 2 y \cos\psi + s^* y^2 = 2 \sin\beta \sin(\beta + \theta) + s^* \sin^2\beta ,

    and every field is an integral along the meridian from the neck
    :math:`y_0 = F^* / (1 + \sqrt{1 + s^* F^*})` to each contact, computed by
    16-point Gauss-Legendre quadrature after the substitution
    :math:`y = y_0 \cosh\tau` (about 1e-13 relative; see the module docstring).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
       (the first integral of the meridian).
    .. [2] Orr, F. M., Scriven, L. E. & Rivas, A. P. (1975). Pendular rings between solids: meniscus properties and
       capillary force. J. Fluid Mech. 67, 723-742. doi:10.1017/S0022112075000572
    .. [3] Duriez, J. & Wan, R. (2017). Contact angle mechanical influence in wet granular soils. Acta Geotech.
       12, 67-83. doi:10.1007/s11440-016-0500-6 (the interface tensor int n (x) n dS).
    """
    return Bridge(*_blocks(beta, contact_angle_rad, suction, ratio, len(_FIELDS), contact_angle2_rad))


def _bridge(beta, theta, suction, ratio, theta2):
    """:func:`bridge` with the second contact angle positional (the solvers' calls)."""
    return Bridge(*_blocks(beta, theta, suction, ratio, len(_FIELDS), theta2))


def gap_of(beta, contact_angle_rad, suction, ratio=1.0, coarse=False, contact_angle2_rad=None) -> np.ndarray:
    r"""Gap* alone of the bridge (the fast path the solvers iterate on).

    Parameters
    ----------
    beta : float or array_like
        Filling angle on particle 1 [rad], > 0.
    contact_angle_rad : float or array_like
        Contact angle θ [rad], in [0, pi/2).
    suction : float or array_like
        Dimensionless suction s* = Delta_u R1 / gamma [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    coarse : bool, default False
        An 8-node rule (about 1e-8 relative on thick necks): enough to bracket a root.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 [rad]; default: ``contact_angle_rad``.

    Returns
    -------
    numpy.ndarray
        gap* = D / R1 [-], broadcast shape; NaN where there is no concave bridge.

    Notes
    -----
    :math:`D^* = L_1 + L_2 - (1 - \cos\beta) - \rho (1 - \cos\delta_2)`, with
    :math:`L_i = \int_{y_0}^{y_i} \frac{F^* - s^* y^2}{\sqrt{4 y^2 - (F^* - s^* y^2)^2}} dy`
    the axial length of the meridian from the neck to contact i (signed when the
    neck lies behind a contact); see :func:`bridge`.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    return _blocks(beta, contact_angle_rad, suction, ratio, 1, contact_angle2_rad, full=False, coarse=coarse)[0]


def _gap(beta, theta, suction, ratio, theta2, coarse=False):
    """:func:`gap_of` with the second contact angle positional (the solvers' calls)."""
    return _blocks(beta, theta, suction, ratio, 1, theta2, full=False, coarse=coarse)[0]


def geometry(beta, contact_angle_rad, suction, ratio=1.0, contact_angle2_rad=None):
    r"""(gap*, volume*, force*, neck*) of the bridge: the first four fields of :func:`bridge`.

    Parameters
    ----------
    beta : float or array_like
        Filling angle on particle 1 [rad], > 0.
    contact_angle_rad : float or array_like
        Contact angle θ [rad], in [0, pi/2).
    suction : float or array_like
        Dimensionless suction s* = Delta_u R1 / gamma [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 [rad]; default: ``contact_angle_rad``.

    Returns
    -------
    gap : numpy.ndarray
        D / R1 [-].
    volume : numpy.ndarray
        V / R1^3 [-].
    force : numpy.ndarray
        F / (pi gamma R1) [-], :math:`F^* = 2 y_0 + s^* y_0^2` (gorge method).
    neck : numpy.ndarray
        r0 / R1 [-].

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    b = bridge(beta, contact_angle_rad, suction, ratio, contact_angle2_rad)
    return b.gap, b.volume, b.force, b.neck


#: rows of a quadrature's matrix summed together by the matrix-vector product (see _quad)
_QUAD_ROWS = 16


def _quad(values, weights):
    """``values @ weights`` (one quadrature per row), every row summed in the same order wherever it stands.

    BLAS sums the rows of a matrix-vector product in groups (of 4 in OpenBLAS's kernels), the last
    n mod 4 rows in another order, which can move the last bit: a row's result would then depend on the rows
    computed with it (a block of a long file, a process's half). The matrix is cut at a multiple of
    _QUAD_ROWS and its last rows are summed padded with zeros, so every row is summed as the groups are.
    """
    n = values.shape[0]
    k = n - n % _QUAD_ROWS
    if k == n:
        return values @ weights
    out = np.empty(n)
    if k:
        out[:k] = values[:k] @ weights
    pad = np.zeros((_QUAD_ROWS, values.shape[1]))
    pad[: n - k] = values[k:]
    out[k:] = (pad @ weights)[: n - k]
    return out


def _pieces(y0, yc, F, s, length_only=False):
    """Integrals from the neck y0 to y = yc: x-length, pi int y^2 dx, area, nn11, nn33 (units of R1)."""
    x = np.maximum(yc - y0, 0.0) / y0
    tm = np.log1p(x + np.sqrt(x * (2.0 + x)))  # acosh(yc / y0) without cancellation
    tau = tm[:, None] * _U
    e = np.exp(0.5 * tau)
    sh = 0.5 * (e - 1.0 / e)
    ch = 0.5 * (e + 1.0 / e)
    dy = 2.0 * y0[:, None] * sh * sh  # y - y0
    y = y0[:, None] + dy
    sc = s[:, None]
    AB = (2.0 + sc * (y + y0[:, None])) * (2.0 * y + F[:, None] - sc * y * y)
    P = F[:, None] - sc * y * y  # 2 y cos(psi)
    # dy / sqrt(y - y0) = sqrt(2 y0) cosh(tau / 2) dtau
    J = (np.sqrt(2.0 * y0) * tm)[:, None] * ch / np.sqrt(AB)
    PJ = P * J
    if length_only:
        return _quad(PJ, _W)
    yy = y * y
    L = _quad(PJ, _W)
    vol = np.pi * _quad(yy * PJ, _W)
    area = 4.0 * np.pi * _quad(yy * J, _W)
    nn11 = 0.5 * np.pi * _quad(P * PJ, _W)
    # nn33 = pi int sqrt((y - y0) A B) dy, integrated on its own (area = 2 nn11 + nn33 is then a check)
    nn33 = np.pi * _quad(np.sqrt(dy * AB) * (2.0 * sh * ch) * (y0 * tm)[:, None], _W)
    return L, vol, area, nn11, nn33


def _second_filling_angle(F, th, s, rho):
    """Filling angle delta2 on the sphere of radius rho carrying the force F* (NaN if none).

    F* = 2 rho sin(d) sin(d + th) + s* rho^2 sin^2(d) = a - M cos(2 d + phi) with
    a = rho cos(th) + s* rho^2 / 2, b = rho sin(th), M = hypot(a, b), phi = atan2(b, a):
    increasing for 2 d + phi in [phi, pi], solved in closed form and polished by one Newton step.
    """
    a = rho * np.cos(th) + 0.5 * s * rho * rho
    b = rho * np.sin(th)
    M = np.hypot(a, b)
    phi = np.arctan2(b, a)
    with np.errstate(invalid="ignore"):
        half = np.arctan2(np.sqrt(F + b * b / (M + a)), np.sqrt(M + a - F))  # (2 d + phi) / 2
        d = half - 0.5 * phi
        g = 2.0 * rho * np.sin(d) * np.sin(d + th) + s * rho * rho * np.sin(d) ** 2 - F
        dg = 2.0 * rho * np.sin(2.0 * d + th) + s * rho * rho * np.sin(2.0 * d)
        d = d - np.where(dg > 0, g / np.where(dg > 0, dg, 1.0), 0.0)
    return np.where((F <= a + M) & (d > 0), d, np.nan)


def _length(y0, yc, F, s, coarse=False, volume=False):
    """x-length of the meridian from the neck y0 to y = yc (units of R1): the gap-only fast path.

    Thick necks (yc < 21 y0) use y = y0 + (yc - y0) t^2, which needs no
    transcendental function and is as accurate there (1e-13); thin ones the
    cosh substitution of :func:`_pieces`. With ``volume`` it returns
    (length, pi int y^2 dx) from the same nodes (the volume-controlled solver's
    fast path).
    """
    d = np.maximum(yc - y0, 0.0)
    out = np.empty(y0.size)
    vol = np.empty(y0.size) if volume else None
    thick = d <= 20.0 * y0
    every = bool(thick.all())  # the usual case: no copies of the rows
    k = slice(None) if every else np.flatnonzero(thick)
    if every or k.size:
        U2, W = (_U8SQ, _W8) if coarse else (_USQ, _W)
        y0k, dk, Fk, sk = (y0, d, F, s) if every else (y0[k], d[k], F[k], s[k])
        # the same operations in the same order as P = F - s y y, Q = P / sqrt((2 + s (y + y0)) (2 y + P)),
        # written into three arrays (fewer temporaries: the chunk's arrays stay in the cache)
        y = np.multiply(dk[:, None], U2)
        np.add(y0k[:, None], y, out=y)
        sc = sk[:, None]
        P = np.multiply(sc, y)
        np.multiply(P, y, out=P)
        np.subtract(Fk[:, None], P, out=P)  # 2 y cos(psi)
        A = np.add(y, y0k[:, None])
        np.multiply(sc, A, out=A)
        np.add(2.0, A, out=A)
        B = np.multiply(2.0, y)
        np.add(B, P, out=B)  # B = 2 y + P
        np.multiply(A, B, out=A)
        np.sqrt(A, out=A)
        Q = np.divide(P, A, out=A)
        root = 2.0 * np.sqrt(dk)
        out[k] = root * _quad(Q, W)
        if volume:
            vol[k] = np.pi * root * _quad(y * y * Q, W)
    if not every:
        k = np.flatnonzero(~thick)
        if volume:
            out[k], vol[k] = _pieces(y0[k], yc[k], F[k], s[k])[:2]
        else:
            out[k] = _pieces(y0[k], yc[k], F[k], s[k], length_only=True)
    return (out, vol) if volume else out


def _gap_equal(b, th, s, coarse=False):
    """gap* alone of bridges between equal spheres (the suction solver's inner loop); NaN where none.

    The general :func:`_pair` with rho = 1: both contacts alike (delta2 = beta), the neck between them
    (beta + theta <= 90 deg, which also keeps beta on the rising side of its contact relation), and
    gap* = 2 (L1 - (1 - cos beta)).
    """
    ok = (b > 0) & (th >= 0) & (b + th <= HALF_PI) & (s >= 0)
    y1 = np.sin(b)
    F = 2.0 * y1 * np.sin(b + th) + s * y1 * y1
    y0 = F / (1.0 + np.sqrt(1.0 + s * F))
    gap = 2.0 * _length(y0, y1, F, s, coarse) - 4.0 * np.sin(0.5 * b) ** 2
    return np.where(ok, gap, np.nan)


def _pair(b, th, s, rho, th2, full=True, coarse=False):
    """The bridge of filling angle b on particle 1 (contact angle th) and th2 on particle 2 (ratio rho).

    Its fields (see _FIELDS; ``full`` False: the gap alone, "gap volume": those two), NaN where there is none. Each
    contact meets its solid at its own angle: particle 1 sets the force F* = 2 sin b sin(b + th) + s* sin^2 b, particle
    2 carries it at its own filling angle (sin(d2 + th2) there; sin th2 on a plane).
    """
    same = th2 is th or np.array_equal(th2, th)
    if full is False and same and np.all(rho == 1.0):
        return [_gap_equal(b, th, s, coarse)]
    n = b.size
    nan = np.full(n, np.nan)
    ok = (b > 0) & (th >= 0) & (th < HALF_PI) & (s >= 0) & (rho > 0) & (th2 >= 0) & (th2 < HALF_PI)
    # the filling angle on particle 1 stays on the rising side of its contact relation (as delta2 does)
    ok &= 2.0 * b + np.arctan2(np.sin(th), np.cos(th) + 0.5 * s) <= np.pi
    y1 = np.sin(b)
    c1 = np.sin(b + th)
    F = 2.0 * y1 * c1 + s * y1 * y1
    equal = (rho == 1.0) if same else (rho == 1.0) & (th2 == th)  # both contacts alike: delta2 = beta
    plane = np.isinf(rho)
    d2 = np.where(equal, b, 0.0)
    y2 = y1.copy()
    c2 = c1.copy()
    sphere = ~equal & ~plane & ok
    if sphere.any():
        d2[sphere] = _second_filling_angle(F[sphere], th2[sphere], s[sphere], rho[sphere])
        y2[sphere] = rho[sphere] * np.sin(d2[sphere])
        c2[sphere] = np.sin(d2[sphere] + th2[sphere])
    flat = plane & ok
    if flat.any():
        sin_t = np.sin(th2[flat])
        with np.errstate(divide="ignore", invalid="ignore"):
            y2[flat] = F[flat] / (sin_t + np.sqrt(sin_t * sin_t + s[flat] * F[flat]))
        c2[flat] = sin_t
    ok &= np.isfinite(y2) & (y2 > 0) & np.isfinite(d2)
    # the meridian narrows from a contact towards the bridge when delta + theta < 90 deg (sign +1)
    sig1 = np.where(b + th <= HALF_PI, 1.0, -1.0)
    sig2 = np.where(plane, 1.0, np.where(d2 + th2 <= HALF_PI, 1.0, -1.0))
    ok &= (sig1 > 0) | (sig2 > 0)
    ok &= ~((sig1 < 0) & (y2 < y1)) & ~((sig2 < 0) & (y1 < y2))
    k = np.flatnonzero(ok)
    res = [nan.copy() for _ in _FIELDS]
    if k.size == 0:
        return res
    Fk, sk = F[k], s[k]
    y0 = Fk / (1.0 + np.sqrt(1.0 + sk * Fk))
    h1 = 2.0 * np.sin(0.5 * b[k]) ** 2
    rk = np.where(plane[k], 0.0, rho[k])
    h2 = 2.0 * rk * np.sin(0.5 * d2[k]) ** 2
    if full == "gap volume":  # gap and volume alone (the volume-controlled solver's iterations)
        L1, v1 = _length(y0, y1[k], Fk, sk, volume=True)
        if equal[k].all():
            L, vol_under = 2.0 * L1, 2.0 * v1
        else:
            L2, v2 = _length(y0, y2[k], Fk, sk, volume=True)
            L, vol_under = sig1[k] * L1 + sig2[k] * L2, sig1[k] * v1 + sig2[k] * v2
        caps = np.pi * (h1 * h1 * (3.0 - h1) + h2 * h2 * (3.0 * rk - h2)) / 3.0
        res[0][k], res[1][k] = L - h1 - h2, vol_under - caps
        return res
    if not full:
        L1 = _length(y0, y1[k], Fk, sk, coarse)
        L = 2.0 * L1 if equal[k].all() else sig1[k] * L1 + sig2[k] * _length(y0, y2[k], Fk, sk, coarse)
        res[0][k] = L - h1 - h2
        return res
    p1 = _pieces(y0, y1[k], Fk, sk)
    eq = equal[k]
    if eq.all():
        tot = [2.0 * q for q in p1]
    else:
        p2 = _pieces(y0, y2[k], Fk, sk)
        tot = [sig1[k] * q1 + sig2[k] * q2 for q1, q2 in zip(p1, p2)]
    L, vol_under, area, nn11, nn33 = tot
    caps = np.pi * (h1 * h1 * (3.0 - h1) + h2 * h2 * (3.0 * rk - h2)) / 3.0
    vals = [L - h1 - h2, vol_under - caps, Fk, y0, d2[k], area, nn11, nn33]
    for r, v in zip(res, vals):
        r[k] = v
    return res


# ---- root finding ------------------------------------------------------------


def illinois(f, lo, hi, f_lo, f_hi, tol=1e-14, iters=100, ftol=None, ends=False):
    """Vectorised Illinois (modified regula falsi) root of f on brackets with f_lo >= 0 >= f_hi.

    Parameters
    ----------
    f : callable
        ``f(x, i)``: the function at points ``x`` of the rows ``i`` (an index array) [any unit].
    lo, hi : array_like
        Bracket ends, one per row [unit of x].
    f_lo, f_hi : array_like
        f at the ends, f_lo >= 0 >= f_hi (a non-finite value: bisection until the end moves).
    tol : float, default 1e-14
        Relative width of the bracket at which a row stops [-].
    iters : int, default 100
        Most iterations.
    ftol : array_like, optional
        Per row: a row stops when |f| <= ftol [unit of f].
    ends : bool, default False
        Return the final bracket too.

    Returns
    -------
    numpy.ndarray or tuple
        The roots [unit of x]; with ``ends``, (x, lo, hi), lo on the side where f >= 0.

    References
    ----------
    .. [1] Dowell, M. & Jarratt, P. (1971). A modified regula falsi method for computing the root of an equation.
       BIT 11, 168-174. doi:10.1007/BF01934364
    """
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    x = lo.copy()
    active = np.ones(lo.shape, dtype=bool)
    side = np.zeros(lo.shape, dtype=int)
    for _ in range(iters):
        if not active.any():
            break
        a = np.flatnonzero(active)
        denom = f_lo[a] - f_hi[a]
        # bisect while an end carries the stand-in value of "no bridge here" (see _below)
        secant = (denom != 0) & (np.abs(f_lo[a]) < 1e299) & (np.abs(f_hi[a]) < 1e299)
        xa = np.where(
            secant, (lo[a] * (-f_hi[a]) + hi[a] * f_lo[a]) / np.where(secant, denom, 1.0), 0.5 * (lo[a] + hi[a])
        )
        # keep strictly inside the bracket (regula falsi can stall on an end)
        span = hi[a] - lo[a]
        xa = np.clip(xa, lo[a] + 1e-3 * span * (side[a] == 1), hi[a] - 1e-3 * span * (side[a] == -1))
        fa = f(xa, a)
        x[a] = xa
        pos = fa >= 0
        lo_new, hi_new = np.where(pos, xa, lo[a]), np.where(pos, hi[a], xa)
        flo_new = np.where(pos, fa, np.where(side[a] == -1, f_lo[a] * 0.5, f_lo[a]))
        fhi_new = np.where(pos, np.where(side[a] == 1, f_hi[a] * 0.5, f_hi[a]), fa)
        side[a] = np.where(pos, 1, -1)
        lo[a], hi[a], f_lo[a], f_hi[a] = lo_new, hi_new, flo_new, fhi_new
        done = (np.abs(hi[a] - lo[a]) <= tol * np.maximum(1.0, np.abs(xa))) | (fa == 0)
        if ftol is not None:
            done |= np.abs(fa) <= ftol[a]
        active[a[done]] = False
    return (x, lo, hi) if ends else x


def golden(f, a, c, iters=60, sign=1.0):
    """Vectorised golden-section search of the maximum of sign * f on [a, c].

    Parameters
    ----------
    f : callable
        ``f(x, i)``: the function at points ``x`` of the rows ``i`` (an index array); non-finite values count
        as -inf.
    a, c : array_like
        Ends of the interval, one per row [unit of x]; f unimodal between them.
    iters : int, default 60
        Golden-section steps (each shrinks the interval by 0.618).
    sign : float, default 1.0
        -1.0 to find the minimum.

    Returns
    -------
    x : numpy.ndarray
        The maximiser of each row [unit of x].
    fx : numpy.ndarray
        f there (not multiplied by ``sign``).

    References
    ----------
    .. [1] Kiefer, J. (1953). Sequential minimax search for a maximum. Proc. Amer. Math. Soc. 4, 502-506.
       doi:10.1090/S0002-9939-1953-0055639-3
    """
    g = (np.sqrt(5.0) - 1.0) / 2.0
    a, c = np.array(a, float), np.array(c, float)
    idx = np.arange(a.size)

    def h(x, i):
        v = sign * f(x, i)
        return np.where(np.isfinite(v), v, -np.inf)

    x1, x2 = c - g * (c - a), a + g * (c - a)
    f1, f2 = h(x1, idx), h(x2, idx)
    for _ in range(iters):
        left = f1 < f2
        a = np.where(left, x1, a)
        c = np.where(left, c, x2)
        x1n = np.where(left, x2, c - g * (c - a))
        x2n = np.where(left, a + g * (c - a), x1)
        fn = h(np.where(left, x2n, x1n), idx)
        f1, f2 = np.where(left, f2, fn), np.where(left, fn, f1)
        x1, x2 = x1n, x2n
    x = 0.5 * (x1 + x2)
    return x, f(x, idx)


def _below(v):
    """A value that failed (no bridge) counts as below any target in the brackets (finite, for regula falsi)."""
    return np.where(np.isfinite(v), v, -1e300)


# ---- bridges from their neck ----------------------------------------------------


def from_neck(neck, contact_angle_rad, suction, ratio=1.0, contact_angle2_rad=None):
    r"""Filling angle on particle 1 and the bridge whose neck radius is y0, at s* >= 0.

    Parameters
    ----------
    neck : float or array_like
        Neck radius y0 = r0 / R1 [-], > 0.
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    suction : float or array_like
        s* = Delta_u R1 / gamma [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 [rad]; default: ``contact_angle_rad``.

    Returns
    -------
    beta : numpy.ndarray
        Filling angle on particle 1 [rad] (NaN if none carries the force).
    bridge : Bridge
        The bridge (see :func:`bridge`).

    Notes
    -----
    The force through the neck, :math:`F^* = 2 y_0 + s^* y_0^2`, equals the one
    through the contact, :math:`2 \sin\beta \sin(\beta+\theta) + s^* \sin^2\beta
    = a - M \cos(2\beta + \varphi)` with :math:`a = \cos\theta + s^*/2`,
    :math:`M = \sqrt{a^2 + \sin^2\theta}`: solved for beta in closed form on the
    rising side. Along the bridges of one gap the neck shrinks monotonically
    from the largest concave bridge to the thinnest, which makes it the
    parameter of the volume-controlled solver.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    return _from_neck(neck, contact_angle_rad, suction, ratio, contact_angle2_rad)


def _from_neck(neck, th, suction, ratio, th2):
    """:func:`from_neck` with the second contact angle positional (None: ``th``)."""
    neck, th, suction, ratio, th2 = _arr(neck, th, suction, ratio, th if th2 is None else th2)
    F = 2.0 * neck + suction * neck * neck
    beta = _second_filling_angle(F, th, suction, np.ones_like(F))
    return beta, _bridge(beta, th, suction, ratio, th2)


def _neck_gap(y0, th, s, rho, th2):
    """gap* alone of the bridge with neck y0 at s* (the fast path of :func:`gap_of`); NaN where there is none."""
    F = 2.0 * y0 + s * y0 * y0
    return _gap(_second_filling_angle(F, th, s, np.ones_like(F)), th, s, rho, th2)


def _floor_suction(y0, th, rho, th2):
    """The smallest suction of the bridges with neck y0.

    0 (the catenoid), or 1e-9 / y0^2 where no catenoid exists (a plane at theta = 0: its bridge grows without bound as
    s* -> 0).
    """
    y0, th, rho, th2 = _arr(y0, th, rho, th2)
    g = _neck_gap(y0, th, 0.0, rho, th2)
    return np.where(np.isfinite(g), 0.0, 1e-9 / (y0 * y0))


def _catenoid(y0, th, rho, th2):
    """The bridge of neck y0 at its smallest suction (see :func:`_floor_suction`)."""
    y0, th, rho, th2 = _arr(y0, th, rho, th2)
    return _from_neck(y0, th, _floor_suction(y0, th, rho, th2), rho, th2)[1]


def _catenoid_gap(y0, th, rho, th2):
    """gap* alone of :func:`_catenoid` (one gap evaluation where the catenoid exists)."""
    y0, th, rho, th2 = _arr(y0, th, rho, th2)
    g = _neck_gap(y0, th, 0.0, rho, th2)
    none = ~np.isfinite(g)
    if none.any():
        g[none] = _neck_gap(y0[none], th[none], 1e-9 / (y0[none] * y0[none]), rho[none], th2[none])
    return g


@renamed_keywords(rho="ratio")
def suction_at_neck(y0, th, ratio, target, field, th2=None):
    """The suction s* >= 0 at which the bridge of neck y0 has a given gap (or volume).

    Parameters
    ----------
    y0 : numpy.ndarray
        Neck radius r0 / R1 [-], 1-D.
    th : numpy.ndarray
        Contact angle θ [rad], one per row (see ``th2``).
    ratio : numpy.ndarray
        Radius ratio R2 / R1 [-]; ``np.inf`` for a plane (the ``ratio`` of :func:`bridge`; the keyword ``rho``
        still works, with a DeprecationWarning).
    target : numpy.ndarray
        The gap* D / R1 or volume* V / R1^3 to reach [-].
    field : {"gap", "volume"}
        Which field ``target`` is.
    th2 : numpy.ndarray, optional
        Contact angle on particle 2 [rad]; default: ``th``.

    Returns
    -------
    numpy.ndarray
        s* = Delta_u R1 / gamma [-]; NaN where no bridge of that neck reaches the target.

    Notes
    -----
    At a fixed neck both the gap and the volume fall as s* rises, from the catenoid (s* = 0); the root is
    found by Illinois iterations in q = s* y0^2 / (1 + s* y0^2).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    y0, th, ratio, target = (np.asarray(x, dtype=float) for x in (y0, th, ratio, target))
    return _suction_at_neck(y0, th, ratio, th if th2 is None else np.asarray(th2, dtype=float), target, field)


def _suction_at_neck(y0, th, rho, th2, target, field):
    """:func:`suction_at_neck` with the second contact angle positional."""

    def value(q, i):
        s = q / (1.0 - q) / (y0[i] * y0[i])  # suction scale of a neck y0: 1 / y0^2
        if field == "gap":  # the gap alone: the fast path
            F = 2.0 * y0[i] + s * y0[i] * y0[i]
            return (
                _below(_gap(_second_filling_angle(F, th[i], s, np.ones_like(F)), th[i], s, rho[i], th2[i])) - target[i]
            )
        return _below(getattr(_from_neck(y0[i], th[i], s, rho[i], th2[i])[1], field)) - target[i]

    idx = np.arange(y0.size)
    s_floor = _floor_suction(y0, th, rho, th2) * y0 * y0
    q0 = s_floor / (1.0 + s_floor)
    f0 = value(q0, idx)
    q_hi = np.full(y0.size, 1.0 - 1e-12)
    f1 = value(q_hi, idx)
    out = np.full(y0.size, np.nan)
    # a target met at s* = 0 to rounding (the ends of the arc are catenoids) is met there
    out[(f0 < 0) & (f0 >= -1e-12 * np.maximum(np.abs(target), 1e-3))] = 0.0
    k = np.flatnonzero((f0 >= 0) & (f1 <= 0))
    if k.size:
        q = illinois(
            lambda x, i: value(x, k[i]),
            q0[k],
            q_hi[k],
            f0[k],
            f1[k],
            ftol=1e-3 * VERIFY_RTOL * np.maximum(np.abs(target[k]), 1e-3 if field == "gap" else 0.0),
        )
        out[k] = q / (1.0 - q) / (y0[k] * y0[k])
    return out


def _arc(y0, th, rho, th2, D, field="volume"):
    """Volume (or another field) of the bridge with neck y0 at gap D; NaN where none."""
    s = _suction_at_neck(y0, th, rho, th2, D, "gap")
    ok = np.isfinite(s)
    out = np.full(y0.size, np.nan)
    if ok.any():
        out[ok] = getattr(_from_neck(y0[ok], th[ok], s[ok], rho[ok], th2[ok])[1], field)
    return out, s


_NECK_GRID = np.geomspace(1e-7, 1.0, 48)  # necks in units of R1


def _neck_grid(th, rho, th2):
    """Grid of necks with the largest bridge of each (see :func:`_catenoid`)."""
    y = np.tile(_NECK_GRID, (th.size, 1))
    return y, _catenoid(y, th[:, None], rho[:, None], th2[:, None])


_SUCTION_GRID = np.geomspace(1e-4, 1.0, 8)  # filling angles of the bracketing scan, in units of the last one


def _fold_scan(th, s, D, rho, th2):
    """Scan of gap*(beta) at fixed s* down a grid of filling angles, from the last concave bridge.

    At fixed suction the gap rises from 0 to a maximum (the rupture gap at this
    suction) and falls (Lian et al. 1993). Scanning down from the largest
    filling angle, the first grid point whose gap reaches D* is the last one
    on the grid (the bracket of the stable root lies just above it); a row
    whose gap falls again before reaching D* has passed the maximum, and every
    smaller filling angle has a smaller gap: its scan stops there. Rows leave
    the scan as they are settled, so most rows need two to four of the eight
    points. Returns (grid, Dg, last, peak): the grid [rad], the coarse gaps
    (-inf where not evaluated, -1e300 where no bridge), the index of the last
    grid point with gap >= D* (-1: none) and of the grid maximum.
    """
    m, ng = th.size, _SUCTION_GRID.size
    b_end = 0.5 * (np.pi - np.arctan2(np.sin(th), np.cos(th) + 0.5 * s))
    grid = b_end[:, None] * _SUCTION_GRID[None, :]
    Dg = np.full((m, ng), -np.inf)
    last = np.full(m, -1)
    peak = np.full(m, -1)
    live = np.arange(m)
    for j in range(ng - 1, -1, -1):
        if live.size == 0:
            break
        v = _below(_gap(grid[live, j], th[live], s[live], rho[live], th2[live], coarse=True))
        Dg[live, j] = v
        up = v >= D[live]
        last[live[up]] = j
        stop = up
        if j < ng - 1:
            prev = Dg[live, j + 1]
            down = ~up & (v < prev) & (prev > -1e299)  # past the maximum, going down
            peak[live[down]] = j + 1
            stop = up | down
        live = live[~stop]
    r = np.arange(m)
    no_peak = (last < 0) & (peak < 0)  # scanned to the bottom of the grid without passing a maximum
    peak[no_peak] = np.argmax(Dg[no_peak], axis=1)
    return grid, Dg, last, np.where(last < 0, peak, -1), r


def _chandrupatla(f, a, b, f_a, f_b, ftol, xtol=1e-14, iters=100):
    """Vectorised root of f on brackets [a, b] with f(a), f(b) of opposite signs (Chandrupatla 1997).

    Inverse quadratic interpolation through the last three points where it is
    safe, bisection otherwise; the root stays bracketed. Stops when |f| <=
    ``ftol`` (per row) or the bracket is ``xtol`` (relative) narrow, and
    returns the end of the final bracket with the smaller |f|.
    Chandrupatla, T. R. (1997). A new hybrid quadratic/bisection algorithm for finding the zero of a nonlinear
    function without using derivatives. Adv. Eng. Softw. 28, 145-149. doi:10.1016/S0965-9978(96)00051-8
    """
    a, b, f_a, f_b = (np.array(v, dtype=float) for v in (a, b, f_a, f_b))
    c, f_c = a.copy(), f_a.copy()
    t = np.full(a.size, 0.5)
    x = np.where(np.abs(f_a) < np.abs(f_b), a, b)
    active = np.ones(a.size, dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(iters):
            k = np.flatnonzero(active)
            if k.size == 0:
                break
            ak, bk, fak, fbk = a[k], b[k], f_a[k], f_b[k]
            xt = ak + t[k] * (bk - ak)
            ft = f(xt, k)
            same = np.signbit(ft) == np.signbit(fak)
            ck, fck = np.where(same, ak, bk), np.where(same, fak, fbk)
            bk, fbk = np.where(same, bk, ak), np.where(same, fbk, fak)
            ak, fak = xt, ft
            a[k], f_a[k], b[k], f_b[k], c[k], f_c[k] = ak, fak, bk, fbk, ck, fck
            better = np.abs(fak) < np.abs(fbk)
            xm, fm = np.where(better, ak, bk), np.where(better, fak, fbk)
            x[k] = xm
            tl = 2.0 * xtol * np.maximum(np.abs(xm), 1e-300) / np.abs(bk - ck)
            done = (tl > 0.5) | (np.abs(fm) <= ftol[k]) | ~np.isfinite(tl)
            xi = (ak - bk) / (ck - bk)
            phi = (fak - fbk) / (fck - fbk)
            iqi = (phi * phi < xi) & ((1.0 - phi) ** 2 < 1.0 - xi)
            tq = fak / (fbk - fak) * fck / (fbk - fck) + (ck - ak) / (bk - ak) * fak / (fck - fak) * fbk / (fck - fbk)
            tn = np.where(iqi & np.isfinite(tq), tq, 0.5)
            t[k] = np.clip(tn, np.minimum(tl, 0.5), np.maximum(1.0 - tl, 0.5))
            active[k[done]] = False
    return x


def _solve_for_suction(theta, suction, gap, ratio, theta2):
    """Stable bridge (larger filling angle) at given s*, gap*: (beta, status)."""
    theta, suction, gap, ratio, theta2 = (x.ravel() for x in _arr(theta, suction, gap, ratio, theta2))
    n = theta.size
    beta = np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < HALF_PI) & (suction >= 0) & (gap >= 0) & (ratio > 0) & np.isfinite(suction)
    ok &= (theta2 >= 0) & (theta2 < HALF_PI)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, status
    th, s, D, rho, th2 = theta[k], suction[k], gap[k], ratio[k], theta2[k]
    grid, Dg, last, peak, r = _fold_scan(th, s, D, rho, th2)
    ng = grid.shape[1]
    top = last == ng - 1  # the gap is above D* up to the last concave bridge: too much water at this suction
    has = (last >= 0) & ~top
    lj = np.clip(last, 0, ng - 2)
    lo, hi = grid[r, lj], grid[r, lj + 1]
    f_lo, f_hi = Dg[r, lj] - D, Dg[r, lj + 1] - D
    nob = np.flatnonzero(last < 0)  # no grid point reaches D*: is the maximum between grid points above it?
    if nob.size:
        # five points around the grid maximum, half a grid step apart (the two new ones coarse too)
        j = peak[nob]
        h = np.sqrt(_SUCTION_GRID[1] / _SUCTION_GRID[0])
        b_mid = grid[nob, j]
        pts = np.minimum(b_mid[:, None] * h ** np.arange(-2.0, 3.0), grid[nob, -1:])
        val = np.full(pts.shape, -np.inf)
        val[:, 2] = Dg[nob, j]
        val[:, 0] = np.where(j >= 1, Dg[nob, np.maximum(j - 1, 0)], -np.inf)
        val[:, 4] = np.where(j <= ng - 2, Dg[nob, np.minimum(j + 1, ng - 1)], -np.inf)
        mids = _below(_gap(pts[:, [1, 3]], th[nob, None], s[nob, None], rho[nob, None], th2[nob, None], coarse=True))
        val[:, 1], val[:, 3] = mids[:, 0], mids[:, 1]
        best = np.clip(np.argmax(val, axis=1), 1, 3)
        rr = np.arange(nob.size)
        vmax = val[rr, best]
        # rows whose five-point maximum is below half the gap are beyond rupture: over 60,000 random pairs
        # (theta 0-89 deg, s* 1e-6-1e8, rho 0.01-100 and planes, wherever the grid meets a bridge) it was never
        # below 0.59 of the true maximum (0.77 for rho >= 0.1)
        miss = nob[vmax >= 0.5 * D[nob]]
        sel = vmax >= 0.5 * D[nob]
        a, c = pts[rr[sel], best[sel] - 1], pts[rr[sel], best[sel] + 1]
    else:
        miss = nob
    if miss.size:  # refine the maximum by golden sections (unimodal between a and c)
        thm, sm, rhom, th2m, Dm = th[miss], s[miss], rho[miss], th2[miss], D[miss]
        bp, dp = golden(lambda x, i: _gap(x, thm[i], sm[i], rhom[i], th2m[i], coarse=True), a, c, iters=12)
        # 12 steps leave the bracket at 0.3 % of its width: the maximum is then known to about 1e-4 relative;
        # rows within 1 % of the gap are refined to 25 steps with the full quadrature, the rest are settled
        close = np.flatnonzero((dp >= 0.99 * Dm) & (dp < 1.01 * Dm))
        if close.size:
            bp[close], dp[close] = golden(
                lambda x, i: _gap(x, thm[close][i], sm[close][i], rhom[close][i], th2m[close][i]),
                a[close],
                c[close],
                iters=25,
            )
        found = dp >= Dm
        has[miss[found]] = True
        lo[miss], f_lo[miss] = bp, dp - Dm
        hi[miss] = c
        f_hi[miss] = _below(_gap(c, thm, sm, rhom, th2m)) - Dm
    good = np.flatnonzero(has)
    thg, sg, Dgd, rhog, th2g = th[good], s[good], D[good], rho[good], th2[good]
    root = _chandrupatla(
        lambda x, i: _below(_gap(x, thg[i], sg[i], rhog[i], th2g[i])) - Dgd[i],
        lo[good],
        hi[good],
        f_lo[good],
        f_hi[good],
        ftol=1e-3 * VERIFY_RTOL * np.maximum(Dgd, 1e-3),
    )
    beta[k[good]] = root
    status[k] = np.where(has, 0, np.where(top, 3, 1))
    return beta, status


def _log_root(f, lo, hi):
    """Root of an increasing-or-decreasing f between necks lo < hi (bracketed), searched in log(neck).

    The bracket end on the side f >= 0 is returned.
    """
    a, c = np.log(lo), np.log(hi)
    fa, fc = f(a, np.arange(a.size)), f(c, np.arange(a.size))
    flip = fa < fc  # Illinois wants f(lo) >= 0 >= f(hi)
    sign = np.where(flip, -1.0, 1.0)
    _, lo_end, hi_end = illinois(lambda x, i: sign[i] * f(x, i), a, c, sign * fa, sign * fc, ends=True)
    # the end where f >= 0: inside the family even when the "root" is where the bridges stop existing
    return np.exp(np.where(flip, hi_end, lo_end))


def _scan_for_volume(theta, volume, gap, ratio, theta2, branch="stable"):
    """(beta, s*, status) of the bridge holding volume* at gap*, stable at constant volume, by a scan of the arc.

    ``branch="thin"``: the other bridge of the same volume and gap, on the thin-neck side of the volume's minimum
    (between the thinnest catenoid spanning the gap and the rupture bridge); status 1 where there is none (at
    contact, or a volume above the thinnest catenoid's). ``branch="exists"``: status 0 where that bridge exists
    (for a volume the stable branch holds: V at most the thinnest catenoid's volume, D > 0), without solving it.

    The fallback of :func:`_solve_for_volume` for the rows its Newton iteration
    does not settle (no bridge, too much water, bridges next to rupture). At a fixed gap the
    concave bridges form one arc, parametrised by the neck
    radius y0 (units of R1): from the largest (the catenoid, s* = 0, at the
    top neck) through the suction-controlled fold to the thinnest catenoid. Along
    it the volume falls from its largest value to a minimum (the rupture volume
    of this gap) and then rises again. The bridge returned is the first one of
    the requested volume met from the top, i.e. the one continuous with the
    bridge at contact when the spheres are pulled apart at constant volume.
    """
    theta, volume, gap, ratio, theta2 = (x.ravel() for x in _arr(theta, volume, gap, ratio, theta2))
    n = theta.size
    beta, suction = np.full(n, np.nan), np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < HALF_PI) & (volume > 0) & (gap >= 0) & (ratio > 0) & np.isfinite(volume)
    ok &= (theta2 >= 0) & (theta2 < HALF_PI)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, suction, status
    th, V, D, rho, th2 = theta[k], volume[k], gap[k], ratio[k], theta2[k]
    m = k.size
    st = np.full(m, 1)
    y, cat = _neck_grid(th, rho, th2)
    gcat = _below(cat.gap)
    # no concave bridge at any gap holds more than the largest catenoid volume (the test rupture_gap uses too)
    too_much = V > np.nanmax(np.where(np.isfinite(cat.volume), cat.volume, -np.inf), axis=1)
    span = gcat >= D[:, None]
    r = np.arange(m)
    # peak of the catenoid gap, refined (a narrow peak can hide between grid necks)
    j = np.argmax(gcat, axis=1)
    lo_j, hi_j = np.maximum(j - 1, 0), np.minimum(j + 1, y.shape[1] - 1)
    ypk, gpk = golden(
        lambda x, i: _catenoid_gap(np.exp(x), th[i], rho[i], th2[i]), np.log(y[r, lo_j]), np.log(y[r, hi_j])
    )
    ypk = np.exp(ypk)
    reach = np.flatnonzero(gpk >= D)

    def cat_gap(x, i, sel):
        return _below(_catenoid_gap(np.exp(x), th[sel][i], rho[sel][i], th2[sel][i])) - D[sel][i]

    y_lo, y_hi = np.full(m, np.nan), np.full(m, np.nan)
    if reach.size:
        # top neck: the catenoid gap falls through D above the peak
        # (or, where it never does, at the edge of the bridges: a plane at small theta)
        cols = np.arange(y.shape[1])
        above = y[reach] > ypk[reach, None]
        last = np.where(span[reach] & above, cols, -1).max(axis=1)  # last spanning neck above the peak
        first = np.where(above, cols, y.shape[1] - 1).min(axis=1)  # first neck above the peak
        a = np.where(last >= 0, y[reach, np.maximum(last, 0)], ypk[reach])
        c = np.where(last >= 0, y[reach, np.minimum(last + 1, y.shape[1] - 1)], y[reach, first])
        c = np.where(c > a, c, a * (1 + 1e-9))
        y_hi[reach] = _log_root(lambda x, i: cat_gap(x, i, reach), a, c)
        rising = reach[D[reach] > 0]
        y_lo[reach[D[reach] == 0]] = _NECK_GRID[0]
        if rising.size:
            first = np.argmax(span[rising], axis=1)
            a = y[rising, np.maximum(first - 1, 0)]
            c = np.minimum(y[rising, first], ypk[rising])
            y_lo[rising] = _log_root(lambda x, i: cat_gap(x, i, rising), a, c)
    has = np.flatnonzero(np.isfinite(y_hi) & np.isfinite(y_lo))
    if branch == "exists":  # a thin-neck bridge of V at D exists iff V is at most the thinnest catenoid's volume
        apart = has[D[has] > 0]
        v_lo = _catenoid(y_lo[apart], th[apart], rho[apart], th2[apart]).volume
        st[:] = 1
        st[apart[V[apart] <= v_lo]] = 0
        status[k] = st
        return beta, suction, status
    v_top = np.full(m, np.nan)
    if has.size:
        v_top[has] = _catenoid(y_hi[has], th[has], rho[has], th2[has]).volume
        st[has] = np.where(V[has] > v_top[has] * (1 + 1e-12), 3, 1)
        cand = has[V[has] <= v_top[has] * (1 + 1e-12)]
    else:
        cand = has
    if cand.size:
        # at contact the volume rises with the neck from 0; at a gap it has one minimum (the rupture volume of
        # the gap), located on a grid of necks and refined
        y_min, v_min = y_lo[cand].copy(), np.zeros(cand.size)
        apart = np.flatnonzero(D[cand] > 0)
        if apart.size:
            sub = cand[apart]
            nk = 24
            frac = np.linspace(0.0, 1.0, nk)
            yg = np.exp(np.log(y_lo[sub])[:, None] + frac * np.log(y_hi[sub] / y_lo[sub])[:, None])
            rep = np.repeat(sub, nk)
            Vg = _arc(yg.ravel(), th[rep], rho[rep], th2[rep], D[rep])[0].reshape(sub.size, nk)
            jm = np.argmin(np.where(np.isfinite(Vg), Vg, np.inf), axis=1)
            rr = np.arange(sub.size)
            a = np.log(yg[rr, np.maximum(jm - 1, 0)])
            c = np.log(yg[rr, np.minimum(jm + 1, nk - 1)])
            x_min, v_sub = golden(
                lambda x, i: _arc(np.exp(x), th[sub][i], rho[sub][i], th2[sub][i], D[sub][i])[0],
                a,
                c,
                iters=40,
                sign=-1.0,
            )
            y_min[apart], v_min[apart] = np.exp(x_min), v_sub
        inside = V[cand] >= v_min
        if branch == "thin":
            # the thin-neck side: from the thinnest catenoid spanning the gap (y_lo) up to the rupture bridge
            # (y_min); the volume falls along it from the catenoid's to the minimum
            apart_rows = D[cand] > 0
            v_lo = np.full(cand.size, np.nan)
            if apart_rows.any():
                sub = cand[apart_rows]
                v_lo[apart_rows] = _catenoid(y_lo[sub], th[sub], rho[sub], th2[sub]).volume
            thin = apart_rows & (V[cand] > v_min) & (V[cand] <= v_lo)
            go = cand[thin]
            if go.size:

                def g(x, i):
                    return _below(_arc(np.exp(x), th[go][i], rho[go][i], th2[go][i], D[go][i])[0]) - V[go][i]

                lo, hi = np.log(y_lo[go]), np.log(y_min[thin])
                root = np.exp(
                    illinois(g, lo, hi, v_lo[thin] - V[go], v_min[thin] - V[go], ftol=1e-3 * VERIFY_RTOL * V[go])
                )
                s = _suction_at_neck(root, th[go], rho[go], th2[go], D[go], "gap")
                b1 = _from_neck(root, th[go], np.where(np.isfinite(s), s, 0.0), rho[go], th2[go])[0]
                beta[k[go]], suction[k[go]] = b1, s
                st[go] = 0
            st[cand[~thin]] = np.where(st[cand[~thin]] == 3, 3, 1)
            status[k] = st
            return beta, suction, status
        go = cand[inside]
        if go.size:

            def f(x, i):
                return _below(_arc(np.exp(x), th[go][i], rho[go][i], th2[go][i], D[go][i])[0]) - V[go][i]

            sel = inside
            lo, hi = np.log(y_min[sel]), np.log(y_hi[go])
            root = np.exp(
                illinois(
                    lambda x, i: -f(x, i),
                    lo,
                    hi,
                    -f(lo, np.arange(go.size)),
                    V[go] - v_top[go],
                    ftol=1e-3 * VERIFY_RTOL * V[go],
                )
            )
            s = _suction_at_neck(root, th[go], rho[go], th2[go], D[go], "gap")
            b1 = _from_neck(root, th[go], np.where(np.isfinite(s), s, 0.0), rho[go], th2[go])[0]
            beta[k[go]], suction[k[go]] = b1, s
            st[go] = 0
    st[(st == 1) & too_much] = 3
    status[k] = st
    return beta, suction, status


# ---- volume control: Newton on the arc ---------------------------------------------

_FD_STEP = 1e-7  # forward-difference step in log(neck) and log(s*) (derivatives to about 1e-7 relative)
_ARC_MARGIN = 1e-5  # smallest relative slope of the volume along the arc that certifies the branch


def _gap_volume_at_neck(x, z, th, rho, th2):
    """(gap*, volume*) of the bridge with neck exp(x) at s* = exp(z); NaN where there is none."""
    y0, s = np.exp(x), np.exp(z)
    F = 2.0 * y0 + s * y0 * y0
    beta = _second_filling_angle(F, th, s, np.ones_like(F))
    return _blocks(beta, th, s, rho, 2, th2, full="gap volume")


def _volume_guess(th, V, D, rho, th2):
    """Starting (log neck, log s*) of the bridge holding V* at gap* D*: a thin film between paraboloids.

    The surfaces near the axis are h(r) = D + r^2 / R* apart (Derjaguin's
    R* = 2 rho / (1 + rho), 2 for a plane); the film of volume V wets a disc
    of radius a with pi (D a^2 + a^4 / (2 R*)) = V; its meridian is a circle
    of radius r1 meeting both surfaces at theta (tilted by their filling
    angles), and s* = 1 / r1 - 1 / y0 (toroidal approximation).
    """
    Rs = np.where(np.isinf(rho), 2.0, 2.0 * rho / (1.0 + np.where(np.isinf(rho), 1.0, rho)))
    a2 = Rs * (np.sqrt(D * D + 2.0 * V / (np.pi * Rs)) - D)
    a = np.sqrt(a2)
    b1 = np.arcsin(np.minimum(a, 1.0))
    b2 = np.where(np.isinf(rho), 0.0, np.arcsin(np.minimum(a / rho, 1.0)))
    r1 = (D + a2 / Rs) / np.maximum(np.cos(th + b1) + np.cos(th2 + b2), 0.05)
    y0 = np.maximum(a - r1 * (1.0 - np.sin(th + b1)), 0.2 * a)
    s = np.maximum(1.0 / r1 - 1.0 / y0, 0.1 / y0)
    return np.log(y0), np.log(s)


def _newton_volume(th, V, D, rho, th2, iters=40, start=None, loose=False):
    """(neck, s*, found) of the bridge holding V* at gap* D*: damped Newton in (log neck, log s*).

    Residuals gap - D and log(volume / V), a forward-difference Jacobian, a
    backtracking line search on their scaled norm. ``found`` rows converged
    (residuals 1e-12 relative, or at the rounding floor within 1e-11) to a
    bridge with s* > 0 on the part of the arc of gap D that the volume
    descends from its top: there the volume along the arc rises with the
    neck (by at least _ARC_MARGIN relative), which, the volume having a single
    minimum on the arc, makes it the bridge :func:`_scan_for_volume` returns.
    The other rows are left to that scan. ``start``: (neck, s*) to start from
    instead of :func:`_volume_guess`; ``loose``: stop at 1e-6 (a stage of a
    continuation, see :func:`_continue_volume`).
    """
    m = th.size
    h = _FD_STEP
    x, z = _volume_guess(th, V, D, rho, th2) if start is None else (np.log(start[0]), np.log(start[1]))
    lv = np.log(V)
    gscale = D + np.cbrt(V)  # length scale of a bridge of volume V (its rupture distance, Lian et al. 1993)
    gtol = 1e-3 * VERIFY_RTOL * np.maximum(D, 1e-3)
    state = np.zeros(m, dtype=int)  # 0 looking for a start, 1 iterating, 2 converged, 3 given up
    xa, za = x.copy(), z.copy()  # last accepted point
    phi = np.full(m, np.inf)
    dx, dz, t = np.zeros(m), np.zeros(m), np.ones(m)
    starts = np.zeros(m, dtype=int)
    slope = np.full(m, np.nan)
    Gz_at = np.full(m, np.nan)
    for _ in range(iters):
        a = np.flatnonzero(state < 2)
        if a.size == 0:
            break
        with np.errstate(all="ignore"):
            g, v = _gap_volume_at_neck(
                np.concatenate([x[a], x[a] + h, x[a]]),
                np.concatenate([z[a], z[a], z[a] + h]),
                np.tile(th[a], 3),
                np.tile(rho[a], 3),
                np.tile(th2[a], 3),
            )
            g, lg = g.reshape(3, -1), np.log(v).reshape(3, -1)
            r1, r2 = g[0] - D[a], lg[0] - lv[a]
            ph = np.hypot(r1 / gscale[a], r2)
            Gx, Gz = (g[1] - g[0]) / h, (g[2] - g[0]) / h
            Lx, Lz = (lg[1] - lg[0]) / h, (lg[2] - lg[0]) / h
            det = Gx * Lz - Gz * Lx
        fin = np.isfinite(ph) & np.isfinite(det) & (det != 0)
        st = state[a]
        # no bridge at the start (or the line search failed): a thinner neck, a lower suction, at most 8 times
        b = a[(st == 0) & ~fin]
        x[b], z[b] = x[b] - 0.15, z[b] - 0.7
        starts[b] += 1
        state[b[starts[b] > 8]] = 3
        acc = fin & ((st == 0) | (ph < (1.0 - 1e-4 * t[a]) * phi[a]))
        b = a[(st == 1) & ~acc]
        t[b] *= 0.5
        lost = b[t[b] < 1e-5]
        starts[lost] += 3
        state[lost] = np.where(starts[lost] > 8, 3, 0)
        x[lost], z[lost] = xa[lost] - 0.1, za[lost]
        b = b[t[b] >= 1e-5]
        x[b], z[b] = xa[b] + t[b] * dx[b], za[b] + t[b] * dz[b]
        b = a[acc]
        r1, r2, Gx, Gz, Lx, Lz, det = (q[acc] for q in (r1, r2, Gx, Gz, Lx, Lz, det))
        ddx = (Gz * r2 - Lz * r1) / det
        ddz = (Lx * r1 - Gx * r2) / det
        if loose:
            conv = (np.abs(r1) <= 1e-6 * gscale[b]) & (np.abs(r2) <= 1e-6)
        else:
            conv = (np.abs(r1) <= gtol[b]) & (np.abs(r2) <= 1e-12)
        conv |= (np.abs(r1) <= 10 * gtol[b]) & (np.abs(r2) <= 1e-11) & (np.abs(ddx) + np.abs(ddz) <= 1e-12)
        state[b] = np.where(conv, 2, 1)
        xa[b], za[b], phi[b] = x[b], z[b], ph[acc]
        # slope of log(volume) along the arc of constant gap, per unit log(neck), and its scale; where Gz = 0 (the
        # gap flat in suction) it is not finite, and such a row is not found (found needs Gz < 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            slope[b] = (Lx * Gz - Lz * Gx) / Gz / (np.abs(Lx) + np.abs(Lz * Gx / Gz))
        Gz_at[b] = Gz
        cap = 1.0 / np.maximum(1.0, np.maximum(np.abs(ddx), np.abs(ddz)))  # at most a factor e per step
        dx[b], dz[b], t[b] = ddx * cap, ddz * cap, 1.0
        x[b], z[b] = x[b] + dx[b], z[b] + dz[b]
    y0, s = np.exp(xa), np.exp(za)
    # s* y0^2 >= 1e-8: clear of the floor suction of _floor_suction (a plane at theta = 0)
    found = (state == 2) & (Gz_at < 0) & (slope > _ARC_MARGIN) & (s * y0 * y0 >= 1e-8)
    return y0, s, found


def _continue_volume(th, V, D, rho, th2, stages=8, factor=0.5):
    """:func:`_newton_volume` by continuation, for rows it does not settle from its guess (large bridges).

    From (V, D) scaled by factor^stages, where the thin-film guess holds (and D / V^(1/3), the gap over the rupture
    distance, is smaller still), back to (V, D), each stage starting from the bridge of the last.
    """
    y0, s = np.exp(_volume_guess(th, V * factor**stages, D * factor**stages, rho, th2))
    alive = np.ones(th.size, dtype=bool)
    for j in range(stages - 1, -1, -1):
        a = np.flatnonzero(alive)
        if a.size == 0:
            break
        f = factor**j
        y0[a], s[a], found = _newton_volume(th[a], V[a] * f, D[a] * f, rho[a], th2[a], start=(y0[a], s[a]), loose=j > 0)
        alive[a[~found]] = False
    return y0, s, alive


def _beyond_rupture(th, V, D, rho, th2):
    """Rows whose volume V* cannot span the gap D* at all, settled for all rows at once (True: no bridge).

    The liquid between the axis and the neck radius y0 (the narrowest radius of the bridge, or less when the
    neck is virtual) spans at least the gap, so V* >= pi y0^2 D*: every bridge of the row has
    y0 <= y_b = sqrt(V* / (pi D*)). At a fixed neck the gap falls as s* rises (see :func:`suction_at_neck`),
    so no bridge of neck y0 spans more than its catenoid (:func:`_catenoid_gap`); the catenoid gap rises with
    the neck up to its peak and falls after. Where it still rises at y_b and is below D* there, no neck
    y0 <= y_b reaches D*: beyond rupture. A row is settled only when some catenoid of the upper necks of
    _NECK_GRID holds at least V* (so that "too much water", V* above every catenoid of the grid, cannot apply,
    as in :func:`_scan_for_volume`); the rest is left to the solver.
    """
    out = np.zeros(th.size, dtype=bool)
    cand = np.flatnonzero(D > 0)
    if cand.size == 0:
        return out
    yb = np.sqrt(V[cand] / (np.pi * D[cand]))
    g = _catenoid_gap(
        np.concatenate([yb, yb * (1.0 + 1e-3)]), np.tile(th[cand], 2), np.tile(rho[cand], 2), np.tile(th2[cand], 2)
    )
    g0, g1 = g[: cand.size], g[cand.size :]
    with np.errstate(invalid="ignore"):
        cand = cand[np.isfinite(g0) & np.isfinite(g1) & (g1 > g0) & (g0 < D[cand] * (1.0 - 1e-9))]
    if cand.size:
        necks = _NECK_GRID[-12:]
        vol = _catenoid(np.tile(necks, (cand.size, 1)), th[cand, None], rho[cand, None], th2[cand, None]).volume
        out[cand] = V[cand] <= np.max(np.where(np.isfinite(vol), vol, -np.inf), axis=1)
    return out


def _solve_for_volume(theta, volume, gap, ratio, theta2):
    """(beta, s*, status) of the bridge holding volume* at gap*, stable at constant volume.

    At a fixed gap the concave bridges form one arc, parametrised by the neck
    radius y0 (units of R1): from the largest (the catenoid, s* = 0, at the
    top neck) through the suction-controlled fold to the thinnest catenoid. Along
    it the volume falls from its largest value to a minimum (the rupture volume
    of this gap) and then rises again. The bridge returned is the first one of
    the requested volume met from the top, i.e. the one continuous with the
    bridge at contact when the spheres are pulled apart at constant volume.
    Newton's method (:func:`_newton_volume`) settles most rows in a few
    iterations; the rest go through the scan of the arc (:func:`_scan_for_volume`).
    """
    theta, volume, gap, ratio, theta2 = (x.ravel() for x in _arr(theta, volume, gap, ratio, theta2))
    n = theta.size
    beta, suction = np.full(n, np.nan), np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < HALF_PI) & (volume > 0) & (gap >= 0) & (ratio > 0) & np.isfinite(volume)
    ok &= (theta2 >= 0) & (theta2 < HALF_PI)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, suction, status
    far = _beyond_rupture(theta[k], volume[k], gap[k], ratio[k], theta2[k])
    status[k[far]] = 1
    k = k[~far]
    th, V, D, rho, th2 = theta[k], volume[k], gap[k], ratio[k], theta2[k]
    for start in range(0, k.size, _CHUNK):
        sl = slice(start, start + _CHUNK)
        y0, s, found = _newton_volume(th[sl], V[sl], D[sl], rho[sl], th2[sl])
        rows = k[sl][found]
        yf, sf = y0[found], s[found]
        beta[rows] = _second_filling_angle(2.0 * yf + sf * yf * yf, th[sl][found], sf, np.ones_like(yf))
        suction[rows], status[rows] = s[found], 0
    rest = k[status[k] != 0]
    big = rest[volume[rest] > 0.05]  # where the thin-film guess is poor: continuation from a small bridge
    if big.size:
        y0, s, found = _continue_volume(theta[big], volume[big], gap[big], ratio[big], theta2[big])
        yf, sf, rows = y0[found], s[found], big[found]
        beta[rows] = _second_filling_angle(2.0 * yf + sf * yf * yf, theta[rows], sf, np.ones_like(yf))
        suction[rows], status[rows] = sf, 0
        rest = k[status[k] != 0]
    if rest.size:
        beta[rest], suction[rest], status[rest] = _scan_for_volume(
            theta[rest], volume[rest], gap[rest], ratio[rest], theta2[rest]
        )
    return beta, suction, status


def _rupture(theta, volume, ratio, theta2):
    """(gap*, beta, s*, status) of the widest bridge holding volume* (rupture at constant volume)."""
    theta, volume, ratio, theta2 = (x.ravel() for x in _arr(theta, volume, ratio, theta2))
    n = theta.size
    out = [np.full(n, np.nan) for _ in range(3)]
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < HALF_PI) & (volume > 0) & (ratio > 0) & np.isfinite(volume)
    ok &= (theta2 >= 0) & (theta2 < HALF_PI)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return (*out, status)
    th, V, rho, th2 = theta[k], volume[k], ratio[k], theta2[k]
    m = k.size

    def gap_at(x, i):
        y0 = np.exp(x)
        s = _suction_at_neck(y0, th[i], rho[i], th2[i], V[i], "volume")
        return _from_neck(y0, th[i], np.where(np.isfinite(s), s, np.nan), rho[i], th2[i])[1].gap

    ng = _NECK_GRID.size
    rep = np.repeat(np.arange(m), ng)
    G = _below(gap_at(np.tile(np.log(_NECK_GRID), m), rep).reshape(m, ng))
    j = np.argmax(G, axis=1)
    found = np.isfinite(G[np.arange(m), j])
    a = np.log(_NECK_GRID[np.maximum(j - 1, 0)])
    c = np.log(_NECK_GRID[np.minimum(j + 1, ng - 1)])
    x, g = golden(gap_at, a, c)
    g_grid = G[np.arange(m), j]
    worse = ~(np.isfinite(g) & (g >= g_grid))  # the refinement failed (an edge of the bridges): keep the grid's
    x, g = np.where(worse, np.log(_NECK_GRID[j]), x), np.where(worse, g_grid, g)
    y0 = np.exp(x)
    s = _suction_at_neck(y0, th, rho, th2, V, "volume")
    b1 = _from_neck(y0, th, s, rho, th2)[0]
    good = found & np.isfinite(g) & (g >= 0)
    for o, v in zip(out, (g, b1, s)):
        o[k[good]] = v[good]
    status[k] = np.where(good, 0, 3)
    return (*out, status)


# ---- verified solvers ------------------------------------------------------------


def _verify(status, beta, theta, s, ratio, theta2, gap=None, volume=None, found=None):
    """Status 4 for every 'ok' row whose bridge does not reproduce the requested gap or volume.

    The gap to absolute 1e-12 near contact, the volume to VERIFY_RTOL relative. ``found``: the bridges already computed
    (a Bridge).
    """
    status = status.copy()
    ok = status == 0
    if not ok.any():
        return status
    if found is not None:
        g, v = found.gap, found.volume
    elif volume is None:  # the gap alone (the fast path, same quadrature accuracy)
        g, v = _gap(np.where(ok, beta, np.nan), theta, np.where(ok, s, 0.0), ratio, theta2), None
    else:
        b = _bridge(np.where(ok, beta, np.nan), theta, np.where(ok, s, 0.0), ratio, theta2)
        g, v = b.gap, b.volume
    good = np.isfinite(g)
    with np.errstate(invalid="ignore"):
        if gap is not None:
            good &= np.abs(g - gap) <= VERIFY_RTOL * np.maximum(np.abs(gap), 1e-3)
        if volume is not None:
            good &= np.abs(v - volume) <= VERIFY_RTOL * np.abs(volume)
    status[ok & ~good] = 4
    return status


def _angles(theta, theta2, *others):
    """(theta, *others, theta2) broadcast and flattened; theta2 None: a copy of theta's values (equal angles)."""
    cols = [x.ravel() for x in _arr(theta, *others, theta if theta2 is None else theta2)]
    return cols


def solve_for_suction(contact_angle_rad, suction, gap, ratio=1.0, contact_angle2_rad=None):
    r"""Filling angle of the stable bridge at a given suction and gap (suction control), verified.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    suction : float or array_like
        s* = Delta_u R1 / gamma [-].
    gap : float or array_like
        D / R1 [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 (sphere or plane) [rad]; default: ``contact_angle_rad``. Each contact line
        meets its solid at its own angle.

    Returns
    -------
    beta : numpy.ndarray
        Filling angle on particle 1 [rad], 1-D; NaN without a bridge.
    status : numpy.ndarray of int
        0 ok, 1 gap beyond rupture at this suction, 2 invalid input, 3 no
        concave bridge (too much water), 4 no verified bridge.

    Notes
    -----
    At fixed s* the gap :math:`D^*(\beta)` (:func:`gap_of`) rises from 0 to a
    maximum, the rupture gap at that suction, and falls: two bridges fit a
    smaller gap. The one of larger filling angle and volume, continuous with
    the bridge at contact, is stable under suction control [1]_ and is
    returned: the root of :math:`D^*(\beta) = D^*` on the falling side,
    bracketed on a grid and refined by Chandrupatla's method. Every ``ok`` row
    reproduces its gap to VERIFY_RTOL (1e-9 relative, 1e-12 absolute below
    1e-3 R1).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    th, suction, gap, ratio, th2 = _angles(contact_angle_rad, contact_angle2_rad, suction, gap, ratio)
    beta, status = _solve_for_suction(th, suction, gap, ratio, th2)
    return beta, _verify(status, beta, th, suction, ratio, th2, gap=gap)


def bridge_at_suction(contact_angle_rad, suction, gap, ratio=1.0, contact_angle2_rad=None):
    r"""The stable bridge at a given suction and gap, with every field, verified on those fields.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    suction : float or array_like
        s* = Delta_u R1 / gamma [-].
    gap : float or array_like
        D / R1 [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 (sphere or plane) [rad]; default: ``contact_angle_rad``. Each contact line
        meets its solid at its own angle.

    Returns
    -------
    beta : numpy.ndarray
        Filling angle on particle 1 [rad], 1-D; NaN without a bridge.
    status : numpy.ndarray of int
        As :func:`solve_for_suction`.
    bridge : Bridge
        Its fields (:func:`bridge`); NaN where status is not 0.

    Notes
    -----
    :func:`solve_for_suction` followed by :func:`bridge`, the gap check of
    every ``ok`` row made on the bridge returned (its
    :math:`D^* = L_1 + L_2 - (1 - \cos\beta) - \rho (1 - \cos\delta_2)`
    to VERIFY_RTOL) instead of a separate evaluation.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    th, suction, gap, ratio, th2 = _angles(contact_angle_rad, contact_angle2_rad, suction, gap, ratio)
    beta, status = _solve_for_suction(th, suction, gap, ratio, th2)
    ok = status == 0
    b = _bridge(np.where(ok, beta, np.nan), th, np.where(ok, suction, 0.0), ratio, th2)
    status = _verify(status, beta, th, suction, ratio, th2, gap=gap, found=b)
    bad = status != 0
    beta[bad] = np.nan
    for k in _FIELDS:
        getattr(b, k)[bad] = np.nan
    return beta, status, b


def solve_for_volume(contact_angle_rad, volume, gap, ratio=1.0, contact_angle2_rad=None, branch="stable"):
    r"""Filling angle and suction of the bridge holding a given volume at a given gap (volume control), verified.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    volume : float or array_like
        Liquid volume V / R1^3 [-], > 0.
    gap : float or array_like
        D / R1 [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 (sphere or plane) [rad]; default: ``contact_angle_rad``. Each contact line
        meets its solid at its own angle.
    branch : {"stable", "thin"}, default "stable"
        ``stable``: the bridge continuous with the bridge at contact (below). ``thin``: the second bridge of the
        same volume and gap, on the thin-neck side of the volume's minimum along the arc (unstable at constant
        volume); status 1 where there is none (at contact, or a volume above the thinnest catenoid spanning
        the gap).

    Returns
    -------
    beta : numpy.ndarray
        Filling angle on particle 1 [rad], 1-D; NaN without a bridge.
    suction : numpy.ndarray
        s* = Delta_u R1 / gamma [-]; NaN without a bridge.
    status : numpy.ndarray of int
        0 ok, 1 beyond rupture (volume too small to span the gap; with ``branch="thin"``: no thin-neck
        bridge), 2 invalid input, 3 too much water for a concave bridge, 4 no bridge reproduced
        gap and volume to VERIFY_RTOL.

    Notes
    -----
    Solves :math:`D^*(y_0, s^*) = D^*` and :math:`V^*(y_0, s^*) = V^*` for the
    neck y0 and s* (:func:`from_neck`, :func:`bridge`). At a fixed gap the
    concave bridges form one arc from the largest catenoid through the
    suction-controlled fold to the thinnest; the volume falls along it to a
    minimum (the rupture volume of that gap) and rises again. The bridge
    returned is the first of the requested volume met from the top, the one
    continuous with the bridge at contact when the particles are pulled apart
    at constant volume [1]_; near rupture it can lie past the suction fold.

    Most rows are settled by a damped Newton iteration in (ln y0, ln s*) from a
    thin-film estimate, and accepted only when the volume along the arc rises
    with the neck there,

    .. math::

        \left.\frac{d \ln V}{d \ln y_0}\right|_{D}
        = \frac{V_x D_z - V_z D_x}{D_z} > 0 \qquad (x = \ln y_0,\ z = \ln s^*),

    which, the volume having a single minimum on the arc, identifies the
    bridge above; large bridges are followed by continuation from a small
    one, and the remaining rows (no bridge, bridges next to rupture, very
    large bridges) go through a scan of the arc. Every ``ok`` row reproduces
    its gap and volume to VERIFY_RTOL (1e-9).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    .. [2] Orr, F. M., Scriven, L. E. & Rivas, A. P. (1975). Pendular rings between solids: meniscus properties and
       capillary force. J. Fluid Mech. 67, 723-742. doi:10.1017/S0022112075000572
    """
    th, volume, gap, ratio, th2 = _angles(contact_angle_rad, contact_angle2_rad, volume, gap, ratio)
    if branch not in ("stable", "thin"):
        raise ValueError(f"branch must be 'stable' or 'thin' (got {branch!r})")
    if branch == "thin":
        beta, s, status = _scan_for_volume(th, volume, gap, ratio, th2, branch="thin")
    else:
        beta, s, status = _solve_for_volume(th, volume, gap, ratio, th2)
    status = _verify(status, beta, th, s, ratio, th2, gap=gap, volume=volume)
    bad = status != 0
    beta[bad], s[bad] = np.nan, np.nan
    return beta, s, status


def rupture_gap(contact_angle_rad, volume, ratio=1.0, contact_angle2_rad=None):
    r"""Rupture distance at constant volume: the widest gap any bridge of this volume spans, verified.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    volume : float or array_like
        V / R1^3 [-], > 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 (sphere or plane) [rad]; default: ``contact_angle_rad``. Each contact line
        meets its solid at its own angle.

    Returns
    -------
    gap : numpy.ndarray
        Rupture gap D_rupt / R1 [-].
    beta : numpy.ndarray
        Filling angle on particle 1 at rupture [rad].
    suction : numpy.ndarray
        s* at rupture [-].
    status : numpy.ndarray of int
        0 ok, 2 invalid input, 3 no concave bridge holds this volume, 4 not verified.

    Notes
    -----
    :math:`D^*_{rupt}(V^*) = \max_{y_0} D^*(y_0, s^*(y_0, V^*))`: for each neck, the
    suction giving the volume, and the gap maximised over necks (golden
    section after a grid). Compare :func:`lian_rupture_gap`,
    :math:`D^*_{rupt} \approx (1 + \theta/2) V^{*1/3}` for equal spheres [1]_.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452 (rupture distance).
    """
    th, volume, ratio, th2 = _angles(contact_angle_rad, contact_angle2_rad, volume, ratio)
    D, beta, s, status = _rupture(th, volume, ratio, th2)
    status = _verify(status, beta, th, s, ratio, th2, volume=volume)
    bad = status != 0
    D[bad], beta[bad], s[bad] = np.nan, np.nan, np.nan
    return D, beta, s, status


def rupture_gap_at_suction(contact_angle_rad, suction, ratio=1.0, contact_angle2_rad=None):
    r"""Rupture distance at constant suction: the widest gap any bridge spans at this suction.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ on particle 1 [rad].
    suction : float or array_like
        s* = Delta_u R1 / gamma [-], >= 0.
    ratio : float or array_like, default 1.0
        rho = R2 / R1 [-]; ``np.inf`` for a plane.
    contact_angle2_rad : float or array_like, optional
        Contact angle on particle 2 [rad]; default: ``contact_angle_rad``.

    Returns
    -------
    gap : numpy.ndarray
        D_rupt / R1 [-], 1-D; NaN where no concave bridge exists at this suction.
    beta : numpy.ndarray
        Filling angle on particle 1 of the bridge at rupture [rad].

    Notes
    -----
    At fixed s* the gap :math:`D^*(\beta)` (:func:`gap_of`) rises from 0 to a maximum and falls [1]_: the
    maximum is located on a grid of 64 filling angles up to the last concave bridge and refined by 60
    golden-section steps (the bracket then 1e-12 of the grid step: the gap to about 1e-15 relative, the
    maximum being flat). A gap wider than this has no bridge at this suction (status 1 of
    :func:`solve_for_suction`).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    th, s, rho, th2 = _angles(contact_angle_rad, contact_angle2_rad, suction, ratio)
    n = th.size
    gap, beta = np.full(n, np.nan), np.full(n, np.nan)
    k = np.flatnonzero(
        (th >= 0) & (th < HALF_PI) & (th2 >= 0) & (th2 < HALF_PI) & (s >= 0) & np.isfinite(s) & (rho > 0)
    )
    if k.size == 0:
        return gap, beta
    th, s, rho, th2 = th[k], s[k], rho[k], th2[k]
    b_end = 0.5 * (np.pi - np.arctan2(np.sin(th), np.cos(th) + 0.5 * s))
    grid = b_end[:, None] * np.geomspace(1e-4, 1.0, 64)[None, :]
    G = _below(_gap(grid, th[:, None], s[:, None], rho[:, None], th2[:, None]))
    j = np.argmax(G, axis=1)
    r = np.arange(k.size)
    found = G[r, j] > -1e299
    a, c = grid[r, np.maximum(j - 1, 0)], grid[r, np.minimum(j + 1, grid.shape[1] - 1)]
    bx, gx = golden(lambda x, i: _gap(x, th[i], s[i], rho[i], th2[i]), a, c)
    better = np.isfinite(gx) & (gx >= G[r, j])
    gap[k] = np.where(found, np.where(better, gx, G[r, j]), np.nan)
    beta[k] = np.where(found, np.where(better, bx, grid[r, j]), np.nan)
    return gap, beta


def lian_rupture_gap(contact_angle_rad, volume):
    r"""Lian et al. (1993) estimate of the rupture distance of equal spheres.

    Parameters
    ----------
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    volume : float or array_like
        V / R^3 [-].

    Returns
    -------
    numpy.ndarray
        D_rupt / R [-].

    Notes
    -----
    .. math::

        D^*_{rupt} = (1 + \theta / 2)\, V^{*1/3}

    (theta in rad), within about 1 % of the exact rupture gap at theta = 0 for
    V* <= 1e-2 (checked in tests/test_bridge_pairs.py).

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452 (the rupture-distance relation).
    """
    return (1.0 + 0.5 * np.asarray(contact_angle_rad, float)) * np.cbrt(np.asarray(volume, float))


# ---- approximations -------------------------------------------------------


def israelachvili_force(R, surface_tension, contact_angle_rad):
    r"""Capillary force between two equal spheres in contact, small volume limit.

    Parameters
    ----------
    R : float or array_like
        Sphere radius [m] (or any length unit, the force then in that unit times N/m).
    surface_tension : float or array_like
        gamma [N/m].
    contact_angle_rad : float or array_like
        Contact angle θ [rad].

    Returns
    -------
    numpy.ndarray
        F [N].

    Notes
    -----
    .. math::

        F = 2 \pi R \gamma \cos\theta

    the limit of the exact bridge at contact as V -> 0 (Derjaguin
    approximation with R* = R; 4 pi R gamma cos(theta) for a sphere and a plane) [1]_.

    References
    ----------
    .. [1] Israelachvili, J. N. (2011). Intermolecular and Surface Forces, 3rd ed. Academic Press
       (ISBN 978-0-12-391927-4; no DOI)
    """
    return 2.0 * np.pi * np.asarray(R, float) * surface_tension * np.cos(contact_angle_rad)


def willett_force(R, surface_tension, contact_angle_rad, volume, gap):
    r"""Willett et al. (2000) closed form for the capillary force between equal spheres at a gap.

    Parameters
    ----------
    R : float or array_like
        Sphere radius [m].
    surface_tension : float or array_like
        gamma [N/m].
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    volume : float or array_like
        Bridge volume [m^3].
    gap : float or array_like
        Separation D [m].

    Returns
    -------
    numpy.ndarray
        F [N].

    Notes
    -----
    .. math::

        F = \frac{2 \pi R \gamma \cos\theta}{1 + 2.1 S + 10 S^2},
        \qquad S = \frac{D}{2} \sqrt{R / V}

    (their simplified expression for equal spheres) [1]_.

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A. & Seville, J. P. K. (2000). Capillary bridges between two
       spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
    """
    S = 0.5 * np.asarray(gap, float) / np.sqrt(np.asarray(volume, float) / R)
    return israelachvili_force(R, surface_tension, contact_angle_rad) / (1.0 + 2.1 * S + 10.0 * S * S)


def toroidal(beta, contact_angle_rad, gap):
    r"""Toroidal (circle-meridian) approximation of the bridge between equal spheres.

    Parameters
    ----------
    beta : float or array_like
        Filling angle [rad].
    contact_angle_rad : float or array_like
        Contact angle θ [rad].
    gap : float or array_like
        D / R [-].

    Returns
    -------
    suction : numpy.ndarray
        s* = Delta_u R / gamma [-].
    volume : numpy.ndarray
        V / R^3 [-].
    force : numpy.ndarray
        F / (pi gamma R) [-] (gorge method).
    neck : numpy.ndarray
        r0 / R [-].

    Notes
    -----
    .. math::

        r_1 = \frac{1 - \cos\beta + D^*/2}{\cos(\beta + \theta)},\quad
        r_2 = \sin\beta - r_1 (1 - \sin(\beta + \theta)),\quad
        s^* = \frac{1}{r_1} - \frac{1}{r_2},\quad F^* = 2 r_2 + s^* r_2^2

    (meridian radius r1, neck r2); the volume by quadrature of the circular
    profile. A few per cent from the exact bridge at small volume [1]_, [2]_.

    References
    ----------
    .. [1] Fisher, R. A. (1926). On the capillary forces in an ideal soil; correction of formulae given by
       W. B. Haines. J. Agric. Sci. 16, 492-505. doi:10.1017/S0021859600007838
    .. [2] Orr, F. M., Scriven, L. E. & Rivas, A. P. (1975). Pendular rings between solids: meniscus properties and
       capillary force. J. Fluid Mech. 67, 723-742. doi:10.1017/S0022112075000572 (range of the circle approximation).
    """
    beta, th, gap = _arr(beta, contact_angle_rad, gap)
    r1 = (1.0 - np.cos(beta) + 0.5 * gap) / np.cos(beta + th)
    r2 = np.sin(beta) - r1 * (1.0 - np.sin(beta + th))
    s = 1.0 / r1 - 1.0 / r2
    xc = r1 * np.cos(beta + th)
    x = xc[..., None] * _U
    y = (r2 + r1)[..., None] - np.sqrt(r1[..., None] ** 2 - x * x)
    v_under = np.pi * xc * ((y * y) @ _W)
    h = 1.0 - np.cos(beta)
    vol = 2.0 * (v_under - np.pi * h * h * (3.0 - h) / 3.0)
    return s, vol, 2.0 * r2 + s * r2 * r2, r2


def has_thin_bridge(contact_angle_rad, volume, gap, ratio=1.0, contact_angle2_rad=None) -> np.ndarray:
    """Whether a second, thin-neck bridge of this volume exists at this gap (for volumes the stable branch holds).

    Parameters
    ----------
    contact_angle_rad, volume, gap, ratio, contact_angle2_rad
        As :func:`solve_for_volume` (V / R1^3, D / R1).

    Returns
    -------
    numpy.ndarray of bool
        True where the volume is at most that of the thinnest catenoid spanning the gap (D > 0): along the arc
        of bridges at this gap the volume falls to its minimum and rises again to that catenoid, so a volume
        between the two is held twice.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). J. Colloid Interface Sci. 161, 138-147.
       doi:10.1006/jcis.1993.1452
    """
    th, volume, gap, ratio, th2 = _angles(contact_angle_rad, contact_angle2_rad, volume, gap, ratio)
    return _scan_for_volume(th, volume, gap, ratio, th2, branch="exists")[2] == 0
