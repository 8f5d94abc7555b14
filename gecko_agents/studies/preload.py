"""Preload-and-pull sweeps of the paper's array (Fig 11a/11b): point functions and shared parts.

The two sweep points — one force-controlled press to a preload and pull-off — are
:func:`quasistatic_preload_point` (the whole array, quasi-static solver) and
:func:`agent_preload_point` (a patch of the pymunk agent model, scaled to the array). The
preload is a protocol quantity: sweep it with the grid name ``"fn.preload_uN"``; the seed
draws the floor. They live in :mod:`gecko_agents.sweep.points`, where sweep files name them.

The rest is what fig11a_preload and fig11b_roughness share: settings, the four sweeps (paper's
method, adhesive friction, w = 0.080 J/m², agent patch), statistics over floor seeds and curve
metrics. Units: the sweeps in µN on the simulated array, the summaries in N on the 10⁷-seta
array (1 N = 10⁶ µN).
"""

from __future__ import annotations

import json
import math
import time

import numpy as np

from gecko_agents import sweep
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY, SetaArray
from gecko_agents.protocol import Press, PullOff
from gecko_agents.studies.common import cores_arg
from gecko_agents.sweep.points import agent_preload_point, quasistatic_preload_point

UN_PER_N = 1e6
FULL_COUNT = PAPER_ARRAY.array.count  # 10⁷ setae
PAPER_SATURATION_N = 2.3  # Fig 11a text: "stabilized at about 2.3 N"
PAPER_ONSET_N = 1.0  # "after the pre-pressure reached 1 N"
W_ALT = 0.080  # Fig 5's w [J/m²] (docs/physics.md, "Work of adhesion")
N_BLOCKS = 1000
RETRACT_STEPS = 2000  # pull-off within 0.05 % of 8000 steps
CURVES = True
"""Whether a quasi-static sweep's points are read off one curve per floor (the
``curve_uN`` of :func:`quasistatic_preload_point`: one shared approach, the retracts batched)
instead of one press-and-pull each; False only for the main-job benchmark's baseline."""
AGENT = {"n_sim": 16, "speed": 0.02}
"""Agent patch settings: 16 rod setae, plate at 0.02 µm/µs (20 mm/s; peak within 0.7 % of
0.005 µm/µs); see :func:`agent_preload_point`."""


# Shared parts of fig11a / fig11b -----------------------------------------------------------


def log_preloads(lo_exp4: int, hi_exp4: int) -> list[float]:
    """Preloads 10^(k/4) N for k in [lo_exp4, hi_exp4] (four per decade) [N]."""
    return [10.0 ** (k / 4) for k in range(lo_exp4, hi_exp4 + 1)]


def parameter_sets(count: int) -> tuple[SetaArray, SetaArray, SetaArray]:
    """(paper's method, adhesive friction, w = W_ALT) on a ``count``-seta array.

    The paper's method is the array with friction cap μ·max(P, 0) (eq 27); adhesive friction is
    the package default μ|P + 2Fc|; the third is the paper's method with Fig 5's w.
    """
    adhesive = PAPER_ARRAY.replace(**{"array.count": count})
    base = adhesive.replace(**{"friction.law": "paper"})
    return base, adhesive, base.replace(**{"contact.w": W_ALT})


def config(quick: bool) -> dict:
    """Sweep settings. ``count`` is the simulated array; results are scaled to 10⁷ setae."""
    if quick:
        return {
            "count": 100_000,
            "n_blocks": 200,
            "retract_steps": 500,
            "preloads_N": [0.1, 1.0, 10.0],
            "floor_seeds": [0],
            "alt_preloads_N": [0.1, 1.0, 10.0],
            "agent_preloads_N": [1.0],
            "agent_seeds": [0],
            "agent": dict(AGENT, n_sim=4, speed=0.1),
        }
    return {
        "count": FULL_COUNT,
        "n_blocks": N_BLOCKS,
        "retract_steps": RETRACT_STEPS,
        "preloads_N": log_preloads(-6, 5),
        "floor_seeds": [0, 1, 2],
        "alt_preloads_N": log_preloads(-6, 5),
        "agent_preloads_N": [0.1, 0.316, 1.0, 3.16, 10.0],
        "agent_seeds": [0, 1, 2],
        "agent": dict(AGENT),
    }


def preload_values(preloads_N, count: int) -> list[float]:
    """Preloads on a ``count``-seta array [µN] with the per-seta preload of the 10⁷-seta array."""
    return [p * UN_PER_N * count / FULL_COUNT for p in preloads_N]


def ok_rows(rows: list[dict], label: str) -> list[dict]:
    """The rows that finished; report the others."""
    bad = [r for r in rows if r["status"] != "ok"]
    for r in bad:
        print(f"{label}: point {r['key']} (seed {r['seed']}) {r['status']}: {r['error']}")
    return [r for r in rows if r["status"] == "ok"]


def compute_seconds(out, rows: list[dict]) -> float:
    """Sum of the points' own run times [s] (from ``points/<key>.json``; a resumed sweep's
    wall time does not show them)."""
    total = 0.0
    for r in rows:
        record = json.loads((out / "points" / f"{r['key']}.json").read_text())
        total += record.get("elapsed_s") or 0.0
    return total


def summarize(rows: list[dict], value: str, scale: float, group: str | None = None) -> dict:
    """{group value: {"preload_N", "mean", "min", "max", "n"} arrays over preloads}.

    ``value`` is a result column, multiplied by ``scale`` (to N on the 10⁷-seta array); the
    preload is the ``fn.preload_uN`` column scaled the same way. Statistics are over floor seeds.
    """
    out = {}
    for g in sorted({r[group] if group else None for r in rows}, key=lambda v: (v is None, v)):
        sub = [r for r in rows if (r[group] if group else None) == g]
        preloads = sorted({r["fn.preload_uN"] for r in sub})
        stats = {"preload_N": [], "mean": [], "min": [], "max": [], "n": []}
        for s in preloads:
            v = np.array([r[value] for r in sub if r["fn.preload_uN"] == s], dtype=float) * scale
            stats["preload_N"].append(s * scale)
            for k, f in (("mean", np.mean), ("min", np.min), ("max", np.max)):
                stats[k].append(float(f(v)))
            stats["n"].append(len(v))
        out[g] = {k: np.asarray(v) for k, v in stats.items()}
    return out


def crossing(x, y, level: float) -> tuple[float, bool]:
    """First x where y reaches ``level``, interpolated linearly in log x.

    Returns (x, exact); exact is False when y starts at or above the level (x is then the
    first x, an upper bound) or never reaches it (NaN).
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    if y[0] >= level:
        return float(x[0]), False
    above = np.flatnonzero(y >= level)
    if above.size == 0:
        return math.nan, False
    i = above[0]
    t = (level - y[i - 1]) / (y[i] - y[i - 1])
    return float(10 ** (np.log10(x[i - 1]) + t * (np.log10(x[i]) - np.log10(x[i - 1])))), True


def curve_metrics(s: dict) -> dict:
    """Saturation (mean pull-off at the largest preload), 90 % preload, rise and last step."""
    P, y = s["preload_N"], s["mean"]
    sat = float(y[-1])
    p90, exact = crossing(P, y, 0.9 * sat)
    return {
        "saturation_N": sat,
        "preload_90_N": p90,
        "preload_90_exact": exact,
        "first_N": float(y[0]),
        "first_preload_N": float(P[0]),
        "last_preload_N": float(P[-1]),
        "last_step_change": float(y[-1] / y[-2] - 1) if len(y) > 1 else math.nan,
        "monotone": bool(np.all(np.diff(y) >= -0.005 * sat)),
    }


def fmt_p90(m: dict) -> str:
    """The 90 % preload as text ("≤" when the first preload is already above 90 %)."""
    if math.isnan(m["preload_90_N"]):
        return "not reached"
    return f"{'' if m['preload_90_exact'] else '≤ '}{m['preload_90_N']:.2g} N"


def qs_kwargs(cfg: dict) -> dict:
    """Keyword arguments of :func:`quasistatic_preload_point`."""
    return {"n_blocks": cfg["n_blocks"], "retract_steps": cfg["retract_steps"]}


def n_workers(args) -> int | None:
    """``--workers`` if given; else --quick without Dask runs its few short points in this
    process (no start-up cost), and a full run one worker process per core."""
    if args.workers is not None:
        return args.workers
    return 1 if args.quick and args.dask is None else None


def quasistatic_sweep(base, grid, preloads_N, cfg, out, args, label) -> list[dict]:
    """run_sweep of :func:`quasistatic_preload_point` (one point = one
    preload × grid point × floor seed, the floor seeds from ``grid["floor.seed"]``; with
    :data:`CURVES` the preloads of one grid point and seed are one curve); rows that
    finished."""
    grid = dict(grid)
    floor_seeds = grid.pop("floor.seed")
    grid["fn.preload_uN"] = preload_values(preloads_N, cfg["count"])
    kwargs = qs_kwargs(cfg) | ({"curve_uN": grid["fn.preload_uN"]} if CURVES else {})
    rows = sweep.run_sweep(
        quasistatic_preload_point,
        base,
        grid,
        floor_seeds,
        out,
        fn_kwargs=kwargs,
        dask=args.dask,
        # a few curves: cheaper in this process than shared out to workers, each of which
        # would start up and compute every curve whose points it is handed
        n_workers=1 if CURVES and args.workers is None and args.dask is None else n_workers(args),
        progress=not args.no_progress,
    )
    return ok_rows(rows, label)


def agent_sweep(base, grid, preloads_N, cfg, out, args) -> list[dict]:
    """run_sweep of :func:`agent_preload_point` on the 10⁷-seta array."""
    grid = dict(grid)
    floor_seeds = grid.pop("floor.seed")
    grid["fn.preload_uN"] = preload_values(preloads_N, FULL_COUNT)
    rows = sweep.run_sweep(
        agent_preload_point,
        base.replace(**{"mechanics": "rod"}),
        grid,
        floor_seeds,
        out,
        fn_kwargs=cfg["agent"],
        dask=args.dask,
        n_workers=n_workers(args),
        progress=not args.no_progress,
    )
    rows = ok_rows(rows, "agent")
    for r in rows:
        if r["preload_held_uN"] < 0.99 * r["preload_patch_uN"]:
            print(
                f"agent: point {r['key']} held {r['preload_held_uN']:.3g} µN of "
                f"{r['preload_patch_uN']:.3g} µN"
            )
    return rows


def run_series(series: dict, cfg: dict, out, args) -> tuple[dict, dict, dict]:
    """Run the named sweeps of one figure, each in its own folder under ``out``.

    ``series``: name → ``(params, grid, preloads_N, subdir, label)``; the name ``"agent"`` is
    run with :func:`agent_sweep`, every other with :func:`quasistatic_sweep` (``label`` names
    it in messages). Returns (rows by name, wall time ``<name>_s`` by name [s], the folders).
    """
    rows, times, dirs = {}, {}, {}
    for name, (params, grid, preloads_N, subdir, label) in series.items():
        dirs[name] = out / subdir if subdir else out
        t0 = time.perf_counter()
        if name == "agent":
            rows[name] = agent_sweep(params, grid, preloads_N, cfg, dirs[name], args)
        else:
            rows[name] = quasistatic_sweep(params, grid, preloads_N, cfg, dirs[name], args, label)
        times[f"{name}_s"] = time.perf_counter() - t0
    return rows, times, dirs


def point_compute_seconds(rows: dict, dirs: dict) -> dict:
    """Sum of the points' own run times per series [s] (see :func:`compute_seconds`)."""
    return {k: compute_seconds(dirs[k], rows[k]) for k in rows}


def block_check(base, cfg, preload_N: float = 1.0) -> dict:
    """Pull-off with N_BLOCKS vs 4 × N_BLOCKS representative heights at one preload."""
    preload = preload_values([preload_N], cfg["count"])[0]
    vals = {}
    curve = {"curve_uN": [preload]} if CURVES else {}  # the method of the sweeps' points
    for nb in (cfg["n_blocks"], 4 * cfg["n_blocks"]):
        kw = qs_kwargs(cfg) | {"n_blocks": nb, "preload_uN": preload} | curve
        vals[nb] = quasistatic_preload_point(base, 0, **kw)["pull_off_uN"]
    a, b = vals.values()
    return {
        "preload_N": preload_N,
        "pull_off_uN_by_n_blocks": {str(k): v for k, v in vals.items()},
        "relative_difference": a / b - 1,
    }


def legend_below(fig, ax, ncol: int = 1) -> None:
    """Put the legend under the axes (the curves fill the panel), one entry per line: the
    labels are long, and an ``outside`` legend makes the constrained layout leave room for it."""
    fig.set_size_inches(7.4, 6.6)
    handles, labels = ax.get_legend_handles_labels()
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=8, frameon=False)


def add_args(parser) -> None:
    parser.add_argument(
        "--dask",
        type=sweep.parse_dask_arg,
        default=None,
        help="run sweep points on Dask: 'local' or 'tcp://host:port' (default: local processes)",
    )
    parser.add_argument(
        "--workers",
        type=cores_arg("--workers"),
        default=None,
        help="local worker processes of the sweeps (default: one per core; 1: in this process)",
    )
    parser.add_argument(
        "--animate",
        action="store_true",
        help="also animate one agent patch pressed to 1 N (detachment.gif)",
    )


def animate_patch(params, cfg: dict, out, preload_N: float = 1.0) -> None:
    """Record one agent patch (rod setae) pressed to its share of ``preload_N`` [N] and pulled
    off, save it under ``out/animated_run`` and render ``out/detachment.gif``."""
    from gecko_agents.render import animate

    n_sim, speed = cfg["agent"]["n_sim"], cfg["agent"]["speed"]
    m = Model(params.replace(**{"mechanics": "rod"}), n_sim=n_sim, seed=0, record_setae=True)
    target = preload_values([preload_N], FULL_COUNT)[0] * n_sim / FULL_COUNT
    h = m.run([Press(target, speed), PullOff(speed)], progress=False)
    h.save(out / "animated_run")
    animate(h, out / "detachment.gif")
