"""Throughput benchmark: the agent model against pymunk's own stepping, and the 10⁷ curve.

Run ``python -m gecko_agents.bench`` (``--quick`` for a seconds-long smoke run). It prints

* seta-steps/s of :class:`gecko_agents.model.Model` for N setae pressed onto a flat floor
  (every tip attached), stepped through a plate move with :meth:`Model.run` (recording
  included), for N = 1 000 and 10 000, with the default (lazy) contact detection and, for the
  default kernel, with full detection;
* two baselines, each one ``space.step`` plus one ``pymunk.batch.get_space_bodies`` read and
  one ``set_space_bodies`` force write per step (the least any pymunk model with per-step
  forces must do): **pymunk with shapes**, the pressed world with a sensor circle and a floor
  pad for every tip (what full detection makes pymunk test every step), and the **bare
  engine**, the same bodies with no shapes at all;
* the agent's rate over each (1 would mean that everything but pymunk's stepping is free),
  the best of a few interleaved repeats of each, so machine noise hits all alike; for the
  numpy kernel and, when numba is installed, the numba one;
* a scaling table (``--scaling``, default N = 10³, 10⁴, 10⁵): ms per step of the pressed
  array, the wall time of a full press-pull (the paper's array, rod setae, σ = 0.5 µm pad
  floor, ``protocol.press_pull(1.0)``) — run for N ≤ ``--run-max`` (and again with the whole
  array taking the located steps, ``multirate=False``, the baseline of the same run) and
  extrapolated above it as (steps of the largest run) × (ms/step at N) — and the process's
  peak resident memory
  after each size (``resource.getrusage``: pymunk's bodies live in C, which tracemalloc does
  not see);
* the wall time of the quasi-static force–displacement curve of the paper's 10⁷-seta array
  (:func:`gecko_agents.quasistatic.press_pull` on
  :func:`~gecko_agents.quasistatic.representative_heights` with the sorted sample, so blocks
  are split at jump-in / stick-slide / release boundaries; heights drawn inside the timing),
  for 2000 and 20 000 blocks, and for 20 000 plain block means;
* the throughput of a sweep of CPU-bound points on a Dask LocalCluster with 2 workers
  relative to 1 (:func:`gecko_agents.sweep.benchmark.benchmark_dask_scaling`; skip with
  ``--no-dask``).

The last line is always ``agent/bare-engine ratio at N=<largest N>: X.XX`` (the default
kernel and detection against the bodies-only engine).
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import time
import warnings

import numpy as np
import pymunk.batch as pb

from gecko_agents import protocol
from gecko_agents import quasistatic as qs
from gecko_agents.bench_precision import (  # noqa: F401  (the work-precision benchmark's home)
    WP_CASES,
    _wp_error,
    pull_off_and_release,
    work_precision,
    wp_measure,
)
from gecko_agents.model import Model, Numerics, numba_available
from gecko_agents.model.runner import run_protocol
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.protocol import DEFAULT_SPEED, Move

__all__ = [
    "pressed_model",
    "bare_engine",
    "agent_rate",
    "elastic_pressed_model",
    "pymunk_rate",
    "press_pull_run",
    "peak_memory_mb",
    "quasistatic_time",
    "main",
]

_READ = pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.VELOCITY


def pressed_model(
    n: int, depth: float = 0.3, settle: int = 200, overrides: dict | None = None, **kw
) -> Model:
    """The paper's array with ``n`` setae over a flat floor, the plate ``depth`` [µm] below
    touch-down and every tip attached, after ``settle`` steps of rest; ``overrides`` are
    dotted parameter overrides (e.g. ``{"contact.crack_speed": 1.0}``)."""
    p = PAPER_ARRAY.replace(**{"array.count": int(n), "floor.sigma": 0.0, **(overrides or {})})
    m = Model.from_options(p, **({"integrator": "explicit"} | kw))  # the explicit step's cost
    place_pressed(m, depth)
    return settle_attached(m, settle)


def place_pressed(m: Model, depth: float) -> float:
    """Put the plate ``depth`` [µm] below touch-down and every tip at rest under its root;
    returns how far the plate moved [µm] (negative: down)."""
    plate_y = m.z_touch - depth
    drop = plate_y - m.plate.position.y
    m.plate.position = (m.plate.position.x, plate_y)
    rest = np.column_stack([m.world.rest_dx, m.world.rest_dy + plate_y])
    for body, xy in zip(m.tips, rest, strict=True):
        body.position = (float(xy[0]), float(xy[1]))
        body.velocity = (0.0, 0.0)
    return drop


def settle_attached(m: Model, settle: int) -> Model:
    """``settle`` steps of rest from a placed state; refuses unless every tip attached."""
    m.reset_state_arrays()
    for _ in range(settle):
        m.step((0.0, 0.0))
    if not np.all(m.attached):
        raise RuntimeError(f"only {int(m.attached.sum())} of {m.n} tips attached after settling")
    return m


def elastic_pressed_model(
    n: int, depth: float = 0.3, settle: int = 200, params=None, **model_kw
) -> Model:
    """:func:`gecko_agents.bench.pressed_model` on an elastic strip: handle, strip and tips
    moved ``depth`` [µm] below touch-down, then ``settle`` steps of rest, every tip attached.
    ``params``: the array (default: the paper's on a flat floor with the default
    :class:`gecko_agents.params.backing.Backing`, uniform drive), with ``n`` setae; ``model_kw`` go
    to
    :class:`gecko_agents.model.Model` (``seed``, ``leader_arm``, ... for
    :class:`gecko_agents.backing.elastic.ElasticBacking`)."""
    if params is None:
        params = PAPER_ARRAY.replace(**{"floor.sigma": 0.0, "backing.kind": "elastic"})
    m = Model.from_options(params.replace(**{"array.count": int(n)}), **model_kw)
    drop = place_pressed(m, depth)
    strip = m.backing.strip  # the strip moves down with its handle
    for link in strip.links:
        link.position = (link.position.x, link.position.y + drop)
    strip.rows = strip.read()
    return settle_attached(m, settle)


def bare_engine(n: int) -> Model:
    """:func:`pressed_model` with every shape taken out of its space: bodies only (the plate
    and N tips, pressed, at rest), for :func:`pymunk_rate`. The model itself is not meant to
    be stepped afterwards."""
    m = pressed_model(n, detection="full")
    m.space.remove(*m.space.shapes)
    return m


def agent_rate(m: Model, steps: int) -> float:
    """Seta-steps per second of ``m.run`` through a ``steps``-step downward plate move."""
    speed = DEFAULT_SPEED
    n0 = steps
    # A Move of exactly `steps` steps (the last one may be partial), run on from where the
    # model stands (best-of-repeats timing: Model.run runs a model once).
    move = [Move(dy=-speed * m.dt * (n0 - 0.5), speed=speed)]
    h = run_protocol(m, move, False, 50_000_000, None, True)
    return m.n * h.meta["n_steps"] / h.meta["wall_time_s"]


def pymunk_rate(m: Model, steps: int) -> float:
    """Seta-steps per second of the bare engine on ``m``'s space: per step one batch read of
    ids, positions and velocities, one batch force write, one ``space.step``."""
    space, dt = m.space, m.dt
    read, write = pb.Buffer(), pb.Buffer()
    read.clear()
    pb.get_space_bodies(space, _READ, read)
    n_rows = len(np.frombuffer(read.int_buf(), dtype=np.uintp))
    forces = np.zeros(2 * n_rows)
    t = time.perf_counter()
    for _ in range(steps):
        read.clear()
        pb.get_space_bodies(space, _READ, read)
        write.set_float_buf(forces)
        pb.set_space_bodies(space, pb.BodyFields.FORCE, write)
        space.step(dt)
    return m.n * steps / (time.perf_counter() - t)


def press_pull_run(
    n: int, progress: bool = False, multirate: bool | None = None
) -> tuple[float, int]:
    """Wall time [s] and steps of a full press-pull of ``n`` setae: the paper's array with rod
    setae on a σ = 0.5 µm pad floor, ``protocol.press_pull(1.0)``, seed 1 (``progress``: show
    the run's progress bar; ``multirate``: :class:`Numerics`' multirate)."""
    p = PAPER_ARRAY.replace(**{"floor.sigma": 0.5, "mechanics": "rod"})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, n_sim=int(n), seed=1, numerics=Numerics(multirate=multirate))
        h = m.run(protocol.press_pull(1.0), progress=progress)
    return h.meta["wall_time_s"], h.meta["n_steps"]


def peak_memory_mb() -> float:
    """Peak resident memory of this process so far [MB] (Linux ru_maxrss is in kB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def quasistatic_time(
    n_setae: int = 10**7,
    n_positions: int = 1000,
    n_blocks: int = 2000,
    seed: int = 0,
    split: bool = True,
) -> tuple[float, float, int]:
    """Wall time [s] of the quasi-static press-and-pull of ``n_setae`` setae (PAPER_ARRAY,
    σ = 1 µm, 1 µm deep) over ``n_positions`` plate positions, including drawing and sorting
    the heights; the pull-off force [µN]; the positions solved before every seta let go.

    ``split``: pass the sorted sample so blocks are split at jump-in, stick/slide and release
    boundaries (:func:`gecko_agents.quasistatic.solve`); else plain block means."""
    t = time.perf_counter()
    rng = np.random.default_rng(seed)
    h, w, sample = qs.representative_heights(
        n_setae, PAPER_ARRAY.floor.sigma, rng, n_blocks, return_sample=True
    )
    n_app = n_positions // 3
    r = qs.press_pull(
        PAPER_ARRAY,
        h,
        1.0,
        weights=w,
        n_approach=n_app,
        n_retract=n_positions - n_app,
        sample=sample if split else None,
    )
    return time.perf_counter() - t, r.pull_off, r.plate_y.size


def _scaling(sizes, run_max, steps, repeats) -> list[dict]:
    """The scaling table's rows (see the module docstring), printed as they come."""
    print("scaling (default kernel and detection; press-pull: rod setae, σ = 0.5 µm pads):")
    print(
        "       N   ms/step (pressed)   press-pull wall [s]   steps   peak RSS [MB]   "
        "whole array located: wall [s], steps"
    )
    rows, run_steps = [], None
    for n in sorted(sizes):
        m = pressed_model(n)
        ms = min(n / agent_rate(m, steps) * 1e3 for _ in range(repeats))
        del m
        whole = (math.nan, 0)
        if n <= run_max or run_steps is None:
            wall, run_steps = press_pull_run(n, progress=n >= 50_000)
            how = "run"
            if n <= run_max:  # the baseline in the same run
                whole = press_pull_run(n, multirate=False)
        else:
            wall, how = run_steps * ms * 1e-3, "extrapolated"
        row = {
            "n": n,
            "ms_per_step": ms,
            "press_pull_s": wall,
            "steps": run_steps,
            "how": how,
            "peak_rss_mb": peak_memory_mb(),
            "whole_array_s": whole[0],
            "whole_array_steps": whole[1],
        }
        rows.append(row)
        print(
            f"{n:>8}   {ms:17.3g}   {wall:12.4g} ({how:>12})   {run_steps:>5}   "
            f"{row['peak_rss_mb']:13.0f}   {whole[0]:10.4g}, {whole[1]}"
        )
    return rows


def _arguments(argv):
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument(
        "--sizes", type=int, nargs="+", default=[1_000, 10_000], help="array sizes N to step"
    )
    ap.add_argument("--steps", type=int, default=300, help="time steps per timed repeat")
    ap.add_argument("--repeats", type=int, default=3, help="repeats (the best one counts)")
    ap.add_argument(
        "--qs-setae", type=int, default=10**7, help="setae of the quasi-static curve (0: skip it)"
    )
    ap.add_argument(
        "--scaling",
        type=int,
        nargs="*",
        default=[1_000, 10_000, 100_000],
        help="sizes N of the scaling table (none: skip it)",
    )
    ap.add_argument(
        "--run-max",
        type=int,
        default=10_000,
        help="largest N whose press-pull is run in the scaling table (larger: extrapolated)",
    )
    ap.add_argument("--quick", action="store_true", help="tiny sizes: a smoke run")
    ap.add_argument(
        "--work-precision",
        action="store_true",
        help="steps and wall time against pull-off and release error, explicit and implicit",
    )
    ap.add_argument(
        "--main-job",
        action="store_true",
        help="the main job against itself without its fast paths, in one run "
        "(gecko_agents.bench_main_job)",
    )
    ap.add_argument(
        "--docs",
        metavar="PATH",
        help="with --work-precision or --main-job: also write its table to PATH (Markdown)",
    )
    ap.add_argument(
        "--no-dask", action="store_true", help="skip the 1- vs 2-worker Dask sweep throughput"
    )
    args = ap.parse_args(argv)
    if args.quick:
        args.sizes, args.steps, args.repeats, args.qs_setae = [50, 200], 40, 2, 10**5
        args.scaling, args.run_max = [20, 200], 20
    return args


def _quasistatic_section(n_setae: int, out: dict) -> None:
    """The quasi-static press-and-pull of ``n_setae`` setae, three ways of blocking."""
    for n_blocks, split in ((2000, True), (20_000, True), (20_000, False)):
        t_qs, pull, n_pos = quasistatic_time(n_setae, n_blocks=n_blocks, split=split)
        out.setdefault("quasistatic_s", t_qs)
        print(
            f"quasi-static press-and-pull of {n_setae:.0e} setae, 1000 plate "
            f"positions ({n_pos} before all let go), {n_blocks} blocks"
            f"{' split at boundaries' if split else ' (plain means)'}, heights "
            f"included: {t_qs:.2f} s, pull-off {pull:.7g} µN"
        )


def _engine_section(n: int, kernels, default: str, args, out: dict) -> None:
    """Agent kernels against pymunk with shapes and against the bare engine at N = ``n``,
    interleaved repeats, best of each."""
    shaped, bare = pressed_model(n, detection="full"), bare_engine(n)
    agents = {(k, "lazy"): pressed_model(n, kernel=k) for k in kernels}
    agents[(default, "full")] = pressed_model(n, kernel=default, detection="full")
    rp = rb = 0.0
    ra = dict.fromkeys(agents, 0.0)
    for _ in range(args.repeats):
        rp = max(rp, pymunk_rate(shaped, args.steps))
        rb = max(rb, pymunk_rate(bare, args.steps))
        for key, m in agents.items():
            ra[key] = max(ra[key], agent_rate(m, args.steps))
    out["pymunk"][n], out["bare"][n] = rp, rb
    print(f"N={n:>6}: pymunk with shapes  {rp:10.4g} seta-steps/s ({n / rp * 1e3:.3g} ms/step)")
    print(
        f"          bare engine (bodies only, no shapes) {rb:10.4g} seta-steps/s "
        f"({n / rb * 1e3:.3g} ms/step)"
    )
    for (k, det), r in ra.items():
        print(
            f"          agent[{k}, {det} detection] {r:10.4g} seta-steps/s "
            f"({n / r * 1e3:.3g} ms/step)  agent/pymunk-with-shapes {r / rp:.2f}  "
            f"agent/bare-engine {r / rb:.2f}"
        )
        if det == "lazy":
            out["agent"][(n, k)] = r
            out["ratio"][(n, k)], out["ratio_bare"][(n, k)] = r / rp, r / rb
        else:
            out["agent_full"] = {n: r}


def _crack_kinetics_section(n: int, args, out: dict) -> None:
    """Crack kinetics (``contact.crack_speed`` finite) against the elastic tip, same N,
    interleaved."""
    elastic = pressed_model(n)
    rate = pressed_model(n, overrides={"contact.crack_speed": 1.0})
    re = rr = 0.0
    for _ in range(args.repeats):
        re = max(re, agent_rate(elastic, args.steps))
        rr = max(rr, agent_rate(rate, args.steps))
    out["rate_dependent_cost"] = re / rr
    print(
        f"N={n:>6}: crack-kinetics tip {rr:10.4g} seta-steps/s, elastic {re:10.4g}: "
        f"cost per seta-step ×{re / rr:.2f}"
    )


def _dask_section(out: dict) -> None:
    try:
        from gecko_agents.sweep.benchmark import benchmark_dask_scaling

        d = benchmark_dask_scaling(n_points=8, work_s=0.5)
    except ImportError as err:
        print(f"sweep on Dask: skipped ({err})")
        return
    out["dask_speedup"] = d["speedup"]
    print(
        f"sweep on Dask, 8 CPU-bound points: 1 worker {d['t1_s']:.2f} s, 2 workers "
        f"{d['t2_s']:.2f} s; 2-worker/1-worker throughput {d['speedup']:.2f} "
        f"({os.cpu_count()} cores)"
    )


def main(argv=None) -> dict:
    """Run the benchmark and print its table; returns the numbers."""
    args = _arguments(argv)
    if args.docs and not os.access(os.path.dirname(os.path.abspath(args.docs)), os.W_OK):
        raise SystemExit(f"--docs {args.docs}: its folder does not exist or is not writable")
    if args.main_job:
        from gecko_agents.bench_main_job import main_job

        return main_job(args.quick, docs=args.docs)
    if args.work_precision:
        return work_precision(args.quick, docs=args.docs)
    default = Model(PAPER_ARRAY, n_sim=max(args.sizes)).kernel
    kernels = ["numpy"] + (["numba"] if numba_available() else [])
    out = {
        "sizes": args.sizes,
        "kernels": kernels,
        "default_kernel": default,
        "agent": {},
        "pymunk": {},
        "bare": {},
        "ratio": {},
        "ratio_bare": {},
    }
    if args.qs_setae:
        _quasistatic_section(args.qs_setae, out)
    for n in args.sizes:
        _engine_section(n, kernels, default, args, out)
    big = max(args.sizes)
    _crack_kinetics_section(big, args, out)
    if args.scaling:
        out["scaling"] = _scaling(args.scaling, args.run_max, args.steps, args.repeats)
    if not args.no_dask and not args.quick:
        _dask_section(out)
    print(f"agent/pymunk-with-shapes ratio at N={big}: {out['ratio'][(big, default)]:.2f}")
    ratio = out["ratio_bare"][(big, default)]
    print(f"agent/bare-engine ratio at N={big}: {ratio:.2f}")
    if not math.isfinite(ratio):
        raise RuntimeError("benchmark produced a non-finite ratio")
    return out


if __name__ == "__main__":
    from gecko_agents.console import WarningLog

    with WarningLog(1) as log:  # one line per validity item, as `gecko-agents bench` prints
        log.family("bench")
        main()
