"""The sample state of every row of a table, completed and checked by the phase relations (capred.physics.phase).

Every command that reads a sample state (`capred triaxial`, `capred shear`'s e/rho_d/G_s, `capred retention`'s
w/rho_d/theta) goes through `table_state`: a row whose given values contradict each other, or imply an impossible
one (S_r > 1), is a problem of the table, named by file, line and column, and raised with the table's others.
"""

from __future__ import annotations

import numpy as np

from ..io import Table
from ..physics import phase

#: table column -> phase-relation name (the columns capred's schemas use for a sample state)
STATE_COLUMNS = {
    "rho_d": "rho_d",
    "rho_s": "rho_s",
    "G_s": "G_s",
    "e": "e",
    "n": "n",
    "w": "w",
    "S_R": "S_r",
    "theta": "theta",
}


def table_state(table: Table, rho_w: float = phase.RHO_W, columns: tuple[str, ...] | None = None) -> dict:
    """The completed sample state of every row; inconsistent rows recorded as problems of ``table``.

    Parameters
    ----------
    table : capred.io.Table
        A table as read (SI values).
    rho_w : float
        Density of water [kg/m^3].
    columns : tuple of str, optional
        The table's columns that are a sample state (default: every column of ``STATE_COLUMNS`` it has).

    Returns
    -------
    dict of str to numpy.ndarray
        Column name -> values of every row (the given ones kept, the others completed, NaN where undetermined);
        {} when the table has no sample-state column. Nothing is raised here: the caller raises the table's
        problems (``table.raise_if_problems()``) with its own.

    References
    ----------
    .. [1] Lambe, T. W. & Whitman, R. V. (1969). Soil Mechanics. Wiley, ch. 3 (no DOI): the phase relations.
    """
    names = [c for c in (columns or tuple(STATE_COLUMNS)) if table.has(c)]
    if not names:
        return {}
    given = {STATE_COLUMNS[c]: table.get(c) for c in names}
    n = len(table)
    try:
        state = phase.complete_state(rho_w=rho_w, **given)
    except phase.InconsistentState as exc:
        inverse = {p: c for c, p in STATE_COLUMNS.items()}
        bad = set()
        for i, q, msg in exc.problems:
            bad.add(i)
            col = inverse.get(q, q)
            table.add_problem(i, col if table.has(col) else names[0], msg)
        # the rows that are consistent are still completed (the caller raises the problems)
        keep = np.array([i not in bad for i in range(n)])
        state = {k: np.full(n, np.nan) for k in phase.STATE}
        if keep.any():
            part = phase.complete_state(rho_w=rho_w, **{k: v[keep] for k, v in given.items()})
            for k in state:
                state[k][keep] = part[k]
    return {c: np.asarray(state[p], float).reshape(n) for c, p in STATE_COLUMNS.items()}
