"""The layer backing (gecko_agents.backing.layer): the roots on an elastic layer bonded to the
holder, in the time-stepped engine."""

import warnings

import numpy as np
import pytest

from gecko_agents import history, protocol
from gecko_agents.backing import LayerBacking
from gecko_agents.backing.layer import ToeplitzSolver
from gecko_agents.model import Model
from gecko_agents.numerics import Numerics
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.params.backing import Backing
from gecko_agents.physics import layer

ROW = PAPER_ARRAY.replace(**{"array.count": 20, "seta.L": 5.0, "floor.sigma": 0.0})


def _run(params, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(params, seed=1, numerics=Numerics(**kw))
        h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
    return m, h


def _layer(**kw):
    return ROW.replace(**{"backing.kind": "layer"} | {f"backing.{k}": v for k, v in kw.items()})


def test_toeplitz_solver_is_the_dense_algebra():
    """T·x and T⁻¹·y by FFT and preconditioned CG equal the dense matrix's."""
    x = 4.0 * np.arange(300)
    C = layer.row_compliance(x, 160.0, 1.413, 0.3, 4.0, 4.0)
    T = ToeplitzSolver(C[:, 0])
    rng = np.random.default_rng(0)
    v = rng.normal(size=x.size)
    np.testing.assert_allclose(T(v), C @ v, rtol=1e-10, atol=1e-12 * np.abs(C @ v).max())
    A = np.eye(x.size) + 0.45 * C
    y = rng.normal(size=x.size)
    got = ToeplitzSolver(A[:, 0]).solve(y, np.zeros(x.size), rtol=1e-13)
    np.testing.assert_allclose(got, np.linalg.solve(A, y), rtol=1e-9, atol=1e-12)


def test_layer_kind_chooses_the_backing_and_its_step():
    m = Model(_layer())
    assert type(m.backing) is LayerBacking and m.integrator == "explicit"
    assert m.kernel == "numpy"
    np.testing.assert_allclose(
        m.backing.compliance,
        layer.row_compliance(m.world.root_dx, 50.0, 1.413, 0.3, ROW.array.pitch, ROW.array.pitch),
        rtol=1e-12,
    )
    with pytest.raises(ValueError, match="integrator = 'implicit'"):
        Model(_layer(), numerics=Numerics(integrator="implicit"))
    with pytest.raises(ValueError, match="kernel"):
        Model(_layer(), numerics=Numerics(kernel="numba"))
    with pytest.raises(ValueError, match="contact"):
        Model(_layer(), numerics=Numerics(contact="callback"))
    with pytest.raises(ValueError, match="leader_arm"):
        Model(_layer(drive="peel_end", leader_arm=5.0))


@pytest.mark.parametrize(("field", "value"), [("nu_b", -0.1), ("nu_b", 0.5), ("t_b", 0.0)])
def test_bad_layer_refused_naming_the_field(field, value):
    with pytest.raises(ValueError, match=f"Backing.{field} = "):
        Backing(kind="layer", **{field: value})
    with pytest.raises(ValueError, match="misalignment_deg"):
        Backing(kind="layer", misalignment_deg=0.5)


def test_stiff_layer_is_the_rigid_plate():
    """A thin, stiff layer carries the rigid plate's pull-off (0.1 %) and holds its roots
    within 1e-4 µm."""
    _, rigid = _run(ROW, integrator="explicit")
    m, stiff = _run(_layer(t_b=1.0, E_b=1e4), integrator="explicit")
    peak_r = -float(np.min(rigid["plate_force_y_uN"]))
    peak_l = -float(np.min(stiff["plate_force_y_uN"]))
    assert peak_l == pytest.approx(peak_r, rel=1e-3)
    assert float(np.max(stiff["layer_deflection_max_um"])) < 1e-4
    assert stiff.backing["layer_deflection_um"].shape == (len(stiff), m.n)


def test_thick_layer_loads_the_edge_thin_shares():
    """Kim & Sitti's mechanism: on a thick layer the outermost setae let go first and the
    pad carries less than on a thin one, which shares the load nearly equally (N·Fc). The
    energy balance (setae + contacts + the layer's ½P·w) closes within 1 %."""
    pulls = {}
    for t in (10.0, 1000.0):
        m, h = _run(_layer(t_b=t))
        pulls[t] = -float(np.min(h["plate_force_y_uN"])) / (m.n * m.Fc)
        assert history.energy_balance_error(h) < 0.01
        assert float(np.max(h["layer_energy_pJ"])) > 0.0
    assert pulls[10.0] == pytest.approx(1.0, abs=0.01)
    assert pulls[1000.0] < 0.9
    front = h["layer_front_x_um"]
    first = front[np.isfinite(front)]
    n_att = np.asarray(h["n_attached"])
    # The first setae to go are the outermost: the front stays at the edge until then.
    edge = float(np.abs(m.world.root_dx).max())
    assert abs(first[0]) == pytest.approx(edge)
    going = np.flatnonzero(np.diff(n_att) < 0)[0]
    assert abs(front[going + 1]) < edge


def test_rod_setae_on_a_layer():
    """The rod's nonlinear setae balance with the layer by Newton steps; the energy closes
    within the history invariant's tolerance (the rigid plate's rod run itself books 2 %)."""
    m, h = _run(_layer(t_b=200.0).replace(mechanics="rod"))
    assert history.energy_balance_error(h) < history.ENERGY_RTOL
    assert 0.5 < -float(np.min(h["plate_force_y_uN"])) / (m.n * m.Fc) < 1.0


@pytest.mark.parametrize("t", [10.0, pytest.param(1000.0, marks=pytest.mark.slow)])
def test_pillar_row_is_the_quasi_static_layer_model(t):
    """Flat-punch pillars on a layer, pressed to 12 µN and pulled at 0.04 µm/µs: the
    engine's pull-off is the event-driven quasi-static model's with the same layer
    compliance (each pillar a spring Ka + punch in series, letting go at Kendall's F_r)
    within 0.1 % (measured: 0.015–0.016 %, the largest tensile force over every step;
    0.005–0.009 % at 0.02 µm/µs)."""
    from gecko_agents.physics import fibril_probe_halfspace as halfspace
    from gecko_agents.physics import punch
    from gecko_agents.studies.probe_test import PILLARS, fibril_stiffness

    n = 12
    p = PILLARS.replace(**{"floor.kind": "gaussian", "array.count": n,
                           "backing.kind": "layer", "backing.t_b": t})  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, seed=0)
        h = m.run(protocol.preload_pull(12.0, speed=0.04), progress=False)
    c, pitch = p.contact, p.array.pitch
    F_r = float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))
    C = layer.row_compliance(m.world.root_dx, t, p.backing.E_b, p.backing.nu_b, pitch, pitch)
    quasi = halfspace.probe_test(np.zeros(n), C + np.eye(n) / fibril_stiffness(p), F_r, 12.0)
    assert h.peak_pull_off == pytest.approx(quasi.pull_off, rel=1e-3)
    assert quasi.pull_off < n * F_r  # the layer shares the load unequally
