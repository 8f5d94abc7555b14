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
    (Contact, "R", -1.0, "[0.001, 100000.0]"), (Contact, "E1", 0.0, "[1e-06, 10000000.0]"),
    (Contact, "nu1", 0.5, "[0.0, 0.5)"), (Contact, "nu2", -0.1, "[0.0, 0.5)"),
    (Contact, "gamma1", math.nan, "(0.0, 10.0]"), (Contact, "E2", math.inf, "[1e-06, 10000000.0]"),
    (Seta, "theta_deg", 90.5, "(0.0, 90.0]"), (Seta, "theta_deg", 0.0, "(0.0, 90.0]"),
    (Seta, "r", 0.0, "[0.001, 100000.0]"), (Array, "count", 0, "[1, 1000000000]"),
    (Array, "count", 2.5, "[1, 1000000000]"), (Floor, "sigma", -0.1, "[0.0, 10000.0]"),
    (Friction, "mu", -0.2, "[0.0, 10.0]"),
])  # fmt: skip
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


# Issue 18, defect 5: validation gaps -------------------------------------------------------


@pytest.mark.parametrize("group", ["contact", "seta", "array", "floor", "friction"])
def test_replace_refuses_a_group_replaced_by_a_non_group(group):
    with pytest.raises(ValueError, match=rf"SetaArray\.{group} = 5 must be a"):
        PAPER_TABLE1.replace(**{group: 5})


@pytest.mark.parametrize("value", [5.0, 1e12, math.inf, 2.5, True])
def test_array_count_is_an_integer_in_range(value):
    with pytest.raises(ValueError, match="Array.count"):
        PAPER_TABLE1.replace(**{"array.count": value})


def test_array_count_refuses_absurd_integers_and_accepts_numpy_integers():
    import numpy as np

    with pytest.raises(ValueError, match=r"Array.count = 1000000000000 is outside"):
        PAPER_TABLE1.replace(**{"array.count": 10**12})
    p = PAPER_TABLE1.replace(**{"array.count": np.int64(5)})
    assert p.array.count == 5 and type(p.array.count) is int  # stored as a Python int
    assert type(Floor(seed=np.uint32(7)).seed) is int


@pytest.mark.parametrize("key, value", [
    ("contact.E1", 1e-300), ("contact.E1", 1e300), ("contact.E2", 1e300), ("contact.R", 1e-9),
    ("seta.L", 1e9), ("seta.r", 1e-12), ("seta.density", 1e3), ("contact.gamma1", 1e3),
    ("contact.w", 1e6), ("friction.mu", 1e3), ("array.pitch", 1e-9), ("floor.sigma", 1e9),
])  # fmt: skip
def test_physically_absurd_values_are_refused(key, value):
    with pytest.raises(ValueError, match=key.split(".")[1]):
        PAPER_ARRAY.replace(**{key: value})


def test_presets_lie_inside_the_ranges():
    for p in (PAPER_TABLE1, PAPER_ARRAY, PAPER_FIG5_READING):
        assert SetaArray.from_dict(p.to_dict()) == p


# Issue 18, defect 4: seeds are never coerced -----------------------------------------------


def test_check_seed():
    import numpy as np

    from gecko_agents.params import check_seed

    assert (
        check_seed(0) == 0 and check_seed(np.int64(5)) == 5 and type(check_seed(np.int32(5))) is int
    )
    for bad in (3.7, 3.0, "5", "abc", True, -1, None, 2**63):
        with pytest.raises(ValueError, match=r"^seed = "):
            check_seed(bad)
