"""Figure sheets: a composite of panels, and each panel alone sized for a one-column journal figure.

A Result's ``figures()`` gives Sheets. The writer draws each sheet as one
composite figure and each of its panels as its own figure
(``figures/<sheet>_<panel>.<format>``). Legends are moved outside the data
area; the constrained layout makes room for them.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from .style import SINGLE_PANEL_SIZE, legend_outside, literal


@dataclass
class Panel:
    name: str  # file-name part: figures/<sheet>_<name>.<fmt>
    draw: Callable  # draw(ax) -> ax
    caption: str = ""


@dataclass
class Sheet:
    title: str
    panels: list[Panel]
    columns: int = 2
    caption: str = ""
    spans: dict[str, int] = field(default_factory=dict)  # panel name -> columns it spans (one row)
    panel_size: tuple[float, float] = (4.6, 3.4)  # inches of one panel in the composite (legend included)


def compose(sheet: Sheet):
    """The composite figure of a sheet, panels in rows of ``columns``."""
    from matplotlib.figure import Figure

    slots = []  # (row, col, span)
    row = col = 0
    for p in sheet.panels:
        span = min(sheet.spans.get(p.name, 1), sheet.columns)
        if col + span > sheet.columns:
            row, col = row + 1, 0
        slots.append((row, col, span))
        col += span
    rows = row + 1
    w, h = sheet.panel_size
    fig = Figure(figsize=(w * sheet.columns + 1.6 * sheet.columns, h * rows + 0.6), layout="constrained")
    grid = fig.add_gridspec(rows, sheet.columns)
    for p, (r, c, span) in zip(sheet.panels, slots):
        ax = fig.add_subplot(grid[r, c:c + span])
        p.draw(ax)
        legend_outside(ax)
    fig.suptitle(literal(sheet.title))
    return fig


def single(sheet: Sheet, panel: Panel):
    """One panel as its own figure, one journal column wide (legend outside, to the right)."""
    from matplotlib.figure import Figure

    w, h = SINGLE_PANEL_SIZE
    with _small_text(None):
        fig = Figure(figsize=(w + 1.6, h), layout="constrained")
        ax = fig.add_subplot()
        panel.draw(ax)
        legend_outside(ax)
    return fig


class _small_text:
    """Journal-sized text in single panels."""

    def __init__(self, fig):
        self.fig = fig

    def __enter__(self):
        import matplotlib as mpl

        self._ctx = mpl.rc_context({"font.size": 7, "axes.titlesize": 7, "axes.labelsize": 7, "xtick.labelsize": 6,
                                    "ytick.labelsize": 6, "lines.markersize": 4})
        self._ctx.__enter__()

    def __exit__(self, *exc):
        return self._ctx.__exit__(*exc)
