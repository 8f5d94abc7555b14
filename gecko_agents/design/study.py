"""A design search from end to end: screen with Optuna, confirm the best designs with the
engine, write the tables, figures, run files and report (:mod:`gecko_agents.design`)."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import gecko_agents.design.confirm as confirm
import gecko_agents.design.folder as folder
import gecko_agents.design.local as local
import gecko_agents.design.parallel as parallel
import gecko_agents.design.report as report
import gecko_agents.design.search as search
import gecko_agents.design.showcase as showcase
from gecko_agents.design.folder import OUTPUT_FILES, check_output

__all__ = ["run_design", "search_study", "screen_flags", "check_output", "OUTPUT_FILES"]


def screen_flags(trials: list) -> dict:
    """Screen validity items not met: name → (trials that broke it, its meaning)."""
    out: dict = {}
    for t in trials:
        for item in t.user_attrs.get("record", {}).get("validity", []):
            if item["ok"] is False:
                n, _ = out.get(item["name"], (0, ""))
                out[item["name"]] = (n + 1, item["meaning"])
    return out


def _confirm(spec, chosen, out: Path, say, workers: int, dask) -> tuple[dict, list[dict]]:
    """The engine's confirmation of the trials ``chosen`` and a run file for each: (trial
    number → the engine's values, the report's rows). A confirmation that failed is a row
    with its reason (``engine["error"]``)."""
    from gecko_agents.output_paths import atomic_write_bytes

    designs = [t.user_attrs["design"] for t in chosen]
    engine = parallel.parallel_map(
        confirm.confirm_design, [(spec, d) for d in designs], workers, dask
    )
    confirmed, rows = {}, []
    (out / "runs").mkdir(parents=True, exist_ok=True)
    for j, (t, design, eng) in enumerate(zip(chosen, designs, engine, strict=True), 1):
        label = f"design_{j}"
        confirmed[t.number] = eng
        screened = t.user_attrs["record"]["screen"]
        ref = screened["pull_off_per_area"]
        if "error" in eng:
            ratio = math.nan
        else:
            ratio = ref / eng["mean"] if eng["mean"] > 0 else math.inf
        rows.append(
            {
                "label": label,
                "trial": t.number,
                "design": design,
                "screen": screened,
                "engine": eng,
                "ratio": ratio,
            }
        )
        text = confirm.run_file_text(spec, design, label)
        atomic_write_bytes(out / "runs" / f"{label}.toml", text.encode())
        engine_said = (
            f"engine failed: {eng['error']}" if "error" in eng else f"engine {eng['mean']:.4g} kPa"
        )
        say(
            f"{label} (trial {t.number}): screen {ref:.4g} kPa, {engine_said} "
            f"({eng['wall_s']:.1f} s)"
        )
    return confirmed, rows


def _versions() -> dict:
    """The package's and its libraries' versions, Optuna's and the code's fingerprint."""
    from importlib.metadata import version

    from gecko_agents.provenance import code_fingerprint, versions

    return {**versions(), "optuna": version("optuna"), "code_fingerprint": code_fingerprint()}


def search_study(spec, out: Path, trials, storage, workers: int, dask, worker: int = 0):
    """The study filled to its trials: in the output folder's SQLite file by this process,
    its designs evaluated here or on ``workers`` local processes
    (:func:`~gecko_agents.design.local.run_local`); at a database URL or on Dask by as many
    workers sharing the store (:func:`~gecko_agents.design.parallel.search_worker`); this
    process, alone on a database URL, is worker number ``worker`` of those sharing it
    (:func:`~gecko_agents.design.search.sampler_seed`)."""
    if storage is None and dask is None:
        return local.run_local(spec, out, trials, workers)
    if workers <= 1 and dask is None:
        return search.run_search(spec, out, trials=trials, storage=storage, worker=worker)
    search.open_study(spec, out, storage)
    url = storage or search.local_storage(out)
    args = [(spec, str(out), trials, url, k) for k in range(workers)]
    parallel.parallel_map(parallel.search_worker, args, workers, dask)
    return search.open_study(spec, out, url)


def run_design(
    spec,
    out,
    *,
    trials: int | None = None,
    storage: str | None = None,
    workers: int = 1,
    dask: str | None = None,
    worker: int = 0,
    say=print,
) -> dict:
    """Run a checked design file's search into ``out``: the study (resumed if ``out`` or
    ``storage`` already holds it; ``workers`` local processes, or as many Dask workers at
    ``dask``, share it and the confirmations; ``worker``: this process's number among those
    sharing a ``storage`` URL by hand), the engine's confirmation of the
    ``spec.confirm`` best designs (the Pareto front first), and ``trials.csv``,
    ``best.json``, ``pareto_front.png``, ``objectives_vs_parameters.png``, ``showcase.png``
    (:mod:`~gecko_agents.design.showcase`), ``runs/*.toml``
    and ``report.md``. Returns the summary written to ``best.json``.

    ``out`` must be new, empty or this study's design folder, and no other command's at the
    time; ``storage`` a database URL Optuna can store trials at
    (:mod:`~gecko_agents.design.folder`). Raises
    :class:`~gecko_agents.design.folder.DesignFolderError` (nothing written) otherwise."""
    out = Path(out)
    name = search.study_name(spec)
    if storage is not None:
        folder.check_storage(storage)
    check_output(out, name, storage)
    out.mkdir(parents=True, exist_ok=True)
    with folder.hold(out):
        check_output(out, name, storage)  # again, held: another command may have written it since
        folder.write_record(out, spec, name, storage)
        if trials is not None:
            held = len(search.completed(search.open_study(spec, out, storage)))
            if held > trials:
                say(
                    f"trials = {trials} asked, but the study already holds {held} finished "
                    f"trials: none run, the report covers all {held}"
                )
        return _search_and_report(spec, out, trials, storage, workers, dask, worker, say)


def _search_and_report(spec, out: Path, trials, storage, workers, dask, worker, say) -> dict:
    """:func:`run_design`'s work in a folder it holds."""
    t0 = time.perf_counter()
    study = search_study(spec, out, trials, storage, workers, dask, worker)
    done = search.completed(study)
    t_screen = time.perf_counter() - t0
    say(f"{len(done)} screening trials in the study ({t_screen:.1f} s)")
    ranked = search.ranked(spec, done)
    front = search.pareto_front(spec, ranked) if len(spec.objectives) > 1 else ranked[:1]
    confirmed, rows = _confirm(spec, ranked[: spec.confirm], out, say, workers, dask)
    on_front = {t.number for t in front}
    for r in rows:
        r["front"] = r["trial"] in on_front
    ran = {n: e for n, e in confirmed.items() if "error" not in e}  # what the figures show
    imp = report.importances(study, spec)
    report.write_csv(out / "trials.csv", report.trial_rows(spec, done, confirmed))
    report.draw_front(spec, done, front, ran, out)
    report.draw_parameters(spec, done, out)
    showcase.draw_showcase(spec, done, front, [r for r in rows if r["trial"] in ran], out)
    flags = screen_flags(done)
    fails = [t.user_attrs.get("error", "cut off") for t in search.failed(study)]
    if fails:
        flags["failed_trials"] = (len(fails), f"the first: {fails[0]}")
    text = report.report_text(spec, rows, imp, len(done), flags)
    from gecko_agents.output_paths import atomic_write_bytes

    atomic_write_bytes(out / "report.md", text.encode())
    summary = {
        "design_file": str(spec.path),
        "sha256": spec.sha256,
        "quick": spec.quick,
        "study": search.study_name(spec),
        "trials": len(done),
        "failed_trials": len(fails),
        "screen_s": t_screen,
        "wall_s": time.perf_counter() - t0,
        "best": rows,
        "importances": imp,
        "pareto_front": [t.number for t in front],
        "workers": workers,
        "dask": dask,
        "versions": _versions(),
    }
    atomic_write_bytes(out / "best.json", json.dumps(summary, indent=1, default=str).encode())
    return summary
