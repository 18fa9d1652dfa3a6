"""Bundled sample data (synthetic; see sample_data/README.md)."""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

SAMPLES = {
    "shear": "shear_tests.csv",
    "triaxial-bounds": "triaxial_tests.csv",
    "triaxial-curves": "triaxial_curves.csv",
    "retention": "retention.csv",
    "prism": "prism_tests.csv",
    "skempton-b": "skempton_cases.csv",
    "rumpf": "rumpf_cases.csv",
    "bridge-solve": "bridge_cases.csv",
    "bridge-compare": "bridge_micro_tests.csv",
    "bridge-rupture": "bridge_rupture.csv",
    "bridge-laws": "bridge_laws_grid.csv",
    "shear-export": "shear_tests_export.xlsx",
    "shear-eu": "shear_tests_eu.csv",
    "shear-curves": "shear_curves.csv",
    "triaxial-export": "triaxial_export",
    "pt-volume": "pt_volume_path.csv",
    "triaxial-groups": "triaxial_groups.csv",
    "retention-convert": "retention_fits.json",
    "history": "lab_history.sqlite",
    "compression": "compression_oedometer.csv",
    "triaxial": "triaxial_failure_states.csv",
}


def sample_path(name: str) -> Path:
    """Path of a bundled sample file, by command name (e.g. 'shear').

    Parameters
    ----------
    name : str
        A key of ``SAMPLES``; another name raises OptionError.

    Returns
    -------
    pathlib.Path
    """
    from .errors import OptionError

    if name not in SAMPLES:
        raise OptionError(f"no sample for '{name}'; there are: {', '.join(SAMPLES)}")
    try:  # installed: the top-level sample_data/ folder ships as capred.sample_data
        folder = Path(str(files("capred.sample_data")))
    except ModuleNotFoundError:  # imported from a source checkout
        folder = Path(__file__).resolve().parents[1] / "sample_data"
    return folder / SAMPLES[name]
