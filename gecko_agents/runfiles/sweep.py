"""Sweep files: plain-text TOML records of a parameter sweep, checked before anything runs.

Units are those of :mod:`gecko_agents.params` (µm, µN, µs, ng). A sweep file names a point
function and the grid it runs on (:func:`gecko_agents.sweep.run_sweep`); the parameter and
quick-variant rules are those of run files (:mod:`gecko_agents.runfiles.run`).

Sweep file
----------
::

    preset = "PAPER_ARRAY"
    point = "quasistatic_preload_point"   # a function of gecko_agents.sweep.points
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
sets refuse, point arguments the point function does not take, the quick variant too — and
every error is a :class:`~gecko_agents.runfiles.schema.RunFileError` naming the file, the key,
the value and the allowed range.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass
from pathlib import Path

from gecko_agents import sweep
from gecko_agents.params import SetaArray
from gecko_agents.runfiles.schema import (
    Ctx,
    apply_params,
    find_preset,
    merge_quick,
    override_kind,
    read_toml,
    sub_table,
)
from gecko_agents.sweep.grid import FN_PREFIX
from gecko_agents.sweep.points import POINT_FUNCTIONS

__all__ = ["SweepSpec", "SWEEP_FILE_NAME", "point_functions", "load_sweep"]

SWEEP_FILE_NAME = "sweep.toml"
"""Name of the sweep file's copy inside a sweep's output directory."""


def point_functions() -> dict[str, object]:
    """Point functions a sweep file may name (:data:`gecko_agents.sweep.points.POINT_FUNCTIONS`)."""
    return dict(POINT_FUNCTIONS)


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


def _point_function(ctx: Ctx, data: dict) -> tuple[str, object, list[str]]:
    """(name, function, names of its keyword arguments) of the file's ``point``."""
    fns = point_functions()
    if "point" not in data:
        raise ctx.error("point", f"missing; name one of {', '.join(fns)}")
    point = ctx.type_("point", data["point"], str)
    if point not in fns:
        raise ctx.error("point", f"unknown point function {point!r}; allowed: {', '.join(fns)}")
    fn = fns[point]
    return point, fn, list(inspect.signature(fn).parameters)[2:]


def _check_grid(ctx: Ctx, base: SetaArray, point: str, kwargs: list[str], grid: dict) -> None:
    """Each grid entry: a point argument ``fn.<name>`` or a parameter with values it takes."""
    for key, values in grid.items():
        where = f"[grid] {key!r}"
        if isinstance(values, list) and values and isinstance(values[0], dict):
            raise ctx.error(where, "must be a list of values")
        if key.startswith(FN_PREFIX):
            if key[len(FN_PREFIX) :] not in kwargs:
                raise ctx.error(
                    where,
                    f"{key[len(FN_PREFIX) :]!r} is not an argument of {point}; "
                    f"allowed: {', '.join(kwargs)}",
                )
            continue
        kind = override_kind(base, key)
        if kind is None:
            raise ctx.error(
                where, "is not a parameter (see `gecko-agents params`) nor fn.<argument>"
            )
        ctx.type_(where, values, list, "a list of values")
        for v in values:
            ctx.type_(where, v, kind)
            try:
                base.replace(**{key: v})
            except (ValueError, TypeError) as err:
                raise ctx.error(where, str(err)) from None


def _check_point_args(ctx: Ctx, point: str, kwargs: list[str], point_args: dict) -> None:
    """Every fixed argument is one the point function takes."""
    for key in point_args:
        if key not in kwargs:
            raise ctx.error(
                f"[point_args] {key}",
                f"is not an argument of {point}; allowed: {', '.join(kwargs)}",
            )


def _check_required_args(ctx: Ctx, point: str, fn, point_args: dict, grid: dict) -> None:
    """Every argument without a default is given in [point_args] or swept as fn.<name>."""
    given = set(point_args) | {k[len(FN_PREFIX) :] for k in grid if k.startswith(FN_PREFIX)}
    for pname, p in list(inspect.signature(fn).parameters.items())[2:]:
        if p.default is inspect.Parameter.empty and pname not in given:
            raise ctx.error(
                "[point_args]",
                f"{point} needs {pname!r}: give it in [point_args] "
                f'or sweep it as "fn.{pname}" in [grid]',
            )


def _sweep_variant(ctx: Ctx, data: dict, quick: bool, path: Path, raw: bytes) -> SweepSpec:
    """One variant of a sweep file (``data`` already merged with [quick] if ``quick``)."""
    name, base_preset = find_preset(ctx, data)
    overrides = sub_table(ctx, data, "params")
    base = apply_params(ctx, base_preset, overrides, "params")
    point, fn, kwargs = _point_function(ctx, data)
    point_args = sub_table(ctx, data, "point_args")
    grid = sub_table(ctx, data, "grid")
    _check_point_args(ctx, point, kwargs, point_args)
    _check_grid(ctx, base, point, kwargs, grid)
    _check_required_args(ctx, point, fn, point_args, grid)
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
        description=ctx.type_("description", data.get("description", ""), str),
    )


def load_sweep(path, *, quick: bool = False) -> SweepSpec:
    """Read and check a sweep file (both variants); with ``quick`` take its ``[quick]`` one.

    Raises
    ------
    RunFileError naming the file, the key, the value and the allowed range.
    """
    path, raw, data = read_toml(path)
    ctx = Ctx(path)
    ctx.keys("top level", data, _SWEEP_KEYS)
    quick_t = sub_table(ctx, data, "quick")
    ctx.keys("[quick]", quick_t, _SWEEP_QUICK_KEYS)
    full = _sweep_variant(ctx, {k: v for k, v in data.items() if k != "quick"}, False, path, raw)
    ctx.variant = " (in the --quick variant)"
    fast = _sweep_variant(
        ctx, merge_quick(ctx, data, quick_t, ("params", "point_args", "grid")), True, path, raw
    )
    return fast if quick else full
