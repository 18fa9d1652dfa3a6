"""Control characters never reach a terminal, SVG or HTML raw (issue 32, item 2): a material named with an OSC
title sequence, ESC[2J, ESC[31m, BEL and a right-to-left override is kept exactly in the JSON (as \\u escapes),
shown as escapes everywhere a person reads it, and flagged once."""

import json
import xml.dom.minidom

import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.io.writers import encode_json
from capred.text_safety import excerpt, json_escape, visible

runner = CliRunner()
EVIL = "\x1b]0;owned\x07\x1b[2J\x1b[31msteel\u202e_2mm"
RAW = ("\x1b", "\x07", "\u202e", "\x9b")


def test_visible_shows_every_control_and_bidi_character():
    assert visible("sand") == "sand"
    assert visible("a\x1b[2Jb\x07") == "a\u241b[2Jb\u2407"  # control pictures ␛ and ␇
    assert visible("a\x9bb") == "a\\x9bb"  # C1 CSI
    assert visible("ab\u202ecd\u2066") == "ab<U+202E>cd<U+2066>"
    assert visible("a\x1bb", pictures=False) == "a\\x1bb"  # figures: fonts lack the pictures
    assert visible("tab\tand\nline") == "tab\tand\nline"  # tab and line feed are text


def test_json_keeps_the_characters_as_escapes():
    data = encode_json({"material": EVIL + "\x9b"})
    assert not any(c.encode() in data for c in ("\u202e", "\x9b"))  # nothing raw in the bytes
    assert b"\\u202e" in data and b"\\u009b" in data and b"\\u001b" in data
    assert json.loads(data)["material"] == EVIL + "\x9b"  # the exact text back
    assert json_escape(b'{"a":"plain"}') == b'{"a":"plain"}'


def test_excerpt_quotes_a_short_piece_with_the_length():
    assert excerpt("x" * 100_000, 10) == "'xxxxxxxxxx…' (100,000 characters)"
    assert excerpt("a\x1bb") == "'a\u241bb'"


@pytest.fixture(scope="module")
def evil_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("evil")
    lines = capred.sample_path("shear").read_text().splitlines()
    src = folder / "evil.csv"
    src.write_text("\n".join(ln.replace("steel_2mm", EVIL) for ln in lines) + "\n")
    out = folder / "out"
    res = runner.invoke(app, ["shear", str(src), "--format", "png,svg", "--out", str(out)])
    return res, out


def test_console_gets_no_raw_control(evil_run):
    res, _ = evil_run
    assert res.exit_code == 0, res.output
    assert not any(c in res.output for c in RAW)
    assert "\u241b]0;owned\u2407" in res.output  # shown, not dropped
    # flagged once, naming the characters
    assert res.output.count("the text holds bidi and control characters") == 1
    assert "U+202E RIGHT-TO-LEFT OVERRIDE" in res.output


def test_svg_is_well_formed_and_html_holds_no_raw_control(evil_run):
    _, out = evil_run
    svgs = sorted(out.glob("*.svg"))
    assert svgs
    for f in svgs:
        xml.dom.minidom.parse(str(f))  # raises on a control character
        assert not any(c in f.read_text(encoding="utf-8") for c in RAW)
    html = (out / "report.html").read_text(encoding="utf-8")
    assert not any(c in html for c in RAW) and "\u241b" in html


def test_json_keeps_the_name_and_lists_the_warning(evil_run):
    _, out = evil_run
    raw = (out / "summary.json").read_bytes()
    assert "\u202e".encode() not in raw and b"\\u202e" in raw
    doc = json.loads(raw)

    def strings(x):
        if isinstance(x, dict):
            for k, v in x.items():
                yield k
                yield from strings(v)
        elif isinstance(x, list):
            for v in x:
                yield from strings(v)
        elif isinstance(x, str):
            yield x

    assert EVIL in set(strings(doc))  # the exact name, character for character
    assert sum("bidi and control characters" in w for w in doc["warnings"]) == 1


def test_error_messages_quote_cells_visibly(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("test_id,material,condition,sigma_N [kPa],tau_max [kPa]\na,m,dry,1,\x1b[2Jx\n")
    res = runner.invoke(app, ["shear", str(p), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code != 0 and "\x1b" not in res.output and "\u241b[2Jx" in res.output


def test_python_api_warnings_and_errors_show_controls_as_escapes(tmp_path):
    """A lab script's terminal gets the same protection: CapredWarning texts and InputError messages."""
    import warnings

    from capred.errors import CapredWarning, InputError

    lines = capred.sample_path("shear").read_text().splitlines()
    src = tmp_path / "evil.csv"
    src.write_text("\n".join(ln.replace("steel_2mm", EVIL) for ln in lines) + "\n")
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        r = capred.run_shear(src)
    texts = [str(w.message) for w in seen if issubclass(w.category, CapredWarning)]
    assert texts and not any(c in t for t in texts for c in RAW)
    assert any(EVIL in w for w in r.warnings) or any("U+202E" in w for w in r.warnings)  # the result keeps text
    bad = tmp_path / "bad.csv"
    bad.write_text("test_id,material,condition,sigma_N [kPa],tau_max [kPa]\na,m,dry,1,\x1b[2J\na,m,dry,2,3\n")
    with pytest.raises(InputError) as err:
        capred.run_shear(bad)
    assert "\x1b" not in str(err.value) and "\u241b[2J" in str(err.value)
    assert err.value.as_json()["errors"][0]["value"] == "\x1b[2J"  # scripts get the exact cell


def test_safe_axes_shows_controls_in_every_text_before_drawing():
    """Title, axis labels, texts, legend labels and category tick labels: no raw ESC or U+202E reaches the SVG."""
    import io
    import xml.etree.ElementTree as ET

    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from capred.text_safety import safe_axes

    fig = Figure()
    ax = fig.add_subplot()
    ax.bar(["sand\x1b[2J", "clay\u202e"], [1, 2], label="bars\x1b")
    ax.set_title("t\u202e")
    ax.set_ylabel("y\x1b")
    ax.text(0, 1, "note\x07")
    labels = safe_axes(ax, ["legend\u202e"])
    assert labels == ["legend<U+202E>"]
    assert ax.get_title() == "t<U+202E>" and ax.get_ylabel() == "y\\x1b"
    fig.canvas.draw()
    ticks = [t.get_text() for t in ax.get_xticklabels()]
    assert ticks == ["sand\\x1b[2J", "clay<U+202E>"]  # category labels shown, as drawn
    buf = io.StringIO()
    fig.savefig(buf, format="svg")
    svg = buf.getvalue()
    ET.fromstring(svg)  # well-formed XML
    assert "\x1b" not in svg and "\u202e" not in svg and "\x07" not in svg
