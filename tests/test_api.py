"""The public API in one import: ``import gecko_agents as ga``."""

import subprocess
import sys

import numpy as np
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


# Numerics: how a run is computed, in one object; the older keyword spellings still work.
P5 = ga.PAPER_TABLE1.replace(mechanics="rod", seta={"L": 5.0})


def _pull(**kw):
    return ga.Model(P5, seed=1, **kw).run(ga.protocol.press_pull(0.5, 0.05), progress=False)


def test_the_older_keywords_warn_and_give_the_same_history_as_numerics():
    new = _pull(numerics=ga.Numerics(integrator="implicit", record_every=7))
    with pytest.warns(DeprecationWarning, match=r"numerics=Numerics\(integrator=…, record_every"):
        old = _pull(integrator="implicit", record_every=7)
    for column in new.columns:
        np.testing.assert_array_equal(old[column], new[column])
    assert old.meta["numerics"] == new.meta["numerics"]
    assert new.meta["numerics"]["record_every"] == 7


def test_the_backing_options_are_parameters_recorded_with_the_run():
    p = P5.replace(backing={"kind": "elastic", "drive": "peel_end"}, array={"count": 4})
    with pytest.warns(DeprecationWarning, match="backing="):
        m = ga.Model(p, leader_arm=5.0, peel_angle_deg=45.0)
    assert (m.params.backing.leader_arm, m.params.backing.peel_angle_deg) == (5.0, 45.0)
    assert m.backing.leader_arm == 5.0
    with pytest.raises(ValueError, match="leader_arm = 5.0 µm needs Backing.drive"):
        P5.replace(backing={"kind": "elastic", "leader_arm": 5.0})
    with pytest.raises(ValueError, match="peel_angle_deg = 180.0"):
        P5.replace(backing={"peel_angle_deg": 180.0})


def test_unknown_or_doubled_model_options_are_refused_by_name():
    with pytest.raises(TypeError, match="speed"):
        ga.Model(P5, speed=1.0)
    with pytest.raises(TypeError, match=r"\['dt'\] inside numerics"):
        ga.Model(P5, numerics=ga.Numerics(), dt=0.1)
    with pytest.raises(TypeError, match="numerics must be a Numerics"):
        ga.Model(P5, numerics={"dt": 0.1})


def test_from_options_takes_every_kind_of_option_without_a_warning(recwarn):
    m = ga.Model.from_options(P5, n_sim=1, seed=2, dt=0.05, integrator="explicit")
    assert (m.numerics.dt, m.numerics.integrator, m.seed) == (0.05, "explicit", 2)
    assert not [w for w in recwarn if issubclass(w.category, DeprecationWarning)]


def test_dir_lists_the_public_api_only():
    import gecko_agents as ga

    assert dir(ga) == sorted(ga.__all__)
    assert not {"import_module", "version", "PackageNotFoundError"} & set(dir(ga))


def test_load_run_is_read_run_file_with_a_deprecation():
    """``ga.load_run`` reads a run file, not a saved run (``ga.load``): it is
    ``ga.read_run_file`` now, the older name served with a warning naming the new one."""
    import gecko_agents as ga

    with pytest.warns(DeprecationWarning, match="gecko_agents.read_run_file"):
        older = ga.load_run
    assert older is ga.read_run_file
