"""The per-seta pad loop (gecko_agents.model.step_loop): blocks, threads and the order of
detachments."""

import warnings

import extras
import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.model import Model, Numerics, numba_available
from gecko_agents.model.step_loop import BLOCK
from gecko_agents.params import PAPER_ARRAY

# Threaded runs and the blocked loop over whole histories: the slow tier.
pytestmark = [
    pytest.mark.skipif(not numba_available(), reason=extras.reason("fast")),
    pytest.mark.slow,
]

# Several blocks of setae on a rough floor, dragged so that tips stick, slide and let go in
# every block.
ARRAY = PAPER_ARRAY.replace(
    **{"array.count": 3 * BLOCK + 17, "seta.L": 5.0, "floor.sigma": 0.3, "mechanics": "rod"}
)
DRAG_PULL = protocol.drag_pull(10.0, 12.0, 60.0, speed=0.05)


def _run(kernel, threaded=False):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(
            ARRAY,
            record_setae=True,
            seed=3,
            numerics=Numerics(kernel=kernel, threads=2 if threaded else 1),
        )
        if threaded and m.loop_threads < 2:
            pytest.skip("numba runs on one thread here (NUMBA_NUM_THREADS)")
        return m.run(DRAG_PULL, progress=False)


@pytest.fixture(scope="module")
def serial():
    return _run("numba")


def test_threaded_blocks_give_the_same_history_bit_for_bit(serial):
    """Sums are taken per block and then in block order, so threads change nothing."""
    threaded = _run("numba", threaded=True)
    for k in serial.scalars:
        np.testing.assert_array_equal(threaded.scalars[k], serial.scalars[k], err_msg=k)
    for k in serial.setae:
        np.testing.assert_array_equal(threaded.setae[k], serial.setae[k], err_msg=k)
    for k in serial.detachments:
        np.testing.assert_array_equal(threaded.detachments[k], serial.detachments[k])


def test_detachments_across_blocks_match_the_vectorized_step(serial):
    """The loop gathers each block's detached tips into one ascending list: the same setae, in
    the same order, as the numpy step (which never blocks)."""
    ref = _run("numpy")
    seta = np.asarray(serial.detachments["seta"])
    assert len(np.unique(seta // BLOCK)) >= 3  # detachments in at least three blocks
    np.testing.assert_array_equal(seta, ref.detachments["seta"])
    np.testing.assert_allclose(serial.detachments["time_us"], ref.detachments["time_us"])
