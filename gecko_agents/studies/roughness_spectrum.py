"""Patch pull-off against the roughness spectrum: Hurst exponent H and RMS height of the floor.

A patch of the paper's array (θ = 60°, rod mechanics) is pressed onto a self-affine floor
(``floor.kind = "self_affine"``: PSD ∝ q^−(1+2H) between the short and long wavelength cutoffs,
flat above the long one; :func:`gecko_agents.floor.self_affine`) and pulled off, for each H
and RMS height σ, over a few floor seeds. The reference row per σ is the paper's floor: an
independent Gaussian height under every seta (eq 28, ``kind = "gaussian"``, correlation length
0). ``--quick`` uses a 5 µm seta, 2 setae and one seed.

Outputs (``renders/roughness_spectrum/``): ``sweep.csv`` (one row per floor kind × H × σ, mean
and spread over seeds), ``floors.png`` (one self-affine floor per H at the largest σ, with its
PSD), ``metadata.json`` (parameters and the statistics of those floors).
"""

from __future__ import annotations

import numpy as np

from gecko_agents import floor, protocol
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.render.floor_plots import draw_profile, draw_psd
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "roughness_spectrum"


def config(quick: bool) -> dict:
    """Grid and run settings."""
    if quick:
        return {
            "hursts": [0.5, 0.8],
            "sigmas": [0.3],
            "seeds": [0],
            "n_sim": 2,
            "overrides": {"seta.L": 5.0},
            "depth": 0.5,
            "speed": 0.05,
            "short_cutoff": 4.0,
            "long_cutoff": 40.0,
        }
    return {
        "hursts": [0.3, 0.5, 0.7, 0.9],
        "sigmas": [0.1, 0.3, 1.0],
        "seeds": [0, 1, 2],
        "n_sim": 10,
        "overrides": {},
        "depth": 1.0,
        "speed": 0.02,
        "short_cutoff": 2.0,
        "long_cutoff": 50.0,
    }


def params_for(cfg: dict, kind: str, sigma: float, hurst: float | None, seed: int):
    """The parameter set of one run."""
    over = {"mechanics": "rod", "floor.sigma": sigma, "floor.seed": seed, **cfg["overrides"]}
    if kind == "self_affine":
        over |= {
            "floor.kind": "self_affine",
            "floor.hurst": hurst,
            "floor.short_cutoff": cfg["short_cutoff"],
            "floor.long_cutoff": cfg["long_cutoff"],
        }
    return PAPER_ARRAY.replace(**over)


def run_row(cfg: dict, kind: str, sigma: float, hurst: float | None) -> dict:
    """Pull-off [µN per simulated seta] over the seeds for one floor."""
    per_seta = []
    for seed in cfg["seeds"]:
        p = params_for(cfg, kind, sigma, hurst, seed)
        h = Model(p, n_sim=cfg["n_sim"]).run(
            protocol.press_pull(cfg["depth"], cfg["speed"]), progress=False
        )
        per_seta.append(h.peak_pull_off / cfg["n_sim"])
    fc = PAPER_ARRAY.contact.pull_off_force
    return {
        "floor": "independent Gaussian (eq 28)" if kind == "gaussian" else "self-affine",
        "hurst": "" if hurst is None else hurst,
        "rms_height_um": sigma,
        "pull_off_per_seta_uN": float(np.mean(per_seta)),
        "spread_uN": float(np.std(per_seta)),
        "fraction_of_Fc": float(np.mean(per_seta) / fc),
        "seeds": len(per_seta),
    }


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    cfg = config(args.quick)
    rows = []
    for sigma in cfg["sigmas"]:
        rows.append(run_row(cfg, "gaussian", sigma, None))
        for hurst in cfg["hursts"]:
            rows.append(run_row(cfg, "self_affine", sigma, hurst))
            if not args.no_progress:
                print(
                    f"σ = {sigma} µm, H = {hurst}: {rows[-1]['pull_off_per_seta_uN']:.3f} µN/seta"
                )
    write_table(out / "sweep.csv", rows)
    # The floors themselves: one per H at the largest σ, as the model builds them.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from gecko_agents.render import save_figure

    fig = Figure(figsize=(10, 3.6), layout="constrained")
    FigureCanvasAgg(fig)
    ax_h, ax_c = fig.subplots(1, 2)
    stats = {}
    sigma = max(cfg["sigmas"])
    for hurst in cfg["hursts"]:
        p = params_for(cfg, "self_affine", sigma, hurst, cfg["seeds"][0])
        prof = floor.for_array(
            p.floor, np.array([0.0, 400.0]), p.array.pitch, 0.0, np.random.default_rng(p.floor.seed)
        )
        st = floor.statistics(
            prof, fit_wavelengths=(2 * cfg["short_cutoff"], cfg["long_cutoff"] / 2)
        )
        stats[f"H={hurst}"] = {k: v for k, v in st.items() if not k.startswith("psd_")}
        draw_profile(ax_h, prof, label=f"H = {hurst}")
        draw_psd(ax_c, prof, st, label=f"H = {hurst} (fit H ≈ {st['hurst']:.2f})")
    ax_h.legend(frameon=False, fontsize="small")
    fig.suptitle(
        f"self-affine floors, RMS height {sigma} µm, λs = {cfg['short_cutoff']} µm, "
        f"λL = {cfg['long_cutoff']} µm"
    )
    save_figure(fig, out / "floors.png")
    write_json(
        out / "metadata.json",
        {"config": cfg, "floor_statistics": stats, "Fc_uN": PAPER_ARRAY.contact.pull_off_force},
    )
    return {"rows": rows}


if __name__ == "__main__":
    main()
