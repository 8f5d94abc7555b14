"""The search: an Optuna study over a design file's space, screened by
:func:`gecko_agents.design.screen.evaluate`.

Optuna (Akiba et al. 2019, KDD, doi:10.1145/3292500.3330701) is imported only here and only
when a search runs (``pip install 'gecko_agents[design]'``). One objective is searched with
its tree-structured Parzen estimator (TPE; Bergstra et al. 2011, NeurIPS), several with NSGA-II
(Deb et al. 2002, IEEE Trans Evol Comput 6:182); both take the constraints (≤ 0 feasible). The
trials are stored in an SQLite file in the output folder by default, so a killed study resumes
with every finished trial kept (the study in it sampled in memory by one process,
:mod:`gecko_agents.design.local`); a database URL (``--storage``) lets several workers share
one study. Every trial records its design (user attribute ``design``) and, in one more (``record``),
its screened objectives, constraint values, metrics and validity items, its floor seeds, the
design file's digest and the code's version and fingerprint: two writes to the store, since
each write and each re-read of a running trial by another worker costs milliseconds of the
storage's own work.
"""

from __future__ import annotations

import contextlib
import math
import time
from pathlib import Path

import numpy as np

from gecko_agents.design.folder import hold
from gecko_agents.design.screen import evaluate, floor_seed
from gecko_agents.design.space import BACKING_KNOBS, KNOBS

__all__ = [
    "require_optuna",
    "study_name",
    "open_study",
    "run_search",
    "suggest",
    "sampler_seed",
    "make_sampler",
    "violation",
    "record_trial",
    "objective_fn",
    "provenance",
    "feasible",
    "constraint_list",
    "STUDY_DB",
]

STUDY_DB = "study.db"
"""The default trial store's file name in the output folder."""

CAUGHT = (ValueError, ArithmeticError, RuntimeError)
"""What a model raises on a design it refuses or cannot solve (a bad value, an overflow, a
solver that finds no equilibrium or no preload): the trial fails, the study goes on, and the
report counts the failures with their first reason; an engine confirmation that raises one is
a row of the report with its reason."""


def require_optuna():
    """The ``optuna`` module, or ImportError saying how to install it."""
    try:
        import optuna
    except ImportError:
        raise ImportError(
            "the design search needs Optuna: pip install 'gecko_agents[design]' "
            "(or pip install optuna)"
        ) from None
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    return optuna


def study_name(spec) -> str:
    """The study's name in its store: the design file's stem, its digest and its variant, so
    an edited design file starts a new study rather than mixing trials."""
    return f"{spec.path.stem}-{spec.sha256[:12]}{'-quick' if spec.quick else ''}"


def search_bounds(spec, key: str) -> tuple[float, float]:
    """The range a knob is sampled in: the design file's, narrowed by the fabrication bounds
    that concern that knob alone (smallest radius, largest aspect ratio), so no trial is spent
    on a design the process cannot make."""
    lo, hi = spec.ranges[key]
    c = spec.constraints
    if key == "radius_um" and "min_radius_um" in c:
        lo = max(lo, c["min_radius_um"])
    if key == "aspect_ratio" and "max_aspect_ratio" in c:
        hi = min(hi, c["max_aspect_ratio"])
    return lo, hi


def suggest(spec, trial) -> dict:
    """One design drawn by the study's sampler (knobs the design file fixes are not drawn,
    nor a backing's knobs for a rigid backing, which has none)."""
    values = {}
    for cat, names in spec.choices.items():
        values[cat] = names[0] if len(names) == 1 else trial.suggest_categorical(cat, list(names))
    for key in KNOBS:
        if key in BACKING_KNOBS and values.get("backing", "rigid") == "rigid":
            continue
        if key in spec.ranges:
            lo, hi = search_bounds(spec, key)
            values[key] = trial.suggest_float(key, lo, hi, log=KNOBS[key].log)
    return values


def own_constraints(optuna) -> bool:
    """Whether this Optuna stores constraints on the trial (``Trial.set_constraint``, 5.0 on);
    older ones take a ``constraints_func``."""
    return hasattr(optuna.trial.Trial, "set_constraint")


def sampler_seed(spec, worker: int = 0, start: int = 0) -> int:
    """The sampler's seed in worker ``worker`` of a study that held ``start`` finished trials
    when the sampler began: the study's seed in the first worker of a new study (so one
    worker's study is the same every time), a seed drawn from (seed, worker[, start]) in the
    others, which would otherwise draw the first one's designs again (a resumed study its
    first run's: a sampler's random draws, TPE's first ten and NSGA-II's first generation, do
    not depend on the trials it holds)."""
    if worker == 0 and start == 0:
        return spec.seed
    key = [spec.seed, worker] + ([start] if start else [])
    return int(np.random.SeedSequence(key).generate_state(1)[0])


def make_sampler(spec, optuna, worker: int = 0, start: int = 0):
    """The study's sampler (TPE for one objective, NSGA-II for several) in worker ``worker``
    of a study holding ``start`` finished trials (:func:`sampler_seed`).
    TPE treats the designs still being evaluated as no better than the worst so far (its
    constant liar), so workers holding several designs each do not all draw near one point;
    with one worker none is pending when it draws, and the study is the same as without."""
    kw = {} if own_constraints(optuna) else {"constraints_func": _constraints_of}
    seed = sampler_seed(spec, worker, start)
    if len(spec.objectives) == 1:
        return optuna.samplers.TPESampler(seed=seed, n_startup_trials=10, constant_liar=True, **kw)
    return optuna.samplers.NSGAIISampler(seed=seed, population_size=20, **kw)


def _constraints_of(frozen) -> list[float]:
    return constraint_list(frozen)


def local_storage(out: Path) -> str:
    """The URL of the default store: the SQLite file :data:`STUDY_DB` in ``out``."""
    return f"sqlite:///{(Path(out) / STUDY_DB).resolve()}"


def open_study(spec, out: Path, storage: str | None = None, worker: int = 0):
    """The study of ``spec`` in ``storage`` (default: ``out/study.db``), created or, if it
    exists there, loaded with its trials; its sampler that of worker ``worker``
    (:func:`sampler_seed`)."""
    optuna = require_optuna()
    local = storage is None
    if local:
        out.mkdir(parents=True, exist_ok=True)
        storage = local_storage(out)
    study = optuna.create_study(
        study_name=study_name(spec),
        storage=_storage(storage, optuna),
        sampler=make_sampler(spec, optuna, worker),
        directions=spec.directions,
        load_if_exists=True,
    )
    if local:  # one process per local file: a running trial there was cut off by a kill
        running = study.get_trials(deepcopy=False, states=(optuna.trial.TrialState.RUNNING,))
        for t in running:
            study._storage.set_trial_state_values(t._trial_id, optuna.trial.TrialState.FAIL)
    if held := len(study.get_trials(deepcopy=False, states=_finished(optuna))):
        study.sampler = make_sampler(spec, optuna, worker, held)  # a resumed study
    study.set_user_attr("design_sha256", spec.sha256)
    return study


def _finished(optuna) -> tuple:
    return (optuna.trial.TrialState.COMPLETE, optuna.trial.TrialState.FAIL)


def _storage(url: str, optuna):
    """Optuna's database storage at ``url``; an SQLite file in write-ahead-log mode with
    ``synchronous = NORMAL``: a commit survives the process being killed (it may not survive
    the machine losing power), and a trial costs milliseconds instead of an fsync per record."""
    rdb = _created(url, optuna)
    if url.startswith("sqlite"):
        from sqlalchemy import event

        def fast(conn, _record):
            conn.execute("PRAGMA journal_mode=WAL")
            conn.execute("PRAGMA synchronous=NORMAL")

        event.listen(rdb.engine, "connect", fast)
        rdb.engine.dispose()
    return rdb


def _created(url: str, optuna, tries: int = 5):
    """Optuna's ``RDBStorage(url)``. Commands started together on a new store race to create
    its tables and version rows (a ``CREATE TABLE`` or an ``INSERT`` the other committed
    first): the loser tries again, finding them there."""
    from sqlalchemy.exc import IntegrityError, OperationalError

    for k in range(tries - 1):
        try:
            return optuna.storages.RDBStorage(url)
        except (IntegrityError, OperationalError):
            time.sleep(0.2 * (k + 1))
    return optuna.storages.RDBStorage(url)


def provenance() -> dict:
    """The package's version and its code's fingerprint, recorded on every trial."""
    from gecko_agents import __version__
    from gecko_agents.provenance import code_fingerprint

    return {"version": __version__, "fingerprint": code_fingerprint()}


def violation(constraints: list[float]) -> float:
    """One number for the sampler from a design's constraint values (≤ 0 kept): the sum of
    the broken ones' values, or the largest value if none is broken. Optuna's TPE and NSGA-II
    use of a trial's constraints only whether all are ≤ 0 and the sum of the positive ones
    (``_get_infeasible_trial_score``, ``_evaluate_penalty``), which this keeps; one value is
    one write to the store instead of two reads and a write per constraint."""
    broken = sum(c for c in constraints if c > 0)
    return float(broken) if broken > 0 else float(max(constraints))


def record_trial(spec, trial, values: dict, res: dict, code: dict, own: bool) -> list[float]:
    """Store one screened design on its trial (its constraint for the sampler, ``design`` and
    ``record``); the objective values to tell Optuna, in the design file's order."""
    cons = [float(res["constraints"][k]) for k in sorted(res["constraints"])] or [0.0]
    if own:
        trial.set_constraint("violation", violation(cons))
    trial.set_user_attr("design", values)
    seeds = [floor_seed(spec, i) for i in range(spec.test["floor_seeds"])]
    trial.set_user_attr(
        "record",
        {
            "screen": res["objectives"],
            "constraint_values": cons,
            "constraints": res["constraints"],
            "metrics": res["metrics"],
            "validity": res["validity"],
            "floor_seeds": seeds,
            "study_seed": spec.seed,
            "design_sha256": spec.sha256,
            "code_version": code["version"],
            "code_fingerprint": code["fingerprint"],
        },
    )
    return [res["objectives"][o] for o in spec.objectives]


def objective_fn(spec):
    """The function Optuna calls: a design's screened objectives, its constraints and records
    stored on the trial (:func:`record_trial`)."""
    code = provenance()
    own = own_constraints(require_optuna())

    def objective(trial):
        values = suggest(spec, trial)
        try:
            res = evaluate(spec, values)
        except CAUGHT as err:  # a design a model refuses: a failed trial, its reason kept
            trial.set_user_attr("error", f"{type(err).__name__}: {err}")
            raise
        out = record_trial(spec, trial, values, res, code, own)
        return out[0] if len(out) == 1 else out

    return objective


def failed(study) -> list:
    """The study's failed trials (a model refused the design, or a run was cut off)."""
    optuna = require_optuna()
    return study.get_trials(deepcopy=False, states=(optuna.trial.TrialState.FAIL,))


def completed(study) -> list:
    optuna = require_optuna()
    return study.get_trials(deepcopy=False, states=(optuna.trial.TrialState.COMPLETE,))


def run_search(
    spec,
    out: Path,
    *,
    trials: int | None = None,
    storage: str | None = None,
    progress=None,
    worker: int = 0,
):
    """Run the study until it holds ``trials`` (default ``spec.trials``) finished trials,
    counting those an earlier or a parallel worker finished, as worker number ``worker`` of
    those sharing it (0 when alone). Returns the study. A study in ``out``'s local file is
    held by this process meanwhile (:func:`gecko_agents.design.folder.hold`)."""
    optuna = require_optuna()
    target = spec.trials if trials is None else trials
    held = contextlib.nullcontext()
    if storage is None:  # a local file belongs to one process
        Path(out).mkdir(parents=True, exist_ok=True)
        held = hold(out)
    with held:
        study = open_study(spec, out, storage, worker)
        left = target - len(completed(study))
        if left > 0:
            done = (optuna.trial.TrialState.COMPLETE,)
            stop = optuna.study.MaxTrialsCallback(target, states=done)
            callbacks = [stop] + ([progress] if progress else [])
            study.optimize(
                objective_fn(spec),
                n_trials=left,
                callbacks=callbacks,
                catch=CAUGHT,
                gc_after_trial=False,
            )
    return study


def constraint_list(trial) -> list[float]:
    """A finished trial's constraint values, in the order of their keys (≤ 0 kept)."""
    return list(trial.user_attrs.get("record", {}).get("constraint_values", [0.0]))


def feasible(trial) -> bool:
    """Whether a finished trial keeps every constraint."""
    return all(c <= 0 for c in constraint_list(trial))


def ranked(spec, trials: list) -> list:
    """Feasible trials, each design once, best first: by the first objective for one
    objective; the non-dominated ones (the Pareto front) first, each part by the first
    objective, for several."""
    ok, seen = [], set()
    for t in trials:  # a sampler may draw one design again: keep its first trial
        key = tuple(sorted(t.params.items()))
        if feasible(t) and all(math.isfinite(v) for v in t.values) and key not in seen:
            seen.add(key)
            ok.append(t)
    sign = [1.0 if d == "maximize" else -1.0 for d in spec.directions]

    def key(t):
        return tuple(-s * v for s, v in zip(sign, t.values, strict=True))

    if len(spec.objectives) == 1:
        return sorted(ok, key=key)
    front = pareto_front(spec, ok)
    ids = {t.number for t in front}
    return sorted(front, key=key) + sorted([t for t in ok if t.number not in ids], key=key)


def pareto_front(spec, trials: list) -> list:
    """The trials no other trial beats in every objective (and strictly in one)."""
    sign = [1.0 if d == "maximize" else -1.0 for d in spec.directions]
    vals = [[s * v for s, v in zip(sign, t.values, strict=True)] for t in trials]

    def dominated(i):
        a = vals[i]
        return any(
            all(b >= x for b, x in zip(vals[j], a, strict=True)) and vals[j] != a
            for j in range(len(vals))
            if j != i
        )

    return [t for i, t in enumerate(trials) if not dominated(i)]
