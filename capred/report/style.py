"""The one look of capred's figures: colour-blind-safe colours and markers per model, axis labels with
symbols and units, user text drawn literally, and legends placed where they never cover data.

Colours are the Okabe & Ito (2008) palette; every model keeps its colour and
marker in every figure of every command.
"""
from __future__ import annotations

OKABE_ITO = {
    "black": "#000000", "orange": "#E69F00", "sky": "#56B4E9", "green": "#009E73",
    "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00", "purple": "#CC79A7", "grey": "#7F7F7F",
}
_C = OKABE_ITO

#: curve name -> matplotlib style: one colour and one marker per curve, everywhere (effective-stress
#: models carry their own style in their registry entry)
MODEL_STYLE: dict[str, dict] = {
    # bridges
    "exact": dict(color=_C["black"], marker="o"),
    "israelachvili": dict(color=_C["purple"], marker="d"),
    "toroidal": dict(color=_C["blue"], marker="^"),
    "willett": dict(color=_C["vermillion"], marker="s"),
    # triaxial bounds
    "lower": dict(color=_C["vermillion"], marker="v"),
    "spherical": dict(color=_C["blue"], marker="o"),
    "edtp": dict(color=_C["green"], marker="^"),
    # retention models and branches
    "vg": dict(color=_C["blue"], marker="o", ls="-"),
    "vg_m_free": dict(color=_C["sky"], marker="s", ls="--"),
    "bc": dict(color=_C["vermillion"], marker="^", ls="-."),
    "drying": dict(color=_C["orange"], marker="o"),
    "wetting": dict(color=_C["blue"], marker="s"),
}

#: axis labels with mathtext symbols and units, by nomenclature name
LABEL = {
    "sigma_N": r"$\sigma_N$ [kPa]",
    "sigma_eff": r"$\sigma'_N$ [kPa]",
    "tau_max": r"$\tau_{max}$ [kPa]",
    "tau_pred": r"$\tau_{pred}$ [kPa]",
    "S_R": r"$S_R$ [–]",
    "suction": r"$\Delta u$ [kPa]",
    "sigma_cap": r"$\sigma_{cap}$ [kPa]",
    "chi": r"$\chi$ [–]",
    "residual": r"$\tau_{pred} - \tau_{max}$ [kPa]",
    "displacement": r"horizontal displacement $\delta$ [mm]",
    "tau": r"$\tau$ [kPa]",
    "p": r"$p$, $p'$ [kPa]",
    "q": r"$q$, $q'$ [kPa]",
    "sigma": r"$\sigma$, $\sigma'$ [kPa]",
    "cap_component": r"capillary stress component [kPa]",
    "sigma_prime": r"$\sigma'$ [kPa]",
    "F_measured": r"measured $F_{cap}$ [mN]",
    "F_predicted": r"predicted $F_{cap}$ [mN]",
    "B": r"$B$ [–]",
    "S_r": r"$S_r$ [–]",
    "theta": r"$\theta$ [–]",
}

#: a one-column journal figure (89 mm wide)
SINGLE_PANEL_SIZE = (3.5, 2.8)


def literal(text) -> str:
    """User text (a material name, a test id) as drawn: '$' escaped, so no mathtext is read into it."""
    return str(text).replace("$", r"\$")


def style(name: str, **over) -> dict:
    """Colour and marker of a model or curve (and any overrides): an effective-stress model's from its registry
    entry, the others' from MODEL_STYLE."""
    from ..physics.effective_stress_models import REGISTRY

    entry = REGISTRY.get(name)
    if entry is not None:
        base = {**entry.style, "color": _C.get(entry.style.get("color"), entry.style.get("color", _C["black"]))}
    else:
        base = MODEL_STYLE.get(name, dict(color=_C["black"], marker="o"))
    return {**base, **over}


def legend_outside(ax, ncol: int = 1) -> None:
    """Move an axes' legend outside its data area (to the right), so that it never covers a point."""
    old = ax.get_legend()
    if old is not None:  # keep what the panel put in its legend (also proxy handles)
        handles = list(getattr(old, "legend_handles", None) or old.legendHandles)
        labels = [t.get_text() for t in old.get_texts()]
        old.remove()
    else:
        handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=7,
                  frameon=False, ncol=ncol)
