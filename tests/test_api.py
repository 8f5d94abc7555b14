"""The public API in one import: ``import gecko_agents as ga``."""

import pkgutil
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import gecko_agents as ga


def test_importing_the_package_loads_neither_pymunk_nor_numba():
    code = (
        "import sys, gecko_agents as ga\n"
        "ga.PAPER_TABLE1.replace(mechanics='rod'); ga.protocol.press_pull(depth=1.0)\n"
        "ga.load_history\n"
        "print(sorted(m for m in ('pymunk', 'numba') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("name", [n for n in ga.__all__ if n != "__version__"])
def test_every_public_name_resolves_to_its_home(name):
    module, attribute = ga._LAZY[name]
    home = __import__(module, fromlist=["_"])
    assert getattr(ga, name) is (home if attribute is None else getattr(home, attribute))


def test_dir_shows_the_public_names_and_no_helper_of_the_loader():
    public = [n for n in dir(ga) if not n.startswith("__")]
    assert public == sorted(n for n in ga.__all__ if n != "__version__")
    assert "__version__" in dir(ga)
    for leaked in ("import_module", "version", "PackageNotFoundError", "load", "load_run"):
        assert leaked not in dir(ga)


@pytest.mark.parametrize(
    "old, new, home",
    [
        ("load", "load_history", "gecko_agents.history"),
        ("load_run", "read_run_file", "gecko_agents.runfiles.run"),
    ],
)
def test_an_old_name_warns_with_its_new_name_and_is_the_same_function(old, new, home):
    with pytest.warns(DeprecationWarning, match=rf"gecko_agents\.{old} .* 0\.3: .*\.{new}"):
        function = getattr(ga, old)
    assert function is getattr(ga, new)
    module = __import__(home, fromlist=["_"])
    with pytest.warns(DeprecationWarning, match=rf"{home}\.{old} .* 0\.3: .*\.{new}"):
        with pytest.raises((FileNotFoundError, ValueError), match="no/such/run"):
            getattr(module, old)("no/such/run")


def test_the_old_names_read_what_the_new_ones_read(tmp_path):
    from test_history import _toy

    from gecko_agents.history import load as old_load
    from gecko_agents.runfiles.run import load_run as old_load_run

    run_dir = _toy().save(tmp_path / "run")
    with pytest.warns(DeprecationWarning, match="load_history"):
        old = old_load(run_dir)
    assert old.run_id() == ga.load_history(run_dir).run_id()
    path = Path(__file__).resolve().parents[1] / "examples" / "preload_pull.toml"
    with pytest.warns(DeprecationWarning, match="read_run_file"):
        spec = old_load_run(path, quick=True)
    assert spec == ga.read_run_file(path, quick=True)


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


def _api_reference_modules():
    """(public, internal) module lists of docs/api.rst's autosummaries, split at its line."""
    text = (Path(__file__).resolve().parents[1] / "docs" / "api.rst").read_text("utf-8")
    public, internal = text.split("\n----\n")
    modules = re.compile(r"^   (gecko_agents[\w.]*)$", re.M)
    return public, modules.findall(public), modules.findall(internal)


def test_the_api_reference_lists_every_module_once_as_public_or_internal():
    package = Path(ga.__file__).parent
    top_level = {
        f"gecko_agents.{m.name}"
        for m in pkgutil.iter_modules([str(package)])
        if not m.name.startswith("_")
    }
    public_text, public, internal = _api_reference_modules()
    assert not set(public) & set(internal)
    applications = {"gecko_agents.studies"}  # command lines with reports, named in the text
    assert sorted(public + internal) == sorted(top_level - applications)
    assert all(f"``{name}``" in public_text for name in applications)
    for name in (n for n in ga.__all__ if n != "__version__"):
        assert f"``ga.{name}``" in public_text, f"ga.{name} is not in the public API's table"
        module, attribute = ga._LAZY[name]
        if attribute is None:
            assert module in public, f"{module} (ga.{name}) is listed as internal"


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
