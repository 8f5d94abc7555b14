"""The Dask sweep-throughput benchmark: one sweep of CPU-bound points on 1, then 2 workers.

Printed by ``python -m gecko_agents.bench``; the points are
:func:`gecko_agents.sweep.points.cpu_bound_point`.
"""

from __future__ import annotations

import importlib
import tempfile
import time
from pathlib import Path

from gecko_agents.params import SetaArray
from gecko_agents.sweep import import_distributed, run_sweep
from gecko_agents.sweep.points import cpu_bound_point

__all__ = ["benchmark_dask_scaling"]


def _warm_up() -> None:
    importlib.import_module("gecko_agents.sweep.points")  # workers import the package first


def benchmark_dask_scaling(
    n_points: int = 8, work_s: float = 0.5, base: SetaArray | None = None
) -> dict[str, float]:
    """Wall time of one sweep of CPU-bound points on a Dask LocalCluster of 1, then 2 workers.

    The amount of work is fixed, not timed: one repeat of :func:`cpu_bound_point` is timed here
    and ``repeats`` chosen so that a point takes about ``work_s`` [s] on an idle core. Each
    cluster is started and its workers have imported gecko_agents before the clock starts; the
    sweep writes into a temporary directory that is removed afterwards.

    Returns
    -------
    dict
        ``"t1_s"``: wall time with 1 worker [s], ``"t2_s"``: with 2 workers [s],
        ``"speedup"``: t1_s / t2_s, ``"repeats"``: repeats per point.
    """
    distributed = import_distributed()
    from gecko_agents.params import PAPER_TABLE1

    base = PAPER_TABLE1 if base is None else base
    cpu_bound_point(base, 0, repeats=3)  # warm up (first calls are slower)
    t0 = time.perf_counter()
    cpu_bound_point(base, 0, repeats=30)
    repeats = max(1, round(work_s / ((time.perf_counter() - t0) / 30)))
    seeds = list(range(n_points))
    times = {}
    with tempfile.TemporaryDirectory(prefix="gecko_sweep_bench_") as tmp:
        for n in (1, 2):
            with (
                distributed.LocalCluster(
                    n_workers=n,
                    threads_per_worker=1,
                    processes=True,
                    host="127.0.0.1",
                    dashboard_address=None,
                ) as cluster,
                distributed.Client(cluster) as client,
            ):
                client.run(_warm_up)
                t0 = time.perf_counter()
                run_sweep(
                    cpu_bound_point,
                    base,
                    {},
                    seeds,
                    Path(tmp) / f"workers_{n}",
                    fn_kwargs={"repeats": repeats},
                    dask=cluster.scheduler_address,
                    progress=False,
                )
                times[n] = time.perf_counter() - t0
    return {"t1_s": times[1], "t2_s": times[2], "speedup": times[1] / times[2], "repeats": repeats}
