"""Fig 10: force vs pressing displacement of the paper's array on a σ = 1 µm floor.

The full array (10⁷ setae, θ = 60°) is computed with the quasi-static solver; the agent model
runs patches of N_sim setae (one row of the array) on several floor seeds and is scaled by
10⁷/N_sim. As in the paper's curve, the plate first presses until the array carries 8.6 N (the
force the paper's Fig 10 starts from), then pulls off. A convergence study (quasi-static patches
over many seeds) gives the N_sim at which a patch estimate of the peak pull-off is within 2 %
of the full array. ``--animate`` also renders a detachment animation of a rod-mechanics patch.

The x axis is the pressing displacement d = (mean-plane touch-down height) − (plate height)
[µm], > 0 pressed, < 0 pulled away; forces are > 0 in compression (docs/physics.md).
"""

from __future__ import annotations

import numpy as np

from gecko_agents import protocol
from gecko_agents import quasistatic as qs
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY, PAPER_FIG5_READING
from gecko_agents.render import PRESSING_LABEL, plot_force_curves, save_figure, touchdown_height
from gecko_agents.studies.common import (
    claim,
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

N_FULL = PAPER_ARRAY.array.count
PRELOAD_N = 8.6  # N, where the paper's Fig 10 curve starts
UN_PER_N = 1e6


def full_array(params, seed, n_blocks, preload_uN):
    """Quasi-static force curve of the whole array: weighted height blocks split where a
    block's setae part ways (jump-in, slide, release), so 2000 blocks give the curve of all
    10⁷ setae to ~1e-9 of the peak (:func:`gecko_agents.quasistatic.representative_heights`;
    2000 vs 4000 split blocks: 1e-11, 20 000 plain block means: 1e-5, eight times slower)."""
    h, w, sample = qs.representative_heights(
        params.array.count,
        params.floor.sigma,
        np.random.default_rng(seed),
        n_blocks,
        return_sample=True,
    )
    return qs.preload_pull(params, h, preload_uN, weights=w, sample=sample)


def patch_peaks(params, n_sim, seeds, preload_uN):
    """Peak pull-off [N] of quasi-static patches of n_sim setae, scaled to the full array."""
    out = []
    for s in seeds:
        h = params.floor.sigma * np.random.default_rng(s).standard_normal(n_sim)
        r = qs.preload_pull(params, h, preload_uN * n_sim / params.array.count)
        out.append(r.pull_off * params.array.count / n_sim / UN_PER_N)
    return np.array(out)


def full_curves(params, quick: bool, preload: float, z_touch: float) -> tuple:
    """The full array, quasi-statically, for both readings of w: (full, alt, their curves)."""
    full = full_array(params, 0, 2_000, preload)
    alt = full_array(
        PAPER_FIG5_READING.replace(
            **{"seta.theta_deg": 60.0, "floor.sigma": 1.0, "array.count": N_FULL}
        ),
        0,
        2_000,
        preload,
    )
    curves = [
        {
            "x": z_touch - full.plate_y,
            "y": full.force_normal / UN_PER_N,
            "label": "quasi-static, full array (10⁷), the paper's linear seta",
            "style": {"color": "k"},
        },
        {
            "x": z_touch - alt.plate_y,
            "y": alt.force_normal / UN_PER_N,
            "label": "quasi-static, w = 0.080 J/m²",
            "style": {"color": "0.5", "linestyle": ":"},
        },
    ]
    return full, alt, curves


def rod_curve(params, preload: float, z_touch: float, n_blocks: int = 200):
    """The full array quasi-statically with large-rotation ``rod`` setae (the physical seta):
    plain weighted height blocks (200 vs 400 blocks: 1e-4 of the peak); (result, its curve)."""
    p = params.replace(mechanics="rod")
    h, w = qs.representative_heights(
        p.array.count, p.floor.sigma, np.random.default_rng(0), n_blocks
    )
    rod = qs.preload_pull(p, h, preload, weights=w)
    curve = {
        "x": z_touch - rod.plate_y,
        "y": rod.force_normal / UN_PER_N,
        "label": "quasi-static, full array (10⁷), rod setae (large rotation)",
        "style": {"color": "tab:green", "linestyle": "--"},
    }
    return rod, curve


def agent_patches(params, n_sims, seeds, quick, progress, preload, out, z_touch, curves, rows):
    """Agent patches (the paper's linear beam), scaled to the full array; appends one row per
    run to ``rows`` and the first seed's curve of the largest patch to ``curves``. Returns the
    peaks [N] by patch size."""
    pull_speed = 0.3 if quick else 0.1  # µm/µs; the linear seta stretches ~250 µm
    agent_peaks = {}
    for n_sim in n_sims:
        agent_peaks[n_sim] = []
        for seed in seeds:
            m = Model(params, n_sim=n_sim, seed=seed)
            scale = params.array.count / n_sim
            prot = [
                protocol.Press(preload / scale, protocol.DEFAULT_SPEED * (4 if quick else 1)),
                protocol.PullOff(pull_speed),
            ]
            h = m.run(prot, progress=progress)
            h.save(out / f"agent_n{n_sim}_seed{seed}")
            peak = h.peak_pull_off * scale / UN_PER_N
            agent_peaks[n_sim].append(peak)
            rows.append(
                {
                    "kind": "agent",
                    "n_sim": n_sim,
                    "seed": seed,
                    "peak_pull_off_N": peak,
                    "max_kinetic_to_elastic": h.meta["max_kinetic_to_elastic"],
                    "wall_time_s": h.meta["wall_time_s"],
                }
            )
            if seed == seeds[0] and n_sim == n_sims[-1]:
                curves.append(
                    {
                        "x": z_touch - h["plate_y_um"],
                        "y": h["force_normal_uN"] * scale / UN_PER_N,
                        "label": f"agent patch N_sim = {n_sim} (×{scale:.3g})",
                        "style": {"color": "tab:blue", "alpha": 0.8},
                    }
                )
    return agent_peaks


def convergence(params, conv_sizes, conv_seeds, preload, full_peak, rows) -> int | None:
    """Quasi-static patches over many seeds; appends a row per size to ``rows``. Returns the
    smallest N_sim whose mean and seed spread are within 2 % of the full array (or None)."""
    within = None
    for n_sim in conv_sizes:
        peaks = patch_peaks(params, n_sim, conv_seeds, preload)
        mean, std = float(peaks.mean()), float(peaks.std(ddof=1))
        ok = abs(mean - full_peak) <= 0.02 * full_peak and std <= 0.02 * full_peak
        if ok and within is None:
            within = n_sim
        rows.append(
            {
                "kind": "quasi-static patch",
                "n_sim": n_sim,
                "seeds": len(conv_seeds),
                "peak_pull_off_N": mean,
                "std_N": std,
                "rel_error_of_mean": mean / full_peak - 1,
                "rel_std": std / full_peak,
            }
        )
    return within


def draw(curves, out) -> None:
    """fig10_array_pulloff.png: force [N] vs pressing displacement, the paper's peak marked."""
    fig = plot_force_curves(
        curves,
        None,
        xlabel=PRESSING_LABEL,
        ylabel="contact force [N]",
        title="Fig 10: array pressed to 8.6 N and pulled off (σ = 1 µm)",
    )
    ax = fig.axes[0]
    ax.set_xscale("symlog", linthresh=5.0)
    ax.axhline(-2.85, color="tab:red", lw=0.8, ls="--", label="paper: −2.85 N")
    ax.legend(fontsize=8)
    save_figure(fig, out / "fig10_array_pulloff.png")


def animate_patch(params, quick, progress, preload, out) -> None:
    """Record a rod-mechanics patch pressed to its share of the preload and pulled off;
    save it under ``out/animated_run`` and render ``out/detachment.gif``."""
    from gecko_agents.render import animate

    p_rod = params.replace(mechanics="rod")
    m = Model(p_rod, n_sim=40 if not quick else 6, seed=1, record_setae=True)
    scale = p_rod.array.count / m.n
    h = m.run([protocol.Press(preload / scale), protocol.PullOff(0.01)], progress=progress)
    h.save(out / "animated_run")
    animate(h, out / "detachment.gif")


def make_claims(full, alt, results, band, n_best, within, conv_sizes, z_touch) -> list[dict]:
    """The three Fig 10 rows of the paper-comparison report."""
    full_peak = results["full_peak_pull_off_N"]
    return [
        claim(
            "Fig 10",
            "the pressed array carries 8.6 N of compression where the curve starts",
            "8.6 N",
            f"8.6 N is reached {z_touch - full.plate_y[full.turn_index]:.2f} µm below "
            f"mean-plane touch-down with {full.n_attached[full.turn_index] / N_FULL:.0%} of "
            "the setae attached",
            "reproduced",
            "8.6 N is the protocol's starting force, not a prediction: we press "
            "to it (force control) and report how deep that is.",
        ),
        claim(
            "Fig 10",
            "maximum adhesion −2.85 N during pull-off",
            "−2.85 N",
            f"−{full_peak:.2f} N (quasi-static, 10⁷ setae); agent patch N_sim = {n_best}: "
            f"−{np.mean(band):.2f} N (range {min(band):.2f}–{max(band):.2f} over "
            f"{len(band)} seeds)",
            "not reproducible from the stated parameters",
            f"Pressed to 8.6 N nearly every tip is in contact and the soft setae let each go "
            f"at ≈ Fc, so the peak approaches N·Fc = {results['ideal_N_Fc_N']:.0f} N, far "
            "above 2.85 N.",
            alternative=f"w = 0.080 J/m²: −{alt.pull_off / UN_PER_N:.2f} N; rod setae "
            f"(quasi-static, 10⁷): −{results['rod_peak_pull_off_N']:.2f} N "
            f"(= {results['rod_peak_pull_off_N'] / results['ideal_N_Fc_N']:.2f} N·Fc: on the "
            "rough floor the rod shares the load unequally, which the linear seta hides)",
        ),
        claim(
            "Fig 10",
            "patch estimate converges to the full array",
            "—",
            f"N_sim = {within} setae (mean and seed spread within 2 %)"
            if within
            else f"not within 2 % up to N_sim = {conv_sizes[-1]}",
            "reproduced" if within else "trend reproduced",
            "Beyond the paper: a row of N_sim setae with independent heights samples eq 28; "
            "the seed spread shrinks as 1/√N_sim.",
        ),
    ]


@command_line
def main(argv=None) -> dict:
    args = parse_args(
        __doc__,
        argv,
        extra=lambda p: p.add_argument(
            "--animate", action="store_true", help="also write detachment.gif"
        ),
    )
    out = output_dir("fig10_array_pulloff", args)
    quick, progress = args.quick, not args.no_progress
    params = PAPER_ARRAY
    preload = PRELOAD_N * UN_PER_N
    z_touch = touchdown_height(params)  # plate height of mean-plane touch-down [µm]

    full, alt, curves = full_curves(params, quick, preload, z_touch)
    rod, rod_c = rod_curve(params, preload, z_touch)
    curves.append(rod_c)
    n_sims = [5] if quick else [10, 40]
    seeds = [1] if quick else [1, 2, 3]
    rows = []
    agent_peaks = agent_patches(
        params, n_sims, seeds, quick, progress, preload, out, z_touch, curves, rows
    )
    # Sizes ×4 apart and 12 seeds: the spread of 12 seeds is known to ~20 %, enough to see it
    # fall as 1/√N_sim and to tell where mean and spread come within 2 %.
    conv_sizes = [10, 40] if quick else [10, 40, 160, 640]
    conv_seeds = range(100, 104 if quick else 112)
    full_peak = full.pull_off / UN_PER_N
    within = convergence(params, conv_sizes, conv_seeds, preload, full_peak, rows)
    rows.append({"kind": "quasi-static full", "n_sim": N_FULL, "peak_pull_off_N": full_peak})
    write_table(out / "sweep.csv", rows)
    draw(curves, out)
    if args.animate:
        animate_patch(params, quick, progress, preload, out)

    agent_mean = {n: float(np.mean(v)) for n, v in agent_peaks.items()}
    n_best = n_sims[-1]
    results = {
        "full_peak_pull_off_N": full_peak,
        "full_max_compression_N": full.preload / UN_PER_N,
        "alt_w080_peak_pull_off_N": alt.pull_off / UN_PER_N,
        "rod_peak_pull_off_N": rod.pull_off / UN_PER_N,
        "agent_peak_pull_off_N": agent_mean,
        "n_sim_within_2pct": within,
        "ideal_N_Fc_N": N_FULL * params.contact.pull_off_force / UN_PER_N,
    }
    write_json(
        out / "metadata.json",
        {
            "params": params.to_dict(),
            "preload_N": PRELOAD_N,
            "seeds": seeds,
            "n_sims": n_sims,
            "results": results,
        },
    )
    results["claims"] = make_claims(
        full, alt, results, agent_peaks[n_best], n_best, within, conv_sizes, z_touch
    )
    return results


if __name__ == "__main__":
    main()
