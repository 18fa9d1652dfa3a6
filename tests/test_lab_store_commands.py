"""Every command of the registry records its lab-store rows from its declarations (Result.store_rows).

One test over capred.reductions.REDUCTIONS: a new command without ``store_rows`` fails it. Each command's quick
run (the sample with the registry's example options) is recorded through the API into a store; the store holds
exactly the rows ``store_rows`` declares, each value equal to the number the run's JSON document gives under
the same key (the conformance "store = API"), each unit the glossary's where the key is a glossary quantity's.
"""

from __future__ import annotations

import math

import pytest

import capred
from capred.lab_store import history, record_run, rows_of
from capred.nomenclature import QUANTITIES, json_key
from capred.reductions import REDUCTIONS

#: commands that refuse to be recorded, with the reason their store_rows gives
REFUSED = {"history": "reads a lab store"}

#: JSON key -> unit of every glossary quantity (its standard error in the same unit)
GLOSSARY_UNITS = {
    json_key(n, s): (q.unit if q.unit not in ("", "-") else "-") for n, q in QUANTITIES.items() for s in ("", "_se")
}


def _numbers(doc, path=()):
    """(path of keys, number) of every number of a JSON document, nested dicts entered."""
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from _numbers(v, (*path, str(k)))
    elif isinstance(doc, (int, float)) and not isinstance(doc, bool):
        yield path, float(doc)


def _in_document(doc, quantity: str, value: float) -> bool:
    """The document gives ``value`` under ``quantity`` (``model.key``: the key in the model's object)."""
    parts = quantity.split(".")
    for path, v in _numbers(doc):
        if len(path) > 1 and path[-1] in ("value", "se"):  # a fitted parameter: {"value": ..., "se": ...}
            path = (*path[:-2], path[-2] + ("_se" if path[-1] == "se" else ""))
        if tuple(path[-len(parts) :]) == tuple(parts) and math.isclose(v, value, rel_tol=1e-12, abs_tol=0.0):
            return True  # the same float written to JSON: equal to its last digit but for rounding of a product
    return False


def _result(red):
    source = capred.sample_path(red.sample) if red.sample else None
    return red.run(source, red.options(**dict(red.example)))


@pytest.mark.parametrize("command", [c for c in REDUCTIONS if c not in REFUSED])
def test_every_command_records_its_declared_rows(command, tmp_path):
    red = REDUCTIONS[command]
    res = _result(red)
    declared = res.store_rows(None)
    assert declared is not None, f"`capred {command}` declares no lab-store rows (Result.store_rows)"
    doc = res.to_json()
    for row in declared:
        assert row.unit is not None and row.unit != "", row
        if row.quantity in GLOSSARY_UNITS:  # a glossary quantity's key: the glossary's unit
            assert row.unit == GLOSSARY_UNITS[row.quantity], row
        assert _in_document(doc, row.quantity, row.value), f"{row.quantity} = {row.value} is not in the JSON"
        if row.ci_low is not None:
            assert row.ci_low <= row.value <= row.ci_high, row
    store = tmp_path / "lab.sqlite"
    record_run(store, res)
    if not declared:
        return
    frame = history(store)
    stored = list(
        zip(frame["material"], frame["quantity"], frame["value"], frame["ci_low"], frame["ci_high"], frame["unit"])
    )
    assert len(stored) == len(declared)
    for got, want in zip(stored, declared):
        assert got[:3] == tuple(want)[:3] and got[5] == want.unit
        for g, w in zip(got[3:5], (want.ci_low, want.ci_high)):
            assert (w is None and math.isnan(g)) or g == w


@pytest.mark.parametrize("command", list(REFUSED))
def test_a_command_that_is_never_recorded_says_why(command):
    res = _result(REDUCTIONS[command])
    with pytest.raises(ValueError, match=REFUSED[command]):
        res.store_rows(None)


def test_a_result_without_declared_rows_is_not_recorded_from_its_json(tmp_path):
    """The JSON walk is gone: a result that declares no rows is refused, its document is not read back."""
    from capred.result import Result

    class Bare(Result):
        command = "bare"

        def to_json(self):  # pragma: no cover - must not be read
            raise AssertionError("the store read the JSON document")

    with pytest.raises(ValueError, match="declares no lab-store rows"):
        rows_of(Bare())


def test_shear_band_angles_are_recorded_in_degrees(tmp_path):
    """capred shear-band once recorded its angles with no unit (the JSON walk knew no 'coulomb_deg'): the
    glossary's shear_band_angle gives deg; Coulomb's angle 45 + phi'/2 = 45 + 31.5/2 = 60.75 deg."""
    res = _result(REDUCTIONS["shear-band"])
    rows = {r.quantity: r for r in res.store_rows(None)}
    assert rows["coulomb_deg"].value == 60.75 and rows["coulomb_deg"].unit == "deg"
    assert rows["coulomb_minus_measured_deg"].value == 0.75  # measured 60 deg in the registry's example


def test_compression_records_its_estimates_for_history(tmp_path):
    """capred compression once recorded e0 alone: its estimates (C_c, lambda = C_c/ln 10, the yield stresses ...)
    are what a lab charts, each with its interval and standard error in its declared unit."""
    res = _result(REDUCTIONS["compression"])
    rows = {r.quantity: r for r in res.store_rows("clay")}
    est = res.to_json()["estimates"]
    c_c, lam = rows["C_c"], rows["lambda"]
    assert c_c.value == est["C_c"]["value"] and (c_c.ci_low, c_c.ci_high) == tuple(est["C_c"]["ci95"])
    assert c_c.unit == "-" and rows["C_c_se"].value == est["C_c"]["se"]
    assert math.isclose(lam.value, c_c.value / math.log(10), rel_tol=1e-12)
    assert rows["sigma_y_kPa"].unit == "kPa"
