"""The pivots of the elastic strip's chain, solved directly: the constraint forces that keep
the links' ends together, one banded linear solve per step, O(n) in the links.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).

Method: Lagrange multipliers for the pivots of an open chain, whose system matrix is banded, so
a direct factorisation costs O(n) (Baraff 1996, "Linear-time dynamics using Lagrange
multipliers", SIGGRAPH '96, 137–146), at the velocity level of the time integrator
(pymunk's semi-implicit Euler), with Baumgarte's (1972, Comput Methods Appl Mech Eng 1:1)
feedback on the gap so that the pivots do not drift apart.

Link j (centre c_j, angle φ_j, mass m, moment of inertia I) has its ends at c_j ± h·u_j,
h = ℓ/2, u_j = (cos φ_j, sin φ_j); pivot j joins link j's +x end to link j+1's −x end, and a
clamp is one more pivot between a fixed anchor and link 0's −x end. Pivot k between a left
body L and a right body R has the gap [µm] and its rate [µm/µs]

    C_k = (c_L + h·u_L) − (c_R − h·u_R),   Ċ_k = J_k·v = v_L + h·ω_L·p_L − v_R + h·ω_R·p_R,

p = (−sin φ, cos φ), so its Jacobian blocks are [I₂, h·p_L] on L and [−I₂, h·p_R] on R. A step
of semi-implicit Euler is v⁺ = d·v + dt·M⁻¹(f + Jᵀλ), then x⁺ = x + v⁺·dt (d the space's
velocity damping factor over dt). The pivot forces λ [µN] are chosen so that

    J·v⁺ = −β·C/dt,   i.e.   (J M⁻¹ Jᵀ)·(λ·dt) = −β·C/dt − J·(d·v + dt·M⁻¹f),

with J and C evaluated at the positions the step reaches (x + v·dt: pymunk moves the bodies
with the old velocities first, and the forces are evaluated there). J M⁻¹ Jᵀ is block
tridiagonal in 2×2 blocks (neighbouring pivots share a link):

    A_kk = (1/m_L + 1/m_R)·I₂ + h²·(p_L p_Lᵀ/I_L + p_R p_Rᵀ/I_R),
    A_k,k+1 = −I₂/m_j + h²·p_j p_jᵀ/I_j   (j the link they share),

symmetric positive definite with half-bandwidth 3, factorised once per step: banded Cholesky
(``scipy.linalg.cholesky_banded``) here, block LDLᵀ in the compiled loop
(:mod:`gecko_agents.backing.pivots_loop`, used when numba is installed). Link L then receives
the force λ and the torque h·p_L·λ (= r × λ, r = h·u_L), link R the force −λ and h·p_R·λ.

β = 1 (:data:`BAUMGARTE_BETA`): the gap the step reaches is removed in one step, to first
order: C(x⁺ + v⁺·dt) = C(x⁺) + J·v⁺·dt + O((ω·dt)²·h). Any 0 < β < 2 contracts the linear
error (there is no iteration for a larger β to destabilise), 1 at once; a smaller β lets the
per-step error pile up to 1/β times as much (1 000 links, uniform pull: largest gap 2.9e-8 µm
at β = 0, 2.1e-9 at 0.2, 5.4e-10 at 1).

The second-order term left by that linear solve is not harmless: the pivots then remove
kinetic energy, ~(ω·dt)² of it per step for links turning at ω (a free chain of 30 links
released bent by 0.03 rad per joint loses 32 % of its energy in 2 500 steps at the zig-zag's
ω·dt = 0.5; pymunk's own PivotJoints at 60 sweeps lose 84 %). So :data:`NEWTON_SOLVES` more solves
with the same factor (modified Newton, as SHAKE: Ryckaert, Ciccotti & Berendsen 1977,
J Comput Phys 23:327) add to λ·dt the impulse A⁻¹·(−C(x⁺ + v⁺·dt)/dt) that closes the gap
the step leaves at the next positions exactly, not to first order: the same chain then keeps
its energy to 0.4 % (3.5 % with one such solve), and the 1 000-link pull's largest gap is
2e-13 µm.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import cho_solve_banded, cholesky_banded

import gecko_agents.backing.pivots_loop as backing_pivots_loop

__all__ = ["ChainPivots", "BAUMGARTE_BETA", "NEWTON_SOLVES"]

BAUMGARTE_BETA = 1.0
"""Fraction of the pivot gap removed per step [-] (Baumgarte 1972; see the module docstring)."""

NEWTON_SOLVES = 2
"""Extra solves per step that remove the gap left after it (see the module docstring)."""


class ChainPivots:
    """The pivots of a chain of ``n_links`` links of length ``ell`` [µm] and, once
    :meth:`clamp` has been called, the clamp of link 0's −x end to a fixed anchor.

    :meth:`forces` returns the pivot forces and torques of a step; :attr:`gap_max` [µm] is the
    largest pivot gap at the positions that step reached (before its correction), and
    ``gap_next`` [µm] the largest the pivot forces leave at the positions after it.
    ``newton`` extra solves with the same factorisation remove the rotation's curvature term
    from the gap after the step as well (position-level, as SHAKE: Ryckaert, Ciccotti &
    Berendsen 1977, J Comput Phys 23:327); 0 is the velocity-level solve with β alone."""

    def __init__(
        self,
        n_links: int,
        ell: float,
        beta: float = BAUMGARTE_BETA,
        newton: int = NEWTON_SOLVES,
        compiled: bool = True,
    ):
        self.n, self.h, self.beta, self.newton = int(n_links), 0.5 * float(ell), float(beta), newton
        self.anchor = None
        self.gap_max = self.gap_next = 0.0
        self._loop = backing_pivots_loop.compiled() if compiled else None

    def clamp(self, anchor: tuple[float, float]) -> None:
        """Pin link 0's −x end to ``anchor`` [µm] (a pivot to the static world)."""
        self.anchor = (float(anchor[0]), float(anchor[1]))

    @property
    def count(self) -> int:
        """Number of pivots."""
        return self.n - 1 + (self.anchor is not None)

    def _gaps(self, x, y, c, s):
        """Gaps (left point − right point) [µm] of the pivots, the clamp's first."""
        h = self.h
        gx = x[:-1] - x[1:] + h * (c[:-1] + c[1:])
        gy = y[:-1] - y[1:] + h * (s[:-1] + s[1:])
        if self.anchor is not None:
            gx = np.concatenate([[self.anchor[0] - x[0] + h * c[0]], gx])
            gy = np.concatenate([[self.anchor[1] - y[0] + h * s[0]], gy])
        return gx, gy

    def _rates(self, vx, vy, w, px, py):
        """J·v: rates of the gaps [µm/µs] for link velocities (vx, vy, ω)."""
        h = self.h
        wx, wy = h * w * px, h * w * py
        dx = vx[:-1] - vx[1:] + wx[:-1] + wx[1:]
        dy = vy[:-1] - vy[1:] + wy[:-1] + wy[1:]
        if self.anchor is not None:
            dx = np.concatenate([[wx[0] - vx[0]], dx])
            dy = np.concatenate([[wy[0] - vy[0]], dy])
        return dx, dy

    def _generalised(self, lx, ly, px, py):
        """Jᵀ·λ: forces and torques on the links of pivot forces (lx, ly) (or impulses).
        Link L of a pivot gets +λ and the torque h·p_L·λ (= r × λ), link R −λ and h·p_R·λ."""
        n, h, P = self.n, self.h, lx.size
        fx, fy, tq = np.zeros(n), np.zeros(n), np.zeros(n)
        right = slice(n - P, n)  # every pivot has a right link
        fx[right] -= lx
        fy[right] -= ly
        tq[right] += h * (px[right] * lx + py[right] * ly)
        lx, ly = lx[P - n + 1 :], ly[P - n + 1 :]  # the clamp has no left link
        left = slice(0, n - 1)
        fx[left] += lx
        fy[left] += ly
        tq[left] += h * (px[left] * lx + py[left] * ly)
        return fx, fy, tq

    def _factor(self, px, py, m, inertia):
        """Banded Cholesky factor of A = J M⁻¹ Jᵀ (upper storage, half-bandwidth 3:
        ab[3 + i − j, j] = A[i, j])."""
        n, P = self.n, self.count
        inv_m, hh = 1.0 / m, self.h**2 / inertia
        pxx, pyy, pxy = hh * px * px, hh * py * py, hh * px * py
        ab = np.zeros((4, 2 * P))
        d0, d1, d01 = ab[3, 0::2], ab[3, 1::2], ab[2, 1::2]
        k = P - n + 1  # the clamp's row first: right link 0 only
        d0[k:] = 2.0 * inv_m + pxx[:-1] + pxx[1:]
        d1[k:] = 2.0 * inv_m + pyy[:-1] + pyy[1:]
        d01[k:] = pxy[:-1] + pxy[1:]
        if k:
            d0[0], d1[0], d01[0] = inv_m + pxx[0], inv_m + pyy[0], pxy[0]
        shared = slice(n - P, n - 1)  # the link that pivots k and k + 1 share
        ab[2, 2::2] = pxy[shared]  # B[1, 0]
        ab[1, 2::2] = pxx[shared] - inv_m  # B[0, 0]
        ab[1, 3::2] = pyy[shared] - inv_m  # B[1, 1]
        ab[0, 3::2] = pxy[shared]  # B[0, 1]
        return cholesky_banded(ab, overwrite_ab=True, check_finite=False)

    def forces(self, pos, vel, m, inertia, dt):
        """Pivot forces fx, fy [µN] and torques [pJ] on the links for one step of ``dt``
        [µs]. ``pos``: (x, y, φ) of the links where the step takes them [µm, rad];
        ``vel``: (vx, vy, ω) the step would give them without the pivots [µm/µs, rad/µs]
        (damped old velocity plus dt·M⁻¹·f); ``m`` [ng], ``inertia`` [ng·µm²] of a link."""
        P = self.count
        if P == 0:
            self.gap_max = self.gap_next = 0.0
            return np.zeros(self.n), np.zeros(self.n), np.zeros(self.n)
        x, y, phi = pos
        vx, vy, w = vel
        if self._loop is not None:
            fx, fy, tq = out = np.empty((3, self.n))
            ax, ay = self.anchor or (0.0, 0.0)
            self.gap_max, self.gap_next = self._loop(
                x,
                y,
                phi,
                vx,
                vy,
                w,
                float(m),
                float(inertia),
                float(dt),
                self.h,
                self.beta,
                int(self.anchor is not None),
                ax,
                ay,
                int(self.newton),
                fx,
                fy,
                tq,
            )
            return out
        c, s = np.cos(phi), np.sin(phi)
        px, py = -s, c
        gx, gy = self._gaps(x, y, c, s)
        self.gap_max = float(np.sqrt(np.max(gx * gx + gy * gy)))
        dgx, dgy = self._rates(vx, vy, w, px, py)
        factor = self._factor(px, py, m, inertia)
        rhs = np.empty(2 * P)
        k = self.beta / dt
        rhs[0::2] = -k * gx - dgx
        rhs[1::2] = -k * gy - dgy
        imp = cho_solve_banded((factor, False), rhs, check_finite=False)  # [µN·µs]
        for solve in range(self.newton + 1):
            ix, iy, it = self._generalised(imp[0::2], imp[1::2], px, py)
            # Where the step then takes the links next (x⁺ + v⁺·dt) and the gap left there.
            phi2 = phi + (w + it / inertia) * dt
            gx, gy = self._gaps(
                x + (vx + ix / m) * dt, y + (vy + iy / m) * dt, np.cos(phi2), np.sin(phi2)
            )
            self.gap_next = float(np.sqrt(np.max(gx * gx + gy * gy)))
            if solve == self.newton:
                break
            rhs[0::2], rhs[1::2] = -gx / dt, -gy / dt
            imp += cho_solve_banded((factor, False), rhs, check_finite=False)
        return ix / dt, iy / dt, it / dt
