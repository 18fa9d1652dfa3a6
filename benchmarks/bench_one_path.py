"""The README's first command against its floor (issue 20): CPU of the whole process tree and wall time.

What it claims: ``capred shear --sample --out DIR`` (every default output:
tables, JSON, one PNG at 300 dpi per main figure sheet -- the report sheet of
each of the sample's two materials, each drawn as one figure laid out once;
the capillary-stress sheets only with ``--figures all`` -- and report.html)
costs <= 2.0x its floor in CPU seconds (aim: 1.5x). The floor is what any
such run must pay: ``python -c "import capred, matplotlib.pyplot"`` plus one
``savefig`` of a 2x2 figure the size of one of capred's sheets (180 x 135 mm,
300 dpi, as many pixels as the report sheet it writes).

Contestants, run in turn (A B C D, A B C D, ...) so that a change of load on a
shared machine hits each alike; medians of the repeats:

- ``floor``:       the imports and the one 2x2 savefig
- ``readme``:      ``capred shear --sample --out DIR`` (the default bootstrap)
- ``boot0``:       the same with ``--bootstrap 0`` (the bootstrap is timed on its own in bench_bootstrap.py)
- ``no-figures``:  ``--bootstrap 0 --no-plots --no-html`` (what the figures and the report cost, by difference)
- ``boot0-1proc``, ``boot0-2proc``: ``--bootstrap 0`` with the figures drawn in one process or two
  (CAPRED_FIGURE_PROCESSES; by default two only when the load average leaves a core free)

CPU counts the figure process a run forks (children are waited for), so the
ratios compare core for core; wall time shows what the second core buys.

With ``--baseline COMMIT`` the capred contestants are also run from that commit
(a temporary git worktree on PYTHONPATH), interleaved with the others: the
before/after of a change in one session.

Run from the repository root: python benchmarks/bench_one_path.py [repeats=5] [--baseline COMMIT]
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import interleaved, ratio_line, run  # noqa: E402

FLOOR = """
import capred, matplotlib.pyplot as plt
fig, axes = plt.subplots(2, 2, figsize=(180 / 25.4, 135 / 25.4))
for ax in axes.flat:
    ax.plot([0, 1, 2], [0, 1, 4], "o-", label="a")
    ax.set_xlabel("x [kPa]")
    ax.legend()
fig.savefig(r"{out}/floor.png", dpi=300)
"""


ROOT = Path(__file__).resolve().parents[1]


def main(repeats: int = 5, baseline: str | None = None) -> None:
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:

        def capred(*args, env=None):
            out = Path(tmp) / ("b" if env else "o")

            def go():
                shutil.rmtree(out, ignore_errors=True)
                # cwd: a neutral folder, so that `python -m` imports capred from PYTHONPATH / the install
                run([py, "-m", "capred", "shear", "--sample", *args, "--out", str(out)], env=env, cwd=tmp)

            return go

        contestants = {
            "floor": lambda: run([py, "-c", FLOOR.format(out=tmp)], cwd=tmp),
            "readme": capred(),
            "boot0": capred("--bootstrap", "0"),
            "no-figures": capred("--bootstrap", "0", "--no-plots", "--no-html"),
            "boot0-1proc": capred("--bootstrap", "0", env={**os.environ, "CAPRED_FIGURE_PROCESSES": "1"}),
            "boot0-2proc": capred("--bootstrap", "0", env={**os.environ, "CAPRED_FIGURE_PROCESSES": "2"}),
        }
        base = Path(tmp) / "baseline"
        if baseline:
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), baseline],
                check=True,
                capture_output=True,
            )
            env = {**os.environ, "PYTHONPATH": str(base)}
            contestants.update({"readme@base": capred(env=env), "boot0@base": capred("--bootstrap", "0", env=env)})
        try:
            for warm in contestants.values():  # the file cache (fonts, .pyc) warm before timing
                warm()
            m = interleaved(contestants, repeats)
        finally:
            if baseline:
                subprocess.run(
                    ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base)], capture_output=True
                )
    for name, v in m.items():
        print(f"{name:12s} CPU {v.cpu:6.2f} s   wall {v.wall:6.2f} s")
    floor = m["floor"]
    print(ratio_line("README command / floor, CPU", m["readme"].cpu, floor.cpu, "<= 2.0x, aim 1.5x"))
    print(ratio_line("README command / floor, wall", m["readme"].wall, floor.wall))
    print(ratio_line("--bootstrap 0 / floor, CPU", m["boot0"].cpu, floor.cpu, "<= 2.0x"))
    print(ratio_line("--bootstrap 0 / floor, wall", m["boot0"].wall, floor.wall))
    fig = m["boot0"].cpu - m["no-figures"].cpu
    print(
        f"figures and report.html: {fig:.2f} s CPU, {m['boot0'].wall - m['no-figures'].wall:.2f} s wall "
        f"({fig / m['boot0'].cpu:.0%} of the --bootstrap 0 run's CPU)"
    )
    print(
        ratio_line("figures in two processes / one, CPU", m["boot0-2proc"].cpu, m["boot0-1proc"].cpu)
        + "; "
        + ratio_line("wall", m["boot0-2proc"].wall, m["boot0-1proc"].wall)
    )
    if baseline:
        for name in ("readme", "boot0"):
            b = m[f"{name}@base"]
            print(
                ratio_line(f"{name} at {baseline} / floor, CPU", b.cpu, floor.cpu)
                + "; "
                + ratio_line("wall", b.wall, floor.wall)
            )


if __name__ == "__main__":
    args = sys.argv[1:]
    base = None
    if "--baseline" in args:
        k = args.index("--baseline")
        base = args[k + 1]
        del args[k : k + 2]
    main(int(args[0]) if args else 5, base)
