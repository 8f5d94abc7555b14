"""Figures and report of the frictional-adhesion study (:mod:`gecko_agents.studies.
frictional_adhesion`): the limit-curve figure, the anisotropy map's figure, and the "beyond the
paper" report with its tables (sweep, map, flatter setae, patch, plate-speed check).

Everything here formats numbers the study and :mod:`gecko_agents.analysis` computed; nothing is
measured here. Units: µm, µN, µs, degrees; adhesion > 0 in tension, shear > 0 along +x.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents import render
from gecko_agents.analysis.ratio import gripping_over_releasing
from gecko_agents.contact import contact_law
from gecko_agents.model.mass_damping import DEFAULT_DAMPING
from gecko_agents.physics import savkoor_briggs as sheared_jkr
from gecko_agents.studies.frictional_adhesion_setup import BASE, DRAG, NAME, PRELOAD, SPEED, TIPS


def report_text(summary, quick, map_rows, below_rows, patch_rows, conv_rows, conv) -> str:
    """beyond_the_paper.md: the sweep's rows beside published values, the map, the flatter
    setae, the patch and the plate-speed check (each section only when it ran)."""
    return (
        beyond_the_paper(summary, quick, map_rows)
        + ("\n" + "\n".join(below_map_section(below_rows)) if below_rows else "")
        + "\n"
        + "\n".join(patch_section(patch_rows))
        + ("\n" + "\n".join(convergence_section(conv_rows, conv)) if conv_rows else "")
    )


def convergence_section(rows: list[dict], conv: dict) -> list[str]:
    """The report's table of the 90° pull-offs against plate speed (rows of
    :func:`~gecko_agents.studies.frictional_adhesion.speed_convergence`) and what the numbers
    of :func:`~gecko_agents.studies.frictional_adhesion.convergence_summary` (``conv``) say."""
    lines = [
        "### Quasi-static check: plate speed",
        "",
        f"μ = 10, 90° pull after the {DRAG:g} µm drag either way (`speed_convergence.csv`); "
        f"pressed to = the largest force of the press, whose target is the {PRELOAD} µN "
        f"preload; KE/E = peak kinetic over peak elastic energy of the run. The tables above "
        f"use {SPEED:g} µm/µs, the package's quasi-static plate speed.",
        "",
        "| tip | plate speed [µm/µs] | contact damping | gripping [µN] | releasing [µN] | ratio "
        "| pressed to [µN] | KE/E gripping / releasing |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['tip']} | {r['speed_um_per_us']:g} | "
            f"{'yes' if r['contact_damping'] else 'off'} | {r['gripping_uN']:.4f} | "
            f"{r['releasing_uN']:.4f} | ×{r['gripping_over_releasing']:.3f} | "
            f"{r['pressed_to_uN']:.3f} | {r['max_kinetic_to_elastic_gripping']:.3f} / "
            f"{r['max_kinetic_to_elastic_releasing']:.3f} |"
        )
    return lines + ["", convergence_text(conv), ""]


def convergence_text(conv: dict) -> str:
    """The plate-speed check in words, from the numbers of ``convergence_summary``."""
    rel = conv["releasing"]
    change = 100 * rel["change"]
    text = (
        f"Spatula: from {rel['speeds'][0]:g} to {rel['speeds'][-1]:g} µm/µs the releasing "
        f"pull-off changes by {change:+.1f} % and the gripping one by "
        f"{100 * conv['gripping']['change']:+.1f} %"
    )
    if len(rel["speeds"]) > 2:
        text += "; per unit of speed between successive speeds the releasing pull-off changes by "
        text += ", ".join(f"{x:.2f}" for x in rel["slopes"]) + " µN per µm/µs"
        text += ": first order in the speed" if rel["first_order"] else " (not first order)"
        if math.isfinite(rel["order"]):
            text += f" (observed order {rel['order']:.2f})"
        text += f"; extrapolated to rest (Richardson, order 1) {rel['limit']:.4f} µN"
    text += "."
    off = conv.get("undamped")
    if off is not None:
        text += (
            f" Without contact damping (normal and tangential ratios {DEFAULT_DAMPING.normal:g} "
            f"and {DEFAULT_DAMPING.tangential:g} set to 0) the {off['speed_um_per_us']:g} µm/µs "
            f"pulls give {off['gripping_uN']:.4f} / {off['releasing_uN']:.4f} µN "
            f"(×{off['gripping_over_releasing']:.3f}), the releasing one "
            f"{100 * off['gap']:+.1f} % from the slowest damped run against {change:+.1f} % "
            "with damping"
        )
        text += (
            ": the speed dependence is mostly the contact dashpots' force ∝ v on the film, "
            "there to damp the contact's ringing, not the peel's physics."
            if off["dashpot_dominated"]
            else "."
        )
    if conv.get("sphere_range") is not None:
        lo, hi = conv["sphere_range"]
        text += (
            f" JKR sphere: its pull-offs span {lo:.4f}–{hi:.4f} µN over these "
            "speeds (it lets go where its load-controlled branch ends, at −Fc)."
        )
    return text


def patch_section(rows: list[dict]) -> list[str]:
    """The patch table: per tip and σ, both drags' pull-off per seta and their ratio."""
    lines = [
        "### A patch on a rough floor",
        "",
        f"{rows[0]['count']} setae, each on its own pad at a Gaussian height (eq 28), pressed to "
        f"{rows[0]['count']} × {PRELOAD} µN, dragged {DRAG:g} µm either way and pulled at 90°, "
        "μ = 10 (`patch.csv`).",
        "",
        "| tip | σ [µm] | attached after the drag (gripping / releasing) | pull-off per seta, "
        "gripping / releasing [µN] | ratio |",
        "|---|---|---|---|---|",
    ]
    for tip, sigma in dict.fromkeys((r["tip"], r["sigma_um"]) for r in rows):
        g, r_ = (
            next(r for r in rows if (r["tip"], r["sigma_um"], r["direction"]) == (tip, sigma, way))
            for way in ("gripping", "releasing")
        )
        ratio = gripping_over_releasing(g["pull_off_per_seta_uN"], r_["pull_off_per_seta_uN"])
        lines.append(
            f"| {TIPS[tip][1]} | {sigma:g} | {g['attached_after_drag']} / "
            f"{r_['attached_after_drag']} | {g['pull_off_per_seta_uN']:.2f} / "
            f"{r_['pull_off_per_seta_uN']:.2f} | ×{ratio:.2f} |"
        )
    return lines + [""]


def draw_map(rows: list[dict], mcfg: dict, out) -> None:
    """Ratio and peel angle at release against drag/lean, one line per (case, θ)."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(11.0, 4.4), layout="constrained")
        ax_r, ax_phi = fig.subplots(1, 2)
        colours = {
            ("spatula", 10.0): "#d62728",
            ("spatula", 0.2): "#fc9272",
            ("sphere", 10.0): "#1f77b4",
            ("sphere_sb", 10.0): "#2ca02c",
        }
        dashes = {55.0: ":", 60.0: "-", 75.0: "--"}
        for tip, mu in mcfg["cases"]:
            for theta in mcfg["thetas"]:
                sel = [r for r in rows if (r["tip"], r["mu"], r["theta_deg"]) == (tip, mu, theta)]
                c, ls = colours.get((tip, mu), "k"), dashes.get(theta, "-")
                lab = f"{TIPS[tip][1]}, μ = {mu:g}, θ = {theta:g}°"
                g = [r for r in sel if r["direction"] == "gripping"]
                ax_r.plot(
                    [r["drag_over_lean"] for r in g],
                    [r["gripping_over_releasing"] for r in g],
                    "o" + ls,
                    color=c,
                    label=lab,
                )
                for way, mk in (("gripping", "o"), ("releasing", "^")):
                    d = [r for r in sel if r["direction"] == way]
                    ax_phi.plot(
                        [r["drag_over_lean"] for r in d],
                        [r["peel_angle_at_pull_off_deg"] for r in d],
                        mk + ls,
                        color=c,
                        label=f"{lab}, {way}",
                    )
        # Runs whose tip let go in the drag itself: their pull starts from a fresh contact.
        # (Each map row carries its pair's ratio, so a lost run marks that ratio.)
        lost = [r for r in rows if math.isfinite(r["let_go_in_drag_at_um"])]
        for ax, key in ((ax_r, "gripping_over_releasing"), (ax_phi, "peel_angle_at_pull_off_deg")):
            if lost:
                ax.plot(
                    [r["drag_over_lean"] for r in lost],
                    [r[key] for r in lost],
                    "x",
                    color="k",
                    ms=9,
                    mew=1.5,
                    zorder=5,
                    label="tip let go in the drag",
                )
        ax_r.axhline(2.0, color="0.6", lw=0.8)
        ax_r.set_xlabel("drag / lean (L cos θ)")
        ax_r.set_ylabel("pull-off at 90°: gripping / releasing")
        ax_r.set_title("anisotropy of the 90° pull-off")
        ax_phi.axhline(90.0, color="0.6", lw=0.8)
        ax_phi.set_xlabel("drag / lean (L cos θ)")
        ax_phi.set_ylabel("force angle at pull-off φ [deg] (> 90°: over the pad)")
        ax_phi.set_title("peel angle at pull-off (o gripping, ^ releasing)")
        for ax in (ax_r, ax_phi):
            render.apply_style(ax)
        ax_r.legend(fontsize=6)
        render.save_figure(fig, out / "anisotropy_map.png")


def draw(rows: list[dict], cfg: dict, out) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(6.4 * len(cfg["mus"]), 4.6), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, len(cfg["mus"])))
        styles = {
            ("sphere", -DRAG): ("o-", "#1f77b4"),
            ("sphere", DRAG): ("o--", "#9ecae1"),
            ("sphere_sb", -DRAG): ("D-", "#2ca02c"),
            ("sphere_sb", DRAG): ("D--", "#98df8a"),
            ("spatula", -DRAG): ("s-", "#d62728"),
            ("spatula", DRAG): ("s--", "#fc9272"),
        }
        for ax, mu in zip(axes, cfg["mus"], strict=True):
            for (tip, drag), (st, c) in styles.items():
                sel = [
                    r for r in rows if r["tip"] == tip and r["mu"] == mu and r["drag_um"] == drag
                ]
                if not sel:
                    continue
                way = "gripping (−x)" if drag < 0 else "releasing (+x)"
                ax.plot(
                    [r["shear_at_release_uN"] for r in sel],
                    [r["adhesion_at_release_uN"] for r in sel],
                    st,
                    color=c,
                    label=f"{TIPS[tip][1]}, dragged {way}",
                )
            if "sphere_sb" in cfg["tips"]:  # the closed form beside the coupled sphere
                law = contact_law(BASE.replace(**TIPS["sphere_sb"][0]))
                T = np.linspace(*ax.get_xlim(), 200)
                Fc = sheared_jkr.pull_off_force(T, law.R, law.w, law.E_star, law.G_star)
                ax.plot(T, Fc, ":", color="0.4", lw=1.0, label="Fc(T), Savkoor & Briggs 1977")
            ax.axhline(0.0, color="0.6", lw=0.8)
            ax.set_xlabel("shear force at release [µN] (+x)")
            ax.set_ylabel("adhesion (normal) force at release [µN]")
            ax.set_title(f"μ = {mu:g}: release forces over pull angles")
            render.apply_style(ax)
            ax.legend(fontsize=7)
        render.save_figure(fig, out / f"{NAME}.png")


def beyond_the_paper(summary: dict, quick: bool, map_rows: list[dict]) -> str:
    """The "beyond the paper" rows: this model beside published values, with sources."""
    lines = [
        "## Beyond the paper: frictional adhesion",
        "",
        f"Single rod seta (θ = 60°, L = 20 µm), preload {PRELOAD} µN, drag {DRAG:g} µm, "
        f"pulled at {SPEED} µm/µs; {'--quick run' if quick else 'full run'} of "
        "`gecko_agents.studies.frictional_adhesion`. Pull-off = largest adhesion in the pull; "
        "α* = the limit line through the origin of the gripping releases (Autumn et al. 2006's "
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
        "Why they differ: a gripping drag flattens the seta, so the film peels at a small "
        "angle and its pad, stretched by partial slip (Chen–Wu–Gao pre-tension), holds more "
        "(stretched, the pad's material covers more floor, and its friction grows with it); "
        "the rod's tip follows its force, so α* is the shaft's own angle at release, not a "
        "property of the tip. A releasing drag pushes the seta over its tip: the film cannot "
        "be pushed (driven over its pad it goes slack, then peels backwards at φ = 180°, "
        "Kendall's w·b/2 ≈ 0.25 µN), but the pressed tip body holds by its own Coulomb "
        "friction μ·P_c. At μ = 10 that holds the tip, the seta rotates over it towards "
        "upright and the 90° pull peels the film with the force turned away from the shaft "
        "(φ > 90° from the gripping shear axis), where it holds far less than the gripping "
        f"film. {sphere_sentence(summary)} With the paper's μ = 0.2 the "
        "pad's friction (2μw·b·ℓ/ℓ0 ≈ 0.2 µN) and the tip's (μ·P_c ≈ 0.1 µN) are below the "
        "seta's forces: pad and tip slide under the seta either way, the pad caps the "
        "pre-tension and both pulls let go where the pad slides (φ ≈ 72°). The ratio depends on "
        "the drag: this table's 8 µm is 0.8 of the lean; the map below repeats the 90° pull "
        "over drags of 0.25–2 leans. Nothing is tuned to the published numbers.",
        "",
    ]
    lines += map_section(map_rows) if map_rows else []
    return "\n".join(lines)


def sphere_sentence(summary: dict) -> str:
    """What the sphere tips give, with the Savkoor–Briggs sphere's numbers when it ran."""
    text = (
        "A sphere tip has no orientation to lose. With the paper's JKR contact (its radius "
        "set by the overlap alone, as a sliding contact's is: Menga, Carbone & Dini 2018) it "
        "lets go at the normal force −Fc whatever the shear: ×1.00."
    )
    sb = summary.get(f"{TIPS['sphere_sb'][1]}, mu=10")
    if sb is None:
        return text
    return text + (
        " Coupled to its shear as a brittle interface couples them (Savkoor & Briggs 1977: "
        "the stick spring's mode-II release rate counts in Griffith's balance), a sphere "
        "holds less the more shear it carries, whichever its sign: after the gripping drag the "
        f"tip carries {sb['gripping_shear_at_release_uN']:.2f} µN of shear at the 90° "
        f"pull-off and lets go at {sb['gripping_uN']:.2f} µN (the load-controlled "
        "Fc − E*T²/(24πwRG*) at that shear), after the releasing drag at "
        f"{sb['releasing_uN']:.2f} µN: ×{sb['gripping_over_releasing_at_90deg']:.2f}, the "
        "opposite of frictional adhesion. Savkoor–Briggs is the strongest coupling (real "
        "interfaces are tougher in shear, Johnson 1997), so a sphere on this seta gives "
        f"×{sb['gripping_over_releasing_at_90deg']:.2f}–×1.00: shear does not make a sphere "
        "grip; the directional effect needs a tip whose release depends on the force's "
        "direction, the film."
    )


def map_section(rows: list[dict]) -> list[str]:
    """The anisotropy map's table (one row per case and θ) and what it shows."""
    factors = sorted({r["drag_over_lean"] for r in rows})
    head = " / ".join(f"{f:g}" for f in factors)
    lines = [
        "### Anisotropy map: drag distance and seta angle",
        "",
        f"90° pull after a drag of {head} × the seta's lean L cos θ, gripping (−x) and "
        "releasing (+x); ratio = gripping / releasing pull-off; φ = angle of the force at the "
        "pull-off from the gripping shear axis (the film's peel angle; for gripping drags α* "
        "read from that one pull); lean = the seta's angle from the floor after the drag (θ at "
        "rest, > 90° flipped over its tip, < 0° folded flat).",
        "",
        f"| tip, μ | θ | ratio ({head}) | φ gripping [°] | φ releasing [°] | lean after the "
        "gripping drag [°] | lean after the releasing drag [°] |",
        "|---|---|---|---|---|---|---|",
    ]

    def seq(sel, key, fmt):
        return " / ".join(format(r[key], fmt) for r in sel)

    cases = dict.fromkeys((r["tip"], r["mu"], r["theta_deg"]) for r in rows)
    for tip, mu, theta in cases:
        sel = [r for r in rows if (r["tip"], r["mu"], r["theta_deg"]) == (tip, mu, theta)]
        g = sorted(
            (r for r in sel if r["direction"] == "gripping"), key=lambda r: r["drag_over_lean"]
        )
        r_ = sorted(
            (r for r in sel if r["direction"] == "releasing"), key=lambda r: r["drag_over_lean"]
        )
        lean = f"{seq(g, 'lean_after_drag_deg', '.0f')} | {seq(r_, 'lean_after_drag_deg', '.0f')}"
        lines.append(
            f"| {tip}, {mu:g} | {theta:g}° | {seq(g, 'gripping_over_releasing', '.2f')} | "
            f"{seq(g, 'peel_angle_at_pull_off_deg', '.0f')} | "
            f"{seq(r_, 'peel_angle_at_pull_off_deg', '.0f')} | {lean} |"
        )
    ratios = [
        r["gripping_over_releasing"] for r in rows if math.isfinite(r["gripping_over_releasing"])
    ]
    lines += [
        "",
        f"Range of the ratio over the map: ×{min(ratios):.2f} to ×{max(ratios):.2f}"
        + (
            " (0: the tip let go in the gripping drag and did not touch again). "
            if min(ratios) == 0
            else ". "
        )
        + let_go_sentence(rows)
        + "A sphere tip is held tangentially by its adhesive friction μ(P + 2Fc), so a "
        "releasing drag past the lean flips its seta (lean > 90°) and the release force "
        "points over the tip (φ > 90°) — yet the JKR tip lets go at the normal force −Fc "
        "whatever the shear, so its ratio stays 1; the Savkoor–Briggs sphere lets go earlier "
        "the more shear it carries, and the gripping drag loads it more, so its ratio is "
        "below 1. A spatula's film holds a push over its pad "
        "only up to w·b/2, its 180° peel force, but its pressed tip body holds by its own "
        "friction μ·P_c. At μ = 10 the tip sticks: a releasing drag of about the lean stands "
        "the seta upright (lean ≈ 90°) and a longer one flips it, and the 90° pull then peels "
        "the film at φ ≈ 80–90°, near Kendall's w·b; the gripping side gains as the drag "
        "flattens the seta (smaller φ) and stretches its pad, which covers more floor and so "
        f"holds a larger pre-tension by friction{film_lost_clause(rows)}. At "
        "μ = 0.2 (μ·P_c ≈ 0.1 µN) the tip slides under the push, the seta flips only at "
        "θ = 75°, and both pulls let go where the pad slides at its cap (φ ≈ 72°). Autumn "
        "et al. (2000)'s large "
        "gripping/releasing contrast for a seta dragged against its curvature needs a tip "
        "that resists the push (here the tip body's friction, at a large μ) and a "
        "release that sees the force direction (the JKR sphere's sees neither shear nor "
        "direction; the Savkoor–Briggs sphere's sees the shear but not its sign).",
        "",
    ]
    return lines


def below_map_section(rows: list[dict]) -> list[str]:
    """The table of :func:`below_map` and what a negative lean means."""
    lines = [
        "### Below the map: flatter setae",
        "",
        "Spatula, a drag of one lean (L cos θ) either way, 90° pull (`below_map.csv`). Lean < 0: "
        "the seta has folded flat, its root below its tip's centre (the pressing and dragging "
        "shear pushed its tip over its pad against only μ·P_c and the pad's cap, and the "
        "flattening seta ran away); then the protocol measures a folded seta, not a gripping or "
        "releasing one.",
        "",
        "| μ | θ | lean after the drag, gripping / releasing [°] | pull-off, gripping / "
        "releasing [µN] | ratio |",
        "|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['mu']:g} | {r['theta_deg']:g}° | {r['lean_gripping_deg']:.0f} / "
            f"{r['lean_releasing_deg']:.0f} | {r['gripping_uN']:.2f} / {r['releasing_uN']:.2f} "
            f"| ×{r['ratio']:.2f} |"
        )
    return lines + [""]


def film_lost_clause(rows: list[dict]) -> str:
    """ ", until …" when a spatula at μ = 10 lost its film in a gripping drag of the map."""
    lost = [
        r
        for r in rows
        if (r["tip"], r["mu"], r["direction"]) == ("spatula", 10.0, "gripping")
        and math.isfinite(r["let_go_in_drag_at_um"])
    ]
    if not lost:
        return ""
    first = min(lost, key=lambda r: r["drag_over_lean"])
    return (
        ", until the flattening seta pulls the film off in the drag itself (from "
        f"{first['drag_over_lean']:g} leans at θ = {first['theta_deg']:g}°)"
    )


def let_go_sentence(rows: list[dict]) -> str:
    """Which map runs lost their tip in the drag
    (:func:`gecko_agents.analysis.drag.let_go_in_drag`), and what followed."""
    lost = [r for r in rows if math.isfinite(r["let_go_in_drag_at_um"])]
    if not lost:
        return "Every tip held through its drag. "
    cases = "; ".join(
        f"{r['tip']}, μ = {r['mu']:g}, θ = {r['theta_deg']:g}°, {r['direction']} "
        f"{r['drag_over_lean']:g} leans: let go at {r['let_go_in_drag_at_um']:.1f} of "
        f"{abs(r['drag_um']):.1f} µm, "
        + (
            f"touched again, lean {r['lean_after_drag_deg']:.0f}° after the drag"
            if r["attached_after_drag"]
            else "did not touch again"
        )
        for r in lost
    )
    return (
        f"Tips that let go in the drag itself ({cases}): the pull after such a drag starts from "
        "the contact the tip made again, or from none. "
    )
