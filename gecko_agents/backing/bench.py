"""A pressed elastic-backing model, the set-up of :func:`gecko_agents.bench.pressed_model` with
``backing.kind = "elastic"``: what the pad peel starts from and what the elastic backing's cost
is measured on.

The chain's pivots are solved directly, O(links) per step (:mod:`gecko_agents.backing.pivots`),
so the strip adds a cost per step proportional to its links, not to their square.
"""

from __future__ import annotations

from gecko_agents.bench import place_pressed, settle_attached
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY

__all__ = ["elastic_pressed_model"]


def elastic_pressed_model(
    n: int, depth: float = 0.3, settle: int = 200, params=None, **model_kw
) -> Model:
    """:func:`gecko_agents.bench.pressed_model` on an elastic strip: handle, strip and tips
    moved ``depth`` [µm] below touch-down, then ``settle`` steps of rest, every tip attached.
    ``params``: the array (default: the paper's on a flat floor with the default
    :class:`gecko_agents.params.backing.Backing`, uniform drive), with ``n`` setae; ``model_kw`` go
    to
    :class:`gecko_agents.model.Model` (``seed``, ``leader_arm``, ... for
    :class:`gecko_agents.backing.elastic.ElasticBacking`)."""
    if params is None:
        params = PAPER_ARRAY.replace(**{"floor.sigma": 0.0, "backing.kind": "elastic"})
    m = Model(params.replace(**{"array.count": int(n)}), **model_kw)
    drop = place_pressed(m, depth)
    strip = m.backing.strip  # the strip moves down with its handle
    for link in strip.links:
        link.position = (link.position.x, link.position.y + drop)
    strip.rows = strip.read()
    return settle_attached(m, settle)
