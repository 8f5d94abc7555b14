"""The mushroom tip (``tip = "mushroom"``) and the corner singularity of its rim: the wedge's
eigenproblem against the values quoted for it, the two detachment modes by hand, the flat punch
recovered when the flange is the stalk's own end, and the mode recorded in the history."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.contact import FlatPunch, MushroomTip, contact_law
from gecko_agents.history import load_history
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY, Contact
from gecko_agents.params.tips import Mushroom
from gecko_agents.physics import flaw_tolerance as ft
from gecko_agents.physics import mushroom, punch
from gecko_agents.physics.wedge import NOT_SINGULAR, singularity_exponent

PILLAR = PAPER_ARRAY.replace(
    **{"seta.theta_deg": 90.0, "array.count": 1, "floor.sigma": 0.0, "contact.R": 1.5}
)


# --- the rim's corner ----------------------------------------------------------------------
def test_bonded_incompressible_square_corner_is_r_to_the_minus_0405():
    lam = singularity_exponent(90.0, 0.5, "bonded")
    assert lam == pytest.approx(0.5946, abs=1e-4)
    assert 1 - lam == pytest.approx(ft.TANG_EXPONENT, abs=0.006)  # Tang's fitted 0.4


def test_corner_singularity_limits():
    # full friction, ν = 1/2: bounded up to 45°, singular above (Aksak et al. 2014, Bogy 1971)
    assert singularity_exponent(45.0) == NOT_SINGULAR
    assert singularity_exponent(30.0) == NOT_SINGULAR
    assert singularity_exponent(50.0) < 0.95
    # the more acute the rim, the weaker the singularity
    lams = [singularity_exponent(t) for t in (50.0, 60.0, 80.0, 90.0, 120.0)]
    assert np.all(np.diff(lams) < 0)
    # frictionless floor: bounded up to 90° (Aksak et al. 2014); at 180° the flat punch's edge,
    # Kendall's square-root crack
    assert singularity_exponent(90.0, floor="frictionless") == NOT_SINGULAR
    assert singularity_exponent(180.0, floor="frictionless") == pytest.approx(0.5, abs=1e-9)


def test_wedge_refuses_bad_input():
    for kw, match in (
        ({"angle_deg": 0.0}, r"angle_deg = 0.0 is outside the allowed range \(0, 180\]"),
        ({"angle_deg": 90.0, "nu": 0.6}, r"nu = 0.6 is outside the allowed range \[0, 0.5\]"),
        ({"angle_deg": 90.0, "floor": "glued"}, "floor = 'glued' must be one of"),
    ):
        with pytest.raises(ValueError, match=match):
            singularity_exponent(**kw)


# --- the two modes, by hand ----------------------------------------------------------------
def test_modes_by_hand():
    a_t, w, E_star, s0 = 2.0, 0.05, 2.0, 0.2
    # a flawed rim is the punch's law
    assert mushroom.edge_pull_off(a_t, w, E_star, s0) == ft.punch_pull_off(a_t, w, E_star, s0)
    # a sharp 90° rim at ν = 1/2: σ₀πa_t²·min(1, 0.83χ^−(1−λ))
    chi = s0**2 * a_t / (2 * math.pi * E_star * w)  # 0.2546: flaw insensitive
    lam = singularity_exponent(90.0)
    sharp = mushroom.edge_pull_off(a_t, w, E_star, s0, "sharp", 90.0, 0.5)
    assert sharp == pytest.approx(math.pi * 4.0 * s0 * min(1.0, 0.83 * chi ** (lam - 1)))
    big = 200.0  # χ = 25.5: flaw sensitive, ≈ Tang's fit (exponent 0.405 against 0.4)
    tang = ft.tang_strength(big, s0, E_star, w) * math.pi * big**2
    sharp_big = mushroom.edge_pull_off(big, w, E_star, s0, "sharp", 90.0)
    assert sharp_big == pytest.approx(tang, rel=0.02)
    # a 45° rim has no edge mode
    assert mushroom.edge_pull_off(a_t, w, E_star, s0, "sharp", 45.0) == math.inf
    # centre: the penny crack σ = √(πE*w/(2c)) over πa_t², bounded by σ₀
    c = 1.0
    assert mushroom.centre_pull_off(a_t, c, w, E_star, math.inf) == pytest.approx(
        math.pi * 4.0 * math.sqrt(math.pi * 0.1 / 2)
    )
    assert mushroom.centre_pull_off(a_t, c, w, E_star, 0.2) == pytest.approx(math.pi * 4.0 * 0.2)
    assert mushroom.centre_pull_off(a_t, 0.0, w, E_star, math.inf) == math.inf


def test_law_takes_the_weaker_mode():
    sharp45 = {"tip": "mushroom", "mushroom.rim": "sharp", "mushroom.rim_angle_deg": 45.0,
               "contact.sigma0": 0.5, "contact.R": 2.0}  # fmt: skip
    law = contact_law(PILLAR.replace(**sharp45))
    assert law.release_mode == "centre"
    assert law.pull_off_force == pytest.approx(math.pi * 4.0 * 0.5)  # uniform at σ₀
    with_defect = contact_law(PILLAR.replace(**sharp45, **{"mushroom.defect_radius": 1.0}))
    E_star, w = PILLAR.contact.E_star, PILLAR.contact.work_of_adhesion
    griffith = math.sqrt(math.pi * E_star * w / 2.0)  # 0.636 MPa at c = 1 µm: above σ₀
    assert with_defect.pull_off_force == pytest.approx(math.pi * 4.0 * min(0.5, griffith))
    small_s0 = contact_law(PILLAR.replace(**sharp45, **{"mushroom.defect_radius": 1.9}))
    assert small_s0.pull_off_force == pytest.approx(
        math.pi * 4.0 * math.sqrt(math.pi * E_star * w / 3.8)
    )
    # a flawed rim lets go at its edge where Kendall's crack is weaker than σ₀
    edge = contact_law(PILLAR.replace(**{"tip": "mushroom", "contact.R": 2.0}))
    assert edge.release_mode == "edge"
    assert edge.pull_off_force == punch.kendall_pull_off(2.0, w, E_star)


@pytest.mark.parametrize("sigma0", [math.inf, 0.3, 5.0])
def test_flange_as_wide_as_the_stalk_is_the_flat_punch(sigma0):
    contact = Contact(R=PILLAR.seta.r, sigma0=sigma0)
    m, f = MushroomTip(contact, Mushroom()), FlatPunch(contact)
    assert m.pull_off_force == f.pull_off_force
    assert m.detach_overlap == f.detach_overlap
    assert np.array_equal(m.constants, f.constants)
    assert m.zero_load_stiffness == f.zero_load_stiffness


def test_mushroom_run_equals_the_punch_run_and_records_the_mode(tmp_path):
    base = PILLAR.replace(**{"contact.R": PILLAR.seta.r, "mechanics": "rod", "array.count": 2})
    runs = {}
    for tip in ("flat_punch", "mushroom"):
        m = Model(base.replace(**{"tip": tip}), n_sim=2, seed=0)
        runs[tip] = m.run(protocol.press_pull(0.1, speed=0.01), progress=False)
    hp, hm = runs["flat_punch"], runs["mushroom"]
    for col in ("force_normal_uN", "plate_y_um", "energy_elastic_pJ", "energy_dissipated_pJ"):
        assert np.array_equal(hp[col], hm[col])
    assert "mode" not in hp.detachments
    assert list(hm.detachments["mode"]) == ["edge", "edge"]
    hm.save(tmp_path / "run")
    assert list(load_history(tmp_path / "run").detachments["mode"]) == ["edge", "edge"]


def test_a_centre_release_in_the_model():
    """A 45° rim (not singular) with a central defect of 1.2 µm under a flange of 2 µm on a
    strong interface (σ₀ = 5 MPa): the penny crack lets go at πa_t²√(πE*w/(2c)) = 8.0 µN,
    within 2 % in a slow pull, and the history says "centre"."""
    p = PILLAR.replace(
        **{"tip": "mushroom", "contact.R": 2.0, "contact.sigma0": 5.0, "mechanics": "rod",
           "mushroom.rim": "sharp", "mushroom.rim_angle_deg": 45.0,
           "mushroom.defect_radius": 1.2, "seta.L": 60.0, "seta.r": 2.0}
    )  # fmt: skip
    c = p.contact
    F = math.pi * 4.0 * math.sqrt(math.pi * c.E_star * c.work_of_adhesion / 2.4)
    h = Model(p, n_sim=1, seed=0).run(protocol.press_pull(0.1, speed=0.005), progress=False)
    assert list(h.detachments["mode"]) == ["centre"]
    assert -h.detachments["force_uN"][0] == pytest.approx(F, rel=0.02)


def test_bad_mushrooms_are_refused():
    mush = {"tip": "mushroom"}
    cases = [
        ({"contact.R": 1.0}, r"Contact.R = 1.0 \(the mushroom's flange radius\) is outside the "
         r"allowed range \[Seta.r = 1.5"),
        ({"mushroom.defect_radius": 1.5}, r"Mushroom.defect_radius = 1.5 is outside the allowed "
         r"range \[0, Contact.R = 1.5\)"),
        ({"mushroom.rim": "sharp"}, "Mushroom.rim = 'sharp' needs a finite Contact.sigma0"),
        ({"mushroom.rim": "round"}, "Mushroom.rim = 'round' must be one of"),
        ({"mushroom.rim_angle_deg": 150.0}, r"rim_angle_deg = 150.0 is outside the allowed "
         r"range \(0.0, 135.0\]"),
        ({"contact.crack_speed": 1.0}, "with tip = 'mushroom' it must be inf"),
    ]  # fmt: skip
    for over, match in cases:
        with pytest.raises(ValueError, match=match):
            PILLAR.replace(**mush, **over)


# --- contact splitting (pillar_designs' pillar_splitting) -----------------------------------
def test_splitting_stops_paying_below_the_flaw_tolerant_radius():
    from gecko_agents.studies import pillar_designs as pd
    from gecko_agents.studies import pillar_splitting as ps

    radii = np.geomspace(0.05, 50.0, 41)
    rows = ps.splitting_rows(pd.BASE, radii)
    _, w, E = pd.BASE.contact.jkr_args()

    def series(name):
        return np.array([r["pull_off_per_area_kPa"] for r in rows if r["design"] == name])

    fraction = math.pi / ps.PITCH_OVER_R**2  # contact area over backing
    kendall = series("flat punch, σ₀ = inf")
    assert np.all(np.diff(kendall) < 0)  # always pays, as a^−1/2
    assert kendall[0] / kendall[-1] == pytest.approx(math.sqrt(1000.0), rel=1e-9)
    capped = series("flat punch, σ₀ = 1 MPa")
    a_cr = ft.flaw_tolerant_radius(1.0, E, w)
    below = radii <= ft.UNIFORM_CHI / (4 / math.pi**2) * a_cr  # the whole face at σ₀
    assert np.allclose(capped[below], 1e3 * fraction * 1.0, rtol=1e-12)  # σ₀ over the area
    assert np.all(capped[~below] < np.minimum(kendall[~below], 1e3 * fraction))  # Dugdale's
    assert capped[-1] == pytest.approx(kendall[-1], rel=0.01)  # a = 77·a_cr
    flange = series("mushroom 45°, σ₀ = 1 MPa")  # no edge mode: σ₀ over the flange at any size
    assert np.allclose(flange, 1e3 * fraction * ps.BETA**2, rtol=1e-12)


@pytest.mark.slow
def test_splitting_model_points_meet_the_closed_form():
    from gecko_agents.studies import pillar_designs as pd
    from gecko_agents.studies import pillar_splitting as ps

    names = ["flat punch, σ₀ = 1 MPa", "mushroom 45°, defect a_t/4, σ₀ = 1 MPa"]
    model = ps.model_rows(pd.BASE, [0.3], pd.SPEED, names)
    closed = {r["design"]: r for r in ps.splitting_rows(pd.BASE, [0.3])}
    for r in model:
        ref = closed[r["design"]]["pull_off_per_area_kPa"]
        assert r["pull_off_per_area_kPa"] == pytest.approx(ref, rel=2e-3)
    assert [r["mode"] for r in model] == ["", "centre"]


def test_a_sharp_rim_lets_go_by_its_own_angle_and_poisson_ratio():
    """A sharp rim of 70° on a flange of ν = 0.3: its edge mode is the wedge's at that angle
    and ν (the singularity, and so the edge strength, depend on both: here they differ from
    the square, incompressible rim's), the centre mode σ₀πa_t² (no defect), and the tip lets
    go by the weaker."""
    p = PILLAR.replace(
        **{"tip": "mushroom", "mushroom.rim": "sharp", "mushroom.rim_angle_deg": 70.0,
           "contact.sigma0": 0.5, "contact.R": 2.0, "contact.nu1": 0.3}
    )  # fmt: skip
    law = contact_law(p)
    E_star, w = p.contact.E_star, p.contact.work_of_adhesion
    edge = mushroom.edge_pull_off(2.0, w, E_star, 0.5, "sharp", 70.0, 0.3)
    assert edge != mushroom.edge_pull_off(2.0, w, E_star, 0.5, "sharp", 90.0, 0.5)
    assert law.edge_force == edge
    assert law.mode_forces == {"edge": edge, "centre": pytest.approx(math.pi * 4.0 * 0.5)}
    assert law.pull_off_force == pytest.approx(min(edge, math.pi * 4.0 * 0.5), rel=1e-15)
