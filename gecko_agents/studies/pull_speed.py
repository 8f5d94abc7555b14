"""Pull-off against pull speed (beyond the paper): the elastic JKR tip and crack kinetics.

Polyurethane is viscoelastic: the edge of a contact that is pulled apart moves at a finite
speed, G − w = w·(|ȧ|/v*)^n (Maugis & Barquins 1978), so a faster pull holds more and
dissipates more. A single seta and a patch of setae (rod mechanics, θ = 60°, a stubby 5 µm
seta so that slow pulls stay short; σ = 0.3 µm pad floor for the patch) are pressed 0.3 µm
at 0.05 µm/µs and pulled off straight up at speeds over three decades, for the elastic tip
(v* = ∞) and two reference crack speeds v*, n = 0.5 (Greenwood & Johnson 1981).

Also plotted: the energy one press-and-pull cycle dissipates per seta (damping, friction,
snap-offs and, with crack kinetics, the crack's own work ∫(G − w)·2πa·|da|). At the fastest
speed the elastic curve itself moves: the seta no longer follows the plate quasi-statically
(inertia; hollow markers: peak kinetic energy above 10 % of the peak elastic energy — at
1 µm/µs a 40-seta patch is thrown off the floor and holds almost nothing), which is the
reference the rate effect is measured against.

Outputs (``renders/pull_speed/``): ``sweep.csv``, ``pull_speed.png``, ``metadata.json``.
"""

from __future__ import annotations

import math
import time

from gecko_agents import protocol, render
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "pull_speed"
BASE = PAPER_ARRAY.replace(**{"mechanics": "rod", "seta.L": 5.0, "floor.sigma": 0.3})
DEPTH, PRESS_SPEED = 0.3, 0.05  # µm, µm/µs
KE_QUASI_STATIC = 0.1  # above this peak kinetic/elastic energy a run is marked not quasi-static


def config(quick: bool) -> dict:
    if quick:
        return {"speeds": [1e-2, 1e-1], "crack_speeds": [math.inf, 1.0], "patch": 3}
    return {"speeds": [1e-3, 1e-2, 1e-1, 1.0], "crack_speeds": [math.inf, 1.0, 0.1], "patch": 40}


def run_point(v_star: float, speed: float, n_sim: int, progress: bool) -> dict:
    """One press and pull-off; peak pull-off and dissipated energy per seta."""
    params = BASE.replace(**{"contact.crack_speed": v_star})
    prot = [protocol.PressTo(DEPTH, PRESS_SPEED), protocol.PullOff(speed)]
    t0 = time.perf_counter()
    h = Model(params, n_sim=n_sim, seed=1).run(prot, progress=progress)
    return {
        "crack_speed_um_per_us": v_star,
        "pull_speed_um_per_us": speed,
        "n_sim": n_sim,
        "pull_off_per_seta_uN": h.peak_pull_off / n_sim,
        "dissipated_per_seta_pJ": float(h["energy_dissipated_pJ"][-1]) / n_sim,
        "max_kinetic_to_elastic": float(h.meta["max_kinetic_to_elastic"]),
        "n_steps": int(h.meta["n_steps"]),
        "wall_time_s": time.perf_counter() - t0,
    }


def draw(rows: list[dict], cfg: dict, Fc: float, out) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(10.0, 4.2), layout="constrained")
        ax_f, ax_d = fig.subplots(1, 2)
        colours = ["black", "#1f77b4", "#d62728"]
        for v_star, c in zip(cfg["crack_speeds"], colours, strict=False):
            for n_sim, style in ((1, "o-"), (cfg["patch"], "s--")):
                sel = [
                    r for r in rows if r["crack_speed_um_per_us"] == v_star and r["n_sim"] == n_sim
                ]
                x = [r["pull_speed_um_per_us"] for r in sel]
                name = "elastic (v* = ∞)" if math.isinf(v_star) else f"v* = {v_star:g} µm/µs"
                who = "1 seta" if n_sim == 1 else f"{n_sim} setae"
                ax_f.plot(
                    x,
                    [r["pull_off_per_seta_uN"] for r in sel],
                    style,
                    color=c,
                    label=f"{name}, {who}",
                )
                ax_d.plot(x, [r["dissipated_per_seta_pJ"] for r in sel], style, color=c)
                # Hollow: not quasi-static (inertia matters), see the module docstring.
                fast = [r for r in sel if r["max_kinetic_to_elastic"] > KE_QUASI_STATIC]
                keys = ((ax_f, "pull_off_per_seta_uN"), (ax_d, "dissipated_per_seta_pJ"))
                for ax, key in keys:
                    ax.plot(
                        [r["pull_speed_um_per_us"] for r in fast],
                        [r[key] for r in fast],
                        style[0],
                        color="white",
                        ms=3.5,
                        zorder=3,
                    )
        ax_f.axhline(Fc, color="0.5", ls=":", label=f"Fc = 1.5πRw = {Fc:.2f} µN")
        hollow = f"hollow: peak kinetic > {KE_QUASI_STATIC:.0%} of elastic energy"
        ax_f.plot([], [], "o", mfc="white", mec="0.3", label=hollow)
        for ax in (ax_f, ax_d):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("pull speed [µm/µs] (1 µm/µs = 1 m/s)")
            render.apply_style(ax)
        ax_f.set_ylabel("peak pull-off per seta [µN]")
        ax_d.set_ylabel("energy dissipated per cycle per seta [pJ]")
        ax_f.set_title("Pull-off vs pull speed")
        ax_d.set_title("Dissipation per press-and-pull cycle")
        ax_f.legend(fontsize=7)
        render.save_figure(fig, out / f"{NAME}.png")


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    cfg = config(args.quick)
    t0 = time.perf_counter()
    rows = [
        run_point(v_star, v, n_sim, not args.no_progress)
        for v_star in cfg["crack_speeds"]
        for n_sim in (1, cfg["patch"])
        for v in cfg["speeds"]
    ]
    write_table(out / "sweep.csv", rows)
    Fc = BASE.contact.pull_off_force
    draw(rows, cfg, Fc, out)

    def excess(v_star, n_sim):
        sel = [r for r in rows if r["crack_speed_um_per_us"] == v_star and r["n_sim"] == n_sim]
        return sel[-1]["pull_off_per_seta_uN"] / sel[0]["pull_off_per_seta_uN"]

    results = {
        "rise_fast_over_slow": {f"{v:g}": excess(v, 1) for v in cfg["crack_speeds"]},
        "runtime_s": time.perf_counter() - t0,
        "claims": [],
    }
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "params": BASE.to_dict(),
            "depth_um": DEPTH,
            "press_speed_um_per_us": PRESS_SPEED,
            "config": cfg,
            "seed": 1,
            "results": results,
        },
    )
    print(
        f"{NAME}: pull-off fast/slow per seta "
        + ", ".join(f"v*={k}: ×{v:.3f}" for k, v in results["rise_fast_over_slow"].items())
        + f"; {results['runtime_s']:.0f} s → {out}"
    )
    return results


if __name__ == "__main__":
    main()
