"""Typed records of `capred bridge solve | compare | rupture | yade-files`.

One field per output column, each with its JSON key, CSV column and unit declared once (capred.result.output, or
:func:`capred.pipelines.row_records.plain` for a label or status); JSON keys, CSV headers and console headers follow
from it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..result import output, record_outputs
from .row_records import RowRecord, plain


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


@dataclass(frozen=True)
class CompareRecord(RowRecord):
    """``capred bridge compare``: per micro-test, the measured force beside the exact bridge and approximations.

    Three approximations, in output units (NaN where a model gives no bridge).

    Attributes
    ----------
    case : list of str or None
        The rows' labels (None without a ``case`` column).
    F_measured : ndarray
        Measured capillary force [mN].
    F_exact, F_toroidal, F_willett, F_israelachvili : ndarray
        Force of the exact bridge, the toroidal approximation (equal spheres), Willett et al. (2000) and
        Israelachvili (Derjaguin) [mN].
    residual_exact, residual_toroidal, residual_willett, residual_israelachvili : ndarray
        Each model's force minus the measured one [mN].
    filling_angle_measured, filling_angle_exact : ndarray
        Measured filling angle (NaN where not measured) and that of the exact bridge [deg].
    status : list of str
        Status of the exact bridge ('ok' ...).
    laws : dict, optional
        Law name -> (force, force minus the measured one) [mN] of every closed-form law of the law registry
        (`capred.spec.bridge_laws.LAWS`), NaN where a law does not apply to the pair's geometry: the columns
        ``F_<law>_mN`` and ``residual_<law>_mN`` after ``status``.

    References
    ----------
    .. [1] Willett, C. D., Adams, M. J., Johnson, S. A., Seville, J. P. K. (2000). Capillary bridges
       between two spherical bodies. Langmuir 16, 9396-9405. doi:10.1021/la000657y
    """

    case: list | None = plain("case")
    F_measured: np.ndarray = output("F_measured_mN", "F_measured", "mN")
    F_exact: np.ndarray = output("F_exact_mN", "F_exact", "mN")
    residual_exact: np.ndarray = output("residual_exact_mN", "residual_exact", "mN")
    F_toroidal: np.ndarray = output("F_toroidal_mN", "F_toroidal", "mN")
    residual_toroidal: np.ndarray = output("residual_toroidal_mN", "residual_toroidal", "mN")
    F_willett: np.ndarray = output("F_willett_mN", "F_willett", "mN")
    residual_willett: np.ndarray = output("residual_willett_mN", "residual_willett", "mN")
    F_israelachvili: np.ndarray = output("F_israelachvili_mN", "F_israelachvili", "mN")
    residual_israelachvili: np.ndarray = output("residual_israelachvili_mN", "residual_israelachvili", "mN")
    filling_angle_measured: np.ndarray = output("filling_angle_measured_deg", "filling_angle_measured", "deg")
    filling_angle_exact: np.ndarray = output("filling_angle_exact_deg", "filling_angle_exact", "deg")
    status: list = plain("status")
    laws: dict | None = None

    def _columns(self):
        yield from super()._columns()
        for name, (force, residual) in (self.laws or {}).items():
            yield f"F_{name}_mN", f"F_{name} [mN]", force
            yield f"residual_{name}_mN", f"residual_{name} [mN]", residual


#: how a plane (R2 = inf) is written in the JSON rows of `bridge rupture` and shown in the console
PLANE = "plane"


@dataclass(frozen=True)
class RuptureRecord(RowRecord):
    """``capred bridge rupture``: per case, the rupture distance at constant volume and the bridge at rupture.

    Beside Lian et al.'s (1993) estimate, in output units (NaN where no rupture was found).

    Attributes
    ----------
    case : list of str or None
        The rows' labels (None without a ``case`` column).
    R, R2 : ndarray
        Radii of the particles [mm]; R2 is inf for a plane (written ``plane`` in the JSON rows).
    contact_angle : ndarray
        Contact angle [deg].
    V_w : ndarray
        Water volume [mm^3].
    D_rupture, D_rupture_lian : ndarray
        Rupture distance, exact and Lian et al.'s estimate (1 + θ/2) V^(1/3) [mm].
    ratio_to_lian : ndarray
        D_rupture / D_rupture_lian [-].
    filling_angle, filling_angle2 : ndarray
        Filling angles at rupture on particle 1 and 2 [deg].
    suction : ndarray
        Suction at rupture [kPa].
    F_cap : ndarray
        Capillary force at rupture [mN].
    r0 : ndarray
        Neck radius at rupture [mm].
    status : list of str
        Status of the search ('ok' ...).

    References
    ----------
    .. [1] Lian, G., Thornton, C., Adams, M. J. (1993). A theoretical study of the liquid bridge forces
       between two rigid spherical bodies. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """

    case: list | None = plain("case")
    R: np.ndarray = output("R_mm", "R", "mm")
    R2: np.ndarray = output("R2_mm", "R2", "mm")
    contact_angle: np.ndarray = output("contact_angle_deg", "contact_angle", "deg")
    V_w: np.ndarray = output("V_w_mm3", "V_w", "mm^3")
    D_rupture: np.ndarray = output("D_rupture_mm", "D_rupture", "mm")
    D_rupture_lian: np.ndarray = output("D_rupture_lian_mm", "D_rupture_lian", "mm")
    ratio_to_lian: np.ndarray = output("ratio_to_lian", "ratio_to_lian", "")
    filling_angle: np.ndarray = output("filling_angle_deg", "filling_angle", "deg")
    filling_angle2: np.ndarray = output("filling_angle2_deg", "filling_angle2", "deg")
    suction: np.ndarray = output("suction_kPa", "suction", "kPa")
    F_cap: np.ndarray = output("F_cap_mN", "F_cap", "mN")
    r0: np.ndarray = output("r0_mm", "r0", "mm")
    status: list = plain("status")

    def json_rows(self, start: int = 0, stop: int | None = None) -> list[dict]:
        """Rows as :meth:`RowRecord.json_rows` gives them, a plane's ``R2_mm`` written ``plane``.

        JSON has no infinity.

        Parameters
        ----------
        start, stop : int, optional
            The rows, ``start`` included, ``stop`` excluded (default: all).

        Returns
        -------
        list of dict
        """
        rows = super().json_rows(start, stop)
        for r in rows:
            if r["R2_mm"] is None or r["R2_mm"] == float("inf"):
                r["R2_mm"] = PLANE
        return rows


@dataclass(frozen=True)
class YadeFileRecord(RowRecord):
    """``capred bridge yade-files``: one row per capillary file written for YADE.

    Attributes
    ----------
    file : list of str
        The file's name, ``M(r=<ratio>)``.
    ratio : ndarray
        Radius ratio r = R2 / R1 >= 1 of the file [-].
    d_star_max : ndarray
        Largest dimensionless distance d* = D / R2 in the file [-].
    uc_star_max : ndarray
        Largest dimensionless suction uc* = Δu R2 / γ in the file [-].
    distances : ndarray of int
        Number of distance blocks [-].
    bridges : ndarray of int
        Number of bridges (rows) [-].
    smallest_block : ndarray of int
        Bridges in the smallest block [-].

    References
    ----------
    .. [1] Scholtès, L., Chareyre, B., Nicot, F., Darve, F. (2009). Micromechanics of granular materials with
       capillary effects. Int. J. Eng. Sci. 47, 64-75 (the files' layout).
    .. [2] Duriez, J., Wan, R. (2017). Contact angle mechanical influence in wet granular soils. Acta Geotech.
       12, 67-83. doi:10.1007/s11440-016-0500-6
    """

    file: list = plain("file")
    ratio: np.ndarray = output("ratio", "ratio", "")
    d_star_max: np.ndarray = output("d_star_max", "d_star_max", "")
    uc_star_max: np.ndarray = output("uc_star_max", "uc_star_max", "")
    distances: np.ndarray = output("distances", "distances", "")
    bridges: np.ndarray = output("bridges", "bridges", "")
    smallest_block: np.ndarray = output("smallest_block", "smallest_block", "")
