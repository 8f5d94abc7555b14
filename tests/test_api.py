"""The public API in one import: ``import gecko_agents as ga``."""

import subprocess
import sys

import pytest

import gecko_agents as ga


def test_importing_the_package_loads_neither_pymunk_nor_numba():
    code = (
        "import sys, gecko_agents as ga\n"
        "ga.PAPER_TABLE1.replace(mechanics='rod'); ga.protocol.press_pull(depth=1.0); ga.load\n"
        "print(sorted(m for m in ('pymunk', 'numba') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("name", [n for n in ga.__all__ if n != "__version__"])
def test_every_public_name_resolves_to_its_home(name):
    module, attribute = ga._LAZY[name]
    home = __import__(module, fromlist=["_"])
    assert getattr(ga, name) is (home if attribute is None else getattr(home, attribute))


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="Modell"):
        ga.Modell  # noqa: B018


def test_replace_takes_a_group_as_a_dict_the_same_as_dotted_names():
    nested = ga.PAPER_ARRAY.replace(floor={"sigma": 0.5, "seed": 3}, mechanics="rod")
    dotted = ga.PAPER_ARRAY.replace(**{"floor.sigma": 0.5, "floor.seed": 3, "mechanics": "rod"})
    assert nested == dotted
    assert (nested.floor.sigma, nested.floor.seed, nested.mechanics) == (0.5, 3, "rod")
    assert nested.contact == ga.PAPER_ARRAY.contact


def test_replace_refuses_an_unknown_field_inside_a_group_dict():
    with pytest.raises(ValueError, match="floor.sigmaa"):
        ga.PAPER_ARRAY.replace(floor={"sigmaa": 0.5})
