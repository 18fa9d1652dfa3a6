"""The registries' declarations (capred/spec/) import no numerical library, and their callables resolve (issue 42)."""

import subprocess
import sys

import pytest

from capred.spec import bridge_laws, chi_laws, effective_stress, retention_models
from capred.spec.callables import ref_of, resolve

SPEC_MODULES = [
    "capred.spec.effective_stress",
    "capred.spec.retention_models",
    "capred.spec.bridge_laws",
    "capred.spec.chi_laws",
    "capred.spec.callables",
]
HEAVY = ("numpy", "scipy", "pandas", "pint", "matplotlib")

#: each registry and the fields of its entries that name a callable
CALLABLE_FIELDS = {
    "effective_stress": (effective_stress.REGISTRY, ("sigma_eff", "tau", "material_values", "chi_of_saturation")),
    "retention": (retention_models.MODELS, ("saturation", "inverse", "canonical")),
    "bridge": (bridge_laws.LAWS, ("force",)),
    "chi": (chi_laws.LAWS, ("chi", "fit", "refit_batch")),
}


@pytest.mark.parametrize("module", SPEC_MODULES)
def test_spec_module_imports_no_numerical_library(module):
    # a fresh interpreter: what the module loads, not what this test session already holds
    code = f"import sys, {module}; print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"{module} imports {out}"


def test_reading_the_registries_imports_no_numerical_library():
    # labels, names, references, the --models lookups and the declared references of every callable
    code = (
        "import sys\n"
        "from capred.spec import effective_stress as es, retention_models as rm, bridge_laws as bl, chi_laws as cl\n"
        "from capred.spec.callables import ref_of\n"
        "es.resolve_models('all'); list(es.MODEL_LABELS.values()); es.bridge_curve_models()\n"
        "[ref_of(e, 'sigma_eff') for e in es.REGISTRY.values()]\n"
        "[(m.help, m.parameter(m.names[0]).range_text, ref_of(m, 'derived')) for m in rm.MODELS.values()]\n"
        "[ref_of(law, 'force') for law in bl.LAWS.values()]; [ref_of(law, 'chi') for law in cl.LAWS.values()]\n"
        f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == ""


@pytest.mark.parametrize("family", sorted(CALLABLE_FIELDS))
def test_every_declared_callable_is_a_module_function_string_that_resolves(family):
    registry, names = CALLABLE_FIELDS[family]
    for key, entry in registry.items():
        for name in names:
            ref = ref_of(entry, name)
            if ref is None:
                continue
            assert isinstance(ref, str) and ":" in ref, (key, name, ref)  # shipped entries are declared as strings
            assert callable(resolve(ref)) and getattr(entry, name) is resolve(ref), (key, name)


def test_the_old_import_paths_are_the_same_registries():
    from capred.fitting import chi_laws as fit_chi
    from capred.fitting import retention_models as fit_rm
    from capred.physics import bridge_laws as phys_bl
    from capred.physics import effective_stress_models as esm

    assert (
        esm.REGISTRY is effective_stress.REGISTRY and esm.EffectiveStressModel is effective_stress.EffectiveStressModel
    )
    assert fit_rm.MODELS is retention_models.MODELS is fit_rm.REGISTRY
    assert phys_bl.LAWS is bridge_laws.LAWS and fit_chi.LAWS is chi_laws.LAWS


def test_resolve_takes_a_string_or_a_callable_and_names_what_is_wrong():
    import math

    assert resolve("math:sqrt")(9.0) == 3.0  # exact in binary floating point
    assert resolve(math.cos) is math.cos and resolve(None) is None
    assert resolve("os.path:join") is resolve("os.path:join")  # imported once, cached
    with pytest.raises(ValueError, match="module:function"):
        resolve("math.sqrt")
    with pytest.raises(ValueError, match="has no 'nothing'"):
        resolve("math:nothing")
    with pytest.raises(ValueError, match="not a function"):
        resolve("math:pi")
    with pytest.raises(ValueError, match="a callable or"):
        resolve(3.0)


def test_a_callable_field_keeps_what_was_declared_through_replace():
    import dataclasses

    entry = effective_stress.REGISTRY["bishop"]
    assert ref_of(entry, "sigma_eff") == "capred.physics.effective_stress_models:_bishop"
    assert ref_of(entry, "tau") is None and entry.tau is None

    def mine(d):
        return d.sigma_N

    other = dataclasses.replace(entry, name="mine", sigma_eff=mine)
    assert other.sigma_eff is mine and ref_of(other, "sigma_eff") is mine
    assert other.chi_of_saturation is entry.chi_of_saturation  # the rest carried over
