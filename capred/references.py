"""The one bibliography of capred: every paper the code relies on.

Code, docstrings, help texts, JSON notes, figures and the README cite a paper
as ``cite("prunier2024", "eq. 27")`` -> "Prunier et al. (2024), eq. 27".
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Reference:
    """One published source of capred's models and methods.

    Attributes
    ----------
    authors : str
        As cited in text: ``"Prunier et al."``, ``"Kool & Parker"``.
    year : int or None
        Year of publication (None: not dated).
    title : str
        Title of the work.
    source : str
        Journal, volume and pages, or the kind of document.
    doi : str or None
        Its DOI, without ``https://doi.org/``.
    """

    authors: str  # as cited in text: "Prunier et al.", "Kool & Parker"
    year: int | None
    title: str
    source: str  # journal, volume and pages, or the kind of document
    doi: str | None = None

    @property
    def short(self) -> str:
        """The citation in text: ``authors (year)``, or ``authors (n.d.)`` without a year."""
        return f"{self.authors} ({self.year})" if self.year else f"{self.authors} (n.d.)"

    def full(self) -> str:
        """The full bibliography entry: authors (year). Title. Source, doi.

        Returns
        -------
        str
        """
        doi = f", doi:{self.doi}" if self.doi else ""
        return f"{self.short}. {self.title}. {self.source}{doi}."


REFERENCES: dict[str, Reference] = {
    "evenepoel": Reference(
        "Evenepoel",
        None,
        "Micro-mechanical characterization of the capillary effective stress in granular materials",
        "Master thesis, Vrije Universiteit Brussel",
    ),
    "bernatzik1948": Reference(
        "Bernatzik",
        1948,
        "The determination of the capillary rise in sand by means of prism pressure tests",
        "Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, paper II b 6",
    ),
    "prunier2024": Reference(
        "Prunier et al.",
        2024,
        "A method to evaluate the capillary stress tensor at failure in unsaturated soils",
        "Eur. J. Environ. Civ. Eng., 1-26",
        "10.1080/19648189.2024.2314099",
    ),
    "pedrotti_tarantino_submitted": Reference(
        "Pedrotti & Tarantino",
        None,
        "Effective stresses for unsaturated states stemming from clay microstructure",
        "Submitted to Geomechanics for Energy and the Environment",
    ),
    "morvan2016": Reference(
        "Morvan et al.", 2016, "Study of the variation of B with Sr", "E-UNSAT 2016, E3S Web of Conferences"
    ),
    "morvan_wong_branque2010": Reference(
        "Morvan et al.",
        2010,
        "An unsaturated soil model with minimal number of parameters based on bounding surface plasticity",
        "Int. J. Numer. Anal. Meth. Geomech. 34:1512-1537",
    ),
    "pedrotti_tarantino2019": Reference(
        "Pedrotti & Tarantino",
        2019,
        "A conceptual constitutive model unifying slurried (saturated), compacted (unsaturated) and dry states",
        "Géotechnique 69(3):217-233",
    ),
    "astm_d4767": Reference(
        "ASTM International",
        2011,
        "Standard test method for consolidated undrained triaxial compression test for cohesive soils",
        "ASTM D4767-11",
    ),
    "vangenuchten1980": Reference(
        "van Genuchten",
        1980,
        "A closed-form equation for predicting the hydraulic conductivity of unsaturated soils",
        "Soil Sci. Soc. Am. J. 44:892-898",
        "10.2136/sssaj1980.03615995004400050002x",
    ),
    "brooks_corey1964": Reference(
        "Brooks & Corey", 1964, "Hydraulic properties of porous media", "Hydrology Paper 3, Colorado State University"
    ),
    "lenhard1989": Reference(
        "Lenhard et al.",
        1989,
        "On the correspondence between Brooks-Corey and van Genuchten models",
        "J. Irrig. Drain. Eng. 115(4):744-751",
        "10.1061/(ASCE)0733-9437(1989)115:4(744)",
    ),
    "kosugi1996": Reference(
        "Kosugi",
        1996,
        "Lognormal distribution model for unsaturated soil hydraulic properties",
        "Water Resour. Res. 32(9):2697-2703",
        "10.1029/96WR01776",
    ),
    "fredlund_xing1994": Reference(
        "Fredlund & Xing",
        1994,
        "Equations for the soil-water characteristic curve",
        "Can. Geotech. J. 31(4):521-532",
        "10.1139/t94-061",
    ),
    "durner1994": Reference(
        "Durner",
        1994,
        "Hydraulic conductivity estimation for soils with heterogeneous pore structure",
        "Water Resour. Res. 30(2):211-223",
        "10.1029/93WR02676",
    ),
    "kool_parker1987": Reference(
        "Kool & Parker",
        1987,
        "Development and evaluation of closed-form expressions for hysteretic soil hydraulic properties",
        "Water Resour. Res. 23(1):105-114",
        "10.1029/WR023i001p00105",
    ),
    "parker_lenhard1987": Reference(
        "Parker & Lenhard",
        1987,
        "A model for hysteretic constitutive relations governing multiphase flow: 1. Saturation-pressure relations",
        "Water Resour. Res. 23(12):2187-2196",
        "10.1029/WR023i012p02187",
    ),
    "mualem1974": Reference(
        "Mualem",
        1974,
        "A conceptual model of hysteresis",
        "Water Resour. Res. 10(3):514-520",
        "10.1029/WR010i003p00514",
    ),
    "vanapalli1996": Reference(
        "Vanapalli et al.",
        1996,
        "Model for the prediction of shear strength with respect to soil suction",
        "Can. Geotech. J. 33(3):379-392",
        "10.1139/t96-060",
    ),
    "khalili_khabbaz1998": Reference(
        "Khalili & Khabbaz",
        1998,
        "A unique relationship for chi for the determination of the shear strength of unsaturated soils",
        "Géotechnique 48(5):681-687",
        "10.1680/geot.1998.48.5.681",
    ),
    "lu_likos2006": Reference(
        "Lu & Likos",
        2006,
        "Suction stress characteristic curve for unsaturated soil",
        "J. Geotech. Geoenviron. Eng. 132(2):131-142",
        "10.1061/(ASCE)1090-0241(2006)132:2(131)",
    ),
    "fredlund1978": Reference(
        "Fredlund et al.",
        1978,
        "The shear strength of unsaturated soils",
        "Can. Geotech. J. 15(3):313-321",
        "10.1139/t78-029",
    ),
    "bishop1959": Reference("Bishop", 1959, "The principle of effective stress", "Teknisk Ukeblad 106(39):859-863"),
    "skempton1954": Reference(
        "Skempton",
        1954,
        "The pore-pressure coefficients A and B",
        "Géotechnique 4(4):143-147",
        "10.1680/geot.1954.4.4.143",
    ),
    "lian1993": Reference(
        "Lian et al.",
        1993,
        "An analytical study of the liquid bridge between two rigid spheres",
        "J. Colloid Interface Sci. 161:138-147",
        "10.1006/jcis.1993.1452",
    ),
    "willett2000": Reference(
        "Willett et al.",
        2000,
        "Capillary bridges between two spherical bodies",
        "Langmuir 16:9396-9405",
        "10.1021/la000657y",
    ),
    "israelachvili": Reference("Israelachvili", 2011, "Intermolecular and Surface Forces", "3rd ed., Academic Press"),
    "orr1975": Reference(
        "Orr et al.",
        1975,
        "Pendular rings between solids: meniscus properties and capillary force",
        "J. Fluid Mech. 67(4):723-742",
        "10.1017/S0022112075000572",
    ),
    "fisher1926": Reference(
        "Fisher",
        1926,
        "On the capillary forces in an ideal soil; correction of formulae given by W. B. Haines",
        "J. Agric. Sci. 16(3):492-505",
        "10.1017/S0021859600007838",
    ),
    "duriez_wan2017": Reference(
        "Duriez & Wan",
        2017,
        "Contact angle mechanical influence in wet granular soils",
        "Acta Geotech. 12:67-83",
        "10.1007/s11440-016-0500-6",
    ),
    "golub_pereyra1973": Reference(
        "Golub & Pereyra",
        1973,
        "The differentiation of pseudo-inverses and nonlinear least squares problems whose variables separate",
        "SIAM J. Numer. Anal. 10(2):413-432",
        "10.1137/0710036",
    ),
    "marquardt1963": Reference(
        "Marquardt",
        1963,
        "An algorithm for least-squares estimation of nonlinear parameters",
        "J. Soc. Ind. Appl. Math. 11(2):431-441",
        "10.1137/0111030",
    ),
    "bates_watts1988": Reference(
        "Bates & Watts", 1988, "Nonlinear Regression Analysis and Its Applications", "Wiley", "10.1002/9780470316757"
    ),
    "efron_tibshirani1993": Reference(
        "Efron & Tibshirani", 1993, "An Introduction to the Bootstrap", "Chapman & Hall", "10.1007/978-1-4899-4541-9"
    ),
    "murphy_topel1985": Reference(
        "Murphy & Topel",
        1985,
        "Estimation and inference in two-step econometric models",
        "J. Bus. Econ. Stat. 3(4):370-379",
        "10.1080/07350015.1985.10509470",
    ),
    "draper_smith1998": Reference(
        "Draper & Smith", 1998, "Applied Regression Analysis", "3rd ed., Wiley", "10.1002/9781118625590"
    ),
    "seber_wild1989": Reference("Seber & Wild", 1989, "Nonlinear Regression", "Wiley", "10.1002/0471725315"),
    "burnham_anderson2002": Reference(
        "Burnham & Anderson", 2002, "Model Selection and Multimodel Inference", "2nd ed., Springer", "10.1007/b97636"
    ),
    "seki2007": Reference(
        "Seki",
        2007,
        "SWRC fit - a nonlinear fitting program with a water retention curve for soils "
        "having unimodal and bimodal pore structure",
        "Hydrol. Earth Syst. Sci. Discuss. 4:407-437",
    ),
    # compression, the classical B(S_r) relations, shear-band angles and Mikami's bridge law (issue 45)
    "casagrande1936": Reference(
        "Casagrande",
        1936,
        "The determination of the pre-consolidation load and its practical significance",
        "Proc. 1st Int. Conf. Soil Mech. Found. Eng., Cambridge MA, 3:60-64",
    ),
    "pacheco_silva1970": Reference(
        "Pacheco Silva",
        1970,
        "A new graphical construction for determination of the pre-consolidation stress of a soil sample",
        "Proc. 4th Brazilian Conf. Soil Mech. Found. Eng., Rio de Janeiro, 2(1):225-232",
    ),
    "schofield_wroth1968": Reference("Schofield & Wroth", 1968, "Critical State Soil Mechanics", "McGraw-Hill, London"),
    "mikami1998": Reference(
        "Mikami et al.",
        1998,
        "Numerical simulation of cohesive powder behavior in a fluidized bed",
        "Chem. Eng. Sci. 53(10):1927-1940",
        "10.1016/S0009-2509(97)00325-4",
    ),
    "hilf1948": Reference(
        "Hilf",
        1948,
        "Estimating construction pore pressures in rolled earth dams",
        "Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, 3:234-240",
    ),
    "lade_hernandez1977": Reference(
        "Lade & Hernandez",
        1977,
        "Membrane penetration effects in undrained tests",
        "J. Geotech. Eng. Div. ASCE 103(GT2):109-125",
    ),
    "schuurman1966": Reference(
        "Schuurman",
        1966,
        "The compressibility of an air/water mixture and a theoretical relation between the air and water pressures",
        "Géotechnique 16(4):269-281",
        "10.1680/geot.1966.16.4.269",
    ),
    "hasan_fredlund1980": Reference(
        "Hasan & Fredlund",
        1980,
        "Pore pressure parameters for unsaturated soils",
        "Can. Geotech. J. 17(3):395-404",
        "10.1139/t80-046",
    ),
    "roscoe1970": Reference(
        "Roscoe",
        1970,
        "The influence of strains in soil mechanics",
        "Géotechnique 20(2):129-170",
        "10.1680/geot.1970.20.2.129",
    ),
    "arthur1977": Reference(
        "Arthur et al.",
        1977,
        "Plastic deformation and failure in granular media",
        "Géotechnique 27(1):53-74",
        "10.1680/geot.1977.27.1.53",
    ),
}


def cite(key: str, where: str | None = None) -> str:
    """In-text citation, e.g. ``cite("prunier2024", "eq. 27")`` -> 'Prunier et al. (2024), eq. 27'.

    Parameters
    ----------
    key : str
        A key of ``REFERENCES``.
    where : str or None, optional
        Equation, table or figure cited.

    Returns
    -------
    str
    """
    ref = REFERENCES[key]
    return f"{ref.short}, {where}" if where else ref.short


def bibliography(keys) -> list[str]:
    """Full entries of the given keys, in the order given, without repeats.

    Parameters
    ----------
    keys : iterable of str
        Keys of ``REFERENCES``.

    Returns
    -------
    list of str
    """
    return [REFERENCES[k].full() for k in dict.fromkeys(keys)]
