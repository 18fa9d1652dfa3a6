"""capred: capillary effective stress and strength from unsaturated-soil lab tests.

Use from a lab script::

    import capred
    result = capred.run_shear("tests.csv")
    result.table()          # pandas DataFrame, one row per test
    result.to_json()        # fits, predictions, metrics, best model

Heavy modules (pandas, scipy, matplotlib, pint) load only when used.
"""
from __future__ import annotations

from importlib import import_module

__version__ = "0.1.0"

_API = {
    "run_shear": "capred.pipelines.shear",
    "ShearOptions": "capred.pipelines.shear",
    "ShearResult": "capred.pipelines.shear",
    "write_shear_outputs": "capred.pipelines.shear",
    "run_triaxial_bounds": "capred.pipelines.triaxial",
    "TriaxialOptions": "capred.pipelines.triaxial",
    "TriaxialResult": "capred.pipelines.triaxial",
    "write_triaxial_outputs": "capred.pipelines.triaxial",
    "run_retention": "capred.pipelines.retention",
    "RetentionOptions": "capred.pipelines.retention",
    "write_retention_outputs": "capred.pipelines.retention",
    "run_prism": "capred.pipelines.calculators",
    "run_skempton_b": "capred.pipelines.calculators",
    "run_rumpf": "capred.pipelines.calculators",
    "solve_bridges": "capred.pipelines.bridge",
    "bridge_curve": "capred.pipelines.bridge",
    "compare_measured": "capred.pipelines.bridge",
    "sample_path": "capred.samples",
    "CapredError": "capred.errors",
    "InputError": "capred.errors",
    "FitError": "capred.errors",
}

__all__ = ["__version__", *_API]


def __getattr__(name: str):
    if name in _API:
        return getattr(import_module(_API[name]), name)
    raise AttributeError(f"module 'capred' has no attribute '{name}'")
