"""Figure files as a journal and a rerun see them (issues 19, 20, 21): printed sizes and dpi read back from the
PNGs, single panels only when asked, report.html embedding the composite already drawn, byte-identical reruns,
the same bytes from one process or two, and progress that stays silent off a terminal."""

import base64
import re

import pytest
from numpy.testing import assert_allclose
from PIL import Image
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.report import outputs
from capred.report.sheets import COLUMN_MM, PAGE_MM, journal_style, panel_figure, sheet_figure, sheet_layout

MM = 25.4
# a printed length [mm] read back from pixels at 300 dpi is exact to one pixel: 25.4/300 = 0.085 mm
ONE_PX_MM = MM / 300
# PNG's pHYs chunk holds whole pixels per metre: a dpi reads back within 0.5 px/m = 0.0127 dpi
PHYS_DPI = 0.5 * 0.0254


@pytest.fixture(scope="module")
def shear_result():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))


@pytest.fixture(scope="module")
def default_run(shear_result, tmp_path_factory):
    """The README's first command's outputs (default options), drawn by this process alone."""
    out = tmp_path_factory.mktemp("default") / "o"
    old = outputs.PARALLEL_MIN_PANELS
    outputs.PARALLEL_MIN_PANELS = 10**9
    try:
        capred.write_outputs(shear_result, out)
    finally:
        outputs.PARALLEL_MIN_PANELS = old
    return out


def _printed_mm(path):
    """(width, height) [mm] and dpi of a PNG, from its pixels and its pHYs chunk."""
    with Image.open(path) as im:
        dpi = im.info["dpi"]
        return im.size[0] / dpi[0] * MM, im.size[1] / dpi[1] * MM, dpi


def _main(result) -> dict:
    """The sheets written by default (those not drawn only on request)."""
    return {k: s for k, s in result.figures().items() if not s.on_request}


def test_composites_fill_the_text_width_at_300_dpi(default_run, shear_result):
    sheets = _main(shear_result)
    pngs = sorted(p.name for p in default_run.glob("*.png"))
    assert pngs == sorted(f"{k}.png" for k in sheets)
    for name, sheet in sheets.items():
        width, height, dpi = _printed_mm(default_run / f"{name}.png")
        # 300 dpi by default; PNG stores whole pixels per metre (11811), off by <= 0.5/m = 0.0127 dpi
        assert_allclose(dpi, (300, 300), atol=PHYS_DPI)
        sheet_figure(sheet)  # measures the room its legends need below their axes (Sheet.legend_room)
        _, w_mm, h_mm = sheet_layout(sheet)
        # two one-column panels and the 10 mm gap: the 180 mm text width of an A4 page, never a strip
        assert w_mm == PAGE_MM
        assert_allclose(width, PAGE_MM, atol=ONE_PX_MM)
        assert_allclose(height, h_mm, atol=ONE_PX_MM)
        assert height < 250  # fits the A4 page's text height with its caption


def test_no_single_panels_unless_asked(default_run):
    assert not (default_run / "figures").exists()
    assert not list(default_run.glob("*.pdf")) and not list(default_run.glob("*.svg"))


def test_single_panels_are_one_or_two_columns_wide(shear_result, tmp_path):
    result = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))
    out = tmp_path / "t"
    capred.write_outputs(result, out, panels=True, dpi=150, html=False)
    sheet = result.figures()["report"]
    files = sorted((out / "figures").glob("report_*.png"))
    assert [f.name for f in files] == sorted(f"report_{p.name}.png" for p in sheet.panels)
    for p in sheet.panels:
        width, _, dpi = _printed_mm(out / "figures" / f"report_{p.name}.png")
        assert_allclose(dpi, (150, 150), atol=PHYS_DPI)  # --dpi is kept
        # the q-p plane spans both columns (180 mm); every other panel is one column (85 mm); 1 px at 150 dpi
        expected = PAGE_MM if sheet.spans.get(p.name, 1) == 2 else COLUMN_MM
        assert_allclose(width, expected, atol=MM / 150)
    composite_w, _, _ = _printed_mm(out / "report.png")
    assert composite_w <= PAGE_MM + MM / 150


def test_panels_option_on_the_command_line(tmp_path):
    res = CliRunner().invoke(
        app, ["retention", "--sample", "--panels", "--format", "png,svg", "--dpi", "100", "--out", str(tmp_path / "o")]
    )
    assert res.exit_code == 0, res.output
    names = sorted(p.name for p in (tmp_path / "o" / "figures").iterdir())
    assert names == ["retention_curves.png", "retention_curves.svg"]


def test_journal_font_sizes(shear_result):
    """Axis labels, tick labels, titles and legends of every panel are 7-9 pt at the printed size."""
    sheet = shear_result.figures()["report_steel_2mm"]
    for panel in sheet.panels:
        fig = panel_figure(sheet, panel, dpi=72)
        for ax in fig.axes:
            texts = [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.get_xticklabels(), *ax.get_yticklabels()]
            if ax.get_legend() is not None:
                texts += ax.get_legend().get_texts()
            sizes = {t.get_fontsize() for t in texts if t.get_text()}
            assert sizes and min(sizes) >= 7 and max(sizes) <= 9, (panel.name, sizes)


def test_report_embeds_the_composite_png_as_written(default_run, shear_result):
    html = (default_run / "report.html").read_text(encoding="utf-8")
    embedded = [base64.b64decode(m) for m in re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)", html)]
    written = [(default_run / f"{k}.png").read_bytes() for k in _main(shear_result)]
    assert embedded == written  # the same bytes: drawn once, not re-rendered for the report
    assert "<svg" not in html  # no second (vector) rendering unless svg was asked for


def test_default_sheets_are_the_report_sheets(default_run, shear_result):
    """By default shear writes each material's report sheet; the capillary-stress sheets are drawn on request
    and report.html names each one left out and how to have it."""
    sheets = shear_result.figures()
    assert sorted(_main(shear_result)) == ["report_sand_208-417um", "report_steel_2mm"]
    extra = sorted(k for k in sheets if k not in _main(shear_result))
    assert extra == ["capillary_sand_208-417um", "capillary_steel_2mm"]
    html = (default_run / "report.html").read_text(encoding="utf-8")
    for k in extra:
        assert f"<b>{k}.</b> Not drawn by default: {sheets[k].title}" in html
    assert html.count("--figures all") == len(extra)
    assert html.count("<figure>") == len(_main(shear_result))  # a sheet left out is a note, not an empty figure


def test_figures_all_draws_the_sheets_on_request(tmp_path, monkeypatch, light):
    import capred.report.presenters as presenters

    def sheets(result):
        out = _light_sheets(result, 2)
        out["s1"].on_request = True
        return out

    monkeypatch.setattr(presenters, "figures", sheets)
    capred.write_outputs(light, tmp_path / "main", dpi=50)
    capred.write_outputs(light, tmp_path / "all", dpi=50, figures="all")
    assert sorted(p.name for p in (tmp_path / "main").glob("*.png")) == ["s0.png"]
    assert sorted(p.name for p in (tmp_path / "all").glob("*.png")) == ["s0.png", "s1.png"]
    assert "Not drawn by default: sheet 1" in (tmp_path / "main" / "report.html").read_text(encoding="utf-8")
    assert "Not drawn by default" not in (tmp_path / "all" / "report.html").read_text(encoding="utf-8")


def test_figures_must_be_main_or_all(shear_result, tmp_path):
    with pytest.raises(capred.OptionError, match="main, all"):
        capred.write_outputs(shear_result, tmp_path / "o", figures="some")
    assert not (tmp_path / "o").exists()


def test_figures_option_on_the_command_line_and_in_a_manifest(tmp_path):
    sample = capred.sample_path("shear")
    res = CliRunner().invoke(
        app,
        [
            "shear",
            str(sample),
            "--figures",
            "all",
            "--dpi",
            "40",
            "--no-html",
            "--bootstrap",
            "0",
            "--out",
            str(tmp_path / "o"),
        ],
    )
    assert res.exit_code == 0, res.output
    assert sorted(p.name.split("_")[0] for p in (tmp_path / "o").glob("*.png")) == ["capillary"] * 2 + ["report"] * 2
    res = CliRunner().invoke(app, ["shear", str(sample), "--figures", "some", "--out", str(tmp_path / "x")])
    assert res.exit_code != 0 and "--figures must be 'main' or 'all'" in res.output and not (tmp_path / "x").exists()
    (tmp_path / "season.csv").write_text(
        f"command,input,options\nshear,{sample},--figures all --dpi 40 --no-html --bootstrap 0\n", encoding="utf-8"
    )
    res = CliRunner().invoke(app, ["batch", str(tmp_path / "season.csv"), "--out", str(tmp_path / "b")])
    assert res.exit_code == 0, res.output
    assert len(list((tmp_path / "b").glob("*/capillary_*.png"))) == 2


def test_sheet_figure_lays_out_like_the_pasted_panels(shear_result):
    """A sheet drawn on one figure puts each panel where its own figure would: the same slot, the same fitted
    axes box (within a pixel: the slots' edges are rounded to whole pixels when pasted)."""
    from capred.report.sheets import sheet_figure

    sheet = shear_result.figures()["report_steel_2mm"]
    dpi = 100
    fig = sheet_figure(sheet, dpi)
    slots, width, height = sheet_layout(sheet)
    assert_allclose((fig.bbox.width, fig.bbox.height), (width / MM * dpi, height / MM * dpi), atol=1)
    assert len(fig.axes) == len(sheet.panels)
    px = dpi / MM
    for ax, slot, panel in zip(fig.axes, slots, sheet.panels):
        own = panel_figure(sheet, panel, dpi).axes[0].get_window_extent()
        box = ax.get_window_extent()
        # in the sheet: the panel's box shifted to its slot (top-left origin in mm, bottom-left in pixels)
        x0 = slot.x * px + own.x0
        y0 = fig.bbox.height - (slot.y + slot.height) * px + own.y0
        assert_allclose([box.x0, box.y0, box.width, box.height], [x0, y0, own.width, own.height], atol=1.0)


def test_report_embeds_the_svg_when_svg_is_asked(tmp_path):
    result = capred.run_retention(capred.sample_path("retention"))
    capred.write_outputs(result, tmp_path / "o", formats=("svg",))
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    svg = (tmp_path / "o" / "retention.svg").read_text(encoding="utf-8")
    assert svg[svg.index("<svg") :] in html
    assert "data:image/png" not in html and not list((tmp_path / "o").glob("*.png"))


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def _light_sheets(result, n: int = 3):
    """Three sheets of two small panels each (mathtext labels, a legend): the engine's work without the cost
    of the shear figures."""
    from capred.report.sheets import Panel, Sheet

    def line(k):
        def draw(ax):
            ax.plot([0, 1, 2], [0, k, 2 * k], "o-", label=f"series {k}")
            ax.set_xlabel(r"$\sigma_N$ [kPa]")
            ax.set_ylabel(r"$\tau_{max}$ [kPa]")
            ax.set_title(f"panel {k}")
            ax.legend()
            return ax

        return draw

    return {f"s{j}": Sheet(f"sheet {j}", [Panel(f"p{k}", line(k + j)) for k in range(2)], 2) for j in range(n)}


@pytest.fixture
def light(monkeypatch):
    import capred.report.presenters as presenters

    monkeypatch.setattr(presenters, "figures", _light_sheets)
    return capred.run_retention(capred.sample_path("retention"))


@pytest.mark.parametrize("formats", [("png",), pytest.param(("pdf", "svg"), marks=pytest.mark.slow)])
def test_reruns_are_byte_identical(tmp_path, monkeypatch, light, formats):
    import capred.report.presenters as presenters

    monkeypatch.setattr(presenters, "figures", lambda result: _light_sheets(result, 1))
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    a, b = tmp_path / "a", tmp_path / "b"
    capred.write_outputs(light, a, formats=formats, panels=True, html=False)
    capred.write_outputs(light, b, formats=formats, panels=True, html=False)
    fa, fb = _files(a), _files(b)
    fa.pop("provenance.json"), fb.pop("provenance.json")
    figs = [n for n in fa if n.rsplit(".", 1)[-1] in formats]
    assert len(figs) == 3 * len(formats)  # the composite and its 2 panels, in each format
    assert fa == fb
    for n in figs:
        data = fa[n]
        assert b"CreationDate" not in data and b"<dc:date>" not in data and b"tIME" not in data
        if n.endswith(".png"):
            with Image.open(a / n) as im:
                assert set(im.info) == {"dpi"}  # no text chunk: no software name, no time


@pytest.mark.parametrize("panels", [True, False])
def test_two_processes_write_the_same_bytes(tmp_path, monkeypatch, light, panels):
    monkeypatch.setattr(outputs, "PARALLEL_MIN_PANELS", 10**9)
    capred.write_outputs(light, tmp_path / "one", panels=panels)
    monkeypatch.setattr(outputs, "PARALLEL_MIN_PANELS", 1)
    monkeypatch.setenv("CAPRED_FIGURE_PROCESSES", "2")  # whatever the machine's load
    calls = []
    real = outputs._two_processes
    monkeypatch.setattr(outputs, "_two_processes", lambda *a: calls.append(1) or real(*a))
    capred.write_outputs(light, tmp_path / "two", panels=panels)
    assert calls  # the forked path ran
    one, two = _files(tmp_path / "one"), _files(tmp_path / "two")
    one.pop("provenance.json"), two.pop("provenance.json")
    html_one, html_two = one.pop("report.html"), two.pop("report.html")
    assert one == two and len(one) > (9 if panels else 3)
    stamp = re.compile(rb"\d{4}-\d\d-\d\dT[0-9:]+(\+00:00|Z)?")  # the report's date (no SOURCE_DATE_EPOCH)
    assert stamp.sub(b"", html_one) == stamp.sub(b"", html_two)


def test_a_failure_in_the_second_process_reaches_the_caller(tmp_path, monkeypatch, light):
    from capred.report.sheets import Panel, Sheet

    def broken(result):
        sheets = _light_sheets(result)
        sheets["s2"] = Sheet("broken", [Panel("p", lambda ax: 1 / 0)], 2)
        return sheets

    import capred.report.presenters as presenters

    monkeypatch.setattr(presenters, "figures", broken)
    monkeypatch.setattr(outputs, "PARALLEL_MIN_PANELS", 1)
    monkeypatch.setenv("CAPRED_FIGURE_PROCESSES", "2")
    with pytest.raises(ZeroDivisionError):
        capred.write_outputs(light, tmp_path / "o")
    assert not (tmp_path / "o").exists()  # nothing half-written


def test_layout_keeps_content_inside_each_panel(shear_result):
    """Every axes and its labels lie within the panel's figure (1 mm margin kept)."""
    from matplotlib.transforms import Bbox

    for sheet in [shear_result.figures()["report_steel_2mm"]]:
        for panel in sheet.panels:
            fig = panel_figure(sheet, panel, dpi=100)
            renderer = fig.canvas.get_renderer()
            with journal_style():
                box = Bbox.union([ax.get_tightbbox(renderer) for ax in fig.axes])
            # 0.5 px of rounding at 100 dpi
            assert box.x0 >= -0.5 and box.y0 >= -0.5, (panel.name, box)
            assert box.x1 <= fig.bbox.width + 0.5 and box.y1 <= fig.bbox.height + 0.5, (panel.name, box)


def test_progress_is_silent_off_a_terminal(tmp_path):
    res = CliRunner().invoke(app, ["retention", "--sample", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0
    assert "drawing figures" not in res.output and "\x1b[" not in res.output


def test_progress_tasks_without_a_display_do_nothing():
    from capred.progress import showing, steps, task

    with task("drawing figures", total=3) as advance:
        advance(3)
    assert list(steps(range(3), "x")) == [0, 1, 2]
    with showing(False):
        with task("y") as advance:
            advance()


@pytest.mark.skipif(not hasattr(__import__("os"), "fork"), reason="no fork on this platform")
def test_a_forked_child_parses_and_opens_its_own_fonts():
    """Parsed mathtext keeps the font objects its glyphs are drawn from; fonts opened before a fork read their
    files through offsets shared with the parent, so a child must not reuse them: it starts with no cached
    parse and no shared parser."""
    import os

    from matplotlib.mathtext import MathTextParser

    from capred.report import sheets

    sheets.warm_up(72)  # parses mathtext labels with the shared parser
    assert sheets._MATHTEXT and MathTextParser._parse_cached.cache_info().currsize > 0
    pid = os.fork()
    if pid == 0:  # the child: report by exit status only
        ok = not sheets._MATHTEXT and MathTextParser._parse_cached.cache_info().currsize == 0
        os._exit(0 if ok else 1)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    assert sheets._MATHTEXT  # the parent keeps its own


# ------------------------------------------------------------------------------ what a person sees (issue 29.8)


def _legend_texts(ax) -> list[str]:
    leg = ax.get_legend()
    return [t.get_text() for t in leg.get_texts()] if leg is not None else []


def test_a_long_legend_makes_the_panel_taller_instead_of_squashing_the_axes():
    """Twelve two-line entries (as `capred retention --model all` has): the legend goes below the axes and the
    panel grows, so the axes keep at least half their panel's nominal height (before: ~15 %) and the legend
    overlaps neither the axes nor the x label."""
    import numpy as np

    from capred.report.sheets import Panel, Sheet, panel_size_mm, sheet_figure

    def draw(ax):
        x = np.linspace(0, 1, 20)
        for k in range(12):
            ax.plot(
                x,
                x * k,
                label=f"model number {k} with a rather long name for a legend\n$S_e = [1 + (\\alpha s)^n]^{{-m}}$ {k}",
            )
        ax.set_xlabel("suction $s$ [kPa]")
        return ax

    sheet = Sheet("A sheet", [Panel("p", draw)], 1, spans={"p": 2})
    nominal_h = panel_size_mm(sheet, sheet.panels[0])[1]
    fig = sheet_figure(sheet)
    assert sheet.legend_room["p"] > 0
    ax = fig.axes[0]
    renderer = fig.canvas.get_renderer()
    axes_h_mm = ax.bbox.height / fig.dpi * MM
    assert axes_h_mm >= 0.5 * nominal_h, (axes_h_mm, nominal_h)
    leg = ax.get_legend().get_window_extent(renderer)
    below = ax.xaxis.get_tightbbox(renderer)
    assert leg.y1 <= below.y0 + 1  # under the x label (1 px of rounding)
    assert leg.y0 >= 0  # and inside the figure


def test_at_least_nine_line_styles_that_differ_in_what_a_reader_sees():
    """The house line styles: the sequence of dash kinds in one period (dot <= 1.5 pt, dash <= 4 pt, long
    dash) differs between every two of them; ten of them. The retention models' styles differ likewise
    (Kosugi dotted, Durner dash-dot-dot: both were dotted)."""
    from capred.fitting.retention_models import MODELS
    from capred.report.style import LINESTYLES

    def kind(ls):
        if ls == "-":
            return ("solid",)
        named = {"--": (0, (3.7, 1.6)), ":": (0, (1, 1.65)), "-.": (0, (6.4, 1.6, 1, 1.6))}
        on = named.get(ls, ls)[1][::2]
        return tuple("dot" if d <= 1.5 else "dash" if d <= 4 else "long" for d in on)

    kinds = [kind(ls) for ls in LINESTYLES]
    assert len(LINESTYLES) >= 9 and len(set(kinds)) == len(kinds), kinds
    retention = [kind(m.style.get("ls", "-")) for m in MODELS.values() if "ls" in m.style]
    assert len(set(retention)) == len(retention), retention


def test_svg_text_is_text(tmp_path, monkeypatch, light):
    """SVG files keep their text as <text> elements (editable), not glyph paths."""
    out = tmp_path / "o"
    capred.write_outputs(light, out, formats=("svg",))
    svg = next(out.glob("*.svg")).read_text(encoding="utf-8")
    assert "<text" in svg
    assert ">sheet " in svg or "sheet 0" in svg  # the title, readable as text


def test_every_error_bar_says_what_it_is(shear_result):
    """The report sheet's bars are 95 % prediction intervals, the capillary sheet's ± 1 standard error: each
    panel with bars says which in its legend (and the captions say it too)."""
    from capred.report.shear_figures import PI_BARS, SE_BARS
    from capred.report.sheets import sheet_figure

    sheets = shear_result.figures()
    report = next(s for k, s in sheets.items() if k.startswith("report_"))
    capillary = next(s for k, s in sheets.items() if k.startswith("capillary_"))
    fig = sheet_figure(report)
    titles = {ax.get_title(): ax for ax in fig.axes}
    assert PI_BARS in _legend_texts(titles["Measured and predicted strength"])
    assert "95 %\nprediction interval" in PI_BARS
    fig = sheet_figure(capillary)
    for ax in fig.axes:
        assert SE_BARS in _legend_texts(ax), ax.get_title()
    assert "± 1\nstandard error" in SE_BARS
    assert all("standard error" in p.caption for p in capillary.panels)


def test_strength_curves_do_not_jump_and_the_pendular_regime_has_its_own_entry(shear_result):
    """Model curves of strength against S_R are drawn over the S_R that the measured suctions give. Before,
    they ran on to 3x the largest suction, into the fitted relation's residual plateau, where the suction (and
    chi Delta u) grows while S_R stays put: the steel's Own 1 curve rose from 0.78 to 1.0 kPa between S_R =
    0.0236 and 0.0197, a vertical stroke at the left edge. The pendular regime is a shaded band with its own
    legend entry, not a line."""
    import numpy as np

    from capred.report.sheets import sheet_figure

    t = shear_result.tests
    for key, sheet in shear_result.figures().items():
        if not key.startswith("report_"):
            continue
        material = key[len("report_") :]
        wet = (t["material"] == material) & (t["condition"] == "wet")
        relation = shear_result.retention_relation(material)
        s = t["suction"][wet]
        lo, hi = sorted(relation.S_R(np.array([s.max(), s.min()])))
        fig = sheet_figure(sheet)
        ax = next(a for a in fig.axes if a.get_title() == "Strength against saturation")
        curves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 20]
        assert curves
        for ln in curves:
            S, tau = np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)
            drawn = S[np.isfinite(tau)]
            assert drawn.size > 60  # about half of CURVE_POINTS: a smooth curve
            assert drawn.min() >= lo - 1e-6 and drawn.max() <= hi + 1e-6, (key, drawn.min(), lo)
        texts = _legend_texts(ax)
        assert any(t.startswith("pendular") for t in texts), texts
        band = [p for p in ax.patches if p.get_label().startswith("pendular")]
        assert len(band) == 1 and not any(ln.get_label().startswith("pendular") for ln in ax.get_lines())
