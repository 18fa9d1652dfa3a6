"""Speed and memory targets of the one path (issue 9), measured as ratios in one session.

1. `capred shear` on 100,000 rows without plots, against the same command of
   the baseline version (git commit BASELINE, checked out in a temporary
   worktree and run from it in the same session): target >= 3x faster. The
   same work is compared: the ranking bootstrap, new since the baseline, is
   off (--bootstrap 0) for the ratio and timed on its own beside it.
2. Peak memory per row: (peak RSS on 100,000 rows - peak RSS on 1,000 rows)
   / 99,000: target < 2 KB.
3. `capred SUBCOMMAND --help` against `python -c "import typer"`: target
   <= 1.5x; `capred --help`: target <= 1.3x.

Run from the repository root with capred installed: python benchmarks/bench_one_path.py [repeats]
"""
from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BASELINE = "df42962"  # the last commit before the one path
ROOT = Path(__file__).resolve().parents[1]

RUN = """
import resource, sys
sys.argv = ["capred"] + sys.argv[1:]
from capred.cli import main
try:
    main()
except SystemExit:
    pass
print("MAXRSS_KB", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)
"""


def timed(cmd: list[str], repeats: int, env=None) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True, env=env)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def peak_kb(args: list[str], env=None) -> int:
    res = subprocess.run([sys.executable, "-c", RUN, *args], check=True, capture_output=True, text=True, env=env)
    return int(next(line.split()[1] for line in res.stderr.splitlines() if line.startswith("MAXRSS_KB")))


def make_rows(path: Path, n: int) -> None:
    from capred.samples import sample_path

    lines = [ln for ln in sample_path("shear").read_text().splitlines() if ln and not ln.startswith("#")]
    header, rows = lines[0], lines[1:]
    out = [header]
    k = 0
    while len(out) <= n:
        for r in rows:
            first, rest = r.split(",", 1)
            out.append(f"{first}-{k},{rest}")
        k += 1
    path.write_text("\n".join(out[: n + 1]) + "\n")


def main(repeats: int = 3) -> None:
    import os

    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        big, small = tmp / "big.csv", tmp / "small.csv"
        make_rows(big, 100_000)
        make_rows(small, 1_000)

        now = timed([py, "-m", "capred", "shear", str(big), "--no-plots", "--bootstrap", "0", "--out",
                     str(tmp / "o")], repeats)
        with_boot = timed([py, "-m", "capred", "shear", str(big), "--no-plots", "--out", str(tmp / "ob")], 1)
        base_dir = tmp / "baseline"
        ok = subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(base_dir), BASELINE],
                            capture_output=True).returncode == 0
        try:
            if ok:
                env = {**os.environ, "PYTHONPATH": str(base_dir)}
                then = timed([py, "-m", "capred", "shear", str(big), "--no-plots", "--out", str(tmp / "b")],
                             repeats, env)
        finally:
            if ok:
                subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(base_dir)],
                               capture_output=True)
        per_row = (peak_kb(["shear", str(big), "--no-plots", "--out", str(tmp / "m1")])
                   - peak_kb(["shear", str(small), "--no-plots", "--out", str(tmp / "m2")])) * 1024 / 99_000

        typer_t = timed([py, "-c", "import typer"], 2 * repeats + 1)
        helps = {args: timed([py, "-m", "capred", *args.split(), "--help"], 2 * repeats + 1)
                 for args in ("", "shear", "bridge solve", "triaxial-bounds")}

    print(f"capred shear, 100,000 rows, no plots   {now:7.2f} s   (--bootstrap 0)")
    print(f"  with the default 2,000-replicate bootstrap {with_boot:7.2f} s")
    if ok:
        print(f"  baseline {BASELINE}                  {then:7.2f} s   speed-up {then / now:.2f}x (target >= 3)")
    else:
        print("  baseline: no git worktree available; speed-up not measured")
    print(f"peak memory per row                    {per_row:7.0f} B   (target < 2048)")
    print(f"import typer                           {typer_t * 1e3:7.0f} ms")
    for args, t in helps.items():
        target = 1.3 if not args else 1.5
        print(f"capred {args + ' ' if args else ''}--help{'':{24 - len(args)}}{t * 1e3:7.0f} ms   ratio "
              f"{t / typer_t:.2f} (target <= {target})")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
