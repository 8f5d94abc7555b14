"""The design search's worker benchmark: one design file's screen with one worker, then with
two sharing one store, in the same run (``gecko-agents design FILE --benchmark``).

Each timed screen is what a user waits for: a new SQLite store in a temporary folder, the
workers (the calling process and the spawned ones, :func:`gecko_agents.design.study.search_study`)
started and run until the store holds the trials. The pairs alternate their order (1 then 2
workers, then 2 then 1, …) so that a machine whose load drifts during the run hits both alike;
the ratio of each pair is reported, not only their median, since the other jobs of a shared
machine set how much of a second core a second worker gets.
"""

from __future__ import annotations

import statistics
import tempfile
import time
from pathlib import Path

__all__ = ["benchmark_workers"]


def _screen_time(spec, trials: int, workers: int) -> tuple[float, int]:
    """(wall time [s], finished trials) of one screen of ``trials`` trials on ``workers``
    workers into a new store."""
    from gecko_agents.design import search, study

    with tempfile.TemporaryDirectory(prefix="gecko_design_bench_") as tmp:
        t0 = time.perf_counter()
        s = study.search_study(spec, Path(tmp), trials, None, workers, None)
        wall = time.perf_counter() - t0
        return wall, len(search.completed(s))


def benchmark_workers(spec, trials: int | None = None, pairs: int = 1, workers: int = 2) -> dict:
    """Wall time of a design file's screen of ``trials`` trials (default the file's) on one
    worker and on ``workers`` workers, ``pairs`` times in alternating order.

    Returns
    -------
    dict
        ``"one_s"``, ``"many_s"``: the wall times [s] of each pair (lists), ``"ratios"``:
        many/one of each pair, ``"ratio"``: their median, ``"trials"``, ``"workers"``.
    """
    if pairs < 1:
        raise ValueError(f"pairs = {pairs!r} must be ≥ 1")
    if workers < 2:
        raise ValueError(f"workers = {workers!r} must be ≥ 2 (compared with one)")
    n = spec.trials if trials is None else int(trials)
    one, many = [], []
    for k in range(pairs):
        order = (1, workers) if k % 2 == 0 else (workers, 1)
        for w in order:
            wall, _ = _screen_time(spec, n, w)
            (one if w == 1 else many).append(wall)
    ratios = [m / o for m, o in zip(many, one, strict=True)]
    return {
        "one_s": one,
        "many_s": many,
        "ratios": ratios,
        "ratio": statistics.median(ratios),
        "trials": n,
        "workers": workers,
    }
