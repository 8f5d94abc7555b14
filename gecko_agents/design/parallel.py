"""Several workers on one design study: local worker processes or the package's Dask backend.

A study in a local SQLite file is run by one process, its evaluations spread over local worker
processes (:mod:`gecko_agents.design.local`). Workers of a database URL or of Dask share the study
through its store (Optuna's database storage): each runs
:func:`gecko_agents.design.search.run_search` until the store holds the study's trials, so
any number of them, started anywhere the store is reachable, fill one study; worker k > 0
draws with its own sampler seed (:func:`~gecko_agents.design.search.sampler_seed`).
``dask="local"`` starts a Dask LocalCluster and ``dask="tcp://host:port"`` uses a running
scheduler whose workers have gecko_agents (and the design extra) installed and reach the store
(a database URL; an SQLite file only on one machine's disk). The engine's confirmations,
independent runs, are mapped over the same workers.
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

__all__ = ["search_worker", "parallel_map"]


def search_worker(spec, out: str, trials: int | None, storage: str | None, worker: int = 0) -> int:
    """Worker number ``worker`` of a shared study: screen until the store holds the study's
    trials; the number of finished trials it then sees."""
    import warnings

    import gecko_agents.design.search as search

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", category=UserWarning)  # Optuna's experimental notes
        study = search.run_search(spec, Path(out), trials=trials, storage=storage, worker=worker)
    return len(search.completed(study))


def parallel_map(fn, args: list[tuple], workers: int, dask: str | None = None) -> list:
    """``[fn(*a) for a in args]`` on ``workers`` spawned processes or on Dask (``"local"`` or
    a scheduler's ``"tcp://host:port"``), in the order of ``args``."""
    if dask is not None:
        return _dask_map(fn, args, workers, dask)
    if workers <= 1 or len(args) <= 1:
        return [fn(*a) for a in args]
    ctx = multiprocessing.get_context("spawn")  # no forked database connection or thread
    with ProcessPoolExecutor(max_workers=min(workers, len(args)), mp_context=ctx) as pool:
        futures = [pool.submit(fn, *a) for a in args]
        return [f.result() for f in futures]


def _dask_map(fn, args: list[tuple], workers: int, address: str) -> list:
    from gecko_agents.sweep.dask_backend import import_distributed

    distributed = import_distributed()
    cluster = None
    if address == "local":
        cluster = distributed.LocalCluster(
            n_workers=max(1, min(workers, len(args))),
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        )
    try:
        with distributed.Client(cluster or address) as client:
            futures = [client.submit(fn, *a, pure=False) for a in args]
            return client.gather(futures)
    finally:
        if cluster is not None:
            cluster.close()
