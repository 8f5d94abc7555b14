"""Seta stiffness (eq 16–21) against beam theory and its limits."""

import numpy as np
from numpy.testing import assert_allclose

from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics import beam


def test_table1_values_from_notes():
    # docs/physics.md, "Seta mechanics": Ka = 0.499 N/m, Kp = 2.11e-3 N/m,
    # Ky = 2.81e-3 (30°), 8.32e-3 (60°).
    Ka = beam.axial_stiffness(1.5, 20.0, 1.413)
    Kp = beam.bending_stiffness(1.5, 20.0, 1.413)
    assert_allclose(Ka, 0.499, rtol=2e-3)
    assert_allclose(Kp, 2.11e-3, rtol=2e-3)
    assert_allclose(beam.longitudinal_stiffness(Ka, Kp, np.radians(30)), 2.81e-3, rtol=2e-3)
    assert_allclose(beam.longitudinal_stiffness(Ka, Kp, np.radians(60)), 8.32e-3, rtol=2e-3)
    assert_allclose(PAPER_TABLE1.Ky, beam.longitudinal_stiffness(Ka, Kp, np.radians(30)))


def test_cantilever_formulas_scale_as_beam_theory():
    # Ka ∝ r²E/L, Kp = 3EI/L³ with I = πr⁴/4.
    assert_allclose(beam.axial_stiffness(2.0, 10.0, 3.0), 4 * beam.axial_stiffness(1.0, 10.0, 3.0))
    inertia = np.pi * 1.5**4 / 4
    assert_allclose(beam.bending_stiffness(1.5, 20.0, 1.413), 3 * 1.413 * inertia / 20.0**3)
    ratio = beam.bending_stiffness(1.0, 20.0, 1.0) / beam.bending_stiffness(1.0, 40.0, 1.0)
    assert_allclose(ratio, 8)


def test_limits_and_symmetry():
    Ka, Kp = 0.5, 0.002
    eps = 1e-9
    assert_allclose(beam.longitudinal_stiffness(Ka, Kp, np.pi / 2 - eps), Ka, rtol=1e-9)
    assert_allclose(beam.transverse_stiffness(Ka, Kp, np.pi / 2 - eps), Kp, rtol=1e-9)
    assert_allclose(beam.longitudinal_stiffness(Ka, Kp, eps), Kp, rtol=1e-9)
    assert_allclose(beam.transverse_stiffness(Ka, Kp, eps), Ka, rtol=1e-9)
    th = np.radians(np.linspace(1, 89, 89))
    assert_allclose(
        beam.longitudinal_stiffness(Ka, Kp, th), beam.transverse_stiffness(Ka, Kp, np.pi / 2 - th)
    )
    # Ky lies between Kp and Ka and grows with θ.
    ky = beam.longitudinal_stiffness(Ka, Kp, th)
    assert np.all(np.diff(ky) > 0) and np.all((ky > Kp) & (ky < Ka))


def test_matrix_inverse_diagonal_gives_eq20_eq21():
    Ka, Kp = 0.5, 0.002
    for deg in (10, 30, 60, 80):
        th = np.radians(deg)
        C = np.linalg.inv(beam.stiffness_matrix(Ka, Kp, th))
        assert_allclose(1 / C[1, 1], beam.longitudinal_stiffness(Ka, Kp, th), rtol=1e-12)
        assert_allclose(1 / C[0, 0], beam.transverse_stiffness(Ka, Kp, th), rtol=1e-12)
        # Axis direction is an eigenvector with eigenvalue Ka.
        n = np.array([np.cos(th), -np.sin(th)])
        assert_allclose(beam.stiffness_matrix(Ka, Kp, th) @ n, Ka * n, atol=1e-15)


def test_deflection_ratio_matches_notes():
    # docs/physics.md, "Seta mechanics": holding Fc = 1.5 µN needs Fc/Ky = 540 µm at 30°
    # (27 L) and 180 µm at 60° (9 L).
    p = PAPER_TABLE1
    Ka, Kp, L = p.axial_stiffness, p.bending_stiffness, p.seta.L
    r30 = beam.deflection_ratio(1.5, Ka, Kp, np.radians(30), L)
    r60 = beam.deflection_ratio(1.5, Ka, Kp, np.radians(60), L)
    # The free tip also moves sideways, so |u| ≥ F/Ky/L.
    assert r30 >= 1.5 / beam.longitudinal_stiffness(Ka, Kp, np.radians(30)) / L
    assert 25 < r30 < 60 and 8 < r60 < 20
    assert beam.deflection_ratio(1e-5, Ka, Kp, np.radians(60), L) < 1e-3


def test_rest_tip_offset_is_the_rest_direction_of_the_stiffness_matrix():
    L, theta = 20.0, np.deg2rad(30.0)
    dx, dy = beam.rest_tip_offset(L, theta)
    assert_allclose([dx, dy], [L * np.sqrt(3) / 2, -L / 2], rtol=1e-15)
    # Ka acts along the rest direction: K·n = Ka·n for Kp = 0.
    n = np.array(beam.rest_tip_offset(1.0, theta))
    assert_allclose(beam.stiffness_matrix(2.0, 0.0, theta) @ n, 2.0 * n, rtol=1e-15)
    # vectorized over angles; the tip leans towards +x and down for 0 < θ < 90°
    dx, dy = beam.rest_tip_offset(L, np.deg2rad([10.0, 60.0, 89.0]))
    assert np.all(dx > 0) and np.all(dy < 0)
    assert_allclose(np.hypot(dx, dy), L, rtol=1e-15)
