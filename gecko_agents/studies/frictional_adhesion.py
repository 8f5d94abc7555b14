"""Frictional adhesion (beyond the paper): load–drag–pull of one seta, sphere and spatula tips.

As in Autumn et al.'s experiments (2006, J Exp Biol 209:3569), a seta (rod mechanics, θ = 60°,
flat floor) is pressed to a small preload, dragged a distance along the floor and pulled off at
an angle β from the floor (β = 0° pulls along +x, the direction the setae lean; 90° straight
up; 180° along −x). Dragging to −x pulls the seta back along its shaft ("gripping"); dragging to
+x pushes it over its tip ("releasing"). At the moment the tip lets go the normal (adhesion,
> 0 when the floor is pulled) and tangential (shear) forces are read: over pull angles they
trace the limit curve of adhesion against shear; the angle from the shear axis of the limit line
through the origin is the critical angle α* of the frictional-adhesion model (adhesion ≤
shear·tan α*, :func:`gecko_agents.analysis.limit_curve.critical_angle`).

Two tips: the JKR sphere (the paper's) and the spatula film (Kendall peel with pre-tension,
:class:`gecko_agents.contact.SpatulaTip`). With the paper's μ = 0.2 both slide long before they
peel, which hides any direction dependence; the scenario also runs a nearly bonded pad
(μ = 10) to show what the geometry alone gives. Nothing is tuned to the published numbers.

The anisotropy map (full runs, or ``--map`` with ``--quick`` for a small one) repeats the 90°
pull over drag distances of 0.25–2 × the seta's lean L cos θ, both ways, for θ = 55°, 60°, 75°:
the gripping/releasing pull-off ratio, the peel angle φ at the pull-off (the angle of the force
from the shear axis, which for a film under tension is its peel angle; for a gripping drag it
is α* read from that one pull) and the seta's lean after the drag (> 90°: flipped over
its tip). Nothing is tuned: it maps the model.

The runs are independent and go to ``--jobs`` worker processes (default 2, slowest first,
:func:`gecko_agents.sweep.workers.map_local`); the tables are the same as one process's.
Every run moves the plate at the package's quasi-static speed (``protocol.DEFAULT_SPEED``,
5·10⁻³ µm/µs). The full run repeats the 90° pulls of the spatula and the JKR sphere (μ = 10)
from 0.05 down to 0.0025 µm/µs, and the spatula's once without contact damping, to show the
pull-offs have converged (``--convergence`` with ``--quick``: 0.05 and 0.005 µm/µs only).

Outputs (``renders/frictional_adhesion/``): ``sweep.csv``, ``frictional_adhesion.png``
(adhesion vs shear at release, the style of Autumn 2006), ``anisotropy_map.csv``,
``anisotropy_map.png``, ``below_map.csv`` (θ = 30°–50°; these three in full runs or with
``--map``), ``patch.csv`` (the same load–drag–pull on a patch of setae on a rough floor),
``speed_convergence.csv`` (full runs or ``--convergence``), ``beyond_the_paper.md``,
``metadata.json``; ``--animate`` adds ``spatula_peel.gif``. A run removes the optional files
it does not write, so a folder never mixes a quick run's report with a full run's tables.

What is read off a run is defined once in :mod:`gecko_agents.analysis` (drag span, release point,
pull-off, let-go and lean after the drag, ratio, α*, plate-speed convergence); the figures and
the report's prose are in :mod:`gecko_agents.studies.frictional_adhesion_report`. The model's
validity warnings are not silenced.
"""

from __future__ import annotations

import itertools
import math
import os
import time

import numpy as np
from tqdm import tqdm

from gecko_agents import protocol, render
from gecko_agents.analysis.convergence import speed_convergence as converge
from gecko_agents.analysis.drag import drag_span, lean_after_drag, let_go_in_drag
from gecko_agents.analysis.limit_curve import critical_angle, force_angle
from gecko_agents.analysis.pull import pull_off, release_point
from gecko_agents.analysis.ratio import gripping_over_releasing
from gecko_agents.model import Model, Numerics
from gecko_agents.model.mass_damping import DEFAULT_DAMPING, Damping
from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.studies import frictional_adhesion_report as report
from gecko_agents.studies.common import (
    command_line,
    jobs_arg,
    output_dir,
    parse_args,
    write_json,
    write_table,
)
from gecko_agents.studies.frictional_adhesion_setup import (  # re-exported
    BASE,
    CONVERGENCE_SPEEDS,
    DRAG,
    NAME,
    PRELOAD,
    SPEED,
    TIPS,
)
from gecko_agents.sweep.workers import map_local


def config(quick: bool) -> dict:
    if quick:
        return {"angles": [90.0, 150.0], "tips": list(TIPS), "mus": [10.0], "drags": [-DRAG, DRAG]}
    return {
        "angles": [15.0, 30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0, 165.0],
        "tips": list(TIPS),
        "mus": [0.2, 10.0],
        "drags": [-DRAG, DRAG],
    }


def run_point(
    tip: str,
    mu: float,
    drag: float,
    beta: float,
    record: bool = False,
    speed: float = SPEED,
    damping: Damping = DEFAULT_DAMPING,
):
    """One load–drag–pull of the single seta at plate speed ``speed`` [µm/µs] with the model's
    damping ratios ``damping``: (row, history). The row has the forces at the release point
    (:func:`gecko_agents.analysis.pull.release_point`: the largest force held in tension in the
    pull), the pull-off (:func:`gecko_agents.analysis.pull.pull_off`), the force the press
    reached (its preload overshoot) and the run's peak kinetic / peak elastic energy."""
    params = BASE.replace(**TIPS[tip][0], **{"friction.mu": mu})
    prot = protocol.drag_pull(PRELOAD, drag, beta, speed=speed)
    model = Model(
        params, seed=1, record_setae=record, damping=damping, numerics=Numerics(record_every=1)
    )
    h = model.run(prot, progress=False)
    release = release_point(h, drag)
    start, _ = drag_span(h, drag)
    row = {
        "tip": tip,
        "mu": mu,
        "drag_um": drag,
        "pull_angle_deg": beta,
        "adhesion_at_release_uN": release.adhesion,
        "shear_at_release_uN": release.shear,
        "pull_off_uN": pull_off(h, drag).adhesion,
        "pressed_to_uN": float(h["force_normal_uN"][: start + 1].max()),
        "max_kinetic_to_elastic": h.meta.get("max_kinetic_to_elastic"),
    }
    return row, h


CONVERGENCE_TIPS = ("spatula", "sphere")  # the tips of the plate-speed check, μ = 10


def point_row(*args) -> dict:
    """The row of :func:`run_point` (same arguments) without its history."""
    return run_point(*args)[0]


def _convergence_cases(speeds) -> list[tuple]:
    undamped = Damping(seta=DEFAULT_DAMPING.seta, normal=0.0, tangential=0.0)
    cases = [(tip, v, DEFAULT_DAMPING) for tip in CONVERGENCE_TIPS for v in speeds]
    return cases + [("spatula", speeds[0], undamped)]


def convergence_tasks(speeds=CONVERGENCE_SPEEDS) -> list[tuple]:
    """The runs of :func:`speed_convergence`: (function, arguments) pairs, both drags per case."""
    return [
        (point_row, (tip, 10.0, d, 90.0, False, v, damping))
        for tip, v, damping in _convergence_cases(speeds)
        for d in (-DRAG, DRAG)
    ]


def speed_convergence(speeds=CONVERGENCE_SPEEDS, results=None) -> list[dict]:
    """The 90° pull-off of a seta at μ = 10 after both drags, per tip (spatula, JKR sphere) and
    plate speed [µm/µs]: one row per tip and speed with both pull-offs [µN], their ratio, the
    force the press reached [µN] and the peak kinetic/elastic energy ratios; then the spatula
    once more at the fastest speed without contact damping (normal and tangential ratios 0,
    :class:`gecko_agents.model.mass_damping.Damping`). A quasi-static result must not depend on the
    speed; a dashpot's force ∝ v vanishes as the plate slows. ``results``: the rows of
    :func:`convergence_tasks`, already run (None: run them here)."""
    if results is None:
        results = [fn(*args) for fn, args in convergence_tasks(speeds)]
    rows = []
    for (tip, v, damping), grip, rel in zip(
        _convergence_cases(speeds), results[::2], results[1::2], strict=True
    ):
        rows.append(
            {
                "tip": tip,
                "speed_um_per_us": v,
                "contact_damping": damping is DEFAULT_DAMPING,
                "gripping_uN": grip["pull_off_uN"],
                "releasing_uN": rel["pull_off_uN"],
                "gripping_over_releasing": gripping_over_releasing(
                    grip["pull_off_uN"], rel["pull_off_uN"]
                ),
                "pressed_to_uN": grip["pressed_to_uN"],
                "max_kinetic_to_elastic_gripping": grip["max_kinetic_to_elastic"],
                "max_kinetic_to_elastic_releasing": rel["max_kinetic_to_elastic"],
            }
        )
    return rows


DASHPOT_SHARE = 0.25
"""The speed dependence is the contact dashpots' when the undamped run at the fastest speed is
closer to the slowest damped run than this fraction of the damped runs' own change."""


def convergence_summary(rows: list[dict]) -> dict:
    """The numbers of the plate-speed check (rows of :func:`speed_convergence`).

    Returns
    -------
    dict with ``releasing`` and ``gripping``: the spatula's damped pull-offs against the speed,
    :func:`gecko_agents.analysis.convergence.speed_convergence` as a dict (speeds [µm/µs],
    slopes [µN per µm/µs], ``first_order``, observed ``order``, Richardson ``limit`` [µN],
    relative ``change`` fastest/slowest − 1); ``undamped``: the undamped row with its ``gap``
    (releasing pull-off over the slowest damped one − 1) and ``dashpot_dominated`` (|gap| <
    :data:`DASHPOT_SHARE` × |change|), or None; ``sphere_range``: the JKR sphere's smallest and
    largest pull-off [µN], or None.
    """
    damped = [r for r in rows if r["tip"] == "spatula" and r["contact_damping"]]
    speeds = [r["speed_um_per_us"] for r in damped]
    out = {}
    for way in ("releasing", "gripping"):
        conv = converge(speeds, [r[f"{way}_uN"] for r in damped])
        out[way] = {**conv.__dict__, "slopes": [float(x) for x in conv.slopes]}
    off = next((r for r in rows if not r["contact_damping"]), None)
    out["undamped"] = None
    if off is not None:
        gap = off["releasing_uN"] / damped[-1]["releasing_uN"] - 1.0
        dominated = abs(gap) < DASHPOT_SHARE * abs(out["releasing"]["change"])
        out["undamped"] = {**off, "gap": gap, "dashpot_dominated": dominated}
    spheres = [r[k] for r in rows if r["tip"] == "sphere" for k in ("gripping_uN", "releasing_uN")]
    out["sphere_range"] = (min(spheres), max(spheres)) if spheres else None
    return out


MAP_CASES = (("spatula", 10.0), ("spatula", 0.2), ("sphere", 10.0), ("sphere_sb", 10.0))
MAP_FACTORS = (0.25, 0.5, 1.0, 1.5, 2.0)  # drag / lean


PATCH_TIPS = ("spatula", "sphere_sb", "sphere")


def patch_config(quick: bool) -> dict:
    """The patch: setae N [-], floor RMS heights σ [µm] (each seta its own pad, eq 28), tips."""
    if quick:
        return {"count": 4, "sigmas": [1.0], "tips": ["spatula"]}
    return {"count": 16, "sigmas": [0.3, 1.0], "tips": list(PATCH_TIPS)}


def patch_point(tip: str, sigma: float, count: int, sign: int) -> dict:
    """A patch of ``count`` setae on a rough floor, pressed to ``count`` × the preload, dragged
    ``sign`` × DRAG (−1 gripping) and pulled at 90°: pull-off per seta [µN]."""
    params = BASE.replace(
        **TIPS[tip][0],
        **{
            "friction.mu": 10.0,
            "array.count": count,
            "floor.sigma": sigma,
            "floor.correlation_length": 0.0,
        },
    )
    drag = sign * DRAG
    prot = protocol.drag_pull(PRELOAD * count, drag, 90.0, speed=SPEED)
    h = Model(params, seed=1, numerics=Numerics(record_every=1)).run(prot, progress=False)
    held = pull_off(h, drag)
    return {
        "tip": tip,
        "sigma_um": sigma,
        "count": count,
        "direction": "gripping" if sign < 0 else "releasing",
        "drag_um": drag,
        "attached_after_drag": int(h["n_attached"][drag_span(h, drag)[1]]),
        "pull_off_per_seta_uN": held.adhesion / count,
    }


def patch_tasks(pcfg: dict) -> list[tuple]:
    """The runs of the patch (:func:`patch_point`): (function, arguments) pairs."""
    return [
        (patch_point, (tip, sigma, pcfg["count"], sign))
        for tip in pcfg["tips"]
        for sigma in pcfg["sigmas"]
        for sign in (-1, 1)
    ]


def sweep_tasks(cfg: dict) -> list[tuple]:
    """The runs of the pull-angle sweep (:func:`point_row`): (function, arguments) pairs."""
    points = itertools.product(cfg["tips"], cfg["mus"], cfg["drags"], cfg["angles"])
    return [(point_row, pt) for pt in points]


def _run_task(fn, args):
    return fn(*args)


def map_config(quick: bool) -> dict:
    """The anisotropy map: (tip, μ) cases, seta angles θ [deg] and drags in units of the lean."""
    if quick:
        return {"cases": [("spatula", 10.0)], "thetas": [60.0], "factors": [0.5, 1.5]}
    return {"cases": list(MAP_CASES), "thetas": [55.0, 60.0, 75.0], "factors": list(MAP_FACTORS)}


def map_point(tip: str, mu: float, theta: float, factor: float, sign: int) -> dict:
    """One 90° pull after a drag of ``sign``·``factor`` × the lean L cos θ (−1 gripping)."""
    lean = BASE.seta.L * math.cos(math.radians(theta))
    drag = sign * factor * lean
    params = BASE.replace(**TIPS[tip][0], **{"friction.mu": mu, "seta.theta_deg": theta})
    prot = protocol.drag_pull(PRELOAD, drag, 90.0, speed=SPEED)
    h = Model(params, seed=1, record_setae=True, numerics=Numerics(record_every=1)).run(
        prot, progress=False
    )
    held = pull_off(h, drag)
    adhesion, shear = held.adhesion, held.shear
    return {
        "tip": tip,
        "mu": mu,
        "theta_deg": theta,
        "drag_over_lean": factor,
        "direction": "gripping" if sign < 0 else "releasing",
        "drag_um": drag,
        "let_go_in_drag_at_um": let_go_in_drag(h, drag),
        "attached_after_drag": int(h["n_attached"][drag_span(h, drag)[1]]),
        "lean_after_drag_deg": lean_after_drag(h, drag),
        "pull_off_uN": adhesion,
        "shear_at_pull_off_uN": shear,
        "peel_angle_at_pull_off_deg": force_angle(adhesion, shear),
    }


def map_tasks(mcfg: dict) -> list[tuple]:
    """The runs of :func:`anisotropy_map`: (function, arguments), gripping then releasing."""
    grid = itertools.product(mcfg["cases"], mcfg["thetas"], mcfg["factors"], (-1, 1))
    return [(map_point, (tip, mu, theta, factor, sign)) for (tip, mu), theta, factor, sign in grid]


def anisotropy_map(mcfg: dict, results=None) -> list[dict]:
    """Per case, θ and drag/lean: both drags' runs and the gripping/releasing pull-off ratio.
    ``results``: the rows of :func:`map_tasks`, already run (None: run them here)."""
    if results is None:
        results = [fn(*args) for fn, args in map_tasks(mcfg)]
    rows = []
    for grip, rel in zip(results[::2], results[1::2], strict=True):
        ratio = gripping_over_releasing(grip["pull_off_uN"], rel["pull_off_uN"])
        rows += [
            {**grip, "gripping_over_releasing": ratio},
            {**rel, "gripping_over_releasing": ratio},
        ]
    return rows


def summarise(rows: list[dict], cfg: dict) -> dict:
    """Per tip and μ: gripping/releasing ratio of the pull-off at β = 90°, and α* of the
    gripping limit curve (:func:`gecko_agents.analysis.limit_curve.critical_angle`)."""
    out = {}
    for tip in cfg["tips"]:
        for mu in cfg["mus"]:
            sel = [r for r in rows if r["tip"] == tip and r["mu"] == mu]
            at90 = {r["drag_um"]: r for r in sel if r["pull_angle_deg"] == 90}
            grip, rel = (at90[d]["pull_off_uN"] if d in at90 else math.nan for d in (-DRAG, DRAG))
            shear = at90[-DRAG]["shear_at_release_uN"] if -DRAG in at90 else math.nan
            g = [r for r in sel if r["drag_um"] < 0]
            out[f"{TIPS[tip][1]}, mu={mu:g}"] = {
                "gripping_uN": grip,
                "releasing_uN": rel,
                "gripping_shear_at_release_uN": shear,
                "gripping_over_releasing_at_90deg": gripping_over_releasing(grip, rel),
                "critical_angle_deg": critical_angle(
                    [r["shear_at_release_uN"] for r in g], [r["adhesion_at_release_uN"] for r in g]
                ),
            }
    return out


BELOW_MAP_THETAS = (30.0, 45.0, 50.0)  # seta angles [deg] below the map's


def _below_map_cases(quick: bool) -> list[tuple]:
    thetas, mus = ((45.0,), (10.0,)) if quick else (BELOW_MAP_THETAS, (10.0, 0.2))
    return [(mu, theta) for mu in mus for theta in thetas]


def below_map_tasks(quick: bool) -> list[tuple]:
    """The runs of :func:`below_map`: (function, arguments), gripping then releasing."""
    return [
        (map_point, ("spatula", mu, theta, 1.0, sign))
        for mu, theta in _below_map_cases(quick)
        for sign in (-1, 1)
    ]


def below_map(quick: bool, results=None) -> list[dict]:
    """Flatter setae than the map's: the spatula at μ = 10 and 0.2, θ = 30°, 45°, 50°, a drag
    of one lean either way and a 90° pull (:func:`map_point` rows, with the ratio).
    ``results``: the rows of :func:`below_map_tasks`, already run (None: run them here)."""
    if results is None:
        results = [fn(*args) for fn, args in below_map_tasks(quick)]
    rows = []
    for (mu, theta), grip, rel in zip(
        _below_map_cases(quick), results[::2], results[1::2], strict=True
    ):
        ratio = gripping_over_releasing(grip["pull_off_uN"], rel["pull_off_uN"])
        rows.append(
            {
                "mu": mu,
                "theta_deg": theta,
                "ratio": ratio,
                "lean_gripping_deg": grip["lean_after_drag_deg"],
                "lean_releasing_deg": rel["lean_after_drag_deg"],
                "gripping_uN": grip["pull_off_uN"],
                "releasing_uN": rel["pull_off_uN"],
            }
        )
    return rows


def _extra_args(p) -> None:
    p.add_argument(
        "--animate", action="store_true", help="also write spatula_peel.gif (gripping, 30°)"
    )
    p.add_argument(
        "--map", action="store_true", help="with --quick: a small anisotropy map too (full: always)"
    )
    p.add_argument(
        "--jobs",
        type=jobs_arg,
        default=min(2, os.cpu_count() or 1),
        help="runs at once in separate processes (default 2; 1 runs them in this process)",
    )
    p.add_argument(
        "--convergence",
        action="store_true",
        help="with --quick: the plate-speed check at two speeds too (full: always)",
    )


def _plan(args, out) -> dict:
    """The run's parts (the slowest first, so that the workers finish together), their
    configurations, and the removal of an earlier run's optional files this run won't write."""
    with_map = args.map or not args.quick
    with_convergence = args.convergence or not args.quick
    optional = {
        "anisotropy_map.csv": with_map,
        "anisotropy_map.png": with_map,
        "below_map.csv": with_map,
        "speed_convergence.csv": with_convergence,
        "spatula_peel.gif": args.animate,
    }
    for name in (n for n, written in optional.items() if not written):
        (out / name).unlink(missing_ok=True)  # an earlier run's, which this report won't describe
    cfg = config(args.quick)
    mcfg = map_config(args.quick) if with_map else None
    pcfg = patch_config(args.quick)
    speeds = CONVERGENCE_SPEEDS if not args.quick else CONVERGENCE_SPEEDS[::3]
    sections = {
        "convergence": convergence_tasks(speeds) if with_convergence else [],
        "map": map_tasks(mcfg) if with_map else [],
        "patch": patch_tasks(pcfg),
        "sweep": sweep_tasks(cfg),
        "below": below_map_tasks(args.quick) if with_map else [],
    }
    return {"cfg": cfg, "mcfg": mcfg, "pcfg": pcfg, "speeds": speeds, "sections": sections}


def _tables(args, out, plan: dict, results: dict) -> dict:
    """Write the tables, figures and report of the finished runs; their rows and summaries."""
    cfg, mcfg = plan["cfg"], plan["mcfg"]
    rows = results["sweep"]
    write_table(out / "sweep.csv", rows)
    report.draw(rows, cfg, out)
    summary = summarise(rows, cfg)
    map_rows, below_rows, conv_rows, conv = [], [], [], None
    if results["map"]:
        map_rows = anisotropy_map(mcfg, results["map"])
        write_table(out / "anisotropy_map.csv", map_rows)
        report.draw_map(map_rows, mcfg, out)
        below_rows = below_map(args.quick, results["below"])
        write_table(out / "below_map.csv", below_rows)
    if results["convergence"]:
        conv_rows = speed_convergence(plan["speeds"], results["convergence"])
        write_table(out / "speed_convergence.csv", conv_rows)
        conv = convergence_summary(conv_rows)
    patch_rows = results["patch"]
    write_table(out / "patch.csv", patch_rows)
    text = report.report_text(
        summary, args.quick, map_rows, below_rows, patch_rows, conv_rows, conv
    )
    atomic_write_bytes(out / "beyond_the_paper.md", text.encode())
    return {
        "summary": summary,
        "map": map_rows,
        "below": below_rows,
        "conv_rows": conv_rows,
        "conv": conv,
    }


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv, extra=_extra_args)
    if args.jobs < 1:
        raise SystemExit(f"--jobs = {args.jobs} must be ≥ 1")
    out = output_dir(NAME, args)
    t0 = time.perf_counter()
    plan = _plan(args, out)
    sections = plan["sections"]
    tasks = [task for part in sections.values() for task in part]
    with tqdm(total=len(tasks), desc="load–drag–pull", disable=args.no_progress) as bar:
        done = map_local(_run_task, tasks, args.jobs, bar.update)
    parts = {}
    for name, part in sections.items():
        parts[name], done = done[: len(part)], done[len(part) :]
    t = _tables(args, out, plan, parts)
    if args.animate:
        _, h = run_point("spatula", plan["cfg"]["mus"][-1], -DRAG, 30.0, record=True)
        h.save(out / "animated_run")
        render.animate(h, out / "spatula_peel.gif")
    results = {
        "summary": t["summary"],
        "runtime_s": time.perf_counter() - t0,
        "jobs": args.jobs,
        "speed_convergence": t["conv"],
        "claims": [],
    }
    if t["map"]:
        ratios = [r["gripping_over_releasing"] for r in t["map"]]
        results["map_ratio_range"] = [float(np.nanmin(ratios)), float(np.nanmax(ratios))]
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "params": BASE.to_dict(),
            "config": plan["cfg"],
            "preload_uN": PRELOAD,
            "drag_um": DRAG,
            "speed_um_per_us": SPEED,
            "seed": 1,
            "map_config": plan["mcfg"],
            "patch_config": plan["pcfg"],
            "below_map": t["below"],
            "speed_convergence": t["conv_rows"],
            "results": results,
        },
    )
    print(
        f"{NAME}: "
        + "; ".join(
            f"{k}: α* {v['critical_angle_deg']:.0f}°, grip/release ×"
            f"{v['gripping_over_releasing_at_90deg']:.2f}"
            for k, v in t["summary"].items()
        )
        + ("; map ratio ×{:.2f}–×{:.2f}".format(*results["map_ratio_range"]) if t["map"] else "")
        + f"; {results['runtime_s']:.0f} s → {out}"
    )
    return results


if __name__ == "__main__":
    main()
