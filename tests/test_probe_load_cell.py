"""What a probe test's load cell reads (gecko_agents.studies.probe_test): the plate's vertical
force, the square field of pillars under the probe, and the refusal to scale a row under a probe
to an array."""

import warnings

import pytest

from gecko_agents import protocol
from gecko_agents.analysis.pull import plate_pull_off, pull_off
from gecko_agents.model import Model
from gecko_agents.physics import fibril_probe_halfspace as hs
from gecko_agents.physics import punch
from gecko_agents.studies import probe_test as pt


def _release_force(p):
    c = p.contact
    return float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))


def test_on_a_flat_floor_the_load_cell_reads_the_contacts_normal_forces():
    """Vertical pillars on a flat floor: every contact normal is vertical, so the plate's
    vertical force at pull-off is the sum of the normal forces (Kendall's F_r per pillar)."""
    p = pt.PILLARS.replace(**{"array.count": 3, "floor.kind": "gaussian"})
    h = Model(p, n_sim=3, seed=0).run(protocol.preload_pull(0.3, speed=pt.SPEED), progress=False)
    assert plate_pull_off(h) == pytest.approx(pull_off(h).adhesion, rel=2e-3)
    assert plate_pull_off(h) == pytest.approx(3 * _release_force(p), rel=0.01)


def test_under_a_probe_the_load_cell_reads_more_than_the_normal_forces():
    """R_p = 30 µm, 3 µN: the outer pillars sit on a 15° slope, stuck by friction; the plate
    weighs the vertical components of their normal and friction forces."""
    row, _ = pt.run_point("flat punch, rigid backing", 5, 30.0, 3.0)
    assert row["pull_off_uN"] > 1.005 * row["contact_pull_off_uN"]


def test_the_field_under_the_probe_is_the_square_lattice_of_independent_fibrils():
    p = pt.PILLARS.replace(**{"array.count": 11, "floor.probe_radius": 30.0})
    m = Model(p, n_sim=11, seed=0)
    F_r, k = _release_force(p), pt.fibril_stiffness(p)
    one = pt.closed_form(m, p, 0.1)  # only the apex pillar reached: F_r each
    assert one["row"] == pytest.approx(F_r) and one["field"] == pytest.approx(F_r)
    full = pt.closed_form(m, p, 1000.0)  # every pillar under the probe pressed
    continuum = float(hs.saturation_pull_off_continuum(30.0, 1.0 / p.array.pitch**2, k, F_r))
    assert 0.85 * continuum < full["field"] <= continuum  # a lattice does not pass the limit
    assert full["row"] < full["field"]


def test_a_row_under_a_probe_does_not_scale_to_the_array():
    p = pt.PILLARS.replace(**{"array.count": 5, "floor.probe_radius": 30.0})
    prot = protocol.preload_pull(0.1, speed=pt.SPEED)
    with pytest.warns(UserWarning, match="not a uniform patch"):
        Model(p, n_sim=3, seed=0).run(prot, progress=False)
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=".*uniform patch.*")
        Model(p, n_sim=5, seed=0).run(prot, progress=False)
