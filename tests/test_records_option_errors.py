"""Option errors name the option as the user types it (issue 28 item 2): ``ShearOptions(confidence=...)``
names ``--confidence``; ``FigureOptions(dpi=...)`` refuses a resolution the CLI would refuse, naming ``dpi``."""

from __future__ import annotations

import pytest

import capred
from capred.errors import OptionError
from capred.pipelines.shear import ShearOptions
from capred.report.outputs import DPI_RANGE, FigureOptions


@pytest.mark.parametrize("value", [0, 1, 1.5, -0.2, float("nan"), "0.95", True])
def test_confidence_error_names_the_option_and_quotes_the_value(value):
    with pytest.raises(OptionError) as err:
        ShearOptions(confidence=value)
    text = str(err.value)
    assert text.startswith("confidence (--confidence)")
    assert repr(value) in text


def test_confidence_inside_the_range_is_kept():
    assert ShearOptions(confidence=0.9).confidence == 0.9


@pytest.mark.parametrize("value", [-3, 0, 29, 2401, 2.5, float("nan"), "300", True, None])
def test_dpi_outside_the_cli_range_is_an_error_naming_dpi(value):
    with pytest.raises(OptionError, match=r"^dpi \(--dpi\) .* between 30 and 2400 .*got"):
        FigureOptions(dpi=value)


def test_dpi_whole_numbers_in_range_are_kept_as_int():
    assert FigureOptions(dpi=DPI_RANGE[0]).dpi == 30
    assert FigureOptions(dpi=300.0).dpi == 300 and isinstance(FigureOptions(dpi=300.0).dpi, int)


@pytest.mark.filterwarnings("ignore::capred.errors.CapredWarning")
def test_write_outputs_refuses_a_negative_dpi_and_writes_nothing(tmp_path):
    r = capred.run_shear(capred.sample_path("shear"), ShearOptions(bootstrap=0))
    with pytest.raises(OptionError, match=r"dpi \(--dpi\)"):
        capred.write_outputs(r, tmp_path / "out", dpi=-3)
    assert not (tmp_path / "out").exists()  # outputs whole or not at all
