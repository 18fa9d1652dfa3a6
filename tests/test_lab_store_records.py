"""Issue 42: the lab store takes its rows from the records through their declarations, never from the JSON read
back; each stored quantity's name, value and unit are those of the one declaration the JSON writes it by, and a
number without a declared unit is refused (never given a guessed unit).

The runs are the bundled samples, recorded by the real command line (`--store`, files written); the JSON files
on disk are the run's own output, read here only to check the store against them.
"""

import json
import sqlite3
import warnings

import pytest
from typer.testing import CliRunner

import capred
from capred import lab_store
from capred.cli import app
from capred.errors import CapredWarning
from capred.records import UndeclaredQuantity, store_row

runner = CliRunner()
# the samples warn on purpose (a correlated pair, a parameter at its bound, heteroscedastic scatter)
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")


def _stored(lab, command: str) -> dict:
    """(material, quantity) -> (value, ci_low, ci_high, unit) of the runs of ``command`` in the store."""
    with sqlite3.connect(lab) as con:
        rows = con.execute(
            "SELECT r.material, r.quantity, r.value, r.ci_low, r.ci_high, r.unit FROM records r "
            "JOIN runs u ON u.id = r.run WHERE u.command = ?",
            (command,),
        ).fetchall()
    out = {(m, q): (v, lo, hi, u) for m, q, v, lo, hi, u in rows}
    assert len(out) == len(rows), "a quantity recorded twice for one material"
    return out


def _run(tmp_path, command: str, *extra: str):
    lab = tmp_path / "lab.sqlite"
    out = tmp_path / command
    args = [command, "--sample", "--no-plots", "--no-html", "--out", str(out), "--store", str(lab), *extra]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return lab, out


def test_shear_store_rows_are_the_envelope_records(tmp_path):
    lab, out = _run(tmp_path, "shear", "--bootstrap", "0")
    stored = _stored(lab, "shear")
    materials = json.loads((out / "summary.json").read_text(encoding="utf-8"))["materials"]
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    declared = {"c_kPa": "kPa", "phi_deg": "deg", "tan_phi": "-", "r2": "-", "scatter_kPa": "kPa"}
    declared |= {"c_se_kPa": "kPa", "phi_se_deg": "deg", "tan_phi_se": "-"}
    assert set(stored) == {(m, q) for m in materials for q in declared}  # counts (n) and labels are not recorded
    for m, block in materials.items():
        for q, unit in declared.items():
            value, lo, hi, got_unit = stored[m, q]
            # the same number as the JSON file: both come from one record through one declaration, no rounding
            assert value == block[q] and got_unit == unit
        # the interval of a value is its own; a standard error has none (the JSON walk gave it c's interval)
        assert [stored[m, "c_kPa"][1], stored[m, "c_kPa"][2]] == block["c_ci95_kPa"]
        assert [stored[m, "phi_deg"][1], stored[m, "phi_deg"][2]] == block["phi_ci95_deg"]
        assert stored[m, "c_se_kPa"][1:3] == (None, None)
        # and the Python API's fitted parameters say the same in the same unit (computed by math rather than
        # numpy: equal to a few ulps, hence the relative tolerance of 1e-12)
        params = result.fits[m].params
        for q in ("c_kPa", "phi_deg", "tan_phi"):
            assert stored[m, q][0] == pytest.approx(params[q].value, rel=1e-12)
            assert stored[m, q][3] == params[q].unit


def test_retention_store_rows_are_the_fitted_parameters(tmp_path):
    lab, out = _run(tmp_path, "retention")
    stored = _stored(lab, "retention")
    doc = json.loads((out / "fits.json").read_text(encoding="utf-8"))
    result = capred.run_retention(capred.sample_path("retention"))
    n_params = 0
    for branch, fits in result.fits.items():
        for model, fit in fits.items():
            block = doc["branches"][branch]["fits"][model]
            for p in fit.params.values():
                value, lo, hi, unit = stored[branch, f"{model}.{p.name}"]
                # value and unit: the Parameter's, which the JSON writes too
                assert value == block[p.name] == pytest.approx(p.value, rel=1e-12) and unit == p.unit
                if block[f"{p.name}_ci95"] is not None:
                    assert [lo, hi] == block[f"{p.name}_ci95"]
                n_params += 1
            for stat in ("r2", "aicc"):
                assert stored[branch, f"{model}.{stat}"] == (block[stat], None, None, "-")
    assert n_params > 10  # three models on two branches
    # the sample fits S_R: rmse and rss are dimensionless, van Genuchten's alpha per kPa and per cm of head
    assert stored["drying", "vg.rmse"][3] == stored["drying", "vg.rss"][3] == "-"
    assert stored["drying", "vg.alpha_per_cm"][3] == "1/cm" and stored["drying", "bc.h_b_cm"][3] == "cm"


def test_triaxial_bounds_store_rows_are_the_envelope_record(tmp_path):
    lab, out = _run(tmp_path, "triaxial-bounds")
    stored = _stored(lab, "triaxial-bounds")
    env = json.loads((out / "summary.json").read_text(encoding="utf-8"))["envelope"]
    units = {"c_kPa": "kPa", "phi_deg": "deg", "M": "-", "k_kPa": "kPa", "M_extension": "-"}
    units |= {"k_extension_kPa": "kPa", "c_se_kPa": "kPa", "phi_se_deg": "deg", "r2": "-"}
    assert set(stored) == {(None, q) for q in units}
    for q, unit in units.items():
        assert stored[None, q][0] == env[q] and stored[None, q][3] == unit
    assert list(stored[None, "phi_deg"][1:3]) == env["phi_ci95_deg"]


def test_a_number_without_a_declared_unit_is_refused():
    with pytest.raises(UndeclaredQuantity, match="'mystery'"):
        store_row("sand", "mystery", 1.0, None)
    assert store_row("sand", "n", 2.0, "") == ("sand", "n", 2.0, None, None, "-")  # declared dimensionless
    assert store_row("sand", "c_kPa", float("nan"), "kPa") is None  # nothing to record (JSON null)


def test_an_undeclared_per_material_value_is_flagged_not_stored(tmp_path):
    """A model that reports a per-material value under a key no declaration knows: named in a CapredWarning and
    left out of the store, never recorded with a unit guessed from its spelling (``_s`` is not seconds)."""
    result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions(bootstrap=0))
    material = next(iter(result.fits))
    result.per_material = {material: {"mystery_s": 1.5}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        lab_store.record_run(tmp_path / "lab.sqlite", result)
    assert any(issubclass(w.category, CapredWarning) and "'mystery_s'" in str(w.message) for w in caught)
    stored = _stored(tmp_path / "lab.sqlite", "shear")
    assert (material, "mystery_s") not in stored and (material, "phi_deg") in stored


def test_triaxial_store_rows_are_the_envelope_and_the_fitted_parameters(tmp_path):
    """`capred triaxial` recorded nothing before (its numbers are nested in the JSON); now each material's
    effective envelope and extended Mohr-Coulomb parameters, as its JSON gives them."""
    lab, out = _run(tmp_path, "triaxial")
    stored = _stored(lab, "triaxial")
    materials = json.loads((out / "summary.json").read_text(encoding="utf-8"))["materials"]
    assert {m for m, _ in stored} == set(materials)
    for m, block in materials.items():
        for key, unit in (("c_kPa", "kPa"), ("phi_deg", "deg"), ("c_se_kPa", "kPa"), ("phi_se_deg", "deg")):
            assert stored[m, key] == (block["envelope"][key], None, None, unit)
        for name, p in block["extended_mohr_coulomb"]["params"].items():
            value, lo, hi, _ = stored[m, name]
            assert value == p["value"] and [lo, hi] == p["ci95"]
            assert stored[m, f"{name}_se"][0] == p["se"]
        assert stored[m, "phi_b_deg"][3] == "deg" and stored[m, "tan_phi_b"][3] == "-"


def test_history_flags_runs_recorded_in_another_unit(tmp_path):
    """A store written by an older capred labelled vg.S_s in seconds (its suffix rule): `capred history` charts
    the values as recorded, heads them with the latest run's declared unit and says so; it infers nothing."""
    lab, _ = _run(tmp_path, "retention")
    with sqlite3.connect(lab) as con:  # the older run (recorded first: id 0): the same record, the suffix rule's unit
        (run,) = con.execute("SELECT id FROM runs").fetchone()
        con.execute(
            "INSERT INTO runs (id, run_key, command, created_utc, capred_version, inputs, options, metadata, "
            "document, test_date) SELECT 0, 'older', command, created_utc, capred_version, inputs, options, metadata, document, "
            "'2000-01-01' FROM runs WHERE id = ?",
            (run,),
        )
        con.execute(
            "INSERT INTO records SELECT (SELECT id FROM runs WHERE run_key = 'older'), material, quantity, value, "
            "ci_low, ci_high, CASE quantity WHEN 'vg.S_s' THEN 's' ELSE unit END FROM records WHERE run = ?",
            (run,),
        )
    res = capred.run_history(lab, material="drying", quantity="vg.S_s", reference=1.0, spread=0.1)
    assert res.unit == "-"
    assert any("different units (-, s)" in w for w in res.warnings)


def test_a_run_without_store_rows_is_refused_not_read_from_its_json(tmp_path):
    """A result that declares no store rows is refused with a message naming its command; its JSON document is
    not walked for numbers (capred guesses no quantity and no unit from a key), and the store is not created."""

    class _Run:
        command = "rumpf"

        def to_json(self):
            doc = {"command": "rumpf", "capred_version": "t", "inputs": [], "options": {}}
            return doc | {"p_cap_kPa": -1.5, "mystery_s": 2.0}

    with pytest.raises(ValueError, match="`capred rumpf` declares no lab-store rows"):
        lab_store.record_run(tmp_path / "lab.sqlite", _Run())
    assert not (tmp_path / "lab.sqlite").exists()
