"""Where a sweep's points run: one point's record, serially or on local worker processes.

Local workers are spawned processes (:class:`concurrent.futures.ProcessPoolExecutor`, "spawn"
on every platform) that exit when the sweep's process dies, even by SIGKILL: on Linux the
kernel sends them SIGKILL via ``prctl(PR_SET_PDEATHSIG)``; everywhere a watchdog thread in each
worker polls its parent every :data:`WATCHDOG_PERIOD` s. SIGINT and SIGTERM in the sweep's
process raise :class:`SweepInterrupted` (:class:`StopOnSignals`), and the pool's running
workers are terminated. The Dask backend is :mod:`gecko_agents.sweep.dask_backend`.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
import threading
import time
import traceback
import warnings
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures import as_completed as futures_as_completed

from gecko_agents.provenance import versions
from gecko_agents.sweep.grid import SweepPoint, plain

__all__ = [
    "WATCHDOG_PERIOD",
    "SweepInterrupted",
    "StopOnSignals",
    "run_point",
    "failed_record",
    "collect",
    "run_local",
    "map_local",
]

WATCHDOG_PERIOD = 1.0
"""How often [s] a worker checks that the sweep's process is still alive."""
WARNINGS_KEY = "_warnings"
"""The key of a record's relayed warnings (see :func:`relay_warnings`); never stored."""
_PR_SET_PDEATHSIG = 1  # linux/prctl.h


class SweepInterrupted(KeyboardInterrupt):
    """A sweep stopped by SIGINT or SIGTERM; its message says how to resume."""


class StopOnSignals:
    """Within the block, SIGINT and SIGTERM raise :class:`SweepInterrupted` in this (main)
    thread; the previous handlers are restored afterwards. No-op outside the main thread."""

    def __init__(self, message: str):
        self.message = message
        self.saved: dict = {}

    def _raise(self, signum, frame):
        raise SweepInterrupted(f"{signal.Signals(signum).name}: {self.message}")

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                self.saved[sig] = signal.signal(sig, self._raise)
        return self

    def __exit__(self, *exc):
        for sig, handler in self.saved.items():
            signal.signal(sig, handler)
        return False


# One point's record ------------------------------------------------------------------------------
def _new_record(fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    return {
        "key": key,
        "point_fn": fn_name,
        "fn_kwargs": fn_kwargs,
        "overrides": point.overrides,
        "seed": point.seed,
        "params": point.params.to_dict(),
        "status": "ok",
        "result": {},
        "error": None,
        "traceback": None,
    }


def _check_result(result, reserved: set[str]) -> dict:
    if not isinstance(result, dict):
        raise TypeError(
            f"point_fn returned {type(result).__name__}, expected a dict of result name → number"
        )
    row = {}
    for name, value in result.items():
        value = plain(value)
        if not isinstance(name, str):
            raise TypeError(f"point_fn returned a result name {name!r} that is not a string")
        if name in reserved:
            raise ValueError(f"point_fn result name {name!r} clashes with a sweep.csv column")
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise TypeError(f"point_fn returned {name} = {value!r}, not a number")
        row[name] = value
    return row


def run_point(fn: Callable, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    """Run one point (in a worker) and return its record; a raising point_fn gives "error"."""
    t0 = time.perf_counter()
    record = _new_record(fn_name, fn_kwargs, point, key)
    # A worker process has no console of its own: its warnings travel with the record and
    # are raised again in the sweep's process (relay_warnings), where the caller's filters
    # and gecko_agents.console collect them like those of an in-process run.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fn(point.params, point.seed, **(fn_kwargs | point.fn_overrides))
            record["result"] = _check_result(
                result, {"key", "seed", "status", "error", *point.overrides}
            )
        except Exception as err:
            record.update(
                status="error",
                error=f"{type(err).__name__}: {err}",
                traceback=traceback.format_exc(),
            )
    record[WARNINGS_KEY] = [(w.category, str(w.message)) for w in caught]
    record["elapsed_s"] = time.perf_counter() - t0
    record["versions"] = versions()
    return record


def relay_warnings(record: dict) -> None:
    """Raise again, in this process, the warnings a point's run raised (and drop them from
    ``record``, which is stored without them)."""
    for category, message in record.pop(WARNINGS_KEY, ()):
        warnings.warn(message, category, stacklevel=2)


def failed_record(
    fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str, err: BaseException
) -> dict:
    """Record for a point whose worker died or whose task could not be sent."""
    record = _new_record(fn_name, fn_kwargs, point, key)
    record.update(
        status="error",
        error=f"{type(err).__name__}: {err}",
        traceback="".join(traceback.format_exception(err)),
        elapsed_s=None,
        versions=versions(),
    )
    return record


def collect(fut, fn_name: str, fn_kwargs: dict, point: SweepPoint, key: str) -> dict:
    """The record of a finished future, or an error record if its worker failed."""
    try:
        return fut.result()
    except Exception as err:  # a dead worker or a task that could not be pickled
        return failed_record(fn_name, fn_kwargs, point, key, err)


# Local worker processes --------------------------------------------------------------------------
def _worker_init(parent_pid: int) -> None:
    """Make a worker process exit when the sweep's process (``parent_pid``) dies.

    On Linux, ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` has the kernel kill the worker when its
    parent dies; a daemon thread polling ``os.getppid()`` covers other platforms (and the
    moment before the prctl call). Workers ignore SIGINT: a Ctrl-C in a terminal reaches the
    whole process group, and the sweep's process decides how to stop them.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # The sweep's processes already share the cores: a model's loop threads would only
    # compete with the other workers (gecko_agents.model.step_loop.PARALLEL_MIN_SETAE).
    try:
        import numba

        numba.set_num_threads(1)
    except ImportError:
        pass
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent_pid:  # the parent died before the prctl call
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(WATCHDOG_PERIOD)
            if os.getppid() != parent_pid:
                os._exit(1)

    threading.Thread(target=watch, name="sweep-parent-watchdog", daemon=True).start()


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's worker processes (running points are abandoned, not recorded)."""
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        if proc.is_alive():
            proc.terminate()
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        proc.join(timeout=5)
        if proc.is_alive():
            proc.kill()


def _local_pool(n_workers: int) -> ProcessPoolExecutor:
    """``n_workers`` spawned worker processes that die with this one (:func:`_worker_init`)."""
    return ProcessPoolExecutor(
        max_workers=n_workers,
        mp_context=multiprocessing.get_context("spawn"),
        initializer=_worker_init,
        initargs=(os.getpid(),),
    )


def run_local(n_workers: int, todo, fn, fn_name, fn_kwargs, finish) -> None:
    """Run the points ``todo`` (pairs of point and key) on a pool of spawned worker processes
    that die with this process; ``finish(record)`` is called as each point completes."""
    pool = _local_pool(min(n_workers, len(todo)))
    try:
        futures = {pool.submit(run_point, fn, fn_name, fn_kwargs, p, k): (p, k) for p, k in todo}
        for fut in futures_as_completed(futures):
            finish(collect(fut, fn_name, fn_kwargs, *futures[fut]))
    except BaseException:
        _stop_workers(pool)  # do not wait for the running points
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


# Any function over a list of tasks ---------------------------------------------------------------
def _call(fn: Callable, args: tuple):
    """``fn(*args)`` in a worker, with the warnings it raised (relayed as :func:`run_point`'s)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = fn(*args)
    return out, [(w.category, str(w.message)) for w in caught]


def map_local(fn: Callable, tasks: list[tuple], n_workers: int, done=None) -> list:
    """``[fn(*args) for args in tasks]``, on ``n_workers`` spawned processes that die with this
    one (1: in this process, in order). ``fn`` must be importable by name (a module-level
    function) and its arguments and results picklable. Results come in the tasks' order;
    ``done()`` is called as each task completes (a progress bar's update). A worker's warnings
    are raised again here as its task completes; a task's exception is raised here and the
    running tasks are abandoned. For the many independent runs of a study; a sweep over
    parameters and seeds with a store to resume from is :func:`gecko_agents.sweep.run_sweep`."""
    if n_workers < 1:
        raise ValueError(f"n_workers = {n_workers} must be ≥ 1")
    if n_workers == 1 or len(tasks) <= 1:
        out = []
        for args in tasks:
            out.append(fn(*args))
            if done is not None:
                done()
        return out
    pool = _local_pool(min(n_workers, len(tasks)))
    results: list = [None] * len(tasks)
    try:
        futures = {pool.submit(_call, fn, args): i for i, args in enumerate(tasks)}
        for fut in futures_as_completed(futures):
            results[futures[fut]], caught = fut.result()
            for category, message in caught:
                warnings.warn(message, category, stacklevel=2)
            if done is not None:
                done()
    except BaseException:
        _stop_workers(pool)  # do not wait for the running tasks
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    return results
