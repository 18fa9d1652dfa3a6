"""Console (and HTML) tables of `capred triaxial-bounds`."""

from __future__ import annotations

import numpy as np

from ..nomenclature import QUANTITIES
from ..nomenclature import label as header
from ..references import cite
from ..table_spec import TableSpec
from .render import fmt, magnitude, spec

_BRANCH = {"compression": "comp.", "extension": "ext.", "general": "true tx."}


def _pm(value, se, scale: float | None = None) -> str:
    """'value ± se', se omitted when unknown.

    The value and the se are 0 when 0 within rounding of ``scale``: an exact fit's standard error of 4.6e-14 kPa beside
    -10 kPa is rounding, printed 0.
    """
    if value is None:
        return "—"
    return fmt(value, scale=scale) if se is None else f"{fmt(value, scale=scale)} ± {fmt(se, 2, scale=scale)}"


def _range(r) -> str:
    """'lower to upper' of an admissible range [kPa] (0 within rounding of the range's own magnitude)."""
    scale = max(abs(r.lower), abs(r.upper)) or None
    return f"{fmt(r.lower, scale=scale)} to {fmt(r.upper, scale=scale)}"


def triaxial_tables(result) -> list[TableSpec]:
    """Envelope, then one row per unsaturated test and bound, then groups (apparent envelope and shared tensor).

    Reads the run's records (capred.pipelines.triaxial_records); headers come from the glossary.

    Parameters
    ----------
    result : capred.pipelines.triaxial.TriaxialResult
        A ``capred triaxial`` run.

    Returns
    -------
    list of capred.table_spec.TableSpec
    """
    e = result.envelope
    env = spec(
        "Effective envelope ("
        + {"extended_mc": "no saturated test: " + e.method, "options": "given as options"}.get(
            e.source, "saturated drained tests"
        )
        + ")",
        ["source", "n", header("c_eff"), "± se", header("phi_eff"), "± se", header("M"), header("k")],
    )
    env.rows.append(
        [
            e.source,
            fmt(e.n),
            fmt(e.c_kPa),
            fmt(e.c_se_kPa),
            fmt(e.phi_deg),
            fmt(e.phi_se_deg),
            fmt(e.M),
            fmt(e.k_kPa),
        ]
    )
    names = {"lower": "LB", "spherical": "UB q=q'", "edtp": "UB EDTP"}
    comps = ("sigma1_cap", "sigma2_cap", "sigma3_cap", "p_cap", "q_cap", "p_prime", "q_prime")
    tb = spec(
        "Capillary stress tensor at failure [kPa], compression +; gain = q'/q'_sat; "
        "θ = Lode angle (0 compression, 60 extension); bound 'none': not axisymmetric (see groups)",
        [
            "test",
            "bound",
            "branch",
            "θ [°]",
            header("sigma3"),
            header("q"),
            *(QUANTITIES[c].symbol for c in comps),
            "gain",
            "σ_cap > 0",
        ],
        left=3,
    )
    tb.label_columns = 2  # test and bound name each row when the table is folded
    t = result.states
    for i in np.flatnonzero(result.unsaturated):
        present = [n for n in ("lower", "spherical", "edtp") if result.bound_states[n].applies(i)]
        head = [
            _BRANCH.get(t.branch[i], t.branch[i]),
            fmt(t.lode_angle[i], 3),
            fmt(t.sigma3[i]),
            fmt(t.q[i]),
        ]
        if not present:
            tb.sections.add(len(tb.rows))
            tb.rows.append([t.test_id[i], "none", *head, *[""] * 9])
            continue
        for k, name in enumerate(present):
            b = result.bound_states[name]
            if k == len(present) - 1:
                tb.sections.add(len(tb.rows))
            stresses = [float(getattr(b, c)[i]) for c in comps]
            # 0 within rounding of the stresses the row was computed from (the test's and the bound's)
            scale = magnitude([*stresses, float(t.sigma3[i]), float(t.q[i])])
            tb.rows.append(
                [
                    t.test_id[i] if k == 0 else "",
                    names[name],
                    *(head if k == 0 else [""] * 4),
                    *(fmt(v, scale=scale) for v in stresses),
                    fmt(b.gain[i]),
                    "yes" if b.positive_component[i] else "",
                ]
            )
    out = [env, tb]
    has_a = np.isfinite(t.skempton_A)
    if has_a.any():
        a = spec(
            "Skempton's A at failure over the shear stage, (Δu − B Δσ3)/(B (Δσ1 − Δσ3)) (Skempton 1954)",
            ["test", "condition", header("q"), header("skempton_A")],
        )
        for i in np.flatnonzero(has_a):
            a.rows.append([t.test_id[i], t.condition[i], fmt(t.q[i]), fmt(t.skempton_A[i], 3)])
        out.append(a)
    if result.groups:
        g = spec(
            f"Groups: apparent envelope ({cite('prunier2024', 'Appendix 1, eq. 35-37, 43')})",
            ["group", "n", "branch", "C [kPa]", "φ [°]", "φ − φ' [°]", "eq. 37 σ_cap", "θ spread [°]", "eq. 49"],
        )
        tensor = spec(
            "Groups: shared capillary tensor [kPa] ± se (n − 1 dof; 95 % intervals in the JSON); without "
            "paired saturated tests, the admissible range lower to upper of each component "
            f"({cite('prunier2024', 'eq. 37, 44-50')})",
            ["group", "method", "σ1,cap", "σ2,cap", "σ3,cap", "p_cap", "C [kPa]", "C'' [kPa]"],
            left=2,
        )
        closure_rows = []
        for r in result.groups:
            apparent = [
                fmt(r.C_apparent),
                fmt(r.phi_apparent),
                # φ − φ' is a difference of two angles: 0 within the rounding of the larger
                fmt(r.phi_difference, sign=True, scale=magnitude([r.phi_apparent, result.envelope.phi_deg])),
                fmt(r.eq37_sigma_cap),
            ]
            if r.C_apparent is None:
                apparent = [r.apparent_error or "—", "", "", ""]
            g.rows.append(
                [
                    r.group,
                    fmt(r.n),
                    _BRANCH.get(r.branch, r.branch),
                    *apparent,
                    fmt(r.lode_spread, 2),
                    "holds" if r.eq49_holds else "fails",
                ]
            )
            if r.error:
                tensor.rows.append([r.group, r.error, *[""] * 6])
                continue
            if r.admissible is not None:  # not determined: the range, never one closure's value as the tensor
                a = r.admissible
                tensor.rows.append(
                    [
                        r.group,
                        "eq. 37: range (no pairs)",
                        *(_range(getattr(a, c)) for c in ("sigma1_cap", "sigma2_cap", "sigma3_cap", "p_cap")),
                        fmt(r.C),
                        "",
                    ]
                )
                closure_rows += [(r.group, c) for c in r.closures]
                continue
            method = (r.method or "— (see notes)").split(" (")[0]
            caps = [abs(getattr(r, f"sigma{k}_cap")) for k in (1, 2, 3) if getattr(r, f"sigma{k}_cap") is not None]
            scale = max(caps + [abs(r.C or 0.0)]) or None  # the magnitudes the tensor came from
            tensor.rows.append(
                [
                    r.group,
                    method,
                    *(_pm(getattr(r, f"sigma{k}_cap"), getattr(r, f"sigma{k}_cap_se"), scale) for k in (1, 2, 3)),
                    fmt(r.p_cap),
                    fmt(r.C),
                    fmt(r.C_fictive),
                ]
            )
        out += [g, tensor]
        if closure_rows:
            cl = spec(
                "Groups without paired saturated tests: the closures that bound the range [kPa] "
                f"(* the one capred reports as its choice; {cite('prunier2024', 'eq. 24, 37, 48')})",
                ["group", "closure", "σ1,cap", "σ2,cap", "σ3,cap", "p_cap"],
                left=2,
            )
            for grp, c in closure_rows:
                scale = max(abs(c.sigma1_cap), abs(c.sigma3_cap)) or None
                cl.rows.append(
                    [
                        grp,
                        ("* " if c.chosen else "") + c.label,
                        *(fmt(getattr(c, k), scale=scale) for k in ("sigma1_cap", "sigma2_cap", "sigma3_cap")),
                        fmt(c.p_cap, scale=scale),
                    ]
                )
            out.append(cl)
    return out
