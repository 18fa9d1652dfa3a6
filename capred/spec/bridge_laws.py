"""The closed-form capillary-force laws of `capred bridge laws` and `capred bridge compare`.

One registry, declared without numerics.

Each law is one entry of :data:`LAWS`: its name, label, paper, equation, validity and the geometries it applies
to, with its force function named as ``"module:function"`` (the functions live in `capred.physics.bridge_laws`,
imported only when a force is computed). Adding a law is adding one entry; both commands, their tables and
figures read only this registry. Importing this module imports no numpy.

References
----------
.. [1] Willett, C. D., Adams, M. J., Johnson, S. A. & Seville, J. P. K. (2000). Capillary bridges between two
   spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y (the laws' common dimensionless form).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .callables import CallableField

__all__ = ["GEOMETRIES", "LAWS", "Law"]

#: the geometries a law may apply to: two equal spheres, two spheres of other radii, a sphere and a plane
GEOMETRIES = ("equal", "unequal", "plane")


@dataclass(frozen=True)
class Law:
    """One closed-form capillary-force law.

    Attributes
    ----------
    name : str
        Registry key (JSON, CSV and CLI spelling).
    label : str
        Short label of figures and tables.
    citation : str
        The paper (authors, year, journal).
    doi : str
        Its DOI.
    equation : str
        The equation implemented, in the paper's terms.
    validity : str
        The range the paper fitted or derived it for.
    geometries : tuple of str
        Where it applies: "equal" (equal spheres), "unequal" (spheres of other radii), "plane".
    force : callable
        ``force(theta, V, D, rho)``: F / (2 pi R1 gamma) [-] over broadcast arrays (theta [rad], V = V/R1^3,
        D = D/R1, rho = R2/R1); NaN where the law gives no force. Declared as ``"module:function"`` or given as
        a callable; reading it gives the callable.
    """

    name: str
    label: str
    citation: str
    doi: str
    equation: str
    validity: str
    geometries: tuple[str, ...]
    force: object = field(default=CallableField(), repr=False)


_F = "capred.physics.bridge_laws:"

#: every closed-form law, by name: one entry each (the commands, their tables and figures read only this)
LAWS: dict[str, Law] = {
    law.name: law
    for law in (
        Law(
            "willett_simple",
            "Willett (simple)",
            "Willett, Adams, Johnson & Seville (2000), Langmuir 16, 9396-9405",
            "10.1021/la000657y",
            "F/(2πR*γ) = cos θ/(1 + 2.1 S⁺ + 10 S⁺²), S⁺ = (D/2)√(R*/V) (eqs. 12-13)",
            "small volumes; derived for equal spheres, R* for others",
            ("equal", "unequal", "plane"),
            _F + "willett_simple",
        ),
        Law(
            "willett_full",
            "Willett (full)",
            "Willett, Adams, Johnson & Seville (2000), Langmuir 16, 9396-9405",
            "10.1021/la000657y",
            "ln F/(2πR*γ) = f1 − f2 exp(f3 ln S⁺ + f4 ln² S⁺) (appendix)",
            "equal spheres, θ 0-50°, V/R³ 1e-5 to 0.1, D > 0",
            ("equal", "unequal", "plane"),
            _F + "willett_full",
        ),
        Law(
            "rabinovich",
            "Rabinovich",
            "Rabinovich, Esayanur & Moudgil (2005), Langmuir 21, 10992-10997",
            "10.1021/la0517639",
            "F/(2πR*γ) = cos θ/(1 + D/(2d)) + sin α sin(θ + α), d = (D/2)(√(1 + 2V/(πR*D²)) − 1) (eqs. 19, 20, A3)",
            "small filling angles; equal spheres, R* for others",
            ("equal", "unequal", "plane"),
            _F + "rabinovich",
        ),
        Law(
            "lambert",
            "Lambert",
            "Lambert, Chau, Delchambre & Régnier (2008), Langmuir 24, 3157-3163",
            "10.1021/la7036444",
            "F/(2πR*γ) = cos θ/(1 + D/(2d)) (eq. 65)",
            "small filling angles; equal spheres, R* for others",
            ("equal", "unequal", "plane"),
            _F + "lambert",
        ),
        Law(
            "soulie",
            "Soulié",
            "Soulié, Cherblanc, El Youssoufi & Saix (2006), Int. J. Numer. Anal. Methods Geomech. 30, 213-228",
            "10.1002/nag.476",
            "F = πγ√(R1R2)[c + exp(a D/R + b)], a, b, c in ln(V/R³), R the larger radius",
            "sphere pairs (not a plane); regression of exact bridges",
            ("equal", "unequal"),
            _F + "soulie",
        ),
        Law(
            "mikami",
            "Mikami",
            "Mikami, Kamiya & Horio (1998), Chem. Eng. Sci. 53, 1927-1940",
            "10.1016/S0009-2509(97)00325-4",
            "F = πγR*[exp(A D/R* + B) + C], A = −1.1 V⁺^−0.53, B = (−0.34 ln V⁺ − 0.96)θ² − 0.019 ln V⁺ + 0.48, "
            "C = 0.0042 ln V⁺ + 0.078, V⁺ = V/R*³",
            "equal spheres (R* for others), D below the rupture gap (0.62θ + 0.99)V⁺^0.34 R*; within 4 % of the "
            "exact bridge at θ = 0, V/R³ 1e-4 to 1e-2, D/R ≤ 0.05; overestimates for θ > 0",
            ("equal", "unequal"),
            _F + "mikami",
        ),
        Law(
            "weigert_ripperger",
            "Weigert & Ripperger",
            "Weigert & Ripperger (1999), Part. Part. Syst. Charact. 16, 238-242",
            "10.1002/(SICI)1521-4117(199910)16:5<238::AID-PPSC238>3.0.CO;2-E",
            "toroidal bridge, sin β = [V/(0.12 C_a C_θ d³)]^(1/4), F at the contact line (eqs. 5-6, 15-17, 21-22)",
            "equal spheres near contact (their fit of β ignores most of the gap)",
            ("equal", "unequal", "plane"),
            _F + "weigert_ripperger",
        ),
    )
}
