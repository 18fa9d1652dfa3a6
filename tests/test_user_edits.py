"""A single run's folder is hash-protected like a batch root: a file a user edited is never replaced silently."""

import json

import pytest

import capred


def _run(out):
    return capred.write_outputs(
        capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0)), out, plots=False, html=False
    )


def test_provenance_records_each_output_hash(tmp_path):
    import hashlib

    out = tmp_path / "o"
    _run(out)
    prov = json.loads((out / "provenance.json").read_text())
    hashes = prov["outputs_sha256"]
    assert set(hashes) == set(prov["outputs"]) - {"provenance.json"}
    for name, digest in hashes.items():  # the hash of the bytes on disk, checkable with sha256sum
        assert hashlib.sha256((out / name).read_bytes()).hexdigest() == digest


def test_a_line_appended_to_a_result_is_not_overwritten(tmp_path):
    out = tmp_path / "o"
    _run(out)
    csv = sorted(out.glob("*.csv"))[0]
    edited = csv.read_bytes() + b"my note,added by hand\n"
    csv.write_bytes(edited)
    with pytest.raises(capred.OutputError, match=rf"{csv.name} changed since capred wrote it"):
        _run(out)
    assert csv.read_bytes() == edited  # the user's line is still there
    assert not [p for p in tmp_path.iterdir() if ".capred-" in p.name]


def test_an_unedited_folder_is_replaced(tmp_path):
    out = tmp_path / "o"
    _run(out)
    _run(out)  # the same files, unchanged: capred's to replace
    assert (out / "provenance.json").exists()


def test_outputs_over_their_bound_are_refused_before_writing(tmp_path, monkeypatch):
    """The bound is stated (100 x the inputs, 512 MiB to 4 GiB, or $CAPRED_MAX_OUTPUT_MEGABYTES): a tiny one set
    here refuses the sample's run, saying how large its tables would be, with nothing written."""
    from capred.io import writers

    assert writers.output_budget(1000) == writers.OUTPUT_FLOOR
    assert writers.output_budget(20 * 2**20) == 100 * 20 * 2**20
    assert writers.output_budget(250 * 2**20) == writers.OUTPUT_MAX  # 250 MB of rows wrote 7.5 GB before
    monkeypatch.setenv("CAPRED_MAX_OUTPUT_MEGABYTES", "0.001")  # 1 kB
    with pytest.raises(capred.OutputError, match="table cells") as info:
        _run(tmp_path / "o")
    assert "CAPRED_MAX_OUTPUT_MEGABYTES" in str(info.value)
    assert not (tmp_path / "o").exists() and not list(tmp_path.iterdir())
