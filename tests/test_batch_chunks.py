"""How a batch cuts its jobs into the pool's tasks (capred.batch.job_chunks): every job once, in order, a few
per task while many are left and one per task at the end, so that the workers finish together."""

import pytest

from capred.batch import MAX_CHUNK, job_chunks


@pytest.mark.parametrize("n, workers", [(2, 2), (3, 2), (20, 2), (1000, 2), (1000, 1), (37, 5)])
def test_every_job_once_in_order(n, workers):
    chunks = job_chunks(1, n, workers)
    covered = [k for a, b in chunks for k in range(a, b)]
    assert covered == list(range(1, n))  # job 0 runs in the batch's own process before the pool starts
    assert all(1 <= b - a <= MAX_CHUNK for a, b in chunks)


def test_tasks_shrink_to_one_job_at_the_end():
    chunks = job_chunks(1, 1000, 2)
    sizes = [b - a for a, b in chunks]
    assert sizes[0] == MAX_CHUNK  # 999 jobs left: a quarter of a worker's share is 124, capped at 8
    assert sizes == sorted(sizes, reverse=True)  # guided: never larger than the task before
    # the last 8 jobs (a quarter of a worker's share below 1) go one per task: at most one job's time apart
    assert sizes[-8:] == [1] * 8
    # 1,000 files in 144 tasks instead of 999: the pool's per-task cost paid about 7 times less often
    assert len(chunks) == 144


def test_few_jobs_one_per_task():
    assert job_chunks(1, 9, 2) == [(k, k + 1) for k in range(1, 9)]
