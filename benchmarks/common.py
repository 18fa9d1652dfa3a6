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

import resource
import statistics
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass
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


def ratio_line(label: str, num: float, den: float, target: str = "") -> str:
    """``label: 12.3x (target ...)``: the ratio a benchmark claims, printed as it is computed."""
    return f"{label}: {num / den:,.2f}x" + (f" (target {target})" if target else "")
