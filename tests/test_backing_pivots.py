"""The strip's pivots, solved directly (:mod:`gecko_agents.backing.pivots`): internal forces
(momentum conserved), no work (a free chain keeps its energy), the gap closed, and the compiled
loop equal to the numpy/LAPACK path."""

import extras
import numpy as np
import pytest

from gecko_agents.backing.pivots import ChainPivots
from gecko_agents.backing.pivots_loop import compiled
from gecko_agents.backing.strip import Strip

ELL = 2.0  # µm


def _bent_free_chain(n=30, bend=0.03, spin=0.0, seed=3):
    """A free chain of ``n`` links along a random walk of link angles (rms turn ``bend``
    [rad] per joint, joints' rest angles 0), links moving at random velocities of rms
    ``spin`` [µm/µs, rad/µs]."""
    rng = np.random.default_rng(seed)
    s = Strip(0.0, ELL, n, 0.0, EI=1e3, rho_A=1.0, zeta=0.0)
    phi = np.cumsum(rng.normal(0.0, bend, n))
    ends = np.concatenate([[0j], np.cumsum(ELL * np.exp(1j * phi))])
    centres = 0.5 * (ends[:-1] + ends[1:])
    for body, z, a in zip(s.links, centres, phi, strict=True):
        body.position, body.angle = (z.real, z.imag), a
        body.velocity = tuple(rng.normal(0.0, spin, 2))
        body.angular_velocity = rng.normal(0.0, spin)
    s.rows = s.read()
    return s, 0.5 / s.omega_max


def test_free_chain_keeps_momentum_and_link_length():
    """No external force: the pivot forces are pairs (Newton's third law), so the total
    momentum stays what it is after the first step (which projects the random velocities onto
    the pivots); and the links' ends stay together while the chain rings and turns at up to
    ω·dt = 0.05 per step: node spacing ℓ to 1e-4, no drift (the gap after each step stays at
    the Newton solves' residual, ~1e-5·ℓ here, ~1e-10 µm in a slow pull)."""
    s, dt = _bent_free_chain(bend=0.1, spin=0.3)
    s.step(dt)
    p0 = s.m * s.rows[:, 3:5].sum(axis=0)
    gaps = []
    for _ in range(2000):
        s.step(dt)
        gaps.append(s.pivots.gap_next)
    assert np.allclose(s.m * s.rows[:, 3:5].sum(axis=0), p0, rtol=1e-9, atol=1e-9)
    x, y = s.nodes()
    assert np.allclose(np.hypot(np.diff(x), np.diff(y)), ELL, rtol=1e-4)
    assert max(gaps) < 1e-4 * ELL
    assert max(gaps[1000:]) < 2.0 * max(gaps[:1000])


def test_pivots_do_no_work_on_a_ringing_free_chain():
    """Released bent from rest, without damping, a free chain keeps bending + kinetic energy
    within 1 % over 2 500 steps at the zig-zag's ω·dt = 0.5 (the velocity-level solve alone,
    newton = 0, loses 32 % of it: the gap's curvature term left to the next step)."""
    s, dt = _bent_free_chain()
    s.step(dt)
    s.step(dt)
    energy = []
    for _ in range(2500):
        s.step(dt)
        energy.append(s.energy_bending + s.kinetic)
    energy = np.array(energy)
    assert np.ptp(energy) < 0.01 * energy[0]


@pytest.mark.skipif(compiled() is None, reason=extras.reason("fast"))
@pytest.mark.parametrize(
    "n, clamp", [pytest.param(300, False, marks=pytest.mark.slow), (7, True), (2, False), (1, True)]
)
def test_compiled_loop_equals_numpy_path(n, clamp):
    """The block-Thomas loop and LAPACK's banded Cholesky give the same forces (1e-10 of the
    largest) on a bent, moving chain, with and without the clamp."""
    rng = np.random.default_rng(1)
    phi = np.cumsum(rng.normal(0.0, 0.1, n))
    ends = np.concatenate([[0j], np.cumsum(ELL * np.exp(1j * phi))]) + (0.3 + 0.1j)
    c = 0.5 * (ends[:-1] + ends[1:])
    pos = (c.real + rng.normal(0.0, 1e-3, n), c.imag, phi)
    vel = tuple(rng.normal(0.0, 1.0, (3, n)))
    out = []
    for fast in (True, False):
        cp = ChainPivots(n, ELL, compiled=fast)
        if clamp:
            cp.clamp((0.3, 0.2))
        out.append((np.array(cp.forces(pos, vel, 1.3, 0.4, 0.01)), cp.gap_max, cp.gap_next))
    (f1, g1, n1), (f2, g2, n2) = out
    assert np.allclose(f1, f2, rtol=0.0, atol=1e-10 * np.abs(f2).max())
    assert g1 == pytest.approx(g2, rel=1e-12)
    assert n1 == pytest.approx(n2, rel=1e-3, abs=1e-12)
