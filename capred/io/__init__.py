"""Reading lab files into SI tables and writing result files: the public API of capred's io layer.

Other layers (pipelines, report, batch, cli) import what they need from here, e.g.
``from ..io import Column, Table, read_table``. Each name lives in one submodule:

- `capred.io.table`: `Column`, `Table`, `read_table` and the header matching the CLI's hints reuse
  (`column_lookup`, `find_header`, `match_header`, `header_key`);
- `capred.io.grid`: `TableSource`, `ReadLimits`, `read_grid`, `source_path`, `SPREADSHEET_SUFFIXES`;
- `capred.io.blocks`: `read_table_blocks` (a long CSV a block at a time);
- `capred.io.manifest`: `read_manifest`;
- `capred.io.json_input`: `read_json` (a JSON input bounded in size and nesting), `json_depth` and
  `MAX_JSON_DEPTH` (the nesting rule, for a reader of its own such as retention-convert's), `run_limits` and
  `limits_of` (the reading limits of a run with no table);
- `capred.io.writers`: the output files (`write_run`, `write_batch_file`, `RunFolder`, `check_target`,
  `check_rows_output` (outputs sized from an input's lines before a run), `encode_csv`, `encode_json`, `encode_rows`, `stream_json`, `safe_name`, `INDEX_HEADER`,
  `second_core_free`, `FileText` and `write_piece`: text written ahead, copied file to file);
- `capred.io.spreadsheet_out`: `source_date_epoch`.

Names are imported from their submodule on first use (PEP 562), so ``import capred.io`` costs nothing and
pulls in no writer, reader or pandas until one is needed.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # what the names are, for readers and type checkers; at run time see __getattr__
    from .blocks import read_table_blocks
    from .grid import SPREADSHEET_SUFFIXES, ReadLimits, TableSource, read_grid, source_path
    from .json_input import MAX_JSON_DEPTH, json_depth, limits_of, read_json, run_limits
    from .manifest import read_manifest
    from .spreadsheet_out import source_date_epoch
    from .table import Column, Table, column_lookup, find_header, header_key, match_header, read_table
    from .writers import (
        INDEX_HEADER,
        FileText,
        RunFolder,
        check_rows_output,
        check_target,
        encode_csv,
        encode_json,
        encode_rows,
        safe_name,
        second_core_free,
        stream_json,
        write_batch_file,
        write_csv_file,
        write_piece,
        write_run,
    )

#: public name -> the submodule that defines it
_WHERE = {
    "read_table_blocks": "blocks",
    **dict.fromkeys(("SPREADSHEET_SUFFIXES", "ReadLimits", "TableSource", "read_grid", "source_path"), "grid"),
    "read_manifest": "manifest",
    **dict.fromkeys(("read_json", "json_depth", "MAX_JSON_DEPTH", "run_limits", "limits_of"), "json_input"),
    "source_date_epoch": "spreadsheet_out",
    **dict.fromkeys(
        ("Column", "Table", "column_lookup", "find_header", "header_key", "match_header", "read_table"), "table"
    ),
    **dict.fromkeys(
        (
            "INDEX_HEADER",
            "FileText",
            "RunFolder",
            "check_rows_output",
            "check_target",
            "encode_csv",
            "encode_json",
            "encode_rows",
            "safe_name",
            "second_core_free",
            "stream_json",
            "write_batch_file",
            "write_csv_file",
            "write_piece",
            "write_run",
        ),
        "writers",
    ),
}

__all__ = [
    "Column",
    "FileText",
    "INDEX_HEADER",
    "ReadLimits",
    "RunFolder",
    "SPREADSHEET_SUFFIXES",
    "Table",
    "TableSource",
    "check_rows_output",
    "check_target",
    "column_lookup",
    "encode_csv",
    "encode_json",
    "encode_rows",
    "find_header",
    "header_key",
    "match_header",
    "read_grid",
    "read_json",
    "json_depth",
    "MAX_JSON_DEPTH",
    "run_limits",
    "limits_of",
    "read_manifest",
    "read_table",
    "read_table_blocks",
    "safe_name",
    "second_core_free",
    "source_date_epoch",
    "source_path",
    "stream_json",
    "write_batch_file",
    "write_csv_file",
    "write_piece",
    "write_run",
]


def __getattr__(name: str):
    """A public name of the io layer, imported from its submodule on first use (PEP 562)."""
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    # not cached here: a test that patches the submodule's attribute is seen by the next import from here
    return getattr(importlib.import_module(f"{__name__}.{where}"), name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
