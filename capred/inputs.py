"""The inputs of a run as its JSON document and provenance.json record them: path, SHA-256, sheet, metadata."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class InputFile:
    """One input of a run: its path as given and the SHA-256 of its bytes."""

    path: str
    sha256: str | None
    sheet: str | None = None
    metadata: tuple = ()  # (key, value) pairs of the metadata block above the header

    def as_dict(self) -> dict:
        """The input as the JSON document and provenance.json record it: path, sha256, and sheet and metadata when present.

        Returns
        -------
        dict
        """
        out = {"path": self.path, "sha256": self.sha256}
        if self.sheet is not None:
            out["sheet"] = self.sheet
        if self.metadata:
            out["metadata"] = dict(self.metadata)
        return out


def input_file(source, table=None) -> InputFile:
    """InputFile of a path, a TableSource or a DataFrame (hash of its CSV text).

    With the sheet and the metadata block of the ``table`` read from it.

    Parameters
    ----------
    source : str, pathlib.Path, TableSource or pandas.DataFrame
        The input as the caller gave it.
    table : capred.io.table.Table or None, optional
        The table read from it, for its sheet and metadata block.

    Returns
    -------
    InputFile
        Path (``"<DataFrame>"`` for a DataFrame) and SHA-256 of the bytes read.
    """
    import dataclasses
    import hashlib

    path = getattr(source, "path", source) if not hasattr(source, "to_csv") else source
    if table is not None and (table.sheet is not None or table.metadata):
        base = input_file(path)
        return dataclasses.replace(base, sheet=table.sheet, metadata=tuple(table.metadata.items()))
    source = path
    if hasattr(source, "to_csv"):
        return InputFile("<DataFrame>", hashlib.sha256(source.to_csv(index=False).encode()).hexdigest())
    p = Path(source)
    if not p.is_file():
        return InputFile(str(source), None)
    h = hashlib.sha256()
    with open(p, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return InputFile(str(source), h.hexdigest())
