"""A long retention fit shows progress (issue 46: work whose cost grows with the input shows progress)."""

import capred
from capred.progress import _PROGRESS


class _Recorder:
    """Stands in for rich's Progress: records each task's total and how far it was advanced."""

    def __init__(self):
        self.tasks = {}

    def add_task(self, description, total=None):
        self.tasks[len(self.tasks)] = [description, total, 0]
        return len(self.tasks) - 1

    def advance(self, task_id, n=1):
        self.tasks[task_id][2] += n

    def remove_task(self, task_id):
        pass


def test_retention_fits_advance_one_step_per_model_and_branch():
    """The sample has a drying and a wetting branch and the default models (vg, vg_m_free, bc): 2 x 3 = 6 steps,
    all done by the end of the run."""
    rec = _Recorder()
    token = _PROGRESS.set(rec)
    try:
        res = capred.run_retention(capred.sample_path("retention"))
    finally:
        _PROGRESS.reset(token)
    (fit_task,) = [t for t in rec.tasks.values() if t[0].startswith("fitting the models")]
    n_models = len(res.options.models)
    assert fit_task[1] == 2 * n_models and fit_task[2] == fit_task[1], fit_task


def test_residuals_in_blocks_of_rows_give_the_same_fits(monkeypatch):
    """A long file's residuals are evaluated a block of rows at a time (bounded memory: a 10 MB file, 430,000
    readings, peaked at 852 MB and now 571 MB, 58 s -> 42 s measured); each row's arithmetic is its own, so the
    fits are the same to the last bit (here forced to one row per block on the sample)."""
    import json

    from capred.fitting import retention_models

    whole = capred.run_retention(capred.sample_path("retention")).to_json()
    monkeypatch.setattr(retention_models, "_CHUNK", 1)  # one row per block
    blocks = capred.run_retention(capred.sample_path("retention")).to_json()
    assert json.dumps(blocks["fits"], sort_keys=True, default=str) == json.dumps(
        whole["fits"], sort_keys=True, default=str
    )
