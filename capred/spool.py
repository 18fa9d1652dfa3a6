"""Long outputs made or kept out of memory, which capred.io.writers streams to disk.

:class:`Rows` (a JSON list made on demand, block by block) and :class:`Spool` (table columns spooled to a temporary
file).
"""

from __future__ import annotations

from collections.abc import Callable


class Rows:
    """A long list of JSON rows made on demand, ``size`` at a time.

    A large result (100,000 shear tests, bridges) puts its per-row list in
    the document as Rows, so the writer can stream it to disk without ever
    holding every row's dict; ``to_json()`` turns it into a plain list.
    """

    #: True when the rows' JSON text is already written (the writer then only copies it, in its own process)
    written_ahead = False

    def __init__(self, n: int, make: Callable[[int, int], list]):
        self.n = n
        self.make = make  # (start, stop) -> list of rows

    def chunks(self, size: int = 2000):
        """The rows, ``size`` at a time (the last chunk may be shorter).

        Parameters
        ----------
        size : int, optional
            Rows per chunk (default 2000).

        Yields
        ------
        list of dict
            The rows of one chunk.
        """
        for start in range(0, self.n, size):
            yield self.make(start, min(self.n, start + size))

    def tolist(self) -> list:
        """Every row at once, as a plain list.

        Returns
        -------
        list of dict
        """
        return self.make(0, self.n)


class Spool:
    """Per-row output columns of a long run, kept block by block in a temporary file instead of in memory.

    A command whose rows are independent (``bridge solve``) appends each
    block's columns (a dict of arrays) as it computes them; the writer reads
    them back one block at a time (``blocks()``), also from a forked process
    (reads use ``os.pread``: no shared file offset). Peak memory is then one
    block's, whatever the number of rows.
    """

    def __init__(self) -> None:
        import tempfile
        import weakref

        self._file = tempfile.TemporaryFile()
        self._closer = weakref.finalize(self, self._file.close)  # the file goes with the spool
        self._index: list[tuple[int, int, int]] = []  # (offset, bytes, rows) of each block
        self._end = 0
        self._cached: tuple[int, dict] | None = None  # the block read last (rows_range reads many slices of it)
        self.n = 0

    def append(self, columns: dict) -> None:
        """Add one block: every column an array of the same length.

        Parameters
        ----------
        columns : dict
            Column name -> array; every block has the same columns.
        """
        import pickle

        data = pickle.dumps(columns, protocol=pickle.HIGHEST_PROTOCOL)
        self._file.seek(self._end)
        self._file.write(data)
        self._file.flush()
        rows = len(next(iter(columns.values()))) if columns else 0
        self._index.append((self._end, len(data), rows))
        self._end += len(data)
        self.n += rows

    def block(self, k: int) -> dict:
        """The columns of block ``k`` (the last block read is kept: reading it again costs nothing).

        Parameters
        ----------
        k : int
            Index of the block, from 0.

        Returns
        -------
        dict
            Column name -> array.
        """
        return self._block(k)

    def _block(self, k: int) -> dict:
        import os
        import pickle

        if self._cached is not None and self._cached[0] == k:
            return self._cached[1]
        offset, size, _ = self._index[k]
        block = pickle.loads(os.pread(self._file.fileno(), size, offset))
        self._cached = (k, block)
        return block

    def blocks(self):
        """The blocks' column dicts, in order.

        Yields
        ------
        dict of str to numpy.ndarray
            One block's columns, name -> values.
        """
        for k in range(len(self._index)):
            yield self._block(k)

    def columns(self, start: int, stop: int) -> dict:
        """Every column of rows ``start`` .. ``stop - 1`` (possibly across blocks).

        Parameters
        ----------
        start, stop : int
            The rows, ``start`` included, ``stop`` excluded.

        Returns
        -------
        dict
            Column name -> array.
        """
        import numpy as np

        parts, first = [], 0
        for k, (_, _, rows) in enumerate(self._index):
            lo, hi = max(start, first), min(stop, first + rows)
            if lo < hi:
                block = self._block(k)
                parts.append({name: v[lo - first : hi - first] for name, v in block.items()})
            first += rows
            if first >= stop:
                break
        if len(parts) == 1:
            return parts[0]
        names = list(self._block(0)) if self._index else []
        return {name: np.concatenate([p[name] for p in parts]) if parts else np.empty(0) for name in names}

    def close(self) -> None:
        """Close the spool's temporary file (an unnamed file: closing it frees its disk space)."""
        self._closer()
