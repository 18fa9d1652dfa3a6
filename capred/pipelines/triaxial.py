"""`capred triaxial-bounds`: bounds of the capillary stress tensor at failure (Prunier et al. 2024).

Saturated drained tests give the effective envelope c', phi'; every
unsaturated test's total failure state is projected on it under three
hypotheses (spherical tensor, lower bound, EDTP upper bound), and groups of
unsaturated tests that share one tensor get the Appendix 1 analysis.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import nomenclature as nom
from ..errors import FitError
from ..fitting.linear import fit_line
from ..io import Column, Table, read_table
from ..parameters import deprecated
from ..physics import triaxial as tx
from ..result import InputFile, Result, input_file, num
from ..spec.triaxial import SCHEMA, TriaxialOptions  # noqa: F401 (declared in spec; re-exported here)
from . import triaxial_records as rec
from .triaxial_curves import export_states, pressure_tolerance
from .triaxial_materials import one_material, zero_suction_envelope
from .triaxial_records import EXTENDED_MC_METHOD, KPA, Envelope

CURVE_SCHEMA = [
    Column("test_id", "text", None, "test identifier"),  # aliases: nomenclature.COLUMN_ALIASES
    Column("axial_strain", "dimensionless", "-", "axial strain", ("eps_a", "eps1", "epsilon_1", "axial_strain_pct")),
    Column("q", "pressure", "kPa", "q", ("deviator", "q_kpa", "deviatoric_stress")),
    Column("vol_strain", "dimensionless", "-", "volumetric strain", ("eps_v", "epsilon_v")),
]

BOUNDS = ("spherical", "lower", "edtp")


def fit_envelope(sigma3_eff, sigma1_eff, confidence=0.95) -> Envelope:
    """c', phi' from saturated failure states by least squares of sigma'_1 on sigma'_3.

    Eq. (25) of Prunier et al. (2024) is linear in the principal-stress plane:
    sigma'_1 = K_p sigma'_3 + 2c' sqrt(K_p). The confining stress is the
    controlled variable and sigma'_1 the measured one, so ordinary least
    squares has its error in the right variable (a fit of q on p would put the
    measured q on both axes, since p = sigma3 + q/3). This is the exact
    Mohr-Coulomb criterion, i.e. the line tangent to the Mohr circles.
    Standard errors of c', phi' follow by the delta method.

    Parameters
    ----------
    sigma3_eff, sigma1_eff : array_like
        Effective principal stresses at failure of the saturated tests [Pa].
    confidence : float
        Level of the line's intervals [-].

    Returns
    -------
    Envelope
        c' [kPa], phi' [deg] with standard errors, the line fit and the c'-phi' correlation.

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.
       doi:10.1080/19648189.2024.2314099, eq. 25.
    """
    f = fit_line(sigma3_eff, sigma1_eff, confidence)
    kp, b = f.slope, f.intercept
    if kp <= 1.0:
        raise FitError(f"saturated failure states give K_p = {kp:.3g} <= 1: no positive friction angle")
    c, phi = tx.envelope_from_principal_fit(kp, b)
    # delta method: phi = asin((K-1)/(K+1)), c = b/(2 sqrt K); J rows (c, phi), columns (b, K)
    dphi_dk = np.degrees(1.0 / ((kp + 1.0) * np.sqrt(kp)))
    dc_db, dc_dk = 1.0 / (2.0 * np.sqrt(kp)), -b / (4.0 * kp**1.5)
    jac = np.array([[dc_db, dc_dk], [0.0, dphi_dk]])
    cov = jac @ f.covariance @ jac.T  # f.covariance: [[var b, cov], [cov, var K]]
    c_se, phi_se = np.sqrt(max(cov[0, 0], 0.0)), np.sqrt(max(cov[1, 1], 0.0))
    corr = float(cov[0, 1] / (c_se * phi_se)) if c_se > 0 and phi_se > 0 else float("nan")
    return Envelope(
        c_kPa=float(c) / KPA,
        phi_deg=float(phi),
        c_se_kPa=float(c_se) / KPA,
        phi_se_deg=float(phi_se),
        source="fit",
        n=f.n,
        r2=float(f.r2),
        fit=f,
        c_phi_correlation=corr,
    )


#: the keys of capred 0.x's ``TriaxialResult.tests`` dict [Pa] and the TestStates fields they came from
_OLD_TEST_KEYS = {"strain_f": "strain_at_failure", "lode": "lode_angle", "membrane": "membrane_correction"}
_TEXT_FIELDS = ("test_id", "condition", "group", "line", "branch", "pair")


@dataclass(repr=False)
class TriaxialResult(Result):
    """Result of `capred triaxial-bounds`: the envelope, every test's bounds and the groups, as typed records.

    Attributes
    ----------
    source : str
        The tests table.
    envelope : Envelope
        c', φ' (``envelope.params``, ``envelope.summary()``) [kPa], [deg].
    states : TestStates
        Every test's failure state [kPa], [deg].
    bound_states : dict of str to BoundStates
        The three bounds (``spherical``, ``lower``, ``edtp``) of every unsaturated test [kPa].
    groups : list of GroupRecord
        Appendix 1 of Prunier et al. (2024) per group.
    notes, warnings : list of str
        What the run did and what the user should check.
    curves : dict of str to Curve
        The raw curves (``--curves``) that gave a test's failure deviator, by test id.
    reference_curves : dict of str to Curve
        The raw curves of tests whose failure deviator the table gives (q_f or sigma1 wins over a curve's peak):
        not used for failure, drawn for reference with the table's q_f beside the curve's peak.
    """

    command = "triaxial-bounds"

    source: str
    envelope: Envelope
    states: rec.TestStates
    bound_states: dict[str, rec.BoundStates]
    groups: list[rec.GroupRecord]
    notes: list[str] = field(default_factory=list)
    options: TriaxialOptions | None = None
    inputs: list[InputFile] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    curves: dict[str, rec.Curve] = field(default_factory=dict)
    reference_curves: dict[str, rec.Curve] = field(default_factory=dict)

    @property
    def unsaturated(self) -> np.ndarray:
        """True for the unsaturated tests [-]."""
        return self.states.condition == "unsaturated"

    # --- the names of capred 0.x, in Pa (one release, with a DeprecationWarning) -------------------------
    @property
    def tests(self) -> dict[str, np.ndarray]:
        """Deprecated: every test's state as a dict of arrays in Pa; use ``states`` (kPa, typed)."""
        out = {}
        for f in dataclasses.fields(self.states):
            key = {v: k for k, v in _OLD_TEST_KEYS.items()}.get(f.name, f.name)
            v = getattr(self.states, f.name)
            out[key] = v if f.name in _TEXT_FIELDS or key == "lode" or key == "strain_f" else v * KPA
        return deprecated("TriaxialResult.tests [Pa]", "TriaxialResult.states (kPa)", out)

    @property
    def bounds(self) -> dict[str, tx.Bound]:
        """Deprecated: the bounds as physics records in Pa; use ``bound_states`` (kPa)."""
        out = {
            name: tx.Bound(b.sigma1_cap * KPA, b.sigma3_cap * KPA, b.p_prime * KPA, b.q_prime * KPA, b.sigma2_cap * KPA)
            for name, b in self.bound_states.items()
        }
        return deprecated("TriaxialResult.bounds [Pa]", "TriaxialResult.bound_states (kPa)", out)

    @property
    def q_sat(self) -> np.ndarray:
        """Deprecated: q'_sat [Pa]; use ``states.q_sat`` (kPa)."""
        return deprecated("TriaxialResult.q_sat [Pa]", "TriaxialResult.states.q_sat (kPa)", self.states.q_sat * KPA)

    def method_notes(self) -> tuple[list[str], list[str]]:
        """The run's choices the methods text states: the extension path, the membrane correction's diameter.

        Returns
        -------
        (list of str, list of str)
            The paragraphs, and the keys of the references they cite.
        """
        opt = self.options or TriaxialOptions()
        out = []
        if (self.states.branch == "extension").any():
            what = {
                "axial-unloading": "the axial stress falls at constant cell pressure, slope −3 in the q-p plane",
                "radial-loading": "the cell pressure rises at constant axial stress, slope 3/2 in the q-p plane",
            }[opt.extension_path]
            out.append(
                "Extension tests: the saturated reference strength q'_sat and the EDTP bound assume the drained "
                f"path '{opt.extension_path}' from the isotropic state ({what}; --extension-path); the failure "
                "point is where that path meets the extension envelope M = 6 sin φ'/(3 + sin φ')."
            )
        if opt.membrane is not None:
            out.append(
                "The deviator is corrected for the membrane as ASTM D4767-11 does, Δq = 4 E_m t_m ε_a / D_c, with "
                "D_c the diameter after consolidation (column D_c, or from the consolidation volume change dV_c); "
                "tests without either use the initial diameter D0, as the notes say."
            )
        return out, (["astm_d4767"] if opt.membrane is not None else [])

    def flags(self, i: int) -> list[str]:
        """What test ``i``'s bounds contradict: a positive (compressive) capillary component, p' < 0.

        Parameters
        ----------
        i : int
            Row of the test (0-based).

        Returns
        -------
        list of str
            ``<bound>_positive_component`` per bound concerned, ``spherical_negative_p_prime``; empty when none.
        """
        out = []
        for name in BOUNDS:
            b = self.bound_states[name]
            if b.applies(i) and b.positive_component[i]:
                out.append(f"{name}_positive_component")
        if self.unsaturated[i] and self.bound_states["spherical"].p_prime[i] < 0:
            out.append("spherical_negative_p_prime")
        return out

    def payload(self, lazy: bool = False) -> dict:
        """The command's own keys of the JSON document.

        Source, envelope, per test its state and bounds (None where a bound does not apply) with its flags, and the
        groups.

        Parameters
        ----------
        lazy : bool, optional
            Give long per-row lists as Rows made on demand (the writer streams them) instead of lists.

        Returns
        -------
        dict
            JSON key -> value (JSON units: mm, kPa, deg, mN).
        """
        tests = []
        for i in range(len(self.states)):
            row = rec.row_json(self.states, i)
            row["q_sat_kPa"] = row["q_sat_kPa"] if self.unsaturated[i] else None
            for name in BOUNDS:
                b = self.bound_states[name]
                row[name] = rec.row_json(b, i) if self.unsaturated[i] and b.applies(i) else None
            row["flags"] = self.flags(i)
            tests.append(row)
        env = rec.to_json(self.envelope)
        env = {k: env[k] for k in ENVELOPE_KEYS}  # the order of capred 0.x
        for key, ci in self._envelope_intervals().items():
            env[nom.json_key(key, "_ci95")] = [num(x) for x in ci]
        return {"source": self.source, "envelope": env, "tests": tests, "groups": [rec.to_json(g) for g in self.groups]}

    def _envelope_intervals(self) -> dict:
        """Glossary name -> 95 % interval of c' [kPa] and phi' [deg], where the envelope was fitted.

        params and the summary give them; {} for an envelope given by --c-eff/--phi-eff.
        """
        if self.envelope.fit is None and self.envelope.source != "extended_mc":
            return {}
        par = self.envelope.params
        return {name: par[nom.json_key(name)].ci95 for name in ("c", "phi")}

    def store_rows(self, material: str | None = None) -> list:
        """The lab store's rows: the effective envelope's glossary quantities.

        c_kPa, phi_deg with their 95 % intervals, M, k_kPa, their extension twins, the standard errors, r2, from the
        record's declarations (capred.pipelines.triaxial_records.store_rows), for the material of the inputs' metadata
        block.

        Parameters
        ----------
        material : str, optional
            The material of the inputs' metadata block.

        Returns
        -------
        list of capred.records.StoreRow
        """
        intervals = {nom.json_key(name): ci for name, ci in self._envelope_intervals().items()}
        return rec.store_rows(self.envelope, material, intervals)

    def tables(self) -> dict:
        """Output tables: ``results`` (one row per test, bounds side by side) and, with groups, ``groups``.

        Returns
        -------
        dict of str to pandas.DataFrame
        """
        cached = self.__dict__.get("_tables")
        if cached is None:
            import pandas as pd

            cached = {"results": self._results_table()}
            if self.groups:
                cached["groups"] = pd.DataFrame([rec.group_csv(g) for g in self.groups])
            self.__dict__["_tables"] = cached
        return cached

    def season_rows(self) -> list[dict]:
        """Rows of a batch's season.csv: one, the effective envelope with its standard errors and the test counts.

        c and phi [kPa, deg] with their standard errors, the numbers of saturated and unsaturated tests and of flagged
        tests.

        Returns
        -------
        list of dict
            ``name [unit]`` -> value.
        """
        e = self.envelope
        n_flag = sum(1 for i in range(len(self.states)) if self.flags(i))
        return [
            {
                "material": "(envelope)",
                **{  # the envelope's declared quantities (JSON c_kPa ...), under their glossary CSV headers
                    nom.column(name, se): num(getattr(e, _envelope_field(name, se).name))
                    for name in ("c", "phi")
                    for se in ("", "_se")
                },
                "n_dry": e.n,
                "n_wet": int(self.unsaturated.sum()),
                "best_model": None,
                "best_rmse [kPa]": None,
                "flagged_tests": n_flag,
            }
        ]

    def _results_table(self):
        import pandas as pd

        cols = rec.row_csv(self.states)
        cols["q_sat [kPa]"] = np.where(self.unsaturated, cols["q_sat [kPa]"], np.nan)
        for name in BOUNDS:
            b = self.bound_states[name]
            keep = self.unsaturated & np.isfinite(b.sigma1_cap)
            for k, v in rec.row_csv(b, name + "_").items():
                v = np.asarray(v)
                cols[k] = np.where(keep, v, None) if v.dtype == bool else np.where(keep, v, np.nan)
        cols["flags"] = [";".join(self.flags(i)) for i in range(len(self.states))]
        return pd.DataFrame(cols)


def _envelope_field(name: str, se: str):
    """The field of the Envelope record that declares glossary quantity ``name`` (its standard error: se="_se")."""
    return next(
        f
        for f in dataclasses.fields(Envelope)
        if f.metadata.get("quantity") == name and f.metadata["se"] == (se == "_se") and not f.metadata["ci"]
    )


#: the keys of the JSON object ``envelope``, in their order
ENVELOPE_KEYS = (
    "c_kPa",
    "phi_deg",
    "M",
    "k_kPa",
    "M_extension",
    "k_extension_kPa",
    "c_se_kPa",
    "phi_se_deg",
    "source",
    "n",
    "r2",
    "method",
)


def _kpa(x) -> float | None:
    return num(float(x) / 1e3)


def load_triaxial_table(table: Table, curves: dict[str, tuple[float, float]] | None) -> tuple[Table, dict]:
    """The deviator q at failure (from q_f, sigma1 or the curves) per test; problems collected in ``table``.

    Returns the table and a dict with ``q`` [Pa], ``strain`` (axial strain at
    failure [-], from the curve or the column ``strain_at_failure``) and
    ``from_curve`` (True where the curve gave q).

    Parameters
    ----------
    table : Table
        The tests table read (test_id, condition, sigma3, q_f or sigma1, ...).
    curves : dict or None
        Test id -> (q at the peak [Pa], axial strain at the peak [-]) from the raw curves.

    Returns
    -------
    tuple
        (``table``, {``q`` [Pa], ``strain`` [-], ``from_curve``}), one value per test.

    Raises
    ------
    InputError
        Where a required column is missing.
    """
    for name in ("test_id", "condition", "sigma3"):
        if name not in table.columns:
            table.missing_column(name)
    if "q_f" not in table.columns and "sigma1" not in table.columns and not curves:
        table.missing_column("q_f", " (or 'sigma1', or raw curves with --curves)")
    table.raise_if_problems()
    n = len(table)
    s3 = table.columns["sigma3"]
    q = table.get("q_f").copy()
    s1 = table.get("sigma1")
    strain = table.get("strain_at_failure").copy()
    from_curve = np.zeros(n, bool)
    table.check_unique("test_id")
    for i in range(n):
        tid = table.columns["test_id"][i]
        if np.isnan(q[i]) and np.isfinite(s1[i]) and np.isfinite(s3[i]):
            q[i] = s1[i] - s3[i]
            if q[i] <= 0:
                table.add_problem(
                    i, "sigma1", f"sigma1 = {table.value_text('sigma1', i)} is not above sigma3: q_f <= 0"
                )
        if np.isnan(q[i]) and curves and tid in curves:
            q[i], strain[i] = curves[tid]
            from_curve[i] = True
            if q[i] <= 0:
                table.add_problem(i, "test_id", f"the curve of '{tid}' peaks at q = {q[i] / 1e3:.4g} kPa <= 0")
        if np.isnan(q[i]) and not any(p.line == int(table.lines[i]) for p in table.problems):
            table.add_problem(
                i,
                "q_f" if "q_f" in table.columns else None,
                "no failure deviator: give 'q_f' or 'sigma1'" + (" or a curve" if curves else ""),
            )
    if curves:
        unknown = sorted(set(curves) - set(table.columns["test_id"]))
        if unknown:
            table.notes.append(f"curves for tests not in the table ignored: {', '.join(unknown)}")
    return table, {"q": q, "strain": strain, "from_curve": from_curve}


def reference_curves_notes(test_ids, q: np.ndarray, from_curve: np.ndarray, peaks: dict) -> list[str]:
    """A note on the curves (``--curves``) of tests whose failure deviator the table gives (q_f or sigma1).

    The table's value wins over a curve's peak; such a curve is not used for failure, and saying nothing would
    drop it silently (a user who gives curves expects them used). The note names those tests and compares each
    curve's peak with the table's q_f: the largest difference says whether the two agree.

    Parameters
    ----------
    test_ids : array of str
        The tests, in the table's order.
    q : ndarray
        Failure deviator of every test [Pa] (after any membrane correction).
    from_curve : ndarray of bool
        True where the curve gave the failure deviator.
    peaks : dict
        Test id -> (q at the curve's peak [Pa], axial strain there [-]).

    Returns
    -------
    list of str
        One note, or none when every curve gave its test's failure (or no curves were given).

    References
    ----------
    Prunier, F., et al. (2024), q-ε1 and εv-ε1 curves with the peak taken as failure (Fig. 10, 15);
    ASTM D4767-11, section 10 (failure as the peak deviator stress, or another criterion a lab chooses).
    """
    ref = [
        (str(t), float(qi), peaks[str(t)][0])
        for t, qi, fc in zip(test_ids, q, from_curve)
        if not fc and str(t) in peaks
    ]
    if not ref:
        return []
    every = "every test has" if not np.any(from_curve) else "these tests have"
    tid, q_f, peak = max(ref, key=lambda r: abs(r[2] - r[1]) / abs(r[1]) if r[1] else np.inf)
    return [
        f"--curves: the curves of {', '.join(r[0] for r in ref)} not used for failure: {every} q_f (or sigma1) in "
        "the table, which wins over a curve's peak; drawn for reference (panels 'reference_curves' of the figures); "
        f"largest difference between a curve's peak and q_f: '{tid}', peak {peak / 1e3:.4g} kPa against q_f "
        f"{q_f / 1e3:.4g} kPa ({(peak - q_f) / q_f * 100:+.2g} %)"
    ]


def consolidated_diameter(table: Table) -> tuple[np.ndarray, np.ndarray]:
    """Diameter after consolidation D_c [m] of every test, for the membrane correction, and where it came from.

    ASTM D4767-11 corrects the deviator with the specimen's diameter after consolidation. It is the column
    ``D_c`` where given; else, from the volume decrease during consolidation ``dV_c`` and the initial
    ``D0``, ``H0``: A_c = (V0 − ΔV_c)/H_c with V0 = π D0² H0/4 and H_c the column ``H_c``, or, without it,
    H0 (1 − ΔV_c/V0)^(1/3) (isotropic consolidation: equal axial and radial strains); else the initial
    diameter D0 (the source says so, and the run notes it).

    Parameters
    ----------
    table : Table
        The tests table (columns D_c, or dV_c with D0, H0 and optional H_c) [m, m^3].

    Returns
    -------
    D_c : ndarray
        Diameter [m] (NaN where neither is known).
    source : ndarray of str
        ``"D_c"``, ``"dV_c"``, ``"D0"`` or ``""`` per test.
    """
    n = len(table)
    dc, d0, h0, hc, dv = (table.get(k) for k in ("D_c", "D0", "H0", "H_c", "dV_c"))
    out, src = np.full(n, np.nan), np.array([""] * n, dtype=object)
    for i in range(n):
        if np.isfinite(dc[i]):
            out[i], src[i] = dc[i], "D_c"
        elif np.isfinite(dv[i]) and np.isfinite(d0[i]) and np.isfinite(h0[i]):
            v0 = np.pi * d0[i] ** 2 / 4 * h0[i]
            if not 0 <= dv[i] < v0:
                table.add_problem(
                    i, "dV_c", f"the volume decrease during consolidation must lie in [0, V0 = {v0 * 1e6:.4g} cm^3)"
                )
                continue
            h = hc[i] if np.isfinite(hc[i]) else h0[i] * (1.0 - dv[i] / v0) ** (1.0 / 3.0)
            out[i], src[i] = np.sqrt(4.0 * (v0 - dv[i]) / h / np.pi), "dV_c"
        elif np.isfinite(d0[i]):
            out[i], src[i] = d0[i], "D0"
    return out, src


def skempton_a_of_curves(table: Table, at_peak: dict) -> tuple[np.ndarray, list[str]]:
    """Skempton's A at failure of every test whose curve logs the pore pressure, and the notes on B and Δσ3.

    A = (Δu − B Δσ3)/(B (Δσ1 − Δσ3)) with the changes over the shear stage, from its first reading to the
    peak (Skempton 1954; Morvan et al. 2016, eq. 1): Δσ1 − Δσ3 = Δq, for saturated tests sheared undrained
    (not where the pore pressure stayed within the pressure tolerance over the whole shear stage, a drained
    shear; noted). B is the tests table's column ``B``, else the B check of the export
    (capred.pipelines.triaxial_curves.b_check: Δu/Δσ3 of its B-check stage, never the shear stage's running
    ``B Value``), else 1 (a saturated specimen; said in a note). A B check outside (0, 1] leaves A uncomputed
    (warned about where it was read). Δσ3 is the change of the export's radial pressure (0, said in a note,
    when it logs none).

    Parameters
    ----------
    table : Table
        The tests table (test_id, optional B).
    at_peak : dict
        Test id -> changes over the shear stage up to the peak: ``du``, ``dq``, ``dsigma3`` [Pa], the range of
        the pore pressure over the stage ``du_range`` [Pa], the export's B check ``B`` [-] and ``B_source``
        ("b_check", "none" or "invalid").

    Returns
    -------
    A : ndarray
        Skempton's A per test [-] (NaN without pore pressures or without a rise of q).
    notes : list of str

    References
    ----------
    .. [1] Skempton, A. W. (1954). The pore-pressure coefficients A and B. Geotechnique 4(4), 143-147.
       doi:10.1680/geot.1954.4.4.143
    .. [2] Morvan, M., Vernay, M. & Breul, P. (2016). Study of the variation of B with Sr. E-UNSAT 2016,
       E3S Web of Conferences, eq. 1.
    """
    n = len(table)
    A = np.full(n, np.nan)
    b_col = table.get("B")
    assumed_b, assumed_s3, drained = [], [], []
    for i in range(n):
        tid = str(table.columns["test_id"][i])
        st = at_peak.get(tid)
        if not st or not np.isfinite(st.get("du", np.nan)) or not st.get("dq", np.nan) > 0:
            continue
        if table.columns["condition"][i] != "saturated":
            continue  # A is a saturated specimen's undrained response; axis translation controls u_w
        if st.get("du_range", np.nan) <= pressure_tolerance(st.get("pore_pressure", np.nan)):
            drained.append(tid)  # the pore pressure never moved in the shear stage: drained, A has no meaning
            continue
        B = b_col[i] if np.isfinite(b_col[i]) else st.get("B", np.nan)
        if not np.isfinite(B) and st.get("B_source") == "invalid":
            continue  # the export's B check is outside (0, 1]: no A rather than a wrong one
        if not np.isfinite(B):
            B = 1.0
            assumed_b.append(tid)
        ds3 = st["dsigma3"]
        if not np.isfinite(ds3):
            ds3 = 0.0
            assumed_s3.append(tid)
        A[i] = (st["du"] - B * ds3) / (B * st["dq"])
    notes = []
    if assumed_b:
        notes.append(
            "Skempton's A with B = 1 (a saturated specimen; the export has no B-check stage; give a column 'B' "
            f"to use another): {', '.join(assumed_b)}"
        )
    if assumed_s3:
        notes.append(f"Skempton's A with Δσ3 = 0 (the export logs no radial pressure): {', '.join(assumed_s3)}")
    if drained:
        notes.append(
            "Skempton's A not computed for tests sheared drained (the pore pressure stayed within the pressure "
            "tolerance over the whole shear stage): " + ", ".join(drained)
        )
    return A, notes


@dataclass
class _PorePressureLog:
    """What :func:`pore_pressures` notes and warns about while it goes through the tests."""

    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    filled_s3: list[str] = field(default_factory=list)  # sigma3 taken from the export's radial pressure
    from_export: list[str] = field(default_factory=list)  # pore pressure taken from the export
    already: list[str] = field(default_factory=list)  # sigma3 already effective

    def close(self) -> None:
        """The notes that name the tests of each list, once every test has been seen."""
        if self.filled_s3:
            self.notes.append(f"sigma3 taken from the export's radial pressure at failure: {', '.join(self.filled_s3)}")
        if self.from_export:
            self.notes.append(
                f"pore pressure taken from the export at failure (sigma' = sigma - u_w saturated, "
                f"sigma - u_a unsaturated): {', '.join(self.from_export)}"
            )
        if self.already:
            self.notes.append(
                f"sigma3 already effective (= radial pressure - pore pressure of the export): {', '.join(self.already)}"
            )


def _initial_suction_from_export(tids, sat, s0, at_peak: dict, log: _PorePressureLog) -> None:
    """Fill blank s0 of unsaturated tests with the export's matric suction at the start of the shear stage."""
    suction0 = np.array([at_peak.get(t, {}).get("suction_initial", np.nan) for t in tids])
    took = np.isnan(s0) & ~sat & np.isfinite(suction0)
    if took.any():  # the export's Matric Suction at the first reading of the shear stage is the initial suction
        s0[took] = suction0[took]
        log.notes.append(
            "s0 taken from the export's matric suction at the start of the shear stage: "
            + ", ".join(f"{tids[i]} ({s0[i] / 1e3:.4g} kPa)" for i in np.flatnonzero(took))
        )


def _table_and_export_pore_pressure(
    table: Table, i: int, tid: str, sat: bool, ub_col, ua_col, exp: dict, s0, log: _PorePressureLog
) -> tuple[float, float]:
    """The pore pressure of test ``i`` from the table and from the export [Pa] (NaN where not given).

    A saturated test's is its back pressure u_w, an unsaturated test's its pore-air pressure u_a (axis
    translation); a blank s0 of an unsaturated test is filled with u_a - u_w where both are known.
    """
    if sat:
        if np.isfinite(ua_col[i]):
            table.add_problem(
                i,
                "u_a",
                "u_a is for unsaturated tests (net stress sigma - u_a); the pore "
                "pressure of a saturated test is its back_pressure",
            )
        u_tab = ub_col[i]
        u_exp = exp["pore_pressure"][i] if np.isfinite(exp["pore_pressure"][i]) else exp["back_pressure"][i]
        return u_tab, u_exp
    u_tab = ua_col[i]
    u_exp = exp["air_pressure"][i]
    u_w = ub_col[i] if np.isfinite(ub_col[i]) else exp["back_pressure"][i]
    if np.isfinite(ub_col[i]) and not (np.isfinite(ua_col[i]) or np.isfinite(u_exp)):
        table.add_problem(
            i,
            "back_pressure",
            "an unsaturated test's back pressure is the pore-water "
            "pressure of axis translation: give the pore-air pressure 'u_a' too (the "
            "stresses are net of u_a)",
        )
    u_a = u_tab if np.isfinite(u_tab) else u_exp
    if np.isnan(s0[i]) and np.isfinite(u_a) and np.isfinite(u_w):
        s0[i] = u_a - u_w
        log.notes.append(f"test '{tid}': s0 = u_a - u_w = {s0[i] / 1e3:.4g} kPa (axis translation)")
    return u_tab, u_exp


def _stresses_are_total(
    tid: str, cell: float, name: str, radial: float, u_tab: float, u_exp: float, log: _PorePressureLog
) -> bool:
    """Whether the table's cell stress ``name`` = ``cell`` [Pa] is total, against the export's radial pressure.

    Equal within :func:`pressure_tolerance` -> total; equal to radial - u -> already effective; otherwise the
    table's value stays total and a warning says so.
    """
    u_known = u_tab if np.isfinite(u_tab) else u_exp
    if abs(cell - radial) <= pressure_tolerance(radial):
        return True
    if (
        np.isfinite(u_known)
        and abs(u_known) > pressure_tolerance(radial)
        and abs(cell - (radial - u_known)) <= pressure_tolerance(radial)
    ):
        log.already.append(tid)
        if np.isfinite(u_tab):
            log.warnings.append(
                f"test '{tid}': {name} = {cell / 1e3:.4g} kPa equals the export's radial "
                f"pressure {radial / 1e3:.4g} kPa minus the pore pressure {u_known / 1e3:.4g} kPa: "
                "the table's stresses are already effective; the pore pressure of the table "
                "is not subtracted again"
            )
        return False
    # a drifting cell: the table's stress is still total, never taken as effective (issue 39)
    u_sub = u_tab if np.isfinite(u_tab) else u_exp
    sub = (
        f"; the pore pressure {u_sub / 1e3:.4g} kPa is subtracted from it as from any total stress"
        if np.isfinite(u_sub) and u_sub != 0
        else ""
    )
    log.warnings.append(
        f"test '{tid}': {name} = {cell / 1e3:.4g} kPa in the table but the export's radial "
        f"pressure at failure is {radial / 1e3:.4g} kPa ("
        + (f"{(radial - cell) / cell * 100:+.2g} %, " if cell else "")
        + f"tolerance {pressure_tolerance(radial) / 1e3:.3g} kPa, ASTM D4767): the table's value is used"
        f"{sub}"
    )
    return True


def pore_pressures(table: Table, at_peak: dict[str, dict[str, float]], q, ext=None) -> dict:
    """The pore pressure to subtract from each test's stresses and whether the table's stresses are total.

    Saturated tests: sigma' = sigma - u_w with u_w the ``back_pressure``
    column, else the export's pore pressure at the peak, else its back
    pressure (Terzaghi). Unsaturated tests under axis translation: the net
    stress sigma - u_a with u_a the ``u_a`` column, else the export's pore-air
    pressure (Fredlund & Morgenstern 1977 stress state variables). The table's
    sigma3 is compared with the export's radial pressure at the peak
    (sigma1 in extension, where the cell pressure is the major stress) within
    :func:`pressure_tolerance`: equal -> total stresses (the pore pressure is
    subtracted); equal to radial - u -> already effective (not subtracted
    again); otherwise a warning. Problems are added to ``table``.

    Parameters
    ----------
    table : Table
        The tests table (test_id, condition, sigma3, s0, back_pressure, u_a) [Pa].
    at_peak : dict
        Test id -> the export's pressures at the peak [Pa] (radial, back, pore and air pressure).
    q : ndarray
        Deviator at failure of each test [Pa].
    ext : ndarray of bool, optional
        Extension tests (their cell pressure is sigma1); default none.

    Returns
    -------
    dict
        ``u`` [Pa] subtracted per test, ``u_b``, ``u_a`` [Pa] (NaN where
        unknown), ``radial`` [Pa] (the export's, NaN without one),
        ``sigma3`` [Pa] (the table's, blank cells filled from the export),
        ``s0`` [Pa] (blank cells filled with u_a - u_b), ``notes``,
        ``warnings``.
    """
    n = len(table)
    tids = [str(t) for t in table.columns["test_id"]]
    sat = table.columns["condition"] == "saturated"
    s3 = table.columns["sigma3"].copy()
    s0 = table.get("s0").copy()
    ub_col, ua_col = table.get("back_pressure").copy(), table.get("u_a").copy()
    if ext is None:
        ext = np.zeros(n, bool)
    exp = {
        k: np.array([at_peak.get(t, {}).get(k, np.nan) for t in tids])
        for k in ("radial_pressure", "back_pressure", "pore_pressure", "air_pressure")
    }
    u = np.zeros(n)
    log = _PorePressureLog()
    _initial_suction_from_export(tids, sat, s0, at_peak, log)
    for i in range(n):
        tid = tids[i]
        u_tab, u_exp = _table_and_export_pore_pressure(table, i, tid, sat[i], ub_col, ua_col, exp, s0, log)
        radial = exp["radial_pressure"][i]
        if np.isnan(s3[i]) and np.isfinite(radial) and not ext[i]:
            s3[i] = radial
            log.filled_s3.append(tid)
        total = np.isfinite(u_tab)
        if np.isfinite(radial) and np.isfinite(s3[i]):
            cell = s3[i] + q[i] if ext[i] else s3[i]
            total = _stresses_are_total(tid, cell, "sigma1" if ext[i] else "sigma3", radial, u_tab, u_exp, log)
        if total:
            if np.isfinite(u_tab):
                u[i] = u_tab
            elif np.isfinite(u_exp):
                u[i] = u_exp
                log.from_export.append(tid)
    log.close()
    ub = np.where(sat, np.where(np.isfinite(ub_col), ub_col, np.where(u != 0, u, np.nan)), ub_col)
    ua = np.where(~sat, np.where(np.isfinite(ua_col), ua_col, np.where(u != 0, u, np.nan)), np.nan)
    return {
        "u": u,
        "u_b": ub,
        "u_a": ua,
        "radial": exp["radial_pressure"],
        "sigma3": s3,
        "s0": s0,
        "notes": log.notes,
        "warnings": log.warnings,
    }


@dataclass
class _Loaded:
    """The tests table read and checked, its raw curves (``--curves``) and the failure deviator of each test.

    ``d`` is :func:`load_triaxial_table`'s (``q`` [Pa], ``strain`` [-], ``from_curve``); ``D_c`` [m] and
    ``D_c_source`` are :func:`consolidated_diameter`'s, None without a membrane correction.
    """

    table: Table
    raw_curves: object | None
    d: dict
    D_c: np.ndarray | None
    D_c_source: np.ndarray | None

    @property
    def at_peak(self) -> dict:
        """Test id -> the export's readings at the peak (empty without curves)."""
        return self.raw_curves.at_peak if self.raw_curves else {}


@dataclass
class _Stresses:
    """Each test's stresses at failure net of its pore pressure [Pa], with its Lode angle [deg] and branch."""

    q: np.ndarray
    dq: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray
    s3_total: np.ndarray
    u: np.ndarray
    p0: np.ndarray
    s0: np.ndarray
    lode: np.ndarray
    branch: np.ndarray
    axi: np.ndarray
    phys_branch: np.ndarray
    pp: dict


def _read_tests(source, opt: TriaxialOptions) -> _Loaded:
    """Read the tests table of one material and its raw curves; the failure deviator of every test."""
    curves = opt.curves
    table = read_table(source, SCHEMA)
    table, material = one_material(table, opt.material)  # one envelope per run: never pooled (issue 40)
    if material is not None:
        table.notes.append(f"material: {material or '(blank)'}")
    raw_curves = None
    D_c, D_c_source = consolidated_diameter(table) if opt.membrane is not None else (None, None)
    if curves is not None:
        from .triaxial_curves import read_curves

        dc = (
            None
            if D_c is None
            else {str(t): x for t, x, w in zip(table.columns["test_id"], D_c, D_c_source) if w in ("D_c", "dV_c")}
        )
        # --ignore-column applies to every file the command reads; a name no file has is warned about once
        raw_curves = read_curves(curves, table, opt.membrane, dc, getattr(source, "ignore_columns", ()))
        table.forget_ignores(raw_curves.ignores_used)
        table.problems += raw_curves.problems  # reported with the table's own, in one round
        table.notes += raw_curves.notes
        table.warnings += raw_curves.warnings
    table, d = load_triaxial_table(table, raw_curves.peaks if raw_curves else None)
    table.raise_if_problems()
    return _Loaded(table, raw_curves, d, D_c, D_c_source)


def _membrane_corrected(loaded: _Loaded, opt: TriaxialOptions, notes: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """The deviator at failure [Pa] after the membrane correction (ASTM D4767-11), and the correction [Pa].

    A curve's readings were corrected before its peak; the others are corrected here with the strain at
    failure and the diameter after consolidation. Problems are added to the table.
    """
    table, d, D_c, D_c_source = loaded.table, loaded.d, loaded.D_c, loaded.D_c_source
    q = d["q"].copy()
    dq = np.zeros(len(table))
    if opt.membrane is None:
        notes.append(
            "no membrane correction of the deviator (give --membrane-thickness and --membrane-modulus "
            "to apply ASTM D4767-11's)"
        )
        return q, dq
    from .triaxial_curves import membrane_correction

    at = loaded.at_peak
    initial = []
    for i in range(len(table)):
        tid = str(table.columns["test_id"][i])
        if d["from_curve"][i]:
            dq[i] = at[tid]["membrane"]
            if at[tid].get("diameter_source") == "D0":
                initial.append(tid)
            continue
        need = [
            w
            for w, ok in (
                ("'strain_at_failure'", np.isfinite(d["strain"][i])),
                ("'D_c' (or 'D0')", np.isfinite(D_c[i])),
            )
            if not ok
        ]
        if need:
            table.add_problem(
                i,
                "test_id",
                f"the membrane correction of '{tid}' needs {' and '.join(need)} (or its raw curve with --curves)",
            )
            continue
        dq[i] = float(membrane_correction(d["strain"][i], D_c[i], *opt.membrane))
        if D_c_source[i] == "D0":
            initial.append(tid)
    q = q - np.where(d["from_curve"], 0.0, dq)  # a curve's readings were corrected before its peak
    for i in np.flatnonzero(q <= 0):
        table.add_problem(int(i), "test_id", f"after the membrane correction ({dq[i] / 1e3:.4g} kPa) q_f <= 0")
    t_m, E_m = opt.membrane
    notes.append(
        f"membrane correction of the deviator (ASTM D4767-11): Δq = 4 E_m t_m ε_a / D_c with "
        f"t_m = {t_m * 1e3:.4g} mm, E_m = {E_m / 1e3:.4g} kPa and D_c the diameter after consolidation "
        "(column 'D_c', or from the volume decrease 'dV_c' with D0 and H0)"
    )
    if initial:
        notes.append(
            "membrane correction with the initial diameter D0 for want of the diameter after consolidation "
            f"(give 'D_c' or 'dV_c'): {', '.join(initial)}; a consolidation that reduces the diameter by "
            "x % underestimates the correction by about x %"
        )
    return q, dq


def _branch_column(table: Table) -> np.ndarray:
    """The ``branch`` column in lower case ('' where blank or absent); other values are problems."""
    branch_col = (
        np.array([str(x).strip().lower() for x in table.columns["branch"]], dtype=object)
        if "branch" in table.columns
        else np.array([""] * len(table), dtype=object)
    )
    for i in np.flatnonzero(~np.isin(branch_col, ("", "compression", "extension"))):
        table.add_problem(
            int(i),
            "branch",
            f"'{table.value_text('branch', int(i))}' is not one of 'compression' "
            "or 'extension' (or blank: the branch follows from sigma2)",
        )
    return branch_col


def _net_stresses(
    loaded: _Loaded, q: np.ndarray, dq: np.ndarray, sat: np.ndarray, notes: list[str], warnings: list[str]
) -> _Stresses:
    """Every test's stresses net of its pore pressure (Terzaghi saturated, u_a unsaturated), Lode angle, branch.

    Raises the table's problems once sigma3 is known; the later problems (a negative net sigma3, sigma2
    outside [sigma3, sigma1], a branch that its sigma2 contradicts) are added to the table.
    """
    table = loaded.table
    branch_col = _branch_column(table)
    s2_raw = table.get("sigma2")
    ext_raw = (branch_col == "extension") | (np.abs(s2_raw - (table.columns["sigma3"] + q)) <= 1e-9 * np.abs(s2_raw))
    pp = pore_pressures(table, loaded.at_peak, q, ext_raw)
    notes += pp["notes"]
    warnings += pp["warnings"]
    u = pp["u"]
    for i in np.flatnonzero(np.isnan(pp["sigma3"])):
        table.add_problem(int(i), "sigma3", "sigma3 is blank")
    table.raise_if_problems()
    s3_total = pp["sigma3"]
    s3 = s3_total - u
    s1 = s3 + q
    s2 = s2_raw - u
    s2 = np.where(np.isnan(s2), np.where(branch_col == "extension", s1, s3), s2)
    lode = np.asarray(tx.lode_angle_deg(s1, s2, s3), float)
    branch = np.atleast_1d(tx.lode_branch(s1, s2, s3)).astype(object)
    for i in np.flatnonzero((branch_col != "") & (branch != branch_col)):
        table.add_problem(
            int(i),
            "branch",
            f"branch '{branch_col[i]}' but sigma2 = {s2_raw[i] / 1e3:.4g} kPa gives a "
            f"Lode angle of {lode[i]:.3g} deg ({branch[i]}; compression is 0, extension 60, within "
            f"{tx.LODE_TOL_DEG:g} deg)",
        )
    axi = branch != "general"
    phys_branch = np.where(axi, branch, "compression")
    p0 = table.get("p0") - u
    p0[np.isnan(p0)] = s3[np.isnan(p0)]
    for i in np.flatnonzero(s3 < 0):
        kind = "effective" if sat[i] else "net"
        table.add_problem(
            int(i),
            "sigma3",
            f"the {kind} confining stress sigma3 - {'u_b' if sat[i] else 'u_a'} = {s3[i] / 1e3:.4g} kPa is negative",
        )
    for i in np.flatnonzero(np.isfinite(s2_raw)):
        if not s3[i] * (1 - 1e-12) <= s2[i] <= s1[i] * (1 + 1e-12):
            table.add_problem(i, "sigma2", "sigma2 must lie between sigma3 and sigma1")
    if np.any(u != 0):
        notes.append(
            "stresses net of the pore pressure: sigma' = sigma - u_b (saturated tests, Terzaghi), "
            "sigma - u_a (unsaturated tests, axis translation); sigma3_total_kPa keeps the cell pressure"
        )
    return _Stresses(q, dq, s1, s2, s3, s3_total, u, p0, pp["s0"], lode, branch, axi, phys_branch, pp)


def _effective_envelope(
    table: Table, opt: TriaxialOptions, sat: np.ndarray, st: _Stresses, notes: list[str]
) -> Envelope | None:
    """The effective envelope c', phi': given, fitted on the saturated tests, or at s -> 0 of the unsaturated.

    None where the saturated tests give none (the problem is added to the table).
    """
    unsat = ~sat
    if opt.c_eff is not None:
        env = Envelope(c_kPa=opt.c_eff / KPA, phi_deg=opt.phi_eff, source="options")
        if sat.any():
            notes.append("envelope taken from --c-eff/--phi-eff; the saturated tests are only plotted")
        return env
    if sat.sum() == 0:
        try:  # issue 40: the unsaturated failure states fix c', phi' at s -> 0 (named as such)
            env = zero_suction_envelope(
                st.s3[unsat], st.s1[unsat], table.get("s0")[unsat], st.branch[unsat], opt.confidence
            )
            notes.append(f"no saturated test: {EXTENDED_MC_METHOD}; --c-eff/--phi-eff override it")
            return env
        except FitError as exc:
            table.add_problem(
                None,
                "condition",
                "no saturated test and no envelope given: add saturated drained tests or pass --c-eff and --phi-eff "
                f"(the envelope at s -> 0 of the unsaturated tests needs their suction s0: {exc})",
            )
            table.raise_if_problems()  # raises: the problem just added
    try:
        return fit_envelope(st.s3[sat], st.s1[sat], opt.confidence)
    except FitError as exc:
        first = int(np.flatnonzero(sat)[0])
        table.add_problem(
            first,
            "condition",
            f"effective envelope from the saturated tests: {exc} (or pass --c-eff and --phi-eff)",
        )
        return None


def _groups_and_pairs(table: Table, sat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ``group`` and ``pair`` columns ('' where absent), checked: problems are added to the table."""
    groups = table.get("group") if "group" in table.columns else np.array([""] * len(table), dtype=object)
    pairs = table.columns["pair"] if "pair" in table.columns else np.array([""] * len(table), dtype=object)
    for g in set(groups) - {""}:
        members = np.flatnonzero(groups == g)
        if len(members) < 2:
            table.add_problem(int(members[0]), "group", f"group '{g}' has one test: a shared tensor needs at least two")
        elif sat[members].any():
            table.add_problem(
                int(members[sat[members]][0]),
                "group",
                f"group '{g}' holds a saturated test; groups are for unsaturated tests",
            )
        elif 0 < sum(bool(x) for x in pairs[members]) < len(members):
            table.add_problem(
                int(members[0]),
                "pair",
                f"group '{g}': give a paired saturated test for every test of the group, or for none",
            )
    ids = {str(x): i for i, x in enumerate(table.columns["test_id"])}
    for i in np.flatnonzero(pairs != ""):
        j = ids.get(str(pairs[i]))
        if sat[i]:
            table.add_problem(
                int(i),
                "pair",
                "a pair is the saturated test paired with an unsaturated one; give it on the unsaturated test's row",
            )
        elif j is None:
            table.add_problem(int(i), "pair", f"no test '{pairs[i]}' in the table")
        elif not sat[j]:
            table.add_problem(int(i), "pair", f"'{pairs[i]}' is not a saturated test")
    return groups, pairs


def _negative_cohesion_warning(env: Envelope, u: np.ndarray, sat: np.ndarray) -> list[str]:
    """A warning where c' < 0: no physical meaning, and the bounds rest on it."""
    if env.c_kPa * KPA >= 0:
        return []
    hint = (
        "; if sigma3 is the cell pressure of back-pressured tests, give their 'back_pressure' (sigma' = sigma - u_b)"
        if not np.any(u[sat] != 0)
        else ""
    )
    return [
        f"c' = {env.c_kPa:.4g} kPa < 0 from the saturated tests: a negative cohesion has no "
        f"physical meaning and the bounds below rest on it{hint}"
    ]


def _capillary_bounds(
    table: Table, st: _Stresses, unsat: np.ndarray, c_eff: float, phi_eff: float, opt: TriaxialOptions, notes: list
) -> dict[str, tx.Bound]:
    """The spherical, lower and EDTP bounds of every unsaturated axisymmetric test (NaN elsewhere) [Pa]."""
    s1, s3, axi, phys_branch, s0 = st.s1, st.s3, st.axi, st.phys_branch, st.s0
    nan = np.full(len(table), np.nan)
    bounds = {}
    s0_or_0 = np.where(np.isnan(s0), 0.0, s0)
    for name, b in (
        ("spherical", tx.spherical_bound(s1, s3, c_eff, phi_eff, phys_branch)),
        ("lower", tx.lower_bound(s1, s3, c_eff, phi_eff, phys_branch)),
        ("edtp", tx.edtp_bound(s1, s3, st.p0, s0_or_0, c_eff, phi_eff, phys_branch, opt.extension_slope)),
    ):
        keep = unsat & axi if name != "edtp" else unsat & axi & np.isfinite(s0)
        bounds[name] = tx.Bound(
            *(
                np.where(keep, getattr(b, f), nan)
                for f in ("sigma1_cap", "sigma3_cap", "p_prime", "q_prime", "sigma2_cap")
            )
        )
    if (unsat & axi & np.isnan(s0)).any():
        notes.append("EDTP bound skipped where s0 (initial suction) is not given")
    if (unsat & ~axi).any():
        notes.append(
            "bounds (section 4 of Prunier et al. 2024) are for axisymmetric tests: none for the "
            f"true-triaxial tests {', '.join(str(x) for x in table.columns['test_id'][unsat & ~axi])}; "
            "a group of them at one Lode angle gets eq. 50"
        )
    if (st.branch == "extension").any():
        notes.append(
            "extension tests (sigma2 = sigma1) use the extension form of the criterion, "
            "M = 6 sin phi'/(3 + sin phi'), in the bounds, q'_sat and the figures; their saturated reference "
            f"strength q'_sat and EDTP bound follow the path '{opt.extension_path}' (slope "
            f"{opt.extension_slope:g} in the q-p plane; --extension-path)"
        )
    return bounds


def _test_columns(
    table: Table, st: _Stresses, groups, pairs, strain: np.ndarray, opt: TriaxialOptions
) -> dict[str, np.ndarray]:
    """Per test, the columns of the group analysis and of the records (SI, the old keys)."""
    nan = np.full(len(table), np.nan)
    return {
        "test_id": table.columns["test_id"],
        "condition": table.columns["condition"],
        "group": groups,
        "line": table.lines,
        "sigma1": st.s1,
        "sigma2": st.s2,
        "sigma3": st.s3,
        "p": tx.mean_stress(st.s1, st.s3, st.s2),
        "q": st.q,
        "p0": st.p0,
        "s0": st.s0,
        "strain_f": strain,
        "lode": st.lode,
        "branch": st.branch,
        "pair": pairs,
        "sigma3_total": st.s3_total,
        "back_pressure": st.pp["u_b"],
        "u_a": st.pp["u_a"],
        "radial_pressure": st.pp["radial"],
        "membrane": np.where(st.dq != 0, st.dq, np.nan) if opt.membrane is not None else nan,
    }


def _test_states(
    loaded: _Loaded, tests: dict, unsat: np.ndarray, q_sat: np.ndarray, notes: list[str], warnings: list[str]
) -> rec.TestStates:
    """The records of every test [kPa], with Skempton's A and the export's state at failure."""
    table = loaded.table
    A, note_A = skempton_a_of_curves(table, loaded.at_peak)
    notes += note_A
    unsat_state, note_state, warn_state = export_states(table, loaded.at_peak)
    notes += note_state
    warnings += warn_state
    return rec.TestStates(
        **{k: tests[k] for k in _TEXT_FIELDS},
        **{
            f.name: np.asarray(tests[{v: k for k, v in _OLD_TEST_KEYS.items()}.get(f.name, f.name)], float)
            * (1.0 if f.name in ("lode_angle", "strain_at_failure") else 1 / KPA)
            for f in dataclasses.fields(rec.TestStates)
            if f.name not in _TEXT_FIELDS and f.name not in ("q_sat", "skempton_A", "suction", "S_R", "void_ratio")
        },
        q_sat=np.where(unsat, q_sat, np.nan) / KPA,
        skempton_A=A,
        suction=unsat_state["suction"] / KPA,
        S_R=unsat_state["S_R"],
        void_ratio=unsat_state["void_ratio"],
    )


def _bound_states(bounds: dict[str, tx.Bound], q_sat: np.ndarray) -> dict[str, rec.BoundStates]:
    """The records of each bound [kPa], with the strength gain q'/q'_sat."""
    bound_states = {}
    for name, b in bounds.items():
        s2c = b.sigma3_cap if b.sigma2_cap is None else b.sigma2_cap
        with np.errstate(invalid="ignore", divide="ignore"):
            gain = b.q_prime / q_sat
        bound_states[name] = rec.BoundStates(
            sigma1_cap=b.sigma1_cap / KPA,
            sigma2_cap=s2c / KPA,
            sigma3_cap=b.sigma3_cap / KPA,
            p_cap=b.p_cap / KPA,
            q_cap=b.q_cap / KPA,
            p_prime=b.p_prime / KPA,
            q_prime=b.q_prime / KPA,
            gain=np.where(np.isfinite(b.sigma1_cap), gain, np.nan),
            positive_component=np.asarray(b.positive, bool),
        )
    return bound_states


def _figure_curves(loaded: _Loaded) -> tuple[dict, dict]:
    """The raw curves that gave a test's failure deviator, and those of the table's other tests (for reference)."""
    raw_curves = loaded.raw_curves
    if not raw_curves:
        return {}, {}
    # the curves that gave a test's failure deviator, for the q-eps1 and epsv-eps1 figures
    table = loaded.table
    used = {str(t) for t, f in zip(table.columns["test_id"], loaded.d["from_curve"]) if f}
    curves_used = {t: c for t, c in raw_curves.curves.items() if t in used}
    # the others of the table's tests: their q_f wins, their curves are drawn for reference
    listed = {str(t) for t in table.columns["test_id"]}
    reference = {t: c for t, c in raw_curves.curves.items() if t in listed and t not in used}
    return curves_used, reference


def run_triaxial_bounds(
    source, options: TriaxialOptions | None = None, curves: str | Path | None = None
) -> TriaxialResult:
    """Envelope, bounds and group analysis of a triaxial table (see module docstring).

    ``source`` is a CSV path or a DataFrame; ``curves`` (or ``options.curves``)
    a long CSV of raw curves. Stresses in the table are total unless a pore
    pressure says otherwise: ``back_pressure`` (saturated tests,
    sigma' = sigma - u_b) and ``u_a`` (unsaturated tests, net stress
    sigma - u_a) are subtracted from sigma3, sigma1, sigma2 and p0.

    Parameters
    ----------
    source : str or Path or DataFrame
        The triaxial tests (test_id, condition, sigma3, q_f or sigma1, S_r, e, ... ).
    options : TriaxialOptions, optional
        Effective envelope, membrane correction, extension path (SI).
    curves : str or Path, optional
        Raw curves: a file, a folder or a glob (default: ``options.curves``).

    Returns
    -------
    TriaxialResult
        The effective envelope, per test the spherical, lower and EDTP bounds, and the groups.

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J., Darve, F. (2024). A method to evaluate the capillary stress
       tensor at failure in unsaturated soils. Eur. J. Environ. Civ. Eng. doi:10.1080/19648189.2024.2314099

    Example
    -------
    >>> r = capred.run_triaxial_bounds(capred.sample_path("triaxial-bounds"))  # doctest: +SKIP
    >>> r.to_json()["tests"][4]["spherical"]["p_cap_kPa"]                     # doctest: +SKIP
    """
    opt = options or TriaxialOptions()
    if curves is not None:
        opt = dataclasses.replace(opt, curves=curves)
    loaded = _read_tests(source, opt)
    table, raw_curves = loaded.table, loaded.raw_curves
    notes = list(table.notes)
    warnings = list(opt.warnings) + list(table.warnings)

    sat = table.columns["condition"] == "saturated"
    unsat = ~sat
    q, dq = _membrane_corrected(loaded, opt, notes)
    notes += reference_curves_notes(
        table.columns["test_id"], q, loaded.d["from_curve"], raw_curves.peaks if raw_curves else {}
    )
    st = _net_stresses(loaded, q, dq, sat, notes, warnings)
    env = _effective_envelope(table, opt, sat, st, notes)
    groups, pairs = _groups_and_pairs(table, sat)
    table.raise_if_problems()
    c_eff, phi_eff = env.c_kPa * KPA, env.phi_deg  # SI for the physics
    warnings += _negative_cohesion_warning(env, st.u, sat)

    bounds = _capillary_bounds(table, st, unsat, c_eff, phi_eff, opt, notes)
    q_sat = tx.drained_strength(st.p0, c_eff, phi_eff, st.phys_branch, opt.extension_slope)
    tests = _test_columns(table, st, groups, pairs, loaded.d["strain"], opt)
    inputs = [input_file(source, table)] + ([input_file(t.path, t) for t in raw_curves.tables] if raw_curves else [])
    group_records = _group_analysis(tests, c_eff, phi_eff)
    for g in group_records:
        notes += [f"group {g.group}: {v}" for v in (g.needs, g.warning) if v]
    states = _test_states(loaded, tests, unsat, q_sat, notes, warnings)
    curves_used, reference = _figure_curves(loaded)
    return TriaxialResult(
        table.path,
        env,
        states,
        _bound_states(bounds, q_sat),
        group_records,
        notes,
        opt,
        inputs,
        warnings,
        curves_used,
        reference,
    )


def _ci95(value: float, se: float, dof: int) -> tuple | None:
    """(low, high) [kPa] of value +- t(0.975, dof) se (values in Pa), None without a finite se."""
    from scipy.stats import t as student

    if dof < 1 or not np.isfinite(se):
        return None
    h = float(student.ppf(0.975, dof)) * se
    return (_kpa(value - h), _kpa(value + h))


def _tensor_fields(gt: tx.GroupTensor) -> dict:
    """The GroupRecord fields of a group's capillary tensor (eq. 48 or 50) [kPa], [deg]."""
    out = {}
    for k in ("sigma1_cap", "sigma2_cap", "sigma3_cap"):
        v, se = getattr(gt, k), getattr(gt, k + "_se")
        out[k], out[f"{k}_se"], out[f"{k}_ci95"] = _kpa(v), _kpa(se), _ci95(v, se, gt.dof)
    out.update(
        {
            "p_cap": _kpa(gt.p_cap),
            "q_cap": _kpa(gt.q_cap),
            "dof": gt.dof,
            "C": _kpa(gt.C_apparent),
            "C_se": _kpa(gt.C_apparent_se),
            "C_fictive": _kpa(gt.C_fictive),
            "C_fictive_se": _kpa(gt.C_fictive_se),
            "Ci": _kpa(gt.Ci_apparent),
            "Ci_fictive": _kpa(gt.Ci_fictive),
            "phi_i": num(gt.phi_i_deg),
            "phi_apparent_se": num(gt.phi_apparent_se_deg),
        }
    )
    return out


def closures(C_apparent: float, c_eff: float, phi_eff: float, branch: str) -> tuple[list, rec.Admissible]:
    """The closures of eq. 48 a group without paired saturated tests allows, and the range between them.

    Eq. 37 and 43 of Prunier et al. (2024) give one equation for an axisymmetric tensor (mean m, half
    difference d of the axial and radial components, compression positive):
    (C − C') cos φ' = d − m sin φ'. The paper closes it two ways, the group analogues of its bounds: the
    lower bound σ1,cap = 0 (eq. 24; capillary stresses are tensile, eq. 20) and the spherical tensor
    (eq. 37, the upper bound q = q'). Every tensor between the two satisfies eq. 37 with both components
    tensile; each component's range runs between its values under the two closures.

    Parameters
    ----------
    C_apparent, c_eff : float
        Apparent cohesion C of the group and effective cohesion C' [Pa].
    phi_eff : float
        Effective friction angle φ' [deg].
    branch : str
        ``"compression"`` (σ2,cap = σ3,cap radial) or ``"extension"`` (σ2,cap = σ1,cap radial).

    Returns
    -------
    list of Closure, Admissible
        The closures (``sigma1_cap_zero`` chosen) and the per-component range [kPa].

    References
    ----------
    .. [1] Prunier, F., Branque, D., Duriez, J. & Darve, F. (2024). Eur. J. Environ. Civ. Eng.
       doi:10.1080/19648189.2024.2314099, eq. 20, 24, 37, 43, 48.
    """
    lower_c2 = tx.fictive_cohesion_lower(C_apparent, c_eff, phi_eff)
    a1, a3 = tx.axisymmetric_group_cap(C_apparent, lower_c2, c_eff, phi_eff)
    sph = float(tx.spherical_group_cap(C_apparent, c_eff, phi_eff))
    out = []
    for name, label, chosen, (s1c, s3c) in (
        ("sigma1_cap_zero", "σ1,cap = 0 (the lower bound, eq. 24)", True, (float(a1), float(a3))),
        ("spherical", "spherical tensor σ1,cap = σ2,cap = σ3,cap (eq. 37)", False, (sph, sph)),
    ):
        s2c = s1c if branch == "extension" else s3c
        out.append(rec.Closure(name, label, chosen, _kpa(s1c), _kpa(s2c), _kpa(s3c), _kpa((s1c + s2c + s3c) / 3)))

    def rng(comp: str) -> rec.Range:
        a, b = (getattr(c, comp) for c in out)
        return rec.Range(min(a, b), max(a, b))

    return out, rec.Admissible(rng("sigma1_cap"), rng("sigma2_cap"), rng("sigma3_cap"), rng("p_cap"))


def _group_analysis(t: dict, c_eff: float, phi_eff: float) -> list[rec.GroupRecord]:
    """Appendix 1 of Prunier et al. (2024) for every group of unsaturated tests sharing one tensor.

    Every group gets the free regression sigma1 = K sigma3 + b through its
    failure states (apparent C, phi; eq. 35 and 43 ask phi = phi') and eq. 37
    (spherical tensor). With each test's paired saturated test (column
    ``pair``) an axisymmetric group gets eq. 48 with the fictive state sigma''
    (eq. 44-47) and a true-triaxial group at one Lode angle (eq. 49, within
    ``tx.LODE_TOL_DEG``) eq. 50, by the least squares the paper recommends
    (section 7.3), with standard errors and 95 % intervals (t, n - 1 dof).
    Without pairs the tensor is not determined: each component's admissible
    range between the closures sigma1_cap = 0 (the lower bound, eq. 24) and
    the spherical tensor (eq. 37) is given (:func:`closures`), and eq. 50 is
    not available; ``needs`` says what is missing. ``t`` holds SI arrays,
    ``c_eff`` [Pa] and ``phi_eff`` [deg] the effective envelope.
    """
    out = []
    index = {str(x): i for i, x in enumerate(t["test_id"])}
    for g in [g for g in dict.fromkeys(t["group"]) if g]:
        sel = np.flatnonzero(t["group"] == g)
        s1, s2, s3 = t["sigma1"][sel], t["sigma2"][sel], t["sigma3"][sel]
        lode = t["lode"][sel]
        branches = sorted(set(t["branch"][sel]))
        res: dict = {
            "group": g,
            "tests": [str(x) for x in t["test_id"][sel]],
            "n": int(sel.size),
            "branch": branches[0] if len(branches) == 1 else "mixed",
            "lode_angles": [num(x) for x in lode],
            "lode_spread": num(np.ptp(lode)),
            "lode_tol": tx.LODE_TOL_DEG,
            "eq49_holds": bool(np.ptp(lode) <= tx.LODE_TOL_DEG),
            "pairs": [t["pair"][i] or None for i in sel],
        }
        if len(branches) > 1:
            res["error"] = (
                f"the group mixes {' and '.join(branches)} tests: one tensor is shared by tests of "
                "one branch (and one Lode angle, eq. 49)"
            )
            out.append(rec.GroupRecord(**res))
            continue
        branch = branches[0]
        C = None
        if np.ptp(s3) > 0:
            kp, b = np.polyfit(s3, s1, 1)
            if kp > 1.0:
                C, phi = tx.envelope_from_principal_fit(kp, b)
                M_app, k_app = tx.envelope_qp(C, phi, "extension" if branch == "extension" else "compression")
                c2 = tx.fictive_cohesion_lower(C, c_eff, phi_eff)
                a1, a3 = tx.axisymmetric_group_cap(C, c2, c_eff, phi_eff)
                res.update(
                    {
                        "apparent_M": num(M_app),
                        "apparent_k": _kpa(k_app),
                        "C_apparent": _kpa(C),
                        "phi_apparent": num(phi),
                        "phi_difference": num(phi - phi_eff),
                        "eq37_sigma_cap": _kpa(tx.spherical_group_cap(C, c_eff, phi_eff)),
                        "eq48_lower": rec.Lower48(_kpa(c2), _kpa(a1), _kpa(a3)),
                    }
                )
            else:
                res["apparent_error"] = f"apparent K_p = {kp:.3g} <= 1: no apparent friction angle"
        else:
            res["apparent_error"] = "all tests of the group share one sigma3: no apparent envelope (eq. 37)"
        paired = all(t["pair"][i] for i in sel)
        p_idx = np.array([index[t["pair"][i]] for i in sel]) if paired else None
        if paired:  # the fictive state sigma'' (eq. 44): the unsaturated circle's centre, the saturated radius
            f1, f3 = tx.fictive_state(s1, s3, t["sigma1"][p_idx], t["sigma3"][p_idx])
            res.update({"fictive_sigma1": [_kpa(x) for x in f1], "fictive_sigma3": [_kpa(x) for x in f3]})
        if branch == "general" and not res["eq49_holds"]:
            res["error"] = (
                f"the Lode angles of the group spread over {np.ptp(lode):.3g} deg > "
                f"{tx.LODE_TOL_DEG:g} deg: eq. 50 needs one Lode angle (eq. 49)"
            )
        elif branch == "general" and paired:
            gt = tx.true_triaxial_group_tensor(
                s1, s2, s3, t["sigma1"][p_idx], t["sigma2"][p_idx], t["sigma3"][p_idx], c_eff, phi_eff
            )
            res["method"] = "eq. 50 (fictive state of the paired saturated tests, constant Lode angle)"
            res.update(_tensor_fields(gt))
            off = np.abs(t["lode"][p_idx] - np.mean(lode)) > tx.LODE_TOL_DEG
            if off.any():
                res["warning"] = "paired saturated tests at another Lode angle than the group: " + ", ".join(
                    str(t["test_id"][i]) for i in p_idx[off]
                )
        elif branch == "general":
            res["needs"] = (
                "eq. 50 needs, for each test, its paired saturated true-triaxial test at the same Lode "
                "angle (column 'pair' naming its test_id): the fictive state sigma'' takes its radii"
            )
        elif paired:
            gt = tx.axisymmetric_group_tensor(
                s1, s3, t["sigma1"][p_idx], t["sigma3"][p_idx], c_eff, phi_eff, branch=branch
            )
            res["method"] = "eq. 48 (fictive state sigma'' of the paired saturated tests, eq. 44-47)"
            res.update(_tensor_fields(gt))
        else:
            res["needs"] = (
                "eq. 48 with the fictive state sigma'' (eq. 44-47) needs, for each test, the saturated "
                "test that reaches the same effective state at failure (column 'pair' naming its "
                "test_id); without it eq. 37 leaves one degree of freedom: each component's admissible "
                "range is given between the closures sigma1_cap = 0 (the lower bound, eq. 24) and the "
                "spherical tensor (eq. 37)"
            )
            if C is not None:
                res["method"] = (
                    "eq. 37: admissible range between the closures sigma1_cap = 0 (chosen, eq. 24) and "
                    "spherical (no paired saturated tests: the tensor itself is not determined)"
                )
                res["closures"], res["admissible"] = closures(C, c_eff, phi_eff, branch)
                res["C"] = res["C_apparent"]
        out.append(rec.GroupRecord(**res))
    return out
