"""`capred history`: one quantity of one material across the runs of a lab's store, on a control chart.

The individuals chart with moving range (Shewhart; Montgomery 2013, section 6.4):
moving ranges ``MR_i = |x_i - x_(i-1)|``; the centre line and the spread come
from the first ``baseline`` runs (8 by default), ``sigma = mean(MR) / d2`` with
``d2 = 1.128`` (subgroups of two), limits ``centre +- 3 sigma``; the moving-range
chart has centre ``mean(MR)`` and upper limit ``D4 mean(MR)``, ``D4 = 3.267``.
A reference value and spread (sigma) the user gives replace the baseline.
Runs beyond the limits are flagged (warnings, JSON, table, figure).

References
----------
D. C. Montgomery (2013), Introduction to Statistical Quality Control, 7th ed., Wiley, section 6.4
(individuals and moving-range charts; d2 = 1.128, D4 = 3.267 for n = 2).
ISO 7870-2:2013, Control charts - Part 2: Shewhart control charts.
ISO/IEC 17025:2017, clause 7.7 (monitoring the validity of results).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError, OptionError, Problem
from ..result import InputFile, Options, Result, input_file, num, output
from ..spec.history import HistoryOptions  # noqa: F401 (declared in spec; re-exported here)
from .row_records import RowRecord, plain

#: control-chart constants for moving ranges of two consecutive values (Montgomery 2013, Appendix VI)
D2 = 1.128
D4 = 3.267


@dataclass(frozen=True)
class ControlLimits:
    """Limits of an individuals chart and its moving-range chart (values in the quantity's unit).

    Attributes
    ----------
    centre, sigma, lcl, ucl : float
        Centre line, process standard deviation, lower and upper control limits (centre -+ 3 sigma).
    mr_centre, mr_ucl : float
        Centre line and upper control limit of the moving-range chart (``D4 mr_centre``).
    basis : str
        Where the limits come from (the first n runs, or the user's reference value and spread).
    """

    centre: float
    sigma: float
    lcl: float
    ucl: float
    mr_centre: float
    mr_ucl: float
    basis: str


def individuals_chart(values, baseline: int = 8, reference: float | None = None, spread: float | None = None):
    """Individuals and moving-range chart of ``values`` in run order.

    Parameters
    ----------
    values : array_like
        The quantity per run, in run order (finite).
    baseline : int
        Number of first runs that set the centre line and sigma (>= 2); ignored with ``reference``.
    reference, spread : float, optional
        A reference value and its standard deviation (both or neither), in the values' unit.

    Returns
    -------
    limits : ControlLimits
    moving_range : ndarray
        ``|x_i - x_(i-1)|``, NaN for the first run.
    beyond : ndarray of bool
        Runs outside ``[lcl, ucl]``.
    mr_beyond : ndarray of bool
        Runs whose moving range exceeds ``mr_ucl``.

    Raises
    ------
    OptionError
        Only one of reference and spread, a spread <= 0, or fewer than 2 runs to set the limits.

    References
    ----------
    Montgomery (2013), section 6.4, eqs. 6.33-6.34 (sigma = MR-bar / d2; limits x-bar -+ 3 MR-bar / d2).
    """
    x = np.asarray(values, float)
    mr = np.full(x.size, np.nan)
    if x.size > 1:
        mr[1:] = np.abs(np.diff(x))
    if (reference is None) != (spread is None):
        raise OptionError(
            "give both --reference and --spread (the reference value and its standard deviation), or neither"
        )
    if reference is not None:
        if not spread > 0:
            raise OptionError(f"--spread (the reference standard deviation) must be > 0 (got {spread})")
        centre, sigma = float(reference), float(spread)
        mr_centre = D2 * sigma
        basis = f"reference value {reference:g} and standard deviation {spread:g} given by the user"
    else:
        if baseline < 2:
            raise OptionError(f"--baseline must be at least 2 runs (got {baseline})")
        n = min(baseline, x.size)
        if n < 2:
            raise OptionError("a control chart needs at least 2 runs to set its limits (or --reference and --spread)")
        centre = float(np.mean(x[:n]))
        mr_centre = float(np.mean(mr[1:n]))
        sigma = mr_centre / D2
        basis = f"the first {n} runs (sigma = mean moving range / {D2})"
    limits = ControlLimits(centre, sigma, centre - 3 * sigma, centre + 3 * sigma, mr_centre, D4 * mr_centre, basis)
    beyond = (x < limits.lcl) | (x > limits.ucl)
    mr_beyond = np.nan_to_num(mr, nan=0.0) > limits.mr_ucl
    return limits, mr, beyond, mr_beyond


@dataclass(frozen=True)
class HistoryRecord(RowRecord):
    """``capred history``: one row per recorded run, the charted quantity in its own unit (``unit``).

    Attributes
    ----------
    unit : str
        Unit of the charted quantity ("-" for a dimensionless one); the unit of value, ci_low, ci_high and
        moving_range.
    run : ndarray of int
        The run's id in the store.
    test_date, input : list of str
        Test date and input file of the run.
    value : ndarray
        The quantity [unit].
    ci_low, ci_high : ndarray
        Its 95 % interval [unit] (NaN where the run has none).
    moving_range : ndarray
        |value − previous value| [unit] (NaN at the first run).
    beyond_limits, mr_beyond_limit : ndarray of bool
        The value beyond the control limits; the moving range beyond its upper limit.

    References
    ----------
    .. [1] Montgomery, D. C. (2013). Introduction to Statistical Quality Control, 7th ed. Wiley, section 6.4.
    """

    unit: str = "-"
    run: np.ndarray = plain("run")
    test_date: list = plain("test_date")
    input: list = plain("input")
    value: np.ndarray = output("value", "value", "{unit}")
    ci_low: np.ndarray = output("ci_low", "ci_low", "{unit}")
    ci_high: np.ndarray = output("ci_high", "ci_high", "{unit}")
    moving_range: np.ndarray = output("moving_range", "moving_range", "{unit}")
    beyond_limits: np.ndarray = plain("beyond_limits")
    mr_beyond_limit: np.ndarray = plain("mr_beyond_limit")

    @property
    def unit_fill(self) -> str:  # the declared "{unit}" is the charted quantity's unit
        """The unit that fills the declared ``{unit}`` of the columns: the charted quantity's ("" when dimensionless)."""
        return "" if self.unit == "-" else self.unit


@dataclass(repr=False)
class HistoryResult(Result):
    """One quantity of one material per run of a store, with its control chart."""

    material: str | None
    quantity: str
    unit: str
    runs: dict[str, np.ndarray]  # run, test_date, input, value, ci_low, ci_high, moving_range, beyond, mr_beyond
    limits: ControlLimits
    baseline_runs: int
    options: Options | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    command = "history"
    json_name = "history.json"

    @property
    def flagged(self) -> list[int]:
        """Ids of the runs beyond the control limits."""
        return [int(r) for r, b in zip(self.runs["run"], self.runs["beyond"]) if b]

    def record(self) -> HistoryRecord:
        """The runs as a typed record.

        Run id, test date, input, the value with its 95 % interval and moving range in the quantity's unit, and the two
        flags.

        Returns
        -------
        HistoryRecord
            One value per run (``record.unit``: the quantity's unit).

        References
        ----------
        .. [1] Montgomery, D. C. (2013). Introduction to Statistical Quality Control, 7th ed. Wiley, section 6.4.
        """
        r = self.runs
        return HistoryRecord(
            unit=self.unit,
            run=np.asarray(r["run"], int),
            test_date=list(r["test_date"]),
            input=list(r["input"]),
            value=np.asarray(r["value"], float),
            ci_low=np.asarray(r["ci_low"], float),
            ci_high=np.asarray(r["ci_high"], float),
            moving_range=np.asarray(r["moving_range"], float),
            beyond_limits=np.asarray(r["beyond"], bool),
            mr_beyond_limit=np.asarray(r["mr_beyond"], bool),
        )

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        :meth:`record` as rows: per run, run id, test date, input, value with its 95 % interval, moving range,
        beyond_limits.

        Returns
        -------
        list of dict
            One dict per row, under the JSON keys.
        """
        return self.record().json_rows()

    def store_rows(self, material: str | None = None) -> list:
        """Refused: a history run reads a store and is never recorded in one.

        Parameters
        ----------
        material : str or None, optional
            The material of the inputs' metadata block (unused).

        Raises
        ------
        ValueError
            Always.
        """
        raise ValueError("`capred history` reads a lab store; its runs are not recorded in one")

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        Material, quantity, unit, the control limits (centre, sigma, lcl, ucl, moving-range centre) and the runs.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        lim = self.limits
        return {
            "material": self.material,
            "quantity": self.quantity,
            "unit": self.unit,
            "limits": {
                "centre": num(lim.centre),
                "sigma": num(lim.sigma),
                "lcl": num(lim.lcl),
                "ucl": num(lim.ucl),
                "mr_centre": num(lim.mr_centre),
                "mr_ucl": num(lim.mr_ucl),
                "basis": lim.basis,
            },
            "flagged_runs": self.flagged,
            "runs": self.rows(),
        }

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``history``: one row per run).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        import pandas as pd

        return {"history": pd.DataFrame(self.record().columns())}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them (``history``).

        Under ``name [unit]`` headers (the unit of the charted quantity).

        Returns
        -------
        dict
            Stem -> DataFrame.
        """
        import pandas as pd

        return {"history": pd.DataFrame(self.record().csv_columns())}


#: at most this many names in a message; the rest are counted and the way to list them all is named
SHOWN = 30


def _names(path, column: str, quantity=None, command=None) -> str:
    """The materials or quantities the store holds (filtered by quantity and command), as a message says them.

    At most :data:`SHOWN` of them, the rest counted with the way to list them all; "none" where it holds none.
    """
    from ..lab_store import count_present, present

    held = present(path, column, quantity, command, limit=SHOWN)
    total = count_present(path, column, quantity, command) if len(held) == SHOWN else len(held)
    if not held:
        return "none"
    text = ", ".join(held)
    if total > len(held):
        args = ", ".join([repr(str(path)), repr(column)] + [f"{k}={v!r}" for k, v in (("quantity", quantity),
                         ("command", command)) if v is not None])  # fmt: skip
        text += (
            f' and {total - len(held)} more (list them all: python -c "from capred.lab_store import present; '
            f"print(*present({args}, limit=None), sep='\\n')\")"
        )
    return text


def _runs(command) -> str:
    return f"`{command}` run" if command is not None else "run"


def _explain_empty(path, opt: HistoryOptions) -> None:
    """Raise the error that says why the store holds no record asked for.

    No record of ``opt.quantity`` (of ``opt.material``, of runs of ``opt.command``): the message says what the
    filtered runs hold, and what the store holds overall.
    """
    from ..lab_store import commands_present, history, present

    def fail(message: str):
        raise InputError(Problem(str(path), None, None, message))

    if not present(path, "quantity", limit=1):
        fail("this store holds no runs yet")
    if opt.command is not None and not present(path, "quantity", command=opt.command, limit=1):
        fail(f"no `{opt.command}` run is recorded in this store; it holds runs of: {', '.join(commands_present(path))}")
    scope = f"the `{opt.command}` runs" if opt.command is not None else "this store"
    if not present(path, "quantity", opt.quantity, opt.command, limit=1):
        overall = f"; the whole store holds: {_names(path, 'quantity')}" if opt.command is not None else ""
        fail(
            f"no {_runs(opt.command)} records quantity '{opt.quantity}'; {scope} hold"
            f"{'s' if opt.command is None else ''} the quantities: {_names(path, 'quantity', command=opt.command)}{overall}"
        )
    held = _names(path, "material", opt.quantity, opt.command)
    unnamed = history(path, quantity=opt.quantity, command=opt.command)["material"].isna().any()
    record = "records" if opt.command is None else "record"
    if held == "none":  # the quantity is recorded, but only without a material
        what = f"{scope} {record} it only without a material (leave out --material to chart it)"
    else:
        what = f"{scope} {record} it for the materials: {held}" + (
            ", and without a material (leave out --material to chart those)" if unnamed else ""
        )
    fail(
        f"no {_runs(opt.command)} records '{opt.quantity}' of material '{opt.material}'; {what}; the whole store "
        f"holds the materials: {_names(path, 'material')}"
    )


def _choose(materials: list, path, opt: HistoryOptions) -> str:
    """The material to chart: ``opt.material``, else the only one the records hold, else an error."""
    if opt.material is not None:
        return opt.material
    if len(materials) == 1:
        return str(materials[0])
    raise OptionError(
        f"--material is needed: the {_runs(opt.command)}s record '{opt.quantity}' for "
        f"{_names(path, 'material', opt.quantity, opt.command)}"
    )


def reduce_history(source, opt: HistoryOptions) -> HistoryResult:
    """The control chart of ``opt.quantity`` of ``opt.material`` over the runs of the store ``source``.

    Parameters
    ----------
    source : str or Path
        The store (``--store`` of the commands).
    opt : HistoryOptions

    Returns
    -------
    HistoryResult

    Raises
    ------
    InputError
        Not a capred store, or no such material or quantity in it.
    OptionError
        The quantity (or material) is needed to choose among several.

    References
    ----------
    Montgomery (2013), section 6.4; ISO/IEC 17025:2017, clause 7.7.
    """
    from ..lab_store import history, present

    path = getattr(source, "path", source)
    # the store is filtered in SQL: only the records of the quantity (and material) asked are read
    if opt.quantity is None:
        if not present(path, "quantity", limit=1):
            raise InputError(Problem(str(path), None, None, "this store holds no runs yet"))
        if opt.command is not None and not present(path, "quantity", command=opt.command, limit=1):
            _explain_empty(path, opt)
        raise OptionError(
            f"--quantity is needed: the {_runs(opt.command)}s of this store hold "
            + _names(path, "quantity", command=opt.command)
        )
    q = history(path, quantity=opt.quantity, command=opt.command, material=opt.material)
    if q.empty:
        _explain_empty(path, opt)
    materials = present(path, "material", opt.quantity, opt.command, limit=2) if opt.material is None else []
    material = _choose(materials, path, opt) if q["material"].notna().any() else None
    rows = q[q["material"] == material] if material is not None else q[q["material"].isna()]
    notes = []
    dup = rows["run"].duplicated()
    if dup.any():
        notes.append(f"{int(dup.sum())} runs gave '{opt.quantity}' more than once: the first value of each is charted")
        rows = rows[~dup]
    missing = ~np.isfinite(rows["value"].to_numpy(float))
    if missing.any():
        notes.append(
            f"{int(missing.sum())} runs have no value of '{opt.quantity}' (runs "
            f"{', '.join(str(r) for r in rows['run'][missing])}): they are listed but not charted"
        )
        rows = rows[~missing]
    import pandas as pd

    dates = pd.to_datetime(rows["test_date"], errors="coerce", format="mixed")
    if dates.notna().all():  # the chart's order is the order of the tests
        rows = rows.assign(_d=dates).sort_values(["_d", "run"], kind="stable").drop(columns="_d")
        order = "test date (the inputs' metadata 'date', else the day recorded), then order recorded"
    else:
        order = "order recorded (some test dates are not dates)"
    notes.append(f"runs in order of {order}")
    x = rows["value"].to_numpy(float)
    limits, mr, beyond, mr_beyond = individuals_chart(x, opt.baseline, opt.reference, opt.spread)
    warnings: list[str] = []
    unit = _chart_unit(rows, opt.quantity, warnings)
    runs = {
        "run": rows["run"].to_numpy(int),
        "test_date": [str(d) for d in rows["test_date"]],
        "input": [str(p) for p in rows["input"]],
        "value": x,
        "ci_low": rows["ci_low"].to_numpy(float),
        "ci_high": rows["ci_high"].to_numpy(float),
        "moving_range": mr,
        "beyond": beyond,
        "mr_beyond": mr_beyond,
    }
    n_base = min(opt.baseline, x.size) if opt.reference is None else 0
    if opt.reference is None and x.size < opt.baseline:
        warnings.append(f"the limits rest on {x.size} runs only (the chart asks for {opt.baseline})")
    label = f"{opt.quantity}" + (f" of {material}" if material is not None else "")
    if "sha256" in rows:  # the same file reduced again (other options): one measurement charted twice
        sha = rows["sha256"].astype(str).to_numpy()
        for digest in dict.fromkeys(d for d in sha[pd.Series(sha).duplicated().to_numpy()] if d not in ("", "None")):
            same = rows["run"].to_numpy(int)[sha == digest]
            warnings.append(
                f"runs {', '.join(map(str, same))} reduce the same input ({rows['input'].to_numpy()[sha == digest][0]}, "
                f"sha256 {digest[:12]}…): one measurement charted {len(same)} times, which shrinks the moving range "
                "and the limits"
            )
    for i in np.flatnonzero(beyond):
        side = "above the upper" if x[i] > limits.ucl else "below the lower"
        bound = limits.ucl if x[i] > limits.ucl else limits.lcl
        warnings.append(
            f"run {runs['run'][i]} ({runs['test_date'][i]}, {runs['input'][i]}): {label} = {x[i]:.4g} {unit} lies "
            f"{side} control limit {bound:.4g} {unit}"
        )
    for i in np.flatnonzero(mr_beyond & ~beyond):
        warnings.append(
            f"run {runs['run'][i]} ({runs['test_date'][i]}): the moving range {mr[i]:.4g} {unit} exceeds its "
            f"control limit {limits.mr_ucl:.4g} {unit}"
        )
    return HistoryResult(
        material,
        opt.quantity,
        unit,
        runs,
        limits,
        n_base,
        opt,
        [input_file(path)],
        opt.warnings + warnings,
        notes,
    )


def _chart_unit(rows, quantity: str, warnings: list) -> str:
    """The unit of the charted runs, as the store recorded it from each run's declarations.

    A unit is never inferred from the quantity's name: runs recorded without one (a store written by an older
    capred, or a command that declares none) and runs that disagree are named in a warning; the chart then
    takes the latest run's unit ("?" where no run has one).
    """
    units = [None if u is None or (isinstance(u, float) and u != u) else str(u) for u in rows["unit"]]
    if not units:
        return "-"
    known = [u for u in units if u is not None]
    latest = max(zip(rows["run"], units), key=lambda t: int(t[0]))[1]
    if len(known) < len(units):
        warnings.append(
            f"{len(units) - len(known)} runs recorded '{quantity}' without a declared unit (an older capred or a "
            "command that declares none): their values are charted as recorded"
        )
    if len(set(known)) > 1:
        warnings.append(
            f"the runs recorded '{quantity}' in different units ({', '.join(sorted(set(known)))}): the chart takes "
            f"'{latest or known[-1]}' of the latest run; the values are charted as recorded (an older capred read "
            "some units from a key's spelling)"
        )
    return latest or (known[-1] if known else "?")


def run_history(store, material=None, quantity=None, baseline=8, reference=None, spread=None) -> HistoryResult:
    """The control chart of one quantity of one material across the runs of a store (see reduce_history).

    Parameters
    ----------
    store : str or Path
        The store's file.
    material : str, optional
        The material (needed when the store holds several for the quantity).
    quantity : str
        A JSON key of the runs' documents, e.g. ``phi_deg`` (shear).
    baseline : int
        First runs that set the limits.
    reference, spread : float, optional
        Reference value and standard deviation, in the quantity's unit, instead of the baseline.

    Returns
    -------
    HistoryResult
    """
    return reduce_history(store, HistoryOptions(material, quantity, baseline, reference, spread))
