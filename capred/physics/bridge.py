"""Pendular liquid bridge between two equal spheres, zero gravity (Evenepoel, VUB thesis; Lian et al. 1993).

Dimensionless core: lengths in units of the sphere radius R, suction
s* = Delta_u R / gamma, force F* = F / (pi gamma R), volume V* = V / R^3.

The meridian y(x) of the bridge (x along the line of centres, neck at x = 0)
obeys the axisymmetric Young-Laplace equation
    Delta_u / gamma = kappa_meridional - cos(psi) / y,
whose first integral is the axial force, the same through every section:
    F* = 2 y cos(psi) + s* y^2.
At the neck (psi = 0, y = y0) this is the thesis's F_cap = pi r0^2 Delta_u +
2 pi r0 gamma; at the contact line (half-filling angle beta, contact angle
theta) y = sin(beta), psi = pi/2 - beta - theta, so
    F* = 2 sin(beta) sin(beta + theta) + s* sin^2(beta).
With cos(psi) = c(y) = (F* - s* y^2)/(2y), dx/dy = c / sqrt(1 - c^2), and
    1 - c = (y - y0)(2 + s*(y + y0)) / (2y)
factors exactly, so the substitution y = y0 + (y_c - y0) t^2 removes the
square-root singularity at the neck and the half-length L and the volume
under the meridian become smooth integrals over t in [0, 1], computed by
Gauss-Legendre quadrature (16 nodes give about 1e-13). Then
    gap* = 2 (L + cos(beta) - 1),
    V*   = 2 (pi int y^2 dx - pi h^2 (3 - h)/3),  h = 1 - cos(beta).
Only concave (pendular) bridges with s* >= 0 are treated: they need
beta + theta < 90 deg.
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

_NODES = 16
_t, _w = leggauss(_NODES)
_T = 0.5 * (_t + 1.0)
_W = 0.5 * _w
_CHUNK = 20000  # cases per vectorised block (bounds memory: chunk x nodes arrays)


def _arr(*xs):
    return [np.asarray(x, dtype=float) for x in np.broadcast_arrays(*xs)]


def geometry(beta, theta, suction):
    """Exact bridge from (half-filling angle beta [rad], contact angle theta [rad], s* >= 0).

    Returns dimensionless (gap*, volume*, force*, neck*). Invalid inputs
    (beta + theta >= pi/2, beta <= 0, s* < 0) give NaN.
    """
    beta, theta, suction = _arr(beta, theta, suction)
    shape = beta.shape
    b, th, s = beta.ravel(), theta.ravel(), suction.ravel()
    out = [np.full(b.size, np.nan) for _ in range(4)]
    ok = (b > 0) & (b + th < 0.5 * np.pi) & (s >= 0) & (th >= 0)
    idx = np.flatnonzero(ok)
    for start in range(0, idx.size, _CHUNK):
        k = idx[start:start + _CHUNK]
        g, v, f, y0 = _geometry(b[k], th[k], s[k])
        out[0][k], out[1][k], out[2][k], out[3][k] = g, v, f, y0
    return tuple(o.reshape(shape) for o in out)


def _geometry(b, th, s):
    yc = np.sin(b)
    F = 2.0 * yc * np.sin(b + th) + s * yc * yc
    y0 = F / (1.0 + np.sqrt(1.0 + s * F))  # root of 2 y0 + s y0^2 = F, stable form
    d = yc - y0
    y = y0[:, None] + d[:, None] * _T**2
    A = 2.0 + s[:, None] * (y + y0[:, None])
    B = 2.0 * y + F[:, None] - s[:, None] * y * y
    g = 2.0 * np.sqrt(np.maximum(d, 0.0))[:, None] * (F[:, None] - s[:, None] * y * y) / np.sqrt(A * B)
    L = g @ _W
    V_under = np.pi * ((g * y * y) @ _W)
    h = 1.0 - np.cos(b)
    gap = 2.0 * (L + np.cos(b) - 1.0)
    vol = 2.0 * (V_under - np.pi * h * h * (3.0 - h) / 3.0)
    return gap, vol, F, y0


def _illinois(f, lo, hi, f_lo, f_hi, tol=1e-14, iters=100):
    """Vectorised Illinois (modified regula falsi) root of f on brackets with f_lo >= 0 >= f_hi."""
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    x = lo.copy()
    active = np.ones(lo.shape, dtype=bool)
    side = np.zeros(lo.shape, dtype=int)
    for _ in range(iters):
        if not active.any():
            break
        a = np.flatnonzero(active)
        denom = f_lo[a] - f_hi[a]
        xa = np.where(denom != 0, (lo[a] * (-f_hi[a]) + hi[a] * f_lo[a]) / np.where(denom != 0, denom, 1.0),
                      0.5 * (lo[a] + hi[a]))
        # keep strictly inside the bracket (regula falsi can stall on an end)
        span = hi[a] - lo[a]
        xa = np.clip(xa, lo[a] + 1e-3 * span * (side[a] == 1), hi[a] - 1e-3 * span * (side[a] == -1))
        fa = f(xa, a)
        x[a] = xa
        pos = fa >= 0
        # bracket update with the Illinois halving of the retained end's value
        lo_new, hi_new = np.where(pos, xa, lo[a]), np.where(pos, hi[a], xa)
        flo_new = np.where(pos, fa, np.where(side[a] == -1, f_lo[a] * 0.5, f_lo[a]))
        fhi_new = np.where(pos, np.where(side[a] == 1, f_hi[a] * 0.5, f_hi[a]), fa)
        side[a] = np.where(pos, 1, -1)
        lo[a], hi[a], f_lo[a], f_hi[a] = lo_new, hi_new, flo_new, fhi_new
        done = (np.abs(hi[a] - lo[a]) <= tol * np.maximum(1.0, np.abs(xa))) | (fa == 0)
        active[a[done]] = False
    return x


def solve_for_suction(theta, suction, gap):
    """Half-filling angle of the stable bridge at given (theta [rad], s*, gap*), and a status.

    At fixed suction the gap, as a function of beta, rises from 0 to a
    maximum (the rupture gap at that suction) and then falls: two bridges fit
    a smaller gap. The one on the falling branch (larger beta, the
    continuation of the bridge at contact) is the stable one and is returned;
    beyond the maximum there is no bridge.
    Status codes: 0 ok, 1 gap beyond rupture at this suction, 2 invalid input.
    """
    theta, suction, gap = (x.ravel() for x in _arr(theta, suction, gap))
    n = theta.size
    beta = np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < 0.5 * np.pi) & (suction > 0) & (gap >= 0)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, status
    th, s, D = theta[k], suction[k], gap[k]
    b_end = 0.5 * np.pi - th
    grid = b_end[:, None] * np.geomspace(1e-4, 1.0 - 1e-9, 14)[None, :]
    Dg = geometry(grid, th[:, None], s[:, None])[0]
    Dg[:, -1] = np.minimum(Dg[:, -1], 2.0 * (np.cos(grid[:, -1]) - 1.0) + 1e-300)
    above = Dg >= D[:, None]
    has = above.any(axis=1)
    # last grid point still at or above the target gap: the bracket of the falling-branch root
    last = np.where(has, above.shape[1] - 1 - np.argmax(above[:, ::-1], axis=1), 0)
    last = np.minimum(last, above.shape[1] - 2)
    r = np.arange(k.size)
    lo, hi = grid[r, last], grid[r, last + 1]
    f_lo, f_hi = Dg[r, last] - D, Dg[r, last + 1] - D
    # a peak between grid points can hide a bracket: refine the maximum where none was found
    miss = np.flatnonzero(~has)
    if miss.size:
        j = np.argmax(Dg[miss], axis=1)
        a = grid[miss, np.maximum(j - 1, 0)]
        c = grid[miss, np.minimum(j + 1, grid.shape[1] - 1)]
        bp, dp = _golden_max(lambda x, i: geometry(x, th[miss][i], s[miss][i])[0], a, c)
        found = dp >= D[miss]
        has[miss[found]] = True
        lo[miss] = bp
        f_lo[miss] = dp - D[miss]
        hi[miss] = c
        f_hi[miss] = geometry(c, th[miss], s[miss])[0] - D[miss]
    good = np.flatnonzero(has)
    root = _illinois(lambda x, i: geometry(x, th[good][i], s[good][i])[0] - D[good][i],
                     lo[good], hi[good], f_lo[good], f_hi[good])
    beta[k[good]] = root
    status[k] = np.where(has, 0, 1)
    return beta, status


def _golden_max(f, a, c, iters=60):
    """Vectorised golden-section maximisation of f on [a, c]; returns (x, f(x))."""
    g = (np.sqrt(5.0) - 1.0) / 2.0
    a, c = a.copy(), c.copy()
    idx = np.arange(a.size)
    x1, x2 = c - g * (c - a), a + g * (c - a)
    f1, f2 = f(x1, idx), f(x2, idx)
    for _ in range(iters):
        left = f1 < f2
        a = np.where(left, x1, a)
        c = np.where(left, c, x2)
        x1n = np.where(left, x2, c - g * (c - a))
        x2n = np.where(left, a + g * (c - a), x1)
        fn = f(np.where(left, x2n, x1n), idx)
        f1, f2 = np.where(left, f2, fn), np.where(left, fn, f1)
        x1, x2 = x1n, x2n
    x = 0.5 * (x1 + x2)
    return x, f(x, idx)


def suction_for_gap(beta, theta, gap):
    """s* >= 0 with gap*(beta, theta, s*) = gap (the gap falls as suction rises); NaN if none."""
    beta, theta, gap = (x.ravel() for x in _arr(beta, theta, gap))
    s = np.full(beta.size, np.nan)
    ok = (beta > 0) & (beta + theta < 0.5 * np.pi) & (gap >= 0)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return s
    b, th, D = beta[k], theta[k], gap[k]
    d0 = geometry(b, th, 0.0)[0] - D
    feasible = np.flatnonzero(d0 >= 0)
    if feasible.size == 0:
        return s
    b, th, D, d0 = b[feasible], th[feasible], D[feasible], d0[feasible]
    # q = s / (1 + s) maps [0, inf) to [0, 1); at q -> 1 the gap tends to 2 (cos beta - 1) < 0
    hi_val = 2.0 * (np.cos(b) - 1.0) - D

    def f(q, i):
        return geometry(b[i], th[i], q / (1.0 - q))[0] - D[i]

    q = _illinois(f, np.zeros(b.size), np.full(b.size, 1.0 - 1e-15), d0, hi_val)
    s[k[feasible]] = q / (1.0 - q)
    return s


def solve_for_volume(theta, volume, gap):
    """(beta, s*, status) of the bridge of given volume* at gap* (theta in rad), verified.

    Two searches: along the family of concave bridges at the gap parametrised
    by the filling angle (from the catenoid spanning the gap to the largest
    catenoid), and along the stable branch parametrised by the suction. A
    candidate counts only if its geometry reproduces the requested gap and
    volume to 1e-9 relative; rows where neither does keep the status of the
    first search (1 beyond rupture, 3 too much water) or get 4 (no verified
    bridge found). Status 2: invalid input.
    """
    theta, volume, gap = (x.ravel() for x in _arr(theta, volume, gap))
    beta, s, status = _solve_for_volume_family(theta, volume, gap)
    bad = ~_verified(beta, theta, s, gap, volume) & (status == 0)
    retry = np.flatnonzero(bad | (status == 1))
    if retry.size:
        b2, s2, st2 = _solve_for_volume_stable_branch(theta[retry], volume[retry], gap[retry])
        good = (st2 == 0) & _verified(b2, theta[retry], s2, gap[retry], volume[retry])
        beta[retry[good]], s[retry[good]], status[retry[good]] = b2[good], s2[good], 0
        still = retry[~good & bad[retry]]
        beta[still], s[still], status[still] = np.nan, np.nan, 4
    return beta, s, status


def _verified(beta, theta, s, gap, volume, rtol=1e-9):
    """Does the bridge (beta, s*) reproduce the gap* (absolute 1e-9 near contact) and volume* to ``rtol``?"""
    g, v, _, _ = geometry(beta, theta, np.where(np.isfinite(s), s, 0.0))
    with np.errstate(invalid="ignore"):
        return ((np.abs(g - gap) <= rtol * np.maximum(np.abs(gap), 1e-6))
                & (np.abs(v - volume) <= rtol * np.abs(volume)) & np.isfinite(beta))


def _solve_for_volume_family(theta, volume, gap):
    """(beta, s*, status) of the bridge of given volume* at gap* (theta in rad).

    At fixed gap, the concave bridges form one family in beta, from the
    catenoid that just spans the gap (s* = 0, smallest beta) to the catenoid
    at the largest beta; the volume grows along it, so the solution is unique.
    Status codes: 0 ok, 1 volume too small to span the gap (beyond rupture),
    3 volume too large for a concave bridge (the water would be above air
    pressure), 2 invalid input.
    """
    theta, volume, gap = (x.ravel() for x in _arr(theta, volume, gap))
    n = theta.size
    beta = np.full(n, np.nan)
    suction = np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < 0.5 * np.pi) & (volume > 0) & (gap >= 0)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, suction, status
    th, V, D = theta[k], volume[k], gap[k]
    b_end = 0.5 * np.pi - th
    # the catenoid gap D0(beta) rises and falls; feasible betas are where D0 >= D
    bpk, dpk = _golden_max(lambda x, i: geometry(x, th[i], 0.0)[0], np.full(k.size, 1e-9), b_end * (1 - 1e-9))
    span = dpk >= D
    b_lo = np.where(D > 0, np.nan, 1e-12)
    b_hi = np.full(k.size, np.nan)
    sp = np.flatnonzero(span)
    if sp.size:
        def d0(x, i, sel=sp):
            return geometry(x, th[sel][i], 0.0)[0] - D[sel][i]
        b_hi[sp] = _illinois(d0, bpk[sp], b_end[sp] * (1 - 1e-12), dpk[sp] - D[sp],
                             2.0 * (np.cos(b_end[sp]) - 1.0) - D[sp])
        pos = sp[D[sp] > 0]
        if pos.size:
            def d0r(x, i, sel=pos):  # rising side, root of -(D0 - D) with the sign flipped for the bracket
                return -(geometry(x, th[sel][i], 0.0)[0] - D[sel][i])
            b_lo[pos] = _illinois(d0r, np.full(pos.size, 1e-9), bpk[pos], D[pos] - geometry(1e-9, th[pos], 0.0)[0],
                                  D[pos] - dpk[pos])
    v_lo = np.where(D > 0, np.nan, 0.0)
    if sp.size:
        pos = sp[D[sp] > 0]
        v_lo[pos] = geometry(b_lo[pos], th[pos], 0.0)[1]
    v_hi = np.full(k.size, np.nan)
    v_hi[sp] = geometry(b_hi[sp], th[sp], 0.0)[1]
    st = np.where(~span, 1, np.where(V < v_lo, 1, np.where(V > v_hi, 3, 0)))
    good = np.flatnonzero(st == 0)
    if good.size:
        def fv(x, i, sel=good):
            s_ = suction_for_gap(x, th[sel][i], D[sel][i])
            return V[sel][i] - geometry(x, th[sel][i], s_)[1]
        f_lo = V[good] - v_lo[good]
        f_hi = V[good] - v_hi[good]
        root = _illinois(fv, b_lo[good], b_hi[good], f_lo, f_hi)
        beta[k[good]] = root
        suction[k[good]] = suction_for_gap(root, th[good], D[good])
    status[k] = st
    return beta, suction, status


def _solve_for_volume_stable_branch(theta, volume, gap):
    """(beta, s*, status) of the stable bridge of given volume* at gap* (theta in rad).

    The stable bridges at a fixed gap form one family parametrised by the
    suction: at each suction the stable bridge is the one solve_for_suction
    returns (the continuation of the bridge at contact), from the catenoid at
    s* -> 0 (the most water a concave bridge holds) up to the rupture suction
    (at contact, no rupture). Along this family the volume is located by a
    scan of log s* and refined by the Illinois method on a sign change, so
    neither the gap(suction) nor the volume(filling angle) relation needs to
    be monotonic.
    Status codes: 0 ok, 1 volume too small to span the gap (beyond rupture),
    3 volume too large for a concave bridge, 2 invalid input.
    """
    theta, volume, gap = (x.ravel() for x in _arr(theta, volume, gap))
    n = theta.size
    beta = np.full(n, np.nan)
    suction = np.full(n, np.nan)
    status = np.full(n, 2, dtype=int)
    ok = (theta >= 0) & (theta < 0.5 * np.pi) & (volume > 0) & (gap >= 0)
    k = np.flatnonzero(ok)
    if k.size == 0:
        return beta, suction, status
    th, V, D = theta[k], volume[k], gap[k]
    m = k.size
    logs = np.linspace(np.log(1e-7), np.log(1e9), 64)  # s* grid (suction in units of gamma/R)

    def vol_at(log_s, rows):
        """Volume* of the stable bridge at (s*, gap) for the given rows (NaN where none)."""
        b, st = solve_for_suction(th[rows], np.exp(log_s), D[rows])
        v = np.where(st == 0, geometry(b, th[rows], np.exp(log_s))[1], np.nan)
        return v

    rows = np.repeat(np.arange(m), logs.size)
    Vg = vol_at(np.tile(logs, m), rows).reshape(m, logs.size)
    # the rupture suction lies between the last grid suction with a bridge and the next: bisect it, so the
    # smallest stable volume (at rupture) is on the grid too
    last = np.where(np.isfinite(Vg).any(axis=1), logs.size - 1 - np.argmax(np.isfinite(Vg)[:, ::-1], axis=1), -1)
    cut = np.flatnonzero((last >= 0) & (last < logs.size - 1))
    extra_s = np.full(m, np.nan)
    extra_v = np.full(m, np.nan)
    if cut.size:
        a, c = logs[last[cut]], logs[last[cut] + 1]
        for _ in range(60):
            mid = 0.5 * (a + c)
            v = vol_at(mid, cut)
            a, c = np.where(np.isfinite(v), mid, a), np.where(np.isfinite(v), c, mid)
        extra_s[cut], extra_v[cut] = a, vol_at(a, cut)
    logs_rows = np.tile(logs, (m, 1))
    ins = np.flatnonzero(np.isfinite(extra_v))
    grid_s = np.full((m, logs.size + 1), np.nan)
    grid_v = np.full((m, logs.size + 1), np.nan)
    grid_s[:, :-1], grid_v[:, :-1] = logs_rows, Vg
    for i in ins:  # insert the rupture point after the last grid point with a bridge
        j = last[i] + 1
        grid_s[i] = np.concatenate([logs_rows[i, :j], [extra_s[i]], logs_rows[i, j:]])
        grid_v[i] = np.concatenate([Vg[i, :j], [extra_v[i]], Vg[i, j:]])
    for i in np.setdiff1d(np.arange(m), ins):
        grid_s[i, -1], grid_v[i, -1] = np.inf, np.nan
    Vg = grid_v
    have = np.isfinite(Vg)
    status_k = np.full(m, 1)
    lo = np.full(m, np.nan)
    hi = np.full(m, np.nan)
    v_lo = np.full(m, np.nan)
    v_hi = np.full(m, np.nan)
    for i in range(m):
        idx = np.flatnonzero(have[i])
        if idx.size == 0:
            continue  # no bridge at this gap at any suction: beyond rupture
        vs = Vg[i, idx]
        if V[i] > np.max(vs) * (1 + 1e-12) and idx[0] == 0:
            status_k[i] = 3
            continue
        # first bracket along rising suction where the volume crosses the target
        d = vs - V[i]
        cross = np.flatnonzero((d[:-1] >= 0) & (d[1:] <= 0) & (np.diff(idx) == 1))
        if cross.size == 0:
            status_k[i] = 3 if V[i] > np.max(vs) else 1
            continue
        c = cross[0]
        lo[i], hi[i] = grid_s[i, idx[c]], grid_s[i, idx[c + 1]]
        v_lo[i], v_hi[i] = d[c], d[c + 1]
        status_k[i] = 0
    good = np.flatnonzero(status_k == 0)
    if good.size:
        root = _illinois(lambda x, j: vol_at(x, good[j]) - V[good[j]], lo[good], hi[good], v_lo[good], v_hi[good],
                         tol=1e-15)
        s_root = np.exp(root)
        b_root, st = solve_for_suction(th[good], s_root, D[good])
        beta[k[good]] = b_root
        suction[k[good]] = s_root
        status_k[good] = np.where(st == 0, 0, 1)
    status[k] = status_k
    return beta, suction, status


# ---- approximations -------------------------------------------------------

def israelachvili_force(R, surface_tension, theta):
    """F = 2 pi R gamma cos(theta): spheres in contact, small volume (Israelachvili; Evenepoel, VUB thesis)."""
    return 2.0 * np.pi * np.asarray(R, float) * surface_tension * np.cos(theta)


def willett_force(R, surface_tension, theta, volume, gap):
    """Willett et al. (2000) closed form for equal spheres:
    F = 2 pi R gamma cos(theta) / (1 + 2.1 S + 10 S^2), S = (gap/2) / sqrt(V/R)."""
    S = 0.5 * np.asarray(gap, float) / np.sqrt(np.asarray(volume, float) / R)
    return israelachvili_force(R, surface_tension, theta) / (1.0 + 2.1 * S + 10.0 * S * S)


def toroidal(beta, theta, gap):
    """Toroidal (circle-meridian) approximation in units of R: (s*, V*, F*, neck*).

    Meridian radius r1 = (1 - cos beta + gap/2) / cos(beta + theta), neck
    r2 = sin beta - r1 (1 - sin(beta + theta)); s* = 1/r1 - 1/r2 (pressure
    deficit of the meridian and neck curvatures); force at the neck (gorge
    method) F* = 2 r2 + s* r2^2; volume by quadrature of the circular profile.
    """
    beta, theta, gap = _arr(beta, theta, gap)
    r1 = (1.0 - np.cos(beta) + 0.5 * gap) / np.cos(beta + theta)
    r2 = np.sin(beta) - r1 * (1.0 - np.sin(beta + theta))
    s = 1.0 / r1 - 1.0 / r2
    xc = r1 * np.cos(beta + theta)
    x = xc[..., None] * _T
    y = (r2 + r1)[..., None] - np.sqrt(r1[..., None] ** 2 - x * x)
    v_under = np.pi * xc * ((y * y) @ _W)
    h = 1.0 - np.cos(beta)
    vol = 2.0 * (v_under - np.pi * h * h * (3.0 - h) / 3.0)
    return s, vol, 2.0 * r2 + s * r2 * r2, r2
