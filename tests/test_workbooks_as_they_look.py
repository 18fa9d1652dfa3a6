"""Workbooks read as they look (issue 32, item 3): the first visible sheet by default (hidden sheets named),
merged cells taking their merged value, formulas without a saved value named."""

import warnings
import zipfile

import pytest
from openpyxl import Workbook

import capred
from capred.errors import InputError
from capred.io.grid import TableSource, read_grid

HEADER = ["test_id", "material", "condition", "sigma_N [kPa]", "tau_max [kPa]"]
# tau = c + sigma tan(phi) with c = 0.37 kPa and tan(phi) = 0.5: the visible sheet's dry envelope
VISIBLE = [["t1", "steel", "dry", 10, 5.37], ["t2", None, "dry", 20, 10.37], ["t3", None, "dry", 30, 15.37]]
HIDDEN = [["old1", "steel", "dry", 10, 8.7], ["old2", "steel", "dry", 20, 13.7], ["old3", "steel", "dry", 30, 18.7]]


def _workbook(path, hidden_first=True, merge=True):
    wb = Workbook()
    old = wb.active
    old.title = "Old"
    for r in [HEADER, *HIDDEN]:
        old.append(r)
    if hidden_first:
        old.sheet_state = "hidden"
    ws = wb.create_sheet("Tests")
    for r in [HEADER, *VISIBLE]:
        ws.append(r)
    if merge:
        ws.merge_cells("B2:B4")  # the material typed once, over its three tests
    wb.save(path)
    return path


def test_a_hidden_first_sheet_is_passed_over_and_named(tmp_path):
    grid = read_grid(TableSource(_workbook(tmp_path / "w.xlsx")))
    assert grid.sheet == "Tests"
    assert grid.warnings == [
        f"{tmp_path / 'w.xlsx'}: the workbook's first sheet 'Old' is hidden: sheet 'Tests', the first visible one, "
        "is read (--sheet 'Old' reads a hidden one)"
    ]
    asked = read_grid(TableSource(tmp_path / "w.xlsx", sheet="Old"))  # --sheet still picks it
    assert asked.sheet == "Old" and asked.notes == ["sheet 'Old' is hidden in the workbook; read as asked (--sheet)"]


def test_shear_reads_the_visible_sheet_with_its_merged_material(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = capred.run_shear(_workbook(tmp_path / "w.xlsx"))
    doc = r.to_json()
    assert list(doc["materials"]) == ["steel"]  # one material, no empty name
    # the visible sheet's c (exact data: 0.37 kPa to rounding), not the hidden one's 3.7
    assert doc["materials"]["steel"]["c_kPa"] == pytest.approx(0.37, abs=1e-9)
    assert any("first sheet 'Old' is hidden" in w for w in doc["warnings"])
    assert any("B2:B4 ('steel')" in n for n in doc["notes"])


def test_formula_without_a_saved_value_is_named(tmp_path):
    wb = Workbook()
    ws = wb.active
    for r in [HEADER, ["t1", "steel", "dry", 10, "=5+0.37"], ["t2", "steel", "dry", 20, 10.37]]:
        ws.append(r)
    wb.save(tmp_path / "f.xlsx")
    with pytest.raises(InputError, match=r"cell E2 \(=5\+0.37\) holds a formula without a saved value"):
        read_grid(TableSource(tmp_path / "f.xlsx"))


NS = (
    'xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" '
    'xmlns:style="urn:oasis:names:tc:opendocument:xmlns:style:1.0" '
    'xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" '
    'xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0"'
)


def _cell(v, attrs=""):
    if isinstance(v, str):
        return f'<table:table-cell {attrs} office:value-type="string"><text:p>{v}</text:p></table:table-cell>'
    return f'<table:table-cell {attrs} office:value-type="float" office:value="{v}"/>'


def _ods(path, body):
    content = (
        f'<?xml version="1.0" encoding="UTF-8"?><office:document-content {NS}><office:automatic-styles>'
        '<style:style style:name="ta1" style:family="table"><style:table-properties table:display="true"/>'
        '</style:style><style:style style:name="ta2" style:family="table">'
        '<style:table-properties table:display="false"/></style:style></office:automatic-styles>'
        f"<office:body><office:spreadsheet>{body}</office:spreadsheet></office:body></office:document-content>"
    )
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("mimetype", "application/vnd.oasis.opendocument.spreadsheet")
        z.writestr("content.xml", content)
    return path


def _row(*cells):
    return "<table:table-row>" + "".join(cells) + "</table:table-row>"


def test_ods_hidden_sheet_merged_cells_and_formula(tmp_path):
    head = _row(*(_cell(h) for h in HEADER))
    hidden = f'<table:table table:name="Old" table:style-name="ta2">{head}{_row(*map(_cell, HIDDEN[0]))}</table:table>'
    visible = (
        f'<table:table table:name="Tests" table:style-name="ta1">{head}'
        + _row(_cell("t1"), _cell("steel", 'table:number-rows-spanned="3"'), *map(_cell, ["dry", 10, 5.37]))
        + _row(_cell("t2"), "<table:covered-table-cell/>", *map(_cell, ["dry", 20, 10.37]))
        + _row(_cell("t3"), "<table:covered-table-cell/>", *map(_cell, ["dry", 30, 15.37]))
        + "</table:table>"
    )
    grid = read_grid(TableSource(_ods(tmp_path / "w.ods", hidden + visible)))
    assert grid.sheet == "Tests" and "first sheet 'Old' is hidden" in grid.warnings[0]
    assert [cells[1] for _, cells in grid.rows[1:]] == ["steel"] * 3
    assert grid.notes == ["merged cells take the value of their first cell: B2:B4 ('steel')"]
    cell = '<table:table-cell table:formula="of:=1+2"/>'
    formula = f'<table:table table:name="F">{head}{_row(_cell("t1"), cell)}</table:table>'
    with pytest.raises(InputError, match=r"cell B2 \(=1\+2\) holds a formula without a saved value"):
        read_grid(TableSource(_ods(tmp_path / "f.ods", formula)))
