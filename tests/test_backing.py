"""The elastic backing: the strip against Euler–Bernoulli, the stiff limit against the rigid
plate, and the parameter checks."""

import math
import warnings

import numpy as np
import pytest

from gecko_agents import history, protocol
from gecko_agents.backing.elastic import ElasticBacking, Strip
from gecko_agents.backing.rigid import RigidBacking
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY, Backing

EI, LENGTH, N_LINKS, RHO_A = 1e4, 100.0, 10, 1.0  # µN·µm², µm, -, ng/µm
STUBBY = PAPER_ARRAY.replace(**{"array.count": 20, "seta.L": 5.0, "floor.sigma": 0.3})


def _cantilever(zeta):
    s = Strip(0.0, LENGTH / N_LINKS, N_LINKS, 0.0, EI, RHO_A, zeta=zeta)
    s.clamp_left()
    return s, 0.5 / s.omega_max


def _end_point_y(s):
    return s.nodes()[1][-1]


def _step_with_end_load(s, dt, P):
    """One step with a downward load P [µN] at the free end (force + torque on the last link)."""
    d = s.rows
    n = s.n
    fy, tq = np.zeros(n), np.zeros(n)
    fy[-1] = -P
    tq[-1] = -P * 0.5 * s.ell * math.cos(d[-1, 2] + d[-1, 5] * dt)
    s.step(dt, 0.0, fy, tq)


@pytest.mark.slow
def test_cantilever_end_deflection_euler_bernoulli():
    """δ = P·L³/(3EI) (Timoshenko & Gere 1972 §7.3) within 1 % once the strip has settled: the
    10-link chain's discretisation error, O(1/N²), measured +0.45 %."""
    s, dt = _cantilever(zeta=0.3)
    s.space.damping = 0.9  # settle to the static shape
    P = 0.01
    for _ in range(8000):
        _step_with_end_load(s, dt, P)
    exact = -P * LENGTH**3 / (3 * EI)
    assert _end_point_y(s) == pytest.approx(exact, rel=0.01)


def test_cantilever_first_frequency():
    """f₁ = 1.875²·√(EI/ρA)/(2πL²) (Euler–Bernoulli cantilever) within 1.5 %: release the
    statically loaded strip without damping and time its zero crossings. The 10 lumped links
    lower f₁ by O(1/N²) (measured −0.84 %); timing two periods adds at most dt/T (0.04 %)."""
    s, dt = _cantilever(zeta=0.3)
    s.space.damping = 0.9
    for _ in range(8000):
        _step_with_end_load(s, dt, 0.01)
    s.space.damping = 1.0
    s.c_rot = 0.0
    f1 = 1.875**2 * math.sqrt(EI / RHO_A) / (2 * math.pi * LENGTH**2)
    ys = []
    for _ in range(int(2.5 / f1 / dt)):
        _step_with_end_load(s, dt, 0.0)
        ys.append(_end_point_y(s))
    ys = np.array(ys)
    up = np.flatnonzero((ys[:-1] < 0) & (ys[1:] >= 0))
    assert up.size >= 2
    period = (up[-1] - up[0]) * dt / (up.size - 1)
    assert 1.0 / period == pytest.approx(f1, rel=0.015)


def test_strip_books_its_energy():
    """A released cantilever rings down: bending + kinetic energy + the joint dampers'
    dissipation stay equal to the energy it was released with (within 1e-4), and without
    damping bending + kinetic energy is conserved."""
    for zeta in (0.0, 0.3):
        s, dt = _cantilever(zeta=0.3)
        s.space.damping = 0.9
        for _ in range(4000):
            _step_with_end_load(s, dt, 0.01)
        s.space.damping = 1.0
        s.c_rot *= zeta / 0.3
        _step_with_end_load(s, dt, 0.0)
        start = s.energy_bending + s.kinetic
        dissipated, totals = 0.0, []
        for _ in range(3000):
            _step_with_end_load(s, dt, 0.0)
            dissipated += s.dissipated
            totals.append(s.energy_bending + s.kinetic + dissipated)
        assert np.allclose(totals, start, rtol=1e-4, atol=0.0)
        assert (dissipated > 0.05 * start) == (zeta > 0)


def _peak_pull(params):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(params, seed=1)
        h = m.run(protocol.press_pull(0.5, speed=0.02), progress=False)
    return m, h


@pytest.mark.slow
def test_stiff_elastic_backing_matches_rigid_plate():
    """A very stiff strip on a stiff handle carries the rigid plate's peak pull-off (1 %)."""
    _, rigid = _peak_pull(STUBBY)
    m, soft = _peak_pull(STUBBY.replace(**{"backing.kind": "elastic", "backing.E_b": 20.0}))
    assert isinstance(m.backing, ElasticBacking)
    peak_r = -float(np.min(rigid["plate_force_y_uN"]))
    peak_e = -float(np.min(soft["plate_force_y_uN"]))
    assert peak_e == pytest.approx(peak_r, rel=0.01)
    assert soft.backing["strip_node_x_um"].shape[0] == len(soft["strip_front_x_um"]) == len(soft)
    assert len(soft) > 10
    # The strip's and the handle's energies are booked: plate work = elastic + kinetic +
    # dissipated holds to 2 % (conftest checks it on every history too).
    assert soft.meta["energy_complete"] is True
    assert history.energy_balance_error(soft) < 0.02


@pytest.mark.parametrize(
    "field, value",
    [("t_b", 0.0), ("t_b", -1.0), ("E_b", 0.0), ("E_b", -2.0), ("kind", "foam"),
     ("drive", "twist"), ("spacing", -1.0)],
)  # fmt: skip
def test_bad_backing_values_refused_naming_the_field(field, value):
    with pytest.raises(ValueError, match=f"Backing.{field}"):
        Backing(**{field: value})


def test_chain_too_coarse_refused():
    p = STUBBY.replace(**{"backing.kind": "elastic", "backing.spacing": 40.0})
    with pytest.raises(ValueError, match="Backing.spacing"):
        Model(p)


def test_chain_of_1000_links_pulls_off_at_equal_load_sharing():
    """A strip of 1 000 links (500 stubby setae, 2 µm links) pressed and pulled uniformly off
    a flat floor carries N·Fc (equal load sharing: every seta lets go at Fc) within 1 %, with
    the energy balance closed to 1 % and the pivots holding (gap < 1e-6 µm). pymunk's
    iterative pivots failed this beyond 225 links (251: 0.79 N·Fc, balance off by 88 %)."""
    p = STUBBY.replace(**{"array.count": 500, "floor.sigma": 0.0, "backing.kind": "elastic",
                          "backing.spacing": 2.0})  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, seed=1)
        strip = m.backing.strip
        gaps = []
        step = strip.step

        def recorded(*args):
            new = step(*args)
            gaps.append(strip.pivots.gap_next)
            return new

        strip.step = recorded
        h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
    assert strip.n == 1000
    assert max(h["strip_setae_force_y_uN"]) == pytest.approx(m.n * m.Fc, rel=0.01)
    assert -float(np.min(h["plate_force_y_uN"])) == pytest.approx(m.n * m.Fc, rel=0.01)
    assert history.energy_balance_error(h) < 0.01
    assert max(gaps) < 1e-6


def test_backing_kind_chooses_the_backing():
    """``params.backing.kind`` chooses the model's backing component; the elastic strip's
    options are its parameters, which the rigid plate refuses."""
    assert type(Model(STUBBY).backing) is RigidBacking
    elastic = STUBBY.replace(**{"backing.kind": "elastic"})
    m = Model(elastic)
    assert type(m) is Model and type(m.backing) is ElasticBacking
    assert m.kernel == "numpy"
    with pytest.raises(ValueError, match="kernel"):
        Model(elastic, numerics=Numerics(kernel="python"))
    with pytest.raises(ValueError, match="contact"):
        Model(elastic, numerics=Numerics(contact="callback"))
    with pytest.raises(ValueError, match="leader_arm = 10.0 µm needs kind = 'elastic'"):
        STUBBY.replace(backing={"leader_arm": 10.0})


@pytest.mark.slow
def test_peel_detachment_front_starts_at_the_pulled_edge_and_moves():
    """A soft strip pulled at its +x end lets go edge first: the front (outermost attached
    seta) starts at the pulled edge and runs across the pad, and the pad carries far less than
    the equal-load-sharing N·Fc (Hui et al. 2004; Bacca et al. 2016)."""
    p = PAPER_ARRAY.replace(
        **{"array.count": 12, "seta.L": 5.0, "floor.sigma": 0.0, "backing.kind": "elastic",
           "backing.E_b": 1.413, "backing.drive": "peel_end"}
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, seed=1)
        h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
    b = h.meta["backing"]
    front = h["strip_front_x_um"]
    front = front[np.isfinite(front)]
    edge = float(m.world.root_dx.max())
    assert front[0] == pytest.approx(edge)
    assert front[-1] < edge - 0.5 * (edge - m.world.root_dx.min())
    assert np.all(np.diff(front) <= 0.0)
    pull_off = max(h["strip_setae_force_y_uN"])
    assert 0.0 < pull_off < 0.5 * m.n * m.Fc
    # The strip's nodes, per record, in the floor's frame: straight and level at the start,
    # and the pulled end hangs from the handle by the handle spring's stretch F/k_h.
    nx, ny = h.backing["strip_node_x_um"], h.backing["strip_node_y_um"]
    assert nx.shape == ny.shape == (len(h), b["n_links"] + 1)
    half = 0.5 * b["length_um"]
    assert np.allclose(nx[0], np.linspace(-half, half, b["n_links"] + 1), atol=1e-3)
    # The handle's force is the plate's: the strip's end hangs below the handle by F/k_h.
    hang = h["plate_y_um"] + h["plate_force_y_uN"] / p.backing.handle_stiffness
    assert np.allclose(ny[:, -1], hang, atol=0.02)
    assert ny[-1, -1] - ny[0, -1] > 1.0  # the end was lifted


@pytest.mark.slow
def test_peel_pull_off_falls_as_the_backing_softens():
    """Aligned and pulled at its +x end (8 setae, β = (λ/L_pad)⁴ from 31 down to 0.03):
    pull-off/(N·Fc) falls as the strip softens (load concentrates at the pulled edge; Hui et
    al. 2004), stays below the rigid plate's equal load sharing, and every front starts at the
    pulled edge and moves across the pad."""
    ratios = []
    for E_b in (20.0, 0.2, 0.02):
        p = PAPER_ARRAY.replace(
            **{"array.count": 8, "seta.L": 5.0, "floor.sigma": 0.0, "backing.kind": "elastic",
               "backing.E_b": E_b, "backing.drive": "peel_end",
               "backing.handle_stiffness": 50.0}
        )  # fmt: skip
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = Model(p, seed=1)
            h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
        front = h["strip_front_x_um"]
        front = front[np.isfinite(front)]
        assert front[0] == pytest.approx(m.world.root_dx.max())
        assert front[-1] < front[0]
        ratios.append(max(h["strip_setae_force_y_uN"]) / (m.n * m.Fc))
    assert ratios[0] > ratios[1] > ratios[2] > 0.0
    assert ratios[0] < 0.5
