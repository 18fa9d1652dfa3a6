"""`capred retention-convert`: its options (``ConvertOptions``); its input is a fits.json, not a table.

Numpy-free (see :mod:`capred.spec`): the models are those of the registry capred.spec.retention_models.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import OptionError
from .constants import GAMMA_W
from .options import Options, Whole
from .retention_models import MODELS


def _power_law_model() -> str:
    """The registry's model of the form S_e = (s_e/s)^λ (the entry with ``power_law``): the default target."""
    return next(k for k, m in MODELS.items() if m.power_law is not None)


#: points of the logarithmic grid between the smallest and largest suction of the data (besides the data's own)
GRID_POINTS = 100


@dataclass(frozen=True)
class ConvertOptions(Options):
    """Options of `capred retention-convert`.

    Attributes
    ----------
    to : str
        Target model (a key of the retention registry).
    model : str or None
        Which fit of FIT.json to convert (default: the lowest AICc of the branch).
    branch : str or None
        Which branch (default: the file's main branch, drying when present).
    gamma_w : float
        Unit weight of water [N/m^3] (the heads in cm of the JSON).
    points : int
        Quadrature nodes (per piece) and points of the misfit's grid between the data's smallest and largest
        suction.
    """

    QUANTITIES = {"gamma_w": "gamma_w"}
    CONSTRAINTS = {"points": Whole(min=10, max=100_000, text="be a whole number from 10 to 100000")}

    to: str = _power_law_model()
    model: str | None = None
    branch: str | None = None
    gamma_w: float = GAMMA_W
    points: int = GRID_POINTS

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.to not in MODELS:
            raise OptionError(f"--to: unknown retention model '{self.to}'; choose from {', '.join(MODELS)}")
        if self.model is not None and self.model not in MODELS:
            raise OptionError(f"--model: unknown retention model '{self.model}'; choose from {', '.join(MODELS)}")


__all__ = ["GRID_POINTS", "ConvertOptions"]
