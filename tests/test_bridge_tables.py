"""Issue 29 item 7 (bridge part): tables that name each row and say where a row beyond rupture would have had a
bridge; bridge figure titles inside their figures."""

import numpy as np
import pytest

from capred.physics import bridge as br
from capred.pipelines import bridge as pb
from capred.report import sheets
from capred.report.bridge_tables import bridge_solve_tables
from capred.samples import sample_path


def _table(result):
    t = bridge_solve_tables(result)[1]
    return [h for h, _ in t.columns], t.rows


def test_rows_are_named_by_case_or_by_radius_and_gap(tmp_path):
    heads, rows = _table(pb.solve_bridges(sample_path("bridge-solve")))
    assert heads[0] == "case" and "R_mm" not in heads
    assert all(r[0] for r in rows)
    f = tmp_path / "nocase.csv"
    f.write_text("R [mm],contact_angle,gap [mm],suction [kPa]\n1,0,0.02,1\n0.5,20,0.3,10\n")
    heads, rows = _table(pb.solve_bridges(f))
    assert heads[:2] == ["R_mm", "gap_mm"]
    assert [r[:2] for r in rows] == [["1", "0.02"], ["0.5", "0.3"]]


def test_beyond_rupture_gives_the_rupture_distance(tmp_path):
    """The distance shown is the widest gap of a bridge at the row's volume or suction: just inside it a bridge
    is found, just outside it none (the solvers' own statuses, 1e-6 apart)."""
    f = tmp_path / "far.csv"
    f.write_text(
        "R [mm],contact_angle,gap [mm],suction [kPa],V_w [mm^3]\n1,0,0.5,,0.001\n0.5,20,0.3,10,\n1,0,0.01,1,\n"
    )
    res = pb.solve_bridges(f)
    assert res.status.tolist() == [1, 1, 0]
    ctx = res.row_context(0, 3)
    D = ctx["D_rupture_mm"]
    assert np.isfinite(D[:2]).all() and np.isnan(D[2])
    # volume control (R = 1 mm, V* = 1e-3): the exact rupture distance, and Lian et al.'s estimate within 1 %
    # at theta = 0 (their relation D = (1 + theta/2) V^(1/3), the README's accuracy statement)
    assert D[0] == pytest.approx(br.rupture_gap(0.0, 1e-3)[0][0], rel=1e-12)
    assert D[0] == pytest.approx(0.1, rel=0.01)
    assert br.solve_for_volume(0.0, 1e-3, D[0] * (1 - 1e-6))[2][0] == 0
    assert br.solve_for_volume(0.0, 1e-3, D[0] * (1 + 1e-6))[2][0] == 1
    # suction control (R = 0.5 mm, 10 kPa, theta = 20 deg): s* = 10e3 * 0.5e-3 / 0.0728
    s_star, th, D_star = 10e3 * 0.5e-3 / 0.0728, np.radians(20.0), D[1] / 0.5
    assert br.solve_for_suction(th, s_star, D_star * (1 - 1e-6))[1][0] == 0
    assert br.solve_for_suction(th, s_star, D_star * (1 + 1e-6))[1][0] == 1
    heads, rows = _table(res)
    assert heads[-1] == "D_rupture_mm" and rows[0][-1] != "—" and rows[2][-1] == "—"


def test_long_runs_name_their_first_rows(tmp_path, monkeypatch):
    monkeypatch.setattr("capred.io.blocks.BLOCK_BYTES", 2_000)  # several blocks
    f = tmp_path / "long.csv"
    with open(f, "w") as fh:
        fh.write("R [mm],contact_angle,gap [mm],suction [kPa]\n")
        fh.writelines(f"1,0,{0.001 * (k % 50)!r},1\n" for k in range(400))
    res = pb.solve_bridges(f)
    assert type(res).__name__ == "BridgeBlocks"
    heads, rows = _table(res)
    assert heads[:2] == ["R_mm", "gap_mm"] and rows[3][:2] == ["1", "0.003"]


@pytest.mark.parametrize("command", ["bridge-rupture", "bridge-compare"])
def test_bridge_figure_titles_are_inside_the_figure(command):
    import capred

    res = capred.run(command.replace("-", " "), sample_path(command))
    for sheet in res.figures().values():
        fig = sheets.sheet_figure(sheet, 100)
        fig.canvas.draw()
        box = fig._suptitle.get_window_extent(fig.canvas.get_renderer())
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width, sheet.title  # not clipped on either side
