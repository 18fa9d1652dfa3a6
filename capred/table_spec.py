"""A console table as every command hands it to capred.report (console, report.html, notebooks).

Title, headers with alignment, rows of text.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class TableSpec:
    """A console table: title, column headers with alignment, rows of text.

    ``total_rows`` is the row count of the full table when only the first rows
    are shown; ``full_table`` names the output file that holds them all.
    """

    title: str
    columns: list[tuple[str, str]]  # (header, "left" | "right")
    rows: list[list[str]] = field(default_factory=list)
    total_rows: int | None = None
    full_table: str | None = None
    bold_rows: set[int] = field(default_factory=set)
    sections: set[int] = field(default_factory=set)  # rows after which a rule is drawn
