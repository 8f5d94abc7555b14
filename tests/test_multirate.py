"""Multirate stepping (gecko_agents.model.multirate): only the setae near an event take the
implicit step's short steps. Oracles: with every seta near it is the whole array's located
step; a seta stepped alone keeps its own history whatever its neighbours do; the energy
books close; where setae are coupled it does not apply."""

import warnings

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.history import ENERGY_RTOL, energy_balance_error
from gecko_agents.model import Model, Numerics
from gecko_agents.model import implicit as implicit_module
from gecko_agents.model import multirate as multirate_module
from gecko_agents.params import PAPER_ARRAY

ROUGH = {"floor.sigma": 0.5, "mechanics": "rod"}


def _run(overrides, n, proto, **numerics):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(PAPER_ARRAY.replace(**overrides), n_sim=n, seed=1, numerics=Numerics(**numerics))
        return m, m.run(proto, progress=False)


def _force_near(monkeypatch, choose):
    """Make every located step's near setae ``choose(near)`` and always multirate."""
    substeps = implicit_module.ImplicitStep.substeps

    def forced(self, vp):
        k = substeps(self, vp)
        if self.near is not None:
            self.near = choose(self.near)
        return k

    monkeypatch.setattr(implicit_module.ImplicitStep, "substeps", forced)
    monkeypatch.setattr(multirate_module.Multirate, "near", lambda self, near, k: near)


@pytest.mark.parametrize(
    "overrides, proto",
    [
        (ROUGH, protocol.press_pull(1.0)),
        pytest.param(  # the linear seta
            {"floor.sigma": 0.5}, protocol.press_pull(1.0), marks=pytest.mark.slow
        ),
        pytest.param(
            {"floor.sigma": 0.3, "mechanics": "rod", "tip": "spatula"},
            protocol.drag_pull(1.0, 0.5, 90.0),
            marks=pytest.mark.slow,
        ),
    ],
    ids=["rod", "linear", "spatula"],
)
@pytest.mark.parametrize("kernel", ["auto", pytest.param("numpy", marks=pytest.mark.slow)])
def test_every_seta_near_is_the_whole_arrays_located_step(monkeypatch, overrides, proto, kernel):
    """With every seta near, the multirate step (the whole array at dt, its near setae's
    share taken out and put back from their k steps alone) is the whole array's k located
    steps: every column and every release to rounding."""
    _, whole = _run(overrides, 6, proto, multirate=False, kernel=kernel)
    _force_near(monkeypatch, np.ones_like)
    m, multi = _run(overrides, 6, proto, kernel=kernel)
    assert multi.meta["multirate_steps"] > 10
    assert multi.meta["n_steps"] < whole.meta["n_steps"]  # a multirate step counts once
    for col in ("force_normal_uN", "force_tangential_uN", "plate_force_x_uN", "work_plate_pJ",
                "energy_elastic_pJ", "energy_kinetic_pJ", "energy_dissipated_pJ"):  # fmt: skip
        a, b = whole[col], multi[col]
        scale = np.max(np.abs(a))
        # Records by simulated time: a record may fall one step apart where k·(dt/k) and
        # dt round apart; compare where the records' times agree.
        same = np.isclose(whole["time_us"], multi["time_us"], rtol=0, atol=1e-6)
        assert same.mean() > 0.99
        np.testing.assert_allclose(b[same], a[same], rtol=0, atol=1e-9 * scale, err_msg=col)
    for col in ("seta", "plate_y_um", "time_us", "force_uN"):
        np.testing.assert_allclose(
            multi.detachments[col], whole.detachments[col], rtol=1e-7, atol=1e-9, err_msg=col
        )


def test_a_seta_stepped_near_keeps_its_own_history(monkeypatch):
    """Two setae on a flat floor, the first always near an event, the second never: each
    lets go where a seta alone does with its steps (located, or the long step throughout),
    and the pull-off is the sum of theirs."""
    flat = {"floor.sigma": 0.0, "mechanics": "rod"}
    proto = protocol.press_pull(1.0)
    m1, located = _run(flat, 1, proto)
    _, long = _run(flat, 1, proto, event_dt=m1.dt)

    def first(near):
        out = np.zeros_like(near)
        out[0] = True
        return out

    _force_near(monkeypatch, first)
    _, pair = _run(flat, 2, proto)
    det = pair.detachments
    assert list(det["seta"]) == [0, 1]
    y = [located.detachments["plate_y_um"][0], long.detachments["plate_y_um"][0]]
    np.testing.assert_allclose(det["plate_y_um"], y, rtol=1e-10)
    assert y[1] - y[0] > 0.01  # the two steps resolve the release apart: the test can fail
    po = [-h["force_normal_uN"].min() for h in (located, long)]
    np.testing.assert_allclose(-pair["force_normal_uN"].min(), sum(po), rtol=1e-6)


@pytest.mark.slow
def test_a_rough_patch_closes_its_books_in_fewer_seta_steps():
    """40 rod setae on a rough floor: the multirate run pulls off within 0.1 % of the whole
    array's located steps, lets every seta go within an event step of plate travel of it,
    closes its energy books within a tenth of their tolerance of the whole array's, in fewer
    seta-steps."""
    proto = protocol.press_pull(1.0)
    _, whole = _run(ROUGH, 40, proto, multirate=False)
    m, multi = _run(ROUGH, 40, proto)
    assert multi.meta["multirate_steps"] > 0
    po = [-h["force_normal_uN"].min() for h in (whole, multi)]
    assert po[1] == pytest.approx(po[0], rel=1e-3)
    a, b = whole.detachments, multi.detachments
    ia, ib = np.argsort(a["seta"], kind="stable"), np.argsort(b["seta"], kind="stable")
    np.testing.assert_array_equal(a["seta"][ia], b["seta"][ib])
    dy = np.abs(a["plate_y_um"][ia] - b["plate_y_um"][ib])
    assert dy.max() < m.event_dt * 1.0  # plate speed 1 µm/µs at most in press_pull
    books = [energy_balance_error(h) for h in (whole, multi)]
    assert books[1] < books[0] + 0.1 * ENERGY_RTOL
    seta_steps = multi.meta["n_steps"] * 40 + multi.meta["multirate_seta_substeps"]
    assert seta_steps < 0.7 * whole.meta["n_steps"] * 40


@pytest.mark.parametrize(
    "overrides, numerics",
    [
        ({"backing.kind": "elastic", "array.count": 4}, {}),
        ({"floor.sigma": 0.5, "floor.correlation_length": 5.0}, {}),
        ({"floor.sigma": 0.5}, {"integrator": "explicit"}),
        ({"floor.sigma": 0.5}, {"multirate": False}),
    ],
    ids=["elastic strip", "continuous floor", "explicit", "off"],
)
def test_multirate_applies_only_where_the_setae_are_independent(overrides, numerics):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        n = overrides.get("array.count", 8)
        m = Model(PAPER_ARRAY.replace(**overrides), n_sim=n, numerics=Numerics(**numerics))
    assert m._multirate is None


def test_multirate_must_be_a_bool():
    with pytest.raises(ValueError, match="multirate = 'yes'"):
        Model(PAPER_ARRAY, n_sim=2, numerics=Numerics(multirate="yes"))


def test_run_files_switch_it(tmp_path):
    """``[model] multirate`` reaches the model; a value that is not a boolean is refused when
    the file loads, naming the key."""
    from gecko_agents.runfiles import run as runfile

    text = """preset = "PAPER_ARRAY"
[params]
mechanics = "rod"
"floor.sigma" = 0.5
[model]
n_sim = 4
multirate = {value}
[protocol]
preset = "press_pull"
depth_um = 0.1
"""
    for value, on in (("false", False), ("true", True)):
        path = tmp_path / f"{value}.toml"
        path.write_text(text.format(value=value))
        assert runfile.read_run_file(path).model["multirate"] is on
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert (runfile.read_run_file(path).build_model()._multirate is not None) is on
    bad = tmp_path / "bad.toml"
    bad.write_text(text.format(value='"yes"'))
    with pytest.raises(runfile.RunFileError, match=r"\[model\] multirate"):
        runfile.read_run_file(bad)
