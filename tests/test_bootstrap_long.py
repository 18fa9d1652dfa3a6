"""The bootstrap of a long material (beyond KEEP_FEATURES_TESTS wet tests) has no cost step (issue 31).

Beyond KEEP_FEATURES_TESTS wet tests the bootstrap used to form every chunk's weighted-sum products again in
every block of one to four replicates (a step of 2-4x in its cost per test). With every model affine it now
runs chunk by chunk (`_score_long`): each chunk's products once, every replicate's counts of the chunk drawn
there (multinomial split of the nw draws among the chunks, then uniform within each). The thresholds are
monkeypatched small so that a table of a few hundred wet tests takes that path; the checks are

- the counts are resamples: nw draws per replicate, each test drawn once per replicate on average;
- every replicate's RMSE is the RMSE of its own resample, computed directly from the counts;
- the same seed gives the same numbers, and the distribution is the block loop's (another stream);
- the work is counted, not timed: each chunk's products are formed once, whatever the replicates.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from capred.fitting.linear import fit_line
from capred.physics import effective_stress_models as esm
from capred.pipelines import shear_analysis as sa
from capred.pipelines.shear import ModelParams

C, TAN_PHI = 300.0, 0.7  # Pa, -
MODELS = ["no_suction", "bishop", "own1"]
NW = 300  # wet tests: beyond the patched KEEP_FEATURES_TESTS below, in 7 chunks of 48 (the last of 12)


def _material(nw: int = NW, n_dry: int = 40, seed: int = 3):
    """One material: ``n_dry`` dry tests at 1-3 kPa, ``nw`` wet tests at scattered suctions (tau on Bishop's
    envelope with chi = S_R, 10 Pa noise) -- close enough between models that the ranking is contested."""
    rng = np.random.default_rng(seed)
    dry_x = rng.uniform(1e3, 3e3, n_dry)
    dry_y = C + TAN_PHI * dry_x + rng.normal(0, 10.0, n_dry)
    fit = fit_line(dry_x, dry_y)
    sigma = rng.choice([1e3, 2e3, 3e3], nw)
    S_R = rng.uniform(0.05, 0.9, nw)
    suction = 4e3 * (1 - S_R) + 300.0
    tau = C + TAN_PHI * (sigma + S_R * suction * rng.uniform(0.3, 1.0, nw)) + rng.normal(0, 10.0, nw)
    d = esm.ModelInputs(
        sigma,
        suction,
        S_R,
        np.full(nw, 1e-3),
        tau,
        np.ones(nw, bool),
        np.array(["m"] * nw, dtype=object),
        np.full(nw, fit.intercept),
        np.full(nw, fit.slope),
        0.0728,
        ModelParams(),
    )
    return d, dry_x, dry_y


@pytest.fixture
def long_path(monkeypatch):
    """Thresholds small enough that NW wet tests are a long material, read in several chunks."""
    monkeypatch.setattr(sa, "KEEP_FEATURES_TESTS", 100)
    monkeypatch.setattr(sa, "CHUNK_TESTS", 48)
    monkeypatch.setattr(sa, "BLOCK_ELEMENTS", 48 * 5)  # groups of 5 replicates per chunk: several groups
    return monkeypatch


def _run(d, dry_x, dry_y, replicates: int, seed: int, monkeypatch, keep_scores: list | None = None):
    if keep_scores is not None:
        real = sa._summarise

        def spy(scores, *args):
            keep_scores.append(scores.copy())
            return real(scores, *args)

        monkeypatch.setattr(sa, "_summarise", spy)
    return sa.bootstrap_ranking(d, dry_x, dry_y, MODELS, ModelParams(), {}, ["bishop", "own1"], replicates, seed, False)


def test_wet_counts_are_resamples_of_every_test():
    """Each replicate's counts sum to nw over the chunks; every chunk and group is yielded once; a test's mean
    count over R replicates is 1 (its count is Binomial(nw, 1/nw), SD ~1, so the mean's SD is 1/sqrt(R) =
    0.022 at R = 2000; 5 SD for each of the 300 tests: a false alarm has probability ~2e-4)."""
    chunks = [slice(k, min(k + 48, NW)) for k in range(0, NW, 48)]
    R = 2000
    W = np.zeros((R, NW))
    seen = np.zeros((R, len(chunks)), int)
    for chunk, first, w in sa._wet_counts(np.random.default_rng(1), NW, R, chunks):
        j = chunks.index(chunk)
        W[first : first + w.shape[0], chunk] += w
        seen[first : first + w.shape[0], j] += 1
    assert (seen == 1).all()
    assert (W.sum(axis=1) == NW).all()
    assert np.all(np.abs(W.mean(axis=0) - 1.0) < 5 / np.sqrt(R))
    # a test's count has the multinomial's variance 1 - 1/nw (a fixed split among the chunks would give 1 - 1/48):
    # pooled over the 300 tests, the estimate's SD is ~sqrt(3/R)/sqrt(300) = 0.0022 (Poisson-like fourth
    # moment); 0.01 is 4.5 SD
    assert abs(W.var(axis=0).mean() - (1 - 1 / NW)) < 0.01
    # and the draws falling in a chunk of k tests vary as Binomial(nw, k/nw) (0 for a fixed split): the sample
    # variance's relative SD is sqrt(2/R) = 3.2 %; 20 % is 6 SD
    for chunk in chunks:
        k = chunk.stop - chunk.start
        assert W[:, chunk].sum(axis=1).var() == pytest.approx(NW * (k / NW) * (1 - k / NW), rel=0.2)


def test_each_replicate_scores_its_own_resample(long_path):
    """The RMSE the chunk loop gives every replicate and model is that model's RMSE on the replicate's resample
    (the counts drawn) with the replicate's refitted dry envelope, computed directly test by test. Tolerance:
    the chunk loop expands the squares into weighted sums (cancellation ~1e-12 relative here); 1e-8."""
    d, dry_x, dry_y = _material()
    counts, envelopes, scores = [], [], []
    real_counts, real_refit = sa._wet_counts, sa._dry_refit

    def wet_counts(*args):
        for out in real_counts(*args):
            counts.append(out)
            yield out

    def dry_refit(*args):
        out = real_refit(*args)
        envelopes.append(out)
        return out

    long_path.setattr(sa, "_wet_counts", wet_counts)
    long_path.setattr(sa, "_dry_refit", dry_refit)
    R = 12
    _run(d, dry_x, dry_y, R, 7, long_path, scores)
    assert len({id(ch) for ch, _, _ in counts}) > 1  # the chunk loop ran, over several chunks
    W = np.zeros((R, NW))
    for chunk, first, w in counts:
        W[first : first + w.shape[0], chunk] += w
    c = np.concatenate([e[0] for e in envelopes])
    b = np.concatenate([e[1] for e in envelopes])
    assert c.size == R  # every dry sample here fits a line: one refit per replicate
    for r in range(R):
        w_r = dataclasses.replace(d, c=np.full(NW, c[r]), tan_phi=np.full(NW, b[r]))
        for k, m in enumerate(MODELS):
            res = sa._tau(m, w_r) - d.tau_max
            want = np.sqrt(np.sum(W[r] * res**2) / W[r].sum())
            assert scores[0][r, k] == pytest.approx(want, rel=1e-8), (r, m)


def test_same_seed_same_numbers_and_the_block_loops_distribution(long_path):
    """Same seed: the same numbers, bit for bit. Against the block loop (thresholds left at their defaults:
    another random stream, the same distribution) at R = 2000: each model's win share differs by at most
    5 SD of the difference of two independent binomial shares (sqrt(2 p (1 - p) / R) <= 0.016), and each
    model's mean RMSE over the replicates by at most 5 SD of the difference of two means."""
    d, dry_x, dry_y = _material()
    R = 2000
    a_scores, b_scores = [], []
    a = _run(d, dry_x, dry_y, R, 11, long_path, a_scores)
    again = _run(d, dry_x, dry_y, R, 11, long_path)
    assert a == again
    long_path.undo()  # the default thresholds: the block loop
    blocks = _run(d, dry_x, dry_y, R, 11, long_path, b_scores)
    for m in MODELS:
        p = (a.probability[m] + blocks.probability[m]) / 2
        assert abs(a.probability[m] - blocks.probability[m]) <= 5 * np.sqrt(2 * max(p * (1 - p), 1e-4) / R)
    sa_, sb = a_scores[0], b_scores[-1]
    for k, m in enumerate(MODELS):
        sd = np.sqrt((sa_[:, k].var() + sb[:, k].var()) / R)
        assert abs(sa_[:, k].mean() - sb[:, k].mean()) <= 5 * sd, m


def test_each_chunk_forms_its_products_once_whatever_the_replicates(long_path):
    """The work is counted: the chunk loop forms the products of each of the 7 chunks once, at R = 40 and at
    R = 400 alike (the block loop formed them in every block: R / block times each)."""
    d, dry_x, dry_y = _material()
    calls = []
    real = sa._affine_features_t

    def counted(affine, rows):
        calls.append(rows)
        return real(affine, rows)

    long_path.setattr(sa, "_affine_features_t", counted)
    for R in (40, 400):
        calls.clear()
        _run(d, dry_x, dry_y, R, 2, long_path)
        assert len(calls) == 7 and len({(s.start, s.stop) for s in calls}) == 7
