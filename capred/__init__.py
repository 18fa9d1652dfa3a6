"""capred: capillary effective stress and strength from unsaturated-soil lab tests.

Use from a lab script::

    import capred
    result = capred.run_shear("tests.csv", capred.ShearOptions(gamma_w="10 kN/m^3"))
    result.table()          # pandas DataFrame, one row per test
    result.to_json()        # the same document as `capred shear tests.csv --json`
    capred.write_outputs(result, "report")   # the files `capred shear --out report` writes

Heavy modules (pandas, scipy, matplotlib, pint) load only when used.
"""

from __future__ import annotations

from importlib import import_module

__version__ = "0.1.0"

_API = {
    "run": "capred.reductions",
    "write_outputs": "capred.report.outputs",
    "run_shear": "capred.pipelines.shear_run",
    "ShearOptions": "capred.spec.shear",  # its declaration (numpy-free)
    "ModelParams": "capred.spec.shear",  # its declaration (numpy-free)
    "ShearResult": "capred.pipelines.shear",
    "run_triaxial_bounds": "capred.pipelines.triaxial",
    "TriaxialOptions": "capred.spec.triaxial",  # its declaration (numpy-free)
    "TriaxialResult": "capred.pipelines.triaxial",
    "run_triaxial_strength": "capred.pipelines.triaxial_strength",
    "TriaxialStrengthOptions": "capred.spec.triaxial_strength",  # its declaration (numpy-free)
    "TriaxialStrengthResult": "capred.pipelines.triaxial_strength",
    "fit_extended_mc": "capred.fitting.extended_mc",
    "complete_state": "capred.physics.phase",
    "run_retention": "capred.pipelines.retention",
    "RetentionOptions": "capred.spec.retention",  # its declaration (numpy-free)
    "RetentionResult": "capred.pipelines.retention",
    "convert_retention": "capred.pipelines.retention_convert",
    "run_prism": "capred.pipelines.calculators",
    "run_skempton_b": "capred.pipelines.calculators",
    "run_rumpf": "capred.pipelines.calculators",
    "run_pt_volume": "capred.pipelines.pt_volume",
    "PTVolumeOptions": "capred.spec.pt_volume",  # its declaration (numpy-free)
    "PTVolumeResult": "capred.pipelines.pt_volume",
    "solve_bridges": "capred.pipelines.bridge",
    "bridge_curve": "capred.pipelines.bridge",
    "compare_measured": "capred.pipelines.bridge",
    "rupture_distances": "capred.pipelines.bridge",
    "compare_laws": "capred.pipelines.bridge_laws",
    "sample_path": "capred.samples",
    "history": "capred.lab_store",
    "run_history": "capred.pipelines.history",
    "CapredError": "capred.errors",
    "InputError": "capred.errors",
    "OptionError": "capred.errors",
    "OutputError": "capred.errors",
    "FitError": "capred.errors",
    "MissingFileError": "capred.errors",
    "CapredWarning": "capred.errors",
}


def _warning(run):
    """The public form of a run function: the result's warnings are also emitted as CapredWarning."""
    import functools

    @functools.wraps(run)
    def public(*args, **kwargs):
        import warnings

        from .errors import CapredWarning
        from .text_safety import visible

        result = run(*args, **kwargs)
        for text in result.all_warnings():  # shown on a terminal: control characters as escapes
            warnings.warn(visible(text), CapredWarning, stacklevel=2)
        return result

    return public


__all__ = ["__version__", *_API]


def __dir__() -> list[str]:
    return sorted(__all__)


def __getattr__(name: str):
    if name in _API:
        value = getattr(import_module(_API[name]), name)
        if (
            name == "run"
            or name.startswith("run_")
            or name in ("solve_bridges", "bridge_curve", "compare_measured", "rupture_distances", "convert_retention")
        ):
            value = globals().setdefault(f"_public_{name}", _warning(value))
        return value
    raise AttributeError(f"module 'capred' has no attribute '{name}'")
