"""The points of a sweep: the Cartesian product of parameter overrides × seeds, checked.

A sweep's ``grid`` maps a dotted parameter name (as in
:meth:`~gecko_agents.params.SetaArray.replace`) or ``"fn.<name>"`` (a keyword argument of the
point function) to a list of values; every combination runs once per seed. Units are those of
:mod:`gecko_agents.params`. Everything here is checked before anything runs: a bad grid or
seed list raises ValueError naming the culprit. Used by :func:`gecko_agents.sweep.run_sweep`
and by the sweep-file checks (:mod:`gecko_agents.runfiles.sweep`).
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from gecko_agents.params import SetaArray, check_seed

__all__ = ["FN_PREFIX", "SweepPoint", "expand_grid", "canonical_json", "plain"]

FN_PREFIX = "fn."
"""Grid names with this prefix sweep a keyword argument of the point function."""


@dataclass(frozen=True)
class SweepPoint:
    """One point of a sweep.

    Attributes
    ----------
    overrides : grid name → value for this point (the grid's names, in grid order).
    seed : seed handed to the point function (≥ 0).
    params : ``base`` with the parameter overrides applied, already validated.
    fn_overrides : point-function keyword arguments from ``"fn.<name>"`` grid entries.
    """

    overrides: dict
    seed: int
    params: SetaArray
    fn_overrides: dict = field(default_factory=dict)


def plain(value):
    """numpy scalars → Python scalars (JSON and the parameter checks want Python numbers)."""
    return value.item() if isinstance(value, np.generic) else value


def canonical_json(obj) -> str:
    """JSON with sorted keys and no spaces: equal objects give equal text (and hashes)."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=True)


def _grid_values(base: SetaArray, name: str, vals) -> list:
    """The checked list of values of one grid entry (a ValueError names the entry)."""
    if isinstance(vals, np.ndarray) and vals.ndim == 1:
        vals = vals.tolist()
    if isinstance(vals, str | bytes) or not isinstance(vals, Sequence):
        raise ValueError(f"sweep grid[{name!r}] must be a list of values, got {vals!r}")
    vals = [plain(v) for v in vals]
    if not vals:
        raise ValueError(f"sweep grid[{name!r}] is an empty list of values")
    repeated = [v for i, v in enumerate(vals) if v in vals[:i]]
    if repeated:
        raise ValueError(f"sweep grid[{name!r}] repeats the value(s) {repeated}")
    if name.startswith(FN_PREFIX):
        if not name[len(FN_PREFIX) :].isidentifier():
            raise ValueError(
                f"sweep grid[{name!r}]: {name[len(FN_PREFIX) :]!r} is not a keyword argument name"
            )
        try:
            canonical_json(vals)
        except TypeError as err:
            raise ValueError(
                f"sweep grid[{name!r}] values must be JSON-serialisable: {err}"
            ) from err
        return vals
    try:
        base.replace(**{name: vals[0]})
    except (ValueError, TypeError) as err:
        raise ValueError(f"sweep grid[{name!r}]: {err}") from err
    return vals


def _checked_seeds(seeds: Sequence[int]) -> list[int]:
    seeds = [plain(s) for s in seeds]
    if not seeds:
        raise ValueError("sweep seeds is empty: give at least one seed")
    for s in seeds:  # the range every seed of the package has (params.check_seed)
        if isinstance(s, bool) or not isinstance(s, int):
            raise ValueError(f"sweep seed {s!r} must be an integer in [0, 2**63)")
        check_seed(s, "sweep seed")
    repeated = sorted({s for i, s in enumerate(seeds) if s in seeds[:i]})
    if repeated:
        raise ValueError(f"sweep seeds repeat the seed(s) {repeated}")
    return seeds


def expand_grid(
    base: SetaArray, grid: dict[str, Sequence], seeds: Sequence[int]
) -> list[SweepPoint]:
    """Every point of ``grid`` × ``seeds``, each with its validated parameter set.

    Order: :func:`itertools.product` over the grid's values in the dict's order (the first name
    varies slowest), with the seeds innermost. An empty grid gives one point per seed on
    ``base``.

    Raises
    ------
    ValueError naming the culprit for: a grid name that is not a parameter, a value list that is
    empty, not a list or has repeated values, a value the parameter refuses, no seeds, a seed
    that is not an integer in [0, 2**63), repeated seeds, or two points with identical
    parameters and seed.
    Every point's :class:`SetaArray` is built here, so nothing has run when this raises.
    """
    if not isinstance(base, SetaArray):
        raise TypeError(f"base must be a SetaArray, got {type(base).__name__}")
    if not isinstance(grid, dict):
        raise TypeError(
            f"grid must be a dict of parameter name → list of values, got {type(grid).__name__}"
        )
    values = {name: _grid_values(base, name, vals) for name, vals in grid.items()}
    seeds = _checked_seeds(seeds)

    points: list[SweepPoint] = []
    seen: dict[str, dict] = {}
    for combo in itertools.product(*values.values()):
        overrides = dict(zip(values, combo, strict=True))
        fn_over = {k[len(FN_PREFIX) :]: v for k, v in overrides.items() if k.startswith(FN_PREFIX)}
        try:
            params = base.replace(
                **{k: v for k, v in overrides.items() if not k.startswith(FN_PREFIX)}
            )
        except (ValueError, TypeError) as err:
            raise ValueError(f"sweep point {overrides}: {err}") from err
        for seed in seeds:
            ident = canonical_json([params.to_dict(), fn_over, seed])
            if ident in seen:
                raise ValueError(
                    f"sweep points {seen[ident]} and {overrides} have identical "
                    f"parameters (seed {seed})"
                )
            seen[ident] = overrides
            points.append(SweepPoint(overrides, seed, params, fn_over))
    return points
