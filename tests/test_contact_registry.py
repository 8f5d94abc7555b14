"""The law a parameter set selects (:func:`gecko_agents.contact.contact_law`) and what the
history invariants may assume of it (:func:`gecko_agents.contact.registry.bounds`)."""

import math

import pytest

from gecko_agents import contact
from gecko_agents.contact.registry import bounds
from gecko_agents.params import PAPER_TABLE1

SPHERE = PAPER_TABLE1.replace(tip="sphere")


@pytest.mark.parametrize(
    ("changes", "law_class"),
    [
        ({}, contact.JKRSphere),
        ({"tip": "hertz"}, contact.HertzSphere),
        ({"tip": "flat_punch"}, contact.FlatPunch),
        ({"tip": "mushroom"}, contact.MushroomTip),
        ({"tip": "spatula"}, contact.SpatulaTip),
        ({"tip": "spatulae"}, contact.SpatulaeTip),
        ({"contact.crack_speed": 0.5}, contact.RateJKRSphere),
        ({"contact.shear_coupling": "savkoor_briggs"}, contact.ShearedJKRSphere),
    ],
)
def test_each_tip_selects_its_law(changes, law_class):
    """A sphere takes crack kinetics only with a finite crack speed and the shear coupling only
    when asked; every other tip its own law, with its parameter groups."""
    law = contact.contact_law(SPHERE.replace(**changes))
    assert type(law) is law_class
    c = SPHERE.replace(**changes).contact
    assert law.R == pytest.approx(c.R, rel=1e-15)


@pytest.mark.parametrize(
    ("changes", "tension"),
    [
        ({}, "Fc"),
        ({"tip": "flat_punch"}, "Fc"),
        ({"contact.crack_speed": 0.5}, "inf"),
        ({"tip": "spatula"}, "inf"),
    ],
)
def test_the_bounds_the_invariants_assume(changes, tension):
    """An elastic tip holds at most its pull-off force; a tip with crack kinetics (its crack
    lags) or a film (many w·b at a small peel angle) has no such bound; the overlap below which
    no tip stays attached and the energy tolerance are the law's."""
    law = contact.contact_law(SPHERE.replace(**changes))
    b = bounds(law)
    expected = law.pull_off_force if tension == "Fc" else math.inf
    assert b["max_tension_uN"] == expected
    assert b["detach_overlap_um"] == law.detach_overlap
    assert b["rate_dependent"] is (changes.get("contact.crack_speed") is not None)
    assert b["energy_tolerance_factor"] == law.energy_tolerance_factor
