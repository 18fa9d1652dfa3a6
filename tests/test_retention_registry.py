"""The retention registry is the single place (issue 28.5): no retention model is named outside its entry in
the retention pipelines and figures; what they need (the default models, the hysteresis fit's model, the
power-law model of skempton-b and retention-convert, derived quantities, branch styles) comes from fields."""

import ast
from pathlib import Path

import pytest

import capred
from capred.fitting import retention_models as rm
from capred.pipelines.retention import RetentionOptions
from capred.pipelines.retention_convert import ConvertOptions

ROOT = Path(__file__).resolve().parents[1] / "capred"
FILES = [
    "pipelines/retention.py",
    "pipelines/retention_convert.py",
    "report/retention_figures.py",
    "report/retention_tables.py",
    "physics/retention.py",
    "fitting/nonlinear.py",
]


def _code_strings(path: Path) -> list[tuple[int, str]]:
    """String constants of a module that are not docstrings (module, class, function)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                docs.add(id(body[0].value))
    return [
        (n.lineno, n.value)
        for n in ast.walk(tree)
        if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in docs
    ]


@pytest.mark.parametrize("name", FILES)
def test_no_retention_model_is_named_outside_the_registry(name):
    names = set(rm.MODELS)
    found = [(line, v) for line, v in _code_strings(ROOT / name) if v in names]
    assert not found, f"{name} names registered models in code: {found}"


def test_the_registry_module_names_its_models_only_in_their_entries():
    """In spec/retention_models.py (the declarations) a model's key appears once, as its entry's name; the
    numerical module fitting/retention_models.py names none."""
    strings = [v for _, v in _code_strings(ROOT / "spec" / "retention_models.py")]
    numerical = [v for _, v in _code_strings(ROOT / "fitting" / "retention_models.py")]
    for key in rm.MODELS:
        assert strings.count(key) == 1 and numerical.count(key) == 0, key


def test_what_the_pipelines_need_comes_from_registry_fields():
    assert RetentionOptions().models == tuple(k for k, m in rm.MODELS.items() if m.default) == rm.default_models()
    assert ConvertOptions().to == rm.power_law_model().name and rm.power_law_model().power_law == ("s_e", "lam")
    assert sum(m.hysteresis_base for m in rm.MODELS.values()) == 1
    assert sum(m.power_law is not None for m in rm.MODELS.values()) == 1
    r = capred.run_retention(
        capred.sample_path("retention"), RetentionOptions(models=("bc",), hysteresis="kool-parker")
    )
    base = rm.hysteresis_model().name
    # the hysteresis fit's model is fitted to each branch alone as well, and its derived m = 1 - 1/n reported
    assert set(r.fits["drying"]) == {"bc", base} and r.independent_aicc() is not None
    js = r.to_json()["branches"]["drying"]["fits"][base]
    n = js["n"]
    assert js["m"] == pytest.approx(1 - 1 / n, rel=1e-15)  # van Genuchten (1980) eq. 21: m = 1 - 1/n
    assert "m" not in r.to_json()["branches"]["drying"]["fits"]["bc"]
