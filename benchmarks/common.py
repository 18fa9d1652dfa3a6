"""Timing helpers shared by the benchmarks: CPU and wall time, interleaved repeats, medians.

CPU time is counted for the whole process tree: this process
(``time.process_time``) plus every child it has waited for
(``resource.getrusage(RUSAGE_CHILDREN)``, which on Linux includes the
children's own waited-for children, e.g. the worker processes of a
``multiprocessing`` pool). Comparing CPU seconds compares core for core
whatever the number of processes each side uses.

Interleaving (A, B, A, B, ...) exposes both sides to the same load on a
shared machine; the median of the repeats is reported.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any


def _children_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


@dataclass
class Timing:
    """One measurement: ``cpu`` [s] of this process and its waited-for children, ``wall`` [s]."""

    cpu: float
    wall: float


def timed(fn: Callable[[], Any]) -> tuple[Any, Timing]:
    """Run ``fn()`` once; return its result and its Timing (CPU of this process and of its children)."""
    c0, k0, w0 = time.process_time(), _children_cpu(), time.perf_counter()
    out = fn()
    w1, c1, k1 = time.perf_counter(), time.process_time(), _children_cpu()
    return out, Timing(cpu=(c1 - c0) + (k1 - k0), wall=w1 - w0)


def run(cmd: list[str], **kw) -> tuple[subprocess.CompletedProcess, Timing]:
    """A command to completion (checked), timed with its whole process tree."""

    def go():
        p = subprocess.run(cmd, capture_output=True, text=True, **kw)
        if p.returncode != 0:
            raise SystemExit(f"{' '.join(cmd)} failed:\n{p.stderr}")
        return p

    return timed(go)


@dataclass
class Medians:
    """Median CPU and wall time [s] of the repeats of one contestant, and every repeat."""

    cpu: float
    wall: float
    repeats: list[Timing]


def interleaved(contestants: dict[str, Callable[[], Any]], repeats: int = 5) -> dict[str, Medians]:
    """Time every contestant ``repeats`` times in turn (A, B, A, B, ...); medians of CPU and wall per name."""
    seen: dict[str, list[Timing]] = {k: [] for k in contestants}
    for _ in range(repeats):
        for name, fn in contestants.items():
            seen[name].append(timed(fn)[1])
    return {
        k: Medians(statistics.median(t.cpu for t in v), statistics.median(t.wall for t in v), v)
        for k, v in seen.items()
    }


def installed_env(pycache: Path | str, base: dict | None = None) -> dict:
    """The environment of a timed ``python -m capred`` run: capred's bytecode cached, as an installed package has it.

    pip compiles a package's bytecode when it installs it, and any other install writes it on the first run. A
    machine that sets PYTHONDONTWRITEBYTECODE (this project's shared one does) would make every timed run compile
    capred's modules again (about 0.25 s for the shear command), a cost no user pays twice: the warm-up run
    writes the bytecode under ``pycache`` (PYTHONPYCACHEPREFIX) instead. CAPRED_BENCH_COMPILE=1 keeps the
    environment as it is. The peers (numpy, scipy, matplotlib, unsatfit) run from site-packages, compiled by pip.
    """
    env = dict(os.environ if base is None else base)
    if os.environ.get("CAPRED_BENCH_COMPILE") != "1":
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = str(pycache)
    return env


def cpu_model() -> str:
    """The processor's model name (/proc/cpuinfo's ``model name``; the platform's processor elsewhere)."""
    import platform

    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as fh:
            for line in fh:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine_line() -> str:
    """``AMD EPYC, 2 cores, load average 1.2 0.9 0.5, 2026-11-29 01:50 UTC``: what a timing was taken on."""
    import datetime

    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    load = " ".join(f"{x:.1f}" for x in os.getloadavg()) if hasattr(os, "getloadavg") else "n/a"
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    return f"{cpu_model()}, {cores} cores, load average {load}, {when}"


def ratio_line(label: str, num: float, den: float, target: str = "") -> str:
    """``label: 12.3x (target ...)``: the ratio a benchmark claims, printed as it is computed."""
    return f"{label}: {num / den:,.2f}x" + (f" (target {target})" if target else "")


# --- data shaped as labs have it --------------------------------------------------------------------------------
# The bundled samples have six distinct normal stresses per material and wet tests at a few suctions: a cost
# that grows with the number of distinct stresses (issue 31: the bootstrap's dense indicator) never shows on
# them. These generators give what a lab's season gives: every dry test at its own stress (weights to 0.01 g),
# campaigns pooled into one file, wet tests at scattered suctions, scatter that grows with the strength.


def _sample_rows(kind: str) -> tuple[str, list[list[str]]]:
    from capred.samples import sample_path

    lines = [ln for ln in sample_path(kind).read_text().splitlines() if ln and not ln.startswith("#")]
    return lines[0], [ln.split(",") for ln in lines[1:]]


def lab_shear_rows(path, n: int, distinct_dry: int | None = None, seed: int = 31, scatter: float = 0.03) -> None:
    """Write ``n`` direct-shear rows (the sample's columns) shaped as a lab's pooled season.

    Campaign k repeats the sample's tests with ids ``<id>-k``. Dry tests: the added mass runs through
    ``distinct_dry`` values per material (None: every dry test its own, 0.01 g apart), tau_max on the
    material's dry line (fitted to the sample in mass units). Wet tests: the column height z1 scattered
    log-normally (SD 20 %) within the material's range, z2 and tau_max interpolated along the sample's own
    (z1, z2, tau) of that material. Every tau_max times (1 + ``scatter`` N(0, 1)): heteroscedastic, its SD
    proportional to the strength.
    """
    import numpy as np

    header, rows = _sample_rows("shear")
    col = {c: k for k, c in enumerate(header.split(","))}
    i_mat, i_cond, i_z1, i_z2 = col["material"], col["condition"], col["z1 [cm]"], col["z2 [cm^3]"]
    i_add, i_cap, i_tau = col["added_mass [g]"], col["cap_mass [g]"], col["tau_max [kPa]"]
    dry_line, wet_curve, dry_levels = {}, {}, {}
    for mat in {r[i_mat] for r in rows}:
        d = [r for r in rows if r[i_mat] == mat and r[i_cond] == "dry"]
        m = np.array([float(r[i_add]) + float(r[i_cap]) for r in d])
        dry_line[mat] = np.polyfit(m, [float(r[i_tau]) for r in d], 1)
        dry_levels[mat] = np.unique([float(r[i_add]) for r in d])
        w = sorted(
            (float(r[i_z1]), float(r[i_z2]), float(r[i_tau])) for r in rows if r[i_mat] == mat and r[i_cond] == "wet"
        )
        wet_curve[mat] = np.array(w).T
    rng = np.random.default_rng(seed)
    noise = 1.0 + scatter * rng.standard_normal(n)
    spread = np.exp(0.2 * rng.standard_normal(n))
    seen_dry = {m: 0 for m in dry_line}
    out = [header]
    for k in range(n):
        cells = list(rows[k % len(rows)])
        mat = cells[i_mat]
        cells[0] = f"{cells[0]}-{k // len(rows)}"
        if cells[i_cond] == "dry":
            j = seen_dry[mat] if distinct_dry is None else seen_dry[mat] % distinct_dry
            seen_dry[mat] += 1
            levels = dry_levels[mat]
            added = levels[j % levels.size] + 0.01 * (j // levels.size)
            cells[i_add] = f"{added:.2f}"
            tau = np.polyval(dry_line[mat], added + float(cells[i_cap]))
        else:
            z1s, z2s, taus = wet_curve[mat]
            z1 = float(np.clip(float(cells[i_z1]) * spread[k], z1s[0], z1s[-1]))
            cells[i_z1] = f"{z1:.3f}"
            cells[i_z2] = f"{np.interp(z1, z1s, z2s):.3f}"
            tau = np.interp(z1, z1s, taus)
        cells[i_tau] = f"{tau * noise[k]:.4f}"
        out.append(",".join(cells))
    Path(path).write_text("\n".join(out) + "\n")


def lab_retention_rows(path, n: int, seed: int = 31, scatter: float = 0.02) -> None:
    """Write ``n`` retention readings (the sample's columns, drying branch) at scattered column heights: z1
    log-uniform over the sample's range, z2 along the sample's drying curve plus a scatter of ``scatter`` V_v
    (N(0, 1), clipped to 0..V_v)."""
    import numpy as np

    header, rows = _sample_rows("retention")
    col = {c: k for k, c in enumerate(header.split(","))}
    dry = sorted((float(r[col["z1 [cm]"]]), float(r[col["z2 [cm^3]"]])) for r in rows if r[col["branch"]] == "drying")
    z1s, z2s = np.array(dry).T
    z2s = np.maximum.accumulate(z2s)  # drained volume grows with the column height
    v_v = float(rows[0][col["V_v [cm^3]"]])
    rng = np.random.default_rng(seed)
    z1 = np.exp(rng.uniform(np.log(z1s[0]), np.log(z1s[-1]), n))
    z2 = np.clip(np.interp(z1, z1s, z2s) + scatter * v_v * rng.standard_normal(n), 0.0, v_v)
    lines = ["z1 [cm],z2 [cm^3],V_v [cm^3],branch"] + [f"{a:.3f},{b:.3f},{v_v},drying" for a, b in zip(z1, z2)]
    Path(path).write_text("\n".join(lines) + "\n")
