"""JSON inputs read within bounds: their size (``--max-megabytes``) before reading, their nesting after.

A JSON file given to a command (``shear --retention fits.json``) is a user's file like a CSV: it is refused,
with one message naming it, when larger than the reading limit (:class:`capred.io.grid.ReadLimits`,
``max_bytes``) before a byte is read, and when nested deeper than :data:`MAX_JSON_DEPTH` (capred's documents
nest about 6 deep; Python's parser would otherwise raise ``RecursionError`` at a few thousand levels).
"""

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from ..errors import InputError, Problem

#: the reading limits of a run with no table to carry them (set by :func:`run_limits`)
_RUN_LIMITS: ContextVar = ContextVar("capred_run_limits", default=None)


@contextmanager
def run_limits(limits):
    """Within the block, a run without a table reads its JSON inputs within ``limits``.

    A table carries the run's limits (``TableSource.limits``); a run from options only (``capred skempton-b
    --retention fits.json``, ``capred shear-band --triaxial summary.json``) has no table, so the CLI states its
    ``--max-megabytes`` here, and a script may too: ``with run_limits(ReadLimits(max_bytes=2**20)): ...``.

    Parameters
    ----------
    limits : capred.io.grid.ReadLimits or None
        The limits; None: the readers' defaults.

    Yields
    ------
    None
    """
    token = _RUN_LIMITS.set(limits)
    try:
        yield
    finally:
        _RUN_LIMITS.reset(token)


def limits_of(source):
    """The reading limits of a run: its table's (``source.limits``), else those of the enclosing :func:`run_limits`.

    Parameters
    ----------
    source : str, Path, DataFrame, TableSource or None
        The run's table, None for a run from options only.

    Returns
    -------
    capred.io.grid.ReadLimits or None
        None: the readers' defaults.
    """
    limits = getattr(source, "limits", None)
    return limits if limits is not None else _RUN_LIMITS.get()


#: deepest nesting of arrays and objects a JSON input may have (capred's own documents nest about 6 deep)
MAX_JSON_DEPTH = 64


def json_depth(doc, limit: int = MAX_JSON_DEPTH) -> int:
    """Nesting depth of a parsed JSON value (a scalar: 0), counted without recursion, up to ``limit + 1``.

    Parameters
    ----------
    doc : object
        A parsed JSON value.
    limit : int
        The walk stops once a value deeper than this is found.

    Returns
    -------
    int
    """
    deepest, stack = 0, [(doc, 0)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            value = value.values()
        elif not isinstance(value, list):
            continue
        depth += 1
        deepest = max(deepest, depth)
        if deepest > limit:
            return deepest
        stack.extend((v, depth) for v in value if isinstance(v, (dict, list)))
    return deepest


def read_json(path, what: str, limits=None):
    """The parsed JSON of the file ``path``, bounded in size and depth.

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        How messages name it, e.g. ``"--retention"``.
    limits : capred.io.grid.ReadLimits, optional
        Its ``max_bytes`` bounds the file's size (default: the reader's default, 256 MiB).

    Returns
    -------
    object
        The parsed document.

    Raises
    ------
    LimitError
        Larger than ``limits.max_bytes`` (nothing read).
    InputError
        Nested deeper than :data:`MAX_JSON_DEPTH`.
    json.JSONDecodeError, UnicodeDecodeError, FileNotFoundError, OSError
        Not JSON, not UTF-8, or as ``open`` raises them: the caller words them for its option.
    """
    import json

    from .grid import ReadLimits

    limits = limits or ReadLimits()
    path = Path(path)
    size = path.stat().st_size
    if size > limits.max_bytes:
        raise limits.error("max_bytes", f"{what}: the file holds {size / 2**20:.1f} MiB", str(path))
    text = path.read_bytes().decode("utf-8-sig", errors="strict")
    try:
        doc = json.loads(text)
    except RecursionError:
        doc = None
        depth = MAX_JSON_DEPTH + 1
    else:
        depth = json_depth(doc)
    if depth > MAX_JSON_DEPTH:
        raise InputError(
            Problem(
                str(path),
                None,
                None,
                f"{what}: arrays and objects nested more than {MAX_JSON_DEPTH} deep (a capred document nests "
                "about 6): not a document capred wrote",
            )
        )
    return doc
