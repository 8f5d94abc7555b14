"""The pull of a load–(drag–)pull: the release point and the pull-off, each defined once.

The pull phase is every record from the end of the drag
(:func:`gecko_agents.analysis.drag.drag_span`; without a drag, from the press's largest force)
to the end of the history.

* **Release point** — the record of the largest force |F| = √(F⊥² + F∥²) the seta held *in
  tension* in the pull: the limit it withstood, the point of a limit curve
  (:mod:`gecko_agents.analysis.limit_curve`). Not the last step before the tip lets go: a
  film's last steps, its pad nearly peeled and its friction gone with it, are a 90° peel of a
  sliver whatever the pull; and a pushed-over seta's pull starts with a compression larger than
  any tension it then holds, which is no release. A pull that never reaches tension has no
  release in tension; its release point is then the record of its largest force
  (:attr:`Release.in_tension` is False).
* **Pull-off** — the record of the largest adhesion (tensile normal force) of the pull; the
  pull-off force is that adhesion, 0 if the pull never reaches tension.

Units: µN. Sign convention: the history's ``force_normal_uN`` is positive in compression,
negative in tension; here **adhesion = −force_normal_uN**, > 0 in tension. Shear = the
tangential force on the tips ``force_tangential_uN``, > 0 along +x (the direction the setae
lean).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gecko_agents.analysis.drag import drag_span

__all__ = [
    "Release",
    "release_index",
    "pull_off_index",
    "pull_start",
    "release_point",
    "pull_off",
    "plate_pull_off",
]


@dataclass(frozen=True)
class Release:
    """The forces at one record of a pull.

    Attributes
    ----------
    index : the record (row of the history).
    adhesion : −normal force [µN], > 0 in tension.
    shear : tangential force [µN], > 0 along +x.
    """

    index: int
    adhesion: float
    shear: float

    @property
    def force(self) -> float:
        """|F| = √(adhesion² + shear²) [µN]."""
        return float(np.hypot(self.adhesion, self.shear))

    @property
    def in_tension(self) -> bool:
        """Whether the seta pulled on the floor there (adhesion > 0)."""
        return self.adhesion > 0.0


def release_index(adhesion, shear) -> int:
    """Index of the largest |F| among the samples in tension (adhesion > 0 [µN]); of the largest
    |F| overall if none is in tension.

    Parameters
    ----------
    adhesion, shear : arrays [µN] of the same length, adhesion > 0 in tension.
    """
    adhesion, shear = np.asarray(adhesion, dtype=float), np.asarray(shear, dtype=float)
    force = np.hypot(adhesion, shear)
    tension = adhesion > 0.0
    return int(np.argmax(np.where(tension, force, -np.inf) if tension.any() else force))


def pull_off_index(adhesion) -> int:
    """Index of the largest adhesion [µN] (> 0 in tension); the first such sample."""
    return int(np.argmax(np.asarray(adhesion, dtype=float)))


def pull_start(h, drag: float | None = None) -> int:
    """First record of the pull phase: the end of the drag span (:func:`drag_span`)."""
    return drag_span(h, drag)[1]


def _pull(h, drag):
    k0 = pull_start(h, drag)
    return k0, -h["force_normal_uN"][k0:], h["force_tangential_uN"][k0:]


def release_point(h, drag: float | None = None) -> Release:
    """The release point of the pull: the largest force held in tension (module docstring).

    Parameters
    ----------
    h : History with ``force_normal_uN``, ``force_tangential_uN`` and the plate's position.
    drag : the drag [µm] before the pull (> 0 along +x, 0 none); ``None`` reads it from the
        protocol (:func:`gecko_agents.analysis.drag.drag_of`).
    """
    k0, adhesion, shear = _pull(h, drag)
    k = release_index(adhesion, shear)
    return Release(k0 + k, float(adhesion[k]), float(shear[k]))


def plate_pull_off(h, drag: float | None = None) -> float:
    """The pull-off a load cell on the plate reads [µN] (≥ 0): the largest pull of the setae on
    the plate over the pull, −``plate_force_y_uN`` (the vertical plate force; > 0 in tension).

    :func:`pull_off` sums the contacts' normal forces instead; the two differ where the
    contacts' normals tilt from the vertical, as under a spherical probe (1.6 % for pillars on
    its 15° slope) or a rough floor, because a test machine weighs only the vertical force.
    """
    k0 = pull_start(h, drag)
    return float(max(0.0, -np.min(np.asarray(h["plate_force_y_uN"][k0:], dtype=float))))


def pull_off(h, drag: float | None = None) -> Release:
    """The pull-off of the pull: the record of its largest adhesion, adhesion clipped at 0.

    ``pull_off(h, drag).adhesion`` is the pull-off force [µN] (≥ 0); ``.shear`` the shear
    carried at that record.
    """
    k0, adhesion, shear = _pull(h, drag)
    k = pull_off_index(adhesion)
    return Release(k0 + k, float(max(0.0, adhesion[k])), float(shear[k]))
