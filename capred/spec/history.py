"""`capred history`: its options (``HistoryOptions``); its input is a lab store, not a table.

Numpy-free (see :mod:`capred.spec`).
"""

from __future__ import annotations

from dataclasses import dataclass

from .options import Options


@dataclass(frozen=True)
class HistoryOptions(Options):
    """Options of `capred history`.

    The material and quantity (a JSON key such as ``phi_deg``) to chart, the number of first runs that set the limits,
    or a reference value and spread in the quantity's unit.
    """

    material: str | None = None
    quantity: str | None = None
    baseline: int = 8
    reference: float | None = None
    spread: float | None = None
    command: str | None = None


__all__ = ["HistoryOptions"]
