"""`capred shear`'s entry: a direct-shear table reduced whole or block by block.

Whole by capred.pipelines.shear.run_table or, when a plain CSV is longer than one block of capred.io.blocks, block by
block (capred.pipelines.shear_long.run_blocks).

Both ways share the steps of capred.pipelines.shear; this module sits above them, so that neither imports the
other's caller.
"""

from __future__ import annotations

from ..io import read_table_blocks
from .shear import SCHEMA, ShearOptions, ShearResult, run_table
from .shear_long import run_blocks

__all__ = ["run_shear"]


def run_shear(source, options: ShearOptions | None = None) -> ShearResult:
    """Reduce a direct-shear table and compare effective-stress models (Evenepoel's four by default).

    ``source`` is a path to a CSV file or a pandas DataFrame. Raises
    InputError (every problem in the file, each with line and column),
    OptionError or FitError; never writes anything.

    A plain CSV longer than one block of capred.io.blocks (about 60,000
    tests) is read and predicted block by block and gives a ShearBlocks (a
    ShearResult whose per-test outputs stay in a temporary file: memory flat
    in the number of tests, the same output files); its problems are raised
    block by block (the first block that has any), repeated test ids after
    the last. With raw curves (``options.curves``) a table is read whole.

    Parameters
    ----------
    source : str or Path or DataFrame
        The direct-shear tests (one row per test).
    options : ShearOptions, optional
        Constants, per-test defaults, models and fitting choices (SI).

    Returns
    -------
    ShearResult
        The dry envelopes, each model's predictions and scores, the ranking and the back-analysis (a
        ShearBlocks for a long plain CSV).

    References
    ----------
    .. [1] Evenepoel, R. Micro-mechanical characterization of the capillary effective stress in granular
       materials. Master thesis, Vrije Universiteit Brussel.

    Example
    -------
    >>> import capred
    >>> r = capred.run_shear(capred.sample_path("shear"))   # doctest: +SKIP
    >>> r.to_json()["materials"]["steel_2mm"]["phi_deg"]     # doctest: +SKIP
    """
    opt = options or ShearOptions()
    if opt.curves is not None:  # raw curves: the table is read whole
        return run_table(source, opt)
    blocks = read_table_blocks(source, SCHEMA)
    table = next(blocks)
    more = next(blocks, None)
    if more is None:
        return run_table(source, opt, table)
    pending = [table, more]  # a long plain CSV is read, computed and kept block by block (issue 20)
    del table, more  # run_blocks lets go of each block once read
    return run_blocks(source, opt, pending, blocks)
