"""A study in a local SQLite file: sampled in memory by one process, every finished trial
written to the file as it finishes, the evaluations on this process or on local workers.

Optuna's database storage (SQLAlchemy over SQLite) costs some 20–50 ms of one core per trial
on the project's machine: a trial's draws, attributes and result are a score of transactions,
and every draw reads the running trials back (the more workers, the more of them). That is as
much as the screen's own evaluation of a design, so workers sharing the file through it gain
little. Here the sampler's study lives in memory (Optuna's ``InMemoryStorage``, the same
sampler and seed, so the same study as the database's), the file receives each finished
trial whole (``Study.add_trial``: one transaction) and holds only finished trials, so a kill
loses only the designs being evaluated; a resumed study first loads the file's trials into
memory. With ``workers`` > 1, ``workers − 1`` spawned processes evaluate designs while this
one keeps them busy (Optuna's ask-and-tell), drawing, storing and telling as results come back,
and evaluates a design itself whenever they are busy: it works while they start, and no core
waits on it.

A local file belongs to one process (:func:`gecko_agents.design.folder.hold`); a study
shared by several processes or machines goes through a database URL and
:func:`gecko_agents.design.search.run_search`.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
from pathlib import Path

import gecko_agents.design.search as search
from gecko_agents.design.folder import hold

__all__ = ["run_local", "memory_study", "QUEUED"]

QUEUED = 8
"""Designs kept in hand for each spawned worker. A JKR sphere takes a hundred times a flat
punch, so a worker needs several designs in hand to stay busy while this process evaluates one
sphere of its own and stores what came back; designs no worker has begun when the draws run
out are taken back and evaluated here, so a deep queue leaves no core idle at
the end."""


def memory_study(spec, store, sampler=None):
    """An in-memory study with the sampler of ``spec`` (or ``sampler``) holding the finished
    trials of ``store`` (complete and failed), in their order; a study resumed draws with a
    seed of its own (:func:`~gecko_agents.design.search.sampler_seed`)."""
    optuna = search.require_optuna()
    done = (optuna.trial.TrialState.COMPLETE, optuna.trial.TrialState.FAIL)
    held = store.get_trials(deepcopy=False, states=done)
    mem = optuna.create_study(
        sampler=sampler or search.make_sampler(spec, optuna, start=len(held)),
        directions=spec.directions,
        study_name="memory",
    )
    mem.add_trials(held)
    return mem


def run_local(spec, out: Path, trials: int | None = None, workers: int = 1, sampler=None):
    """Run the study of ``spec`` in ``out/study.db`` until it holds ``trials`` (default
    ``spec.trials``) finished trials, evaluating on this process (``workers`` = 1) or on it
    and ``workers − 1`` spawned processes; ``sampler``, an Optuna sampler in place of the
    design file's (the worker benchmark's). Returns the stored study. This process holds
    ``out`` meanwhile (:func:`gecko_agents.design.folder.hold`): a second process is refused."""
    Path(out).mkdir(parents=True, exist_ok=True)
    with hold(out):
        store = search.open_study(spec, out)
        left = (spec.trials if trials is None else trials) - len(search.completed(store))
        if left > 0:
            _fill(spec, store, left, workers, sampler)
    return store


def _fill(spec, store, n: int, workers: int, sampler) -> None:
    """``n`` more trials of the study ``store``, drawn in memory, each stored as it finishes."""
    optuna = search.require_optuna()
    mem = memory_study(spec, store, sampler)

    def keep(study, frozen):
        store.add_trial(frozen)

    if workers <= 1:
        mem.optimize(
            search.objective_fn(spec),
            n_trials=n,
            callbacks=[keep],
            catch=search.CAUGHT,
            gc_after_trial=False,
        )
    else:
        _batched(spec, mem, store, n, workers, optuna)


def _batched(spec, mem, store, n: int, workers: int, optuna) -> None:
    """``n`` trials of ``mem`` on this process and ``workers − 1`` spawned ones, each stored
    in ``store`` as it finishes: the spawned ones kept busy (:data:`QUEUED` designs each), this
    one evaluating a design whenever they are (so it works while they start, and no core waits
    on it)."""
    code, own = search.provenance(), search.own_constraints(optuna)
    ctx = multiprocessing.get_context("spawn")  # no forked database connection or thread

    def draw():
        trial = mem.ask()
        return trial, search.suggest(spec, trial)

    def finish(trial, values, result) -> None:
        if isinstance(result, search.CAUGHT):  # a design a model refuses: a failed trial
            trial.set_user_attr("error", f"{type(result).__name__}: {result}")
            frozen = mem.tell(trial, state=optuna.trial.TrialState.FAIL)
        else:
            frozen = mem.tell(trial, search.record_trial(spec, trial, values, result, code, own))
        store.add_trial(frozen)

    running: dict = {}
    with cf.ProcessPoolExecutor(max_workers=workers - 1, mp_context=ctx) as pool:
        while n > 0 or running:
            while n > 0 and len(running) < QUEUED * (workers - 1):
                trial, values = draw()
                running[pool.submit(_evaluate, spec, values)] = (trial, values)
                n -= 1
            if n > 0:
                trial, values = draw()
                n -= 1
                finish(trial, values, _evaluate(spec, values))
                done = [f for f in running if f.done()]
            elif stolen := _steal(running):
                trial, values = running.pop(stolen)
                finish(trial, values, _evaluate(spec, values))
                done = [f for f in running if f.done()]
            else:
                done = cf.wait(running, return_when=cf.FIRST_COMPLETED).done
            for f in done:
                trial, values = running.pop(f)
                finish(trial, values, f.result())


def _steal(running: dict):
    """A design handed to the workers that none has begun (cancelled there, so this process
    evaluates it), the last handed first; None if each has begun."""
    for f in reversed(list(running)):
        if f.cancel():
            return f
    return None


def _evaluate(spec, values):
    """The screen of one design, or the error a model refused it with (returned, so a worker
    process hands it back like a result)."""
    try:
        return search.evaluate(spec, values)
    except search.CAUGHT as err:
        return err
