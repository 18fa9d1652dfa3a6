"""`capred bridge yade-files`: capillary files for YADE's Law2_ScGeom_CapillaryPhys_Capillarity.

YADE interpolates capillary bridges in pre-computed tables, one text file per
radius ratio r = R2 / R1 >= 1 named ``M(r=<ratio>)``, read from the folder
YADE runs in. Layout (Scholtès et al. 2009, Int. J. Eng. Sci. 47:64-75;
Duriez & Wan 2017, doi:10.1007/s11440-016-0500-6): first line the ratio,
second line the number of distance blocks; each block is a line
``<count> 0 0 0 0 0 0 0`` followed by ``<count>`` tab-separated rows
``d* uc* V* F* delta1 delta2 nn11 nn33`` at one distance, by rising suction,
in YADE's variables: lengths over the larger radius R2 (d* = D/R2,
V* = V/R2^3, nn = int n(x)n dS / R2^2), uc* = Delta_u R2 / gamma,
F* = F / (2 pi gamma R2), filling angles in degrees (delta1 on the smaller
particle). Every row is the exact stable bridge at its (d*, uc*): nothing is
interpolated.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..physics import bridge as br
from ..result import InputFile, Result
from ..spec.bridge import DEFAULT_RATIOS, YadeOptions  # noqa: F401 (declared in spec; re-exported here)
from .bridge_records import YadeFileRecord

#: the ratios YADE's law opens (its list is fixed in the C++ source)
YADE_RATIOS = DEFAULT_RATIOS
FIRST_SUCTION = 0.002  # smallest positive uc* (Scholtes' files start there)
MIN_MEAN_FILLING_ANGLE = 1.0  # deg: the largest suction keeps this mean filling angle at contact


def file_name(ratio: float) -> str:
    """YADE's file name for a ratio: ``M(r=1)``, ``M(r=1.1)``, ``M(r=10)``.

    Parameters
    ----------
    ratio : float
        Radius ratio R2/R1 [-].

    Returns
    -------
    str
    """
    return f"M(r={ratio:g})"


@dataclass
class CapillaryFile:
    """One ratio's table, in YADE's variables (columns d*, uc*, V*, F*, delta1, delta2, nn11, nn33)."""

    ratio: float
    d_max: float  # largest d* with a bridge at zero suction
    uc_max: float  # largest uc*
    distances: np.ndarray
    suctions: np.ndarray
    rows: np.ndarray  # (n, 8), grouped by distance, suction rising
    counts: np.ndarray  # rows per distance block

    def text(self) -> str:
        """The file as YADE reads it.

        Returns
        -------
        str
            The ratio, the number of blocks, then each block's header and rows (shortest round-trip numbers).
        """
        lines = [f"{self.ratio:g}", str(len(self.counts))]
        start = 0
        for c in self.counts:
            lines.append(f"{int(c)} 0 0 0 0 0 0 0")
            lines.extend("\t".join(repr(float(v)) for v in row) for row in self.rows[start : start + c])
            start += c
        return "\n".join(lines) + "\n"


def capillary_file(ratio: float, contact_angle_rad: float, n_dist: int = 80, n_suct: int = 350) -> CapillaryFile:
    """The exact capillary file of one radius ratio r >= 1 at contact angle ``contact_angle_rad`` [rad].

    Internally lengths are in units of the smaller radius R1 (rho = r); the
    table is converted to YADE's R2 units on the way out.

    Parameters
    ----------
    ratio : float
        Radius ratio r = R2/R1 >= 1 [-].
    contact_angle_rad : float
        Contact angle [rad].
    n_dist : int, optional
        Number of distances, from 0 to the largest gap bridged at zero suction [-].
    n_suct : int, optional
        Number of suctions per distance [-].

    Returns
    -------
    CapillaryFile
        The table in YADE's dimensionless variables (d*, uc*, V*, F*, delta1, delta2, nn11, nn33).
    """
    r = float(ratio)
    theta = float(contact_angle_rad)
    # largest gap at zero suction: the maximum of the catenoid gap over the filling angle
    b_end = 0.5 * (np.pi - theta)
    grid = np.linspace(1e-3, b_end, 400)
    g = br.gap_of(grid, theta, 0.0, r)
    j = int(np.nanargmax(g))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    b_star, g_star = br.golden(lambda x, i: br.gap_of(x, theta, 0.0, r), np.array([lo]), np.array([hi]))
    b_star, D_max = float(b_star[0]), float(g_star[0])
    # largest suction: the bridge at contact whose mean filling angle is MIN_MEAN_FILLING_ANGLE
    s_max = _suction_at_mean_filling_angle(theta, r, np.radians(MIN_MEAN_FILLING_ANGLE))
    uc = np.r_[0.0, np.geomspace(FIRST_SUCTION, s_max * r, n_suct - 1)]
    d = np.linspace(0.0, D_max / r, n_dist)
    D_grid, U_grid = np.meshgrid(d * r, uc / r, indexing="ij")  # R1 units
    beta, status = br.solve_for_suction(theta, U_grid.ravel(), D_grid.ravel(), r)
    beta, status = beta.reshape(D_grid.shape), status.reshape(D_grid.shape)
    # the last distance is the maximum itself: its zero-suction bridge is the one found above
    if status[-1, 0] != 0:
        beta[-1, 0], status[-1, 0] = b_star, 0
    ok = status == 0
    b = br.bridge(beta[ok], theta, U_grid[ok], r)
    rows = np.column_stack(
        [
            D_grid[ok] / r,
            U_grid[ok] * r,
            b.volume / r**3,
            b.force / (2.0 * r),
            np.degrees(beta[ok]),
            np.degrees(b.delta2),
            b.nn11 / r**2,
            b.nn33 / r**2,
        ]
    )
    return CapillaryFile(r, D_max / r, s_max * r, d, uc, rows, ok.sum(axis=1))


def _suction_at_mean_filling_angle(theta: float, r: float, target: float) -> float:
    """s* (R1 units) of the bridge at contact with (delta1 + delta2) / 2 = target [rad]."""

    def mean_angle(log_y0):
        y0 = np.exp(np.atleast_1d(log_y0))
        n = y0.size
        s = br.suction_at_neck(y0, np.full(n, theta), np.full(n, r), np.zeros(n), "gap")
        beta, b = br.from_neck(y0, theta, s, r)
        return 0.5 * (beta + b.delta2), s

    logs = np.linspace(np.log(1e-6), np.log(0.5), 60)
    m, _ = mean_angle(logs)
    k = int(np.flatnonzero(np.isfinite(m) & (m >= target))[0])
    root = br.illinois(
        lambda x, i: target - mean_angle(x)[0],
        np.array([logs[k - 1]]),
        np.array([logs[k]]),
        np.array([target - m[k - 1]]),
        np.array([target - m[k]]),
    )
    return float(mean_angle(root)[1][0])


@dataclass(repr=False)
class YadeResult(Result):
    """Capillary files for YADE, one per radius ratio, and their summary."""

    command = "bridge yade-files"
    json_name = "yade_files.json"

    files: list[CapillaryFile]
    options: YadeOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def record(self) -> YadeFileRecord:
        """One row per capillary file as a typed record.

        Its name, ratio, largest d* and uc*, numbers of distances and bridges and the smallest block.

        Returns
        -------
        YadeFileRecord
            One value per file, in YADE's dimensionless variables.

        References
        ----------
        .. [1] Scholtès, L., Chareyre, B., Nicot, F., Darve, F. (2009). Micromechanics of granular materials
           with capillary effects. Int. J. Eng. Sci. 47, 64-75 (the files' layout).
        """
        f = self.files
        return YadeFileRecord(
            file=[file_name(x.ratio) for x in f],
            ratio=np.array([x.ratio for x in f], float),
            d_star_max=np.array([x.d_max for x in f], float),
            uc_star_max=np.array([x.uc_max for x in f], float),
            distances=np.array([len(x.counts) for x in f], int),
            bridges=np.array([x.rows.shape[0] for x in f], int),
            smallest_block=np.array([x.counts.min() for x in f], int),
        )

    def summary_rows(self) -> list[dict]:
        """One row per capillary file (:meth:`record` as JSON rows).

        Its name, ratio, largest d* and uc*, numbers of distances and bridges and the smallest block.

        Returns
        -------
        list of dict
        """
        return self.record().json_rows()

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the contact angle of the files (glossary ``contact_angle``, deg).

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import quantity_store_row

        row = quantity_store_row(material, "contact_angle", self.options.contact_angle if self.options else 0.0)
        return [] if row is None else [row]

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: contact_angle_deg and the summary row of each file.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        return {"contact_angle_deg": self.options.contact_angle if self.options else 0.0, "files": self.summary_rows()}

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``yade_files``: the summary rows).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        return {"yade_files": pd.DataFrame(self.record().columns())}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``yade_files``), under ``name [unit]`` headers.

        Returns
        -------
        dict
            Stem -> DataFrame.
        """
        import pandas as pd

        return {"yade_files": pd.DataFrame(self.record().csv_columns())}

    def extra_files(self) -> dict[str, bytes]:
        """The capillary files themselves, ``M(r=<ratio>)``, in YADE's layout (ASCII).

        Returns
        -------
        dict
            File name -> bytes.
        """
        return {file_name(f.ratio): f.text().encode("ascii") for f in self.files}


def reduce_yade_files(source, opt: YadeOptions) -> YadeResult:
    """Every capillary file of ``opt.ratios`` (``source`` is unused: the files need no input).

    Parameters
    ----------
    source : None
        Unused.
    opt : YadeOptions
        Ratios [-], contact angle [deg], distances and suctions per file [-].

    Returns
    -------
    YadeResult
        One CapillaryFile per ratio (a warning for ratios YADE does not open).
    """
    contact_angle_rad = np.radians(opt.contact_angle)
    from ..progress import steps

    files = [
        capillary_file(r, contact_angle_rad, opt.distances, opt.suctions)
        for r in steps(opt.ratios, "capred: capillary files", len(opt.ratios))
    ]
    res = YadeResult(files, opt, [], list(opt.warnings))
    odd = [r for r in opt.ratios if r not in YADE_RATIOS]
    if odd:
        res.warnings.append(
            "YADE's capillary law opens only the files of r = 1, 1.1, 1.25, 1.5, 1.75, 2, 3, 4, 5 "
            f"and 10; the files of r = {', '.join(f'{r:g}' for r in odd)} are for other codes"
        )
    return res
