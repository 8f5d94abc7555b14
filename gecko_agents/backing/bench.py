"""A pressed elastic-backing model, the set-up of :func:`gecko_agents.bench.pressed_model` with
``backing.kind = "elastic"``: what the pad peel starts from and what the elastic backing's cost
is measured on.

The chain's pivots are solved directly, O(links) per step (:mod:`gecko_agents.backing.pivots`),
so the strip adds a cost per step proportional to its links, not to their square.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY

__all__ = ["elastic_pressed_model"]


def elastic_pressed_model(
    n: int, depth: float = 0.3, settle: int = 200, params=None, **model_kw
) -> Model:
    """:func:`gecko_agents.bench.pressed_model` on an elastic strip: handle, strip and tips
    moved ``depth`` [µm] below touch-down, then ``settle`` steps of rest, every tip attached.
    ``params``: the array (default: the paper's on a flat floor with the default
    :class:`gecko_agents.params.Backing`, uniform drive), with ``n`` setae; ``model_kw`` go to
    :class:`gecko_agents.model.Model` (``seed``, ``leader_arm``, ... for
    :class:`gecko_agents.backing.elastic.ElasticBacking`)."""
    if params is None:
        params = PAPER_ARRAY.replace(**{"floor.sigma": 0.0, "backing.kind": "elastic"})
    m = Model(params.replace(**{"array.count": int(n)}), **model_kw)
    plate_y = m.z_touch - depth
    drop = plate_y - m.plate.position.y
    m.plate.position = (m.plate.position.x, plate_y)
    rest = np.column_stack([m.world.rest_dx, m.world.rest_dy + plate_y])
    for body, xy in zip(m.tips, rest, strict=True):
        body.position = (float(xy[0]), float(xy[1]))
        body.velocity = (0.0, 0.0)
    strip = m.backing.strip
    for link in strip.links:
        link.position = (link.position.x, link.position.y + drop)
    strip.rows = strip.read()
    m.reset_state_arrays()
    for _ in range(settle):
        m.step((0.0, 0.0))
    if not np.all(m.attached):
        raise RuntimeError(f"only {int(m.attached.sum())} of {n} tips attached after settling")
    return m
