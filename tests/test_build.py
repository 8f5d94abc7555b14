"""The build step (gecko_agents.model.build): every choice from a registry, checked once; a
refusal names both choices that do not go together; the setup is what the model runs."""

import dataclasses
import itertools
import warnings

import pytest

from gecko_agents.backing import BACKINGS
from gecko_agents.model import Model, Numerics
from gecko_agents.model.build import MECHANICS, build
from gecko_agents.params import PAPER_ARRAY

ROW = PAPER_ARRAY.replace(**{"array.count": 3, "seta.L": 5.0})


def test_the_setup_is_frozen_and_is_what_the_model_runs():
    setup = build(ROW)
    with pytest.raises(dataclasses.FrozenInstanceError):
        setup.dt = 1.0
    m = Model(ROW)
    assert (m.setup.integrator, m.setup.kernel, m.setup.dt) == (m.integrator, m.kernel, m.dt)
    assert m.setup.seta.mass == m.mass and m.setup.seta.omega_max == m.omega_max


@pytest.mark.parametrize(
    "floor",
    [{"correlation_length": 0.0}, {"correlation_length": 2.0},
     {"kind": "probe", "probe_radius": 200.0, "sigma": 0.0}],
    ids=["pads", "continuous", "probe"],
)  # fmt: skip
def test_the_build_step_knows_the_floor_the_world_builds(floor):
    p = ROW.replace(floor=floor)
    assert build(p).pads == Model(p).world.pads


@pytest.mark.parametrize(
    "mechanics, kind, integrator",
    list(itertools.product(MECHANICS, BACKINGS, ("explicit", "implicit"))),
)
def test_every_combination_builds_or_is_refused_naming_both(mechanics, kind, integrator):
    """A combination the engine runs gives a model; one it does not is refused before any body
    is built, the message naming the integrator or mechanics and the backing or mechanics
    that rules it out."""
    p = ROW.replace(**{"mechanics": mechanics, "backing.kind": kind})
    backing, mech = BACKINGS[kind], MECHANICS[mechanics]
    runs = mechanics in backing.mechanics and (
        integrator == "explicit" or (mech.jacobian and backing.implicit)
    )
    if runs:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert Model(p, n_sim=2, numerics=Numerics(integrator=integrator)).integrator == (
                integrator
            )
        return
    with pytest.raises(ValueError) as err:
        build(p, Numerics(integrator=integrator))
    named = [
        f"integrator = {integrator!r}",
        f"mechanics = {mechanics!r}",
        f"backing.kind = {kind!r}",
    ]
    assert sum(name in str(err.value) for name in named) >= 2, str(err.value)
