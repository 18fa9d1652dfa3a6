"""report/ reads records, never the JSON document (issue 28 item 1): the console tables of `bridge compare`,
`bridge rupture`, `bridge yade-files`, `history` and `pt-volume` are built from the typed records
(CompareRecord, RuptureRecord, YadeFileRecord, HistoryRecord, PTVolumePoints) with ``to_json``, ``rows``,
``summary_rows`` and the DataFrames blocked, and show the numbers the JSON holds; each column of a record is
declared once, and its JSON key and CSV header follow from that declaration."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import capred
from capred.pipelines.bridge import compare_measured, rupture_distances
from capred.pipelines.bridge_records import CompareRecord, RuptureRecord, YadeFileRecord
from capred.pipelines.history import HistoryRecord, run_history
from capred.pipelines.yade_files import YadeOptions, reduce_yade_files
from capred.report.presenters import console_tables
from capred.report.render import row_table
from capred.result import csv_header

pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")

#: what report/ must not read: the JSON document, its per-row dicts and the output DataFrames
BLOCKED = ("to_json", "json_lazy", "payload", "rows", "summary_rows", "tables", "csv_tables")


def _tables_without_json(result, monkeypatch):
    """The console tables of a result with every JSON- and DataFrame-producing method made to raise."""

    def refuse(*args, **kwargs):
        raise AssertionError("report/ read the JSON document, its rows or a DataFrame")

    for name in BLOCKED:
        if hasattr(result, name):
            monkeypatch.setattr(result, name, refuse)
    tables = console_tables(result)
    monkeypatch.undo()
    return tables


def _same_as_json(table, doc_rows, keys, full_table):
    # the table equals the one row_table builds from the JSON rows: same headers, same formatted numbers
    expected = row_table(table.title, doc_rows, keys, full_table)
    assert [c[0] for c in table.columns] == keys
    assert table.rows == expected.rows


@pytest.fixture(scope="module")
def compare():
    return compare_measured(capred.sample_path("bridge-compare"))


@pytest.fixture(scope="module")
def rupture():
    return rupture_distances(capred.sample_path("bridge-rupture"))


@pytest.fixture(scope="module")
def yade():
    # two small files: 10 distances, 20 suctions each (a run of a few seconds)
    return reduce_yade_files(None, YadeOptions(ratios=(1.0, 2.0), distances=10, suctions=20))


@pytest.fixture(scope="module")
def history():
    return run_history(capred.sample_path("history"), quantity="phi_deg")


def test_bridge_compare_table_from_the_record(compare, monkeypatch):
    table, laws = _tables_without_json(compare, monkeypatch)  # the pairs, then each registry law's residuals
    assert len(laws.rows) == len(compare.record().laws)
    keys = ["case", "F_measured_mN", "F_exact_mN", "F_toroidal_mN", "F_willett_mN", "F_israelachvili_mN", "status"]
    _same_as_json(table, compare.rows(), keys, "compare.csv")
    rec = compare.record()
    assert isinstance(rec, CompareRecord)
    # a residual is the model's force minus the measured one (both in mN): exact to rounding of one subtraction
    ok = np.isfinite(rec.F_exact)
    np.testing.assert_allclose(rec.residual_exact[ok], rec.F_exact[ok] - rec.F_measured[ok], rtol=0, atol=1e-12)
    # the sample's m01 as the console shows it: measured 0.4155 mN (the input file), exact 0.4132 mN
    assert table.rows[0][:3] == ["m01", "0.4155", "0.4132"]


def test_bridge_rupture_table_from_the_record(rupture, monkeypatch):
    (table,) = _tables_without_json(rupture, monkeypatch)
    keys = [
        "case",
        "R_mm",
        "R2_mm",
        "contact_angle_deg",
        "V_w_mm3",
        "D_rupture_mm",
        "D_rupture_lian_mm",
        "ratio_to_lian",
        "status",
    ]
    _same_as_json(table, rupture.rows(), keys, "rupture.csv")
    rec = rupture.record()
    assert isinstance(rec, RuptureRecord)
    # Lian et al. (1993): D_rupture = (1 + θ/2) V^(1/3); θ = 0 and V = 1e-3 mm^3 give 0.1 mm exactly
    i = rupture.rows().index(next(r for r in rupture.rows() if r["case"] == "equal_0deg_1e-3"))
    assert rec.D_rupture_lian[i] == pytest.approx(0.1, rel=1e-12)  # one cube root: rounding only
    assert table.rows[i][6] == "0.1"
    # a plane is the word in the JSON rows and the console, inf in the record (and rupture.csv)
    planes = [j for j, r in enumerate(rupture.rows()) if r["R2_mm"] == "plane"]
    assert planes and all(math.isinf(rec.R2[j]) and table.rows[j][2] == "plane" for j in planes)


def test_yade_table_from_the_record(yade, monkeypatch):
    (table,) = _tables_without_json(yade, monkeypatch)
    keys = ["file", "ratio", "d_star_max", "uc_star_max", "distances", "bridges", "smallest_block"]
    _same_as_json(table, yade.summary_rows(), keys, "yade_files.csv")
    rec = yade.record()
    assert isinstance(rec, YadeFileRecord)
    # each file has the 10 distance blocks asked for, and its bridges are the sum of its blocks
    assert [r[0] for r in table.rows] == ["M(r=1)", "M(r=2)"]
    assert [r[4] for r in table.rows] == ["10", "10"]
    assert list(rec.bridges) == [int(f.counts.sum()) for f in yade.files]


def test_history_table_from_the_record(history, monkeypatch):
    runs, limits = _tables_without_json(history, monkeypatch)
    rows = [
        {**r, "flag": "OUT" if r["beyond_limits"] else ("MR" if r["mr_beyond_limit"] else "")} for r in history.rows()
    ]
    keys = ["run", "test_date", "value", "ci_low", "ci_high", "moving_range", "flag"]
    _same_as_json(runs, rows, keys, "history.csv")
    rec = history.record()
    assert isinstance(rec, HistoryRecord) and rec.unit == "deg"
    # the moving range is |x_i − x_(i−1)| (Montgomery 2013, section 6.4): exact to one subtraction
    np.testing.assert_allclose(rec.moving_range[1:], np.abs(np.diff(rec.value)), rtol=0, atol=1e-12)
    assert math.isnan(rec.moving_range[0]) and runs.rows[0][5] == "—"
    assert [r[0] for r in limits.rows] == ["centre", "sigma", "LCL", "UCL", "MR centre", "MR UCL"]


def test_pt_volume_tables_from_the_records(monkeypatch):
    result = capred.run_pt_volume(capred.sample_path("pt-volume"), capred.PTVolumeOptions(example_kaolin=True))
    doc = result.to_json()
    lines, points, stages = _tables_without_json(result, monkeypatch)
    # the numbers of the JSON, formatted as the console does (4 significant digits)
    from capred.report.render import fmt

    p = doc["parameters"]
    assert lines.rows[0][1:5] == [
        fmt(p["lambda_W"]),
        fmt(p["kappa_W"]),
        fmt(p["e_ncl_W"]),
        fmt(p["reference_stress_kPa"]),
    ]
    for row, r in zip(points.rows, doc["points"]):
        assert row[2:10] == [
            fmt(r[k]) for k in ("sigma_kPa", "suction_kPa", "S_r", "sigma_W_kPa", "sigma_A_kPa", "e", "e_W", "e_A")
        ]
    assert len(points.rows) == 20 and points.total_rows == len(doc["points"]) == 21  # the sample's 21 points
    for row, s in zip(stages.rows, doc["stages"]):
        assert row[0] == s["stage"]
        assert row[2:6] == [fmt(s["S_r_end"]), fmt(s["sigma_W_end_kPa"]), fmt(s["sigma_A_end_kPa"]), fmt(s["e_end"])]
        assert row[6] == fmt(s["de"], sign=True)
    # eq. 1: σ'_W = (σ − u_w) S_r at every shown point, in kPa, to the JSON's rounding
    for r in doc["points"]:
        assert r["sigma_W_kPa"] == pytest.approx((r["sigma_kPa"] - r["u_w_kPa"]) * r["S_r"], rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("record", [CompareRecord, RuptureRecord])
def test_bridge_csv_headers_follow_the_one_rule(record):
    # bridge compare / rupture headers are as before: the JSON key's csv_header (name [unit]), a dimensionless
    # ratio [-], a label or status its key
    values = {f.name: (["a", "b"] if f.name in ("case", "status") else np.zeros(2)) for f in dataclasses.fields(record)}
    if "laws" in values:  # compare: each registered law's force and residual
        values["laws"] = {"toy_law": (np.zeros(2), np.zeros(2))}
    rec = record(**values)
    for key, head in zip(rec.columns(), rec.csv_columns()):
        assert head == {"ratio_to_lian": "ratio_to_lian [-]"}.get(key, csv_header(key))
    assert len(rec) == 2 and rec.json_rows()[1]["status"] == "b"


def test_yade_and_history_csv_headers_carry_units(yade, history):
    assert list(yade.csv_tables()["yade_files"].columns) == [
        "file",
        "ratio [-]",
        "d_star_max [-]",
        "uc_star_max [-]",
        "distances [-]",
        "bridges [-]",
        "smallest_block [-]",
    ]
    assert list(history.csv_tables()["history"].columns) == [
        "run",
        "test_date",
        "input",
        "value [deg]",
        "ci_low [deg]",
        "ci_high [deg]",
        "moving_range [deg]",
        "beyond_limits",
        "mr_beyond_limit",
    ]
    # JSON keys are unchanged
    assert list(history.rows()[0]) == [
        "run",
        "test_date",
        "input",
        "value",
        "ci_low",
        "ci_high",
        "moving_range",
        "beyond_limits",
        "mr_beyond_limit",
    ]


@pytest.mark.parametrize("name", ["compare", "rupture", "history"])
def test_figures_from_the_records(name, compare, rupture, history, monkeypatch):
    # the compare and rupture sheets and the control chart take their numbers from the records too
    from capred.report.presenters import figures

    result = {"compare": compare, "rupture": rupture, "history": history}[name]

    def refuse(*args, **kwargs):
        raise AssertionError("report/ read the JSON document, its rows or a DataFrame")

    for blocked in BLOCKED:
        if hasattr(result, blocked):
            monkeypatch.setattr(result, blocked, refuse)
    sheets = figures(result)
    monkeypatch.undo()
    assert list(sheets) == [{"compare": "compare", "rupture": "rupture", "history": "control_chart"}[name]]


def test_pt_volume_stage_record():
    result = capred.run_pt_volume(capred.sample_path("pt-volume"), capred.PTVolumeOptions(example_kaolin=True))
    rec = result.stage_record()
    # stages.csv headers as before: labels and lines plain, stresses [kPa], the rest dimensionless [-]
    assert list(rec.csv_columns()) == [
        "stage",
        "first_step [-]",
        "last_step [-]",
        "first_line",
        "last_line",
        "e_end [-]",
        "de [-]",
        "de_W [-]",
        "de_A [-]",
        "S_r_end [-]",
        "sigma_W_end [kPa]",
        "sigma_A_end [kPa]",
    ]
    # Δe of a run is e at its last point minus e at the point before it (the first point for the first run),
    # and the runs' Δe add up to e_final − e_initial: exact to the rounding of a few subtractions
    e = result.points.e
    assert rec.de[0] == pytest.approx(e[result.stages[0].last] - e[0], abs=1e-12)
    assert sum(rec.de) == pytest.approx(e[result.stages[-1].last] - e[0], abs=1e-12)
    assert rec.json_rows() == result.to_json()["stages"]
