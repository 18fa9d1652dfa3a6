"""JSON inputs bounded in size and nesting (capred.io.json_input; shear --retention)."""

import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.errors import InputError, LimitError
from capred.io.grid import ReadLimits
from capred.io.json_input import MAX_JSON_DEPTH, json_depth, read_json

runner = CliRunner()


def test_depth_by_hand():
    assert json_depth(1) == 0
    assert json_depth([]) == 1
    assert json_depth({"a": [1, {"b": [2]}]}) == 4  # object > array > object > array


def test_deep_nesting_is_refused_without_recursion_error(tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000)  # Python's parser alone raises RecursionError
    with pytest.raises(InputError, match=f"nested more than {MAX_JSON_DEPTH} deep"):
        read_json(path, "--retention")
    path.write_text("[" * (MAX_JSON_DEPTH + 1) + "]" * (MAX_JSON_DEPTH + 1))
    with pytest.raises(InputError, match="nested"):
        read_json(path, "--retention")
    path.write_text("[" * MAX_JSON_DEPTH + "]" * MAX_JSON_DEPTH)
    assert json_depth(read_json(path, "--retention")) == MAX_JSON_DEPTH


def test_size_is_refused_before_reading(tmp_path):
    path = tmp_path / "big.json"
    path.write_text("[" + "0," * 600_000 + "0]")  # 1.2 MB
    with pytest.raises(LimitError, match="--max-megabytes"):
        read_json(path, "--retention", ReadLimits(max_bytes=2**20))


def test_shear_retention_json_too_deep_is_one_message(tmp_path):
    import capred

    fits = tmp_path / "fits.json"
    fits.write_text('{"fits": ' + "[" * 5000 + "]" * 5000 + "}")
    res = runner.invoke(
        app, ["shear", str(capred.sample_path("shear")), "--retention", str(fits), "--bootstrap", "0", "--no-plots",
              "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code != 0 and "nested more than" in res.stderr and "Traceback" not in res.output, res.output
    assert not (tmp_path / "o").exists()


def test_toml_manifest_nested_deeper_than_the_limit_is_one_message(tmp_path):
    """tomllib parses by recursion: 50,000 nested arrays raised RecursionError through `capred batch`."""
    manifest = tmp_path / "m.toml"
    manifest.write_text('[[run]]\ncommand = "shear"\ninput = "a.csv"\noptions = ' + "[" * 50_000 + "]" * 50_000 + "\n")
    res = runner.invoke(app, ["batch", str(manifest), "--out", str(tmp_path / "o")])
    assert res.exit_code != 0 and "nested more than" in res.stderr and "Traceback" not in res.output, res.output


def _padded_json(path, megabytes: float) -> None:
    """A JSON object of ``megabytes`` MB, most of it blanks (valid JSON whatever its content)."""
    path.write_text('{"pad": 0' + " " * int(megabytes * 2**20) + "}")


def test_shear_retention_json_honours_max_megabytes(tmp_path):
    """--max-megabytes 1 reaches --retention's JSON (it was read up to the 256 MiB default): a 1.5 MiB file is
    refused before it is read, naming the option, with nothing written."""
    import capred

    fits = tmp_path / "fits.json"
    _padded_json(fits, 1.5)
    res = runner.invoke(
        app, ["shear", str(capred.sample_path("shear")), "--retention", str(fits), "--max-megabytes", "1",
              "--bootstrap", "0", "--no-plots", "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code == 1 and "--retention" in res.stderr and "--max-megabytes" in res.stderr, res.output
    assert "1.5 MiB" in res.stderr and "Traceback" not in res.output
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "args",
    [
        pytest.param(["skempton-b", "--sample", "--compression", "{json}"], id="skempton-b --compression"),
        pytest.param(["shear-band", "--triaxial", "{json}"], id="shear-band --triaxial"),
        pytest.param(["pt-volume", "--sample", "--compression-w", "{json}"], id="pt-volume --compression-w"),
    ],
)
def test_every_json_input_refuses_deep_nesting_in_one_message(tmp_path, args):
    """100,000 nested arrays (Python's parser alone raises RecursionError): one message, exit 1, nothing
    written, for each command that reads a JSON of another run."""
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    args = [a.replace("{json}", str(deep)) for a in args]
    res = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "nested more than" in res.stderr, res.output
    assert "Traceback" not in res.output and not (tmp_path / "o").exists()


def test_skempton_compression_json_honours_max_megabytes(tmp_path):
    """skempton-b's --compression is read within the run's --max-megabytes (a table given: its limits)."""
    import capred

    big = tmp_path / "compression.json"
    _padded_json(big, 1.5)
    res = runner.invoke(
        app, ["skempton-b", str(capred.sample_path("skempton-b")), "--compression", str(big), "--max-megabytes", "1",
              "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code == 1 and "--max-megabytes" in res.stderr and "1.5 MiB" in res.stderr, res.output
    assert not (tmp_path / "o").exists()


def test_skempton_retention_json_honours_max_megabytes(tmp_path):
    """skempton-b's --retention (a fits.json, read by retention-convert's reader, 16 MiB by default) within the
    run's --max-megabytes: a 1.5 MiB file is refused under --max-megabytes 1, naming its size."""
    import capred

    fits = tmp_path / "fits.json"
    _padded_json(fits, 1.5)
    res = runner.invoke(
        app, ["skempton-b", str(capred.sample_path("skempton-b")), "--retention", str(fits), "--max-megabytes", "1",
              "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code == 1 and "1.5 MiB, more than the 1 MiB" in res.stderr, res.output
    assert not (tmp_path / "o").exists()


def test_pt_volume_compression_json_honours_max_megabytes(tmp_path):
    """pt-volume's --compression-w is read within the run's --max-megabytes (it was read as the options were built,
    always within the 256 MiB default): a 1.5 MiB file is refused under --max-megabytes 1, naming the file and the
    limit, with nothing written."""
    big = tmp_path / "compression.json"
    _padded_json(big, 1.5)
    res = runner.invoke(
        app, ["pt-volume", "--sample", "--compression-w", str(big), "--max-megabytes", "1",
              "--out", str(tmp_path / "o")],
    )  # fmt: skip
    assert res.exit_code == 1 and "--max-megabytes" in res.stderr and "1.5 MiB" in res.stderr, res.output
    assert str(big) in res.stderr and "limit of 1 MiB" in res.stderr and "Traceback" not in res.output
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    "args",
    [
        pytest.param(["skempton-b", "--S-R", "0.9", "--compression", "{json}"], id="skempton-b --compression"),
        pytest.param(["skempton-b", "--S-R", "0.9", "--retention", "{json}"], id="skempton-b --retention"),
        pytest.param(["shear-band", "--triaxial", "{json}", "--dilatancy-angle", "8"], id="shear-band --triaxial"),
    ],
)
def test_json_inputs_of_a_run_without_a_table_honour_max_megabytes(tmp_path, args):
    """A run from options only has no table to carry --max-megabytes: the CLI states it for the run (run_limits),
    so a 1.5 MiB JSON input is refused under --max-megabytes 1, naming the file and its size, nothing written."""
    big = tmp_path / "input.json"
    _padded_json(big, 1.5)
    args = [a.replace("{json}", str(big)) for a in args]
    res = runner.invoke(app, [*args, "--max-megabytes", "1", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1 and "--max-megabytes" in res.stderr and "1.5 MiB" in res.stderr, res.output
    assert str(big) in res.stderr and "Traceback" not in res.output
    assert not (tmp_path / "o").exists()


def test_run_limits_reach_a_python_run_without_a_table(tmp_path):
    """From Python: ``run_limits`` states the limits of a run with no table (the reader's default is 256 MiB)."""
    from capred.io import run_limits
    from capred.pipelines.calculators import ShearBandOptions, reduce_shear_band

    big = tmp_path / "summary.json"
    _padded_json(big, 1.5)
    opt = ShearBandOptions(triaxial=str(big), dilatancy_angle=8.0)
    with run_limits(ReadLimits(max_bytes=2**20)), pytest.raises(LimitError, match="1.5 MiB"):
        reduce_shear_band(None, opt)
