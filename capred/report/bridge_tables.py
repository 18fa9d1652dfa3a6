"""Console (and HTML) tables of `capred bridge ...`."""

from __future__ import annotations

import numpy as np

from ..table_spec import TableSpec
from .render import MAX_ROWS, row_table, spec


def bridge_solve_tables(result) -> list[TableSpec]:
    """Console tables of ``capred bridge solve``: the summary, then the first rows of the exact bridges (all in solve.csv).

    Parameters
    ----------
    result : capred.pipelines.bridge_solve.BridgeResult
        A ``capred bridge solve`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    keys = [
        "case",
        "r0_mm",
        "F_cap_mN",
        "V_w_mm3",
        "filling_angle_deg",
        "filling_angle2_deg",
        "suction_kPa",
        "S_R",
        "sigma_prime_kPa",
        "status",
    ]
    rows = result.rows_range(0, MAX_ROWS)
    codes, counts = np.unique(result.status, return_counts=True)
    summary = spec("Bridges solved", ["status", "rows"])
    summary.rows = [[result.status_text(k), str(v)] for k, v in zip(codes, counts)]
    context = result.row_context(0, len(rows)) if hasattr(result, "row_context") else {}
    named = bool(rows) and "case" in rows[0]
    extra = [] if named else ["R_mm", "gap_mm"]  # no case label: the row is named by its radius and gap
    if np.any(np.isfinite(context.get("D_rupture_mm", []))):
        extra.append("D_rupture_mm")  # where a row beyond rupture would have had its bridge
    for j, r in enumerate(rows):
        for k in extra:
            r[k] = float(context[k][j])
    keys = keys[:1] + [k for k in extra if k != "D_rupture_mm"] + keys[1:] + [k for k in extra if k == "D_rupture_mm"]
    present = [k for k in keys if rows and k in rows[0]]
    if "filling_angle2_deg" in present and np.all(result.inputs_si["ratio"] == 1):
        present.remove("filling_angle2_deg")  # equal spheres: the same angle twice
    return [summary, row_table("Exact capillary bridges", rows, present, "solve.csv", total=result.status.size)]


def bridge_compare_tables(result) -> list[TableSpec]:
    """Console tables of ``capred bridge compare``.

    Measured against predicted force [mN] per pair (all in compare.csv), and each closed-form law's residuals over
    the pairs it applies to.

    Parameters
    ----------
    result : capred.pipelines.bridge.CompareResult
        A ``capred bridge compare`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    from ..physics.bridge_laws import LAWS

    keys = ["case", "F_measured_mN", "F_exact_mN", "F_toroidal_mN", "F_willett_mN", "F_israelachvili_mN", "status"]
    record = result.record()
    rows = record.json_rows()  # the typed record (CompareRecord): JSON keys are the console headers
    present = [k for k in keys if rows and k in rows[0]]
    laws = spec("Closed-form laws against the measured forces [mN]", ["law", "pairs", "RMS residual", "mean residual"])
    for name, (_, residual) in (record.laws or {}).items():
        r = np.asarray(residual, float)
        r = r[np.isfinite(r)]
        rms, mean = (np.sqrt(np.mean(r**2)), np.mean(r)) if r.size else (None, None)
        laws.rows.append([LAWS[name].label, str(r.size), *("—" if v is None else f"{v:.4g}" for v in (rms, mean))])
    pairs = row_table("Measured against predicted capillary force [mN]", rows, present, "compare.csv")
    return [pairs, laws] if laws.rows else [pairs]


def bridge_curve_tables(result) -> list[TableSpec]:
    """Console table of ``capred bridge curve``: each model's RMS relative error of σ' against the exact bridge.

    Inside and outside the pendular regime.

    Parameters
    ----------
    result : capred.pipelines.bridge.CurveResult
        A ``capred bridge curve`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    err = result.summary()["rms_relative_error_vs_exact"]  # computed from the curve, not read from the JSON
    lim = result.pendular_limit
    t = spec("RMS relative error of σ' against the exact bridge", ["model", f"S_R < {lim:g}", f"S_R >= {lim:g}"])
    for m in err["inside"]:  # the curve's approximations: Israelachvili, then the registry's models drawn on it
        t.rows.append([m, *(f"{err[r][m]:.1%}" if err[r][m] is not None else "—" for r in ("inside", "outside"))])
    return [t]


def bridge_laws_tables(result) -> list[TableSpec]:
    """Console tables of `bridge laws`.

    Each law over every point, the headline (geometry x gap), and the regions with the laws within the tolerance.

    Parameters
    ----------
    result : capred.pipelines.bridge_laws.LawsResult
        A ``capred bridge laws`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    from ..physics.bridge_laws import LAWS

    tol = f"{result.tolerance:.0%}"
    overall = spec(
        "Closed-form laws against the exact bridge (|F_law/F_exact − 1|)",
        ["law", "points", "median", "max", f"regions within {tol}"],
    )
    for r in result.overall():
        overall.rows.append(
            [
                LAWS[r["law"]].label,
                str(r["n"]),
                "—" if r["median_error"] is None else f"{r['median_error']:.1%}",
                "—" if r["max_error"] is None else f"{r['max_error']:.0%}",
                f"{r['regions_within']} of {r['regions']}",
            ]
        )
    head = spec(
        "Median |error| by geometry and gap (over volumes and angles)",
        ["geometry", "D/R", *[law.label for law in LAWS.values()]],
        2,
    )
    for r in result.headline():
        head.rows.append(
            [
                r["geometry"],
                r["D_over_R"],
                *("—" if r[f"{k}_median"] is None else f"{r[f'{k}_median']:.1%}" for k in LAWS),
            ]
        )
    rows = []
    by_region: dict = {}
    for r in result.regions():
        by_region.setdefault(r["region"], []).append(r)
    for region, items in by_region.items():
        good = [LAWS[i["law"]].label for i in items if i["within"]]
        # the best law gives a force at every point of the region: one undefined at some of them (Willett's full
        # regression at contact) is not a choice a DEM code can follow there
        points = max((i["n"] or 0 for i in items), default=0)
        whole = (i for i in items if i["max_error"] is not None and i["n"] == points)
        best = min(whole, key=lambda i: i["max_error"], default=None)
        rows.append(
            {
                "region": region,
                "within": ", ".join(good) or "none",
                "best": "—" if best is None else f"{LAWS[best['law']].label} ({best['max_error']:.1%})",
            }
        )
    where = row_table(
        f"Laws within {tol} at every point of a region (best: smallest largest error among laws defined at every point)",
        rows,
        ["region", "within", "best"],
        "regions.csv",
        left=("region", "within", "best"),
    )
    return [overall, head, where]
