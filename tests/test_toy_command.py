"""A new command is two registry entries (issue 28): its Reduction (with its Options and result) and its presenter.

The toy below is registered in those two places only; its CLI is built from its Options (capred.cli.generated):
each option declared once, its help from the Options docstring, its unit from the glossary, values numbers from
the command line to the computation.
"""

import json
import sys
import textwrap

import typer
from typer.testing import CliRunner

from capred.cli import common
from capred.cli.generated import register_generated
from capred.reductions import REDUCTIONS, Reduction
from capred.report import presenters

TOY = textwrap.dedent(
    '''
    """A toy command: the hydrostatic suction gamma_w z of a hanging column."""
    from dataclasses import dataclass

    from capred.result import Options, Result, TableSpec


    @dataclass(frozen=True)
    class ToyOptions(Options):
        """Options of the toy.

        Attributes
        ----------
        gamma_w : float
            Unit weight of water [N/m^3].
        heights : tuple
            Heights of the sample above the water level [m].
        """

        QUANTITIES = {"gamma_w": "gamma_w"}
        gamma_w: float = 9810.0
        heights: tuple = (0.1, 0.2)


    class ToyResult(Result):
        command = "toy-suction"

        def __init__(self, options):
            self.options, self.inputs, self.notes, self.warnings = options, [], [], []
            self.suction_kPa = [options.gamma_w * float(z) / 1e3 for z in options.heights]

        def payload(self, lazy=False):
            return {"suction_kPa": self.suction_kPa}

        def tables(self):
            import pandas as pd

            return {"results": pd.DataFrame({"suction_kPa": self.suction_kPa})}


    def run_toy(source, options):
        return ToyResult(options)


    def toy_tables(result):
        spec = TableSpec("Suction of the hanging column", [("suction [kPa]", "right")])
        spec.rows.extend([[f"{s:.4g}"] for s in result.suction_kPa])
        return [spec]
    '''
)


def test_a_toy_command_is_two_entries_and_gets_its_cli(tmp_path, monkeypatch):
    (tmp_path / "toy_suction.py").write_text(TOY, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "toy_suction", raising=False)
    red = Reduction("toy-suction", "toy_suction:run_toy", "toy_suction:ToyOptions", "none", None, "toy_suction")
    monkeypatch.setitem(REDUCTIONS, red.name, red)  # place 1: the reduction
    monkeypatch.setitem(  # place 2: its presenter
        presenters.PRESENTERS,
        red.name,
        presenters.Presenter(lambda r: {}, lambda r: __import__("toy_suction").toy_tables(r)),
    )
    monkeypatch.setattr(common, "BUILDERS", dict(common.BUILDERS))
    app = typer.Typer(rich_markup_mode=None)  # plain help, as capred's app (rich would read [kN/m^3] as markup)
    app.callback()(lambda: None)
    assert register_generated(app, common.BUILDERS) == ["toy-suction"]
    runner = CliRunner()
    help_text = " ".join(runner.invoke(app, ["toy-suction", "--help"]).output.split())  # wrapped lines joined
    assert "--gamma-w" in help_text and "--heights" in help_text and "Unit weight of water" in help_text
    # --gamma-w in the glossary's unit (kN/m^3): 10 kN/m^3 x 0.5 m = 5 kPa, by hand
    res = runner.invoke(app, ["toy-suction", "--gamma-w", "10", "--heights", "0.5,1", "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["suction_kPa"] == [5.0, 10.0]
    # a value with a unit of its own, as on every hand-written command: 10000 N/m^3 = 10 kN/m^3
    res = runner.invoke(app, ["toy-suction", "--gamma-w", "10000 N/m^3", "--heights", "0.5,1", "--json"])
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["suction_kPa"] == [5.0, 10.0]
    # the glossary's unit and range, and the Options default in that unit
    assert "[kN/m^3; > 0]" in help_text and "[default: 9.81]" in help_text
    res = runner.invoke(app, ["toy-suction", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    assert "0.981" in res.output  # its presenter's console table: 9.81 kN/m^3 x 0.1 m = 0.981 kPa
    assert (tmp_path / "o" / "results.csv").read_text().splitlines()[0] == "suction [kPa]"
