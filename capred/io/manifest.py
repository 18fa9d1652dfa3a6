"""Read a batch manifest: one run per line (CSV) or per [[run]] table (TOML).

A CSV manifest has a header naming ``command`` and ``input`` (and
``options``); lines starting with '#' and blank lines are skipped. A TOML
manifest holds ``[[run]]`` tables with ``command``, ``input`` (strings) and
``options`` (a string as typed on the command line, or a list of arguments).
Either is UTF-8 (with or without BOM), UTF-16 or Windows-1252 (as data
files). Every problem of a manifest (a short row, a wrong type, no runs) is
collected and raised once as an InputError naming the file, line and column.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import InputError, Problem

#: a manifest lists runs, a few to a few thousand; a larger file is not a manifest
MAX_MANIFEST_BYTES = 16 * 2**20


def read_manifest(path: Path) -> list[tuple[int, str, str, list[str] | str]]:
    """(line, command, input, options) per run, from a CSV or TOML manifest.

    Options are a string as typed on the command line (CSV, or a TOML string)
    or a list of arguments (a TOML list). Raises InputError (every problem of
    the file, each with its line and column) when a run cannot be read or the
    manifest holds no run.

    Parameters
    ----------
    path : str or pathlib.Path
        The manifest, a ``.csv`` or ``.toml`` file.

    Returns
    -------
    list of tuple
        ``(line, command, input, options)`` of each run, in the manifest's order.
    """
    path = Path(path)
    if not path.exists():
        from ..errors import MissingFileError

        raise MissingFileError(str(path))
    shown = str(path)
    if not path.is_file():
        raise InputError(Problem(shown, None, None, "not a file"))
    size = path.stat().st_size
    if size > MAX_MANIFEST_BYTES:
        raise InputError(
            Problem(
                shown,
                None,
                None,
                f"{size / 2**20:.1f} MiB is not a manifest (one run per line; at "
                f"most {MAX_MANIFEST_BYTES // 2**20} MiB are read)",
            )
        )
    data = path.read_bytes()
    if b"\x00" in data[:4096] and data[:2] not in (b"\xff\xfe", b"\xfe\xff"):
        raise InputError(Problem(shown, None, None, "this is a binary file, not a CSV or TOML manifest"))
    from .grid import decode_text

    text = decode_text(data)
    runs = _toml_runs(shown, text) if path.suffix.lower() == ".toml" else _csv_runs(shown, text)
    if not runs:
        raise InputError(
            Problem(
                shown,
                None,
                None,
                "the manifest lists no runs (CSV: a line per run under the "
                "header command,input,options; TOML: [[run]] tables)",
            )
        )
    return runs


def _csv_runs(shown: str, text: str) -> list[tuple[int, str, str, str]]:
    import csv
    import io

    reader = csv.reader(io.StringIO(text))
    rows, start = [], 1
    try:
        for row in reader:
            if row and not row[0].lstrip().startswith("#") and any(c.strip() for c in row):
                rows.append((start, row))
            start = reader.line_num + 1
    except csv.Error as exc:
        raise InputError(Problem(shown, start, None, f"{exc} (a quote is not closed?)")) from None
    if not rows:
        raise InputError(Problem(shown, None, None, "the manifest is empty"))
    header_line, header_cells = rows[0]
    header = [h.strip().lower() for h in header_cells]
    if "command" not in header or "input" not in header:
        raise InputError(Problem(shown, header_line, None, "the header needs 'command' and 'input' (and 'options')"))
    from .table import edits_within

    for h in header:
        near = [w for w in ("command", "input", "options") if h != w and edits_within(h, w, 2)]
        if near and near[0] not in header:
            raise InputError(
                Problem(
                    shown,
                    header_line,
                    h,
                    f"the header has '{h}': did you mean '{near[0]}'? (the columns are command, input and options)",
                )
            )
    ci, ii = header.index("command"), header.index("input")
    oi = header.index("options") if "options" in header else None
    width = len(header)
    problems, runs = [], []
    for n, r in rows[1:]:
        if len(r) < width:
            missing = [h for j, h in enumerate(header) if j >= len(r) and h in ("command", "input")]
            if missing:
                problems.append(
                    Problem(
                        shown,
                        n,
                        missing[0],
                        f"the line has {len(r)} field{'s' * (len(r) != 1)} "
                        f"but the header has {width} "
                        f"({', '.join(header_cells)}): no {missing[0]}",
                    )
                )
                continue
        elif len(r) > width and any(c.strip() for c in r[width:]):
            problems.append(
                Problem(
                    shown,
                    n,
                    None,
                    f"the line has {len(r)} fields but the header has {width}: "
                    "quote the options if they hold a comma "
                    '(shear,a.csv,"--gamma-w 10, ...")',
                )
            )
            continue
        command, source = r[ci].strip(), r[ii].strip()
        for name, value in (("command", command), ("input", source)):
            if not value:
                problems.append(Problem(shown, n, name, f"no {name}"))
        if command and source:
            runs.append((n, command, source, r[oi].strip() if oi is not None and oi < len(r) else ""))
    if problems:
        raise InputError(problems)
    return runs


def _toml_runs(shown: str, text: str) -> list[tuple[int, str, str, list[str] | str]]:
    import tomllib

    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        where = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        line = int(where.group(1)) if where else None
        raise InputError(Problem(shown, line, None, f"not valid TOML: {exc}")) from None
    except RecursionError:  # tomllib parses nested arrays and tables by recursion
        doc = None
    from .json_input import MAX_JSON_DEPTH, json_depth

    if doc is None or json_depth(doc) > MAX_JSON_DEPTH:
        raise InputError(
            Problem(
                shown,
                None,
                None,
                f"arrays or tables nested more than {MAX_JSON_DEPTH} deep: not a manifest (a run is a [[run]] "
                "table of command, input and options)",
            )
        )
    runs = doc.get("run", [])
    run_line = _line_of(text, r"^\s*run\s*=") or _line_of(text, r"^\s*\[\[\s*run\s*\]\]")
    if isinstance(runs, dict):
        raise InputError(
            Problem(
                shown,
                _line_of(text, r"^\s*\[\s*run\s*\]"),
                "run",
                "a single [run] table: write each run as [[run]] (double brackets)",
            )
        )
    if not isinstance(runs, list):
        raise InputError(
            Problem(
                shown,
                run_line,
                "run",
                f"'run' must be [[run]] tables (each with command, input and options), not a {_toml_type(runs)}",
            )
        )
    unknown = sorted(k for k in doc if k != "run")
    if unknown and not runs:
        raise InputError(
            Problem(
                shown,
                None,
                unknown[0],
                f"no [[run]] tables, but '{unknown[0]}': runs are written [[run]] with command, input and options",
            )
        )
    starts = [k + 1 for k, ln in enumerate(text.splitlines()) if re.match(r"^\s*\[\[\s*run\s*\]\]", ln)]
    problems, out = [], []
    for k, r in enumerate(runs, start=1):
        line = starts[k - 1] if len(starts) == len(runs) else run_line
        if not isinstance(r, dict):
            problems.append(
                Problem(
                    shown,
                    line,
                    "run",
                    f"run number {k} is a {_toml_type(r)}, not a table with command, input and options",
                )
            )
            continue
        bad = False
        for key in ("command", "input"):
            value = r.get(key)
            if value is None:
                problems.append(Problem(shown, line, key, f"[[run]] number {k} needs '{key}'"))
                bad = True
            elif not isinstance(value, str) or not value.strip():
                problems.append(
                    Problem(
                        shown, _key_line(text, line, key), key, f"'{key}' must be a non-empty string (got {value!r})"
                    )
                )
                bad = True
        opts = r.get("options", "")
        if isinstance(opts, list):
            if not all(isinstance(o, (str, int, float)) and not isinstance(o, bool) for o in opts):
                problems.append(
                    Problem(
                        shown,
                        _key_line(text, line, "options"),
                        "options",
                        f"'options' must be a string or a list of strings and numbers (got {opts!r})",
                    )
                )
                bad = True
            opts = [str(o) for o in opts]
        elif not isinstance(opts, str):
            problems.append(
                Problem(
                    shown,
                    _key_line(text, line, "options"),
                    "options",
                    f"'options' must be a string or a list of arguments (got {opts!r})",
                )
            )
            bad = True
        extra = sorted(set(r) - {"command", "input", "options"})
        if extra:
            problems.append(
                Problem(
                    shown,
                    line,
                    extra[0],
                    f"[[run]] number {k}: unknown key '{extra[0]}' (a run has command, input and options)",
                )
            )
            bad = True
        if not bad:
            out.append((line if line is not None else k, r["command"].strip(), r["input"].strip(), opts))
    if problems:
        raise InputError(problems)
    return out


def _line_of(text: str, pattern: str) -> int | None:
    for k, ln in enumerate(text.splitlines(), start=1):
        if re.match(pattern, ln):
            return k
    return None


def _key_line(text: str, start: int | None, key: str) -> int | None:
    """The line of ``key = ...`` in the run table starting at line ``start`` (else ``start``)."""
    if start is None:
        return None
    lines = text.splitlines()
    for k in range(start, len(lines)):
        if re.match(r"^\s*\[", lines[k]):
            break
        if re.match(rf"^\s*{re.escape(key)}\s*=", lines[k]):
            return k + 1
    return start


def _toml_type(value) -> str:
    return {bool: "boolean", int: "number", float: "number", str: "string", list: "list", dict: "table"}.get(
        type(value), type(value).__name__
    )
