"""Issue 39 part 7: a bridge solved by volume says when a second (thin-neck) bridge of the same volume and gap
exists, and `--branch thin` gives it."""

import json

import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.physics import bridge as br

runner = CliRunner()


def _both(th, V, D):
    out = []
    for branch in ("stable", "thin"):
        beta, s, st = br.solve_for_volume(th, V, D, branch=branch)
        out.append((st[0], None if st[0] else br.bridge(beta, th, s)))
    return out


def test_two_bridges_near_rupture_one_elsewhere():
    """theta = 0, V/R^3 = 1e-3 (rupture at D/R = 0.1008): at D/R = 0.1 both bridges reproduce the volume and the
    gap (to 1e-9, the solver's verification; checked again here to 1e-8), the thin one with the thinner neck and
    the lower suction and force; far from rupture (0.05) and at contact there is only the stable one. Close to
    rupture the two meet (necks within 2 % at 0.99999 of the rupture gap)."""
    (s1, a), (s2, b) = _both(0.0, 1e-3, 0.1)
    assert s1 == 0 and s2 == 0
    for x in (a, b):
        assert x.volume[0] == pytest.approx(1e-3, rel=1e-8) and x.gap[0] == pytest.approx(0.1, rel=1e-8)
    assert b.neck[0] < a.neck[0] and b.force[0] < a.force[0]
    for D in (0.05, 0.0):
        (s1, _), (s2, _) = _both(0.0, 1e-3, D)
        assert s1 == 0 and s2 == 1
    r = br.rupture_gap(0.0, 1e-3, 1.0)[0][0]
    (_, a), (s2, b) = _both(0.0, 1e-3, 0.99999 * r)
    assert s2 == 0 and b.neck[0] == pytest.approx(a.neck[0], rel=0.02)


def test_cli_says_so_and_branch_thin_gives_it(tmp_path):
    f = tmp_path / "cases.csv"
    f.write_text(
        "case,R [mm],gamma,contact_angle,gap [mm],V_w [mm^3]\nnear,1,0.0728,0,0.1,0.001\nfar,1,0.0728,0,0.05,0.001\n"
    )
    stable = runner.invoke(app, ["bridge", "solve", str(f), "--json"])
    assert stable.exit_code == 0, stable.output
    doc = json.loads(stable.output)
    assert any("second, thin-neck bridge" in n for n in doc["notes"])
    rows = {r["case"]: r for r in doc["rows"]} if "rows" in doc else None
    text = json.dumps(doc)
    assert "a second (thin-neck) bridge of this volume and gap exists" in text
    thin = runner.invoke(app, ["bridge", "solve", str(f), "--branch", "thin", "--json"])
    assert thin.exit_code == 0, thin.output
    d2 = json.loads(thin.output)
    assert any("--branch thin" in n for n in d2["notes"])
    assert "no thin-neck bridge" in json.dumps(d2)
    del rows
    bad = runner.invoke(app, ["bridge", "solve", str(f), "--branch", "thick"])
    assert bad.exit_code == 1 and "stable or thin" in bad.output


def test_existence_criterion_agrees_with_the_thin_solve():
    """The cheap criterion (volume at most the thinnest catenoid's at this gap) agrees with solving for the thin
    bridge on 300 random rows near rupture (fixed seed)."""
    import numpy as np

    rng = np.random.default_rng(5)
    n = 300
    th, V = rng.uniform(0, 0.6, n), 10 ** rng.uniform(-4, -1.5, n)
    D = br.rupture_gap(th, V, np.ones(n))[0] * (1 - 10 ** rng.uniform(-4, -0.5, n))
    ok = br.solve_for_volume(th, V, D)[2] == 0
    thin = br.solve_for_volume(th, V, D, branch="thin")[2] == 0
    exists = br.has_thin_bridge(th, V, D)
    assert thin.sum() > 10 and np.array_equal(thin[ok], exists[ok])
