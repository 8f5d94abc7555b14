"""Run files and sweep files: plain-text TOML records of exactly what was simulated.

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
    n_sim = 1                          # simulated setae, 1–20 000 (default: array.count)
    seed = 1                           # run seed ≥ 0 (default: floor.seed)
    dt_us = 0.01                       # time step [µs] (default: 0.75/ω_max)
    record_setae = true                # per-seta arrays (animations need them)
    kernel = "auto"                    # auto | numpy | numba | python

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

Sweep file
----------
::

    preset = "PAPER_ARRAY"
    point = "quasistatic_preload_point"   # a point function of gecko_agents.sweep
    seeds = [0, 1]
    out_dir = "sweeps/roughness"          # optional (default sweeps/<file stem>), cwd-relative
    workers = 2                           # optional: local worker processes (1 = serial)
    [params]                              # base overrides, as in a run file
    [grid]                                # dotted parameter name or fn.<kwarg> → list
    "floor.sigma" = [0.5, 1.0]
    "fn.preload_uN" = [1e6, 3e6]
    [point_args]                          # fixed keyword arguments of the point function
    n_blocks = 1000
    [quick]                               # --quick: [quick.params], [quick.grid] and
                                          # [quick.point_args] merge, quick.seeds and
                                          # quick.workers replace

Everything is checked when the file is loaded — unknown keys, wrong types, values the parameter
sets or protocol segments refuse, the quick variant too — and every error is a
:class:`RunFileError` naming the file, the key, the value and the allowed range, so nothing
starts on a file with an error in it.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib.util
import inspect
import os
import re
import shutil
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from . import params as params_mod
from . import protocol as prot
from .history import History, atomic_write_bytes, invariant_violations
from .params import SetaArray

__all__ = [
    "RunFileError",
    "RunSpec",
    "SweepSpec",
    "PRESETS",
    "SEGMENTS",
    "PROTOCOL_PRESETS",
    "preset_docs",
    "point_functions",
    "load_run",
    "load_sweep",
    "execute_run",
    "RUN_FILE_NAME",
    "SWEEP_FILE_NAME",
]

RUN_FILE_NAME = "run.toml"
"""Name of the run file's copy inside a run directory."""
SWEEP_FILE_NAME = "sweep.toml"
"""Name of the sweep file's copy inside a sweep's output directory."""


class RunFileError(ValueError):
    """A run or sweep file that cannot be run; the message names the file and the key."""


def _discover_presets() -> dict[str, SetaArray]:
    return {
        name: value
        for name, value in vars(params_mod).items()
        if name.isupper() and isinstance(value, SetaArray)
    }


PRESETS: dict[str, SetaArray] = _discover_presets()
"""Parameter presets by name: every upper-case :class:`SetaArray` of :mod:`gecko_agents.params`."""


def preset_docs() -> dict[str, str]:
    """Each preset's docstring (the string literal after its assignment in params.py)."""
    try:
        tree = ast.parse(inspect.getsource(params_mod))
    except (OSError, TypeError, SyntaxError):
        return {}
    out: dict[str, str] = {}
    body = tree.body
    for node, nxt in zip(body, body[1:], strict=False):
        if (
            isinstance(node, ast.Assign)
            and len(node.targets) == 1
            and isinstance(node.targets[0], ast.Name)
            and node.targets[0].id in PRESETS
            and isinstance(nxt, ast.Expr)
            and isinstance(nxt.value, ast.Constant)
            and isinstance(nxt.value.value, str)
        ):
            out[node.targets[0].id] = inspect.cleandoc(nxt.value.value)
    return out


# Protocol schema: run-file key → constructor argument --------------------------------------------
SEGMENTS: dict[str, tuple[type, dict[str, str]]] = {
    "move": (prot.Move, {"dx_um": "dx", "dy_um": "dy", "speed_um_per_us": "speed"}),
    "press_to": (prot.PressTo, {"depth_um": "depth", "speed_um_per_us": "speed"}),
    "press": (prot.Press, {"preload_uN": "preload", "speed_um_per_us": "speed", "band": "band"}),
    "hold": (prot.Hold, {"duration_us": "duration"}),
    "pull_off": (
        prot.PullOff,
        {
            "speed_um_per_us": "speed",
            "angle_deg": "angle_deg",
            "clearance_um": "clearance",
            "max_travel_um": "max_travel",
        },
    ),
}
"""Segment name → (class of :mod:`gecko_agents.protocol`, run-file key → field)."""

PROTOCOL_PRESETS: dict[str, tuple[object, dict[str, str]]] = {
    "press_pull": (prot.press_pull, {"depth_um": "depth", "speed_um_per_us": "speed"}),
    "preload_pull": (prot.preload_pull, {"preload_uN": "preload", "speed_um_per_us": "speed"}),
    "drag_pull": (
        prot.drag_pull,
        {
            "preload_uN": "preload",
            "drag_um": "drag",
            "angle_deg": "angle_deg",
            "speed_um_per_us": "speed",
        },
    ),
}
"""Preset protocol name → (function of :mod:`gecko_agents.protocol`, run-file key → argument)."""

_MODEL_KEYS = {"n_sim": int, "seed": int, "dt_us": float, "record_setae": bool, "kernel": str}
_MODEL_RANGES = {
    "seed": "an integer ≥ 0",
    "n_sim": "an integer in [1, 20000]",
    "dt_us": "a time step > 0 µs (below the stability bound the model states)",
}
_TYPE_NAMES = {
    int: "an integer",
    float: "a number",
    bool: "true or false",
    str: "a string",
    dict: "a table",
    list: "an array",
}


# Small checks ----------------------------------------------------------------------------------
class _Ctx:
    """Where we are in a file, for error messages."""

    def __init__(self, path: Path):
        self.path = path
        self.variant = ""

    def error(self, where: str, message: str) -> RunFileError:
        return RunFileError(f"{self.path}: {where}: {message}{self.variant}")

    def type_(self, where: str, value, kind: type, what: str = ""):
        ok = (
            isinstance(value, bool)
            if kind is bool
            else isinstance(value, int) and not isinstance(value, bool)
            if kind is int
            else isinstance(value, int | float) and not isinstance(value, bool)
            if kind is float
            else isinstance(value, kind)
        )
        if not ok:
            raise self.error(where, f"{value!r} must be {what or _TYPE_NAMES[kind]}")
        return float(value) if kind is float else value

    def keys(self, where: str, table: dict, allowed) -> None:
        unknown = [k for k in table if k not in allowed]
        if unknown:
            raise self.error(
                where, f"unknown key {unknown[0]!r}; allowed keys: {', '.join(sorted(allowed))}"
            )


def _read_toml(path) -> tuple[Path, bytes, dict]:
    path = Path(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise RunFileError(f"{path}: no such file") from None
    except OSError as err:
        raise RunFileError(f"{path}: cannot be read: {err}") from err
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as err:
        raise RunFileError(f"{path}: is not UTF-8 text: {err}") from err
    except tomllib.TOMLDecodeError as err:
        raise RunFileError(f"{path}: is not valid TOML: {err}") from err
    return path, raw, data


def _preset(ctx: _Ctx, data: dict) -> tuple[str, SetaArray]:
    if "preset" not in data:
        inside = [k for k, v in data.items() if isinstance(v, dict) and "preset" in v]
        hint = (
            f" (preset sits in [{inside[0]}]: top-level keys go above the first [table] header)"
            if inside
            else ""
        )
        raise ctx.error("preset", f"missing; name one of {', '.join(PRESETS)}{hint}")
    name = ctx.type_("preset", data["preset"], str)
    for key, value in PRESETS.items():
        if key.lower() == name.lower():
            return key, value
    raise ctx.error("preset", f"unknown preset {name!r}; allowed: {', '.join(PRESETS)}")


def _override_kind(base: SetaArray, dotted: str):
    """Expected type of a dotted parameter (from the preset's current value), or None."""
    part, _, name = dotted.partition(".")
    obj = base if not name else getattr(base, part, None)
    attr = part if not name else name
    if obj is None or not dataclasses.is_dataclass(obj):
        return None
    fields = {f.name: f for f in dataclasses.fields(obj)}
    if attr not in fields or dataclasses.is_dataclass(getattr(obj, attr)):
        return None
    current = getattr(obj, attr)
    if isinstance(current, bool):
        return bool
    if isinstance(current, str):
        return str
    if isinstance(current, int) and "int" in str(fields[attr].type):
        return int
    return float


def _apply_params(
    ctx: _Ctx, base: SetaArray, overrides: dict, table: str, quick_keys=()
) -> SetaArray:
    """``base`` with the overrides applied one by one, so an error names its key."""
    out = base
    for key, value in overrides.items():
        where = f"[{'quick.' if key in quick_keys else ''}{table}] {key!r}"
        kind = _override_kind(base, key)
        if kind is None:
            try:
                base.replace(**{key: value})
            except (ValueError, TypeError) as err:
                raise ctx.error(where, f"{err} (see `gecko-agents params`)") from None
            raise ctx.error(where, "is not a parameter (see `gecko-agents params`)")
        value = ctx.type_(where, value, kind)
        try:
            out = out.replace(**{key: value})
        except (ValueError, TypeError) as err:
            raise ctx.error(where, str(err)) from None
    return out


def _table(ctx: _Ctx, data: dict, key: str, where: str | None = None) -> dict:
    value = data.get(key, {})
    return ctx.type_(where or f"[{key}]", value, dict)


def _culprit(err: Exception, mapping: dict[str, str]) -> str | None:
    """The run-file key whose field a protocol ValueError names (``PressTo.depth = …``)."""
    m = re.match(r"\w+\.(\w+) = ", str(err))
    if m:
        for key, fname in mapping.items():
            if fname == m.group(1):
                return key
    return None


def _build_call(
    ctx: _Ctx, where: str, func, mapping: dict[str, str], table: dict, skip: str
) -> object:
    ctx.keys(where, table, {skip, *mapping})
    kwargs = {}
    for key, value in table.items():
        if key == skip:
            continue
        kwargs[mapping[key]] = ctx.type_(f"{where} {key}", value, float)
    sig = inspect.signature(func)
    inverse = {v: k for k, v in mapping.items()}
    for name, p in sig.parameters.items():
        if p.default is inspect.Parameter.empty and name not in kwargs:
            raise ctx.error(where, f"missing required key {inverse.get(name, name)!r}")
    try:
        return func(**kwargs)
    except (ValueError, TypeError) as err:
        key = _culprit(err, mapping)
        at = f"{where} {key}" if key else where
        raise ctx.error(at, str(err)) from None


def _protocol(ctx: _Ctx, spec, where: str) -> list:
    """Protocol segments from an array of segment tables or one preset table."""
    if isinstance(spec, dict):
        if "preset" not in spec:
            raise ctx.error(
                where,
                "a [protocol] table needs preset = one of "
                f"{', '.join(PROTOCOL_PRESETS)} (or use [[protocol]] "
                "segments)",
            )
        name = ctx.type_(f"{where} preset", spec["preset"], str)
        if name not in PROTOCOL_PRESETS:
            raise ctx.error(
                f"{where} preset",
                f"unknown protocol preset {name!r}; allowed: {', '.join(PROTOCOL_PRESETS)}",
            )
        func, mapping = PROTOCOL_PRESETS[name]
        return list(_build_call(ctx, f"{where} ({name})", func, mapping, spec, "preset"))
    if not isinstance(spec, list) or not spec:
        raise ctx.error(
            where, "must be [[protocol]] segment tables or a [protocol] table with a preset"
        )
    segments = []
    for i, seg in enumerate(spec, 1):
        at = f"{where} segment {i}"
        seg = ctx.type_(at, seg, dict)
        if "segment" not in seg:
            raise ctx.error(at, f"missing key 'segment' = one of {', '.join(SEGMENTS)}")
        kind = ctx.type_(f"{at} segment", seg["segment"], str)
        if kind not in SEGMENTS:
            raise ctx.error(
                f"{at} segment", f"unknown segment {kind!r}; allowed: {', '.join(SEGMENTS)}"
            )
        cls, mapping = SEGMENTS[kind]
        segments.append(_build_call(ctx, f"{at} ({kind})", cls, mapping, seg, "segment"))
    return segments


def _merge(ctx: _Ctx, data: dict, quick: dict, tables: tuple[str, ...]) -> dict:
    """``data`` with the quick tables merged into (or, for the rest, replacing) its own."""
    out = dict(data)
    for key, value in quick.items():
        if key in tables:
            out[key] = {**_table(ctx, data, key), **_table(ctx, quick, key, f"[quick.{key}]")}
        else:
            out[key] = value
    return out


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
        ``dt``, ``record_setae``, ``kernel``; absent ones take the model's defaults).
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

    def build_model(self):
        """The :class:`~gecko_agents.model.Model` (its own checks reported as run-file errors)."""
        from .model import Model

        try:
            return Model(self.params, **self.model)
        except (ValueError, TypeError) as err:
            m = re.match(r"(n_sim|dt|kernel|seed)\b", str(err))
            key = {"dt": "dt_us"}.get(m.group(1), m.group(1)) if m else None
            where = f"[model] {key}" if key else "[model]"
            raise RunFileError(f"{self.path}: {where}: {err}") from None


_RUN_KEYS = {"description", "preset", "params", "model", "protocol", "quick"}
_RUN_QUICK_KEYS = {"params", "model", "protocol"}


def _run_variant(ctx: _Ctx, data: dict, quick: dict | None, path: Path, raw: bytes) -> RunSpec:
    """One variant of a run file; ``quick`` is the [quick] table it was merged with, if any."""
    quick_t = quick or {}
    name, base = _preset(ctx, data)
    overrides = _table(ctx, data, "params")
    params = _apply_params(ctx, base, overrides, "params", quick_t.get("params", {}))
    model_t = _table(ctx, data, "model")
    in_quick = quick_t.get("model", {})
    ctx.keys("[quick.model]" if quick else "[model]", model_t, _MODEL_KEYS)
    model: dict = {}
    for key, value in model_t.items():
        where = f"[{'quick.' if key in in_quick else ''}model] {key}"
        model[{"dt_us": "dt"}.get(key, key)] = ctx.type_(where, value, _MODEL_KEYS[key])
        bad = {
            "seed": lambda v: v < 0,
            "n_sim": lambda v: v < 1,
            "dt_us": lambda v: not 0 < v < float("inf"),
        }.get(key, lambda v: False)
        if bad(value):
            raise ctx.error(where, f"{value} must be {_MODEL_RANGES[key]}")
    if "protocol" not in data:
        raise ctx.error("[protocol]", "missing: give [[protocol]] segments or a [protocol] preset")
    segments = _protocol(
        ctx, data["protocol"], "[quick.protocol]" if "protocol" in quick_t else "[protocol]"
    )
    description = ctx.type_("description", data.get("description", ""), str)
    resolved = {"preset": name, "params": overrides, "model": model_t, "protocol": data["protocol"]}
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
    )


def load_run(path, *, quick: bool = False) -> RunSpec:
    """Read and check a run file; with ``quick`` take its ``[quick]`` variant.

    Both variants are checked whichever is asked for. Without a ``[quick]`` table, ``quick``
    caps ``n_sim`` at 3.

    Raises
    ------
    RunFileError naming the file, the key, the value and the allowed range.
    """
    path, raw, data = _read_toml(path)
    ctx = _Ctx(path)
    ctx.keys("top level", data, _RUN_KEYS)
    quick_t = _table(ctx, data, "quick")
    ctx.keys("[quick]", quick_t, _RUN_QUICK_KEYS)
    full = _run_variant(ctx, {k: v for k, v in data.items() if k != "quick"}, None, path, raw)
    ctx.variant = " (in the --quick variant)"
    if "quick" in data:
        fast = _run_variant(
            ctx, _merge(ctx, data, quick_t, ("params", "model")), quick_t, path, raw
        )
    else:
        n = min(full.model.get("n_sim", full.params.array.count), 3)
        fast = dataclasses.replace(full, quick=True, model={**full.model, "n_sim": n})
    return fast if quick else full


# Sweep files -------------------------------------------------------------------------------------
def point_functions() -> dict[str, object]:
    """Point functions a sweep file may name: the ``*_point`` functions of gecko_agents.sweep."""
    from . import sweep

    return {
        name: getattr(sweep, name)
        for name in sweep.__all__
        if name.endswith("_point") and callable(getattr(sweep, name))
    }


@dataclass(frozen=True)
class SweepSpec:
    """A checked sweep file: arguments of :func:`gecko_agents.sweep.run_sweep` and more.

    Attributes
    ----------
    path, text, quick, preset, overrides, description : as in :class:`RunSpec`.
    base : the base :class:`SetaArray` (preset + ``[params]``).
    point : the point function's name; ``point_fn`` its ``"module:function"`` name.
    point_args : fixed keyword arguments of the point function.
    grid : dotted name (or ``fn.<kwarg>``) → list of values; ``seeds`` the seeds.
    out_dir : the output directory; ``workers`` local worker processes (None: all cores).
    n_points : grid points × seeds.
    """

    path: Path
    text: bytes
    quick: bool
    preset: str
    overrides: dict
    base: SetaArray
    point: str
    point_fn: str
    point_args: dict
    grid: dict
    seeds: list
    out_dir: Path
    workers: int | None
    n_points: int
    description: str = ""


_SWEEP_KEYS = {
    "description",
    "preset",
    "params",
    "point",
    "point_args",
    "grid",
    "seeds",
    "out_dir",
    "workers",
    "quick",
}
_SWEEP_QUICK_KEYS = {"params", "point_args", "grid", "seeds", "workers"}


def _sweep_variant(ctx: _Ctx, data: dict, quick: bool, path: Path, raw: bytes) -> SweepSpec:
    from . import sweep

    name, base_preset = _preset(ctx, data)
    overrides = _table(ctx, data, "params")
    base = _apply_params(ctx, base_preset, overrides, "params")
    fns = point_functions()
    if "point" not in data:
        raise ctx.error("point", f"missing; name one of {', '.join(fns)}")
    point = ctx.type_("point", data["point"], str)
    if point not in fns:
        raise ctx.error("point", f"unknown point function {point!r}; allowed: {', '.join(fns)}")
    fn = fns[point]
    point_args = _table(ctx, data, "point_args")
    grid = _table(ctx, data, "grid")
    sig = inspect.signature(fn)
    kwargs = [n for n in list(sig.parameters)[2:]]
    for key in point_args:
        if key not in kwargs:
            raise ctx.error(
                f"[point_args] {key}",
                f"is not an argument of {point}; allowed: {', '.join(kwargs)}",
            )
    for key, values in grid.items():
        if isinstance(values, list) and values and isinstance(values[0], dict):
            raise ctx.error(f"[grid] {key!r}", "must be a list of values")
        if key.startswith(sweep.FN_PREFIX) and key[len(sweep.FN_PREFIX) :] not in kwargs:
            raise ctx.error(
                f"[grid] {key!r}",
                f"{key[len(sweep.FN_PREFIX) :]!r} is not an "
                f"argument of {point}; allowed: "
                f"{', '.join(kwargs)}",
            )
        if not key.startswith(sweep.FN_PREFIX):
            kind = _override_kind(base, key)
            if kind is None:
                raise ctx.error(
                    f"[grid] {key!r}",
                    "is not a parameter (see `gecko-agents params`) nor fn.<argument>",
                )
            ctx.type_(f"[grid] {key!r}", values, list, "a list of values")
            for v in values:
                ctx.type_(f"[grid] {key!r}", v, kind)
                try:
                    base.replace(**{key: v})
                except (ValueError, TypeError) as err:
                    raise ctx.error(f"[grid] {key!r}", str(err)) from None
    given = set(point_args) | {
        k[len(sweep.FN_PREFIX) :] for k in grid if k.startswith(sweep.FN_PREFIX)
    }
    for pname, p in list(sig.parameters.items())[2:]:
        if p.default is inspect.Parameter.empty and pname not in given:
            raise ctx.error(
                "[point_args]",
                f"{point} needs {pname!r}: give it in [point_args] "
                f'or sweep it as "fn.{pname}" in [grid]',
            )
    seeds = ctx.type_("seeds", data.get("seeds", [0]), list, "an array of integers ≥ 0")
    try:
        points = sweep.expand_grid(base, grid, seeds)
    except (ValueError, TypeError) as err:
        raise ctx.error(
            "[grid]" if "grid" in str(err) or "point" in str(err) else "seeds", str(err)
        ) from None
    out_dir = Path(ctx.type_("out_dir", data.get("out_dir", f"sweeps/{path.stem}"), str))
    workers = data.get("workers")
    if workers is not None:
        workers = ctx.type_("workers", workers, int)
        if workers < 1:
            raise ctx.error("workers", f"{workers} must be an integer ≥ 1")
    description = ctx.type_("description", data.get("description", ""), str)
    return SweepSpec(
        path=path,
        text=raw,
        quick=quick,
        preset=name,
        overrides=dict(overrides),
        base=base,
        point=point,
        point_fn=f"{fn.__module__}:{fn.__qualname__}",
        point_args=dict(point_args),
        grid=dict(grid),
        seeds=list(seeds),
        out_dir=out_dir,
        workers=workers,
        n_points=len(points),
        description=description,
    )


def load_sweep(path, *, quick: bool = False) -> SweepSpec:
    """Read and check a sweep file (both variants); with ``quick`` take its ``[quick]`` one.

    Raises
    ------
    RunFileError naming the file, the key, the value and the allowed range.
    """
    path, raw, data = _read_toml(path)
    ctx = _Ctx(path)
    ctx.keys("top level", data, _SWEEP_KEYS)
    quick_t = _table(ctx, data, "quick")
    ctx.keys("[quick]", quick_t, _SWEEP_QUICK_KEYS)
    full = _sweep_variant(ctx, {k: v for k, v in data.items() if k != "quick"}, False, path, raw)
    ctx.variant = " (in the --quick variant)"
    fast = _sweep_variant(
        ctx, _merge(ctx, data, quick_t, ("params", "point_args", "grid")), True, path, raw
    )
    return fast if quick else full


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
    written into a hidden sibling directory that replaces ``out`` only once complete, so an
    interrupted or failed run leaves ``out`` as it was.

    Raises
    ------
    RunFileError if ``out`` exists and is not a run directory (it would be replaced); whatever
    the run raises (nothing is written then).
    """
    out = Path(out)
    if out.exists() and not (
        out.is_dir() and ((out / RUN_FILE_NAME).is_file() or not any(out.iterdir()))
    ):
        raise RunFileError(
            f"{out}: exists and is not a run directory (no {RUN_FILE_NAME}); choose another --out"
        )
    if animation not in (None, "gif", "mp4"):
        raise ValueError(f"animation = {animation!r} must be None, 'gif' or 'mp4'")
    if animation == "mp4" and importlib.util.find_spec("imageio_ffmpeg") is None:
        raise RunFileError(
            "--mp4 needs the ffmpeg binary from imageio-ffmpeg: pip install -e '.[video]' "
            "(or use --gif)"
        )
    kwargs = dict(spec.model)
    if animation:
        kwargs["record_setae"] = True
    model = dataclasses.replace(spec, model=kwargs).build_model()
    out.parent.mkdir(parents=True, exist_ok=True)
    stage = _staging_dir(out)
    shutil.rmtree(stage, ignore_errors=True)
    try:
        history = model.run(spec.protocol, progress=progress)
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
        from . import render

        render.plot_history(history, stage / "force_history.png")
        from .floor_plots import plot_floor

        plot_floor(model.profile, stage / "floor.png", stats=history.meta["floor_statistics"])
        if animation:
            render.animate(history, stage / f"detachment.{animation}")
        _replace_dir(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return out, history


def _replace_dir(stage: Path, out: Path) -> None:
    """Put the complete ``stage`` at ``out`` (replacing an older run directory there)."""
    if out.exists():
        old = out.parent / f".{out.name}.old-{os.getpid()}"
        shutil.rmtree(old, ignore_errors=True)
        os.replace(out, old)
        os.replace(stage, out)
        shutil.rmtree(old, ignore_errors=True)
    else:
        os.replace(stage, out)
