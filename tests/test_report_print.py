"""report.html prints whole (issue 21, item 2): every column of every table on A4, figures at their printed size,
options in the units a user types and only those in force, the date from SOURCE_DATE_EPOCH, the template compiled
once per process, the methods of the fitted retention models.

The print test needs a Chromium and poppler-utils (pdftotext, pdfimages); without them it is skipped with the
reason. On Debian: ``apt-get install -y chromium poppler-utils``.
"""

import re
import shutil
import subprocess
from datetime import UTC
from html.parser import HTMLParser

import pytest

import capred
from capred.reductions import REDUCTIONS
from capred.report import html as report_html

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
PDFTOTEXT = shutil.which("pdftotext")
PDFIMAGES = shutil.which("pdfimages")


@pytest.fixture(scope="module")
def shear_result():
    return capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))


class _Tables(HTMLParser):
    """Header cells of every table of a document, per table."""

    def __init__(self):
        super().__init__()
        self.tables, self._in_th = [], False

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
        self._in_th = tag == "th"

    def handle_endtag(self, tag):
        if tag == "th":
            self._in_th = False

    def handle_data(self, data):
        if self._in_th and self.tables:
            self.tables[-1].append(data.strip())


def _print_pdf(html_path, pdf_path, tmp_path):
    if not CHROMIUM:
        pytest.skip("no Chromium on PATH (apt-get install -y chromium)")
    if not (PDFTOTEXT and PDFIMAGES):
        pytest.skip("no pdftotext/pdfimages on PATH (apt-get install -y poppler-utils)")
    subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}",
            "--no-pdf-header-footer",
            f"--print-to-pdf={pdf_path}",
            html_path.as_uri(),
        ],
        check=True,
        capture_output=True,
        timeout=120,
    )
    assert pdf_path.read_bytes().startswith(b"%PDF")


@pytest.mark.slow  # ~25 s: a report written with its figures, printed by Chromium
def test_printed_report_keeps_every_column(tmp_path, shear_result):
    out = tmp_path / "o"
    capred.write_outputs(shear_result, out)
    pdf = tmp_path / "report.pdf"
    _print_pdf(out / "report.html", pdf, tmp_path)
    info = (
        subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True).stdout if shutil.which("pdfinfo") else ""
    )
    if info:  # A4 portrait: 595 x 842 pt
        w, h = map(float, re.search(r"Page size:\s+([\d.]+) x ([\d.]+)", info).groups())
        assert (round(w), round(h)) == (595, 842)
    text = subprocess.run([PDFTOTEXT, str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    words = set(text.split())
    columns = [str(c) for c in shear_result.table().columns]
    assert len(columns) > 40  # the table that printed cut after S_R
    for c in columns:  # every header prints (it may wrap at its spaces, never at a cut edge)
        assert set(c.split()) <= words, c
    # the test's identity is repeated in every column group of the per-row table
    parser = _Tables()
    parser.feed((out / "report.html").read_text(encoding="utf-8"))
    labels = ["test_id", "material", "condition"]
    groups = [t for t in parser.tables if t[:3] == labels]
    assert len(groups) >= 2 and sorted(sum((g[3:] for g in groups), [])) == sorted(
        c for c in columns if c not in labels
    )
    # every summary-table header prints too
    from capred.report.presenters import console_tables

    for spec in console_tables(shear_result):
        for head, _ in spec.columns:
            assert set(head.split()) <= words, head
    # figures print at their own size: 300 dpi PNGs placed at 300 ppi (text 7-9 pt as drawn), never shrunk
    images = subprocess.run([PDFIMAGES, "-list", str(pdf)], capture_output=True, text=True, check=True).stdout
    ppi = [float(line.split()[12]) for line in images.splitlines()[2:] if line.split()[2] == "image"]
    assert ppi and min(ppi) >= 300 * 0.99  # pdfimages rounds to whole ppi


def test_column_groups_fit_the_page_and_repeat_the_test():
    columns = ["test_id", "material"] + [f"column_{k} [kPa]" for k in range(40)]
    rows = [["T-1", "sand", *("123.456" for _ in range(40))]]
    groups = report_html.column_groups(columns, rows)
    assert all(g[:2] == [0, 1] for g in groups)
    assert sorted(j for g in groups for j in g[2:]) == list(range(2, 42))  # each column once
    # width of a column: its longest word ("column_10") or cell at 7 pt, plus padding; each group within 186 mm
    for g in groups:
        width = sum(
            max(len(w) for w in columns[j].split() + [rows[0][j]]) * report_html.CHAR_MM + report_html.CELL_MM
            for j in g
        )
        assert width <= report_html.PRINT_WIDTH_MM


def test_options_in_the_units_a_user_types(tmp_path, shear_result):
    html = report_html.render_html(shear_result, {}, False)
    rows = re.findall(r"<tr><td class=\"l\">([^<]+)</td><td class=\"l\">([^<]*)</td><td class=\"l\">([^<]*)</td>", html)
    options = {name: (value, unit) for name, value, unit in rows}
    assert options["gamma_w"] == ("9.81", "kN/m³")  # 9810 N/m³ as typed: 9.81 kN/m³
    assert options["ambient_pressure"] == ("101.325", "kPa")
    assert "9810" not in html and "N/m^3" not in html
    # only the options in force: no model parameter of the thesis models, nothing that is None
    assert not [n for n in options if n.startswith("model_params.")]
    assert "box_area" not in options and "curves" not in options
    vanapalli = capred.run_shear(
        capred.sample_path("shear"),
        capred.ShearOptions(bootstrap=0, models=("bishop", "vanapalli"), model_params=capred.ModelParams(s_res=0.05)),
    )
    html = report_html.render_html(vanapalli, {}, False)
    assert '>model_params.s_res</td><td class="l">0.05<' in html


def test_report_date_from_source_date_epoch(monkeypatch, shear_result):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")  # 2023-11-14 22:13:20 UTC
    assert "2023-11-14T22:13:20+00:00" in report_html.render_html(shear_result, {}, False)
    monkeypatch.delenv("SOURCE_DATE_EPOCH")
    from datetime import datetime

    stamp = re.search(r"· (\d{4}-\d\d-\d\dT[\d:]+\+00:00)", report_html.render_html(shear_result, {}, False))
    age = datetime.now(UTC) - datetime.fromisoformat(stamp.group(1))
    assert abs(age.total_seconds()) < 120  # now, within the test's own run time


def test_template_compiled_once_per_process(shear_result):
    report_html._template.cache_clear()
    for _ in range(3):
        report_html.render_html(shear_result, {}, False)
    assert report_html._template.cache_info().misses == 1 and report_html._template.cache_info().hits == 2


def test_retention_methods_from_the_registry(tmp_path):
    from capred.fitting.retention_models import MODELS
    from capred.references import REFERENCES

    result = capred.run_retention(capred.sample_path("retention"))
    html = report_html.render_html(result, {}, False)
    import html as html_lib

    text = html_lib.unescape(html)
    fitted = {m for fits in result.fits.values() for m in fits}
    assert fitted
    for m in fitted:
        assert MODELS[m].method in text
        for key in MODELS[m].references:
            doi = getattr(REFERENCES[key], "doi", None)
            if doi:
                assert doi in text


@pytest.mark.parametrize("command", sorted(REDUCTIONS))
def test_every_command_renders_its_report(command):
    """Every command of the registry (capred.reductions.REDUCTIONS: a new command is tested without editing this
    file) on its quick run (its sample and example options): the report holds the options in force and the
    per-row table, and no option in SI or unit in caret notation (m^3, s^-1; a formula's ')^(' is not a unit)
    before the methods."""
    red = REDUCTIONS[command]
    result = red.run(capred.sample_path(red.sample) if red.sample else None, red.options(**dict(red.example)))
    html = report_html.render_html(result, {}, False)
    assert "Options in force" in html and "Per-row table" in html
    text = re.sub(r"<[^>]+>", "", html).split("Methods")[0]
    assert "N/m^3" not in html and not re.search(r"[A-Za-z]\^[-+]?\d", text), re.search(r".{40}\^.{20}", text)


# --- issue 29.4: a lab report ----------------------------------------------------------------------------------
def _workbook_with_metadata(path):
    """The shear sample as a workbook under a lab's metadata block (operator, date, apparatus)."""
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.title = "Direct shear"
    for row in (["Operator", "Jane Doe"], ["Date", "2026-03-14"], ["Apparatus", "60 mm shear box"], []):
        ws.append(row)
    lines = capred.sample_path("shear").read_text(encoding="utf-8").splitlines()
    import csv

    for row in csv.reader(x for x in lines if not x.startswith("#")):
        ws.append([float(c) if c.replace(".", "", 1).replace("-", "", 1).isdigit() else c for c in row])
    wb.save(path)
    return path


@pytest.fixture(scope="module")
def lab_report(tmp_path_factory):
    pytest.importorskip("openpyxl")
    tmp = tmp_path_factory.mktemp("lab")
    source = _workbook_with_metadata(tmp / "lab.xlsx")
    result = capred.run_shear(source, capred.ShearOptions(bootstrap=0))
    capred.write_outputs(result, tmp / "out", dpi=40)
    return (tmp / "out" / "report.html").read_text(encoding="utf-8")


def test_report_opens_with_the_inputs_metadata_block(lab_report):
    head = lab_report.split("What was run")[0]  # before anything else of the run
    assert "Jane Doe" in head and "Operator" in head and "2026-03-14" in head and "60 mm shear box" in head


def test_figures_are_numbered_and_name_their_material(lab_report):
    captions = re.findall(r"<figcaption>(.*?)</figcaption>", lab_report, flags=re.S)
    assert len(captions) == 2  # the two report sheets drawn by default (steel, sand)
    for k, (caption, material) in enumerate(zip(captions, ("steel_2mm", "sand_208-417um")), start=1):
        assert f"<b>Figure {k}.</b>" in caption and material in caption and "lab.xlsx" in caption


def test_headings_stay_with_what_follows_and_the_appendix_prints_landscape(lab_report):
    css = lab_report.split("</style>")[0]
    assert re.search(r"h1, h2, h3[^{]*\{[^}]*break-after: avoid", css)
    assert "@page rows { size: A4 landscape" in css and "page: rows" in css
    appendix = lab_report.split('<section class="appendix">')[1]
    assert "Per-row table" in appendix


def test_per_row_appendix_groups_fit_a_landscape_page():
    """The per-row table of the shear sample (52 tests, ~100 columns) in groups of at most 273 mm of 7 pt
    text: fewer groups than on portrait pages (186 mm), every column once."""
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    per_row = report_html._per_row(result)
    columns = per_row["columns"]
    _, head, _ = report_html._row_table(result, report_html.MAX_REPORT_ROWS)
    rows = [
        [report_html._cell(v) if not isinstance(v, float) else report_html.fmt(v) for v in r]
        for r in zip(*head.values())
    ]
    portrait = report_html.column_groups(columns, rows, report_html.PRINT_WIDTH_MM)
    landscape = report_html.column_groups(columns, rows, report_html.APPENDIX_WIDTH_MM)
    assert len(per_row["parts"]) == len(landscape) < len(portrait)
