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
import signal
import sys
import threading
from collections.abc import Callable

from gecko_agents import __version__
from gecko_agents.console import WarningLog, add_verbosity_arguments, verbosity
from gecko_agents.output_paths import output_dir_arg
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

from gecko_agents.cli.common import (
    EXIT_FAILURE,
    EXIT_INTERRUPTED,
    EXIT_OK,
    EXIT_USAGE,
    HELP_WIDTH,
    PROG,
    UsageError,
)
from gecko_agents.cli.common import error as _err
from gecko_agents.cli.design import add_design, cmd_design
from gecko_agents.cli.runs import add_run, add_sweep, cmd_run, cmd_sweep


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
        "--work-precision",
        action="store_true",
        help="the work-precision benchmark: explicit and implicit steps against their error",
    )


def _cmd_bench(args, extra) -> int:
    from gecko_agents import bench

    flags = [
        f
        for f, on in (
            ("--quick", args.quick),
            ("--no-dask", args.no_dask),
            ("--work-precision", args.work_precision),
        )
        if on
    ]
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
        return textwrap.fill(
            " ".join(text.split()),
            HELP_WIDTH,
            initial_indent=first or indent,
            subsequent_indent=indent,
            break_on_hyphens=False,
        )

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
        add_run,
        cmd_run,
        "run a run file and write its run directory",
        "gecko-agents run examples/single_seta_press_pull.toml --quick --gif\n"
        "  gecko-agents run runs/single_seta_press_pull/run.toml   # re-run a copy",
    ),
    "sweep": Command(
        add_sweep,
        cmd_sweep,
        "run a parameter sweep file (resumable; local processes or Dask)",
        "gecko-agents sweep examples/sweep_roughness_preload.toml --quick\n"
        "  gecko-agents sweep examples/sweep_roughness_preload.toml --resume "
        "--dask local",
    ),
    "design": Command(
        add_design,
        cmd_design,
        "search fibre array designs for a surface, a material and a process (needs optuna)",
        "gecko-agents design examples/design_pillars.toml --quick --out /tmp/design",
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


def _terminated(signum, frame):
    """SIGTERM (a batch system's kill) takes Ctrl-C's path: staged files removed, exit 130."""
    raise KeyboardInterrupt(f"signal {signum}")


def main(argv=None) -> int:
    """Run the command line on ``argv`` (default ``sys.argv[1:]``); returns the exit code."""
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _terminated) if in_main_thread else None
    try:
        return _main(argv)
    finally:
        if in_main_thread:
            signal.signal(signal.SIGTERM, previous)


def _main(argv) -> int:
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
    except SystemExit as stop:  # a delegate's own argument parser or its refusal
        if isinstance(stop.code, int):
            return stop.code
        if stop.code is not None:
            _err(str(stop.code))
        return EXIT_USAGE
    except KeyboardInterrupt:
        _err("interrupted: nothing was left half-written")
        return EXIT_INTERRUPTED
    except OSError as err:  # a full disk, a file-size limit, a folder gone read-only
        _err(f"could not write the results ({err}); nothing was left half-written")
        return EXIT_FAILURE


if __name__ == "__main__":
    sys.exit(main())
