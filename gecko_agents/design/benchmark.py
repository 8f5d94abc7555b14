"""The design search's worker benchmark: one design file's screen with one worker, then with
two sharing one store, in the same run (``gecko-agents design FILE --benchmark``).

Each timed screen is what a user waits for: a new SQLite store in a temporary folder, the
workers started and run until the store holds the trials
(:func:`gecko_agents.design.study.search_study`). The pairs alternate their order (1 then 2
workers, then 2 then 1, …) so that a machine whose load drifts during the run hits both alike;
the ratio of each pair is reported, not only their median, since the other jobs of a shared
machine set how much of a second core a second worker gets. Before each pair the same fixed
amount of pure-Python work is timed on one process and on two at once (:func:`machine_ratio`):
1 where two cores are free, 2 where only one is, the best two workers could do then.
"""

from __future__ import annotations

import statistics
import tempfile
import time
from pathlib import Path

__all__ = ["benchmark_workers", "machine_ratio"]


def _spin(n: int) -> int:
    s = 0
    for i in range(n):
        s += i
    return s


def machine_ratio(n: int = 20_000_000) -> float:
    """Wall time of two processes each counting to ``n`` at once over one process doing it
    alone (both spawned before the clock starts): how much of a second core the machine
    gives now."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    ctx = multiprocessing.get_context("spawn")
    times = []
    for k in (1, 2):
        with ProcessPoolExecutor(max_workers=k, mp_context=ctx) as pool:
            list(pool.map(_spin, [1] * k))  # the processes started
            t0 = time.perf_counter()
            list(pool.map(_spin, [n] * k))
            times.append(time.perf_counter() - t0)
    return times[1] / times[0]


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
        many/one of each pair, ``"ratio"``: their median, ``"machine"``: :func:`machine_ratio`
        before each pair, ``"trials"``, ``"workers"``.
    """
    if pairs < 1:
        raise ValueError(f"pairs = {pairs!r} must be ≥ 1")
    if workers < 2:
        raise ValueError(f"workers = {workers!r} must be ≥ 2 (compared with one)")
    n = spec.trials if trials is None else int(trials)
    one, many, machine = [], [], []
    for k in range(pairs):
        machine.append(machine_ratio())
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
        "machine": machine,
        "trials": n,
        "workers": workers,
    }
