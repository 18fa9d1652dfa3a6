"""Which rows of a long table are shown.

The one rule shared by the pipelines (which keep those rows of a long run in memory) and report/ (which draws and prints
them).

Figures draw at most ``MAX_MARKERS`` markers per series (a seeded random sample above it), and per-row
console tables list the first ``MAX_ROWS`` rows; every output file holds every row.
"""

from __future__ import annotations

import numpy as np

#: panels draw at most this many markers per series; above it, a random sample (seed THIN_SEED) and a note
MAX_MARKERS = 2000
THIN_SEED = 0
#: Per-row tables show at most this many rows; the rest are in the output files.
MAX_ROWS = 20


def sample_rows(index, limit: int = MAX_MARKERS, seed: int = THIN_SEED) -> np.ndarray:
    """At most ``limit`` of the row indices ``index`` (a boolean mask or indices), in increasing order.

    All of them, or a random sample without replacement (``numpy.random.default_rng(seed)``).

    Parameters
    ----------
    index : array_like of bool or int
        The rows of one series.
    limit : int
        Most rows kept [-].
    seed : int
        Seed of the sample: the same rows every run.

    Returns
    -------
    ndarray of int
    """
    index = np.asarray(index)
    if index.dtype == bool:
        index = np.flatnonzero(index)
    if index.size <= limit:
        return index
    return np.sort(np.random.default_rng(seed).choice(index, limit, replace=False))
