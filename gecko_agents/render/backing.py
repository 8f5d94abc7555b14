"""The elastic backing in the detachment animation: where the strip and its detachment front
are at each frame, read from ``history.meta["backing"]``
(:meth:`gecko_agents.backing.elastic.ElasticModel.run`).

Units: µm, µs. The backing is recorded on its own clock (``time_us``, one entry per backing
record); each animation frame takes the backing record nearest in time. ``nodes_x_um`` and
``nodes_y_um`` (when recorded) hold, per backing record, the strip's n + 1 node positions in the
frame of the seta roots and tips. ``front_x_um`` is the detachment front as a *material*
abscissa of the strip (the root abscissa ``root_dx_um`` of the attached seta nearest the pulled
side, measured on the straight strip; NaN when nothing is attached).

The links are rigid, so a material abscissa a lies on the straight segment between the two
nodes around it, at the fraction given by a between their material abscissae: linear
interpolation along the nodes is exact, whatever the strip's bending or tilt.
"""

from __future__ import annotations

import numpy as np

__all__ = ["BackingTrack", "nearest_records"]


def nearest_records(t_records: np.ndarray, t_frames: np.ndarray) -> np.ndarray:
    """Index into ``t_records`` [µs] (sorted ascending) of the record nearest each time in
    ``t_frames`` [µs]; a tie goes to the earlier record."""
    t_records = np.asarray(t_records, dtype=float)
    t_frames = np.asarray(t_frames, dtype=float)
    if len(t_records) == 1:
        return np.zeros(len(t_frames), dtype=int)
    right = np.clip(np.searchsorted(t_records, t_frames), 1, len(t_records) - 1)
    left = right - 1
    later = (t_records[right] - t_frames) < (t_frames - t_records[left])
    return np.where(later, right, left)


class BackingTrack:
    """The strip's geometry at each record of a History with an elastic backing.

    Parameters
    ----------
    backing : ``history.meta["backing"]``: needs ``time_us`` [µs] and ``front_x_um`` [µm];
        ``nodes_x_um`` and ``nodes_y_um`` [µm] (lists of node positions per backing record),
        ``node_abscissae_um`` (the nodes' material abscissae, recorded by a strip with a leader
        arm) or else ``length_um`` (strip length) are used when present.
    times : the History's ``time_us`` [µs], one per record.

    Attributes
    ----------
    record : backing record drawn at each History record (nearest in time), shape (n_records,).
    has_nodes : whether the strip's nodes were recorded (else only the front is known).
    """

    def __init__(self, backing: dict, times):
        t_b = np.asarray(backing["time_us"], dtype=float)
        if t_b.size == 0:
            raise ValueError('history.meta["backing"] has no records (empty time_us)')
        self.record = nearest_records(t_b, times)
        front = backing.get("front_x_um", np.full(t_b.size, np.nan))
        self.front = np.asarray(front, dtype=float)
        self.has_nodes = "nodes_x_um" in backing and "nodes_y_um" in backing
        if self.has_nodes:
            self.nodes_x = np.asarray(backing["nodes_x_um"], dtype=float)
            self.nodes_y = np.asarray(backing["nodes_y_um"], dtype=float)
            if self.nodes_x.shape != self.nodes_y.shape or self.nodes_x.shape[0] != t_b.size:
                raise ValueError(
                    f'history.meta["backing"]: nodes_x_um {self.nodes_x.shape} and nodes_y_um '
                    f"{self.nodes_y.shape} must both be (backing records = {t_b.size}, nodes)"
                )
            if "node_abscissae_um" in backing:  # a leader arm: links beyond the pad
                self.material = np.asarray(backing["node_abscissae_um"], dtype=float)
            else:
                self.material = self._material_abscissae(backing.get("length_um"))
            if self.material.shape != self.nodes_x.shape[1:]:
                raise ValueError(
                    f'history.meta["backing"]: {self.material.size} node abscissae for '
                    f"{self.nodes_x.shape[1]} nodes"
                )

    def _material_abscissae(self, length) -> np.ndarray:
        """Abscissae [µm] of the nodes on the straight strip, centred on 0 like the roots'.

        The strip spans [−length/2, length/2] in equal links; without ``length_um``, the length
        is the first record's polyline length (the links are rigid, so any record's would do).
        """
        if length is None:
            length = float(np.hypot(*np.diff([self.nodes_x[0], self.nodes_y[0]], axis=1)).sum())
        return np.linspace(-0.5 * length, 0.5 * length, self.nodes_x.shape[1])

    def nodes(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The strip's node positions (x, y) [µm] at History record ``k``."""
        j = self.record[k]
        return self.nodes_x[j], self.nodes_y[j]

    def on_strip(self, k: int, abscissa) -> tuple[np.ndarray, np.ndarray]:
        """Where the strip's material points at ``abscissa`` [µm] are at History record ``k``."""
        x, y = self.nodes(k)
        return np.interp(abscissa, self.material, x), np.interp(abscissa, self.material, y)

    def front_abscissa(self, k: int) -> float:
        """Detachment front at History record ``k``: material abscissa [µm], NaN if none."""
        return float(self.front[self.record[k]])

    def extent(self) -> tuple[float, float, float, float] | None:
        """(x min, x max, y min, y max) [µm] of every recorded node; None without nodes."""
        if not self.has_nodes or self.nodes_x.size == 0:
            return None
        x, y = self.nodes_x, self.nodes_y
        return float(x.min()), float(x.max()), float(y.min()), float(y.max())
