"""`capred bridge laws`: the closed-form capillary-force laws of DEM codes judged against capred's exact bridge.

On a grid of gaps D/R, volumes V/R^3, contact angles and geometries (equal spheres, unequal spheres R2/R,
a sphere and a plane), each registered law (:data:`capred.physics.bridge_laws.LAWS`) and the exact
Young-Laplace bridge give the force at the same contact angle, volume and gap, the exact one on the stable
branch (the bridge continuous with the one at contact when the particles are pulled apart at constant volume,
:func:`capred.physics.bridge.solve_for_volume`). Forces are in units of 2 pi R gamma (R the radius of
particle 1: the sphere of a sphere-plane pair). Regions are bins of D/R x V/R^3 x contact angle x geometry;
per region, each law's median and largest relative error, and whether it stays within the tolerance (5 %)
at every point of the region. Points beyond rupture (no exact bridge) are left out and counted.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..io import Table, read_table
from ..physics import bridge as br
from ..physics import bridge_laws as bl
from ..result import InputFile, Result, input_file, num
from ..spec.bridge import LAWS_SCHEMA, LawsOptions  # noqa: F401 (declared in spec; re-exported here)

#: region edges: D/R, V/R^3, contact angle [deg] (each bin [lo, hi))
GAP_EDGES = (0.0, 0.01, 0.05, np.inf)
VOLUME_EDGES = (0.0, 1e-3, 1e-2, np.inf)
ANGLE_EDGES = (0.0, 15.0, 35.0, 90.0)


def _label_bins(edges, fmt) -> list[str]:
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        out.append(f"< {fmt(hi)}" if lo == 0 else (f">= {fmt(lo)}" if np.isinf(hi) else f"{fmt(lo)}-{fmt(hi)}"))
    return out


def _bin(values, edges) -> np.ndarray:
    return np.clip(np.searchsorted(np.asarray(edges), values, side="right") - 1, 0, len(edges) - 2)


@dataclass(repr=False)
class LawsResult(Result):
    """The laws' forces and the exact force on a grid, their relative errors, and the statistics per region."""

    command = "bridge laws"
    json_name = "laws.json"

    source: str | None
    gap: np.ndarray  # D / R
    volume: np.ndarray  # V / R^3
    angle_deg: np.ndarray  # contact angle [deg]
    ratio: np.ndarray  # R2 / R, inf for a plane
    exact: np.ndarray  # F / (2 pi R gamma), NaN beyond rupture
    status: np.ndarray  # of the exact solver (capred.pipelines.bridge.STATUS)
    forces: dict[str, np.ndarray]  # law -> F / (2 pi R gamma)
    tolerance: float = 0.05
    options: LawsOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def errors(self) -> dict[str, np.ndarray]:
        """Relative error of each law, F_law / F_exact - 1 [-]; NaN without an exact bridge or a law force.

        Returns
        -------
        dict of str to numpy.ndarray
            Law name -> relative error per point [-].
        """
        with np.errstate(invalid="ignore", divide="ignore"):
            return {k: F / self.exact - 1.0 for k, F in self.forces.items()}

    def geometry(self) -> np.ndarray:
        """Geometry "equal", "unequal" or "plane" of each point.

        Returns
        -------
        numpy.ndarray of str
            One label per point (:func:`capred.physics.bridge_laws.geometry_of`).
        """
        return bl.geometry_of(self.ratio)

    def region_keys(self) -> np.ndarray:
        """Per point, its region: (geometry, D/R bin, V/R^3 bin, angle bin) as one label.

        Returns
        -------
        numpy.ndarray of str
            One label per point.
        """
        g = _label_bins(GAP_EDGES, lambda x: f"{x:g}")
        v = _label_bins(VOLUME_EDGES, lambda x: f"{x:g}")
        a = _label_bins(ANGLE_EDGES, lambda x: f"{x:g}°")
        geo = np.where(
            np.isinf(self.ratio),
            "sphere-plane",
            np.where(self.ratio == 1.0, "equal spheres", np.char.add("R2/R = ", self.ratio.astype(str))),
        )
        gi, vi, ai = _bin(self.gap, GAP_EDGES), _bin(self.volume, VOLUME_EDGES), _bin(self.angle_deg, ANGLE_EDGES)
        return np.array(
            [f"{x}; D/R {g[i]}; V/R³ {v[j]}; θ {a[k]}" for x, i, j, k in zip(geo.tolist(), gi, vi, ai)], dtype=object
        )

    def regions(self) -> list[dict]:
        """Per region (in first-seen order) and law: the errors of the law there.

        Points compared, median and largest |relative error|, and whether every point is within the tolerance.

        Returns
        -------
        list of dict
            One dict per region and law: ``region``, ``law``, ``n``, ``beyond_rupture``, ``median_error`` and
            ``max_error`` [-] (None without points), ``within``.
        """
        cached = self.__dict__.get("_regions")
        if cached is not None:
            return cached
        keys = self.region_keys()
        err = self.errors()
        out = []
        for key in dict.fromkeys(keys.tolist()):
            sel = keys == key
            n_exact = int(np.sum(sel & (self.status == 0)))
            for name, e in err.items():
                x = np.abs(e[sel])
                x = x[np.isfinite(x)]
                out.append(
                    {
                        "region": key,
                        "law": name,
                        "n": int(x.size),
                        "beyond_rupture": int(np.sum(sel & (self.status != 0))),
                        "median_error": num(float(np.median(x))) if x.size else None,
                        "max_error": num(float(np.max(x))) if x.size else None,
                        # within: a force at every point with an exact bridge, each within the tolerance
                        "within": bool(x.size and x.size == n_exact and np.max(x) <= self.tolerance),
                    }
                )
        self.__dict__["_regions"] = out
        return out

    def overall(self) -> list[dict]:
        """Per law over every point with an exact bridge: n, median and largest |relative error|, regions within.

        Returns
        -------
        list of dict
            One dict per law: ``law``, ``n``, ``median_error`` and ``max_error`` [-] (None without points), and
            ``regions_within`` of its ``regions``.
        """
        err = self.errors()
        regions = self.regions()
        out = []
        for name, e in err.items():
            x = np.abs(e[np.isfinite(e)])
            mine = [r for r in regions if r["law"] == name and r["n"]]
            out.append(
                {
                    "law": name,
                    "n": int(x.size),
                    "median_error": num(float(np.median(x))) if x.size else None,
                    "max_error": num(float(np.max(x))) if x.size else None,
                    "regions_within": sum(r["within"] for r in mine),
                    "regions": len(mine),
                }
            )
        return out

    def headline(self) -> list[dict]:
        """Per geometry and D/R bin (over every volume and angle): each law's median and largest |relative error| [-].

        The README's headline table.

        Returns
        -------
        list of dict
            One dict per geometry, D/R bin and law.
        """
        err = self.errors()
        geo = self.geometry()
        gi = _bin(self.gap, GAP_EDGES)
        labels = _label_bins(GAP_EDGES, lambda x: f"{x:g}")
        out = []
        for g in ("equal", "unequal", "plane"):
            for i, lab in enumerate(labels):
                sel = (geo == g) & (gi == i)
                if not sel.any():
                    continue
                row = {"geometry": g, "D_over_R": lab, "n": int(np.sum(sel & (self.status == 0)))}
                for name, e in err.items():
                    x = np.abs(e[sel])
                    x = x[np.isfinite(x)]
                    row[f"{name}_median"] = num(float(np.median(x))) if x.size else None
                    row[f"{name}_max"] = num(float(np.max(x))) if x.size else None
                out.append(row)
        return out

    def point_columns(self) -> dict[str, np.ndarray]:
        """Per point: inputs, the exact force, each law's force and relative error (JSON keys).

        Returns
        -------
        dict of str to numpy.ndarray
            JSON key -> values per point (forces in units of 2 pi R gamma).
        """
        cols = {
            "D_over_R": self.gap,
            "V_over_R3": self.volume,
            "contact_angle_deg": self.angle_deg,
            "R2_over_R": self.ratio,
            "F_exact": self.exact,
        }
        err = self.errors()
        for name, F in self.forces.items():
            cols[f"F_{name}"] = F
            cols[f"error_{name}"] = err[name]
        return cols

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Per grid point: D_over_R, V_over_R3, contact_angle_deg, R2_over_R ('plane' for a plane), F_exact, and each law's
        force F_<law> and relative error error_<law>; forces in units of 2 pi R gamma.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        cols = self.point_columns()
        keys = list(cols)
        out = []
        for values in zip(*(cols[k].tolist() for k in keys)):
            r = {k: (num(v) if k != "R2_over_R" else ("plane" if np.isinf(v) else v)) for k, v in zip(keys, values)}
            out.append(r)
        return out

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the tolerance, a relative error (dimensionless; LawsOptions.tolerance).

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from ..records import store_row

        row = store_row(material, "tolerance", self.tolerance, "-")
        return [] if row is None else [row]

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        The source, the tolerance, each law with its citation, the regions and the points.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        return {
            "source": self.source,
            "tolerance": self.tolerance,
            "laws": [
                {
                    "name": law.name,
                    "citation": law.citation,
                    "doi": law.doi,
                    "equation": law.equation,
                    "validity": law.validity,
                    "geometries": list(law.geometries),
                }
                for law in bl.LAWS.values()
            ],
            "overall": self.overall(),
            "headline": self.headline(),
            "regions": self.regions(),
            "points": self.rows(),
        }

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame.

        ``laws``: one row per grid point; ``regions``: each law's median and largest error per region.

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        points = pd.DataFrame(self.point_columns())
        points["R2_over_R"] = [("plane" if np.isinf(r) else r) for r in self.ratio.tolist()]
        return {"laws": points, "regions": pd.DataFrame(self.regions())}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them, under ``name [unit]`` headers.

        ``laws`` and ``regions``, dimensionless columns headed ``[-]``, the contact angle ``[deg]``.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        t = self.tables()
        return {
            "laws": t["laws"].rename(
                columns=lambda k: {"R2_over_R": k, "contact_angle_deg": "contact_angle [deg]"}.get(k, f"{k} [-]")
            ),
            "regions": t["regions"].rename(
                columns={"median_error": "median_error [-]", "max_error": "max_error [-]", "n": "n [-]"}
            ),
        }


def _grid(opt: LawsOptions):
    D, V, A, Rh = np.meshgrid(opt.gaps, opt.volumes, opt.angles, opt.ratios, indexing="ij")
    return D.ravel(), V.ravel(), A.ravel(), Rh.ravel()


#: points of a grid solved at once; a larger grid is solved a chunk at a time, with a progress bar
CHUNK_POINTS = 2048


def _exact(th, V, D, rho):
    """``br.solve_for_volume`` over the points, a chunk of CHUNK_POINTS at a time (with progress) when more."""
    if D.size <= CHUNK_POINTS:
        return br.solve_for_volume(th, V, D, rho)
    from ..progress import task

    parts = []
    with task("exact bridges (points)", total=D.size) as advance:
        for a in range(0, D.size, CHUNK_POINTS):
            sl = slice(a, a + CHUNK_POINTS)
            parts.append(br.solve_for_volume(th[sl], V[sl], D[sl], rho[sl]))
            advance(len(th[sl]))
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(3))


def compare_laws(source=None, options: LawsOptions | None = None) -> LawsResult:
    """Every registered law against the exact bridge on a grid.

    The grid is a file of D_over_R, V_over_R3, contact_angle and optional R2_over_R rows, or the options' grid.

    Parameters
    ----------
    source : path, DataFrame or Table, optional
        The grid, one point per row; None: the grid of ``options``.
    options : LawsOptions, optional
        The default grid and the tolerance.

    Returns
    -------
    LawsResult
        Forces in units of 2 pi R gamma, relative errors, statistics per region.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452 (the exact bridge)
    """
    opt = options or LawsOptions()
    inputs, warnings, notes = [], list(opt.warnings), []
    path = None
    if source is None:
        D, V, A, rho = _grid(opt)
    else:
        table = source if isinstance(source, Table) else read_table(source, LAWS_SCHEMA)
        for name in ("D_over_R", "V_over_R3", "contact_angle"):
            if name not in table.columns:
                table.missing_column(name)
        table.raise_if_problems()
        for name in ("D_over_R", "V_over_R3", "contact_angle"):
            for i in np.flatnonzero(np.isnan(table.columns[name])):
                table.add_problem(i, name, f"blank {name}")
        for i in np.flatnonzero(table.columns["contact_angle"] >= 90):
            table.add_problem(i, "contact_angle", "pendular bridges need a contact angle below 90 deg")
        rho = table.get("R2_over_R").copy() if "R2_over_R" in table.columns else np.ones(len(table))
        for i in np.flatnonzero(np.isnan(rho)):
            table.add_problem(i, "R2_over_R", "blank R2_over_R (give a ratio, or 'plane')")
        table.raise_if_problems()
        D, V, A = table.columns["D_over_R"], table.columns["V_over_R3"], table.columns["contact_angle"]
        inputs, path = [input_file(source, table)], table.path
        warnings += table.warnings
        notes += list(table.notes)
    th = np.radians(A)
    beta, s, status = _exact(th, V, D, rho)
    ok = status == 0
    exact = np.full(D.size, np.nan)
    if ok.any():
        exact[ok] = 0.5 * br.bridge(beta[ok], th[ok], s[ok], rho[ok]).force  # F/(pi gamma R) -> F/(2 pi gamma R)
    forces = {name: bl.law_force(name, th, V, D, rho) for name in bl.LAWS}
    far = int(np.sum(~ok))
    if far:
        notes.append(
            f"{far} of {D.size} points have no exact bridge (beyond rupture, or too much water for a concave "
            "bridge): left out of the statistics."
        )
    notes.append(
        "Forces in units of 2πRγ (R: particle 1, the sphere of a sphere-plane pair); relative error "
        "F_law/F_exact − 1 at equal contact angle, volume and gap, the exact bridge on the stable branch."
    )
    return LawsResult(
        str(path) if path is not None else None,
        np.asarray(D, float),
        np.asarray(V, float),
        np.asarray(A, float),
        np.asarray(rho, float),
        exact,
        status,
        forces,
        opt.tolerance,
        opt,
        inputs,
        warnings,
        notes,
    )


__all__ = ["compare_laws", "LawsOptions", "LawsResult", "LAWS_SCHEMA"]
