"""The ``gecko-agents`` command line.

::

    gecko-agents run RUNFILE.toml [--out DIR] [--quick] [--gif|--mp4] [--quiet|--verbose]
    gecko-agents sweep SWEEPFILE.toml [--out DIR] [--quick] [--dask ADDR] [--resume]
    gecko-agents reproduce [--quick] [--quiet|--verbose]
    gecko-agents render RUN_DIR [--gif|--mp4]
    gecko-agents bench [--quick] [--quiet|--verbose]
    gecko-agents params [PRESET]
    gecko-agents calibrate ...        (when gecko_agents/calibrate.py is present)

Run files are described in :mod:`gecko_agents.runfiles.run`, sweep files in
:mod:`gecko_agents.runfiles.sweep`; ``examples/`` holds one of each kind of study. ``python -m
gecko_agents`` is this command line too. Exit codes: 0 success, 1 the run failed, 2 a usage
or input error (nothing was run), 130 interrupted (Ctrl-C; nothing half-written).

Warnings (:mod:`gecko_agents.console`): ``run``, ``reproduce`` and ``bench`` print one short
line per validity item per run family and end with a one-line validity summary; ``--quiet``
keeps the summary only, ``--verbose`` prints every warning as it comes.

Each subcommand is one ``_cmd_<name>(args, extra) -> int`` handler and one entry of
:data:`COMMANDS`, which builds its parser; adding a subcommand touches nothing else.
"""

from __future__ import annotations

import argparse
import dataclasses
import shlex
import sys
import time
from collections.abc import Callable
from pathlib import Path

from gecko_agents import __version__
from gecko_agents.console import WarningLog, add_verbosity_arguments, summary_line, verbosity
from gecko_agents.output_paths import check_output_dir, output_dir_arg
from gecko_agents.params.table import parameter_table

__all__ = [
    "main",
    "COMMANDS",
    "EXIT_OK",
    "EXIT_FAILURE",
    "EXIT_USAGE",
    "EXIT_INTERRUPTED",
    "parameter_table",
]

EXIT_OK, EXIT_FAILURE, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130
PROG = "gecko-agents"
HELP_WIDTH = 100  # longest line ``params`` prints


class UsageError(Exception):
    """Bad input found by a handler (exit code 2)."""


def _err(message: str) -> None:
    print(f"{PROG}: error: {message}", file=sys.stderr)


def _checked(out: Path) -> Path:
    """A default output folder, checked as ``--out`` is (a usage error if it cannot be written)."""
    try:
        return check_output_dir(out, "the default output folder")
    except ValueError as err:
        raise UsageError(f"{err}; give --out") from None


# run ---------------------------------------------------------------------------------------------
def _add_run(p: argparse.ArgumentParser) -> None:
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


def _cmd_run(args, extra) -> int:
    from gecko_agents.runfiles import run as runfile

    spec = runfile.load_run(args.runfile, quick=args.quick)
    out = args.out if args.out is not None else _checked(_default_run_dir(args.runfile))
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
    except KeyboardInterrupt:
        _err(
            f"interrupted: nothing was written to {out} (a run directory already there is "
            f"untouched); start again with: {PROG} run {' '.join(argv)}"
        )
        return EXIT_INTERRUPTED
    except Exception as err:
        _err(f"the run failed ({type(err).__name__}): {err}; nothing was written to {out}")
        return EXIT_FAILURE
    m = history.meta
    print(
        f"wrote {out}/ in {time.perf_counter() - t0:.1f} s: {m.get('n_sim')} setae, "
        f"{m.get('n_steps')} steps of {m.get('dt_us', float('nan')):.3g} µs "
        f"({m.get('kernel')} kernel); peak pull-off {history.peak_pull_off:.4g} µN"
    )
    bad = m["run_file"]["invariant_violations"]
    if bad:
        _err(f"the history breaks its invariants: {'; '.join(bad)}")
        return EXIT_FAILURE
    print(
        f"re-run it with: {PROG} run {shlex.quote(str(out / runfile.RUN_FILE_NAME))}"
        f"{' --quick' if args.quick else ''}"
    )
    print(summary_line([m["validity"]], f"'validity' in {out / 'metadata.json'}"))
    return EXIT_OK


# sweep -------------------------------------------------------------------------------------------
def _add_sweep(p: argparse.ArgumentParser) -> None:
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


def _cmd_sweep(args, extra) -> int:
    from gecko_agents import sweep
    from gecko_agents.output_paths import atomic_write_bytes
    from gecko_agents.runfiles import sweep as sweepfile
    from gecko_agents.sweep.store import read_record

    spec = sweepfile.load_sweep(args.sweepfile, quick=args.quick)
    out = args.out if args.out is not None else _checked(spec.out_dir)
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
    print(
        f"{spec.path}{' (quick)' if spec.quick else ''}: {spec.point} on {spec.preset}, "
        f"{spec.n_points} points → {out}/"
    )
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(out / sweepfile.SWEEP_FILE_NAME, spec.text)
    t0 = time.perf_counter()
    try:
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
        _err(
            f"interrupted: {done} finished point(s) are stored in {points_dir}/; resume with: "
            + " ".join(resume)
        )
        return EXIT_INTERRUPTED
    except ImportError as err:
        raise UsageError(str(err)) from None
    reused = sum(r["key"] in stored_ok and r["status"] == "ok" for r in rows)
    errors = [r for r in rows if r["status"] != "ok"]
    print(
        f"wrote {out / 'sweep.csv'} in {time.perf_counter() - t0:.1f} s: "
        f"{len(rows) - len(errors)} of {len(rows)} points ok"
        + (f", {reused} reused from an earlier run" if reused else "")
    )
    if errors:
        _err(
            f"{len(errors)} point(s) failed, e.g. seed {errors[0]['seed']}: "
            f"{errors[0]['error']}; after a fix, re-run with: " + " ".join(resume)
        )
        return EXIT_FAILURE
    return EXIT_OK


# reproduce ---------------------------------------------------------------------------------------
def _add_reproduce(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--quick",
        action="store_true",
        help="small runs of every study: the report's shape in about a minute on 2 cores",
    )
    p.add_argument(
        "--out", type=output_dir_arg, default=None, help="output folder (default renders/)"
    )
    p.add_argument("--no-progress", action="store_true", help="hide progress bars")
    add_verbosity_arguments(p)


def _cmd_reproduce(args, extra) -> int:
    from gecko_agents.studies import reproduce_paper

    argv = (["--quick"] if args.quick else []) + (["--out", str(args.out)] if args.out else [])
    argv += ["--no-progress"] if args.no_progress else []
    argv += (["--quiet"] if args.quiet else []) + (["--verbose"] if args.verbose else [])
    argv += list(extra)
    try:
        reproduce_paper.main(argv)
    except KeyboardInterrupt:
        _err(
            "interrupted: scenarios that finished keep their outputs (each file is written "
            f"atomically); run `{PROG} reproduce` again to redo the rest"
        )
        return EXIT_INTERRUPTED
    return EXIT_OK


# render ------------------------------------------------------------------------------------------
def _add_render(p: argparse.ArgumentParser) -> None:
    from gecko_agents import render

    render.add_arguments(p)


def _cmd_render(args, extra) -> int:
    from gecko_agents import render

    return render.run(args)


# bench -------------------------------------------------------------------------------------------
def _add_bench(p: argparse.ArgumentParser) -> None:
    p.add_argument("--quick", action="store_true", help="tiny sizes: a smoke run (seconds)")
    p.add_argument(
        "--no-dask", action="store_true", help="skip the 1- vs 2-worker Dask sweep throughput"
    )
    add_verbosity_arguments(p)
    p.add_argument(
        "--work-precision", action="store_true",
        help="the work-precision benchmark: explicit and implicit steps against their error",
    )  # fmt: skip


def _cmd_bench(args, extra) -> int:
    from gecko_agents import bench

    flags = [f for f, on in (("--quick", args.quick), ("--no-dask", args.no_dask),
                             ("--work-precision", args.work_precision)) if on]  # fmt: skip
    with WarningLog(verbosity(args)) as log:
        log.family("bench")
        bench.main(flags + list(extra))
    return EXIT_OK


# params ------------------------------------------------------------------------------------------
def _add_params(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "preset",
        nargs="?",
        default=None,
        help="preset name (case-insensitive); without it, list the presets",
    )


def _cmd_params(args, extra) -> int:
    import textwrap

    from gecko_agents.runfiles.run import PRESETS, preset_docs

    def wrapped(text: str, indent: str, first: str = "") -> str:
        return textwrap.fill(" ".join(text.split()), HELP_WIDTH, initial_indent=first or indent,
                             subsequent_indent=indent, break_on_hyphens=False)  # fmt: skip

    docs = preset_docs()
    if args.preset is None:
        print("Presets (show one with: gecko-agents params NAME):")
        for name in PRESETS:
            print(wrapped(docs.get(name, "").split("\n\n", 1)[0], " " * 4, f"  {name}: "))
        return EXIT_OK
    match = [n for n in PRESETS if n.lower() == args.preset.lower()]
    if not match:
        raise UsageError(f"unknown preset {args.preset!r}; allowed: {', '.join(PRESETS)}")
    name = match[0]
    print(wrapped(docs.get(name, "").split("\n\n", 1)[0], "  ", f"{name}: "))
    print(
        wrapped(
            "Units: µm, µN, µs, ng; MPa = µN/µm², µN/µm = N/m = J/m². Derived quantities in "
            "parentheses; override a parameter in a run file's [params] by its dotted name "
            '(e.g. "seta.L" = 5.0). Each parameter\'s meaning is on the lines under it.',
            "",
        )
    )
    print()
    rows = [("parameter", "value", "unit", "equation")]
    table = parameter_table(PRESETS[name])
    rows += [(n, v, u, e) for n, v, u, _, e in table]
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    for i, row in enumerate(rows):
        print("  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip())
        if i == 0:
            print("  ".join("-" * w for w in widths))
        elif table[i - 1][3]:
            print(wrapped(table[i - 1][3], " " * 4))
    return EXIT_OK


# calibrate ---------------------------------------------------------------------------------------
def _add_calibrate(p: argparse.ArgumentParser) -> None:
    """Every argument is handed to :func:`gecko_agents.calibrate.main` (its own --help)."""


def _cmd_calibrate(args, extra) -> int:
    from gecko_agents import calibrate

    return calibrate.main(list(extra), prog=f"{PROG} calibrate")


# The table of subcommands ------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class Command:
    """A subcommand: its parser's arguments, its handler, one-line help and an example."""

    add_arguments: Callable[[argparse.ArgumentParser], None]
    handler: Callable[[argparse.Namespace, list[str]], int]
    help: str
    example: str
    passthrough: bool = False  # unknown arguments go to the delegate instead of an error
    own_help: bool = True  # False: --help too goes to the delegate


COMMANDS: dict[str, Command] = {
    "run": Command(
        _add_run,
        _cmd_run,
        "run a run file and write its run directory",
        "gecko-agents run examples/single_seta_press_pull.toml --quick --gif\n"
        "  gecko-agents run runs/single_seta_press_pull/run.toml   # re-run a copy",
    ),
    "sweep": Command(
        _add_sweep,
        _cmd_sweep,
        "run a parameter sweep file (resumable; local processes or Dask)",
        "gecko-agents sweep examples/sweep_roughness_preload.toml --quick\n"
        "  gecko-agents sweep examples/sweep_roughness_preload.toml --resume "
        "--dask local",
    ),
    "reproduce": Command(
        _add_reproduce,
        _cmd_reproduce,
        "reproduce the paper's figures and write renders/paper_comparison.md",
        "gecko-agents reproduce --quick --out /tmp/renders",
        passthrough=True,
    ),
    "render": Command(
        _add_render,
        _cmd_render,
        "draw force_history.png and a detachment animation of a run directory",
        "gecko-agents render runs/patch_rough_floor --gif --frames 120",
    ),
    "bench": Command(
        _add_bench,
        _cmd_bench,
        "speed of the agent model against bare pymunk, and the 10⁷-seta curve",
        "gecko-agents bench --quick --no-dask\n"
        "  (other options of python -m gecko_agents.bench, e.g. --sizes 1000 "
        "--steps 300, are passed on)",
        passthrough=True,
    ),
    "params": Command(
        _add_params,
        _cmd_params,
        "print a parameter preset with units and paper equations",
        "gecko-agents params PAPER_ARRAY",
    ),
    "calibrate": Command(
        _add_calibrate,
        _cmd_calibrate,
        "fit parameters to measured curves (gecko_agents.calibrate)",
        "gecko-agents calibrate data.csv --free contact.w=0.01:0.2 --out fit/",
        passthrough=True,
        own_help=False,
    ),
}
"""Subcommand name → ``Command``."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=PROG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Gecko-inspired setae arrays pressed onto and pulled off a rough floor "
        "(units µm, µN, µs, ng).",
        epilog="examples:\n  gecko-agents params PAPER_TABLE1\n"
        "  gecko-agents run examples/single_seta_press_pull.toml --quick\n\n"
        "exit codes: 0 success, 1 run failed, 2 usage or input error, 130 interrupted",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name, cmd in COMMANDS.items():
        p = sub.add_parser(
            name,
            help=cmd.help,
            description=cmd.help[0].upper() + cmd.help[1:] + ".",
            epilog=f"example:\n  {cmd.example}",
            add_help=cmd.own_help,
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        cmd.add_arguments(p)
        p.set_defaults(_command=name)
    return parser


def main(argv=None) -> int:
    """Run the command line on ``argv`` (default ``sys.argv[1:]``); returns the exit code."""
    from gecko_agents.runfiles.run import RunFileError

    parser = build_parser()
    try:
        args, extra = parser.parse_known_args(argv)
    except SystemExit as stop:  # --help, --version (0) or a usage error (2)
        return stop.code if isinstance(stop.code, int) else EXIT_USAGE
    cmd = COMMANDS[args._command]
    if extra and not cmd.passthrough:
        _err(f"unrecognized arguments: {' '.join(extra)} (see {PROG} {args._command} --help)")
        return EXIT_USAGE
    try:
        return cmd.handler(args, extra)
    except (RunFileError, UsageError) as err:
        _err(str(err))
        return EXIT_USAGE
    except SystemExit as stop:  # a delegate's own argument parser
        return stop.code if isinstance(stop.code, int) else EXIT_USAGE
    except KeyboardInterrupt:
        _err("interrupted: nothing was left half-written")
        return EXIT_INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
