"""`capred retention` readable on the page (issue 29, items 1 and 8): console tables at 80, 100 and 120 columns
show every model's name, R², AICc and weight with no number cut; the `--model all` figure keeps its axes, its y
label and distinguishable line styles, and names the input file."""

import io
import itertools
import warnings

import pytest
from rich.console import Console

import capred
from capred.fitting.retention_models import MODELS
from capred.report.presenters import console_tables
from capred.report.render import render_tables
from capred.report.retention_figures import RETENTION_STYLES


@pytest.fixture(scope="module")
def everything():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        return capred.run_retention(
            capred.sample_path("retention"), capred.RetentionOptions(models="all", hysteresis="kool-parker")
        )


@pytest.mark.parametrize("width", [80, 100, 120])
def test_console_tables_fit_the_terminal_with_every_number_whole(everything, width):
    con = Console(file=io.StringIO(), width=width, force_terminal=True, color_system=None)
    specs = console_tables(everything)
    render_tables(specs, con)
    text = con.file.getvalue()
    assert max(len(line) for line in text.splitlines()) <= width
    lines = text.splitlines()
    for spec in specs:
        for row in spec.rows:
            for cell in row:  # every cell on one line, whole: nothing cut, wrapped or squeezed to nothing
                assert any(cell.strip() in line for line in lines), (width, spec.title, cell)
    # every model of both branches with its R², AICc and weight, each on the model's own row
    for b in everything.fits:
        for r in everything.fit_records(b):
            model_table = next(s for s in specs if s.title.startswith(f"Retention models, branch {b}"))
            row = next(x for x in model_table.rows if x[0] == r.model)
            assert any(all(cell in line for cell in (row[0], row[2], row[4], row[6])) for line in lines), row
    assert "(1/2)" not in text  # no table folded into pieces at these widths


def test_figure_keeps_its_axes_with_every_model(everything):
    """The legend of seven models goes below the axes and the sheet grows: the axes keep at least the height they
    have with one model and its legend beside them (within 5 %: the tick labels differ), the y label lies inside
    the figure, the title names the input file."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        few = capred.run_retention(capred.sample_path("retention"), capred.RetentionOptions(models=("vg",)))
    heights = []
    for r in (few, everything):
        fig = r.plot("retention")
        fig.canvas.draw()
        ax = fig.axes[0]
        heights.append(ax.get_position().height * fig.get_size_inches()[1])
        label = ax.yaxis.label.get_window_extent()
        assert label.x0 >= 0 and label.y0 >= 0 and label.y1 <= fig.bbox.height  # not clipped
        assert "retention.csv" in fig._suptitle.get_text()
    assert heights[1] >= 0.95 * heights[0]


def test_line_styles_are_distinguishable():
    """At least nine styles, each pair differing in marker or dash pattern; Kosugi and Durner differ in both."""

    def key(st):
        return (str(st.get("ls")), st.get("marker"))

    assert len(RETENTION_STYLES) >= 9
    assert len({key(s) for s in RETENTION_STYLES}) == len(RETENTION_STYLES)
    styles = [m.style for m in MODELS.values()]
    for a, b in itertools.combinations(styles, 2):
        assert key(a) != key(b)
    k, d = MODELS["kosugi"].style, MODELS["durner"].style
    assert k["ls"] != d["ls"] and k.get("marker") != d.get("marker")
