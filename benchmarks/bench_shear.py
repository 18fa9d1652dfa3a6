"""`capred shear` on 100,000 rows: every default output against tables and JSON alone (issue 20).

What it claims: the run with every default output (tables, JSON, the
default bootstrap, one composite PNG per figure sheet at 300 dpi, report.html)
costs <= 3x the same run with ``--no-plots --no-html --bootstrap 0``, in CPU
seconds of the whole process tree; figures of a large table do not grow with
its rows. Both are printed with their wall times, and the figures and report
alone (``--bootstrap 0`` with and without them) as a third contestant, so the
bootstrap's share is visible too.

The 100,000 rows repeat sample_data/shear_tests.csv (52 tests) with unique
test ids and tau_max perturbed by a seeded relative noise of 2 % (so that the
repeats are not identical points), both materials kept.

Contestants run in turn (A B C, A B C, ...), medians of the repeats.

With ``--lab`` the rows are shaped as a lab's season instead (``common.lab_shear_rows``: every dry test at its
own normal stress, wet tests at scattered suctions, heteroscedastic scatter; issue 31: <= 2x).

Run from the repository root: python benchmarks/bench_shear.py [repeats=3] [rows=100000] [--lab]
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import installed_env, interleaved, ratio_line, run  # noqa: E402


def make_rows(path: Path, n: int, seed: int = 20) -> None:
    """``n`` rows of shear tests: the sample repeated, test ids made unique, tau_max perturbed by 2 % (seeded)."""
    import numpy as np

    from capred.samples import sample_path

    lines = [ln for ln in sample_path("shear").read_text().splitlines() if ln and not ln.startswith("#")]
    header, rows = lines[0], lines[1:]
    cols = header.split(",")
    tau = cols.index("tau_max [kPa]")
    rng = np.random.default_rng(seed)
    noise = 1.0 + 0.02 * rng.standard_normal(n)
    out = [header]
    for k in range(n):
        cells = rows[k % len(rows)].split(",")
        cells[0] = f"{cells[0]}-{k // len(rows)}"
        cells[tau] = f"{float(cells[tau]) * noise[k]:.4f}"
        out.append(",".join(cells))
    path.write_text("\n".join(out) + "\n")


def main(repeats: int = 3, n: int = 100_000, lab: bool = False) -> None:
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp) / "shear_100k.csv"
        if lab:  # every dry test at its own stress, a pooled season (issue 31)
            from common import lab_shear_rows

            lab_shear_rows(data, n)
        else:
            make_rows(data, n)
        print(f"load {os.getloadavg()}, {'lab-shaped rows (common.lab_shear_rows)' if lab else 'the sample repeated'}")

        env = installed_env(Path(tmp) / "pycache")

        def shear(*args):
            out = Path(tmp) / "o"

            def go():
                shutil.rmtree(out, ignore_errors=True)
                run([py, "-m", "capred", "shear", str(data), *args, "--out", str(out)], env=env, cwd=tmp)

            return go

        contestants = {
            "defaults": shear(),
            "boot0": shear("--bootstrap", "0"),
            "tables": shear("--no-plots", "--no-html", "--bootstrap", "0"),
        }
        m = interleaved(contestants, repeats)
    for name, v in m.items():
        print(f"{name:9s} CPU {v.cpu:7.2f} s   wall {v.wall:7.2f} s")
    print(
        ratio_line(
            f"{n:,} rows, every default output / --no-plots --no-html --bootstrap 0, CPU",
            m["defaults"].cpu,
            m["tables"].cpu,
            "<= 2x (issue 31, lab-shaped rows)" if lab else "<= 3x (issue 20)",
        )
    )
    print(ratio_line("  the same, wall", m["defaults"].wall, m["tables"].wall))
    print(ratio_line("figures and report.html (--bootstrap 0) / tables, CPU", m["boot0"].cpu, m["tables"].cpu))
    print(ratio_line("  the same, wall", m["boot0"].wall, m["tables"].wall))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--lab"]
    main(int(args[0]) if args else 3, int(args[1]) if len(args) > 1 else 100_000, "--lab" in sys.argv)
