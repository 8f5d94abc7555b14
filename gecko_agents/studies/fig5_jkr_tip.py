"""Paper Fig 5: one JKR tip (R = 4 µm) — force vs contact radius and force vs overlap.

Panel (a) is eq 7, P(a); panel (b) is eq 7 against eq 10, P(δ), walked the way the paper's
text walks it: approach O → A (jump-in at δ = 0 to −(8/9)Fc), on along the branch through
B (zero load, δ0) into compression; retract back along the stable branch past C (maximum
adhesion −Fc, the load-controlled pull-off at a = 0.63 a0) down to D (δc, −(5/9)Fc, the
displacement-controlled end of the branch) and the jump D → E (δc, 0). The part of eq 10
below a(δc) cannot be reached and is drawn dotted.

Both readings of the work of adhesion are drawn: the paper's stated rule w = 2√(γ1γ2) with
γ1 = 40, γ2 = 170 mJ/m² (w = 0.165 J/m², PAPER_TABLE1) and w = 0.080 J/m², the value Fig 5's
−1.5 µN implies (PAPER_FIG5_READING). The paper's quoted points are drawn as open squares.

Writes fig5a_<reading>.png, fig5b_<reading>.png, points.csv (every marked point, both
readings), claims.csv and metadata.json into renders/fig5_jkr_tip/ (or --out).
"""

from __future__ import annotations

import matplotlib as mpl
import numpy as np
from scipy.optimize import brentq

from gecko_agents.params import PAPER_FIG5_READING, PAPER_TABLE1
from gecko_agents.physics import jkr
from gecko_agents.render import (
    APPROACH_COLOUR,
    RETRACT_COLOUR,
    STYLE_RC,
    plot_force_curves,
    save_figure,
)
from gecko_agents.studies.common import (
    GREY,
    PAPER_DELTA_S_COEF,
    claim,
    command_line,
    num,
    off_paper,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "fig5_jkr_tip"

# The paper's numbers, as printed (section 3.1): (overlap [µm], force [µN]) in Fig 5b,
# (contact radius [µm], force [µN]) for C in Fig 5a. Typed in; compared, never fitted.
PAPER_A = (0.0, -1.35)
PAPER_C_FORCE, PAPER_C_RADIUS = -1.5, 1.24  # maximum adhesion [µN] at a [µm]
PAPER_D = (-0.8, -0.75)
PAPER_E = (-0.8, 0.0)

READINGS = {
    "stated_w": (PAPER_TABLE1, "stated w = 2√(γ1γ2)"),
    "fig5_reading": (PAPER_FIG5_READING, "Fig 5 reading w = 0.080 J/m²"),
}


def key_points(contact) -> dict:
    """Every marked point of Fig 5 for one Contact: (a [µm], δ [µm], P [µN]) plus scalars."""
    R, w, E = contact.jkr_args()
    Fc = float(jkr.pull_off_force(R, w))
    a0 = float(jkr.zero_load_contact_radius(R, w, E))
    a_A = float(jkr.radius_from_overlap(0.0, R, w, E))
    a_C = float(jkr.contact_radius_from_force(-Fc, R, w, E))
    a_D = float(jkr.snap_off_radius(R, w, E))
    d_C = float(jkr.overlap_from_radius(a_C, R, w, E))
    d_D = float(jkr.snap_off_overlap(R, w, E))
    delta_s = PAPER_DELTA_S_COEF * a0**2 / R
    pts = {
        "O": (None, 0.0, 0.0),  # no contact: no radius
        "A": (a_A, 0.0, float(jkr.force_from_overlap(0.0, R, w, E))),
        "B": (a0, float(jkr.overlap_from_radius(a0, R, w, E)), 0.0),
        "C": (a_C, d_C, -Fc),
        "D": (a_D, d_D, float(jkr.force_from_radius(a_D, R, w, E))),
        "E": (None, d_D, 0.0),
    }
    return {
        "R": R,
        "w": w,
        "E_star": E,
        "Fc": Fc,
        "a0": a0,
        "points": pts,
        "delta_s": delta_s,
        "P_at_delta_s": float(jkr.force_from_overlap(delta_s, R, w, E)),
        "delta_c_over_a0sq_R": d_D * R / a0**2,
        "delta_C_over_a0sq_R": d_C * R / a0**2,
        "a_C_over_a0": a_C / a0,
    }


def curves_for(contact, n: int, kp: dict, d_min: float) -> tuple[list, list]:
    """Curve dicts for panels (a) and (b)."""
    R, w, E = contact.jkr_args()
    Fc, pts = kp["Fc"], kp["points"]
    a_D = pts["D"][0]
    # Branch drawn up to a compressive force of 2 Fc (well into Hertz-like compression).
    a_max = float(jkr.contact_radius_from_force(2.0 * Fc, R, w, E))
    a_unst = np.linspace(0.0, a_D, max(n // 4, 20))
    a_st = np.linspace(a_D, a_max, n)
    P_unst = jkr.force_from_radius(a_unst, R, w, E)
    P_st = jkr.force_from_radius(a_st, R, w, E)
    d_unst = jkr.overlap_from_radius(a_unst, R, w, E)
    d_st = jkr.overlap_from_radius(a_st, R, w, E)

    panel_a = [
        {
            "x": a_st,
            "y": P_st,
            "label": "eq 7, reachable branch (a ≥ a_D)",
            "style": {"color": "k"},
        },
        {
            "x": a_unst,
            "y": P_unst,
            "label": "eq 7, a < a_D (never reached)",
            "style": {"color": GREY, "ls": ":"},
        },
        {
            "x": [PAPER_C_RADIUS],
            "y": [PAPER_C_FORCE],
            "label": f"paper's C ({PAPER_C_RADIUS:g} µm, {num(PAPER_C_FORCE, 'g')} µN)",
            "style": {"ls": "", "marker": "s", "mfc": "none", "color": GREY, "markersize": 8},
        },
    ]

    d_A, P_A = pts["A"][1:]
    d_D, P_D = pts["D"][1:]
    on_branch_from_A = a_st >= pts["A"][0]
    panel_b = [
        # Approach: free (P = 0) up to O, jump O → A, then along the branch into compression.
        {
            "x": np.concatenate([[d_min, 0.0, d_A], d_st[on_branch_from_A]]),
            "y": np.concatenate([[0.0, 0.0, P_A], P_st[on_branch_from_A]]),
            "label": "approach: O → A jump, A → B → compression",
            "style": {"color": APPROACH_COLOUR, "lw": 4.5, "alpha": 0.45, "solid_capstyle": "butt"},
        },
        # Retract: back along the stable branch to D, jump D → E, free again.
        {
            "x": np.concatenate([d_st[::-1], [d_D, d_D, d_min]]),
            "y": np.concatenate([P_st[::-1], [P_D, 0.0, 0.0]]),
            "label": "retract: B → A → C → D, jump D → E",
            "style": {"color": RETRACT_COLOUR, "lw": 1.5},
        },
        {
            "x": d_unst,
            "y": P_unst,
            "label": "eq 10, a < a_D (never reached)",
            "style": {"color": GREY, "ls": ":"},
        },
        {
            "x": [PAPER_A[0], PAPER_D[0], PAPER_E[0]],
            "y": [PAPER_A[1], PAPER_D[1], PAPER_E[1]],
            "label": "paper's A, D, E as printed",
            "style": {"ls": "", "marker": "s", "mfc": "none", "color": GREY, "markersize": 8},
        },
    ]
    return panel_a, panel_b


def draw(key: str, contact, title: str, kp: dict, n: int, out, d_min: float) -> list:
    """Write fig5a_<key>.png and fig5b_<key>.png; return the paths."""
    panel_a, panel_b = curves_for(contact, n, kp, d_min)
    pts = kp["points"]
    paths = []
    for panel, curves, names, col, xlabel, xname in (
        ("a", panel_a, "ABCD", 0, "contact radius a [µm]", "a"),
        ("b", panel_b, "OABCDE", 1, "contact depth (overlap) δ [µm]", "δ"),
    ):
        fig = plot_force_curves(
            curves,
            None,
            xlabel=xlabel,
            ylabel="contact force P [µN]",
            title=f"Fig 5{panel}: R = {kp['R']:g} µm, E* = {kp['E_star']:.3f} MPa, "
            f"w = {kp['w']:.4f} J/m²\n({title})",
            points=[(pts[k][col], pts[k][2], k) for k in names],
        )
        ax = fig.axes[0]
        table = "\n".join(
            f"{k}: {xname} = {num(pts[k][col])} µm, P = {num(pts[k][2])} µN" for k in names
        )
        with mpl.rc_context(STYLE_RC):
            ax.axhline(0.0, color="#888888", lw=0.6, zorder=1)
            ax.axvline(0.0, color="#888888", lw=0.6, zorder=1)
            ax.plot([], [], " ", label=table)
            ax.margins(y=0.08)
            ax.legend(loc="best", fontsize=8)
        path = out / f"fig5{panel}_{key}.png"
        save_figure(fig, path)
        paths.append(path)
    return paths


def what_the_paper_needs(kp: dict, alt: dict, alt_contact) -> dict:
    """What the paper's printed C radius and D overlap would need, solved with the package's
    own functions: E* [MPa] for 1.24 µm at w = 0.080; w [J/m²] (and P(δc) [µN]) for δc =
    −0.8 µm at the stated E*; w and γ1 [J/m²] for 1.24 µm at the stated E*."""
    R, w_alt, _ = alt_contact.jkr_args()
    E_needed = brentq(
        lambda E: float(jkr.contact_radius_from_force(-alt["Fc"], R, w_alt, E)) - PAPER_C_RADIUS,
        1e-3,
        1e3,
        xtol=1e-12,
    )
    w_for_D = brentq(
        lambda w: float(jkr.snap_off_overlap(R, w, kp["E_star"])) - PAPER_D[0],
        1e-4,
        10.0,
        xtol=1e-12,
    )

    def a_C_of_w(w):  # load-controlled pull-off radius at the stated E*
        return float(jkr.contact_radius_from_force(-jkr.pull_off_force(R, w), R, w, kp["E_star"]))

    w_for_C = brentq(lambda w: a_C_of_w(w) - PAPER_C_RADIUS, 1e-4, 10.0, xtol=1e-14)
    g1_for_C = brentq(
        lambda g: float(jkr.work_of_adhesion(g, alt_contact.gamma2)) - w_for_C,
        1e-8,
        10.0,
        xtol=1e-14,
    )
    return {
        "E_needed": E_needed,
        "w_for_D": w_for_D,
        "P_for_D": float(jkr.force_from_overlap(PAPER_D[0], R, w_for_D, kp["E_star"])),
        "w_for_C": w_for_C,
        "g1_for_C": g1_for_C,
    }


def _claim_A(kp: dict, alt: dict) -> dict:
    """Fig 5b: the jump-in point A."""
    w_s, w_a = num(kp["w"], ".3f"), num(alt["w"], ".3f")
    s, a = kp["points"], alt["points"]
    return claim(
        "Fig 5b",
        "point A: the approach jumps in at zero overlap to (0, −1.35 µN)",
        "A = (0, −1.35 µN)",
        f"A = (0, {num(s['A'][2], '.3f')} µN) = −(8/9)Fc at w = {w_s} J/m²",
        "not reproducible from the stated parameters",
        f"w = 2√(γ1γ2) = {w_s} J/m² doubles every adhesive force, and −1.35 µN is "
        f"−(8/9)Fc only for w ≈ {w_a} J/m².",
        f"A = (0, {num(a['A'][2], '.3f')} µN) at w = {w_a} J/m² "
        f"({off_paper(a['A'][2], PAPER_A[1])})",
    )


def _claim_C_force(kp: dict, alt: dict, alt_contact) -> dict:
    """Fig 5a: the maximum adhesion force at C."""
    w_a = num(alt["w"], ".3f")
    return claim(
        "Fig 5a",
        "point C: maximum adhesion force −1.5 µN",
        "−1.5 µN",
        f"−Fc = −1.5πRw = {num(-kp['Fc'], '.3f')} µN",
        "not reproducible from the stated parameters",
        f"The stated γ1, γ2 give Fc = {num(kp['Fc'], '.2f')} µN; −1.5 µN at R = "
        f"{kp['R']:g} µm needs w = {w_a} J/m² (= {num(alt['w'] / alt_contact.gamma1, '.2f')}"
        " γ1).",
        f"−Fc = {num(-alt['Fc'], '.3f')} µN at w = {w_a} J/m² "
        f"({off_paper(-alt['Fc'], PAPER_C_FORCE)})",
    )


def _claim_C_radius(kp: dict, alt: dict, alt_contact, need: dict) -> dict:
    """Fig 5a: the contact radius at C."""
    w_a = num(alt["w"], ".3f")
    R = alt_contact.R
    return claim(
        "Fig 5a",
        "point C: contact radius 1.24 µm at maximum adhesion",
        "a = 1.24 µm",
        f"a = {num(kp['points']['C'][0], '.3f')} µm (= {num(kp['a_C_over_a0'], '.3f')} a0, "
        f"a0 = {num(kp['a0'], '.3f')} µm)",
        "not reproducible from the stated parameters",
        f"JKR puts the load-controlled pull-off at a = 0.63 a0 for any w, and neither "
        f"reading gives 1.24 µm: at w = {w_a} J/m² it would need "
        f"E* = {num(need['E_needed'], '.2f')} MPa instead of {num(alt['E_star'], '.3f')} MPa.",
        f"a = {num(alt['points']['C'][0], '.3f')} µm at w = {w_a} J/m² "
        f"({off_paper(alt['points']['C'][0], PAPER_C_RADIUS)}); 1.24 µm at the stated E* "
        f"needs w = {num(need['w_for_C'], '.4f')} J/m², i.e. γ1 = "
        f"{1e3 * need['g1_for_C']:.2f} mJ/m² with γ2 = {1e3 * alt_contact.gamma2:g} mJ/m², "
        f"whose Fc is {num(jkr.pull_off_force(R, need['w_for_C']))} µN",
    )


def _claim_D(kp: dict, alt: dict, need: dict) -> dict:
    """Fig 5b: the end of contact D and the jump D → E."""
    s, a = kp["points"], alt["points"]
    w_a = num(alt["w"], ".3f")
    return claim(
        "Fig 5b",
        "point D (−0.8, −0.75) ends the contact; jump D → E (−0.8, 0)",
        "D = (−0.8 µm, −0.75 µN), E = (−0.8 µm, 0)",
        f"D = (δc, −(5/9)Fc) = ({num(s['D'][1], '.3f')} µm, {num(s['D'][2], '.3f')} µN); "
        f"the paper's own δs = −0.21a0²/R = {num(kp['delta_s'], '.3f')} µm "
        f"(P there {num(kp['P_at_delta_s'], '.3f')} µN)",
        "not reproducible from the stated parameters",
        f"The branch ends at δc, so no contact exists at δ = −0.8 µm for either reading; "
        f"δc = −0.8 µm would need w = {num(need['w_for_D'], '.3f')} J/m² (then P(δc) = "
        f"{num(need['P_for_D'], '.2f')} µN), and the printed ratio D/C = "
        f"{num(PAPER_D[1] / PAPER_C_FORCE, '.2f')} is not JKR's 5/9 = {num(5 / 9, '.3f')}.",
        f"w = {w_a}: D = ({num(a['D'][1], '.3f')} µm, {num(a['D'][2], '.3f')} µN), "
        f"δs = {num(alt['delta_s'], '.3f')} µm "
        f"(P there {num(alt['P_at_delta_s'], '.3f')} µN)",
    )


def _claim_delta_s(kp: dict, alt: dict) -> dict:
    """Section 2.1: the paper's separation displacement δs = −0.21 a0²/R."""
    return claim(
        "Sec 2.1",
        "separation displacement δs = −0.21 a0²/R",
        "δs = −0.21 a0²/R",
        f"displacement control δc = {num(kp['delta_c_over_a0sq_R'], '.3f')} a0²/R; "
        f"load control δ(C) = {num(kp['delta_C_over_a0sq_R'], '.3f')} a0²/R",
        "not reproducible from the stated parameters",
        "The coefficient −0.21 matches neither JKR end of contact (both coefficients are "
        "the same for every R, w and E*); it lies between them.",
        f"w = {num(alt['w'], '.3f')}: {num(alt['delta_c_over_a0sq_R'], '.3f')} and "
        f"{num(alt['delta_C_over_a0sq_R'], '.3f')} a0²/R",
    )


def build_claims(kp: dict, alt: dict, alt_contact) -> list[dict]:
    """The paper-comparison rows for Fig 5 (ours: stated w; alternative: w = 0.080)."""
    need = what_the_paper_needs(kp, alt, alt_contact)
    return [
        _claim_A(kp, alt),
        _claim_C_force(kp, alt, alt_contact),
        _claim_C_radius(kp, alt, alt_contact, need),
        _claim_D(kp, alt, need),
        _claim_delta_s(kp, alt),
    ]


def point_rows(kps: dict) -> list[dict]:
    """points.csv: every marked point of both readings, and the paper's δs (µm, µN)."""
    rows = []
    for key, kp in kps.items():
        for name, (a, d, P) in kp["points"].items():
            rows.append(
                {
                    "reading": key,
                    "w_J_m2": kp["w"],
                    "E_star_MPa": kp["E_star"],
                    "point": name,
                    "contact_radius_um": a,
                    "overlap_um": d,
                    "force_uN": P,
                }
            )
        rows.append(
            {
                "reading": key,
                "w_J_m2": kp["w"],
                "E_star_MPa": kp["E_star"],
                "point": "paper_delta_s",
                "contact_radius_um": None,
                "overlap_um": kp["delta_s"],
                "force_uN": kp["P_at_delta_s"],
            }
        )
    return rows


def summary(kp: dict) -> dict:
    """One reading's numbers for metadata.json (µm, µN, J/m², MPa)."""
    return {
        "w_J_m2": kp["w"],
        "E_star_MPa": kp["E_star"],
        "Fc_uN": kp["Fc"],
        "a0_um": kp["a0"],
        "delta_s_paper_um": kp["delta_s"],
        "points": {
            k: {"contact_radius_um": v[0], "overlap_um": v[1], "force_uN": v[2]}
            for k, v in kp["points"].items()
        },
    }


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    n = 150 if args.quick else 1200

    kps = {key: key_points(p.contact) for key, (p, _) in READINGS.items()}
    # Shared overlap window: both readings' δc and the paper's printed D must be visible.
    d_min = 1.25 * min([kp["points"]["D"][1] for kp in kps.values()] + [PAPER_D[0]])
    figures = []
    for key, (p, title) in READINGS.items():
        figures += draw(key, p.contact, title, kps[key], n, out, d_min)

    write_table(out / "points.csv", point_rows(kps))

    stated, alt = kps["stated_w"], kps["fig5_reading"]
    claims = build_claims(stated, alt, PAPER_FIG5_READING.contact)
    write_table(out / "claims.csv", claims)

    results = {key: summary(kp) for key, kp in kps.items()}
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "curve_points": n,
            "params": {key: p.to_dict() for key, (p, _) in READINGS.items()},
            "results": results,
            "claims": claims,
            "figures": [f.name for f in figures],
        },
    )
    return {
        "claims": claims,
        "out": str(out),
        **results,
        "Fc_uN": stated["Fc"],
        "Fc_fig5_reading_uN": alt["Fc"],
        "point_A_uN": stated["points"]["A"][2],
        "point_A_fig5_reading_uN": alt["points"]["A"][2],
        "delta_c_um": stated["points"]["D"][1],
        "delta_c_fig5_reading_um": alt["points"]["D"][1],
    }


if __name__ == "__main__":
    res = main()
    for row in res["claims"]:
        print(
            f"[{row['figure']}] {row['claim']}\n  paper: {row['paper']}\n  ours:  {row['ours']}"
            f"\n  alt:   {row['alternative']}\n  -> {row['verdict']}: {row['reason']}"
        )
