"""The writer's fast paths (float columns printed as one matrix, JSON rows encoded straight from columns, a
forked half of a long solve) write the bytes of the plain cell-by-cell definitions."""

import csv
import io
import json
import math

import numpy as np
import orjson
import pandas as pd
import pytest

from capred.io.writers import encode_csv, stream_json, write_csv_file
from capred.pipelines import bridge as pb
from capred.pipelines import bridge_solve as bs


def _cell(x, eu=False):
    """A float cell as the writer defines it: shortest round trip as orjson prints one Python float (e.g. 1e16,
    not Python's 1e+16), blank where not finite, a decimal comma in the excel-eu dialect."""
    if not math.isfinite(x):
        return ""
    text = orjson.dumps(x).decode()
    return text.replace(".", ",") if eu else text


def _columns(n=2500, seed=3):
    rng = np.random.default_rng(seed)
    cols = {"case": np.array([f"c,{i}" if i % 5 else f"=x{i}" for i in range(n)], dtype=object)}
    for k in range(3):
        a = rng.standard_normal(n) * 10.0 ** rng.integers(-30, 30, n)
        a[rng.random(n) < 0.2] = np.nan
        a[rng.random(n) < 0.02] = np.inf * np.sign(rng.standard_normal())
        cols[f"x{k}_mm"] = a
    cols["count"] = rng.integers(-5, 5, n)
    cols["single"] = rng.random(n).astype(np.float32)
    cols["status"] = np.array(["ok", "no bridge"], dtype=object)[rng.integers(0, 2, n)]
    cols["y"] = np.array([0.1, -0.0, 1e16, 1e-7, 5e-324])[rng.integers(0, 5, n)]
    return cols


@pytest.mark.parametrize("dialect", ["standard", "excel-eu"])
def test_float_columns_printed_at_once_are_the_cells_one_by_one(dialect):
    eu = dialect == "excel-eu"
    cols = _columns(n=12_500)  # two chunks of 10,000 rows
    buf = io.BytesIO()
    write_csv_file(buf, cols, dialect)
    rows = list(csv.reader(io.StringIO(buf.getvalue().decode("utf-8").lstrip("\ufeff")), delimiter=";" if eu else ","))
    assert rows[0] == list(cols) and len(rows) == 12_500 + 1
    for j, (k, v) in enumerate(cols.items()):
        if v.dtype.kind == "f":  # every float cell, exactly
            assert [r[j] for r in rows[1:]] == [_cell(x, eu) for x in v.astype(float).tolist()], k
    assert [r[0] for r in rows[1:6]] == (
        ["'=x0", "c,1", "c,2", "c,3", "c,4"] if eu else ["=x0", "c,1", "c,2", "c,3", "c,4"]
    )


def test_float_matrix_rows_and_the_other_columns_line_up():
    """Runs of float columns between text and integer columns: each row's cells in header order."""
    cols = {
        "a": np.array([1.5, np.nan]),
        "t": np.array(["p", "q"], dtype=object),
        "b": np.array([2.0, -1e-300]),
        "c": np.array([np.inf, 3.25]),
        "i": np.array([7, 8]),
        "d": np.array([0.1, 0.2]),
    }
    assert encode_csv(cols) == b"a,t,b,c,i,d\n1.5,p,2.0,,7,0.1\n,q,-1e-300,3.25,8,0.2\n"
    only = {"a": np.array([1.5, np.nan]), "b": np.array([np.nan, np.nan])}
    assert encode_csv(only) == b"a,b\n1.5,\n,\n"
    # a DataFrame gives the bytes of the same columns as a dict
    assert encode_csv(pd.DataFrame(cols)) == encode_csv(cols)


def test_bridge_json_rows_from_columns_are_the_row_dicts(tmp_path):
    """The writer's JSON of a BridgeResult (rows encoded chunk by chunk from the columns, NaN as null) is the
    JSON of its rows() (dicts, None where no bridge)."""
    rng = np.random.default_rng(2)
    n = 4100  # three chunks of 2,000 rows
    R, th = rng.uniform(0.1, 2.0, n).tolist(), rng.uniform(0, 60, n).tolist()
    D = (rng.uniform(0, 0.05, n) * R).tolist()
    s = (10 ** rng.uniform(-1, 1.5, n)).tolist()
    lines = ["case,R [mm],contact_angle [deg],gap [mm],suction [kPa]"]
    lines += [f'c{i} "q",{R[i]!r},{th[i]!r},{D[i]!r},{s[i]!r}' for i in range(n)]
    (tmp_path / "in.csv").write_text("\n".join(lines) + "\n")
    res = pb.solve_bridges(tmp_path / "in.csv")
    assert 0 < np.sum(res.status == 0) < n  # bridges, and rows without one (null cells)
    buf = io.BytesIO()
    stream_json(res.payload(lazy=True), buf.write)
    assert json.loads(buf.getvalue()) == json.loads(json.dumps(res.payload()))
    assert buf.getvalue() == orjson.dumps(res.payload()) + b"\n"  # byte for byte


def test_a_forked_half_that_fails_is_solved_by_the_parent(monkeypatch):
    """_in_parallel: the rows of one process, and a child that dies leaves its half to the parent."""
    import os

    calls = []

    def solver(x):
        calls.append(os.getpid())
        if os.getpid() != parent:
            raise RuntimeError("the child fails")
        return (2.0 * x, x + 1.0)

    parent = os.getpid()
    monkeypatch.setattr(bs, "_PARALLEL_ROWS", 4)
    monkeypatch.setenv("CAPRED_PROCESSES", "2")
    x = np.arange(10.0)
    a, b = bs._in_parallel(solver, x)
    np.testing.assert_array_equal(a, 2.0 * x)  # exact: the same arithmetic on every row
    np.testing.assert_array_equal(b, x + 1.0)
    assert calls == [parent, parent]  # the first half, then the half the child did not deliver


def test_a_second_process_only_on_a_free_core(monkeypatch):
    """second_core_free: two cores and a load average that leaves one idle; CAPRED_PROCESSES decides instead."""
    import os

    from capred.io.writers import second_core_free

    monkeypatch.delenv("CAPRED_PROCESSES", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.9, 0.0, 0.0))  # this run, and an idle core
    assert second_core_free()
    monkeypatch.setattr(os, "getloadavg", lambda: (1.6, 0.0, 0.0))  # the other core busy
    assert not second_core_free()
    monkeypatch.setenv("CAPRED_PROCESSES", "2")
    assert second_core_free()
    monkeypatch.setenv("CAPRED_PROCESSES", "1")
    monkeypatch.setattr(os, "getloadavg", lambda: (0.0, 0.0, 0.0))
    assert not second_core_free()
    monkeypatch.delenv("CAPRED_PROCESSES")
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    assert not second_core_free()
