r"""What a user's text may not carry raw out of capred: terminal controls, bidi overrides, characters XML forbids.

A material named ``"\x1b]0;owned\x07sand"`` or ``"sand\u202egnp.exe"`` is data: capred keeps it exactly
(JSON holds the same characters, written as ``\u`` escapes) but never lets it act on a terminal, an HTML page
or an SVG file. The rules, in one place:

- C0 controls (U+0000-001F, but tab and line feed) and DEL are shown as their Unicode control pictures
  (ESC as ␛, BEL as ␇: U+2400-2421);
- C1 controls (U+0080-009F, e.g. the CSI U+009B that some terminals obey like ESC [) are shown as ``\x9b``;
- bidi embeddings, overrides and isolates (U+202A-202E, U+2066-2069), which reorder what a reader sees, are
  shown as ``<U+202E>``, and a file holding any is flagged once, as a warning (:func:`controls_warning`);
- JSON keeps every character; C1 and bidi controls are written as ``\u`` escapes (C0 always are).

Where text leaves capred: the console (capred.report.render), report.html (a jinja finalize of
capred.report.html), SVG figures (capred.io.writers makes every saved .svg well-formed), error messages (the
CLI), and messages that quote a cell (:func:`excerpt`, at most a short piece of a long cell, with its length).
"""

from __future__ import annotations

import re

#: bidi embeddings, overrides (U+202A-202E) and isolates (U+2066-2069)
BIDI = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")
_UNSAFE = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")
_UNSAFE_BYTES = re.compile(rb"\xc2[\x80-\x9f]|\xe2\x80[\xaa-\xae]|\xe2\x81[\xa6-\xa9]")
#: the longest piece of a cell a message quotes
EXCERPT = 40


def _shown(ch: str) -> str:
    o = ord(ch)
    if o < 0x20:
        return chr(0x2400 + o)
    if o == 0x7F:
        return "\u2421"
    return _escaped(ch)


def _escaped(ch: str) -> str:
    o = ord(ch)
    return f"\\x{o:02x}" if o <= 0xFF else f"<U+{o:04X}>"


def visible(text: str, pictures: bool = True) -> str:
    r"""``text`` with its control and bidi characters shown (control pictures, ``\x9b``, ``<U+202E>``).

    Parameters
    ----------
    text : str
        Any text (a cell, a message, a label).

    pictures : bool
        C0 controls as control pictures (␛; terminals and browsers have the glyphs), else as ``\x1b`` (figures:
        the fonts of plots lack the control pictures).

    Returns
    -------
    str
        The same text when it holds none (the common case costs one regex search).

    Examples
    --------
    >>> visible("sand\x1b[2J")
    'sand␛[2J'
    """
    if not isinstance(text, str) or _UNSAFE.search(text) is None:
        return text
    shown = _shown if pictures else _escaped
    return _UNSAFE.sub(lambda m: shown(m.group()), text)


def has_unsafe(text: str) -> bool:
    """True when ``text`` holds a control or bidi character that :func:`visible` would show.

    Parameters
    ----------
    text : str
        Any text (not a str: False).

    Returns
    -------
    bool
    """
    return isinstance(text, str) and _UNSAFE.search(text) is not None


def controls_warning(where: str, text: str) -> str:
    """The one warning for a file whose text holds control or bidi characters (the first such cell named).

    Parameters
    ----------
    where : str
        Where the text is, e.g. "t.csv, line 4, column 'material'".
    text : str
        The text (a cell).

    Returns
    -------
    str
        The warning: which characters, how they are shown and kept.
    """
    found = sorted({m.group() for m in _UNSAFE.finditer(text)})
    names = ", ".join(_name(ch) for ch in found[:5])
    bidi = any(ch in BIDI for ch in found)
    return (
        f"{where}: the text holds {'bidi and control' if bidi and len(found) > 1 else 'bidi' if bidi else 'control'} "
        f"characters ({names}), which can reorder or hide what a reader sees: shown as escapes in the console, "
        "report and figures, kept exact (\\u escapes) in the JSON"
    )


def _name(ch: str) -> str:
    import unicodedata

    o = ord(ch)
    special = {0x1B: "ESC", 0x07: "BEL", 0x08: "BS", 0x0D: "CR", 0x00: "NUL", 0x7F: "DEL", 0x9B: "CSI"}
    return f"U+{o:04X} {special.get(o) or unicodedata.name(ch, 'control')}"


def excerpt(text: str, limit: int = EXCERPT) -> str:
    """A short, visible quote of a cell for a message: ``'abc…' (100,000,000 characters)`` when longer.

    Parameters
    ----------
    text : str
        The cell.
    limit : int
        The most characters quoted [-].

    Returns
    -------
    str
        The quote, control characters shown.
    """
    if len(text) <= limit:
        return f"'{visible(text)}'"
    return f"'{visible(text[:limit])}…' ({len(text):,} characters)"


def xml_safe(text: str) -> str:
    r"""``text`` fit for an XML 1.0 document (SVG), every control character shown as an ASCII escape.

    XML forbids C0 but tab, line feed and carriage return; bidi controls are shown too (``\x1b``: the fonts of figures
    lack the control pictures).

    Parameters
    ----------
    text : str
        Text for an SVG.

    Returns
    -------
    str
    """
    if not isinstance(text, str) or _UNSAFE.search(text) is None:
        return text
    # no '<' or '&' is inserted: the text may be a whole SVG document, its markup already escaped
    return _UNSAFE.sub(lambda m: _escaped(m.group()).replace("<", "[").replace(">", "]"), text)


def safe_axes(ax, labels=None):
    """Show the control and bidi characters of every text a panel put on ``ax``.

    Title, axis labels, texts and annotations, the labels its legend will show, before matplotlib lays it out or draws
    it: the one neutraliser of figure text whatever its source (a file, an option, a lab store), so no raw control
    reaches an SVG (where XML forbids it) or the terminal (matplotlib's missing-glyph warning quotes the character).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        A panel's axes, drawn.
    labels : list of str, optional
        The labels the panel asked its legend to show.

    Returns
    -------
    list of str or None
        ``labels`` made visible (None stays None).
    """

    def fix(text):
        return visible(text, pictures=False) if has_unsafe(text) else text

    texts = [ax.title, getattr(ax, "_left_title", None), getattr(ax, "_right_title", None)]
    texts += [ax.xaxis.label, ax.yaxis.label, *ax.texts]
    for t in texts:
        if t is not None and has_unsafe(t.get_text()):
            t.set_text(fix(t.get_text()))
    for artist in (*ax.lines, *ax.collections, *ax.patches, *ax.containers):
        label = artist.get_label()
        if has_unsafe(label):
            artist.set_label(fix(label))
    for axis in (ax.xaxis, ax.yaxis):  # tick labels of user text: categories, or set_ticklabels
        _safe_ticks(axis, fix)
    return None if labels is None else [fix(str(x)) for x in labels]


def _safe_ticks(axis, fix) -> None:
    """Wrap an axis's formatter in ``fix`` when its tick labels are user text holding controls."""
    from matplotlib.ticker import FuncFormatter

    inner = axis.get_major_formatter()
    units = getattr(inner, "_units", None)  # matplotlib.category.StrCategoryFormatter
    table = getattr(getattr(inner, "func", None), "args", ())  # FuncFormatter of Axis.set_ticklabels
    texts = list(units) if isinstance(units, dict) else [v for d in table if isinstance(d, dict) for v in d.values()]
    if any(has_unsafe(str(t)) for t in texts):
        axis.set_major_formatter(FuncFormatter(lambda x, pos=None: fix(str(inner(x, pos)))))


def json_escape(data: bytes) -> bytes:
    r"""UTF-8 JSON bytes with C1 and bidi controls written as ``\u`` escapes (the same characters, inert).

    JSON's structure is ASCII, so these bytes occur only inside strings.

    Parameters
    ----------
    data : bytes
        UTF-8 JSON.

    Returns
    -------
    bytes
    """
    if b"\xc2" not in data and b"\xe2" not in data:
        return data
    return _UNSAFE_BYTES.sub(lambda m: b"\\u%04x" % ord(m.group().decode("utf-8")), data)


def safe_spec(spec):
    """A console table (capred.table_spec.TableSpec) with its title, headers and cells made :func:`visible`.

    Parameters
    ----------
    spec : capred.table_spec.TableSpec
        A console table.

    Returns
    -------
    capred.table_spec.TableSpec
        ``spec`` itself when nothing needs to be shown.
    """
    import dataclasses

    cells = [spec.title, *(h for h, _ in spec.columns), *(c for row in spec.rows for c in row)]
    if not any(has_unsafe(c) for c in cells):
        return spec
    return dataclasses.replace(
        spec,
        title=visible(spec.title),
        columns=[(visible(h), a) for h, a in spec.columns],
        rows=[[visible(c) for c in row] for row in spec.rows],
    )


def html_finalize(value):
    """The jinja ``finalize`` of capred's HTML templates: every value shown is made :func:`visible`.

    Markup stays markup; text is escaped afterwards by autoescape.

    Parameters
    ----------
    value : object
        A value the template shows.

    Returns
    -------
    object
        ``value``, or its visible form when it is text holding control or bidi characters.
    """
    if isinstance(value, str) and has_unsafe(value):
        from markupsafe import Markup

        return Markup(visible(str(value))) if isinstance(value, Markup) else visible(value)
    return value
