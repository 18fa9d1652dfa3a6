"""Figure sheets: panels drawn once at journal sizes, composed into sheets laid out for an A4 page.

A Result's ``figures()`` gives Sheets of Panels (``Panel.draw(ax)`` puts the
content into one Axes). Each panel is drawn once, on its own figure of a
journal's width: one column (``COLUMN_MM`` = 85 mm) or, for a panel the sheet
spans over two columns, the full text width (``PAGE_MM`` = 180 mm). Its layout
(constrained layout, which makes room for the legend beside the axes) is
computed once and then frozen, so that drawing and saving never run it again.

The composite of a sheet is made from those panels: at most two columns of
panels per row (a sheet never gets wider than 180 mm, the text width of an A4
page), a title band above. As a raster (PNG, and the picture in report.html)
it is the panels' pixels pasted into one image, so nothing is drawn twice; a
vector composite (PDF, SVG, or a Figure for a notebook) is drawn again with
every axes placed exactly where the panel's own layout put it.

Text is 7-9 pt at these sizes (``RC``), and the files carry no timestamp and
no random id (``RC["svg.hashsalt"]``, ``NO_STAMP``): a rerun writes the same bytes.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field

from .style import legend_outside, literal

#: one journal column [mm]
COLUMN_MM = 85.0
#: two journal columns: the text width of an A4 page, and the widest sheet [mm]
PAGE_MM = 180.0
#: gap between the two columns of a sheet [mm]
COLUMN_GAP_MM = PAGE_MM - 2 * COLUMN_MM
#: gap between two rows of a sheet [mm]
ROW_GAP_MM = 2.0
#: height of the band holding the sheet's title [mm]
TITLE_MM = 7.0
#: a two-column panel is this much taller than a one-column panel of the same sheet
WIDE_HEIGHT = 1.25
MM_PER_INCH = 25.4

#: journal-sized text and lines (7-9 pt at the printed size), fonts embedded as TrueType in PDF and text kept
#: as text in SVG (editable, as journals ask), and a fixed salt for SVG ids (the same ids on every run)
RC = {
    "font.size": 8.0,
    "axes.titlesize": 8.0,
    "axes.labelsize": 8.0,
    "xtick.labelsize": 7.0,
    "ytick.labelsize": 7.0,
    "legend.fontsize": 7.0,
    "legend.title_fontsize": 7.0,
    "figure.titlesize": 9.0,
    "axes.titley": 1.0,  # titles at the top of the axes (no panel has top ticks): no search for a place per draw
    "lines.linewidth": 1.0,
    "lines.markersize": 4.0,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "xtick.major.size": 3.0,
    "ytick.major.size": 3.0,
    "patch.linewidth": 0.6,
    "figure.facecolor": "white",
    "savefig.facecolor": "white",
    "pdf.fonttype": 42,
    "svg.fonttype": "none",  # SVG text as <text> elements: editable in Inkscape or Illustrator
    "ps.fonttype": 42,
    "svg.hashsalt": "capred",
    # glyphs rasterised as outlined, without FreeType's hinting: hinting snaps stems to the pixel grid of a
    # screen (~100 dpi) and adds nothing a reader sees at 300 dpi, while its bytecode costs a fifth of drawing
    # a report sheet (text is half of it); PDF and SVG never hint
    "text.hinting": "no_hinting",
}

#: no timestamp or software version in figure files: reruns give the same bytes
NO_STAMP = {
    "png": {"Software": None},
    "pdf": {"CreationDate": None, "Producer": None, "Creator": None},
    "svg": {"Date": None, "Creator": None},
}


@dataclass
class Panel:
    """One panel of a sheet: ``draw(ax)`` draws its content into an Axes."""

    name: str  # file-name part: figures/<sheet>_<name>.<fmt>
    draw: Callable  # draw(ax) -> ax
    caption: str = ""


@dataclass
class Sheet:
    """Panels shown together on one figure.

    ``columns`` per row at most (wrapped to two, the width of a page), a panel named in ``spans`` with 2 takes a whole
    row at two-column width; ``panel_size`` gives the panels' aspect (height / width of its two numbers); an
    ``on_request`` sheet is written only when every sheet is asked for (``write_outputs(..., figures="all")``,
    ``--figures all``).
    """

    title: str
    panels: list[Panel]
    columns: int = 2
    caption: str = ""
    spans: dict[str, int] = field(default_factory=dict)  # panel name -> columns it spans (one row)
    panel_size: tuple[float, float] = (4.6, 3.4)  # only its aspect counts: height / width
    on_request: bool = False  # not among the sheets written by default
    #: panel name -> room [mm] added below a panel whose legend, placed under the axes, would take more than
    #: LEGEND_BELOW_MAX of its height: measured on the first draw, then every layout (``sheet_layout``,
    #: ``panel_figure``, ``compose_raster``) gives the panel that much more height, so the axes keep theirs
    legend_room: dict = field(default_factory=dict, repr=False, compare=False)


@contextmanager
def journal_style(salt: str | None = None):
    """Matplotlib settings of every capred figure while the block runs (``salt``: the SVG id salt).

    Parameters
    ----------
    salt : str or None, optional
        Salt of the SVG element ids (same salt, same ids: reproducible files).
    """
    import matplotlib as mpl

    rc = dict(RC)
    if salt is not None:
        rc["svg.hashsalt"] = f"capred:{salt}"
    with mpl.rc_context(rc):
        yield


# --- geometry -----------------------------------------------------------------------------------------------
def panel_size_mm(sheet: Sheet, panel: Panel) -> tuple[float, float]:
    """Printed size of a panel [mm].

    One column (85 mm) wide, or the page width (180 mm) when the sheet spans it over two columns; its height from the
    sheet's aspect, plus any room its legend needs below the axes (``Sheet.legend_room``).

    Parameters
    ----------
    sheet : Sheet
        The sheet.
    panel : Panel
        One of its panels.

    Returns
    -------
    tuple of float
        (width, height) [mm].
    """
    w, h = sheet.panel_size
    aspect = h / w if w > 0 else 0.75
    extra = sheet.legend_room.get(panel.name, 0.0)
    if sheet.spans.get(panel.name, 1) >= 2:
        return PAGE_MM, COLUMN_MM * aspect * WIDE_HEIGHT + extra
    return COLUMN_MM, COLUMN_MM * aspect + extra


@dataclass(frozen=True)
class Slot:
    """Where a panel sits in its sheet: left and top edges and size [mm] (from the sheet's top-left corner)."""

    x: float
    y: float
    width: float
    height: float


def sheet_layout(sheet: Sheet) -> tuple[list[Slot], float, float]:
    """Slots of the panels and the sheet's (width, height) [mm].

    Rows of at most two one-column panels (``min(columns, 2)``), a spanned panel alone in its row, the title band on
    top.

    Parameters
    ----------
    sheet : Sheet
        The sheet.

    Returns
    -------
    tuple
        (slots, width [mm], height [mm]).
    """
    columns = max(1, min(int(sheet.columns), 2))
    slots: list[Slot] = []
    y, x, row_h, used = TITLE_MM, 0.0, 0.0, 0
    width = 0.0
    for p in sheet.panels:
        w, h = panel_size_mm(sheet, p)
        wide = w > COLUMN_MM
        if used and (wide or used >= columns):
            y, x, row_h, used = y + row_h + ROW_GAP_MM, 0.0, 0.0, 0
        slots.append(Slot(x, y, w, h))
        width = max(width, x + w)
        x += w + COLUMN_GAP_MM
        row_h = max(row_h, h)
        used = columns if wide else used + 1
    return slots, width or COLUMN_MM, y + row_h


# --- one panel ----------------------------------------------------------------------------------------------
#: a legend wider than this share of its panel goes below the axes instead of beside them
LEGEND_SIDE_MAX = 0.30
#: a legend beside the axes may be this share of its panel's height at most (a taller one would push the axes
#: up to make room for it below them): beyond, it goes below
LEGEND_SIDE_HEIGHT = 0.80
#: a legend below the axes may take this share of its panel's height; a longer one makes the panel taller
#: (``Sheet.legend_room``) instead of squashing the axes
LEGEND_BELOW_MAX = 0.30
#: white margin kept around a panel's content [mm]
PAD_MM = 1.0


_MATHTEXT = []  # the one mathtext parser of every capred figure drawn by Agg (made on first use)
#: Agg renderers by (width px, height px, dpi), shared by every figure of that size (``_canvas``)
_RENDERERS: dict = {}
#: sizes of figure whose renderer is kept (a run draws two or three sizes: sheets of 2 and 1 rows, a title)
KEEP_RENDERERS = 4
#: sheet figures handed back after their files were written (``release``), by (width px, height px, dpi,
#: panels): the next sheet of that shape (the other material's, the next file's of a batch) is drawn on them
_TEMPLATES: dict = {}
#: shapes of sheet kept
KEEP_TEMPLATES = 4


#: text layouts and glyph bitmaps of capred's Agg renderers (``_cached_text``), by font, size, dpi and text or
#: glyph: kept across the sheets of a run and the files of a batch, emptied at a fork and when this many are held
#: (a 300-dpi glyph's bitmap is ~260 bytes, ~0.5 kB with its key: at most ~10 MB; a shear file's two sheets
#: hold ~1,000)
_LAYOUTS: dict = {}
_GLYPHS: dict = {}
KEEP_GLYPHS = 20_000
#: the matplotlib versions whose Agg text drawing ``_cached_text`` repeats (tests/test_sheet_text_cache.py checks
#: the pixels against matplotlib's own drawing); any other version draws its text itself
CACHED_TEXT_VERSIONS = ("3.11.",)


def _cached_text(renderer) -> None:
    """Let an Agg renderer of capred's sheets lay out each text and render each glyph once (matplotlib 3.11).

    matplotlib 3.11 draws a text glyph by glyph: it shapes the string (``FT2Font._layout``), then for every
    glyph sets the font's size and a transform (two small numpy products) and renders the glyph's bitmap with
    FreeType at its sub-pixel position. About half the time a 300-dpi sheet takes to draw is its ~90 texts
    (55 of 105 ms, measured on the shear sample's sheet). Here a text's layout is kept by (font, size, dpi,
    string, hinting, features, language), and a glyph's bitmap by (font, size, dpi, glyph, transform, the
    sub-pixel part of its position, hinting, antialiasing): FreeType renders a glyph moved by whole pixels into
    the same bitmap moved by whole pixels, so the kept bitmap is pasted where matplotlib would have rendered
    it. The pixels are matplotlib's own (tests/test_sheet_text_cache.py); a tick label, axis label or legend
    entry drawn again (the other material's sheet, the next file of a batch) costs one paste.
    Applied to matplotlib 3.11 only (``CACHED_TEXT_VERSIONS``), where these private methods were checked.
    """
    import math

    import matplotlib
    import numpy as np

    cls = type(renderer)
    if not matplotlib.__version__.startswith(CACHED_TEXT_VERSIONS) or "draw_text" in vars(renderer):
        return
    try:
        from matplotlib.backends.backend_agg import get_hinting_flag
        from matplotlib.ft2font import FT2Font, RenderMode
    except ImportError:  # pragma: no cover - another matplotlib
        return
    needed = ("_layout", "_render_glyph", "_set_transform")
    if not all(hasattr(FT2Font, n) for n in needed) or not hasattr(cls, "_draw_text_glyphs_and_boxes"):
        return  # pragma: no cover
    own_glyphs = cls._draw_text_glyphs_and_boxes.__get__(renderer)

    def draw_text(gc, x, y, s, prop, angle, ismath=False, mtext=None):  # RendererAgg.draw_text, layouts kept
        if ismath:
            return renderer.draw_mathtext(gc, x, y, s, prop, angle)
        font = renderer._prepare_font(prop)
        flags = get_hinting_flag()
        features = mtext.get_fontfeatures() if mtext is not None else None
        language = mtext.get_language() if mtext is not None else None
        size = prop.get_size_in_points()
        try:
            key = (font, size, renderer.dpi, s, flags, _frozen(features), _frozen(language))
            items = _LAYOUTS.get(key)
        except TypeError:  # pragma: no cover - an unhashable feature list: no keeping
            key, items = None, None
        if items is None:
            items = [
                (item.ft_object, item.glyph_index, item.x, item.y)
                for item in font._layout(s, flags=flags, features=features, language=language)
            ]
            if key is not None:
                if len(_LAYOUTS) >= KEEP_GLYPHS:
                    _LAYOUTS.clear()
                _LAYOUTS[key] = items
        glyphs(gc, x, y, angle, ((ft, size, index, 0, 1, dx, dy) for ft, index, dx, dy in items), [])

    def glyphs(gc, x, y, angle, items, boxes):  # RendererAgg._draw_text_glyphs_and_boxes, bitmaps kept
        if boxes:  # a mathtext with rules (fraction bars): matplotlib's own drawing
            return own_glyphs(gc, x, y, angle, items, boxes)
        cos = math.cos(math.radians(angle))
        sin = math.sin(math.radians(angle))
        flags = get_hinting_flag()
        antialiased = gc.get_antialiased()
        height = renderer.height
        draw = renderer._renderer.draw_text_image
        for font, size, index, slant, extend, dx, dy in items:  # dy is upwards
            # matplotlib's transform (0x10000 R) @ [[extend, extend slant], [0, 1]], rounded as it rounds it
            a, b, c, d = 0x10000 * cos, 0x10000 * -sin, 0x10000 * sin, 0x10000 * cos
            matrix = (
                round(a * extend),
                round(a * (extend * slant) + b),
                round(c * extend),
                round(c * (extend * slant) + d),
            )
            px = round(0x40 * (x + dx * cos - dy * sin))
            py = round(0x40 * (height - y + dx * sin + dy * cos))  # FreeType's y is upwards
            key = (font, size, renderer.dpi, index, matrix, px & 63, py & 63, flags, antialiased)
            kept = _GLYPHS.get(key)
            if kept is None:
                font.set_size(size, renderer.dpi)
                font._set_transform(np.array(matrix, dtype=int).reshape(2, 2), [px & 63, py & 63])
                bitmap = font._render_glyph(index, flags, RenderMode.NORMAL if antialiased else RenderMode.MONO)
                buffer = np.array(bitmap.buffer, copy=True)
                if not antialiased:
                    buffer *= 0xFF
                if len(_GLYPHS) >= KEEP_GLYPHS:
                    _GLYPHS.clear()
                kept = _GLYPHS[key] = (buffer, bitmap.left, bitmap.top)
            buffer, left, top = kept
            # draw_text_image's y is downwards and the bitmap's bottom side; whole pixels moved back in
            draw(buffer, left + (px >> 6), int(height) - (top + (py >> 6)) + buffer.shape[0], 0, gc)

    renderer.draw_text = draw_text
    renderer._draw_text_glyphs_and_boxes = glyphs
    renderer._capred_text_boxes = True  # Text._get_layout kept for this renderer's texts (_kept_text_boxes)
    _kept_text_boxes()


#: each text's layout (its box, lines and their offsets from its anchor, ``Text._get_layout``) on capred's Agg
#: renderers, by what it depends on (``_kept_text_boxes``): kept across sheets and files, emptied at a fork
_TEXT_BOXES: dict = {}


def _kept_text_boxes() -> None:
    """Let ``Text._get_layout`` answer once per text state on capred's Agg renderers (matplotlib 3.11).

    matplotlib lays a text out again each time its extent is asked: a tick label's box for the axis's tight
    box, for the axis label's place, for the spines, then its drawing; a legend's entries for the legend's
    box at every packing (some 850 layouts a shear file, a tenth of a season's CPU). A layout is the text's
    box and its lines' offsets *relative to its anchor*: it depends on the string, the font, the dpi, the
    alignment, the rotation and its mode, the line spacing, whether mathtext is parsed and the hinting, not
    on where the text stands, so it is kept by those (wrapped texts, whose lines depend on their place, and TeX texts are
    laid out each time). Callers read the layout and never change it (matplotlib 3.11: ``Text.draw``,
    ``Text.get_window_extent``, ``Text.update_bbox_position_size``, ``TextArea.get_bbox``). Renderers other
    than capred's (a user's own figures) are untouched: their texts are laid out by matplotlib as always.
    """
    from matplotlib import rcParams as rc
    from matplotlib.text import Text

    if getattr(Text._get_layout, "_capred", False):
        return
    own = Text._get_layout

    def _get_layout(self, renderer):
        if not getattr(renderer, "_capred_text_boxes", False) or self.get_wrap() or self.get_usetex():
            return own(self, renderer)
        key = (
            self.get_text(),
            hash(self._fontproperties),  # FontProperties compare by their hash (matplotlib's own text caches)
            self.get_figure(root=True).dpi,
            self._linespacing,
            self._multialignment,
            self._horizontalalignment,
            self._verticalalignment,
            self.get_rotation(),
            self.get_rotation_mode(),
            self._parse_math,
            rc["text.hinting"],  # the text's measure depends on the hinting in force (a notebook's own style)
            rc["text.hinting_factor"],
        )
        kept = _TEXT_BOXES.get(key)
        if kept is None:
            kept = own(self, renderer)
            if len(_TEXT_BOXES) >= KEEP_GLYPHS:
                _TEXT_BOXES.clear()
            _TEXT_BOXES[key] = kept
        return kept

    _get_layout._capred = True
    _get_layout.own = own  # matplotlib's own (tests/test_sheet_text_cache.py compares the two)
    Text._get_layout = _get_layout


def _frozen(value):
    """A list (of font features, of languages) as a tuple, so that it can be part of a key."""
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    return value


def _forget_fonts_after_fork() -> None:
    """In a forked child: drop the shared mathtext parser and every cached parse.

    A parse keeps the font objects its glyphs are drawn from, and font objects opened before the fork read their files
    through offsets the parent shares (FreeType then fails: "too many hints", "invalid outline"); matplotlib forgets its
    own font cache at a fork, this forgets the parses, so the child opens fonts of its own.
    """
    import sys

    _MATHTEXT.clear()
    _RENDERERS.clear()  # they hold the parent's parser
    _TEMPLATES.clear()  # their texts were measured with the parent's fonts
    _LAYOUTS.clear()  # their glyphs' fonts are the parent's
    _TEXT_BOXES.clear()
    _GLYPHS.clear()
    mathtext = sys.modules.get("matplotlib.mathtext")
    if mathtext is not None:
        mathtext.MathTextParser._parse_cached.cache_clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_fonts_after_fork)


def _canvas(fig):
    r"""Give ``fig`` an Agg canvas: layout and drawing then share one renderer and its text-size cache.

    Every such renderer also shares one mathtext parser, whose cache keeps each parsed label (a label such
    as ``$\tau_{max}$ [kPa]`` costs 10-50 ms to parse): a label repeated in another panel or sheet at the
    same size and dpi is parsed once. Figures of one size share one renderer (``_RENDERERS``): its pixel
    buffer is allocated once and its text-size cache (tick labels, legend entries, titles) serves every
    sheet of a run and every file of a batch. A draw clears the buffer first, and ``raster`` copies it.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    key = (*canvas.get_width_height(physical=True), fig.dpi)
    renderer = _RENDERERS.get(key)
    if renderer is None:
        renderer = canvas.get_renderer()
        renderer._get_font_height_metrics = _font_heights(renderer.dpi)
        _cached_text(renderer)
        if len(_RENDERERS) >= KEEP_RENDERERS:
            _RENDERERS.pop(next(iter(_RENDERERS)))
        _RENDERERS[key] = renderer
    canvas.renderer, canvas._lastKey = renderer, key  # what FigureCanvasAgg.get_renderer reuses
    if not _MATHTEXT:
        _MATHTEXT.append(renderer.mathtext_parser)
    renderer.mathtext_parser = _MATHTEXT[0]
    return renderer


def _font_heights(dpi: float):
    """The font's line metrics that matplotlib's text layout asks for every line of every text, once per font.

    ``Text._get_layout`` asks a renderer for ``_get_font_height_metrics(prop)`` when it has one, else finds
    the font file, opens it and reads its OS/2 or hhea table for each text it lays out (about a tenth of a
    sheet's drawing). This gives the same three numbers from the same tables, computed once per font and size:
    (ascent, descent, line gap) [px] at ``dpi``, the renderer's (and its figure's) resolution.
    """
    from matplotlib.font_manager import fontManager, get_font

    seen: dict = {}

    def metrics(prop):
        key = (
            tuple(prop.get_family()),
            prop.get_slant(),
            prop.get_variant(),
            prop.get_weight(),
            prop.get_stretch(),
            prop.get_size_in_points(),
            prop.get_file(),
            prop.get_math_fontfamily(),
        )
        out = seen.get(key)
        if out is None:
            out = (None, None, None)
            font = get_font(fontManager._find_fonts_by_props(prop))
            for table_name, gap, ascent, descent in (
                ("OS/2", "sTypoLineGap", "sTypoAscender", "sTypoDescender"),
                ("hhea", "lineGap", "ascent", "descent"),
            ):  # as matplotlib.text.Text._get_layout reads them
                table = font.get_sfnt_table(table_name)
                if table is None:
                    continue
                scale = 1 / font.get_sfnt_table("head")["unitsPerEm"] * prop.get_size_in_points() * dpi / 72
                out = (table[ascent] * scale, -table[descent] * scale, table[gap] * scale)
                break
            seen[key] = out
        return out

    return metrics


@contextmanager
def _ticks_once(axes):
    """Make each axis of ``axes`` place and label its ticks once per state while the block runs.

    A state is the axis's view interval, its axes' box, its locator and formatter: matplotlib asks again for the tick
    labels' extents, the axis label's place and each spine's extent (four to eight times per axis and draw), each time
    recomputing the same tick positions and label texts. The same state gives the same ticks, so the first answer is
    kept.
    """
    patched = []
    for ax in axes:
        for axis in (ax.xaxis, ax.yaxis):
            if "_update_ticks" in vars(axis):
                continue
            update = axis._update_ticks
            memo: dict = {}

            def once(axis=axis, update=update, memo=memo):
                bounds = axis.axes.bbox.bounds
                state = (
                    *axis.get_view_interval(),
                    *bounds,
                    id(axis.get_major_locator()),
                    id(axis.get_major_formatter()),
                    id(axis.get_minor_locator()),
                    id(axis.get_minor_formatter()),
                    axis.get_scale(),
                )
                if memo.get("state") != state:
                    memo["ticks"], memo["state"] = update(), state
                return memo["ticks"]

            axis._update_ticks = once
            patched.append(axis)
    try:
        yield
    finally:
        for axis in patched:
            del axis._update_ticks


def _draw_panel(panel, ax):
    """``panel.draw(ax)`` with its ``ax.legend(...)`` call recorded instead of run.

    The legend is then built once, where ``_dress`` puts it, not also where the panel asked. Returns (handles, labels)
    the panel gave (None, None: the axes' labelled artists).
    """
    asked = {}

    def legend(*args, **kwargs):
        asked["handles"] = kwargs.get("handles", args[0] if args else None)
        asked["labels"] = kwargs.get("labels", args[1] if len(args) > 1 else None)

    ax.legend = legend
    try:
        panel.draw(ax)
    finally:
        del ax.legend
    from ..text_safety import safe_axes  # controls shown before anything is measured or drawn

    return asked.get("handles"), safe_axes(ax, asked.get("labels"))


#: the size of a legend beside its axes [px] (and its font size [pt]) by (labels, panel width and height [px],
#: dpi): it depends on nothing else (the handles' boxes have a fixed size), so a panel whose legend was found
#: too big to stand beside its axes builds it below them at once (a batch's files repeat their legends)
_SIDE_LEGENDS: dict = {}
#: legends whose size beside the axes is kept
KEEP_SIDE_LEGENDS = 256


def _below(size, width_px: float, height_px: float | None) -> bool:
    """Whether a legend of ``size`` (width, height) [px] beside its axes is too wide or too tall for its panel."""
    return not (
        size[0] <= LEGEND_SIDE_MAX * width_px and (height_px is None or size[1] <= LEGEND_SIDE_HEIGHT * height_px)
    )


def _dress(ax, width_px: float, renderer, height_px: float | None = None, handles=None, labels=None) -> float:
    """Put the axes' legend outside its data.

    Beside the axes (``style.legend_outside``), or, when that would take more than ``LEGEND_SIDE_MAX`` of the panel's
    width, below the x-axis label, in as many columns as the panel's width holds (rows balanced).

    Returns the height [px] the legend below needs beyond ``LEGEND_BELOW_MAX`` of ``height_px`` (the
    panel's height; 0 when it fits or is beside the axes): the room to add to the panel so that the
    legend never squashes the axes. ``handles``, ``labels``: what the panel asked its legend to show
    (``_draw_panel``), else its labelled artists or its legend.
    """
    from matplotlib.transforms import ScaledTranslation

    known = None
    if handles is None and ax.get_legend() is None:  # the axes' own labelled artists
        artists, own = ax.get_legend_handles_labels()
        known = _SIDE_LEGENDS.get((tuple(own), width_px, height_px, renderer.dpi))
    if known is not None and _below(known, width_px, height_px):  # measured before: straight below
        side, fontsize = known[0], known[2]
        handles, labels = artists, own
    else:
        legend_outside(ax, handles=handles, labels=labels)
        leg = ax.get_legend()
        if leg is None:
            return 0.0
        box = leg.get_window_extent(renderer)
        labels = [t.get_text() for t in leg.get_texts()]
        fontsize = leg.get_texts()[0].get_fontsize() if labels else RC["legend.fontsize"]
        side = box.width
        if known is None and handles is None:
            if len(_SIDE_LEGENDS) >= KEEP_SIDE_LEGENDS:
                _SIDE_LEGENDS.pop(next(iter(_SIDE_LEGENDS)))
            _SIDE_LEGENDS[(tuple(labels), width_px, height_px, renderer.dpi)] = (box.width, box.height, fontsize)
        if not _below((box.width, box.height), width_px, height_px):
            return 0.0
        handles = list(leg.legend_handles)
        artists, own = ax.get_legend_handles_labels()
        if own == labels:  # the axes' own artists: error bars keep their look in the new legend
            handles = artists
        leg.remove()
    drop = _below_axis_pt(ax) / 72 * ax.figure.dpi  # px from the axes' bottom to the legend's top
    fits = max(1, min(len(labels), int(0.95 * width_px // max(side, 1.0))))
    rows = -(-len(labels) // fits)
    ncol = max(1, -(-len(labels) // max(rows, 1)))  # the fewest columns giving that many rows
    leg = ax.legend(
        handles,
        labels,
        loc="upper center",
        bbox_to_anchor=(0.5, 0.0),
        ncol=ncol,
        fontsize=fontsize,
        bbox_transform=ax.transAxes + ScaledTranslation(0, -drop / ax.figure.dpi, ax.figure.dpi_scale_trans),
        frameon=False,
        borderaxespad=0.0,
        columnspacing=1.2,
        handlelength=1.8,
    )
    if height_px is None:
        return 0.0
    return max(0.0, leg.get_window_extent(renderer).height + drop - LEGEND_BELOW_MAX * height_px)


def _below_axis_pt(ax) -> float:
    """Height of what hangs below an axes' bottom spine [pt].

    Ticks, tick labels, the axis label (mathtext with sub- or superscripts included), plus a 2 pt gap; from the
    settings, without laying out any text.
    """
    import matplotlib as mpl

    rc = mpl.rcParams
    label = 1.45 * rc["axes.labelsize"] + rc["axes.labelpad"] if ax.get_xlabel() else 0.0
    ticks = (
        rc["xtick.major.size"] + rc["xtick.major.pad"] + 1.3 * rc["xtick.labelsize"]
        if ax.xaxis.get_major_locator() is not None and ax.xaxis.get_visible()
        else 0.0
    )
    return ticks + label + 2.0


def _fit(fig, renderer, pad_mm: float = PAD_MM, axes=None, region=None) -> None:
    """Fixed layout in one pass.

    Move and scale a panel's axes (with any colour bar or twin, as a group) so that everything drawn around them (tick
    labels, axis labels, title, legend) just fits its region.

    ``axes``: the group (default: every axes of the figure); ``region``: (x0, y0, x1, y1) of the room it
    has [figure pixels, from the lower left corner] (default: the whole figure).
    """
    from matplotlib.transforms import Bbox

    axes = [ax for ax in (fig.axes if axes is None else axes) if ax.get_visible()]
    if not axes:
        return
    with _ticks_once(axes):
        tight = Bbox.union([b for b in (ax.get_tightbbox(renderer) for ax in axes) if b is not None])
    inner = Bbox.union([ax.bbox for ax in axes])  # after apply_aspect: the boxes as drawn
    W, H = fig.bbox.width, fig.bbox.height
    X0, Y0, X1, Y1 = region if region is not None else (0.0, 0.0, W, H)
    RW, RH = X1 - X0, Y1 - Y0
    pad = pad_mm / MM_PER_INCH * fig.dpi
    x0 = X0 + pad + (inner.x0 - tight.x0)
    x1 = X1 - pad - (tight.x1 - inner.x1)
    y0 = Y0 + pad + (inner.y0 - tight.y0)
    y1 = Y1 - pad - (tight.y1 - inner.y1)
    if x1 - x0 < 0.25 * RW:  # decorations too wide for the panel: keep a readable plot, let them spill
        x0, x1 = 0.5 * (x0 + x1) - 0.125 * RW, 0.5 * (x0 + x1) + 0.125 * RW
    if y1 - y0 < 0.25 * RH:
        y0, y1 = 0.5 * (y0 + y1) - 0.125 * RH, 0.5 * (y0 + y1) + 0.125 * RH
    old = Bbox.union([ax.get_position(original=True) for ax in axes])
    sx, sy = (x1 - x0) / W / old.width, (y1 - y0) / H / old.height
    for ax in axes:
        p = ax.get_position(original=True)
        ax.set_position((x0 / W + (p.x0 - old.x0) * sx, y0 / H + (p.y0 - old.y0) * sy, p.width * sx, p.height * sy))


def freeze_layout(fig) -> None:
    """Run the figure's layout engine once, then switch it off: later draws and saves keep these positions.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    None

    References
    ----------
    Matplotlib layout engines, https://matplotlib.org/stable/api/layout_engine_api.html.
    """
    engine = fig.get_layout_engine()
    if engine is not None:
        engine.execute(fig)
        fig.set_layout_engine("none")


def panel_figure(sheet: Sheet, panel: Panel, dpi: float = 300.0):
    """A panel alone on its own figure at its printed size (``panel_size_mm``), laid out once.

    The layout is fixed in one pass (``_fit``): the axes take the room their labels, title and legend leave.
    A legend below the axes that needs more than ``LEGEND_BELOW_MAX`` of the height makes the panel taller
    (recorded in ``sheet.legend_room`` for the sheet's other layouts) before the layout: nothing is drawn twice.

    Parameters
    ----------
    sheet : Sheet
        The sheet the panel belongs to (its spans and aspect set the size).
    panel : Panel
        The panel to draw.
    dpi : float
        Resolution the figure is laid out and drawn at [dots per inch].

    Returns
    -------
    matplotlib.figure.Figure
        The panel's figure (with an Agg canvas), its layout final.
    """
    from matplotlib.figure import Figure

    w, h = panel_size_mm(sheet, panel)
    with journal_style():
        fig = Figure(figsize=(_inches(w, dpi), _inches(h, dpi)), dpi=dpi)
        renderer = _canvas(fig)
        ax = fig.add_axes((0.15, 0.15, 0.7, 0.7))
        handles, labels = _draw_panel(panel, ax)
        extra = _dress(ax, fig.bbox.width, renderer, fig.bbox.height, handles, labels)
        if extra > 0 and panel.name not in sheet.legend_room:  # taller by the legend's excess
            sheet.legend_room[panel.name] = extra / dpi * MM_PER_INCH
            w, h = panel_size_mm(sheet, panel)
            fig.set_size_inches(_inches(w, dpi), _inches(h, dpi))
            renderer = _canvas(fig)  # the new size's renderer, with the shared mathtext parser
        _fit(fig, renderer)
    return fig


def single(sheet: Sheet, panel: Panel, dpi: float = 300.0):
    """One panel as its own figure, one journal column (85 mm) or two (180 mm) wide (see ``panel_figure``).

    Parameters
    ----------
    sheet : Sheet
        The sheet.
    panel : Panel
        One of its panels.
    dpi : float, optional
        Resolution of raster output [dots per inch].

    Returns
    -------
    matplotlib.figure.Figure
    """
    return panel_figure(sheet, panel, dpi)


def warm_up(dpi: float = 300.0) -> None:
    """Draw a tiny panel so that fonts, glyph caches and the mathtext parser are loaded.

    The panel has a title, mathtext labels, ticks, a legend and markers: a process forked afterwards inherits what it
    loaded instead of loading its own.

    Parameters
    ----------
    dpi : float, optional
        Resolution of the tiny figure [dots per inch].
    """
    from matplotlib.figure import Figure

    with journal_style():
        fig = Figure(figsize=(1.0, 0.8), dpi=dpi)
        _canvas(fig)
        ax = fig.add_axes((0.3, 0.3, 0.6, 0.6))
        ax.plot([0, 1], [0, 1], "o-", label=r"$\sigma_N$")
        ax.errorbar([0.5], [0.5], yerr=[0.1], fmt="s")
        ax.set_title("t")
        ax.set_xlabel(r"$\tau_{max}$ [kPa]")
        ax.set_ylabel(r"$S_R$ [–]")
        ax.legend()
        encode_png(raster(fig), dpi)


# --- rasters ------------------------------------------------------------------------------------------------
def raster(fig):
    """The figure drawn once by Agg at its own dpi: a copy of the renderer's RGBA buffer.

    RGBA, not RGB: the buffer is copied whole (one memcpy; the next figure of that size reuses the buffer);
    dropping the alpha byte of every pixel costs a strided copy, done once, by ``encode_png`` as it lays out
    its rows. Opaque: every figure has a white face.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.

    Returns
    -------
    numpy.ndarray
        Shape (rows, columns, 4), dtype uint8.
    """
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    with journal_style(), _ticks_once(fig.axes):
        canvas.draw()
    return np.array(canvas.buffer_rgba(), copy=True)


def _px(mm: float, dpi: float) -> int:
    return int(round(mm / MM_PER_INCH * dpi))


def _inches(mm: float, dpi: float) -> float:
    """A length [mm] as figure inches holding a whole number of pixels at ``dpi`` (Agg truncates the rest)."""
    return max(_px(mm, dpi), 1) / dpi


def _title_raster(title: str, width_mm: float, dpi: float):
    from matplotlib.figure import Figure

    with journal_style():
        fig = Figure(figsize=(_inches(width_mm, dpi), _inches(TITLE_MM, dpi)), dpi=dpi)
        fig.text(
            0.5, 0.45, literal(title), ha="center", va="center", fontsize=RC["figure.titlesize"], wrap=len(title) > 80
        )
        return raster(fig)


def compose_raster(sheet: Sheet, panel_rasters: list, dpi: float):
    """The sheet's composite as one RGB array: the panels' own rasters pasted into their slots under the title.

    Parameters
    ----------
    sheet : Sheet
        The sheet.
    panel_rasters : list of ndarray
        ``raster(panel_figure(sheet, p, dpi))`` of each panel, in the sheet's order.
    dpi : float
        Resolution of the rasters [dots per inch].

    Returns
    -------
    ndarray
        (rows, columns, 3) uint8 image of the whole sheet, ``sheet_layout`` sizes at ``dpi``.
    """
    import numpy as np

    slots, width, height = sheet_layout(sheet)
    out = np.full((_px(height, dpi), _px(width, dpi), 3), 255, np.uint8)
    title = _title_raster(sheet.title, width, dpi)
    th, tw = min(title.shape[0], out.shape[0]), min(title.shape[1], out.shape[1])
    out[:th, :tw] = title[:th, :tw, :3]
    for img, s in zip(panel_rasters, slots):
        r0, c0 = _px(s.y, dpi), _px(s.x, dpi)
        h, w = min(img.shape[0], out.shape[0] - r0), min(img.shape[1], out.shape[1] - c0)
        out[r0 : r0 + h, c0 : c0 + w] = img[:h, :w, :3]
    return out


def encode_png(image, dpi: float, compress_level: int = 3) -> bytes:
    """PNG bytes of an RGB array with its resolution (pHYs) and no text chunk (no time, no software).

    Every row is stored unfiltered (PNG filter type 0) and deflated at ``compress_level``: a figure is mostly
    flat white with thin lines, which deflate alone packs as small as adaptive filtering does (about 320 kB for
    a 180 x 135 mm sheet at 300 dpi) in a third of the time.

    Parameters
    ----------
    image : ndarray
        (rows, columns, 3) uint8 RGB pixels, or (rows, columns, 4) RGBA (``raster``; the alpha is dropped).
    dpi : float
        Resolution written in the pHYs chunk [dots per inch], stored as whole pixels per metre.
    compress_level : int
        zlib level, 0-9.

    Returns
    -------
    bytes
        The PNG file (signature, IHDR, pHYs, IDAT, IEND), the same bytes for the same pixels.
    """
    import struct
    import zlib

    import numpy as np

    img = np.asarray(image, dtype=np.uint8)
    if img.ndim != 3 or img.shape[2] not in (3, 4):
        raise ValueError(f"encode_png wants (rows, columns, 3) RGB or 4 RGBA pixels, got shape {img.shape}")
    h, w = img.shape[:2]
    rows = np.empty((h, 3 * w + 1), np.uint8)
    rows[:, 0] = 0  # filter type None
    if img.shape[2] == 3:
        rows[:, 1:] = img.reshape(h, 3 * w)
    else:  # RGBA: the alpha dropped channel by channel (long strided copies, 2-3x faster than img[..., :3])
        rgb = rows[:, 1:].reshape(h, w, 3)
        for c in range(3):
            rgb[..., c] = img[..., c]

    def chunk(tag: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))

    ppm = int(dpi / 0.0254 + 0.5)  # pixels per metre, as PIL rounds them
    return b"".join(
        [
            b"\x89PNG\r\n\x1a\n",
            chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)),  # 8-bit RGB, no interlace
            chunk(b"pHYs", struct.pack(">IIB", ppm, ppm, 1)),  # unit: metre
            chunk(b"IDAT", zlib.compress(rows, compress_level)),  # the array's buffer: no 12 MB copy first
            chunk(b"IEND", b""),
        ]
    )


# --- one figure per sheet ------------------------------------------------------------------------------------
def _tick_state(ax) -> tuple:
    """What a panel may change of its axes' ticks: the tick settings (``tick_params``) and the scales."""
    return tuple(
        (repr(sorted(axis._major_tick_kw.items())), repr(sorted(axis._minor_tick_kw.items())), axis.get_scale())
        for axis in (ax.xaxis, ax.yaxis)
    )


def _clear(ax) -> None:
    """An axes of a released sheet (``release``) back to the state of a new one, keeping its tick objects.

    ``Axes.clear`` resets the artists, limits, labels, scales, locators and formatters, and throws away the
    ticks, which the next draw makes anew (about a sixth of a sheet's drawing: each tick is five artists whose
    properties are copied from the first). ``release`` pools only sheets whose panels left the tick settings
    and scales as a new axes has them (``_tick_state``), so the kept ticks are those a new axes would make:
    while ``clear`` runs, its passing of the background patch and of the grid setting to fresh ticks (which
    would make them) is skipped, the kept ticks having both already. The aspect, adjustable box and anchor,
    which ``clear`` keeps, are reset as well.
    """
    from matplotlib.artist import Artist

    kept = [(axis, vars(axis).get("majorTicks"), vars(axis).get("minorTicks")) for axis in (ax.xaxis, ax.yaxis)]
    for axis, _, _ in kept:
        axis.set_clip_path = axis.set_tick_params = _later
    try:
        ax.clear()
    finally:
        for axis, _, _ in kept:
            del axis.set_clip_path, axis.set_tick_params
    ax.set_aspect("auto")
    ax.set_adjustable("box")
    ax.set_anchor("C")
    ax.set_box_aspect(None)
    for axis, major, minor in kept:
        if major is not None:
            axis.majorTicks = major
        if minor is not None:
            axis.minorTicks = minor
        Artist.set_clip_path(axis, ax.patch)  # the axis' own; its ticks clip to the same box of the axes


def _later(*args, **kwargs) -> None:
    """``Axis.set_clip_path`` and ``Axis.set_tick_params`` while ``_clear`` clears an axes (see there)."""


def release(fig) -> None:
    """Hand a sheet's figure back once its files are written.

    The next sheet of the same shape drawn with ``sheet_figure(..., reuse=True)`` is drawn on it (its axes cleared,
    their ticks kept: ``_clear``).

    Only a figure whose panels kept the axes as a new figure has them is kept (one axes per panel, linear
    scales, the default tick settings, no figure legend or other text than the title); else nothing happens.
    The caller must not use ``fig`` afterwards.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure made by ``sheet_figure(..., reuse=True)``.
    """
    key = getattr(fig, "_capred_template", None)
    if key is None:
        return
    fresh = fig._capred_tick_state
    if (
        len(fig.axes) != key[3]
        or any(ax.name != "rectilinear" or _tick_state(ax) != state for ax, state in zip(fig.axes, fresh))
        or fig.legends
        or fig.lines
        or fig.patches
        or fig.images
        or fig.artists
        or [t for t in fig.texts if t is not fig._suptitle]
    ):
        return
    if key not in _TEMPLATES and len(_TEMPLATES) >= KEEP_TEMPLATES:
        _TEMPLATES.pop(next(iter(_TEMPLATES)))
    _TEMPLATES[key] = fig


def _template(key, figsize, dpi):
    """A released figure of shape ``key`` set back to ``figsize`` with its axes cleared, or None."""
    fig = _TEMPLATES.pop(key, None)
    if fig is None:
        return None
    if fig._suptitle is not None:
        fig._suptitle.remove()
        fig._suptitle = None
    if tuple(fig.get_size_inches()) != figsize:  # a long legend had made it taller
        fig.set_size_inches(*figsize)
    for ax in fig.axes:
        _clear(ax)
    if [_tick_state(ax) for ax in fig.axes] != fig._capred_tick_state:  # not as new: a new figure instead
        return None
    return fig


def sheet_figure(sheet: Sheet, dpi: float = 300.0, reuse: bool = False):
    """A whole sheet drawn on one figure.

    The title band on top, each panel in its slot (``sheet_layout``), every panel's axes fitted to its slot in one pass
    (``_fit``), the layout then final.

    The panels share one renderer, so a text seen in several panels (axis labels, tick labels, legend
    entries) is measured once; the figure is drawn once whatever is saved from it (PNG, PDF, SVG); a
    legend below its axes that needs a taller panel (``Sheet.legend_room``) makes the figure taller before the
    layout. Its pixels
    at ``dpi`` are those of ``compose_raster`` of the panels' own figures (the same sizes and layout rule).

    With ``reuse``, the sheet is drawn on a figure of the same shape handed back by ``release`` when there is
    one (its axes cleared, their ticks kept), and the figure may be handed back after its files are written:
    for writers that are done with a figure before they draw the next (``write_outputs``), never for a figure
    given to a user. The pixels are those of a new figure.

    Parameters
    ----------
    sheet : Sheet
        The sheet.
    dpi : float
        Resolution the figure is laid out and drawn at [dots per inch].
    reuse : bool, optional
        Draw on a released figure of the same shape when there is one, and allow ``release``.

    Returns
    -------
    matplotlib.figure.Figure
        The sheet's figure (with an Agg canvas), ``sheet_layout`` size rounded to whole pixels, no layout engine.
    """
    from matplotlib.figure import Figure

    slots, width, height = sheet_layout(sheet)
    grown: dict[str, float] = {}
    figsize = (_inches(width, dpi), _inches(height, dpi))
    key = (_px(width, dpi), _px(height, dpi), float(dpi), len(sheet.panels))
    with journal_style():
        fig = _template(key, figsize, dpi) if reuse else None
        pool = list(fig.axes) if fig is not None else []
        if fig is None:
            fig = Figure(figsize=figsize, dpi=dpi)
        renderer = _canvas(fig)
        W, H = fig.bbox.width, fig.bbox.height
        px = dpi / MM_PER_INCH
        title = fig.suptitle(
            literal(sheet.title), y=1 - 0.55 * TITLE_MM * px / H, va="center", wrap=len(sheet.title) > 80
        )
        groups, states = [], []
        for k, (panel, slot) in enumerate(zip(sheet.panels, slots)):
            x0, x1 = slot.x * px, (slot.x + slot.width) * px
            y1 = H - slot.y * px
            y0 = y1 - slot.height * px
            rect = (
                x0 / W + 0.15 * slot.width * px / W,
                y0 / H + 0.15 * slot.height * px / H,
                0.7 * slot.width * px / W,
                0.7 * slot.height * px / H,
            )
            if k < len(pool):
                ax = pool[k]
                ax.set_position(rect)
            else:
                ax = fig.add_axes(rect)
            states.append(_tick_state(ax))
            before = len(fig.axes)
            handles, labels = _draw_panel(panel, ax)
            extra = _dress(ax, x1 - x0, renderer, y1 - y0, handles, labels)
            if extra > 0 and panel.name not in sheet.legend_room:
                grown[panel.name] = extra / dpi * MM_PER_INCH
            groups.append([ax, *fig.axes[before:]])  # with any colour bar or twin the panel added
        if grown:  # a legend needs more room below its axes: those panels taller, the figure with them
            sheet.legend_room.update(grown)
            slots, width, height = sheet_layout(sheet)
            fig.set_size_inches(_inches(width, dpi), _inches(height, dpi))
            renderer = _canvas(fig)  # the new size's renderer, with the shared mathtext parser
            W, H = fig.bbox.width, fig.bbox.height
            title.set_y(1 - 0.55 * TITLE_MM * px / H)
        for group, slot in zip(groups, slots):  # the layout, once, in the final slots
            y1 = H - slot.y * px
            region = (slot.x * px, y1 - slot.height * px, (slot.x + slot.width) * px, y1)
            _fit(fig, renderer, axes=group, region=region)
    if reuse:
        fig._capred_template, fig._capred_tick_state = key, states
    return fig


# --- vector composite ---------------------------------------------------------------------------------------
def compose(sheet: Sheet, dpi: float = 300.0, panel_figures: list | None = None):
    """The composite figure of a sheet (for PDF/SVG and notebooks): the title on top, each panel in its slot.

    Without ``panel_figures`` it is ``sheet_figure(sheet, dpi)`` (one figure, one layout pass); with them,
    each panel's axes are placed where its own figure's frozen layout put them.

    Parameters
    ----------
    sheet : Sheet
        The sheet.
    dpi : float
        Resolution of the figure [dots per inch] (raster output only).
    panel_figures : list of Figure, optional
        ``panel_figure(sheet, p, dpi)`` of each panel when already made (their layouts are reused).

    Returns
    -------
    matplotlib.figure.Figure
        The composite, with no layout engine (its positions are final).
    """
    from matplotlib.figure import Figure

    if panel_figures is None:
        return sheet_figure(sheet, dpi)
    slots, width, height = sheet_layout(sheet)
    with journal_style():
        fig = Figure(figsize=(width / MM_PER_INCH, height / MM_PER_INCH), dpi=dpi)
        renderer = _canvas(fig)
        fig.suptitle(literal(sheet.title), y=1 - 0.45 * TITLE_MM / height, va="center", wrap=len(sheet.title) > 80)
        for panel, slot, pfig in zip(sheet.panels, slots, panel_figures):
            before = len(fig.axes)
            x0, y1 = slot.x / width, 1 - slot.y / height
            sx, sy = slot.width / width, slot.height / height
            ax = fig.add_axes((x0, y1 - sy, sx, sy))
            handles, labels = _draw_panel(panel, ax)
            for mine, theirs in zip(fig.axes[before:], pfig.axes):  # the panel's axes, colour bars, twins
                p = theirs.get_position(original=True)
                mine.set_position((x0 + p.x0 * sx, y1 - sy + p.y0 * sy, p.width * sx, p.height * sy))
            _dress(ax, pfig.bbox.width, renderer, None, handles, labels)  # the legend placed as in the panel
    return fig
