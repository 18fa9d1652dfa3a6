#!/usr/bin/env bash
# capred on a many-core machine (issue 31, item 4): the whole `capred bridge solve` command (CSV in, CSV and
# JSON out) on 1, 2, 4, 8 and 16 processes for 1,000,000 bridges, and `capred --help` against `import typer`.
#
# Run from the repository root, with the project's virtual environment carried along (no network needed):
#     PYTHON=.venv/bin/python bash benchmarks/device_cores.sh [rows=1000000] [workers=1,2,4,8,16] [repeats=3]
# Each figure is printed with the load average; every run's outputs are checked byte-identical to one process's.
# About 3 minutes on 16 cores (1M rows: ~10 s on one process).
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${PYTHON:-python3}"
ROWS="${1:-1000000}"
WORKERS="${2:-1,2,4,8,16}"
REPEATS="${3:-3}"
export PYTHONPATH="$PWD${PYTHONPATH:+:$PYTHONPATH}"
export OPENBLAS_NUM_THREADS=1  # as the console script sets it
echo "== $(date -u +%FT%TZ) $(uname -srm); $(nproc) cores; $("$PY" --version 2>&1); load $(cut -d' ' -f1-3 /proc/loadavg)"
grep -m1 "model name" /proc/cpuinfo || true
echo "== capred --help against import typer (CPU of the process, medians of 15, interleaved)"
"$PY" benchmarks/bench_startup.py 15
echo "== capred bridge solve on ${WORKERS} processes, ${ROWS} bridges, ${REPEATS} interleaved repeats"
(cd benchmarks && "$PY" bench_bridge_cores.py "$ROWS" "$WORKERS" "$REPEATS")
echo "== done $(date -u +%FT%TZ); load $(cut -d' ' -f1-3 /proc/loadavg)"
