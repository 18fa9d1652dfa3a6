"""The one bibliography of capred: every paper the code relies on.

Code, docstrings, help texts, JSON notes, figures and the README cite a paper
as ``cite("prunier2024", "eq. 27")`` -> "Prunier et al. (2024), eq. 27".
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Reference:
    authors: str  # as cited in text: "Prunier et al.", "Kool & Parker"
    year: int | None
    title: str
    source: str  # journal, volume and pages, or the kind of document
    doi: str | None = None

    @property
    def short(self) -> str:
        return f"{self.authors} ({self.year})" if self.year else f"{self.authors} (n.d.)"

    def full(self) -> str:
        doi = f", doi:{self.doi}" if self.doi else ""
        return f"{self.short}. {self.title}. {self.source}{doi}."


REFERENCES: dict[str, Reference] = {
    "evenepoel": Reference(
        "Evenepoel", None,
        "Micro-mechanical characterization of the capillary effective stress in granular materials",
        "Master thesis, Vrije Universiteit Brussel"),
    "bernatzik1948": Reference(
        "Bernatzik", 1948,
        "The determination of the capillary rise in sand by means of prism pressure tests",
        "Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, paper II b 6"),
    "prunier2024": Reference(
        "Prunier et al.", 2024,
        "A method to evaluate the capillary stress tensor at failure in unsaturated soils",
        "Eur. J. Environ. Civ. Eng., 1-26", "10.1080/19648189.2024.2314099"),
    "pedrotti_tarantino": Reference(
        "Pedrotti & Tarantino", None,
        "Effective stresses for unsaturated states stemming from clay microstructure",
        "Submitted to Geomechanics for Energy and the Environment"),
    "morvan2016": Reference(
        "Morvan et al.", 2016, "Study of the variation of B with Sr",
        "E-UNSAT 2016, E3S Web of Conferences"),
    "vangenuchten1980": Reference(
        "van Genuchten", 1980,
        "A closed-form equation for predicting the hydraulic conductivity of unsaturated soils",
        "Soil Sci. Soc. Am. J. 44:892-898", "10.2136/sssaj1980.03615995004400050002x"),
    "brooks_corey1964": Reference(
        "Brooks & Corey", 1964, "Hydraulic properties of porous media",
        "Hydrology Paper 3, Colorado State University"),
    "kosugi1996": Reference(
        "Kosugi", 1996, "Lognormal distribution model for unsaturated soil hydraulic properties",
        "Water Resour. Res. 32(9):2697-2703", "10.1029/96WR01776"),
    "fredlund_xing1994": Reference(
        "Fredlund & Xing", 1994, "Equations for the soil-water characteristic curve",
        "Can. Geotech. J. 31(4):521-532", "10.1139/t94-061"),
    "durner1994": Reference(
        "Durner", 1994, "Hydraulic conductivity estimation for soils with heterogeneous pore structure",
        "Water Resour. Res. 30(2):211-223", "10.1029/93WR02676"),
    "kool_parker1987": Reference(
        "Kool & Parker", 1987, "Development and evaluation of closed-form expressions for hysteretic soil "
        "hydraulic properties", "Water Resour. Res. 23(1):105-114", "10.1029/WR023i001p00105"),
    "vanapalli1996": Reference(
        "Vanapalli et al.", 1996, "Model for the prediction of shear strength with respect to soil suction",
        "Can. Geotech. J. 33(3):379-392", "10.1139/t96-060"),
    "khalili_khabbaz1998": Reference(
        "Khalili & Khabbaz", 1998,
        "A unique relationship for chi for the determination of the shear strength of unsaturated soils",
        "Géotechnique 48(5):681-687", "10.1680/geot.1998.48.5.681"),
    "lu_likos2006": Reference(
        "Lu & Likos", 2006, "Suction stress characteristic curve for unsaturated soil",
        "J. Geotech. Geoenviron. Eng. 132(2):131-142", "10.1061/(ASCE)1090-0241(2006)132:2(131)"),
    "fredlund1978": Reference(
        "Fredlund et al.", 1978, "The shear strength of unsaturated soils",
        "Can. Geotech. J. 15(3):313-321", "10.1139/t78-029"),
    "bishop1959": Reference(
        "Bishop", 1959, "The principle of effective stress", "Teknisk Ukeblad 106(39):859-863"),
    "skempton1954": Reference(
        "Skempton", 1954, "The pore-pressure coefficients A and B", "Géotechnique 4(4):143-147",
        "10.1680/geot.1954.4.4.143"),
    "lian1993": Reference(
        "Lian et al.", 1993, "An analytical study of the liquid bridge between two rigid spheres",
        "J. Colloid Interface Sci. 161:138-147", "10.1006/jcis.1993.1452"),
    "willett2000": Reference(
        "Willett et al.", 2000, "Capillary bridges between two spherical bodies",
        "Langmuir 16:9396-9405", "10.1021/la000657y"),
    "israelachvili": Reference(
        "Israelachvili", None, "Intermolecular and Surface Forces", "Academic Press"),
    "duriez_wan2017": Reference(
        "Duriez & Wan", 2017, "Contact angle mechanical influence in wet granular soils",
        "Acta Geotech. 12:67-83", "10.1007/s11440-016-0500-6"),
    "seki2007": Reference(
        "Seki", 2007, "SWRC fit - a nonlinear fitting program with a water retention curve for soils "
        "having unimodal and bimodal pore structure", "Hydrol. Earth Syst. Sci. Discuss. 4:407-437"),
}


def cite(key: str, where: str | None = None) -> str:
    """In-text citation, e.g. ``cite("prunier2024", "eq. 27")`` -> 'Prunier et al. (2024), eq. 27'."""
    ref = REFERENCES[key]
    return f"{ref.short}, {where}" if where else ref.short


def bibliography(keys) -> list[str]:
    """Full entries of the given keys, in the order given, without repeats."""
    return [REFERENCES[k].full() for k in dict.fromkeys(keys)]
