"""The seta mechanics by name (``params.mechanics``): what the engine runs each with.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["MECHANICS", "Mechanics"]


@dataclass(frozen=True)
class Mechanics:
    """What the engine runs one seta mechanics (``params.mechanics``) with.

    Attributes
    ----------
    name : the ``params.mechanics`` value.
    jacobian : the implicit step has this mechanics' stiffness (its Jacobian); without it,
        the explicit step only.
    loops : the pad loops (:mod:`gecko_agents.model.step_loop`, kernels "numba" and
        "python") solve it; without them, the numpy kernel only.
    independent : each seta is one tip body, stepped alone by a multirate step
        (:mod:`gecko_agents.model.multirate`); the elastica's chain is not.
    """

    name: str
    jacobian: bool
    loops: bool
    independent: bool


MECHANICS = {
    "linear": Mechanics("linear", jacobian=True, loops=True, independent=True),
    "rod": Mechanics("rod", jacobian=True, loops=True, independent=True),
    "elastica": Mechanics("elastica", jacobian=False, loops=False, independent=False),
}
"""The seta mechanics by the name ``params.mechanics`` selects (eq 16–21: the linear beam;
the rod of large rotations; the elastica's chain, :mod:`gecko_agents.physics.elastica`)."""
