"""The drag of a load–drag–pull (:func:`gecko_agents.protocol.drag_pull`) in a recorded history.

Where the drag starts and ends among the records, whether the tip let go during it, and the
seta's lean at its end.

Units: µm, degrees. Sign conventions: x positive in the direction the setae lean; a drag
``drag`` [µm] > 0 moves the plate along +x (releasing: the seta is pushed over its tip),
< 0 along −x (gripping: the seta is pulled back along its shaft). Every function takes a
:class:`~gecko_agents.history.History` (or any mapping with the same columns) and the drag
[µm]; without a drag argument it is read from the history's protocol (``meta["protocol"]``).
"""

from __future__ import annotations

import math
import re

import numpy as np

__all__ = ["drag_of", "drag_span", "let_go_in_drag", "lean_after_drag"]

MOVED_UM = 1e-9
"""Plate travel [µm] above which the plate has left where it was (rounding is far below)."""

AT_END_UM = 1e-6
"""Distance [µm] within which the plate is at the drag's end (a Move lands on it exactly)."""

_MOVE = re.compile(r"Move\(dx=([^,)]+)")


def drag_of(h) -> float:
    """The drag [µm] of a history's protocol: ``dx`` of its :class:`~gecko_agents.protocol.Move`
    segment as recorded in ``h.meta["protocol"]``; 0 if it has none.

    Raises
    ------
    ValueError
        If the protocol has more than one sideways move (not a load–drag–pull).
    """
    moves = [float(m.group(1)) for seg in h.meta.get("protocol", ()) if (m := _MOVE.match(seg))]
    moves = [dx for dx in moves if dx != 0.0]
    if len(moves) > 1:
        raise ValueError(f"protocol has {len(moves)} sideways moves; give the drag explicitly")
    return moves[0] if moves else 0.0


def _drag(h, drag):
    return drag_of(h) if drag is None else drag


def drag_span(h, drag: float | None = None) -> tuple[int, int]:
    """Indices of the records where the drag starts and ends.

    Start: the last record before the plate moves along x. End: the first record with the
    plate at its start + ``drag`` [µm] (within ``AT_END_UM``) and still at the drag's
    height; if that record was not kept (``record_every`` > 1), the last record at the drag's
    height, before the pull lifted the plate (a pull along the floor, at 0° or 180°, never
    lifts it: keep every record for those). Without a drag (``drag == 0``) both are the
    record of the press's largest normal force, so the pull phase
    (:mod:`gecko_agents.analysis.pull`) starts there.

    Parameters
    ----------
    h : History, with ``plate_x_um``, ``plate_y_um`` and ``force_normal_uN``.
    drag : the drag [µm] (> 0 along +x); ``None`` reads it from the protocol (:func:`drag_of`).

    Returns
    -------
    (start, end) : record indices, start ≤ end.
    """
    drag = _drag(h, drag)
    px = np.asarray(h["plate_x_um"])
    if drag == 0:
        k = int(np.argmax(h["force_normal_uN"]))
        return k, k
    moved = np.flatnonzero(np.abs(px - px[0]) > MOVED_UM)
    if not moved.size:
        raise ValueError(f"the plate never moves along x; no drag of {drag} µm in this history")
    start = int(moved[0]) - 1
    py = np.asarray(h["plate_y_um"])
    on_line = np.abs(py - py[start + 1]) <= MOVED_UM  # the drag keeps the plate's height
    at_end = np.flatnonzero((np.abs(px - (px[0] + drag)) < AT_END_UM) & on_line)
    if at_end.size:
        return start, int(at_end[0])
    off_line = np.flatnonzero(~on_line[start + 1 :])
    end = start + int(off_line[0]) if off_line.size else len(px) - 1
    return start, end


def let_go_in_drag(h, drag: float | None = None) -> float:
    """How far the plate had dragged [µm, > 0] when a tip first let go during the drag.

    A tip lets go where ``n_attached`` drops between successive records of the drag span
    (:func:`drag_span`); the distance is the plate's travel along x from the drag's start.

    Returns
    -------
    float : the travel [µm], or NaN if every tip held through the drag.
    """
    start, end = drag_span(h, drag)
    px, attached = np.asarray(h["plate_x_um"]), np.asarray(h["n_attached"])
    drops = np.flatnonzero(np.diff(attached[start : end + 1]) < 0)
    return float(abs(px[start + drops[0] + 1] - px[start])) if len(drops) else math.nan


def lean_after_drag(h, drag: float | None = None, seta: int = 0) -> float:
    """The seta's angle from the floor [degrees] at the end of the drag.

    Measured from −x as the seta angle θ is: atan2(root height above the tip, tip x − root x).
    θ at rest; > 90°: the root has passed over the tip, the seta flipped; < 0°: folded flat,
    its root below the tip's centre. Needs per-seta records (``record_setae=True``).

    Parameters
    ----------
    h : History with per-seta ``tip_x_um``, ``tip_y_um`` and the roots' offsets from the
        plate ``geometry["root_dx_um"]``, ``geometry["root_dy_um"]``.
    drag : the drag [µm]; ``None`` reads it from the protocol.
    seta : which seta (column of the per-seta arrays).
    """
    k = drag_span(h, drag)[1]
    px, py = h["plate_x_um"], h["plate_y_um"]
    tx, ty = h.setae["tip_x_um"][k, seta], h.setae["tip_y_um"][k, seta]
    root_x = px[k] + float(h.geometry["root_dx_um"][seta])
    root_y = py[k] + float(h.geometry["root_dy_um"][seta])
    return math.degrees(math.atan2(root_y - ty, tx - root_x))
