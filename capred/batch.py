"""Run one reduction on many files, or a manifest of runs, optionally in worker processes.

Each file is a job with its own output folder, written as a transaction by
capred.io.writers. A job never raises: bad input makes it ``failed`` (with
the message), an unexpected exception makes it ``crashed`` (its traceback in
the folder's errors.log), and after Ctrl-C the jobs not yet done are
``interrupted``. ``index.csv`` lists every job and every file written, and is
written in every case.
"""

from __future__ import annotations

import time
import traceback
from contextlib import contextmanager, nullcontext
from dataclasses import dataclass, field
from datetime import UTC
from pathlib import Path

from .errors import CapredError

STATUSES = ("ok", "failed", "crashed", "interrupted")


@dataclass
class Job:
    """One run of a batch: the command, its input, output folder and options, as the manifest gives them.

    Attributes
    ----------
    command : str
        The command as typed (``"shear"``, ``"bridge solve"``).
    source : Path or None
        The input file (None for a calculator run from its options).
    out_dir : Path
        The run's output folder.
    options : object
        The command's Options record.
    plots : bool
        Draw the figures.
    keep_json : bool
        Keep the JSON document in the outcome (``Outcome.result_json``).
    output : capred.cli.common.OutputOptions or None
        How the files are written (None: the defaults).
    """

    command: str
    source: Path | None
    out_dir: Path
    options: object
    plots: bool = True
    keep_json: bool = False
    output: object = None  # capred.cli.common.OutputOptions (None: the defaults)
    #: the command that reproduces this file's run alone (``capred shear FILE OPTIONS``), recorded in its
    #: provenance.json and report.html; None: this process's command line
    command_line: str | None = None


@dataclass
class Outcome:
    """How one run of a batch ended, as index.csv and season.csv record it.

    Each field is described where it is declared: the command, input and output folder, the status (one of
    ``STATUSES``) and its message, the files written, the seconds taken, and the run's season rows, headline,
    warning count and options.
    """

    command: str
    source: str
    out_dir: str
    status: str
    message: str = ""
    outputs: list[str] = field(default_factory=list)
    seconds: float = 0.0
    result_json: dict | None = None
    season: list[dict] = field(default_factory=list)  # the result's season rows, model ids as their labels
    headline: str = ""  # the run's main results in a line, with labels (season.csv)
    warnings: int = 0  # how many warnings the run gave
    options: str = ""  # the run's options that differ from its command's defaults (season.csv)

    @property
    def ok(self) -> bool:
        """Whether the run succeeded (status ``"ok"``)."""
        return self.status == "ok"


def run_job(job: Job):
    """(result, written paths) of one job; raises CapredError on bad input or unwritable output.

    Parameters
    ----------
    job : Job
        The command, its input, output folder, options and output settings.

    Returns
    -------
    tuple
        ``(result, written)``: the command's Result and the list of paths written (empty when
        ``job.out_dir`` is None).

    Raises
    ------
    CapredError
        On bad input, or where the output folder may not be written.
    """
    from .reductions import REDUCTIONS
    from .report.outputs import write_outputs

    if job.out_dir is not None:  # refuse a folder capred may not replace before computing anything
        from .io import check_target
        from .report.outputs import check_outputs_ahead

        check_target(job.out_dir, [job.source] if job.source is not None else [])
        check_outputs_ahead(job.command, job.source, job.options, job.out_dir)
    result = REDUCTIONS[job.command].run(job.source, job.options)
    if job.out_dir is None:  # --json without --out: nothing written
        return result, []
    o = job.output
    kw = (
        dict(
            formats=o.formats,
            dpi=o.dpi,
            html=o.html,
            csv_dialect=o.csv_dialect,
            xlsx=o.xlsx,
            panels=o.panels,
            figures=o.figures,
            store=getattr(o, "store", None),
        )
        if o
        else {}
    )
    return result, write_outputs(result, job.out_dir, plots=job.plots, command_line=job.command_line, **kw)


def run_safely(job: Job) -> Outcome:
    """Outcome of one job: ok, failed (CapredError) or crashed (any other exception).

    Parameters
    ----------
    job : Job
        The job to run.

    Returns
    -------
    Outcome
        Its status, message, files written, duration [s], season rows, headline and warning count.
    """
    t0 = time.perf_counter()
    from .io import source_path

    src = str(source_path(job.source)) if job.source is not None else ""
    changed = changed_options(job.options)
    try:
        result, written = run_job(job)
    except CapredError as exc:
        return Outcome(
            job.command, src, str(job.out_dir), "failed", str(exc), seconds=time.perf_counter() - t0, options=changed
        )
    except Exception as exc:  # a bug: keep the traceback for the report, let the other files run
        log = _save_traceback(job, traceback.format_exc())
        return Outcome(
            job.command,
            src,
            str(job.out_dir),
            "crashed",
            f"unexpected error {type(exc).__name__}: {exc} (traceback in {log})",
            [log] if log else [],
            time.perf_counter() - t0,
            options=changed,
        )
    rows = labelled(result.season_rows())
    return Outcome(
        job.command,
        src,
        str(job.out_dir),
        "ok",
        "",
        [str(p) for p in written],
        time.perf_counter() - t0,
        result.to_json() if job.keep_json else None,
        rows,
        headline(rows) or _count_line(result),
        len(result.all_warnings()),
        changed,
    )


def changed_options(options) -> str:
    """The options of a run that differ from its command's defaults, as a user types them, ``; ``-separated.

    E.g. ``dry_loss huber; bootstrap 0; gamma_w 10 kN/m³`` ("" when every option has its default).

    The defaults are those of the command's options record (the field defaults of its dataclass, which the CLI
    leaves in force when an option is not given); a nested record (model parameters) is compared field by field
    and shown as ``model_params.vg_n 1.6``. Numbers are compared with a relative tolerance of 1e-12, so a value
    typed in another unit that converts back to the default (``9.81 kN/m^3``) is not a change. Output options
    (--no-plots, --dpi) are not listed: they change no number of the run.

    Parameters
    ----------
    options : object
        A command's options record (a dataclass instance); anything else gives "".

    Returns
    -------
    str
        The changed options with their values and units.
    """
    import dataclasses

    if options is None or not dataclasses.is_dataclass(options) or isinstance(options, type):
        return ""
    from .report.html import option_value

    parts = []
    for name, value, quantity in _changed(options, ""):
        text, unit = option_value(value, quantity)
        parts.append(f"{name} {text}" + (f" {unit}" if unit else ""))
    return "; ".join(parts)


def _changed(options, prefix: str) -> list:
    """(dotted name, value, Quantity or None) of each field of a dataclass record that differs from its default."""
    import dataclasses

    from .nomenclature import QUANTITIES

    out = []
    quantities = getattr(options, "QUANTITIES", {})
    for f in dataclasses.fields(options):
        if f.name.startswith("_") or not f.init:
            continue
        value = getattr(options, f.name)
        if f.default is not dataclasses.MISSING:
            default = f.default
        elif f.default_factory is not dataclasses.MISSING:
            default = f.default_factory()
        else:  # a required field: always the user's
            default = dataclasses.MISSING
        if dataclasses.is_dataclass(value) and not isinstance(value, type):
            out += _changed(value, f"{prefix}{f.name}.")
            continue
        if _same(value, default):
            continue
        if value is not None and hasattr(value, "to_csv"):  # a table given through the API
            value = "(a table)"
        elif hasattr(value, "__fspath__"):  # a path: as typed
            value = str(value)
        q = quantities.get(f.name)
        out.append((prefix + f.name, value, QUANTITIES.get(q) if q else None))
    return out


def _same(value, default) -> bool:
    """Whether an option's value is its default (numbers within 1e-12 relative; sequences element-wise)."""
    import math
    import numbers

    if default is value:
        return True
    if isinstance(value, numbers.Real) and isinstance(default, numbers.Real) and not isinstance(value, bool):
        return not isinstance(default, bool) and math.isclose(value, default, rel_tol=1e-12, abs_tol=0.0)
    if isinstance(value, (list, tuple)) and isinstance(default, (list, tuple)):
        return len(value) == len(default) and all(_same(a, b) for a, b in zip(value, default))
    try:
        return bool(value == default)
    except Exception:  # an array or a table compared with a default: not the default
        return False


def _save_traceback(job: Job, text: str) -> str:
    """errors.log (with a provenance.json listing it, so a rerun may replace the folder) in the job's folder."""
    import sys
    from datetime import datetime

    from . import __version__
    from .io import RunFolder, check_target, encode_json

    try:
        if job.out_dir is None:
            return ""
        folder = RunFolder(check_target(job.out_dir, [job.source] if job.source else []))
        folder.write_bytes("errors.log", f"capred {job.command} {job.source}\n\n{text}".encode())
        folder.write_bytes(
            "provenance.json",
            encode_json(
                {
                    "capred_version": __version__,
                    "command": job.command,
                    "command_line": job.command_line if job.command_line is not None else " ".join(sys.argv),
                    "python": sys.version.split()[0],
                    "inputs": [str(job.source)] if job.source is not None else [],
                    "outputs": ["errors.log", "provenance.json"],
                    "status": "crashed",
                    "created_utc": datetime.now(UTC).replace(microsecond=0).isoformat(),
                },
                True,
            ),
        )
        return str(folder.commit()[0])
    except (CapredError, OSError):
        return ""


def default_workers(n_jobs: int) -> int:
    """Worker processes for ``n_jobs`` jobs: one per core this process may use, never more than the jobs.

    Parameters
    ----------
    n_jobs : int
        Number of jobs to run [-].

    Returns
    -------
    int
        Number of worker processes, at least 1 [-].
    """
    import os

    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    return max(1, min(cores, n_jobs))


def _warm(jobs: list[Job]) -> None:
    """Import what every job needs once, in the parent, so that forked workers inherit it.

    A worker otherwise spends ~1 s of CPU importing pandas, the pipeline and the report before its first file.
    """
    from importlib import import_module

    from .reductions import REDUCTIONS

    import_module("capred.report.outputs")
    import_module("capred.io.writers")
    for command in {j.command for j in jobs}:
        red = REDUCTIONS.get(command)
        if red is not None:
            import_module(red.run_path.split(":")[0])
    if any(j.output is None or j.output.html for j in jobs if j.out_dir is not None):
        import_module("capred.report.html")
    if any(j.output is not None and j.output.xlsx for j in jobs if j.out_dir is not None):
        import_module("openpyxl")


def _openblas_controls() -> list:
    """(set, get) C functions of every OpenBLAS library loaded in this process.

    numpy's and scipy's each bundle one, found through /proc/self/maps; none elsewhere than Linux or without OpenBLAS.
    """
    import ctypes

    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            paths = {line.split()[-1] for line in maps if "openblas" in line.rsplit("/", 1)[-1].lower()}
    except OSError:  # pragma: no cover - not Linux
        return []
    out = []
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)  # already loaded: the same handle, nothing new is mapped
        except OSError:  # pragma: no cover
            continue
        for prefix in ("scipy_openblas", "openblas"):
            for suffix in ("64_", ""):
                set_ = getattr(lib, f"{prefix}_set_num_threads{suffix}", None)
                get_ = getattr(lib, f"{prefix}_get_num_threads{suffix}", None)
                if set_ is not None and get_ is not None:
                    set_.argtypes, set_.restype, get_.restype = [ctypes.c_int], None, ctypes.c_int
                    out.append((set_, get_))
                    break
            else:
                continue
            break
    return out


@contextmanager
def single_threaded_blas():
    """OpenBLAS on one thread while a batch runs, its thread counts restored after.

    A batch's matrix products are small (a bootstrap's 2,000 x 14 counts times 14 x 28 sums) and its files
    already fill the cores, one worker each. OpenBLAS's own threads on such products only wait and spin: on a
    2-core machine they doubled the CPU time of a shear file (122 -> 68 ms, benchmarks/bench_batch.py) for no
    gain in wall time. Forked workers inherit the setting.
    """
    controls = _openblas_controls()
    before = [get_() for _, get_ in controls]
    for set_, _ in controls:
        set_(1)
    try:
        yield
    finally:
        for (set_, _), n in zip(controls, before):
            set_(n)


#: prctl(2) option that sends a signal to this process when its parent dies (linux/prctl.h)
PR_SET_PDEATHSIG = 1


def die_with_parent(parent: int) -> None:
    """Make this worker process end when ``parent`` (the batch) dies, even by ``kill -9``.

    Linux's PR_SET_PDEATHSIG sends SIGKILL to the worker then. Elsewhere a thread watches the parent's pid twice a
    second and ends the worker when it is gone. A parent already gone ends the worker at once.

    Parameters
    ----------
    parent : int
        Process id of the batch that started the worker.
    """
    import os
    import signal
    import sys

    armed = False
    if sys.platform.startswith("linux"):
        import ctypes

        try:
            libc = ctypes.CDLL(None, use_errno=True)
            armed = libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
        except (OSError, AttributeError):  # pragma: no cover - no prctl
            armed = False
    if os.getppid() != parent:  # the parent died before the signal was armed
        os._exit(1)
    if not armed:  # pragma: no cover - not Linux: a watchdog thread
        import threading
        import time

        def watch() -> None:
            while os.getppid() == parent:
                time.sleep(0.5)
            os._exit(1)

        threading.Thread(target=watch, daemon=True, name="capred-parent-watch").start()


def _pool(workers: int):
    """A process pool whose workers die with this process (``die_with_parent``).

    Forked workers where the platform offers it (they start with capred imported).
    """
    import multiprocessing
    import os
    import sys
    from concurrent.futures import ProcessPoolExecutor

    kw = dict(max_workers=workers, initializer=die_with_parent, initargs=(os.getpid(),))
    if sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods():
        return ProcessPoolExecutor(mp_context=multiprocessing.get_context("fork"), **kw)
    return ProcessPoolExecutor(**kw)  # pragma: no cover


def run_all(jobs: list[Job], workers: int | None = None, on_done=None) -> tuple[list[Outcome], bool]:
    """Outcomes of every job in input order, and whether the run was interrupted (Ctrl-C).

    Parameters
    ----------
    jobs : list of Job
        The runs, each with its own output folder.
    workers : int, optional
        Worker processes; None (the default): one per core, at most one per
        job (see ``default_workers``). One worker runs the jobs in this process.
    on_done : callable, optional
        Called with each Outcome as its job ends.

    Returns
    -------
    (list of Outcome, bool)
        One outcome per job, in the order of ``jobs``, and True after Ctrl-C
        or a worker's death (the jobs not done are then ``interrupted``).
    """
    if workers is None or workers < 1:
        workers = default_workers(len(jobs))
    outcomes: dict[int, Outcome] = {}
    interrupted = False
    try:
        if len(jobs) > 1:  # what the jobs import is loaded first: its BLAS libraries are then limited too
            _warm(jobs)
        with single_threaded_blas() if len(jobs) > 1 else nullcontext():
            _run(jobs, workers, outcomes, on_done)
    except KeyboardInterrupt:
        interrupted = True
    except Exception as exc:  # a worker process died: the jobs it held are reported, not lost
        if type(exc).__name__ != "BrokenProcessPool":
            raise
        interrupted = True
    result = []
    for k, job in enumerate(jobs):
        if k in outcomes:
            result.append(outcomes[k])
        else:
            result.append(
                Outcome(
                    job.command,
                    str(getattr(job.source, "path", job.source) or ""),
                    str(job.out_dir),
                    "interrupted",
                    "not run: the batch was interrupted",
                )
            )
    return result, interrupted


#: most jobs a worker is handed at once (`job_chunks`)
MAX_CHUNK = 8


def job_chunks(first: int, stop: int, workers: int) -> list[tuple[int, int]]:
    """The jobs ``first`` .. ``stop - 1`` cut into the pool's tasks, (start, stop) each, in order.

    Guided scheduling: each task a quarter of a worker's share of the jobs left, at most MAX_CHUNK and at least one.

    A task of several jobs pays the pool's per-task cost (pickling, queues, wake-ups: ~0.1 ms of CPU, measured
    with 2,000 empty jobs) once; the last tasks hold one job each, so that the workers finish together.

    Parameters
    ----------
    first, stop : int
        The jobs to cut [-].
    workers : int
        Worker processes [-].

    Returns
    -------
    list of (int, int)
    """
    out, k = [], first
    while k < stop:
        size = max(1, min(MAX_CHUNK, (stop - k) // (4 * max(workers, 1))))
        out.append((k, k + size))
        k += size
    return out


def run_chunk(jobs: list[Job]) -> list[Outcome]:
    """The outcomes of a few jobs run in turn in one worker (`run_safely` each).

    Parameters
    ----------
    jobs : list of Job
        The jobs, run in order.

    Returns
    -------
    list of Outcome
        One per job, in the same order.
    """
    return [run_safely(job) for job in jobs]


def _run(jobs: list[Job], workers: int, outcomes: dict, on_done) -> None:
    """Run the jobs, in this process or in a pool, filling ``outcomes`` (job index -> Outcome) as they end.

    With a pool, the first job runs in this process before the workers are forked: what a job loads on first
    use (pandas, scipy.special, jinja2 and the compiled report template, pint's registry: ~0.85 s of CPU for a
    shear file, against ~0.05 s for the next one) is then loaded once and inherited by every worker instead
    of loaded again by each (benchmarks/bench_batch.py).
    """

    def done(k: int, outcome: Outcome) -> None:
        outcomes[k] = outcome
        if on_done:
            on_done(outcome)

    if workers <= 1 or len(jobs) <= 2:
        for k, job in enumerate(jobs):
            done(k, run_safely(job))
        return
    done(0, run_safely(jobs[0]))
    import gc
    from concurrent.futures import as_completed

    gc.collect()
    gc.freeze()  # the workers' collections leave the inherited objects alone: their pages stay shared
    try:
        pool = _pool(min(workers, len(jobs) - 1))
        try:
            futures = {pool.submit(run_chunk, jobs[a:b]): a for a, b in job_chunks(1, len(jobs), workers)}
            for fut in as_completed(futures):
                for j, outcome in enumerate(fut.result()):
                    done(futures[fut] + j, outcome)
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
    finally:
        gc.unfreeze()


def output_dirs(commands: list[str], sources: list[Path], root: Path) -> list[Path]:
    """One folder per input under ``root``: <prefix>_<stem>, made unique with parent names or a number.

    Parameters
    ----------
    commands : list of str
        The command of each job (its registry entry gives the folder prefix).
    sources : list of Path
        The input of each job (None where a command reads no file: stem ``options``).
    root : Path
        The batch output folder.

    Returns
    -------
    list of Path
        One output folder per job, in the order of ``sources``.
    """
    from .io import source_path
    from .reductions import REDUCTIONS

    sources = [source_path(p) for p in sources]
    prefixes = [REDUCTIONS[c].out_prefix for c in commands]
    stems = [Path(p).stem if p is not None else "options" for p in sources]
    names = [f"{prefix}_{stem}" for prefix, stem in zip(prefixes, stems)]
    from collections import Counter

    repeats = Counter(names)
    for i, p in enumerate(sources):
        if p is not None and repeats[names[i]] > 1:
            names[i] = f"{prefixes[i]}_{Path(p).parent.name}_{stems[i]}"
    seen: dict[str, int] = {}
    out = []
    for n in names:
        k = seen.get(n.lower(), 0)
        seen[n.lower()] = k + 1
        out.append(root / (n if k == 0 else f"{n}_{k + 1}"))
    return out


def _runs(root: Path, outcomes: list[Outcome]) -> list[str]:
    """The run folders of a batch, relative to its root."""
    out = []
    for o in outcomes:
        try:
            out.append(Path(o.out_dir).relative_to(root).as_posix())
        except ValueError:
            continue
    return out


def relative(path, root) -> str:
    """A path as index.csv and season.csv write it: relative to the batch root, with '/' ("" for none).

    Parameters
    ----------
    path : str or Path or None
        The path to write.
    root : str or Path
        The batch root.

    Returns
    -------
    str
        The POSIX path relative to ``root``; "" when ``path`` is empty.
    """
    import os

    if not path:
        return ""
    full, base = os.path.abspath(path), os.path.abspath(root)
    under = base if base.endswith(os.sep) else base + os.sep
    if full.startswith(under):  # the usual case, a file of the batch: what relpath gives, without its cost
        return full[len(under) :].replace(os.sep, "/")
    try:
        return Path(os.path.relpath(full, base)).as_posix()
    except ValueError:  # pragma: no cover - another drive (Windows)
        return Path(path).as_posix()


def one_line(message: str) -> str:
    """A message of several lines (one per problem) as one CSV cell: its lines stripped, joined by ' | '.

    Parameters
    ----------
    message : str
        A message, possibly of several lines.

    Returns
    -------
    str
        The message on one line.
    """
    return " | ".join(x.strip(" -") for x in message.splitlines() if x.strip())


# --- labels and units of the season tables --------------------------------------------------------------
def model_label(name):
    """The label of a model, law or retention model as its registry gives it; other values as they are.

    ``own1`` -> ``Own 1``, ``vg`` -> ``van Genuchten, m = 1 - 1/n``.

    Parameters
    ----------
    name : str or object
        A model, law or retention-model id; any other value is returned unchanged.

    Returns
    -------
    str or object
        The registry label, or ``name`` itself where no registry knows it.
    """
    if not isinstance(name, str):
        return name
    from .fitting.retention_models import MODELS
    from .physics.effective_stress_models import REGISTRY

    for registry in (REGISTRY, MODELS):
        entry = registry.get(name)
        if entry is not None and getattr(entry, "label", None):
            return entry.label
    return name


def unit_header(key: str, values) -> str:
    """A season column's header in the ``name [unit]`` form of every capred CSV, from the names' one source.

    A header that has its unit already (``c [kPa]``: a result's season rows write them from its records) is
    kept; a JSON key with a unit suffix (``alpha_per_kPa``) gets the header every capred CSV gives it
    (:func:`capred.result.csv_header`, ``alpha [1/kPa]``); a quantity of the glossary
    (capred.nomenclature.QUANTITIES, ``B``) its glossary unit; another number ``[-]`` (a count, a
    dimensionless score: ``n_points``, ``r2``); a text column its name alone.

    Parameters
    ----------
    key : str
        The season column's key.
    values : iterable
        The column's values (decide ``[-]`` for numbers or no unit for text).

    Returns
    -------
    str
        The CSV header.
    """
    import numbers

    from .nomenclature import QUANTITIES
    from .result import csv_header

    if key.endswith("]") and " [" in key:
        return key
    head = csv_header(key)
    if head != key:
        return head
    present = [v for v in values if v is not None]
    if present and all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in present):
        q = QUANTITIES.get(key)
        return f"{key} [{q.unit if q is not None else '-'}]"
    return key


def labelled(rows: list[dict]) -> list[dict]:
    """Season rows with every model id (``best_model``, ``*_model``) replaced by its registry label.

    Parameters
    ----------
    rows : list of dict
        Season rows of a result.

    Returns
    -------
    list of dict
        New rows (the input is not modified) with model ids as labels.
    """
    return [{k: (model_label(v) if k.endswith("model") else v) for k, v in r.items()} for r in rows]


def headline(rows: list[dict]) -> str:
    """The main results of a run in one line, from its season rows.

    Per row its label (material, branch), its first two measured values with units and its best model, e.g. ``steel_2mm:
    c 0.3701 kPa, phi 34.59 deg, best model: Own 2``; rows separated by `` | ``.

    Parameters
    ----------
    rows : list of dict
        Season rows of a result, model ids already labelled.

    Returns
    -------
    str
        The headline ("" when no row gives anything).
    """
    from .report.render import fmt

    parts = []
    for r in rows:
        label = next((v for k, v in r.items() if isinstance(v, str) and not k.endswith("model")), "")
        values = []
        for k, v in r.items():
            if len(values) == 2:
                break
            if isinstance(v, float) and "_se" not in k and not k.startswith("n_"):
                head = unit_header(k, [v])
                name, _, unit = head.partition(" [")
                unit = unit.rstrip("]")
                values.append(f"{name} {fmt(v)}" + (f" {unit}" if unit and unit != "-" else ""))
        best = next((v for k, v in r.items() if k.endswith("model") and v), None)
        if best:
            values.append(f"best model: {best}")
        parts.append((f"{label}: " if label else "") + ", ".join(values))
    return " | ".join(p for p in parts if p)


def _count_line(result) -> str:
    """The headline of a run without season rows: how many rows its table holds."""
    try:
        n = result.row_count()
    except Exception:  # pragma: no cover - a result that cannot count its rows still gets its season row
        return ""
    return f"{n} row{'s' if n != 1 else ''}"


def write_index(root: Path, outcomes: list[Outcome], batch_files=()) -> Path:
    """index.csv: the one list of everything a batch wrote.

    Every input with its status, message and each output file written, then every file of the batch root
    (``batch_files``: season.csv, season_<command>.csv, season.html; provenance.json) as rows of command ``batch``.
    Paths are relative to the batch root.

    Refused (OutputError) where an index.csv exists that capred did not write (or a user edited since);
    recorded with its hash in the batch's provenance.json.

    Parameters
    ----------
    root : Path
        The batch root folder.
    outcomes : list of Outcome
        The outcome of every job.
    batch_files : sequence of path, optional
        The other files written at the batch root.

    Returns
    -------
    Path
        The index.csv written.
    """
    import csv
    import io

    from .io import INDEX_HEADER, write_batch_file

    root = Path(root)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(INDEX_HEADER.split(","))
    for o in outcomes:
        message = one_line(o.message)
        src = relative(o.source, root)
        if o.outputs:
            for f in o.outputs:
                w.writerow([o.command, src, o.status, message, relative(f, root)])
        else:
            w.writerow([o.command, src, o.status, message, ""])
    for name in [*(Path(p).name for p in batch_files), "index.csv", "provenance.json"]:
        w.writerow(["batch", "", "ok", "", name])
    return write_batch_file(root, "index.csv", buf.getvalue().encode("utf-8"), runs=_runs(root, outcomes))


def season_tables(root: Path, outcomes: list[Outcome]) -> tuple[dict, dict]:
    """(season, {command: details}) of a batch, each a mapping of ``name [unit]`` header to column.

    ``season`` has one row per run with what every command shares: command, input (relative to the batch
    root), status, the reason of a failure, the materials (or branches), the headline results with labels,
    the number of warnings and its report. ``details`` holds each command's own rows
    (``Result.season_rows``: per material, branch or envelope) with the input they come from: one kind of
    record per table.

    Parameters
    ----------
    root : Path
        The batch root folder.
    outcomes : list of Outcome
        The outcome of every job.

    Returns
    -------
    tuple of dict
        ``(season, details)``: the table of runs and, per command, its table of detail rows.
    """
    root = Path(root)
    details = {}
    for o in outcomes:
        for r in o.season:
            details.setdefault(o.command, []).append({"input": relative(o.source, root), **r})
    return season_table(season_runs(root, outcomes)), {c: _with_units(season_columns(r)) for c, r in details.items()}


# --- season.csv as typed records: one SeasonRun per run, each field declaring its header once ------------
def season_field(unit: str | None = None, description: str = ""):
    """A field of :class:`SeasonRun`: its header is the field's name, with ``[unit]`` for a number.

    Parameters
    ----------
    unit : str or None, optional
        Unit of a numeric column (``"-"`` for a count); None for text.
    description : str, optional
        What the column holds (the README's season.csv table).

    Returns
    -------
    dataclasses.Field
    """
    return field(default=None, metadata={"unit": unit, "description": description})


@dataclass(frozen=True)
class SeasonRun:
    """One run of a batch as season.csv gives it: what every command shares.

    Attributes
    ----------
    command : str
        The command run.
    input : str
        Its input, relative to the batch root.
    status : str
        ``ok``, ``failed``, ``crashed`` or ``interrupted``.
    reason : str
        Why a run did not succeed, on one line ("" when ok).
    material : str
        The materials (or branches, envelopes) of its season rows, ``; ``-separated.
    headline : str
        The run's main results in a line, with labels and units.
    options : str
        The run's options that differ from its command's defaults, as a user types them ("" for none).
    warnings : int or None
        How many warnings the run gave [-] (None unless ok).
    report : str
        Its report.html, relative to the batch root ("" when none).
    """

    command: str = season_field(description="the command run")
    input: str = season_field(description="its input, relative to the batch root")
    status: str = season_field(description="ok, failed, crashed or interrupted")
    reason: str = season_field(description="why a run did not succeed")
    material: str = season_field(description="the materials, branches or envelopes of its results")
    headline: str = season_field(description="its main results in a line")
    options: str = season_field(description="its options that differ from the command's defaults")
    warnings: int | None = season_field("-", "how many warnings the run gave")
    report: str = season_field(description="its report.html, relative to the batch root")

    @classmethod
    def header(cls, f) -> str:
        """The CSV and season.html header of field ``f``: ``name`` (text) or ``name [unit]`` (a number).

        Parameters
        ----------
        f : dataclasses.Field
            A field of SeasonRun.

        Returns
        -------
        str
        """
        unit = f.metadata.get("unit")
        return f.name if unit is None else f"{f.name} [{unit}]"


def season_runs(root: Path, outcomes: list[Outcome]) -> list[SeasonRun]:
    """The season record of every run of a batch, in the order of ``outcomes``.

    Parameters
    ----------
    root : Path
        The batch root folder (paths are written relative to it).
    outcomes : list of Outcome
        The outcome of every job.

    Returns
    -------
    list of SeasonRun
    """
    root = Path(root)
    runs = []
    for o in outcomes:
        report = Path(o.out_dir) / "report.html"
        link = report.relative_to(root).as_posix() if o.ok and report.exists() and _under(report, root) else ""
        labels = [next((v for v in r.values() if isinstance(v, str)), "") for r in o.season]
        runs.append(
            SeasonRun(
                command=o.command,
                input=relative(o.source, root),
                status=o.status,
                reason=one_line(o.message) if not o.ok else "",
                material="; ".join(x for x in dict.fromkeys(labels) if x),
                headline=o.headline,
                options=o.options,
                warnings=o.warnings if o.ok else None,
                report=link,
            )
        )
    return runs


def season_table(runs: list[SeasonRun]) -> dict:
    """season.csv's columns from its records: ``{header: array}``, headers from the fields' declarations.

    Parameters
    ----------
    runs : list of SeasonRun
        The runs.

    Returns
    -------
    dict
        Header -> column (as :func:`season_columns` types it); every field's column, even for no run.
    """
    import dataclasses

    import numpy as np

    fields = dataclasses.fields(SeasonRun)
    cols = season_columns([{f.name: getattr(r, f.name) for f in fields} for r in runs])
    return {SeasonRun.header(f): cols.get(f.name, np.array([], dtype=object)) for f in fields}


def _under(path: Path, root: Path) -> bool:
    try:
        path.relative_to(root)
    except ValueError:
        return False
    return True


def _with_units(columns: dict) -> dict:
    return {unit_header(k, v.tolist()): v for k, v in columns.items()}


def season_file(command: str) -> str:
    """The file of one command's season details: ``season_<command>.csv``.

    ``bridge solve`` -> ``season_bridge-solve.csv``.

    Parameters
    ----------
    command : str
        The command's name.

    Returns
    -------
    str
        The file name.
    """
    return f"season_{command.replace(' ', '-')}.csv"


def write_season(root: Path, outcomes: list[Outcome]) -> list[Path]:
    """Write season.csv, season_<command>.csv and season.html, each protected and recorded.

    season.csv has one row per run (command, input, status, reason, material, headline, options, warnings, report),
    season_<command>.csv each command's detail rows and season.html a section per command; each is protected as every
    batch root file is (refused where a file of that name exists that capred did not write, e.g. a manifest called
    season.csv, or that a user edited since) and recorded in the batch's provenance.json.

    Parameters
    ----------
    root : Path
        The batch root folder.
    outcomes : list of Outcome
        The outcome of every job.

    Returns
    -------
    list of Path
        The files written: season.csv, one season_<command>.csv per command with details, season.html.
    """
    from .io import encode_csv, write_batch_file
    from .report.html import render_season

    root = Path(root)
    table, details = season_tables(root, outcomes)
    runs = _runs(root, outcomes)
    names = {c: season_file(c) for c in details}
    written = [write_batch_file(root, "season.csv", encode_csv(table), runs)]
    for command, columns in details.items():
        written.append(write_batch_file(root, names[command], encode_csv(columns), runs))
    files = [p.name for p in written] + ["season.html", "index.csv", "provenance.json"]
    page = render_season(table, sections=details, files=files)
    written.append(write_batch_file(root, "season.html", page.encode("utf-8"), runs))
    return written


def season_columns(rows: list[dict]) -> dict:
    """The season table's columns (every key of any row, in order of first appearance) as arrays.

    Counts stay whole numbers (Python ints, None where a run has none: ``n_dry`` of a retention row), other numbers
    floats (NaN where a run has none), text and mixed columns objects (None where missing).

    Parameters
    ----------
    rows : list of dict
        The season rows.

    Returns
    -------
    dict
        Column name -> numpy array (object for counts and text, float otherwise).
    """
    import numbers

    import numpy as np

    names = list(dict.fromkeys(k for r in rows for k in r))
    out = {}
    for name in names:
        values = [r.get(name) for r in rows]
        present = [v for v in values if v is not None]
        if present and all(isinstance(v, numbers.Integral) and not isinstance(v, (bool, np.bool_)) for v in present):
            out[name] = np.array([None if v is None else int(v) for v in values], dtype=object)
        elif present and all(isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_)) for v in present):
            out[name] = np.array([np.nan if v is None else float(v) for v in values], dtype=float)
        else:
            out[name] = np.array(values, dtype=object)
    return out


# --- `capred batch --json` as typed records: each field declares its JSON key once ----------------------
def json_field(description: str):
    """A field of :class:`BatchFile` or :class:`BatchDocument`: its JSON key is the field's name.

    Parameters
    ----------
    description : str
        What the key holds (the README's ``--json`` description).

    Returns
    -------
    dataclasses.Field
    """
    return field(default=None, metadata={"description": description})


def _record_json(record) -> dict:
    """``{field name: value}`` of a JSON record, in declaration order (nested records and lists of them too)."""
    import dataclasses

    def plain(v):
        if dataclasses.is_dataclass(v) and not isinstance(v, type):
            return _record_json(v)
        if isinstance(v, (list, tuple)):
            return [plain(x) for x in v]
        return v

    return {f.name: plain(getattr(record, f.name)) for f in dataclasses.fields(record)}


@dataclass(frozen=True)
class BatchFile:
    """One run of a batch as ``capred batch --json`` gives it (a JSON object per input).

    Attributes
    ----------
    input : str
        The input file, as the batch read it.
    command : str
        The command run.
    status : str
        ``ok``, ``failed``, ``crashed`` or ``interrupted``.
    ok : bool
        ``status == "ok"``.
    error : str or None
        Why the run did not succeed (None when ok).
    out_dir : str or None
        Its output folder (None when the batch wrote no files).
    result : dict or None
        The run's own JSON document (None unless ok).
    """

    input: str = json_field("the input file")
    command: str = json_field("the command run")
    status: str = json_field("ok, failed, crashed or interrupted")
    ok: bool = json_field("whether the run succeeded")
    error: str | None = json_field("why the run did not succeed (null when ok)")
    out_dir: str | None = json_field("its output folder (null when the batch wrote no files)")
    result: dict | None = json_field("the run's JSON document, as `capred <command> --json` prints it")

    @classmethod
    def of(cls, outcome: Outcome, wrote: bool) -> BatchFile:
        """The record of one outcome.

        Parameters
        ----------
        outcome : Outcome
            A job's outcome.
        wrote : bool
            Whether the batch wrote output folders (``--out``, or a command that writes by default).

        Returns
        -------
        BatchFile
        """
        return cls(
            input=outcome.source,
            command=outcome.command,
            status=outcome.status,
            ok=outcome.ok,
            error=outcome.message or None,
            out_dir=outcome.out_dir if wrote else None,
            result=outcome.result_json,
        )

    def to_json(self) -> dict:
        """The JSON object: one key per field, in declaration order.

        Returns
        -------
        dict
        """
        return _record_json(self)


@dataclass(frozen=True)
class BatchDocument:
    """What ``capred batch --json`` prints: every run, the index written and the counts of bad runs.

    Attributes
    ----------
    files : list of BatchFile
        Every run, in the order of the batch.
    index : str or None
        The index.csv written (None when the batch wrote no files).
    failed : int
        How many runs failed or crashed [-].
    interrupted : int
        How many runs Ctrl-C left undone [-].
    """

    files: list = json_field("every run, in the order of the batch")
    index: str | None = json_field("the index.csv written (null when the batch wrote no files)")
    failed: int = json_field("how many runs failed or crashed")
    interrupted: int = json_field("how many runs Ctrl-C left undone")

    @classmethod
    def of(cls, outcomes: list[Outcome], index: Path | None, wrote: bool) -> BatchDocument:
        """The document of a batch's outcomes.

        Parameters
        ----------
        outcomes : list of Outcome
            The outcome of every job.
        index : Path or None
            The index.csv written.
        wrote : bool
            Whether the batch wrote output folders.

        Returns
        -------
        BatchDocument
        """
        return cls(
            files=[BatchFile.of(o, wrote) for o in outcomes],
            index=str(index) if index else None,
            failed=sum(o.status in ("failed", "crashed") for o in outcomes),
            interrupted=sum(o.status == "interrupted" for o in outcomes),
        )

    def to_json(self) -> dict:
        """The JSON document: one key per field, in declaration order (``files`` as a list of objects).

        Returns
        -------
        dict
        """
        return _record_json(self)
