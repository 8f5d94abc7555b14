"""Frictional adhesion (beyond the paper): load–drag–pull of one seta, sphere and spatula tips.

As in Autumn et al.'s experiments (2006, J Exp Biol 209:3569), a seta (rod mechanics, θ = 60°,
flat floor) is pressed to a small preload, dragged a distance along the floor and pulled off at
an angle β from the floor (β = 0° pulls along +x, the direction the setae lean; 90° straight
up; 180° along −x). Dragging to −x pulls the seta back along its shaft ("gripping"); dragging to
+x pushes it over its tip ("releasing"). At the moment the tip lets go the normal (adhesion,
> 0 when the floor is pulled) and tangential (shear) forces are read: over pull angles they
trace the limit curve of adhesion against shear; the angle from the shear axis of the limit line
through the origin is the critical angle α* of the frictional-adhesion model (adhesion ≤
shear·tan α*, :func:`gecko_agents.limit_curve.critical_angle`).

Two tips: the JKR sphere (the paper's) and the spatula film (Kendall peel with pre-tension,
:class:`gecko_agents.contact.SpatulaTip`). With the paper's μ = 0.2 both slide long before they
peel, which hides any direction dependence; the scenario also runs a nearly bonded pad
(μ = 10) to show what the geometry alone gives. Nothing is tuned to the published numbers.

Outputs (``renders/frictional_adhesion/``): ``sweep.csv``, ``frictional_adhesion.png``
(adhesion vs shear at release, the style of Autumn 2006), ``beyond_the_paper.md``,
``metadata.json``; ``--animate`` adds ``spatula_peel.gif``.
"""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from _common import output_dir, parse_args, write_json, write_table

from gecko_agents import protocol, render
from gecko_agents.history import atomic_write_bytes
from gecko_agents.limit_curve import critical_angle
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY

NAME = "frictional_adhesion"
BASE = PAPER_ARRAY.replace(**{"mechanics": "rod", "floor.sigma": 0.0, "array.count": 1})
PRELOAD = 0.2  # µN: a rod seta with a spatula folds flat under 1 µN at μ = 0.2
DRAG = 8.0  # µm
SPEED = 0.05  # µm/µs


def config(quick: bool) -> dict:
    if quick:
        return {"angles": [90.0, 150.0], "tips": ["sphere", "spatula"], "mus": [10.0],
                "drags": [-DRAG, DRAG]}  # fmt: skip
    return {"angles": [15.0, 30.0, 45.0, 60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0, 165.0],
            "tips": ["sphere", "spatula"], "mus": [0.2, 10.0], "drags": [-DRAG, DRAG]}  # fmt: skip


def release_forces(h, drag: float) -> tuple[float, float, float]:
    """(adhesion, shear, pull-off) [µN] of the pull phase (the rows after the drag): adhesion
    = −normal force (> 0 in tension) and shear = tangential force on the tips at the step of
    the largest force the seta held in the pull, the limit it withstood (a film's last steps,
    its pad nearly peeled and its friction gone with it, are a 90° peel of a sliver whatever
    the pull); pull-off = the largest adhesion of the pull phase."""
    px = h["plate_x_um"]
    k0 = int(np.flatnonzero(np.abs(px - (px[0] + drag)) < 1e-6)[0]) if drag else 0
    normal, shear = -h["force_normal_uN"][k0:], h["force_tangential_uN"][k0:]
    k = int(np.argmax(np.hypot(normal, shear)))
    return float(normal[k]), float(shear[k]), float(max(0.0, normal.max()))


def run_point(tip: str, mu: float, drag: float, beta: float, record: bool = False):
    params = BASE.replace(**{"tip": tip, "friction.mu": mu})
    prot = protocol.drag_pull(PRELOAD, drag, beta, speed=SPEED)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity diagnostics are in the histories' metadata
        h = Model(params, seed=1, record_setae=record, record_every=1).run(prot, progress=False)
    adhesion, shear, pull_off = release_forces(h, drag)
    row = {"tip": tip, "mu": mu, "drag_um": drag, "pull_angle_deg": beta,
           "adhesion_at_release_uN": adhesion, "shear_at_release_uN": shear,
           "pull_off_uN": pull_off}  # fmt: skip
    return row, h


def summarise(rows: list[dict], cfg: dict) -> dict:
    """Per tip and μ: gripping/releasing ratio of the pull-off at β = 90°, and α* of the
    gripping limit curve (:func:`gecko_agents.limit_curve.critical_angle`)."""
    out = {}
    for tip in cfg["tips"]:
        for mu in cfg["mus"]:
            sel = [r for r in rows if r["tip"] == tip and r["mu"] == mu]
            at90 = {r["drag_um"]: r["pull_off_uN"] for r in sel if r["pull_angle_deg"] == 90}
            grip, rel = at90.get(-DRAG, math.nan), at90.get(DRAG, math.nan)
            g = [r for r in sel if r["drag_um"] < 0]
            out[f"{tip}, mu={mu:g}"] = {
                "gripping_uN": grip,
                "releasing_uN": rel,
                "gripping_over_releasing_at_90deg": grip / rel if rel > 0 else math.nan,
                "critical_angle_deg": critical_angle(
                    [r["shear_at_release_uN"] for r in g], [r["adhesion_at_release_uN"] for r in g]
                ),
            }
    return out


def draw(rows: list[dict], cfg: dict, out) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(6.4 * len(cfg["mus"]), 4.6), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, len(cfg["mus"])))
        styles = {
            ("sphere", -DRAG): ("o-", "#1f77b4"),
            ("sphere", DRAG): ("o--", "#9ecae1"),
            ("spatula", -DRAG): ("s-", "#d62728"),
            ("spatula", DRAG): ("s--", "#fc9272"),
        }
        for ax, mu in zip(axes, cfg["mus"], strict=True):
            for (tip, drag), (st, c) in styles.items():
                sel = [r for r in rows if r["tip"] == tip and r["mu"] == mu
                       and r["drag_um"] == drag]  # fmt: skip
                if not sel:
                    continue
                way = "gripping (−x)" if drag < 0 else "releasing (+x)"
                ax.plot([r["shear_at_release_uN"] for r in sel],
                        [r["adhesion_at_release_uN"] for r in sel], st, color=c,
                        label=f"{tip}, dragged {way}")  # fmt: skip
            ax.axhline(0.0, color="0.6", lw=0.8)
            ax.set_xlabel("shear force at release [µN] (+x)")
            ax.set_ylabel("adhesion (normal) force at release [µN]")
            ax.set_title(f"μ = {mu:g}: release forces over pull angles")
            render.apply_style(ax)
            ax.legend(fontsize=7)
        render.save_figure(fig, out / f"{NAME}.png")


def beyond_the_paper(summary: dict, quick: bool) -> str:
    """The "beyond the paper" rows: this model beside published values, with sources."""
    lines = [
        "## Beyond the paper: frictional adhesion",
        "",
        f"Single rod seta (θ = 60°, L = 20 µm), preload {PRELOAD} µN, drag {DRAG:g} µm, "
        f"pulled at {SPEED} µm/µs; {'--quick run' if quick else 'full run'} of "
        "`scenarios/frictional_adhesion.py`. Pull-off = largest adhesion in the pull; α* = the "
        "limit line through the origin of the gripping releases (Autumn et al. 2006's "
        "F⊥ ≤ F∥·tan α*).",
        "",
        "| quantity | this model | published | source |",
        "|---|---|---|---|",
    ]
    for key, s in summary.items():
        lines.append(
            f"| α* ({key}) | {s['critical_angle_deg']:.0f}° | ≈25–30° for setae, arrays and "
            "toes (the figure the issue quotes; the abstract we could read gives none) | Autumn "
            "et al. 2006, J Exp Biol 209:3569 |"
        )
        lines.append(
            f"| gripping/releasing pull-off at 90° ({key}) | "
            f"×{s['gripping_over_releasing_at_90deg']:.2f} ({s['gripping_uN']:.2f} / "
            f"{s['releasing_uN']:.2f} µN) | large adhesion only after a preload and a drag in "
            "the gripping direction; angled mushroom fibres 10× | Autumn et al. 2000, Nature "
            "405:681; Geikowsky, Gorumlu & Aksak 2018, Beilstein J Nanotechnol 9 |"
        )
    lines += [
        "",
        "Why they differ: in this model a gripping drag pre-stretches the spatula's pad "
        "(partial slip, Chen–Wu–Gao pre-tension), which raises its pull-off, but both "
        "drags end with the seta still leaning the same way (an 8 µm drag against a 10 µm "
        "lean), so both films peel with the force pointing back along the shaft at 40–65°, "
        "never over their pads; the rod's tip follows its force, so α* is the shaft's own "
        "angle after the drag, not a property of the tip. A sphere tip has no orientation to "
        "lose and shows almost none. With the paper's μ = 0.2 the pad's friction "
        "(2μw·b·ℓ/ℓ0 ≈ 0.2 µN) is below the peel forces: the pad slides under the tip, "
        "caps the pre-tension and the difference shrinks. Nothing is tuned to the published "
        "numbers.",
        "",
    ]
    return "\n".join(lines)


def main(argv=None) -> dict:
    args = parse_args(
        __doc__, argv,
        extra=lambda p: p.add_argument("--animate", action="store_true",
                                       help="also write spatula_peel.gif (gripping, 30°)"),
    )  # fmt: skip
    out = output_dir(NAME, args)
    cfg = config(args.quick)
    t0 = time.perf_counter()
    rows = []
    for tip in cfg["tips"]:
        for mu in cfg["mus"]:
            for drag in cfg["drags"]:
                for beta in cfg["angles"]:
                    rows.append(run_point(tip, mu, drag, beta)[0])
    write_table(out / "sweep.csv", rows)
    draw(rows, cfg, out)
    summary = summarise(rows, cfg)
    atomic_write_bytes(out / "beyond_the_paper.md", beyond_the_paper(summary, args.quick).encode())
    if args.animate:
        _, h = run_point("spatula", cfg["mus"][-1], -DRAG, 30.0, record=True)
        h.save(out / "animated_run")
        render.animate(h, out / "spatula_peel.gif")
    results = {"summary": summary, "runtime_s": time.perf_counter() - t0, "claims": []}
    write_json(out / "metadata.json", {
        "scenario": NAME, "quick": args.quick, "params": BASE.to_dict(), "config": cfg,
        "preload_uN": PRELOAD, "drag_um": DRAG, "speed_um_per_us": SPEED, "seed": 1,
        "results": results,
    })  # fmt: skip
    print(f"{NAME}: " + "; ".join(
        f"{k}: α* {v['critical_angle_deg']:.0f}°, grip/release ×"
        f"{v['gripping_over_releasing_at_90deg']:.2f}" for k, v in summary.items())
        + f"; {results['runtime_s']:.0f} s → {out}")  # fmt: skip
    return results


if __name__ == "__main__":
    main()
