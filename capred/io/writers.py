"""The one writer of capred: any Result becomes one output folder, as a transaction.

A run writes into a new hidden folder beside ``--out`` and only when every
file is written swaps it in place of ``--out`` (an atomic exchange where the
system offers one), so ``--out`` always holds exactly one complete run: no
stale files of an earlier run, no mix after an interruption or when two runs
target the same folder (the swaps are serialised by a lock on the parent
folder). Before anything is computed, ``check_target`` refuses an output
folder that holds an input, that is a file, that is not a capred output
folder, or that cannot be written.

Numbers keep their digits: JSON floats are written in shortest round-trip
form and CSV floats as Python's repr (at least 10 significant digits, exact
round trip).
"""

from __future__ import annotations

import contextlib
import errno
import io
import json
import math
import os
import re
import shutil
import sys
import tempfile
from datetime import UTC
from pathlib import Path

from ..errors import CapredError, OutputError

_UMASK = os.umask(0)
os.umask(_UMASK)
_TMP = ".capred-tmp-"
_OLD = ".capred-old-"
#: JSON documents shorter than this (compact) are written indented, larger ones compactly.
INDENT_LIMIT = 256 * 1024


# --- encoding ------------------------------------------------------------------------------------
def _finite(obj):
    """``obj`` with every number JSON can hold as is and every other number null (recursively).

    NaN, infinities, integers beyond what JSON readers keep (|n| >= 2**63;
    written as a float when one holds them) and numpy scalars and arrays of
    those become Python floats, ints or None.
    """
    import math

    if isinstance(obj, dict):
        return {k if isinstance(k, str) else str(k): _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    if isinstance(obj, (str, bool)) or obj is None:
        return obj
    if hasattr(obj, "tolist") and not isinstance(obj, (int, float)):  # numpy scalar or array
        return _finite(obj.tolist())
    if isinstance(obj, int):
        if abs(obj) < 2**63:
            return obj
        try:
            return float(obj)
        except OverflowError:
            return None
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    return obj


def _dumps(obj, indent: bool = False) -> bytes:
    """JSON bytes: orjson when installed (fast), else the standard library's C encoder.

    Never fails on a number: NaN, infinities and integers too large for JSON
    readers are written as null (see ``_finite``).
    """
    from ..text_safety import json_escape  # C1 and bidi controls as \u escapes: the same text, inert

    try:
        import orjson
    except ImportError:  # pragma: no cover - orjson is a dependency; kept for a minimal install
        obj = _finite(obj)
        if indent:
            return json_escape(json.dumps(obj, ensure_ascii=False, indent=2, allow_nan=False).encode("utf-8"))
        return json_escape(json.dumps(obj, ensure_ascii=False, separators=(",", ":"), allow_nan=False).encode("utf-8"))
    option = orjson.OPT_SERIALIZE_NUMPY | (orjson.OPT_INDENT_2 if indent else 0)
    try:
        return json_escape(orjson.dumps(obj, option=option))  # NaN and infinities already become null
    except (orjson.JSONEncodeError, OverflowError):  # an integer beyond 64 bits, a numpy type orjson lacks
        return json_escape(orjson.dumps(_finite(obj), option=option))


def encode_json(doc, indent: bool | None = None) -> bytes:
    """JSON bytes of ``doc``: indented for small documents, compact for large ones.

    Floats are written in shortest round-trip form (every digit kept).

    Parameters
    ----------
    doc : dict
        The JSON document (NaN and infinities are written as null).
    indent : bool or None, optional
        True: indented, False: compact; None (default): indented below ``INDENT_LIMIT`` bytes.

    Returns
    -------
    bytes
        UTF-8 JSON followed by a newline.
    """
    compact = _dumps(doc)
    if indent is False or (indent is None and len(compact) > INDENT_LIMIT):
        return compact + b"\n"
    return _dumps(doc, indent=True) + b"\n"


class FileText:
    """Text already written to another file: ``length`` bytes at ``offset`` of the open file descriptor ``fd``.

    A run's temporary file (capred.pipelines.bridge_blocks). :func:`write_piece` copies it file to file in the kernel,
    without reading it into this process.

    Parameters
    ----------
    fd : int
        Open file descriptor of the file that holds the text.
    offset : int
        Where the text starts in it [bytes].
    length : int
        Its length [bytes].
    keep : object, optional
        The file object that owns ``fd``, kept open as long as this piece is (its descriptor is not reused).
    """

    __slots__ = ("fd", "offset", "length", "keep")

    def __init__(self, fd: int, offset: int, length: int, keep=None) -> None:
        self.fd, self.offset, self.length, self.keep = fd, offset, length, keep

    def __len__(self) -> int:
        return self.length

    def __bytes__(self) -> bytes:
        return _pread(self.fd, self.length, self.offset)


#: bytes read at a time where a FileText cannot be copied in the kernel, and copied per call where it can
_COPY_CHUNK = 1 << 22
_KERNEL_CHUNK = 1 << 26
#: errors that say "not between these two files" (another file system, a pipe, an append-only file, an old
#: kernel): the text is then read and written; any other error (a full disk) is raised at once
_NOT_HERE = {
    getattr(errno, name)
    for name in ("EXDEV", "EINVAL", "ENOSYS", "EOPNOTSUPP", "ENOTSUP", "EBADF", "ENOTSOCK", "ESPIPE")
    if hasattr(errno, name)
}


class Stopped(Exception):
    """A copy asked to stop (``write_piece``'s ``stop`` set): the run is being cancelled."""


def write_piece(fh, piece, stop=None) -> None:
    """Write ``piece`` (bytes-like, or a :class:`FileText`) to the binary file ``fh``.

    A FileText goes file to file in the kernel (``os.copy_file_range``, else ``os.sendfile``) when ``fh`` is an
    operating-system file (``open(path, "wb")``, ``sys.stdout.buffer`` redirected to a file); else (a pipe, a
    BytesIO, a gzip or other wrapping file object, a system without either call) it is read a chunk at a time
    and written through ``fh.write``: the same bytes either way.

    Parameters
    ----------
    fh : binary file or object with ``write``
        Where to write.
    piece : bytes-like or FileText
        What to write.
    stop : threading.Event, optional
        When set, the copy stops at its next chunk and raises :class:`Stopped`.
    """
    if not isinstance(piece, FileText):
        fh.write(piece)
        return
    offset, left = piece.offset, piece.length
    dst = _os_file(fh)
    if dst is not None:
        for copy in (_copy_range, _send):
            if copy is None:
                continue
            try:
                while left:
                    if stop is not None and stop.is_set():
                        raise Stopped
                    done = copy(piece.fd, dst, offset, min(left, _KERNEL_CHUNK))
                    if done <= 0:
                        break
                    offset, left = offset + done, left - done
            except OSError as exc:
                if exc.errno not in _NOT_HERE:
                    raise
            if not left:
                break
        fh.seek(os.lseek(dst, 0, os.SEEK_CUR))  # the file object's position: where the kernel's writes ended
    while left:
        if stop is not None and stop.is_set():
            raise Stopped
        data = _pread(piece.fd, min(left, _COPY_CHUNK), offset)
        if not data:
            raise OSError(errno.EIO, f"text of a temporary file ended {left} bytes early")
        fh.write(data)
        offset, left = offset + len(data), left - len(data)


def _os_file(fh) -> int | None:
    """The descriptor of ``fh``, flushed, when it is an operating-system file; None for anything else.

    A file whose position the kernel may move: a FileIO, or a buffered reader/writer straight on one.
    """
    raw = getattr(fh, "raw", fh)
    if not isinstance(raw, io.FileIO) or not (fh is raw or isinstance(fh, (io.BufferedWriter, io.BufferedRandom))):
        return None
    try:
        fh.flush()
        fd = raw.fileno()
        os.lseek(fd, 0, os.SEEK_CUR)  # seekable (not a pipe)
    except (OSError, ValueError):
        return None
    return fd


def _pread(fd: int, size: int, offset: int) -> bytes:
    if hasattr(os, "pread"):
        return os.pread(fd, size, offset)
    os.lseek(fd, offset, os.SEEK_SET)  # pragma: no cover - Windows
    return os.read(fd, size)  # pragma: no cover


class _Writes:
    """A ``write`` callable as a file object that has only ``write``."""

    def __init__(self, write) -> None:
        self.write = write


def _copy_range(src: int, dst: int, offset: int, count: int) -> int:
    return os.copy_file_range(src, dst, count, offset)


def _send(src: int, dst: int, offset: int, count: int) -> int:
    return os.sendfile(dst, src, offset, count)


if not hasattr(os, "copy_file_range"):  # pragma: no cover - not Linux
    _copy_range = None
if not hasattr(os, "sendfile"):  # pragma: no cover
    _send = None


def stream_json(doc: dict, write) -> None:
    """Write a document whose values may be Rows (made on demand) chunk by chunk through ``write(bytes)``.

    Memory stays bounded by one chunk of rows. A document without Rows that
    is small is written indented, like encode_json.

    Parameters
    ----------
    doc : dict
        The JSON document; a value may be a :class:`capred.result.Rows`.
    write : callable
        Takes each chunk of bytes in order (e.g. a binary file's ``write``; text its run wrote ahead,
        :class:`FileText`, is then copied file to file).
    """
    from ..spool import Rows

    owner = getattr(write, "__self__", None)  # the file of a bound ``write``
    target = owner if hasattr(owner, "write") else _Writes(write)

    def put(data) -> None:
        if isinstance(data, FileText) and not getattr(write, "takes_file_text", False):
            write_piece(target, data)
        else:
            write(data)

    if not any(isinstance(v, Rows) for v in doc.values()):
        write(encode_json(doc))
        return
    write(b"{")
    for k, (key, value) in enumerate(doc.items()):
        write((b"," if k else b"") + _dumps(key) + b":")
        if isinstance(value, Rows):
            write(b"[")
            first = True
            # a Rows that can encode its rows itself (column by column, the same bytes) does
            pieces = value.json_chunks() if hasattr(value, "json_chunks") else map(encode_rows, value.chunks())
            for data in pieces:
                if len(data):
                    if not first:
                        write(b",")
                    put(data)
                    first = False
            write(b"]")
        else:
            write(_dumps(value))
    write(b"}\n")


def encode_rows(rows: list) -> bytes:
    """The JSON of a list of rows without its brackets; empty for no rows.

    What stream_json writes of each chunk of Rows: NaN and infinities as null, floats in shortest round-trip form.

    Parameters
    ----------
    rows : list of dict
        The rows to encode.

    Returns
    -------
    bytes
        The comma-separated JSON objects (no brackets).
    """
    return _dumps(rows)[1:-1] if rows else b""


#: what starts a formula in a spreadsheet (OWASP "CSV injection": =, +, -, @, tab, carriage return)
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")


def defuse(text: str) -> str:
    """Text a spreadsheet shows as text: a leading ``'`` before text that would start a formula.

    The OWASP recommendation against CSV (formula) injection: a cell
    beginning with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return is
    prefixed with a single quote, which Excel and LibreOffice show as a text
    cell and never evaluate. Used for the ``excel-eu`` CSV dialect (made to be
    opened in Excel); the standard CSV keeps text verbatim (it is data).

    Parameters
    ----------
    text : str
        A text cell.

    Returns
    -------
    str
        ``text``, prefixed with ``'`` when it starts with a formula character.
    """
    return "'" + text if text.startswith(FORMULA_START) else text


def _csv_cell(value, sep: str = ",", joiner: str = ";", eu: bool = False) -> str:
    """One cell of an object column: text quoted as CSV needs, lists joined, blanks empty.

    With ``eu`` (the Excel dialect) decimal commas, and text that would start a formula defused.
    """
    if hasattr(value, "item") and not isinstance(value, str):  # a numpy scalar
        value = value.item()
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return ""
    if isinstance(value, float):
        return repr(value).replace(".", ",") if eu else repr(value)
    if isinstance(value, (bool, int)):
        return str(value)
    text = joiner.join(map(str, value)) if isinstance(value, (list, tuple)) else str(value)
    if eu:
        text = defuse(text)
    if any(ch in text for ch in (sep, '"', "\n", "\r")):
        return '"' + text.replace('"', '""') + '"'
    return text


def _csv_column(values, sep: str = ",", joiner: str = ";", eu: bool = False) -> list[str]:
    """Cells of one column; numbers in shortest round-trip form (via orjson's float printer)."""
    import numpy as np

    a = np.asarray(values)
    if a.dtype.kind in "fiu" and a.size:
        try:
            import orjson
        except ImportError:  # pragma: no cover
            cells = ["" if not np.isfinite(x) else repr(x) for x in a.tolist()]
        else:
            text = orjson.dumps(
                a.astype(float) if a.dtype.kind == "f" else a, option=orjson.OPT_SERIALIZE_NUMPY
            ).decode("ascii")[1:-1]
            cells = text.replace("null", "").split(",")
        return [c.replace(".", ",") for c in cells] if eu else cells
    if a.dtype.kind == "b":
        return ["True" if x else "False" for x in a.tolist()]
    values = a.tolist()
    if values and set(map(type, values)) == {str}:  # plain text: quote only if some cell needs it
        joined = "\x00".join(values)
        if not any(ch in joined for ch in (sep, '"', "\n", "\r")) and not (
            eu and any(x.startswith(FORMULA_START) for x in values)
        ):
            return values
    return [_csv_cell(x, sep, joiner, eu) for x in values]


def _column_arrays(frame) -> list:
    """The columns of a DataFrame as arrays (without making a Series per column where pandas allows)."""
    get = getattr(frame, "_get_column_array", None)  # pandas >= 1.3; a Series per column otherwise
    if get is not None:
        try:
            return [np_array(get(i)) for i in range(frame.shape[1])]
        except (TypeError, IndexError, AttributeError):  # pragma: no cover - a pandas without it
            pass
    return [frame.iloc[:, i].to_numpy() for i in range(frame.shape[1])]


def np_array(values):
    """``values`` as a numpy array (an extension array, e.g. nullable integers, through to_numpy).

    Parameters
    ----------
    values : array_like
        A numpy array, a pandas Series or extension array, or a sequence.

    Returns
    -------
    numpy.ndarray
        ``values`` itself when it already is one (no copy).
    """
    import numpy as np

    return (
        values
        if isinstance(values, np.ndarray)
        else np.asarray(values.to_numpy() if hasattr(values, "to_numpy") else values)
    )


def write_csv_file(path, frame, dialect: str = "standard") -> None:
    """A DataFrame (a mapping of column name to array, or a capred.result.Spool of them) as UTF-8 CSV.

    Floats in shortest round-trip form (every digit kept), NaN as an empty cell, lists joined with ';', text quoted
    where CSV needs it. ``path`` may be a binary file.

    ``dialect="excel-eu"``: what a Belgian, French or German Excel opens as columns: ';' separators,
    decimal commas, lists joined with '|', a UTF-8 byte-order mark (so 'µ' and '°' survive), and text that
    would start a formula prefixed with ``'`` (see ``defuse``). The standard dialect writes text verbatim.

    Parameters
    ----------
    path : str, pathlib.Path or binary file
        Where to write.
    frame : mapping or capred.result.Spool
        Column name -> array (all of one length), or a Spool of such blocks.
    dialect : {"standard", "excel-eu"}, optional
        The CSV dialect (default "standard").
    """
    import numpy as np

    eu = dialect == "excel-eu"
    sep, joiner = (";", "|") if eu else (",", ";")
    with contextlib.ExitStack() as stack:
        fh = path if hasattr(path, "write") else stack.enter_context(open(path, "wb"))
        if eu:
            fh.write("\ufeff".encode("utf-8"))
        pieces = frame.csv_pieces(dialect) if hasattr(frame, "csv_pieces") else None
        if pieces is not None:  # a table whose CSV text its run has written ahead (capred.pipelines.bridge_blocks)
            for data in pieces:
                write_piece(fh, data)
            return
        blocks = frame.blocks() if hasattr(frame, "blocks") else [frame]  # a Spool: block by block
        for k, block in enumerate(blocks):
            names = list(block) if isinstance(block, dict) else list(block.columns)
            arrays = list(block.values()) if isinstance(block, dict) else _column_arrays(block)
            if k == 0:
                fh.write(
                    (sep.join(_csv_column(np.array([str(c) for c in names], dtype=object), sep, eu=eu)) + "\n").encode(
                        "utf-8"
                    )
                )
            runs = _float_runs(arrays)
            for start in range(0, len(arrays[0]) if arrays else 0, 10_000):  # memory bounded by one chunk
                stop = start + 10_000
                if runs == [(0, len(arrays))]:  # every column a float column: the rows as they come
                    fh.write(("\n".join(_float_lines(arrays, sep, eu, start, stop)) + "\n").encode("utf-8"))
                    continue
                columns, j = [], 0
                while j < len(arrays):
                    run = next((r for r in runs if r[0] == j), None)
                    if run is not None:  # consecutive float columns: one string per row, printed at once
                        columns.append(_float_lines(arrays[run[0] : run[1]], sep, eu, start, stop))
                        j = run[1]
                    else:
                        columns.append(_csv_column(arrays[j][start:stop], sep, joiner, eu))
                        j += 1
                fh.write(("\n".join(map(sep.join, zip(*columns))) + "\n").encode("utf-8"))


def _float_runs(arrays) -> list[tuple[int, int]]:
    """(first, end) of each run of consecutive 1-D float columns (numpy arrays), when orjson is installed."""
    import numpy as np

    try:
        import orjson  # noqa: F401
    except ImportError:  # pragma: no cover - orjson is a dependency
        return []
    runs: list[tuple[int, int]] = []
    for j, a in enumerate(arrays):
        if isinstance(a, np.ndarray) and a.ndim == 1 and a.dtype.kind == "f":
            if runs and runs[-1][1] == j:
                runs[-1] = (runs[-1][0], j + 1)
            else:
                runs.append((j, j + 1))
    return runs


def _float_lines(arrays, sep: str, eu: bool, start: int, stop: int) -> list[str]:
    """Rows start..stop of float columns as CSV text, one string per row.

    The cells _csv_column writes (shortest round-trip form, NaN and infinities empty, decimal commas with ``eu``),
    printed by one orjson call on the rows that hold a number, as a matrix; a row without any is its separators alone.
    """
    import numpy as np
    import orjson

    n = len(arrays[0][start:stop])
    matrix = np.empty((n, len(arrays)))
    for j, a in enumerate(arrays):
        matrix[:, j] = a[start:stop]
    finite = np.isfinite(matrix)
    some = np.flatnonzero(finite.any(axis=1))
    if some.size < n:
        matrix = matrix[some]
    text = orjson.dumps(matrix, option=orjson.OPT_SERIALIZE_NUMPY).decode("ascii")[2:-2] if some.size else ""
    if some.size and not finite[some].all():
        text = text.replace("null", "")
    if eu:  # ';' between cells (and rows: '];['), decimal commas
        text, between = text.replace(",", sep).replace(".", ","), "]" + sep + "["
    else:
        text, between = (text, "],[") if sep == "," else (text.replace(",", sep), "]" + sep + "[")
    rows = text.split(between) if some.size else []
    if some.size == n:
        return rows
    lines = np.full(n, sep * (len(arrays) - 1), dtype=object)
    lines[some] = rows
    return lines.tolist()


def encode_csv(frame) -> bytes:
    """The bytes write_csv_file writes (for tests and small tables).

    Parameters
    ----------
    frame : mapping
        Column name -> array (all of one length).

    Returns
    -------
    bytes
        The standard-dialect CSV.
    """
    buf = io.BytesIO()
    write_csv_file(buf, frame)
    return buf.getvalue()


def safe_name(name: str, taken: set[str], limit: int = 80) -> str:
    """A file-name stem for a user label (material, sheet), unique among ``taken`` (which it joins).

    Parameters
    ----------
    name : str
        The user's label.
    taken : set of str
        Stems already used (lower case); the new stem is added to it.
    limit : int, optional
        Most characters of the stem before a ``_2``, ``_3`` suffix (default 80).

    Returns
    -------
    str
        ``name`` with every character but letters, digits, ``.``, ``-`` and ``_`` replaced by ``_``.
    """
    stem = re.sub(r"[^\w.-]", "_", name, flags=re.ASCII).strip(".") or "unnamed"
    stem = stem[:limit]
    candidate, k = stem, 2
    while candidate.lower() in taken:
        candidate, k = f"{stem}_{k}", k + 1
    taken.add(candidate.lower())
    return candidate


# --- checks before computing ------------------------------------------------------------------------
#: files the operating system's file browsers leave in any folder; never a user's work
OS_LITTER = frozenset({".DS_Store", "Thumbs.db", "desktop.ini"})
#: the files a batch writes into its root folder (beside one folder per input)
BATCH_FILES = ("index.csv", "season.csv", "season.html")
#: a batch's root files whose names depend on its commands (season_<command>.csv): protected as BATCH_FILES
BATCH_FILE_PATTERNS = ("season_*.csv",)


def batch_file_names(root) -> list[str]:
    """Every root file name a batch writes or has written in ``root``.

    BATCH_FILES, the files there that match BATCH_FILE_PATTERNS, and those its provenance.json records.

    Parameters
    ----------
    root : str or pathlib.Path
        A batch's output folder.

    Returns
    -------
    list of str
        File names, without repeats, in that order.
    """
    import fnmatch

    names = list(BATCH_FILES)
    try:
        present = sorted(os.listdir(root))
    except OSError:
        present = []
    names += [n for n in present if any(fnmatch.fnmatch(n, p) for p in BATCH_FILE_PATTERNS)]
    names += list(batch_record(root))
    return list(dict.fromkeys(names))


#: the header capred writes on a batch's index.csv
INDEX_HEADER = "command,input,status,message,output"


def _listing(folder: Path) -> tuple[set[str], set[str]]:
    """(files, folders) under ``folder`` as relative POSIX paths; links are files (never followed)."""
    files, dirs = set(), set()
    stack = [(folder, "")]
    while stack:
        here, rel = stack.pop()
        with os.scandir(here) as it:
            for entry in it:
                name = f"{rel}{entry.name}"
                if entry.is_dir(follow_symlinks=False):
                    dirs.add(name)
                    stack.append((Path(entry.path), name + "/"))
                else:
                    files.add(name)
    return files, dirs


def _provenance(folder: Path) -> dict | None:
    """A folder's provenance.json when capred wrote it (it names a capred version), else None."""
    try:
        doc = json.loads((folder / "provenance.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc if isinstance(doc, dict) and "capred_version" in doc else None


def foreign_files(folder) -> list[str]:
    """Files and folders in a run folder that its provenance.json does not list (sorted, relative).

    A run folder is capred's to replace only when this is empty: every file
    in it was written by the run its provenance.json records (the files
    browsers leave, ``OS_LITTER``, do not count). A folder without a capred
    provenance.json has only foreign files.

    Parameters
    ----------
    folder : str or pathlib.Path
        A run folder (none there: no foreign file).

    Returns
    -------
    list of str
        Relative paths; a folder ends with ``/``.
    """
    folder = Path(folder)
    if not folder.is_dir():
        return []
    files, dirs = _listing(folder)
    prov = _provenance(folder)
    outputs = prov.get("outputs") if prov is not None else None
    listed = {o for o in outputs if isinstance(o, str)} if isinstance(outputs, list) else set()
    parents = {"/".join(n.split("/")[:k]) for n in listed for k in range(1, n.count("/") + 1)}
    foreign = [f for f in files if f not in listed and f.rsplit("/", 1)[-1] not in OS_LITTER]
    foreign += [d + "/" for d in dirs if d not in parents]
    foreign += edited_files(folder, prov, files)
    return sorted(foreign)


def edited_files(folder, prov: dict | None = None, files=None) -> list[str]:
    """Files a run's provenance.json lists with a SHA-256 (``outputs_sha256``) whose content differs now.

    A user edited them after capred wrote them, so they are no longer capred's to replace.

    Parameters
    ----------
    folder : str or pathlib.Path
        A run folder.
    prov : dict, optional
        Its provenance.json (read when not given).
    files : set of str, optional
        The files present (listed when not given).

    Returns
    -------
    list of str
        Relative paths, sorted (empty for a folder written before hashes were recorded).
    """
    folder = Path(folder)
    prov = _provenance(folder) if prov is None else prov
    hashes = prov.get("outputs_sha256") if prov is not None else None
    if not isinstance(hashes, dict):
        return []
    files = _listing(folder)[0] if files is None else files
    edited = []
    for name, digest in hashes.items():
        if name in files and isinstance(digest, str):
            path = folder / name
            if path.is_symlink() or not path.is_file() or _sha256(path) != digest:
                edited.append(name)
    return sorted(edited)


def _foreign_message(out: Path, foreign: list[str]) -> str:
    shown = ", ".join(foreign[:5]) + (f" and {len(foreign) - 5} more" if len(foreign) > 5 else "")
    prov = _provenance(out)
    if prov is not None and prov.get("command") == "batch":
        return (
            f"--out {out} is the folder of a batch (index.csv and one folder per input); a single run is "
            "written into a folder of its own: give another --out"
        )
    if prov is None:
        return (
            f"--out {out} is a folder capred did not write (it holds {shown}); capred replaces its output "
            "folder as a whole: give a new or empty folder"
        )
    edited = [f for f in foreign if f in edited_files(out, prov)]
    if edited:
        named = ", ".join(edited[:5]) + (f" and {len(edited) - 5} more" if len(edited) > 5 else "")
        return (
            f"--out {out}: {named} changed since capred wrote {'it' if len(edited) == 1 else 'them'} (the SHA-256 "
            "recorded in provenance.json differs); capred never replaces a file a user edited: move it out "
            "or give another folder"
        )
    return (
        f"--out {out} holds files capred did not write: {shown}; capred replaces its output folder as a "
        "whole and never deletes a file it did not write: move them out or give another folder"
    )


def _sha256(path: Path) -> str:
    import hashlib

    with open(path, "rb") as fh:  # streamed: an output may be larger than the memory a run may take
        return hashlib.file_digest(fh, "sha256").hexdigest()


def batch_record(root) -> dict:
    """The root files a batch wrote into ``root``, {name: [SHA-256, ...]}, from its provenance.json.

    A name holds two hashes only while its file is being replaced (the one
    before and the one after), so a batch killed at any moment leaves a file
    the record still recognises.

    Parameters
    ----------
    root : str or pathlib.Path
        A batch's output folder.

    Returns
    -------
    dict
        File name -> list of SHA-256 hex digests; empty without a batch's provenance.json.
    """
    prov = _provenance(Path(root))
    files = prov.get("batch_files") if prov is not None and prov.get("command") == "batch" else None
    if not isinstance(files, dict):
        return {}
    return {k: [h for h in v if isinstance(h, str)] for k, v in files.items() if isinstance(v, list)}


def foreign_batch_files(root) -> list[str]:
    """Which of a batch's root files exist in ``root`` but were not written by a capred batch.

    The root files are ``BATCH_FILES`` and provenance.json. capred recognises
    its own by the batch's provenance.json, which records the SHA-256 of each
    root file it wrote (a file edited since is no longer capred's), and an
    index.csv also by its header (folders of earlier versions). A
    provenance.json that is not a batch's (a single run's report) is foreign
    too: a batch root is not a report folder.

    Parameters
    ----------
    root : str or pathlib.Path
        A batch's output folder.

    Returns
    -------
    list of str
        Names of the root files capred did not write.
    """
    root = Path(root)
    record = batch_record(root)
    foreign = []
    for name in batch_file_names(root):
        path = root / name
        if not os.path.lexists(path):
            continue
        if path.is_symlink() or not path.is_file():
            foreign.append(name)
        elif _sha256(path) in record.get(name, ()):
            continue
        elif (  # an index.csv of a batch before hashes were recorded (no record at all): known by its header
            name == "index.csv"
            and not record
            and path.read_bytes()[: len(INDEX_HEADER) + 1] == (INDEX_HEADER + "\n").encode()
        ):
            continue
        else:
            foreign.append(name)
    prov = root / "provenance.json"
    if os.path.lexists(prov) and (_provenance(root) or {}).get("command") != "batch":
        foreign.append("provenance.json")
    return foreign


def check_target(out, inputs=(), replace: bool = True) -> Path:
    """Refuse an output folder that cannot or must not receive a run; return its absolute path.

    ``replace`` is True for a run folder (replaced whole: refused unless every
    file in it is one its provenance.json lists) and False for a batch root
    (only its index.csv, season.csv, season.html, provenance.json and one
    folder per input are written: refused where one of those root files
    exists that capred did not write, e.g. a manifest named season.csv).
    Raises OutputError with one clear message.

    Parameters
    ----------
    out : str or pathlib.Path
        The output folder (``--out``).
    inputs : sequence of str or pathlib.Path, optional
        The input files, which the output folder must not hold or replace.
    replace : bool, optional
        True (default) for a run folder, False for a batch root.

    Returns
    -------
    pathlib.Path
        The absolute path of ``out``.
    """
    try:
        return _check_target(Path(os.path.abspath(out)), inputs, replace)
    except OSError as exc:
        raise _os_error(Path(out), exc) from None


def _check_target(out: Path, inputs, replace: bool) -> Path:
    real = Path(os.path.realpath(out))
    from .grid import source_path

    for src in inputs:
        src = source_path(src)
        if src is None or hasattr(src, "to_csv"):
            continue
        s = Path(os.path.realpath(src))
        if s == real or real in s.parents:
            raise OutputError(
                f"--out {out} holds the input {src}; capred never writes over its inputs: choose another output folder"
            )
    if out.exists() and not out.is_dir():
        raise OutputError(f"--out {out} is a file, not a folder: choose a folder name")
    cwd = Path(os.path.realpath(Path.cwd()))
    if replace and (real == cwd or real in cwd.parents):
        raise OutputError(
            f"--out {out} is the current folder or one of its parents; capred replaces its output "
            "folder as a whole: give a new folder name, e.g. --out report"
        )
    if replace and out.is_dir():
        foreign = foreign_files(out)
        if foreign:
            raise OutputError(_foreign_message(out, foreign))
    if not replace and out.is_dir():
        foreign = foreign_batch_files(out)
        if foreign == ["provenance.json"] and _provenance(out) is not None:
            raise OutputError(
                f"--out {out} is the report folder of one run (capred {_provenance(out).get('command')}); "
                "a batch writes index.csv and one folder per input into a folder of its own: "
                "give another --out"
            )
        if foreign:
            raise OutputError(
                f"--out {out} holds {', '.join(foreign)}, which capred did not write; a batch writes "
                f"{', '.join(BATCH_FILES)} and provenance.json there and never writes over a file it did not "
                "write (a manifest among them?): choose another --out or move the file"
            )
    parent = out if not replace and out.is_dir() else out.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if _read_only(parent):
        raise OutputError(f"cannot write to {parent}: it is on a read-only file system; nothing was written")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"cannot write to {parent}: permission denied")
    return out


def _read_only(folder: Path) -> bool:
    """True when ``folder`` lies on a file system mounted read-only (said so, not as 'permission denied')."""
    try:
        return bool(os.statvfs(folder).f_flag & os.ST_RDONLY)
    except (OSError, AttributeError):  # no statvfs (Windows): the write itself will tell
        return False


#: free bytes below which a failure while saving figures is taken for a full disk
_FULL_DISK_BYTES = 1 << 20


def _drawing_error(out: Path, exc: BaseException) -> OutputError | None:
    """The clear message for a failure while the figures and report were drawn and saved, or None for a bug.

    A full disk can surface from matplotlib as another exception raised while it handles the OSError (e.g. an
    AttributeError when closing a half-written file): the OSError is then in the exception's context. A killed
    drawing process surfaces as a RuntimeError of capred.report.outputs.
    """
    seen = set()
    e = exc
    while e is not None and id(e) not in seen:
        seen.add(id(e))
        if isinstance(e, OSError) and e.errno is not None:
            return _os_error(out, e)
        e = e.__cause__ or e.__context__
    try:  # an exception sent back by the drawing process has lost its context: the disk itself tells
        if shutil.disk_usage(out.parent).free < _FULL_DISK_BYTES:
            return _os_error(out, OSError(errno.ENOSPC, "no space left on the device"))
    except OSError:
        pass
    if isinstance(exc, RuntimeError) and "process drawing figures" in str(exc):
        return OutputError(f"cannot write the outputs to {out}: {exc} (killed, or out of memory?); nothing was written")
    return None


# --- the transaction ---------------------------------------------------------------------------------
@contextlib.contextmanager
def _locked(folder: Path):
    """Exclusive lock on a folder (serialises swaps into it); a no-op where flock is missing."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock


def _exchange(a: Path, b: Path) -> bool:
    """Atomically swap two paths (Linux renameat2 RENAME_EXCHANGE); False where unsupported."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd, rename_exchange = -100, 2
    if fn(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EPERM):
        return False
    raise OSError(err, os.strerror(err), str(b))


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _sweep_stale(parent: Path, stem: str) -> None:
    """Remove hidden work folders of earlier runs into the same target that were killed.

    The folder's names are compared as text (no glob pattern: a batch's folder holds one folder per input,
    and a stem may hold characters a pattern would read, such as '[').
    """
    prefix = f".{stem}.capred-"
    try:
        names = [n for n in os.listdir(parent) if n.startswith(prefix)]
    except OSError:
        return
    for name in names:
        m = _STALE.match(name, len(prefix) - len(".capred-"))
        if m and int(m.group(1)) != os.getpid() and not _pid_alive(int(m.group(1))):
            shutil.rmtree(parent / name, ignore_errors=True)


#: the tail of a work folder's name: .capred-tmp-<pid>- or .capred-old-<pid>-
_STALE = re.compile(r"\.capred-(?:tmp|old)-(\d+)-")


def _prefix(out: Path, kind: str) -> str:
    return f".{out.name[:100]}{kind}{os.getpid()}-"


def _os_error(out: Path, exc: OSError) -> OutputError:
    reason = {
        errno.ENOSPC: "no space left on the device",
        errno.EDQUOT: "disk quota exceeded",
        errno.EACCES: "permission denied",
        errno.EROFS: "read-only file system",
        errno.ENAMETOOLONG: "a file name is too long",
    }.get(exc.errno, exc.strerror or str(exc))
    return OutputError(f"cannot write the outputs to {out}: {reason}; nothing was written")


def _safe_svg(path: Path) -> None:
    """Rewrite an SVG file whose text holds control or bidi characters with them shown (capred.text_safety)."""
    from ..text_safety import has_unsafe, xml_safe

    text = path.read_text(encoding="utf-8", errors="surrogateescape")
    if has_unsafe(text):
        path.write_text(xml_safe(text), encoding="utf-8", errors="surrogateescape")


def _sealed(seal, undo) -> None:
    """Call ``seal()`` (the new folder in place); on any failure ``undo()`` (the earlier folder back) and re-raise."""
    if seal is None:
        return
    try:
        seal()
    except BaseException:
        undo()
        raise


class RunFolder:
    """A hidden work folder that becomes ``out`` on ``commit()``; removed if anything fails."""

    def __init__(self, out: Path):
        if os.path.islink(out):  # a symlinked --out: the run goes where the link points, the link stays
            out = Path(os.path.realpath(out))
        self.out = out
        self.names: list[str] = []
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
            self.tmp = Path(tempfile.mkdtemp(prefix=_prefix(out, _TMP), dir=out.parent))
            os.chmod(self.tmp, 0o777 & ~_UMASK)
        except OSError as exc:
            raise _os_error(out, exc) from None

    def write_bytes(self, name: str, data: bytes) -> None:
        """Write file ``name`` of the run into the work folder and record it (see ``done``).

        Parameters
        ----------
        name : str
            File name, relative to the run folder.
        data : bytes
            The whole content.
        """
        with open(self.tmp / name, "wb") as fh:
            fh.write(data)
        self.done(name)

    def path_for(self, name: str) -> Path:
        """Path to write ``name`` to directly (call ``done(name)`` afterwards).

        Parameters
        ----------
        name : str
            File name, relative to the run folder.

        Returns
        -------
        pathlib.Path
            Its path in the work folder.
        """
        return self.tmp / name

    def done(self, name: str) -> None:
        """Record a file written into the work folder (with the usual permissions).

        An SVG is made well-formed (a control character in a label, which XML forbids, is shown as its control picture).

        Parameters
        ----------
        name : str
            File name, relative to the run folder.
        """
        if name.endswith(".svg"):
            _safe_svg(self.tmp / name)
        os.chmod(self.tmp / name, 0o666 & ~_UMASK)
        self.names.append(name)

    def commit(self, seal=None) -> list[Path]:
        """Move the work folder into place as the output folder, replacing an earlier run of capred's (under a lock).

        Raises OutputError, leaving the earlier run intact, when the output folder is a file or now holds a file
        its provenance.json does not list (or a file capred wrote that was edited since).

        Parameters
        ----------
        seal : callable or None, optional
            Called once the new folder is in place, before the earlier run is removed (recording the run in a
            lab store); if it raises, the earlier folder is put back and the new one removed (with ``abort``).

        Returns
        -------
        list of pathlib.Path
            The files written, in the output folder.
        """
        out = self.out
        with _locked(out.parent):
            _sweep_stale(out.parent, out.name[:100])
            if out.exists():
                if not out.is_dir():
                    raise OutputError(f"--out {out} is a file, not a folder: choose a folder name")
                foreign = foreign_files(out)  # again, under the lock: a file saved there while we computed
                if foreign:
                    raise OutputError(_foreign_message(out, foreign))
                if _exchange(self.tmp, out):  # self.tmp now holds the earlier run
                    _sealed(seal, lambda: _exchange(self.tmp, out))
                else:
                    old = Path(tempfile.mkdtemp(prefix=_prefix(out, _OLD), dir=out.parent))
                    os.replace(out, old / "run")
                    os.replace(self.tmp, out)

                    def back():
                        os.replace(out, self.tmp)
                        os.replace(old / "run", out)
                        shutil.rmtree(old, ignore_errors=True)

                    _sealed(seal, back)
                    self.tmp = old
                shutil.rmtree(self.tmp, ignore_errors=True)  # now holds the earlier run
            else:
                os.replace(self.tmp, out)
                _sealed(seal, lambda: os.replace(out, self.tmp))
        return [out / n for n in self.names]

    def abort(self) -> None:
        """Remove the work folder and what was written into it (the output folder is left as it was)."""
        shutil.rmtree(self.tmp, ignore_errors=True)


def write_run(
    result,
    out,
    command_line: str | None = None,
    csv_dialect: str = "standard",
    xlsx: bool = False,
    artifacts=None,
    seal=None,
) -> list[Path]:
    """Write the files of ``result`` into the folder ``out``, whole or not at all.

    Files: each table as ``<name>.csv`` (``csv_dialect`` "standard" or
    "excel-eu"), the JSON document, ``tables.xlsx`` (when ``xlsx``), the
    command's own files, then whatever ``artifacts(folder)`` adds (the
    figures and report.html drawn by capred.report.outputs; this module never
    draws), and ``provenance.json``. Returns the paths written.
    Raises OutputError (nothing written, an earlier run in ``out`` intact).

    Parameters
    ----------
    result : capred.result.Result
        The run to write.
    out : str or pathlib.Path
        The output folder.
    command_line : str or None, optional
        Recorded in provenance.json (default: ``sys.argv`` joined).
    csv_dialect : {"standard", "excel-eu"}, optional
        Dialect of the CSV tables.
    xlsx : bool, optional
        Also write every table into ``tables.xlsx``.
    artifacts : callable or None, optional
        ``artifacts(folder)`` writes further files (figures, report) into the :class:`RunFolder`.
    seal : callable or None, optional
        ``seal(out)`` is called once the folder is in place (see :meth:`RunFolder.commit`): recording the run in
        a lab store; if it raises, the earlier folder is put back and nothing is written.

    Returns
    -------
    list of pathlib.Path
        The files written, in ``out``.
    """
    out = check_target(out, [i.path for i in result.inputs if i.path != "<DataFrame>"])
    folder = RunFolder(out)
    json_writer = None
    try:
        doc = result.json_lazy()
        json_writer = _JsonWriter(folder.path_for(result.json_name), doc)  # a long document: in a second process
        tables = result.csv_tables()
        check_output_size(result, tables, out)  # said before a table is written
        for name, frame in tables.items():
            write_csv_file(folder.path_for(f"{name}.csv"), frame, csv_dialect)
            folder.done(f"{name}.csv")
        if xlsx:
            from .spreadsheet_out import write_workbook

            write_workbook(folder.path_for("tables.xlsx"), result.tables())
            folder.done("tables.xlsx")
        for name, data in result.extra_files().items():
            folder.write_bytes(name, data)
        json_writer.finish()
        folder.done(result.json_name)
        if artifacts is not None:
            try:
                artifacts(folder)
            except (CapredError, OSError):
                raise
            except Exception as exc:
                clear = _drawing_error(out, exc)
                if clear is None:
                    raise
                raise clear from None
        hashes = {n: _sha256(folder.path_for(n)) for n in folder.names}  # a user's later edit is then seen
        folder.write_bytes("provenance.json", encode_json(provenance(result, folder.names, command_line, hashes), True))
        return folder.commit(None if seal is None else lambda: seal(out))
    except OSError as exc:
        _cancel(json_writer, folder)
        raise _os_error(out, exc) from None
    except BaseException:
        _cancel(json_writer, folder)
        raise


#: outputs may take this many times the bytes of the run's inputs (a shear file's results and JSON take about 45
#: times its bytes: 55 columns written for each 7 read) ...
OUTPUT_MULTIPLE = 100
#: ... or this many bytes, whichever is larger (a calculator without input files, a small file's report) ...
OUTPUT_FLOOR = 512 * 2**20
#: ... and never more than this many bytes (a run's tables are read by people and spreadsheets)
OUTPUT_MAX = 4 * 2**30
#: the environment variable that raises the outputs' bound [MiB], for a run meant to write that much
OUTPUT_VARIABLE = "CAPRED_MAX_OUTPUT_MEGABYTES"
#: bytes a table cell takes in the CSV and its share of the JSON document, about, with a margin (measured: a
#: shear run's results of 27.5 million cells, 304 MB of CSV and 568 MB of JSON: 32 bytes a cell)
BYTES_PER_CELL = 40


def output_budget(input_bytes: int) -> int:
    """The most bytes a run's tables may take.

    OUTPUT_MULTIPLE times its inputs, at least OUTPUT_FLOOR, at most OUTPUT_MAX, or ``$CAPRED_MAX_OUTPUT_MEGABYTES`` MiB
    where set.

    Parameters
    ----------
    input_bytes : int
        The bytes of the run's input files.

    Returns
    -------
    int
        Bytes.
    """
    given = os.environ.get(OUTPUT_VARIABLE, "").strip()
    if given:
        try:
            return int(float(given) * 2**20)
        except ValueError:
            raise OutputError(f"{OUTPUT_VARIABLE}={given!r} is not a number of megabytes") from None
    return min(OUTPUT_MAX, max(OUTPUT_FLOOR, OUTPUT_MULTIPLE * input_bytes))


def _cells(table) -> int:
    """Cells of a table as write_csv_file takes it (0 where its text is already written: csv_pieces)."""
    if hasattr(table, "csv_pieces"):
        return 0
    if hasattr(table, "shape"):
        return int(table.shape[0]) * max(1, int(table.shape[1]))
    if isinstance(table, dict):
        first = next(iter(table.values()), ())
        return len(first) * len(table)
    if callable(getattr(table, "columns", None)):  # a Spool or a long run's blocks: rows x the first row's columns
        rows = getattr(table, "n", None)
        if rows is None:
            rows = sum(int(r) for _, _, r in getattr(table, "_index", ()))
        return int(rows) * max(1, len(table.columns(0, 1))) if rows else 0
    return 0


def check_output_size(result, tables: dict, out) -> None:
    """Refuse, before anything is written, a run whose tables would take more than :func:`output_budget`.

    The size is estimated as cells x :data:`BYTES_PER_CELL` (the CSV and the JSON document). A long file's run
    was already sized from its lines before it was computed (:func:`check_rows_output`); this is what a run
    sized by no such count (a workbook, a DataFrame) is checked by.

    Parameters
    ----------
    result : capred.result.Result
        The run (its inputs' sizes).
    tables : dict
        Its CSV tables, name -> DataFrame.
    out : pathlib.Path
        The output folder (for the message).

    Raises
    ------
    OutputError
        Over the bound, saying how large, why and how to allow it.
    """
    check_output_estimate(sum(_cells(t) for t in tables.values()), [i.path for i in result.inputs], out)


def check_output_estimate(cells: int, inputs, out) -> None:
    """Refuse a run whose outputs would take more than :func:`output_budget` of its ``inputs``.

    The outputs are ``cells`` table cells, about :data:`BYTES_PER_CELL` bytes each as CSV and JSON; checked before its
    tables are written, or before anything is computed when its input's lines size them (:func:`check_rows_output`).

    Parameters
    ----------
    cells : int
        Table cells the run writes (or would write).
    inputs : sequence of path
        The run's input files (their sizes set the bound; a path that is not a file counts 0).
    out : pathlib.Path
        The output folder (for the message).

    Raises
    ------
    OutputError
        Over the bound, saying how large, why and how to allow it; nothing is written.
    """
    estimate = cells * BYTES_PER_CELL
    if estimate <= OUTPUT_FLOOR and not os.environ.get(OUTPUT_VARIABLE):  # the common case: no file looked at
        return
    size = 0
    for path in inputs:
        try:
            size += os.path.getsize(path)
        except (OSError, TypeError, ValueError):
            pass
    budget = output_budget(size)
    if estimate > budget:
        raise OutputError(
            f"the outputs of this run would take about {estimate / 2**30:.2f} GiB ({cells:,} table cells, as CSV "
            f"and JSON), more than {budget / 2**30:.2f} GiB ({OUTPUT_MULTIPLE} times the inputs' "
            f"{size / 2**20:.1f} MiB, at least {OUTPUT_FLOOR / 2**20:.0f} MiB and at most {OUTPUT_MAX / 2**30:.0f} "
            f"GiB); nothing was written to {out}. To write them, set {OUTPUT_VARIABLE} to the megabytes allowed"
        )


def check_rows_output(source, cells_per_row: int, out, extra_inputs=()) -> None:
    """Refuse, before its input is read as a table, a run whose outputs would exceed :func:`output_budget`.

    The input file's data lines (capred.io.blocks.data_lines, less the header) x ``cells_per_row`` x
    :data:`BYTES_PER_CELL`.

    Only a plain text file is counted, a block of bytes at a time (about 1 s for 250 MB); a workbook, a
    DataFrame, a FIFO or device (never opened here) or a file too short to matter (at most one row per two bytes
    under the bound) costs nothing.

    Parameters
    ----------
    source : str, pathlib.Path, pandas.DataFrame or TableSource
        The run's input table.
    cells_per_row : int
        Table cells its outputs take per input row.
    out : pathlib.Path
        The output folder (for the message).
    extra_inputs : sequence of path, optional
        Further inputs of the run (their bytes count toward the bound).

    Raises
    ------
    OutputError
        Over the bound, with nothing written.
    """
    from .blocks import data_lines
    from .grid import SPREADSHEET_SUFFIXES, source_path

    path = source_path(source) if source is not None else None
    if not cells_per_row or not isinstance(path, (str, os.PathLike)):
        return
    path = Path(path)
    try:
        size = path.stat().st_size if path.is_file() else 0
    except OSError:
        return  # the reader says what is wrong with the file
    if not size or path.suffix.lower() in SPREADSHEET_SUFFIXES:
        return
    if (size // 2) * cells_per_row * BYTES_PER_CELL <= OUTPUT_FLOOR and not os.environ.get(OUTPUT_VARIABLE):
        return
    try:
        rows = max(0, data_lines(path) - 1)  # less the header
    except OSError:
        return
    check_output_estimate(rows * cells_per_row, [path, *extra_inputs], out)


def _cancel(json_writer, folder) -> None:
    """Stop the JSON writer, then remove the run's temporary folder, also when a second Ctrl-C cuts the wait."""
    try:
        if json_writer is not None:
            json_writer.cancel()
    finally:
        folder.abort()


#: a JSON document with more rows than this is written by a forked process while the tables are written
PARALLEL_JSON_ROWS = 20_000


def second_core_free(variable: str = "CAPRED_PROCESSES") -> bool:
    """True when a second process would run on a core of its own.

    Two cores or more, a load average that leaves one idle, not a batch's worker (the batch already uses the cores),
    fork available. The environment ``variable`` set to 1 or 2 decides instead.

    On a busy shared machine a forked helper's extra CPU (its copied pages, its own start) buys no time: measured on
    ``capred bridge solve`` of 100,000 rows with the other core busy, 1.30 s CPU and 1.10 s wall in two processes
    against 1.22 s and 1.02 s in one (benchmarks/bench_bridge_cli.py). The bridge solver and the JSON writer ask
    with CAPRED_PROCESSES, the figure sheets with CAPRED_FIGURE_PROCESSES.

    Parameters
    ----------
    variable : str, optional
        Environment variable that forces the answer ("1": one process, "2": two).

    Returns
    -------
    bool
        True when a second process is worth starting.
    """
    if os.name != "posix" or not hasattr(os, "fork"):
        return False
    forced = os.environ.get(variable)
    if forced in ("1", "2"):
        return forced == "2"
    mp = sys.modules.get("multiprocessing")  # a batch's worker has imported it; a plain run has not
    if mp is not None and mp.current_process().daemon:
        return False
    cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]  # this run itself counts for up to one
    except OSError:
        load = 0.0
    return cores >= 2 and load < cores - 0.5


class _JsonWriter:
    """Writes the JSON document to ``path``, at once or in a forked child.

    A long one, on a POSIX machine with two cores, is written in a forked child while the caller writes the other files;
    ``finish()`` waits and re-raises its failure.
    """

    def __init__(self, path, doc: dict) -> None:
        import os

        from ..spool import Rows

        self.path, self.doc, self.pid, self.thread, self.failed = path, doc, None, None, None
        self.stop = None  # set to stop the thread between two pieces (cancel)
        rows = [v for v in doc.values() if isinstance(v, Rows)]
        # rows whose JSON text their run wrote ahead (capred.pipelines.bridge_blocks) are only copied, file to
        # file in the kernel: a thread does it while the caller writes the other files (no process of its own)
        if rows and all(v.written_ahead for v in rows):
            import threading

            self.stop = threading.Event()
            self.thread = threading.Thread(target=self._write_caught, name="capred-json", daemon=True)
            self.thread.start()
            return
        long = sum(v.n for v in rows) > PARALLEL_JSON_ROWS
        if long and second_core_free():
            import gc

            gc.freeze()  # neither process's collections visit the objects they share (until finish or cancel)
            self.pid = os.fork()
            if self.pid == 0:  # the child: write, then leave without running the parent's clean-up
                code = 1
                try:
                    self._write()
                    code = 0
                finally:
                    os._exit(code)
        else:
            self._write()

    def _write(self) -> None:
        with open(self.path, "wb") as fh:
            if self.stop is None:
                stream_json(self.doc, fh.write)
                return

            def write(data) -> None:
                if self.stop.is_set():
                    raise Stopped
                write_piece(fh, data, self.stop)

            write.takes_file_text = True  # the text written ahead, copied by write_piece above
            stream_json(self.doc, write)

    def _write_caught(self) -> None:
        try:
            self._write()
        except BaseException as exc:  # raised again by finish(), in the caller's thread
            self.failed = exc

    def finish(self) -> None:
        import os

        if self.thread is not None:
            self.thread.join()
            self.thread = None
            if self.failed is not None:
                raise self.failed
            return
        if self.pid is None:
            return
        import gc

        try:
            _, status = os.waitpid(self.pid, 0)
        finally:
            self.pid = None
            gc.unfreeze()
        if status != 0:  # the child failed (disk full, ...): try once more here, where the error is raised
            self._write()

    def cancel(self) -> None:
        import os
        import signal

        if self.thread is not None:  # the copy stops at its next piece (at most _COPY_CHUNK bytes on)
            self.stop.set()
            self.thread.join()
            self.thread = None
        if self.pid is not None:
            import gc

            try:
                os.kill(self.pid, signal.SIGKILL)
                os.waitpid(self.pid, 0)
            except OSError:
                pass
            self.pid = None
            gc.unfreeze()


def provenance(result, outputs: list[str], command_line: str | None = None, hashes: dict | None = None) -> dict:
    """Record of a run: capred version, command line, input hashes, options, outputs.

    Parameters
    ----------
    result : capred.result.Result
        The run.
    outputs : list of str
        Names of the files written (provenance.json is added).
    command_line : str or None, optional
        The command line to record (default: ``sys.argv`` joined).
    hashes : dict, optional
        SHA-256 of each output, recorded as ``outputs_sha256``: the next run into the folder refuses to replace
        a file whose content changed since (:func:`edited_files`).

    Returns
    -------
    dict
        The provenance.json document (creation time in UTC).
    """
    from datetime import datetime

    doc = result.header()
    return {
        "capred_version": doc["capred_version"],
        "command": doc["command"],
        "command_line": command_line if command_line is not None else " ".join(sys.argv),
        "python": sys.version.split()[0],
        "inputs": doc["inputs"],
        "options": doc["options"],
        "option_units": doc["option_units"],
        "warnings": doc["warnings"],
        "outputs": sorted(outputs + ["provenance.json"]),
        **({"outputs_sha256": dict(sorted(hashes.items()))} if hashes is not None else {}),
        "created_utc": datetime.now(UTC).replace(microsecond=0).isoformat(),
    }


def write_batch_file(root, name: str, data: bytes, runs=None, command_line: str | None = None) -> Path:
    """Write one of a batch's root files (``BATCH_FILES``) into ``root`` and record it in provenance.json.

    Refuse (OutputError) where a file of that name exists that capred did not write.

    Parameters
    ----------
    root : str or Path
        The batch's root folder.
    name : str
        index.csv, season.csv or season.html.
    data : bytes
        The file's content.
    runs : list of str, optional
        The run folders of the batch (recorded in provenance.json).
    command_line : str, optional
        Recorded in provenance.json (default: this process's argv).

    Returns
    -------
    Path
        The file written.
    """
    import hashlib

    root = Path(os.path.abspath(root))
    try:
        root.mkdir(parents=True, exist_ok=True)
        with _locked(root):
            foreign = [f for f in foreign_batch_files(root) if f in (name, "provenance.json")]
            if foreign:
                raise OutputError(
                    f"{root / foreign[0]} exists and capred did not write it; a batch never writes "
                    "over a file it did not write (a manifest?): move it or choose another --out"
                )
            record = batch_record(root)
            new = hashlib.sha256(data).hexdigest()
            current = _sha256(root / name) if (root / name).is_file() else None
            old = [h for h in record.get(name, []) if h == current]
            record[name] = [*old, new] if new not in old else [new]
            _write_batch_provenance(root, record, runs, command_line)  # both hashes while the file changes
            atomic_write_bytes(root / name, data)
            record[name] = [new]
            _write_batch_provenance(root, record, runs, command_line)
    except OSError as exc:
        raise _os_error(root, exc) from None
    return root / name


def _write_batch_provenance(root: Path, record: dict, runs, command_line) -> None:
    from datetime import datetime

    from .. import __version__

    before = _provenance(root) or {}
    if runs is None:
        runs = before.get("runs", [])
    doc = {
        "capred_version": __version__,
        "command": "batch",
        "command_line": command_line if command_line is not None else " ".join(sys.argv),
        "python": sys.version.split()[0],
        "outputs": sorted([*record, "provenance.json"]),
        "runs": sorted(runs),
        "batch_files": {k: record[k] for k in sorted(record)},
        "created_utc": datetime.now(UTC).replace(microsecond=0).isoformat(),
    }
    atomic_write_bytes(root / "provenance.json", encode_json(doc, True))


def atomic_write_bytes(path: Path, data: bytes) -> Path:
    """One file written under a temporary name and renamed into place (used for a batch's index.csv).

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (its folder is created when absent).
    data : bytes
        The whole content.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    except OSError as exc:
        raise _os_error(path.parent, exc) from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, 0o666 & ~_UMASK)
        os.replace(tmp, path)
    except OSError as exc:
        Path(tmp).unlink(missing_ok=True)
        raise _os_error(path.parent, exc) from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
