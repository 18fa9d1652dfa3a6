"""Write result files atomically, and the provenance record of a run.

Every file is written to a temporary name in the target folder and renamed
into place, so an interrupted run never leaves a half-written table that looks
complete. Floats are written with a fixed format so reruns give the same bytes.
"""
from __future__ import annotations

import hashlib
import io
import json
import os
import sys
import tempfile
from pathlib import Path

FLOAT_FORMAT = "%.6g"
_UMASK = os.umask(0)
os.umask(_UMASK)


def atomic_write_bytes(path: Path, data: bytes) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, 0o666 & ~_UMASK)  # mkstemp creates 0600; give the usual permissions
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def write_text(path: Path, text: str) -> Path:
    return atomic_write_bytes(path, text.encode("utf-8"))


def write_json(path: Path, obj) -> Path:
    return write_text(path, json.dumps(obj, indent=2, ensure_ascii=False) + "\n")


def write_csv(path: Path, frame) -> Path:
    """A pandas DataFrame as CSV with the fixed float format."""
    buf = io.StringIO()
    frame.to_csv(buf, index=False, float_format=FLOAT_FORMAT, lineterminator="\n")
    return write_text(path, buf.getvalue())


def write_png(path: Path, figure, dpi: int = 150) -> Path:
    """A matplotlib Figure as PNG (no timestamp metadata: reruns give the same bytes)."""
    buf = io.BytesIO()
    figure.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    return atomic_write_bytes(path, buf.getvalue())


def sha256(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 16), b""):
            h.update(block)
    return h.hexdigest()


def provenance(command: str, inputs: list[str | Path], options: dict, outputs: list[Path]) -> dict:
    """Record of a run: capred version, command line, input hashes, options, outputs."""
    from datetime import datetime, timezone

    from .. import __version__

    return {
        "capred_version": __version__,
        "command": command,
        "command_line": " ".join(sys.argv),
        "python": sys.version.split()[0],
        "inputs": [{"path": str(p), "sha256": sha256(p) if Path(str(p)).is_file() else None} for p in inputs],
        "options": options,
        "outputs": sorted(Path(p).name for p in outputs),
        "created_utc": datetime.now(timezone.utc).replace(microsecond=0).isoformat(),
    }
