"""Issue 42: the lab store takes each quantity's unit from its declaration, never from the spelling of its key.

Before, a suffix rule read ``vg.S_s`` (van Genuchten's saturated degree of saturation, dimensionless) as a value
in seconds (``_s``) and `capred history` headed it ``value [s]``.
"""

import sqlite3

import pytest
from typer.testing import CliRunner

from capred.cli import app
from capred.lab_store import declared_units
from capred.samples import sample_path

runner = CliRunner()
# the sample's fits warn on purpose (a correlated pair, a parameter at its bound)
pytestmark = pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    """One retention run of the sample, stored by `capred retention --store` (files written)."""
    root = tmp_path_factory.mktemp("units")
    lab = root / "lab.sqlite"
    args = ["retention", str(sample_path("retention")), "--out", str(root / "run"), "--store", str(lab)]
    res = runner.invoke(app, [*args, "--no-plots", "--no-html"])
    assert res.exit_code == 0, res.output
    return root, lab


def _history(root, quantity: str) -> tuple[str, str]:
    """`capred history` of one quantity of the drying branch: (console text, history.csv's header line)."""
    out = root / quantity.replace(".", "_")
    args = ["history", str(root / "lab.sqlite"), "--quantity", quantity, "--material", "drying"]
    res = runner.invoke(app, [*args, "--reference", "1", "--spread", "0.1", "--out", str(out)])
    assert res.exit_code == 0, res.output
    return res.stdout, (out / "history.csv").read_text(encoding="utf-8").splitlines()[0]


def test_saturated_degree_of_saturation_is_dimensionless(store):
    root, lab = store
    console, header = _history(root, "vg.S_s")
    assert "[s]" not in console and "[s]" not in header
    assert header.startswith("run,test_date,input,value [-],ci_low [-],ci_high [-]")
    with sqlite3.connect(lab) as con:
        units = dict(con.execute("SELECT quantity, unit FROM records WHERE material = 'drying'").fetchall())
    assert units["vg.S_s"] == units["vg.S_res"] == units["vg.n"] == "-"
    assert units["vg.alpha_per_kPa"] == "1/kPa" and units["vg.alpha_per_cm"] == "1/cm"


def test_a_pressure_is_in_kpa(store):
    root, _ = store
    console, header = _history(root, "bc.s_e_kPa")  # Brooks-Corey's air-entry suction, declared in kPa
    assert "bc.s_e_kPa of drying [kPa]" in console
    assert header.startswith("run,test_date,input,value [kPa],ci_low [kPa],ci_high [kPa]")


def test_units_come_from_the_glossary_not_the_suffix():
    units = declared_units()
    assert units["phi_deg"] == ("phi", "deg") and units["c_kPa"] == ("c", "kPa") and units["c_se_kPa"] == ("c", "kPa")
    assert units["S_s"] == ("S_s", "-") and units["theta_s"] == ("theta_s", "m³/m³")
    assert "sigma_N_kPa" in units and units["sigma_N_kPa"][1] == "kPa"  # sigma_N: a stress, not newtons
    # a shear envelope's numbers (capred shear's materials block)
    assert [units[k][1] for k in ("tan_phi", "tan_phi_se", "r2", "scatter_kPa")] == ["-", "-", "-", "kPa"]
