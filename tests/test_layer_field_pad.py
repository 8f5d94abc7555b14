"""The fibre field on a layer at pad scale (gecko_agents.physics.pad_field): its operator and
kernel against the event-to-event field's (the home of the model), its load-step solution
against the event-to-event press and pull with the tolerances at zero, the tolerances'
effect on the pull-off, and its refusals."""

import math

import numpy as np
import pytest

from gecko_agents.physics import layer, pad_field
from gecko_agents.physics import layer_field as lf

E, NU, F_R, K = 1.413, 0.3, 4.66, 2.0


def _field(t, n=9, cls=lf.LayerField):
    return cls(n=n, pitch=4.0, radius=1.5, stiffness=K, release_force=F_R, thickness=t,
               modulus=E, poisson=NU)  # fmt: skip


@pytest.mark.parametrize(("t", "n"), [(2.0, 40), (10.0, 12), (math.inf, 12), (160.0, 12)])
@pytest.mark.parametrize("single", [False, True])
def test_operator_is_the_event_to_event_fields(t, n, single):
    """C·f by the pad's FFT (padded only as far as the kernel reaches: a 2 µm layer's field
    of 40 needs 40 + 15, not 80) equals the event-to-event field's on random forces, to
    round-off (1e-9; the event-to-event field rounds distances to 1e-9 µm) or, in single
    precision, 1e-6."""
    field = _field(t, n)
    op = pad_field.PadOperator(field, single=single)
    f = np.random.default_rng(3).normal(size=(n, n))
    ref = lf.LayerOperator(field)(f)
    np.testing.assert_allclose(op(f), ref, rtol=0, atol=(1e-6 if single else 1e-9) * abs(ref).max())
    assert op.self_term == lf.LayerOperator(field).self_term
    if t == 2.0:
        assert op.m < 2 * n


@pytest.mark.parametrize(("t", "reach"), [(20.0, 100.0), (1120.0, 2000.0), (5.0, 200.0)])
def test_interpolated_kernel_is_the_point_kernel(t, reach):
    """Past DIRECT_MAX distances the kernel is 1/(πE*r) less a spline of the layer's
    correction: within 1e-9 of the self term of the point kernel at lattice distances (4 µm
    pitch) out to ``reach`` [µm], past the kernel's cutoff (30 t) for the 5 µm layer, where
    both are 0; the self term exact."""
    i, j = np.meshgrid(np.arange(int(reach / 4.0)), np.arange(40), indexing="ij")
    r = np.unique(4.0 * np.hypot(i, j).ravel())
    got = pad_field._interpolated_kernel(r, t, E, NU, 1.5)
    pick = np.r_[0, np.random.default_rng(2).choice(r.size, 150, replace=False)]
    ref = layer.point_kernel(r[pick], t, E, NU, 1.5)
    assert got[0] == ref[0]
    np.testing.assert_allclose(got[pick], ref, rtol=0, atol=1e-9 * ref[0])
    assert np.all(got[r > layer.CUTOFF * t] == 0.0)


@pytest.mark.parametrize("t", [10.0, 200.0, math.inf])
@pytest.mark.parametrize(("probe_radius", "tilt"), [(60.0, 0.0), (math.inf, 0.0), (math.inf, 0.5)])
def test_zero_tolerance_is_the_event_to_event_test(t, probe_radius, tilt):
    """With force_tol = cascade_tol = 0 the load steps meet every release the event-to-event
    test meets: the same pull-off, preload depth, contact and fibres that let go (9 × 9)."""
    field = _field(t)
    h = lf.probe_heights(field, probe_radius, tilt)
    exact = lf.press_pull(field, h, 20.0, resolution=1e-9)
    got = pad_field.press_pull_pad(field, h, 20.0, force_tol=0.0, cg_tol=1e-9)
    assert got.pull_off == pytest.approx(exact.pull_off, rel=1e-7)
    assert got.depth_max == pytest.approx(exact.depth_max, rel=1e-7)
    assert got.attached_max == exact.attached_max
    np.testing.assert_array_equal(np.isfinite(got.released_at), np.isfinite(exact.released_at))
    np.testing.assert_allclose(got.released_at, exact.released_at, rtol=1e-6)


@pytest.mark.parametrize(("t", "tilt"), [(160.0, 0.0), (1120.0, 0.0), (160.0, 1.0)])
def test_tolerances_cost_less_than_half_a_percent(t, tilt):
    """A 32 × 32 field of the backing-layer study's pillars (k = 0.45 µN/µm): the pad's
    default tolerances (releases within 0.3 % of F_r at a depth, 5 % within a cascade), stopped
    once the pull-off is decided, in single precision, hold the event-to-event pull-off to
    0.5 % in fewer solves."""
    field = lf.LayerField(n=32, pitch=4.0, radius=1.5, stiffness=0.45, release_force=F_R,
                          thickness=t, modulus=E, poisson=NU)  # fmt: skip
    h = lf.probe_heights(field, math.inf, tilt)
    P = 0.2 * 32 * 32 * F_R
    exact = lf.press_pull(field, h, P, resolution=1e-6)
    got = pad_field.press_pull_pad(field, h, P, **pad_field.PAD_TOLERANCES)
    assert got.pull_off == pytest.approx(exact.pull_off, rel=5e-3)
    assert got.solves < exact.solves


def test_stopping_early_keeps_the_pull_off():
    """Stopped once the fibres left could not hold the largest tension reached, the pull-off
    is the full pull's, and the fibres left keep release depth NaN."""
    field = _field(40.0, 16, pad_field.PadField)
    h = np.zeros((16, 16))
    full = pad_field.press_pull_pad(field, h, 50.0)
    early = pad_field.press_pull_pad(field, h, 50.0, stop_early=True)
    assert early.pull_off == full.pull_off
    left = np.isnan(early.released_at)
    assert left.sum() * F_R <= early.pull_off and not np.isnan(full.released_at).any()
    assert early.solves < full.solves


KW = {"pitch": 4.0, "radius": 1.5, "stiffness": K, "release_force": F_R, "thickness": 10.0,
      "modulus": E, "poisson": NU}  # fmt: skip


def test_a_pad_field_takes_4096_and_the_oracle_1000():
    """A pad field is the event-to-event field's up to n = 4096; the oracle stops at 1000,
    each refusal naming its class, value and range."""
    assert pad_field.PadField(n=4096, **KW).n == 4096
    with pytest.raises(ValueError, match=r"^PadField\.n = 4097 .*\[1, 4096\]"):
        pad_field.PadField(n=4097, **KW)
    with pytest.raises(ValueError, match=r"^LayerField\.n = 1001 .*\[1, 1000\]"):
        lf.LayerField(n=1001, **KW)


@pytest.mark.parametrize(
    ("kw", "match"),
    [({"preload": 0.0}, "preload"), ({"force_tol": 0.1}, "force_tol"),
     ({"force_tol": -1e-3}, "force_tol"), ({"cascade_tol": 0.5}, "cascade_tol"),
     ({"cg_tol": 0.0}, "cg_tol"), ({"cg_tol": 1e-2}, "cg_tol")],
)  # fmt: skip
def test_bad_pad_test_refused(kw, match):
    field = _field(10.0, 5)
    args = {"preload": 1.0} | kw
    with pytest.raises(ValueError, match=rf"^{match} = "):
        pad_field.press_pull_pad(field, np.zeros((5, 5)), **args)
    with pytest.raises(ValueError, match="heights"):
        pad_field.press_pull_pad(field, np.zeros((4, 5)), 1.0)
