"""Progress of long single runs on a terminal.

The reduction's loops (``steps()``), the figures and the files (``task()``) advance a rich progress bar on standard
error while ``showing()`` is active.

The bar appears only once a run has lasted ``DELAY`` seconds (a quick run prints
nothing extra) and disappears when the block ends. The command line turns it on
for a terminal without ``--json``; scripts, notebooks and pipes see nothing.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import TypeVar

T = TypeVar("T")
_PROGRESS: ContextVar = ContextVar("capred_progress", default=None)
#: seconds a run lasts before its bar appears
DELAY = 1.0
_wanted = False  # set once a command line on a terminal asked for progress (see ``wanted``)


def steps(items: Iterable[T], description: str, total: int | None = None) -> Iterator[T]:
    """Iterate over ``items``, advancing a progress bar when one is showing.

    Parameters
    ----------
    items : iterable
        What to iterate over.
    description : str
        Text of the bar.
    total : int or None, optional
        Number of items (default ``len(items)``).

    Yields
    ------
    object
        Each item of ``items``.
    """
    progress = _PROGRESS.get()
    if progress is None:
        yield from items
        return
    task_id = progress.add_task(description, total=total if total is not None else len(items))  # type: ignore[arg-type]
    try:
        for item in items:
            yield item
            progress.advance(task_id)
    finally:
        progress.remove_task(task_id)


@contextmanager
def task(description: str, total: int | None = None) -> Iterator[Callable[[int], None]]:
    """A bar for one stage of a run (``total`` steps; None: a stage of unknown length); yields ``advance(n=1)``.

    Without a progress display (a script, a pipe, ``--json``) ``advance`` does nothing.

    Parameters
    ----------
    description : str
        Text of the bar.
    total : int or None, optional
        Number of steps; None: unknown.

    Yields
    ------
    callable
        ``advance(n=1)``, to call as steps are done.
    """
    progress = _PROGRESS.get()
    if progress is None:
        yield lambda n=1: None
        return
    task_id = progress.add_task(description, total=total)
    try:
        yield lambda n=1: progress.advance(task_id, n)
    finally:
        progress.remove_task(task_id)


def wanted() -> bool:
    """Whether this process is a command-line run that shows progress.

    Returns
    -------
    bool
        True once ``showing(True)`` was entered.
    """
    return _wanted


def detach() -> None:
    """Forget the display in a forked child process (only the parent draws the bar)."""
    _PROGRESS.set(None)


@contextmanager
def showing(enabled: bool, delay: float = DELAY):
    """Show the progress of ``steps()`` and ``task()`` on standard error while the block runs.

    Shown when ``enabled``, from ``delay`` seconds on; inside another ``showing`` block, its display is reused.

    Parameters
    ----------
    enabled : bool
        Show a display (False: the block runs without one).
    delay : float, optional
        Seconds before the display appears [s] (a short run shows none).
    """
    global _wanted
    if not enabled:
        yield
        return
    _wanted = True
    if _PROGRESS.get() is not None:
        yield
        return
    import threading

    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    progress = Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=Console(stderr=True),
        transient=True,
    )
    timer = threading.Timer(delay, progress.start)
    timer.daemon = True
    token = _PROGRESS.set(progress)
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
        timer.join()  # a start under way ends before the stop
        _PROGRESS.reset(token)
        progress.stop()
