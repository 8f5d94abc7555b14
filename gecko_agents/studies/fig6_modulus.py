"""Paper Fig 6: JKR tip contact for seta moduli E1 = 0.1, 1 and 10 MPa.

Panel (a): contact radius vs force (eq 8 / eq 7); panel (b): force vs overlap (eq 7 with
eq 10). Everything else is the paper's section 3.1.1 set (PAPER_TABLE1: R = 4 µm, ν1 = 0.3,
floor 55 GPa with ν2 = 0.25, w = 2√(γ1γ2) = 0.165 J/m²). Solid: the branch a tip can follow
(down to the displacement-controlled end D at δc); dotted: the rest of eq 7/10, never
reached; dashed in (b): the jump D → E to zero force. C marks the load-controlled pull-off
(−Fc at a = 0.63 a0), the same force for every modulus.

The paper's radii (3.69 µm at 0.1 MPa, 0.74 µm at 10 MPa "under the same contact force") are
drawn as grey lines in (a). sweep.csv lists, per modulus, the radius and overlap at common forces
(−Fc, 0 and +1 µN), the pull-off force and the end of contact.

Writes fig6a.png, fig6b.png, sweep.csv, claims.csv and metadata.json into
renders/fig6_modulus/ (or --out).
"""

from __future__ import annotations

from scipy.optimize import brentq

from gecko_agents.params import PAPER_FIG5_READING, PAPER_TABLE1
from gecko_agents.physics import jkr
from gecko_agents.studies.common import (
    GREY,
    claim,
    command_line,
    jkr_family,
    num,
    output_dir,
    parse_args,
    rel_off,
    save_on_zero_axes,
    write_json,
    write_table,
)

NAME = "fig6_modulus"
MODULI_MPA = (0.1, 1.0, 10.0)  # E1, the paper's three values
COMMON_FORCE_UN = 1.0  # a compressive force shared by all moduli [µN], besides 0 and −Fc
# The paper's numbers (section 3.1.1), typed in for comparison only.
PAPER_RADIUS_LOW_E, PAPER_RADIUS_HIGH_E = 3.69, 0.74  # µm at 0.1 MPa and at 10 MPa


def inner_radius(P: float, R: float, w: float, E: float) -> float:
    """Contact radius on the branch a < 0.63 a0 where eq 7 gives the tensile force P [µm].

    eq 8 (:func:`jkr.contact_radius_from_force`) returns the other root, a ≥ 0.63 a0; on
    0 < a < 0.63 a0 eq 7 falls monotonically from 0 to −Fc, so the root is bracketed there.
    """
    a_C = float(jkr.contact_radius_from_force(-jkr.pull_off_force(R, w), R, w, E))
    return brentq(
        lambda a: float(jkr.force_from_radius(a, R, w, E)) - P, 1e-12 * a_C, a_C, xtol=1e-14
    )


def contact_numbers(contact) -> dict:
    """Key numbers of one tip: radii and overlaps at the common forces, pull-off, end of contact."""
    R, w, E = contact.jkr_args()
    Fc = float(jkr.pull_off_force(R, w))
    a_C = float(jkr.contact_radius_from_force(-Fc, R, w, E))
    a_D = float(jkr.snap_off_radius(R, w, E))
    d_D = float(jkr.snap_off_overlap(R, w, E))
    out = {
        "E1_MPa": contact.E1,
        "E_star_MPa": E,
        "w_J_m2": w,
        "Fc_uN": Fc,
        "a_pull_off_um": a_C,
        "overlap_pull_off_um": float(jkr.overlap_from_radius(a_C, R, w, E)),
        "a_end_um": a_D,
        "overlap_end_um": d_D,
        "force_end_uN": float(jkr.force_from_radius(a_D, R, w, E)),
    }
    for tag, P in (("0", 0.0), (f"{COMMON_FORCE_UN:g}uN", COMMON_FORCE_UN)):
        a = float(jkr.contact_radius_from_force(P, R, w, E))
        out[f"a_at_{tag}_um"] = a
        out[f"overlap_at_{tag}_um"] = float(jkr.overlap_from_radius(a, R, w, E))
    return out


def _curves(contacts: list, rows: list[dict], n: int, P_max: float) -> tuple[list, ...]:
    """Curves (:func:`~gecko_agents.studies.common.jkr_family`) and marked points of panels
    (a) and (b), per modulus."""
    labels = [f"E1 = {r['E1_MPa']:g} MPa (E* = {r['E_star_MPa']:.3g} MPa)" for r in rows]
    ends = [
        f"{lab}: D at δc = {num(r['overlap_end_um'])} µm"
        for lab, r in zip(labels, rows, strict=True)
    ]
    ca, cb = jkr_family(contacts, rows, labels, ends, n, P_max)
    pa, pb = [], []
    for row in rows:
        pa += [
            (0.0, row["a_at_0_um"], f"a0 = {num(row['a_at_0_um'])} µm"),
            (-row["Fc_uN"], row["a_pull_off_um"], f"C: {num(row['a_pull_off_um'])} µm"),
        ]
        pb += [(row["overlap_end_um"], row["force_end_uN"], "D")]
    return ca, cb, pa, pb


def _add_paper_lines(ca: list, cb: list, f_lo: float, P_max: float) -> None:
    """Append the paper's two radii to panel (a) as grey dashed lines over [f_lo, P_max] [µN],
    and the legend notes on the line styles to both panels."""
    for radius in (PAPER_RADIUS_LOW_E, PAPER_RADIUS_HIGH_E):
        ca.append(
            {
                "x": [f_lo, P_max],
                "y": [radius, radius],
                "label": None
                if radius == PAPER_RADIUS_HIGH_E
                else f"paper: {PAPER_RADIUS_LOW_E:g} µm at {MODULI_MPA[0]:g} MPa, "
                f"{PAPER_RADIUS_HIGH_E:g} µm at {MODULI_MPA[-1]:g} MPa",
                "style": {"color": GREY, "ls": "--", "lw": 0.9},
            }
        )
    ca.append(
        {
            "x": [],
            "y": [],
            "label": "dotted: a < a(δc), never reached",
            "style": {"color": GREY, "ls": ":"},
        }
    )
    cb.append(
        {
            "x": [],
            "y": [],
            "label": "dotted: a < a(δc), never reached;\ndashed: jump D → E (contact lost)",
            "style": {"color": GREY, "ls": ":"},
        }
    )


def draw(contacts: list, rows: list[dict], n: int, out) -> list:
    """fig6a.png (radius vs force) and fig6b.png (force vs overlap)."""
    P_max = 2.0 * max(r["Fc_uN"] for r in rows)
    ca, cb, pa, pb = _curves(contacts, rows, n, P_max)
    _add_paper_lines(ca, cb, -max(r["Fc_uN"] for r in rows), P_max)
    sub = f"R = {contacts[0].R:g} µm, w = {rows[0]['w_J_m2']:.4f} J/m²"
    return [
        save_on_zero_axes(
            ca,
            pa,
            ("contact force P [µN]", "contact radius a [µm]"),
            f"Fig 6a: contact radius vs force, {sub}",
            out / "fig6a.png",
            head_room=0.5,
        ),
        save_on_zero_axes(
            cb,
            pb,
            ("contact depth (overlap) δ [µm]", "contact force P [µN]"),
            f"Fig 6b: force vs contact depth, {sub}",
            out / "fig6b.png",
            head_room=0.0,
        ),
    ]


def paper_radii(contacts: list, rows: list[dict]) -> dict:
    """Radius ratios of the lowest to the highest modulus at the common forces, and the
    forces at which each curve has the paper's radius, with the other modulus's two radii
    (a < 0.63 a0 and a ≥ 0.63 a0) at that force [µm, µN]."""
    lo, hi = contacts[0], contacts[-1]
    r_lo, r_hi = rows[0], rows[-1]
    # Radius ratio low-E/high-E at each common force (JKR: the same at every force).
    ratios = {
        "−Fc": r_lo["a_pull_off_um"] / r_hi["a_pull_off_um"],
        "0": r_lo["a_at_0_um"] / r_hi["a_at_0_um"],
        f"{COMMON_FORCE_UN:g} µN": (
            r_lo[f"a_at_{COMMON_FORCE_UN:g}uN_um"] / r_hi[f"a_at_{COMMON_FORCE_UN:g}uN_um"]
        ),
    }
    # Which force gives the paper's radius on each curve, and what the other modulus has there.
    P1 = float(jkr.force_from_radius(PAPER_RADIUS_LOW_E, *lo.jkr_args()))
    P2 = float(jkr.force_from_radius(PAPER_RADIUS_HIGH_E, *hi.jkr_args()))
    hi_at_P1 = (
        inner_radius(P1, *hi.jkr_args()),
        float(jkr.contact_radius_from_force(P1, *hi.jkr_args())),
    )
    lo_at_P2 = (
        inner_radius(P2, *lo.jkr_args()),
        float(jkr.contact_radius_from_force(P2, *lo.jkr_args())),
    )
    return {
        "radius_ratio_at_common_force": ratios,
        "paper_radius_ratio": PAPER_RADIUS_LOW_E / PAPER_RADIUS_HIGH_E,
        "force_for_paper_low_E_radius_uN": P1,
        "force_for_paper_high_E_radius_uN": P2,
        "high_E_radii_at_that_force_um": hi_at_P1,
        "low_E_radii_at_that_force_um": lo_at_P2,
    }


def _claim_radius(rows: list[dict], alt_rows: list[dict], nb: dict) -> dict:
    """Fig 6a: the radius under the same force against the modulus."""
    r_lo, r_hi = rows[0], rows[-1]
    a_lo, a_hi = alt_rows[0], alt_rows[-1]
    ratios, paper_ratio = nb["radius_ratio_at_common_force"], nb["paper_radius_ratio"]
    P1, P2 = nb["force_for_paper_low_E_radius_uN"], nb["force_for_paper_high_E_radius_uN"]
    hi_at_P1, lo_at_P2 = nb["high_E_radii_at_that_force_um"], nb["low_E_radii_at_that_force_um"]
    branch1 = "a < 0.63a0" if PAPER_RADIUS_LOW_E < r_lo["a_pull_off_um"] else "a ≥ 0.63a0"
    branch2 = "a < 0.63a0" if PAPER_RADIUS_HIGH_E < r_hi["a_pull_off_um"] else "a ≥ 0.63a0"
    E_lo, E_hi = f"{r_lo['E1_MPa']:g} MPa", f"{r_hi['E1_MPa']:g} MPa"
    return claim(
        "Fig 6a",
        "contact radius under the same force falls from 3.69 µm (0.1 MPa) to 0.74 µm (10 MPa)",
        f"3.69 → 0.74 µm (×{paper_ratio:.2f})",
        f"a({E_lo})/a({E_hi}) = "
        + ", ".join(f"{v:.3f}" for v in ratios.values())
        + " at P = "
        + ", ".join(ratios)
        + f" (e.g. zero load "
        f"{num(r_lo['a_at_0_um'])} → {num(r_hi['a_at_0_um'])} µm); 3.69 µm at {E_lo} needs "
        f"P = {num(P1)} µN ({branch1}), where {E_hi} gives {num(hi_at_P1[0], '.3f')} or "
        f"{num(hi_at_P1[1], '.3f')} µm; 0.74 µm at {E_hi} needs P = {num(P2)} µN "
        f"({branch2}), where {E_lo} gives {num(lo_at_P2[0], '.3f')} or "
        f"{num(lo_at_P2[1], '.3f')} µm",
        "trend reproduced",
        f"JKR shrinks the radius by (E*({E_hi})/E*({E_lo}))^(1/3) = {ratios['0']:.2f} at any "
        f"common force, so no single force gives both 3.69 and 0.74 µm (×{paper_ratio:.2f}).",
        f"w = {alt_rows[0]['w_J_m2']:.3f} J/m²: at the common pull-off force −Fc = "
        f"{num(-a_lo['Fc_uN'], '.3f')} µN, a = {num(a_lo['a_pull_off_um'], '.3f')} → "
        f"{num(a_hi['a_pull_off_um'], '.3f')} µm "
        f"({rel_off(a_lo['a_pull_off_um'], PAPER_RADIUS_LOW_E)} and "
        f"{rel_off(a_hi['a_pull_off_um'], PAPER_RADIUS_HIGH_E)} off the paper's radii); "
        f"zero load {num(a_lo['a_at_0_um'], '.3f')} → {num(a_hi['a_at_0_um'], '.3f')} µm",
    )


def _claim_push_off(rows: list[dict], alt_rows: list[dict]) -> dict:
    """Fig 6: the maximum push-off force against the modulus."""
    Fcs = ", ".join(num(r["Fc_uN"], ".3f") for r in rows)
    ends = ", ".join(num(r["force_end_uN"], ".3f") for r in rows)
    Es = ", ".join(f"{r['E1_MPa']:g}" for r in rows)
    return claim(
        "Fig 6",
        "the maximum push-off force changes little with the modulus",
        "little change",
        f"Fc = {Fcs} µN and P(δc) = {ends} µN for E1 = {Es} MPa",
        "reproduced",
        "JKR's pull-off −1.5πRw (and −(5/9) of it under displacement control) does not "
        "contain E* at all.",
        f"w = {alt_rows[0]['w_J_m2']:.3f} J/m²: Fc = "
        + ", ".join(num(r["Fc_uN"], ".3f") for r in alt_rows)
        + " µN",
    )


def _claim_deformation(rows: list[dict], alt_rows: list[dict]) -> dict:
    """Fig 6b: the overlap under the same force against the modulus."""
    Es = ", ".join(f"{r['E1_MPa']:g}" for r in rows)
    depth0 = ", ".join(num(r["overlap_at_0_um"], ".3f") for r in rows)
    depth1 = ", ".join(num(r[f"overlap_at_{COMMON_FORCE_UN:g}uN_um"], ".3f") for r in rows)
    return claim(
        "Fig 6b",
        "under the same force the deformation gets smaller as E rises",
        "smaller deformation at higher E",
        f"overlap at zero load {depth0} µm, at +{COMMON_FORCE_UN:g} µN {depth1} µm, end of "
        f"contact δc = "
        + ", ".join(num(r["overlap_end_um"], ".3f") for r in rows)
        + f" µm for E1 = {Es} MPa",
        "reproduced",
        "At a fixed force JKR overlaps scale as E*^(−2/3), so they shrink monotonically "
        "with the modulus.",
        f"w = {alt_rows[0]['w_J_m2']:.3f} J/m²: overlap at zero load "
        + ", ".join(num(r["overlap_at_0_um"], ".3f") for r in alt_rows)
        + " µm",
    )


def build_claims(contacts: list, rows: list[dict], alt_rows: list[dict]) -> tuple[list, dict]:
    """Paper-comparison rows for Fig 6; also returns the numbers behind them."""
    numbers = paper_radii(contacts, rows)
    claims = [
        _claim_radius(rows, alt_rows, numbers),
        _claim_push_off(rows, alt_rows),
        _claim_deformation(rows, alt_rows),
    ]
    return claims, numbers


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    n = 150 if args.quick else 1200
    params = [PAPER_TABLE1.replace(**{"contact.E1": E1}) for E1 in MODULI_MPA]
    alt_params = [PAPER_FIG5_READING.replace(**{"contact.E1": E1}) for E1 in MODULI_MPA]
    contacts = [p.contact for p in params]
    rows = [contact_numbers(c) for c in contacts]
    alt_rows = [contact_numbers(p.contact) for p in alt_params]
    figures = draw(contacts, rows, n, out)
    write_table(
        out / "sweep.csv",
        [dict(r, reading="stated_w") for r in rows]
        + [dict(r, reading="fig5_reading") for r in alt_rows],
    )
    claims, numbers = build_claims(contacts, rows, alt_rows)
    write_table(out / "claims.csv", claims)
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "curve_points": n,
            "moduli_MPa": MODULI_MPA,
            "common_force_uN": COMMON_FORCE_UN,
            "params": {
                "stated_w": [p.to_dict() for p in params],
                "fig5_reading": [p.to_dict() for p in alt_params],
            },
            "results": {"stated_w": rows, "fig5_reading": alt_rows, **numbers},
            "claims": claims,
            "figures": [f.name for f in figures],
        },
    )
    return {
        "claims": claims,
        "out": str(out),
        "sweep": rows,
        "sweep_fig5_reading": alt_rows,
        "pull_off_uN": [r["Fc_uN"] for r in rows],
        "radius_at_zero_load_um": [r["a_at_0_um"] for r in rows],
        **numbers,
    }


if __name__ == "__main__":
    res = main()
    for row in res["claims"]:
        print(
            f"[{row['figure']}] {row['claim']}\n  paper: {row['paper']}\n  ours:  {row['ours']}"
            f"\n  alt:   {row['alternative']}\n  -> {row['verdict']}: {row['reason']}"
        )
