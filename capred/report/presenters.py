"""What each command shows: its figure sheets and its console tables, looked up by the result's command.

This is the one place that knows how a result is presented. ``pipelines/``
computes records and never imports this package; the CLI, the batch runner,
the HTML report and a notebook (``result.plot()``, ``result._repr_html_()``)
all come here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..table_spec import TableSpec


@dataclass(frozen=True)
class Presenter:
    """How one command's result is shown.

    Attributes
    ----------
    figures : callable
        ``figures(result) -> {file stem: Sheet}``: the figure sheets of the run
        (drawn only when asked for).
    tables : callable
        ``tables(result) -> list[TableSpec]``: the console (and HTML) summary tables.
    """

    figures: Callable[[object], dict]
    tables: Callable[[object], list[TableSpec]]


def _none(result) -> dict:
    return {}


def _shear_figures(result) -> dict:
    import numpy as np

    from ..io import safe_name
    from .shear_figures import sheet_capillary_stress, sheet_curves, sheet_shear_report

    taken: set[str] = set()
    out = {}
    t = result.tests
    wet = t["condition"] == "wet"
    for m in result.materials:
        name = safe_name(m, taken)
        out[f"report_{name}"] = sheet_shear_report(result, m)
        if np.any(wet & (t["material"] == m)):
            out[f"capillary_{name}"] = sheet_capillary_stress(result, m)
        if result.curves is not None and any(
            str(tid) in result.curves.curves for tid in t["test_id"][t["material"] == m]
        ):
            out[f"curves_{name}"] = sheet_curves(result, m)
    return out


def _lazy(module: str, name: str) -> Callable:
    """A function of a report module, imported on first call (matplotlib loads only when drawing)."""

    def call(result):
        from importlib import import_module

        return getattr(import_module(f"capred.report.{module}"), name)(result)

    call.__name__ = name
    return call


def _one(module: str, name: str, stem: str) -> Callable:
    sheet = _lazy(module, name)
    return lambda result: {stem: sheet(result)}


def _calc_figures(result) -> dict:
    if result.command == "prism" and getattr(result, "figure_data", None) is not None:
        from .calculator_figures import sheet_prism

        return {"prism": sheet_prism(**result.figure_data)}
    if result.command != "skempton-b" or getattr(result, "figure_data", None) is None:
        return {}
    from .calculator_figures import sheet_skempton

    return {"skempton-b": sheet_skempton(**result.figure_curves())}


def _rupture_tables(result) -> list[TableSpec]:
    from .render import row_table

    keys = [
        "case",
        "R_mm",
        "R2_mm",
        "contact_angle_deg",
        "V_w_mm3",
        "D_rupture_mm",
        "D_rupture_lian_mm",
        "ratio_to_lian",
        "status",
    ]
    rows = result.record().json_rows()  # the typed record (RuptureRecord): JSON keys are the console headers
    present = [k for k in keys if rows and k in rows[0]]
    return [row_table("Rupture distance at constant volume", rows, present, "rupture.csv")]


def _yade_tables(result) -> list[TableSpec]:
    from .render import row_table

    rows = result.record().json_rows()  # the typed record (YadeFileRecord), one row per file
    return [
        row_table(
            "YADE capillary files (exact bridges, YADE's dimensionless variables)",
            rows,
            list(rows[0]) if rows else [],
            "yade_files.csv",
        )
    ]


#: command -> Presenter: one entry per command
PRESENTERS: dict[str, Presenter] = {
    "shear": Presenter(_shear_figures, _lazy("shear_tables", "shear_tables")),
    "triaxial-bounds": Presenter(
        _one("triaxial_figures", "sheet_triaxial", "report"), _lazy("triaxial_tables", "triaxial_tables")
    ),
    "triaxial": Presenter(
        _lazy("triaxial_strength_figures", "triaxial_strength_figures"),
        _lazy("triaxial_strength_figures", "triaxial_strength_tables"),
    ),
    "retention": Presenter(
        _one("retention_figures", "sheet_retention", "retention"), _lazy("retention_tables", "retention_tables")
    ),
    "retention-convert": Presenter(
        _one("retention_figures", "sheet_convert", "retention_convert"), _lazy("retention_tables", "convert_tables")
    ),
    "prism": Presenter(_calc_figures, _lazy("calculator_tables", "calc_tables")),
    "skempton-b": Presenter(_calc_figures, _lazy("calculator_tables", "calc_tables")),
    "rumpf": Presenter(_calc_figures, _lazy("calculator_tables", "calc_tables")),
    "shear-band": Presenter(_none, _lazy("calculator_tables", "calc_tables")),
    "history": Presenter(
        _one("history_figures", "sheet_history", "control_chart"), _lazy("history_figures", "history_tables")
    ),
    "bridge solve": Presenter(_none, _lazy("bridge_tables", "bridge_solve_tables")),
    "bridge curve": Presenter(
        _one("bridge_figures", "sheet_curve", "curve"), _lazy("bridge_tables", "bridge_curve_tables")
    ),
    "bridge compare": Presenter(
        lambda r: {"compare": _lazy("bridge_figures", "sheet_compare")(r.record().json_rows())},
        _lazy("bridge_tables", "bridge_compare_tables"),
    ),
    "bridge rupture": Presenter(
        lambda r: {"rupture": _lazy("bridge_figures", "sheet_rupture")(r.record().json_rows())}, _rupture_tables
    ),
    "bridge yade-files": Presenter(_none, _yade_tables),
    "bridge laws": Presenter(
        _one("bridge_laws_figures", "sheet_laws", "laws"), _lazy("bridge_tables", "bridge_laws_tables")
    ),
    "compression": Presenter(
        _one("compression_figures", "sheet_compression", "compression"),
        _lazy("compression_figures", "compression_tables"),
    ),
    "pt-volume": Presenter(
        _one("pt_volume_figures", "sheet_pt_volume", "pt_volume"), _lazy("pt_volume_tables", "pt_volume_tables")
    ),
}


def presenter(result) -> Presenter:
    """The Presenter of a result's command (a result of an unknown command shows no figure and no table).

    Parameters
    ----------
    result : capred.result.Result
        Any command's result.

    Returns
    -------
    Presenter
    """
    return PRESENTERS.get(result.command, Presenter(_none, lambda r: []))


def figures(result) -> dict:
    """Figure sheets of a result: {file stem: Sheet}.

    Parameters
    ----------
    result : capred.result.Result
        Any command's result.

    Returns
    -------
    dict
        File stem -> capred.report.sheets.Sheet.
    """
    return presenter(result).figures(result)


def draws_figures(result) -> bool:
    """False for a command that never draws a figure (``bridge solve``, ``bridge yade-files``).

    Parameters
    ----------
    result : capred.result.Result
        Any command's result.

    Returns
    -------
    bool
    """
    return presenter(result).figures is not _none


def console_tables(result) -> list[TableSpec]:
    """Summary tables of a result, for the console and report.html.

    Parameters
    ----------
    result : capred.result.Result
        Any command's result.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    return presenter(result).tables(result)
