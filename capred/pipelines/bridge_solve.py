"""`capred bridge solve` on one table: its columns, options, result record, and the solver.

The solver is spread over the processes the run may use. capred.pipelines.bridge (the commands) and
capred.pipelines.bridge_blocks (a long file block by block) both build on it; it imports neither.
"""

from __future__ import annotations

import pickle
from dataclasses import dataclass, field
from itertools import repeat

import numpy as np

from ..io import Table, read_table
from ..physics import bridge as br
from ..records import per_case_store_rows
from ..result import InputFile, Result, Rows, json_list, num
from ..result import csv_header as result_csv_header
from ..spec.bridge import ANGLE, ANGLE2, CASE, GAMMA, RADIUS, RADIUS2, SOLVE_SCHEMA, VOLUME, BridgeOptions  # noqa: F401 (declared in spec; re-exported here)
from .bridge_records import BridgeRecord

# 1: the gap is too wide for this suction or volume; 3: so much water that the bridge would be
# convex (water above air pressure), outside the pendular model
STATUS = {
    0: "ok",
    1: "no bridge: beyond rupture",
    2: "invalid input",
    3: "no concave bridge: too much water",
    4: "no bridge found: the solution did not reproduce the requested gap and volume (or suction) to 1e-9",
}
#: every bridge reported ok reproduces the requested gap and volume (or suction) to this relative tolerance
VERIFY_RTOL = br.VERIFY_RTOL


@dataclass(repr=False)
class BridgeResult(Result):
    """Bridges, one per case, SI inside; tables and JSON in mm, mN, kPa."""

    command = "bridge solve"
    json_name = "solve.json"

    source: str
    #: per case, SI: R and R2/R ratio [m, -], gamma [N/m], contact_angle_rad [rad], gap [m]
    inputs_si: dict[str, np.ndarray]
    beta: np.ndarray  # filling angle on particle 1 [rad]
    suction: np.ndarray  # Pa
    shape: br.Bridge  # dimensionless, units of R and gamma
    status: np.ndarray
    note: list[str]
    labels: list[str] | None = None
    notes: list[str] = field(default_factory=list)
    options: BridgeOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def volume(self) -> np.ndarray:
        """Water volume [m^3]."""
        return self.shape.volume * self.inputs_si["R"] ** 3

    @property
    def force(self) -> np.ndarray:
        """Capillary force [N]."""
        return self.shape.force * np.pi * self.inputs_si["gamma"] * self.inputs_si["R"]

    @property
    def neck(self) -> np.ndarray:
        """Neck radius r0 [m] (a virtual neck, behind one contact, when the meridian widens across the bridge)."""
        return self.shape.neck * self.inputs_si["R"]

    def record(self) -> BridgeRecord:
        """The bridges as a typed record in output units (mm, mN, mm^3, mm^2, deg, kPa).

        NaN where no bridge was found.

        S_R = 3 V_w / (2 pi R^3) and sigma' = F / (pi R^2) are the unit cell of the particle of radius R
        (Evenepoel's thesis); nn11 = nn22 and nn33 are the transverse and axial components of the
        integral of n (x) n over the liquid-gas interface (area = 2 nn11 + nn33).

        Returns
        -------
        BridgeRecord
            One array per output quantity, one value per row.
        """
        R, g = self.inputs_si["R"], self.inputs_si["gamma"]
        ok = self.status == 0
        b = self.shape

        def out(x):
            return np.where(ok, x, np.nan)

        return BridgeRecord(
            r0=out(self.neck * 1e3),
            F_cap=out(self.force * 1e3),
            F_L=out(np.pi * self.neck**2 * self.suction * 1e3),
            F_T=out(2 * np.pi * self.neck * g * 1e3),
            V_w=out(self.volume * 1e9),
            filling_angle=out(np.degrees(self.beta)),
            filling_angle2=out(np.degrees(b.delta2)),
            suction=out(self.suction / 1e3),
            S_R=out(3 * self.volume / (2 * np.pi * R**3)),
            sigma_prime=out(self.force / (np.pi * R**2) / 1e3),
            area=out(b.area * R**2 * 1e6),
            nn11=out(b.nn11 * R**2 * 1e6),
            nn33=out(b.nn33 * R**2 * 1e6),
        )

    def columns(self) -> dict[str, np.ndarray]:
        """Output columns under their JSON keys (:meth:`record`, :meth:`BridgeRecord.columns`).

        Returns
        -------
        dict of str to numpy.ndarray
            JSON key -> values per row, in output units (mm, mN, mm^3, mm^2, deg, kPa).
        """
        return self.record().columns()

    @staticmethod
    def status_text(code: int) -> str:
        """The meaning of a bridge's status code.

        Parameters
        ----------
        code : int
            A status of the ``status`` column (0 to 4).

        Returns
        -------
        str
            Its text in ``STATUS`` ("ok", "no bridge: beyond rupture", ...).
        """
        return STATUS[int(code)]

    def _cols(self) -> dict:
        """Every output column (arrays; text as object arrays), computed once."""
        cached = self.__dict__.get("_cols_cache")
        if cached is None:
            cached = ({"case": np.asarray(self.labels, dtype=object)} if self.labels else {}) | self.columns()
            cached["status"] = np.array([STATUS[k] for k in range(len(STATUS))], dtype=object)[self.status.astype(int)]
            cached["note"] = np.asarray(self.note, dtype=object)
            self.__dict__["_cols_cache"] = cached
        return cached

    def _frame(self):
        import pandas as pd

        return pd.DataFrame(self._cols(), copy=False)

    def rows_range(self, start: int, stop: int) -> list[dict]:
        """JSON rows start..stop (NaN as None, an empty note left out), built column by column.

        Parameters
        ----------
        start, stop : int
            First row and one past the last row (0-based) [-].

        Returns
        -------
        list of dict
            The JSON rows.
        """
        return json_rows(self._cols_range(start, stop))

    def _cols_range(self, start: int, stop: int) -> dict:
        return {k: v[start:stop] for k, v in self._cols().items()}

    def rows(self) -> list[dict]:
        """The per-row records of the JSON document, NaN written as None.

        Every bridge: inputs, r0, forces, V_w, filling angles, area, S_R, sigma', status.

        Returns
        -------
        list of dict
            One dict per row, JSON keys with units in their suffix.
        """
        return self.rows_range(0, self.status.size)

    def row_context(self, start: int, stop: int) -> dict[str, np.ndarray]:
        """What names rows start..stop in a table, and where a row beyond rupture would have had a bridge.

        Parameters
        ----------
        start, stop : int
            The rows (as :meth:`rows_range`).

        Returns
        -------
        dict of str to numpy.ndarray
            ``R_mm`` and ``gap_mm`` (the row's radius and gap [mm]) and ``D_rupture_mm``: on a row beyond
            rupture, the widest gap any bridge of its volume (volume control) or suction (suction control)
            spans [mm] (:func:`rupture_gap_of_rows`); NaN on the other rows.
        """
        return row_context(self.inputs_si, self.status, start, stop)

    store_rows = per_case_store_rows  # bridges per case: nothing to chart across runs

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document: the source and the bridges (a ColumnRows when lazy).

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        n = self.status.size
        return {"source": self.source, "bridges": ColumnRows(n, self._cols_range) if lazy else self.rows()}

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame (``solve``: one row per bridge).

        Returns
        -------
        dict
            Stem -> DataFrame, the per-row table first.
        """
        return {"solve": self._frame()}

    def csv_tables(self) -> dict:
        """The tables as the CSV writer takes them, under ``name [unit]`` headers.

        ``solve``, built from the output columns.

        Returns
        -------
        dict
            Stem -> table (DataFrame or column mapping).
        """
        return {"solve": with_csv_headers(self._cols())}


_RECORD_HEADERS = BridgeRecord.csv_headers()
#: columns of text (no unit in their header)
TEXT_COLUMNS = ("case", "status", "note", "model", "law", "region")


def csv_header(key: str) -> str:
    """The CSV header of a JSON key of a bridge table: ``name [unit]``.

    ``r0_mm`` -> ``r0 [mm]``, ``S_R`` -> ``S_R [-]``; a text column keeps its name. The columns of `bridge solve` take
    theirs from :class:`BridgeRecord`; the other bridge tables' keys end in their unit.

    Parameters
    ----------
    key : str
        The JSON key (unit suffix form, kept in JSON for compatibility).

    Returns
    -------
    str
        The header in the house's ``name [unit]`` form.
    """
    if key in TEXT_COLUMNS:
        return key
    declared = _RECORD_HEADERS.get(key)
    if declared is not None:
        return declared
    header = result_csv_header(key)  # the one rule for unit suffixes (capred.result)
    return header if header != key else f"{key} [-]"


class HeadedSpool:
    """A :class:`capred.result.Spool` of JSON-keyed columns read under ``name [unit]`` headers.

    The CSV writer reads its blocks so; the spool itself is not copied.
    """

    def __init__(self, spool, encoded=None) -> None:
        self.spool, self.encoded = spool, encoded

    def blocks(self):
        """The spool's blocks with CSV headers.

        Yields
        ------
        dict
            One block's columns under ``name [unit]`` headers.
        """
        for block in self.spool.blocks():
            yield with_csv_headers(block)

    @property
    def n(self) -> int:
        """Rows held."""
        return self.spool.n

    def columns(self, start: int, stop: int) -> dict:
        """Rows ``start`` .. ``stop - 1`` under CSV headers (what report.html shows of a long run).

        Parameters
        ----------
        start, stop : int
            The rows, ``start`` included, ``stop`` excluded.

        Returns
        -------
        dict
            ``name [unit]`` header -> array.
        """
        return with_csv_headers(self.spool.columns(start, stop))

    def csv_pieces(self, dialect: str):
        """The CSV text of every block, already written by the run's processes, header first.

        The bytes :func:`capred.io.writers.write_csv_file` writes of :meth:`blocks` (capred.pipelines.bridge_blocks);
        None where the text was not written ahead (one process) or is wanted in another dialect than the standard one.

        Parameters
        ----------
        dialect : str
            The CSV dialect asked for.

        Returns
        -------
        iterator of bytes or None
        """
        if self.encoded is None or dialect != "standard":
            return None
        return self.encoded.csv_pieces()


def with_csv_headers(table):
    """A table (dict of columns or DataFrame) with ``name [unit]`` headers (see :func:`csv_header`).

    Parameters
    ----------
    table : dict or pandas.DataFrame
        Columns under their JSON keys.

    Returns
    -------
    dict or pandas.DataFrame
        The same columns (not copied: a dict of the same arrays, or a renamed view) under CSV headers.
    """
    if isinstance(table, dict):
        return {csv_header(k): v for k, v in table.items()}
    import pandas as pd

    # pandas >= 3 never copies here (copy-on-write) and deprecates the keyword; pandas 2 needs it not to copy
    no_copy = {} if int(pd.__version__.split(".")[0]) >= 3 else {"copy": False}
    return table.rename(columns=csv_header, **no_copy)


#: rows of a long run whose inputs are kept to name them in the console and report tables
HEAD_ROWS = 100


def rupture_gap_of_rows(inputs_si: dict, rows: np.ndarray) -> np.ndarray:
    """The rupture distance [m] of some rows: at their volume (rows given V_w) or suction (rows given one).

    Parameters
    ----------
    inputs_si : dict
        A result's inputs (``R`` [m], ``contact_angle_rad``, ``contact_angle2_rad`` [rad], ``ratio`` [-],
        ``gamma`` [N/m], ``suction`` [Pa] and ``V_w`` [m^3], NaN where the row gave the other).
    rows : numpy.ndarray of int
        The rows.

    Returns
    -------
    numpy.ndarray
        D_rupture [m] per row: :func:`capred.physics.bridge.rupture_gap` at constant volume,
        :func:`capred.physics.bridge.rupture_gap_at_suction` at constant suction; NaN where no bridge holds
        the volume or exists at the suction.

    References
    ----------
    .. [1] Lian, G., Thornton, C. & Adams, M. J. (1993). An analytical study of the liquid bridge between two rigid
       spheres. J. Colloid Interface Sci. 161, 138-147. doi:10.1006/jcis.1993.1452
    """
    i = inputs_si
    R, th, rho = i["R"][rows], i["contact_angle_rad"][rows], i["ratio"][rows]
    th2 = i.get("contact_angle2_rad", i["contact_angle_rad"])[rows]
    out = np.full(rows.size, np.nan)
    V = i["V_w"][rows] if "V_w" in i else np.full(rows.size, np.nan)
    s = i["suction"][rows] if "suction" in i else np.full(rows.size, np.nan)
    v = np.flatnonzero(np.isfinite(V))
    if v.size:
        out[v] = br.rupture_gap(th[v], V[v] / R[v] ** 3, rho[v], th2[v])[0] * R[v]
    u = np.flatnonzero(np.isfinite(s) & ~np.isfinite(V))
    if u.size:
        s_star = s[u] * R[u] / i["gamma"][rows][u]
        out[u] = br.rupture_gap_at_suction(th[u], s_star, rho[u], th2[u])[0] * R[u]
    return out


def row_context(inputs_si: dict, status: np.ndarray, start: int, stop: int) -> dict[str, np.ndarray]:
    """``R_mm``, ``gap_mm`` and, on rows beyond rupture, ``D_rupture_mm`` of rows start..stop.

    NaN where the inputs are not kept: past the HEAD_ROWS of a long run; see :meth:`BridgeResult.row_context`.

    Parameters
    ----------
    inputs_si : dict
        The run's inputs in SI (``R``, ``gap`` [m], ``ratio`` [-], ...), kept for the first HEAD_ROWS rows.
    status : ndarray of int
        Status code per row (0: a verified bridge).
    start, stop : int
        First row and one past the last row (0-based) [-].

    Returns
    -------
    dict
        ``R_mm``, ``gap_mm``, ``D_rupture_mm`` -> array [mm].
    """
    n = max(0, min(stop, status.size) - start)
    kept = max(0, min(n, inputs_si["R"].size - start)) if "R" in inputs_si else 0
    out = {k: np.full(n, np.nan) for k in ("R_mm", "gap_mm", "D_rupture_mm")}
    if kept:
        sl = slice(start, start + kept)
        out["R_mm"][:kept] = inputs_si["R"][sl] * 1e3
        out["gap_mm"][:kept] = inputs_si["gap"][sl] * 1e3
        far = np.flatnonzero(status[sl] == 1)
        if far.size:
            out["D_rupture_mm"][far] = rupture_gap_of_rows(inputs_si, start + far) * 1e3
    return out


def json_rows(cols: dict[str, np.ndarray], nan_as_none: bool = True) -> list[dict]:
    """JSON rows of output columns (an empty note left out), built column by column.

    Parameters
    ----------
    cols : dict of str to numpy.ndarray
        Output columns of equal length, with a ``note`` column (object arrays: text).
    nan_as_none : bool, default True
        Non-finite numbers as None; False keeps them as floats, for an encoder that writes them as null
        (orjson, :func:`capred.io.writers.stream_json`): the same JSON, without an object array per column.

    Returns
    -------
    list of dict
        One dict per row, keys in column order, ``note`` last and only where it is not empty.
    """
    keys = [k for k in cols if k != "note"]
    values = [cols[k].tolist() if cols[k].dtype == object or not nan_as_none else json_list(cols[k]) for k in keys]
    out = list(map(dict, map(zip, repeat(keys), zip(*values))))
    for r, note in zip(out, cols["note"].tolist()):
        if note:
            r["note"] = note
    return out


class ColumnRows(Rows):
    """JSON rows made on demand from output columns (``columns(start, stop)``).

    The writer encodes them chunk by chunk straight from the columns (:meth:`json_chunks`: no None per non-finite cell,
    the same bytes).
    """

    def __init__(self, n: int, columns) -> None:
        super().__init__(n, lambda start, stop: json_rows(columns(start, stop)))
        self.columns = columns

    def json_chunks(self, size: int = 2000):
        """The rows' JSON objects joined by commas, ``size`` rows per chunk (bytes, no brackets).

        Parameters
        ----------
        size : int, optional
            Rows per chunk [-].

        Yields
        ------
        bytes
            The encoded rows of one chunk.
        """
        from ..io import encode_rows

        for start in range(0, self.n, size):
            yield encode_rows(json_chunk_rows(self.columns(start, min(self.n, start + size))))


def json_chunk_rows(cols: dict) -> list[dict]:
    """``json_rows(cols, nan_as_none=False)`` for the writer.

    The rows without any number (no bridge) and without a note share one dict per status, so only the rows with a bridge
    cost a dict of their own.

    Parameters
    ----------
    cols : dict of str to ndarray
        A block's output columns under their JSON keys.

    Returns
    -------
    list of dict
        One JSON row per bridge.
    """
    n = len(cols["status"])
    numeric = [k for k, v in cols.items() if v.dtype != object]
    if not numeric or any(v.dtype == object and k not in ("status", "note") for k, v in cols.items()):
        return json_rows(cols, nan_as_none=False)  # a case label per row: nothing to share
    empty = cols["note"] == ""
    for k in numeric:
        empty &= ~np.isfinite(cols[k])
    if not empty.any():
        return json_rows(cols, nan_as_none=False)
    rows = np.empty(n, dtype=object)
    full = np.flatnonzero(~empty)
    if full.size:
        rows[full] = json_rows({k: v[full] for k, v in cols.items()}, nan_as_none=False)
    status = cols["status"]
    for text in dict.fromkeys(status[empty].tolist()):
        same = np.flatnonzero(empty & (status == text))
        shared = json_rows({k: v[same[:1]] for k, v in cols.items()}, nan_as_none=False)[0]
        rows[same] = [shared] * same.size
    return rows.tolist()


def frame_records(frame, drop_empty: str | None = None) -> list[dict]:
    """DataFrame rows as dicts, NaN as None, an empty ``drop_empty`` cell left out.

    Parameters
    ----------
    frame : pandas.DataFrame
        A result table.
    drop_empty : str, optional
        A column whose empty (None) cells are left out of their row's dict.

    Returns
    -------
    list of dict

    References
    ----------
    capred's own input conventions (README, "`capred shear`: input format"); no external source.
    """
    keys = list(frame.columns)
    cols = [[num(x) if isinstance(x, float) else x for x in frame[k].tolist()] for k in keys]
    out = []
    for values in zip(*cols):
        r = dict(zip(keys, values))
        if drop_empty is not None and not r.get(drop_empty):
            r.pop(drop_empty, None)
        out.append(r)
    return out


def read_cases(source, required: tuple[str, ...], required_one_of: tuple[str, ...], opt: BridgeOptions, schema=None):
    """The table of cases with its surface tension, radius ratio and second contact angle.

    Read from ``source``, or a Table already read; the radius ratio R2/R is 1 without an R2 column, the contact angle on
    the second particle in rad.

    Parameters
    ----------
    source : path, file or Table
        The cases.
    required : tuple of str
        Columns every case needs.
    required_one_of : tuple of str
        Columns of which a case needs at least one.
    opt : BridgeOptions
        The run's options (defaults of columns left out).
    schema : list of Column, optional
        The columns read (default: `bridge solve`'s).

    Returns
    -------
    (Table, ndarray, ndarray, ndarray)
        The table, surface tension [N/m], radius ratio [-] and second contact angle [rad] per case.

    References
    ----------
    Lian, G., Thornton, C. & Adams, M. J. (1993). A theoretical study of the liquid bridge forces between two rigid spherical bodies. J. Colloid Interface Sci. 161:138-147, doi:10.1006/jcis.1993.1452.
    """
    table = source if isinstance(source, Table) else read_table(source, schema or SOLVE_SCHEMA)
    for name in required:
        if name not in table.columns:
            table.missing_column(name)
    if required_one_of and not any(n in table.columns for n in required_one_of):
        table.missing_column(required_one_of[0], "".join(f" (or '{n}')" for n in required_one_of[1:]))
    if any(n not in table.columns for n in required) or (
        required_one_of and not any(n in table.columns for n in required_one_of)
    ):
        table.raise_if_problems()  # without its columns nothing else can be checked
    gamma = table.get("gamma").copy()
    gamma[np.isnan(gamma)] = opt.surface_tension
    for name in ("contact_angle", "contact_angle2"):
        for i in np.flatnonzero(table.get(name) >= 90):
            table.add_problem(
                i,
                name,
                f"contact angle {table.value_text(name, i)} deg: pendular bridges need a contact angle below 90 deg",
            )
    reported = {(p.line, p.column) for p in table.problems}  # a cell already explained (text in a number)
    for name in required:
        for i in np.flatnonzero(np.isnan(table.columns[name])):
            if (int(table.lines[i]), table.headers.get(name, name)) not in reported:
                table.add_problem(i, name, f"blank {name}")
    ratio = np.ones(len(table))
    if "R2" in table.columns:
        for i in np.flatnonzero(np.isnan(table.columns["R2"])):
            table.add_problem(i, "R2", "blank R2 (give a radius, or 'plane')")
        ratio = table.columns["R2"] / table.columns["R"]
    angle2 = table.get("contact_angle2").copy()
    blank = np.isnan(angle2)
    angle2[blank] = table.columns["contact_angle"][blank] if opt.contact_angle2 is None else opt.contact_angle2
    return table, gamma, ratio, np.radians(angle2)


def solve_table(table: Table, options: BridgeOptions | None = None) -> BridgeResult:
    """One bridge per row of a table already read.

    R (and R2), gamma, contact_angle (and contact_angle2), gap and suction or V_w (the work of
    :func:`capred.pipelines.bridge.solve_bridges` on one table or block).

    Parameters
    ----------
    table : Table
        The cases, read (capred.io.table.Table).
    options : BridgeOptions, optional
        Surface tension [N/m] and second contact angle [deg] for rows without them.

    Returns
    -------
    BridgeResult
        One bridge (or a status) per row.
    """
    opt = options or BridgeOptions()
    table, gamma, ratio, th2 = read_cases(table, ("R", "contact_angle", "gap"), ("suction", "V_w"), opt)
    s_in, v_in = table.get("suction"), table.get("V_w")
    for i in np.flatnonzero(np.isnan(s_in) & np.isnan(v_in)):
        table.add_problem(i, "suction" if "suction" in table.columns else "V_w", "give suction or V_w")
    for i in np.flatnonzero(np.isfinite(s_in) & np.isfinite(v_in)):
        table.add_problem(i, "V_w", "give suction or V_w, not both")
    table.raise_if_problems()
    R, th, D = table.columns["R"], np.radians(table.columns["contact_angle"]), table.columns["gap"]
    res = solve_arrays(
        table.path,
        R,
        gamma,
        th,
        D,
        ratio,
        s_in,
        v_in,
        list(table.columns["case"]) if "case" in table.columns else None,
        table.notes,
        th2,
        opt.workers,
        opt.branch,
    )
    res.options, res.warnings = opt, opt.warnings + table.warnings  # inputs: set by solve_in_blocks
    return res


def solve_arrays(
    source, R, gamma, th, D, ratio, s_in, v_in, labels=None, notes=None, th2=None, workers=None, branch="stable"
) -> BridgeResult:
    """Suction-controlled rows (s_in finite) and volume-controlled rows (v_in finite), SI in.

    ``th2`` the contact angle on the second particle [rad] (None: ``th``); ``workers``: processes (None: see
    :func:`processes`).

    Parameters
    ----------
    source : InputFile or None
        Where the cases came from (provenance).
    R, gamma, th, D, ratio, s_in, v_in : ndarray
        Per case: radius [m], surface tension [N/m], contact angle [rad], gap [m], radius ratio [-],
        suction [Pa] and water volume [m^3] (NaN where the case is controlled by the other).
    labels, notes : sequence, optional
        Case labels and notes carried to the result.
    th2 : ndarray, optional
        Contact angle on the second particle [rad].
    workers : int, optional
        Processes to use.
    branch : str, optional
        ``stable`` or ``thin`` (volume-controlled rows; see BridgeOptions).

    Returns
    -------
    BridgeResult

    References
    ----------
    Lian, G., Thornton, C. & Adams, M. J. (1993). A theoretical study of the liquid bridge forces between two rigid spherical bodies. J. Colloid Interface Sci. 161:138-147, doi:10.1006/jcis.1993.1452.
    """
    th2 = th if th2 is None else th2
    n = R.size
    beta, s_star, status = np.full(n, np.nan), np.full(n, np.nan), np.full(n, 2)
    by_s = np.flatnonzero(np.isfinite(s_in))
    by_v = np.flatnonzero(np.isfinite(v_in))
    note = [""] * n
    notes = list(notes or [])
    fields = {k: np.full(n, np.nan) for k in br.Bridge.__dataclass_fields__}
    if by_s.size:
        s_star[by_s] = s_in[by_s] * R[by_s] / gamma[by_s]
        beta[by_s], status[by_s], *values = _in_parallel(
            _suction_rows, th[by_s], s_star[by_s], D[by_s] / R[by_s], ratio[by_s], th2[by_s], workers=workers
        )
        for k, v in zip(fields, values):
            fields[k][by_s] = v
        if np.any((status[by_s] == 0) & (D[by_s] > 0)):
            notes.append(
                "At a given gap and suction two bridges fit; the stable one (larger filling angle and "
                "volume, continuous with the bridge at contact) is given."
            )
    if by_v.size:
        beta[by_v], s_star[by_v], status[by_v], past_fold, *values = _in_parallel(
            _volume_rows if branch == "stable" else _volume_rows_thin,
            th[by_v],
            v_in[by_v] / R[by_v] ** 3,
            D[by_v] / R[by_v],
            ratio[by_v],
            th2[by_v],
            workers=workers,
        )
        for k, v in zip(fields, values):
            fields[k][by_v] = v
        code = past_fold.astype(int)
        for i in by_v[(code & 1) > 0]:
            note[i] = (
                "stable at constant volume only (past the suction-controlled fold): at this suction "
                "an open water supply would jump to a larger bridge; close to rupture"
            )
        second = by_v[(code & 2) > 0]
        for i in second:
            note[i] += ("; " if note[i] else "") + SECOND_BRIDGE
        if second.size:
            notes.append(
                f"{second.size} volume-controlled row(s) also have a second, thin-neck bridge of the same volume "
                "and gap (near rupture; unstable at constant volume): --branch thin gives it"
            )
        if branch == "thin":
            none = by_v[status[by_v] == 1]
            for i in none:
                note[i] = "no thin-neck bridge of this volume at this gap (at contact, or not near rupture)"
            notes.append(
                "--branch thin: each volume-controlled row gives the second bridge of its volume and gap, on the "
                "thin-neck side of the volume's minimum along the arc (unstable at constant volume)"
            )
    shape = br.Bridge(**fields)
    return BridgeResult(
        source,
        {
            "R": R,
            "gamma": gamma,
            "contact_angle_rad": th,
            "gap": D,
            "ratio": ratio,
            "contact_angle2_rad": th2,
            "suction": s_in,  # Pa, NaN on volume-controlled rows
            "V_w": v_in,  # m^3, NaN on suction-controlled rows
        },
        beta,
        s_star * gamma / R,
        shape,
        status,
        note,
        labels,
        notes,
    )


_PARALLEL_ROWS = 30_000  # below this, one process is faster than starting a second


def _suction_rows(th, s, D, rho, th2):
    """Suction-controlled rows: (beta, status, every field of the bridge) — one unit of parallel work."""
    beta, status, b = br.bridge_at_suction(th, s, D, rho, th2)
    return (beta, status, *(getattr(b, k) for k in br.Bridge.__dataclass_fields__))


#: the note of a row that has a second (thin-neck) bridge of the same volume and gap
SECOND_BRIDGE = "a second (thin-neck) bridge of this volume and gap exists (unstable at constant volume; --branch thin)"


def _volume_rows_thin(th, V, D, rho, th2):
    """Volume-controlled rows on the thin-neck branch: (beta, s*, status, 0, every field of the bridge)."""
    beta, s, status = br.solve_for_volume(th, V, D, rho, th2, branch="thin")
    b = br.bridge(beta, th, np.where(np.isfinite(s), s, 0.0), rho, th2)
    return (beta, s, status, np.zeros(beta.size), *(getattr(b, k) for k in br.Bridge.__dataclass_fields__))


def _volume_rows(th, V, D, rho, th2):
    """Volume-controlled rows (V = V_w / R^3), one unit of parallel work.

    Returns (beta, s*, status, a code (+1 past the suction-controlled fold, +2 a second thin-neck bridge of the same
    volume and gap exists), every field of the bridge).

    A bridge is past the fold when the stable bridge at its own suction and gap (suction control) is not
    this one: an open water supply would make it jump to a larger bridge.
    """
    beta, s, status = br.solve_for_volume(th, V, D, rho, th2)
    ok = np.flatnonzero(status == 0)
    past = np.zeros(beta.size)
    if ok.size:
        b_s, st_s = br.solve_for_suction(th[ok], s[ok], D[ok], rho[ok], th2[ok])
        with np.errstate(invalid="ignore"):
            past[ok] = (st_s != 0) | ~(np.abs(b_s - beta[ok]) <= 1e-6 * beta[ok])
        # a second (thin-neck) bridge exists only near rupture, where the stable one is past the fold (measured on
        # 20,000 random rows: every row with one was); the check needs the thinnest catenoid, ~0.2 ms a row
        near = ok[(past[ok] > 0) & (D[ok] > 0)]
        if near.size:
            past[near[br.has_thin_bridge(th[near], V[near], D[near], rho[near], th2[near])]] += 2
    b = br.bridge(beta, th, np.where(np.isfinite(s), s, 0.0), rho, th2)
    return (beta, s, status, past, *(getattr(b, k) for k in br.Bridge.__dataclass_fields__))


def processes(requested: int | None = None) -> int:
    """How many processes may solve the rows of this run.

    Parameters
    ----------
    requested : int, optional
        ``--workers`` / ``BridgeOptions.workers``: this many, whatever the load (one where fork is missing).

    Returns
    -------
    int
        ``requested``; else the environment's ``CAPRED_PROCESSES`` (any whole number >= 1); else one per core
        this process may use (its CPU affinity) that the load average leaves idle, this run counting as one
        (two cores and a load below 1.5: two; 16 cores and a load of 8: nine); one in a batch's worker process
        (the batch already spreads its files over the cores) and where ``os.fork`` is missing.

    Notes
    -----
    On a busy shared machine a second process's extra CPU buys no time: measured on ``capred bridge solve`` of
    100,000 rows with the other core busy, 1.30 s CPU and 1.10 s wall in two processes against 1.22 s and 1.02 s
    in one (benchmarks/bench_bridge_cli.py); hence the load rule.
    """
    import math
    import os
    import sys

    if os.name != "posix" or not hasattr(os, "fork"):
        return 1
    if requested is not None:
        return max(1, int(requested))
    forced = os.environ.get("CAPRED_PROCESSES", "").strip()
    if forced.isdigit() and int(forced) >= 1:
        return int(forced)
    mp = sys.modules.get("multiprocessing")  # a batch's worker has imported it; a plain run has not
    if mp is not None and mp.current_process().daemon:
        return 1
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = 0.0
    return max(1, min(cores, math.ceil(cores - 0.5 - load) + 1))


def _parts(n: int, k: int) -> list[tuple[int, int]]:
    """(start, stop) of ``k`` contiguous parts of ``n`` rows, as equal as can be, the first part the smallest."""
    edges = [(n * j) // k for j in range(k + 1)]
    return [(edges[j], edges[j + 1]) for j in range(k)]


def _in_parallel(solver, *columns, workers: int | None = None):
    """``solver(*columns)`` on contiguous parts of the rows in as many processes as the run may use.

    Parts 2..k are solved by forked children (the run's helpers when a run is open, see :class:`helper`; else
    ones forked for this call, which inherit their part instead of receiving it), each sending its result
    back through a pipe, while this process solves part 1; should a child fail, this process solves its
    part itself, so an error is raised where it can be reported. Each row is computed by the same operations
    whatever part it falls in (see capred.physics.bridge._quad), so the result is the same to the bit for
    any number of processes. A part holds at least _PARALLEL_ROWS / 2 rows (fewer rows: fewer processes).
    """
    n = columns[0].size
    if ONE_PROCESS:  # a process of a run spread block by block (capred.pipelines.bridge_blocks): its block whole
        return solver(*columns)
    wanted = _RUN_PROCESSES if _IN_RUN and workers is None else processes(workers)
    k = max(1, min(wanted, n // max(1, _PARALLEL_ROWS // 2)))
    if k == 1:
        return solver(*columns)
    parts = _parts(n, k)
    jobs = [[c[a:b] for c in columns] for a, b in parts]
    if _IN_RUN:
        while len(_HELPERS) < k - 1:
            _HELPERS.append(_Helper())
        helpers = _HELPERS[: k - 1]
        for h, job in zip(helpers, jobs[1:]):
            h.submit(solver, job)
        own = []
    else:
        own = helpers = [_Helper((solver, job)) for job in jobs[1:]]  # each job inherited by its child, not sent
    try:
        results = [solver(*jobs[0])]
        for h, job in zip(helpers, jobs[1:]):
            got = h.result()
            results.append(solver(*job) if got is None else got)  # a child failed: solved (and raised) here
    finally:
        for h in own:
            h.close()
    return tuple(np.concatenate(parts_) for parts_ in zip(*results))


class _Helper:
    """A forked process that solves what it is sent (``submit``, then ``result``) until it is closed.

    ``live``: the helpers not yet closed (a child forked later closes its copies of their pipes).

    One helper serves every block of a long run (capred.pipelines.bridge_blocks): one fork per run instead of
    one per block. Messages are pickles behind their length, over two pipes. The cyclic garbage collector
    leaves the objects both processes share alone (``gc.freeze``) while the helper lives, so their pages stay
    shared.
    """

    live: list = []

    def __init__(self, job=None) -> None:
        """Fork the helper; ``job`` ((solver, columns), optional) is its first, handed over by the fork."""
        import gc
        import os

        to_child, self._to_child = os.pipe()
        self._from_child, from_child = os.pipe()
        gc.freeze()
        self.pid = os.fork()
        if self.pid == 0:  # the child: serve, then leave without running the parent's clean-up
            code = 1
            try:
                gc.disable()  # numpy arrays only: nothing to collect
                os.close(self._to_child)
                os.close(self._from_child)
                for other in _Helper.live:  # the parent's ends of the other helpers' pipes: theirs alone, so
                    for fd in (other._to_child, other._from_child):  # that each sees its end of jobs
                        try:
                            os.close(fd)
                        except OSError:
                            pass
                if job is not None:
                    send_message(from_child, _run(job))
                self._serve(to_child, from_child)
                code = 0
            finally:
                os._exit(code)
        os.close(to_child)
        os.close(from_child)
        self.alive = True
        _Helper.live.append(self)

    @staticmethod
    def _serve(inbox: int, outbox: int) -> None:
        while (job := receive_message(inbox)) is not None:
            send_message(outbox, _run(job))

    def submit(self, solver, columns) -> None:
        """Send a job (``solver`` must pickle: a module's function)."""
        try:
            send_message(self._to_child, (solver, columns))
        except (OSError, pickle.PicklingError, AttributeError, TypeError):
            self.alive = False

    def result(self):
        """The child's answer; None when it failed or is gone."""
        if not self.alive:
            return None
        try:
            out = receive_message(self._from_child)
        except (OSError, EOFError):
            out = None
        if out is None:
            self.alive = False
        return out

    def close(self) -> None:
        import gc
        import os
        import signal

        if self.pid is None:
            return
        try:
            os.close(self._to_child)  # end of the jobs: the child leaves
            os.close(self._from_child)
            if not self.alive:  # it failed, or may be stuck: it goes
                os.kill(self.pid, signal.SIGKILL)
            os.waitpid(self.pid, 0)
        except OSError:
            pass
        finally:
            self.pid, self.alive = None, False
            if self in _Helper.live:
                _Helper.live.remove(self)
            if not _Helper.live:
                gc.unfreeze()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _run(job):
    """A helper's answer to (solver, columns): the result, or None when it fails.

    The parent then solves it again and reports the error.
    """
    solver, columns = job
    try:
        return solver(*columns)
    except Exception:
        return None


def send_message(fd: int, obj) -> None:
    """Write one message (a picklable object, length-prefixed) to a pipe between the run's processes.

    Parameters
    ----------
    fd : int
        The pipe's writing end.
    obj : object
        What to send.
    """
    import os

    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    view = memoryview(len(data).to_bytes(8, "little") + data)
    while view:
        view = view[os.write(fd, view) :]


def receive_message(fd: int):
    """The next message written by :func:`send_message`.

    Parameters
    ----------
    fd : int
        The pipe's reading end.

    Returns
    -------
    object or None
        The message; None at the end of the pipe.
    """
    head = _read_exactly(fd, 8)
    if head is None:
        return None
    body = _read_exactly(fd, int.from_bytes(head, "little"))
    if body is None:
        raise EOFError("the helper process left mid-message")
    return pickle.loads(body)


def _read_exactly(fd: int, size: int) -> bytes | None:
    import os

    buf = bytearray()
    while len(buf) < size:
        chunk = os.read(fd, min(size - len(buf), 1 << 20))
        if not chunk:
            return None
        buf += chunk
    return bytes(buf)


#: the helper processes of the run under way (see :class:`helper`); the processes the run may use
_HELPERS: list = []
_RUN_PROCESSES = 1
_IN_RUN = False
#: True while a run spreads whole blocks over its processes (capred.pipelines.bridge_blocks): each block is then
#: solved in the one process that read it
ONE_PROCESS = False


class helper:
    """Context of a long run: parts 2..k of its blocks go to the same k - 1 helper processes.

    They are forked at the first block that needs them (or at once with ``start``) and closed at the end
    (capred.pipelines.bridge_blocks.solve_in_blocks). The number of processes is decided once for the run
    (:func:`processes`).

    Forked before the run's data are read (``start``), the processes share only what was there before:
    the pages the parent later fills are its own, not copies of shared ones.
    """

    def __init__(self, start: bool = False, workers: int | None = None) -> None:
        self.start, self.workers = start, workers

    def __enter__(self):
        global _RUN_PROCESSES, _IN_RUN
        _IN_RUN, _RUN_PROCESSES = True, processes(self.workers)  # decided once for the run
        if self.start:
            while len(_HELPERS) < _RUN_PROCESSES - 1:
                _HELPERS.append(_Helper())
        return self

    def __exit__(self, *exc) -> None:
        global _RUN_PROCESSES, _IN_RUN
        _IN_RUN, _RUN_PROCESSES = False, 1
        while _HELPERS:
            _HELPERS.pop().close()
