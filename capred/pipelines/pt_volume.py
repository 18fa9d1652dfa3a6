"""`capred pt-volume`: void ratio along a path of total stress, pore pressures and S_r (Pedrotti & Tarantino).

Reads a path table (one row per point: ``sigma``, ``u_w`` or ``suction``,
``u_a``, ``S_r``; pressures in kPa unless a header says otherwise; optional
``step`` and ``stage`` labels), takes the compressibility lines of the clay
reconstituted from slurry (W) and compressed from dry powder (A) as options,
and runs :func:`capred.physics.pedrotti_tarantino.simulate_volume_path`.
Every point gives one record row: the inputs, σ'_W and σ'_A (eq. 1-2), e,
e^W, e^A (eq. 5), the void-ratio changes of the four pore classes (eq. 6-10)
and flags. Rows with an impossible state are reported by file line.

References
----------
Pedrotti, M., Tarantino, A., "Effective stresses for unsaturated states stemming from clay
microstructure", submitted to Geomechanics for Energy and the Environment: eq. 1-10, Fig. 13-17.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from ..io import read_table
from ..physics import pedrotti_tarantino as pt
from ..references import cite
from ..result import InputFile, Result, input_file, json_list, num, output
from ..spec.pt_volume import LINE_OPTIONS, SCHEMA, PTVolumeOptions  # noqa: F401 (declared in spec; re-exported here)
from .row_records import RowRecord, plain


@dataclass(frozen=True)
class PTVolumePoints:
    """The simulated path, one value per point (SI); JSON keys and results.csv columns from ``output``.

    Increments (``de_*``, ``w_*``, ``sigma_star_*``) belong to the step that ends at the point (NaN at the
    first point and where the class is absent).

    Attributes
    ----------
    sigma, u_w, u_a, suction : ndarray
        Total stress, pore-water and pore-air pressure and suction u_a − u_w [Pa].
    S_R : ndarray
        Degree of saturation of the path [-].
    sigma_W, sigma_A : ndarray
        σ'_W = (σ − u_w) S_r and σ'_A = (σ − u_a)(1 − S_r) [Pa] (eq. 1-2).
    e, e_W, e_A : ndarray
        Void ratio of the sample and of its water- and air-saturated parts [-] (eq. 5).
    solid_fraction_W : ndarray
        Share of the solids in the water-saturated part [-].
    ncl_fraction_W, ncl_fraction_A : ndarray
        Share of each part's solids on its ncl [-].
    de_WW, de_AA : ndarray
        Void-ratio change of the pores that kept their fluid [-] (eq. 7/10 and 6).
    de_AW, de_WA : ndarray
        Void-ratio change of the pores that changed fluid, air to water (eq. 9) and water to air (eq. 8) [-].
    w_AW, w_WA : ndarray
        Share of the receiving part's voids that changed fluid in the step [-] (the weights of eq. 3-4).
    sigma_star_W, sigma_star_A : ndarray
        Equivalent pre-consolidation stresses σ'*_W (eq. 9) and σ*_A (eq. 8) [Pa].
    """

    sigma: np.ndarray = output("sigma_kPa", "sigma", "kPa", 1e-3)
    u_w: np.ndarray = output("u_w_kPa", "u_w", "kPa", 1e-3)
    u_a: np.ndarray = output("u_a_kPa", "u_a", "kPa", 1e-3)
    suction: np.ndarray = output("suction_kPa", "suction", "kPa", 1e-3)
    S_R: np.ndarray = output("S_r", "S_r")
    sigma_W: np.ndarray = output("sigma_W_kPa", "sigma_W", "kPa", 1e-3)
    sigma_A: np.ndarray = output("sigma_A_kPa", "sigma_A", "kPa", 1e-3)
    e: np.ndarray = output("e", "e")
    e_W: np.ndarray = output("e_W", "e_W")
    e_A: np.ndarray = output("e_A", "e_A")
    solid_fraction_W: np.ndarray = output("solid_fraction_W", "solid_fraction_W")
    ncl_fraction_W: np.ndarray = output("ncl_fraction_W", "ncl_fraction_W")
    ncl_fraction_A: np.ndarray = output("ncl_fraction_A", "ncl_fraction_A")
    de_WW: np.ndarray = output("de_WW", "de_WW")
    de_AA: np.ndarray = output("de_AA", "de_AA")
    de_AW: np.ndarray = output("de_AW", "de_AW")
    de_WA: np.ndarray = output("de_WA", "de_WA")
    w_AW: np.ndarray = output("w_AW", "w_AW")
    w_WA: np.ndarray = output("w_WA", "w_WA")
    sigma_star_W: np.ndarray = output("sigma_star_W_kPa", "sigma_star_W", "kPa", 1e-3)
    sigma_star_A: np.ndarray = output("sigma_star_A_kPa", "sigma_star_A", "kPa", 1e-3)

    @classmethod
    def from_path(cls, path: pt.PTVolumePath) -> PTVolumePoints:
        """The points of a simulated path as the record's columns.

        Parameters
        ----------
        path : capred.physics.pedrotti_tarantino.PTVolumePath
            The path the model computed (SI units).

        Returns
        -------
        PTVolumePoints
            Its columns, with the suction u_a - u_w [Pa] added.
        """
        names = {f.name for f in fields(cls)} - {"suction"}
        return cls(suction=path.u_a - path.u_w, **{k: getattr(path, k) for k in names})


#: boolean flags of each point (JSON true/false, CSV True/False)
FLAGS = ("loading_W", "loading_A", "yielding_W", "yielding_A")


@dataclass(frozen=True)
class Stage:
    """A run of consecutive points with the same ``stage`` label.

    Attributes
    ----------
    label : str
        The label.
    first, last : int
        0-based indices of its first and last point.
    de, de_W, de_A : float
        Change of e, e^W, e^A [-] from the point before the run (its first point for the first run) to its
        last point.
    """

    label: str
    first: int
    last: int
    de: float
    de_W: float
    de_A: float


def stage_runs(labels, e, e_W, e_A) -> list[Stage]:
    """Runs of consecutive equal stage labels with the changes of e, e^W and e^A over each (see Stage).

    Parameters
    ----------
    labels : sequence
        Stage label of each point.
    e, e_W, e_A : ndarray
        Void ratio of the sample, of the water-saturated and of the air-saturated pores per point [-].

    Returns
    -------
    list of Stage
        One Stage per run of equal labels, in order.
    """
    out: list[Stage] = []
    start = 0
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            before = max(start - 1, 0)
            out.append(
                Stage(
                    str(labels[start]),
                    start,
                    i - 1,
                    float(e[i - 1] - e[before]),
                    float(e_W[i - 1] - e_W[before]),
                    float(e_A[i - 1] - e_A[before]),
                )
            )
            start = i
    return out


@dataclass(frozen=True)
class StageRecord(RowRecord):
    """The stages of a labelled path, one row per run of equal ``stage`` labels.

    stages.csv and the JSON's ``stages``, each column declared once.

    Attributes
    ----------
    stage : list of str
        The label.
    first_step, last_step : ndarray
        Step of the run's first and last point [-].
    first_line, last_line : ndarray of int
        Their lines in the file.
    e_end : ndarray
        Void ratio at the run's last point [-].
    de, de_W, de_A : ndarray
        Change of e, e^W, e^A over the run, from the point before it [-] (eq. 5).
    S_R_end : ndarray
        Degree of saturation at the last point [-] (JSON ``S_r_end``).
    sigma_W_end, sigma_A_end : ndarray
        σ'_W and σ'_A at the last point [kPa] (eq. 1-2).

    References
    ----------
    .. [1] Pedrotti, M., Tarantino, A. (submitted). Effective stresses for unsaturated states stemming from clay
       microstructure. Geomechanics for Energy and the Environment (capred.references,
       ``pedrotti_tarantino_submitted``), eq. 1-2 and 5.
    """

    stage: list = plain("stage")
    first_step: np.ndarray = output("first_step", "first_step", "")
    last_step: np.ndarray = output("last_step", "last_step", "")
    first_line: np.ndarray = plain("first_line")
    last_line: np.ndarray = plain("last_line")
    e_end: np.ndarray = output("e_end", "e_end", "")
    de: np.ndarray = output("de", "de", "")
    de_W: np.ndarray = output("de_W", "de_W", "")
    de_A: np.ndarray = output("de_A", "de_A", "")
    S_R_end: np.ndarray = output("S_r_end", "S_r_end", "")
    sigma_W_end: np.ndarray = output("sigma_W_end_kPa", "sigma_W_end", "kPa")
    sigma_A_end: np.ndarray = output("sigma_A_end_kPa", "sigma_A_end", "kPa")


@dataclass(repr=False)
class PTVolumeResult(Result):
    """Result of `capred pt-volume`.

    Attributes
    ----------
    source : str
        The path file.
    points : PTVolumePoints
        The simulated path (records of every point).
    path : PTVolumePath
        The physics' own result (flags, substeps, the lines used).
    step : ndarray
        Step of each point (the file's ``step`` column, else 0, 1, 2...) [-].
    stage : list of str or None
        Stage labels of the points (None without a ``stage`` column).
    line : ndarray of int
        Line of each point in the file.
    stages : list of Stage
        Runs of equal stage labels (empty without labels).
    """

    command = "pt-volume"
    json_name = "results.json"

    source: str
    points: PTVolumePoints
    path: pt.PTVolumePath
    step: np.ndarray
    stage: list | None
    line: np.ndarray
    stages: list
    options: PTVolumeOptions
    notes: list[str] = field(default_factory=list)
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def params(self) -> pt.PTVolumeParameters:
        """The compressibility lines the path was computed with (``path.params``)."""
        return self.path.params

    def fluid_change(self) -> list[str]:
        """Which pores changed fluid in the step ending at each point.

        Returns
        -------
        list of str
            Per point: 'air_to_water', 'water_to_air' or ''.
        """
        aw, wa = self.points.w_AW > 0, self.points.w_WA > 0
        return ["air_to_water" if a else ("water_to_air" if w else "") for a, w in zip(aw, wa)]

    def parameters_json(self) -> dict:
        """The six line parameters of the run, its reference stress and which were illustrative.

        Returns
        -------
        dict
            lambda_W, kappa_W, e_ncl_W, lambda_A, kappa_A, e_ncl_A [-], reference_stress_kPa [kPa] and
            ``illustrative`` (the names taken from EXAMPLE_KAOLIN).
        """
        p = self.params
        return {
            "lambda_W": num(p.lambda_W),
            "kappa_W": num(p.kappa_W),
            "e_ncl_W": num(p.e_ncl_W),
            "lambda_A": num(p.lambda_A),
            "kappa_A": num(p.kappa_A),
            "e_ncl_A": num(p.e_ncl_A),
            "reference_stress_kPa": num(p.reference_stress / 1e3),
            "illustrative": self.options.illustrative(),
        }

    def rows(self) -> list[dict]:
        """JSON rows of the points.

        Returns
        -------
        list of dict
            One dict per point: line, step, the stage where labelled, and the columns in their JSON units.
        """
        from ..result import record_json_columns

        n = len(self.step)
        cols = {"line": [int(x) for x in self.line], "step": json_list(self.step)}
        if self.stage is not None:
            cols["stage"] = list(self.stage)
        cols.update(record_json_columns({None: self.points}, 0, n))
        for k in FLAGS:
            cols[k] = [bool(x) for x in getattr(self.path, k)]
        cols["fluid_change"] = self.fluid_change()
        keys = tuple(cols)
        return [dict(zip(keys, vals)) for vals in zip(*cols.values())]

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the initial and final void ratios (``e_initial``, ``e_final``).

        The glossary's void ratio, dimensionless, for the material of the inputs' metadata block. The count of points is
        not recorded.

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        from .. import nomenclature as nom
        from ..records import store_row

        e, unit = self.points.e, nom.QUANTITIES["void_ratio"].unit
        rows = [store_row(material, "e_initial", num(e[0]), unit), store_row(material, "e_final", num(e[-1]), unit)]
        return [r for r in rows if r is not None]

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        Source, model, parameters, number of points, initial and final e, sub-steps, points and stages.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        e = self.points.e
        return {
            "source": self.source,
            "model": f"{cite('pedrotti_tarantino_submitted')}, eq. 1-10",
            "parameters": self.parameters_json(),
            "n_points": len(self.step),
            "e_initial": num(e[0]),
            "e_final": num(e[-1]),
            "substeps": [int(x) for x in self.path.substeps],
            "points": self.rows(),
            "stages": self.stage_record().json_rows(),
        }

    def stage_record(self) -> StageRecord:
        """The stages (runs of equal ``stage`` labels) as a typed record.

        Their steps and lines, e, S_r, σ'_W and σ'_A at each run's last point and the changes of e, e^W and e^A over it.

        Returns
        -------
        StageRecord
            One row per stage (none without labels); stresses in kPa.

        References
        ----------
        .. [1] Pedrotti, M., Tarantino, A. (submitted), eq. 1-2 and 5 (capred.references,
           ``pedrotti_tarantino_submitted``).
        """
        st, last = self.stages, [s.last for s in self.stages]
        first = [s.first for s in st]
        return StageRecord(
            stage=[s.label for s in st],
            first_step=np.asarray(self.step, float)[first],
            last_step=np.asarray(self.step, float)[last],
            first_line=np.asarray(self.line, int)[first],
            last_line=np.asarray(self.line, int)[last],
            e_end=np.asarray(self.points.e, float)[last],
            de=np.array([s.de for s in st], float),
            de_W=np.array([s.de_W for s in st], float),
            de_A=np.array([s.de_A for s in st], float),
            S_R_end=np.asarray(self.points.S_R, float)[last],
            sigma_W_end=np.asarray(self.points.sigma_W, float)[last] / 1e3,
            sigma_A_end=np.asarray(self.points.sigma_A, float)[last] / 1e3,
        )

    def tables(self) -> dict:
        """Output tables: file stem -> pandas DataFrame.

        Returns
        -------
        dict of str to pandas.DataFrame
            ``results``: one row per point; ``stages``: one row per run of equal stage labels (when labelled).
        """
        cached = self.__dict__.get("_tables")
        if cached is None:
            cached = self.__dict__["_tables"] = self._tables()
        return cached

    def _tables(self) -> dict:
        import pandas as pd

        from ..result import record_columns

        cols: dict = {"line": self.line, "step [-]": self.step}
        if self.stage is not None:
            cols["stage"] = self.stage
        cols.update(record_columns({None: self.points}))
        for k in FLAGS:
            cols[k] = np.asarray(getattr(self.path, k), bool)
        cols["fluid_change"] = self.fluid_change()
        out = {"results": pd.DataFrame(cols)}
        if self.stages:
            out["stages"] = pd.DataFrame(self.stage_record().csv_columns())
        return out

    def method_notes(self) -> tuple[list[str], list[str]]:
        """The run's lines for the methods text.

        And, where used, that they are the illustrative EXAMPLE_KAOLIN values.

        Returns
        -------
        tuple
            (paragraphs, reference keys).

        References
        ----------
        .. [1] Pedrotti, M., Tarantino, A. Effective stresses for unsaturated states stemming from clay
           microstructure. Submitted to Geomechanics for Energy and the Environment; eq. 1-10.
        """
        p = self.params
        text = (
            f"Lines of this run: slurry (W) λ_W = {p.lambda_W:g}, κ_W = {p.kappa_W:g}, e_ncl,W = {p.e_ncl_W:g}; "
            f"dry powder (A) λ_A = {p.lambda_A:g}, κ_A = {p.kappa_A:g}, e_ncl,A = {p.e_ncl_A:g}; intercepts at "
            f"σ_ref = {p.reference_stress / 1e3:g} kPa."
        )
        if self.options.illustrative():
            text += (
                " " + ", ".join(self.options.illustrative()) + " are the illustrative EXAMPLE_KAOLIN values "
                "(not from the paper, which prints none)."
            )
        return [text], ["pedrotti_tarantino_submitted"]


def run_pt_volume(source, options: PTVolumeOptions | None = None) -> PTVolumeResult:
    """Simulate the void ratio along a path with the volume-change model of Pedrotti & Tarantino.

    Parameters
    ----------
    source : str, Path, DataFrame or TableSource
        The path: one row per point with ``sigma`` (total mean stress), ``u_w`` (or ``suction`` = u_a − u_w),
        ``u_a`` (optional, default 0: atmospheric air) [kPa unless the header gives a unit] and ``S_r`` [-];
        optional ``step`` and ``stage`` labels.
    options : PTVolumeOptions
        The lines of slurry (W) and dry-powder (A) clay (or ``example_kaolin``), the initial yield stresses
        and the sub-steps.

    Returns
    -------
    PTVolumeResult
        One record per point: σ'_W, σ'_A, e, e^W, e^A, the pore-class changes and flags.

    Raises
    ------
    InputError
        Missing columns or points that cannot be simulated (S_r outside [0, 1], σ − u_w ≤ 0 where the
        water-saturated part exists, σ − u_a ≤ 0 where the air-saturated part exists), each with its line.
    OptionError
        Lines missing or out of range.

    References
    ----------
    Pedrotti & Tarantino (submitted), eq. 1-2 (σ'_W, σ'_A), 5 (coupling), 6-10 (pore classes), Fig. 13-17.
    """
    opt = options if options is not None else PTVolumeOptions()
    params = opt.parameters()
    table = read_table(source, SCHEMA)
    notes = list(table.notes)
    for name in ("sigma", "S_r"):
        if name not in table.columns:
            table.missing_column(name)
    if "u_w" not in table.columns and "suction" not in table.columns:
        table.missing_column("u_w", " (or 'suction' = u_a - u_w)")
    table.raise_if_problems()
    u_a = table.get("u_a", 0.0).copy()
    if "u_a" not in table.columns:
        notes.append("no u_a column: the pore air is taken as atmospheric (u_a = 0)")
    if "u_w" in table.columns:
        u_w = table.get("u_w").copy()
        if "suction" in table.columns:
            fill = np.isnan(u_w)
            u_w[fill] = (u_a - table.get("suction"))[fill]
    else:
        u_w = u_a - table.get("suction")
    sigma, S_r = table.get("sigma"), table.get("S_r")
    values = {"sigma": sigma, "u_w": u_w, "u_a": u_a, "S_r": S_r}
    for name, v in values.items():
        where = name if name in table.columns else ("suction" if name == "u_w" else None)
        for i in np.flatnonzero(np.isnan(v)):
            table.add_problem(i, where, f"no value for '{name}'")
    table.raise_if_problems()
    for i, col, message in pt.path_problems(sigma, u_w, u_a, S_r):
        shown = col if col in table.columns else ("suction" if col == "u_w" and "suction" in table.columns else None)
        table.add_problem(i if i >= 0 else None, shown, message)
    table.raise_if_problems()

    path = pt.simulate_volume_path(
        sigma,
        u_w,
        u_a,
        S_r,
        params=params,
        initial_yield_W=opt.initial_yield_W,
        initial_yield_A=opt.initial_yield_A,
        substeps=opt.substeps,
    )
    points = PTVolumePoints.from_path(path)
    n = len(sigma)
    step = table.get("step").copy() if "step" in table.columns else np.arange(n, dtype=float)
    if "step" in table.columns and np.isnan(step).any():
        notes.append("blank 'step' cells: those points are numbered by their position (from 0)")
        step[np.isnan(step)] = np.flatnonzero(np.isnan(step))
    stage = [str(s) for s in table.columns["stage"]] if "stage" in table.columns else None
    stages = stage_runs(stage, path.e, path.e_W, path.e_A) if stage is not None else []

    warnings = list(opt.warnings) + list(table.warnings)
    for part, fit_file in (("W", opt.compression_W), ("A", opt.compression_A)):
        if fit_file is not None:
            notes.append(f"λ_{part}, κ_{part}, e_ncl,{part} from the compression test {fit_file}")
    if opt.illustrative():
        warnings.append(
            "lines " + ", ".join(opt.illustrative()) + " are EXAMPLE_KAOLIN: illustrative values for "
            "a kaolin, NOT from Pedrotti & Tarantino (who print none) nor from this soil; the void "
            "ratios show the model's behaviour, not a prediction"
        )
    if opt.substeps is None and len(path.substeps):
        notes.append(
            f"{int(path.substeps.sum())} sub-steps in all ({len(path.substeps)} steps; automatic: "
            "|ΔS_r| ≤ 0.002 and |Δ ln σ'| ≤ 0.02 in each)"
        )
    return PTVolumeResult(
        table.path,
        points,
        path,
        step,
        stage,
        np.asarray(table.lines, int),
        stages,
        opt,
        notes,
        [input_file(source, table)],
        warnings,
    )


__all__ = ["run_pt_volume", "PTVolumeOptions", "PTVolumeResult", "PTVolumePoints", "Stage", "SCHEMA"]
