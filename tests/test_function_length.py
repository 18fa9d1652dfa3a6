"""No function of capred/pipelines or capred/cli longer than 100 lines, docstring aside (issue 42, point 3).

A long function mixes steps; each step is a function named after what it does. The length is counted from the
first statement after the docstring to the last line of the body (blank and comment lines inside included), as
the issue counted it; nested functions are measured on their own as well as inside their parent.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import capred

ROOT = Path(capred.__file__).resolve().parent
FOLDERS = ("pipelines", "cli")
LIMIT = 100


def body_lines(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of a function's body, its docstring left out."""
    body = fn.body
    first = body[0]
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
        body = body[1:]
    if not body:
        return 0
    return body[-1].end_lineno - body[0].lineno + 1


def long_functions(folder: Path, limit: int = LIMIT) -> list[str]:
    """'path:line name (n lines)' for every function of ``folder`` whose body exceeds ``limit`` lines."""
    out = []
    for path in sorted(folder.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and body_lines(node) > limit:
                out.append(f"{path.relative_to(folder.parent)}:{node.lineno} {node.name} ({body_lines(node)} lines)")
    return out


def test_the_counter_counts_body_lines_without_the_docstring():
    """Checked by hand on two small functions: 3 statements on 3 lines after a 3-line docstring; one statement
    over 4 lines and no docstring."""
    src = 'def f():\n    """Doc.\n\n    More."""\n    a = 1\n    b = 2\n    return a + b\n\n\ndef g():\n    return (\n        1,\n        2,\n    )\n'
    f, g = ast.parse(src).body
    assert body_lines(f) == 3
    assert body_lines(g) == 4


def test_the_counter_finds_a_long_function(tmp_path):
    """A function of 101 body lines is named; one of 100 is not."""
    (tmp_path / "m.py").write_text(
        "def long():\n" + "    x = 1\n" * 101 + "\n\ndef short():\n" + "    x = 1\n" * 100, encoding="utf-8"
    )
    found = long_functions(tmp_path)
    assert len(found) == 1 and " long (101 lines)" in found[0]


@pytest.mark.parametrize("folder", FOLDERS)
def test_no_function_over_100_lines(folder):
    assert not long_functions(ROOT / folder), "split these into named steps:\n" + "\n".join(
        long_functions(ROOT / folder)
    )
