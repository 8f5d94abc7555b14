"""Contact splitting with an interface of finite strength: pull-off per area of backing against
pillar radius, for flat punches and mushroom tips, at a fixed area fraction.

Part of the pillar-designs study (:mod:`gecko_agents.studies.pillar_designs`, which writes its
table ``pillar_splitting.csv`` and figure ``pillar_splitting.png``). The pillars are the study's
polyurethane (E = 1.413 MPa, ν = 0.3) on glass, of aspect L/2r = 5, on a square lattice whose
pitch grows with the radius (pitch/r = 4/1.5, the study's 44 % area fraction), so that every
radius covers the backing alike. A flat punch's pull-off per area is then
(πa²/pitch²)·σ, σ its pull-off stress:

* without a strength limit (σ₀ = inf), Kendall's √(8E*w/(πa)): splitting always pays, as a^−1/2;
* with a strength σ₀, the Dugdale punch (:func:`gecko_agents.physics.flaw_tolerance.
  punch_pull_off`), below min(Kendall's, σ₀): splitting pays down to about the flaw-tolerant
  radius a_cr = 8E*w/(πσ₀²) and not below 0.540·a_cr, where the whole face holds σ₀;
* a mushroom (flange 1.2 × its stalk, Aksak et al.'s optimum, sharp 45° rim, not singular)
  lets go from its centre at σ₀ over the flange with no defect, whatever its size; with a
  central defect a quarter of the flange's radius, by Griffith's penny crack, capped at σ₀.

The interface strength σ₀ is an assumption here (no measured value for polyurethane on glass
was read): 0.3 and 1 MPa, the latter Aksak, Şahin & Sitti's (2014) "reasonable value" for
PDMS. The lines are the closed forms; the markers are single pillars pressed 1 % of their
length and pulled off in the time-stepped model (``mechanics = "elastica"``), their largest
tension.
"""

from __future__ import annotations

import math

from gecko_agents import protocol, render
from gecko_agents.model import Model
from gecko_agents.physics import flaw_tolerance as ft
from gecko_agents.physics import mushroom

__all__ = [
    "DESIGNS",
    "QUICK_DESIGNS",
    "splitting_rows",
    "model_rows",
    "draw_splitting",
    "splitting_section",
]

PITCH_OVER_R = 4.0 / 1.5
ASPECT = 5.0
BETA = 1.2  # flange over stalk radius
DESIGNS = {
    "flat punch, σ₀ = inf": {"tip": "flat_punch", "sigma0": math.inf},
    "flat punch, σ₀ = 0.3 MPa": {"tip": "flat_punch", "sigma0": 0.3},
    "flat punch, σ₀ = 1 MPa": {"tip": "flat_punch", "sigma0": 1.0},
    "mushroom 45°, σ₀ = 1 MPa": {"tip": "mushroom", "sigma0": 1.0, "defect": 0.0},
    "mushroom 45°, defect a_t/4, σ₀ = 1 MPa": {"tip": "mushroom", "sigma0": 1.0, "defect": 0.25},
}
"""The designs compared: tip, σ₀ [MPa] and (mushroom) the defect radius over the flange's."""
QUICK_DESIGNS = ["flat punch, σ₀ = 1 MPa", "mushroom 45°, σ₀ = 1 MPa"]
"""The designs run in the model by ``--quick``."""


def _pull_off(design: dict, a: float, contact) -> float:
    """Closed-form pull-off [µN] of one pillar of stalk radius a [µm]."""
    _, w, E_star = contact.jkr_args()
    if design["tip"] == "flat_punch":
        return float(ft.punch_pull_off(a, w, E_star, design["sigma0"]))
    a_t = BETA * a
    modes = mushroom.pull_offs(
        a_t, design["defect"] * a_t, w, E_star, design["sigma0"], "sharp", 45.0, contact.nu1
    )
    return min(modes.values())


def splitting_rows(base, radii) -> list[dict]:
    """Closed-form pull-off per area of backing [kPa] of each design at stalk radii [µm]."""
    rows = []
    for name, design in DESIGNS.items():
        for a in radii:
            F = _pull_off(design, float(a), base.contact)
            pitch = PITCH_OVER_R * a
            rows.append(
                {
                    "design": name,
                    "source": "closed form",
                    "radius_um": float(a),
                    "pull_off_uN": F,
                    "pull_off_per_area_kPa": 1e3 * F / pitch**2,
                }
            )
    return rows


def model_params(base, design: dict, a: float):
    """One pillar of stalk radius a [µm] of ``design`` (the study's base, aspect L/2r = 5)."""
    over = {
        "tip": design["tip"],
        "seta.r": a,
        "seta.L": 2.0 * ASPECT * a,
        "contact.R": a,
        "array.count": 1,
        "array.pitch": PITCH_OVER_R * a,
        "spatula.b": 2.0 * a,
        "contact.sigma0": design["sigma0"],
    }
    if design["tip"] == "mushroom":
        over |= {
            "contact.R": BETA * a,
            "mushroom.rim": "sharp",
            "mushroom.rim_angle_deg": 45.0,
            "mushroom.defect_radius": design["defect"] * BETA * a,
        }
    return base.replace(**over)


def model_rows(base, radii, speed: float, names=None) -> list[dict]:
    """The time-stepped model's pull-off per area [kPa] of single pillars: pressed 1 % of L,
    pulled at ``speed`` [µm/µs], the largest tension of any step (``History.peak_pull_off``;
    the detachment records the law's own force at release); with the mode that released
    them."""
    rows = []
    for name in names or DESIGNS:
        for a in radii:
            p = model_params(base, DESIGNS[name], float(a))
            h = Model(p, n_sim=1, seed=0).run(
                protocol.press_pull(0.01 * p.seta.L, speed=speed), progress=False
            )
            F = h.peak_pull_off
            mode = h.detachments.get("mode")
            rows.append(
                {
                    "design": name,
                    "source": "model",
                    "radius_um": float(a),
                    "pull_off_uN": F,
                    "pull_off_per_area_kPa": 1e3 * F / p.array.pitch**2,
                    "mode": str(mode[0]) if mode is not None and len(mode) else "",
                }
            )
    return rows


def draw_splitting(rows, base, out) -> None:
    """Pull-off per area of backing against pillar radius (log–log), the flaw-tolerant radii
    marked."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    _, w, E = base.contact.jkr_args()
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(6.8, 4.6), layout="constrained")
        ax = fig.subplots()
        for name in DESIGNS:
            line = [r for r in rows if r["design"] == name and r["source"] == "closed form"]
            (ln,) = ax.plot(
                [r["radius_um"] for r in line],
                [r["pull_off_per_area_kPa"] for r in line],
                label=name,
            )
            pts = [r for r in rows if r["design"] == name and r["source"] == "model"]
            ax.plot(
                [r["radius_um"] for r in pts],
                [r["pull_off_per_area_kPa"] for r in pts],
                "o",
                color=ln.get_color(),
                mfc="none",
            )
        for s0 in sorted({d["sigma0"] for d in DESIGNS.values() if math.isfinite(d["sigma0"])}):
            a_cr = float(ft.flaw_tolerant_radius(s0, E, w))
            ax.axvline(a_cr, ls=":", color="0.5", lw=1)
            ax.annotate(
                f"a_cr({s0:g} MPa)",
                (a_cr, 0.98),
                xycoords=("data", "axes fraction"),
                rotation=90,
                va="top",
                ha="right",
                fontsize="small",
                color="0.4",
            )
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("pillar (stalk) radius a [µm], pitch = 2.67 a")
        ax.set_ylabel("pull-off per area of backing [kPa]")
        ax.set_title("where splitting stops paying (lines: closed form, ○: model)")
        ax.legend(fontsize="small")
        render.save_figure(fig, out / "pillar_splitting.png")


def splitting_section(rows, base) -> str:
    """The report's lines: each design's pull-off per area at the smallest and largest radius,
    the flat punch's flaw-tolerant radius, and how far the model's pillars are from the closed
    forms."""
    _, w, E = base.contact.jkr_args()
    lines = []
    for name, d in DESIGNS.items():
        line = sorted(
            (r for r in rows if r["design"] == name and r["source"] == "closed form"),
            key=lambda r: r["radius_um"],
        )
        lo, hi = line[0], line[-1]
        text = (
            f"- {name}: {lo['pull_off_per_area_kPa']:.3g} kPa at a = {lo['radius_um']:.2g} "
            f"µm, {hi['pull_off_per_area_kPa']:.3g} kPa at {hi['radius_um']:.2g} µm"
        )
        if d["tip"] == "flat_punch" and math.isfinite(d["sigma0"]):
            a_cr = float(ft.flaw_tolerant_radius(d["sigma0"], E, w))
            text += f"; no gain from splitting below a_cr = {a_cr:.3g} µm"
        lines.append(text)
    model = [r for r in rows if r["source"] == "model"]
    if model:
        ratios = [
            r["pull_off_uN"] / _pull_off(DESIGNS[r["design"]], r["radius_um"], base.contact)
            for r in model
        ]
        worst = max(abs(x - 1.0) for x in ratios)
        lines += [
            "",
            f"The model's single pillars are within {100 * worst:.2g} % of the closed forms.",
        ]
    head = (
        "Contact splitting with an interface strength (`pillar_designs/pillar_splitting.png`, "
        "table `pillar_splitting.csv`; pitch = 2.67 a):"
    )
    return "\n".join([head, "", *lines, ""])
