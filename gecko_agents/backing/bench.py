"""Cost of the elastic backing: seta-steps per second of a pressed elastic-backing model, the
set-up of :func:`gecko_agents.bench.pressed_model` with ``backing.kind = "elastic"``.

The issue's target: an elastic backing costs at most 2× the rigid plate per seta-step at
N = 10 000 (``backing_rate(n, steps)`` beside :func:`gecko_agents.bench.agent_rate` of
:func:`gecko_agents.bench.pressed_model`; N = 10 000 is a strip of 1 516 links). The chain's
pivots are solved directly, O(links) per step (:mod:`gecko_agents.backing.pivots`), so the
strip adds a cost per step proportional to its links, not to their square.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.backing.elastic import ElasticModel
from gecko_agents.bench import agent_rate
from gecko_agents.params import PAPER_ARRAY

__all__ = ["elastic_pressed_model", "backing_rate"]


def elastic_pressed_model(
    n: int, depth: float = 0.3, settle: int = 200, params=None, **model_kw
) -> ElasticModel:
    """:func:`gecko_agents.bench.pressed_model` on an elastic strip: handle, strip and tips
    moved ``depth`` [µm] below touch-down, then ``settle`` steps of rest, every tip attached.
    ``params``: the array (default: the paper's on a flat floor with the default
    :class:`gecko_agents.params.Backing`, uniform drive), with ``n`` setae; ``model_kw`` go to
    :class:`gecko_agents.backing.elastic.ElasticModel` (``seed``, ``leader_arm``, ...)."""
    if params is None:
        params = PAPER_ARRAY.replace(**{"floor.sigma": 0.0, "backing.kind": "elastic"})
    m = ElasticModel(params.replace(**{"array.count": int(n)}), **model_kw)
    plate_y = m.z_touch - depth
    drop = plate_y - m.plate.position.y
    m.plate.position = (m.plate.position.x, plate_y)
    rest = np.column_stack([m.world.rest_dx, m.world.rest_dy + plate_y])
    for body, xy in zip(m.tips, rest, strict=True):
        body.position = (float(xy[0]), float(xy[1]))
        body.velocity = (0.0, 0.0)
    for link in m.strip.links:
        link.position = (link.position.x, link.position.y + drop)
    m.strip.rows = m.strip.read()
    m.reset_state_arrays()
    for _ in range(settle):
        m.step((0.0, 0.0))
    if not np.all(m.attached):
        raise RuntimeError(f"only {int(m.attached.sum())} of {n} tips attached after settling")
    return m


def backing_rate(n: int, steps: int) -> float:
    """Seta-steps per second of an elastic-backing model of ``n`` setae, pressed
    (:func:`elastic_pressed_model`), through a ``steps``-step downward plate move
    (:func:`gecko_agents.bench.agent_rate`)."""
    return agent_rate(elastic_pressed_model(n), steps)
