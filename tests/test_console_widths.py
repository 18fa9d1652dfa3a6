"""Every command's console tables fit terminals of 80, 100 and 120 columns (issue 29.1).

The commands come from the registry (capred.reductions.REDUCTIONS), so a new command is tested here without
editing this file; each runs on its bundled sample (or its default options, for a command without input).
"""

import re

import pytest
from rich.cells import cell_len
from rich.console import Console

from capred.reductions import REDUCTIONS
from capred.report.presenters import console_tables
from capred.report.render import label_columns, render_tables, row_labels

WIDTHS = (80, 100, 120)
#: two box-drawing verticals side by side (or a top/bottom border joint next to another): a column of width 0
ZERO_WIDTH = re.compile("[┃│][┃│]|[┏┳┡╇┗┻┌┬├┼└┴][┳╇┻┬┼┴]")
_SPLIT = re.compile(r"[\s┃│]+")
#: the range separator of the presenters ('0.0383 … 0.0591'): a value on either side, not a border


def sample_result(command: str):
    """The result of the quick run of the registry (``Reduction.example_args``: ``capred COMMAND --sample`` and
    its example options, or those options alone for a command without input), built by the CLI's own parser,
    so each command's sample options (pt-volume's example lines) are those a user gets."""
    import typer.main

    from capred.cli import _subcommand, app
    from capred.cli.common import BUILDERS

    red = REDUCTIONS[command]
    cmd = _subcommand(typer.main.get_command(app), command)
    ctx = cmd.make_context(command, red.example_args()[len(command.split()) :])  # --sample and its options
    inv = BUILDERS[command](**ctx.params)
    return red.run(inv.sources[0] if inv.sources else None, inv.options)


@pytest.fixture(scope="module")
def samples():
    return {name: console_tables(sample_result(name)) for name in REDUCTIONS}


def _printed(specs, width: int) -> str:
    con = Console(width=width, record=True, force_terminal=True, color_system=None)
    render_tables(specs, con)
    return con.export_text()


@pytest.mark.parametrize("command", sorted(REDUCTIONS))
def test_every_command_fits_80_100_and_120_columns(samples, command):
    specs = samples[command]
    assert specs, f"{command}: no console table"
    for width in WIDTHS:
        text = _printed(specs, width)
        lines = text.splitlines()
        assert all(cell_len(line) <= width for line in lines), (command, width, max(map(cell_len, lines)))
        assert not ZERO_WIDTH.search(text), (command, width, ZERO_WIDTH.search(text).group(0))
        # nothing cut by rich (its ellipsis ends a cell; a range 'low … high' of a presenter has a value after it)
        assert "…" not in text  # a cut value; ranges print "low to high"
        words = _SPLIT.split(text)
        tokens = set(words) | {w[:-1] for w in words if w.endswith(":")}  # 'name:' of a stacked pair
        for spec in specs:
            labels = label_columns(spec)
            for j, (head, _) in enumerate(spec.columns):  # every value's header, word by word (they wrap)
                # (a stacked block heads with its labels' values alone and leaves empty cells out)
                if j not in labels and any(row[j].strip() for row in spec.rows):
                    assert set(head.split()) <= tokens, (command, width, head)
            for row, label in zip(spec.rows, row_labels(spec)):
                for cell in row:  # every cell whole: each of its words stands as a word of the output
                    assert set(cell.split()) <= tokens, (command, width, cell)
                for part in label.split(" · "):  # each row names itself
                    assert set(part.split()) <= tokens, (command, width, label)


def test_retention_on_100_columns_shows_every_model_r2_aicc_and_weight(samples):
    """The issue's 'done when': every model's name, R², AICc and weight on a 100-column terminal: on the
    model's row of the table, or in its block of name: value pairs where a table is too wide."""
    models = [spec for spec in samples["retention"] if "R²" in [h for h, _ in spec.columns]]
    assert models  # one table of models per branch
    for spec in models:
        text = _printed([spec], 100)
        heads = [h for h, _ in spec.columns]
        for row in spec.rows:
            line = next((x for x in text.splitlines() if _SPLIT.split(x.strip(" ┃│"))[0] == row[0]), None)
            if line is not None:  # a row of the table
                for name in ("R²", "AICc", "weight"):
                    assert row[heads.index(name)] in _SPLIT.split(line), (row[0], name)
                continue
            after = text.split(f"\n{row[0]}\n", 1)[1].splitlines()
            block = "\n".join(after[: next(k for k, x in enumerate(after + [""]) if not x.startswith(" "))])
            for name in ("R²", "AICc", "weight"):
                assert f"{name}: {row[heads.index(name)]}" in block, (row[0], name)
