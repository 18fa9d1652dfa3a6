"""Defects found by trying capred as a new lab user would, on tables shaped as labs keep them (a 'Test no' id
column, a metadata block, every dry test at its own normal stress, one dry outlier): each test fails without
its fix."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

import capred


def _shear_file(tmp_path):
    """Dry tests each at its own sigma_N on tau = 2 + sigma_N tan 33 deg (4 % scatter), test 8 sheared 60 %
    high; wet tests with suction and S_R given; a metadata block above the header."""
    rng = np.random.default_rng(1)
    tan_phi = np.tan(np.radians(33.0))
    lines = ["Project:,Dike A", "Operator:,J. Doe", "", "Test no,material,condition,sigma_N [kPa],tau_max [kPa],"]
    lines[-1] += "suction [kPa],S_R,R [mm]"
    for i, s in enumerate(np.linspace(10, 200, 12)):
        tau = (2.0 + s * tan_phi) * (1 + 0.04 * rng.standard_normal()) * (1.6 if i == 7 else 1.0)
        lines.append(f"{i + 1},silty sand,dry,{s:.2f},{tau:.3f},,,0.1")
    for k, (s, u, S) in enumerate([(25, 5, 0.8), (50, 10, 0.6), (100, 20, 0.4), (150, 40, 0.2)]):
        tau = (2.0 + (s + S * u) * tan_phi) * (1 + 0.04 * rng.standard_normal())
        lines.append(f"{13 + k},silty sand,wet,{s},{tau:.3f},{u},{S},0.1")
    path = tmp_path / "shear.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def _huber_run(tmp_path):
    opts = capred.ShearOptions(models=("bishop",), bootstrap=0, dry_loss="huber", errors="proportional")
    with pytest.warns(capred.CapredWarning):
        return capred.run_shear(_shear_file(tmp_path), opts)


def test_dry_outlier_is_named_by_the_labs_test_id(tmp_path):
    # the console, the JSON and the warnings named the outlier by its file line only; the lab knows it as
    # test no. 8
    r = _huber_run(tmp_path)
    out = r.to_json()["materials"]["silty sand"]["outliers"]
    assert [o["test_id"] for o in out] == ["8"]
    line = out[0]["line"]
    assert any(f"dry test '8' (line {line})" in w for w in r.warnings)
    from capred.report.shear_tables import shear_tables

    dry = shear_tables(r)[0]
    assert dry.rows[0][[h for h, _ in dry.columns].index("outliers")] == f"8 (line {line})"


def test_report_explains_the_dry_outlier_flag_and_the_loss(tmp_path):
    from capred.report.html import _flags

    r = _huber_run(tmp_path)
    meaning = dict((f, m) for f, _, m in _flags(r))
    assert meaning["dry_outlier"]  # the flag table of report.html had an empty meaning for it
    methods = " ".join(" ".join(p) for p in r.method_notes())
    assert "fitted by least squares with standard errors" not in methods  # it was fitted by Huber's loss
    assert "Huber" in methods


def test_group_mohr_circles_log_nothing_on_the_console(caplog):
    # matplotlib logged "Ignoring fixed x limits to fulfill fixed data aspect ..." on every run with groups
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from capred.report.triaxial_figures import plot_group_circles

    r = capred.run_triaxial_bounds(capred.sample_path("triaxial-groups"))
    fig = Figure()
    ax = fig.add_subplot()
    with caplog.at_level(logging.WARNING, logger="matplotlib"):
        plot_group_circles(ax, r)
        FigureCanvasAgg(fig).draw()  # the aspect is applied, and logged, at drawing
    assert not [rec for rec in caplog.records if "Ignoring fixed" in rec.getMessage()]
    assert ax.get_xlim()[0] == 0 and ax.get_ylim()[0] == 0  # the limits kept


def test_retention_runs_are_recorded_in_the_lab_store(tmp_path):
    from capred.lab_store import history, record_run

    def vg(s, a, n, tr=0.05, ts=0.38):
        return tr + (ts - tr) * (1 + (a * s) ** n) ** -(1 - 1 / n)

    s = np.array([0.5, 1, 2, 4, 6, 8, 10, 15, 20, 30, 50, 80, 120, 200, 500])
    frame = pd.DataFrame({"suction [kPa]": s, "theta": vg(s, 0.12, 1.9), "branch": "drying"})
    r = capred.run_retention(frame, capred.RetentionOptions(models=("vg",)))
    store = tmp_path / "lab.sqlite"
    record_run(store, r)
    rec = history(store)
    vg_fit = r.to_json()["branches"]["drying"]["fits"]["vg"]
    alpha = rec[(rec["material"] == "drying") & (rec["quantity"] == "vg.alpha_per_kPa")]
    assert len(alpha) == 1  # retention runs recorded no quantity at all
    # the stored number is the JSON's, to the last bit
    assert alpha["value"].iloc[0] == vg_fit["alpha_per_kPa"]
    assert alpha["unit"].iloc[0] == "1/kPa"  # not 'kPa'
    assert (alpha["ci_low"].iloc[0], alpha["ci_high"].iloc[0]) == tuple(vg_fit["alpha_per_kPa_ci95"])
    n = rec[rec["quantity"] == "vg.n"]  # van Genuchten's n is a parameter here, not a count
    assert n["value"].iloc[0] == vg_fit["n"]
    # exact synthetic curve: the fit returns the generating alpha to the optimiser's tolerance (1e-6 relative)
    assert alpha["value"].iloc[0] == pytest.approx(0.12, rel=1e-4)


def test_querying_a_store_leaves_no_side_files(tmp_path):
    # a store capred records into is in WAL mode; the read-only (mode=ro) connection of `capred history`
    # created lab.sqlite-wal and lab.sqlite-shm and could not remove them
    import hashlib

    from capred.lab_store import history, record_run

    store = tmp_path / "lab.sqlite"
    opts = capred.ShearOptions(models=("bishop",), bootstrap=0)
    with pytest.warns(capred.CapredWarning):
        record_run(store, capred.run_shear(_shear_file(tmp_path), opts))
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["lab.sqlite", "shear.csv"]
    before = hashlib.sha256(store.read_bytes()).hexdigest()
    frame = history(store, quantity="phi_deg")
    assert len(frame) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == names
    assert hashlib.sha256(store.read_bytes()).hexdigest() == before  # a query changes nothing
    from capred.lab_store import connect_readonly

    con = connect_readonly(store)
    with pytest.raises(Exception, match="readonly|read-only|query_only"):
        con.execute("DELETE FROM runs")
    con.close()


def test_missing_retention_file_is_reported_as_missing(tmp_path):
    # it said "not a fits.json written by capred retention ([Errno 2] No such file or directory ...)"
    from capred.pipelines.shear import model_params_from_retention

    with pytest.raises(capred.MissingFileError, match="file not found"):
        model_params_from_retention(tmp_path / "fits.json")
    table = tmp_path / "readings.csv"
    table.write_text("suction [kPa],theta\n1,0.3\n")
    with pytest.raises(capred.OptionError, match=r"not JSON: Expecting value, line 1"):
        model_params_from_retention(table)


def test_figure_heading_names_its_input_once(tmp_path):
    # report.html of capred retention read "Figure 1. Water retention curves (ret.csv) (ret.csv)."
    import re

    s = np.array([1.0, 3, 10, 30, 100, 300, 1000])  # 7 readings: a 4-parameter fit needs parameters + 3
    path = tmp_path / "ret.csv"
    theta = 0.05 + 0.33 * (1 + (0.1 * s) ** 2) ** -0.5  # van Genuchten, n = 2
    path.write_text("suction [kPa],theta\n" + "".join(f"{a},{b:.5f}\n" for a, b in zip(s, theta)))
    r = capred.run_retention(path, capred.RetentionOptions(models=("vg",)))
    capred.write_outputs(r, tmp_path / "out", dpi=50)
    page = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    heading = re.search(r"<b>Figure 1\.</b>([^<]*)", page).group(1)
    assert heading.count("ret.csv") == 1, heading


def test_skempton_effective_stress_error_shows_the_values_and_units():
    # p0=100 from a script is 100 Pa: the error said only "p0 - u0 ... must be > 0"
    with pytest.raises(capred.OptionError, match=r"read p0 = 0\.1 kPa, u0 = 30 kPa.*in Pa"):
        capred.run_skempton_b(S_R=0.9, p0=100)
    with pytest.raises(capred.OptionError, match=r"read p0 = 20 kPa, u0 = 30 kPa$"):
        capred.run_skempton_b(S_R=0.9, p0="20 kPa")


def test_dry_tests_only_give_the_envelope_without_empty_tables(tmp_path):
    # a file of dry tests printed two empty wet-test tables (headers, no rows) and said nothing about why
    from capred.report.shear_tables import shear_tables

    lines = _shear_file(tmp_path).read_text().splitlines()
    path = tmp_path / "dry.csv"
    path.write_text("\n".join(line for line in lines if ",wet," not in line) + "\n")
    r = capred.run_shear(path, capred.ShearOptions(bootstrap=0))
    tables = shear_tables(r)
    assert [t.title.split(" ")[0] for t in tables] == ["Dry"]
    assert tables[0].rows[0][1] == "12"  # its 12 dry tests
    assert any("no wet tests" in n for n in r.all_notes())


def test_triaxial_envelope_intervals_in_json_and_in_the_lab_store(tmp_path):
    # Python's envelope.params gave c' and phi' with 95 % intervals, the JSON had none, and a triaxial run
    # recorded nothing in the lab store (its document has no 'materials' block)
    from capred.lab_store import history, record_run

    r = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))
    env = r.to_json()["envelope"]
    par = r.envelope.params
    assert env["c_ci95_kPa"] == list(par["c_kPa"].ci95)
    assert env["phi_ci95_deg"] == list(par["phi_deg"].ci95)
    # the interval is c' -/+ t(0.975, n - 2) se, by hand from the JSON's own se
    from scipy import stats

    t = stats.t.ppf(0.975, env["n"] - 2)  # capred takes t from its own quantile routine: rel 1e-6 covers both
    assert env["c_ci95_kPa"] == pytest.approx([env["c_kPa"] - t * env["c_se_kPa"], env["c_kPa"] + t * env["c_se_kPa"]])
    store = tmp_path / "lab.sqlite"
    record_run(store, r)
    phi = history(store, quantity="phi_deg")
    assert phi["value"].tolist() == [env["phi_deg"]]
    assert (phi["ci_low"].iloc[0], phi["ci_high"].iloc[0]) == tuple(env["phi_ci95_deg"])


def test_one_dry_test_error_reads_in_the_singular():
    # "dry fit impossible: 1 points: at least 3 are needed"
    from capred.errors import FitError
    from capred.fitting.linear import fit_line

    with pytest.raises(FitError, match=r"^1 point: at least 3"):
        fit_line(np.array([10.0]), np.array([8.0]))
    with pytest.raises(FitError, match=r"^2 points: at least 3"):
        fit_line(np.array([10.0, 20.0]), np.array([8.0, 15.0]))


def test_history_warns_when_one_input_is_charted_twice(tmp_path):
    # the same file reduced twice (another --bootstrap) is two runs of the store: the chart counted one
    # measurement twice, with a moving range of 0, and said nothing
    from capred.lab_store import record_run

    path = _shear_file(tmp_path)
    store = tmp_path / "lab.sqlite"
    for reps in (0, 20):
        with pytest.warns(capred.CapredWarning):
            record_run(store, capred.run_shear(path, capred.ShearOptions(models=("bishop",), bootstrap=reps)))
    r = capred.run_history(store, quantity="phi_deg")
    assert list(r.runs["run"]) == [1, 2]
    assert r.runs["moving_range"][1] == 0  # the same phi twice
    assert any("runs 1, 2 reduce the same input" in w for w in r.warnings)
