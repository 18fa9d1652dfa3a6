"""The lines of a long plain CSV after its first 200, read as columns a window of lines at a time (issue 46).

The table reader (capred.io.table.grid_table) reads the first 200 lines row by row (header, units row, metadata)
and hands the rest of a plain file (no quote, no carriage return, no blank line) here. A numeric column becomes
floats window by window, without a Python string per cell; its cells' text is cut out of the file's text only when
a message quotes one (:class:`TailCells`). A text column is a list of its cells, equal cells one string. Memory
then follows the data: the file's text, 8 bytes per number, a pointer per text cell (measured on a 100 MB
retention table of 4.36 million rows: 2.39 GB before, see tests/test_hostile_memory.py).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: characters of text per window: about 200,000 lines of a four-column table, a few tens of MB of strings at once
WINDOW_CHARS = 4 * 2**20


class PlainTail:
    """The lines ``text[start:end]`` of a file, every one holding ``width`` cells separated by ``delimiter``.

    No line end after the last; the first of them is line ``first_line`` of the file (see :meth:`rectangular`).
    """

    def __init__(self, text: str, start: int, end: int, first_line: int, delimiter: str, width: int = 0):
        self.text, self.start, self.end = text, start, end
        self.first_line, self.delimiter, self.width = first_line, delimiter, width
        self._starts: np.ndarray | None = None
        self.n = text.count("\n", start, end) + 1

    def windows(self):
        """(start, end) of consecutive pieces of whole lines, about :data:`WINDOW_CHARS` each.

        Yields
        ------
        (int, int)
            Offsets in ``text`` of each piece's first character and of the line end after it.
        """
        a = self.start
        while a < self.end:
            b = self.text.find("\n", min(a + WINDOW_CHARS, self.end), self.end)
            b = self.end if b < 0 else b
            yield a, b
            a = b + 1

    def rectangular(self) -> bool:
        """True when every line holds ``width - 1`` delimiters (the table's header width).

        Returns
        -------
        bool
        """
        d, want = self.delimiter, self.width - 1
        for a, b in self.windows():
            if any(ln.count(d) != want for ln in self.text[a:b].split("\n")):
                return False
        return True

    def last_line(self) -> str:
        """The last line of the tail.

        Returns
        -------
        str
            Its text, without a line end.
        """
        return self.text[self.text.rfind("\n", self.start, self.end) + 1 : self.end]

    def drop_last_line(self) -> None:
        """Leave the last line out (a note under the data); the tail may become empty (``n`` 0)."""
        cut = self.text.rfind("\n", self.start, self.end)
        self.end = max(self.start, cut)
        self.n -= 1
        self._starts = None

    def split(self, a: int, b: int) -> list[str]:
        """The cells of the lines ``text[a:b]``, row after row.

        Parameters
        ----------
        a, b : int
            Offsets in ``text`` of a piece of whole lines (as :meth:`windows` gives them).

        Returns
        -------
        list of str
            The cells as written, ``width`` per line.
        """
        d = self.delimiter
        return self.text[a:b].replace("\n", d).split(d)

    def cells(self, j: int) -> list[str]:
        """Column ``j`` as a list of its cells' text.

        Parameters
        ----------
        j : int
            The column's index (from 0).

        Returns
        -------
        list of str
            The cells as written, one per line; equal cells are one string.
        """
        out: list[str] = []
        seen: dict[str, str] = {}
        for a, b in self.windows():
            out += [seen.setdefault(c, c) for c in self.split(a, b)[j :: self.width]]
            if len(seen) > 100_000:  # a column of distinct values: no table of them
                seen = {}
        return out

    def first_cells(self, j: int, k: int) -> list[str]:
        """The first ``k`` cells of column ``j`` (or fewer).

        Parameters
        ----------
        j : int
            The column's index (from 0).
        k : int
            How many cells.

        Returns
        -------
        list of str
            The cells as written, from the first window only.
        """
        for a, b in self.windows():
            return self.split(a, b)[j :: self.width][:k]
        return []

    def cell(self, i: int, j: int) -> str:
        """Cell ``j`` of line ``i``, as written.

        Parameters
        ----------
        i : int
            The line's index in the tail (from 0).
        j : int
            The column's index (from 0).

        Returns
        -------
        str
        """
        if self._starts is None:
            self._starts = self._line_starts()
        a = int(self._starts[i])
        b = self.text.find("\n", a, self.end)
        return self.text[a : self.end if b < 0 else b].split(self.delimiter)[j]

    def _line_starts(self) -> np.ndarray:
        """Where each line begins in ``text``, found with numpy a window at a time (8 bytes a line)."""
        parts = [np.array([self.start])]
        for a, b in self.windows():
            chars = np.frombuffer(self.text[a:b].encode("utf-32-le"), np.uint32)
            parts.append(np.flatnonzero(chars == 10) + (a + 1))
            if b < self.end:
                parts.append(np.array([b + 1]))
        return np.concatenate(parts)


class TailCells(Sequence):
    """Column ``j`` of a :class:`PlainTail` as text, stripped, cut out when a message needs a cell (Table.raw).

    ``head`` holds the cells of the rows read before the tail.
    """

    def __init__(self, head: list[str], tail: PlainTail, j: int):
        self.head, self.tail, self.j = head, tail, j

    def __len__(self) -> int:
        return len(self.head) + self.tail.n

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        k = i - len(self.head)
        return self.head[i] if k < 0 else self.tail.cell(k, self.j).strip()


def read_columns(tail: PlainTail, numeric: list[int], text: list[int], parse, stripped):
    """The tail's numeric columns as floats and its text columns as lists, one window of lines at a time.

    The columns ``numeric`` and ``text``; each window is split once.

    A numeric column is parsed by ``parse`` (capred.io.table's _parse_column) on its cells as ``stripped`` gives
    them; where a window holds a cell that is not a plain number or blank, the column is None (the caller reads it
    cell by cell, naming the bad cells). A text column's equal cells are one string.

    Parameters
    ----------
    tail : PlainTail
        The lines to read.
    numeric, text : list of int
        The indices of the numeric and of the text columns.
    parse : callable
        Parser of a numeric column's stripped cells (capred.io.table's _parse_column).
    stripped : callable
        The cells of a column as ``parse`` takes them.

    Returns
    -------
    (dict, dict)
        Column index -> float array or None; column index -> list of str.
    """
    parts: dict[int, list | None] = {j: [] for j in numeric}
    texts: dict[int, list[str]] = {j: [] for j in text}
    seen: dict[int, dict[str, str]] = {j: {} for j in text}
    w = tail.width
    for a, b in tail.windows():
        flat = tail.split(a, b)
        for j in numeric:
            if parts[j] is not None:
                values = parse(stripped(flat[j::w]), False)
                parts[j] = None if values is None else parts[j] + [values]
        for j in text:
            table = seen[j]
            texts[j] += [table.setdefault(c, c) for c in flat[j::w]]
            if len(table) > 100_000:  # a column of distinct values (ids): no table of them
                seen[j] = {}
        del flat
    values = {j: (None if p is None else np.concatenate(p) if p else np.empty(0)) for j, p in parts.items()}
    return values, texts
