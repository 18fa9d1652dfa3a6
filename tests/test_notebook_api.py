"""The API as a notebook or a lab script uses it: short repr, _repr_html_, plot(), Python warnings, dir(capred),
callable retention fits, models="all", a missing file as FileNotFoundError."""

import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

import capred
from capred.reductions import REDUCTIONS


@pytest.fixture(scope="module")
def shear():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        return capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))


def test_dir_lists_the_public_api():
    names = dir(capred)
    assert {"run_shear", "run_triaxial_bounds", "run_retention", "write_outputs", "CapredWarning"} <= set(names)


def test_repr_is_one_short_line(shear):
    text = repr(shear)
    assert "\n" not in text and len(text) < 200 and "shear" in text and "52 rows" in text


def test_repr_html_is_a_compact_summary(shear):
    html = shear._repr_html_()
    assert "Dry envelope" in html and "<table>" in html
    assert html.count("data:image/png;base64,") == 1  # one small figure
    assert len(html.encode("utf-8")) < 30_000  # issue 29.2: under 30 KB (it was the full report, over 80 KB)
    assert "result.report_html()" in html and "result.plot()" in html  # where the rest is


@pytest.mark.parametrize("command", sorted(REDUCTIONS))
def test_repr_html_of_every_command_stays_under_30_kb(command):
    """Every command of the registry (capred.reductions.REDUCTIONS: a new command is tested without editing this
    file), on its quick run: a compact summary (issue 29.2), with at most one small figure where it draws."""
    from test_console_widths import sample_result

    result = sample_result(command)
    html = result._repr_html_()
    assert "<table>" in html and len(html.encode("utf-8")) < 30_000
    assert html.count("data:image/png;base64,") <= (1 if result.figures() else 0)


def test_report_html_is_the_full_report_with_its_figures(shear):
    page = shear.report_html()
    assert page.startswith("<!DOCTYPE html>") and "Per-row table" in page and "Options in force" in page
    main = [k for k, sheet in shear.figures().items() if not getattr(sheet, "on_request", False)]
    assert page.count("data:image/png;base64,") == len(main) == 2  # each main sheet inlined (steel, sand)


def test_plot_returns_figures_without_writing(shear, tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    monkeypatch.chdir(tmp_path)
    figs = shear.plot()
    assert figs and all(isinstance(f, Figure) for f in figs.values())
    one = shear.plot(next(iter(figs)))
    assert isinstance(one, Figure)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(capred.OptionError):
        shear.plot("no_such_sheet")


def test_implausible_values_are_python_warnings():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0, gamma_w="10 N/m^3"))
    texts = [str(w.message) for w in caught if issubclass(w.category, capred.CapredWarning)]
    assert any("gamma_w" in t for t in texts)  # implausible option
    assert any("pendular" in t for t in texts)  # regime warning
    assert issubclass(capred.CapredWarning, UserWarning)
    assert set(texts) == set(r.warnings)  # the same warnings as the JSON and the report


def test_models_all_in_the_options():
    params = capred.ModelParams(s_res=0.05, air_entry="1 kPa", vg_alpha="0.5 1/kPa", vg_n=3.0)
    opts = capred.ShearOptions(models="all", model_params=params, bootstrap=0)
    from capred.physics.effective_stress_models import REGISTRY

    assert opts.models == tuple(REGISTRY)
    assert capred.ShearOptions(models="thesis").models == ("no_suction", "bishop", "own1", "own2")


def test_retention_fit_is_callable_in_S_R_and_suction():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", capred.CapredWarning)
        r = capred.run_retention(capred.sample_path("retention"))
    fit = r.fits["drying"]["vg"]
    p = fit.params
    s = np.array([1e3, 5e3, 2e4])  # Pa
    # van Genuchten (1980), eq. 21 with m = 1 - 1/n, by hand
    se = (1 + (p["alpha"] * s) ** p["n"]) ** -(1 - 1 / p["n"])
    assert_allclose(fit.S_R(s), p["y_r"] + (p["y_s"] - p["y_r"]) * se, rtol=1e-12)
    assert_allclose(fit.suction_at_S_R(fit.S_R(s)), s, rtol=1e-9)  # the inverse, closed form


def test_missing_file_is_a_file_not_found_error(tmp_path):
    with pytest.raises(FileNotFoundError):
        capred.run_shear(tmp_path / "nope.csv")
    with pytest.raises(capred.InputError):
        capred.run_shear(tmp_path / "nope.csv")
