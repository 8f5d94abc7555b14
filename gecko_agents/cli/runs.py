"""The ``run`` and ``sweep`` subcommands: a run file to a run directory, a sweep file to a
table of points (:mod:`gecko_agents.runfiles`)."""

from __future__ import annotations

import argparse
import shlex
import shutil
import time
from pathlib import Path

from gecko_agents.cli.common import (
    EXIT_FAILURE,
    EXIT_INTERRUPTED,
    EXIT_OK,
    EXIT_USAGE,
    PROG,
    UsageError,
    checked,
    error,
)
from gecko_agents.console import WarningLog, add_verbosity_arguments, summary_line, verbosity
from gecko_agents.output_paths import output_dir_arg

__all__ = ["add_run", "cmd_run", "add_sweep", "cmd_sweep"]


# run ---------------------------------------------------------------------------------------------
def add_run(p: argparse.ArgumentParser) -> None:
    p.add_argument("runfile", type=Path, help="run file (TOML; see examples/)")
    p.add_argument(
        "--out",
        type=output_dir_arg,
        default=None,
        help="run directory to write (default runs/<run file name>; an older run "
        "directory there is replaced once the new one is complete)",
    )
    p.add_argument(
        "--quick",
        action="store_true",
        help="the file's [quick] variant: a tiny run for a first look and the tests",
    )
    kind = p.add_mutually_exclusive_group()
    kind.add_argument(
        "--gif",
        dest="animation",
        action="store_const",
        const="gif",
        help="also write detachment.gif (records every seta)",
    )
    kind.add_argument(
        "--mp4",
        dest="animation",
        action="store_const",
        const="mp4",
        help="also write detachment.mp4 (needs pip install -e '.[video]')",
    )
    p.add_argument("--no-progress", action="store_true", help="hide the progress bar")
    add_verbosity_arguments(p)


def _default_run_dir(runfile: Path) -> Path:
    from gecko_agents.runfiles.run import RUN_FILE_NAME

    if runfile.name == RUN_FILE_NAME:  # the copy inside a run directory: do not overwrite it
        return Path("runs") / f"{runfile.resolve().parent.name}-rerun"
    return Path("runs") / runfile.stem


def _run_command(args) -> str:
    """The ``run`` command line of ``args``, every option given, quoted for a shell."""
    words = [PROG, "run", str(args.runfile)]
    words += ["--out", str(args.out)] if args.out is not None else []
    words += ["--quick"] if args.quick else []
    words += [f"--{args.animation}"] if args.animation else []
    words += ["--no-progress"] if args.no_progress else []
    words += ["--quiet"] if getattr(args, "quiet", False) else []
    words += ["--verbose"] if getattr(args, "verbose", False) else []
    return shlex.join(words)


def cmd_run(args, extra) -> int:
    from gecko_agents.model.cost import RunCostError
    from gecko_agents.runfiles import run as runfile

    spec = runfile.read_run_file(args.runfile, quick=args.quick)
    out = args.out if args.out is not None else checked(_default_run_dir(args.runfile))
    seg = ", ".join(type(s).__name__ for s in spec.protocol)
    print(
        f"{spec.path}{' (quick)' if spec.quick else ''}: {spec.preset}"
        f"{' + ' + str(len(spec.overrides)) + ' overrides' if spec.overrides else ''}, "
        f"{spec.params.mechanics} setae, protocol {seg}"
    )
    if spec.description:
        print(f"  {spec.description}")
    argv = [str(args.runfile)] + (["--quick"] if args.quick else [])
    t0 = time.perf_counter()
    try:
        with WarningLog(verbosity(args)) as log:
            log.family(args.runfile.name)
            out, history = runfile.execute_run(
                spec, out, animation=args.animation, progress=not args.no_progress, argv=argv
            )
    except runfile.RunFileError:
        raise
    except RunCostError as err:  # refused before the first step: an input error
        error(f"{spec.path}: {err}; nothing was written to {out}")
        return EXIT_USAGE
    except KeyboardInterrupt:
        error(
            f"interrupted: nothing was written to {out} (a run directory already there is "
            f"untouched); start again with: {_run_command(args)}"
        )
        return EXIT_INTERRUPTED
    except Exception as err:
        error(f"the run failed ({type(err).__name__}): {err}; nothing was written to {out}")
        return EXIT_FAILURE
    m = history.meta
    print(
        f"wrote {out}/ in {time.perf_counter() - t0:.1f} s: {m.get('n_sim')} setae, "
        f"{m.get('n_steps')} steps of {m.get('dt_us', float('nan')):.3g} µs "
        f"({m.get('kernel')} kernel); peak pull-off {history.peak_pull_off:.4g} µN"
    )
    bad = m["run_file"]["invariant_violations"]
    if bad:
        error(
            f"the history breaks its invariants: {'; '.join(bad)}; {out} is kept for "
            "inspection (its metadata.json records the violations under run_file)"
        )
        return EXIT_FAILURE
    print(
        f"re-run it with: {PROG} run {shlex.quote(str(out / runfile.RUN_FILE_NAME))}"
        f"{' --quick' if args.quick else ''}"
    )
    print(summary_line([m["validity"]], f"'validity' in {out / 'metadata.json'}"))
    return EXIT_OK


# sweep -------------------------------------------------------------------------------------------
def add_sweep(p: argparse.ArgumentParser) -> None:
    from gecko_agents.sweep import parse_dask_arg

    p.add_argument("sweepfile", type=Path, help="sweep file (TOML; see examples/)")
    p.add_argument(
        "--out",
        type=output_dir_arg,
        default=None,
        help="output directory (default: the file's out_dir, else sweeps/<name>)",
    )
    p.add_argument("--quick", action="store_true", help="the file's [quick] variant")
    p.add_argument(
        "--dask",
        type=parse_dask_arg,
        default=None,
        metavar="ADDR",
        help="'local' (a Dask cluster on this machine) or tcp://host:port (a running "
        "scheduler); default: local worker processes",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        help="local worker processes (default: the file's workers, else all cores)",
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue a sweep whose output directory already holds points: "
        "finished points are kept, the others run",
    )
    p.add_argument("--no-progress", action="store_true", help="hide the progress bar")
    add_verbosity_arguments(p)


def cmd_sweep(args, extra) -> int:
    from gecko_agents import sweep
    from gecko_agents.output_paths import atomic_write_bytes
    from gecko_agents.runfiles import sweep as sweepfile
    from gecko_agents.sweep.store import read_record

    spec = sweepfile.load_sweep(args.sweepfile, quick=args.quick)
    out = args.out if args.out is not None else checked(spec.out_dir)
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers {args.workers} must be ≥ 1")
    workers = args.workers if args.workers is not None else spec.workers
    if args.dask not in (None, "local"):
        workers = None  # the scheduler's own workers run the points
    points_dir = out / "points"
    before = {p.stem for p in points_dir.glob("*.json")} if points_dir.is_dir() else set()
    stored_ok = {  # points an earlier run finished: reused, not recomputed
        k for k in before if (read_record(points_dir / f"{k}.json", k) or {}).get("status") == "ok"
    }
    if before and not args.resume:
        raise UsageError(
            f"{out} already holds {len(before)} point file(s) of a sweep; add "
            "--resume to continue it (finished points are kept) or choose another "
            "--out"
        )
    resume = [PROG, "sweep", str(args.sweepfile), "--resume"]
    resume += ["--out", str(out)] if args.out is not None else []
    resume += ["--quick"] if args.quick else []
    resume += ["--dask", args.dask] if args.dask else []
    resume += ["--workers", str(args.workers)] if args.workers is not None else []
    print(
        f"{spec.path}{' (quick)' if spec.quick else ''}: {spec.point} on {spec.preset}, "
        f"{spec.n_points} points → {out}/"
    )
    created = not out.exists()
    t0 = time.perf_counter()
    try:
        out.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(out / sweepfile.SWEEP_FILE_NAME, spec.text)
        with WarningLog(verbosity(args)) as log:  # the points' warnings, relayed by the sweep
            log.family(args.sweepfile.name)
            rows = sweep.run_sweep(
                spec.point_fn,
                spec.base,
                spec.grid,
                spec.seeds,
                out,
                fn_kwargs=spec.point_args,
                dask=args.dask,
                n_workers=workers,
                progress=not args.no_progress,
            )
    except KeyboardInterrupt:
        done = len(list(points_dir.glob("*.json"))) if points_dir.is_dir() else 0
        error(
            f"interrupted: {done} finished point(s) are stored in {points_dir}/; resume with: "
            + shlex.join(resume)
        )
        return EXIT_INTERRUPTED
    except ImportError as err:
        raise UsageError(str(err)) from None
    except OSError as err:  # a full disk or a file-size limit: keep the points, say so
        return _sweep_not_written(err, out, created, resume)
    reused = sum(r["key"] in stored_ok and r["status"] == "ok" for r in rows)
    errors = [r for r in rows if r["status"] != "ok"]
    print(
        f"wrote {out / 'sweep.csv'} in {time.perf_counter() - t0:.1f} s: "
        f"{len(rows) - len(errors)} of {len(rows)} points ok"
        + (f", {reused} reused from an earlier run" if reused else "")
    )
    if errors:
        error(
            f"{len(errors)} point(s) failed, e.g. seed {errors[0]['seed']}: "
            f"{errors[0]['error']}; after a fix, re-run with: " + shlex.join(resume)
        )
        return EXIT_FAILURE
    return EXIT_OK


def _sweep_not_written(err: OSError, out: Path, created: bool, resume: list[str]) -> int:
    """A sweep whose files could not be written (a full disk, a file-size limit): a folder this
    command made and no point finished is removed; finished points are kept for ``--resume``."""
    points_dir = out / "points"
    done = len(list(points_dir.glob("*.json"))) if points_dir.is_dir() else 0
    if created and not done:
        shutil.rmtree(out, ignore_errors=True)  # only the sweep file this command wrote
        error(f"writing the sweep failed ({err}); nothing was left in {out}")
    else:
        error(
            f"writing the sweep failed ({err}); {done} finished point(s) are stored in "
            f"{points_dir}/; free space, then resume with: " + shlex.join(resume)
        )
    return EXIT_FAILURE
