"""The dry envelope of a material as the Python API shows it: ``result.fits[material]``.

``fit.params["c_kPa"]``, ``fit.params["phi_deg"]``, ``fit.params["tan_phi"]`` carry the JSON names and units
(kPa, degrees); ``fit.summary()`` is a plain-text report. The SI line behind it (`capred.fitting.linear.LineFit`,
what the pipeline computes with) is ``fit.line``. The old attributes (``intercept`` [Pa], ``slope``,
``intercept_se``, ``slope_se``, ``intercept_ci``, ``slope_ci``) keep their old values and units for one
release and warn with their replacement (`capred.parameters.deprecated`).
"""

from __future__ import annotations

import math

from ..fitting.linear import LineFit
from ..parameters import Parameter, Parameters, correlation_from_covariance, deprecated, fit_report

#: old LineFit attribute -> its replacement (said in the DeprecationWarning)
RENAMED = {
    "intercept": 'params["c_kPa"].value (kPa)',
    "slope": 'params["tan_phi"].value (or params["phi_deg"])',
    "intercept_se": 'params["c_kPa"].stderr (kPa)',
    "slope_se": 'params["tan_phi"].stderr',
    "intercept_ci": 'params["c_kPa"].ci95 (kPa)',
    "slope_ci": 'params["tan_phi"].ci95',
    "covariance": "line.covariance (SI) or params.correlation",
}


class EnvelopeFit:
    """The dry envelope tau = c + sigma_N tan(phi) of one material, in the user's units.

    Parameters
    ----------
    line : LineFit
        The SI fit (c [Pa], tan phi [-]).
    material : str
        Material name (for the summary's title).
    source : str
        Input file (for the summary's title).
    warnings : sequence of str
        What the run says about this fit (outliers, scatter growing with stress ...).

    Attributes
    ----------
    params : capred.parameters.Parameters
        ``c_kPa`` [kPa] (fixed at 0 through the origin), ``phi_deg`` [deg], ``tan_phi`` [-].
    line : LineFit
        The SI fit.

    References
    ----------
    .. [1] Draper, N. R. & Smith, H. (1998). Applied Regression Analysis, 3rd ed. Wiley,
       doi:10.1002/9781118625590, ch. 1 (the straight line, its standard errors and t intervals).
    """

    def __init__(self, line: LineFit, material: str = "", source: str = "", warnings=()):
        self.line = line
        self.material = material
        self.source = source
        self.warnings = list(warnings)

    @property
    def params(self) -> Parameters:
        """c_kPa, phi_deg, tan_phi with standard errors and 95 % intervals (phi by the delta method)."""
        f = self.line
        b = float(f.slope)
        phi = math.degrees(math.atan(b))
        phi_se = math.degrees(f.slope_se / (1.0 + b * b))
        lo, hi = f.slope_ci
        c_lo, c_hi = f.intercept_ci
        origin = f.through_origin
        items = (
            Parameter(
                "c_kPa",
                f.intercept / 1e3,
                0.0 if origin else f.intercept_se / 1e3,
                (0.0, 0.0) if origin else (c_lo / 1e3, c_hi / 1e3),
                "kPa",
                "cohesion intercept c of the dry envelope",
                origin,
            ),
            Parameter(
                "phi_deg",
                phi,
                phi_se,
                (math.degrees(math.atan(lo)), math.degrees(math.atan(hi))),
                "deg",
                "friction angle φ of the dry envelope",
            ),
            Parameter("tan_phi", b, f.slope_se, (lo, hi), "-", "friction coefficient tan φ of the dry envelope"),
        )
        corr = {} if origin else correlation_from_covariance(["c_kPa", "tan_phi"], f.covariance)
        if ("c_kPa", "tan_phi") in corr:
            corr[("c_kPa", "phi_deg")] = corr[("c_kPa", "tan_phi")]  # phi is monotone in tan phi
        return Parameters(items, corr)

    def summary(self) -> str:
        """A plain-text report: parameters with SE and 95 % CI, correlations above 0.9, statistics, warnings.

        Returns
        -------
        str
        """
        f = self.line
        stats = {
            "n (dry)": f.n,
            "dof": f.dof,
            "R²": f.r2,
            "s [kPa]": math.sqrt(f.residual_variance) / 1e3 if f.dof > 0 else math.nan,
            "errors": getattr(f, "errors", "constant"),
            "loss": getattr(f, "loss", "ols"),
        }
        where = f" ({self.source})" if self.source else ""
        return fit_report(f"dry envelope of material '{self.material}'{where}", self.params, stats, self.warnings)

    def __getattr__(self, name):
        if name in ("line", "__setstate__", "__getstate__") or name.startswith("__"):
            raise AttributeError(name)
        value = getattr(self.line, name)
        if name in RENAMED:
            return deprecated(f"fits[material].{name}", f"fits[material].{RENAMED[name]}", value)
        return value

    def __repr__(self) -> str:
        p = self.params
        return (
            f"<EnvelopeFit {self.material!r}: c = {p['c_kPa'].value:.4g} kPa, "
            f"phi = {p['phi_deg'].value:.4g} deg, n = {self.line.n}>"
        )


def envelope_fits(lines: dict, source: str = "", warnings: dict | None = None) -> dict[str, EnvelopeFit]:
    """``{material: EnvelopeFit}`` of ``{material: LineFit}`` (the API view of the dry fits).

    Parameters
    ----------
    lines : {material: LineFit}
    source : str
        Input file.
    warnings : {material: list of str}, optional

    Returns
    -------
    dict
    """
    warnings = warnings or {}
    return {m: EnvelopeFit(f, m, source, warnings.get(m, ())) for m, f in lines.items()}


def line_of(fit) -> LineFit:
    """The SI LineFit of ``fit`` (an EnvelopeFit or already a LineFit).

    Parameters
    ----------
    fit : EnvelopeFit or LineFit
        A fitted envelope.

    Returns
    -------
    LineFit
        The line fit, in SI.
    """
    return fit.line if isinstance(fit, EnvelopeFit) else fit


__all__ = ["EnvelopeFit", "envelope_fits", "line_of"]
