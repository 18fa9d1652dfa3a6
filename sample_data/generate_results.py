"""Regenerate the samples that are capred outputs: ``python sample_data/generate_results.py [DIR]``.

- ``retention_fits.json``: the fits.json of ``capred retention --sample`` (input of ``capred retention-convert``);
- ``lab_history.sqlite``: a lab store of 12 days of dry direct-shear tests of one sand recorded as with
  ``--store``, the friction angle of day 9 shifted out of control (input of ``capred history``).

Run it after ``generate.py`` (it reads ``retention.csv``). Deterministic: fixed seed, the inputs' paths kept
as bare file names, each run's recording time set to noon of its test date, and the store written in
SQLite's rollback-journal mode (so that reading it read-only, inside an installed package, needs no side file).
The procedure is described in README.md here.
"""

from __future__ import annotations

import json
import math
import os
import sqlite3
import sys
import tempfile
from pathlib import Path

import numpy as np

G = 9.81  # m/s^2
#: g added to the 120 g cap of a 36 cm^2 box (the loads of shear_tests.csv's dry tests)
ADDED_G = (0.0, 77.47, 200.0, 400.0, 700.0, 1000.0)
SEED = 20261126
DAYS = 12
PHI_DEG = 35.0  # the sand's friction angle, day to day scatter 0.3 deg
PLANTED_DAY = 9  # its friction angle shifted by +3 deg (about 10 times the day-to-day scatter)
MATERIAL = "Toyoura sand"


def season_file(day: int, phi_deg: float, rng) -> str:
    """One day's dry direct-shear tests (six loads) with a metadata block naming the test date."""
    rows = [
        "# capred sample: SYNTHETIC dry direct-shear tests (not measured data); sample_data/generate_results.py",
        f"date: 2026-03-{day:02d}",
        f"material: {MATERIAL}",
        "test_id,material,condition,V_v [cm^3],added_mass [g],cap_mass [g],box_area [cm^2],tau_max [kPa]",
    ]
    for i, m in enumerate(ADDED_G):
        sigma = (120.0 + m) * 1e-3 * G / 36e-4 / 1e3  # kPa
        tau = sigma * math.tan(math.radians(phi_deg)) + rng.normal(0.0, 0.01)
        rows.append(f"T{i:02d},{MATERIAL},dry,30.5,{m},120.0,36.0,{tau:.4f}")
    return "\n".join(rows) + "\n"


def make_fits(out: Path) -> None:
    """``retention_fits.json``: the document `capred retention --sample` writes, its input named by file name."""
    import capred
    from capred.io.writers import encode_json

    source = out / "retention.csv"
    doc = json.loads(encode_json(capred.run_retention(source).to_json()).decode("utf-8"))
    for entry in doc["inputs"]:
        entry["path"] = Path(entry["path"]).name
    doc["source"] = Path(doc["source"]).name
    (out / "retention_fits.json").write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


def make_store(out: Path) -> None:
    """``lab_history.sqlite``: 12 shear runs recorded into a new store, one out of control."""
    import capred
    from capred.lab_store import record_run

    target = out / "lab_history.sqlite"
    rng = np.random.default_rng(SEED)
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)  # the runs record their inputs by these bare names
        try:
            for day in range(1, DAYS + 1):
                phi = PHI_DEG + rng.normal(0.0, 0.3) + (3.0 if day == PLANTED_DAY else 0.0)
                name = f"shear_2026-03-{day:02d}.csv"
                Path(name).write_text(season_file(day, phi, rng), encoding="utf-8")
                result = capred.run_shear(name, capred.ShearOptions(bootstrap=0))
                record_run("lab.sqlite", result)
            con = sqlite3.connect("lab.sqlite", isolation_level=None)
            con.execute("UPDATE runs SET created_utc = test_date || 'T12:00:00+00:00'")
            con.execute("PRAGMA journal_mode = DELETE")
            con.execute("VACUUM")
            con.close()
            target.write_bytes(Path("lab.sqlite").read_bytes())
        finally:
            os.chdir(here)


def main(folder: str | None = None) -> None:
    import warnings

    out = Path(folder) if folder else Path(__file__).resolve().parent
    with warnings.catch_warnings():  # the planted day and the fits warn on purpose
        warnings.simplefilter("ignore")
        make_fits(out)
        make_store(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
