"""Deprecated: the former van Genuchten fitter, kept only as a name for one caller.

The duplicate fitter that lived here is gone; every retention fit goes through
:func:`capred.fitting.retention_models.fit_model`. ``capred/pipelines/shear_analysis.py``
still imports :func:`fit_van_genuchten`; once it calls ``fit_model("vg", s, y)`` this
module can be deleted.
"""
from __future__ import annotations

from .retention_models import RetentionFit, fit_model


def fit_van_genuchten(s, y, fixed=None, bounds=None, m_free=False) -> RetentionFit:
    """Van Genuchten (1980) fit of (s, y): ``fit_model("vg" or "vg_m_free", s, y, fixed)``.

    Parameters
    ----------
    s : array_like
        Suctions [Pa].
    y : array_like
        Water contents [m³/m³] or S_R [-].
    fixed : dict[str, float], optional
        Fixed parameters (internal names, SI).
    bounds : None
        Ignored (the bounds are the registry's); kept for the old signature.
    m_free : bool
        m free (``vg_m_free``) instead of m = 1 - 1/n.

    Returns
    -------
    RetentionFit

    References
    ----------
    van Genuchten (1980), doi:10.2136/sssaj1980.03615995004400050002x, eq. 21.
    """
    return fit_model("vg_m_free" if m_free else "vg", s, y, fixed)
