"""`capred --help` against `import typer`, the floor of any typer CLI (issue 31, item 5: <= 1.3x), and
`capred shear --help` (a command's help with its input columns).

All as whole processes (``python -m capred --help``, ``python -c "import typer"``, ...), interleaved
(A B C, A B C, ...), medians of CPU (the process tree) and wall time; the load average is printed with them.

capred runs with its bytecode cached, as an installed package has it (pip compiles on install; typer's is
cached in the environment): a warm-up run writes it to a temporary PYTHONPYCACHEPREFIX, also where the
environment sets PYTHONDONTWRITEBYTECODE (which would make every run compile capred's command modules again,
about 0.05 s CPU). Set CAPRED_BENCH_COMPILE=1 to keep the environment's setting.

Run from the repository root: python benchmarks/bench_startup.py [repeats=9]
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import installed_env, interleaved, ratio_line, run  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(repeats: int = 9) -> None:
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        env = {**installed_env(tmp), "PYTHONPATH": str(ROOT)}
        contestants = {
            "import typer": lambda: run([py, "-c", "import typer"], env=env),
            "capred --help": lambda: run([py, "-m", "capred", "--help"], env=env),
            "shear --help": lambda: run([py, "-m", "capred", "shear", "--help"], env=env),
            "python": lambda: run([py, "-c", "pass"], env=env),
        }
        for warm in contestants.values():  # bytecode written, files cached
            warm()
        print(f"load {os.getloadavg()}")
        m = interleaved(contestants, repeats)
    for name, v in m.items():
        print(f"{name:14s} CPU {v.cpu:6.3f} s   wall {v.wall:6.3f} s")
    typer_cpu, typer_wall = m["import typer"].cpu, m["import typer"].wall
    print(ratio_line("capred --help / import typer, CPU", m["capred --help"].cpu, typer_cpu, "<= 1.3x"))
    print(ratio_line("  the same, wall", m["capred --help"].wall, typer_wall))
    print(ratio_line("capred shear --help / import typer, CPU", m["shear --help"].cpu, typer_cpu))
    print(ratio_line("  the same, wall", m["shear --help"].wall, typer_wall))
    print(f"load {os.getloadavg()}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 9)
