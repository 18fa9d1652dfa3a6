"""No import circles, and imports go down the layers (issues 28.7 and 42): a static import graph of every capred
module (ast, nothing executed), so a circle cannot come back unnoticed; and every module imports.

Layers, top to bottom: cli -> batch -> pipelines, result (a Result displays itself through report/) -> io, report,
lab_store -> the records (records, spool, user_units, csv_headers, inputs, table_spec) -> fitting -> physics ->
the base modules (errors, units, nomenclature, ...). A module may import from its own layer or below, at load
time or inside a function: no import goes up, and the graph of every import (inside functions too) has no
circle.
"""

import ast
import functools
import importlib
from pathlib import Path

import pytest

import capred
import capred.io

PACKAGE = Path(capred.__file__).resolve().parent
#: layer of each top-level part of capred (a higher layer may import a lower one, never the reverse)
LAYERS = {
    "testing": 7,  # the shipped conformance checks: run an entry as the commands do (pipelines, report)
    "cli": 7,
    "batch": 6,
    "pipelines": 5,
    "io": 4,
    "report": 4,
    "lab_store": 4,  # the SQLite store of a lab's runs: files, as io/
    "result": 5,  # Options and Result: a Result displays itself through report/ (report.notebook)
    # what io/ and report/ read of a run: the records' mapping to JSON and tables, and its pieces
    **dict.fromkeys(("records", "spool", "user_units", "csv_headers", "inputs", "table_spec"), 3),
    "fitting": 2,
    "physics": 1,
    **{
        base: 0
        for base in (
            "errors",
            "units",
            "nomenclature",
            "references",
            "parameters",
            "sampling",
            "progress",
            "samples",
            "reductions",
            "text_safety",  # pure string rules for terminals, HTML and SVG
            "spec",  # numpy-free declarations: the registries, their functions named as "module:function"
        )
    },
}
#: imports inside functions that go up a layer, with why
LAZY_UP = {
    # an Options class (capred.spec, numpy-free so that --help is cheap) whose checks need numerics when the
    # options are built: imported inside the method, at run time only
    ("capred.spec.calculators", "capred.physics.calculators"): "skempton-b --compare: the relations' names",
    ("capred.spec.calculators", "capred.physics.skempton_elastoplastic"): "skempton-b: the bounding surface's check",
    ("capred.spec.pt_volume", "capred.physics.pedrotti_tarantino"): "pt-volume: the model's parameters",
    ("capred.spec.pt_volume", "capred.pipelines.compression"): "pt-volume --compression-w: a compression.json",
    ("capred.spec.retention", "capred.fitting.retention_models"): "retention --fixed: the parameters' JSON names",
}


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = ["capred", *path.relative_to(PACKAGE).with_suffix("").parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()
#: capred.io's public names and the submodule of each (capred/io/__init__.py)
IO_API = capred.io._WHERE


def _targets(module: str, node, package: bool) -> list[str]:
    """The capred modules an import statement names (a name imported from a package that is a module counts
    as that module)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names if a.name.split(".")[0] == "capred"]
    base = module.split(".") if package else module.split(".")[:-1]
    if node.level:
        base = base[: len(base) - (node.level - 1)]
        target = ".".join(base + ([node.module] if node.module else []))
    else:
        target = node.module or ""
    if target.split(".")[0] != "capred":
        return []
    return [_where(target, a.name) for a in node.names]


def _where(target: str, name: str) -> str:
    """The module ``from target import name`` loads: a submodule of that name, or for a name of capred.io's
    public API (imported from its submodule on first use) that submodule, else ``target`` itself."""
    if f"{target}.{name}" in MODULES:
        return f"{target}.{name}"
    if target == "capred.io" and name in IO_API:
        return f"capred.io.{IO_API[name]}"
    return target


@functools.cache
def _tree(path: Path) -> ast.Module:
    """The syntax tree of a capred module, parsed once per test session (the tests below only read it)."""
    return ast.parse(path.read_text(encoding="utf-8"))


@functools.cache
def graph() -> dict[str, tuple[set[str], set[str]]]:
    """module -> (modules imported when it is imported, modules imported only inside its functions); computed
    once per session (several tests read it; every module's source is parsed once)."""
    out = {}
    for module, path in MODULES.items():
        tree = _tree(path)
        package = path.name == "__init__.py"
        now: set[str] = set()
        for node in tree.body:  # module level (also under if/try at module level)
            for sub in ast.walk(node) if isinstance(node, (ast.If, ast.Try)) else [node]:
                if isinstance(sub, (ast.Import, ast.ImportFrom)):
                    now.update(_targets(module, sub, package))
        every = {
            t
            for n in ast.walk(tree)
            if isinstance(n, (ast.Import, ast.ImportFrom))
            for t in _targets(module, n, package)
        }
        out[module] = (
            {t for t in now if t in MODULES and t != module},
            {t for t in every - now if t in MODULES and t != module},
        )
    return out


def layer(module: str) -> int | None:
    parts = module.split(".")
    return LAYERS.get(parts[1]) if len(parts) > 1 else None  # capred itself (the API) stands above all


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in edges:
        if v not in index:
            visit(v)
    return out


def test_every_module_has_a_layer():
    assert all(layer(m) is not None for m in MODULES if m not in ("capred", "capred.__main__")), [
        m for m in MODULES if layer(m) is None and m not in ("capred", "capred.__main__")
    ]


def test_no_import_circle_when_modules_load():
    g = graph()
    assert cycles({m: now for m, (now, _) in g.items()}) == []


def test_imports_go_down_the_layers():
    up = []
    for module, (now, later) in graph().items():
        for target in now | later:
            a, b = layer(module), layer(target)
            if a is None or b is None or b <= a:
                continue
            if target in later and (module, target) in LAZY_UP:
                continue
            up.append((module, target, "at import" if target in now else "in a function"))
    assert up == []


def test_the_former_circles_are_gone():
    """result.py -> report (only report.notebook, inside Result's display methods), and no module of report/,
    io/ or lab_store imports result.py (they read the records' modules below it), at load time or later."""
    now, later = graph()["capred.result"]
    assert not [t for t in now if t.startswith(("capred.report", "capred.io"))]
    assert {t for t in later if t.startswith("capred.report")} <= {"capred.report.notebook"}
    below = [m for m in MODULES if m.startswith(("capred.report", "capred.io", "capred.lab_store"))]
    assert [m for m in below if "capred.result" in graph()[m][0] | graph()[m][1]] == []


#: circles of the full graph that are known and being removed elsewhere, with why (keep it empty)
KNOWN_CIRCLES: dict[tuple[str, ...], str] = {}


def every_import() -> dict[str, set[str]]:
    """module -> every capred module it names in an import statement anywhere: at load time, inside functions,
    under ``if TYPE_CHECKING`` (what a PEP 562 ``__getattr__`` loads is named there). ``from ..io import X``
    is an edge to the submodule ``capred.io.X`` when there is one, else to the package ``capred.io``."""
    out = {}
    for module, path in MODULES.items():
        package = path.name == "__init__.py"
        names = set()
        for node in ast.walk(_tree(path)):
            if isinstance(node, ast.Import):
                names.update(a.name for a in node.names if a.name.split(".")[0] == "capred")
            elif isinstance(node, ast.ImportFrom):
                base = module.split(".") if package else module.split(".")[:-1]
                if node.level:
                    base = base[: len(base) - (node.level - 1)]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                if target.split(".")[0] == "capred":
                    names.update(
                        f"{target}.{a.name}" if f"{target}.{a.name}" in MODULES else target for a in node.names
                    )
        out[module] = {t for t in names if t in MODULES and t != module}
    return out


def test_no_import_circle_counting_imports_inside_functions():
    """Issue 42: the graph of every import, inside functions too, has no circle (each is named if one comes
    back: move the code to the layer it belongs to, do not hide the import)."""
    found = [c for c in cycles(every_import()) if tuple(c) not in KNOWN_CIRCLES]
    assert found == [], "import circles:\n" + "\n".join(" <-> ".join(c) for c in found)


def test_every_known_circle_is_still_there():
    """An exception outlives its circle by no commit: once the circle is gone, its entry goes too."""
    found = {tuple(c) for c in cycles(every_import())}
    assert [c for c in KNOWN_CIRCLES if c not in found] == []


def test_the_circle_finder_finds_circles():
    """The finder itself, on a made-up graph: a 3-circle and a 2-circle are found, a chain and a self-import are
    not."""
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": {"e"}, "e": {"d"}, "f": {"f", "a"}}
    assert sorted(cycles(edges)) == [["a", "b", "c"], ["d", "e"]]


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m != "capred.__main__"))
def test_every_module_imports(module):
    importlib.import_module(module)


#: cross-module uses of a private name that are allowed, with why (keep it empty or tiny)
PRIVATE_ALLOWED: dict[tuple[str, str, str], str] = {}


def private_uses(sources: dict[str, str] | None = None) -> list[tuple[str, str, str, int]]:
    """(module, module it uses, private name, line) of every private name (one leading underscore, not a dunder)
    that a capred module imports from another (``from X import _name``) or reads off another module it imported
    (``X._name``). ``sources``: module -> source text (default: every capred module, read from disk)."""
    trees = (
        {m: _tree(p) for m, p in MODULES.items()}
        if sources is None
        else {m: ast.parse(text) for m, text in sources.items()}
    )
    out = []
    for module, tree in trees.items():
        package = module in MODULES and MODULES[module].name == "__init__.py"
        bound: dict[str, str] = {}  # local name -> capred module it stands for
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                bound.update({a.asname or a.name: a.name for a in node.names if a.name in MODULES})
            elif isinstance(node, ast.ImportFrom):
                for a, target in zip(node.names, _targets(module, node, package)):
                    if target in MODULES and target.endswith("." + a.name):
                        bound[a.asname or a.name] = target
                    elif a.name.startswith("_") and not a.name.startswith("__") and target != module:
                        out.append((module, target, a.name, node.lineno))
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in bound:
                name, target = node.attr, bound[node.value.id]
                if name.startswith("_") and not name.startswith("__") and target != module:
                    out.append((module, target, name, node.lineno))
    return out


def test_no_private_name_is_used_across_modules():
    """Issue 28.7: a helper another module needs is public (with its numpydoc docstring) or lives there."""
    assert len(PRIVATE_ALLOWED) <= 3  # tiny, each with its reason
    used = [u for u in private_uses() if u[:3] not in PRIVATE_ALLOWED]
    assert used == [], used


def test_the_private_name_scan_finds_what_it_should():
    """The scan itself: both spellings of a cross-module private use are caught (relative and absolute
    imports); a module's own private names and dunders are not."""
    probe = (
        "from capred.io import table\nfrom . import grid as g\nfrom .table import _x, read_table\n"
        "table._y\ng._z\ng.__doc__\n_own = 1\n"
    )
    found = {(t, n) for m, t, n, _ in private_uses({"capred.io.probe": probe})}
    assert found == {("capred.io.table", "_x"), ("capred.io.table", "_y"), ("capred.io.grid", "_z")}


def test_io_has_a_small_public_api():
    """Issue 28.7: capred.io's ``__all__`` names what the other layers use, each from its one submodule, loaded on
    first use; and every name another layer imports from a submodule of io is in that API."""
    import capred.io as io

    assert sorted(io.__all__) == sorted(IO_API)
    for name in io.__all__:
        sub = importlib.import_module(f"capred.io.{IO_API[name]}")
        assert getattr(io, name) is getattr(sub, name), name
    with pytest.raises(AttributeError):
        io.not_a_name  # noqa: B018
    outside = set()
    for module, path in MODULES.items():
        if module.startswith("capred.io"):
            continue
        tree = _tree(path)
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                for a, target in zip(node.names, _targets(module, node, path.name == "__init__.py")):
                    if target.startswith("capred.io.") and not target.endswith("." + a.name):
                        outside.add(a.name)
    assert outside <= set(io.__all__), outside - set(io.__all__)
