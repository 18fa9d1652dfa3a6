"""Console (and HTML) tables of `capred pt-volume`: the path points and, when labelled, its stages."""

from __future__ import annotations

from ..records import num, record_outputs, scale_value
from ..table_spec import TableSpec
from .render import MAX_ROWS, fmt, spec


def pt_volume_tables(result) -> list[TableSpec]:
    """The lines used, the path points (at most 20 shown; all in results.csv) and the stages (label runs).

    Parameters
    ----------
    result : capred.pipelines.pt_volume.PTVolumeResult
        A ``capred pt-volume`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    # from the typed results (options, the lines used, PTVolumePoints, Stage), never the JSON document
    par = result.params
    illustrative = result.options.illustrative()
    lines = spec(
        "Compressibility lines (Pedrotti & Tarantino: slurry W, dry powder A; e = e_ncl − λ ln(σ'/σ_ref))",
        ["part", "λ", "κ", "e_ncl", "σ_ref [kPa]", "source"],
    )
    for part, name in (("W", "W (reconstituted from slurry)"), ("A", "A (compressed from dry powder)")):
        keys = (f"lambda_{part}", f"kappa_{part}", f"e_ncl_{part}")
        fitted = result.options.from_compression()
        source = (
            "EXAMPLE_KAOLIN (illustrative)"
            if any(k in illustrative for k in keys)
            else ("compression test" if any(k in fitted for k in keys) else "options")
        )
        lines.rows.append(
            [name, *(fmt(num(getattr(par, k))) for k in keys), fmt(num(par.reference_stress / 1e3)), source]
        )

    pts = result.points  # SI: stresses in Pa, shown in kPa
    n = len(result.step)
    labelled = n > 0 and result.stage is not None
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
    change = result.fluid_change()
    # each column in the unit its PTVolumePoints field declares (capred.records.output: kPa for a stress)
    out = {name: [num(x) for x in scale_value(v[: min(n, MAX_ROWS)], o.scale)] for name, o, v in record_outputs(pts)}
    for i in range(min(n, MAX_ROWS)):
        points.rows.append(
            [
                fmt(num(result.step[i])),
                *([result.stage[i]] if labelled else []),
                fmt(out["sigma"][i]),
                fmt(out["suction"][i]),
                fmt(out["S_R"][i]),
                fmt(out["sigma_W"][i]),
                fmt(out["sigma_A"][i]),
                fmt(out["e"][i]),
                fmt(out["e_W"][i]),
                fmt(out["e_A"][i]),
                change[i].replace("_to_", " → "),
            ]
        )
    if n > MAX_ROWS:
        points.total_rows, points.full_table = n, "results.csv"
    tables = [lines, points]
    if result.stages:
        st = spec(
            "Stages (runs of equal 'stage' labels; Δ from the point before the run)",
            ["stage", "steps", "S_r", "σ'_W [kPa]", "σ'_A [kPa]", "e", "Δe", "Δe_W", "Δe_A"],
        )
        sr = result.stage_record()  # the typed record of the stages (stages.csv, the JSON's "stages")
        for s in sr.json_rows():
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
        tables.append(st)
    return tables
