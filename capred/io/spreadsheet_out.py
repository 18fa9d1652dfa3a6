"""tables.xlsx: one workbook per run, a sheet per table, units in the header row, numbers as numbers."""
from __future__ import annotations

import re


def _sheet_title(name: str, taken: set[str]) -> str:
    title = re.sub(r"[\[\]:*?/\\]", "_", name)[:31] or "table"
    base, k = title, 2
    while title.lower() in taken:
        title = f"{base[:28]}_{k}"
        k += 1
    taken.add(title.lower())
    return title


def write_workbook(path, tables: dict) -> None:
    """Every table of a result in one .xlsx workbook (NaN as empty cells, lists joined with ';')."""
    import math

    from openpyxl import Workbook

    wb = Workbook()
    wb.remove(wb.active)
    taken: set[str] = set()
    for name, frame in tables.items():
        ws = wb.create_sheet(_sheet_title(name, taken))
        ws.append([str(c) for c in frame.columns])
        for row in frame.itertuples(index=False):
            cells = []
            for v in row:
                if isinstance(v, (list, tuple)):
                    v = ";".join(map(str, v))
                elif isinstance(v, float) and not math.isfinite(v):
                    v = None
                elif hasattr(v, "item"):  # numpy scalar -> Python number
                    v = v.item()
                    if isinstance(v, float) and not math.isfinite(v):
                        v = None
                cells.append(v)
            ws.append(cells)
        ws.freeze_panes = "A2"
    wb.save(path)
