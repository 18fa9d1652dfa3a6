"""Text written ahead to a temporary file (capred.io.FileText) reaches every kind of output as the same bytes.

A long `bridge solve` on several processes writes its CSV and JSON text ahead; the writers copy it file to file
in the kernel (os.copy_file_range or os.sendfile), or read and write it where that cannot be done (a pipe, an
in-memory buffer). The bytes must be the same whichever way they went.
"""

from __future__ import annotations

import io
import os
import tempfile

from capred.io import FileText, stream_json, write_piece
from capred.result import Rows

TEXT = b"".join(b'{"row":%d,"x":%r},' % (k, k / 7) for k in range(20_000))


def _ahead(text: bytes, lead: bytes = b"junk before the text "):
    """A temporary file holding ``text`` after some other bytes; the FileText of ``text`` in it."""
    f = tempfile.TemporaryFile()
    f.write(lead + text + b" and after")
    f.flush()
    return f, FileText(f.fileno(), len(lead), len(text))


def test_a_file_gets_the_bytes_and_its_position_moves_past_them(tmp_path):
    src, piece = _ahead(TEXT)
    with src, open(tmp_path / "out", "wb") as fh:
        fh.write(b"head,")
        write_piece(fh, piece)
        fh.write(b"tail")  # written after the copied text, not over it
    assert (tmp_path / "out").read_bytes() == b"head," + TEXT + b"tail"


def test_an_object_without_a_file_gets_the_bytes_read():
    src, piece = _ahead(TEXT)
    buf = io.BytesIO()
    with src:
        buf.write(b"[")
        write_piece(buf, piece)
    assert buf.getvalue() == b"[" + TEXT


def test_a_pipe_gets_the_bytes():
    src, piece = _ahead(TEXT[:30_000])  # less than a pipe's buffer: no reader needed
    r, w = os.pipe()
    with src, os.fdopen(w, "wb") as fh:
        write_piece(fh, piece)
    with os.fdopen(r, "rb") as out:
        assert out.read() == TEXT[:30_000]


class _Ahead(Rows):
    """Rows whose JSON text is in a temporary file (as capred.pipelines.bridge_blocks hands it out)."""

    written_ahead = True

    def __init__(self, pieces) -> None:
        super().__init__(2, lambda a, b: [])
        self.pieces = pieces

    def json_chunks(self, size: int = 2000):
        yield from self.pieces


def test_stream_json_copies_text_written_ahead_to_a_file_or_a_callable(tmp_path):
    a, b = b'{"k":1}', b'{"k":2}'
    src, first = _ahead(a)
    piece_b = FileText(first.fd, first.offset, 0)  # an empty piece: no comma for it
    with src:
        src.seek(0, os.SEEK_END)
        at = src.tell()
        src.write(b)
        src.flush()
        doc = {"command": "x", "rows": _Ahead([first, piece_b, FileText(src.fileno(), at, len(b))])}
        with open(tmp_path / "doc.json", "wb") as fh:
            stream_json(doc, fh.write)
        chunks: list[bytes] = []
        stream_json(doc, chunks.append)
    expected = b'{"command":"x","rows":[{"k":1},{"k":2}]}\n'
    assert (tmp_path / "doc.json").read_bytes() == expected
    assert b"".join(chunks) == expected


def test_a_wrapping_file_object_gets_the_bytes_through_its_own_write(tmp_path):
    """A gzip file has a descriptor, but the bytes must go through its compressor, not to the descriptor."""
    import gzip

    src, piece = _ahead(TEXT)
    with src, gzip.open(tmp_path / "out.gz", "wb") as fh:
        fh.write(b"[")
        write_piece(fh, piece)
    assert gzip.decompress((tmp_path / "out.gz").read_bytes()) == b"[" + TEXT


def test_a_copy_asked_to_stop_stops_and_the_text_reads_as_bytes(tmp_path):
    import threading

    import pytest

    from capred.io.writers import Stopped

    src, piece = _ahead(TEXT)
    stop = threading.Event()
    stop.set()
    with src:
        assert bytes(piece) == TEXT
        with open(tmp_path / "out", "wb") as fh, pytest.raises(Stopped):
            write_piece(fh, piece, stop)
