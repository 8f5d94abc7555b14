"""Constants of the quasi-static ``rod`` seta (:class:`RodSetup`), shared by the rod's
equilibrium (:mod:`gecko_agents.quasistatic.rod_equilibrium`) and its stepping
(:mod:`gecko_agents.quasistatic.rod`). Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gecko_agents.params import SetaArray
from gecko_agents.physics import beam, jkr
from gecko_agents.physics.friction import friction_cap, friction_cap_slope

__all__ = ["RodSetup"]


@dataclass(frozen=True)
class RodSetup:
    """Constants of the quasi-static ``rod`` seta (see :func:`rod_force`).

    Attributes: R [µm], w [µN/µm], E_star [MPa], Fc [µN], L [µm], theta [rad], Ka [µN/µm],
    k_phi [µN·µm/rad], k_t (stick spring of the contact [µN/µm], ``inf``: a sticking tip does
    not move), mu [-], law, lateral (``"coupled"`` or ``"free"``), a_c (end of the JKR stable
    branch [µm]), a0 (zero-load radius [µm]), Ky (eq 20 [µN/µm]).
    """

    R: float
    w: float
    E_star: float
    Fc: float
    L: float
    theta: float
    Ka: float
    k_phi: float
    k_t: float
    mu: float
    law: str
    lateral: str
    a_c: float
    a0: float
    Ky: float
    Kxx: float
    Kxy: float

    @classmethod
    def from_params(
        cls,
        params: SetaArray,
        lateral: str = "coupled",
        stiffness_scale: float = 1.0,
        tangential_stiffness: float = math.inf,
    ) -> RodSetup:
        """The rod of ``params`` (Ka, Kp scaled by ``stiffness_scale``), contact and friction."""
        if not tangential_stiffness > 0:
            raise ValueError(f"tangential_stiffness = {tangential_stiffness!r} must be > 0")
        if lateral not in ("coupled", "free"):
            raise ValueError(f"lateral = {lateral!r} must be 'coupled' or 'free'")
        if not stiffness_scale > 0:
            raise ValueError(f"stiffness_scale = {stiffness_scale!r} must be > 0")
        R, w, Es = params.contact.jkr_args()
        Ka = params.axial_stiffness * stiffness_scale
        Kp = params.bending_stiffness * stiffness_scale
        K = beam.stiffness_matrix(Ka, Kp, params.seta.theta)
        L = params.seta.L
        return cls(
            R,
            w,
            Es,
            params.contact.pull_off_force,
            L,
            params.seta.theta,
            Ka,
            Kp * L * L,
            float(tangential_stiffness),
            params.friction.mu if lateral == "coupled" else 0.0,
            params.friction.law,
            lateral,
            float(jkr.snap_off_radius(R, w, Es)),
            float(jkr.zero_load_contact_radius(R, w, Es)),
            float(K[1, 1] - K[0, 1] ** 2 / K[0, 0]),
            float(K[0, 0]),
            float(K[0, 1]),
        )

    def cap(self, P):
        """Tangential force cap [µN] for normal force(s) P [µN] (as :meth:`Friction.cap`)."""
        return friction_cap(P, self.Fc, self.mu, self.law == "paper")

    def dcap(self, P):
        """d cap / dP [-]."""
        return friction_cap_slope(P, self.Fc, self.mu, self.law == "paper")

    @property
    def rest(self) -> tuple[float, float]:
        """Free tip position relative to the root [µm]."""
        return self.L * math.cos(self.theta), -self.L * math.sin(self.theta)
