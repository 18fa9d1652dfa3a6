"""Issue 20: `bridge solve`'s rows in one or two processes, and the note on volume-controlled bridges past the
suction-controlled fold."""

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

import capred.pipelines.bridge as pb
import capred.pipelines.bridge_solve as bs
from capred.physics import bridge as br


def thin_bridge(gap, s):
    """Equal spheres, theta = 0, R = 1: the bridge of smaller filling angle at (gap*, s*), unstable under
    suction control (on the rising side of gap*(beta))."""
    grid = np.linspace(0.001, 1.5, 3000)
    j = int(np.nanargmax(br.gap_of(grid, 0.0, s)))
    b = brentq(lambda x: float(br.gap_of(x, 0.0, s)) - gap, grid[0], grid[j], xtol=1e-15)
    return br.bridge(b, 0.0, s)


def write_rows(path, gap, volume):
    with open(path, "w") as fh:
        fh.write("R [mm],contact_angle [deg],gap [mm],V_w [mm^3]\n")
        fh.writelines(f"1.0,0.0,{g!r},{v!r}\n" for g, v in zip(gap, volume))


def test_volume_rows_past_the_suction_fold_carry_the_note(tmp_path):
    # the thin bridges of (gap*, s*) = (0.1, 2), (0.3, 0.1), (0.3, 0.5) are the ones held at constant volume
    # (tests/test_bridge.py: the volume along the arc rises with the neck there), past the suction fold; the
    # stable bridges of the same pairs, and a bridge at contact, are not
    pairs = [(0.1, 2.0), (0.3, 0.1), (0.3, 0.5)]
    thin = [float(thin_bridge(g, s).volume) for g, s in pairs]
    stable = [float(br.bridge(br.solve_for_suction(0.0, s, g)[0], 0.0, s).volume[0]) for g, s in pairs]
    gap = [g for g, _ in pairs] * 2 + [0.0]
    write_rows(tmp_path / "v.csv", gap, thin + stable + [1e-3])
    res = pb.solve_bridges(tmp_path / "v.csv")
    assert np.all(res.status == 0)
    past = ["past the suction-controlled fold" in n for n in res.note]
    assert past == [True] * 3 + [False] * 4


@pytest.mark.parametrize("control", ["suction", "V_w"])
def test_two_processes_give_the_rows_of_one(tmp_path, monkeypatch, control):
    rng = np.random.default_rng(5)
    n = 41
    R = rng.uniform(0.1, 2.0, n)
    th = rng.uniform(0.0, 60.0, n)
    D = rng.uniform(0.0, 0.05, n) * R
    s = 10 ** rng.uniform(-1, 1.5, n)  # kPa; about a third beyond rupture
    if control == "V_w":
        s_star = s * 1e3 * R * 1e-3 / 0.0728
        b, st = br.solve_for_suction(np.radians(th), s_star, D / R)
        x = np.where(st == 0, br.bridge(b, np.radians(th), s_star).volume * R**3, 1e-9 * R**3)  # mm^3
    else:
        x = s
    unit = "kPa" if control == "suction" else "mm^3"
    with open(tmp_path / "in.csv", "w") as fh:
        fh.write(f"R [mm],contact_angle [deg],gap [mm],{control} [{unit}]\n")
        fh.writelines(",".join(map(repr, row)) + "\n" for row in zip(R.tolist(), th.tolist(), D.tolist(), x.tolist()))
    one = pb.solve_bridges(tmp_path / "in.csv")
    monkeypatch.setattr(bs, "_PARALLEL_ROWS", 10)  # both halves of the 41 rows, the second in a forked process
    monkeypatch.setenv("CAPRED_PROCESSES", "2")  # whatever the machine's load
    two = pb.solve_bridges(tmp_path / "in.csv")
    assert 0 < np.sum(one.status == 0) < n  # bridges and rows without one
    assert np.array_equal(one.status, two.status)
    assert one.note == two.note
    for k, v in one.columns().items():
        # exact: every row is solved by the same operations in the same order whatever rows share its batch
        # (the quadrature's matrix products sum every row alike: capred.physics.bridge._quad)
        np.testing.assert_array_equal(two.columns()[k], v)


@pytest.mark.parametrize("ratio", [1.0, 0.5])
def test_a_bridge_does_not_depend_on_the_rows_solved_with_it(ratio):
    """bridge_at_suction on rows cut in two anywhere gives, bit for bit, the rows of one call: the last rows of
    a batch are summed like the others (BLAS would sum the last n mod 4 rows of a matrix product in another
    order and move the last bit, and with it a root finder's stopping point). Rows of one radius ratio: a batch
    of equal spheres alone takes the equal-sphere fast path, whose gap rounds differently in the last bit."""
    rng = np.random.default_rng(3)
    n = 6000
    R = rng.uniform(0.1, 2.0, n)
    th = np.radians(rng.uniform(0.0, 60.0, n))
    s_star = 10 ** rng.uniform(-1, 1.5, n) * 1e3 * R * 1e-3 / 0.0728
    D = rng.uniform(0.0, 0.05, n)
    rho = np.full(n, ratio)
    whole = br.bridge_at_suction(th, s_star, D, rho)
    assert 0 < np.sum(whole[1] == 0) < n
    for cut in (1, 7, 2049, 4095):  # across the quadrature's groups of rows and its 2,048-row blocks
        a = br.bridge_at_suction(th[:cut], s_star[:cut], D[:cut], rho[:cut])
        b = br.bridge_at_suction(th[cut:], s_star[cut:], D[cut:], rho[cut:])
        np.testing.assert_array_equal(np.concatenate([a[0], b[0]]), whole[0])
        for k in br._FIELDS:
            np.testing.assert_array_equal(np.concatenate([getattr(a[2], k), getattr(b[2], k)]), getattr(whole[2], k))


def test_the_quadrature_sum_is_the_matrix_product():
    """_quad is values @ weights, each row summed as BLAS sums its groups of rows (to the last bit, or within
    one rounding of the other order: 4 ulp of the sum of 16 positive terms)."""
    rng = np.random.default_rng(0)
    values, weights = rng.random((37, 16)), rng.random(16)
    assert_allclose(br._quad(values, weights), values @ weights, rtol=4 * np.finfo(float).eps, atol=0)
    np.testing.assert_array_equal(br._quad(values[:32], weights), values[:32] @ weights)  # whole groups: as BLAS
    for k in range(37):  # a row alone, or in any company, is summed alike
        assert br._quad(values[k : k + 1], weights)[0] == br._quad(values, weights)[k]


def _random_cases(path, n=61, seed=9):
    rng = np.random.default_rng(seed)
    R = rng.uniform(0.1, 2.0, n)
    th = rng.uniform(0.0, 60.0, n)
    th2 = rng.uniform(0.0, 60.0, n)
    D = rng.uniform(0.0, 0.05, n) * R
    V = 10 ** rng.uniform(-4, -1.5, n) * R**3
    with open(path, "w") as fh:
        fh.write("R [mm],R2 [mm],contact_angle [deg],contact_angle2 [deg],gap [mm],V_w [mm^3]\n")
        fh.writelines(
            ",".join(map(repr, row)) + "\n"
            for row in zip(R.tolist(), (1.5 * R).tolist(), th.tolist(), th2.tolist(), D.tolist(), V.tolist())
        )
    return path


@pytest.mark.parametrize("how", [("env", 3), ("env", 5), ("option", 4)])
def test_any_number_of_processes_gives_the_rows_of_one(tmp_path, monkeypatch, how):
    f = _random_cases(tmp_path / "in.csv")
    monkeypatch.setenv("CAPRED_PROCESSES", "1")
    one = pb.solve_bridges(f)
    monkeypatch.setattr(bs, "_PARALLEL_ROWS", 10)  # parts of >= 5 rows: 61 rows take every process asked for
    forks = []
    real_fork = bs._Helper.__init__

    def counting(self, job=None):
        forks.append(1)
        real_fork(self, job)

    monkeypatch.setattr(bs._Helper, "__init__", counting)
    kind, k = how
    if kind == "env":
        monkeypatch.setenv("CAPRED_PROCESSES", str(k))
        many = pb.solve_bridges(f)
    else:
        many = pb.solve_bridges(f, pb.BridgeOptions(workers=k))  # the option wins over CAPRED_PROCESSES=1
    assert len(forks) == k - 1  # k processes: this one and k - 1 helpers
    assert bs._HELPERS == [] and bs._Helper.live == []  # every helper closed with the run
    assert 0 < np.sum(one.status == 0)
    assert np.array_equal(one.status, many.status) and one.note == many.note
    for key, v in one.columns().items():
        np.testing.assert_array_equal(many.columns()[key], v)  # exact: the same operations on every row


def test_processes_rule(monkeypatch):
    """--workers, then CAPRED_PROCESSES (any N), then the idle cores this process may use, this run counting as
    one: 2 cores at a load of 1.4 -> 2, at 1.6 -> 1; 16 cores at a load of 8 -> 9, idle -> 16."""
    import os

    monkeypatch.delenv("CAPRED_PROCESSES", raising=False)
    for cores, load, want in ((2, 1.4, 2), (2, 1.6, 1), (16, 8.0, 9), (16, 0.0, 16), (1, 0.0, 1)):
        monkeypatch.setattr(os, "sched_getaffinity", lambda _pid, c=cores: set(range(c)))
        monkeypatch.setattr(os, "getloadavg", lambda ld=load: (ld, ld, ld))
        assert bs.processes() == want, (cores, load)
    monkeypatch.setenv("CAPRED_PROCESSES", "7")
    assert bs.processes() == 7
    assert bs.processes(3) == 3
    monkeypatch.setenv("CAPRED_PROCESSES", "many")  # not a number: the rule of the cores
    assert bs.processes() == 1  # 1 core (the last of the loop above)
    assert bs._parts(10, 3) == [(0, 3), (3, 6), (6, 10)]


def test_workers_option_is_checked():
    from capred.errors import OptionError

    for bad in (0, -2, 1.5):
        with pytest.raises(OptionError, match="workers"):
            pb.BridgeOptions(workers=bad)
