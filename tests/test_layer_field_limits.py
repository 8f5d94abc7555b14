"""The fibre field on a layer (gecko_agents.physics.layer_field) at the edges of what it
accepts and of what it resolves: each parameter's range taken at its ends and refused just
outside them, a single fibre (the closed form of its spring on the layer), the FFT operator
against the dense compliance, events that fall within ``resolution`` of each other, every
release at its fibre's pull-off (a dense solve per event), and the counters against an
independent count. No test here may warn (``filterwarnings = error``)."""

import math
import re

import numpy as np
import pytest

from gecko_agents.physics import fibril_probe, layer
from gecko_agents.physics import layer_field as lf

pytestmark = pytest.mark.filterwarnings("error")

E, NU, F_R, K = 1.413, 0.3, 4.66, 2.0
BASE = {"n": 5, "pitch": 5.0, "radius": 1.5, "stiffness": K, "release_force": F_R,
        "thickness": 10.0, "modulus": E, "poisson": NU}  # fmt: skip


def _field(**kw):
    return lf.LayerField(**(BASE | kw))


# each parameter at the ends of its range (taken) and just outside them (refused)
TAKEN = [("n", 1), ("n", 1000), ("n", np.int64(7)), ("radius", 2.5), ("radius", 1e-9),
         ("pitch", 3.0), ("stiffness", 1e-300), ("release_force", 1e-300),
         ("modulus", 1e-300), ("thickness", 1e-300), ("thickness", math.inf),
         ("poisson", 0.0), ("poisson", 0.5)]  # fmt: skip
REFUSED = [("n", 0, r"\[1, 1000\]"), ("n", 1001, r"\[1, 1000\]"), ("n", 5.0, r"\[1, 1000\]"),
           ("radius", 0.0, r"\(0, pitch/2 = 2\.5\] µm$"),
           ("radius", math.nextafter(2.5, 3.0), r"\(0, pitch/2 = 2\.5\] µm$"),
           ("radius", -1.0, r"\(0, pitch/2 = 2\.5\] µm$"),
           ("pitch", 0.0, r"\(0, inf\)$"), ("pitch", math.inf, r"\(0, inf\)$"),
           ("stiffness", -1.0, r"\(0, inf\)$"), ("stiffness", math.nan, r"\(0, inf\)$"),
           ("release_force", 0.0, r"\(0, inf\)$"), ("modulus", math.inf, r"\(0, inf\)$"),
           ("modulus", "1.4", r"\(0, inf\)$"), ("thickness", 0.0, r"\(0, inf\] µm$"),
           ("thickness", math.nan, r"\(0, inf\] µm$"), ("thickness", -1.0, r"\(0, inf\] µm$"),
           ("poisson", -1e-12, r"\[0, 0\.5\]$"),
           ("poisson", math.nextafter(0.5, 1.0), r"\[0, 0\.5\]$")]  # fmt: skip


@pytest.mark.parametrize(("name", "value"), TAKEN)
def test_each_range_is_taken_at_its_ends(name, value):
    """n in [1, 1000], the base radius up to half the pitch (touching bases), a pitch of
    twice the radius, positive scales as small as 1e-300, the half-space (t = inf) and ν at
    0 and ½ are fields; a pitch of 1e-300 µm with bases of 5e-301 µm too."""
    field = _field(**{name: value})
    assert getattr(field, name) == value
    assert lf.LayerField(**(BASE | {"pitch": 1e-300, "radius": 5e-301})).pitch == 1e-300


@pytest.mark.parametrize(("name", "value", "span"), REFUSED)
def test_each_range_is_refused_just_outside(name, value, span):
    """Just outside each range (the next float past pitch/2 and past ½, n = 0 and 1001, a
    float n, a zero, negative, infinite or NaN scale, a string), the error names the
    parameter, its value and its range."""
    with pytest.raises(
        ValueError, match=rf"^LayerField\.{name} = {re.escape(repr(value))} .* {span}"
    ):
        _field(**{name: value})


def test_a_single_fibre_is_its_spring_in_series_with_its_base():
    """n = 1: the fibre (1/k) in series with the layer under its base disc (C₀, the disc's
    mean compliance, :func:`gecko_agents.physics.layer.point_kernel` at 0). Pressed to P it
    sinks d = P(1/k + C₀); pulled, it holds F_r and lets go at d = −F_r(1/k + C₀), the front at
    the centre (r = 0). The path's counts are integers."""
    field = _field(n=1)
    c0 = float(layer.point_kernel(0.0, 10.0, E, NU, 1.5))
    assert lf.LayerOperator(field).self_term == pytest.approx(c0, rel=1e-15)
    got = lf.press_pull(field, np.zeros((1, 1)), 3.0)
    series = 1.0 / K + c0
    assert got.depth_max == pytest.approx(3.0 * series, rel=1e-12)
    assert got.pull_off == pytest.approx(F_R, rel=1e-12)
    np.testing.assert_allclose(got.depth, [3.0 * series, -F_R * series, -F_R * series], rtol=1e-12)
    np.testing.assert_allclose(got.force, [3.0, -F_R, 0.0], rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(got.attached, [1, 1, 0])
    assert got.attached.dtype.kind == "i" and got.attached_max == 1
    np.testing.assert_array_equal(got.front, [math.nan, 0.0, math.nan])
    assert got.released_at[0, 0] == pytest.approx(-F_R * series, rel=1e-12)
    assert got.release_event[0, 0] == 1


def test_a_thin_layer_under_one_fibre_is_a_spring_of_its_confined_modulus():
    """A layer 1e-3 of the base radius thick under a single fibre: a column of the confined
    modulus M over the base's area, compliance t/(M·πc²) (the thin limit of
    :mod:`gecko_agents.physics.layer`, within 1.5·t/c, its edge's share; measured 1.1e-4),
    in series with 1/k."""
    t, c = 1.5e-3, 1.5
    field = _field(n=1, thickness=t)
    got = lf.press_pull(field, np.zeros((1, 1)), 3.0)
    spring = t / (layer.confined_modulus(E, NU) * math.pi * c * c)
    assert got.depth_max - 3.0 / K == pytest.approx(3.0 * spring, rel=1.5 * t / c)


def test_the_fft_operator_is_the_dense_compliance():
    """C·f by the zero-padded FFT is the dense lattice compliance
    (:func:`gecko_agents.physics.layer.field_compliance`) times f, for any f: not periodic
    (the far corner does not see the near one as a neighbour); its self term is C₀₀. The
    operator takes the kernel at distances rounded to 1e-9 µm: measured within 7.5e-12 of the
    largest displacement."""
    for t, n in ((10.0, 6), (math.inf, 5), (2.0, 1)):
        field = _field(n=n, thickness=t)
        op = lf.LayerOperator(field)
        x, y = field.positions()
        C = layer.field_compliance(x.ravel(), y.ravel(), t, E, NU, 1.5)
        f = np.random.default_rng(7).normal(size=(n, n))
        w = op(f)
        assert w.shape == (n, n)
        np.testing.assert_allclose(w.ravel(), C @ f.ravel(), rtol=0, atol=5e-11 * np.abs(w).max())
        assert op.self_term == C[0, 0]


def test_the_counters_are_the_solves_and_products_made(monkeypatch):
    """``solves`` is the number of conjugate-gradient solves and ``matvecs`` that of FFT
    products C·f (each one inverse FFT), counted here independently by wrapping both."""
    count = {"cg": 0, "irfft2": 0}
    cg, irfft2 = lf.cg, np.fft.irfft2

    def counted_cg(*args, **kwargs):
        count["cg"] += 1
        return cg(*args, **kwargs)

    def counted_irfft2(*args, **kwargs):
        count["irfft2"] += 1
        return irfft2(*args, **kwargs)

    monkeypatch.setattr(lf, "cg", counted_cg)
    monkeypatch.setattr(np.fft, "irfft2", counted_irfft2)
    field = _field()
    got = lf.press_pull(field, lf.probe_heights(field, 40.0), 2.0)
    assert got.solves == count["cg"] > 0
    assert got.matvecs == count["irfft2"] > got.solves
    op = lf.LayerOperator(field)
    for _ in range(3):
        op(np.ones((5, 5)))
    assert op.calls == 3


@pytest.mark.parametrize(
    ("kw", "name"),
    [({"preload": 0.0}, "preload"), ({"preload": -1.0}, "preload"),
     ({"preload": math.inf}, "preload"), ({"preload": math.nan}, "preload"),
     ({"resolution": 0.0}, "resolution"), ({"resolution": -1e-4}, "resolution"),
     ({"resolution": math.inf}, "resolution"), ({"resolution": math.nan}, "resolution")],
)  # fmt: skip
def test_a_test_is_refused_outside_its_ranges(kw, name):
    """preload and resolution in (0, inf): zero, negative, infinite and NaN refused, naming
    the parameter and its value; heights with a NaN or of another shape refused."""
    field = _field(n=3)
    args = {"preload": 1.0, "resolution": 1e-4} | kw
    with pytest.raises(ValueError, match=rf"^{name} = {re.escape(repr(kw[name]))} µ"):
        lf.press_pull(field, np.zeros((3, 3)), **args)


def test_a_test_takes_the_smallest_preload_and_resolution():
    """A preload of 1e-12 µN and a resolution of 1e-300 µm are taken: the flat probe's nine
    fibres share the preload, each at P/9 on its spring and the layer."""
    field = _field(n=3)
    got = lf.press_pull(field, np.zeros((3, 3)), 1e-12, resolution=1e-300)
    assert got.attached_max == 9 and got.pull_off > 0
    for h in (np.full((3, 3), math.nan), np.zeros((3, 4))):
        with pytest.raises(ValueError, match="heights"):
            lf.press_pull(field, h, 1.0)


def test_the_default_resolution_resolves_a_tilted_probes_columns():
    """A flat probe tilted 0.5° over a 5 × 5 field on a stiff layer (E = 1e7 MPa: the fibres
    independent to ~1e-7), its columns 4.4e-2 µm apart in height, with the default resolution,
    1e-4 µm: the press takes one column per event, at the column's own depth, and reaches the
    independent fibres' depth at the preload and their pull-off
    (:mod:`gecko_agents.physics.fibril_probe`); measured within 7e-8 of them."""
    field = _field(modulus=1e7)
    h = lf.probe_heights(field, math.inf, 0.5)
    got = lf.press_pull(field, h, 20.0)
    step = 5.0 * math.tan(math.radians(0.5))
    top = int(np.argmax(got.depth)) + 1
    np.testing.assert_array_equal(got.attached[:top], [5, 10, 15, 20, 25])
    np.testing.assert_allclose(got.depth[: top - 1], step * np.arange(1, 5), rtol=1e-6)
    d_max = fibril_probe.depth_for_preload(20.0, h.ravel(), K)
    assert got.depth_max == pytest.approx(d_max, rel=1e-6)
    assert got.pull_off == pytest.approx(
        fibril_probe.probe_pull_off(h.ravel(), K, F_R, d_max), rel=1e-6
    )
    np.testing.assert_array_equal(got.attached[top:], [25, 20, 15, 10, 5, 0])


def _stepped(field, d1, d2):
    """Heights of a 3 × 3 field: the centre at 0, the four edge fibres at −d1, the corners
    at −d2 [µm]."""
    h = np.full((3, 3), -d2)
    h[1, :] = h[:, 1] = -d1
    h[1, 1] = 0.0
    return h


@pytest.mark.parametrize(("resolution", "merged"), [(1e-3, True), (1e-9, False)])
def test_events_within_resolution_go_together(resolution, merged):
    """Independent fibres (a layer of 1e7 MPa) under a flat probe, the centre's tip at 0,
    the edges' 2e-3 µm and the corners' 2.5e-3 µm lower: with a resolution of 1e-3 µm the
    corners (5e-4 µm past the edges) attach with the edges when the probe reaches the edges,
    and let go with them; with 1e-9 µm each ring has its own event. Each event is at its
    ring's depth, d = −h on the press and −F_r/k − h on the pull (to 5e-7 µm: the stiff layer's
    compliance, measured 1.6e-7 µm on the pull)."""
    field = _field(n=3, modulus=1e7)
    d1, d2 = 2e-3, 2.5e-3
    got = lf.press_pull(field, _stepped(field, d1, d2), 10.0, resolution=resolution)
    rel = -F_R / K
    if merged:
        press, pull = [d1], [rel + d2, rel, rel]
        attached = [1, 9, 9, 1, 0]
    else:
        press, pull = [d1, d2], [rel + d2, rel + d1, rel, rel]
        attached = [1, 5, 9, 9, 5, 1, 0]
    top = len(press)
    d_max = (10.0 / K + 4 * d1 + 4 * d2) / 9  # Σ k(d + h_i) = P
    np.testing.assert_allclose(got.depth, press + [d_max] + pull, rtol=0, atol=5e-7)
    np.testing.assert_array_equal(got.attached, attached)
    assert got.force[0] == pytest.approx(K * d1, rel=1e-4)
    corner = got.release_event[0, 0]
    assert (got.release_event[0, 1] == corner) == merged
    assert got.released_at[0, 0] == pytest.approx(rel + d2, abs=5e-7)
    assert got.release_event[1, 1] == got.depth.size - 2 > corner > top


@pytest.mark.parametrize(("t", "tilt"), [(400.0, 0.0), (10.0, 0.3)])
def test_every_fibre_lets_go_at_its_pull_off(t, tilt):
    """A flat probe (aligned, or tilted 0.3°) pulled off a 7 × 7 field on a thick layer
    (the edges let go first and the rest follow in a cascade) or a thin one: at each event of
    the pull, the dense solve with the fibres still attached before it,
    (C_AA + I/k)·f = d + h_A (:func:`gecko_agents.physics.layer.field_compliance`), puts
    every fibre the event lets go at −F_r or beyond and every other at −F_r or above, and
    the probe's force is their sum. Tolerance 1e-7·F_r: the conjugate gradients' rtol and the
    resolution, 1e-9 (measured 5e-10)."""
    field = _field(n=7, thickness=t)
    h = lf.probe_heights(field, math.inf, tilt)
    x, y = field.positions()
    C = layer.field_compliance(x.ravel(), y.ravel(), t, E, NU, 1.5) + np.eye(49) / K
    got = lf.press_pull(field, h, 30.0, resolution=1e-9)
    ev, top = got.release_event.ravel(), int(np.argmax(got.depth)) + 1
    assert ev.min() == top and got.attached_max == 49
    for j in range(top, got.depth.size - 1):
        A = np.flatnonzero(ev >= j)
        f = np.linalg.solve(C[np.ix_(A, A)], got.depth[j] + h.ravel()[A])
        going = ev[A] == j
        assert going.any() and got.attached[j] == A.size
        assert np.all(f[going] <= -F_R * (1 - 1e-7))
        assert np.all(f[~going] >= -F_R * (1 + 1e-7))
        assert got.force[j] == pytest.approx(f.sum(), rel=1e-7)
    assert got.pull_off == pytest.approx(-got.force.min(), rel=1e-15)


def test_a_cascade_at_one_depth_takes_only_the_fibres_past_their_pull_off():
    """A flat probe tilted 0.3° pulled off a 7 × 7 field on a 10 µm layer with a coarse
    resolution, 1e-2 µm: an event at the depth of the one before it (a cascade step, the
    field unstable after a release) lets go only fibres that the dense solve with the fibres
    attached before it puts at −F_r or beyond; fibres within the resolution of their pull-off
    but not past it wait for an event of their own. Tolerance 1e-7·F_r (the solves' rtol;
    measured: each at least 2.5e-4·F_r past it)."""
    field = _field(n=7)
    h = lf.probe_heights(field, math.inf, 0.3)
    x, y = field.positions()
    C = layer.field_compliance(x.ravel(), y.ravel(), 10.0, E, NU, 1.5) + np.eye(49) / K
    got = lf.press_pull(field, h, 30.0, resolution=1e-2)
    ev, top = got.release_event.ravel(), int(np.argmax(got.depth)) + 1
    steps = [j for j in range(top + 1, got.depth.size - 1) if got.depth[j] == got.depth[j - 1]]
    assert steps  # the pull has cascades
    for j in steps:
        A = np.flatnonzero(ev >= j)
        f = np.linalg.solve(C[np.ix_(A, A)], got.depth[j] + h.ravel()[A])
        assert np.all(f[ev[A] == j] <= -F_R * (1 - 1e-7))
