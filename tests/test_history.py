"""A lab's history (capred.lab_store, `capred history`): the SQLite store and the individuals / moving-range chart."""

import json
import math
import multiprocessing
import sqlite3

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred import lab_store as hist
from capred.cli import app
from capred.errors import InputError, OptionError
from capred.pipelines.history import D2, D4, individuals_chart

runner = CliRunner()
# the runs and charts here warn on purpose (a planted out-of-control run, a slightly negative dry cohesion)
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")
G = 9.81
MASSES = (0.0, 77.47, 200.0, 400.0, 700.0, 1000.0)  # g added to a 120 g cap on a 36 cm^2 box (the sample's loads)


def _season_file(path, day: int, phi_deg: float, rng) -> None:
    """Dry direct-shear tests of Toyoura sand whose true friction angle is ``phi_deg``, dated ``day`` of March."""
    rows = [
        f"date: 2026-03-{day:02d}",
        "operator: A. Lab",
        "test_id,material,condition,V_v [cm^3],added_mass [g],cap_mass [g],box_area [cm^2],tau_max [kPa]",
    ]
    for i, m in enumerate(MASSES):
        sigma = (120.0 + m) * 1e-3 * G / 36e-4 / 1e3  # kPa
        tau = sigma * math.tan(math.radians(phi_deg)) + rng.normal(0.0, 0.01)
        rows.append(f"T{i:02d},Toyoura sand,dry,30.5,{m},120.0,36.0,{tau:.4f}")
    path.write_text("\n".join(rows) + "\n")


PLANTED = 15  # the 15th test day: the friction angle shifted by +3 deg (about 10 sigma of the season's spread)


@pytest.fixture(scope="module")
def season(tmp_path_factory):
    """20 runs recorded by `capred batch --store` with 2 workers (concurrent writers); run 15 out of control."""
    root = tmp_path_factory.mktemp("season")
    rng = np.random.default_rng(20260301)
    lines = ["command,input,options"]
    for day in range(1, 21):
        phi = 35.0 + rng.normal(0.0, 0.3) + (3.0 if day == PLANTED else 0.0)
        _season_file(root / f"day{day:02d}.csv", day, phi, rng)
        lines.append(f"shear,day{day:02d}.csv,--bootstrap 0 --no-plots --no-html")
    (root / "season.csv").write_text("\n".join(lines) + "\n")
    store = root / "lab.sqlite"
    res = runner.invoke(
        app, ["batch", str(root / "season.csv"), "--out", str(root / "runs"), "--store", str(store), "--workers", "2"]
    )
    assert res.exit_code == 0, res.output
    return root, store


def test_season_control_chart_flags_the_planted_run(season):
    root, store = season
    out = root / "chart"
    args = ["history", str(store), "--material", "Toyoura sand", "--quantity", "phi_deg", "--out", str(out)]
    res = runner.invoke(app, [*args, "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert len(doc["runs"]) == 20
    dates = [r["test_date"] for r in doc["runs"]]
    assert dates == sorted(dates)  # test order, whatever order the workers recorded in
    flagged = [r for r in doc["runs"] if r["beyond_limits"]]
    planted = next(r for r in doc["runs"] if r["test_date"] == f"2026-03-{PLANTED:02d}")
    # the planted run lies ~3 deg (~10 sigma of the season's spread) above: flagged, and the farthest out.
    # An in-control run may be flagged too (a false alarm: 8 baseline runs estimate sigma loosely; with this
    # seed the 11th day, 2.8 true sigma above, is), so the test does not ask that no other run is.
    assert planted["beyond_limits"] and planted["run"] in doc["flagged_runs"]
    assert doc["flagged_runs"] == [r["run"] for r in flagged]
    centre = doc["limits"]["centre"]
    assert max(doc["runs"], key=lambda r: abs(r["value"] - centre)) is planted
    assert any(
        f"run {planted['run']} (2026-03-15" in w and "above the upper control limit" in w for w in doc["warnings"]
    )
    # each run carries its 95 % interval from the shear fit
    assert all(r["ci_low"] < r["value"] < r["ci_high"] for r in doc["runs"])
    # limits from the first 8 runs (in test order), sigma = mean moving range / 1.128: recomputed here
    x = np.array([r["value"] for r in doc["runs"]])
    mr = np.abs(np.diff(x[:8]))
    assert doc["limits"]["centre"] == pytest.approx(x[:8].mean(), rel=1e-12)
    assert doc["limits"]["ucl"] == pytest.approx(x[:8].mean() + 3 * mr.mean() / 1.128, rel=1e-12)
    for name in ("history.csv", "control_chart.png", "history.json", "report.html", "provenance.json"):
        assert (out / name).exists(), name
    # the console: the table of runs and the flag
    res = runner.invoke(app, args[:6])
    assert res.exit_code == 0 and "OUT" in res.stdout and "Control limits" in res.stdout


def test_season_api_dataframe(season):
    _, store = season
    frame = capred.history(store, material="Toyoura sand", quantity="phi_deg")
    assert len(frame) == 20 and set(frame["command"]) == {"shear"}
    assert list(frame.columns[:4]) == ["run", "test_date", "created_utc", "command"]
    assert frame["sha256"].nunique() == 20 and (frame["unit"] == "deg").all()
    res = capred.run_history(store, material="Toyoura sand", quantity="phi_deg")
    assert len(res.flagged) >= 1 and res.runs["value"][res.runs["beyond"]].max() > 37
    # the store keeps the provenance: the metadata block and the options of each run
    con = sqlite3.connect(store)
    meta, options = con.execute("SELECT metadata, options FROM runs LIMIT 1").fetchone()
    con.close()
    assert json.loads(meta)["operator"] == "A. Lab" and json.loads(options)["bootstrap"] == 0


def test_run_recorded_twice_is_stored_once(tmp_path):
    rng = np.random.default_rng(1)
    _season_file(tmp_path / "a.csv", 1, 35.0, rng)
    store = tmp_path / "lab.sqlite"
    for out in ("o1", "o2"):
        res = runner.invoke(
            app,
            ["shear", str(tmp_path / "a.csv"), "--bootstrap", "0", "--no-plots", "--no-html", "--out",
             str(tmp_path / out), "--store", str(store)],
        )  # fmt: skip
        assert res.exit_code == 0, res.output
    assert len(capred.history(store)["run"].unique()) == 1
    # other options: another run
    res = runner.invoke(
        app,
        ["shear", str(tmp_path / "a.csv"), "--bootstrap", "0", "--gamma-w", "9.8", "--no-plots", "--no-html", "--out",
         str(tmp_path / "o3"), "--store", str(store)],
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    assert len(capred.history(store)["run"].unique()) == 2


def test_store_from_environment(tmp_path, monkeypatch):
    rng = np.random.default_rng(2)
    _season_file(tmp_path / "a.csv", 2, 35.0, rng)
    store = tmp_path / "env.sqlite"
    monkeypatch.setenv("CAPRED_STORE", str(store))
    result = capred.run_shear(tmp_path / "a.csv", capred.ShearOptions(bootstrap=0))
    capred.write_outputs(result, tmp_path / "o", plots=False, html=False)
    assert capred.history(store, quantity="phi_deg")["material"].tolist() == ["Toyoura sand"]


@pytest.mark.parametrize(
    "make,message",
    [
        (lambda p: p.write_text("run,phi\n1,35\n"), "not a SQLite database"),
        (lambda p: _foreign(p), "another application's SQLite database"),
        (lambda p: _damaged(p), "damaged"),
        (lambda p: _newer(p), "newer capred"),
    ],
)
def test_foreign_or_damaged_store_is_an_error_and_untouched(tmp_path, make, message):
    store = tmp_path / "lab.sqlite"
    make(store)
    before = store.read_bytes()
    rng = np.random.default_rng(3)
    _season_file(tmp_path / "a.csv", 3, 35.0, rng)
    res = runner.invoke(
        app,
        ["shear", str(tmp_path / "a.csv"), "--bootstrap", "0", "--no-plots", "--out", str(tmp_path / "o"), "--store",
         str(store)],
    )  # fmt: skip
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert message in res.stderr and str(store) in res.stderr
    assert store.read_bytes() == before
    assert not (tmp_path / "o").exists()  # checked before any file is written
    res = runner.invoke(app, ["history", str(store), "--quantity", "phi_deg"])
    assert res.exit_code == 1 and message in res.stderr
    assert store.read_bytes() == before


def _foreign(path):
    con = sqlite3.connect(path)
    con.execute("CREATE TABLE samples (id INTEGER, phi REAL)")
    con.execute("INSERT INTO samples VALUES (1, 35.0)")
    con.commit()
    con.close()


def _store_v(path, version):
    con = sqlite3.connect(path)
    for sql in hist.MIGRATIONS[0]:
        con.execute(sql)
    con.execute(f"PRAGMA application_id = {hist.APPLICATION_ID}")
    con.execute(f"PRAGMA user_version = {version}")
    con.commit()
    return con


def _newer(path):
    _store_v(path, hist.SCHEMA_VERSION + 1).close()


def _damaged(path):
    _foreign(path)
    data = bytearray(path.read_bytes())
    data[100:4096] = b"\xff" * (4096 - 100)  # the first page's b-tree header and cells overwritten
    path.write_bytes(bytes(data))


def test_migration_from_schema_1(tmp_path):
    """A store of schema 1 (no test_date column, no index) is migrated in place and keeps its runs."""
    store = tmp_path / "old.sqlite"
    con = _store_v(store, 1)
    con.execute(
        "INSERT INTO runs (run_key, command, created_utc, capred_version, inputs, options, metadata, document) "
        "VALUES ('k1', 'shear', '2026-01-05T10:00:00+00:00', '0.0.9', '[]', '{}', ?, '{}')",
        (json.dumps({"date": "2025-12-24"}),),
    )
    con.execute(
        "INSERT INTO runs (run_key, command, created_utc, capred_version, inputs, options, metadata, document) "
        "VALUES ('k2', 'shear', '2026-01-06T10:00:00+00:00', '0.0.9', '[]', '{}', '{}', '{}')"
    )
    con.execute("INSERT INTO records VALUES (1, 'sand', 'phi_deg', 35.1, 34.5, 35.7, 'deg')")
    con.execute("INSERT INTO records VALUES (2, 'sand', 'phi_deg', 35.3, NULL, NULL, 'deg')")
    con.commit()
    con.close()
    con = hist.connect(store)
    assert con.execute("PRAGMA user_version").fetchone()[0] == hist.SCHEMA_VERSION == 2
    con.close()
    frame = capred.history(store, quantity="phi_deg")
    assert frame["test_date"].tolist() == ["2025-12-24", "2026-01-06"]  # the metadata date, else the day recorded
    assert frame["value"].tolist() == [35.1, 35.3]


def _record_many(args):
    store, k = args

    class _R:
        command = "rumpf"

        def store_rows(self, material=None):  # the rows a Result declares: p_cap in kPa
            from capred.records import store_row

            return [store_row(material, "p_cap_kPa", self.to_json()["p_cap_kPa"], "kPa")]

        def to_json(self):
            return {"command": "rumpf", "capred_version": "t", "inputs": [], "options": {"k": k}, "p_cap_kPa": -k}

    for j in range(5):
        _R.to_json = lambda self, j=j: {
            "command": "rumpf",
            "capred_version": "t",
            "inputs": [],
            "options": {"k": k, "j": j},
            "p_cap_kPa": -(k * 10 + j),
        }
        hist.record_run(store, _R())
    return k


def test_concurrent_writers_never_corrupt(tmp_path):
    """Four processes record 5 runs each at once into a new store: 20 runs, every record, integrity ok."""
    store = str(tmp_path / "lab.sqlite")
    # fresh interpreters (spawn): a fork of the test process inherits whatever threads and locks earlier tests left
    # (one full-suite run under load hung here with forked workers); a timeout turns any hang into a failure
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(4) as pool:
        done = pool.map_async(_record_many, [(store, k) for k in range(4)]).get(timeout=300)
    assert sorted(done) == [0, 1, 2, 3]
    frame = capred.history(store, quantity="p_cap_kPa")
    assert sorted(frame["value"]) == sorted(-(k * 10 + j) for k in range(4) for j in range(5))
    con = sqlite3.connect(store)
    assert con.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    assert con.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    con.close()


def test_individuals_chart_by_hand():
    # x = 10, 12, 11, 13, 12, 11, 10, 12: MR = 2, 1, 2, 1, 1, 1, 2 (mean 10/7); centre 91/8 = 11.375;
    # sigma = (10/7)/1.128 = 1.26646; UCL = 11.375 + 3 sigma = 15.1744; LCL = 7.5756; MR UCL = 3.267 * 10/7
    x = [10, 12, 11, 13, 12, 11, 10, 12, 16, 11]
    lim, mr, beyond, mr_beyond = individuals_chart(x)
    assert lim.centre == pytest.approx(11.375, rel=1e-12)
    assert lim.sigma == pytest.approx(10 / 7 / 1.128, rel=1e-12)
    assert lim.ucl == pytest.approx(15.1744, abs=1e-4) and lim.lcl == pytest.approx(7.5756, abs=1e-4)
    assert lim.mr_ucl == pytest.approx(3.267 * 10 / 7, rel=1e-12)
    assert np.isnan(mr[0]) and mr[8] == 4 and mr[9] == 5
    assert beyond.tolist() == [False] * 8 + [True, False]  # 16 > 15.17
    assert mr_beyond.tolist() == [False] * 8 + [False, True]  # MR 5 > 4.667; MR 4 is not
    assert (D2, D4) == (1.128, 3.267)  # Montgomery (2013), Appendix VI, n = 2


def test_individuals_chart_reference_and_errors():
    lim, _, beyond, _ = individuals_chart([35.0, 35.2, 36.6], reference=35.0, spread=0.5)
    assert (lim.lcl, lim.ucl) == (33.5, 36.5) and beyond.tolist() == [False, False, True]
    assert lim.mr_centre == pytest.approx(1.128 * 0.5)
    with pytest.raises(OptionError, match="both"):
        individuals_chart([1, 2, 3], reference=1.0)
    with pytest.raises(OptionError, match="at least 2"):
        individuals_chart([1.0])


def test_history_errors_name_what_the_store_holds(season):
    _, store = season
    res = runner.invoke(app, ["history", str(store), "--quantity", "phi_deg", "--material", "Ottawa sand"])
    assert res.exit_code == 1 and "no run records 'phi_deg' of material 'Ottawa sand'" in res.stderr
    assert "this store records it for the materials: Toyoura sand;" in res.stderr
    res = runner.invoke(app, ["history", str(store)])
    assert res.exit_code == 1 and "--quantity is needed" in res.stderr and "phi_deg" in res.stderr
    with pytest.raises(InputError, match="no capred store"):
        capred.history(store.parent / "none.sqlite")


def test_known_sigma_limits_false_alarm_rate_by_simulation():
    # In control, N(mu, sigma) with the reference mu and sigma given: P(|x - mu| > 3 sigma) = 2 (1 - Phi(3)) =
    # 0.0026998. 200,000 runs (fixed seed): the count's binomial sd is sqrt(n p (1-p)) = 23.2; 4 sd tolerance.
    rng = np.random.default_rng(7)
    n, p = 200_000, 0.0026998
    x = rng.normal(35.0, 0.4, n)
    _, _, beyond, _ = individuals_chart(x, reference=35.0, spread=0.4)
    assert abs(beyond.sum() - n * p) < 4 * math.sqrt(n * p * (1 - p))
    # the moving-range estimate is unbiased for sigma: E[MR] = d2 sigma = 1.128 sigma for n = 2 (Montgomery 2013)
    lim, *_ = individuals_chart(x, baseline=n)
    # relative sd of the estimate: (0.8525/1.128) sqrt(1 + 2 rho) / sqrt(n) ~ 0.2 % (rho ~ 0.22, overlapping ranges);
    # 1 % is 5 sd
    assert lim.sigma == pytest.approx(0.4, rel=1e-2)
