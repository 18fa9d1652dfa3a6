"""Model comparison rules shared by the pipelines that rank models and the tables that print the ranking.

Which models are compared on one set of tests (`compared`), and the printed resolution of a bootstrap's
ΔRMSE interval (`difference_resolution`, also the adaptive bootstrap's stopping rule).
"""

from __future__ import annotations

import numpy as np


def difference_resolution(ci) -> float | None:
    """The printed resolution of the ends of a ΔRMSE interval [its unit].

    The decimal step 10^floor(log10(w/5)) with w the interval's width (5 to 50 steps across it: about two significant
    digits of the width, what a percentile interval of a few thousand resamples can claim), None for no interval or a
    zero width.

    Parameters
    ----------
    ci : (float, float) or None
        The interval's ends.

    Returns
    -------
    float or None

    References
    ----------
    .. [1] Efron, B. & Tibshirani, R. J. (1993). An Introduction to the Bootstrap. Chapman & Hall,
       doi:10.1007/978-1-4899-4541-9, ch. 19 (the Monte-Carlo error of bootstrap percentiles).
    """
    if ci is None or not all(np.isfinite(ci)):
        return None
    width = float(ci[1] - ci[0])
    if not width > 0:
        return None
    return float(10.0 ** np.floor(np.log10(width / 5.0)))


def compared(metrics: dict) -> tuple[list[str], dict[str, int]]:
    """The models compared on one set of wet tests, and those listed apart with the count of tests they lack.

    Every model is scored on the same candidate tests; a model that predicts fewer of them than the model that
    predicts the most (e.g. the exact bridge, which has no concave bridge for a wet test holding much water) is
    left out of the ranking, the AICc weights and the bootstrap, so that no model wins on an easier subset
    (issue 41.2): ranking on the common subset instead would throw away the tests the others predict.

    Parameters
    ----------
    metrics : dict
        Model name -> its scores (anything with ``n``, the wet tests it predicts; e.g. ModelMetrics), all on the
        same candidate tests.

    Returns
    -------
    (list of str, dict of str to int)
        The compared models (in ``metrics``' order) and {model: wet tests it lacks} of the others.

    References
    ----------
    .. [1] Burnham, K. P. & Anderson, D. R. (2002). Model Selection and Multimodel Inference, 2nd ed. Springer,
       doi:10.1007/b97636, section 2.11 (information criteria compare models fitted to the same data).
    """
    most = max((v.n for v in metrics.values()), default=0)
    inside = [m for m, v in metrics.items() if v.n == most and most > 0]
    apart = {m: most - v.n for m, v in metrics.items() if m not in inside}
    return inside, apart
