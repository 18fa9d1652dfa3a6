"""The README's first command against its floor (issues 20 and 31): CPU of the whole process tree and wall time.

What it claims: ``capred shear --sample --out DIR`` (every default output:
tables, JSON, one PNG at 300 dpi per main figure sheet -- the report sheet of
each of the sample's two materials, each drawn as one figure laid out once;
the capillary-stress sheets only with ``--figures all`` -- and report.html)
costs <= 1.5x its floor (issue 31), in CPU seconds and in wall time.

The floor (issue 31: "the floor draws and saves the same two sheets once with plain matplotlib") is a
script that imports ``matplotlib.pyplot``, loads the sample's shear result (pickled by this benchmark
before the timing: the fits are not drawing), and for each of the two report sheets makes a pyplot figure of
the sheet's size with a 2 x 2 grid of axes and constrained layout, lets each of capred's panel functions
draw its artists on its axes (the same points, lines, bands, error bars and legends, with capred's font
sizes: ``capred.report.sheets.RC``; each legend set beside its axes, as capred places it, so that no draw
searches the axes for a free corner), sets the sheet's title and saves it with ``savefig(dpi=300)``: plain
matplotlib's figure, layout and PNG writer drawing the same content, without capred's own layout, figure
reuse, PNG encoder, tables, JSON or report.html.

``floor-2x2`` is issue 20's floor, kept for comparison: ``python -c "import capred, matplotlib.pyplot"`` plus
one ``savefig`` of a 2x2 figure the size of one of capred's sheets (180 x 135 mm, 300 dpi) with one line and
a legend per axes.

Contestants, run in turn (A B C D, A B C D, ...) so that a change of load on a
shared machine hits each alike; medians of the repeats:

- ``floor``:       the same two sheets drawn and saved with plain matplotlib (above)
- ``floor-2x2``:   issue 20's floor: the imports and one simple 2x2 savefig
- ``readme``:      ``capred shear --sample --out DIR`` (the default bootstrap)
- ``boot0``:       the same with ``--bootstrap 0`` (the bootstrap is timed on its own in bench_bootstrap.py)
- ``no-figures``:  ``--bootstrap 0 --no-plots --no-html`` (what the figures and the report cost, by difference)
- ``boot0-1proc``, ``boot0-2proc``: ``--bootstrap 0`` with the figures drawn in one process or two
  (CAPRED_FIGURE_PROCESSES; by default two only when the load average leaves a core free)

capred's bytecode is cached as an installed package has it (common.installed_env).

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
from common import installed_env, interleaved, ratio_line, run  # noqa: E402

FLOOR_SHEETS = """
import pickle
import matplotlib as mpl
mpl.use("agg")
import matplotlib.pyplot as plt
from capred.report.presenters import figures
from capred.report.sheets import RC, sheet_layout

with open(r"{pickle}", "rb") as f:
    result = pickle.load(f)
with mpl.rc_context(RC):
    for name, sheet in figures(result).items():
        if sheet.on_request:
            continue
        _, width, height = sheet_layout(sheet)
        fig, axes = plt.subplots(2, 2, figsize=(width / 25.4, height / 25.4), layout="constrained")
        for panel, ax in zip(sheet.panels, axes.flat):
            panel.draw(ax)
            legend = ax.get_legend()
            if legend is not None:  # beside the axes, as capred puts it: no search for a free corner
                legend.set_loc("center left")
                legend.set_bbox_to_anchor((1.02, 0.5))
        fig.suptitle(sheet.title)
        fig.savefig(r"{out}/" + name + ".png", dpi=300)
        plt.close(fig)
"""

FLOOR_2X2 = """
import capred, matplotlib.pyplot as plt
fig, axes = plt.subplots(2, 2, figsize=(180 / 25.4, 135 / 25.4))
for ax in axes.flat:
    ax.plot([0, 1, 2], [0, 1, 4], "o-", label="a")
    ax.set_xlabel("x [kPa]")
    ax.legend()
fig.savefig(r"{out}/floor.png", dpi=300)
"""


ROOT = Path(__file__).resolve().parents[1]


def write_sample_result(path: Path) -> None:
    """The README command's result (the shear sample, default options) pickled for the floor: the fits are
    computed here, before the timing, so that the floor times drawing and saving alone."""
    import pickle
    import warnings

    import capred

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the sample's two expected warnings
        result = capred.run_shear(capred.sample_path("shear"), capred.ShearOptions())
    path.write_bytes(pickle.dumps(result))


def main(repeats: int = 5, baseline: str | None = None) -> None:
    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        # one BLAS thread everywhere: capred's command asks for it itself; numpy's idle OpenBLAS threads would
        # otherwise charge the floor ~0.1 s of CPU for no work
        mine = {**installed_env(Path(tmp) / "pycache"), "OPENBLAS_NUM_THREADS": "1"}
        pickled = Path(tmp) / "shear_sample.pickle"
        write_sample_result(pickled)

        def capred(*args, env=None):
            out = Path(tmp) / ("b" if env else "o")

            def go():
                shutil.rmtree(out, ignore_errors=True)
                # cwd: a neutral folder, so that `python -m` imports capred from PYTHONPATH / the install
                run([py, "-m", "capred", "shear", "--sample", *args, "--out", str(out)], env=env or mine, cwd=tmp)

            return go

        contestants = {
            "floor": lambda: run([py, "-c", FLOOR_SHEETS.format(pickle=pickled, out=tmp)], env=mine, cwd=tmp),
            "floor-2x2": lambda: run([py, "-c", FLOOR_2X2.format(out=tmp)], env=mine, cwd=tmp),
            "readme": capred(),
            "boot0": capred("--bootstrap", "0"),
            "no-figures": capred("--bootstrap", "0", "--no-plots", "--no-html"),
            "boot0-1proc": capred("--bootstrap", "0", env={**mine, "CAPRED_FIGURE_PROCESSES": "1"}),
            "boot0-2proc": capred("--bootstrap", "0", env={**mine, "CAPRED_FIGURE_PROCESSES": "2"}),
        }
        base = Path(tmp) / "baseline"
        if baseline:
            subprocess.run(
                ["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base), baseline],
                check=True,
                capture_output=True,
            )
            env = {**installed_env(Path(tmp) / "pycache-base"), "PYTHONPATH": str(base)}
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
    print(f"load average {os.getloadavg()[0]:.2f} at the end")
    floor = m["floor"]
    print(
        ratio_line(
            "README command / floor (the same two sheets, plain matplotlib), CPU", m["readme"].cpu, floor.cpu, "<= 1.5x"
        )
    )
    print(
        ratio_line(
            "README command / floor (the same two sheets, plain matplotlib), wall",
            m["readme"].wall,
            floor.wall,
            "<= 1.5x",
        )
    )
    print(ratio_line("--bootstrap 0 / floor, CPU", m["boot0"].cpu, floor.cpu))
    print(ratio_line("--bootstrap 0 / floor, wall", m["boot0"].wall, floor.wall))
    f20 = m["floor-2x2"]
    print(
        ratio_line(
            "README command / issue 20's floor (one simple 2x2 figure), CPU", m["readme"].cpu, f20.cpu, "<= 2.0x"
        )
    )
    print(ratio_line("README command / issue 20's floor (one simple 2x2 figure), wall", m["readme"].wall, f20.wall))
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
