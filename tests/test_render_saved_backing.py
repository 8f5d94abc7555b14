"""An elastic backing drawn from a run saved to disk and loaded back: the strip the frame draws
is the strip the run recorded (no fake ``meta["backing"]`` or records, unlike the toy in
tests/test_render.py)."""

import warnings

import numpy as np
import pytest

from gecko_agents import history, protocol, render
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY

pytestmark = pytest.mark.slow  # a strip run, saved, loaded and drawn


def test_elastic_backing_of_a_saved_run_is_drawn_through_its_recorded_nodes(tmp_path):
    p = PAPER_ARRAY.replace(
        **{"array.count": 6, "seta.L": 5.0, "floor.sigma": 0.0, "backing.kind": "elastic",
           "backing.E_b": 1.413, "backing.drive": "peel_end"}
    )  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, seed=1, record_setae=True)
        h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
    h.save(tmp_path / "run")
    loaded = history.load_history(tmp_path / "run")
    assert loaded.meta["backing"] == h.meta["backing"]
    nodes_x, nodes_y = loaded.backing["strip_node_x_um"], loaded.backing["strip_node_y_um"]
    np.testing.assert_array_equal(nodes_x, h.backing["strip_node_x_um"])
    k = int(np.argmin(loaded["plate_y_um"]))  # deepest press: every tip attached
    assert loaded["n_attached"][k] > 0
    frame = render.render_frame(loaded, k)
    np.testing.assert_array_equal(frame.strip.get_xdata(), nodes_x[k])
    np.testing.assert_array_equal(frame.strip.get_ydata(), nodes_y[k])
    assert not frame.side_ax.patches  # the strip replaces the rigid plate
    # The strip bends under the pull: its nodes are not on one line at the peak pull-off.
    j = int(np.argmin(loaded["force_normal_uN"]))
    assert np.ptp(nodes_y[j]) > 1e-6
