"""`capred pt-volume`: what it reads (``SCHEMA``) and its options (``PTVolumeOptions``).

Numpy-free (see :mod:`capred.spec`): the model's parameters are built by capred.physics.pedrotti_tarantino
when asked for, at run time.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..errors import OptionError
from .columns import Column
from .constants import PATH_COLUMNS
from .options import Flag, Options, Whole


def _pt():
    """capred.physics.pedrotti_tarantino (numpy: at run time only)."""
    from ..physics import pedrotti_tarantino

    return pedrotti_tarantino


SCHEMA = [
    Column("step", "dimensionless", "-", "step number of the point", ("point", "point_no"), None, decisive=False),
    Column("stage", "text", None, "stage label (A, A-B, B...)", ("label", "stage_label"), decisive=False),
    Column("sigma", "pressure", "kPa", PATH_COLUMNS["sigma"][1], ("total_stress", "mean_stress", "p")),
    Column("u_w", "pressure", "kPa", PATH_COLUMNS["u_w"][1], ("uw", "pore_water_pressure")),
    Column("u_a", "pressure", "kPa", PATH_COLUMNS["u_a"][1], ("ua", "pore_air_pressure")),
    Column(
        "suction",
        "pressure",
        "kPa",
        "matric suction u_a - u_w (instead of u_w)",
        ("s", "matric_suction", "ua_uw"),
        "nonnegative",
    ),
    Column("S_r", "dimensionless", "-", PATH_COLUMNS["S_r"][1], ("Sr", "S_R", "degree_of_saturation")),
]


#: the six line parameters: option field -> CLI option
LINE_OPTIONS = {
    "lambda_W": "--lambda-w",
    "kappa_W": "--kappa-w",
    "e_ncl_W": "--e-ncl-w",
    "lambda_A": "--lambda-a",
    "kappa_A": "--kappa-a",
    "e_ncl_A": "--e-ncl-a",
}


@dataclass(frozen=True)
class PTVolumeOptions(Options):
    """Options of `capred pt-volume`.

    Attributes
    ----------
    lambda_W, kappa_W, e_ncl_W : float, optional
        ncl slope, url slope and ncl void ratio at ``reference_stress`` of the clay reconstituted from slurry
        [-] (natural-log slopes, λ = C_c/ln 10).
    lambda_A, kappa_A, e_ncl_A : float, optional
        The same for the clay compressed from dry powder [-].
    reference_stress : float
        σ_ref where the intercepts are read [Pa, or a string with a unit]; default 1 kPa.
    example_kaolin : bool
        Take the lines not given from ``EXAMPLE_KAOLIN`` (illustrative values, not from the paper; the run
        says so in a warning).
    initial_yield_W, initial_yield_A : float, optional
        Largest σ'_W (σ'_A) carried before the first point [Pa]; default: the first point's own stress
        (both parts on their ncl, the end of compaction).
    substeps : int, optional
        Sub-steps per step between two points; default: automatic (|ΔS_r| ≤ 0.002, |Δ ln σ'| ≤ 0.02).
    compression_W, compression_A : str, optional
        compression.json of `capred compression` on the clay reconstituted from slurry (W) or compressed from dry
        powder (A): λ, κ and e_ncl (moved to ``reference_stress``) of the part whose options are not given.
    """

    QUANTITIES = {
        "lambda_W": "lambda_W",
        "kappa_W": "kappa_W",
        "e_ncl_W": "e_ncl_W",
        "lambda_A": "lambda_A",
        "kappa_A": "kappa_A",
        "e_ncl_A": "e_ncl_A",
        "reference_stress": "reference_stress",
        "initial_yield_W": "initial_yield_W",
        "initial_yield_A": "initial_yield_A",
    }
    OPTION_NAMES = {**LINE_OPTIONS, "initial_yield_W": "--initial-yield-w", "initial_yield_A": "--initial-yield-a"}
    CONSTRAINTS = {
        "substeps": Whole(min=1, max=100_000, text="be a whole number from 1 to 100000"),
        "example_kaolin": Flag(),
    }

    lambda_W: float | None = None
    kappa_W: float | None = None
    e_ncl_W: float | None = None
    lambda_A: float | None = None
    kappa_A: float | None = None
    e_ncl_A: float | None = None
    reference_stress: float = 1.0e3
    example_kaolin: bool = False
    initial_yield_W: float | None = None
    initial_yield_A: float | None = None
    substeps: int | None = None
    compression_W: str | Path | None = None
    compression_A: str | Path | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        for part, path in (("W", self.compression_W), ("A", self.compression_A)):
            given = [
                LINE_OPTIONS[k]
                for k in (f"lambda_{part}", f"kappa_{part}", f"e_ncl_{part}")
                if getattr(self, k) is not None
            ]
            if path is not None and given:
                raise OptionError(f"give --compression-{part.lower()} or {', '.join(given)}, not both")
        if self.compression_W is None and self.compression_A is None:
            object.__setattr__(self, "_from_fits", {})
            if all(self._line(k) is not None for k in LINE_OPTIONS) or self.example_kaolin:
                self.parameters()  # kappa < lambda and the other joint checks, at once

    def read_fits(self, limits=None) -> None:
        """Read the compression.json files given (``compression_W``, ``compression_A``), once, within ``limits``.

        The run calls it with its reading limits (``--max-megabytes``) before anything else; without that call the
        files are read, when first needed, within the reader's defaults (256 MiB).

        Parameters
        ----------
        limits : capred.io.ReadLimits, optional
            The run's reading limits.

        Raises
        ------
        InputError
            A file larger than the limit, or not a compression.json.
        OptionError
            A test without unloading stage (no κ), or lines out of their joint domain (κ < λ ...).
        """
        if hasattr(self, "_from_fits"):
            return
        object.__setattr__(self, "_from_fits", self._lines_from_compression(limits))
        if all(self._line(k) is not None for k in LINE_OPTIONS) or self.example_kaolin:
            self.parameters()  # kappa < lambda and the other joint checks, as soon as the lines are known

    def _lines_from_compression(self, limits=None) -> dict:
        """λ, κ, e_ncl of each part given by a compression.json (e_ncl moved to the run's reference stress)."""
        from ..pipelines.compression import load_compression_fit

        out = {}
        for part, path in (("W", self.compression_W), ("A", self.compression_A)):
            if path is None:
                continue
            lines = load_compression_fit(path, limits)
            if lines.url_slope is None:
                raise OptionError(
                    f"--compression-{part.lower()} {lines.source}: the test has no unloading stage, so no κ_{part}"
                )
            out[f"lambda_{part}"] = lines.ncl_slope
            out[f"kappa_{part}"] = lines.url_slope
            out[f"e_ncl_{part}"] = lines.e_ncl_at(self.reference_stress)
        return out

    def _line(self, k: str):
        v = getattr(self, k)
        if v is None:
            self.read_fits()
            return self._from_fits.get(k)
        return v

    def from_compression(self) -> list[str]:
        """The line parameters taken from a compression.json.

        Returns
        -------
        list of str
            Their option names; empty without a compression.json.
        """
        self.read_fits()
        return list(self._from_fits)

    def illustrative(self) -> list[str]:
        """The line parameters taken from EXAMPLE_KAOLIN.

        Returns
        -------
        list of str
            Their option names; empty unless ``example_kaolin``.
        """
        return [k for k in LINE_OPTIONS if self._line(k) is None] if self.example_kaolin else []

    def parameters(self):
        """The compressibility lines of the run.

        Returns
        -------
        capred.physics.pedrotti_tarantino.PTVolumeParameters
            The lines given, those not given taken from EXAMPLE_KAOLIN with ``example_kaolin``.

        Raises
        ------
        OptionError
            Naming every missing option when some are not given (and ``example_kaolin`` is not set).
        """
        missing = [k for k in LINE_OPTIONS if self._line(k) is None]
        if missing and not self.example_kaolin:
            raise OptionError(
                "the volume-change model of Pedrotti & Tarantino needs the compressibility lines of the clay "
                "reconstituted from slurry (W) and compressed from dry powder (A); missing: "
                + ", ".join(LINE_OPTIONS[k] for k in missing)
                + " (natural-log slopes lambda, kappa and the ncl void ratio e_ncl at --reference-stress, "
                "default 1 kPa), or --example-kaolin for illustrative kaolin values"
            )
        values = {
            k: (self._line(k) if self._line(k) is not None else getattr(_pt().EXAMPLE_KAOLIN, k)) for k in LINE_OPTIONS
        }
        try:  # the physics refuses lines out of their domain (kappa < lambda ...): its text is the options'
            return _pt().PTVolumeParameters(**values, reference_stress=self.reference_stress)
        except ValueError as exc:
            raise OptionError(str(exc)) from None


__all__ = ["LINE_OPTIONS", "PATH_COLUMNS", "SCHEMA", "PTVolumeOptions"]
