"""`capred --help` against `import typer`, the floor of any typer CLI (issue 31, item 5: <= 1.3x).

Both as whole processes (``python -m capred --help`` and ``python -c "import typer"``), interleaved
(A B, A B, ...), medians of CPU (the process tree) and wall time; the load average is printed with them.

Run from the repository root: python benchmarks/bench_startup.py [repeats=9]
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import interleaved, ratio_line, run  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(repeats: int = 9) -> None:
    py = sys.executable
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    contestants = {
        "import typer": lambda: run([py, "-c", "import typer"], env=env),
        "capred --help": lambda: run([py, "-m", "capred", "--help"], env=env),
        "python": lambda: run([py, "-c", "pass"], env=env),
    }
    print(f"load {os.getloadavg()}")
    m = interleaved(contestants, repeats)
    for name, v in m.items():
        print(f"{name:14s} CPU {v.cpu:6.3f} s   wall {v.wall:6.3f} s")
    print(ratio_line("capred --help / import typer, CPU", m["capred --help"].cpu, m["import typer"].cpu, "<= 1.3x"))
    print(ratio_line("  the same, wall", m["capred --help"].wall, m["import typer"].wall))
    print(f"load {os.getloadavg()}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 9)
