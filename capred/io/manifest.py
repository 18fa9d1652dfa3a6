"""Read a batch manifest: one run per line (CSV) or per [[run]] table (TOML)."""
from __future__ import annotations

from pathlib import Path

from ..errors import InputError, Problem


def read_manifest(path: Path) -> list[tuple[int, str, str, list[str] | str]]:
    """(line, command, input, options) per run, from a CSV or TOML manifest.

    Options are a string as typed on the command line (CSV, or a TOML string)
    or a list of arguments (a TOML list).
    """

    if not path.exists():
        from ..errors import MissingFileError

        raise MissingFileError(str(path))
    if not path.is_file():
        raise InputError(Problem(str(path), None, None, "not a file"))
    text = path.read_text(encoding="utf-8-sig")
    if path.suffix.lower() == ".toml":
        import tomllib

        try:
            runs = tomllib.loads(text).get("run", [])
        except tomllib.TOMLDecodeError as exc:
            raise InputError(Problem(str(path), None, None, f"not valid TOML: {exc}")) from None
        out = []
        for k, r in enumerate(runs, start=1):
            if not isinstance(r, dict) or "command" not in r or "input" not in r:
                raise InputError(Problem(str(path), None, None, f"[[run]] number {k} needs 'command' and 'input'"))
            opts = r.get("options", "")
            out.append((k, str(r["command"]), str(r["input"]), [str(o) for o in opts] if isinstance(opts, list)
                        else str(opts)))
        return out
    import csv

    rows = [(n, row) for n, row in enumerate(csv.reader(text.splitlines()), start=1)
            if row and not row[0].lstrip().startswith("#") and any(c.strip() for c in row)]
    if not rows:
        raise InputError(Problem(str(path), None, None, "the manifest is empty"))
    header = [h.strip().lower() for h in rows[0][1]]
    if "command" not in header or "input" not in header:
        raise InputError(Problem(str(path), rows[0][0], None, "the header needs 'command' and 'input' (and 'options')"))
    ci, ii = header.index("command"), header.index("input")
    oi = header.index("options") if "options" in header else None
    return [(n, r[ci].strip(), r[ii].strip(), r[oi].strip() if oi is not None and oi < len(r) else "")
            for n, r in rows[1:]]
