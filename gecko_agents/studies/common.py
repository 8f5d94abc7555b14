"""Shared plumbing for the studies: arguments, output folders, tables, claims.

Every scenario has ``main(argv=None) -> dict`` and accepts ``--quick`` (seconds, small N, used
by the tests) and ``--out DIR`` (default ``renders/<name>/``); it writes only there. The dict it
returns holds its key numbers and, for reproduce_paper, ``"claims"``: rows of the
paper-comparison table built with :func:`claim`.
"""

from __future__ import annotations

import argparse
import csv
import functools
import io
import json
import os
import sys
from pathlib import Path

import numpy as np

from gecko_agents.console import WarningLog, add_verbosity_arguments
from gecko_agents.output_paths import (
    all_or_nothing,
    atomic_write_bytes,
    make_dir,
    output_dir_arg,
)
from gecko_agents.physics import jkr
from gecko_agents.provenance import versions

RENDERS = Path("renders")
"""Default output root, relative to the current directory: ``renders/<study>/``."""

VERDICTS = ("reproduced", "trend reproduced", "not reproducible from the stated parameters")
GREY = "#7f7f7f"
"""Colour of reference curves (the parts of eq 7/10 no tip reaches, N·Fc lines)."""
PAPER_DELTA_S_COEF = -0.21
"""The paper's separation overlap δs = −0.21 a0²/R (section 2.1; docs/physics.md, "Snap-off")."""


def num(x: float, spec: str = ".2f") -> str:
    """``format(x, spec)`` with a typographic minus."""
    return format(x, spec).replace("-", "\u2212")


def rel_off(ours: float, paper: float) -> str:
    """Relative distance from the paper's number, e.g. ``"6.4 %"``."""
    return f"{100 * abs(ours - paper) / abs(paper):.1f} %"


def off_paper(ours: float, paper: float) -> str:
    """How far ``ours`` is from the paper's number, e.g. ``"0.7 % off the paper's value"``."""
    return f"{rel_off(ours, paper)} off the paper's value"


def writable_dir(value: str) -> Path:
    """``--out`` as argparse ``type=``: a folder that exists or can be made, and is writable
    (:func:`gecko_agents.output_paths.output_dir_arg`: an empty value, an existing file, a path
    under a file and an unwritable folder are usage errors, exit 2). Not created here: a
    usage error found later in the command line leaves nothing behind."""
    return output_dir_arg(value)


def cores_arg(option: str):
    """An argparse ``type=`` for ``option`` (``--jobs``, ``--workers``): worker processes, an
    integer from 1 to this machine's cores (more only queue for the same cores and multiply
    the memory)."""

    def parse(value: str) -> int:
        cores = os.cpu_count() or 1
        try:
            jobs = int(value)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{option} {value!r} is not an integer") from None
        if not 1 <= jobs <= cores:
            raise argparse.ArgumentTypeError(
                f"{option} {jobs} must be in [1, {cores}] (this machine's cores)"
            )
        return jobs

    return parse


jobs_arg = cores_arg("--jobs")
"""``--jobs`` as argparse ``type=`` (:func:`cores_arg`)."""


def command_line(main):
    """Decorate a study's ``main(argv=None)``: called from the command line (``argv`` None),
    its warnings go through :class:`gecko_agents.console.WarningLog` at the ``--quiet`` /
    ``--verbose`` level given (one short line per validity item at the end by default), as
    under ``reproduce_paper``; called with ``argv`` (by another study or a test), the caller's
    warning handling stands."""

    @functools.wraps(main)
    def run(argv=None):
        name = main.__module__.rsplit(".", 1)[-1]
        with all_or_nothing():  # a study that fails leaves its folder as it found it
            if argv is not None:
                return main(argv)
            argv = sys.argv[1:]
            level = 0 if "--quiet" in argv else 2 if "--verbose" in argv else 1
            try:
                with WarningLog(level) as log:
                    log.family(name)
                    return main(argv)
            except OSError as err:  # a full disk or a file-size limit, from the command line
                message = f"could not write the results ({err}); nothing was left half-written"
                print(f"{name}: error: {message}", file=sys.stderr)
                raise SystemExit(1) from None

    return run


def parse_args(doc: str, argv=None, extra=None) -> argparse.Namespace:
    """Parse the common options; ``extra(parser)`` may add scenario-specific ones."""
    parser = argparse.ArgumentParser(description=(doc or "").strip().splitlines()[0])
    parser.add_argument(
        "--quick", action="store_true", help="small and fast (seconds): for tests and a first look"
    )
    parser.add_argument(
        "--out",
        type=writable_dir,
        default=None,
        help="output folder, created if needed (default renders/<scenario>/)",
    )
    parser.add_argument("--no-progress", action="store_true", help="hide progress bars")
    add_verbosity_arguments(parser)
    if extra is not None:
        extra(parser)
    return parser.parse_args(argv)


def output_dir(name: str, args: argparse.Namespace) -> Path:
    """The scenario's output folder, created if needed."""
    out = args.out if args.out is not None else RENDERS / name
    return make_dir(out)


def write_table(path: Path, rows: list[dict]) -> Path:
    """Write dict rows as CSV (atomic); columns from the union of keys in first-seen order."""
    cols: list[str] = []
    for r in rows:
        cols += [k for k in r if k not in cols]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    atomic_write_bytes(Path(path), buf.getvalue().encode())
    return Path(path)


def write_json(path: Path, data: dict) -> Path:
    """Write JSON (atomic) with the package versions added under ``versions``."""
    data = dict(data, versions=versions())
    atomic_write_bytes(Path(path), json.dumps(data, indent=2, default=float).encode())
    return Path(path)


def claim(
    figure: str,
    claim: str,
    paper: str,
    ours: str,
    verdict: str,
    reason: str,
    alternative: str = "—",
) -> dict:
    """One row of renders/paper_comparison.md. ``ours``/``alternative`` are computed strings."""
    if verdict not in VERDICTS:
        raise ValueError(f"verdict {verdict!r} must be one of {VERDICTS}")
    return {
        "figure": figure,
        "claim": claim,
        "paper": paper,
        "ours": ours,
        "alternative": alternative,
        "verdict": verdict,
        "reason": reason,
    }


def jkr_curves(contact, n: int, P_max: float) -> dict:
    """Arrays along eq 7/10 for one tip (µm, µN): the reachable branch a ≥ a_c up to the
    compressive force P_max (``a_st``, ``P_st``, ``d_st``) and the part below a_c that no
    tip reaches (``a_un``, ``P_un``, ``d_un``)."""
    R, w, E = contact.jkr_args()
    a_D = float(jkr.snap_off_radius(R, w, E))
    a_max = float(jkr.contact_radius_from_force(P_max, R, w, E))
    a_st = np.linspace(a_D, a_max, n)
    a_un = np.linspace(0.0, a_D, max(n // 4, 20))
    return {
        "a_st": a_st,
        "P_st": jkr.force_from_radius(a_st, R, w, E),
        "d_st": jkr.overlap_from_radius(a_st, R, w, E),
        "a_un": a_un,
        "P_un": jkr.force_from_radius(a_un, R, w, E),
        "d_un": jkr.overlap_from_radius(a_un, R, w, E),
    }


def jkr_family(contacts, rows, labels_a, labels_b, n: int, P_max: float) -> tuple[list, list]:
    """Curves of a family of JKR tips for :func:`gecko_agents.render.plot_force_curves`, one
    colour each: panel (a) radius against force [µm, µN], panel (b) force against overlap
    [µN, µm]; the reachable branch solid, the rest of eq 7/10 dotted and, in (b), the jump
    D → E to zero force dashed at the displacement-controlled end (each row's
    ``overlap_end_um``, ``force_end_uN``)."""
    from gecko_agents.render import STYLE_RC

    colours = STYLE_RC["axes.prop_cycle"].by_key()["color"][: len(rows)]
    ca, cb = [], []
    for contact, row, la, lb, col in zip(contacts, rows, labels_a, labels_b, colours, strict=True):
        c = jkr_curves(contact, n, P_max)
        ca += [
            {"x": c["P_st"], "y": c["a_st"], "label": la, "style": {"color": col}},
            {"x": c["P_un"], "y": c["a_un"], "style": {"color": col, "ls": ":"}},
        ]
        cb += [
            {"x": c["d_st"], "y": c["P_st"], "label": lb, "style": {"color": col}},
            {"x": c["d_un"], "y": c["P_un"], "style": {"color": col, "ls": ":"}},
            {
                "x": [row["overlap_end_um"]] * 2,
                "y": [row["force_end_uN"], 0.0],
                "style": {"color": col, "ls": "--", "lw": 1.0},
            },
        ]
    return ca, cb


def save_on_zero_axes(curves, points, labels, title: str, path: Path, head_room: float) -> Path:
    """Write ``path``: the curves (:func:`gecko_agents.render.plot_force_curves`) with the axes
    through zero drawn, the legend top left and ``head_room`` × the y span added above the
    curves for it."""
    import matplotlib as mpl

    from gecko_agents.render import STYLE_RC, plot_force_curves, save_figure

    xlabel, ylabel = labels
    fig = plot_force_curves(curves, None, xlabel=xlabel, ylabel=ylabel, points=points, title=title)
    ax = fig.axes[0]
    with mpl.rc_context(STYLE_RC):
        ax.axhline(0.0, color="#888888", lw=0.6, zorder=1)
        ax.axvline(0.0, color="#888888", lw=0.6, zorder=1)
        lo, hi = ax.get_ylim()
        ax.set_ylim(top=hi + head_room * (hi - lo))
        ax.legend(loc="upper left", fontsize=8)
    save_figure(fig, path)
    return path


def run_scenario(name: str, argv: list[str], verbosity: int = 1) -> tuple[dict, float, dict]:
    """Run scenario ``name``'s ``main(argv)`` (here or in a worker process: a module-level
    function, so it pickles by name); returns (its result, wall time [s], the warnings it
    gave as :meth:`gecko_agents.console.WarningLog.records`). At ``verbosity`` 2 the warnings
    are printed as they come; otherwise the caller reports them."""
    import importlib
    import time

    from gecko_agents.console import WarningLog

    t0 = time.perf_counter()
    with WarningLog(verbosity=2 if verbosity >= 2 else -1) as log:
        res = importlib.import_module(f"gecko_agents.studies.{name}").main(argv)
    return res, time.perf_counter() - t0, log.records()
