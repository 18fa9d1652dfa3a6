"""Numpydoc sections on the public functions and methods of capred (issue 42, point 5).

The form of every docstring (summary line, blank lines, raw strings, no undocumented public name) is ruff's
``D`` rules with the numpy convention, configured in pyproject.toml and run by ``ruff check .`` in CI, as
pastas does. What ruff does not check is whether a docstring has the sections its function needs; this file
measures that:

- a public function is a module-level function of ``capred/`` whose name has no leading underscore, in a
  module whose name has none either; a public method is such a function in a public class (dunders are
  private names; properties need only their docstring, as numpydoc documents them like attributes);
- it "has its sections" when its docstring exists and has ``Parameters`` when it takes arguments (besides
  self/cls) and ``Returns`` (or ``Yields``) when it returns or yields a value; for the public functions of
  ``capred/physics/`` and ``capred/fitting/`` (the science) also ``References``, as STYLE.md asks;
- the share of public functions, and that of public methods, that have their sections must each be at
  least ``FLOOR``.

Only the modules under the D rules are measured: a module pyproject.toml exempts from them (``per-file-ignores``
with "D", "until the #42 branches land") is left out, so each module joins the measure as it joins the lint.
The source is read, not imported: the measure needs no numpy and sees each function as written.
"""

import ast
import fnmatch
import inspect
import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "capred"

#: the share of public functions, and of public methods, that must have their numpydoc sections (issue 42)
FLOOR = 0.95

#: the packages whose public functions cite their sources in a References section (STYLE.md, after pvlib)
SCIENCE = ("capred/physics/", "capred/fitting/")

_SECTION = re.compile(r"^[ \t]*([A-Z][A-Za-z ]+?)[ \t]*\n[ \t]*-{3,}[ \t]*$", re.MULTILINE)


def sections(doc: str | None) -> set[str]:
    """Titles of the numpydoc sections of a docstring, as numpydoc writes them (title, then dashes)."""
    return {m.group(1) for m in _SECTION.finditer(inspect.cleandoc(doc or ""))}


def _decorators(fn: ast.FunctionDef) -> set[str]:
    out = set()
    for d in fn.decorator_list:
        d = d.func if isinstance(d, ast.Call) else d
        out.add(d.attr if isinstance(d, ast.Attribute) else getattr(d, "id", ""))
    return out


def _returns_value(fn: ast.FunctionDef) -> bool:
    """Whether ``fn`` itself (not a function nested in it) returns or yields a value other than None."""
    stack = list(fn.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
            continue
        if isinstance(node, (ast.Return, ast.Yield)) and node.value is not None:
            if not (isinstance(node.value, ast.Constant) and node.value.value is None):
                return True
        if isinstance(node, ast.YieldFrom):
            return True
        stack.extend(ast.iter_child_nodes(node))
    return False


def missing_sections(fn: ast.FunctionDef, method: bool = False, science: bool = False) -> list[str]:
    """The numpydoc sections ``fn``'s docstring needs and lacks ("docstring" when it has none)."""
    doc = ast.get_docstring(fn)
    if not doc or not doc.strip():
        return ["docstring"]
    decorators = _decorators(fn)
    if decorators & {"property", "cached_property"}:
        return []
    have = sections(doc)
    args = fn.args
    names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]
    names += [a.arg for a in (args.vararg, args.kwarg) if a is not None]
    if method and "staticmethod" not in decorators:
        names = names[1:]  # self or cls
    need = []
    if names and not have & {"Parameters", "Other Parameters"}:
        need.append("Parameters")
    if _returns_value(fn) and not have & {"Returns", "Yields"}:
        need.append("Returns")
    if science and not method and "References" not in have:
        need.append("References")
    return need


def _exempt_patterns() -> list[str]:
    """The per-file-ignores of pyproject.toml that switch the D rules off (globs relative to the root)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    ignores = config["tool"]["ruff"]["lint"].get("per-file-ignores", {})
    return [pattern for pattern, rules in ignores.items() if "D" in rules]


def public_callables(root: Path = PACKAGE, exempt: list[str] | None = None):
    """(qualified name, is_method, missing sections) of every public function and method under ``root``."""
    exempt = _exempt_patterns() if exempt is None else exempt
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if (path.name.startswith("_") and path.name != "__init__.py") or any(fnmatch.fnmatch(rel, p) for p in exempt):
            continue
        science = rel.startswith(SCIENCE)
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if not node.name.startswith("_") and "overload" not in _decorators(node):
                    yield f"{rel}:{node.name}", False, missing_sections(node, science=science)
            elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                for m in node.body:
                    if not isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) or m.name.startswith("_"):
                        continue
                    decorators = _decorators(m)
                    if "overload" in decorators or any(d in ("setter", "deleter") for d in decorators):
                        continue
                    yield f"{rel}:{node.name}.{m.name}", True, missing_sections(m, method=True)


def _parse_function(source: str) -> ast.FunctionDef:
    return ast.parse(inspect.cleandoc(source)).body[0]


def test_the_measure_on_examples():
    documented = _parse_function('''
        def f(x, *, y=1):
            """Twice x.

            Parameters
            ----------
            x : float
                A length [m].
            y : int
                Unused.

            Returns
            -------
            float
                2 x [m].

            References
            ----------
            .. [1] Someone (2024). doi:10.0/x, eq. 1.
            """
            return 2 * x
    ''')
    bare = _parse_function('''
        def g(x):
            """Twice x. Parameters: x [m]. Returns 2 x."""
            def inner():
                return 1
            if x:
                return 2 * x
    ''')
    procedure = _parse_function('''
        def h():
            """Print the answer."""
            def inner():
                return 42  # a nested function's return is not h's
            print(inner())
            return
    ''')
    generator = _parse_function('''
        def k(items):
            """The items.

            Parameters
            ----------
            items : list
                Anything.
            """
            yield from items
    ''')
    method = ast.parse(
        inspect.cleandoc('''
        class C:
            def m(self):
                """Nothing returned, no argument but self."""
            @property
            def p(self):
                """A value [m]."""
                return 1
            def n(self, x):
                """Takes x."""
        ''')
    ).body[0]
    m, p, n = method.body
    assert missing_sections(documented, science=True) == []
    assert missing_sections(bare) == ["Parameters", "Returns"]
    assert missing_sections(bare, science=True) == ["Parameters", "Returns", "References"]
    assert missing_sections(procedure) == []
    assert missing_sections(generator) == ["Returns"]
    assert missing_sections(m, method=True) == [] and missing_sections(p, method=True) == []
    assert missing_sections(n, method=True) == ["Parameters"]
    assert missing_sections(ast.parse("def q(x):\n    return x").body[0]) == ["docstring"]


def test_measured_modules_are_the_linted_ones():
    # the measure leaves out exactly what ruff's D rules leave out: a module exempted from both or from neither
    exempt = _exempt_patterns()
    assert "tests/**/*.py" in exempt
    measured = {name.split(":")[0] for name, _, _ in public_callables()}
    assert measured, "no module measured"
    assert not any(fnmatch.fnmatch(rel, p) for rel in measured for p in exempt)


def test_public_functions_and_methods_have_their_numpydoc_sections():
    items = list(public_callables())
    for methods in (False, True):
        kind = "methods" if methods else "functions"
        group = [(name, miss) for name, is_method, miss in items if is_method == methods]
        lacking = sorted(f"{name} {miss}" for name, miss in group if miss)
        share = 1 - len(lacking) / len(group)
        assert share >= FLOOR, (
            f"public {kind}: {share:.1%} of {len(group)} have their sections; lacking:\n" + "\n".join(lacking)
        )
