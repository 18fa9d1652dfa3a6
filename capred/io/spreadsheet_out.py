"""tables.xlsx: one workbook per run, a sheet per table, units in the header row, numbers as numbers.

Safe and reproducible:

- every text cell is stored as text (an inline string), never as a formula,
  so a material named ``=HYPERLINK("http://...")`` reads as those characters
  and runs nothing when the workbook opens;
- control characters, which the XML of a workbook cannot hold (U+0000-U+0008,
  U+000B, U+000C, U+000E-U+001F), are shown as their Unicode control pictures
  (U+2400 + code, e.g. U+000B as '␋'), so a stray control character in a
  label neither crashes the writer nor vanishes silently;
- no current time is stored: the document's created/modified properties and
  the zip entries' dates come from ``SOURCE_DATE_EPOCH`` when it is set (the
  reproducible-builds convention) and are 1980-01-01 00:00 UTC (the earliest
  date a zip entry holds) otherwise, so a rerun writes the same bytes.
"""

from __future__ import annotations

import re
import zipfile
from datetime import UTC

#: characters an XML 1.0 document (and so a workbook) cannot hold, as openpyxl checks them
_ILLEGAL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")
#: the earliest date a zip entry can carry
_ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)


def _sheet_title(name: str, taken: set[str]) -> str:
    title = _ILLEGAL.sub("_", re.sub(r"[\[\]:*?/\\]", "_", name))[:31] or "table"
    base, k = title, 2
    while title.lower() in taken:
        title = f"{base[:28]}_{k}"
        k += 1
    taken.add(title.lower())
    return title


def safe_text(text: str) -> str:
    """``text`` with each control character an XML workbook cannot hold replaced by its control picture.

    Parameters
    ----------
    text : str
        Any text (a material name, a test id).

    Returns
    -------
    str
        The same text; U+0000-U+0008, U+000B, U+000C and U+000E-U+001F become
        U+2400-U+241F (Unicode block "Control Pictures"), tab, newline and
        carriage return are kept.
    """
    return _ILLEGAL.sub(lambda m: chr(0x2400 + ord(m.group())), text)


def source_date_epoch():
    """The time ``SOURCE_DATE_EPOCH`` sets, for reproducible builds.

    Returns
    -------
    datetime.datetime or None
        The UTC datetime of the variable's seconds since 1970; None when it is unset or not a number.
    """
    import os
    from datetime import datetime

    value = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    try:
        return datetime.fromtimestamp(int(value), UTC) if value else None
    except (ValueError, OverflowError, OSError):
        return None


class _FixedDateZip(zipfile.ZipFile):
    """A ZipFile whose entries all carry one date (no current time in the archive)."""

    date_time = _ZIP_EPOCH

    def _info(self, name: str) -> zipfile.ZipInfo:
        info = zipfile.ZipInfo(name, date_time=self.date_time)
        info.compress_type = zipfile.ZIP_DEFLATED
        info.external_attr = 0o644 << 16
        return info

    def writestr(self, zinfo_or_arcname, data, *args, **kwargs):
        if isinstance(zinfo_or_arcname, str):
            zinfo_or_arcname = self._info(zinfo_or_arcname)
        return super().writestr(zinfo_or_arcname, data, *args, **kwargs)

    def write(self, filename, arcname=None, *args, **kwargs):
        with open(filename, "rb") as fh:
            data = fh.read()
        return self.writestr(arcname or str(filename), data)


def _cells(row, text_cell):
    """Cells of one row: numbers as numbers, NaN/inf empty, lists joined with ';', text as text."""
    import math

    out = []
    for v in row:
        if isinstance(v, (list, tuple)):
            v = ";".join(map(str, v))
        elif hasattr(v, "item") and not isinstance(v, str):  # numpy scalar -> Python number
            v = v.item()
        if isinstance(v, float):
            out.append(v if math.isfinite(v) else None)
        elif isinstance(v, int) and not isinstance(v, bool) and abs(v) >= 2**53:
            out.append(text_cell(str(v)))  # more digits than a spreadsheet number keeps: the digits, as text
        elif isinstance(v, (bool, int)):
            out.append(v)
        elif v is None or type(v).__name__ in ("NAType", "NaTType"):
            out.append(None)
        else:
            out.append(text_cell(str(v)))
    return out


def write_workbook(path, tables: dict) -> None:
    """Every table of a result in one .xlsx workbook (NaN as empty cells, lists joined with ';').

    Parameters
    ----------
    path : str, Path or binary file
        Where the workbook goes.
    tables : dict of str to DataFrame
        Sheet name -> table; column names (with units) make the header row.
    """
    from datetime import datetime

    from openpyxl import Workbook
    from openpyxl.cell import WriteOnlyCell
    from openpyxl.writer.excel import ExcelWriter

    wb = Workbook(write_only=True)
    when = source_date_epoch()
    stamp = when.replace(tzinfo=None) if when is not None else datetime(*_ZIP_EPOCH)
    wb.properties.created = stamp
    wb.properties.modified = stamp
    wb.properties.creator = "capred"
    taken: set[str] = set()
    for name, frame in tables.items():
        ws = wb.create_sheet(_sheet_title(str(name), taken))
        ws.freeze_panes = "A2"

        def text_cell(text: str, ws=ws):
            cell = WriteOnlyCell(ws)
            cell._value, cell.data_type = safe_text(text), "s"  # stored as a string, never a formula
            return cell

        ws.append([text_cell(str(c)) for c in frame.columns])
        for row in frame.itertuples(index=False):
            ws.append(_cells(row, text_cell))
    archive = _FixedDateZip(path, "w", zipfile.ZIP_DEFLATED, allowZip64=True)
    if when is not None:
        archive.date_time = max(_ZIP_EPOCH, tuple(when.timetuple())[:6])
    try:
        ExcelWriter(wb, archive).save()  # not wb.save(): that stamps the current time as "modified"
    finally:
        archive.close()
