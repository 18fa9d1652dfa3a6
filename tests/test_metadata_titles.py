"""Metadata as the workbook shows it (issue 39, part 5): a merged title row above the metadata block is the title,
once, in summary.json, provenance.json and report.html's record of the input; not a key holding the title
repeated once per column it spans."""

import json
import zipfile

from openpyxl import Workbook
from typer.testing import CliRunner

from capred.cli import app
from capred.io import read_table
from capred.pipelines.shear import SCHEMA

runner = CliRunner()
TITLE = "Direct shear tests, 2 mm steel spheres (campaign 2024)"
HEADER = ["test_id", "material", "condition", "sigma_N [kPa]", "tau_max [kPa]"]
# tau = 0.37 + 0.5 sigma_N (kPa): the dry envelope c 0.37 kPa, tan(phi) 0.5
ROWS = [["t1", "steel", "dry", 10, 5.37], ["t2", "steel", "dry", 20, 10.37], ["t3", "steel", "dry", 30, 15.37]]


def _xlsx(path, title_rows=1):
    wb = Workbook()
    ws = wb.active
    ws.append([TITLE])
    for _ in range(title_rows - 1):
        ws.append([None])
    ws.merge_cells(f"A1:J{title_rows}")  # the title over ten columns (and title_rows rows)
    ws.append(["Operator:", "R. E."])
    ws.append(["Date", "2024-03-14"])
    ws.append(HEADER)
    for r in ROWS:
        ws.append(r)
    wb.save(path)
    return path


NS = (
    'xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" '
    'xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" '
    'xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0"'
)


def _cell(v, attrs=""):
    if isinstance(v, str):
        return f'<table:table-cell {attrs} office:value-type="string"><text:p>{v}</text:p></table:table-cell>'
    return f'<table:table-cell {attrs} office:value-type="float" office:value="{v}"/>'


def _ods(path):
    def row(*cells):
        return "<table:table-row>" + "".join(cells) + "</table:table-row>"

    title = row(
        _cell(TITLE, 'table:number-columns-spanned="10"'),
        '<table:covered-table-cell table:number-columns-repeated="9"/>',
    )
    body = (
        title
        + row(_cell("Operator:"), _cell("R. E."))
        + row(_cell("Date"), _cell("2024-03-14"))
        + row(*map(_cell, HEADER))
        + "".join(row(*map(_cell, r)) for r in ROWS)
    )
    content = (
        f'<?xml version="1.0" encoding="UTF-8"?><office:document-content {NS}><office:body><office:spreadsheet>'
        f'<table:table table:name="Tests">{body}</table:table></office:spreadsheet></office:body>'
        "</office:document-content>"
    )
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("mimetype", "application/vnd.oasis.opendocument.spreadsheet")
        z.writestr("content.xml", content)
    return path


EXPECTED = {"title": TITLE, "Operator": "R. E.", "Date": "2024-03-14"}


def test_merged_title_row_is_the_title_once(tmp_path):
    for f in (_xlsx(tmp_path / "w.xlsx"), _ods(tmp_path / "w.ods"), _xlsx(tmp_path / "two.xlsx", title_rows=2)):
        t = read_table(f, SCHEMA)
        assert t.metadata == EXPECTED, f.name
        assert len(t) == 3  # the data rows are untouched


def test_merged_title_in_every_output_that_records_the_input(tmp_path):
    out = tmp_path / "out"
    res = runner.invoke(app, ["shear", str(_xlsx(tmp_path / "w.xlsx")), "--no-plots", "--out", str(out)])
    assert res.exit_code == 0, res.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["inputs"][0]["metadata"] == EXPECTED
    provenance = json.loads((out / "provenance.json").read_text())
    assert [i.get("metadata") for i in provenance["inputs"]] == [EXPECTED]
    html = (out / "report.html").read_text(encoding="utf-8")
    assert html.count(TITLE) == 1 + html.count(f"<title>{TITLE}")  # the record of the input names it once
    assert f"{TITLE} {TITLE}" not in html
