"""The elastic backing in the detachment animation: where the strip and its detachment front
are at each record, read from the History's backing records
(:class:`gecko_agents.backing.elastic.ElasticBacking`, recorded by
:class:`gecko_agents.model.recorder.Recorder`).

Units: µm. ``history.backing["strip_node_x_um"]`` and ``["strip_node_y_um"]`` hold, per record,
the strip's n + 1 node positions in the frame of the seta roots and tips;
``history.geometry["strip_node_abscissa_um"]`` the nodes' material abscissae (on the straight
strip, the pad centred on 0). ``history["strip_front_x_um"]`` is the detachment front as a
*material* abscissa of the strip (the root abscissa ``root_dx_um`` of the attached seta nearest
the pulled side; NaN when nothing is attached).

The links are rigid, so a material abscissa a lies on the straight segment between the two
nodes around it, at the fraction given by a between their material abscissae: linear
interpolation along the nodes is exact, whatever the strip's bending or tilt.
"""

from __future__ import annotations

import numpy as np

__all__ = ["BackingTrack"]


class BackingTrack:
    """The strip's geometry at each record of a History with an elastic backing.

    Parameters
    ----------
    history : a :class:`~gecko_agents.history.History` with the column ``strip_front_x_um``
        [µm]; the nodes ``history.backing["strip_node_x_um"]``, ``["strip_node_y_um"]`` [µm]
        (n_records, nodes) and their abscissae ``geometry["strip_node_abscissa_um"]`` [µm]
        are drawn when present (else only the front is known).

    Attributes
    ----------
    has_nodes : whether the strip's nodes were recorded.
    """

    def __init__(self, history):
        self.front = np.asarray(history["strip_front_x_um"], dtype=float)
        b = history.backing
        self.has_nodes = "strip_node_x_um" in b and "strip_node_y_um" in b
        if self.has_nodes:
            self.nodes_x = np.asarray(b["strip_node_x_um"], dtype=float)
            self.nodes_y = np.asarray(b["strip_node_y_um"], dtype=float)
            if self.nodes_x.shape != self.nodes_y.shape or self.nodes_x.shape[0] != len(history):
                raise ValueError(
                    f"history.backing: strip_node_x_um {self.nodes_x.shape} and "
                    f"strip_node_y_um {self.nodes_y.shape} must both be (records = "
                    f"{len(history)}, nodes)"
                )
            self.material = np.asarray(history.geometry["strip_node_abscissa_um"], dtype=float)
            if self.material.shape != self.nodes_x.shape[1:]:
                raise ValueError(
                    f'history.geometry["strip_node_abscissa_um"]: {self.material.size} node '
                    f"abscissae for {self.nodes_x.shape[1]} nodes"
                )

    @classmethod
    def of(cls, history) -> BackingTrack | None:
        """The track of ``history``, or None when it has no elastic backing's records."""
        return cls(history) if "strip_front_x_um" in history.scalars else None

    def nodes(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The strip's node positions (x, y) [µm] at record ``k``."""
        return self.nodes_x[k], self.nodes_y[k]

    def on_strip(self, k: int, abscissa) -> tuple[np.ndarray, np.ndarray]:
        """Where the strip's material points at ``abscissa`` [µm] are at record ``k``."""
        x, y = self.nodes(k)
        return np.interp(abscissa, self.material, x), np.interp(abscissa, self.material, y)

    def front_abscissa(self, k: int) -> float:
        """Detachment front at record ``k``: material abscissa [µm], NaN if none."""
        return float(self.front[k])

    def extent(self) -> tuple[float, float, float, float] | None:
        """(x min, x max, y min, y max) [µm] of every recorded node; None without nodes."""
        if not self.has_nodes or self.nodes_x.size == 0:
            return None
        x, y = self.nodes_x, self.nodes_y
        return float(x.min()), float(x.max()), float(y.min()), float(y.max())
