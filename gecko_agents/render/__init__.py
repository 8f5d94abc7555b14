"""Figures and animations drawn from a recorded :class:`~gecko_agents.history.History` only.

Units on every axis: µm, µN, µs. The floor's mean plane is y = 0, y points up. Force curves
are drawn against the pressing displacement d = (touch-down height) − (plate height) [µm],
positive when the plate is pressed towards the floor past the height at which a resting tip
touches the mean plane, negative when pulled away beyond it; forces are positive in
compression, negative in tension (docs/physics.md, "Sign conventions").

* :func:`animate` — side view of the array (plate, setae, tips coloured by contact state, floor,
  all to scale) next to the force–displacement curve, written as a GIF (Pillow) or MP4 (ffmpeg
  from ``imageio-ffmpeg``, the ``video`` extra);
* :func:`render_frame` — one frame of that animation, with the axes, for tests and stills;
* :func:`plot_history` — force vs plate displacement, approach and retract, pull-off, snap-offs;
* :func:`plot_force_curves`, :func:`annotate_points`, :func:`apply_style`, :data:`STYLE_RC` —
  the shared look of the scenario figures.

Command line: ``python -m gecko_agents.render RUN_DIR [--gif|--mp4] [--window N] [--frames N]
[--fps N]`` writes ``RUN_DIR/detachment.gif`` (or ``.mp4``) and ``RUN_DIR/force_history.png``.

Figures are plain :class:`matplotlib.figure.Figure` objects on an Agg canvas: no pyplot, no GUI
backend, no global state, and nothing here imports pymunk. The parts, one concept each:
:mod:`~gecko_agents.render.style` (the look, atomic saving), :mod:`~gecko_agents.render.force_plots`
(force–displacement curves), :mod:`~gecko_agents.render.scene` (one animation frame); this
module writes the animation and is the render command. Every name listed above is importable
from here.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import matplotlib as mpl
import numpy as np
from matplotlib.animation import FFMpegWriter, PillowWriter
from PIL import Image

from gecko_agents.history import History, load_history
from gecko_agents.output_paths import replace_into
from gecko_agents.render.force_plots import (
    PRESSING_LABEL,
    plot_force_curves,
    plot_history,
    pressing_displacement,
    touchdown_height,
)
from gecko_agents.render.scene import (
    MAX_FRAMES,
    Frame,
    Scene,
    frame_records,
    render_frame,
    window_range,
)
from gecko_agents.render.style import (
    APPROACH_COLOUR,
    DPI,
    FIGSIZE,
    PNG_DPI,
    RETRACT_COLOUR,
    STATE_COLOURS,
    STYLE_RC,
    annotate_points,
    apply_style,
    atomic_target,
    save_figure,
)

__all__ = [
    "STYLE_RC",
    "STATE_COLOURS",
    "APPROACH_COLOUR",
    "RETRACT_COLOUR",
    "MAX_FRAMES",
    "FIGSIZE",
    "DPI",
    "PNG_DPI",
    "Frame",
    "animate",
    "render_frame",
    "frame_records",
    "window_range",
    "plot_history",
    "plot_force_curves",
    "annotate_points",
    "apply_style",
    "save_figure",
    "touchdown_height",
    "pressing_displacement",
    "PRESSING_LABEL",
    "main",
]


class _GifWriter(PillowWriter):
    """PillowWriter fed with ready RGB arrays, palettising each frame as it comes.

    A GIF frame holds at most 256 colours anyway; converting at once keeps 1 byte/pixel in
    memory instead of 3, and the fast octree quantiser is ~8× quicker than Pillow's default
    median cut for a mean error of ~1/255 on these flat-coloured drawings.
    """

    def grab_rgb(self, rgb: np.ndarray) -> None:
        frame = Image.fromarray(rgb).quantize(256, method=Image.Quantize.FASTOCTREE)
        self._frames.append(frame)


def _mp4_writer(fps: float) -> tuple[FFMpegWriter, str]:
    """An FFMpegWriter and the ffmpeg binary from ``imageio-ffmpeg``."""
    try:
        import imageio_ffmpeg
    except ImportError as err:
        raise RuntimeError(
            "MP4 output needs the ffmpeg binary from imageio-ffmpeg: "
            "pip install -e '.[video]' (or write a .gif)"
        ) from err
    # With codec "h264" matplotlib rounds the frame to even pixels and asks for yuv420p, so
    # the file plays everywhere.
    writer = FFMpegWriter(fps=fps, codec="h264")
    return writer, imageio_ffmpeg.get_ffmpeg_exe()


def animate(
    history: History,
    path,
    *,
    window: int = 40,
    frames: int | None = None,
    fps: float = 20,
    fmt: str | None = None,
    dpi: float = DPI,
) -> Path:
    """Animate a run: the array seen from the side next to its force–displacement curve.

    Parameters
    ----------
    history : a run recorded with per-seta data (``record_setae=True``); positions in µm,
        forces in µN, time in µs.
    path : output file; written atomically (temporary file in the same directory, renamed).
    window : number of setae drawn around the centre of the array (the frame says which).
    frames : number of frames, evenly spread over the records; default min(records, 300).
    fps : frames per second of the movie [1/s].
    fmt : ``"gif"`` (Pillow) or ``"mp4"`` (ffmpeg from ``imageio-ffmpeg``); default from the
        suffix of ``path``.
    dpi : resolution [pixel/inch]; frames are :data:`FIGSIZE` × dpi pixels.

    Tips are circles of radius R coloured by :data:`STATE_COLOURS`; the side view is to scale.
    Returns the path written. Raises ValueError for a run without per-seta data or an unknown
    format, RuntimeError for MP4 without ``imageio-ffmpeg``.
    """
    path = Path(path)
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in ("gif", "mp4"):
        raise ValueError(f"unknown animation format {fmt!r} for {str(path)!r}: use .gif or .mp4")
    if fps <= 0:
        raise ValueError(f"fps = {fps!r} must be > 0")
    records = frame_records(len(history), frames)
    rc = dict(STYLE_RC)
    if fmt == "mp4":
        writer, exe = _mp4_writer(fps)
        rc["animation.ffmpeg_path"] = exe
    else:
        writer = _GifWriter(fps=fps)
    scene = Scene(history, window, dpi)
    tmp = atomic_target(path, f".{fmt}")
    try:
        with mpl.rc_context(rc):
            writer.setup(scene.fig, str(tmp), dpi=dpi)
            for k in records:
                if fmt == "gif":
                    writer.grab_rgb(scene.rgb_fast(int(k)))
                else:  # ffmpeg takes whole redrawn frames through a pipe
                    scene.draw(int(k))
                    writer.grab_frame()
            writer.finish()
        replace_into(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


# Command line -----------------------------------------------------------------------------------
def main(argv=None) -> int:
    """``python -m gecko_agents.render RUN_DIR [--gif|--mp4] [--window N] [--frames N]
    [--fps N]``: render a saved run into RUN_DIR/detachment.gif (or .mp4) and
    RUN_DIR/force_history.png. Returns the exit code (2 on a missing or corrupt run)."""
    parser = argparse.ArgumentParser(
        prog="python -m gecko_agents.render", description="Render a saved gecko_agents run."
    )
    add_arguments(parser)
    return run(parser.parse_args(argv))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The render command's arguments (``python -m gecko_agents.render`` and
    ``gecko-agents render``)."""
    parser.add_argument("run_dir", type=Path, help="directory written by History.save")
    kind = parser.add_mutually_exclusive_group()
    kind.add_argument(
        "--gif", dest="fmt", action="store_const", const="gif", help="animated GIF (default)"
    )
    kind.add_argument(
        "--mp4",
        dest="fmt",
        action="store_const",
        const="mp4",
        help="MP4 video (needs pip install -e '.[video]')",
    )
    parser.add_argument("--window", type=int, default=40, help="setae drawn (default 40)")
    parser.add_argument("--frames", type=int, default=None, help="frames (default ≤ 300)")
    parser.add_argument("--fps", type=float, default=20, help="frames per second (default 20)")


def run(args: argparse.Namespace) -> int:
    """Render the run directory ``args.run_dir`` (arguments of :func:`add_arguments`);
    returns the exit code (2 on a missing or corrupt run)."""
    try:
        start = time.perf_counter()
        # The animation's arguments first: a bad one must not cost the figure already there.
        if args.fps is not None and not args.fps > 0:
            raise ValueError(f"--fps {args.fps!r} must be > 0")
        window_range(1, args.window)
        if args.frames is not None:
            frame_records(max(args.frames, 1), args.frames)
        history = load_history(args.run_dir)
        png = args.run_dir / "force_history.png"
        plot_history(history, png)
        print(f"wrote {png}")
        movie = animate(
            history,
            args.run_dir / f"detachment.{args.fmt or 'gif'}",
            window=args.window,
            frames=args.frames,
            fps=args.fps,
        )
        print(f"wrote {movie}")
        print(f"rendered in {time.perf_counter() - start:.1f} s")
    except (FileNotFoundError, ValueError, RuntimeError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0
