"""Pillar designs: pull-off per area of a row of vertical pillars against how far they were
pressed, for three tip shapes, two aspect ratios and three floors, with the pillars that
buckled under the preload marked.

The pillars are the paper's polyurethane (E = 1.413 MPa, ν = 0.3) as vertical columns of radius
r = 1.5 µm at a 4 µm pitch (square lattice: 16 µm² of backing per pillar), modelled as bar-chain
elasticas that bend and buckle (``mechanics = "elastica"``, :mod:`gecko_agents.physics.elastica`)
on a rigid backing. Tips, all 1.5 µm in radius: a JKR sphere (``sphere``, the paper's tip), a
flat punch (``flat_punch``: Kendall's pull-off, its face held flat while bonded) and a
thin-film spatula (``spatula``, the package's gecko-like tip; pad floors only). Floors: flat
glass, a rough floor (Gaussian pads, σ = 0.2 µm, eq 28) and the measured Dektak scan
(``gecko_agents.data.DEKTAK_PROFILE``, RMS 0.094 µm). Each run presses five pillars a depth
past touch-down of 1 %, 5 % or 20 % of their length (displacement control: a buckled column
carries no more than about its Euler load, so a force preload above it would crush it flat) and
pulls them straight off at 0.05 µm/µs (friction μ = 0.5). The preload is the largest force
the pillars carried.

Buckling is marked where the preload per pillar reached the buckling load of the pillar's end
condition with shear (:func:`gecko_agents.physics.columns.shear_column_load`): clamped–clamped
for the flat punch (face held flat, stuck), clamped–pinned for the sphere and the spatula
(stuck, free to turn) — the loads the model meets within 2 % (``tests/test_pillars.py``).
At L/2r = 5 and 10 shear puts them 22 % and 7 % below Euler's 4π²EI/L² for the punch and 14 %
and 4 % below 2.046π²EI/L² for the others (column ``euler_load_uN`` keeps Euler's). A pillar
pressed past buckling carries about that load (a little more while the press runs: the
bending mode grows slowly near the bifurcation).

What the model says (full run, 66 runs, the table ``pillar_designs.csv``):

* The mushroom wins on every floor and at every press: 626–635 kPa of backing, against
  280–291 kPa for the flat punch, 71–73 kPa for the sphere and 33–35 kPa for the spatula.
  That is each tip's own pull-off over 16 µm²: σ₀ = 1 MPa over the mushroom's 1.8 µm flange
  (its rim not singular, it lets go from its centre; an upper bound, see
  :mod:`gecko_agents.physics.mushroom`), Kendall's 4.66 µN for a 1.5 µm punch, 1.5πRw =
  1.17 µN for the sphere, the film's peel force for the spatula. A punch's whole face bonds; a
  sphere's contact is a fraction of it (and its a/R = 1.0 here is far outside JKR's a ≪ R: the
  validity table flags it).
* The rough floor (σ = 0.2 µm pads) costs at most 2 %, because each pillar meets its own flat
  pad (eq 28): a punch face is never tilted against its pad, and the pillars are compliant
  enough to reach pads 0.2 µm apart. On the measured scan a 1 % press (0.15 µm) of the
  shorter pillars leaves some of them off the floor: 116 kPa for the punch, 380 kPa for the
  mushroom, 43 kPa for the sphere. A 5 % press brings them all on.
* Buckling costs nothing measurable with the faces held bonded (the default): 0.98–1.00 × the
  pull-off of the same design pressed below its buckling load. The measured floor's 1.15–1.24 ×
  is the partial contact of the 1 % press, not buckling. The punch face stays bonded and flat
  through the buckle, and the column straightens as it is pulled.

Experiments on mushroom pillars report "extremely low pull-off force" once the pillars buckle
(Yagüe Isla & Kroner 2015, Adv Funct Mater 25:2444, the literature report's row): their
pillars' ends tilt and peel at the edge when the column buckles. With the faces' edges free to
open (``contact.edge_opening``, :mod:`gecko_agents.model.face_opening`; the study's
``pillar_buckling.png``, :mod:`.pillar_buckling`) a round-edged punch loses its whole pull-off
once its buckled face's edge reaches the toughness, which happens for large pillars first: a
1.5 µm punch keeps it after a 40 % press, a 15 µm one loses it after 20 %. A mushroom whose
rim is not singular keeps it at every size, as Paretkar et al.'s (2013) end-flap fibrils do;
the model does not reproduce a mushroom's loss (a tilted flange's partial contact is not
modelled).

The tilted face in closed form (``pillar_tilt.png``, table ``pillar_tilt.csv``): a punch face
bonded at a tilt α, or carrying the moment a lateral load Q puts on it, opens at one edge
first (:func:`gecko_agents.physics.punch.tilted_pull_off`: F = F_K − 3|M|/a, the face's
rotational stiffness k_r = 4E*a³/3, the pillar's end moment M = (QL/2)/(1 + EI/(k_r·L))). For
the study's punch (a = 1.5 µm, F_K = 4.66 µN) the pull-off falls linearly with the tilt and is
gone at α = √(πw/(2E*a)) = 19.1°. A lateral load removes it at 0.33 µN (L/2r = 5) and 0.16 µN
(L/2r = 10), 7 % and 3.4 % of F_K: the moment's arm, L/2, is 15 and 30 times the edge's a/3.
The points on the rigid-clamp lines are the model's own elastica pushed sideways with its face
clamped and no axial force, its face moment put into the same criterion: the end moment is
0.99 and 0.97 × QL/2 at u/L = 0.10 and 0.21 (pull-off within 0.3 % of the closed form), 0.82 ×
at u/L = 0.52 (pull-off 9 % above it): large deflection lowers the end moment. Experiments
on 400 µm PDMS pillars find the flat tip's pull-off "strongly" tilt dependent and the
mushroom's not, once in full contact (Kroner & Arzt, "Single macropillars as model systems
for tilt angle dependent adhesion measurements", abstract read; journal details not checked):
the same trend, not a quantitative comparison (their tilt is of the probe before contact).
The study's runs hold the bonded face rigidly (``contact.edge_opening`` off), so the moment
does not reach the detachment; what it would change is measured here: each flat-punch run logs,
by the same criterion, the largest K/K_c its faces' edges reach while pressed and the face
moment's share 3|M|/a over F_K while pulled (:class:`EdgeLog`, table columns
``edge_K_over_Kc_pressed`` and ``moment_share_pulled``). Full run: pressed past buckling (20 %
of L) the edge reaches K/K_c = 0.34–0.39 on the three floors (G ≤ 0.15 w); below its buckling
load it stays closed (K ≤ 0; 0.09–0.11 for L/2r = 10 pressed 5 %, just past its load). Pulled,
the moment adds at most 0.02 % of F_K. So the clamped face's moment does not open the edge of
these 1.5 µm pillars in straight press-pulls; it opens that of larger ones
(:mod:`.pillar_buckling`).

The flat-faced tips have an interface strength σ₀ = 1 MPa (an assumption, :data:`SIGMA0`),
and the full run adds a mushroom tip (flange 1.2 × the stalk, sharp 45° rim, no defect: it lets
go from its centre at σ₀ over the flange). Contact splitting (:mod:`.pillar_splitting`,
``pillar_splitting.png``): pull-off per area of backing against pillar radius at a fixed area
fraction, the closed forms with single pillars of the model on them (within 0.03 %). A flat
punch gains as a^−1/2 (Kendall) only down to its flaw-tolerant radius a_cr = 8E*w/(πσ₀²),
7.2 µm at σ₀ = 0.3 MPa and 0.65 µm at 1 MPa, and not below; a mushroom whose rim is not
singular holds σ₀ over its flange at every size, 636 kPa here, unless a defect that scales with
it brings Griffith's a^−1/2 back above 1.3 µm.

``--quick``: flat glass, one aspect ratio (L/2r = 5), the sphere and the flat punch, two
press depths (1 % and 20 % of L), two radii of the splitting runs.
"""

from __future__ import annotations

import math
import time

import numpy as np

from gecko_agents import protocol, render
from gecko_agents.analysis.pull import pull_off
from gecko_agents.data import DEKTAK_PROFILE
from gecko_agents.floor import readers
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import columns, punch
from gecko_agents.physics.elastica import Elastica
from gecko_agents.studies import pillar_buckling as pb
from gecko_agents.studies import pillar_splitting as ps
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "pillar_designs"
R_PILLAR, N_PILLARS, SPEED, SEED = 1.5, 5, 0.05, 0
BASE = PAPER_ARRAY.replace(
    **{
        "seta.theta_deg": 90.0,
        "seta.r": R_PILLAR,
        "mechanics": "elastica",
        "contact.R": R_PILLAR,
        "friction.mu": 0.5,
        "array.count": N_PILLARS,
        "floor.sigma": 0.0,
        "spatula.b": 2 * R_PILLAR,
    }
)
FLOORS = ("flat", "rough", "measured")
EULER = {"flat_punch": 4.0, "mushroom": 4.0, "sphere": 2.046, "spatula": 2.046}  # × π²EI/L²
MARKERS = {"sphere": "o", "flat_punch": "s", "spatula": "^", "mushroom": "D"}
SIGMA0 = 1.0
"""Interface strength of the flat-faced tips [MPa], an assumption (Aksak, Şahin & Sitti's 2014
value for PDMS); the 1.5 µm punch's Kendall stress, 0.66 MPa, lies below it, so the punch is
Kendall's. The mushroom: flange 1.2 × the stalk, a sharp 45° rim (not singular), no defect."""


def config(quick: bool) -> dict:
    if quick:
        return {
            "tips": ["sphere", "flat_punch"],
            "aspect": [5.0],
            "floors": ["flat"],
            "strains": [0.01, 0.2],
            "split_radii": [0.3, 3.0],
            "split_designs": ps.QUICK_DESIGNS,
            "buckling_radii": [15.0],
            "buckling_strains": [0.01, 0.2],
        }
    return {
        "tips": ["sphere", "flat_punch", "spatula", "mushroom"],
        "aspect": [5.0, 10.0],
        "floors": list(FLOORS),
        "strains": [0.01, 0.05, 0.2],
        "split_radii": [0.2, 0.6, 2.0, 6.0],
        "split_designs": None,
        "buckling_radii": [1.5, 5.0, 15.0],
        "buckling_strains": [0.01, 0.2, 0.4],
    }


def euler_load(tip: str, L: float) -> float:
    """The buckling load of a pillar of length L [µm] with ``tip``'s end condition [µN]."""
    EI = BASE.contact.E1 * math.pi * R_PILLAR**4 / 4.0
    return EULER[tip] * math.pi**2 * EI / L**2


def buckling_load(tip: str, L: float) -> float:
    """The buckling load of a pillar of length L [µm] with ``tip``'s end condition, shear
    included (:func:`gecko_agents.physics.columns.shear_column_load`) [µN]."""
    chain = Elastica(1, L, R_PILLAR, BASE.contact.E1, math.pi / 2, nu=BASE.contact.nu1)
    case = "clamped" if EULER[tip] == 4.0 else "pinned"
    return float(columns.shear_column_load(chain.EI, chain.kGA, L, case))


def params_for(tip: str, aspect: float, floor_kind: str):
    L = 2.0 * R_PILLAR * aspect
    over = {"tip": tip, "seta.L": L}
    if tip in ("flat_punch", "mushroom"):
        over |= {"contact.sigma0": SIGMA0}
    if tip == "mushroom":
        over |= {
            "contact.R": 1.2 * R_PILLAR,
            "mushroom.rim": "sharp",
            "mushroom.rim_angle_deg": 45.0,
        }
    if floor_kind == "rough":
        over |= {"floor.sigma": 0.2}
    return BASE.replace(**over)


class EdgeLog(Elastica):
    """The study's elastica, logging what a bonded punch face's edge sees by the tilted-punch
    criterion (:func:`gecko_agents.physics.punch.edge_stress_intensity`): the largest
    K/K_c = (3|M|/a − P)/F_K over the steps its faces are pressed (P > 0 compressive) and the
    largest share 3|M|/a/F_K of the face moment M (its clamp spring's torque) while they are
    pulled. Observation only: the run is the plain elastica's, step for step."""

    edge_a = edge_FK = math.nan
    press_peak = pull_share = -math.inf

    def solve(self, d, held):
        F, U = super().solve(d, held)
        if np.any(self.held):
            M = np.abs(self.face_moment()[self.held])
            P = -F[self.held, 1]  # the tip sits below its root: pressed, the pillar pushes down
            pressed, pulled = P > 0, P < 0
            term = 3.0 * M / self.edge_a
            if pressed.any():
                peak = float(np.max(term[pressed] - P[pressed])) / self.edge_FK
                self.press_peak = max(self.press_peak, peak)
            if pulled.any():
                self.pull_share = max(self.pull_share, float(np.max(term[pulled])) / self.edge_FK)
        return F, U


def run_point(tip, aspect, floor_kind, strain, profile=None) -> dict | None:
    """Pull-off per area of one design and floor pressed ``strain``·L past touch-down; None
    where the tip cannot stand on the floor (the spatula needs pads)."""
    if tip == "spatula" and floor_kind == "measured":
        return None
    p = params_for(tip, aspect, floor_kind)
    m = Model(
        p, n_sim=N_PILLARS, seed=SEED, floor_profile=profile if floor_kind == "measured" else None
    )
    log = None
    if tip == "flat_punch":  # the same chain, observed (EdgeLog)
        log = m.physics.chain = EdgeLog.of(p, N_PILLARS)
        a, w, E = p.contact.jkr_args()
        log.edge_a, log.edge_FK = a, float(punch.kendall_pull_off(a, w, E))
    h = m.run(protocol.press_pull(strain * p.seta.L, speed=SPEED), progress=False)
    preload = float(np.max(h["force_normal_uN"])) / N_PILLARS
    area = N_PILLARS * p.array.pitch**2  # µm² of backing
    F = pull_off(h).adhesion
    P_E, P_cr = euler_load(tip, p.seta.L), buckling_load(tip, p.seta.L)
    return {
        "tip": tip,
        "aspect_L_over_2r": aspect,
        "L_um": p.seta.L,
        "floor": floor_kind,
        "press_strain": strain,
        "preload_per_pillar_uN": preload,
        "euler_load_uN": P_E,
        "buckling_load_uN": P_cr,
        "buckled": bool(preload >= 0.98 * P_cr),
        "pull_off_uN": F,
        "pull_off_per_area_kPa": 1e3 * F / area,
        "attached_max": int(np.max(h["n_attached"])),
        "edge_K_over_Kc_pressed": log.press_peak
        if log and log.press_peak > -math.inf
        else math.nan,
        "moment_share_pulled": log.pull_share if log else math.nan,
    }


def tilt_rows(aspects, n: int = 25) -> list[dict]:
    """Closed-form pull-off of the study's flat punch against the face's tilt α and against a
    lateral load Q at the pillar's end (:mod:`gecko_agents.physics.punch`), for pillars of the
    given aspect ratios, the face's turn resisted by the half-space (k_r = 4E*a³/3) or held
    rigidly (the elastica's clamp); plus, on the rigid line, the elastica's own face moment
    under a lateral push (one row per aspect ratio, ``source = "elastica"``)."""
    a, w, E = BASE.contact.jkr_args()
    F_K = float(punch.kendall_pull_off(a, w, E))
    k_r = float(punch.punch_rotation_stiffness(a, E))
    EI = BASE.contact.E1 * math.pi * R_PILLAR**4 / 4.0
    rows = []
    for alpha in np.linspace(0.0, math.sqrt(math.pi * w / (2 * E * a)), n):
        F = float(punch.tilt_pull_off(a, w, E, alpha))
        rows.append(
            {
                "load": "tilt",
                "source": "closed form",
                "face": "half-space",
                "aspect_L_over_2r": math.nan,
                "tilt_deg": math.degrees(alpha),
                "lateral_uN": math.nan,
                "pull_off_uN": F,
                "over_kendall": F / F_K,
            }
        )
    for aspect in aspects:
        L = 2.0 * R_PILLAR * aspect
        for face, kr in (("half-space", k_r), ("rigid clamp", math.inf)):
            Q0 = 2.0 * a * F_K * (1.0 + EI / (kr * L)) / (3.0 * L)  # where F reaches 0
            for Q in np.linspace(0.0, Q0, n):
                F = float(punch.tilted_pull_off(a, w, E, punch.lateral_load_moment(Q, L, EI, kr)))
                rows.append(
                    {
                        "load": "lateral",
                        "source": "closed form",
                        "face": face,
                        "aspect_L_over_2r": aspect,
                        "tilt_deg": math.nan,
                        "lateral_uN": float(Q),
                        "pull_off_uN": F,
                        "over_kendall": F / F_K,
                    }
                )
        for frac in (0.1, 0.25):  # pushed as far as the linear beam would be at frac·Q0
            Q, M = elastica_face_moment(L, frac * Q0 * L**3 / (12.0 * EI))
            F = float(punch.tilted_pull_off(a, w, E, M))
            rows.append(
                {
                    "load": "lateral",
                    "source": "elastica",
                    "face": "rigid clamp",
                    "aspect_L_over_2r": aspect,
                    "tilt_deg": math.nan,
                    "lateral_uN": Q,
                    "pull_off_uN": F,
                    "over_kendall": F / F_K,
                }
            )
    return rows


def elastica_face_moment(L: float, u: float) -> tuple[float, float]:
    """Lateral force [µN] and face moment [µN·µm] of the study's pillar (bar-chain elastica,
    length L [µm]) whose face, bonded at rest and clamped there, is pushed u [µm] sideways with
    no axial force (its end's height found by the secant method)."""
    chain = Elastica(1, L, R_PILLAR, BASE.contact.E1, math.pi / 2, nu=BASE.contact.nu1)
    rest = chain.rest_end()
    chain.solve(rest[None, :], True)  # the face bonds at rest and is clamped there

    def axial(y):
        chain.solve(np.array([[rest[0] + u, y]]), True)
        return float(chain.lam[0, 1])

    y0, y1 = rest[1], rest[1] + 1e-3 * L
    f0, f1 = axial(y0), axial(y1)
    for _ in range(50):
        if abs(f1) < 1e-12 or f1 == f0:
            break
        y0, y1, f0 = y1, y1 - f1 * (y1 - y0) / (f1 - f0), f1
        f1 = axial(y1)
    return float(chain.lam[0, 0]), float(chain.face_moment()[0])


def draw_tilt(rows, out) -> None:
    """Pull-off over Kendall's against the face's tilt and against the lateral load."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(9.5, 4.0), layout="constrained")
        ax_t, ax_q = fig.subplots(1, 2, sharey=True)
        tilt = [r for r in rows if r["load"] == "tilt"]
        ax_t.plot([r["tilt_deg"] for r in tilt], [r["over_kendall"] for r in tilt], "-")
        ax_t.set_xlabel("tilt of the bonded face against the floor α [°]")
        ax_t.set_ylabel("pull-off / Kendall's √(8πE*wa³)")
        ax_t.set_title("face held at a tilt: F = F_K − 4E*a²α")
        for aspect in dict.fromkeys(r["aspect_L_over_2r"] for r in rows if r["load"] != "tilt"):
            color = None
            for face, ls in (("half-space", "-"), ("rigid clamp", "--")):
                sel = [
                    r
                    for r in rows
                    if r["aspect_L_over_2r"] == aspect
                    and r["face"] == face
                    and r["source"] == "closed form"
                ]
                (line,) = ax_q.plot(
                    [r["lateral_uN"] for r in sel],
                    [r["over_kendall"] for r in sel],
                    ls=ls,
                    color=color,
                    label=f"L/2r = {aspect:g}, face: {face}",
                )
                color = line.get_color()
            pts = [r for r in rows if r["aspect_L_over_2r"] == aspect and r["source"] == "elastica"]
            ax_q.plot(
                [r["lateral_uN"] for r in pts],
                [r["over_kendall"] for r in pts],
                "o",
                color=color,
                label=f"L/2r = {aspect:g}, elastica's clamped face",
            )
        ax_q.set_xlabel("lateral load at the pillar's end Q [µN]")
        ax_q.set_title("pillar pushed sideways: M = (QL/2)/(1 + EI/(k_r L))")
        ax_q.legend(fontsize="small")
        render.save_figure(fig, out / "pillar_tilt.png")


def winners(rows) -> list[str]:
    """One line per floor and preload: the design with the largest pull-off per area."""
    lines = []
    for fl in dict.fromkeys(r["floor"] for r in rows):
        for eps in dict.fromkeys(r["press_strain"] for r in rows):
            sel = [r for r in rows if r["floor"] == fl and r["press_strain"] == eps]
            best = max(sel, key=lambda r: r["pull_off_per_area_kPa"])
            lines.append(
                f"{fl} floor, pressed {100 * eps:g} % of L: {best['tip']} at "
                f"L/2r = {best['aspect_L_over_2r']:g} holds "
                f"{best['pull_off_per_area_kPa']:.3g} kPa"
            )
    return lines


def section(rows, lines) -> str:
    """The report's section: the winner per floor and preload, and what buckling cost."""
    kept = []
    for tip in dict.fromkeys(r["tip"] for r in rows):
        for fl in dict.fromkeys(r["floor"] for r in rows):
            sel = [r for r in rows if r["tip"] == tip and r["floor"] == fl]
            below = [r["pull_off_uN"] for r in sel if not r["buckled"]]
            above = [r["pull_off_uN"] for r in sel if r["buckled"]]
            if below and above:
                kept.append(
                    f"- {tip}, {fl} floor: after a buckling preload "
                    f"{np.mean(above) / np.mean(below):.3f} × the pull-off below it"
                )
    edges = [
        f"- flat_punch, {r['floor']} floor, L/2r = {r['aspect_L_over_2r']:g}, pressed "
        f"{100 * r['press_strain']:g} % of L: edge K/K_c up to "
        + (
            f"{r['edge_K_over_Kc_pressed']:.3g} pressed"
            if math.isfinite(r["edge_K_over_Kc_pressed"])
            else "— (no face pressed)"
        )
        + ", moment share "
        f"{r['moment_share_pulled']:.2g} of F_K pulled"
        for r in rows
        if r["tip"] == "flat_punch"
    ]
    return "\n".join(
        [
            "## Beyond the paper: pillar designs",
            "",
            f"Vertical elastica pillars, r = {R_PILLAR:g} µm, {N_PILLARS} per run "
            "(`pillar_designs/pillar_designs.png`, table `pillar_designs.csv`).",
            "",
            *[f"- {line}" for line in lines],
            "",
            "Pull-off after a preload that buckled the pillars, over that below it "
            "(experiments on PDMS pillars lose adhesion there; these runs hold the faces bonded, "
            "see `pillar_buckling.png` for faces free to open):",
            "",
            *kept,
            "",
            "The punch faces' edges by the tilted-punch criterion (K/K_c = (3|M|/a − P)/F_K, "
            "M the clamped face's moment; 1 would open the edge):",
            "",
            *edges,
            "",
            "",
        ]
    )


def tilt_section(tilt) -> str:
    """The report's lines on the tilted face: where each load leaves no pull-off."""
    gone = [r for r in tilt if r["source"] == "closed form" and r["over_kendall"] <= 1e-9]
    lines = [
        f"- face held at a tilt: no pull-off left from α = {r['tilt_deg']:.3g}°"
        if r["load"] == "tilt"
        else f"- L/2r = {r['aspect_L_over_2r']:g}, face {r['face']}: no pull-off left from a "
        f"lateral load of {r['lateral_uN']:.3g} µN"
        for r in gone
    ]
    return "\n".join(
        [
            "Flat punch with a tilted face or a lateral load (closed form, "
            "`pillar_designs/pillar_tilt.png`; F = F_K − 3|M|/a, in the dynamic law with "
            "contact.edge_opening):",
            "",
            *lines,
            "",
        ]
    )


def draw(rows, cfg, out) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    floors = cfg["floors"]
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(4.0 * len(floors) + 0.8, 4.2), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, len(floors), sharey=True))
        for ax, fl in zip(axes, floors, strict=True):
            for tip in cfg["tips"]:
                for aspect, ls in zip(cfg["aspect"], ("-", "--"), strict=False):
                    sel = [
                        r
                        for r in rows
                        if r["floor"] == fl and r["tip"] == tip and r["aspect_L_over_2r"] == aspect
                    ]
                    if not sel:
                        continue
                    x = [r["preload_per_pillar_uN"] for r in sel]
                    y = [r["pull_off_per_area_kPa"] for r in sel]
                    (line,) = ax.plot(
                        x, y, ls=ls, marker=MARKERS[tip], label=f"{tip}, L/2r = {aspect:g}"
                    )
                    bx = [a for a, r in zip(x, sel, strict=True) if r["buckled"]]
                    by = [b for b, r in zip(y, sel, strict=True) if r["buckled"]]
                    ax.plot(bx, by, "x", ms=11, color=line.get_color())
            ax.set_xscale("log")
            ax.set_xlabel("preload per pillar (largest force carried) [µN]")
            ax.set_title(f"{fl} floor (×: buckled under the preload)")
        axes[0].set_ylabel("pull-off per area of backing [kPa]")
        axes[0].legend(fontsize="small")
        render.save_figure(fig, out / f"{NAME}.png")


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    cfg = config(args.quick)
    t0 = time.perf_counter()
    profile = readers.read_text(DEKTAK_PROFILE) if "measured" in cfg["floors"] else None
    rows = []
    for fl in cfg["floors"]:
        for tip in cfg["tips"]:
            for aspect in cfg["aspect"]:
                for eps in cfg["strains"]:
                    row = run_point(tip, aspect, fl, eps, profile)
                    if row is not None:
                        rows.append(row)
                        print(
                            f"{NAME}: {fl}, {tip}, L/2r = {aspect:g}, pressed "
                            f"{100 * eps:g} % of L: {row['pull_off_per_area_kPa']:.3g} kPa",
                            flush=True,
                        )
    write_table(out / f"{NAME}.csv", rows)
    draw(rows, cfg, out)
    tilt = tilt_rows(cfg["aspect"])
    write_table(out / "pillar_tilt.csv", tilt)
    draw_tilt(tilt, out)
    split = ps.splitting_rows(BASE, np.geomspace(0.05, 50.0, 61))
    split += ps.model_rows(BASE, cfg["split_radii"], SPEED, cfg["split_designs"])
    write_table(out / "pillar_splitting.csv", split)
    ps.draw_splitting(split, BASE, out)
    buck = pb.buckling_rows(BASE, cfg["buckling_radii"], cfg["buckling_strains"], SPEED)
    write_table(out / "pillar_buckling.csv", buck)
    pb.draw_buckling(buck, out)
    lines = winners(rows)
    results = {"winners": lines, "runtime_s": time.perf_counter() - t0}
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "params": BASE.to_dict(),
            "config": cfg,
            "pillars": N_PILLARS,
            "speed_um_per_us": SPEED,
            "seed": SEED,
            "rows": rows,
            "floor_file": DEKTAK_PROFILE.name if profile is not None else None,
            "results": results,
        },
    )
    (out / "section.md").write_text(
        section(rows, lines)
        + tilt_section(tilt)
        + "\n"
        + ps.splitting_section(split, BASE)
        + "\n"
        + pb.buckling_section(buck)
    )
    print("\n".join(f"{NAME}: {line}" for line in lines))
    print(f"{NAME}: {len(rows)} runs, {results['runtime_s']:.0f} s → {out}")
    return results


if __name__ == "__main__":
    main()
