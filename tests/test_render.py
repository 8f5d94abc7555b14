"""render: GIF frames and size, tip colours at the right pixels, determinism, clear errors."""

import re
import subprocess
import sys

import extras
import numpy as np
import pytest
from PIL import Image

from gecko_agents import history as hist
from gecko_agents import protocol, render
from gecko_agents.model import Model
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.render import force_plots

N_REC = 30
TENSION_SETA, TENSION_RECORD = 2, 22  # seta 2 holds on in tension while the plate rises
SLIDE_SETA, DEEPEST = 3, 14  # seta 3 slides at the deepest point
DETACH_RECORD = 25


def _toy(N=5, pitch=30.0, mechanics="linear"):
    """Plate goes down 7 µm and back up 12 µm; tips follow the rest pose unless held.

    Free tips sit at root + L(cos θ, −sin θ) = root + (17.3, −10) µm; with R = 4 µm a tip
    touches the floor (y = 0) once the plate is below y = 14 µm.
    """
    p = PAPER_TABLE1.replace(**{"array.count": N, "array.pitch": pitch, "mechanics": mechanics})
    L, th, R = p.seta.L, p.seta.theta, p.contact.R
    plate_y = np.concatenate(
        [np.linspace(20.0, 13.0, DEEPEST + 1), np.linspace(13.0, 25.0, N_REC - DEEPEST)[1:]]
    )
    t = np.arange(N_REC) * 0.5
    root_dx = (np.arange(N) - (N - 1) / 2) * pitch
    tip_x = np.tile(root_dx + L * np.cos(th), (N_REC, 1))
    tip_y = np.tile(plate_y[:, None] - L * np.sin(th), (1, N))
    overlap = R - tip_y
    state = np.where(overlap > 0, hist.STATE_STICK, hist.STATE_FREE)
    force = np.where(overlap > 0, 2.0 * overlap, 0.0)
    # Seta 2 stays stuck (overlap −0.1 µm, pulling) from the turnaround until it snaps off.
    hold = np.arange(N_REC)
    held = (hold > DEEPEST) & (hold < DETACH_RECORD)
    tip_y[held, TENSION_SETA] = R + 0.1
    overlap[held, TENSION_SETA] = -0.1
    state[held, TENSION_SETA] = hist.STATE_STICK
    force[held, TENSION_SETA] = -1.2
    tip_x[held, TENSION_SETA] += 1.5  # dragged a little sideways
    state[DEEPEST - 2 : DEEPEST + 2, SLIDE_SETA] = hist.STATE_SLIP
    force_total = force.sum(axis=1)
    scalars = {
        "time_us": t,
        "plate_x_um": np.zeros(N_REC),
        "plate_y_um": plate_y,
        "force_normal_uN": force_total,
        "force_tangential_uN": 0.1 * force_total,
        "plate_force_x_uN": -0.1 * force_total,
        "plate_force_y_uN": force_total,
        "n_attached": (state > 0).sum(axis=1).astype(float),
        "n_sliding": (state == hist.STATE_SLIP).sum(axis=1).astype(float),
        "energy_elastic_pJ": np.abs(force_total),
        "energy_kinetic_pJ": np.zeros(N_REC),
        "energy_dissipated_pJ": np.linspace(0, 1, N_REC),
        "work_plate_pJ": np.zeros(N_REC),
    }
    setae = {
        "tip_x_um": tip_x,
        "tip_y_um": tip_y,
        "force_normal_uN": force,
        "force_tangential_uN": 0.1 * force,
        "overlap_um": overlap,
        "state": state.astype(np.int8),
    }
    floor_x = np.linspace(-200.0, 200.0, 81)
    geometry = {
        "root_dx_um": root_dx,
        "root_dy_um": np.zeros(N),
        "floor_x_um": floor_x,
        "floor_y_um": 0.3 * np.sin(floor_x / 7.0),
    }
    k = DETACH_RECORD
    det = {
        "seta": np.array([TENSION_SETA]),
        "time_us": np.array([t[k] - 0.25]),
        "plate_y_um": np.array([plate_y[k - 1]]),
        "overlap_um": np.array([-0.1]),
        "force_uN": np.array([-1.2]),
    }
    assert all(c in scalars for c in hist.SCALAR_COLUMNS)
    assert all(f in setae for f in hist.PER_SETA_FIELDS)
    return hist.History(p, 0, scalars, setae, geometry, det, {"dt_us": 0.5})


@pytest.fixture(scope="module")
def toy():
    return _toy()


@pytest.fixture(scope="module")
def gif(toy, tmp_path_factory):
    return render.animate(toy, tmp_path_factory.mktemp("anim") / "run.gif", dpi=60)


def _gif_frames(path):
    with Image.open(path) as im:
        frames = []
        for i in range(im.n_frames):
            im.seek(i)
            frames.append(np.asarray(im.convert("RGB")))
        return frames


def _colour_at(rgb, rc, half=2):
    """Median colour of a small square around pixel (row, col)."""
    r, c = rc
    return np.median(rgb[r - half : r + half + 1, c - half : c + half + 1].reshape(-1, 3), axis=0)


def _is(colour, hex_code, tol=40):
    target = np.array([int(hex_code[i : i + 2], 16) for i in (1, 3, 5)])
    return np.all(np.abs(colour - target) <= tol)


@pytest.mark.slow
def test_gif_has_one_frame_per_record_at_the_promised_size(gif):
    with Image.open(gif) as im:
        assert im.n_frames == N_REC
        assert im.size == (round(render.FIGSIZE[0] * 60), round(render.FIGSIZE[1] * 60))
    assert not list(gif.parent.glob(".*"))  # the temporary file was renamed away


def test_frames_are_spread_over_the_records():
    np.testing.assert_array_equal(render.frame_records(30), np.arange(30))
    r = render.frame_records(1000)
    assert len(r) == 300 and r[0] == 0 and r[-1] == 999 and np.all(np.diff(r) > 0)
    assert len(render.frame_records(1000, 7)) == 7
    assert len(render.frame_records(5, 50)) == 5


def test_side_view_changes_while_the_plate_moves(toy, gif):
    frames = _gif_frames(gif)
    frame = render.render_frame(toy, 0, dpi=60)
    box = frame.side_ax.get_window_extent()
    h = frames[0].shape[0]
    rows = slice(int(h - box.y1) + 2, int(h - box.y0) - 2)
    cols = slice(int(box.x0) + 2, int(box.x1) - 2)
    for a, b in zip(frames[:-1], frames[1:], strict=True):
        assert np.any(a[rows, cols] != b[rows, cols])


@pytest.mark.parametrize(
    ("k", "seta", "colour"),
    [
        (TENSION_RECORD, TENSION_SETA, "tension"),
        (TENSION_RECORD, 0, "free"),
        (DEEPEST, 0, "compressed"),
        (DEEPEST, SLIDE_SETA, "sliding"),
        (0, SLIDE_SETA, "free"),
    ],
)
def test_tip_colour_at_the_tip(toy, k, seta, colour):
    frame = render.render_frame(toy, k)
    rgb = frame.rgb()
    assert rgb.shape == (
        round(render.FIGSIZE[1] * render.DPI),
        round(render.FIGSIZE[0] * render.DPI),
        3,
    )
    rc = frame.pixel(toy.setae["tip_x_um"][k, seta], toy.setae["tip_y_um"][k, seta])
    assert _is(_colour_at(rgb, rc), render.STATE_COLOURS[colour])


def test_gif_frame_shows_the_tension_colour_at_the_tip(toy, gif):
    frame = render.render_frame(toy, TENSION_RECORD, dpi=60)
    rgb = _gif_frames(gif)[TENSION_RECORD]
    x, y = toy.setae["tip_x_um"][TENSION_RECORD], toy.setae["tip_y_um"][TENSION_RECORD]
    assert _is(
        _colour_at(rgb, frame.pixel(x[TENSION_SETA], y[TENSION_SETA]), 1),
        render.STATE_COLOURS["tension"],
    )
    assert _is(_colour_at(rgb, frame.pixel(x[1], y[1]), 1), render.STATE_COLOURS["free"])


def test_rod_mechanics_and_sub_frame_selection(tmp_path):
    out = render.animate(_toy(mechanics="rod"), tmp_path / "rod.gif", frames=4, dpi=40)
    with Image.open(out) as im:
        assert im.n_frames == 4


def test_same_history_gives_the_same_bytes(toy, tmp_path):
    a = render.animate(toy, tmp_path / "a.gif", frames=6, dpi=40)
    b = render.animate(toy, tmp_path / "b.gif", frames=6, dpi=40)
    assert a.read_bytes() == b.read_bytes()


def test_window_of_a_large_array_is_announced():
    assert render.window_range(1000, 40) == range(480, 520)
    assert render.window_range(5, 40) == range(5)
    h = _toy(N=100, pitch=4.0)
    frame = render.render_frame(h, 5, window=10)
    assert frame.shown == range(45, 55)
    # The announcement's numbers: first and last seta shown (1-based) and the array's size.
    assert [int(n) for n in re.findall(r"\d+", frame.window_text)] == [45, 54, 100]
    assert frame.window_text in [t.get_text() for t in frame.figure.texts]
    assert render.render_frame(_toy(), 5).window_text == ""


def test_side_view_is_to_scale(toy):
    frame = render.render_frame(toy, 0)
    x0, y0 = frame.side_ax.transData.transform((0.0, 0.0))
    x1, y1 = frame.side_ax.transData.transform((10.0, 10.0))
    assert x1 - x0 == pytest.approx(y1 - y0, rel=1e-6)


def test_no_per_seta_data_is_refused(toy, tmp_path):
    bare = hist.History(toy.params, 0, toy.scalars, geometry=toy.geometry)
    with pytest.raises(ValueError, match="record_setae=True"):
        render.animate(bare, tmp_path / "x.gif")
    assert not list(tmp_path.iterdir())


def test_bad_format_and_missing_ffmpeg(toy, tmp_path, monkeypatch):
    with pytest.raises(ValueError, match="gif or .mp4"):
        render.animate(toy, tmp_path / "x.avi")
    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)  # import now fails
    with pytest.raises(RuntimeError, match=r"pip install -e '\.\[video\]'"):
        render.animate(toy, tmp_path / "x.mp4")
    assert not list(tmp_path.iterdir())


def test_plot_history_labels_legend_and_marks(toy, tmp_path):
    fig = render.plot_history(toy, tmp_path / "f.png")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "pressing displacement d [µm] (> 0 pressed)"
    assert ax.get_ylabel() == "contact force [µN]"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert {"approach", "retract"} <= set(labels)
    assert any(s.startswith("pull-off") for s in labels)
    # The snap-off marks: one per detachment of the toy run, their count in the legend.
    (snap,) = [s for s in labels if s.startswith("snap-off")]
    (marks,) = [ln for ln in ax.get_lines() if ln.get_label() == snap]
    assert int(re.search(r"\((\d+)\)", snap).group(1)) == len(marks.get_xdata()) == 1
    with Image.open(tmp_path / "f.png") as im:
        assert im.size == (round(6.4 * render.PNG_DPI), round(4.4 * render.PNG_DPI))
    assert [p.name for p in tmp_path.iterdir()] == ["f.png"]


def test_approach_and_retract_split_where_the_plate_turns():
    y = np.array([5.0, 4.0, 4.0, 3.0, 3.5, 3.5, 6.0, 2.0])
    assert force_plots._direction_runs(y) == [(0, 3, True), (3, 6, False), (6, 7, True)]


def test_plot_force_curves_and_annotations(tmp_path):
    x = np.linspace(-1, 1, 20)
    curves = [
        {"x": x, "y": x**2, "label": "a"},
        {"x": x, "y": -x, "label": "b", "style": {"ls": "--", "color": "k"}},
    ]
    fig = render.plot_force_curves(
        curves, tmp_path / "c.png", "overlap δ [µm]", "force P [µN]", "two curves"
    )
    ax = fig.axes[0]
    render.annotate_points(ax, [(0.0, 0.0, "origin"), (1.0, -1.0, "end")])
    assert ax.get_xlabel() == "overlap δ [µm]" and ax.get_title() == "two curves"
    assert "origin" in [t.get_text() for t in ax.texts]
    assert (tmp_path / "c.png").is_file()


def _cli(*args):
    return subprocess.run(
        [sys.executable, "-m", "gecko_agents.render", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=60,
    )


def _is_module(name: str) -> bool:
    import importlib.util

    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:  # an attribute of a module, not a submodule
        return False


def _imports_of(module: str, seen=None) -> set[str]:
    """Every module ``module`` imports, following the package's own modules (read from their
    source, so the package's ``__init__`` and whatever else is loaded do not count)."""
    import ast
    import importlib.util

    seen = set() if seen is None else seen
    if module in seen:
        return set()
    seen.add(module)
    origin = importlib.util.find_spec(module).origin
    package = module if origin.endswith("__init__.py") else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(open(origin).read())):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            found.add(node.module)
        elif isinstance(node, ast.ImportFrom):  # from .x import y, from . import x
            base = importlib.util.resolve_name("." * node.level + (node.module or ""), package)
            subs = [f"{base}.{a.name}" for a in node.names]
            modules = [m for m in subs if _is_module(m)]
            # ``from . import x`` imports the package's __init__ only for x not a submodule.
            if node.module or len(modules) < len(subs):
                modules.append(base)
            for name in modules:
                found.add(name)
                found |= _imports_of(name, seen)
    return found


def test_render_imports_no_pymunk_and_no_pyplot():
    imported = _imports_of("gecko_agents.render")
    assert {"gecko_agents.render.force_plots", "gecko_agents.render.scene"} <= imported  # it works
    assert not {m for m in imported if m.split(".")[0] == "pymunk"}
    assert "matplotlib.pyplot" not in imported
    # Drawing reads a History only: no arrow back to the model, its world or the command line.
    engine = {"model", "world", "backing", "loop", "kernels", "recorder", "cli", "runfile"}
    assert not {m for m in imported if m.removeprefix("gecko_agents.") in engine}


@pytest.mark.slow
def test_missing_and_corrupt_runs(tmp_path, capsys):
    assert render.main([str(tmp_path / "nope")]) == 2
    err = capsys.readouterr().err
    assert str(tmp_path / "nope") in err  # the error names the directory it looked for
    res = _cli(tmp_path / "nope")
    assert res.returncode == 2 and str(tmp_path / "nope") in res.stderr
    assert "Traceback" not in res.stderr and len(res.stderr.strip().splitlines()) == 1
    _toy().save(tmp_path / "run")
    (tmp_path / "run" / "history.csv").write_text("garbage,1\nx,y\n")
    res = _cli(tmp_path / "run")
    assert res.returncode == 2 and "history.csv" in res.stderr
    assert "Traceback" not in res.stderr and len(res.stderr.strip().splitlines()) == 1


def test_cli_renders_a_saved_run(tmp_path, capsys):
    _toy().save(tmp_path / "run")
    assert render.main([str(tmp_path / "run"), "--frames", "3", "--fps", "5"]) == 0
    out = capsys.readouterr().out
    gif, png = tmp_path / "run" / "detachment.gif", tmp_path / "run" / "force_history.png"
    assert str(gif) in out and str(png) in out
    with Image.open(gif) as im:
        assert im.n_frames == 3
    assert png.is_file()


def test_one_sign_convention_for_displacement_in_plots_and_animation(toy):
    """d = touch-down height − plate height: > 0 pressed, < 0 pulled away (docs/physics.md)."""
    p = toy.params
    z_touch = p.contact.R + p.seta.L * np.sin(p.seta.theta)  # tip on y = 0 at rest (14 µm)
    assert render.touchdown_height(p) == pytest.approx(z_touch, rel=1e-12)
    d = render.pressing_displacement(toy)
    assert_d = z_touch - toy["plate_y_um"]
    assert np.allclose(d, assert_d, rtol=0, atol=1e-12)
    assert d[DEEPEST] == pytest.approx(1.0) and d[-1] == pytest.approx(-11.0)
    # the force curve's x data and the animation's marker use the same d
    fig = render.plot_history(toy)
    xs = np.concatenate(
        [
            line.get_xdata()
            for line in fig.axes[0].get_lines()
            if line.get_label() in ("approach", "retract")
        ]
    )
    assert xs.max() == pytest.approx(d.max()) and xs.min() == pytest.approx(d.min())
    frame = render.render_frame(toy, DEEPEST)
    marker = frame.force_ax.get_lines()[-1]
    assert marker.get_xdata()[0] == pytest.approx(d[DEEPEST])
    assert frame.force_ax.get_xlabel() == render.PRESSING_LABEL
    caption = [t.get_text() for t in frame.figure.texts if "pressing displacement" in t.get_text()]
    shown = re.search(r"[+-]\d+\.\d{3} µm", caption[0]).group(0)  # d in the caption, 3 decimals
    assert float(shown.split()[0]) == pytest.approx(d[DEEPEST], abs=5e-4)


def test_mp4_is_written_with_the_video_extra(toy, tmp_path):
    extras.require("video")
    out = render.animate(toy, tmp_path / "run.mp4", frames=4, dpi=40)
    data = out.read_bytes()
    assert len(data) > 1000 and data[4:8] == b"ftyp"  # an ISO media (MP4) file
    assert not list(tmp_path.glob("*.tmp*"))


# elastic backing (issue 14) -------------------------------------------------------------------

LINK = 30.0  # µm: the toy strip is 5 links under 5 setae at 30 µm pitch, 150 µm long


def _with_backing(toy, nodes=True):
    """``toy`` with fake elastic-backing records, one per record as the Recorder writes them: a
    sagging strip drifting +0.5 µm per record whose nodes sit at material abscissae −75, −45,
    …, 75 µm, the front at the node of abscissa 45 µm, and nothing attached in the last five
    records."""
    from dataclasses import replace

    n = len(toy)
    material = np.linspace(-75.0, 75.0, 6)
    plate_y = toy["plate_y_um"]
    nodes_x = np.tile(material, (n, 1)) + 0.5 * np.arange(n)[:, None]
    nodes_y = plate_y[:, None] - 2.0 * np.cos(material / 75.0 * np.pi / 2)[None, :]
    front = np.where(np.arange(n) < n - 5, 45.0, np.nan)
    pull = {"strip_setae_force_x_uN": np.zeros(n), "strip_setae_force_y_uN": np.zeros(n)}
    scalars = {**toy.scalars, "strip_front_x_um": front, **pull}
    backing, geometry = {}, dict(toy.geometry)
    if nodes:
        backing = {"strip_node_x_um": nodes_x, "strip_node_y_um": nodes_y}
        geometry["strip_node_abscissa_um"] = material
    h = replace(toy, scalars=scalars, backing=backing, geometry=geometry)
    return h, nodes_x, nodes_y


def test_backing_strip_is_drawn_through_the_recorded_nodes(toy):
    h, nodes_x, nodes_y = _with_backing(toy)
    k = 9
    frame = render.render_frame(h, k)
    np.testing.assert_array_equal(frame.strip.get_xdata(), nodes_x[k])
    np.testing.assert_array_equal(frame.strip.get_ydata(), nodes_y[k])
    assert not frame.side_ax.patches  # the strip replaces the rigid plate
    # The front (abscissa 45 µm) is node 4; the roots (−60, −30, …, 60 µm) sit halfway
    # between two nodes, each on its rigid link.
    np.testing.assert_allclose(frame.front.get_xydata(), [[nodes_x[k, 4], nodes_y[k, 4]]])
    rods = [c for c in frame.side_ax.collections if type(c).__name__ == "LineCollection"]
    roots = np.array([seg[0] for seg in rods[0].get_segments()])
    half = 0.5 * (nodes_x[k, :-1] + nodes_x[k, 1:]), 0.5 * (nodes_y[k, :-1] + nodes_y[k, 1:])
    np.testing.assert_allclose(roots, np.column_stack(half), atol=1e-12)
    # Drawn where promised: the strip's colour at a node inside the view.
    rgb = frame.rgb()
    assert _is(_colour_at(rgb, frame.pixel(nodes_x[k, 2], nodes_y[k, 2]), 1), "#444444")


def test_backing_front_follows_recorded_node_abscissae(toy):
    """A strip with a leader arm has nodes beyond the pad: the front is placed by the nodes'
    recorded material abscissae, not by equal links."""
    from dataclasses import replace

    h, nodes_x, nodes_y = _with_backing(toy)
    g = dict(h.geometry, strip_node_abscissa_um=np.array([-75.0, -45.0, -15.0, 15.0, 30.0, 45.0]))
    frame = render.render_frame(replace(h, geometry=g), 9)  # the front at node 5 now
    np.testing.assert_allclose(frame.front.get_xydata(), [[nodes_x[9, 5], nodes_y[9, 5]]])
    g["strip_node_abscissa_um"] = np.array([0.0, 1.0])
    with pytest.raises(ValueError, match="2 node abscissae for 6 nodes"):
        render.render_frame(replace(h, geometry=g), 9)


def test_backing_front_vanishes_once_nothing_is_attached(toy):
    h, *_ = _with_backing(toy)
    k = len(h) - 1
    assert np.isnan(h["strip_front_x_um"][k])
    assert len(render.render_frame(h, k).front.get_xdata()) == 0


def test_backing_without_nodes_keeps_the_plate_and_puts_the_front_on_it(toy):
    h, *_ = _with_backing(toy, nodes=False)
    k = 3
    frame = render.render_frame(h, k)
    assert frame.strip is None and len(frame.side_ax.patches) == 1  # the rigid plate
    want = [[h["plate_x_um"][k] + 45.0, h["plate_y_um"][k]]]  # its lower edge (root_dy = 0)
    np.testing.assert_allclose(frame.front.get_xydata(), want)


def test_backing_animation_is_written(toy, tmp_path):
    h, *_ = _with_backing(toy)
    out = render.animate(h, tmp_path / "strip.gif", frames=4, dpi=40)
    assert len(_gif_frames(out)) == 4


def _with_film(toy):
    """``toy`` with film-tip records: each attached tip's peel front 5 µm beyond its centre
    (+x) and a pad of ℓ = 3 µm, NaN while free."""
    from dataclasses import replace

    attached = toy.setae["state"] != hist.STATE_FREE
    front = np.where(attached, toy.setae["tip_x_um"] + 5.0, np.nan)
    ell = np.where(attached, 3.0, np.nan)
    setae = {**toy.setae, "film_front_x_um": front, "film_attached_um": ell}
    return replace(toy, setae=setae)


def test_film_and_pad_are_drawn_from_the_recorded_front():
    """Each attached film tip: the free film from its front on the floor to its tip body's
    bottom, the pad from the front over ℓ of floor; nothing for a free tip; the pad's colour
    where it lies."""
    from gecko_agents.render.scene import FILM_COLOUR

    h = _with_film(_toy())
    k, i = TENSION_RECORD, TENSION_SETA
    frame = render.render_frame(h, k)
    attached = np.flatnonzero(h.setae["state"][k] != hist.STATE_FREE)
    assert len(frame.films.get_segments()) == len(attached) == len(frame.pads.get_segments())
    j = list(attached).index(i)
    x0 = h.setae["tip_x_um"][k, i] + 5.0
    floor_x = h.geometry["floor_x_um"]

    def floor(x):  # the toy's floor polyline, as stored
        return np.interp(x, floor_x, 0.3 * np.sin(floor_x / 7.0))

    y0 = floor(x0)
    film = frame.films.get_segments()[j]
    np.testing.assert_allclose(film[0], [x0, y0])
    bottom = h.setae["tip_y_um"][k, i] - h.params.contact.R
    np.testing.assert_allclose(film[1], [h.setae["tip_x_um"][k, i], max(bottom, y0)])
    pad = frame.pads.get_segments()[j]
    np.testing.assert_allclose(pad[:, 0], [x0, x0 + 3.0])
    rgb = frame.rgb()
    mid = x0 + 1.5
    assert _is(_colour_at(rgb, frame.pixel(mid, floor(mid)), 0), FILM_COLOUR)
    plain = render.render_frame(_toy(), k)
    assert plain.films is None and plain.pads is None


@pytest.mark.slow
@pytest.mark.parametrize("bad", [["--frames", "0"], ["--fps", "0"], ["--window", "0"]])
def test_a_bad_animation_argument_is_refused_before_the_figure_is_rewritten(tmp_path, bad):
    h = Model(PAPER_TABLE1, n_sim=1, seed=1).run(protocol.press_pull(0.3, speed=0.05),
                                                 progress=False)  # fmt: skip
    run_dir = h.save(tmp_path / "run")
    png = run_dir / "force_history.png"
    png.write_bytes(b"the figure already there")
    assert render.main([str(run_dir), *bad]) == 2
    assert png.read_bytes() == b"the figure already there"
