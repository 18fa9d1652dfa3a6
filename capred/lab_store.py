"""A lab's history: every run recorded in one SQLite file, queried per material and quantity.

``capred <command> --store lab.sqlite`` (or the environment variable
``CAPRED_STORE``) records each run whose files are written: its provenance
(inputs' SHA-256, options, capred version, date, the inputs' metadata block),
its JSON document, and a long table ``records(run, material, quantity, value,
ci_low, ci_high, unit)`` for querying. ``capred history lab.sqlite --material
M --quantity Q`` draws the individuals and moving-range chart of the quantity
(capred.pipelines.history); :func:`history` gives the records as a DataFrame.

The file is protected like a user's data:

- it is recognised by its SQLite header, ``PRAGMA application_id`` and
  ``PRAGMA user_version`` (the schema version) before anything is written: a
  file that is not SQLite, another application's database, a damaged file or
  one written by a newer capred is a clear :class:`~capred.errors.InputError`
  and is never modified;
- an older schema is migrated in one transaction (:data:`MIGRATIONS`);
- each run is one ``BEGIN IMMEDIATE`` transaction, in WAL mode with a busy
  timeout, so that a batch's workers may record at the same time;
- a run recorded twice (same command, inputs' SHA-256 and options) is stored once, and the second run's
  notes say so (:func:`recorded_as`); a run that writes no files is not recorded, and says so.

References
----------
ISO/IEC 17025:2017, clause 7.7 (ensuring the validity of results: control charts).
SQLite, "Write-Ahead Logging", https://www.sqlite.org/wal.html.
"""

from __future__ import annotations

import errno
import functools
import hashlib
import json
import os
import sqlite3
from pathlib import Path

from .errors import InputError, Problem

#: identifies a capred store (PRAGMA application_id): "CAPR" in ASCII
APPLICATION_ID = 0x43415052
#: the environment variable that names the store once for every command
STORE_VARIABLE = "CAPRED_STORE"
#: seconds a writer waits for another's transaction before giving up
BUSY_TIMEOUT_S = 60.0

#: schema migrations: MIGRATIONS[k] takes a store from version k to k + 1 (version 0: an empty file)
MIGRATIONS: tuple[tuple[str, ...], ...] = (
    (  # 0 -> 1: runs and their long records
        """CREATE TABLE runs (
            id INTEGER PRIMARY KEY,
            run_key TEXT NOT NULL UNIQUE,
            command TEXT NOT NULL,
            created_utc TEXT NOT NULL,
            capred_version TEXT NOT NULL,
            inputs TEXT NOT NULL,
            options TEXT NOT NULL,
            metadata TEXT NOT NULL,
            out_dir TEXT,
            document TEXT NOT NULL
        )""",
        """CREATE TABLE records (
            run INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
            material TEXT,
            quantity TEXT NOT NULL,
            value REAL,
            ci_low REAL,
            ci_high REAL,
            unit TEXT
        )""",
    ),
    (  # 1 -> 2: the test date from the metadata block, and an index for the history query
        "ALTER TABLE runs ADD COLUMN test_date TEXT",
        "UPDATE runs SET test_date = COALESCE("
        "json_extract(metadata, '$.date'), json_extract(metadata, '$.test_date'), substr(created_utc, 1, 10))",
        "CREATE INDEX records_material_quantity ON records(material, quantity)",
    ),
)
SCHEMA_VERSION = len(MIGRATIONS)

_DATE_KEYS = ("date", "test_date", "test date", "test start", "test_start")


def _problem(path, message: str) -> InputError:
    return InputError(Problem(str(path), None, None, message))


def _kind(path: Path) -> str | None:
    """None where ``path`` is absent or a regular file (after links); else why it cannot be a store.

    Nothing is opened: a FIFO or a device as the store is refused by its ``stat`` alone (opening a FIFO for
    reading waits for a writer forever).
    """
    import stat

    try:
        st = os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):
            return f"is a symbolic link to {os.readlink(path)}, which does not exist"
        return None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return "is a symbolic link that loops (it points back at itself)"
        return f"cannot be examined ({exc.strerror or exc})"
    if stat.S_ISDIR(st.st_mode):
        return "is a folder, not a capred store (give a file such as lab.sqlite)"
    if not stat.S_ISREG(st.st_mode):
        what = "a FIFO (named pipe)" if stat.S_ISFIFO(st.st_mode) else "a device or socket"
        return f"is {what}, not a file: a capred store is a SQLite file; it was not opened"
    return None


def _has_frames(wal: Path) -> bool:
    """Whether the write-ahead log ``wal`` holds frames (False where it is absent or vanishes meanwhile).

    Another writer's last connection deletes its log when it closes, at any moment: the log is examined in one
    ``stat``, never as "exists, then its size".
    """
    try:
        return wal.stat().st_size > 0
    except FileNotFoundError:
        return False


def _header_pages(head: bytes, size: int) -> str | None:
    """Why the 100-byte SQLite header ``head`` does not fit a file of ``size`` bytes, or None.

    The header's page size (offset 16) and page count (offset 28, valid while the change counter at 24 equals
    the one at 92) give the file's length: a truncated or padded file is seen here without reading its pages.
    References: SQLite, "Database File Format", section 1.3, https://www.sqlite.org/fileformat.html.
    """
    raw = int.from_bytes(head[16:18], "big")
    page = 65536 if raw == 1 else raw
    if page < 512 or page > 65536 or page & (page - 1):
        return f"its header gives a page size of {raw} bytes"
    count = int.from_bytes(head[28:32], "big")
    if count and head[24:28] == head[92:96] and count * page > size:
        return f"its header counts {count} pages of {page} bytes but the file holds {size} bytes (truncated?)"
    return None


def _inspect(path: Path) -> tuple[int, int] | None:
    """(application_id, user_version) of an existing file, read-only; None for a new (absent or empty) store.

    Raises InputError for a path that is not a regular file (a FIFO, a device, a dangling or looping link), a
    file that is not a SQLite database, is damaged or belongs to another application.

    The file is not scanned whole (no ``PRAGMA quick_check``, whose cost grows with every run recorded): the
    header, the schema and the pages a run reads or writes are checked, SQLite verifying each page it reads.
    """
    why = _kind(path)
    if why is not None:
        raise _problem(path, why)
    if not path.exists():
        return None
    _side_files(path)  # before any connection, which would open (or create) them
    with open(path, "rb") as fh:
        head = fh.read(100)
    if not head:
        return None  # an empty file: another writer is creating the store, or `touch lab.sqlite`
    if not head.startswith(b"SQLite format 3\x00"):
        raise _problem(path, "is not a SQLite database, so not a capred store; it was left untouched")
    wal = Path(f"{path}-wal")
    # with a write-ahead log holding frames the file's header may run ahead of its pages (a checkpoint in
    # progress writes page 1 first): the header's page count is then SQLite's to reconcile, not checked here
    if len(head) < 100:
        bad = "its header is cut short"
    elif _has_frames(wal):
        bad = None
    else:
        bad = _header_pages(head, path.stat().st_size)
    if bad is not None:
        raise _problem(path, f"is a damaged SQLite file ({bad}); it was left untouched")
    try:
        con = sqlite3.connect(_readonly_uri(path), uri=True, timeout=BUSY_TIMEOUT_S)
        try:
            app = con.execute("PRAGMA application_id").fetchone()[0]
            version = con.execute("PRAGMA user_version").fetchone()[0]
            tables = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
        finally:
            con.close()
    except sqlite3.DatabaseError as exc:
        raise _problem(path, f"is a damaged SQLite file ({exc}); it was left untouched") from None
    if app == 0 and version == 0 and not tables:
        return None  # an empty database
    if app != APPLICATION_ID:
        raise _problem(
            path,
            f"is another application's SQLite database (tables: {', '.join(tables[:5]) or 'none'}), not a "
            "capred store; it was left untouched",
        )
    if version > SCHEMA_VERSION:
        raise _problem(
            path,
            f"was written by a newer capred (schema {version}; this capred reads up to {SCHEMA_VERSION}); "
            "it was left untouched",
        )
    return app, version


#: the columns of each table at SCHEMA_VERSION, in order (what :func:`verify_schema` expects)
COLUMNS = {
    "runs": (
        "id",
        "run_key",
        "command",
        "created_utc",
        "capred_version",
        "inputs",
        "options",
        "metadata",
        "out_dir",
        "document",
        "test_date",
    ),
    "records": ("run", "material", "quantity", "value", "ci_low", "ci_high", "unit"),
}


def verify_schema(con: sqlite3.Connection, path) -> None:
    """Raise InputError unless the store's schema is the one this capred writes.

    Its version, each table with its columns (:data:`COLUMNS`), and no trigger (capred creates none: a trigger would run
    another program's statements on every run recorded).

    Parameters
    ----------
    con : sqlite3.Connection
        An open connection to the store.
    path : str or Path
        The store's file (for the message).
    """
    version = con.execute("PRAGMA user_version").fetchone()[0]
    if version != SCHEMA_VERSION:
        raise _problem(
            path,
            f"says schema version {version} but this capred writes schema {SCHEMA_VERSION}; it was left untouched",
        )
    for table, cols in COLUMNS.items():
        have = tuple(r[1] for r in con.execute(f"PRAGMA table_info({table})"))
        if not have:
            raise _problem(path, f"has no table '{table}' (was it dropped?); it was left untouched")
        missing = [c for c in cols if c not in have]
        if missing:
            raise _problem(
                path,
                f"has lost the column{'s' if len(missing) > 1 else ''} {', '.join(missing)} of table '{table}' "
                "(altered by another program?); it was left untouched",
            )
    triggers = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type = 'trigger' LIMIT 5")]
    if triggers:
        raise _problem(
            path,
            f"holds triggers capred did not create ({', '.join(triggers)}): they would run on every run "
            "recorded; it was left untouched",
        )


def connect(path, create: bool = True) -> sqlite3.Connection:
    """An open connection to the store at ``path``, created or migrated to :data:`SCHEMA_VERSION` as needed.

    Parameters
    ----------
    path : str or Path
        The store's file (e.g. ``lab.sqlite``).
    create : bool
        Create the store where there is none (recording); False: a missing store is an error (querying).

    Returns
    -------
    sqlite3.Connection
        In WAL mode, with a busy timeout of :data:`BUSY_TIMEOUT_S` and foreign keys on.

    Raises
    ------
    InputError
        The file is not a capred store, is damaged or newer (it is never modified), or is missing and
        ``create`` is False.
    """
    path = Path(path)
    state = _inspect(path)
    if state is None and not create:
        raise _problem(path, "no capred store here (record runs into it with --store or CAPRED_STORE)")
    if state is None and not path.parent.exists():
        raise _problem(path, f"the folder {path.parent} does not exist")
    con = sqlite3.connect(str(path), timeout=BUSY_TIMEOUT_S, isolation_level=None)
    try:
        con.execute(f"PRAGMA busy_timeout = {int(BUSY_TIMEOUT_S * 1000)}")
        if state is None or state[1] < SCHEMA_VERSION:
            _migrate(con, path)
        con.execute("PRAGMA journal_mode = WAL")
        con.execute("PRAGMA foreign_keys = ON")
    except sqlite3.DatabaseError as exc:
        con.close()
        raise _problem(path, f"cannot be opened as a capred store ({exc})") from None
    return con


def _readonly_uri(path: Path) -> str:
    """The URI that opens ``path`` for reading only, so that SQLite leaves no side file.

    ``mode=rw`` where the file and its folder can be written (the connection is then made ``query_only``), else
    ``mode=ro&immutable=1`` (a store shipped inside an installed package).

    A ``mode=ro`` connection to a store in WAL mode (every store capred records into) creates ``-wal`` and
    ``-shm`` beside it and, being read-only, cannot remove them when it closes: every ``capred history`` left
    two files behind. A read-write connection that only queries removes them as the last one to close.
    """
    from urllib.parse import quote

    uri = f"file:{quote(str(path.resolve()))}"
    if os.access(path, os.W_OK) and os.access(path.parent, os.W_OK):
        return uri + "?mode=rw"
    return uri + "?mode=ro&immutable=1"


def connect_readonly(path) -> sqlite3.Connection:
    """A read-only connection to the store at ``path`` (querying): nothing in the file is ever changed.

    A store of an older schema is copied into memory and migrated there, so that it reads like a current one
    while the file keeps its schema (the next run recorded into it migrates it in place).

    Parameters
    ----------
    path : str or Path
        The store's file (e.g. ``lab.sqlite``, or the bundled sample store).

    Returns
    -------
    sqlite3.Connection
        Query-only (``PRAGMA query_only``; ``mode=ro`` where the store cannot be written), or an in-memory
        copy at :data:`SCHEMA_VERSION`.

    Raises
    ------
    InputError
        No store at ``path``, or a file that is not a capred store, is damaged or newer.

    References
    ----------
    SQLite, "Uniform Resource Identifiers" (``mode=ro``, ``immutable``), https://www.sqlite.org/uri.html.
    """
    path = Path(path)
    state = _inspect(path)
    if state is None:
        raise _problem(path, "no capred store here (record runs into it with --store or CAPRED_STORE)")
    con = None
    try:
        con = sqlite3.connect(_readonly_uri(path), uri=True, timeout=BUSY_TIMEOUT_S, isolation_level=None)
        con.execute("PRAGMA query_only = ON")  # no statement of this connection can change the store
        con.execute(f"PRAGMA busy_timeout = {int(BUSY_TIMEOUT_S * 1000)}")
        if state[1] < SCHEMA_VERSION:
            memory = sqlite3.connect(":memory:", isolation_level=None)
            con.backup(memory)
            con.close()
            con = memory
            _migrate(con, path)
    except sqlite3.DatabaseError as exc:
        if con is not None:
            con.close()
        raise _problem(path, f"cannot be read as a capred store ({exc}); it was left untouched") from None
    return con


def _migrate(con: sqlite3.Connection, path: Path) -> None:
    """Bring the store to SCHEMA_VERSION in one transaction (another writer may have done it meanwhile)."""
    con.execute("BEGIN IMMEDIATE")
    try:
        _migrate_within(con, path)
        con.execute("COMMIT")
    except BaseException:
        con.execute("ROLLBACK")
        raise


def _migrate_within(con: sqlite3.Connection, path: Path) -> None:
    """The migration's statements, inside the caller's transaction (SQLite's schema changes are transactional)."""
    app = con.execute("PRAGMA application_id").fetchone()[0]
    version = con.execute("PRAGMA user_version").fetchone()[0]
    tables = con.execute("SELECT count(*) FROM sqlite_master WHERE type = 'table'").fetchone()[0]
    if app != APPLICATION_ID and (app != 0 or version != 0 or tables):
        raise _problem(path, "is not a capred store; it was left untouched")
    if version > SCHEMA_VERSION:
        raise _problem(path, f"was written by a newer capred (schema {version}); it was left untouched")
    if app == APPLICATION_ID and version == SCHEMA_VERSION:
        return
    try:
        for step in MIGRATIONS[version:]:
            for sql in step:
                con.execute(sql)
    except sqlite3.OperationalError as exc:
        raise _problem(
            path,
            f"says schema version {version} but its tables do not match that version ({exc}); it was left untouched",
        ) from None
    con.execute(f"PRAGMA application_id = {APPLICATION_ID}")
    con.execute(f"PRAGMA user_version = {SCHEMA_VERSION}")


# --- what a run records ---------------------------------------------------------------------------------------
@functools.cache
def declared_units() -> dict[str, tuple[str, str]]:
    """JSON key -> (quantity, unit) of every number a run's document names by a declared quantity.

    From the declarations, never from a key's spelling: each glossary quantity (capred/nomenclature.py) gives
    its JSON key, the name with its unit (:func:`capred.nomenclature.json_key`, ``phi_deg``, ``c_kPa``; the name
    alone for a dimensionless one), and the key of its standard error (``c_se_kPa``); each retention parameter
    its JSON name (capred.fitting.retention_models.JSON_NAMES and ``json_name``: ``alpha_per_kPa`` in 1/kPa,
    ``S_s`` and ``S_res`` dimensionless, ``theta_s`` in m³/m³).

    Returns
    -------
    dict
        Key -> (the quantity's name, its unit; "-" when dimensionless).
    """
    from .fitting.retention_models import JSON_NAMES, json_name
    from .nomenclature import QUANTITIES, json_key

    out: dict[str, tuple[str, str]] = {}
    for name, q in QUANTITIES.items():
        unit = q.unit if q.unit not in ("", "-") else "-"
        out[json_key(name)] = out[json_key(name, "_se")] = (name, unit)
    retention = [json_name(y, quantity) for y in ("y_r", "y_s") for quantity in ("theta", "S_R", "w")]
    for key, _, unit in list(JSON_NAMES.values()) + retention:
        out[key] = (key, unit)
    return out


def rows_of(result, metadata: dict | None = None) -> list[tuple]:
    """The long records ``(material, quantity, value, ci_low, ci_high, unit)`` of a run.

    From the result's records through their declarations (``result.store_rows(material)``: the JSON key, value,
    95 % interval and unit of one declaration each; capred.records.StoreRow), never from the JSON read back;
    the material is the one the inputs' metadata block names (``material``), or none.

    Parameters
    ----------
    result : capred.result.Result
        Any command's result.
    metadata : dict, optional
        The inputs' metadata block.

    Returns
    -------
    list of tuple

    Raises
    ------
    ValueError
        The result declares no rows (``store_rows`` returns None: a command that has not declared them).
    """
    meta = metadata or {}
    material = next((str(v) for k, v in meta.items() if str(k).strip().lower() == "material"), None)
    declared = getattr(result, "store_rows", None)
    rows = None if declared is None else declared(material)
    if rows is None:
        raise ValueError(
            f"`capred {getattr(result, 'command', '?')}` declares no lab-store rows (Result.store_rows): its run cannot be recorded"
        )
    return [tuple(r) for r in rows]


def run_key(doc: dict) -> str:
    """SHA-256 of what makes a run the same run: the command, the inputs' SHA-256 (and sheet) and the options.

    Parameters
    ----------
    doc : dict
        A run's provenance document (``command``, ``inputs`` with ``sha256`` and ``sheet``, ``options``).

    Returns
    -------
    str
        Hex digest.
    """
    ident = {
        "command": doc.get("command"),
        "inputs": [(i.get("sha256"), i.get("sheet")) for i in doc.get("inputs", [])],
        "options": doc.get("options"),
    }
    return hashlib.sha256(json.dumps(ident, sort_keys=True, default=str).encode()).hexdigest()


def _metadata(doc: dict) -> dict:
    meta: dict = {}
    for i in doc.get("inputs", []):
        meta.update(i.get("metadata") or {})
    return meta


def _test_date(meta: dict, created: str) -> str:
    for k, v in meta.items():
        if str(k).strip().lower() in _DATE_KEYS and str(v).strip():
            return str(v).strip()
    return created[:10]


def _side_files(path: Path) -> None:
    """Refuse a store whose journal side files (``-wal``, ``-shm``, ``-journal``) are not regular files."""
    for side in ("-wal", "-shm", "-journal"):
        why = _kind(Path(f"{path}{side}"))
        if why is not None:
            raise _problem(path, f"cannot be written: its side file {path.name}{side} {why}; nothing was written")


def _unwritable(path: Path, exc: BaseException) -> InputError:
    return _problem(
        path,
        f"cannot be written ({exc}): is the file or its folder read-only, immutable, on a read-only file system, "
        "or damaged? nothing was written",
    )


class Recorder:
    """A store opened for recording one run, checked before the run's folder is written.

    ``Recorder(store)`` refuses, with nothing written anywhere, a store that cannot take the run: a FIFO or
    device (refused by ``stat``, never opened), a dangling or looping link, side files that are not files,
    a foreign, damaged or newer file, a schema that lost a table or column or carries triggers, and a file or
    folder that cannot be written (the write lock is taken and the schema migrated inside a transaction that
    is rolled back). :meth:`record` is then called once the run's folder is in place
    (:meth:`capred.io.writers.RunFolder.commit`), and a failure there puts the earlier folder back: the store
    never holds a run without its folder, nor a folder its run.

    Parameters
    ----------
    store : str or Path
        The store's file (created by :meth:`record` where absent).

    Raises
    ------
    InputError
        The store cannot take the run (one clear message; nothing written).
    """

    def __init__(self, store):
        self.path = path = Path(store)
        state = _inspect(path)
        self.con = None
        if state is None:  # a new store: its folder must take a file (created when the run is recorded)
            folder = path.parent
            if not folder.is_dir():
                raise _problem(path, f"the folder {folder} does not exist")
            try:
                import tempfile

                fd, probe = tempfile.mkstemp(prefix=f".{path.name[:60]}.probe-", dir=folder)
                os.close(fd)
                os.unlink(probe)
            except OSError as exc:
                raise _problem(path, f"cannot be created in {folder} ({exc.strerror or exc}); nothing was written")
            return
        try:
            self.con = sqlite3.connect(str(path), timeout=BUSY_TIMEOUT_S, isolation_level=None)
            self.con.execute(f"PRAGMA busy_timeout = {int(BUSY_TIMEOUT_S * 1000)}")
            self.con.execute("BEGIN IMMEDIATE")  # the write lock: fails on a store that cannot be written
            try:
                _migrate_within(self.con, path)
                verify_schema(self.con, path)
                self.con.execute(f"PRAGMA user_version = {SCHEMA_VERSION}")  # a write, rolled back
            finally:
                self.con.execute("ROLLBACK")
        except sqlite3.Error as exc:
            self.close()
            raise _unwritable(path, exc) from None
        finally:  # no connection is held while the run draws (its figures may be drawn by a forked process)
            self.close()

    def close(self) -> None:
        """Close the store's connection (nothing pending)."""
        if self.con is not None:
            self.con.close()
            self.con = None

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def record(self, result, out_dir=None) -> tuple[int, bool]:
        """Record the run in one transaction (see :func:`record_run`).

        Parameters
        ----------
        result : capred.result.Result
            Any command's result.
        out_dir : str or Path, optional
            The folder its files were written to (recorded).

        Returns
        -------
        (int, bool)
            The run's id and whether it was new.
        """
        from datetime import UTC, datetime

        from .io import encode_json

        # the document the run wrote (NaN as null), kept whole in the runs table with its provenance
        doc = json.loads(encode_json(result.to_json()).decode("utf-8"))
        key = run_key(doc)
        meta = _metadata(doc)
        rows = rows_of(result, meta)
        created = datetime.now(UTC).replace(microsecond=0).isoformat()
        path = self.path
        try:
            if self.con is None:
                why = _kind(path)  # again: the path may have changed while the run was drawn
                if why is not None:
                    raise _problem(path, why)
                _side_files(path)
                self.con = sqlite3.connect(str(path), timeout=BUSY_TIMEOUT_S, isolation_level=None)
                self.con.execute(f"PRAGMA busy_timeout = {int(BUSY_TIMEOUT_S * 1000)}")
            con = self.con
            if con.execute("PRAGMA journal_mode").fetchone()[0] != "wal":
                con.execute("PRAGMA journal_mode = WAL")
            con.execute("PRAGMA foreign_keys = ON")
            con.execute("BEGIN IMMEDIATE")
            try:
                _migrate_within(con, path)
                verify_schema(con, path)
                row = con.execute("SELECT id FROM runs WHERE run_key = ?", (key,)).fetchone()
                if row is not None:
                    con.execute("COMMIT")
                    return int(row[0]), False
                _check_tail(con, path)
                cur = con.execute(
                    "INSERT INTO runs (run_key, command, created_utc, capred_version, inputs, options, metadata, "
                    "out_dir, document, test_date) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                    (
                        key,
                        doc.get("command", ""),
                        created,
                        doc.get("capred_version", ""),
                        json.dumps(doc.get("inputs", [])),
                        json.dumps(doc.get("options", {})),
                        json.dumps(meta),
                        None if out_dir is None else os.path.abspath(out_dir),
                        json.dumps(doc),
                        _test_date(meta, created),
                    ),
                )
                run = cur.lastrowid
                con.executemany(
                    "INSERT INTO records (run, material, quantity, value, ci_low, ci_high, unit) "
                    "VALUES (?,?,?,?,?,?,?)",
                    [(run, *r) for r in rows],
                )
                con.execute("COMMIT")
                return int(run), True
            except BaseException:
                if con.in_transaction:
                    con.execute("ROLLBACK")
                raise
        except sqlite3.Error as exc:
            raise _unwritable(path, exc) from None


def _check_tail(con: sqlite3.Connection, path: Path) -> None:
    """The pages a new run is appended next to hold the last run whole: its row reads back as UTF-8 JSON.

    A damaged page elsewhere is found by SQLite when it is read (``database disk image is malformed``); this
    catches damage in the text of the last run, which SQLite does not checksum. The cost is one run's row, not
    the whole file.
    """
    try:
        row = con.execute(
            "SELECT id, json_valid(document), json_valid(inputs), CAST(document AS BLOB) FROM runs "
            "WHERE id = (SELECT max(id) FROM runs)"
        ).fetchone()
    except sqlite3.DatabaseError as exc:
        raise _problem(path, f"is a damaged capred store ({exc}); nothing was appended to it") from None
    if row is None:
        return
    ok = bool(row[1]) and bool(row[2])
    try:
        row[3].decode("utf-8")
    except UnicodeDecodeError:
        ok = False
    if not ok:
        raise _problem(
            path, f"is a damaged capred store (the record of run {row[0]} is not intact); nothing was appended to it"
        )


def check_store(store) -> None:
    """Raise InputError where ``store`` cannot take a run (see :class:`Recorder`; nothing changes).

    Parameters
    ----------
    store : str or Path
        The store's file.
    """
    Recorder(store).close()


def record_run(store, result, out_dir=None) -> tuple[int, bool]:
    """Record one run in the store: provenance, JSON document and long records, in one transaction.

    Parameters
    ----------
    store : str or Path
        The store's file; created where absent.
    result : capred.result.Result
        Any command's result.
    out_dir : str or Path, optional
        The folder its files were written to (recorded).

    Returns
    -------
    (int, bool)
        The run's id and whether it was new (False: the same run was already recorded; nothing changed).

    Raises
    ------
    InputError
        The store cannot take the run (see :class:`Recorder`; never modified).
    """
    with Recorder(store) as rec:
        return rec.record(result, out_dir)


def store_from(store=None):
    """The store to record into: ``store`` if given, else ``$CAPRED_STORE``, else None (nothing recorded).

    Parameters
    ----------
    store : str or Path, optional
        The store given by option.

    Returns
    -------
    str or Path or None
    """
    if store is not None:
        return store
    return os.environ.get(STORE_VARIABLE) or None


def history(store, material: str | None = None, quantity: str | None = None, command: str | None = None):
    """The records of a store as a DataFrame, one row per (run, material, quantity), oldest run first.

    Parameters
    ----------
    store : str or Path
        The store's file (``--store`` of the commands).
    material, quantity, command : str, optional
        Keep only this material, quantity (a JSON key such as ``phi_deg``) or command.

    Returns
    -------
    pandas.DataFrame
        Columns ``run, test_date, created_utc, command, input, sha256, material, quantity, value, ci_low,
        ci_high, unit, out_dir``.

    Raises
    ------
    InputError
        No store at ``store``, or a file that is not a capred store (never modified).

    Notes
    -----
    The store is opened read-only (:func:`connect_readonly`): a query never changes it, not even its schema.

    References
    ----------
    ISO/IEC 17025:2017, clause 7.7.
    """
    import pandas as pd

    cols = [
        "run",
        "test_date",
        "created_utc",
        "command",
        "input",
        "sha256",
        "material",
        "quantity",
        "value",
        "ci_low",
        "ci_high",
        "unit",
        "out_dir",
    ]
    where, args = _where(material, quantity, command)
    sql = (
        "SELECT u.id, u.test_date, u.created_utc, u.command, json_extract(u.inputs, '$[0].path'), "
        "json_extract(u.inputs, '$[0].sha256'), r.material, r.quantity, r.value, r.ci_low, r.ci_high, r.unit, "
        "u.out_dir FROM records r JOIN runs u ON u.id = r.run" + where + " ORDER BY u.id, r.rowid"
    )
    rows = _query(store, sql, args)
    frame = pd.DataFrame(rows, columns=cols)
    for c in ("value", "ci_low", "ci_high"):
        frame[c] = frame[c].astype(float)
    return frame


def _where(material=None, quantity=None, command=None) -> tuple[str, list]:
    where, args = [], []
    for col, val in (("r.material", material), ("r.quantity", quantity), ("u.command", command)):
        if val is not None:
            where.append(f"{col} = ?")
            args.append(val)
    return (" WHERE " + " AND ".join(where) if where else ""), args


class _NotText(ValueError):
    """A text value of the store that is not UTF-8 (a damaged page)."""


def _text(raw: bytes) -> str:
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _NotText(f"a text value is not UTF-8 (byte 0x{raw[exc.start]:02x} at position {exc.start})") from None


def _query(store, sql: str, args=()) -> list:
    """Rows of one query on the store opened read-only; a damaged page or text is a clear InputError."""
    con = connect_readonly(store)
    con.text_factory = _text
    try:
        return con.execute(sql, args).fetchall()
    except (sqlite3.DatabaseError, _NotText) as exc:
        raise _problem(store, f"is a damaged capred store ({exc}); it was left untouched") from None
    finally:
        con.close()


def present(store, column: str, quantity=None, command=None, limit: int | None = 41) -> list[str]:
    """The distinct materials or quantities the store holds (for a quantity, a command), sorted, at most ``limit``.

    Parameters
    ----------
    store : str or Path
        The store's file.
    column : {"material", "quantity"}
        Which values.
    quantity, command : str, optional
        Only the records of this quantity, of runs of this command.
    limit : int or None
        At most this many values (the query stops there); None: all of them.

    Returns
    -------
    list of str
    """
    if column not in ("material", "quantity"):
        raise ValueError(column)
    where, args = _where(None, quantity, command)
    join = " JOIN runs u ON u.id = r.run" if command is not None else ""
    sql = (
        f"SELECT DISTINCT r.{column} FROM records r{join}{where}"
        + (" AND" if where else " WHERE")
        + f" r.{column} IS NOT NULL ORDER BY r.{column}"
        + ("" if limit is None else f" LIMIT {int(limit)}")
    )
    return [str(r[0]) for r in _query(store, sql, args)]


def count_present(store, column: str, quantity=None, command=None) -> int:
    """How many distinct materials or quantities the store holds (filtered as in :func:`present`).

    Parameters
    ----------
    store : str or Path
        The store's file.
    column : {"material", "quantity"}
        Which values.
    quantity, command : str, optional
        Only the records of this quantity, of runs of this command.

    Returns
    -------
    int
    """
    if column not in ("material", "quantity"):
        raise ValueError(column)
    where, args = _where(None, quantity, command)
    join = " JOIN runs u ON u.id = r.run" if command is not None else ""
    sql = f"SELECT COUNT(DISTINCT r.{column}) FROM records r{join}{where}"
    return int(_query(store, sql, args)[0][0])


def commands_present(store) -> list[str]:
    """The commands whose runs the store holds, sorted.

    Parameters
    ----------
    store : str or Path
        The store's file.

    Returns
    -------
    list of str
    """
    return [str(r[0]) for r in _query(store, "SELECT DISTINCT command FROM runs ORDER BY command")]


def recorded_as(store, result) -> int | None:
    """The id of the run of the store that is ``result``'s run, or None.

    The same run: the same command, inputs' SHA-256 and options (:func:`run_key`). None where the store holds
    none (or there is no store yet). The store is only read.

    Parameters
    ----------
    store : str or Path
        The store's file.
    result : capred.result.Result
        Any command's result.

    Returns
    -------
    int or None
    """
    from .io import encode_json

    if _inspect(Path(store)) is None:
        return None
    # the run's identity is in the document's header (command, inputs, options): the payload is not built
    doc = json.loads(encode_json(result.header()).decode("utf-8"))
    row = _query(store, "SELECT id FROM runs WHERE run_key = ?", (run_key(doc),))
    return int(row[0][0]) if row else None
