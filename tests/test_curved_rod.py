"""The circular-arc seta shaft (gecko_agents.physics.curved_rod) against closed forms: the
straight rod of eq 16–21 at no turn, and Castigliano's quarter-circle cantilever by hand."""

import math

import numpy as np
import pytest

from gecko_agents.physics import beam
from gecko_agents.physics.curved_rod import arc_points, curved_rod_compliance


def test_no_turn_is_the_straight_rod_of_eq_16_to_21():
    L, E, r = 63.0, 1600.0, 1.5
    EI, EA = E * math.pi * r**4 / 4.0, E * math.pi * r**2
    for theta in (0.3, math.radians(45.0), 1.2):
        K = beam.stiffness_matrix(EA / L, 3.0 * EI / L**3, theta)
        C = curved_rod_compliance(L, EI, EA, theta, 0.0)
        np.testing.assert_allclose(C, np.linalg.inv(K), rtol=1e-10)


def test_quarter_circle_cantilever_by_castigliano():
    """Clamped at (R, 0) with its tangent up, free at (0, R): bending alone gives
    C_xx = (3π/4 − 2)R³/EI, C_yy = (π/4)R³/EI, C_xy = R³/(2EI) (∫ over ψ of the moments
    R(1 − sin ψ) and R cos ψ of unit tip forces, ds = R dψ)."""
    R, EI = 10.0, 2.0
    L = 0.5 * math.pi * R
    theta, turn = -0.75 * math.pi, 0.5 * math.pi  # chord at 135°, tangent from 90° to 180°
    x, y = arc_points(L, theta, turn, np.array([0.0, L]))
    np.testing.assert_allclose([x[1], y[1]], [-R, R], atol=1e-12)  # tip relative to the root
    C = curved_rod_compliance(L, EI, 1e15, theta, turn)
    expected = np.array([[0.75 * math.pi - 2.0, 0.5], [0.5, 0.25 * math.pi]]) * R**3 / EI
    np.testing.assert_allclose(C, expected, rtol=1e-9)


def test_stiff_in_bending_the_arc_keeps_only_its_axial_compliance():
    """With EI → ∞ only the axial term ∫ t tᵀ ds/EA is left, t = (cos φ, sin φ) the tangent,
    turning uniformly φ = φ₀ + κs (φ₀ = −θ − turn/2, κ = turn/L): by hand
    ∫cos²φ ds = L/2 + Δsin2φ/(4κ), ∫sin²φ ds = L/2 − Δsin2φ/(4κ), ∫sinφ cosφ ds = −Δcos2φ/(4κ)
    (Δ: tip value − root value), both turning ways."""
    L, EA, theta = 10.0, 2.0, 0.5
    for turn in (1.2, -0.7):
        k, p0, p1 = turn / L, -theta - turn / 2, -theta + turn / 2
        dsin, dcos = math.sin(2 * p1) - math.sin(2 * p0), math.cos(2 * p1) - math.cos(2 * p0)
        C = np.array(
            [[L / 2 + dsin / (4 * k), -dcos / (4 * k)], [-dcos / (4 * k), L / 2 - dsin / (4 * k)]]
        )
        np.testing.assert_allclose(
            curved_rod_compliance(L, 1e30, EA, theta, turn), C / EA, rtol=1e-12, atol=1e-15
        )


def test_a_curved_shaft_is_never_as_stiff_as_a_straight_one_loaded_along_its_axis():
    L, EI, EA, theta = 63.0, 4000.0, 11000.0, math.radians(45.0)
    axial = np.array([math.cos(theta), -math.sin(theta)])
    along_chord = []
    for turn in (0.0, 0.05, 0.2, 0.8, 1.6):
        C = curved_rod_compliance(L, EI, EA, theta, turn)
        assert np.all(np.linalg.eigvalsh(C) > 0)
        along_chord.append(1.0 / (axial @ C @ axial))
    assert along_chord[0] == pytest.approx(EA / L)  # straight: the axial stiffness
    assert np.all(np.diff(along_chord) < 0)  # the more it turns, the more a chord load bends it


@pytest.mark.parametrize(
    "args, name",
    [((0.0, 1.0, 1.0, 0.0, 0.0), "L"), ((1.0, -1.0, 1.0, 0.0, 0.0), "EI"),
     ((1.0, 1.0, 0.0, 0.0, 0.0), "EA"), ((1.0, 1.0, 1.0, 0.0, 7.0), "turn")],
)  # fmt: skip
def test_bad_input_is_refused_by_name(args, name):
    """The message names the parameter and its value: ``name = value``."""
    with pytest.raises(ValueError, match=f": {name} = "):
        curved_rod_compliance(*args)
