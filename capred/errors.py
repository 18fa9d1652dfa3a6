"""Exceptions raised by capred.

The library raises these; the command line turns them into one clean message
and a non-zero exit code. Any other exception is a bug and keeps its traceback.
"""

from __future__ import annotations

from dataclasses import dataclass


class CapredError(Exception):
    """Base class of every error capred reports to a user."""


@dataclass(frozen=True)
class Problem:
    """One thing wrong with an input file, located as a spreadsheet shows it."""

    file: str
    line: int | None
    column: str | None
    message: str
    sheet: str | None = None
    value: str | None = None

    def __str__(self) -> str:
        where = self.file
        if self.sheet is not None:
            where += f", sheet '{self.sheet}'"
        if self.line is not None:
            where += f", line {self.line}"
        if self.column is not None:
            where += f", column '{self.column}'"
        from .text_safety import visible  # a message reaches a terminal: a cell's control characters as escapes

        return visible(f"{where}: {self.message}")


class InputError(CapredError):
    """Bad input data. Carries every problem found in a file, not only the first."""

    def __init__(self, problems: list[Problem] | Problem):
        if isinstance(problems, Problem):
            problems = [problems]
        # report in file order: header problems first, then rows as a spreadsheet lists them
        self.problems = sorted(problems, key=lambda p: (p.file, p.line or 0))
        super().__init__(self._text())

    #: the console lists this many problems, then says how many more there are
    SHOWN = 20

    #: the same message in this many lines of one column is shown once, with the count and the first lines
    SAME = 3

    def _grouped(self) -> list[str]:
        """The problems as shown, one line each.

        The same problem in many lines of a column is shown once, with the count and the first lines (cells that are not
        numbers: with their first values).
        """
        import re

        def key(p: Problem):
            m = re.fullmatch(r"('.*') is not a number(.*)", p.message, re.S)
            return (p.file, p.sheet, p.column, "not a number" + m.group(2) if m else p.message), m

        groups: dict[tuple, list[Problem]] = {}
        for p in self.problems:
            groups.setdefault(key(p)[0], []).append(p)
        out, done = [], set()
        for p in self.problems:
            k, m = key(p)
            same = groups[k]
            if len(same) < self.SAME or p.line is None:
                out.append(str(p))
                continue
            if k in done:
                continue
            done.add(k)
            lines = ", ".join(str(q.line) for q in same[:5]) + (", ..." if len(same) > 5 else "")
            if m is not None:  # values differ: the count, the first lines and values
                firsts = ", ".join(
                    dict.fromkeys(re.match(r"('.*') is not a number", q.message, re.S)[1] for q in same[:5])
                )
                text = f"{len(same):,} cells are not numbers (lines {lines}: {firsts}){m.group(2)}"
                out.append(str(Problem(p.file, None, p.column, text, p.sheet)))
            else:
                out.append(f"{Problem(p.file, None, p.column, p.message, p.sheet)} (in {len(same):,} lines: {lines})")
        return out

    def _text(self) -> str:
        if len(self.problems) == 1:
            return str(self.problems[0])
        shown = self._grouped()
        if len(shown) == 1:
            return shown[0]
        head = f"{len(self.problems)} problems in the input:"
        lines = [head, *("  - " + t for t in shown[: self.SHOWN])]
        if len(shown) > self.SHOWN:
            lines.append(f"  ... and {len(shown) - self.SHOWN} more (--json lists them all)")
        return "\n".join(lines)

    def as_json(self) -> dict:
        """Every problem as a JSON-ready mapping, for scripts.

        Returns
        -------
        dict
            ``{"errors": [{"file", "sheet", "line", "column", "value", "message"}, ...]}``, one entry per problem
            in the order found.
        """
        return {
            "errors": [
                {
                    "file": p.file,
                    "sheet": p.sheet,
                    "line": p.line,
                    "column": p.column,
                    "value": p.value,
                    "message": p.message,
                }
                for p in self.problems
            ]
        }


class UnitError(CapredError):
    """A unit that is unknown or of the wrong dimension (outside a file context)."""


class FitError(CapredError):
    """A fit that cannot be made from the data given (too few points, degenerate data)."""


class OptionError(CapredError):
    """An invalid command-line option or function argument value."""


class OutputError(CapredError):
    """Outputs that cannot be written where asked (a file as --out, an input in the way, a full disk)."""


class MissingFileError(InputError, FileNotFoundError):
    """An input file that does not exist: a capred InputError that is also a FileNotFoundError."""

    def __init__(self, path: str, message: str = "file not found"):
        InputError.__init__(self, Problem(str(path), None, None, message))
        self.filename = str(path)
        self.errno = 2
        self.strerror = message

    def __str__(self) -> str:
        return self._text()


class LimitError(InputError):
    """An input over a reading limit (decompressed size, cells, columns), refused before it is read whole.

    ``limit`` names the limit (a field of :class:`capred.io.grid.ReadLimits`:
    ``max_bytes``, ``max_cells`` or ``max_columns``) and ``value`` its setting;
    the message says how to raise it.
    """

    def __init__(self, problem: Problem, limit: str, value: int):
        self.limit = limit
        self.value = value
        super().__init__(problem)


class CapredWarning(UserWarning):
    """An implausible value or a model used outside its regime: the run goes on, the result says so.

    Every such warning is also in the result's ``warnings`` (JSON, console, report.html); the public API
    (``capred.run_shear`` and friends) emits each as a Python warning of this class.
    """
