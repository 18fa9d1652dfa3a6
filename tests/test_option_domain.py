"""Every input inside its domain (issue 46, part 3): NaN and infinities in options, derived stresses, grain radii."""

import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.parameters import non_finite_options

runner = CliRunner()


@pytest.mark.parametrize(
    "args,named",
    [
        (["bridge", "laws", "--ratios", "nan"], "--ratios = nan"),
        (["bridge", "laws", "--gaps", "nan,inf"], "--gaps = nan, inf"),
        (["bridge", "laws", "--volumes", "0.01,inf"], "--volumes = inf"),
    ],
)
def test_nan_and_infinities_in_options_are_errors(tmp_path, args, named):
    res = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert res.exit_code != 0 and named in res.stderr and "finite number" in res.stderr, res.output
    assert not (tmp_path / "o").exists()


def test_non_finite_options_lists_fields():
    from dataclasses import dataclass

    @dataclass(frozen=True)
    class Opt:
        a: float = 1.0
        b: tuple = (1.0, 2.0)
        limit: float = float("inf")  # an unbounded default is not the user's
        flag: bool = True

    assert non_finite_options(Opt()) == []
    assert non_finite_options(Opt(a=float("nan"), b=(1.0, float("inf")))) == ["--a = nan", "--b = inf"]


def test_derived_normal_stress_gets_the_measured_bound(tmp_path):
    """added_mass = 1e300 g on a 36 cm^2 box: sigma_N = (m g)/A = 2.7e297 kPa, refused by the 1 GPa bound of a
    measured sigma_N, naming the masses (no numpy overflow warning reaches the user)."""
    path = tmp_path / "am.csv"
    path.write_text(
        "test_id,material,condition,added_mass [g],cap_mass [g],box_area [cm^2],tau_max [kPa]\n"
        "T0,s,dry,0,120,36,20\nT1,s,dry,1e300,120,36,40\nT2,s,dry,500,120,36,60\n"
    )
    res = runner.invoke(app, ["shear", str(path), "--bootstrap", "0", "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1, res.output
    assert "line 3" in res.stderr and "sigma_N derived from added_mass = 1e300" in res.stderr
    assert "1 GPa" in res.stderr and "RuntimeWarning" not in res.output
    assert not (tmp_path / "o").exists()


def test_grain_radius_outside_any_laboratory_is_refused(tmp_path):
    path = tmp_path / "bs.csv"
    path.write_text("R [mm],contact_angle [deg],gap [mm],suction [kPa]\n1e-300,0,0,10\n0.5,0,0,10\n1e300,0,0,10\n")
    res = runner.invoke(app, ["bridge", "solve", str(path), "--no-plots", "--out", str(tmp_path / "o")])
    assert res.exit_code == 1, res.output
    assert "line 2" in res.stderr and "below 1e-06 mm" in res.stderr  # 1 nm, the glossary's floor
    assert "line 4" in res.stderr and "10 m radius" in res.stderr


def test_bridge_laws_grid_over_its_bound_asks_for_yes(tmp_path):
    """200 gaps x 200 volumes x the 3 default angles x 3 ratios: 360,000 exact bridges (over 120 s before)."""
    from capred.cli.bridge_commands import MAX_GRID_POINTS

    gaps = ",".join(str(i / 1000) for i in range(200))
    volumes = ",".join(str((i + 1) / 2000) for i in range(200))
    res = runner.invoke(app, ["bridge", "laws", "--gaps", gaps, "--volumes", volumes, "--out", str(tmp_path / "o")])
    assert res.exit_code != 0 and "360,000 points" in res.stderr and "--yes" in res.stderr, res.output
    assert f"{MAX_GRID_POINTS:,}" in res.stderr and not (tmp_path / "o").exists()


def test_bridge_laws_chunked_solve_gives_the_same_forces(monkeypatch):
    """A grid solved a chunk at a time (with progress) gives the forces of one call (each point alone)."""
    import numpy as np

    from capred.pipelines import bridge_laws

    opt = bridge_laws.LawsOptions(gaps=(0.0, 0.05), volumes=(1e-3, 1e-2), angles=(0.0, 20.0), ratios=(1.0,))
    whole = bridge_laws.compare_laws(options=opt)
    monkeypatch.setattr(bridge_laws, "CHUNK_POINTS", 3)
    chunked = bridge_laws.compare_laws(options=opt)
    np.testing.assert_array_equal(chunked.status, whole.status)
    np.testing.assert_allclose(chunked.exact, whole.exact, rtol=1e-9, equal_nan=True)  # the same solver per point
