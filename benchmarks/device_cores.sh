#!/usr/bin/env bash
# capred's issue-31 figures on a lent many-core measuring machine, as one prepared run (no network there):
#   - `capred bridge solve` (CSV in, CSV and JSON out) on 1, 2, 4, 8 and 16 processes for 1,000,000 bridges;
#   - the 2-core targets on two idle cores (every process pinned to cores 0 and 1, the rest of the machine
#     idle): bridge solve on 1 and 2 processes, a season through `capred batch`, the README command against its
#     floor, retention against unsatfit, 100,000 lab-shaped shear rows, and `capred --help` against typer;
#   - `capred bridge solve` against per-bridge solve_ivp on one pinned core.
#
# Run from the repository root, with the wheels of ../shared/tools/device-wheels.sh (plus unsatfit's) in .whl/:
#     bash benchmarks/device_cores.sh [rows=1000000] [season files=300]
# SECTIONS="cores bridge2 season readme retention ivp shear100k startup" (any of them) runs those alone.
# Each section has its own time limit and prints the load average; every output is checked as each benchmark
# checks it (bridge solve: byte-identical to one process). The log is written to $OUT/device.log when OUT is set.
set -uo pipefail
cd "$(dirname "$0")/.."
ROWS="${1:-1000000}"
FILES="${2:-300}"
LOG="${OUT:-/tmp}/device.log"
PY="${PYTHON:-python3}"
case "$PY" in  # an absolute path: the sections run from benchmarks/
  */*) PY="$(cd "$(dirname "$PY")" && pwd)/$(basename "$PY")" ;;
  *) PY="$(command -v "$PY")" ;;
esac
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1  # as capred's console script sets them
if ! "$PY" -c "import typer, pint, orjson, openpyxl, odf" 2>/dev/null && [ -d .whl ]; then
  # the packages the machine lacks (capred itself runs from this tree)
  "$PY" -m pip install -q --no-index --no-deps --target "$HOME/site" $(ls .whl/*.whl | grep -v '/capred-') \
    >/dev/null 2>&1 || echo "pip install of .whl failed"
  export PYTHONPATH="$PWD:$HOME/site"
else
  export PYTHONPATH="$PWD${PYTHONPATH:+:$PYTHONPATH}"
fi
# the command pinned to the cores listed (e.g. 0,1), its children with it, without needing taskset
PIN='import os, sys; os.sched_setaffinity(0, {int(c) for c in sys.argv[1].split(",")}); os.execv(sys.argv[2], sys.argv[2:])'
section() {  # key, name, seconds, cores (all: unpinned), python arguments...
  local key="$1" name="$2" limit="$3" cores="$4"
  shift 4
  case " ${SECTIONS:-$key} " in *" $key "*) ;; *) return 0 ;; esac  # SECTIONS="key ...": those alone
  echo "== $name ($(date -u +%T); load $(cut -d' ' -f1-3 /proc/loadavg))"
  if [ "$cores" = all ]; then
    timeout "$limit" "$PY" "$@"
  else
    timeout "$limit" "$PY" -c "$PIN" "$cores" "$PY" "$@"
  fi
  echo "-- rc $? ($(date -u +%T); load $(cut -d' ' -f1-3 /proc/loadavg))"
}
{
  echo "== $(date -u +%FT%TZ) $(uname -srm); $(getconf _NPROCESSORS_ONLN) cores; $("$PY" --version 2>&1)"
  grep -m1 "model name" /proc/cpuinfo || true
  "$PY" -c 'import numpy, scipy, matplotlib, pandas, typer; print("numpy", numpy.__version__, "scipy", scipy.__version__, "matplotlib", matplotlib.__version__, "pandas", pandas.__version__, "typer", typer.__version__)'
  cd benchmarks
  section cores "bridge solve, ${ROWS} bridges, 1-16 processes" 170 all bench_bridge_cores.py "$ROWS" 1,2,4,8,16 3 --command-only
  section bridge2 "two cores: bridge solve, ${ROWS} bridges, 1 and 2 processes" 100 0,1 bench_bridge_cores.py "$ROWS" 1,2 3 --command-only
  section season "two cores: a season of ${FILES} files, every default output, 2 workers" 140 0,1 bench_batch.py "$FILES" 1 --only every-output --workers 2
  section readme "two cores: the README command against its floor" 90 0,1 bench_one_path.py 3
  section retention "two cores: retention on 10,000 readings against unsatfit" 70 0,1 bench_retention.py --process 10000 3
  CAPRED_PROCESSES=1 section ivp "one core: bridge solve against per-bridge solve_ivp, 200,000 rows" 90 0 bench_bridge_cli.py 200000 3
  section shear100k "two cores: 100,000 lab-shaped shear rows" 100 0,1 bench_shear.py 1 100000 --lab
  section startup "two cores: capred --help against import typer" 40 0,1 bench_startup.py 9
  echo "== done $(date -u +%FT%TZ)"
} 2>&1 | tee "$LOG"
