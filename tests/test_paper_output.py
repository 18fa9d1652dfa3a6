"""Paper-ready output (issue 10): vector figures and single panels, honest curves, legends off the data,
literal user text, report.html, spreadsheet-friendly tables, the batch season table."""

import re
import shutil
from html.parser import HTMLParser
from xml.etree import ElementTree

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.report.sheets import compose, single

runner = CliRunner()


@pytest.fixture(scope="module")
def shear_result():
    return capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=50))


@pytest.mark.slow
def test_vector_sheets_and_single_panels(tmp_path):
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    capred.write_outputs(result, tmp_path / "o", formats=("pdf", "svg"), panels=True)
    out = tmp_path / "o"
    assert (out / "report_steel_2mm.pdf").read_bytes().startswith(b"%PDF")
    ElementTree.parse(out / "report_steel_2mm.svg")  # well-formed SVG
    panels = sorted(p.name for p in (out / "figures").glob("report_steel_2mm_*.svg"))
    assert panels == [
        "report_steel_2mm_dry_envelope.svg",
        "report_steel_2mm_measured_vs_predicted.svg",
        "report_steel_2mm_residuals.svg",
        "report_steel_2mm_strength_vs_saturation.svg",
    ]
    width = ElementTree.parse(out / "figures" / panels[0]).getroot().get("width")
    # one journal column, 85 mm = 240.9 pt, legend included
    assert float(width.rstrip("pt")) == pytest.approx(85 / 25.4 * 72, abs=0.5)
    assert not list(out.glob("*.png"))


def _data_points(fig):
    """Display coordinates of every plotted data point of every axes."""
    pts = []
    for ax in fig.axes:
        for line in ax.lines:
            xy = line.get_xydata()
            if len(xy) and line.get_transform() is not None:
                pts.append(line.get_transform().transform(xy))
        for coll in ax.collections:
            off = coll.get_offsets()
            if len(off):
                pts.append(coll.get_offset_transform().transform(off))
    return np.vstack([p for p in pts if len(p)]) if pts else np.empty((0, 2))


@pytest.mark.parametrize("make", ["composite", "single"])
def test_legends_never_cover_data(shear_result, make):
    for sheet in shear_result.figures().values():
        figs = [compose(sheet)] if make == "composite" else [single(sheet, p) for p in sheet.panels]
        for fig in figs:
            from matplotlib.backends.backend_agg import FigureCanvasAgg

            FigureCanvasAgg(fig).draw()  # one draw places the legends ("best") and gives their extents
            pts = _data_points(fig)
            pts = pts[np.all(np.isfinite(pts), axis=1)]
            for ax in fig.axes:
                leg = ax.get_legend()
                if leg is None:
                    continue
                box = leg.get_window_extent()
                inside = (pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1)
                assert not inside.any(), (sheet.title, ax.get_title())


def test_user_text_is_drawn_literally(tmp_path):
    text = (
        capred.sample_path("shear").read_text().replace("steel_2mm", r"$\frac{a}{$").replace("sand_208-417um", "[/x]")
    )
    (tmp_path / "t.csv").write_text(text)
    res = runner.invoke(app, ["shear", str(tmp_path / "t.csv"), "--bootstrap", "0", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    assert r"$\frac{a}{$" in res.stdout and "[/x]" in res.stdout  # console: no markup read into it
    result = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0))
    fig = compose(next(v for k, v in result.figures().items() if k.startswith("report_") and "frac" in k))
    assert r"\$\frac{a}{\$" in fig._suptitle.get_text()  # '$' escaped: drawn as typed
    html = (tmp_path / "o" / "report.html").read_text()
    assert "$\\frac{a}{$" in html and "[/x]" in html


def _model_lines(ax, labels):
    return [
        ln
        for ln in ax.lines
        if ln.get_linestyle() not in ("None", "none", " ", "")
        and len(ln.get_xdata()) > 2
        and ln.get_color() not in ("k", "0.6")
    ]


def test_no_connecting_lines_without_a_retention_relation(tmp_path):
    # three wet tests at two suctions: no retention relation can be fitted, so markers only
    text = (
        "test_id,condition,sigma_N [kPa],tau_max [kPa],suction [kPa],S_R,R [mm]\n"
        "d1,dry,1,1.0452,,,\nd2,dry,2,1.7598,,,\nd3,dry,3,2.4744,,,\n"
        "w1,wet,1,1.5,2,0.3,1\nw2,wet,2,2.2,2,0.3,1\nw3,wet,1,1.3,4,0.1,1\n"
    )
    (tmp_path / "t.csv").write_text(text)
    result = capred.run_shear(tmp_path / "t.csv", capred.ShearOptions(bootstrap=0))
    assert result.retention_relation("(all)") is None
    sheet = next(v for k, v in result.figures().items() if k.startswith("report_"))
    panel = next(p for p in sheet.panels if p.name == "strength_vs_saturation")
    fig = single(sheet, panel)
    assert not _model_lines(fig.axes[0], None)
    assert "no water-retention relation" in panel.caption
    # with a relation (the sample: enough wet tests to fit one), model curves are drawn and the caption says how
    sample = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    sheet = sample.figures()["report_steel_2mm"]
    panel = next(p for p in sheet.panels if p.name == "strength_vs_saturation")
    assert "fitted to the tests' own (suction, S_R) pairs" in panel.caption
    assert _model_lines(single(sheet, panel).axes[0], None)


def test_zero_suction_readings_are_in_a_marked_strip(tmp_path):
    (tmp_path / "r.csv").write_text(
        "suction [kPa],S_R\n0,1\n0,0.99\n1,0.98\n2,0.9\n4,0.6\n8,0.3\n16,0.15\n32,0.1\n64,0.08\n"
    )
    result = capred.run_retention(tmp_path / "r.csv")
    sheet = result.figures()["retention"]
    fig = single(sheet, sheet.panels[0])
    ax = fig.axes[0]
    assert any(t.get_text() == "s = 0" for t in ax.texts)
    for line in ax.lines:
        if line.get_transform() is ax.transData:  # data-coordinate points: every suction is a measured, positive one
            assert np.all(np.asarray(line.get_xdata(), float) > 0)
    strip = [ln for ln in ax.lines if ln.get_transform() is not ax.transData]
    assert strip and sorted(np.concatenate([ln.get_ydata() for ln in strip])) == [0.99, 1.0]


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.tags = [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        for k, v in attrs:
            if k in ("src", "href", "xlink:href") and v:
                self.refs.append(v)


@pytest.mark.parametrize(
    "args",
    [
        ["shear", "--sample", "--bootstrap", "0", "--models", "bishop,vanapalli", "--s-res", "0"],
        ["triaxial-bounds", "--sample"],
        ["retention", "--sample"],
        ["bridge", "compare", "--sample"],
    ],
)
def test_report_html_is_self_contained(tmp_path, args):
    res = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    parser = _Links()
    parser.feed(html)
    # no network, no other file: only in-document references (#id) and embedded images (data:) are allowed
    assert all(r.startswith(("#", "data:image/")) for r in parser.refs), [
        r[:40] for r in parser.refs if not r.startswith(("#", "data:image/"))
    ][:3]
    assert ("svg" in parser.tags or "img" in parser.tags) and "table" in parser.tags
    assert "link" not in parser.tags and "script" not in parser.tags
    assert "What was run" in html and "Warnings and flags" in html and "Methods" in html
    assert "@page { size: A4" in html
    assert "sha256" in html
    assert "doi:" in html  # references with their DOI


def test_report_can_be_skipped(tmp_path):
    res = runner.invoke(
        app, ["shear", "--sample", "--bootstrap", "0", "--no-plots", "--no-html", "--out", str(tmp_path / "o")]
    )
    assert res.exit_code == 0 and not (tmp_path / "o" / "report.html").exists()


def test_excel_eu_csv_and_xlsx(tmp_path):
    res = runner.invoke(
        app,
        [
            "shear",
            "--sample",
            "--bootstrap",
            "0",
            "--no-plots",
            "--csv-dialect",
            "excel-eu",
            "--xlsx",
            "--out",
            str(tmp_path / "eu"),
        ],
    )
    assert res.exit_code == 0, res.output
    runner.invoke(app, ["shear", "--sample", "--bootstrap", "0", "--no-plots", "--out", str(tmp_path / "std")])
    raw = (tmp_path / "eu" / "results.csv").read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf")  # UTF-8 BOM: Excel reads µ, °, – correctly
    eu = pd.read_csv(tmp_path / "eu" / "results.csv", sep=";", decimal=",", encoding="utf-8-sig")
    std = pd.read_csv(tmp_path / "std" / "results.csv")
    assert list(eu.columns) == list(std.columns)
    num = std.select_dtypes("number").columns
    np.testing.assert_array_equal(eu[num].to_numpy(), std[num].to_numpy())  # every digit kept in both
    assert "outside_pendular|chi1_gt_1" in raw.decode("utf-8-sig") or "outside_pendular" in raw.decode("utf-8-sig")
    from openpyxl import load_workbook

    wb = load_workbook(tmp_path / "eu" / "tables.xlsx")
    assert wb.sheetnames == ["results", "summary", "metrics"]
    ws = wb["results"]
    header = [c.value for c in ws[1]]
    assert "tau_max [kPa]" in header and "z1 [cm]" in header
    assert isinstance(ws.cell(row=2, column=header.index("tau_max [kPa]") + 1).value, float)


def test_results_csv_starts_with_the_raw_inputs():
    cols = list(capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)).table().columns)
    raw = ["z1 [cm]", "z2 [cm^3]", "V_v [cm^3]", "added_mass [g]", "cap_mass [g]", "box_area [cm^2]", "R [mm]"]
    assert cols[4:11] == raw and cols.index("sigma_N [kPa]") > cols.index("R [mm]")


def test_no_python_repr_in_cells(tmp_path):
    res = runner.invoke(
        app, ["triaxial-bounds", str(capred.sample_path("triaxial-bounds")), "--no-plots", "--out", str(tmp_path / "o")]
    )
    assert res.exit_code == 0
    for f in (tmp_path / "o").glob("*.csv"):
        assert "['" not in f.read_text() and "[]" not in f.read_text()


def test_batch_season_table(tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    for k in range(2):
        shutil.copy(capred.sample_path("shear"), runs / f"s{k}.csv")
    res = runner.invoke(
        app, ["shear", str(runs / "*.csv"), "--no-plots", "--bootstrap", "0", "--out", str(tmp_path / "o")]
    )
    assert res.exit_code == 0, res.output
    assert len(pd.read_csv(tmp_path / "o" / "season.csv")) == 2  # one row per run
    season = pd.read_csv(tmp_path / "o" / "season_shear.csv")  # shear's details: one row per material
    assert len(season) == 4  # 2 files x 2 materials
    assert {
        "c [kPa]",
        "phi [deg]",
        "c_se [kPa]",
        "phi_se [deg]",
        "best_model",
        "best_rmse [kPa]",
        "flagged_tests [-]",
    } <= set(season.columns)
    assert (tmp_path / "o" / pd.read_csv(tmp_path / "o" / "season.csv")["report"][0]).exists()
    html = (tmp_path / "o" / "season.html").read_text()
    assert 'href="shear_s0/report.html"' in html


# --- one house style (issue 21, item 1) ---------------------------------------------------------------------
from capred.report.style import MAX_MARKERS, OKABE_ITO  # noqa: E402


def _texts(fig):
    """Every text a reader sees in the axes of a figure except tick labels: titles, axis labels, legend, notes."""
    out = []
    for ax in fig.axes:
        out += [ax.get_title(loc) for loc in ("left", "center", "right")]
        out += [ax.get_xlabel(), ax.get_ylabel()] + [t.get_text() for t in ax.texts]
        leg = ax.get_legend()
        if leg is not None:
            out += [t.get_text() for t in leg.get_texts()]
    return [t for t in out if t]


def _outside_math(text):
    return "".join(text.split("$")[0::2])


@pytest.fixture(scope="module")
def curves_result():
    return capred.run_shear(
        capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, curves=capred.sample_path("shear-curves"))
    )


def _command_sheets(curves_result):
    from capred.reductions import REDUCTIONS

    yield from curves_result.figures().items()
    yield from capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds")).figures().items()
    yield from capred.run_retention(capred.sample_path("retention")).figures().items()
    for cmd in ("bridge compare", "bridge rupture", "skempton-b"):
        red = REDUCTIONS[cmd]
        yield from red.run(capred.sample_path(red.sample), red.options()).figures().items()
    yield from REDUCTIONS["bridge curve"].run(None, REDUCTIONS["bridge curve"].options(points=200)).figures().items()


@pytest.mark.slow
def test_labels_are_mathtext_and_panels_have_one_title(curves_result):
    seen = 0
    for name, sheet in _command_sheets(curves_result):
        for panel in sheet.panels:
            fig = single(sheet, panel)
            assert fig._suptitle is None  # a panel alone: no figure title (the caption is the report's)
            ax = fig.axes[0]
            assert sum(bool(ax.get_title(loc)) for loc in ("left", "center", "right")) <= 1
            for text in _texts(fig):
                raw = _outside_math(text)
                # no raw sub- or superscripts (S_R, φ_b, ^(2/3)) outside mathtext; test ids are drawn literally
                assert not re.search(r"[A-Za-zα-ωφχσ]_[A-Za-z0-9{]|\^\(|\^[0-9{]", raw), (name, panel.name, text)
            seen += 1
        if len(sheet.panels) == 1:  # the sheet's title is the one title of its only panel
            fig = compose(sheet)
            assert not fig.axes[0].get_title(), name
    assert seen >= 20


def test_curves_of_15_tests_never_share_a_look_and_vertical_displacement_is_drawn(curves_result):
    sheet = curves_result.figures()["curves_steel_2mm"]
    names = [p.name for p in sheet.panels]
    assert names == ["curves_dry", "vertical_dry", "curves_wet", "vertical_wet", "dilatancy"]
    ax = single(sheet, sheet.panels[2]).axes[0]  # 14 wet tests
    lines = [ln for ln in ax.lines if not ln.get_label().startswith("_")]
    assert len(lines) == 14
    looks = {(ln.get_color(), str(ln.get_linestyle()), ln.get_marker()) for ln in lines}
    assert len(looks) == len(lines)
    assert {ln.get_color() for ln in lines} <= {v.lower() for v in OKABE_ITO.values()} | set(OKABE_ITO.values())
    # the δv-δ panel draws the file's vertical displacements [mm] of each test as read
    raw = pd.read_csv(capred.sample_path("shear-curves"), comment="#")
    w01 = raw[raw["test_id"] == "ST-W01"]
    ax = single(sheet, sheet.panels[3]).axes[0]
    line = next(ln for ln in ax.lines if ln.get_label() == "_ST-W01")
    np.testing.assert_allclose(line.get_xdata(), w01["displacement [mm]"], rtol=1e-12)  # mm -> m -> mm
    np.testing.assert_allclose(line.get_ydata(), w01["vertical_displacement [mm]"], rtol=1e-12)
    # dilatancy at the peak: the result's own angles, one marker per test
    ax = single(sheet, sheet.panels[4]).axes[0]
    psi = np.concatenate([ln.get_ydata() for ln in ax.lines if ln.get_label() in ("dry tests", "wet tests")])
    mat = curves_result.tests["material"] == "steel_2mm"
    np.testing.assert_allclose(np.sort(psi), np.sort(curves_result.tests["dilatancy_angle"][mat]), rtol=0)


def test_mohr_panel_in_okabe_ito():
    result = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))
    sheet = result.figures()["report"]
    ax = single(sheet, next(p for p in sheet.panels if p.name == "mohr_circles")).axes[0]
    from matplotlib.colors import to_hex

    colours = {to_hex(ln.get_color()).upper() for ln in ax.lines}
    assert colours <= set(OKABE_ITO.values()), colours
    assert len(colours) >= 3  # total, effective (LB), saturated and the envelope told apart


def test_strength_against_saturation_one_line_style_per_normal_stress(shear_result):
    sheet = shear_result.figures()["report_steel_2mm"]
    ax = single(sheet, next(p for p in sheet.panels if p.name == "strength_vs_saturation")).axes[0]
    from matplotlib.colors import to_hex

    for model in shear_result.models:
        colour = to_hex(capred.report.style.style(model)["color"])
        curves = [ln for ln in ax.lines if to_hex(ln.get_color()) == colour and len(ln.get_xdata()) > 2]
        assert len(curves) == 2, model  # the sample's two normal stresses of the wet steel tests
        assert len({str(ln.get_linestyle()) for ln in curves}) == 2, model
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert r"$\sigma_N$ = 0.327 kPa" in legend and r"$\sigma_N$ = 0.538 kPa" in legend


def test_retention_legend_from_the_registry():
    from capred.fitting.retention_models import MODELS

    result = capred.run_retention(capred.sample_path("retention"))
    sheet = result.figures()["retention"]
    ax = single(sheet, sheet.panels[0]).axes[0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    fitted = {m for fits in result.fits.values() for m in fits}
    for m in fitted:
        assert f"{MODELS[m].label}\n{MODELS[m].equation}" in legend
    handles = dict(zip(legend, ax.get_legend().legend_handles))
    for m in fitted:
        assert (
            handles[f"{MODELS[m].label}\n{MODELS[m].equation}"].get_linestyle()
            == ax.lines[0].__class__([], [], ls=MODELS[m].style["ls"]).get_linestyle()
        )


def test_large_tables_draw_a_stated_sample(tmp_path):
    lines = capred.sample_path("shear").read_text().splitlines()
    head = next(ln for ln in lines if ln.startswith("test_id"))
    rows = [ln for ln in lines if ln.startswith("ST-")]
    body = [head] + [",".join([f"{r.split(',')[0]}-{k}", *r.split(",")[1:]]) for k in range(200) for r in rows]
    (tmp_path / "big.csv").write_text("\n".join(body) + "\n")
    result = capred.run_shear(tmp_path / "big.csv", capred.ShearOptions(bootstrap=0))
    n_wet = int(np.sum(result.tests["condition"] == "wet"))
    assert n_wet == 2800
    sheet = result.figures()["report_steel_2mm"]
    panel = next(p for p in sheet.panels if p.name == "measured_vs_predicted")
    assert "random sample of 2,000 of the 2,800 wet tests" in panel.caption  # the panel's tests, not 5,200
    dry = next(p for p in sheet.panels if p.name == "dry_envelope")
    assert "random sample of 2,000 of the 2,400 dry tests" in dry.caption  # 12 dry tests of steel x 200

    ax = single(sheet, panel).axes[0]
    markers = [ln for ln in ax.lines if ln.get_linestyle() in ("None", "none", "")]
    assert len(markers) == len(result.models)
    assert all(len(ln.get_xdata()) == MAX_MARKERS for ln in markers)  # a fixed cost, whatever the row count
    assert any("random sample of 2,000 of 2,800 tests" in t.get_text() for t in ax.texts)


def test_report_flags_of_a_spooled_table_are_counted_block_by_block():
    """report.html's flag table of a long run reads the spool's flags column block by block (never every
    column of every row at once) and counts as for a table in memory: 2 + 1 tests with 'a', 1 with 'b'."""
    import numpy as np

    from capred.report.html import _flags
    from capred.result import Spool

    spool = Spool()
    spool.append({"x": np.zeros(3), "flags": np.array(["a", "", "a;b"], dtype=object)})
    spool.append({"x": np.zeros(2), "flags": np.array(["a", ""], dtype=object)})

    class Long:
        def csv_tables(self):
            return {"results": spool}

    assert [(f, n) for f, n, _ in _flags(Long())] == [("a", 3), ("b", 1)]


def test_report_prints_an_interval_cell_as_its_numbers_not_a_python_list():
    """The retention fits' per-row table holds 95 % intervals (lists): report.html prints each bound as any
    number (4 significant digits) joined by '; ', as the CSV joins lists, never '[0.0317..., 0.0608...]'."""
    import re

    import pandas as pd

    import capred
    from capred.report.html import render_html

    result = capred.run_retention(capred.sample_path("retention"))
    # retention's tables now hold each bound in its own column (parameters.csv): a table with an interval cell
    table = pd.DataFrame({"model": ["vg"], "ci95": [[0.0317123, 0.0608456]]})
    result.__dict__["csv_tables"] = lambda: {"fits": table}  # the per-row table report.html prints
    html = render_html(result, {}, False)
    assert not re.search(r"<td>\[[-0-9.e]+, ", html)
    assert re.search(r"<td>[-0-9.e]+; [-0-9.e]+</td>", html)
