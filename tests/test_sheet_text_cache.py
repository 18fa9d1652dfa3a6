"""Sheets drawn with their texts' layouts and glyph bitmaps kept (capred.report.sheets._cached_text, issue 44 item 3)
have matplotlib's own pixels, bit for bit: the first draw (bitmaps rendered at their sub-pixel offset and moved by
whole pixels) and a second one (every glyph pasted from the cache), against a renderer matplotlib made itself."""

from __future__ import annotations

import warnings

import matplotlib
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import capred
from capred.report import sheets
from capred.report.sheets import raster, sheet_figure


def _own_pixels(fig) -> np.ndarray:
    """The figure drawn by a renderer matplotlib made itself (no kept layouts or bitmaps)."""
    canvas = FigureCanvasAgg(fig)  # a new canvas: a new RendererAgg, none of capred's
    with sheets.journal_style():  # the style raster() draws in (hinting, antialiasing)
        canvas.draw()
    assert "draw_text" not in vars(canvas.get_renderer())
    return np.array(canvas.buffer_rgba(), copy=True)


@pytest.fixture(scope="module")
def results():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return [
            capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)),
            capred.run("retention", capred.sample_path("retention")),
        ]


@pytest.mark.skipif(
    not matplotlib.__version__.startswith(sheets.CACHED_TEXT_VERSIONS), reason="texts drawn by matplotlib itself"
)
def test_kept_glyphs_give_matplotlibs_pixels(results):
    sheets._LAYOUTS.clear()
    sheets._GLYPHS.clear()
    sheets._TEXT_BOXES.clear()
    drawn = 0
    for result, n in zip(results, (2, 1)):  # two shear sheets (rotated labels, mathtext, legends), one retention
        for sheet in list(result.figures().values())[:n]:
            if not isinstance(sheet, sheets.Sheet):
                continue
            fig = sheet_figure(sheet, 100.0)  # 100 dpi: the same code path as 300, a ninth of the pixels
            assert "draw_text" in vars(fig.canvas.get_renderer())  # capred's renderer keeps texts
            first = raster(fig)  # bitmaps rendered now, pasted by whole pixels
            again = raster(fig)  # every glyph from the cache
            own = _own_pixels(fig)
            assert np.array_equal(first, own), sheet.title
            assert np.array_equal(again, own), sheet.title
            drawn += 1
    assert drawn == 3 and len(sheets._GLYPHS) > 100  # glyphs were kept, and the pixels are matplotlib's


@pytest.mark.skipif(
    not matplotlib.__version__.startswith(sheets.CACHED_TEXT_VERSIONS), reason="texts laid out by matplotlib itself"
)
def test_kept_text_layouts_are_matplotlibs(results):
    """Every text of a sheet drawn twice (the second time from the kept layouts) has the layout matplotlib's own
    Text._get_layout gives it: the same box and the same lines at the same offsets, to the last bit."""
    from matplotlib.text import Text

    sheets._TEXT_BOXES.clear()
    sheet = next(s for s in results[0].figures().values() if isinstance(s, sheets.Sheet))
    fig = sheet_figure(sheet, 100.0)
    raster(fig)
    renderer = fig.canvas.get_renderer()
    own = Text._get_layout.own
    texts = [t for t in fig.findobj(Text) if t.get_text()]
    assert len(texts) > 50 and len(sheets._TEXT_BOXES) > 20  # tick labels, axis labels, legends were kept
    with sheets.journal_style():  # the style the sheet was laid out in (hinting)
        for t in texts:
            kept, fresh = t._get_layout(renderer), own(t, renderer)
            assert kept[0].bounds == fresh[0].bounds, t.get_text()
            assert kept[1] == fresh[1] and kept[2] == fresh[2], t.get_text()
    # a user's own renderer is left to matplotlib: nothing is kept for it
    n = len(sheets._TEXT_BOXES)
    mine = FigureCanvasAgg(fig).get_renderer()
    for t in texts:
        t._get_layout(mine)
    assert len(sheets._TEXT_BOXES) == n
