r"""Phase relations of a soil sample: any consistent subset of its state completes the rest (SI units).

The state of a sample is eight numbers tied by five relations (solids, water and air in a unit volume):

.. math::

    \rho_s = G_s\,\rho_w, \qquad e = \frac{\rho_s}{\rho_d} - 1, \qquad n = \frac{e}{1 + e}, \qquad
    S_r\,e = w\,G_s, \qquad \theta = \frac{w\,\rho_d}{\rho_w} = S_r\,n

(e.g. Lambe & Whitman 1969, ch. 3; Craig's Soil Mechanics, ch. 1). `complete_state` propagates what is
given through these relations until nothing more follows; a value given AND implied by others is checked
against them (a relative tolerance for the rounding of published tables), and a set that contradicts itself
raises `InconsistentState`, naming the quantities and the values on both sides.

References
----------
.. [1] Lambe, T. W. & Whitman, R. V. (1969). Soil Mechanics. Wiley, ch. 3 (no DOI): the phase relations.
.. [2] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.,
   doi:10.1080/19648189.2024.2314099, Table 1: a sample state (w, rho_s, rho_d, e, S_r) that these relations
   tie together (tests/test_phase.py).
"""

from __future__ import annotations

import numpy as np

#: density of water [kg/m^3] (4 C; the glossary's rho_w)
RHO_W = 1000.0

#: the quantities of a sample state, in the order reported: name -> (unit, description)
STATE = {
    "rho_d": ("kg/m^3", "dry density"),
    "rho_s": ("kg/m^3", "density of the solids"),
    "G_s": ("-", "specific gravity of the solids"),
    "e": ("-", "void ratio"),
    "n": ("-", "porosity"),
    "w": ("-", "gravimetric water content"),
    "S_r": ("-", "degree of saturation"),
    "theta": ("-", "volumetric water content"),
}

#: absolute tolerance of the consistency check, per quantity (beside the relative ``rtol``): the last digit of
#: a published table (densities to 10 kg/m^3 = 0.01 g/cm^3, ratios to 0.005)
_ATOL = {"rho_d": 10.0, "rho_s": 10.0, "G_s": 0.01, "e": 0.005, "n": 0.005, "w": 0.002, "S_r": 0.005, "theta": 0.005}

#: physically possible ranges: (lower, upper, lower open, upper open)
_RANGES = {
    "rho_d": (0.0, None, True, False),
    "rho_s": (0.0, None, True, False),
    "G_s": (0.0, None, True, False),
    "e": (0.0, None, True, False),
    "n": (0.0, 1.0, True, True),
    "w": (0.0, None, False, False),
    "S_r": (0.0, 1.0, False, False),
    "theta": (0.0, 1.0, False, True),
}


class InconsistentState(ValueError):
    """A sample state whose given values contradict the phase relations, or lie outside physical ranges.

    Attributes
    ----------
    problems : list of (int, str, str)
        (row index, quantity, message) of every problem found, rows in order.
    """

    def __init__(self, problems: list[tuple[int, str, str]]):
        self.problems = sorted(problems, key=lambda p: p[0])
        super().__init__("; ".join(f"row {i}: {msg}" for i, _, msg in self.problems))


def _rules(rho_w: float):
    """(output, inputs, function) of every way one quantity follows from others."""
    return (
        ("rho_s", ("G_s",), lambda G: G * rho_w),
        ("G_s", ("rho_s",), lambda rs: rs / rho_w),
        ("e", ("rho_s", "rho_d"), lambda rs, rd: rs / rd - 1.0),
        ("rho_d", ("rho_s", "e"), lambda rs, e: rs / (1.0 + e)),
        ("rho_s", ("rho_d", "e"), lambda rd, e: rd * (1.0 + e)),
        ("n", ("e",), lambda e: e / (1.0 + e)),
        ("e", ("n",), lambda n: n / (1.0 - n)),
        ("S_r", ("w", "G_s", "e"), lambda w, G, e: w * G / e),
        ("w", ("S_r", "e", "G_s"), lambda S, e, G: S * e / G),
        ("e", ("w", "G_s", "S_r"), lambda w, G, S: np.where(S > 0, w * G / np.where(S > 0, S, 1.0), np.nan)),
        ("G_s", ("S_r", "e", "w"), lambda S, e, w: np.where(w > 0, S * e / np.where(w > 0, w, 1.0), np.nan)),
        ("theta", ("w", "rho_d"), lambda w, rd: w * rd / rho_w),
        ("w", ("theta", "rho_d"), lambda t, rd: t * rho_w / rd),
        ("rho_d", ("theta", "w"), lambda t, w: np.where(w > 0, t * rho_w / np.where(w > 0, w, 1.0), np.nan)),
        ("theta", ("S_r", "n"), lambda S, n: S * n),
        ("S_r", ("theta", "n"), lambda t, n: t / n),
        ("n", ("theta", "S_r"), lambda t, S: np.where(S > 0, t / np.where(S > 0, S, 1.0), np.nan)),
    )


def _describe(v: float, name: str) -> str:
    unit = STATE[name][0]
    return f"{v:.4g} {unit}" if unit != "-" else f"{v:.4g}"


def complete_state(rtol: float = 0.01, rho_w: float = RHO_W, **given) -> dict[str, np.ndarray]:
    r"""Every quantity of a sample state from any consistent subset of it.

    .. math::

        \rho_s = G_s\rho_w,\quad e = \rho_s/\rho_d - 1,\quad n = e/(1+e),\quad S_r e = w G_s,\quad
        \theta = w\rho_d/\rho_w = S_r n

    Parameters
    ----------
    rtol : float, default 0.01
        Relative tolerance of the check of a value that is given and also follows from others [-] (beside an
        absolute tolerance of one last published digit: 10 kg/m^3 for densities, 0.005 for ratios, 0.002 for w).
    rho_w : float, default 1000
        Density of water [kg/m^3].
    **given
        Any of ``rho_d`` [kg/m^3], ``rho_s`` [kg/m^3], ``G_s`` [-], ``e`` [-], ``n`` [-], ``w`` [-],
        ``S_r`` [-], ``theta`` [-]: scalars or arrays (broadcast together), NaN or None where unknown.

    Returns
    -------
    dict of str to numpy.ndarray
        Every quantity of ``STATE`` (NaN where the given values do not determine it), in the units above.

    Raises
    ------
    InconsistentState
        A given value outside its physical range (S_r or n outside [0, 1], a density <= 0 ...) or a given value
        that contradicts the others beyond the tolerance; every such row is named.
    ValueError
        An unknown quantity name.

    References
    ----------
    .. [1] Lambe, T. W. & Whitman, R. V. (1969). Soil Mechanics. Wiley, ch. 3 (no DOI).
    """
    unknown = set(given) - set(STATE)
    if unknown:
        raise ValueError(f"unknown sample-state quantity {', '.join(sorted(unknown))}; known: {', '.join(STATE)}")
    arrays = {k: np.asarray(np.nan if v is None else v, dtype=float) for k, v in given.items()}
    shape = np.broadcast_shapes(*(a.shape for a in arrays.values())) if arrays else ()
    state = {k: np.array(np.broadcast_to(arrays.get(k, np.nan), shape), dtype=float) for k in STATE}
    flat = {k: v.reshape(-1) for k, v in state.items()}
    _check_ranges(flat, "given")

    problems: list[tuple[int, str, str]] = []
    given_names = set(arrays)
    derived_from: dict[str, np.ndarray] = {k: np.full(flat[k].shape, "", dtype=object) for k in STATE}
    for k in given_names:
        derived_from[k][np.isfinite(flat[k])] = "given"
    changed = True
    with np.errstate(divide="ignore", invalid="ignore"):
        while changed:
            changed = False
            for out, ins, f in _rules(rho_w):
                known = np.all([np.isfinite(flat[i]) for i in ins], axis=0)
                if not known.any():
                    continue
                value = f(*(flat[i] for i in ins))
                value = np.broadcast_to(value, known.shape)
                ok = known & np.isfinite(value)
                fill = ok & ~np.isfinite(flat[out])
                check = ok & np.isfinite(flat[out])
                tol = rtol * np.maximum(np.abs(flat[out]), np.abs(value)) + _ATOL[out]
                for i in np.flatnonzero(check & (np.abs(flat[out] - value) > tol)):
                    src = derived_from[out][i] or "derived"
                    problems.append(
                        (
                            int(i),
                            out,
                            f"{out} = {_describe(flat[out][i], out)} ({src}) but {', '.join(ins)} give "
                            f"{_describe(value[i], out)} ({', '.join(f'{n} = {_describe(flat[n][i], n)}' for n in ins)})",
                        )
                    )
                if fill.any():
                    flat[out][fill] = value[fill]
                    derived_from[out][fill] = "from " + ", ".join(ins)
                    changed = True
            if problems:
                break
    if problems:
        # one message per row (a contradiction shows through several relations; the first names it)
        seen, unique = set(), []
        for p in problems:
            if p[0] not in seen:
                seen.add(p[0])
                unique.append(p)
        raise InconsistentState(unique)
    _check_ranges(flat, "implied by the others")
    return {k: flat[k].reshape(shape) for k in STATE}


def _check_ranges(flat: dict[str, np.ndarray], how: str) -> None:
    """Raise InconsistentState for every value outside its physical range (``how``: given or implied)."""
    problems = []
    for k, v in flat.items():
        lo, hi, lo_open, hi_open = _RANGES[k]
        with np.errstate(invalid="ignore"):
            bad = np.isfinite(v) & ((v <= lo) if lo_open else (v < lo))
            if hi is not None:
                bad |= np.isfinite(v) & ((v >= hi) if hi_open else (v > hi))
        for i in np.flatnonzero(bad):
            span = f"{'(' if lo_open else '['}{lo:g}, {'inf' if hi is None else f'{hi:g}'}{')' if hi_open else ']'}"
            problems.append((int(i), k, f"{STATE[k][1]} {k} = {_describe(v[i], k)} ({how}) lies outside {span}"))
    if problems:
        raise InconsistentState(problems)
