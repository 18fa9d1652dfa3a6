"""`capred shear` on a long table, block by block (issue 20): memory flat in the number of tests.

A plain CSV longer than one block of `capred.io.blocks` is read, checked and derived block by block; the
compact per-test arrays every fit needs stay in memory, the test ids, raw inputs and every per-test output are
spooled to a temporary file (`capred.result.Spool`) and written back block by block. `run_blocks` is what
`capred.pipelines.shear_run.run_shear` calls for such a table; `ShearBlocks` is the result (a ShearResult whose
per-test outputs stay in the spool). The reduction itself (derivation, fits, predictions, scores, bootstrap)
is `capred.pipelines.shear`'s: outputs are those of the whole-table run, byte for byte.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..physics import shear as ph
from ..progress import steps, task
from ..result import Spool, input_file
from .shear import (
    RAW_INPUTS,
    ShearOptions,
    ShearResult,
    best_of,
    bootstrap_materials,
    check_shear_table,
    derive_tests,
    documented_column,
    filled_column,
    fit_dry_envelopes,
    fit_saturated_envelopes,
    metrics_table,
    model_inputs_of,
    predict_models,
    score_models,
    summary_table,
    values_by_material,
)
from .shear_fits import envelope_fits
from .shear_records import BackAnalysis, ModelPrediction, Sampled

#: per-test arrays a long run keeps in memory for every test: what the fits, metrics, flags, bootstrap and figures
#: read (about 60 bytes a test with the material and condition, which refer to one str object per name)
_COMPACT = ("sigma_N", "suction", "S_R", "tau_max", "R")
#: tests per piece of the spools: a block read (capred.io.blocks, ~60,000 tests) is predicted, spooled and written
#: in pieces of this many, so that predicting and writing take a quarter of the memory reading takes
_SPOOL_ROWS = 16_384


class _RowProblems:
    """Problems of a long table, located by row over all its blocks (as Table.add_problem locates them)."""

    def __init__(self, path: str, sheet, headers: dict, lines: np.ndarray, text: dict):
        self.path, self.sheet, self.headers, self.lines, self.text = path, sheet, headers, lines, text
        self.problems: list = []

    def add_problem(self, row: int, column: str | None, message: str, value: str | None = None) -> None:
        from ..errors import Problem

        if value is None and column in self.text:
            value = str(self.text[column][row])
        self.problems.append(
            Problem(
                self.path,
                int(self.lines[row]),
                self.headers.get(column, column) if column else None,
                message,
                self.sheet,
                value,
            )
        )

    def raise_if_problems(self) -> None:
        if self.problems:
            from ..errors import InputError

            raise InputError(self.problems)


def _trim() -> None:
    """Hand the heap memory freed by a block back to the system (glibc's malloc_trim; nothing elsewhere).

    glibc raises its mmap threshold once a large array is freed, so later block-sized arrays come from the
    heap, which it keeps after they are freed: without this a million-test run held ~110 MB it no longer used
    (measured: 244 MB resident after run_shear, 133 MB after a trim).
    """
    trim = _TRIM[0]
    if trim is None:
        try:
            import ctypes

            trim = ctypes.CDLL(None).malloc_trim
        except (OSError, AttributeError):
            trim = False
        _TRIM[0] = trim
    if trim:
        trim(0)


_TRIM: list = [None]


def _interned(values, names: dict) -> np.ndarray:
    """An object array of ``values`` in which equal strings are one object (the first seen, kept in ``names``)."""
    return np.array([names.setdefault(v, v) for v in values.tolist()], dtype=object)


def _flat(records: dict) -> dict:
    """The output arrays of records ({prefix: record}) as one flat dict (pairs as two arrays), for a Spool."""
    out = {}
    for prefix, rec in records.items():
        for f in dataclasses.fields(rec):
            v = vars(rec)[f.name]  # the stored (SI) value, past a renamed attribute's warning
            if "output" not in f.metadata or v is None:
                continue
            if isinstance(v, tuple):
                out[f"{prefix}|{f.name}|0"], out[f"{prefix}|{f.name}|1"] = v
            else:
                out[f"{prefix}|{f.name}"] = v
    return out


def _record(cls, prefix: str, arrays: dict, **fixed):
    """A record of ``cls`` rebuilt from the flat arrays of ``_flat`` (any mapping of key to array-like)."""
    values = {}
    for f in dataclasses.fields(cls):
        key = f"{prefix}|{f.name}"
        if key in arrays:
            values[f.name] = arrays[key]
        elif key + "|0" in arrays:
            values[f.name] = (arrays[key + "|0"], arrays[key + "|1"])
    return cls(**fixed, **values)


def _sample_rows(wet, mat, suction, materials) -> np.ndarray:
    """Rows whose per-test outputs a long run keeps in memory.

    The samples its figures draw (capred.sampling of the same index sets as the report's figures) and the first wet
    tests its console table lists.
    """
    from ..sampling import MAX_ROWS, sample_rows

    parts = [np.flatnonzero(wet)[:MAX_ROWS]]
    for m in materials:
        wet_m = wet & (mat == m)
        parts += [sample_rows(np.flatnonzero(wet_m)), sample_rows(np.flatnonzero(wet_m & (suction > 0)))]
    return np.unique(np.concatenate(parts)).astype(np.int64)


@dataclass
class _Harvest:
    """Pass 1's harvest of every block.

    The compact per-test arrays of ``_COMPACT``, line numbers, interned materials and conditions, hashes of the test
    ids, sizes of the spooled pieces, notes, warnings and the problems of the blocks that have some.
    """

    keep: dict[str, list]
    lines: list = field(default_factory=list)
    mats: list = field(default_factory=list)
    conds: list = field(default_factory=list)
    hashes: list = field(default_factory=list)
    sizes: list = field(default_factory=list)
    mat_names: dict[str, str] = field(default_factory=dict)
    cond_names: dict[str, str] = field(default_factory=dict)
    notes: dict[str, None] = field(default_factory=dict)
    warnings: dict[str, None] = field(default_factory=dict)
    found: list = field(default_factory=list)


def _harvest_block(table, d: dict, h: _Harvest, spool_in: Spool) -> None:
    """Keep one block's compact arrays in ``h`` and spool its test ids and raw inputs, in pieces."""
    ids = table.columns["test_id"]
    for k in _COMPACT:
        h.keep[k].append(d[k])
    h.lines.append(table.lines.astype(np.int32))  # line numbers of a file below max_bytes fit
    h.mats.append(_interned(table.columns["material"], h.mat_names))
    h.conds.append(_interned(table.columns["condition"], h.cond_names))
    h.hashes.append(np.fromiter(map(hash, ids.tolist()), dtype=np.int64, count=len(ids)))
    spooled = {
        "test_id": ids,
        **{f"in_{name}": documented_column(table, name) for name in RAW_INPUTS if name in table.columns},
    }
    for lo in range(0, len(table), _SPOOL_ROWS):
        spool_in.append({k: v[lo : lo + _SPOOL_ROWS] for k, v in spooled.items()})
        h.sizes.append(min(_SPOOL_ROWS, len(table) - lo))
    h.notes.update(dict.fromkeys(table.notes))
    h.warnings.update(dict.fromkeys(table.warnings))


def _read_blocks(pending: list, blocks, opt: ShearOptions, spool_in: Spool) -> _Harvest:
    """Pass 1: read, check and derive each block, one block's cells in memory at a time."""
    import itertools

    h = _Harvest({k: [] for k in _COMPACT})

    def tables():
        while pending:
            yield pending.pop(0)  # the caller keeps no reference: one block's cells in memory at a time

    with task("reading tests, block by block") as advance_read:  # a bar on a terminal
        for table in itertools.chain(tables(), blocks):
            check_shear_table(table, unique=False)
            if "test_id" in table.columns:
                for i in np.flatnonzero(table.columns["test_id"] == ""):
                    table.add_problem(int(i), "test_id", "empty test_id")
            box = filled_column(table, "box_area", opt.box_area)
            with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
                d = derive_tests(table, opt, box)
            if table.problems:  # every block is read: the file's problems are reported at once
                h.found += table.problems
                del table, d, box
                advance_read()
                continue
            _harvest_block(table, d, h, spool_in)
            del table, d, box
            _trim()
            advance_read()
    return h


@dataclass
class _Gathered:
    """The blocks' arrays joined.

    Piece starts in the spools, line numbers, materials, conditions, the compact per-test arrays, and the problems of
    the whole table.
    """

    starts: np.ndarray
    lines: np.ndarray
    mat: np.ndarray
    cond: np.ndarray
    d: dict[str, np.ndarray]
    problems: _RowProblems


def _gather(h: _Harvest, path, sheet, headers: dict, spool_in: Spool) -> _Gathered:
    """Join the blocks' arrays (letting go of the per-block lists) and raise the problems of the whole table.

    Repeated test ids among the blocks included.
    """
    if h.found and not h.sizes:  # no block without problems
        from ..errors import InputError

        raise InputError(h.found)
    starts = np.concatenate([[0], np.cumsum(h.sizes)]).astype(np.int64)
    lines_all = np.concatenate(h.lines)
    mat, cond = np.concatenate(h.mats), np.concatenate(h.conds)
    h.lines = h.mats = h.conds = None
    d = {k: np.concatenate(v) for k, v in h.keep.items()}
    h.keep = None
    problems = _RowProblems(path, sheet, headers, lines_all, {"condition": cond, "material": mat})
    problems.problems += h.found  # with the repeated test ids among the blocks without problems
    _duplicate_ids(np.concatenate(h.hashes) if h.hashes else np.zeros(0, np.int64), spool_in, starts, problems)
    h.hashes = None
    _trim()
    problems.raise_if_problems()
    return _Gathered(starts, lines_all, mat, cond, d, problems)


def _fit_envelopes(g: _Gathered, materials: list, opt: ShearOptions, spool_in: Spool) -> tuple[dict, dict]:
    """The dry and saturated envelopes of every material.

    An outlier is named by its id, read back from the spool (as a whole table names it).
    """
    fits = fit_dry_envelopes(g.problems, g.d, g.mat, g.cond, materials, opt)
    saturated_fits = fit_saturated_envelopes(g.problems, g.d, g.mat, g.cond, materials, opt)
    g.problems.raise_if_problems()
    for fit in fits.values():
        diag = fit.diagnostics
        flagged = np.flatnonzero(np.asarray(diag.get("outlier", []), bool))
        if flagged.size and "rows" in diag:
            ids = np.full(len(diag["rows"]), None, dtype=object)
            ids[flagged] = _spooled(spool_in, g.starts, "test_id", np.asarray(diag["rows"][flagged], np.int64))
            diag["test_ids"] = ids
    return fits, saturated_fits


def _predict_by_piece(
    g: _Gathered, wet: np.ndarray, md, fits: dict, laws: dict, opt: ShearOptions, spool_out: Spool
) -> tuple[dict[str, Sampled], dict[str, np.ndarray]]:
    """Pass 2: every model's prediction piece by piece, spooled whole.

    Kept in memory at the sampled rows only (and every test's tau, for the scores).
    """
    d, starts = g.d, g.starts
    rows = _sample_rows(wet, g.mat, d["suction"], list(fits))
    n = int(starts[-1])
    taus = {m: np.empty(n) for m in opt.models}
    samples: dict[str, list] = {}
    for k in steps(range(len(starts) - 1), "predicting, piece by piece"):
        lo, hi = int(starts[k]), int(starts[k + 1])
        sl = slice(lo, hi)
        part = {name: d[name][sl] for name in ("sigma_N", "suction", "tau_max")}
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            preds, back = predict_models(part, wet[sl], md.subset(sl), fits, laws, opt)
            cols = {
                "chi1": np.where(wet[sl], ph.chi1(d["S_R"][sl]), 0.0),
                "chi2": np.where(wet[sl], ph.chi2(d["S_R"][sl], d["R"][sl], opt.surface_tension), 0.0),
                **_flat(preds),
                **_flat({"back": back}),
            }
        spool_out.append(cols)
        for m in opt.models:
            taus[m][lo:hi] = preds[m].si.tau
        here = rows[(rows >= lo) & (rows < hi)] - lo
        for key, v in cols.items():
            samples.setdefault(key, []).append(v[here])
        del preds, back, cols, part
        _trim()
    sampled = {key: Sampled(rows, np.concatenate(v), n) for key, v in samples.items()}
    return sampled, taus


def _bootstrap_and_forget_tests(
    result: ShearBlocks, tests, g: _Gathered, wet, fits: dict, saturated_fits: dict, fitted, opt: ShearOptions
) -> None:
    """The bootstrap of the model ranking (``--bootstrap``), on every test.

    Then ``result.model_inputs`` keeps the fitted laws and no tests.
    """
    d, mat, cond = g.d, g.mat, g.cond
    if opt.bootstrap > 0:
        result.model_inputs = dataclasses.replace(
            model_inputs_of(tests, wet, mat, fits, opt, saturated_fits), fitted=fitted
        )
        result.ranking = bootstrap_materials(result, wet, mat, cond, opt)
    none = {k: d[k][:0] for k in _COMPACT}
    result.model_inputs = dataclasses.replace(  # the fitted laws, no tests
        model_inputs_of(none, wet[:0], mat[:0], fits, opt, saturated_fits), fitted=fitted
    )


def run_blocks(source, opt: ShearOptions, pending: list, blocks) -> ShearBlocks:
    """`capred shear` on a table of several blocks (capred.io.blocks): memory flat in the number of tests.

    Pass 1 reads each block, checks and derives it, keeps the compact per-test arrays of ``_COMPACT`` (and the
    material and condition) and spools the test ids and raw inputs; then the dry fits and chi laws are fitted on
    every test. Pass 2 predicts block by block and spools every per-test output; the writer reads both spools
    back block by block. Outputs are those of the whole-table run, byte for byte.

    Parameters
    ----------
    source : str, Path or capred.io.grid.TableSource
        The long table.
    opt : ShearOptions
        The run's options.
    pending : list of capred.io.Table
        The first two blocks, already read (let go of as they are used).
    blocks : iterator of capred.io.Table
        The blocks that follow (capred.io.blocks.read_table_blocks).

    Returns
    -------
    ShearBlocks
        The run, its per-test outputs spooled on disk.
    """
    from . import shear_analysis as sa

    first = pending[0]
    inputs = [input_file(source, first)]
    path, sheet, headers = first.path, first.sheet, dict(first.headers)
    del first
    spool_in, spool_out = Spool(), Spool()
    try:
        h = _read_blocks(pending, blocks, opt, spool_in)
        g = _gather(h, path, sheet, headers, spool_in)
        d, mat, cond = g.d, g.mat, g.cond
        materials = list(h.mat_names)
        wet = cond == "wet"
        fits, saturated_fits = _fit_envelopes(g, materials, opt, spool_in)

        tests = _LongTests({"material": mat, "condition": cond, "line": g.lines, **d})
        md = model_inputs_of(tests, wet, mat, fits, opt, saturated_fits)
        laws = sa.fit_laws(md, opt.models, list(fits), opt.model_params, fits=fits)
        md = dataclasses.replace(
            md, fitted={model: {m: law.values for m, law in by_mat.items()} for model, by_mat in laws.items()}
        )
        per_material = values_by_material(md, wet, mat, fits, opt)
        sampled, taus = _predict_by_piece(g, wet, md, fits, laws, opt, spool_out)
        predictions = {m: _record(ModelPrediction, m, {**sampled, f"{m}|tau": taus[m]}, model=m) for m in opt.models}
        back = _record(BackAnalysis, "back", sampled)
        fitted = md.fitted
        del md  # its per-test envelope arrays: made again for the bootstrap, after the predictions go
        _trim()
        scored = score_models(d, wet, mat, fits, laws, predictions, opt)
        result = ShearBlocks(
            source=path,
            options=opt,
            tests=tests,
            fits=envelope_fits(fits, path),
            metrics=scored["metrics"],
            metrics_overall=scored["overall"],
            best_model={m: best_of(v) for m, v in scored["metrics"].items()},
            best_model_overall=best_of(scored["overall"]),
            notes=opt.notes + list(h.notes),
            per_material=per_material,
            inputs=inputs,
            warnings=list(opt.warnings) + list(h.warnings) + scored["warnings"],
            metrics_pendular=scored["pendular"],
            metrics_pendular_overall=scored["overall_pendular"],
            laws=laws,
            model_inputs=None,
            curves=None,
            predictions=predictions,
            back=back,
            saturated_fits=saturated_fits,
            heteroscedasticity=scored["heteroscedasticity"],
            spool_in=spool_in,
            spool_out=spool_out,
            starts=g.starts,
        )
        tests.result = result
        # what needs every test's prediction, made now; then the predictions are kept at the sampled rows only
        code, names = ShearResult._flag_codes(result)
        result.__dict__["_flag_code"] = (code.astype(np.uint8 if len(names) <= 256 else np.int64), names)
        result.model_selection()
        result.predictions = {m: p.replace(tau=sampled[f"{m}|tau"]) for m, p in predictions.items()}
        del predictions, taus
        _trim()
        _bootstrap_and_forget_tests(result, tests, g, wet, fits, saturated_fits, fitted, opt)
        _trim()
        return result
    except BaseException:
        spool_in.close()
        spool_out.close()
        raise


def _duplicate_ids(hashes: np.ndarray, spool: Spool, starts: np.ndarray, problems: _RowProblems) -> None:
    """Repeated test ids of a long table (as Table.check_unique words them).

    Found by their hashes and confirmed on the ids themselves, read back from the spool (no Python str per test held at
    once).
    """
    sorted_h = np.sort(hashes)
    repeated = np.unique(sorted_h[1:][sorted_h[1:] == sorted_h[:-1]])
    del sorted_h
    if not repeated.size:
        return
    rows = np.flatnonzero(np.isin(hashes, repeated))
    seen: dict[str, int] = {}
    for i, v in zip(rows.tolist(), _spooled(spool, starts, "test_id", rows)):
        if v in seen:
            problems.add_problem(i, "test_id", f"duplicate test_id '{v}' (first on line {seen[v]})", v)
        else:
            seen[v] = int(problems.lines[i])


def _spooled(spool: Spool, starts: np.ndarray, key: str, rows: np.ndarray) -> list:
    """The values of one spooled column at ``rows`` (increasing row numbers)."""
    out: list = []
    for k in range(len(starts) - 1):
        lo, hi = starts[k], starts[k + 1]
        here = rows[(rows >= lo) & (rows < hi)]
        if here.size:
            out += spool.block(k)[key][here - lo].tolist()
    return out


class _LongTests(dict):
    """``ShearBlocks.tests``: the compact per-test arrays in memory.

    Any other column (test_id, the raw inputs, chi1, chi2) is read back from the spools, whole, when asked for.
    """

    result = None

    def __missing__(self, key):
        r = self.result
        if r is None:
            raise KeyError(key)
        if key in ("chi1", "chi2"):
            spool = r.spool_out
        elif key in r.spool_in.block(0):
            spool = r.spool_in
        else:
            raise KeyError(key)
        return np.concatenate([b[key] for b in spool.blocks()])


class _ResultsBlocks:
    """results.csv of a long run for capred.io.writers.write_csv_file.

    ``blocks()`` gives each block's columns, made from the spools one block at a time; ``columns(start, stop)`` as a
    Spool's.
    """

    def __init__(self, result: ShearBlocks):
        self.result = result
        self.n = int(result.starts[-1])

    def blocks(self):
        for k in range(len(self.result.starts) - 1):
            yield self.result._block(k)._results_columns()

    def columns(self, start: int, stop: int):
        """Every column of rows start..stop-1; more than one block's rows: columns made when looked up."""
        if stop - start > int(np.max(np.diff(self.result.starts))):
            return _LazyColumns(self.result, start, stop)
        return self.result._columns(start, stop)


class _LazyColumns(dict):
    """Columns of many rows of a long run, each made only when looked up (``flags`` from memory)."""

    def __init__(self, result, start: int, stop: int):
        super().__init__(dict.fromkeys(result._block(0)._results_columns()))
        self.result, self.start, self.stop = result, start, stop

    def __getitem__(self, key):
        if key not in self:
            raise KeyError(key)
        if key == "flags":
            return np.asarray(self.result._flag_texts()[self.start : self.stop], dtype=object)
        return self.result._columns(self.start, self.stop, key)[key]

    def items(self):
        return ((k, self[k]) for k in self)

    def values(self):
        return (self[k] for k in self)


@dataclass(repr=False)
class ShearBlocks(ShearResult):
    """The result of `capred shear` on a long table (several blocks of capred.io.blocks).

    A ShearResult whose per-test outputs stay on disk.

    In memory, for every test: ``tests`` sigma_N, suction, S_R, tau_max, R, material, condition, line, and
    a flag code. Every per-test array of ``predictions`` and ``back`` is a
    :class:`capred.pipelines.shear_records.Sampled`: kept at the rows the figures and console tables show;
    ``model_inputs`` holds the fitted laws and no tests; ``tests["test_id"]`` and the raw inputs are read back whole
    when asked for, ``table()`` builds the whole DataFrame. results.csv and the JSON are written block by
    block from the spools, the same bytes as the whole-table run.
    """

    spool_in: object = None  # Spool: test_id and the raw inputs of each block
    spool_out: object = None  # Spool: chi1, chi2, every model's prediction and the back-analysis of each block
    starts: np.ndarray | None = None  # first row of each block, and the number of tests last

    def _block(self, k: int) -> ShearResult:
        """Block ``k`` as a ShearResult of its own tests (what _results_columns and _test_rows read)."""
        cached = self.__dict__.get("_block_cache")
        if cached is not None and cached[0] == k:
            return cached[1]
        if cached is not None:  # the block before goes first (the writer and the JSON child read in order)
            del self.__dict__["_block_cache"], cached
            _trim()
        lo, hi = int(self.starts[k]), int(self.starts[k + 1])
        a, b = self.spool_in.block(k), self.spool_out.block(k)
        t = self.tests
        tests = {
            "test_id": a["test_id"],
            "material": t["material"][lo:hi],
            "condition": t["condition"][lo:hi],
            "line": t["line"][lo:hi],
            **{key: v for key, v in a.items() if key != "test_id"},
            **{key: t[key][lo:hi] for key in _COMPACT},
            "chi1": b["chi1"],
            "chi2": b["chi2"],
        }
        part = ShearResult(
            source=self.source,
            options=self.options,
            tests=tests,
            fits=self.fits,
            metrics={},
            metrics_overall={},
            best_model={},
            best_model_overall=None,
            predictions={m: _record(ModelPrediction, m, b, model=m) for m in self.models},
            back=_record(BackAnalysis, "back", b),
        )
        # the flags of its rows from the whole run's (a dry outlier's row is a row of the whole table)
        code, names = self._flag_codes()
        part.__dict__["_flags"] = list(names[code[lo:hi]])
        self.__dict__["_block_cache"] = (k, part)
        return part

    def _columns(self, start: int, stop: int, key: str | None = None) -> dict:
        """results.csv columns (or one) of rows start..stop-1, across blocks."""
        parts = []
        for k in range(len(self.starts) - 1):
            lo, hi = int(self.starts[k]), int(self.starts[k + 1])
            a, b = max(start, lo), min(stop, hi)
            if a < b:
                cols = self._block(k)._results_columns()
                parts.append({name: v[a - lo : b - lo] for name, v in cols.items() if key is None or name == key})
        if len(parts) == 1:
            return parts[0]
        return {name: np.concatenate([p[name] for p in parts]) for name in parts[0]} if parts else {}

    def _test_rows(self, start: int, stop: int) -> list[dict]:
        rows: list[dict] = []
        for k in range(len(self.starts) - 1):
            lo, hi = int(self.starts[k]), int(self.starts[k + 1])
            a, b = max(start, lo), min(stop, hi)
            if a < b:
                rows += self._block(k)._test_rows(a - lo, b - lo)
        return rows

    def test_ids(self, rows) -> list[str]:
        """The test_id of each of ``rows``, read back from the spooled inputs.

        Parameters
        ----------
        rows : array_like of int
            Row numbers (0-based, over all blocks).

        Returns
        -------
        list of str
            The test ids.
        """
        return [str(x) for x in _spooled(self.spool_in, self.starts, "test_id", np.asarray(rows, dtype=np.int64))]

    def _flag_codes(self) -> tuple[np.ndarray, np.ndarray]:
        return self.__dict__["_flag_code"]

    def _flag_texts(self) -> np.ndarray:
        """Flags of every test, ';'-joined (an object array made on each call: nothing per test is kept)."""
        code, names = self._flag_codes()
        return names[code]

    def row_count(self) -> int:
        """Number of tests of the run, over all blocks.

        Returns
        -------
        int
            The count [-].
        """
        return int(self.starts[-1])

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them, under ``name [unit]`` headers.

        ``results`` written block by block, ``summary`` and ``metrics``.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        cached = self.__dict__.get("_csv_tables")
        if cached is None:
            cached = self.__dict__["_csv_tables"] = {
                "results": _ResultsBlocks(self),
                "summary": summary_table(self, frame=False),
                "metrics": metrics_table(self, frame=False),
            }
        return cached

    def tables(self) -> dict:
        """Output tables: ``results`` (every test, in memory: for tables.xlsx or a script) and ``summary``.

        Returns
        -------
        dict of str to pandas.DataFrame
        """
        cached = self.__dict__.get("_tables")
        if cached is None:
            import pandas as pd

            cached = self.__dict__["_tables"] = {
                "results": pd.DataFrame(self._columns(0, self.row_count()), copy=False),
                "summary": summary_table(self),
                "metrics": metrics_table(self),
            }
        return cached

    def close(self) -> None:
        """Remove the spool files now (they also go when the result is garbage collected)."""
        self.spool_in.close()
        self.spool_out.close()
