"""Typed record of `capred bridge solve`: one field per output quantity, each with its JSON key, CSV column and
unit declared once (capred.result.output); JSON keys and CSV headers follow from it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..result import output, record_outputs


@dataclass(frozen=True)
class BridgeRecord:
    """The bridges of a run in output units, one value per row (NaN where no bridge was found).

    Attributes
    ----------
    r0 : ndarray
        Neck radius [mm] (a virtual neck behind one contact when the meridian widens across the bridge).
    F_cap : ndarray
        Capillary force F_cap = F_L + F_T [mN].
    F_L : ndarray
        Its pressure part pi r0^2 Delta_u [mN].
    F_T : ndarray
        Its surface-tension part 2 pi r0 gamma [mN].
    V_w : ndarray
        Water volume [mm^3].
    filling_angle : ndarray
        Filling angle on particle 1 (radius R) [deg].
    filling_angle2 : ndarray
        Filling angle on particle 2 [deg]; 0 on a plane.
    suction : ndarray
        Suction Delta_u [kPa].
    S_R : ndarray
        Degree of saturation of the unit cell of particle 1, 3 V_w / (2 pi R^3) [-].
    sigma_prime : ndarray
        F_cap / (pi R^2) [kPa].
    area : ndarray
        Liquid-gas interface area [mm^2].
    nn11, nn33 : ndarray
        Transverse (= nn22) and axial components of the integral of n (x) n over that interface [mm^2].
    """

    r0: np.ndarray = output("r0_mm", "r0", "mm")
    F_cap: np.ndarray = output("F_cap_mN", "F_cap", "mN")
    F_L: np.ndarray = output("F_L_mN", "F_L", "mN")
    F_T: np.ndarray = output("F_T_mN", "F_T", "mN")
    V_w: np.ndarray = output("V_w_mm3", "V_w", "mm^3")
    filling_angle: np.ndarray = output("filling_angle_deg", "filling_angle", "deg")
    filling_angle2: np.ndarray = output("filling_angle2_deg", "filling_angle2", "deg")
    suction: np.ndarray = output("suction_kPa", "suction", "kPa")
    S_R: np.ndarray = output("S_R", "S_R", "")
    sigma_prime: np.ndarray = output("sigma_prime_kPa", "sigma_prime", "kPa")
    area: np.ndarray = output("area_mm2", "area", "mm^2")
    nn11: np.ndarray = output("nn11_mm2", "nn11", "mm^2")
    nn33: np.ndarray = output("nn33_mm2", "nn33", "mm^2")

    def columns(self) -> dict[str, np.ndarray]:
        """The output columns under their JSON keys, in declaration order.

        Returns
        -------
        dict of str to numpy.ndarray
            JSON key -> values (output units).
        """
        return {o.json: v for _, o, v in record_outputs(self)}

    @staticmethod
    def csv_headers() -> dict[str, str]:
        """JSON key -> CSV header (``name [unit]``, ``[-]`` for a dimensionless value) of every field.

        Returns
        -------
        dict of str to str
        """
        import dataclasses

        out = {}
        for f in dataclasses.fields(BridgeRecord):
            o = f.metadata["output"]
            out[o.json] = f"{o.column} [{o.unit or '-'}]"
        return out
