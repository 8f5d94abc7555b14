"""The ``design`` subcommand: a design file to a searched, confirmed and reported set of fibre
array designs (:mod:`gecko_agents.design`)."""

from __future__ import annotations

import argparse
import shlex
import time
import warnings
from pathlib import Path

from gecko_agents.cli.common import (
    EXIT_FAILURE,
    EXIT_INTERRUPTED,
    EXIT_OK,
    PROG,
    UsageError,
    checked,
    error,
)
from gecko_agents.output_paths import output_dir_arg

__all__ = ["add_design", "cmd_design"]


def add_design(p: argparse.ArgumentParser) -> None:
    from gecko_agents.sweep import parse_dask_arg

    p.add_argument("designfile", type=Path, help="design file (TOML; see examples/)")
    p.add_argument(
        "--out",
        type=output_dir_arg,
        default=None,
        help="output folder (default designs/<design file name>, with _quick for --quick): new, "
        "empty or this study's own, whose study is then resumed",
    )
    p.add_argument(
        "--trials", type=int, default=None, help="screening trials (default: the file's)"
    )
    p.add_argument(
        "--storage",
        default=None,
        metavar="URL",
        help="Optuna database URL shared by several workers (default: an SQLite file "
        "study.db in the output folder)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=1,
        help="processes evaluating the designs (this one and N - 1 spawned) and the "
        "confirmations (default 1)",
    )
    p.add_argument(
        "--dask",
        type=parse_dask_arg,
        default=None,
        metavar="ADDR",
        help="'local' (a Dask cluster of --workers processes) or tcp://host:port (a running "
        "scheduler; its workers need the design extra and a --storage URL they reach)",
    )
    p.add_argument(
        "--worker",
        type=int,
        default=0,
        metavar="K",
        help="this command's number among commands sharing a --storage study by hand: each "
        "draws designs with its own seed (0, the default, with the study's)",
    )
    p.add_argument("--quick", action="store_true", help="the file's [quick] variant")
    p.add_argument(
        "--benchmark",
        action="store_true",
        help="time the screen on one worker and on --workers (default 2) sharing one SQLite "
        "store, in temporary folders, and print the ratio; nothing is written",
    )


def cmd_design(args, extra) -> int:
    from gecko_agents.design import folder, load_design
    from gecko_agents.design.search import require_optuna, study_name

    spec = load_design(args.designfile, quick=args.quick)
    if args.trials is not None and args.trials < 1:
        raise UsageError(f"--trials {args.trials} must be ≥ 1")
    if args.workers < 1:
        raise UsageError(f"--workers {args.workers} must be ≥ 1")
    if args.worker < 0 or (args.worker and not args.storage):
        raise UsageError(f"--worker {args.worker} must be ≥ 0, and > 0 only with --storage")
    try:
        require_optuna()
    except ImportError as err:
        raise UsageError(str(err)) from None
    if args.benchmark:
        return _benchmark(spec, args)
    stem = spec.path.stem + ("_quick" if spec.quick else "")
    out = args.out if args.out is not None else checked(Path("designs") / stem)
    try:
        if args.storage is not None:
            folder.check_storage(args.storage)
        folder.check_output(out, study_name(spec), args.storage)
    except folder.DesignFolderError as err:
        raise UsageError(str(err)) from None
    again = _design_command(args, out)
    print(
        f"{spec.path}{' (quick)' if spec.quick else ''}: {', '.join(spec.objectives)} over "
        f"{', '.join([*spec.ranges, *[c for c, v in spec.choices.items() if len(v) > 1]])} "
        f"→ {out}/"
    )
    t0 = time.perf_counter()
    try:
        summary = _run(spec, out, args)
    except KeyboardInterrupt:
        error("interrupted: every finished trial is stored; resume with: " + again)
        return EXIT_INTERRUPTED
    except Exception as err:
        full = folder.storage_full(err)
        if full is None or isinstance(err, UsageError):
            raise
        where = args.storage or str(out / "study.db")
        error(
            f"{where}: the disk is full ({full}); every finished trial is stored: free some "
            "space and resume with: " + again
        )
        return EXIT_FAILURE
    _said(summary, out, time.perf_counter() - t0)
    return EXIT_OK


def _design_command(args, out: Path) -> str:
    """The ``design`` command line of ``args`` into ``out``, every option given, quoted for a
    shell."""
    words = [PROG, "design", str(args.designfile)] + (["--quick"] if args.quick else [])
    words += ["--out", str(out)] + (["--storage", args.storage] if args.storage else [])
    words += ["--trials", str(args.trials)] if args.trials is not None else []
    words += ["--workers", str(args.workers)] if args.workers != 1 else []
    words += ["--dask", args.dask] if args.dask else []
    words += ["--worker", str(args.worker)] if args.worker else []
    return shlex.join(words)


def _run(spec, out: Path, args) -> dict:
    """:func:`~gecko_agents.design.run_design` with the command's options; a folder or store
    it refuses is a usage error."""
    from gecko_agents.design import folder, run_design

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", category=UserWarning)  # Optuna's experimental notes
            return run_design(
                spec,
                out,
                trials=args.trials,
                storage=args.storage,
                workers=args.workers,
                dask=args.dask,
                worker=args.worker,
            )
    except folder.DesignFolderError as err:
        raise UsageError(str(err)) from None
    except ImportError as err:  # --dask without the dask extra
        raise UsageError(str(err)) from None


def _said(summary: dict, out: Path, wall: float) -> None:
    """The command's last lines: what it wrote and the best design."""
    best = summary["best"]
    failed = [b for b in best if "error" in b["engine"]]
    print(
        f"wrote {out}/report.md in {wall:.1f} s: {summary['trials']} trials"
        + (f" ({summary['failed_trials']} failed)" if summary["failed_trials"] else "")
        + f", {len(best)} designs confirmed"
        + (f" ({len(failed)} failed in the engine)" if failed else "")
    )
    if best:
        from gecko_agents.design.space import in_use

        b = best[0]
        knobs = ", ".join(
            f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
            for k, v in in_use(b["design"]).items()
        )
        engine = b["engine"].get("error") or f"engine {b['engine']['mean']:.4g} kPa"
        print(f"best: {knobs}; {engine}")


def _benchmark(spec, args) -> int:
    """``--benchmark``: the screen's wall time on one worker against several, in one run."""
    from gecko_agents.design.benchmark import benchmark_workers

    if args.storage or args.dask:
        raise UsageError(
            "--benchmark times local workers on a new SQLite store: no --storage/--dask"
        )
    workers = args.workers if args.workers > 1 else 2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", category=UserWarning)  # Optuna's experimental notes
        b = benchmark_workers(spec, trials=args.trials, pairs=2, workers=workers)
    rows = zip(b["one_s"], b["many_s"], b["ratios"], b["machine"], b["cpu_ratios"], strict=True)
    for one, many, r, m, c in rows:
        print(
            f"{b['trials']} trials: 1 worker {one:.1f} s, {workers} workers {many:.1f} s "
            f"({r:.2f}×; two CPU-bound processes took {m:.2f}× one's time then; CPU time "
            f"per worker {c:.2f}×)"
        )
    print(f"{workers} workers / 1 worker: {b['ratio']:.2f} (median of {len(b['ratios'])} pairs)")
    return EXIT_OK
