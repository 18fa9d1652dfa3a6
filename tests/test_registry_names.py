"""A registered name is spelled only in its registry (issue 28 item 5).

Every effective-stress model, χ law, bridge law and retention model is one registry entry; the rest of the
package reaches it through the entry's fields, never by comparing or indexing with its name. The check reads
every module of ``capred/`` as Python (``ast``) and collects the string constants equal to a registered name
(docstrings and messages that mention a name inside longer text are not constants equal to it). A constant
outside its registry module is a special case, unless it is on the allow-list below.
"""

import ast
from functools import cache
from pathlib import Path

import pytest

import capred
from capred.fitting.chi_laws import LAWS as CHI_LAWS
from capred.fitting.retention_models import MODELS as RETENTION_MODELS
from capred.physics.bridge_laws import LAWS as BRIDGE_LAWS
from capred.physics.effective_stress_models import REGISTRY as STRESS_MODELS

PACKAGE = Path(capred.__file__).parent

#: registry module (relative to capred/) -> the names it registers; a name registered in two families (the fitted
#: χ laws are effective-stress models too) may be spelled in both registry modules. Each family has two: its
#: numpy-free declarations (capred/spec/) and the numerical functions they name.
REGISTRIES = {
    "spec/effective_stress.py": set(STRESS_MODELS),
    "physics/effective_stress_models.py": set(STRESS_MODELS),
    "spec/chi_laws.py": set(CHI_LAWS),
    "fitting/chi_laws.py": set(CHI_LAWS),
    "spec/bridge_laws.py": set(BRIDGE_LAWS),
    "physics/bridge_laws.py": set(BRIDGE_LAWS),
    "spec/retention_models.py": set(RETENTION_MODELS),
    "fitting/retention_models.py": set(RETENTION_MODELS),
}

#: TO BE EMPTIED: modules owned by other work that still special-case a registered name (file -> names). Keep it as
#: short as true: `test_allow_list_is_as_short_as_true` fails on an entry that no longer special-cases, so remove
#: the entry when its site moves into the registry entry.
ALLOWED = {
    # shear reads a fits.json of vg / bc into van Genuchten or Brooks-Corey parameters of the models
    "pipelines/shear.py": {"vg", "vg_m_free", "bc"},
    "pipelines/shear_analysis.py": {"vg"},
}

#: not special cases: a command's registry entry names a model as the value of an option of its example run (data,
#: like a sample file; `capred retention-convert` requires --to)
EXAMPLE_VALUES = {"reductions.py": {"bc"}}


def registered_names() -> dict[str, set[str]]:
    """name -> the registry modules where it may be spelled."""
    out: dict[str, set[str]] = {}
    for module, names in REGISTRIES.items():
        for name in names:
            out.setdefault(name, set()).add(module)
    return out


def name_constants(path: Path, names) -> set[str]:
    """The registered names spelled as a whole string constant in one module."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    return {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)} & set(names)


@cache
def spellings() -> dict[str, frozenset[str]]:
    """module (relative to capred/) -> the registered names spelled in it, outside their own registry modules."""
    names = registered_names()
    out: dict[str, frozenset[str]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        module = path.relative_to(PACKAGE).as_posix()
        found = {n for n in name_constants(path, names) if module not in names[n]}
        if found:
            out[module] = frozenset(found)
    return out


def test_registries_are_not_empty():
    # the check below means nothing if a registry could not be read
    for module, names in REGISTRIES.items():
        assert names, module
        assert (PACKAGE / module).is_file(), module


def test_name_constants_finds_a_special_case(tmp_path):
    # the detector itself: a comparison with a name is found, the name inside a sentence is not
    path = tmp_path / "m.py"
    path.write_text('def f(m):\n    """Uses bishop."""\n    return m == "bishop" or "own2 is long"\n')
    assert name_constants(path, {"bishop", "own2"}) == {"bishop"}


def test_registered_names_are_spelled_only_in_their_registry():
    found = spellings()
    allowed = {m: ALLOWED.get(m, set()) | EXAMPLE_VALUES.get(m, set()) for m in found}
    unexpected = {m: sorted(v - allowed[m]) for m, v in found.items() if v - allowed[m]}
    assert unexpected == {}, (
        "a registered name is special-cased outside its registry: put what the site needs in a field of the "
        f"registry entry ({unexpected})"
    )


@pytest.mark.parametrize("module", sorted(ALLOWED) + sorted(EXAMPLE_VALUES))
def test_allow_list_is_as_short_as_true(module):
    still = spellings().get(module, set())
    stale = sorted((ALLOWED.get(module, set()) | EXAMPLE_VALUES.get(module, set())) - still)
    assert not stale, f"{module} no longer special-cases {stale}: remove them from ALLOWED in this test"
