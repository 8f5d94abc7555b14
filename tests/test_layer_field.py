"""The quasi-static fibre field on a layer (gecko_agents.physics.layer_field): its FFT and
conjugate-gradient solution against the exact event-driven probe test on the dense layer
compliance, the rigid-backing closed form, and its refusals."""

import math

import numpy as np
import pytest

from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import fibril_probe, layer
from gecko_agents.physics import fibril_probe_halfspace as halfspace
from gecko_agents.physics import layer_field as lf

E, NU, F_R, K = 1.413, 0.3, 4.66, 2.0


def _field(t, n=9):
    return lf.LayerField(n=n, pitch=4.0, radius=1.5, stiffness=K, release_force=F_R,
                         thickness=t, modulus=E, poisson=NU)  # fmt: skip


@pytest.mark.parametrize("t", [10.0, 200.0, math.inf])
@pytest.mark.parametrize(("probe_radius", "tilt"), [(60.0, 0.0), (math.inf, 0.0), (math.inf, 0.5)])
def test_field_is_the_event_driven_probe_test(t, probe_radius, tilt):
    """The same pull-off and contact as probe_test(h, I/k + C_layer, F_r, P) (dense)."""
    field = _field(t)
    h = lf.probe_heights(field, probe_radius, tilt)
    x, y = field.positions()
    C = layer.field_compliance(x.ravel(), y.ravel(), t, E, NU, 1.5) + np.eye(x.size) / K
    exact = halfspace.probe_test(h.ravel(), C, F_R, 20.0)
    got = lf.press_pull(field, h, 20.0, resolution=1e-9)
    assert got.pull_off == pytest.approx(exact.pull_off, rel=1e-8)
    assert got.attached_max == exact.attached_max
    assert got.depth_max == pytest.approx(exact.depth_max, rel=1e-8)
    assert np.isfinite(got.released_at).sum() == exact.attached_max


def test_rigid_limit_is_independent_fibres():
    """A very stiff layer: the independent-fibre closed form (fibril_probe) under a sphere."""
    field = lf.LayerField(n=15, pitch=4.0, radius=1.5, stiffness=K, release_force=F_R,
                          thickness=1.0, modulus=1e7, poisson=0.3)  # fmt: skip
    h = lf.probe_heights(field, 80.0)
    got = lf.press_pull(field, h, 30.0, resolution=1e-9)
    d_max = fibril_probe.depth_for_preload(30.0, h.ravel(), K)
    closed = fibril_probe.probe_pull_off(h.ravel(), K, F_R, d_max)
    assert got.pull_off == pytest.approx(closed, rel=1e-6)


def test_flat_probe_thin_layer_holds_more():
    """Aligned flat probe: a thin layer shares the load, a thick one loads the edge."""
    pulls = [lf.press_pull(_field(t, 15), np.zeros((15, 15)), 10.0).pull_off for t in (4.0, 400.0)]
    assert pulls[0] > pulls[1]
    assert pulls[0] <= 15 * 15 * F_R * (1 + 1e-9)


def test_from_params_and_heights():
    f = lf.LayerField.from_params(PAPER_ARRAY, 5, thickness=160.0)
    assert (f.thickness, f.modulus, f.poisson) == (160.0, PAPER_ARRAY.backing.E_b, 0.3)
    assert f.pitch == PAPER_ARRAY.array.pitch and f.release_force > 0
    h = lf.probe_heights(_field(20.0, 5), math.inf, 1.0)
    assert h.max() == 0.0 and np.all(h[0] == 0.0)  # the −x edge touches first
    assert h[-1, 0] == pytest.approx(-math.tan(math.radians(1.0)) * 16.0)


@pytest.mark.parametrize(
    ("field", "value", "match"),
    [("thickness", 0.0, "thickness"), ("thickness", -2.0, "thickness"),
     ("poisson", 0.6, r"poisson = 0\.6 must be in \[0, 0\.5\]"), ("poisson", -0.1, "poisson"),
     ("radius", 3.0, "radius"), ("n", 0, "n = 0"), ("stiffness", 0.0, "stiffness")],
)  # fmt: skip
def test_bad_field_refused(field, value, match):
    kw = {"n": 5, "pitch": 4.0, "radius": 1.5, "stiffness": K, "release_force": F_R,
          "thickness": 10.0, "modulus": E, "poisson": NU} | {field: value}  # fmt: skip
    with pytest.raises(ValueError, match=match):
        lf.LayerField(**kw)


def test_bad_test_refused():
    field = _field(10.0, 5)
    with pytest.raises(ValueError, match="preload"):
        lf.press_pull(field, np.zeros((5, 5)), 0.0)
    with pytest.raises(ValueError, match="heights"):
        lf.press_pull(field, np.zeros((4, 5)), 1.0)
    with pytest.raises(ValueError, match="tilt_deg"):
        lf.probe_heights(field, 50.0, 1.0)


def test_incompressible_layer_is_taken_as_it_is():
    """ν = ½ (no confined modulus: G → q²t³/(3μ)) is the dense event-driven test's too; on
    a thin layer the confined centre is the stiffest place and lets go first, the edges,
    free to contract, last."""
    field = lf.LayerField(n=9, pitch=4.0, radius=1.5, stiffness=K, release_force=F_R,
                          thickness=4.0, modulus=0.3, poisson=0.5)  # fmt: skip
    x, y = field.positions()
    C = layer.field_compliance(x.ravel(), y.ravel(), 4.0, 0.3, 0.5, 1.5) + np.eye(x.size) / K
    exact = halfspace.probe_test(np.zeros(x.size), C, F_R, 10.0)
    got = lf.press_pull(field, np.zeros((9, 9)), 10.0, resolution=1e-9)
    assert got.pull_off == pytest.approx(exact.pull_off, rel=1e-8)
    ev = got.release_event
    assert ev[4, 4] == ev.min() and ev[0, 4] > ev[4, 4] and ev[0, 0] > ev[4, 4]


def test_from_params_puts_the_seta_and_its_contact_in_series():
    """A fibre of the field is the seta's bending spring K_y (eq 20) in series with its tip's
    zero-load contact stiffness k_c: 1/k = 1/K_y + 1/k_c, softer than either, and it lets go
    at the tip law's pull-off force."""
    from gecko_agents.contact import contact_law

    law = contact_law(PAPER_ARRAY)
    f = lf.LayerField.from_params(PAPER_ARRAY, 5)
    assert 1.0 / f.stiffness == pytest.approx(
        1.0 / PAPER_ARRAY.Ky + 1.0 / law.zero_load_stiffness, rel=1e-12
    )
    assert f.stiffness < min(PAPER_ARRAY.Ky, law.zero_load_stiffness)
    assert f.release_force == law.pull_off_force


def test_the_limits_of_the_probe_are_accepted():
    """A flat probe tilted to ±10° (the range's ends) and a sphere of any radius > 0 (here
    0.5 µm) are taken; ±10.5° and a radius of 0 are refused, naming the parameter."""
    field = _field(10.0, 5)
    for tilt in (-10.0, 10.0):
        h = lf.probe_heights(field, math.inf, tilt)
        assert h.max() == 0.0 and h.min() == pytest.approx(-math.tan(math.radians(10.0)) * 16.0)
    assert lf.probe_heights(field, 0.5, 0.0).max() == 0.0
    for tilt in (-10.5, 10.5):
        with pytest.raises(ValueError, match=rf"^tilt_deg = {tilt}"):
            lf.probe_heights(field, math.inf, tilt)
    with pytest.raises(ValueError, match=r"^probe_radius = 0"):
        lf.probe_heights(field, 0.0, 0.0)


def test_the_path_of_a_tilted_probe_is_the_event_driven_tests():
    """A flat probe tilted 0.5° over a 5 × 5 field on a 10 µm layer (no symmetry across the
    tilt): the press passes through the dense event-driven test's events (depth, force,
    fibres attached), and every event of its pull is one of the field's, which also records
    each step of a cascade at one depth. Each fibre's release depth is that of the event its
    index points at, and the front of an event is the mean distance from the centre of the
    fibres that let go there. The field is centred on 0, ``pitch`` apart."""
    field = _field(10.0, 5)
    x, y = field.positions()
    np.testing.assert_allclose(x[:, 0], [-8.0, -4.0, 0.0, 4.0, 8.0], atol=1e-15)
    np.testing.assert_array_equal(y, x.T)
    h = lf.probe_heights(field, math.inf, 0.5)
    C = layer.field_compliance(x.ravel(), y.ravel(), 10.0, E, NU, 1.5) + np.eye(x.size) / K
    exact = halfspace.probe_test(h.ravel(), C, F_R, 20.0)
    got = lf.press_pull(field, h, 20.0, resolution=1e-9)
    top = int(np.argmax(exact.depth)) + 1
    np.testing.assert_allclose(got.depth[:top], exact.depth[:top], rtol=1e-8)
    np.testing.assert_allclose(got.force[:top], exact.force[:top], rtol=1e-8)
    np.testing.assert_array_equal(got.attached[:top], exact.attached[:top])
    for d, F, n in zip(exact.depth[top:], exact.force[top:], exact.attached[top:], strict=True):
        i = np.flatnonzero(np.isclose(got.depth, d, rtol=1e-8) & (got.attached == n))
        assert i.size and got.force[i[0]] == pytest.approx(F, rel=1e-8, abs=1e-9)
    ev = got.release_event
    np.testing.assert_array_equal(got.depth[ev], got.released_at)
    r = np.hypot(x, y)
    for j in range(top, got.depth.size - 1):
        assert got.front[j] == pytest.approx(r[ev == j].mean(), rel=1e-12)


@pytest.mark.parametrize(("shift", "scale"), [(0.6, 1.0), (-0.3, 1.0), (0.0, 1e-6), (0.0, 1e6)])
def test_only_relative_heights_matter_and_forces_scale_out(shift, scale):
    """A sphere (R_p = 30 µm) pressed to 0.5 µN into a 5 × 5 field on a 10 µm layer, its
    fibres' tips all shifted by c, or every force scaled by λ (stiffness, layer modulus,
    release force and preload: the compliances over λ): the same attached counts and depths
    shifted by −c, every force times λ. Fibres the probe never reaches keep release depth
    NaN and event −1."""
    kw = {"n": 5, "pitch": 4.0, "radius": 1.5, "thickness": 10.0, "poisson": NU}
    ref_field = lf.LayerField(stiffness=K, release_force=F_R, modulus=E, **kw)
    field = lf.LayerField(stiffness=K * scale, release_force=F_R * scale, modulus=E * scale, **kw)
    h = lf.probe_heights(ref_field, 30.0)
    ref = lf.press_pull(ref_field, h, 0.5, resolution=1e-9)
    got = lf.press_pull(field, h + shift, 0.5 * scale, resolution=1e-9)
    assert got.pull_off == pytest.approx(scale * ref.pull_off, rel=1e-8)
    np.testing.assert_allclose(got.depth, ref.depth - shift, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(got.force, scale * ref.force, rtol=1e-8, atol=1e-9 * scale)
    np.testing.assert_array_equal(got.attached, ref.attached)
    never = ref.release_event == -1
    assert never.any() and np.isnan(ref.released_at[never]).all()
    np.testing.assert_array_equal(got.release_event, ref.release_event)
