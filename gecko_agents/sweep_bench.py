"""Cheap point functions for sweep tests and demos, and the Dask sweep-throughput benchmark.

* :func:`analytic_point` — a closed-form result row (microseconds per point), the point the
  sweep tests and the ``gecko-agents sweep`` examples use;
* :func:`cpu_bound_point` — a fixed amount of arithmetic per point, for timing workers;
* :func:`benchmark_dask_scaling` — wall time of a sweep of CPU-bound points on a Dask
  LocalCluster of 1, then 2 workers (printed by ``python -m gecko_agents.bench``).

Units are those of :mod:`gecko_agents.params` (µm, µN).
"""

from __future__ import annotations

import importlib
import tempfile
import time
from pathlib import Path

import numpy as np

from .params import SetaArray
from .sweep import import_distributed, run_sweep

__all__ = ["analytic_point", "cpu_bound_point", "benchmark_dask_scaling"]


def analytic_point(params: SetaArray, seed: int) -> dict[str, float]:
    """A cheap closed-form result row (for tests and demos); the seed draws the floor.

    Returns
    -------
    ``pull_off_single_uN`` JKR pull-off of one tip Fc [µN]; ``snap_off_overlap_um`` δc [µm]
    (< 0); ``pull_off_ideal_array_uN`` N·Fc, all setae letting go together [µN];
    ``mean_floor_height_um`` mean of 1000 floor heights drawn with
    ``numpy.random.default_rng(seed)`` and σ = ``params.floor.sigma`` [µm].
    """
    from .floor import seta_heights

    fc = params.contact.pull_off_force
    heights = seta_heights(1000, params.floor.sigma, np.random.default_rng(seed))
    return {
        "pull_off_single_uN": fc,
        "snap_off_overlap_um": params.contact.snap_off_overlap,
        "pull_off_ideal_array_uN": params.array.count * fc,
        "mean_floor_height_um": float(np.mean(heights)),
    }


def cpu_bound_point(
    params: SetaArray, seed: int, *, repeats: int = 300, n_overlaps: int = 10_000
) -> dict[str, float]:
    """A CPU-bound point for benchmarks: ``repeats`` JKR force curves of ``n_overlaps`` overlaps.

    Each repeat evaluates :func:`gecko_agents.jkr.force_from_overlap` on overlaps drawn
    uniformly in [δc, 1 µm] with ``numpy.random.default_rng(seed)`` (≈ 1.5 ms per repeat for
    10⁴ overlaps on one core; arrays that small stay in cache, so the work is arithmetic, not
    memory traffic). Returns the mean force [µN] and the most tensile force [µN].
    """
    from . import jkr

    rng = np.random.default_rng(seed)
    args = params.contact.jkr_args()
    lo = params.contact.snap_off_overlap
    total, lowest = 0.0, np.inf
    for _ in range(int(repeats)):
        force = jkr.force_from_overlap(rng.uniform(lo, 1.0, int(n_overlaps)), *args)
        total += float(force.mean())
        lowest = min(lowest, float(force.min()))
    return {"mean_force_uN": total / max(int(repeats), 1), "min_force_uN": lowest}


def _warm_up() -> None:
    importlib.import_module("gecko_agents.sweep_bench")


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
    ``{"t1_s": wall time with 1 worker [s], "t2_s": with 2 workers [s],
    "speedup": t1_s / t2_s, "repeats": repeats per point}``.
    """
    distributed = import_distributed()
    from .params import PAPER_TABLE1

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
