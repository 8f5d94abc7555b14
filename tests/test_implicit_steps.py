"""The implicit step's length, event location and friction cap
(:mod:`gecko_agents.model.implicit`) by hand: the default step (twenty explicit steps 0.75/ω,
at most 0.01 µm of plate travel at the default speed, whole event steps), the steps a segment,
a bound or an event takes, which tips count as near an event, and a sticking tip whose
implicit friction passes its Coulomb cap (Thornton 1991's adhesive cap μ|P + 2Fc|, the paper's
μ·max(P, 0)) sliding at the cap. Three setae and no run: the fast tier's guard of the step's
bookkeeping. Units: µm, µN, µs, ng.
"""

import math
from types import SimpleNamespace

import extras
import numpy as np
import pytest

from gecko_agents.model import Model, Numerics
from gecko_agents.model.implicit import (
    FREE_RINGING_SHARE,
    check_integrator,
    default_event_dt,
    implicit_time_step,
    whole_event_steps,
)
from gecko_agents.model.implicit_kernel import pad_kernels, pad_solver
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics.friction import friction_cap

THREE = PAPER_TABLE1.replace(**{"array.count": 3})


def _model(params=THREE, **numerics):
    return Model(
        params, n_sim=3, numerics=Numerics(integrator="implicit", kernel="numpy", **numerics)
    )


def test_whole_event_steps_and_the_default_steps_by_hand():
    """Whole event steps within a bound, at least one (0.9/0.3 is 3 steps despite its
    rounding to 2.9999999999999996); the event step 0.75/ω; the default step 20·0.75/ω where
    it travels at most 0.01 µm at 0.005 µm/µs (2 µs), else the most whole event steps
    within 2 µs (the travel itself if no event step fits); a chosen dt stands."""
    assert whole_event_steps(1.0, 0.3) == pytest.approx(0.9, rel=1e-15)
    assert whole_event_steps(0.9, 0.3) == pytest.approx(0.9, rel=1e-15)
    assert whole_event_steps(0.2, 0.3) == 0.3
    assert default_event_dt(7.5) == 0.1
    assert implicit_time_step(None, 10.0) == pytest.approx(1.5, rel=1e-15)  # 20·0.075 < 2
    # ω = 5: 20·0.15 = 3 µs > 2 µs: 13 event steps of 0.15 (1.95 µs), 6 of a chosen 0.3.
    assert implicit_time_step(None, 5.0) == pytest.approx(1.95, rel=1e-12)
    assert implicit_time_step(None, 5.0, event_dt=0.3) == pytest.approx(1.8, rel=1e-12)
    assert implicit_time_step(None, 5.0, event_dt=2.5) == pytest.approx(2.0, rel=1e-12)
    assert implicit_time_step(None, 7.5) == pytest.approx(2.0, rel=1e-12)  # exactly 20·0.1
    assert implicit_time_step(0.5, 5.0) == 0.5 and implicit_time_step(3, 5.0) == 3.0
    for bad in (0, 0.0, -1.0, math.inf, math.nan, "1"):
        with pytest.raises(ValueError, match="dt = "):
            implicit_time_step(bad, 5.0)


def test_auto_picks_the_implicit_step_where_it_is_verified():
    """``auto``: the implicit step for batch contact with the linear seta, the rod and the
    elastic strip; the explicit one for callback contact, the elastica's chain and the
    layer backing; a named integrator stands where it can run."""
    assert check_integrator("auto", "batch") == "implicit"
    assert check_integrator("auto", "callback") == "explicit"
    assert check_integrator("auto", "batch", PAPER_TABLE1) == "implicit"
    assert check_integrator("auto", "batch", PAPER_TABLE1.replace(mechanics="rod")) == "implicit"
    elastica = PAPER_TABLE1.replace(mechanics="elastica")
    layer = PAPER_TABLE1.replace(**{"backing.kind": "layer"})
    elastic = PAPER_TABLE1.replace(**{"backing.kind": "elastic"})
    assert check_integrator("auto", "batch", elastica) == "explicit"
    assert check_integrator("auto", "batch", layer) == "explicit"
    assert check_integrator("auto", "batch", elastic) == "implicit"
    assert check_integrator("auto", "callback", PAPER_TABLE1) == "explicit"
    assert check_integrator("explicit", "callback") == "explicit"
    with pytest.raises(ValueError, match="integrator = 'implicit' with mechanics = 'elastica'"):
        check_integrator("implicit", "batch", elastica)
    with pytest.raises(ValueError, match="contact = 'batch'"):
        check_integrator("implicit", "callback")


def test_the_event_steps_of_a_chosen_step():
    """dt = 1 µs, events at 0.3 µs: 4 event steps (⌈3.33⌉), at 0.25 µs exactly 4 (not 5 by
    rounding); nothing located yet, no energy scale."""
    for event_dt in (0.3, 0.25):
        step = _model(dt=1.0, event_dt=event_dt)._implicit
        assert step.k_event == 4 and step.event_dt == 0.25
        assert step.n_located == 0 and step.energy_scale == 0.0 and step.near is None
    default = _model()._implicit  # 20 explicit steps 0.75/ω, events at one
    assert default.k_event == 20
    assert default.event_dt == pytest.approx(0.75 / _model().omega_max, rel=1e-12)


def test_a_change_of_step_keeps_the_recorded_kinetic_energy():
    """set_dt rescales the tips' force so that the recorder's kinetic energy ½m·v·(v + F·dt/m)
    is unchanged, and the loop's constants take the new dt and dt/(2m)."""
    m = _model()
    for i, tip in enumerate(m.world.tips):
        tip.velocity = (0.1 * i, -0.2)
    m.advance(0.0, 0.0)
    ke = m.kinetic_energy()
    assert abs(ke) > 1e-3
    dt = m.dt / 3
    m._implicit.set_dt(dt)
    assert m.dt == dt and m._constants.dt == dt and m.physics.c is m._constants
    assert m._constants.hm == pytest.approx(0.5 * dt / m.mass, rel=1e-15)
    assert m.kinetic_energy() == pytest.approx(ke, rel=1e-14)


def test_a_segment_and_a_bound_shorten_the_default_step_to_whole_event_steps():
    """The default step (20 event steps of 0.75/ω ≈ 0.099 µs) under a segment at 0.01 µm/µs
    (1 µs of travel cap): 10 event steps; at 0.2 µm/µs (0.05 µs) one event step, or the travel
    itself when the event step was chosen longer; a chosen dt stands. A bound of 0.5 µs: 5
    event steps; of 0.05 µs: one step of 0.05 µs."""
    m = _model()
    step = m._implicit
    ev, full = step.event_dt, step.dt_full
    step.begin_segment(None)
    assert step.dt_base == full and m.dt == full
    step.begin_segment(0.01)
    assert step.dt_base == pytest.approx(10 * ev, rel=1e-12) and m.dt == step.dt_base
    step.begin_segment(0.2)
    assert step.dt_base == pytest.approx(ev, rel=1e-12)
    long_events = _model(event_dt=0.5)._implicit
    long_events.begin_segment(0.1)
    assert long_events.dt_base == pytest.approx(0.1, rel=1e-12)
    chosen = _model(dt=1.0)._implicit
    k_chosen = chosen.k_event
    chosen.begin_segment(0.2)
    chosen.limit_step(0.05)
    assert chosen.dt_base == chosen.dt_full == 1.0 and chosen.k_event == k_chosen
    step.limit_step(5.0)
    assert step.dt_full == full and step.k_event == 20
    step.limit_step(full)  # a bound at the step itself changes nothing
    assert step.dt_full == full and step.k_event == 20 and step.event_dt == ev
    step.limit_step(0.5)
    assert step.dt_full == pytest.approx(5 * ev, rel=1e-12) and step.k_event == 5
    assert step.dt_base == step.dt_full and m.dt == step.dt_full and step._dt_prev == m.dt
    step.limit_step(0.05)
    assert step.dt_full == pytest.approx(0.05, rel=1e-12) and step.k_event == 1


def _near(m, vx, vy, attached, delta, k_raw=None, k_rate=None, normal=None, scale=0.0):
    """(k, near) of ``substeps`` at the plate speed 0.005 µm/µs for tips in the given state."""
    s, step = m.state, m._implicit
    s.pv[2], s.pv[3] = vx, vy
    s.attached[:] = attached
    s.delta[:] = delta
    step._k_raw = np.where(attached, 1.0, np.nan) if k_raw is None else np.asarray(k_raw)
    step._k_rate = np.zeros(3) if k_rate is None else np.asarray(k_rate)
    step.normal = normal
    step.energy_scale = scale
    k = step.substeps((0.0, 0.005))
    assert m.dt == pytest.approx(step.dt_base / k, rel=1e-15)
    return k, (np.zeros(3, bool) if step.near is None else step.near)


def test_which_tips_are_near_an_event():
    """Near an event, the step splits into its 20 event steps: an attached tip faster than
    twice the plate (0.01 µm/µs), free tips as fast while their kinetic energy passes a tenth
    of the books' tolerance of the run's energy scale, a tip within two steps of its snap-off
    overlap or (moving towards the floor) of its jump-in, a tip past its load-controlled
    pull-off (dP/dδ < 0) or reaching it within two steps at its last rate; on a continuous
    floor the attached tips' speed along their normal."""
    m = _model()
    step, law = m._implicit, m.law
    dt = step.dt_base
    free, att = [False] * 3, [True, False, False]
    off = law.detach_overlap
    zero = np.zeros(3)
    assert _near(m, zero, zero, free, np.nan) == (1, pytest.approx([False] * 3))
    assert step.near is None and step.n_located == 0
    k, near = _near(m, [0.0101, 0.0, 0.0], zero, att, [0.1, np.nan, np.nan])
    assert k == 20 and list(near) == [True, False, False] and step.n_located == 20
    assert _near(m, [0.0, 0.0, 0.0], [-0.0101, 0, 0], att, [0.1, np.nan, np.nan])[0] == 20
    assert step.n_located == 40  # every located step counted
    assert _near(m, [0.0099, 0, 0], zero, att, [0.1, np.nan, np.nan])[0] == 1
    # Free and fast: near while their kinetic energy counts.
    ke = 0.5 * m.mass * 0.02**2
    vx, vy = [0, 0.012, 0], [0, 0.016, 0]  # 0.02 µm/µs
    assert list(_near(m, vx, vy, free, np.nan)[1]) == [False, True, False]
    assert _near(m, vx, vy, free, np.nan, scale=0.9 * ke / FREE_RINGING_SHARE)[0] > 1
    assert _near(m, vx, vy, free, np.nan, scale=1.1 * ke / FREE_RINGING_SHARE)[0] == 1
    # Within two steps (2·dt·|v_n| = 0.0198 µm at 0.005 µm/µs) of snap-off or jump-in.
    vy = np.array([-0.005, -0.005, 0.005])
    d_in = [off + 0.019, -0.019, -0.001]  # the third moves away from the floor
    assert list(_near(m, zero, vy, att, d_in)[1]) == [True, True, False]
    assert _near(m, zero, vy, att, [off + 0.021, -0.021, -0.001])[0] == 1
    assert list(_near(m, zero, -vy, att, [off + 0.019, -0.019, -0.5])[1]) == [True, False, False]
    # Past the pull-off, or reaching it within two steps at the last rate.
    ks = dict(k_raw=[-0.1, np.nan, np.nan], k_rate=[10.0, 0.0, 0.0])
    assert _near(m, zero, zero, att, [0.1, np.nan, np.nan], **ks)[0] == 20
    ks = dict(k_raw=[1.0, np.nan, np.nan], k_rate=[-1.01 / (2 * dt), 0.0, 0.0])
    assert _near(m, zero, zero, att, [0.1, np.nan, np.nan], **ks)[0] == 20
    ks = dict(k_raw=[1.0, np.nan, np.nan], k_rate=[-0.99 / (2 * dt), 0.0, 0.0])
    assert _near(m, zero, zero, att, [0.1, np.nan, np.nan], **ks)[0] == 1
    # A continuous floor: the attached tip's speed along its normal (0.6, 0.8) (0.005 µm/µs
    # here); a free tip's jump-in reads its y velocity.
    normal = np.array([[0.6, 0.0, 0.0], [0.8, 1.0, 1.0]])
    vx, vy = [-0.005 / 0.6, 0.0, 0.005], [0.0, 0.0, -0.005]
    near = _near(m, vx, vy, att, [off + 0.019, np.nan, -0.019], normal=normal)[1]
    assert list(near) == [True, False, True]
    # n·v = 0.6·v_x + 0.8·v_y = 0 along the facet: not near, though v_y alone would reach.
    vx, vy = [-0.0064, 0.0, 0.0], [0.0048, 0.0, 0.0]
    assert _near(m, vx, vy, att, [off + 0.004, np.nan, -0.5], normal=normal)[0] == 1
    assert _near(m, vx, [-0.0048, 0, 0], att, [off + 0.004, np.nan, -0.5], normal=normal)[0] == 20
    step.normal = None


def test_two_event_steps_are_located_and_one_is_not():
    """A step of two event steps (dt = 1 µs, events at 0.5 µs) splits near an event and not
    away from one; a step no longer than its event step is never split."""
    m = _model(dt=1.0, event_dt=0.5)
    step = m._implicit
    att, zero = [True, False, False], np.zeros(3)
    assert _near(m, zero, zero, att, [0.1, np.nan, np.nan]) == (1, pytest.approx([False] * 3))
    k, near = _near(m, [0.02, 0.0, 0.0], zero, att, [0.1, np.nan, np.nan])
    assert k == 2 and list(near) == [True, False, False] and step.n_located == 2
    one = _model(dt=0.5, event_dt=1.0)
    assert one._implicit.k_event == 1
    assert _near(one, [0.02, 0.0, 0.0], zero, att, [0.1, np.nan, np.nan])[0] == 1
    assert one._implicit.near is None and one._implicit.n_located == 0


def _sticking(m, P, Ft, kt, fx, fy=None, v0=(0.0, 0.0)):
    """Three attached tips at rest with normal force ``P`` and tangential force ``Ft`` [µN],
    explicit forces F = (Ft, P); returns the F that ``_stick_past_cap`` returns for the
    implicit forces (``fx``, ``fy``) [µN], with the stick springs ``kt`` and dampers
    (c_t where kt > 0), the latter two as left."""
    s = m.state
    if m._implicit._pad is False:  # the numpy test (the model's first step would set it)
        m._implicit._pad = None
    s.pv[2], s.pv[3] = v0
    s.attached[:] = True
    s.slip[:] = np.asarray(kt) == 0.0
    s.P[:], s.Ft[:] = P, Ft
    s.F[0], s.F[1] = Ft, P
    kt = np.array(kt, float)
    ct = np.where(kt > 0.0, m.c_t, 0.0)
    fy = np.zeros(3) if fy is None else np.asarray(fy, float)
    out = m._implicit._stick_past_cap(np.asarray(fx, float), fy, kt, ct)
    return out, kt, ct


@pytest.mark.parametrize("compiled", [False, True])
def test_a_sticking_tip_past_its_cap_slides_at_the_cap(compiled):
    """A tip at rest sticking with F_t = 1 µN under the adhesive cap μ|P + 2Fc| (1.44 µN at
    P = 1 µN): with an implicit force that moves it along −x its friction at the step's end,
    F_t − dt·k_t·v₁ − c_t·(v₁ − v₀) with v₁ = F'·dt/m, is ≈ 9.9 µN, past the cap: it slides
    this step at +cap, its stick spring and damper out of the Jacobian; along +x (−7.9 µN) at
    −cap; a soft stick spring (0.5 µN/µm) too. A small motion (1.09 µN) keeps it sticking,
    and a sliding tip (no stick spring) is left to the kernel's return mapping whatever its
    force. The compiled test (the pad kernels) agrees."""
    m = _model()
    if compiled:
        if pad_kernels() is None:
            pytest.skip(extras.reason("fast"))
        m._implicit._pad = pad_kernels()
    Fc, mu, kt0, dt, mass = m.Fc, 0.2, m.k_t, m.dt, m.mass
    cap = friction_cap(1.0, Fc, mu, False)
    assert cap == pytest.approx(mu * (1.0 + 2 * Fc))
    v1 = -0.1 * dt / mass
    f = 1.0 - dt * kt0 * v1 - m.c_t * v1  # by hand: ≈ 9.9 µN
    assert f > 2 * cap
    out, kt, ct = _sticking(m, 1.0, 1.0, [kt0, kt0, 0.5], [-0.1, -0.001, -0.1])
    np.testing.assert_allclose(out[0], [cap, 1.0, cap], rtol=1e-15)
    np.testing.assert_array_equal(out[1], [1.0, 1.0, 1.0])
    assert list(kt) == [0.0, kt0, 0.0] and list(ct) == [0.0, m.c_t, 0.0]
    assert list(m.state.slip) == [True, False, True]
    np.testing.assert_allclose(m.state.Ft, [cap, 1.0, cap], rtol=1e-15)
    out = _sticking(m, 1.0, 1.0, [kt0, kt0, kt0], [0.1, 0.001, 0.0])[0]
    np.testing.assert_allclose(out[0], [-cap, 1.0, 1.0], rtol=1e-15)
    assert _sticking(m, 1.0, 1.0, [kt0, kt0, kt0], [-0.001, 0.001, 0.0])[0] is None
    assert _sticking(m, 1.0, 5.0, [0.0, 0.0, 0.0], [-0.1, -0.1, -0.1])[0] is None
    soft = _sticking(m, 1.0, 1.0, [0.5, 0.0, 0.0], [-0.1, 0.0, 0.0])[0]  # the soft spring alone
    assert soft is not None and soft[0, 0] == pytest.approx(cap, rel=1e-15)


def test_in_tension_under_the_papers_cap_a_tip_holds_no_shear():
    """The paper's cap μ·max(P, 0) (eq 27): a tip in tension (P = −1 µN) that the kernel left
    sticking with no friction slides at a friction of 0 once the implicit step moves it; the
    adhesive cap would have held it."""
    m = _model(THREE.replace(**{"friction.law": "paper"}))
    kt0 = m.k_t
    out, kt, _ = _sticking(m, -1.0, 0.0, [kt0, kt0, kt0], [-0.001, 0.0, 0.001])
    np.testing.assert_array_equal(out[0], [0.0, 0.0, 0.0])
    assert list(kt) == [0.0, kt0, 0.0] and list(m.state.slip) == [True, False, True]
    adhesive = _model()
    assert _sticking(adhesive, -1.0, 0.0, [kt0, kt0, kt0], [-0.001, 0.0, 0.001])[0] is None


def test_on_a_continuous_floor_the_cap_acts_along_the_floors_tangent():
    """On a facet tilted by 60° (n = (sin 60°, cos 60°), t = (n_y, −n_x)) a tip moved along
    −t slides at the cap along t: F' − F = (cap − F_t)·t; a tip moved as fast along n keeps
    sticking (its friction reads the tangent alone)."""
    m = _model()
    a = math.radians(60.0)
    n = np.array([math.sin(a), math.cos(a)])
    t = np.array([n[1], -n[0]])
    m._implicit.normal = np.repeat(n[:, None], 3, axis=1)
    Fc, kt0 = m.Fc, m.k_t
    cap = friction_cap(1.0, Fc, 0.2, False)
    fx = [-0.1 * t[0], -0.1 * n[0], 0.0]
    fy = [-0.1 * t[1], -0.1 * n[1], 0.0]
    s = m.state
    # Every tip also moves along n at 0.2 µm/µs (no tangential speed: v₀·t = 0; read along
    # another direction it would take the second tip past its cap).
    out, kt, _ = _sticking(m, 1.0, 1.0, [kt0, kt0, kt0], fx, fy, v0=0.2 * n[:, None])
    F = np.array([[1.0] * 3, [1.0] * 3])  # as _sticking set it
    np.testing.assert_allclose(out[:, 0] - F[:, 0], (cap - 1.0) * t, rtol=1e-14)
    np.testing.assert_array_equal(out[:, 1:], F[:, 1:])
    assert list(kt) == [0.0, kt0, kt0] and s.Ft[0] == pytest.approx(cap, rel=1e-15)
    m._implicit.normal = None


def test_the_compiled_kernels_run_only_where_their_assumptions_hold():
    """The compiled pad solve needs numba's pad loop, a pad floor (no contact normals), a rigid
    plate (one root point) and a linear or rod seta: any one missing, the numpy step runs."""
    if pad_kernels() is None:
        pytest.skip(extras.reason("fast"))
    fits = dict(kernel="numba", rigid=True, mechanics="rod", normal=None)
    for change in ({}, {"mechanics": "linear"}):
        k = fits | change
        model = SimpleNamespace(
            kernel=k["kernel"],
            backing=SimpleNamespace(rigid=k["rigid"]),
            params=SimpleNamespace(mechanics=k["mechanics"]),
        )
        assert pad_solver(model, SimpleNamespace(normal=k["normal"])) is pad_kernels()
    for change in (
        {"kernel": "numpy"},
        {"normal": np.zeros((2, 3))},
        {"rigid": False},
        {"mechanics": "elastica"},
    ):
        k = fits | change
        model = SimpleNamespace(
            kernel=k["kernel"],
            backing=SimpleNamespace(rigid=k["rigid"]),
            params=SimpleNamespace(mechanics=k["mechanics"]),
        )
        assert pad_solver(model, SimpleNamespace(normal=k["normal"])) is None, change
