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
