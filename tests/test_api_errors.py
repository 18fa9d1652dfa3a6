"""An API error names the API parameter and quotes the value as the caller gave it (issue 28, item 2).

``ShearOptions(box_area=-3)`` used to answer "... (got -30000 cm^2)": the SI reading of a plain number, which
the caller never typed. Every Options class now says ``box_area=-3`` (what was typed), the unit a plain number
is read in (with the reading), and how to give a unit; a string is quoted in its own spelling.
"""

from __future__ import annotations

import importlib
import pkgutil

import pytest

import capred.pipelines
from capred.errors import OptionError
from capred.pipelines.shear import ShearOptions
from capred.pipelines.triaxial import TriaxialOptions
from capred.result import Options


def _options_classes():
    for m in pkgutil.iter_modules(capred.pipelines.__path__):
        importlib.import_module(f"capred.pipelines.{m.name}")
    seen, todo = [], list(Options.__subclasses__())
    while todo:
        cls = todo.pop()
        if cls not in seen:
            seen.append(cls)
            todo.extend(cls.__subclasses__())
    return sorted(seen, key=lambda c: c.__name__)


FIELDS = [(cls, name) for cls in _options_classes() for name in cls.QUANTITIES]


def test_every_options_class_is_checked():
    """The walk finds the Options of every command family (a class that escapes it would go unchecked)."""
    names = {cls.__name__ for cls, _ in FIELDS}
    assert {"ShearOptions", "TriaxialOptions", "RetentionOptions", "PrismOptions", "SkemptonOptions"} <= names
    assert len(FIELDS) >= 50


@pytest.mark.parametrize(("cls", "name"), FIELDS, ids=[f"{c.__name__}.{n}" for c, n in FIELDS])
def test_value_quoted_as_given(cls, name):
    """The first physically impossible value of (-3, 3.5e12, -3.5e12) is quoted exactly as typed, after the
    parameter's API name; every dimensional option has one (3.5e12 exceeds any bound: 1 GPa for a stress)."""
    for bad in (-3, 3.5e12, -3.5e12):
        try:
            cls(**{name: bad})
        except OptionError as exc:
            text = str(exc)
            assert text.startswith(name), text
            assert f"(got {name}={bad!r}" in text, text
            return
    pytest.fail(f"{cls.__name__}({name}=...) accepted -3, 3.5e12 and -3.5e12")


def test_box_area_plain_number():
    """-3 as typed, the unit it was read in (m^2: the documented SI unit of a plain number) and its reading in the
    output unit, -3 m^2 = -30000 cm^2 (1 m^2 = 1e4 cm^2), with the way to give a unit."""
    with pytest.raises(OptionError) as err:
        ShearOptions(box_area=-3)
    text = str(err.value)
    assert text == (
        "box_area (--box-area): shear box area must be > 0 cm^2 (got box_area=-3, a plain number read in m^2, "
        "that is -30000 cm^2; give a unit, e.g. box_area='-3 cm^2')"
    )
    assert "got -30000" not in text  # the SI reading is never presented as what the caller gave


def test_string_kept_as_typed():
    """A value with a unit is quoted in the caller's spelling, with its reading where the units differ."""
    with pytest.raises(OptionError) as err:
        ShearOptions(box_area="-3 cm^2")
    assert str(err.value) == "box_area (--box-area): shear box area must be > 0 cm^2 (got box_area='-3 cm^2')"
    with pytest.raises(OptionError) as err:
        ShearOptions(box_area="-3 m^2")
    assert str(err.value).endswith("(got box_area='-3 m^2', that is -30000 cm^2)")
    with pytest.raises(OptionError, match=r"gamma_w \(--gamma-w\): .*\(got gamma_w='-9.81 kN/m\^3'\)$"):
        ShearOptions(gamma_w="-9.81 kN/m^3")


def test_unit_of_wrong_kind_quoted():
    with pytest.raises(OptionError, match=r"not a unit of area.*\(got box_area='3 kPa'\)$"):
        ShearOptions(box_area="3 kPa")


def test_plain_number_in_output_unit_gets_no_hint():
    """An angle's plain number is read in degrees, the unit users type: no 'give a unit' advice."""
    with pytest.raises(OptionError) as err:
        TriaxialOptions(c_eff=0, phi_eff=95)
    assert str(err.value).endswith("(got phi_eff=95)")


def test_triaxial_confidence_and_pairs():
    """TriaxialOptions checks its confidence level (it accepted 2 before) and names both API parameters."""
    with pytest.raises(OptionError, match=r"^confidence .*between 0 and 1.*\(got 2;"):
        TriaxialOptions(confidence=2)
    with pytest.raises(OptionError, match=r"both --c-eff and --phi-eff \(Python: c_eff and phi_eff\).*c_eff='5 kPa'"):
        TriaxialOptions(c_eff="5 kPa")
    assert TriaxialOptions(c_eff="5 kPa", phi_eff=30).c_eff == pytest.approx(5000.0, rel=1e-15)
