"""Progress of long single runs: a reduction wraps its loop in ``steps()``; the command line shows a rich
progress bar on a terminal (set up by ``showing()``); scripts and pipes see nothing."""
from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from typing import Iterable, Iterator, TypeVar

T = TypeVar("T")
_PROGRESS: ContextVar = ContextVar("capred_progress", default=None)


def steps(items: Iterable[T], description: str, total: int | None = None) -> Iterator[T]:
    """Iterate over ``items``, advancing a progress bar when one is showing."""
    progress = _PROGRESS.get()
    if progress is None:
        yield from items
        return
    task = progress.add_task(description, total=total if total is not None else len(items))  # type: ignore[arg-type]
    for item in items:
        yield item
        progress.advance(task)
    progress.remove_task(task)


@contextmanager
def showing(enabled: bool):
    """Show the progress of ``steps()`` loops on standard error while the block runs (when ``enabled``)."""
    if not enabled:
        yield
        return
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=Console(stderr=True), transient=True) as progress:
        token = _PROGRESS.set(progress)
        try:
            yield
        finally:
            _PROGRESS.reset(token)
