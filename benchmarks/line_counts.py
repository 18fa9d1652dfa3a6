"""Lines of capred/ per layer at a git commit: physical lines and code lines.

Code lines leave out docstrings, comments and blank lines, so that documenting a function does not read as
machinery. The machinery is cli/, io/, report/, pipelines/ and the top-level modules (issue 42); the science is
physics/ and fitting/; spec/ holds the numpy-free declarations.

Usage (from the repository root)::

    python benchmarks/line_counts.py 570d5d3 HEAD
"""

from __future__ import annotations

import ast
import io
import subprocess
import sys
import tokenize

MACHINERY = ("cli", "io", "report", "pipelines", "top level")
SKIPPED = (tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT, tokenize.ENDMARKER)


def _git(*args: str) -> str:
    return subprocess.run(["git", *args], capture_output=True, text=True, check=True).stdout


def _docstring_lines(tree: ast.AST) -> set[int]:
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if (
                isinstance(first, ast.Expr)
                and isinstance(first.value, ast.Constant)
                and isinstance(first.value.value, str)
            ):
                out.update(range(first.lineno, first.end_lineno + 1))
    return out


def counts(rev: str) -> dict[str, list[int]]:
    """{layer: [physical lines, code lines]} of capred/ at ``rev``."""
    out: dict[str, list[int]] = {}
    for path in _git("ls-tree", "-r", "--name-only", rev, "capred").split():
        if not path.endswith(".py"):
            continue
        src = _git("show", f"{rev}:{path}")
        docs = _docstring_lines(ast.parse(src))
        code = {
            line
            for tok in tokenize.generate_tokens(io.StringIO(src).readline)
            if tok.type not in SKIPPED
            for line in range(tok.start[0], tok.end[0] + 1)
            if line not in docs
        }
        parts = path.split("/")
        layer = parts[1] if len(parts) > 2 else "top level"
        row = out.setdefault(layer, [0, 0])
        row[0] += src.count("\n")
        row[1] += len(code)
    return out


def main(revs: list[str]) -> None:
    """Print a table of the layers' lines at each commit."""
    table = {rev: counts(rev) for rev in revs}
    layers = sorted({layer for c in table.values() for layer in c})
    print("layer".ljust(12) + "".join(f"{rev[:10]:>24}" for rev in revs))
    print(" " * 12 + "".join(f"{'physical':>12}{'code':>12}" for _ in revs))
    for name, rows in [(layer, [layer]) for layer in layers] + [("machinery", MACHINERY), ("total", layers)]:
        cells = "".join(
            f"{sum(c.get(r, [0, 0])[0] for r in rows):>12,}{sum(c.get(r, [0, 0])[1] for r in rows):>12,}"
            for c in table.values()
        )
        print(name.ljust(12) + cells)


if __name__ == "__main__":
    main(sys.argv[1:] or ["HEAD"])
