"""Regenerate the sample files that look like lab and instrument exports, from the synthetic samples.

``python -m capred.sample_data.generate_exports [DIR]`` writes:

- ``shear_tests_export.xlsx``: the direct-shear sample as a workbook: a metadata
  block above the header, headers as a spreadsheet user types them, a units row.
- ``shear_tests_eu.csv``: the same as a European CSV export: ';' separators,
  decimal commas, a metadata block and a units row.
- ``shear_curves.csv``: raw curves (displacement, shear force, vertical
  displacement) of the steel-sphere tests whose peaks are the sample's tau_max.
- ``triaxial_export/*.csv``: one instrument export per unsaturated triaxial test
  (metadata block with test id and specimen size, units row); one of them gives
  only the axial force, so q comes from the corrected area.

Deterministic; every number derives from shear_tests.csv and triaxial_curves.csv.
"""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

import numpy as np

BOX_AREA_M2 = 36e-4
D0_MM = 38.0


def _rows(path: Path) -> list[dict]:
    text = "\n".join(ln for ln in path.read_text().splitlines() if not ln.startswith("#"))
    return list(csv.DictReader(io.StringIO(text)))


def shear_export_xlsx(rows: list[dict], out: Path) -> None:
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.title = "Direct shear"
    for line in (
        ("Laboratory", "capred sample lab (synthetic data)"),
        ("Apparatus", "60 mm shear box"),
        ("Operator", "—"),
        ("Made by", "sample_data/generate_exports.py"),
    ):
        ws.append(list(line))
    ws.append([])
    ws.append(
        [
            "Test ID",
            "Material",
            "Condition",
            "Suction head",
            "Air volume",
            "Void volume",
            "Added mass",
            "Cap mass",
            "Box area",
            "Particle radius",
            "Peak shear stress",
        ]
    )
    ws.append(["", "", "", "cm", "cm3", "cm3", "g", "g", "cm2", "mm", "kPa"])
    keys = [
        "test_id",
        "material",
        "condition",
        "z1 [cm]",
        "z2 [cm^3]",
        "V_v [cm^3]",
        "added_mass [g]",
        "cap_mass [g]",
        "box_area [cm^2]",
        "R [mm]",
        "tau_max [kPa]",
    ]
    for r in rows:
        ws.append(
            [r[k] if k in ("test_id", "material", "condition") else (float(r[k]) if r[k] else None) for k in keys]
        )
    wb.properties.creator = "capred"
    buf = io.BytesIO()
    wb.save(buf)
    out.write_bytes(buf.getvalue())


def shear_export_eu(rows: list[dict]) -> str:
    lines = [
        "Laboratoire;capred sample lab (synthetic data)",
        "Appareil;boîte de cisaillement 60 mm",
        "Date;2026-11-21",
        "",
        "test_id;material;condition;z1;z2;V_v;added_mass;cap_mass;box_area;R;tau_max",
        ";;;cm;cm3;cm3;g;g;cm2;mm;kPa",
    ]
    keys = [
        "test_id",
        "material",
        "condition",
        "z1 [cm]",
        "z2 [cm^3]",
        "V_v [cm^3]",
        "added_mass [g]",
        "cap_mass [g]",
        "box_area [cm^2]",
        "R [mm]",
        "tau_max [kPa]",
    ]
    for r in rows:
        lines.append(";".join(r[k].replace(".", ",") for k in keys))
    return "\n".join(lines) + "\n"


def shear_curves(rows: list[dict]) -> str:
    """Hyperbolic rise to the peak at 1.5 mm, softening to 85 %; dilation after contraction."""
    lines = [
        "# capred sample: SYNTHETIC raw direct-shear curves of the steel-sphere tests of shear_tests.csv;",
        "# the peak of each curve (at 1.5 mm) is that test's tau_max. Made by sample_data/generate_exports.py.",
        "test_id,displacement [mm],F [N],vertical_displacement [mm]",
    ]
    delta = np.round(np.arange(0.0, 6.0001, 0.25), 2)
    for r in rows:
        if r["material"] != "steel_2mm":
            continue
        f_peak = float(r["tau_max [kPa]"]) * 1e3 * BOX_AREA_M2
        x = delta / 1.5
        shape = np.where(x <= 1, 2 * x / (1 + x * x), 1 - 0.15 * np.minimum((x - 1) / 2, 1))
        vert = -0.02 * delta + 0.012 * delta**2
        for d, s, v in zip(delta, shape, vert):
            lines.append(f"{r['test_id']},{d:.2f},{f_peak * s:.6g},{v:.4f}")
    return "\n".join(lines) + "\n"


def triaxial_exports(curves: list[dict], folder: Path) -> None:
    folder.mkdir(exist_ok=True)
    area0 = np.pi * (D0_MM * 1e-3) ** 2 / 4
    for k, tid in enumerate(dict.fromkeys(r["test_id"] for r in curves)):
        mine = [r for r in curves if r["test_id"] == tid]
        force_only = k == 0
        lines = [
            f"Test ID: {tid}",
            f"Initial diameter (mm): {D0_MM:g}",
            "Initial height (mm): 76",
            "Note: synthetic export made by sample_data/generate_exports.py from triaxial_curves.csv",
            "",
        ]
        if force_only:
            lines.append("Axial Strain (%),Axial Force (kN),Volumetric Strain (%)")
            lines.append("%,kN,%")
        else:
            lines.append("Axial Strain (%),Deviator Stress (kPa),Volumetric Strain (%)")
            lines.append("%,kPa,%")
        for r in mine:
            eps, q, ev = float(r["axial_strain [%]"]), float(r["q [kPa]"]), float(r["vol_strain [%]"])
            if force_only:
                area = area0 * (1 - ev / 100) / (1 - eps / 100)
                lines.append(f"{eps:.2f},{q * 1e3 * area / 1e3:.9g},{ev:.3f}")
            else:
                lines.append(f"{eps:.2f},{q:.2f},{ev:.3f}")
        (folder / f"{tid}.csv").write_text("\n".join(lines) + "\n")


def main(folder: str | None = None) -> None:
    out = Path(folder) if folder else Path(__file__).parent
    here = Path(__file__).parent
    rows = _rows(here / "shear_tests.csv")
    shear_export_xlsx(rows, out / "shear_tests_export.xlsx")
    (out / "shear_tests_eu.csv").write_text(shear_export_eu(rows), encoding="utf-8")
    (out / "shear_curves.csv").write_text(shear_curves(rows))
    triaxial_exports(_rows(here / "triaxial_curves.csv"), out / "triaxial_export")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
