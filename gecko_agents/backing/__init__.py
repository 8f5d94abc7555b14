"""Backings: what holds the seta roots. A :class:`gecko_agents.model.Model` holds one, chosen
by ``params.backing.kind`` (:data:`BACKINGS`): the rigid plate of the paper
(:class:`~gecko_agents.backing.rigid.RigidBacking`, which also states the interface) or an
elastic strip pulled through a handle spring
(:class:`~gecko_agents.backing.elastic.ElasticBacking`) or an elastic layer bonded to the holder
(:class:`~gecko_agents.backing.layer.LayerBacking`)."""

from __future__ import annotations

from gecko_agents.backing.elastic import ElasticBacking
from gecko_agents.backing.layer import LayerBacking
from gecko_agents.backing.rigid import RigidBacking

__all__ = ["BACKINGS", "backing_class", "ElasticBacking", "LayerBacking", "RigidBacking"]

BACKINGS = {"rigid": RigidBacking, "elastic": ElasticBacking, "layer": LayerBacking}
"""The backing class of each ``params.backing.kind``."""


def backing_class(kind: str):
    """The backing class of ``params.backing.kind`` = ``kind``."""
    if kind not in BACKINGS:
        raise ValueError(f"backing.kind = {kind!r}: choose one of {sorted(BACKINGS)}")
    return BACKINGS[kind]
