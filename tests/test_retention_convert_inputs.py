"""`capred retention-convert` reads a FIT.json as hostile input (issue 46, item 3): every fitted parameter inside
its model's domain, every count, statistic and suction range a number of the right kind, the file a regular JSON
file of bounded size and depth; each gives one clean message, exit 1, nothing written."""

import json

import pytest
from typer.testing import CliRunner

from capred.cli import app

runner = CliRunner()


@pytest.fixture(scope="module")
def fits_json(tmp_path_factory):
    out = tmp_path_factory.mktemp("conv") / "r"
    res = runner.invoke(app, ["retention", "--sample", "--out", str(out), "--no-plots", "--model", "vg"])
    assert res.exit_code == 0, res.output
    return json.loads((out / "fits.json").read_text(encoding="utf-8"))


def _edit(doc, **changes):
    d = json.loads(json.dumps(doc))
    fit = d["branches"][d["main_branch"]]["fits"]["vg"]
    for k, v in changes.items():
        if k.startswith("si_"):
            fit["params_si"][k[3:]] = v
        else:
            fit[k] = v
    return d


def _convert(tmp_path, text: str):
    src = tmp_path / "fits.json"
    src.write_text(text, encoding="utf-8")
    out = tmp_path / "o"
    res = runner.invoke(app, ["retention-convert", str(src), "--to", "bc", "--out", str(out)])
    return res, out


CASES = [
    ({"si_n": 0.5}, "n = 0.5 lies outside"),
    ({"si_n": -3}, "n = -3 lies outside"),
    ({"si_n": True}, "must be a number"),
    ({"si_n": "2"}, "must be a number"),
    ({"si_alpha": 1e308}, "the curve is flat"),
    ({"si_alpha": -1e-4}, "lies outside"),
    ({"si_y_r": 0.9, "si_y_s": 0.5}, "is not below"),
    ({"rss": "x"}, "'rss' must be a number"),
    ({"n_points": 2.5}, "'n_points' must be a whole number"),
    ({"n_points": -4}, "'n_points' must be a whole number"),
    ({"converged": "yes"}, "'converged' must be true or false"),
    ({"suction_points_kPa": None, "suction_range_kPa": {"a": 1}}, "'suction_range_kPa' must be a list"),
    ({"suction_points_kPa": None, "suction_range_kPa": [0, 10]}, "positive suctions"),
    ({"suction_points_kPa": [1, True]}, "must be a number"),
    ({"suction_points_kPa": [5, 5]}, "not all equal"),
]


@pytest.mark.parametrize("changes,message", CASES, ids=[str(c) for c, _ in CASES])
def test_a_value_outside_its_domain_is_a_clean_error(tmp_path, fits_json, changes, message):
    res, out = _convert(tmp_path, json.dumps(_edit(fits_json, **changes)))
    assert res.exit_code == 1, res.output
    assert message in res.output and "Traceback" not in res.output
    assert not out.exists()


@pytest.mark.parametrize(
    "token,field",
    [("NaN", "n_points"), ("Infinity", "n_points"), ("Infinity", "n"), ("[0, Infinity]", "suction_range_kPa")],
)
def test_nan_and_infinity_tokens_are_not_json(tmp_path, fits_json, token, field):
    """Python's json writes NaN and Infinity; they are not JSON (RFC 8259), and capred never writes them."""
    marker = "__MARK__"
    changes = {f"si_{field}" if field == "n" else field: marker}
    if field == "suction_range_kPa":
        changes["suction_points_kPa"] = None
    text = json.dumps(_edit(fits_json, **changes)).replace(f'"{marker}"', token)
    res, out = _convert(tmp_path, text)
    assert res.exit_code == 1 and "not valid JSON" in res.output and "Traceback" not in res.output
    assert not out.exists()


def test_deep_nesting_is_refused_cleanly(tmp_path):
    res, out = _convert(tmp_path, "[" * 100_000 + "]" * 100_000)
    assert res.exit_code == 1 and "not valid JSON" in res.output and "Traceback" not in res.output


def test_a_file_over_the_size_limit_is_refused_before_it_is_read(tmp_path, fits_json):
    """--max-megabytes 1 on a 2 MiB file (valid JSON padded with spaces)."""
    src = tmp_path / "fits.json"
    src.write_text(json.dumps(fits_json) + " " * (2 * 2**20), encoding="utf-8")
    out = tmp_path / "o"
    res = runner.invoke(app, ["retention-convert", str(src), "--to", "bc", "--out", str(out), "--max-megabytes", "1"])
    assert res.exit_code == 1 and "--max-megabytes" in res.output and "Traceback" not in res.output
    assert not out.exists()


def test_the_untouched_file_converts(tmp_path, fits_json):
    res, out = _convert(tmp_path, json.dumps(fits_json))
    assert res.exit_code == 0, res.output
    assert (out / "fits.json").exists()


def test_the_api_checks_a_dict_as_it_checks_a_file(fits_json):
    """capred.convert_retention(dict) with n = inf (a Python float, which JSON cannot hold)."""
    import capred
    from capred.errors import OptionError

    with pytest.raises(OptionError, match="must be finite"):
        capred.convert_retention(_edit(fits_json, si_n=float("inf")), to="bc")
