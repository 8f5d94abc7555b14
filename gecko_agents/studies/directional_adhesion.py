"""Directional adhesion (beyond the paper): drag the pressed array along or against the seta
tilt, then pull off at an angle; peak pull-off force vs pull angle.

Geckos stick when their setae are dragged towards their tips and let go when pushed back. Here
a patch of setae (θ = 60°, rod mechanics so that large swings stay physical) is pressed to a
preload, dragged by ±drag along x (+x is the direction the setae lean towards), and pulled off
along angles from 30° to 150° (90° = straight up). Per run, after the drag
(:mod:`gecko_agents.analysis.pull`): the peak normal pull-off (the largest adhesion of the pull)
and the peak total pull, the magnitude of the contact force (normal and tangential) at the
release point, the largest force held in tension (0 if the pull never reached tension).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gecko_agents import protocol
from gecko_agents.analysis.pull import pull_off, release_point
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.render import plot_force_curves, save_figure
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

PRELOAD_PER_SETA = 1.0  # µN
DRAG = 4.0  # µm


@dataclass(frozen=True)
class Plan:
    """The sweep: setae simulated, drag length [µm], pull angles [°], drags [µm], plate
    speed [µm/µs]."""

    n_sim: int
    drag_len: float
    angles: list
    drags: list
    speed: float


def plan_for(quick: bool) -> Plan:
    """The full sweep, or a seconds-long one for ``--quick``."""
    drag_len = 1.0 if quick else DRAG
    return Plan(
        n_sim=2 if quick else 12,
        drag_len=drag_len,
        angles=[60.0, 120.0] if quick else [30.0, 60.0, 90.0, 120.0, 150.0],
        drags=[drag_len, -drag_len] if quick else [drag_len, 0.0, -drag_len],
        speed=0.1 if quick else 0.01,
    )


def run_one(params, plan: Plan, drag: float, angle: float, args, out) -> dict:
    """Press the setae to the preload, drag by ``drag`` [µm], pull off at ``angle`` [°]; one
    sweep row (per-seta peaks [µN]). With ``--animate`` the first pull-off angle after a drag
    along the tilt also saves its run and detachment.gif."""
    n_sim, speed = plan.n_sim, plan.speed
    record = args.animate and drag > 0 and angle == plan.angles[0]
    m = Model(params, n_sim=n_sim, seed=7, record_setae=record)
    prot = protocol.drag_pull(PRELOAD_PER_SETA * n_sim, drag, angle, speed=speed)
    h = m.run(prot, progress=not args.no_progress)
    if record:
        from gecko_agents.render import animate

        h.save(out / "animated_run")
        animate(h, out / "detachment.gif")
    release = release_point(h, drag)
    normal = pull_off(h, drag).adhesion
    total = release.force if release.in_tension else 0.0
    return {
        "drag_um": drag,
        "pull_angle_deg": angle,
        "n_sim": n_sim,
        "peak_normal_pull_off_uN_per_seta": normal / n_sim,
        "peak_total_pull_uN_per_seta": total / n_sim,
        "n_detachments": len(h.detachments["seta"]),
    }


def draw(rows: list[dict], drags: list, drag_len: float, pull_off_force: float, out) -> None:
    """directional_adhesion.png: peak pull per seta against pull angle, one curve per drag,
    with the single-tip pull-off Fc [µN] for scale."""
    curves = []
    for drag in drags:
        sel = [r for r in rows if r["drag_um"] == drag]
        label = {
            drag_len: f"dragged +{drag_len:g} µm (along the tilt)",
            0.0: "no drag",
            -drag_len: f"dragged −{drag_len:g} µm (against the tilt)",
        }[drag]
        curves.append(
            {
                "x": [r["pull_angle_deg"] for r in sel],
                "y": [r["peak_total_pull_uN_per_seta"] for r in sel],
                "label": label,
                "style": {"marker": "o"},
            }
        )
    fig = plot_force_curves(
        curves,
        None,
        xlabel="pull angle from +x [°] (90 = straight up)",
        ylabel="peak pull-off per seta [µN]",
        title="Directional adhesion: drag then pull (rod setae, θ = 60°)",
    )
    fig.axes[0].axhline(pull_off_force, color="0.5", ls=":", label="Fc")
    fig.axes[0].legend(fontsize=8)
    save_figure(fig, out / "directional_adhesion.png")


@command_line
def main(argv=None) -> dict:
    args = parse_args(
        __doc__,
        argv,
        extra=lambda p: p.add_argument(
            "--animate", action="store_true", help="also write detachment.gif (drag along, 60°)"
        ),
    )
    out = output_dir("directional_adhesion", args)
    params = PAPER_ARRAY.replace(**{"mechanics": "rod", "floor.sigma": 0.5})
    plan = plan_for(args.quick)
    rows = [run_one(params, plan, d, a, args, out) for d in plan.drags for a in plan.angles]
    write_table(out / "sweep.csv", rows)
    draw(rows, plan.drags, plan.drag_len, params.contact.pull_off_force, out)
    along = [r["peak_total_pull_uN_per_seta"] for r in rows if r["drag_um"] > 0]
    against = [r["peak_total_pull_uN_per_seta"] for r in rows if r["drag_um"] < 0]
    results = {
        "mean_pull_along_uN": float(np.mean(along)),
        "mean_pull_against_uN": float(np.mean(against)),
        "claims": [],
    }
    write_json(
        out / "metadata.json",
        {
            "params": params.to_dict(),
            "n_sim": plan.n_sim,
            "preload_per_seta_uN": PRELOAD_PER_SETA,
            "drag_um": plan.drag_len,
            "speed_um_per_us": plan.speed,
            "results": results,
        },
    )
    return results


if __name__ == "__main__":
    main()
