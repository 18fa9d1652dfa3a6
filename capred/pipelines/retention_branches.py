r"""Drying, wetting and scanning branches of a retention record read in time order.

A reversal of the suction's direction starts a new branch only when the suction has moved back from its running
extreme by more than a noise tolerance,

.. math:: \tau(s_x) = \max(r\, s_x,\; f\,(s_{max} - s_{min})),

with s_x the extreme (the reversal point), r :data:`REVERSAL_RELATIVE` of the reading and f :data:`REVERSAL_RANGE`
of the measured range (both options of `capred retention`; the defaults are justified in
docs/user_guide/retention_branches.md). A dip smaller than that (an evaporation record's tensiometer noise) stays
in its branch.

Each branch is then *main* or *scanning*, after the memory rule of independent-domain hysteresis (Mualem 1974;
Parker & Lenhard 1987): a drying reading lies on the main drying curve when its suction exceeds every suction
reached since the record last stood at its wet end (its smallest suction); a wetting reading lies on the main
wetting curve when its suction is below every suction reached since the record last stood at its dry end. Other
readings start at a reversal inside the measured range: they are ``scanning``.

References
----------
.. [1] Mualem, Y. (1974). A conceptual model of hysteresis. Water Resour. Res. 10(3):514-520,
   doi:10.1029/WR010i003p00514.
.. [2] Parker, J. C., Lenhard, R. J. (1987). A model for hysteretic constitutive relations governing multiphase
   flow: 1. Saturation-pressure relations. Water Resour. Res. 23(12):2187-2196, doi:10.1029/WR023i012p02187.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..spec.retention import LABELS, REVERSAL_RANGE, REVERSAL_RELATIVE  # noqa: E402, F401 (declared once in spec)


@dataclass(frozen=True)
class Branches:
    """The branches of a record.

    Attributes
    ----------
    label : ndarray of str
        ``drying``, ``wetting`` or ``scanning`` per reading.
    direction : ndarray of int
        +1 where the suction rises (drying), -1 where it falls (wetting), per reading (its segment's).
    segment : ndarray of int
        The segment (run of one direction between confirmed reversals) of each reading, 0, 1, ...
    turning : tuple of int
        Index of the reading at each confirmed reversal (the last reading of the segment it ends).
    against : int
        Readings that step against their segment's direction by less than the tolerance (noise kept in it).
    tolerance : tuple of float
        (relative to the reading [-], fraction of the range [-]) used.
    """

    label: np.ndarray
    direction: np.ndarray
    segment: np.ndarray
    turning: tuple
    against: int
    tolerance: tuple


def _tol(x: float, span: float, relative: float, of_range: float) -> float:
    return max(relative * abs(x), of_range * span)


def segments(s, relative: float = REVERSAL_RELATIVE, of_range: float = REVERSAL_RANGE):
    """Direction of each reading and the confirmed reversals, ignoring reversals below the noise tolerance.

    Parameters
    ----------
    s : array_like
        Suction of each reading in time order [Pa] (any unit).
    relative, of_range : float
        The tolerance: a fraction of the suction at the reversal and of the record's range [-].

    Returns
    -------
    (ndarray of int, ndarray of int, tuple of int)
        Direction (+1 drying, -1 wetting) and segment index per reading, and the index of each reversal point.
    """
    s = np.asarray(s, float)
    n = s.size
    span = float(s.max() - s.min()) if n else 0.0
    seg = np.zeros(n, dtype=int)
    turning: list[int] = []
    starts_dir: list[int] = []
    d, lo, hi, ext = 0, 0, 0, 0
    for i in range(1, n):
        if d == 0:
            hi = i if s[i] >= s[hi] else hi
            lo = i if s[i] <= s[lo] else lo
            if s[hi] - s[lo] > _tol(s[lo] if lo < hi else s[hi], span, relative, of_range):
                d = 1 if lo < hi else -1
                ext = hi if d > 0 else lo
            continue
        if (s[i] - s[ext]) * d >= 0:
            ext = i
        elif abs(s[ext] - s[i]) > _tol(s[ext], span, relative, of_range):
            starts_dir.append(d)
            turning.append(ext)
            seg[ext + 1 :] += 1
            d = -d
            part = s[turning[-1] + 1 : i + 1]
            ext = turning[-1] + 1 + int(np.argmax(part) if d > 0 else np.argmin(part))
    starts_dir.append(d if d != 0 else 1)
    direction = np.array([starts_dir[k] for k in seg], dtype=int) if n else np.zeros(0, dtype=int)
    return direction, seg, tuple(turning)


def infer_branches(s, relative: float = REVERSAL_RELATIVE, of_range: float = REVERSAL_RANGE) -> Branches:
    """Drying, wetting and scanning readings of a record in time order (see the module docstring).

    Parameters
    ----------
    s : array_like
        Suction of each reading in time order [Pa].
    relative, of_range : float
        The noise tolerance (:data:`REVERSAL_RELATIVE`, :data:`REVERSAL_RANGE`).

    Returns
    -------
    Branches
        Labels, directions, segments and reversal points.

    References
    ----------
    Mualem (1974), doi:10.1029/WR010i003p00514; Parker & Lenhard (1987), doi:10.1029/WR023i012p02187 (the
    main curves bound every scanning curve; a scanning loop closes at its reversal point).
    """
    s = np.asarray(s, float)
    direction, seg, turning = segments(s, relative, of_range)
    n = s.size
    label = np.empty(n, dtype=object)
    if n == 0:
        return Branches(label, direction, seg, turning, 0, (relative, of_range))
    span = float(s.max() - s.min())
    wet_end = s.min() + _tol(s.min(), span, relative, of_range)
    dry_end = s.max() - _tol(s.max(), span, relative, of_range)
    for k in range(int(seg.max()) + 1):
        idx = np.flatnonzero(seg == k)
        a = int(idx[0])
        d = direction[a]
        before = s[:a]
        if d > 0:
            visits = np.flatnonzero(before <= wet_end)
            since = before[visits[-1] :] if visits.size else before
            ref = since.max() if since.size else -np.inf
            main = s[idx] >= ref - (_tol(ref, span, relative, of_range) if np.isfinite(ref) else 0.0)
            label[idx] = np.where(main, "drying", "scanning")
        else:
            visits = np.flatnonzero(before >= dry_end)
            since = before[visits[-1] :] if visits.size else before
            ref = since.min() if since.size else np.inf
            main = s[idx] <= ref + (_tol(ref, span, relative, of_range) if np.isfinite(ref) else 0.0)
            label[idx] = np.where(main, "wetting", "scanning")
    steps = np.diff(s)
    against = int(np.sum(steps * direction[1:] < 0))  # a reversal's first reading steps with its new direction
    return Branches(label, direction, seg, turning, against, (relative, of_range))


def single_direction(s, relative: float = REVERSAL_RELATIVE, of_range: float = REVERSAL_RANGE) -> str:
    """``drying`` or ``wetting``: the direction of the longest run of a record (for ``--branches single``).

    Parameters
    ----------
    s : array_like
        Suction of each reading in time order [Pa].
    relative, of_range : float
        The noise tolerance (:data:`REVERSAL_RELATIVE`, :data:`REVERSAL_RANGE`).

    Returns
    -------
    str
        The label all readings take.
    """
    direction, seg, _ = segments(s, relative, of_range)
    if direction.size == 0:
        return "drying"
    counts = np.bincount(seg)
    return "drying" if direction[np.flatnonzero(seg == int(np.argmax(counts)))[0]] > 0 else "wetting"


def reversal_points(direction, turning) -> list[tuple[int, int]]:
    """The reversal points a record passed, with their kind, for the closure of scanning curves.

    Parameters
    ----------
    direction : ndarray of int
        +1/-1 per reading.
    turning : sequence of int
        Indices of the confirmed reversals.

    Returns
    -------
    list of (int, int)
        (index, kind) with kind +1 at a suction maximum (drying turned to wetting) and -1 at a minimum; the first
        reading counts as a reversal of the kind opposite to the first segment's direction.
    """
    out = [(0, -int(direction[0]))] if len(direction) else []
    out += [(int(t), int(direction[t])) for t in turning]
    return out
