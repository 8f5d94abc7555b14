"""Parameter sweeps: the Cartesian product of parameter overrides × seeds, one run per point.

A sweep is ``grid`` (dotted parameter name → list of values, as in
:meth:`~gecko_agents.params.SetaArray.replace`) × ``seeds``; every point is an independent call
``point_fn(params, seed, **fn_kwargs) -> dict[str, float]`` that returns one result row
(e.g. peak pull-off [µN], snap-off depth [µm]). Units are those of :mod:`gecko_agents.params`.
A grid name ``"fn.<name>"`` sweeps a keyword argument of the point function instead of a
parameter (e.g. ``{"fn.preload_uN": [1e5, 1e6]}`` for a protocol quantity).

On disk (``out_dir``)::

    points/<key>.json   one file per finished point, written atomically: overrides, seed, full
                        parameters, result row, status ("ok" or "error" with the message and
                        traceback), elapsed seconds, library versions, and the SHA-256 of
                        all that ("sha256": a file edited by hand is recomputed, not reused)
    sweep.csv           one row per point in :func:`expand_grid` order, rebuilt from the point
                        files after every call of :func:`run_sweep`

A point's ``key`` is a short hash of the point function's dotted name, ``fn_kwargs``, the full
parameter set and the seed, so re-running a sweep skips every point already stored with status
"ok" (an interrupted sweep resumes and loses nothing) and retries the points that failed.

Points run in local processes (:class:`concurrent.futures.ProcessPoolExecutor`, "spawn" start
method on every platform), serially in this process (``n_workers=1``), or on Dask distributed
(``dask="local"`` or ``dask="tcp://host:port"``; ``pip install -e '.[dask]'``). Workers import
``point_fn`` by name, so it must be a top-level function of an importable module; a script
that runs a sweep in local processes needs the usual ``if __name__ == "__main__":`` guard.

This module is the engine's entry, :func:`run_sweep`; its parts are one module per concept:
:mod:`~gecko_agents.sweep.grid` (the points), :mod:`~gecko_agents.sweep.store` (keys, point
files, sweep.csv), :mod:`~gecko_agents.sweep.workers` (one point's record, local processes,
signals) and :mod:`~gecko_agents.sweep.dask_backend` (Dask). Their public names are importable from
here. The point functions sweep files name are in :mod:`gecko_agents.sweep.points`. Code
that calls :func:`run_sweep` directly may pass any importable top-level function; one in a
plain module on ``sys.path`` runs on local worker processes and a Dask LocalCluster (they start
with this process's ``sys.path``), and for a remote scheduler such a file module is sent to
the workers (``Client.upload_file``).

Command line: ``gecko-agents sweep SWEEPFILE.toml`` (or ``python -m gecko_agents sweep …``);
sweep files are described in :mod:`gecko_agents.runfiles.sweep`. This engine imports nothing of the
command line.

Stopping. Local worker processes exit when the sweep's process dies, even by SIGKILL (on Linux
the kernel sends them SIGKILL via ``prctl(PR_SET_PDEATHSIG)``; everywhere a watchdog thread in
each worker polls its parent every :data:`WATCHDOG_PERIOD` s). SIGINT (Ctrl-C) and SIGTERM stop
the sweep: running workers are terminated, finished points stay stored, ``sweep.csv`` is
written, and :class:`SweepInterrupted` (a KeyboardInterrupt) says how to resume.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Sequence
from pathlib import Path

from gecko_agents.params import SetaArray
from gecko_agents.sweep.dask_backend import (
    DaskArgError,
    import_distributed,
    parse_dask_arg,
    run_dask,
)
from gecko_agents.sweep.grid import FN_PREFIX, SweepPoint, canonical_json, expand_grid
from gecko_agents.sweep.store import point_code, point_key, read_record, write_record, write_table
from gecko_agents.sweep.workers import (
    WATCHDOG_PERIOD,
    StopOnSignals,
    SweepInterrupted,
    relay_warnings,
    run_local,
    run_point,
)

__all__ = [
    "SweepPoint",
    "expand_grid",
    "point_key",
    "point_code",
    "run_sweep",
    "parse_dask_arg",
    "DaskArgError",
    "SweepInterrupted",
    "import_distributed",
    "FN_PREFIX",
    "WATCHDOG_PERIOD",
]


def _resolve_point_fn(point_fn) -> tuple[Callable, str]:
    """(callable, "module:qualname"), checking that workers can import it by that name."""
    if isinstance(point_fn, str):
        module, sep, qualname = point_fn.partition(":")
        if not sep or not module or not qualname:
            raise ValueError(f"point_fn {point_fn!r} must be a dotted name 'module:function'")
        try:
            obj = importlib.import_module(module)
            for part in qualname.split("."):
                obj = getattr(obj, part)
        except (ImportError, AttributeError) as err:
            raise ValueError(f"point_fn {point_fn!r} cannot be imported: {err}") from err
        if not callable(obj):
            raise ValueError(f"point_fn {point_fn!r} is not callable")
        return obj, point_fn
    if not callable(point_fn):
        raise TypeError(f"point_fn must be a callable or 'module:function', got {point_fn!r}")
    module = getattr(point_fn, "__module__", None)
    qualname = getattr(point_fn, "__qualname__", "")
    name = f"{module}:{qualname}"
    try:
        found = _resolve_point_fn(name)[0] if module and "<" not in qualname else None
    except ValueError:
        found = None
    if found is not point_fn:
        raise ValueError(
            f"point_fn {point_fn!r} must be a top-level function of an importable "
            f"module (workers import it by name), not a lambda or local function"
        )
    return point_fn, name


def _checked_options(fn_kwargs, dask, n_workers) -> tuple[dict, str | None, int]:
    """(fn_kwargs, dask, n_workers) of :func:`run_sweep`, checked, with the defaults filled
    in; raises before anything runs."""
    fn_kwargs = dict(fn_kwargs or {})
    try:
        canonical_json(fn_kwargs)
    except TypeError as err:
        raise ValueError(
            f"fn_kwargs must be JSON-serialisable (they are part of each point's key): {err}"
        ) from err
    dask = parse_dask_arg(dask)
    if n_workers is not None and (
        isinstance(n_workers, bool) or not isinstance(n_workers, int) or n_workers < 1
    ):
        raise ValueError(f"n_workers = {n_workers!r} must be an integer ≥ 1")
    if dask is not None and dask != "local" and n_workers is not None:
        raise ValueError(
            f"n_workers cannot be set with dask={dask!r}: the scheduler's own "
            f"workers run the points"
        )
    if dask is not None:
        import_distributed()
    return fn_kwargs, dask, n_workers or os.cpu_count() or 1


def _points_to_run(out: Path, points, keys) -> list[tuple[SweepPoint, str]]:
    """The (point, key) pairs not yet stored with status "ok"; says what is reused, what is
    recomputed because its file is damaged, and what belongs to other code or parameters."""
    point_dir = out / "points"
    records = {k: read_record(point_dir / f"{k}.json", k) for k in keys}
    done = {k for k, r in records.items() if (r or {}).get("status") == "ok"}
    todo = [(p, k) for p, k in zip(points, keys, strict=True) if k not in done]
    point_dir.mkdir(parents=True, exist_ok=True)
    stored = {f.stem for f in point_dir.glob("*.json")}
    damaged = sorted(k for k in stored & set(keys) if records[k] is None)
    failed = sum(1 for k in stored & set(keys) if records[k] is not None and k not in done)
    foreign = len(stored - set(keys))
    notes = [
        f"{len(damaged)} damaged point file(s) (unreadable, truncated or edited after they "
        f"were written: {', '.join(f'{k}.json' for k in damaged[:3])}"
        f"{' …' if len(damaged) > 3 else ''}) are recomputed"
        if damaged
        else "",
        f"{failed} point(s) that failed before are retried" if failed else "",
        f"{foreign} stored points from other code or parameters are not used" if foreign else "",
    ]
    if done or any(notes):
        print(
            f"sweep {out}: reusing {len(done)} of {len(points)} points computed by this code"
            + "".join(f"; {n}" for n in notes if n),
            flush=True,
        )
    return todo


def _progress_bar(total: int, done: int, progress: bool):
    from tqdm.auto import tqdm

    return tqdm(total=total, initial=done, disable=not progress, desc="sweep", unit="point")


def _finisher(point_dir: Path, bar) -> Callable[[dict], None]:
    """``finish(record)``: store a finished point and count it (and its errors) on ``bar``."""
    n_errors = 0

    def finish(record: dict) -> None:
        nonlocal n_errors
        relay_warnings(record)
        write_record(point_dir, record)
        n_errors += record["status"] != "ok"
        bar.update(1)
        if n_errors:
            bar.set_postfix(errors=n_errors)

    return finish


def _run_points(todo, dask, n_workers: int, fn, fn_name: str, fn_kwargs: dict, finish) -> None:
    """Run the (point, key) pairs ``todo`` on Dask, serially here (one worker) or on local
    worker processes, calling ``finish(record)`` as each completes."""
    if todo and dask is not None:
        run_dask(dask, n_workers, todo, fn, fn_name, fn_kwargs, finish)
    elif todo and n_workers == 1:
        for point, key in todo:
            finish(run_point(fn, fn_name, fn_kwargs, point, key))
    elif todo:
        run_local(n_workers, todo, fn, fn_name, fn_kwargs, finish)


def run_sweep(
    point_fn,
    base: SetaArray,
    grid: dict[str, Sequence],
    seeds: Sequence[int],
    out_dir,
    *,
    fn_kwargs: dict | None = None,
    dask: str | None = None,
    n_workers: int | None = None,
    progress: bool = True,
) -> list[dict]:
    """Run every point of ``grid`` × ``seeds`` that is not already stored, then write sweep.csv.

    Parameters
    ----------
    point_fn : top-level function ``point_fn(params, seed, **fn_kwargs) -> dict[str, number]``
        or its name ``"module:function"``; workers import it by name.
    base : parameter set the overrides apply to.
    grid : dotted parameter name → list of values (see :func:`expand_grid`).
    seeds : integer seeds ≥ 0, each run on every grid point.
    out_dir : directory for ``points/<key>.json`` and ``sweep.csv`` (created if missing).
    fn_kwargs : extra keyword arguments for every call (JSON-serialisable; part of the key).
    dask : ``None`` for local processes, ``"local"`` for a Dask LocalCluster of ``n_workers``
        single-threaded worker processes on loopback, or ``"tcp://host:port"`` for a running
        scheduler (whose workers must have gecko_agents installed; ``n_workers`` must be None).
    n_workers : number of worker processes, default ``os.cpu_count()``; with ``dask=None``,
        1 runs the points serially in this process.
    progress : show a tqdm progress bar over the points.

    Returns
    -------
    The rows of ``sweep.csv`` as dicts, in :func:`expand_grid` order: ``key``, ``seed``, each
    override, each result field, ``status`` ("ok", "error" or "missing" if the sweep was
    interrupted before the point finished) and ``error`` (None when ok).

    Raises
    ------
    ValueError / TypeError for a bad spec, ImportError if Dask is asked for and not installed:
    all before anything runs or any file is created. :class:`SweepInterrupted` on SIGINT or
    SIGTERM, after stopping the workers and writing ``sweep.csv``: the same call resumes.
    """
    points = expand_grid(base, grid, seeds)
    fn, fn_name = _resolve_point_fn(point_fn)
    fn_kwargs, dask, n_workers = _checked_options(fn_kwargs, dask, n_workers)

    out = Path(out_dir)
    point_dir = out / "points"
    code = point_code(fn)
    keys = [point_key(fn_name, fn_kwargs | p.fn_overrides, p.params, p.seed, code) for p in points]
    todo = _points_to_run(out, points, keys)

    bar = _progress_bar(len(points), len(points) - len(todo), progress)
    finish = _finisher(point_dir, bar)
    stop = StopOnSignals(
        f"sweep stopped; finished points are stored in {point_dir}/ and the same run_sweep "
        "call (or gecko-agents sweep … --resume) resumes it"
    )
    try:
        with stop:
            _run_points(todo, dask, n_workers, fn, fn_name, fn_kwargs, finish)
    finally:
        bar.close()
        rows = write_table(out / "sweep.csv", points, keys, list(grid), point_dir)
    return rows
