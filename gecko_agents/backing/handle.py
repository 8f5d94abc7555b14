"""The handle spring of an elastic strip: the spring and damper through which the handle (the
kinematic body the protocol moves, ``World.plate``) pulls the strip
(:class:`gecko_agents.backing.elastic.ElasticBacking`).

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["HandleSpring"]


class HandleSpring:
    """The handle's spring k·(handle point − link point) + c·(v_handle − v_point) on the links
    it holds: k_h/n on each link centre (``drive = "uniform"``) or k_h on the strip's +x end
    (``"peel_end"``: of the leader arm, if any).

    Parameters
    ----------
    strip : the :class:`gecko_agents.backing.strip.Strip`, laid out. world : the world (the
        handle's position). backing : ``params.backing`` (drive, handle_stiffness [µN/µm]).
    n_links : the pad's links; n_arm : the leader arm's. length : the pad's length [µm].
    alpha : the strip's misalignment [rad] (the handle holds it turned).

    Attributes
    ----------
    link : the links it holds. s : the abscissa on each from its centre [µm]. dx, dy : the
        handle's points relative to the handle [µm]. k : the stiffness of each [µN/µm].
    c : the damper of each [µN·µs/µm] (set once the links' inertia is scaled).
    energy : ½k·|Δ|² at the last step's end [pJ].
    """

    def __init__(self, strip, world, backing, n_links, n_arm, length, alpha):
        self.strip = strip
        if backing.drive == "uniform":
            self.link = np.arange(n_links)
            self.s = np.zeros(n_links)
            self.dx = strip.x_centre.copy()
            self.k = backing.handle_stiffness / n_links
        else:  # the +x end of the strip (of the arm, if any)
            self.link = np.array([strip.n - 1])
            self.s = np.array([0.5 * strip.ell])
            self.dx = np.array([0.5 * length])
            self.k = backing.handle_stiffness
        self.dy = np.zeros_like(self.dx)
        if n_arm:  # the arm's end, where kink_up laid it
            ex, ey = strip.nodes()
            pp = world.plate.position
            self.dx[0], self.dy[0] = ex[-1] - pp.x, ey[-1] - pp.y
        if alpha:  # the handle holds the strip turned: its attachment points turn with it
            self.dx, self.dy = self.dx * math.cos(alpha), self.dx * math.sin(alpha)
        self.c = 0.0
        self.energy = 0.0

    def forces(self, data, hx, hy, vpx, vpy, fx, fy, tq, dt):
        """The spring and damper on the links it holds, the handle at (``hx``, ``hy``) [µm]
        moving at (``vpx``, ``vpy``) [µm/µs], the links' rows ``data``; added to the links'
        forces ``fx``, ``fy`` [µN] and torques ``tq`` [µN·µm]; books its energy ½k·|Δ|² at the
        end of the step ``dt`` [µs]. Returns its force, its damper's share (x, y) [µN] and
        the lever arms [µm]."""
        hl = self.link
        qx, qy, qvx, qvy, qox, qoy = self.strip.points(data, hl, self.s, dt)
        ex, ey = hx + self.dx - qx, hy + self.dy - qy
        self.energy = 0.5 * self.k * float(ex @ ex + ey @ ey)
        Fcx, Fcy = self.c * (vpx - qvx), self.c * (vpy - qvy)
        Fhx, Fhy = self.k * ex + Fcx, self.k * ey + Fcy
        np.add.at(fx, hl, Fhx)
        np.add.at(fy, hl, Fhy)
        np.add.at(tq, hl, qox * Fhy - qoy * Fhx)
        return Fhx, Fhy, Fcx, Fcy, qox, qoy
