"""The reader never crashes with a traceback: it reads the file or explains why (issue 6)."""

import string

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from capred.errors import CapredError
from capred.pipelines.retention import run_retention
from capred.pipelines.shear import ShearOptions
from capred.pipelines.shear_run import run_shear
from capred.pipelines.triaxial import run_triaxial_bounds

NAMES = [
    "test_id",
    "material",
    "condition",
    "z1",
    "z2",
    "V_v",
    "added_mass",
    "cap_mass",
    "box_area",
    "R",
    "tau_max",
    "sigma_N",
    "suction",
    "S_R",
    "Tau max",
    "tau_max_kPa",
    "Sr",
    "q_f",
    "sigma3",
    "head",
    "theta",
]
UNITS = ["", " [kPa]", " (mm)", " [g]", " [cm^3]", " [%]", " [blorp]", " [kg/cm^2]", " [", " (]", " [m/s]"]
CELLS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-(10**6), 10**6).map(str),
    st.sampled_from(["", "dry", "wet", "saturated", "unsaturated", "NA", "1,5", "0,35", "-", "nan", "1e309", '"x"']),
    st.text(alphabet=string.printable + "µ°é²", max_size=8),
)


@st.composite
def tables(draw):
    ncol = draw(st.integers(1, 8))
    header = [draw(st.sampled_from(NAMES)) + draw(st.sampled_from(UNITS)) for _ in range(ncol)]
    rows = draw(st.lists(st.lists(CELLS, min_size=0, max_size=ncol + 1), max_size=6))
    sep = draw(st.sampled_from([",", ";", "\t"]))
    quote = draw(st.booleans())

    def line(cells):
        return sep.join(f'"{c}"' if quote and sep not in c else c for c in cells)

    lines = [line(header)] + [line(r) for r in rows]
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines))), "# comment")
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines))), "")
    text = draw(st.sampled_from(["\n", "\r\n"])).join(lines)
    encoding = draw(st.sampled_from(["utf-8", "utf-8-sig", "cp1252", "utf-16"]))
    return text.encode(encoding, errors="replace")


SETTINGS = settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@SETTINGS
@given(data=tables())
def test_fuzzed_tables_read_or_explain(tmp_path, data):
    path = tmp_path / "fuzz.csv"
    path.write_bytes(data)
    for run in (run_shear, run_triaxial_bounds, run_retention):
        try:
            run(path)
        except CapredError as exc:
            assert str(exc)  # a message, not a traceback


@SETTINGS
@given(data=st.binary(max_size=300))
def test_random_bytes_read_or_explain(tmp_path, data):
    path = tmp_path / "bytes.csv"
    path.write_bytes(data)
    _reduced_or_explained(lambda: run_shear(path), path)


def _reduced_or_explained(run, path):
    """What must hold for any input: a result whose JSON document encodes (no NaN, no inf) and has one row per
    test, or a capred error whose message names the file (an InputError: every problem located in it)."""
    import orjson

    from capred.errors import InputError

    try:
        result = run()
    except CapredError as exc:
        assert str(exc)
        if isinstance(exc, InputError):
            assert all(p.file == str(path) for p in exc.problems), exc.problems
        return None
    doc = result.to_json()
    orjson.dumps(doc)  # raises on NaN/inf or a type JSON cannot hold
    rows = doc.get("tests")
    assert rows is None or len(rows) == len(result.table())
    return doc


def test_european_export_semicolon_decimal_comma_bom(tmp_path):
    text = (
        "\ufefftest_id;condition;sigma_N [kPa];tau_max [kPa]\r\n\r\n"
        'a;dry;1,0;1,0452\r\nb;dry;2,0;1,7598\r\n"c";dry;3,0;2,4744\r\n'
    )
    path = tmp_path / "eu.csv"
    path.write_bytes(text.encode("utf-8"))
    js = run_shear(path).to_json()
    assert abs(js["materials"]["(all)"]["tan_phi"] - 0.7146) < 1e-9


NUM = st.one_of(st.floats(-1e3, 1e4, allow_nan=False).map(lambda x: f"{x:.6g}"), st.just(""), st.just("0"))


@st.composite
def valid_header_tables(draw, header, text_cols):
    rows = []
    for _ in range(draw(st.integers(1, 8))):
        rows.append(",".join(draw(st.sampled_from(text_cols[h])) if h in text_cols else draw(NUM) for h in header))
    return ",".join(header) + "\n" + "\n".join(rows) + "\n"


SHEAR_HEADER = [
    "test_id",
    "material",
    "condition",
    "z1",
    "z2",
    "V_v",
    "added_mass",
    "cap_mass",
    "box_area",
    "R",
    "tau_max",
]
TRI_HEADER = ["test_id", "condition", "sigma3", "q_f", "p0", "s0", "sigma2", "group"]


@SETTINGS
@given(
    text=valid_header_tables(
        SHEAR_HEADER, {"test_id": ["a", "b", "c", "d", "e"], "material": ["m", "n"], "condition": ["dry", "wet"]}
    )
)
def test_fuzzed_values_shear(tmp_path, text):
    path = tmp_path / "v.csv"
    path.write_text(text)
    doc = _reduced_or_explained(lambda: run_shear(path, ShearOptions(bootstrap=0)), path)
    if doc is not None:  # every test of the file is in the result, in file order
        assert [t["test_id"] for t in doc["tests"]] == [line.split(",")[0] for line in text.splitlines()[1:]]


@SETTINGS
@given(
    text=valid_header_tables(
        TRI_HEADER,
        {"test_id": ["a", "b", "c", "d", "e"], "group": ["", "A"], "condition": ["saturated", "unsaturated"]},
    )
)
def test_fuzzed_values_triaxial(tmp_path, text):
    path = tmp_path / "v.csv"
    path.write_text(text)
    _reduced_or_explained(lambda: run_triaxial_bounds(path), path)


# --- manifests and spreadsheet XML (issue 19): fuzzed, they are read or explained -----------------------------------
MANIFEST_CELLS = st.one_of(
    st.sampled_from(
        [
            "shear",
            "retention",
            "triaxial-bounds",
            "frobnicate",
            "",
            "a.csv",
            "runs/*.csv",
            "--no-plots",
            "--gamma-w 10",
            '"x,y"',
            "--model vg",
            "r\u00e9sum\u00e9.csv",
            "#",
            "'",
            '"',
        ]
    ),
    st.text(alphabet=string.printable + "é\x00", max_size=10),
)


@st.composite
def manifests(draw):
    if draw(st.booleans()):  # CSV
        header = draw(
            st.sampled_from(
                [
                    "command,input,options",
                    "command,input",
                    "command,input,option",
                    "input",
                    "Command, Input ,Options",
                    "",
                ]
            )
        )
        rows = draw(st.lists(st.lists(MANIFEST_CELLS, max_size=5).map(",".join), max_size=5))
        text, name = "\n".join([header, *rows]) + "\n", "m.csv"
    else:  # TOML
        strings = MANIFEST_CELLS.map(repr).map(lambda r: r.replace("\\", ""))
        values = st.one_of(
            st.integers(-5, 5),
            st.booleans(),
            strings,
            st.lists(MANIFEST_CELLS, max_size=3).map(lambda xs: "[" + ", ".join(map(repr, xs)) + "]"),
        )
        parts = []
        for _ in range(draw(st.integers(0, 3))):
            head = draw(st.sampled_from(["[[run]]", "[run]", "run = 5", "[[runs]]", ""]))
            keys = draw(st.lists(st.sampled_from(["command", "input", "options", "option", "run"]), max_size=4))
            parts.append("\n".join([head, *(f"{k} = {draw(values)}" for k in keys)]))
        text, name = "\n".join(parts) + "\n", "m.toml"
    encoding = draw(st.sampled_from(["utf-8", "utf-8-sig", "cp1252", "utf-16"]))
    return name, text.encode(encoding, errors="replace")


@SETTINGS
@given(manifest=manifests())
def test_fuzzed_manifests_read_or_explain(tmp_path, manifest):
    from pathlib import Path

    from capred.io.manifest import read_manifest

    name, data = manifest
    path = Path(tmp_path) / name
    path.write_bytes(data)
    try:
        runs = read_manifest(path)
    except CapredError as exc:
        assert str(exc) and str(path) in str(exc)  # the message names the file
    else:  # every run has its line, a command, an input and options
        assert runs and all(isinstance(n, int) and c and i and isinstance(o, (str, list)) for n, c, i, o in runs)


XML_PIECES = st.sampled_from(
    [
        '<row r="2">',
        "</row>",
        "<row>",
        '<c r="A1">',
        '<c r="XFD3" t="s">',
        '<c t="b">',
        '<c t="inlineStr"><is><t>x</t></is>',
        "</c>",
        "<v>1.5</v>",
        "<v>-1</v>",
        "<v>99</v>",
        "<v>x</v>",
        '<c r="B2" t="e"><v>#DIV/0!</v>',
        "<f>SUM(A1)</f>",
        "<v>1e999</v>",
        '<c r="ZZZZ9">',
        "&amp;",
        "&lol;",
        "<!-- c -->",
        " ",
    ]
)


_BLANK_WORKBOOK: list = []  # the parts of an empty workbook, made once


@SETTINGS
@given(pieces=st.lists(XML_PIECES, max_size=30))
def test_fuzzed_sheet_xml_reads_or_explains(tmp_path, pieces):
    """Any sheet XML inside a valid workbook: rows of text, or one clear InputError (never another exception)."""
    import zipfile
    from pathlib import Path

    from openpyxl import Workbook

    from capred.io.grid import TableSource, read_grid

    path = Path(tmp_path) / "w.xlsx"
    if not _BLANK_WORKBOOK:
        Workbook().save(path)
        with zipfile.ZipFile(path) as z:
            _BLANK_WORKBOOK.extend((n, z.read(n)) for n in z.namelist())
    members = _BLANK_WORKBOOK
    sheet = (
        '<worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData>'
        + "".join(pieces)
        + "</sheetData></worksheet>"
    ).encode()
    with zipfile.ZipFile(path, "w") as z:
        for n, d in members:
            z.writestr(n, sheet if n == "xl/worksheets/sheet1.xml" else d)
    try:
        grid = read_grid(TableSource(path))
    except CapredError as exc:
        assert str(path) in str(exc)
    else:
        assert all(isinstance(n, int) and all(isinstance(c, str) for c in cells) for n, cells in grid.rows)


# --- issue 32, item 9: workbook structure and control characters -----------------------------------------------------
SHEET_PIECES = st.sampled_from(
    [
        '<row r="2">',
        '<row r="99999999999999999999999">',
        '<row r="1048577">',
        "</row>",
        '<c r="A1" t="inlineStr"><is><t>test_id</t></is></c>',
        '<c r="B1" t="inlineStr"><is><t>material</t></is></c>',
        '<c r="B2" t="inlineStr"><is><t>m\x1b[2J\u202e</t></is></c>',
        '<c r="C2"><f>A1*2</f><v/></c>',
        '<c r="C3"><f>A1*2</f><v>4</v></c>',
        '<c r="A3"><v>1.5</v></c>',
        "<x><x><x>",
        "</x></x></x>",
    ]
)
AFTER_DATA = st.sampled_from(
    [
        "",
        '<mergeCells><mergeCell ref="B2:B4"/></mergeCells>',
        '<mergeCells><mergeCell ref="A1:XFD1048576"/></mergeCells>',
        '<mergeCells><mergeCell ref="B2"/><mergeCell ref="Q:Z"/></mergeCells>',
        "<y/>" * 50,
    ]
)


@SETTINGS
@given(
    pieces=st.lists(SHEET_PIECES, max_size=25),
    after=AFTER_DATA,
    states=st.lists(st.sampled_from(["visible", "hidden", "veryHidden"]), min_size=2, max_size=2),
    sheet=st.sampled_from([None, "1", "2", "S2", "nope"]),
)
def test_fuzzed_workbook_structure_reads_or_explains(tmp_path, pieces, after, states, sheet):
    """Hidden sheets, merged ranges (sane and absurd), formulas with and without values, huge row numbers and
    nesting in a two-sheet workbook: rows of text, or one clear CapredError."""
    import zipfile
    from pathlib import Path

    from openpyxl import Workbook

    from capred.io.grid import TableSource, read_grid

    path = Path(tmp_path) / "w.xlsx"
    wb = Workbook()
    wb.active.title = "S1"
    wb.create_sheet("S2")
    wb.save(path)
    with zipfile.ZipFile(path) as z:
        members = [(n, z.read(n)) for n in z.namelist()]
    sheet_xml = (
        '<worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData>'
        + "".join(pieces)
        + "</sheetData>"
        + after
        + "</worksheet>"
    ).encode()
    with zipfile.ZipFile(path, "w") as z:
        for n, d in members:
            if n == "xl/workbook.xml":
                for name, state in zip(("S1", "S2"), states):
                    d = d.replace(f'name="{name}"'.encode(), f'name="{name}" state="{state}"'.encode())
            z.writestr(n, sheet_xml if n.startswith("xl/worksheets/sheet") else d)
    try:
        grid = read_grid(TableSource(path, sheet))
    except CapredError as exc:
        assert str(path) in str(exc)
    else:
        assert all(isinstance(n, int) and 1 <= n <= 1_048_576 for n, _ in grid.rows)
        assert all(isinstance(c, str) for _, cells in grid.rows for c in cells)


ODS_PIECES = st.sampled_from(
    [
        "<table:table-row>",
        '<table:table-row table:number-rows-repeated="1048576">',
        '<table:table-row table:number-rows-repeated="99999999999999999999">',
        "</table:table-row>",
        '<table:table-cell office:value-type="string"><text:p>test_id</text:p></table:table-cell>',
        '<table:table-cell office:value-type="float" office:value="1.5"/>',
        '<table:table-cell table:number-rows-spanned="3" office:value-type="string"><text:p>m</text:p>'
        "</table:table-cell>",
        '<table:table-cell table:number-columns-spanned="5000" office:value-type="string"><text:p>w</text:p>'
        "</table:table-cell>",
        "<table:covered-table-cell/>",
        '<table:table-cell table:formula="of:=1+2"/>',
        '<table:table-cell office:value-type="string"><text:p>a<text:s text:c="40000"/>b</text:p></table:table-cell>',
        '<table:table-cell office:value-type="string"><text:p>\x1b]0;t\x07\u2066x</text:p></table:table-cell>',
        '<table:table-cell table:number-columns-repeated="3" office:value-type="float" office:value="2"/>',
    ]
)


@SETTINGS
@given(
    pieces=st.lists(ODS_PIECES, max_size=20),
    hidden_first=st.booleans(),
    sheet=st.sampled_from([None, "1", "2", "B", "nope"]),
)
def test_fuzzed_ods_structure_reads_or_explains(tmp_path, pieces, hidden_first, sheet):
    """Repeats, spans, covered cells, formulas, expanded spaces and control characters in an .ods with a
    hidden first sheet or not: rows of text, or one clear CapredError."""
    import zipfile
    from pathlib import Path

    from capred.io.grid import TableSource, read_grid

    ns = (
        'xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" '
        'xmlns:style="urn:oasis:names:tc:opendocument:xmlns:style:1.0" '
        'xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" '
        'xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0"'
    )
    body = "".join(pieces)
    style = ' table:style-name="h"' if hidden_first else ""
    content = (
        f'<?xml version="1.0" encoding="UTF-8"?><office:document-content {ns}><office:automatic-styles>'
        '<style:style style:name="h" style:family="table"><style:table-properties table:display="false"/>'
        "</style:style></office:automatic-styles><office:body><office:spreadsheet>"
        f'<table:table table:name="A"{style}>{body}</table:table><table:table table:name="B">{body}</table:table>'
        "</office:spreadsheet></office:body></office:document-content>"
    )
    path = Path(tmp_path) / "w.ods"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("mimetype", "application/vnd.oasis.opendocument.spreadsheet")
        z.writestr("content.xml", content.encode())
    try:
        grid = read_grid(TableSource(path, sheet))
    except CapredError as exc:
        assert str(path) in str(exc)
    else:
        assert all(isinstance(n, int) and 1 <= n <= 1_048_576 for n, _ in grid.rows)
        assert all(len(c) <= 32_767 for _, cells in grid.rows for c in cells)


CONTROL_TEXT = st.text(
    alphabet=st.sampled_from(
        list("ab ,;\t")
        + ["\x1b", "\x07", "\x00", "\x08", "\x7f", "\x85", "\x9b", "\u202a", "\u202e", "\u2066", "\u2069"]
    ),
    min_size=1,
    max_size=12,
)


@SETTINGS
@given(name=CONTROL_TEXT)
def test_fuzzed_control_characters_never_leave_raw(tmp_path, name):
    """A material named with any mix of C0, C1 and bidi controls: the JSON keeps it exactly (escaped bytes
    only), the console and the visible form hold none of them raw."""
    import io
    import json
    import warnings

    from rich.console import Console

    from capred.io.writers import encode_json
    from capred.report.render import render
    from capred.text_safety import visible

    raw = set("\x1b\x07\x00\x08\x7f\x85\x9b\u202a\u202e\u2066\u2069")
    assert not raw & set(visible(name))
    cell = '"' + name.replace('"', '""') + '"'
    path = tmp_path / "c.csv"
    path.write_text(
        "test_id,material,condition,sigma_N [kPa],tau_max [kPa]\n"
        + "".join(f"t{i},{cell},dry,{10 * i},{0.37 + 5 * i}\n" for i in range(1, 4)),
        encoding="utf-8",
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            result = run_shear(path, ShearOptions(bootstrap=0))
        except CapredError as exc:
            assert not raw & set(visible(str(exc)))
            return
    data = encode_json(result.to_json())
    assert not any(c.encode() in data for c in ("\x85", "\x9b", "\u202a", "\u202e", "\u2066", "\u2069"))
    json.loads(data)
    out = io.StringIO()
    render(result, console=Console(file=out, width=120, force_terminal=False))
    assert not raw & set(out.getvalue())
