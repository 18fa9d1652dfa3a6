"""capred.spec, the declaration layer: numpy-free, and its declarative option checks.

The CLI and `--help` are built from capred.spec at run time, so the layer must load no numerical library
(capred/spec/__init__.py states the rule); the constraints replace hand-written ``__post_init__`` checks and keep
their wording.
"""

import json
import math
import pkgutil
import subprocess
import sys
from dataclasses import dataclass

import pytest

import capred.spec
from capred.errors import OptionError
from capred.spec.options import Interval, Options, Probability, StrOptions, Whole

HEAVY = ("numpy", "pandas", "pint", "matplotlib", "scipy", "typer")


def test_every_spec_module_imports_no_numerical_library():
    names = [f"capred.spec.{m.name}" for m in pkgutil.iter_modules(capred.spec.__path__)]
    assert "capred.spec.options" in names and "capred.spec.columns" in names
    code = (
        "import importlib, json, sys\n"
        f"for n in {names!r}: importlib.import_module(n)\n"
        f"print(json.dumps(sorted(m for m in {HEAVY!r} if m in sys.modules)))"
    )
    got = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(got.stdout) == []


@dataclass(frozen=True)
class _Demo(Options):
    CONSTRAINTS = {
        "confidence": Probability(),
        "bootstrap": Whole(min=0),
        "loss": StrOptions(("ols", "huber", "tukey")),
        "limit": Interval(0, 1, closed="right"),
        "width": Interval(0, None, closed="neither"),
    }

    confidence: float = 0.95
    bootstrap: int = 10
    loss: str = "ols"
    limit: float = 1.0
    width: float | None = None


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"confidence": 1.0}, "confidence (--confidence) must lie strictly between 0 and 1, e.g. 0.95 (got 1.0)"),
        ({"confidence": math.nan}, "confidence (--confidence) must lie strictly between 0 and 1, e.g. 0.95 (got nan)"),
        ({"bootstrap": -1}, "bootstrap (--bootstrap) must be a whole number >= 0 (got -1)"),
        ({"bootstrap": True}, "bootstrap (--bootstrap) must be a whole number >= 0 (got True)"),
        ({"bootstrap": 2.0}, "bootstrap (--bootstrap) must be a whole number >= 0 (got 2.0)"),
        ({"loss": "l1"}, "loss (--loss) must be ols, huber or tukey (got 'l1')"),
        ({"limit": 0.0}, "limit (--limit) must lie in (0, 1] (got 0.0)"),
        ({"width": math.inf}, "width (--width) must be > 0 (got inf)"),
        ({"width": -math.inf}, "width (--width) must be > 0 (got -inf)"),
        ({"width": "wide"}, "width (--width) must be > 0 (got 'wide')"),
    ],
)
def test_a_broken_constraint_is_an_option_error_naming_field_option_rule_and_value(kw, message):
    with pytest.raises(OptionError) as err:
        _Demo(**kw)
    assert str(err.value) == message


def test_values_within_their_constraints_pass_and_none_means_not_given():
    d = _Demo(confidence=0.5, bootstrap=0, loss="tukey", limit=1.0, width=None)
    assert (d.confidence, d.bootstrap, d.loss, d.limit, d.width) == (0.5, 0, "tukey", 1.0, None)


@pytest.mark.parametrize("rule", [Interval(), Interval(0, None), Interval(None, 5), Probability(), Whole()])
def test_nan_and_infinities_break_every_numeric_constraint(rule):
    for bad in (math.nan, math.inf, -math.inf):
        assert not rule.accepts(bad)


def test_column_and_options_keep_their_old_import_paths():
    import capred.spec.columns
    import capred.spec.options
    from capred.io.table import Column
    from capred.result import Options as Old
    from capred.result import as_given

    assert Column is capred.spec.columns.Column
    assert Old is capred.spec.options.Options and as_given is capred.spec.options.as_given
