"""The elastica chain of a seta (gecko_agents.physics.elastica) by hand: its Timoshenko shear
stiffness, its crooked rest shape, a face that bonds in the direction it touches in, the
refusal of a tip it cannot reach, and a chain swung far from straight: its stretch is its
links' axial forces over their stiffness, its force the gradient of its energy."""

import math

import numpy as np
import pytest

from gecko_agents.physics.elastica import Elastica, shear_coefficient

L, R, E, THETA = 60.0, 1.5, 1.413, math.radians(60.0)  # µm, µm, MPa, rad


def test_shear_stiffness_is_kappa_g_a():
    """κ·G·A with G = E/(2(1 + ν)) (isotropic) and A = πr² (Timoshenko's shear stiffness)."""
    for nu in (0.0, 0.3, 0.5):
        e = Elastica(1, L, R, E, THETA, nu=nu)
        G = E / (2.0 * (1.0 + nu))
        assert e.kGA == pytest.approx(shear_coefficient(nu) * G * math.pi * R * R, rel=1e-15)


def test_rest_shape_is_an_arc_whose_tip_is_offset_by_the_imperfection():
    """The stress-free chain is an arc of curvature κ = 2·imperfection/L turning
    counter-clockwise from −θ: its tip stands off the straight shaft by ½κL² = imperfection·L
    to first order (here 1e-3·60 µm; the arc's own correction is O(κ²L²) relative)."""
    for imperfection in (1e-3, 1e-2):
        e = Elastica(1, L, R, E, THETA, imperfection=imperfection)
        across = np.array([math.sin(THETA), math.cos(THETA)])  # +90° from (cos θ, −sin θ)
        assert e.rest_end() @ across == pytest.approx(imperfection * L, rel=2 * imperfection)


def test_a_face_bonds_in_the_direction_it_touches_in():
    """A free chain bent a little, then held at the same end: the face bonds at the direction
    its section has there, so bonding changes neither the force nor the energy (no jump) and
    its clamp carries no moment."""
    e = Elastica(1, L, R, E, THETA)
    d = (e.rest_end() + [0.05, 0.05])[None]
    F_free, U_free = e.solve(d, [False])
    F_held, U_held = e.solve(d, [True])
    np.testing.assert_allclose(F_held, F_free, rtol=1e-9)
    assert U_held == pytest.approx(U_free, rel=1e-9)
    assert abs(e.face_moment()[0]) < 1e-12


def test_a_tip_the_chain_cannot_reach_is_refused_naming_its_seta():
    """Seta 1's end moved 0.5 µm along and 1 µm across from rest in one solve (a step far
    too long): its Newton solve finds no equilibrium, and the error names that seta."""
    e = Elastica(2, L, R, E, THETA)
    d = np.array([e.rest_end(), e.rest_end() + [0.5, 1.0]])
    with pytest.raises(RuntimeError, match=r"setae \[1\] found no equilibrium"):
        e.solve(d, [False, False])


def test_a_column_pressed_nearly_flat_is_refused_as_crushed():
    """A held end pressed to 0.2 L from its root in one solve has no equilibrium the chain
    reaches; the refusal names the cause (a force preload above the Euler load crushes a
    buckled pillar), not a time step."""
    e = Elastica(1, L, R, E, THETA)
    with pytest.raises(RuntimeError, match=r"end 0\.20 L from its root\): the column is pressed"):
        e.solve(np.array([[0.0, 0.2 * L]]), [True])


def test_a_held_face_moved_sideways_carries_the_guided_beams_moment():
    """A face held at its bonded direction and moved δ across the axis is a beam clamped at
    both ends with one end moved sideways without turning: M = 6EI·δ/L² (Gere & Timoshenko,
    Mechanics of Materials, fixed-guided beam), turning the face back (positive), within the
    chain's discretisation and Timoshenko's shear softening (measured 1.3 % below at 16
    links); a free tip's face carries none."""
    e = Elastica(2, L, R, E, THETA)
    rest = e.rest_end()
    axis = rest / np.hypot(*rest)
    delta = 0.01
    d = np.array([rest + delta * np.array([-axis[1], axis[0]])] * 2)
    e.solve(d, [True, False])
    M = e.face_moment()
    assert M[0] == pytest.approx(6.0 * e.EI * delta / L**2, rel=0.02)
    assert M[1] == 0.0


def test_a_parameter_sets_chain_shears_with_its_own_poisson_ratio():
    """Elastica.of takes every property of the set, ν1 included: its shear stiffness is the
    chain's built from ν1 by hand, not the default ν's."""
    from gecko_agents.params import PAPER_TABLE1

    p = PAPER_TABLE1.replace(mechanics="elastica", **{"contact.nu1": 0.45})
    s = p.seta
    e = Elastica.of(p, 1)
    same = Elastica(1, s.L, s.r, p.contact.E1, s.theta, s.links, s.imperfection, nu=0.45)
    default = Elastica(1, s.L, s.r, p.contact.E1, s.theta, s.links, s.imperfection)
    assert e.kGA == same.kGA != default.kGA
    np.testing.assert_array_equal(e.Ks[1], same.Ks[1])


def test_the_shear_coefficient_of_a_circle_takes_cowpers_values():
    """Cowper (1966, J Appl Mech 33:335) for a solid circle: 6/7 at ν = 0, 0.886 at ν = 0.3
    (the value usually quoted for steel-like solids), 9/10 at ν = ½, rising with ν."""
    assert shear_coefficient(0.0) == pytest.approx(6.0 / 7.0, rel=1e-15)
    assert shear_coefficient(0.3) == pytest.approx(0.886, abs=5e-4)
    assert shear_coefficient(0.5) == pytest.approx(0.9, rel=1e-15)
    nu = np.linspace(0.0, 0.5, 11)
    assert np.all(np.diff(shear_coefficient(nu)) > 0)


def _swung(held):
    """A chain whose end is swung 60° about its root at its rest distance in 12 solves (each
    a Newton solve from the last shape): the chain, its end d [µm] and the force λ [µN] the
    tip applies to its end (−F)."""
    e = Elastica(1, L, R, E, THETA)
    rest = e.rest_end()
    for a in np.linspace(0.0, math.radians(60.0), 13)[1:]:
        turn = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        d = turn @ rest
        F, _ = e.solve(d[None], [held])
    return e, d, -F[0]


@pytest.mark.parametrize("held", [True, False], ids=["held face", "free tip"])
def test_the_columns_stretch_is_its_links_axial_forces_over_their_stiffness(held):
    """No load acts along the chain between its root and its end, so link k carries the end's
    force projected on its centreline, N_k = λ·t_k, and stretches N_k·ℓ/(EA) = N_k/(n·Ka);
    the column's stretch s (shared by its links, module docstring) is their sum. Stretching
    the chain uniformly scales its end vector, so virtual work gives the same s from the ends
    alone: Ka·s·(L + s) = λ·d. The end is swung 60° about the root: the links span 0.71 rad
    (held face, its last two 0.39 rad apart) and 0.75 rad (free tip), and s is 2.7 % and
    1.9 % of L. Tolerance 1e-10·|λ|/Ka: above the Newton solve's (1e-12), below any stretch
    read off the wrong links' angles."""
    e, d, lam = _swung(held)
    t = np.stack([np.cos(e.phi[0]), np.sin(e.phi[0])], axis=1)
    s, scale = e.stretch[0], np.hypot(*lam) / e.Ka
    assert np.ptp(e.phi[0]) > 0.6  # links far from parallel
    if held:
        assert abs(e.phi[0, -1] - e.phi[0, -2]) > 0.3
    assert s == pytest.approx((t @ lam).sum() / (e.n * e.Ka), abs=1e-10 * scale)
    assert s == pytest.approx(lam @ d / (e.Ka * (L + s)), abs=1e-10 * scale)


@pytest.mark.parametrize("held", [True, False], ids=["held face", "free tip"])
def test_the_force_on_a_swung_chain_is_the_gradient_of_its_energy(held):
    """The chain is conservative: the force λ its end takes is ∂U/∂d (Castigliano's first
    theorem), here by central differences of h = 1e-3 µm on the chain swung 60°, whose stretch
    (2–3 % of L) makes the links' lever arms ℓ + s/n differ from ℓ by as much. Tolerance
    1e-6·|λ|: above the truncation (~h², 2.5e-8 measured) and the solver's end tolerance
    (1e-12·L per energy, 6e-8 over 2h), below a lever arm or axial row read wrongly."""
    e, d, lam = _swung(held)
    h = 1e-3
    grad = [
        (e.peek((d + h * u)[None])[1][0] - e.peek((d - h * u)[None])[1][0]) / (2 * h)
        for u in np.eye(2)
    ]
    np.testing.assert_allclose(grad, lam, rtol=0, atol=1e-6 * np.hypot(*lam))
