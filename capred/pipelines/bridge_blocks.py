"""`capred bridge solve` on a long file: read, solved and kept block by block.

So memory stays flat (issue 20), and spread over the processes the run may use, reading, parsing and writing included
(issue 31).

Rows of ``bridge solve`` are independent: each block of lines (capred.io.blocks)
is solved as a table of its own and its output columns go to a
:class:`capred.result.Spool` on disk; only the status and the radius ratio of
every row stay in memory. A file of one block gives the ordinary
:class:`capred.pipelines.bridge.BridgeResult`.

On several processes (``--workers N`` / ``CAPRED_PROCESSES=N``, any N) each process reads the file, and
parses and solves the blocks it is first to reach; each keeps its blocks' output columns in a file of its own
(:class:`SpreadSpool`). When the document is written, the processes again share the blocks, writing their CSV
and JSON text ahead, so the writers only copy it in order. The files are byte for byte those of one process
(the same blocks, each solved by the same operations, written by the same functions); a problem in any block
makes the run start again on the usual path, which reports it as one process does.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import CapredError
from ..io import blocks as blocks_module
from ..io import read_table_blocks
from ..progress import task
from ..records import per_case_store_rows
from ..result import InputFile, Result, Spool, input_file
from . import bridge_solve as pb

#: output columns that are text, not numbers (BridgeResult.columns leaves them out)
_TEXT_COLUMNS = ("case", "status", "note")


@dataclass(repr=False)
class BridgeBlocks(Result):
    """Bridges of a long table, one per row, their output columns kept on disk block by block.

    It offers what the writer and a script need of a :class:`BridgeResult`: ``rows()``, ``rows_range()``,
    ``columns()`` (the same keys), ``status``, ``to_json()``. The per-row SI arrays of a BridgeResult
    (``force``, ``volume``, ``neck``, ``beta``, ``suction``, ``shape``) are not kept: ``columns()`` gives the
    same quantities in output units.

    Attributes
    ----------
    source : str
        The file read.
    status : ndarray of int
        Per row: 0 a verified bridge, else the code of :data:`capred.pipelines.bridge.STATUS`.
    inputs_si : dict
        ``ratio``: R2/R per row [-]; the other inputs of :class:`BridgeResult` for the first
        :data:`capred.pipelines.bridge_solve.HEAD_ROWS` rows (what names them in the tables).
    spool : Spool
        The output columns (mm, mN, mm^3, mm^2, deg, kPa), as ``BridgeResult`` writes them.
    """

    command = "bridge solve"
    json_name = "solve.json"

    source: str
    status: np.ndarray
    inputs_si: dict
    spool: Spool
    options: pb.BridgeOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    status_text = staticmethod(pb.BridgeResult.status_text)
    #: processes that write the CSV and JSON text of the blocks ahead of the writer, and the blocks of the
    #: spool (set by a spread run)
    processes = 1
    n_blocks = 0

    def rows_range(self, start: int, stop: int) -> list[dict]:
        """JSON rows start..stop, read back from the spool.

        Parameters
        ----------
        start, stop : int
            First row and one past the last row (0-based) [-].

        Returns
        -------
        list of dict
            The JSON rows.
        """
        return pb.json_rows(self.spool.columns(start, stop))

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Every row of the run, read back from the spool.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        return self.rows_range(0, self.status.size)

    def row_context(self, start: int, stop: int) -> dict[str, np.ndarray]:
        """As :meth:`capred.pipelines.bridge_solve.BridgeResult.row_context` (NaN past the first HEAD_ROWS).

        Parameters
        ----------
        start, stop : int
            First row and one past the last row (0-based) [-].

        Returns
        -------
        dict
            ``R_mm``, ``gap_mm``, ``D_rupture_mm`` -> array [mm].
        """
        return pb.row_context(self.inputs_si, self.status, start, stop)

    def columns(self) -> dict[str, np.ndarray]:
        """The numeric output columns of every row, read back into memory.

        As :meth:`BridgeResult.columns` gives them (mm, mN, mm^3, mm^2, deg, kPa; NaN where no bridge was found).

        Returns
        -------
        dict of str to numpy.ndarray
            JSON key -> values of every row.
        """
        return {k: v for k, v in self._all().items() if k not in _TEXT_COLUMNS}

    def _all(self) -> dict[str, np.ndarray]:
        return self.spool.columns(0, self.status.size)

    store_rows = per_case_store_rows  # bridges per case: nothing to chart across runs

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the bridges (a ColumnRows when lazy).

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        n = self.status.size
        if not lazy:
            return {"source": self.source, "bridges": self.rows()}
        encoded = self._encoded()  # a long document about to be written: its text written ahead, on every process
        rows = pb.ColumnRows(n, self.spool.columns) if encoded is None else _EncodedRows(n, self.spool.columns, encoded)
        return {"source": self.source, "bridges": rows}

    def _encoded(self):
        """The CSV and JSON text of every block, written ahead on the run's processes (None: one process)."""
        if self.processes < 2:
            return None
        if "_encoded_text" not in self.__dict__:
            try:
                encoded = _encode_blocks(self.spool, self.processes, self.n_blocks)
            except Exception:  # pragma: no cover - a system limit (fork, files): the writers write from the spool
                encoded = None
            self.__dict__["_encoded_text"] = encoded
        return self.__dict__["_encoded_text"]

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``solve``: every row, all in memory, for tables.xlsx).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        return {"solve": pd.DataFrame(self._all(), copy=False)}  # tables.xlsx: every row in memory

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them, under ``name [unit]`` headers.

        ``solve``: a HeadedSpool written block by block.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        # written block by block, under name [unit] headers (or the text written ahead by a spread run)
        return {"solve": pb.HeadedSpool(self.spool, self.__dict__.get("_encoded_text"))}


def solve_in_blocks(source, opt: pb.BridgeOptions):
    """Solve every row of ``source`` block by block (see the module docstring).

    Parameters
    ----------
    source : path, DataFrame or TableSource
        The table of cases (see capred.pipelines.bridge.solve_bridges).
    opt : BridgeOptions
        Options of the run.

    Returns
    -------
    BridgeResult or BridgeBlocks
        A BridgeResult when the table is one block; else a BridgeBlocks.

    Raises
    ------
    InputError
        The problems of the first block that has any (nothing is returned).
    """
    if _long(source):
        k = pb.processes(opt.workers)
        if k > 1:
            res = _solve_spread(source, opt, k)
            if res is not None:
                return res
    with pb.helper(start=_long(source), workers=opt.workers):  # the same helper processes for every block
        return _solve_in_blocks(source, opt)


def _long(source) -> bool:
    """True for a CSV file read in several blocks: its blocks are long enough to be shared by two processes."""
    try:
        size = Path(source).stat().st_size if isinstance(source, (str, Path)) else 0
    except OSError:
        return False
    return size > blocks_module.BLOCK_BYTES + blocks_module.BLOCK_BYTES // 4


def _solve_in_blocks(source, opt: pb.BridgeOptions):
    blocks = read_table_blocks(source, pb.SOLVE_SCHEMA)
    table = next(blocks)
    res = pb.solve_table(table, opt)
    res.inputs = [input_file(source, table)]
    path = str(table.path)
    del table  # one block in memory at a time: its cells go before the next is read
    table = next(blocks, None)
    if table is None:
        return res
    spool = Spool()
    try:
        status, ratio = [res.status], [res.inputs_si["ratio"]]
        head = {k: v[: pb.HEAD_ROWS] for k, v in res.inputs_si.items() if k != "ratio"}
        notes, warnings, inputs = dict.fromkeys(res.notes), dict.fromkeys(res.warnings), res.inputs
        spool.append(res._cols())
        del res
        size = Path(path).stat().st_size
        with task("solving bridges, block by block", total=-(-size // blocks_module.BLOCK_BYTES)) as advance:
            advance(1)  # the first block, solved above
            while table is not None:
                part = pb.solve_table(table, opt)
                del table
                spool.append(part._cols())
                status.append(part.status)
                ratio.append(part.inputs_si["ratio"])
                notes.update(dict.fromkeys(part.notes))
                warnings.update(dict.fromkeys(part.warnings))
                del part
                advance(1)
                table = next(blocks, None)
    except BaseException:
        spool.close()
        raise
    return BridgeBlocks(
        path,
        np.concatenate(status).astype(np.int8),
        {"ratio": np.concatenate(ratio), **head},
        spool,
        opt,
        inputs,
        list(notes),
        list(warnings),
    )


# ---------------------------------------------------------------------------------------------------------------
# a long file spread over several processes (issue 31, item 4)


def _solve_spread(source, opt: pb.BridgeOptions, k: int):
    """Read, parse and solve the blocks of ``source`` on ``k`` processes, gathered in file order.

    This one and k - 1 forked workers, each block whole, as one process would solve it. The result (a
    :class:`BridgeBlocks`) then writes the CSV and JSON text of its blocks on ``k`` processes too, when its document is
    asked for (:func:`_encode_blocks`).

    Each process reads the file itself (capred.io.blocks.read_table_blocks with ``select``): a block is parsed
    and solved by the first process to reach it (:class:`_Claims`; block 0, which names the run, by this
    one), so a process slowed by other work takes fewer blocks. Each process keeps its blocks' output columns
    in a file of its own (:class:`SpreadSpool`); only their places and statuses cross between processes. The
    result is the same, to the bit, as that of one process: the same blocks, each solved by the same
    operations.

    Returns None (nothing kept: the caller runs the usual path, which reports any problem as one process
    does) when a block has a problem or a process fails.
    """
    import tempfile

    size = Path(source).stat().st_size
    # four blocks a process at least (down to a quarter of the usual block): many processes share the file evenly
    block_bytes = min(blocks_module.BLOCK_BYTES, max(size // (4 * k), blocks_module.BLOCK_BYTES // 4))
    claims = _Claims(2 * (size // block_bytes) + 8)  # more than the blocks of the file
    files = [tempfile.TemporaryFile() for _ in range(k)]
    workers: list[_Worker] = []
    out = None
    try:
        for j in range(1, k):
            workers.append(_Worker(source, opt, j, claims, files[j], block_bytes))
        out = _gather(source, opt, k, workers, claims, files, block_bytes)
    except (_WorkerFailed, CapredError):
        out = None
    except Exception:  # pragma: no cover - the spread machinery failed (a system limit): the usual path runs
        out = None
    finally:
        for w in workers:
            w.close()
        claims.close()
        if not isinstance(out, BridgeBlocks):
            for f in files:
                f.close()
    return out


class _WorkerFailed(Exception):
    """A process could not give one of its blocks (a problem in it, or the process failed)."""


class _Claims:
    """Which process takes each block: the first to ask for it.

    One byte per block (0: free, else the process's number + 1) in memory shared by the forked processes, changed under
    a POSIX record lock (held per process). A block beyond the table is the first process's.
    """

    def __init__(self, n: int) -> None:
        import mmap
        import tempfile

        self.map = mmap.mmap(-1, max(1, n))
        self.map[0] = 1  # block 0 names the run: the first process's
        self._lock = tempfile.TemporaryFile()

    def take(self, i: int, me: int) -> bool:
        """True when block ``i`` is (now) process ``me``'s."""
        import fcntl

        if i >= len(self.map):
            return me == 0
        fcntl.lockf(self._lock, fcntl.LOCK_EX)
        try:
            if self.map[i] == 0:
                self.map[i] = me + 1
            return self.map[i] == me + 1
        finally:
            fcntl.lockf(self._lock, fcntl.LOCK_UN)

    def close(self) -> None:
        self.map.close()
        self._lock.close()


def _write_all(fd: int, data: bytes) -> None:
    import os

    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


def _solve_block(table, opt, fd: int, offset: int):
    """Solve one block and append to file ``fd`` (at ``offset``) what the gathering process keeps of it.

    Pickled: (status, ratio, notes, warnings), then its output columns; returns (the result, (offset and size [B] of the
    first, offset and size [B] of the columns, rows)): only these few numbers cross between processes, so a pipe never
    fills and a worker never waits for the gathering process.
    """
    import pickle

    part = pb.solve_table(table, opt)
    meta = pickle.dumps(
        (part.status, part.inputs_si["ratio"], part.notes, part.warnings), protocol=pickle.HIGHEST_PROTOCOL
    )
    data = pickle.dumps(part._cols(), protocol=pickle.HIGHEST_PROTOCOL)
    _write_all(fd, meta)
    _write_all(fd, data)
    return part, (offset, len(meta), offset + len(meta), len(data), part.status.size)


class _Worker:
    """A forked process that reads, parses and solves the blocks it claims.

    It keeps their columns in its own file and sends, block by block, what the gathering process keeps (then ``None``;
    ``"fail"`` when it stops).
    """

    live_fds: list = []

    def __init__(self, source, opt, me: int, claims: _Claims, f, block_bytes: int) -> None:
        import gc
        import os

        self._from_child, write_end = os.pipe()
        gc.freeze()
        self.pid = os.fork()
        if self.pid == 0:  # the child: serve, then leave without running the parent's clean-up
            code = 1
            try:
                gc.disable()
                os.close(self._from_child)
                for fd in _Worker.live_fds:  # the other workers' pipes are theirs alone
                    try:
                        os.close(fd)
                    except OSError:
                        pass
                self._serve(source, opt, me, claims, f.fileno(), write_end, block_bytes)
                code = 0
            finally:
                os._exit(code)
        os.close(write_end)
        _Worker.live_fds.append(self._from_child)

    @staticmethod
    def _serve(source, opt, me, claims, fd, outbox, block_bytes) -> None:
        pb.ONE_PROCESS = True
        offset = 0
        try:
            blocks = read_table_blocks(
                source, pb.SOLVE_SCHEMA, block_bytes=block_bytes, select=lambda i: claims.take(i, me)
            )
            for i, table in enumerate(blocks):
                if table is not None:
                    _, kept = _solve_block(table, opt, fd, offset)
                    del table
                    offset += kept[1] + kept[3]
                    pb.send_message(outbox, (i, *kept))
            pb.send_message(outbox, None)
        except Exception:  # a problem in a block (or anything else): the usual path runs and reports it
            pb.send_message(outbox, "fail")

    def results(self) -> list:
        """Every message of the worker up to its end; raises _WorkerFailed when it failed or is gone."""
        out = []
        while True:
            try:
                got = pb.receive_message(self._from_child)
            except (OSError, EOFError):
                got = "fail"
            if got is None:
                return out
            if isinstance(got, str):
                raise _WorkerFailed
            out.append(got)

    def close(self) -> None:
        import gc
        import os
        import signal

        if self.pid is None:
            return
        try:
            os.close(self._from_child)
            os.kill(self.pid, signal.SIGKILL)  # done, or no longer needed
            os.waitpid(self.pid, 0)
        except OSError:
            pass
        finally:
            if self._from_child in _Worker.live_fds:
                _Worker.live_fds.remove(self._from_child)
            self.pid = None
            if not _Worker.live_fds:
                gc.unfreeze()


def _gather(source, opt, k: int, workers: list, claims: _Claims, files: list, block_bytes: int):
    """The blocks of the gathering process and the workers' results, in file order."""
    first = inputs = head = path = None
    kept: dict[int, tuple] = {}
    offset, n = 0, 0
    size = Path(source).stat().st_size
    pb.ONE_PROCESS = True
    try:
        with task("solving bridges, block by block", total=-(-size // block_bytes)) as advance:
            blocks = read_table_blocks(
                source, pb.SOLVE_SCHEMA, block_bytes=block_bytes, select=lambda i: claims.take(i, 0)
            )
            for i, table in enumerate(blocks):
                n = i + 1
                if table is not None:
                    part, got = _solve_block(table, opt, files[0].fileno(), offset)
                    if i == 0:
                        first, inputs, path = part, [input_file(source, table)], str(table.path)
                        head = {key: v[: pb.HEAD_ROWS] for key, v in part.inputs_si.items() if key != "ratio"}
                    del table, part
                    offset += got[1] + got[3]
                    kept[i] = (0, *got)
                advance(1)
    finally:
        pb.ONE_PROCESS = False
    for j, w in enumerate(workers, start=1):
        for i, *got in w.results():
            kept[i] = (j, *got)
    if sorted(kept) != list(range(n)):  # pragma: no cover - a block nobody solved
        raise _WorkerFailed
    if n == 1:  # one block: the ordinary result
        first.inputs = inputs
        return first
    import os
    import pickle

    notes, warnings, status, ratio = {}, {}, [], []
    for i in range(n):
        j, meta_offset, meta_size, *_ = kept[i]
        st, rt, block_notes, block_warnings = pickle.loads(os.pread(files[j].fileno(), meta_size, meta_offset))
        status.append(st)
        ratio.append(rt)
        notes.update(dict.fromkeys(block_notes))
        warnings.update(dict.fromkeys(block_warnings))
    spool = SpreadSpool(files, [(kept[i][0], *kept[i][3:]) for i in range(n)])
    res = BridgeBlocks(
        path,
        np.concatenate(status).astype(np.int8),
        {"ratio": np.concatenate(ratio), **head},
        spool,
        opt,
        inputs,
        list(notes),
        list(warnings),
    )
    res.processes, res.n_blocks = k, n
    return res


class SpreadSpool:
    """The output columns of a spread run, block by block in the files of the processes that solved them.

    What a :class:`capred.result.Spool` offers (``n``, ``block``, ``blocks``, ``columns``, ``close``).

    Parameters
    ----------
    files : list of file
        The processes' files (temporary, unnamed).
    index : list of tuple
        Per block in order: (file number, offset [B], size [B], rows).
    """

    def __init__(self, files: list, index: list) -> None:
        import weakref

        self._files, self._index = files, index
        self._closer = weakref.finalize(self, _close_all, list(files))
        self._cached: tuple[int, dict] | None = None
        self.n = sum(rows for *_, rows in index)

    def block(self, k: int) -> dict:
        """The columns of block ``k`` (the last block read is kept).

        Parameters
        ----------
        k : int
            Index of the block, from 0.

        Returns
        -------
        dict
            Column name -> array.
        """
        import os
        import pickle

        if self._cached is not None and self._cached[0] == k:
            return self._cached[1]
        f, offset, size, _ = self._index[k]
        block = pickle.loads(os.pread(self._files[f].fileno(), size, offset))
        self._cached = (k, block)
        return block

    def blocks(self):
        """The blocks' column dicts, in order.

        Yields
        ------
        dict of str to numpy.ndarray
            One block's columns, JSON key -> values.
        """
        for k in range(len(self._index)):
            yield self.block(k)

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
        parts, first = [], 0
        for k, (*_, rows) in enumerate(self._index):
            lo, hi = max(start, first), min(stop, first + rows)
            if lo < hi:
                block = self.block(k)
                parts.append({name: v[lo - first : hi - first] for name, v in block.items()})
            first += rows
            if first >= stop:
                break
        if len(parts) == 1:
            return parts[0]
        names = list(self.block(0)) if self._index else []
        return {name: np.concatenate([p[name] for p in parts]) if parts else np.empty(0) for name in names}

    def close(self) -> None:
        """Close the files (unnamed: closing them frees their disk space)."""
        self._closer()


def _close_all(files) -> None:
    for f in files:
        f.close()


class _EncodedRows(pb.ColumnRows):
    """The rows of a spread run whose JSON text its processes have written ahead (:func:`_encode_blocks`)."""

    written_ahead = True  # the JSON writer copies the text: no process of its own (capred.io.writers)

    def __init__(self, n: int, columns, encoded) -> None:
        super().__init__(n, columns)
        self.encoded = encoded

    def json_chunks(self, size: int = 2000):
        """The rows' JSON objects joined by commas, one block per chunk.

        The bytes of :meth:`capred.pipelines.bridge_solve.ColumnRows.json_chunks`, cut at the blocks' ends.

        Parameters
        ----------
        size : int, optional
            Unused (a block per chunk).

        Yields
        ------
        bytes
        """
        yield from self.encoded.json_pieces()


class _Encoded:
    """The CSV and JSON text of every block of a spool, in temporary files.

    The CSV in the standard dialect, the header with the first block; (file, CSV offset, CSV bytes, JSON offset, JSON
    bytes) per block. The text is handed out as places in those files (capred.io.FileText: the writers copy it file to
    file, in the kernel).
    """

    def __init__(self, files, index) -> None:
        import weakref

        self.files, self.index = files, index
        self._closer = weakref.finalize(self, _close_all, list(files))

    def _text(self, f: int, offset: int, size: int):
        from ..io import FileText

        return FileText(self.files[f].fileno(), offset, size, keep=self) if size else b""  # self: files stay open

    def csv_pieces(self):
        """The CSV text, block by block (capred.io.FileText)."""
        for f, c_off, c_len, _, _ in self.index:
            yield self._text(f, c_off, c_len)

    def json_pieces(self):
        """The JSON rows, block by block.

        capred.io.FileText: objects joined by commas; empty for a block of no rows.
        """
        for f, _, _, j_off, j_len in self.index:
            yield self._text(f, j_off, j_len)


class _Sink:
    """A binary file's ``write`` onto a file descriptor, unbuffered, counting the bytes.

    ``skip_line``: the text up to its first line end is left out (the CSV header of a block after the first).
    """

    def __init__(self, fd: int, skip_line: bool = False) -> None:
        self.fd, self.skip, self.size = fd, skip_line, 0

    def write(self, data: bytes) -> None:
        if self.skip:
            cut = data.find(b"\n")
            if cut < 0:
                return
            data, self.skip = data[cut + 1 :], False
        _write_all(self.fd, data)
        self.size += len(data)


def _encode_block(block: dict, first: bool, fd: int) -> tuple[int, int]:
    """Append to file ``fd`` the CSV text and the JSON rows of one spool block; (CSV bytes, JSON bytes).

    The CSV with the header for the first block: the bytes the writers write of it (capred.io.writers.write_csv_file,
    and stream_json of :meth:`capred.pipelines.bridge_solve.ColumnRows.json_chunks`, chunk by chunk).
    """
    from ..io import encode_rows, write_csv_file

    csv = _Sink(fd, skip_line=not first)
    write_csv_file(csv, pb.with_csv_headers(block), "standard")
    js = _Sink(fd)
    n = len(block["status"])
    for start in range(0, n, _JSON_ROWS):  # as ColumnRows.json_chunks: memory bounded by one chunk of rows
        data = encode_rows(pb.json_chunk_rows({key: v[start : start + _JSON_ROWS] for key, v in block.items()}))
        if data:
            js.write(data if js.size == 0 else b"," + data)
    return csv.size, js.size


#: rows per chunk of JSON text (as capred.pipelines.bridge_solve.ColumnRows.json_chunks)
_JSON_ROWS = 2000


def _encode_share(spool, me: int, n_blocks: int, claims: _Claims, fd: int) -> list[tuple[int, int, int, int, int]]:
    """The blocks process ``me`` claims, their text appended to file ``fd``.

    (block, CSV offset, bytes, JSON offset, bytes) each.
    """
    out, offset = [], 0
    for i in range(n_blocks):
        if not claims.take(i, me):
            continue
        csv, js = _encode_block(spool.block(i), i == 0, fd)
        out.append((i, offset, csv, offset + csv, js))
        offset += csv + js
    return out


def _encode_blocks(spool, k: int, n_blocks: int):
    """The CSV and JSON text of every block of ``spool``, written on ``k`` processes.

    This one and k - 1 forked, each block by the first to reach it; None when a process failed (the writers then write
    from the spool, in one process).
    """
    import gc
    import os
    import tempfile

    k = max(1, min(k, n_blocks))
    files = [tempfile.TemporaryFile() for _ in range(k)]
    claims = _Claims(n_blocks)
    claims.map[0] = 0  # any process may take the first block here
    children = []
    index: dict[int, tuple] = {}
    ok = True
    gc.freeze()
    try:
        for j in range(1, k):
            read_end, write_end = os.pipe()
            pid = os.fork()
            if pid == 0:
                code = 1
                try:
                    gc.disable()
                    os.close(read_end)
                    for _, fd in children:
                        os.close(fd)
                    pb.send_message(write_end, _encode_share(spool, j, n_blocks, claims, files[j].fileno()))
                    code = 0
                finally:
                    os._exit(code)
            os.close(write_end)
            children.append((pid, read_end))
        for i, *where in _encode_share(spool, 0, n_blocks, claims, files[0].fileno()):
            index[i] = (0, *where)
        for j, (pid, fd) in enumerate(children, start=1):
            try:
                got = pb.receive_message(fd)
            except (OSError, EOFError):
                got = None
            if got is None:
                ok = False
            else:
                for i, *where in got:
                    index[i] = (j, *where)
    finally:
        for pid, fd in children:
            os.close(fd)
            try:
                os.waitpid(pid, 0)
            except OSError:
                pass
        claims.close()
        gc.unfreeze()
    if not ok or sorted(index) != list(range(n_blocks)):
        _close_all(files)
        return None
    return _Encoded(files, [index[i] for i in range(n_blocks)])
