"""The pymunk world: lazy contact detection gives full detection's flags on every step."""

import warnings

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.model import Model, Numerics
from gecko_agents.model.setup import numba_threads
from gecko_agents.params import PAPER_ARRAY

# Stubby setae (L = 5 µm) on a rough pad floor (σ = 0.5 µm): a press, a drag and a pull-off
# take a few thousand steps, and the tips meet their pads at different heights and slide.
ROUGH = PAPER_ARRAY.replace(
    **{"array.count": 200, "seta.L": 5.0, "floor.sigma": 0.5, "mechanics": "rod"}
)
SPEED = 0.05  # µm/µs


def _trajectory(m):
    """Plate velocities [µm/µs]: press 0.5 µm past touch-down, drag 6 µm along +x (tips
    slide from ~5 µm on) and 1 µm back, pull up until every tip is free (at most 2 L)."""
    step = SPEED * m.dt
    n_press = int((m.plate_start - (m.z_touch - 0.5)) / step)
    n_drag, n_back = int(6.0 / step), int(1.0 / step)
    n_pull = int((0.5 + 2 * m.L) / step)
    return (
        [(0.0, -SPEED)] * n_press
        + [(SPEED, 0.0)] * n_drag
        + [(-SPEED, 0.0)] * n_back
        + [(0.0, SPEED)] * n_pull
    )


def _same_history(a, b):
    """Two histories are the same bit for bit: every scalar, per-seta array and detachment."""
    assert a.meta["n_steps"] == b.meta["n_steps"]
    assert a.scalars.keys() == b.scalars.keys()
    for k in a.scalars:
        assert np.array_equal(a.scalars[k], b.scalars[k], equal_nan=True), k
    for k in a.setae:
        assert np.array_equal(a.setae[k], b.setae[k], equal_nan=True), k
    assert a.detachments.keys() == b.detachments.keys()
    for k in a.detachments:
        assert np.array_equal(a.detachments[k], b.detachments[k], equal_nan=True), k


def test_lazy_detection_has_full_detections_flags_and_state_on_every_step():
    full = Model(ROUGH, seed=7, numerics=Numerics(detection="full"))
    lazy = Model(ROUGH, seed=7, numerics=Numerics(detection="lazy"))
    assert (full.world.detection, lazy.world.detection) == ("full", "lazy")
    begins = separates = slid = sensors = steps = 0
    prev = np.zeros(full.n, dtype=bool)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for vp in _trajectory(full):
            full.step(vp)
            lazy.step(vp)
            steps += 1
            cand = full.state.candidate
            assert np.array_equal(lazy.state.candidate, cand), f"flags differ at step {steps}"
            assert np.array_equal(lazy.attached, full.attached), f"attached at step {steps}"
            assert np.array_equal(lazy.state.block, full.state.block, equal_nan=True)
            begins += int(np.count_nonzero(cand & ~prev))
            separates += int(np.count_nonzero(prev & ~cand))
            prev = cand.copy()
            slid += int(np.count_nonzero(full.state.slip))
            sensors += int(np.count_nonzero(lazy.world.in_space))
            if steps > 1000 and not full.attached.any() and not cand.any():
                break
    # The run is one that can tell: every tip met its pad and let go, tips slid, and lazy
    # detection kept few sensors in the space, every flag change seen by a pymunk callback.
    assert begins >= full.n and separates >= full.n
    assert slid > 0
    assert not full.attached.any()
    assert sensors < 0.2 * full.n * steps
    assert lazy.world.geometric_flips == 0
    assert full.world.geometric_flips == 0


def test_lazy_and_full_detection_give_bit_identical_histories():
    p = ROUGH.replace(**{"array.count": 40})
    runs = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for det in ("full", "lazy"):
            m = Model(p, seed=3, record_setae=True, numerics=Numerics(detection=det))
            runs[det] = m.run(protocol.drag_pull(1.0, 1.0, 60.0, speed=SPEED), progress=False)
    a, b = runs["full"], runs["lazy"]
    assert (a.meta["detection"], b.meta["detection"]) == ("full", "lazy")
    _same_history(a, b)


def test_auto_detection_is_lazy_on_pads_and_full_elsewhere():
    assert Model(ROUGH, n_sim=5).world.detection == "lazy"
    assert Model(ROUGH, n_sim=5, numerics=Numerics(contact="callback")).world.detection == "full"
    smooth = ROUGH.replace(**{"floor.correlation_length": 3.0})
    assert Model(smooth, n_sim=5).world.detection == "full"


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"detection": "sometimes"}, "detection = 'sometimes'"),
        ({"detection": "lazy", "contact": "callback"}, "needs contact='batch'"),
        ({"detection": "lazy", "floor": 3.0}, "needs a pad floor"),
        ({"n_sim": 300_000}, "n_sim = 300000 must be an integer in"),
    ],
)
def test_bad_detection_is_refused_naming_it(kw, match):
    kw = dict(kw)
    p = ROUGH
    if "floor" in kw:
        p = ROUGH.replace(**{"floor.correlation_length": kw.pop("floor")})
    kw.setdefault("n_sim", 5)
    with pytest.raises(ValueError, match=match):
        Model(p, **kw)


@pytest.mark.slow
def test_threads_give_the_same_history():
    """threads > 1 runs the numba loop's blocks on numba's threads: press, drag (tips slide)
    and pull-off are the same bit for bit as on one thread."""
    p = ROUGH.replace(**{"array.count": 40})
    runs = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for threads in (1, 3):
            m = Model(p, seed=3, record_setae=True, numerics=Numerics(threads=threads))
            runs[threads] = m.run(protocol.drag_pull(1.0, 6.0, 60.0, speed=SPEED), progress=False)
    a, b = runs[1], runs[3]
    assert a.meta["loop_threads"] == 1
    assert b.meta["loop_threads"] == (numba_threads() if a.meta["kernel"] == "numba" else 1)
    assert np.max(a.scalars["n_sliding"]) > 0
    _same_history(a, b)


@pytest.mark.parametrize(
    ("threads", "kw"),
    [(0, {}), (-1, {}), (2.0, {}), (True, {}), ("2", {}), (65, {}), (2, {"contact": "callback"})],
)
def test_bad_threads_refused_naming_it(threads, kw):
    with pytest.raises(ValueError, match="threads = "):
        Model.from_options(ROUGH, n_sim=5, **kw, numerics=Numerics(threads=threads))


def test_automatic_threads_only_for_large_models_and_only_on_idle_cores(tmp_path, monkeypatch):
    from gecko_agents.model import setup as ms

    monkeypatch.setattr(ms.os, "cpu_count", lambda: 4)
    monkeypatch.setattr(ms, "numba_threads", lambda: 4)
    loadavg = tmp_path / "loadavg"
    monkeypatch.setattr(ms, "_LOADAVG", str(loadavg))
    big = ms.PARALLEL_MIN_SETAE
    for runnable, idle in [(1, 4), (2, 3), (4, 1), (9, 1)]:  # the caller is one of them
        loadavg.write_text(f"0.50 0.40 0.30 {runnable}/210 4242\n")
        assert ms.idle_cores() == idle
        assert ms.choose_threads(None, big) == idle
        assert ms.choose_threads(None, big - 1) == 1
        assert ms.choose_threads(3, 10) == 3  # asked for: always given
