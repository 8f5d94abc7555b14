"""Parameter validation and presets."""

import math

import pytest
from numpy.testing import assert_allclose

from gecko_agents.params import (
    PAPER_ARRAY,
    PAPER_FIG5_READING,
    PAPER_TABLE1,
    Array,
    Contact,
    Floor,
    Friction,
    Seta,
    SetaArray,
)


@pytest.mark.parametrize("cls, field, value, allowed", [
    (Contact, "R", -1.0, "(0.0, inf)"), (Contact, "E1", 0.0, "(0.0, inf)"),
    (Contact, "nu1", 0.5, "[0.0, 0.5)"), (Contact, "nu2", -0.1, "[0.0, 0.5)"),
    (Contact, "gamma1", math.nan, "(0.0, inf)"), (Contact, "E2", math.inf, "(0.0, inf)"),
    (Seta, "theta_deg", 90.0, "(0.0, 90.0)"), (Seta, "theta_deg", 0.0, "(0.0, 90.0)"),
    (Seta, "r", 0.0, "(0.0, inf)"), (Array, "count", 0, "[1, inf)"),
    (Array, "count", 2.5, "[1, inf)"), (Floor, "sigma", -0.1, "[0.0, inf)"),
    (Friction, "mu", -0.2, "[0.0, inf)"),
])
def test_bad_values_name_field_value_and_range(cls, field, value, allowed):
    with pytest.raises(ValueError) as err:
        cls(**{field: value})
    msg = str(err.value)
    assert f"{cls.__name__}.{field}" in msg and repr(value) in msg and allowed in msg


def test_bad_choices():
    with pytest.raises(ValueError, match="law"):
        Friction(law="sticky")
    with pytest.raises(ValueError, match="mechanics"):
        SetaArray(mechanics="spring")
    with pytest.raises(ValueError, match="unknown parameter"):
        PAPER_ARRAY.replace(**{"floor.roughness": 1.0})


def test_presets_and_derived_values():
    assert PAPER_TABLE1.seta.theta_deg == 30 and PAPER_ARRAY.seta.theta_deg == 60
    assert PAPER_ARRAY.array.count == 10_000_000
    assert_allclose(PAPER_TABLE1.contact.work_of_adhesion, 0.1649, rtol=1e-3)
    assert_allclose(PAPER_FIG5_READING.contact.pull_off_force, 1.508, rtol=1e-3)
    assert_allclose(PAPER_FIG5_READING.contact.E_star, 1.553, rtol=1e-3)


def test_replace_and_dict_round_trip():
    p = PAPER_ARRAY.replace(**{"floor.sigma": 0.5, "mechanics": "rod"})
    assert p.floor.sigma == 0.5 and p.mechanics == "rod" and p.contact == PAPER_ARRAY.contact
    assert SetaArray.from_dict(p.to_dict()) == p
    with pytest.raises(ValueError, match="sigma"):
        PAPER_ARRAY.replace(**{"floor.sigma": -1})
