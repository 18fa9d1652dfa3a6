"""CSV text split a chunk at a time (capred.io.grid.line_chunks): the same rows and line numbers as whole."""

import random

from capred.io import grid


def _text(seed=0, n=3000):
    rng = random.Random(seed)
    lines = []
    for k in range(n):
        r = rng.random()
        lines.append("" if r < 0.3 else " \t" if r < 0.4 else ",,;" if r < 0.5 else f"a{k},{k},x{k}")
    return "\n".join(lines)


def _naive(text, delim, first_line=1):
    return [(k + first_line, ln.split(delim)) for k, ln in enumerate(text.split("\n")) if ln and not ln.isspace()]


def test_chunks_join_back_to_the_text():
    text = _text()
    for size in (1, 7, 100, 10**6):
        assert "\n".join(grid.line_chunks(text, size)) == text


def test_rows_and_line_numbers_across_chunk_boundaries(monkeypatch):
    text = _text()
    monkeypatch.setattr(grid, "CHUNK_CHARS", 50)  # many boundaries (the default is 1 MiB)
    monkeypatch.setattr(grid.line_chunks, "__defaults__", (50,))
    rows = grid.parse_rows(text, ",", first_line=5)
    expected = _naive(text, ",", 5)
    for k in range(min(200, len(expected))):  # the first 200 rows' cells are stripped
        expected[k] = (expected[k][0], [c.strip() for c in expected[k][1]])
    assert rows == expected


def test_delimiter_rows_counted_across_chunk_boundaries(monkeypatch):
    text = _text(seed=1)
    whole = grid.Grid("t.csv", None, [], (",",), first_line=1)
    expect = grid.blank_delimiter_rows(whole, text)
    monkeypatch.setattr(grid.line_chunks, "__defaults__", (50,))
    chunked = grid.Grid("t.csv", None, [], (",",), first_line=1)
    assert grid.blank_delimiter_rows(chunked, text) == expect
    assert chunked.delimiter_rows == whole.delimiter_rows > 0
    assert chunked.delimiter_lines == whole.delimiter_lines
    lines = text.split("\n")
    assert all(set(lines[n - 1]) <= set(",;") for n in chunked.delimiter_lines)  # the lines named are such rows


def test_rows_are_split_into_at_most_max_columns_cells(tmp_path):
    """A line of 200,000 cells under a 3-column header: refused at that line without making its cells; a row of
    trailing empty cells (a spreadsheet export) is read as the narrow row it is."""
    import pytest

    from capred.errors import LimitError
    from capred.io import TableSource, read_grid

    path = tmp_path / "wide.csv"
    path.write_text("a,b,c\n1,2,3\n" + ",".join(["ab"] * 200_000) + "\n4,5,6" + "," * 5000 + "\n")
    g = read_grid(TableSource(path))
    with pytest.raises(LimitError, match="200,000 cells") as info:
        g.parse_all(",")
    assert info.value.problems[0].line == 3 and info.value.limit == "max_columns"
    path.write_text("a,b,c\n1,2,3\n4,5,6" + "," * 5000 + "\n")
    g = read_grid(TableSource(path))
    g.parse_all(",")
    assert [len(cells) for _, cells in g.rows] == [3, 3, 1001]  # trailing empties kept as one empty cell
    assert g.rows[2][1][:3] == ["4", "5", "6"] and not any(g.rows[2][1][3:])
