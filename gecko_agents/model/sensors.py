"""Lazy detection on a pad floor: a tip has its sensor in the pymunk space only while it is
within a thin band around the sensor's edge, the only place where a begin or separate can
happen; pymunk delivers those events, and the flags of the other tips follow from where they
are (:meth:`LazySensors.update` says why they equal full detection's).

Units: µm, µs (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["LazySensors"]


class LazySensors:
    """The sensors of lazy detection (:class:`gecko_agents.model.world.World`,
    ``detection = "lazy"``).

    Parameters
    ----------
    state : the per-seta state (``xy``, ``pv``, ``candidate``). h : the pads' heights [µm].
    sensor_radius : [µm]. space : the pymunk space. sensors, pad_shapes : each tip's sensor
        circle and pad segment (they join and leave the space together).

    Attributes
    ----------
    in_space : the tips whose sensors are in the space (bool (N,)).
    removing : sensors are being taken out (the world ignores the separates that fires).
    geometric_flips : flags changed without a pymunk event (a tip that jumped the band).
    """

    band = 0.05
    """Rounding margin of lazy detection [µm] (see :meth:`update`)."""

    def __init__(self, state, h, sensor_radius, space, sensors, pad_shapes):
        self.state, self.h, self.sensor_radius = state, h, sensor_radius
        self.space, self.sensors, self.pad_shapes = space, sensors, pad_shapes
        n = len(sensors)
        self.in_space = np.zeros(n, dtype=bool)
        self._want = np.zeros(n, dtype=bool)
        self._g = np.zeros(n)
        self._w = np.zeros(n)
        self._d = np.zeros(n)
        self._primed = False
        self.removing = False
        self.geometric_flips = 0

    def update(self, dt: float) -> None:
        """Lazy detection: before a step of ``dt`` [µs], give sensors to the tips near the
        sensor's edge, take them from the others and set the others' flags.

        Reads ``state.xy`` (2, N) [µm], the positions x + v·dt that pymunk integrates the tips
        to and detects collisions at (the model's step leaves them there), and ``state.pv``.

        Why the flags equal full detection's. A sensor of radius r_s overlaps its pad, a horizontal
        window at height h reaching more than r_s beyond the tip on both sides
        (:meth:`gecko_agents.model.world.World.recentre_pads`), exactly when the gap g = |y − h| <
        r_s: pymunk finds the window's closest point (x, h) and tests distance² < r_s². Tip i keeps
        a sensor this step iff |g − r_s| ≤ m_i = ``band`` + 2·|v_y|·dt. Those tips are tested by
        pymunk as under full detection. The others are at least m_i ≥ ``band`` = 0.05 µm from the
        edge, ~10¹⁰ times the rounding of g and of pymunk's distance (µm-sized numbers, relative
        precision 1e-16), so their overlap is decided by the sign of g − r_s and set here: True
        inside (g < r_s − m_i), False outside. A tip whose sensor joins this step starts False, so
        only a begin from pymunk in this step makes it True; a sensor leaving the space fires a
        separate, which is ignored (the flag is set from g as for any tip without a sensor). Hence
        after every step ``state.candidate`` is the overlap of every sensor with its pad at the
        step's positions, as full detection gives it.

        Why pymunk still delivers the events. A flag changes only when g crosses r_s. The
        band's 2·|v_y|·dt term holds a tip moving at up to twice its current vertical speed
        in the band on the step it crosses, so the crossing is seen by pymunk's callbacks;
        a tip that jumps across the whole band in one step is still set right, and is counted
        in ``geometric_flips`` (0 in the tests and benchmarks: see ``tests/test_world.py``).
        """
        s, r_s = self.state, self.sensor_radius
        g, m, want = self._g, self._w, self._want
        np.subtract(s.xy[1], self.h, out=g)
        np.abs(g, out=g)
        np.abs(s.pv[3], out=m)
        m *= 2.0 * dt
        m += self.band
        d = self._d
        np.subtract(g, r_s, out=d)
        inside = d < 0.0
        np.abs(d, out=d)
        np.less_equal(d, m, out=want)
        cand, have = s.candidate, self.in_space
        if not np.array_equal(want, have):
            space, sensors, pads = self.space, self.sensors, self.pad_shapes
            leave = np.flatnonzero(have & ~want)
            join = np.flatnonzero(want & ~have)
            if leave.size:
                self.removing = True
                try:
                    space.remove(*(sensors[i] for i in leave))
                    space.remove(*(pads[i] for i in leave))
                finally:
                    self.removing = False
            if join.size:
                cand[join] = False  # a begin in this step makes it True
                space.add(*(pads[i] for i in join))
                space.add(*(sensors[i] for i in join))
            np.copyto(have, want)
        free = ~want
        if self._primed:  # the first step sets the flags pymunk's first begins would
            self.geometric_flips += int(np.count_nonzero((cand != inside) & free))
        self._primed = True
        np.copyto(cand, inside, where=free)
