"""Console (and HTML) tables of `capred pt-volume`: the path points and, when labelled, its stages."""

from __future__ import annotations

from ..result import TableSpec
from .render import MAX_ROWS, fmt, spec


def pt_volume_tables(result) -> list[TableSpec]:
    """The lines used, the path points (at most 20 shown; all in results.csv) and the stages (label runs).

    Parameters
    ----------
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    list of capred.result.TableSpec
    """
    js = result.to_json()
    p = js["parameters"]
    lines = spec(
        "Compressibility lines (Pedrotti & Tarantino: slurry W, dry powder A; e = e_ncl − λ ln(σ'/σ_ref))",
        ["part", "λ", "κ", "e_ncl", "σ_ref [kPa]", "source"],
    )
    for part, name in (("W", "W (reconstituted from slurry)"), ("A", "A (compressed from dry powder)")):
        keys = (f"lambda_{part}", f"kappa_{part}", f"e_ncl_{part}")
        source = "EXAMPLE_KAOLIN (illustrative)" if any(k in p["illustrative"] for k in keys) else "options"
        lines.rows.append([name, *(fmt(p[k]) for k in keys), fmt(p["reference_stress_kPa"]), source])

    labelled = js["points"] and "stage" in js["points"][0]
    head = [
        "step",
        *(["stage"] if labelled else []),
        "σ [kPa]",
        "u_a − u_w [kPa]",
        "S_r",
        "σ'_W [kPa]",
        "σ'_A [kPa]",
        "e",
        "e_W",
        "e_A",
        "fluid change",
    ]
    points = spec(
        "Path points (eq. 1-2: σ'_W = (σ − u_w) S_r, σ'_A = (σ − u_a)(1 − S_r); eq. 5: e)",
        head,
        left=2 if labelled else 1,
    )
    for r in js["points"][:MAX_ROWS]:
        points.rows.append(
            [
                fmt(r["step"]),
                *([r["stage"]] if labelled else []),
                fmt(r["sigma_kPa"]),
                fmt(r["suction_kPa"]),
                fmt(r["S_r"]),
                fmt(r["sigma_W_kPa"]),
                fmt(r["sigma_A_kPa"]),
                fmt(r["e"]),
                fmt(r["e_W"]),
                fmt(r["e_A"]),
                r["fluid_change"].replace("_to_", " → "),
            ]
        )
    if len(js["points"]) > MAX_ROWS:
        points.total_rows, points.full_table = len(js["points"]), "results.csv"
    out = [lines, points]
    if js["stages"]:
        st = spec(
            "Stages (runs of equal 'stage' labels; Δ from the point before the run)",
            ["stage", "steps", "S_r", "σ'_W [kPa]", "σ'_A [kPa]", "e", "Δe", "Δe_W", "Δe_A"],
        )
        for s in js["stages"]:
            steps = (
                fmt(s["first_step"])
                if s["first_step"] == s["last_step"]
                else f"{fmt(s['first_step'])}–{fmt(s['last_step'])}"
            )
            st.rows.append(
                [
                    s["stage"],
                    steps,
                    fmt(s["S_r_end"]),
                    fmt(s["sigma_W_end_kPa"]),
                    fmt(s["sigma_A_end_kPa"]),
                    fmt(s["e_end"]),
                    fmt(s["de"], sign=True),
                    fmt(s["de_W"], sign=True),
                    fmt(s["de_A"], sign=True),
                ]
            )
        out.append(st)
    return out
