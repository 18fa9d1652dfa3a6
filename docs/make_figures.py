"""Regenerate every picture the README shows, from the bundled samples.

Run from the repository root with capred installed:

    python docs/make_figures.py

It runs the commands below into a temporary folder and copies the figures
the README uses into docs/ (at ``DPI``: the figures are drawn at their printed
size, 85 or 180 mm wide, so 200 dpi is sharp on a screen and keeps the
repository small). With a Chromium on the PATH (``chromium`` or
``chromium-browser``), it also takes a screenshot of a report.html
(docs/report_html.png); without one, that picture is left as it is.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

DOCS = Path(__file__).resolve().parent
DPI = "200"
RUNS = {
    "shear": ["shear", "--sample", "--seed", "0", "--dpi", DPI],
    "triaxial": ["triaxial-bounds", "--sample", "--dpi", DPI],
    "bridge": ["bridge", "curve", "--points", "400", "--dpi", DPI],
}
PICTURES = {  # docs/<name> <- <run>/<file>
    "shear_report_sand.png": ("shear", "report_sand_208-417um.png"),
    "shear_capillary_sand.png": ("shear", "capillary_sand_208-417um.png"),
    "triaxial_report.png": ("triaxial", "report.png"),
    "bridge_curve.png": ("bridge", "curve.png"),
}


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name, args in RUNS.items():
            subprocess.run(
                [sys.executable, "-m", "capred", *args, "--out", str(tmp / name)], check=True, capture_output=True
            )
        for picture, (run, file) in PICTURES.items():
            shutil.copyfile(tmp / run / file, DOCS / picture)
            print(f"docs/{picture}")
        browser = shutil.which("chromium") or shutil.which("chromium-browser")
        if browser:
            subprocess.run(
                [
                    browser,
                    "--headless",
                    "--no-sandbox",
                    "--disable-gpu",
                    "--hide-scrollbars",
                    "--disable-background-networking",
                    "--disable-component-update",
                    "--disable-sync",
                    "--no-first-run",
                    f"--user-data-dir={tmp / 'profile'}",
                    "--window-size=1000,1400",
                    f"--screenshot={DOCS / 'report_html.png'}",
                    (tmp / "shear" / "report.html").as_uri(),
                ],
                check=True,
                capture_output=True,
                timeout=120,
            )
            print("docs/report_html.png")
        else:
            print("no chromium: docs/report_html.png not updated", file=sys.stderr)


if __name__ == "__main__":
    main()
