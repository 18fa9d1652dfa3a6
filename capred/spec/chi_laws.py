"""The χ laws fitted per material by `capred shear` and `capred triaxial`.

One registry, declared without numerics.

A χ law is fitted on the wet tests of the effective-stress model of the same name (its ``fitted`` parameters).
Each entry of :data:`LAWS` names its parameters, a typical value of each (SI) and its functions as
``"module:function"``: the law χ itself, its one-shot fit and its batch refit (the functions live in
`capred.fitting.chi_laws`, imported only when a law is fitted). Importing this module imports no numpy.

References
----------
.. [1] Vanapalli, S. K., Fredlund, D. G., Pufahl, D. E. & Clifton, A. W. (1996). Model for the prediction
   of shear strength with respect to soil suction. Can. Geotech. J. 33(3):379-392, doi:10.1139/t96-060.
.. [2] Khalili, N. & Khabbaz, M. H. (1998). A unique relationship for chi for the determination of the
   shear strength of unsaturated soils. Geotechnique 48(5):681-687, doi:10.1680/geot.1998.48.5.681.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .callables import CallableField

__all__ = ["LAWS", "ChiLaw"]


@dataclass(frozen=True)
class ChiLaw:
    """A fitted χ law of the effective-stress registry: its parameters, χ, its one-shot fit and its batch refit.

    The callable fields are declared as ``"module:function"`` strings or given as callables; reading one gives
    the callable.

    Attributes
    ----------
    fit : callable
        ``fit(w, model_params, start=None, dry=None) -> FittedLaw`` on the wet tests ``w``
        (a `capred.physics.effective_stress_models.ModelInputs`).
    refit_batch : callable
        ``refit_batch(w, model_params, c, tan_phi, weights, start) -> (params, residuals)`` for R
        replicates (see `capred.fitting.chi_laws.refit_chi_power_batch`).
    name : str
        The name of the law and of its effective-stress model (a key of
        `capred.spec.effective_stress.REGISTRY`).
    parameters : tuple of str
        SI names of the fitted parameters (keys of `capred.fitting.chi_laws.LAW_PARAMETERS`).
    typical : dict
        A typical value of each parameter (SI): the law's conformance check evaluates χ there.
    chi : callable
        ``chi(S_R, suction, **params) -> χ`` [-] over broadcast arrays (S_R [-], suction [Pa], the parameters
        in SI).
    """

    fit: object = field(default=CallableField(), repr=False)
    refit_batch: object = field(default=CallableField(), repr=False)
    name: str = ""
    parameters: tuple[str, ...] = ()
    typical: dict = field(default_factory=dict)
    chi: object = field(default=CallableField(), repr=False)


_F = "capred.fitting.chi_laws:"

#: every fitted χ law, by the name of its effective-stress model
LAWS: dict[str, ChiLaw] = {
    law.name: law
    for law in (
        ChiLaw(
            _F + "_fit_chi_power_law",
            _F + "_refit_chi_power_law",
            name="chi_power",
            parameters=("kappa",),
            typical={"kappa": 2.0},
            chi=_F + "chi_power_law",
        ),
        ChiLaw(
            _F + "_fit_khalili_law",
            _F + "_refit_khalili_law",
            name="khalili_fit",
            parameters=("s_b", "eta"),
            typical={"s_b": 20e3, "eta": 0.55},
            chi=_F + "khalili_law",
        ),
    )
}
