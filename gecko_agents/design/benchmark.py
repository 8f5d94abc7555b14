"""The design search's worker benchmark: one design file's screen with one worker, then with
two sharing one store, in the same run (``gecko-agents design FILE --benchmark``).

Each timed screen is what a user waits for: a new SQLite store in a temporary folder, the
workers started and run until the store holds the trials
(:func:`gecko_agents.design.local.run_local`). Its designs are drawn by Optuna's random
sampler with the study's seed, so both screens evaluate the same designs (a JKR sphere costs
a hundred flat punches; a study's own sampler, steered by the results, draws a different mix
with two workers). The pairs alternate their order (1 then 2
workers, then 2 then 1, …) so that a machine whose load drifts during the run hits both alike;
the ratio of each pair is reported, not only their median, since the other jobs of a shared
machine set how much of a second core a second worker gets. Before each pair the same fixed
amount of pure-Python work is timed on one process and on two at once (:func:`machine_ratio`):
1 where two cores are free, 2 where only one is, the best two workers could do then; and the
CPU time of all the processes is taken beside the wall time: shared over the workers, it is
the wall time they would take with a core each.
"""

from __future__ import annotations

import resource
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


def _cpu() -> tuple[float, float]:
    """CPU time [s] (user + system) of this process and of its finished children."""
    me, kids = (resource.getrusage(w) for w in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return me.ru_utime + me.ru_stime, kids.ru_utime + kids.ru_stime


def _screen_time(spec, trials: int, workers: int) -> tuple[float, float]:
    """(wall time [s], CPU time of all its processes [s]) of one screen of ``trials`` trials
    on ``workers`` workers into a new store, the designs drawn by Optuna's random sampler with
    the study's seed: the same designs, whatever the order results come back in."""
    from gecko_agents.design import local, search

    optuna = search.require_optuna()
    with tempfile.TemporaryDirectory(prefix="gecko_design_bench_") as tmp:
        me0, kids0 = _cpu()
        t0 = time.perf_counter()
        sampler = optuna.samplers.RandomSampler(seed=spec.seed)
        local.run_local(spec, Path(tmp), trials, workers, sampler=sampler)
        wall = time.perf_counter() - t0
        me1, kids1 = _cpu()
    return wall, (me1 - me0) + (kids1 - kids0)


def benchmark_workers(spec, trials: int | None = None, pairs: int = 1, workers: int = 2) -> dict:
    """Wall time of a design file's screen of ``trials`` trials (default the file's) on one
    worker and on ``workers`` workers, ``pairs`` times in alternating order.

    Returns
    -------
    dict
        ``"one_s"``, ``"many_s"``: the wall times [s] of each pair (lists), ``"ratios"``:
        many/one of each pair, ``"ratio"``: their median, ``"machine"``: :func:`machine_ratio`
        before each pair, ``"cpu_ratios"``: the CPU time of all processes with many workers,
        shared over them, over the one worker's, each pair (the wall-time ratio where every
        worker has a core of its own and the designs split evenly: what the work costs, which
        a busy machine changes little), ``"trials"``, ``"workers"``.
    """
    if pairs < 1:
        raise ValueError(f"pairs = {pairs!r} must be ≥ 1")
    if workers < 2:
        raise ValueError(f"workers = {workers!r} must be ≥ 2 (compared with one)")
    n = spec.trials if trials is None else int(trials)
    one, many, machine, cpu = [], [], [], {1: [], workers: []}
    for k in range(pairs):
        machine.append(machine_ratio())
        order = (1, workers) if k % 2 == 0 else (workers, 1)
        for w in order:
            wall, total = _screen_time(spec, n, w)
            (one if w == 1 else many).append(wall)
            cpu[w].append(total)
    ratios = [m / o for m, o in zip(many, one, strict=True)]
    cpu_ratios = [m / workers / o for m, o in zip(cpu[workers], cpu[1], strict=True)]
    return {
        "one_s": one,
        "many_s": many,
        "ratios": ratios,
        "ratio": statistics.median(ratios),
        "machine": machine,
        "cpu_ratios": cpu_ratios,
        "trials": n,
        "workers": workers,
    }
