"""Run files: plain-text TOML records of exactly what was simulated, and running them.

Units are those of :mod:`gecko_agents.params` (µm, µN, µs, ng); protocol keys carry their unit
in their name (``depth_um``, ``speed_um_per_us``, ``preload_uN``, ``duration_us``, …).

Run file
--------
::

    description = "one seta of Table 1 pressed 0.5 µm and pulled off"   # optional
    preset = "PAPER_TABLE1"            # a preset of gecko_agents.params (`gecko-agents params`)

    [params]                           # overrides by dotted name (SetaArray.replace)
    "seta.L" = 5.0
    mechanics = "rod"

    [model]                            # all optional
    n_sim = 1                          # simulated setae, 1 to array.count and at most
                                       # model.setup.MAX_N (default: array.count)
    seed = 1                           # run seed ≥ 0 (default: floor.seed)
    dt_us = 0.01                       # time step [µs] (default: the integrator's)
    record_setae = true                # per-seta arrays (animations need them)
    kernel = "auto"                    # auto | numpy | numba | python
    integrator = "explicit"            # auto | explicit | implicit (default: auto, the
                                       # implicit step where verified, gecko_agents.model.implicit)
    event_dt_us = 0.5                  # the implicit step near events [µs] (default: one
                                       # explicit step; longer: fewer steps, later releases)
    multirate = false                  # near events, only the setae near them step short
                                       # (default: where the setae are independent; true
                                       # where they are not is refused)

    [[protocol]]                       # segments in order ...
    segment = "press_to"
    depth_um = 0.5
    speed_um_per_us = 0.05

    [[protocol]]
    segment = "pull_off"

    # ... or one preset protocol instead of the segments:
    # [protocol]
    # preset = "press_pull"
    # depth_um = 0.5

    [floor]                            # optional: a measured scan as the floor
    file = "dektak"                    # the packaged scan (gecko_agents.data) or a path
    offset_um = 0.0                    # where on the scan the floor starts [µm] (default 0)

    [quick.model]                      # what `--quick` changes: [quick.params],
    n_sim = 1                          # [quick.model] merge into the tables above,
                                       # quick.protocol replaces the protocol

Segments (:mod:`gecko_agents.protocol`; every key but ``segment`` has a default unless marked
required):

==========  ========================================================================
segment     keys
==========  ========================================================================
move        dx_um, dy_um [µm], speed_um_per_us [µm/µs]
press_to    depth_um [µm] (required), speed_um_per_us
press       preload_uN [µN] (required), speed_um_per_us, band [-] (fraction of preload)
hold        duration_us [µs] (required)
pull_off    speed_um_per_us, angle_deg [degrees from +x], clearance_um, max_travel_um [µm]
==========  ========================================================================

Preset protocols: ``press_pull`` (depth_um, speed_um_per_us), ``preload_pull`` (preload_uN,
speed_um_per_us), ``drag_pull`` (preload_uN, drag_um, angle_deg, speed_um_per_us).

Sweep files (the same presets, ``[params]`` and ``[quick]`` rules, a grid instead of a
protocol) are described in :mod:`gecko_agents.runfiles.sweep`; their names are importable from here.
The checks both kinds of file share are in :mod:`gecko_agents.runfiles.schema`.

Everything is checked when the file is loaded — unknown keys, wrong types, values the parameter
sets or protocol segments refuse, the quick variant too — and every error is a
:class:`RunFileError` naming the file, the key, the value and the allowed range, so nothing
starts on a file with an error in it.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import os
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gecko_agents._deprecation import renamed
from gecko_agents._run_directory import saved_run_id
from gecko_agents.diagnostics import MeaninglessRunError
from gecko_agents.history import RUN_FILES, History, invariant_violations
from gecko_agents.model.implicit import INTEGRATORS
from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.params import SetaArray
from gecko_agents.runfiles.schema import (
    PRESETS,
    PROTOCOL_PRESETS,
    SEGMENTS,
    Ctx,
    RunFileError,
    apply_params,
    build_protocol,
    find_preset,
    merge_quick,
    preset_docs,
    read_toml,
    sub_table,
)
from gecko_agents.runfiles.sweep import SWEEP_FILE_NAME, SweepSpec, load_sweep, point_functions

__all__ = [
    "RunFileError",
    "RunSpec",
    "SweepSpec",
    "PRESETS",
    "SEGMENTS",
    "PROTOCOL_PRESETS",
    "preset_docs",
    "point_functions",
    "read_run_file",
    "load_sweep",
    "execute_run",
    "RUN_FILE_NAME",
    "RUN_DIR_FILES",
    "SWEEP_FILE_NAME",
]

RUN_FILE_NAME = "run.toml"
"""Name of the run file's copy inside a run directory."""

MAX_DESCRIPTION = 2000
"""Longest run-file description [characters]: a line or a paragraph, echoed by ``run``."""

_MODEL_KEYS = {
    "n_sim": int,
    "seed": int,
    "dt_us": float,
    "record_setae": bool,
    "kernel": str,
    "integrator": str,
    "event_dt_us": float,
    "multirate": bool,
}
_MODEL_ARGS = {"dt_us": "dt", "event_dt_us": "event_dt"}  # run-file key → Model keyword
_MODEL_RANGES = {
    "integrator": f"one of {INTEGRATORS}",
    "seed": "an integer ≥ 0",
    "n_sim": "an integer in [1, array.count] (and at most gecko_agents.model.setup.MAX_N)",
    "dt_us": "a time step > 0 µs (below the stability bound the model states)",
    "event_dt_us": "a time step > 0 µs (the implicit step only)",
}


# Run files ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RunSpec:
    """A checked run file.

    Attributes
    ----------
    path : the run file; ``text`` its bytes (copied verbatim into the run directory).
    quick : whether the ``[quick]`` variant was taken.
    preset : preset name; ``overrides`` the ``[params]`` in effect (dotted name → value).
    params : the validated :class:`SetaArray`.
    model : keyword arguments of :class:`~gecko_agents.model.Model` (``n_sim``, ``seed``,
        ``dt``, ``record_setae``, ``kernel``, ``integrator``, ``event_dt``, ``multirate``; absent
        ones take the model's defaults).
    protocol : the protocol segments.
    description : the file's description (may be empty).
    resolved : the tables in effect (after ``--quick``), for metadata.json.
    """

    path: Path
    text: bytes
    quick: bool
    preset: str
    overrides: dict
    params: SetaArray
    model: dict
    protocol: list
    description: str = ""
    resolved: dict = field(default_factory=dict)
    floor_profile: object = None

    def build_model(self):
        """The :class:`~gecko_agents.model.Model` (its own checks reported as run-file errors)."""
        from gecko_agents.model import Model

        try:
            return Model.from_options(self.params, **self.model, floor_profile=self.floor_profile)
        except (ValueError, TypeError) as err:
            m = re.match(r"(n_sim|dt|event_dt|kernel|seed|integrator)\b", str(err))
            key = {v: k for k, v in _MODEL_ARGS.items()}.get(m.group(1), m.group(1)) if m else None
            where = f"[model] {key}" if key else "[model]"
            raise RunFileError(f"{self.path}: {where}: {err}") from None


_RUN_KEYS = {"description", "preset", "params", "model", "protocol", "quick", "floor"}
SCANS = {"dektak": "DEKTAK_PROFILE"}
"""``[floor] file`` names of the scans shipped in :mod:`gecko_agents.data`."""


def _floor(ctx: Ctx, table: dict):
    """The measured floor of a ``[floor]`` table (None without one): the scan from
    ``offset_um`` on, its start moved to x = 0."""
    if not table:
        return None
    ctx.keys("[floor]", table, {"file", "offset_um"})
    name = ctx.type_("[floor] file", table.get("file", ""), str)
    from gecko_agents import data, floor
    from gecko_agents.floor import readers

    path = getattr(data, SCANS[name]) if name in SCANS else ctx.path.parent / name
    if not name or not Path(path).is_file():
        raise ctx.error(
            "[floor] file",
            f"{name!r} is not a readable scan; give a path "
            f"(relative to the run file) or one of {', '.join(SCANS)}",
        )
    try:
        prof = readers.load(path)
    except (ValueError, OSError) as err:
        raise ctx.error("[floor] file", f"{name!r} cannot be read as a profile: {err}") from None
    offset = ctx.type_("[floor] offset_um", table.get("offset_um", 0.0), float)
    span = float(prof.x[-1] - prof.x[0])
    if not 0.0 <= offset < span:
        raise ctx.error("[floor] offset_um", f"{offset!r} is outside the scan, [0, {span:g}) µm")
    k = int(np.searchsorted(prof.x, prof.x[0] + offset))
    return floor.Profile(
        x=prof.x[k:] - prof.x[k], y=prof.y[k:], spacing=prof.spacing, source=prof.source
    )


_RUN_QUICK_KEYS = {"params", "model", "protocol"}


def _run_variant(ctx: Ctx, data: dict, quick: dict | None, path: Path, raw: bytes) -> RunSpec:
    """One variant of a run file; ``quick`` is the [quick] table it was merged with, if any."""
    quick_t = quick or {}
    name, base = find_preset(ctx, data)
    overrides = sub_table(ctx, data, "params")
    params = apply_params(ctx, base, overrides, "params", quick_t.get("params", {}))
    model_t = sub_table(ctx, data, "model")
    in_quick = quick_t.get("model", {})
    ctx.keys("[quick.model]" if quick else "[model]", model_t, _MODEL_KEYS)
    model: dict = {}
    for key, value in model_t.items():
        where = f"[{'quick.' if key in in_quick else ''}model] {key}"
        model[_MODEL_ARGS.get(key, key)] = ctx.type_(where, value, _MODEL_KEYS[key])
        bad = {
            "seed": lambda v: v < 0,
            "dt_us": lambda v: not 0 < v < float("inf"),
            "event_dt_us": lambda v: not 0 < v < float("inf"),
            "integrator": lambda v: v not in INTEGRATORS,
        }.get(key, lambda v: False)
        allowed = _MODEL_RANGES.get(key, "")
        if key == "n_sim":  # no more setae simulated than the array has
            allowed = allowed.replace("array.count", f"array.count = {params.array.count}")
            bad = lambda v: not 1 <= v <= params.array.count  # noqa: E731
        if bad(value):
            raise ctx.error(where, f"{value} must be {allowed}")
    if "protocol" not in data:
        raise ctx.error("[protocol]", "missing: give [[protocol]] segments or a [protocol] preset")
    segments = build_protocol(
        ctx, data["protocol"], "[quick.protocol]" if "protocol" in quick_t else "[protocol]"
    )
    description = ctx.type_("description", data.get("description", ""), str)
    if len(description) > MAX_DESCRIPTION:
        raise ctx.error(
            "description", f"has {len(description)} characters; at most {MAX_DESCRIPTION}"
        )
    resolved = {"preset": name, "params": overrides, "model": model_t, "protocol": data["protocol"]}
    floor_t = sub_table(ctx, data, "floor")
    if floor_t:
        resolved["floor"] = floor_t
    return RunSpec(
        path=path,
        text=raw,
        quick=quick is not None,
        preset=name,
        overrides=dict(overrides),
        params=params,
        model=model,
        protocol=segments,
        description=description,
        resolved=resolved,
        floor_profile=_floor(ctx, floor_t),
    )


def read_run_file(path, *, quick: bool = False) -> RunSpec:
    """Read and check a run file; with ``quick`` take its ``[quick]`` variant.

    Both variants are checked whichever is asked for. Without a ``[quick]`` table, ``quick``
    caps ``n_sim`` at 3 (not under a spherical probe, where a row of fewer pillars does not
    stand for the array: validity item ``probe_scale``).

    Raises
    ------
    RunFileError naming the file, the key, the value and the allowed range.
    """
    path, raw, data = read_toml(path)
    ctx = Ctx(path)
    ctx.keys("top level", data, _RUN_KEYS)
    quick_t = sub_table(ctx, data, "quick")
    ctx.keys("[quick]", quick_t, _RUN_QUICK_KEYS)
    full = _run_variant(ctx, {k: v for k, v in data.items() if k != "quick"}, None, path, raw)
    ctx.variant = " (in the --quick variant)"
    if "quick" in data:
        fast = _run_variant(
            ctx, merge_quick(ctx, data, quick_t, ("params", "model")), quick_t, path, raw
        )
    else:  # under a probe a row of fewer pillars does not scale to the array: no cap
        n = full.model.get("n_sim", full.params.array.count)
        n = n if full.params.floor.kind == "probe" else min(n, 3)
        fast = dataclasses.replace(full, quick=True, model={**full.model, "n_sim": n})
    return fast if quick else full


load_run = renamed(
    "gecko_agents.runfiles.run.load_run", "gecko_agents.runfiles.run.read_run_file", read_run_file
)


# Running -----------------------------------------------------------------------------------------
def _staging_dir(out: Path) -> Path:
    """This process's hidden sibling of ``out``; removes those left by killed processes."""
    for left in out.parent.glob(f".{out.name}.partial-*"):
        pid = left.name.rsplit("-", 1)[-1]
        if pid.isdigit() and int(pid) != os.getpid() and not _alive(int(pid)):
            shutil.rmtree(left, ignore_errors=True)
    return out.parent / f".{out.name}.partial-{os.getpid()}"


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists but belongs to someone else
        return True
    return True


RUN_DIR_FILES = (*RUN_FILES, RUN_FILE_NAME, "floor.png")
"""Every file :func:`execute_run` may write into a run directory; it writes and replaces no
other (files a user added to a run directory stay)."""


def _names(names: list[str], most: int = 5) -> str:
    shown = ", ".join(names[:most])
    return shown + (f" and {len(names) - most} more" if len(names) > most else "")


def _check_run_target(out: Path, animation: str | None) -> None:
    """Refuse, before anything runs: ``out`` a dangling link or a file; a folder that is not
    empty and not a run directory (one this function's runs write: a saved run's
    metadata.json beside run.toml), whose files a run must not touch; a run directory where
    one of the run's own file names is a folder; an animation format that cannot be written."""
    if out.is_symlink() and not out.exists():
        raise RunFileError(f"{out}: is a symbolic link to a missing target; choose another --out")
    if out.exists() and not out.is_dir():
        raise RunFileError(f"{out}: exists and is not a folder; choose another --out")
    entries = sorted(p.name for p in out.iterdir()) if out.exists() else []
    if entries and (saved_run_id(out) is None or not (out / RUN_FILE_NAME).is_file()):
        raise RunFileError(
            f"{out}: is not empty ({_names(entries)}) and is not a run directory (a saved run's "
            f"metadata.json beside its {RUN_FILE_NAME}); a run writes into a new or empty "
            "folder or replaces a run directory's own files: choose another --out"
        )
    clash = [n for n in RUN_DIR_FILES if (out / n).is_dir() or (out / n).is_symlink()]
    if clash:
        raise RunFileError(
            f"{out}: {_names(clash)} is a folder or link where the run writes a file; "
            "choose another --out"
        )
    if animation not in (None, "gif", "mp4"):
        raise ValueError(f"animation = {animation!r} must be None, 'gif' or 'mp4'")
    if animation == "mp4" and importlib.util.find_spec("imageio_ffmpeg") is None:
        raise RunFileError(
            "--mp4 needs the ffmpeg binary from imageio-ffmpeg: pip install -e '.[video]' "
            "(or use --gif)"
        )


def execute_run(
    spec: RunSpec,
    out,
    *,
    animation: str | None = None,
    progress: bool = True,
    argv: list[str] | None = None,
) -> tuple[Path, History]:
    """Run a checked run file and write its run directory ``out``.

    The directory holds ``history.csv``, ``metadata.json`` and ``setae.npz``
    (:meth:`History.save`), ``force_history.png``, ``floor.png`` (profile and PSD),
    ``detachment.gif``/``.mp4`` if
    ``animation`` is ``"gif"``/``"mp4"`` (per-seta recording is then switched on; it does not
    change the dynamics), and the run file copied verbatim as ``run.toml``. Everything is
    written into a hidden sibling directory whose files replace the run's own files in ``out``
    only once complete, so an interrupted or failed run leaves ``out`` as it was. ``out`` must
    be new, empty or a run directory; a run directory keeps every file a user added
    (:data:`RUN_DIR_FILES` are the only names written or removed).

    Raises
    ------
    RunFileError if ``out`` is a non-empty folder that is not a run directory (nothing is
    touched); whatever the run raises (nothing is written then).
    """
    out = Path(out)
    _check_run_target(out, animation)
    kwargs = dict(spec.model)
    if animation:
        kwargs["record_setae"] = True
    model = dataclasses.replace(spec, model=kwargs).build_model()
    out.parent.mkdir(parents=True, exist_ok=True)
    stage = _staging_dir(out)
    shutil.rmtree(stage, ignore_errors=True)
    try:
        history = model.run(spec.protocol, progress=progress)
        _refuse_untouched(history)
        history.meta["run_file"] = {
            "file": str(spec.path),
            "copy": RUN_FILE_NAME,
            "quick": spec.quick,
            "description": spec.description,
            "resolved": spec.resolved,
            "command": "gecko-agents run " + " ".join(argv or [str(spec.path)]),
            "invariant_violations": invariant_violations(history),
        }
        history.save(stage)
        atomic_write_bytes(stage / RUN_FILE_NAME, spec.text)
        from gecko_agents import render

        render.plot_history(history, stage / "force_history.png")
        from gecko_agents.render.floor_plots import plot_floor

        plot_floor(model.profile, stage / "floor.png", stats=history.meta["floor_statistics"])
        if animation:
            render.animate(history, stage / f"detachment.{animation}")
        _replace_dir(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return out, history


def _refuse_untouched(history: History) -> None:
    """MeaninglessRunError, before anything is written, if no tip ever attached: a run file's
    run exists to measure contact (the library lets a run travel freely; a run file does not)."""
    if float(np.max(history["n_attached"], initial=0.0)) > 0:
        return
    reach = float(history.meta["z_touch_um"]) - float(np.min(history["plate_y_um"]))
    raise MeaninglessRunError(
        f"no tip ever touched the floor: the plate came at most {reach:.3g} µm past the height "
        "at which a resting tip touches the floor's mean plane (negative: it stayed above it), "
        "so the run measured nothing; press to a positive depth, or slower if the plate went "
        "past the floor "
        "(the validity item quasi_static says how fast the setae follow)",
        history,
    )


def _replace_dir(stage: Path, out: Path) -> None:
    """Put the complete run of ``stage`` at ``out``. An existing run directory keeps every file
    that is not one of :data:`RUN_DIR_FILES`; its metadata.json goes first and comes back last,
    so a directory caught half-way never loads as a run."""
    if not out.exists():
        os.replace(stage, out)
        return
    (out / "metadata.json").unlink(missing_ok=True)
    produced = {p.name for p in stage.iterdir()}
    for name in RUN_DIR_FILES:  # a figure or animation of the previous run
        if name not in produced:
            (out / name).unlink(missing_ok=True)
    for name in [*sorted(produced - {"metadata.json"}), "metadata.json"]:
        os.replace(stage / name, out / name)
    stage.rmdir()
