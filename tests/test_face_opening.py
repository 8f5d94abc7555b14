"""Buckling-induced detachment (``contact.edge_opening``): the face's detachment overlap moves
with the moment its pillar puts on it (the tilted-punch criterion), faces opened that way do
not bond again until their tip has left the floor, and in the model a round-edged punch pressed
past buckling loses its adhesion while a mushroom whose rim is not singular keeps it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.contact import FlatPunch
from gecko_agents.history import invariant_violations
from gecko_agents.model import Model, Numerics
from gecko_agents.model.face_opening import FaceOpening
from gecko_agents.params import PAPER_ARRAY, Contact
from gecko_agents.physics import punch

R = 15.0  # µm: big enough that a buckled pillar's face moment reaches the edge's toughness
PILLAR = PAPER_ARRAY.replace(
    **{"seta.theta_deg": 90.0, "mechanics": "elastica", "seta.r": R, "contact.R": R,
       "seta.L": 10 * R, "array.count": 1, "array.pitch": 40.0, "floor.sigma": 0.0,
       "friction.mu": 0.5, "spatula.b": 2 * R, "tip": "flat_punch"}
)  # fmt: skip


def test_detachment_overlap_is_the_tilted_punch_criterion():
    law = FlatPunch(Contact(R=2.0, edge_opening=True))
    a, w, E = 2.0, law.w, law.E_star
    op = FaceOpening(law, 4)
    F_K = punch.kendall_pull_off(a, w, E)
    M = np.array([0.0, 0.1, a * F_K / 3, 2 * a * F_K / 3])
    op.update(M)
    # P = 2E*aδ at the edge's Griffith point: P = −(F_K − 3|M|/a) (punch.tilted_pull_off)
    P = 2 * E * a * op.detach_at
    assert op.detach_at[0] == law.detach_overlap  # no moment: Kendall's, exactly
    assert P[1] == pytest.approx(-punch.tilted_pull_off(a, w, E, 0.1), rel=1e-12)
    assert op.detach_at[2] == pytest.approx(0.0, abs=1e-15)  # opens as soon as it is not pressed
    assert P[3] == pytest.approx(F_K, rel=1e-12)  # opens while pressed by F_K
    op.update(-M)  # the sign of the moment does not matter
    assert 2 * E * a * op.detach_at[3] == pytest.approx(F_K, rel=1e-12)


def test_an_opened_face_carries_compression_only_and_lets_go_at_zero_overlap():
    law = FlatPunch(Contact(R=2.0, edge_opening=True))
    op = FaceOpening(law, 2)
    op.update(np.array([2 * law.a * law.pull_off_force / 3, 0.0]))  # face 0: opens below F_K
    idx, yes = np.arange(2), np.ones(2, bool)
    gone = op.screen(idx, np.array([0.05, 0.05]), yes)  # pressed: face 0 opens, stays on
    assert gone.tolist() == [False, False] and op.opened.tolist() == [True, False]
    assert op.count == 1
    op.update(np.zeros(2))  # the moment gone: an opened face stays open
    gone = op.screen(idx, np.array([1e-9, law.detach_overlap / 2]), yes)
    assert gone.tolist() == [False, False] and op.opened.tolist() == [True, False]
    gone = op.screen(idx, np.array([-1e-9, law.detach_overlap / 2]), yes)  # no tension held
    assert gone.tolist() == [True, False] and op.opened.tolist() == [False, False]
    gone = op.screen(idx, np.array([0.1, 1.01 * law.detach_overlap]), yes)  # bonded: Kendall's
    assert gone.tolist() == [False, True]


def _run(params, eps):
    """Pressed eps·L and pulled off. Half the default step: a 147 µN punch letting go at its
    full pull-off leaves the O(F²dt²/m) error of the release step's record (FlatPunch's
    energy tolerance) at 4–5 % of the run's energy with the default, above the 4 % allowed."""
    dt = 0.5 * Model(params, n_sim=1, seed=0).dt
    m = Model(params, n_sim=1, seed=0, numerics=Numerics(dt=dt))
    h = m.run(protocol.press_pull(eps * params.seta.L, speed=0.01), progress=False)
    return m, h


@pytest.mark.slow
def test_round_edged_punch_loses_its_adhesion_after_buckling_and_a_mushroom_keeps_it():
    """A 15 µm punch pillar (L/2r = 5) pressed 20 % of its length, past buckling: its face's
    edge reaches K/K_c = 1.16 by the tilted-punch criterion, opens while pressed and does not
    bond again, so nothing is left to pull; pressed 1 % it keeps Kendall's pull-off; without
    the rule it keeps it after buckling too. A mushroom with a sharp 45° rim (no edge mode)
    keeps its whole pull-off after the same press. The energy balances in each run."""
    opening = PILLAR.replace(**{"contact.edge_opening": True})
    m, h = _run(opening, 0.2)
    assert m.physics.opening.count == 1
    assert h.peak_pull_off < 1e-3 * m.law.pull_off_force
    assert abs(h.detachments["force_uN"][0]) < 1e-3 * m.law.pull_off_force  # at δ = 0
    assert not invariant_violations(h)
    assert _run(opening, 0.01)[1].peak_pull_off == pytest.approx(m.law.pull_off_force, rel=0.01)
    assert _run(PILLAR, 0.2)[1].peak_pull_off == pytest.approx(m.law.pull_off_force, rel=0.01)
    mush = opening.replace(
        **{"tip": "mushroom", "contact.R": 1.2 * R, "contact.sigma0": 1.0,
           "mushroom.rim": "sharp", "mushroom.rim_angle_deg": 45.0}
    )  # fmt: skip
    mm, hm = _run(mush, 0.2)
    assert hm.peak_pull_off == pytest.approx(mm.law.pull_off_force, rel=0.01)
    assert mm.physics.opening.count == 0 and math.isinf(mm.law.edge_force)


def test_edge_opening_is_refused_where_there_is_no_bonded_face_on_an_elastica():
    with pytest.raises(ValueError, match="Contact.edge_opening = True needs a flat face"):
        PILLAR.replace(**{"contact.edge_opening": True, "tip": "sphere"})
    with pytest.raises(ValueError, match="mechanics = 'rod'"):
        PILLAR.replace(**{"contact.edge_opening": True, "mechanics": "rod"})
    with pytest.raises(ValueError, match="Contact.edge_opening = 1 must be True or False"):
        Contact(edge_opening=1)
