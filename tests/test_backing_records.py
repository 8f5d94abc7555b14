"""A backing as a component of the model, recorded like the rest of the run: the rigid plate's
histories are the ones from before the backing became a component (bit for bit), and an
elastic strip's records go through the Recorder into the History, are saved and loaded with the
run, and are drawn from the loaded run."""

import hashlib
import warnings

import extras
import numpy as np
import pytest

from gecko_agents import history, protocol, render
from gecko_agents.backing.elastic import STRIP_ARRAYS, STRIP_COLUMNS
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY

ROUGH = PAPER_ARRAY.replace(**{"array.count": 6, "seta.L": 5.0, "floor.sigma": 0.3})


def _digest(h) -> str:
    """sha256 (16 hex digits) of every recorded array of ``h``: scalars, per-seta arrays and
    detachments, each with its name."""
    d = hashlib.sha256()
    for group in (h.scalars, h.setae, h.detachments):
        for k in sorted(group):
            d.update(k.encode())
            d.update(np.ascontiguousarray(group[k]).tobytes())
    return d.hexdigest()[:16]


@pytest.mark.parametrize(
    "kernel, press, digest",
    [pytest.param("auto", False, "30b14a5a22253292", marks=extras.needs("fast")),
     ("numpy", True, "a1c736c72a242776"),
     ("python", False, "792f9f9053e0f64a")],
)  # fmt: skip
def test_rigid_plate_histories_are_bit_identical_to_before(kernel, press, digest):
    """The rigid plate (``backing.kind = "rigid"``, the default) as a component: the same
    history bit for bit as the model that had the plate built in (pinned on the development
    machine from that code, commit 04094c1; numpy 2, numba for "auto"), but for the
    detachments' force, since the law's at its release, and the recorded dissipated energy,
    which books the dampers' work at the kinetic energy's half step
    (``Stepping.damping_half_step``; the pins of 04094c1 without those columns are
    unchanged). A drag on a rough floor with the loops, a press and pull with the
    numpy kernel."""
    prot = (
        protocol.press_pull(0.3, speed=0.05)
        if press
        else protocol.drag_pull(0.3, 3.0, 60.0, speed=0.05)
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(
            ROUGH,
            seed=2,
            record_setae=True,
            numerics=Numerics(kernel=kernel, integrator="explicit"),
        )
        h = m.run(prot, progress=False)
    assert "strip_front_x_um" not in h.scalars and not h.backing
    assert _digest(h) == digest


@pytest.fixture(scope="module")
def peeled(tmp_path_factory):
    """A 12-seta pad on a soft strip peeled at its +x end, per-seta records on, saved."""
    p = PAPER_ARRAY.replace(
        **{"array.count": 12, "seta.L": 5.0, "floor.sigma": 0.0, "backing.kind": "elastic",
           "backing.E_b": 1.413, "backing.drive": "peel_end"}
    )  # fmt: skip
    m = Model(p, seed=1, record_setae=True, numerics=Numerics(integrator="explicit"))
    h = m.run(protocol.press_pull(0.3, speed=0.05), progress=False)
    return m, h, h.save(tmp_path_factory.mktemp("runs") / "peel")


@pytest.mark.slow
def test_strip_records_are_history_columns_and_arrays(peeled):
    m, h, _ = peeled
    n_nodes = m.backing.strip.n + 1
    for c in STRIP_COLUMNS:
        assert h[c].shape == (len(h),)
    for a in STRIP_ARRAYS:
        assert h.backing[a].shape == (len(h), n_nodes)
    assert h.geometry["strip_node_abscissa_um"].shape == (n_nodes,)
    # The last record is the model's state at the end of the run.
    x, y = m.backing.strip.nodes()
    np.testing.assert_array_equal(h.backing["strip_node_x_um"][-1], x)
    np.testing.assert_array_equal(h.backing["strip_node_y_um"][-1], y)
    assert "time_us" not in h.meta["backing"]  # static figures only
    assert h.meta["backing"]["n_links"] == m.backing.strip.n
    front = h["strip_front_x_um"]
    assert np.isfinite(front).any() and np.isnan(front[-1])  # NaN while nothing is attached
    assert history.invariant_violations(h) == []


@pytest.mark.slow
def test_saved_elastic_run_loads_from_its_directory_alone(peeled):
    _, h, run_dir = peeled
    loaded = history.load_history(run_dir)
    assert loaded.columns == h.columns == history.SCALAR_COLUMNS + STRIP_COLUMNS
    for c in h.columns:
        np.testing.assert_array_equal(loaded[c], h[c])
    for k, v in h.backing.items():
        np.testing.assert_array_equal(loaded.backing[k], v)
    np.testing.assert_array_equal(
        loaded.geometry["strip_node_abscissa_um"], h.geometry["strip_node_abscissa_um"]
    )
    assert loaded.meta["backing"]["length_um"] == h.meta["backing"]["length_um"]
    assert loaded.run_id() == h.run_id()
    assert history.invariant_violations(loaded) == []


@pytest.mark.slow
def test_a_strip_column_edited_on_disk_is_refused(peeled, tmp_path):
    """The backing's columns are part of the run's identity: an edited value does not load."""
    _, h, _ = peeled
    h.save(tmp_path)
    csv = tmp_path / "history.csv"
    lines = csv.read_text().split("\n")
    row = lines[1].split(",")  # the header, then the first record
    row[-1] = repr(float(row[-1]) + 1.0)  # strip_setae_force_y_uN of the first record
    lines[1] = ",".join(row)
    csv.write_text("\n".join(lines))
    with pytest.raises(ValueError, match="history.csv is not the file run .* SHA-256"):
        history.load_history(tmp_path)


@pytest.mark.slow
def test_loaded_elastic_run_is_drawn_with_its_strip(peeled, tmp_path):
    """Rendered from the loaded run: the strip is drawn through the nodes recorded at that
    record, the front marker sits on it at the recorded front's abscissa, and the animation
    is written."""
    m, h, run_dir = peeled
    loaded = history.load_history(run_dir)
    front = h["strip_front_x_um"]
    k = int(np.flatnonzero(np.isfinite(front))[len(h) // 4])
    frame = render.render_frame(loaded, k, window=m.n)
    np.testing.assert_array_equal(frame.strip.get_xdata(), h.backing["strip_node_x_um"][k])
    np.testing.assert_array_equal(frame.strip.get_ydata(), h.backing["strip_node_y_um"][k])
    s = h.geometry["strip_node_abscissa_um"]
    want = [np.interp(front[k], s, h.backing[f"strip_node_{c}_um"][k]) for c in "xy"]
    np.testing.assert_allclose(frame.front.get_xydata(), [want])
    out = render.animate(loaded, tmp_path / "peel.gif", frames=3, dpi=40)
    assert out.stat().st_size > 1000
