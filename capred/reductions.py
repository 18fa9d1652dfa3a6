"""Every command of capred as a reduction: ``run(source, options) -> Result``.

The functions are named as "module:function" and imported only when a
reduction runs, so that `capred --help` loads no numerical library.
"""
from __future__ import annotations

from dataclasses import dataclass
from importlib import import_module


@dataclass(frozen=True)
class Reduction:
    name: str  # the command as typed: "shear", "bridge solve"
    run_path: str  # "module:function" taking (source, options)
    options_path: str  # "module:class" of its options
    source: str  # "required", "optional" (cases from options or a file) or "none"
    sample: str | None  # key of capred.samples.SAMPLES
    out_prefix: str  # default output folder: ./capred_out/<prefix>_<input stem>

    def run(self, source, options):
        module, name = self.run_path.split(":")
        return getattr(import_module(module), name)(source, options)

    def options(self, **kw):
        module, name = self.options_path.split(":")
        return getattr(import_module(module), name)(**kw)


_P = "capred.pipelines."
REDUCTIONS: dict[str, Reduction] = {r.name: r for r in (
    Reduction("shear", _P + "shear:run_shear", _P + "shear:ShearOptions", "required", "shear", "shear"),
    Reduction("triaxial-bounds", _P + "triaxial:run_triaxial_bounds", _P + "triaxial:TriaxialOptions", "required",
              "triaxial-bounds", "triaxial"),
    Reduction("retention", _P + "retention:run_retention", _P + "retention:RetentionOptions", "required",
              "retention", "retention"),
    Reduction("prism", _P + "calculators:reduce_prism", _P + "calculators:PrismOptions", "optional", "prism",
              "prism"),
    Reduction("skempton-b", _P + "calculators:reduce_skempton_b", _P + "calculators:SkemptonOptions", "optional",
              "skempton-b", "skempton"),
    Reduction("rumpf", _P + "calculators:reduce_rumpf", _P + "calculators:RumpfOptions", "optional", "rumpf",
              "rumpf"),
    Reduction("bridge solve", _P + "bridge:solve_bridges", _P + "bridge:BridgeOptions", "required", "bridge-solve",
              "bridge"),
    Reduction("bridge compare", _P + "bridge:compare_measured", _P + "bridge:BridgeOptions", "required",
              "bridge-compare", "bridge_compare"),
    Reduction("bridge rupture", _P + "bridge:rupture_distances", _P + "bridge:BridgeOptions", "required",
              "bridge-rupture", "bridge_rupture"),
    Reduction("bridge yade-files", _P + "yade_files:reduce_yade_files", _P + "yade_files:YadeOptions", "none", None,
              "yade_files"),
    Reduction("bridge curve", _P + "bridge:reduce_curve", _P + "bridge:CurveOptions", "none", None, "bridge_curve"),
)}


def run(command: str, source=None, options=None, **option_values):
    """Run any command from a script: ``capred.run("shear", "tests.csv", gamma_w="10 kN/m^3")``."""
    red = REDUCTIONS[command]
    if options is None:
        options = red.options(**option_values)
    return red.run(source, options)
