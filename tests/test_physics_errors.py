"""capred.physics raises plain ValueErrors; the pipelines and the CLI turn them into capred's messages (issue 42.3).

The physics knows values, not files or options: a value it refuses is a ValueError with a clear text. The
pipeline that calls it (skempton-b's bounding-surface rows) or the command line that builds the options
(κ not below λ, checked as the options are made) reports that text word for word, with exit status 1 and no
traceback; any other ValueError is a bug and keeps its traceback.
"""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import capred
from capred.cli import app
from capred.cli.common import physics_refusal
from capred.errors import OptionError
from capred.physics import pedrotti_tarantino as pt
from capred.physics import skempton_elastoplastic as sep

PHYSICS = Path(capred.__file__).resolve().parent / "physics"


def _errors_imports(path: Path) -> list[str]:
    """Every name a module imports from capred.errors (relative or absolute, at any depth of the module)."""
    names = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            absolute = node.level == 0 and node.module == "capred.errors"
            relative = node.level == 2 and node.module == "errors"  # capred/physics/x.py: from ..errors
            if absolute or relative:
                names += [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            names += [a.name for a in node.names if a.name == "capred.errors"]
    return names


def test_physics_imports_nothing_from_capred_errors():
    found = {p.name: _errors_imports(p) for p in sorted(PHYSICS.glob("*.py"))}
    assert len(found) > 10  # every physics module was read
    assert {k: v for k, v in found.items() if v} == {}


def test_the_import_check_sees_both_spellings(tmp_path):
    mod = tmp_path / "m.py"
    mod.write_text(
        "from ..errors import OptionError\nimport capred.errors\ndef f():\n    from capred.errors import X\n"
    )
    assert _errors_imports(mod) == ["OptionError", "capred.errors", "X"]


def test_physics_refuses_values_with_value_errors():
    with pytest.raises(ValueError, match=r"need 0 < kappa \(0.3\) < lambda0 \(0.2\)"):
        sep.BoundingSurfaceCompliance(kappa_elastic=0.3, lambda0=0.2)
    with pytest.raises(ValueError, match=r"S_R must lie in \(0, 1\]"):
        sep.skempton_b_incremental(0.0)
    with pytest.raises(ValueError, match="kappa_W must lie in"):
        pt.PTVolumeParameters(lambda_W=0.1, kappa_W=0.2, e_ncl_W=2.0, lambda_A=0.1, kappa_A=0.01, e_ncl_A=1.8)


def test_only_a_value_error_raised_in_physics_is_a_refusal():
    try:
        sep.BoundingSurfaceCompliance(kappa_elastic=0.3, lambda0=0.2)
    except ValueError as exc:
        refusal = physics_refusal(exc)
    assert isinstance(refusal, OptionError) and str(refusal) == "need 0 < kappa (0.3) < lambda0 (0.2)"
    try:
        np.zeros(2).reshape(3)  # numpy's ValueError: a bug, not a refused value
    except ValueError as exc:
        assert physics_refusal(exc) is None
    assert physics_refusal(ValueError("never raised")) is None


def test_cli_reports_a_value_the_physics_refuses_in_a_row(tmp_path):
    """S_r = 0 on skempton-b's bounding-surface drying path: the physics' text, exit 1, nothing written."""
    cases = tmp_path / "cases.csv"
    cases.write_text("S_r,kappa,e0,p0,u0\n0,0.006,0.6,200,100\n", encoding="utf-8")
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["skempton-b", str(cases), "--model", "bounding-surface", "--out", str(out)])
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert "Error: S_R must lie in (0, 1]" in res.stderr
    assert not out.exists()


def test_cli_reports_a_value_the_physics_refuses_in_the_options(tmp_path):
    """kappa not below lambda0, checked by the physics as the options are built: the same message as before."""
    res = CliRunner().invoke(
        app, ["skempton-b", "--S-R", "0.9", "--model", "bounding-surface", "--lambda0", "0.005", "--json"]
    )
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert "Error: need 0 < kappa (0.006) < lambda0 (0.005)" in res.stderr


def test_batch_reports_a_value_the_physics_refuses_in_a_manifest(tmp_path):
    """The same refusal in one line of a batch manifest: a problem of that line, no traceback, no run."""
    (tmp_path / "cases.csv").write_text("S_r,kappa,e0,p0,u0\n0.9,0.006,0.6,200,100\n", encoding="utf-8")
    manifest = tmp_path / "m.csv"
    manifest.write_text(
        "command,input,options\nskempton-b,cases.csv,--model bounding-surface --lambda0 0.005\n", encoding="utf-8"
    )
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["batch", str(manifest), "--out", str(out), "--workers", "1"])
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert "line 2" in res.stderr and "need 0 < kappa (0.006) < lambda0 (0.005)" in res.stderr
    assert not out.exists()


def test_options_built_from_python_report_the_physics_refusal_as_an_option_error():
    """The API keeps its contract: options whose values the physics refuses raise OptionError, with its text."""
    from capred.spec.calculators import SkemptonOptions
    from capred.spec.pt_volume import PTVolumeOptions

    with pytest.raises(OptionError, match=r"need 0 < kappa \(0.3\) < lambda0 \(0.2\)"):
        SkemptonOptions(model="bounding-surface", kappa_elastic=0.3, lambda0=0.2)
    with pytest.raises(OptionError, match="kappa_W must lie in"):
        PTVolumeOptions(lambda_W=0.1, kappa_W=0.2, e_ncl_W=2.0, lambda_A=0.1, kappa_A=0.01, e_ncl_A=1.8)
