"""Adhesion left after a preload past buckling, with the faces' edges free to open
(``contact.edge_opening``, :mod:`gecko_agents.model.face_opening`): round-edged flat punches
against mushrooms, at three pillar radii.

Part of the pillar-designs study (:mod:`gecko_agents.studies.pillar_designs`, which writes
``pillar_buckling.csv`` and ``pillar_buckling.png``). Single vertical pillars of the study's
polyurethane (L/2r = 5) are pressed 1 %, 20 % or 40 % of their length and pulled off. The
punch's edge is round (an edge crack, Kendall's); the mushroom's flange (1.2 × the stalk,
σ₀ = 1 MPa) has a sharp 45° rim, which is not singular, so no moment opens it. By the
tilted-punch criterion a buckled pillar's face opens where 3|M|/a − P reaches Kendall's force;
M grows as the pillar's E·r³ and Kendall's force as √(E*w)·r^1.5, so the criterion is met by
large pillars first (√r): the 1.5 µm punch keeps its pull-off after presses of 20 % and 40 %
of L, the 5 µm one keeps it after 20 % and loses all of it after 40 %, the 15 µm one loses it
after 20 %; the mushrooms keep theirs (within 0.5 %) at every radius and press. Experiments:
round-edged fibrils lose adhesion at buckling preloads, fibrils with end flaps keep it
(Paretkar et al. 2013, J R Soc Interface 10:20130171, abstract read).
"""

from __future__ import annotations

from gecko_agents import protocol, render
from gecko_agents.model import Model, Numerics

__all__ = ["TIPS", "buckling_rows", "draw_buckling", "buckling_section"]

TIPS = ("flat_punch", "mushroom")


def params_for(base, tip: str, r: float):
    """One pillar of radius r [µm], aspect L/2r = 5, faces free to open (the study's base)."""
    over = {
        "tip": tip,
        "seta.r": r,
        "contact.R": r,
        "seta.L": 10.0 * r,
        "array.count": 1,
        "array.pitch": 8.0 * r / 3.0,
        "spatula.b": 2.0 * r,
        "contact.edge_opening": True,
    }
    if tip == "mushroom":
        over |= {
            "contact.R": 1.2 * r,
            "contact.sigma0": 1.0,
            "mushroom.rim": "sharp",
            "mushroom.rim_angle_deg": 45.0,
        }
    return base.replace(**over)


def buckling_rows(base, radii, strains, speed: float) -> list[dict]:
    """Pull-off after each press, over that after the 1 % press, for each tip and radius."""
    rows = []
    for tip in TIPS:
        for r in radii:
            p = params_for(base, tip, float(r))
            first = None
            for eps in strains:
                # half the default step: a large punch let go at its full pull-off books the
                # release step's O(F²dt²/m) energy error (tests/test_face_opening.py)
                dt = 0.5 * Model(p, n_sim=1, seed=0).dt
                m = Model(p, n_sim=1, seed=0, numerics=Numerics(dt=dt))
                h = m.run(protocol.press_pull(eps * p.seta.L, speed=speed), progress=False)
                F = h.peak_pull_off
                first = F if first is None else first
                rows.append(
                    {
                        "tip": tip,
                        "radius_um": float(r),
                        "press_strain": eps,
                        "preload_uN": float(h["force_normal_uN"].max()),
                        "pull_off_uN": F,
                        "over_lightest_press": F / first,
                        "faces_opened": int(m.physics.opening.count),
                    }
                )
    return rows


def draw_buckling(rows, out) -> None:
    """Pull-off over that after the lightest press against the press depth."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(6.4, 4.2), layout="constrained")
        ax = fig.subplots()
        for tip, ls, mk in (("flat_punch", "-", "s"), ("mushroom", "--", "D")):
            for r in dict.fromkeys(x["radius_um"] for x in rows):
                sel = [x for x in rows if x["tip"] == tip and x["radius_um"] == r]
                ax.plot(
                    [100 * x["press_strain"] for x in sel],
                    [x["over_lightest_press"] for x in sel],
                    ls=ls,
                    marker=mk,
                    label=f"{tip}, r = {r:g} µm",
                )
        ax.set_xlabel("press depth [% of L] (past buckling above ~2 %)")
        ax.set_ylabel("pull-off / pull-off after a 1 % press")
        ax.set_title("adhesion left after buckling, edges free to open")
        ax.legend(fontsize="small")
        render.save_figure(fig, out / "pillar_buckling.png")


def buckling_section(rows) -> str:
    """The report's lines: what is left after the deepest press, per tip and radius."""
    deepest = max(x["press_strain"] for x in rows)
    lines = [
        f"- {x['tip']}, r = {x['radius_um']:g} µm: ×{x['over_lightest_press']:.3g} "
        f"(faces opened by their moment: {x['faces_opened']})"
        for x in rows
        if x["press_strain"] == deepest
    ]
    head = (
        f"Adhesion left after a press of {100 * deepest:g} % of L, past buckling, edges "
        "free to open (`pillar_designs/pillar_buckling.png`), over that after a 1 % press:"
    )
    return "\n".join([head, "", *lines, ""])
