"""Sheets drawn on the figure of the previous sheet of their shape (issue 31, item 3: a season in minutes):
the same pixels as on a new figure, whatever was drawn before, and only figures left as new are reused."""

import warnings

import numpy as np
import pytest

import capred
from capred.report import sheets
from capred.report.sheets import Panel, Sheet, encode_png, raster, release, sheet_figure


def _run(path, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return capred.run_shear(path, capred.ShearOptions(bootstrap=0, **options))


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """Shear runs whose sheets differ in their data, ticks, legends and shapes: the sample; the sample ten times
    stronger and with its raw curves (other tick labels, a curves sheet); the steel alone (one material)."""
    sample = capred.sample_path("shear")
    lines = sample.read_text().splitlines()
    head = [k for k, line in enumerate(lines) if line and not line.startswith("#")][0]
    cols = lines[head].split(",")
    tau = cols.index("tau_max [kPa]")
    stronger, steel = lines[: head + 1], lines[: head + 1]
    for line in lines[head + 1 :]:
        cells = line.split(",")
        if len(cells) == len(cols):
            steel += [line] if "steel" in line else []
            cells[tau] = f"{10 * float(cells[tau]):.6g}"
            line = ",".join(cells)
        stronger.append(line)
    folder = tmp_path_factory.mktemp("reuse")
    (folder / "stronger.csv").write_text("\n".join(stronger) + "\n")
    (folder / "steel.csv").write_text("\n".join(steel) + "\n")
    return [
        _run(sample),
        _run(folder / "stronger.csv", curves=capred.sample_path("shear-curves")),
        _run(folder / "steel.csv"),
    ]


def _sheets(result):
    """Every sheet of a run, made anew (a sheet records the room its legends took)."""
    return list(result.figures().values())


def _png(sheet, reuse):
    fig = sheet_figure(sheet, 100, reuse=reuse)
    png = encode_png(raster(fig), 100)
    if reuse:
        release(fig)
    return png


def test_a_sheet_on_a_reused_figure_has_the_pixels_of_a_new_one(results, monkeypatch):
    """Each sheet of three different runs, drawn in turn on the figures the previous sheets handed back, gives
    the bytes it gives on a new figure: nothing of an earlier sheet (data, limits, tick labels, legends, a
    taller panel, the equal aspect of measured-vs-predicted) survives into the next."""
    monkeypatch.setattr(sheets, "_TEMPLATES", {})
    order = [(r, k) for r in (2, 0, 1) for k in range(len(_sheets(results[r])))]
    fresh = {(r, k): _png(_sheets(results[r])[k], reuse=False) for r, k in set(order)}
    assert not sheets._TEMPLATES  # a figure not drawn for reuse is never kept
    reused = 0
    for r, k in order:
        sheet = _sheets(results[r])[k]
        before = dict(sheets._TEMPLATES)
        fig = sheet_figure(sheet, 100, reuse=True)
        reused += any(fig is f for f in before.values())
        png = encode_png(raster(fig), 100)
        release(fig)
        assert png == fresh[(r, k)], (r, k, sheet.title)
    assert reused >= len(order) // 2  # most sheets were drawn on a figure handed back


def _probe(changes):
    """A sheet of two panels; the first applies ``changes(ax)`` to its axes."""

    def first(ax):
        ax.plot([0, 1], [0, 2], label="a")
        changes(ax)
        ax.legend()

    return Sheet("probe", [Panel("p1", first), Panel("p2", lambda ax: ax.plot([1, 2], [3, 1]))], 2)


@pytest.mark.parametrize(
    "changes",
    [
        lambda ax: ax.tick_params(labelbottom=False),
        lambda ax: ax.set_yscale("log"),
        lambda ax: ax.figure.colorbar(ax.scatter([0, 1], [0, 1], c=[0, 1]), ax=ax),
        lambda ax: ax.figure.text(0.5, 0.5, "a figure text"),
    ],
    ids=["tick settings", "log scale", "colour bar", "figure text"],
)
def test_only_a_figure_left_as_new_is_handed_back(changes, monkeypatch):
    """A sheet whose panel changed its ticks' settings, a scale, added an axes or a figure text is not reused:
    the next sheet of its shape gets a new figure and the pixels a new figure gives."""
    monkeypatch.setattr(sheets, "_TEMPLATES", {})
    fig = sheet_figure(_probe(changes), 100, reuse=True)
    raster(fig)
    release(fig)
    assert not sheets._TEMPLATES
    plain = _probe(lambda ax: None)
    fig = sheet_figure(plain, 100, reuse=True)
    raster(fig)
    release(fig)
    assert list(sheets._TEMPLATES.values()) == [fig]  # a sheet left as new is kept...
    again = sheet_figure(_probe(lambda ax: None), 100, reuse=True)
    assert again is fig  # ...and the next one of its shape is drawn on it
    assert np.array_equal(raster(again), raster(sheet_figure(_probe(lambda ax: None), 100)))
