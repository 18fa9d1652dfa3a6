"""Typed records of the calculators `capred prism`, `skempton-b` and `rumpf`: one array per field over the cases.

Every field names its glossary entry (capred.nomenclature.QUANTITIES) once, with :func:`case_value`; from the
field's name and that entry follow

- the Python attribute (the field's name), in the unit of the JSON and console (kPa, deg, mm, cm, N/m, -),
- the JSON key: the name plus the unit's suffix (``break_tension_kPa``, ``diameter_mm``,
  ``surface_tension_N_per_m``; nothing for a dimensionless number: ``S_r``, ``kappa``),
- the CSV header ``name [unit]`` (``break_tension [kPa]``, ``S_r [-]``),
- the console and HTML header ``symbol [unit]`` (capred.nomenclature.label: ``σ_b [kPa]``).

The JSON keys are those of capred 0.x. The CSV headers of dimensionless columns gained ``[-]`` (README,
"Renamed in this release"); capred's readers take both spellings.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..nomenclature import QUANTITIES, label
from ..result import num, unit_suffix


def case_value(quantity: str, *, output: bool = False, json: str | None = None):
    """A record field: one value per case of glossary quantity ``quantity``, in its output unit.

    Parameters
    ----------
    quantity : str
        Key of capred.nomenclature.QUANTITIES (its unit, symbol and description).
    output : bool, optional
        The calculator computes the field (False: an input of the case).
    json : str, optional
        The name in the JSON key and CSV header where capred 0.x spelled it otherwise than the Python attribute
        (``S_r`` for ``S_R``, ``kappa`` for ``kappa_elastic``).

    Returns
    -------
    dataclasses.Field
        Default None (a field the run does not have).
    """
    if quantity not in QUANTITIES:
        raise KeyError(f"{quantity!r} is not in the glossary (capred.nomenclature.QUANTITIES)")
    return field(default=None, metadata={"quantity": quantity, "output": output, "json": json})


def json_key(f: dataclasses.Field) -> str:
    """The JSON key of a case field: its name and its unit's suffix (``p0_kPa``; ``S_r`` for a number).

    Parameters
    ----------
    f : dataclasses.Field
        A field declared with :func:`case_value`.

    Returns
    -------
    str
        The key.
    """
    unit = QUANTITIES[f.metadata["quantity"]].unit
    name = f.metadata["json"] or f.name
    return name if unit in ("-", "") else f"{name}_{unit_suffix(unit)}"


def csv_header(f: dataclasses.Field) -> str:
    """The CSV header of a case field, ``name [unit]`` (``[-]`` for a number).

    Parameters
    ----------
    f : dataclasses.Field
        A field declared with :func:`case_value`.

    Returns
    -------
    str
        The header.
    """
    return f"{f.metadata['json'] or f.name} [{QUANTITIES[f.metadata['quantity']].unit or '-'}]"


def console_header(f: dataclasses.Field) -> str:
    """The console and HTML header of a case field: the glossary's ``symbol [unit]``.

    Parameters
    ----------
    f : dataclasses.Field
        A field declared with :func:`case_value`.

    Returns
    -------
    str
        E.g. ``"σ_b [kPa]"``.
    """
    return label(f.metadata["quantity"])


class Cases:
    """What every calculator record shares: its columns in output order and their JSON and CSV forms."""

    def columns(self) -> list[dataclasses.Field]:
        """The fields the run has, in the order of the JSON and the tables (inputs, then results).

        Returns
        -------
        list of dataclasses.Field
        """
        have = [f for f in dataclasses.fields(self) if "quantity" in f.metadata and getattr(self, f.name) is not None]
        return [f for f in have if not self.is_output(f)] + [f for f in have if self.is_output(f)]

    def is_output(self, f: dataclasses.Field) -> bool:
        """True when the calculator computed field ``f`` (a result), False for an input of the case.

        Parameters
        ----------
        f : dataclasses.Field
            One of the record's fields.

        Returns
        -------
        bool
        """
        return bool(f.metadata["output"])

    def __len__(self) -> int:
        first = self.columns()
        return 0 if not first else int(np.size(getattr(self, first[0].name)))

    def json_columns(self, outputs: bool | None = None) -> dict[str, np.ndarray]:
        """``{JSON key: array}`` of the inputs (``outputs=False``), the results (True) or both (None).

        Parameters
        ----------
        outputs : bool or None, optional
            Which fields.

        Returns
        -------
        dict
            JSON key -> array in the output unit.
        """
        return {
            json_key(f): np.asarray(getattr(self, f.name), float)
            for f in self.columns()
            if outputs is None or self.is_output(f) == outputs
        }

    def store_rows(self, material=None) -> list:
        """The lab store's rows of a single case: each result (not the inputs) under its JSON key.

        In its glossary unit (capred.records.StoreRow); none for several cases, whose results the JSON document does not
        give at its top level (a calculator's table of cases is not a series of one material).

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import store_row

        if len(self) != 1:
            return []
        rows = []
        for f in self.columns():
            if self.is_output(f):
                unit = QUANTITIES[f.metadata["quantity"]].unit
                row = store_row(material, json_key(f), np.asarray(getattr(self, f.name), float)[0], unit)
                if row is not None:
                    rows.append(row)
        return rows

    def csv_columns(self) -> dict[str, np.ndarray]:
        """``{name [unit]: array}`` of every field the run has, in output order.

        Returns
        -------
        dict
        """
        return {csv_header(f): np.asarray(getattr(self, f.name), float) for f in self.columns()}

    def console_columns(self) -> dict[str, np.ndarray]:
        """``{symbol [unit]: array}`` of every field the run has, in output order (console and report.html).

        Returns
        -------
        dict
        """
        return {console_header(f): np.asarray(getattr(self, f.name), float) for f in self.columns()}

    def json_rows(self, labels: list[str] | None = None) -> list[dict]:
        """One JSON object per case: its label (``case``, if any), inputs and results; NaN as None.

        Parameters
        ----------
        labels : list of str or None, optional
            The cases' labels.

        Returns
        -------
        list of dict
        """
        cols = {k: [num(x) for x in v] for k, v in self.json_columns().items()}
        return [
            {**({"case": labels[i]} if labels else {}), **{k: c[i] for k, c in cols.items()}} for i in range(len(self))
        ]


@dataclass(frozen=True, eq=False)
class PrismCases(Cases):
    """`capred prism` per case (Bernatzik 1948): the break tension and friction angle, P_kmax and h_c.

    Attributes
    ----------
    break_tension : ndarray
        Break tension σ_b of the prism [kPa].
    friction_angle : ndarray
        Friction angle ρ of the sand [deg].
    P_kmax : ndarray
        Maximal capillary pressure σ_b (1 − sin ρ)/(2 sin ρ) [kPa].
    capillary_rise : ndarray
        Capillary rise h_c = P_kmax/γ_w [cm].
    P_kmax_over_sigma_b : ndarray
        P_kmax/σ_b [-].

    References
    ----------
    .. [1] Bernatzik, W. (1948). The determination of the capillary rise in sand by means of prism pressure
       tests. Proc. 2nd Int. Conf. Soil Mech. Found. Eng., Rotterdam, paper II b 6.
    """

    break_tension: np.ndarray = case_value("break_tension")
    friction_angle: np.ndarray = case_value("friction_angle")
    P_kmax: np.ndarray = case_value("P_kmax", output=True)
    capillary_rise: np.ndarray = case_value("capillary_rise", output=True)
    P_kmax_over_sigma_b: np.ndarray = case_value("P_kmax_over_sigma_b", output=True)


@dataclass(frozen=True, eq=False)
class SkemptonCases(Cases):
    """`capred skempton-b` per case (Morvan et al. 2016): B from S_r, or S_r from B.

    Attributes
    ----------
    S_R, B : ndarray
        Degree of saturation [-] (JSON ``S_r``) and Skempton's B [-]: the one given, and the one computed
        (``solved``).
    kappa_elastic, e0 : ndarray
        Slope of the elastic line in e-ln p' [-] and initial void ratio [-].
    p0, u0, pa0 : ndarray
        Mean total stress, initial pore pressure and absolute initial air pressure [kPa].
    s_e, bc_lambda : ndarray or None
        Brooks-Corey air-entry suction [kPa] and pore-size index [-] of the suction-equilibrium model (None
        without it).
    solved : str
        ``"B"`` or ``"S_R"``: the field the calculator computed.

    References
    ----------
    .. [1] Morvan, M., Vernay, M., Breul, P. (2016). Study of the variation of B with Sr. E-UNSAT 2016,
       E3S Web of Conferences; eqs. 10, 13-24.
    """

    S_R: np.ndarray = case_value("S_R", json="S_r")
    B: np.ndarray = case_value("B")
    kappa_elastic: np.ndarray = case_value("kappa_elastic", json="kappa")
    e0: np.ndarray = case_value("e0")
    p0: np.ndarray = case_value("p0")
    u0: np.ndarray = case_value("u0")
    pa0: np.ndarray = case_value("pa0")
    s_e: np.ndarray = case_value("air_entry")
    bc_lambda: np.ndarray = case_value("bc_lambda")
    solved: str = "B"

    def is_output(self, f: dataclasses.Field) -> bool:
        """True for the one of S_R and B the calculator solved for, False for every other field.

        Parameters
        ----------
        f : dataclasses.Field
            One of the record's fields.

        Returns
        -------
        bool
        """
        return f.name == self.solved

    def columns(self) -> list[dataclasses.Field]:
        """The given one of S_R and B first, then the model's inputs, then the computed one (capred 0.x's order).

        Returns
        -------
        list of dataclasses.Field
        """
        have = [f for f in dataclasses.fields(self) if "quantity" in f.metadata and getattr(self, f.name) is not None]
        given = [f for f in have if f.name in ("S_R", "B") and f.name != self.solved]
        rest = [f for f in have if f.name not in ("S_R", "B")]
        return given + rest + [f for f in have if f.name == self.solved]


@dataclass(frozen=True, eq=False)
class SkemptonCurves(Cases):
    """`capred skempton-b --curve`: B against S_r for every model the options ask for (Morvan et al. 2016).

    Attributes
    ----------
    S_R : ndarray
        Degrees of saturation of the curve [-] (JSON ``S_r``).
    B_eq10, B_suction, B_bounding_NC, B_bounding_OC : ndarray or None
        B of the elastic skeleton (eq. 10), with suction equilibrium, and of the bounding-surface
        reconstruction normally and over-consolidated [-] (None: not asked for).
    B_skempton1954, B_hilf_lade, B_schuurman1966 : ndarray or None
        The classical relations of ``--compare`` (capred.physics.calculators.SKEMPTON_RELATIONS) on the same
        skeleton [-].

    References
    ----------
    .. [1] Morvan, M., Vernay, M., Breul, P. (2016). E-UNSAT 2016; eqs. 10, 13-24; Fig. 1-3, 5, 6.
    """

    S_R: np.ndarray = case_value("S_R", json="S_r")
    B_eq10: np.ndarray = case_value("B", output=True)
    B_suction: np.ndarray = case_value("B", output=True)
    B_bounding_NC: np.ndarray = case_value("B", output=True)
    B_bounding_OC: np.ndarray = case_value("B", output=True)
    B_skempton1954: np.ndarray = case_value("B", output=True)
    B_hilf_lade: np.ndarray = case_value("B", output=True)
    B_schuurman1966: np.ndarray = case_value("B", output=True)

    def console_columns(self) -> dict[str, np.ndarray]:
        """``{header: array}``: S_R [-] then each model's B under its name (one symbol, several curves).

        Returns
        -------
        dict
        """
        return {
            (console_header(f) if f.name == "S_R" else f"{f.name} [-]"): np.asarray(getattr(self, f.name), float)
            for f in self.columns()
        }


@dataclass(frozen=True, eq=False)
class RumpfCases(Cases):
    """`capred rumpf` per case: Rumpf's mean capillary stress of a granular packing (Prunier et al. 2024, eq. 19).

    Attributes
    ----------
    shape_factor, void_ratio, S_R : ndarray
        Particle shape factor, void ratio and degree of saturation [-] (JSON ``S_r``).
    diameter : ndarray
        Apparent particle diameter [mm].
    surface_tension : ndarray
        Surface tension of water [N/m].
    contact_angle : ndarray
        Contact angle [deg].
    p_cap : ndarray
        Mean capillary stress [kPa] (negative: tensile).

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J., Darve, F. (2024). Eur. J. Environ. Civ. Eng.
       doi:10.1080/19648189.2024.2314099, eq. 19.
    """

    shape_factor: np.ndarray = case_value("shape_factor")
    void_ratio: np.ndarray = case_value("void_ratio")
    S_R: np.ndarray = case_value("S_R", json="S_r")
    diameter: np.ndarray = case_value("diameter")
    surface_tension: np.ndarray = case_value("surface_tension")
    contact_angle: np.ndarray = case_value("contact_angle")
    p_cap: np.ndarray = case_value("p_cap", output=True)


@dataclass(frozen=True, eq=False)
class ShearBandCases(Cases):
    """`capred shear-band` per case: the classical shear-band angles beside a measured one.

    Attributes
    ----------
    phi_eff : ndarray
        Effective friction angle φ' [deg].
    dilatancy_angle : ndarray or None
        Dilatancy angle ψ [deg] (given, or from the dilatancy rate).
    measured : ndarray or None
        Measured angle of the band [deg] (NaN where none).
    coulomb, roscoe, arthur : ndarray
        45 + φ'/2, 45 + ψ/2 and 45 + (φ' + ψ)/4 [deg] (Roscoe and Arthur need ψ).
    coulomb_minus_measured, roscoe_minus_measured, arthur_minus_measured : ndarray or None
        Differences to the measured angle [deg].

    References
    ----------
    .. [1] Roscoe (1970), Géotechnique 20(2), 129-170; Arthur et al. (1977), Géotechnique 27(1), 53-74;
       Prunier et al. (2024), Fig. 14 (measured 70 and 60 deg).
    """

    phi_eff: np.ndarray = case_value("phi_eff")
    dilatancy_angle: np.ndarray = case_value("dilatancy_angle")
    measured: np.ndarray = case_value("shear_band_angle")
    coulomb: np.ndarray = case_value("shear_band_angle", output=True)
    roscoe: np.ndarray = case_value("shear_band_angle", output=True)
    arthur: np.ndarray = case_value("shear_band_angle", output=True)
    coulomb_minus_measured: np.ndarray = case_value("shear_band_angle", output=True)
    roscoe_minus_measured: np.ndarray = case_value("shear_band_angle", output=True)
    arthur_minus_measured: np.ndarray = case_value("shear_band_angle", output=True)

    def console_columns(self) -> dict[str, np.ndarray]:
        """The console table's columns: each angle under its own name (one symbol, several angles).

        Returns
        -------
        dict of str to numpy.ndarray
            ``{header: angles [deg]}``.
        """
        return {f"{f.name} [deg]": np.asarray(getattr(self, f.name), float) for f in self.columns()}
