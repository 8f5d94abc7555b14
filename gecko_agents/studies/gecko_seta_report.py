"""Tables, figure and prose of the gecko-seta study (:mod:`gecko_agents.studies.gecko_seta`):
``sweep.csv``, ``array_estimate.csv``, ``gecko_seta.png`` and ``gecko_seta.md``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.studies.common import write_table

__all__ = ["write", "figure", "travel"]


def travel(h) -> np.ndarray:
    """Path length the plate has travelled [µm] at each record (press, drag, pull)."""
    x, y = np.asarray(h["plate_x_um"]), np.asarray(h["plate_y_um"])
    return np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])


def figure(path: Path, rows: list[dict], h, attached, alpha: float) -> Path:
    """Three panels: the adhesion against the shear at every let-go over the pull angles, with
    the critical angle's line (α* [deg]); the force against the plate's travel through the
    press, drag and 90° pull; the fraction of the spatulae's pads attached along the same
    travel."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    dragged = [r for r in rows if r["drag_um"] and r["mu"] == rows[0]["mu"]]
    for r in dragged:
        ax[0].plot(
            r["let_go_shear_uN"],
            r["let_go_adhesion_uN"],
            "o",
            label=f"β = {r['pull_angle_deg']:g}°",
        )
    pressed = [r for r in rows if not r["drag_um"]]
    for r in pressed:
        ax[0].plot(r["let_go_shear_uN"], r["let_go_adhesion_uN"], "k^", label="pressed, 90°")
    if np.isfinite(alpha):
        s_max = max([1e-9] + [x for r in rows for x in r["let_go_shear_uN"]])
        ax[0].plot([0.0, s_max], [0.0, s_max * np.tan(np.radians(alpha))], "k:", lw=1)
    ax[0].set(xlabel="shear at let-go [µN]", ylabel="adhesion at let-go [µN]")
    ax[0].set_title(f"every let-go: α* = {alpha:.0f}°")
    ax[0].legend(fontsize=7)
    t = travel(h)
    ax[1].plot(t, h["force_normal_uN"], label="normal (> 0 pressed)")
    ax[1].plot(t, h["force_tangential_uN"], label="tangential")
    ax[1].set(xlabel="plate travel [µm]", ylabel="force on the floor [µN]")
    ax[1].set_title("press, drag back 5 µm, pull at 90°")
    ax[1].legend()
    ax[2].plot(t, attached)
    ax[2].set(xlabel="plate travel [µm]", ylabel="pad attached ℓ/ℓ0 [-]", ylim=(-0.05, 1.05))
    ax[2].set_title("the spatulae's attachment")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _flat(row: dict) -> dict:
    """A sweep row for CSV: its lists of let-go forces joined by spaces."""
    return {
        k: " ".join(f"{x:.4g}" for x in v) if isinstance(v, list) else v for k, v in row.items()
    }


def write(out: Path, rows, arr, ours: dict, h, attached, branches: dict) -> None:
    """Write the study's tables, figure and report into ``out``."""
    write_table(out / "sweep.csv", [_flat(r) for r in rows])
    write_table(out / "array_estimate.csv", arr)
    figure(out / "gecko_seta.png", rows, h, attached, ours["ours_critical_angle"]["value"])
    lines = ["# One tokay seta, branched into spatulae", "", "| quantity | ours |", "|---|---|"]
    lines += [f"| {name} | {v['text']} |" for name, v in ours.items()]
    lines += [
        "",
        "| seta | per seta [µN] | setae per cm² | flat floor [N/cm²] | σ = 1 µm patch [N/cm²] |",
        "|---|---|---|---|---|",
    ]
    lines += [
        f"| {r['seta']} | {r['per_seta_uN']:.3g} | {r['setae_per_cm2']:.3g} | "
        f"{r['flat_N_per_cm2']:.3g} | {r['rough_N_per_cm2']:.3g} ({r['n_sim']} setae) |"
        for r in arr
    ]
    lines += [
        "",
        f"Rigid branches: the N branches in parallel are {branches['over_axial']:.3g} times as "
        f"stiff axially as the shaft and {branches['over_bending']:.3g} times its bending "
        f"stiffness ({branches['branches_uN_per_um']:.3g} µN/µm).",
    ]
    atomic_write_bytes(out / "gecko_seta.md", ("\n".join(lines) + "\n").encode())
