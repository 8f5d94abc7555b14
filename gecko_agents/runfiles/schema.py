"""What run files and sweep files share: presets, parameter overrides, protocol segments, and
errors that name the file, the key, the value and the allowed range.

Units are those of :mod:`gecko_agents.params` (µm, µN, µs, ng); protocol keys carry their unit
in their name (``depth_um``, ``speed_um_per_us``, ``preload_uN``, ``duration_us``, …). The file
formats themselves are described in :mod:`gecko_agents.runfiles.run` and
:mod:`gecko_agents.runfiles.sweep`; every check here raises :class:`RunFileError`.
"""

from __future__ import annotations

import ast
import dataclasses
import inspect
import json
import re
import tomllib
from pathlib import Path

from gecko_agents import params as params_mod
from gecko_agents import protocol as prot
from gecko_agents.params import SetaArray
from gecko_agents.params import presets as presets_mod

__all__ = [
    "RunFileError",
    "PRESETS",
    "SEGMENTS",
    "PROTOCOL_PRESETS",
    "preset_docs",
    "Ctx",
    "read_toml",
    "find_preset",
    "override_kind",
    "apply_params",
    "sub_table",
    "build_protocol",
    "merge_quick",
]


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
    """Each preset's docstring (the string literal after its assignment in params/presets.py)."""
    try:
        tree = ast.parse(inspect.getsource(presets_mod))
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

_TYPE_NAMES = {
    int: "an integer",
    float: "a number",
    bool: "true or false",
    str: "a string",
    dict: "a table",
    list: "an array",
}


# Small checks ----------------------------------------------------------------------------------
class Ctx:
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


def read_toml(path) -> tuple[Path, bytes, dict]:
    path = Path(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise RunFileError(f"{path}: no such file") from None
    except OSError as err:
        raise RunFileError(f"{path}: cannot be read: {err}") from err
    if raw.startswith(b"\xef\xbb\xbf"):
        raise RunFileError(
            f"{path}: starts with a UTF-8 byte-order mark (BOM), which TOML does not allow; "
            "save it as UTF-8 without a BOM"
        )
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as err:
        raise RunFileError(f"{path}: is not UTF-8 text: {err}") from err
    except tomllib.TOMLDecodeError as err:
        raise RunFileError(f"{path}: is not valid TOML: {err}") from err
    return path, raw, data


def find_preset(ctx: Ctx, data: dict) -> tuple[str, SetaArray]:
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


def override_kind(base: SetaArray, dotted: str):
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


def apply_params(
    ctx: Ctx, base: SetaArray, overrides: dict, table: str, quick_keys=()
) -> SetaArray:
    """``base`` with the overrides, applied together (a constraint between fields, such as
    ``floor.kind = "probe"`` with ``floor.sigma = 0``, holds whatever their order); if that
    fails the error names the key or keys to blame (``_culprits``)."""
    typed = {}
    for key, value in overrides.items():
        where = f"[{'quick.' if key in quick_keys else ''}{table}] {key!r}"
        if isinstance(value, dict):  # a nested table, [params.seta]: say it in TOML
            head = f"[{'quick.' if key in quick_keys else ''}{table}]"
            lines = "; ".join(f'"{key}.{k}" = {_toml_value(v)}' for k, v in value.items())
            lines = lines or f'"{key}.<field>" = <value>'
            raise ctx.error(
                where,
                f"is a nested table ([{table}.{key}]); give its fields by dotted name under "
                f"{head} instead: {lines}",
            )
        kind = override_kind(base, key)
        if kind is None:
            try:
                base.replace(**{key: value})
            except (ValueError, TypeError) as err:
                raise ctx.error(where, f"{err} (see `gecko-agents params`)") from None
            raise ctx.error(where, "is not a parameter (see `gecko-agents params`)")
        typed[key] = ctx.type_(where, value, kind)
    try:
        return base.replace(**typed)
    except (ValueError, TypeError) as err:
        culprits = _culprits(base, typed, str(err))
        where = ", ".join(f"[{'quick.' if k in quick_keys else ''}{table}] {k!r}" for k in culprits)
        raise ctx.error(where or f"[{table}]", str(err)) from None


def _culprits(base: SetaArray, typed: dict, message: str) -> list[str]:
    """The overrides to blame for ``base.replace(**typed)`` failing with ``message``: those
    without which the rest is accepted (a constraint between fields, such as ``floor.kind =
    "probe"`` with ``floor.sigma = 0``, holds whatever else fails), else those whose field the
    message names."""
    alone = []
    for key in typed:
        try:
            base.replace(**{k: v for k, v in typed.items() if k != key})
        except (ValueError, TypeError):
            continue
        alone.append(key)
    named = [k for k in typed if re.search(rf"\b{re.escape(k)}\b", message, re.IGNORECASE)]
    return [k for k in alone if k in named] or alone or named


def _toml_value(value) -> str:
    """A value as TOML writes it (for advice in error messages)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    return repr(value)


def sub_table(ctx: Ctx, data: dict, key: str, where: str | None = None) -> dict:
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
    ctx: Ctx, where: str, func, mapping: dict[str, str], table: dict, skip: str
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


def build_protocol(ctx: Ctx, spec, where: str) -> list:
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


def merge_quick(ctx: Ctx, data: dict, quick: dict, tables: tuple[str, ...]) -> dict:
    """``data`` with the quick tables merged into (or, for the rest, replacing) its own."""
    out = dict(data)
    for key, value in quick.items():
        if key in tables:
            out[key] = {**sub_table(ctx, data, key), **sub_table(ctx, quick, key, f"[quick.{key}]")}
        else:
            out[key] = value
    return out
