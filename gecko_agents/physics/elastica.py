"""A pillar that can buckle: the discrete elastica of a clamped column (Hencky's bar chain) that
shears (Timoshenko) and stretches along its length.

The seta of ``mechanics = "elastica"``: a chain of n rigid links of length ℓ = L/n joined by
rotary springs, clamped at its root at the rest angle −θ to +x. Its links are massless: at
every step the chain is in equilibrium with its root on the backing and its end at the tip body
(whose mass carries the dynamics, as for the other setae), found by Newton's method from the
previous step's shape. The tip's rotation is free (a sphere or a tip off the floor) or held in
the direction its face bonded in (a flat face bonded to the floor, whose face cannot tilt:
:class:`gecko_agents.contact.FlatPunch`); a face that lets go releases what its clamp stored
(booked as dissipated, as a snap-off's contact energy).

Bending: the joint springs are k = EI/ℓ between links and 2EI/ℓ at a clamped end (the clamp
and its mirror image make a joint of a chain twice as long), I = πr⁴/4: Hencky's bar-chain
discretisation of the elastica, whose critical loads converge on Euler's as 1/n²
(Timoshenko & Gere, Theory of Elastic Stability, 2nd ed., 1961, ch. 2).

Shear: each link's cross-section turns by θ_j = φ_j − γ_j, its centreline by φ_j; the joint
springs act on the sections, and a shear spring ½κGAℓ·γ_j² on each link (G = E/(2(1 + ν)),
κ = 6(1 + ν)/(7 + 6ν) for a solid circle, Cowper 1966, J Appl Mech 33:335). The shear force is
thus the load's component across the centreline, Engesser's assumption, and the chain buckles
at P = P_E/(1 + P_E/(κGA)) (Engesser 1891; Timoshenko & Gere 1961, §2.16): 4.8 % below
Euler's at L/r = 6 for a clamped–free pillar, 0.2–1 % at L/r = 30. The energy is quadratic in
γ and the geometry does not involve it, so γ is eliminated exactly (static condensation): the
joint angles u = Dφ − b carry the stiffness K_s = (K⁻¹ + D·S⁻¹·Dᵀ)⁻¹, K the joint springs,
S the shear springs, D the differences of link angles (``tests/test_pillars.py`` measures the
chain's linear stability against Engesser's and Euler's loads).

Axial: Ka = πr²E/L (eq 17) over the whole column, its stretch s shared equally by the links
(length ℓ + s/n each), so that a column shortened by tens of per cent before it buckles (a
stubby clamped pillar) keeps every link's length positive. The joint springs are per link of
the unstretched column, so a column shortened by ε = P/(EA) buckles at P(1 − P/(EA)) = P_cr of
the linear theory (+1.7 % at L/r = 6 clamped–free). An initially crooked column picks the side
it buckles to: the stress-free chain is a circular arc whose tip lies ``imperfection``·L to +x
of the straight column (for a vertical pillar the branch would otherwise be a coin toss decided
by rounding).

Unknowns per seta: absolute link angles φ_1..φ_n, the axial stretch s and the force λ the tip
body applies to the chain's end (the seta pushes the tip with −λ). Energy
V = ½uᵀK_s u + ½Ka·s², u = Dφ − b (b: the root angle, the rest shape's joint angles and, with
the tip held, the section direction φ_b of its face when it bonded);
end r(q) = Σ (ℓ + s/n)(cos φ_j, sin φ_j). Equilibrium: ∇V = Jᵀλ, r(q) = d.

Units: µm, µN, MPa; angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Elastica", "DEFAULT_LINKS", "shear_coefficient"]

DEFAULT_LINKS = 16
"""Links of the chain: 16 put the three Euler loads within 1.3 % (see the module docstring)."""

_MAX_ITER = 200  # a snap of the chain between branches takes many 0.2 rad steps


def shear_coefficient(nu):
    """Timoshenko's shear coefficient of a solid circular section κ = 6(1 + ν)/(7 + 6ν) [-]
    (Cowper 1966, J Appl Mech 33:335).

    Parameters
    ----------
    nu : Poisson's ratio [-].
    """
    return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


class Elastica:
    """The bar-chain elastica of N setae (module docstring), warm-started step to step.

    Parameters
    ----------
    n_setae : N. L : seta length [µm]. r : seta radius [µm]. E : seta modulus [MPa].
    theta : rest angle to the backing [rad]. links : n. imperfection : rest tip offset of
    the crooked column over L [-]. nu : Poisson's ratio of the seta [-] (its shear modulus).
    shear : ``False`` leaves shear out (κGA → ∞, the Euler–Bernoulli chain).
    """

    def __init__(
        self, n_setae, L, r, E, theta, links=DEFAULT_LINKS, imperfection=1e-3, nu=0.3, shear=True
    ):
        self.n, self.N = int(links), int(n_setae)
        self.L, self.ell = float(L), float(L) / links
        self.EI = E * math.pi * r**4 / 4.0
        self.Ka = E * math.pi * r * r / L
        self.kGA = shear_coefficient(nu) * E / (2.0 * (1.0 + nu)) * math.pi * r * r
        n = self.n
        k = np.full(n + 1, self.EI / self.ell)  # k[0] root, k[j] between links j and j+1
        k[0] = 2.0 * self.EI / self.ell
        k[n] = 2.0 * self.EI / self.ell  # tip clamp (used where the tip is held)
        self.k = k
        self._stiffness(shear)
        # Crooked rest shape: a circular arc of curvature κ, tip offset ≈ ½κL² = imperfection·L
        # towards +x (the chain turns counter-clockwise from −θ).
        kappa = 2.0 * imperfection / L
        s_mid = (np.arange(n) + 0.5) * self.ell
        self.phi_rest = -theta + kappa * s_mid
        self.root_angle = -theta
        self.phi = np.tile(self.phi_rest, (self.N, 1))
        self.stretch = np.zeros(self.N)
        self.lam = np.zeros((self.N, 2))
        # The held tips and the section direction their face was bonded in [rad]: a face
        # bonds in the direction it touches in (no energy jump), lets go of what the clamp
        # then stores.
        self.held = np.zeros(self.N, bool)
        self.clamp = np.full(self.N, self.phi_rest[-1])
        self.released = 0.0  # clamp energy let go by tips released in the last solve [pJ]
        self._last = None  # (d, force, energy) of the last solve: what a record asks again
        self.iterations = 0  # Newton iterations of the last solve (largest over setae)

    def _stiffness(self, shear: bool) -> None:
        """The condensed joint stiffnesses K_s of the free and the held chain (index 0, 1),
        their ∂²V/∂φ² (B) and the matrices G giving the shear γ = G·u that minimises the energy
        at joint angles u (module docstring)."""
        n = self.n
        D = np.eye(n + 1, n) - np.eye(n + 1, n, -1)  # rows: root, n − 1 joints, tip clamp
        D[n, n - 1] = 1.0
        self.D = D
        self.Ks, self.B, self.G = [], [], []
        for m in (n, n + 1):  # free tip: no clamp row; held: with it
            Dm, Km = D[:m], np.diag(self.k[:m])
            if shear:
                S = self.kGA * self.ell * np.eye(n)
                Ks = np.linalg.inv(np.linalg.inv(Km) + Dm @ np.linalg.solve(S, Dm.T))
                G = np.linalg.solve(S + Dm.T @ Km @ Dm, Dm.T @ Km)
            else:
                Ks, G = Km, np.zeros((n, m))
            self.Ks.append(Ks)
            self.B.append(Dm.T @ Ks @ Dm)
            self.G.append(G)

    @classmethod
    def of(cls, params, n_setae: int) -> Elastica:
        """The chains of ``n_setae`` setae of a :class:`gecko_agents.params.SetaArray`."""
        s = params.seta
        return cls(
            n_setae,
            s.L,
            s.r,
            params.contact.E1,
            s.theta,
            s.links,
            s.imperfection,
            params.contact.nu1,
        )

    def peek(self, d) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`solve` at ``d`` with the tips held as in the last solve, leaving the chain's
        state as it was (forces and energies at positions other than the step's)."""
        last = self._last
        if last is not None and np.array_equal(last[0], d):  # the step's own positions
            return last[1], last[2]
        kept = (
            self.phi,
            self.stretch,
            self.lam,
            self.iterations,
            self.held,
            self.clamp.copy(),
            self.released,
            last,
        )
        try:
            return self.solve(d, self.held)
        finally:
            (
                self.phi,
                self.stretch,
                self.lam,
                self.iterations,
                self.held,
                self.clamp,
                self.released,
                self._last,
            ) = kept

    # ------------------------------------------------------------------ geometry
    def _end(self, phi, s):
        c, sn = np.cos(phi), np.sin(phi)
        ell = self.ell + s / self.n
        return np.column_stack([ell * c.sum(1), ell * sn.sum(1)]), c, sn

    def rest_end(self) -> np.ndarray:
        """Root-to-tip vector of the stress-free chain [µm], shape (2,)."""
        c, s = np.cos(self.phi_rest), np.sin(self.phi_rest)
        return np.array([self.ell * c.sum(), self.ell * s.sum()])

    def _joints(self, phi, clamp) -> np.ndarray:
        """u (N, n + 1): the joint angles from rest, the last the held face's turn [rad]."""
        u = (phi - self.phi_rest) @ self.D.T
        u[:, -1] = phi[:, -1] - clamp
        return u

    def _bending(self, u, held) -> np.ndarray:
        """½uᵀK_s u of each seta [pJ], with the clamp row where held."""
        n = self.n
        free = 0.5 * np.einsum("ij,jk,ik->i", u[:, :n], self.Ks[0], u[:, :n])
        tied = 0.5 * np.einsum("ij,jk,ik->i", u, self.Ks[1], u)
        return np.where(held, tied, free)

    def energy(self, phi, s, held) -> np.ndarray:
        """V of each seta [pJ] (module docstring)."""
        return self._bending(self._joints(phi, self.clamp), held) + 0.5 * self.Ka * s * s

    def face_moment(self) -> np.ndarray:
        """Moment the clamp of each held face carries at the last solve [µN·µm] (the torque of
        its last row of K_s; a positive one would turn the face counter-clockwise back to its
        bonded direction), 0 for a free tip."""
        tau = (self._joints(self.phi, self.clamp) @ self.Ks[1].T)[:, -1]
        return np.where(self.held, tau, 0.0)

    def section_angle(self, phi) -> np.ndarray:
        """Direction of the last link's cross-section of free chains at link angles ``phi``
        [rad]: φ_n − γ_n with the shear that minimises the energy."""
        u = self._joints(phi, phi[:, -1])[:, : self.n]
        return phi[:, -1] - (u @ self.G[0].T)[:, -1]

    # ------------------------------------------------------------------ Newton
    def _system(self, phi, s, lam, held, clamp):
        N, n = phi.shape
        c, sn = np.cos(phi), np.sin(phi)
        ell = (self.ell + s / n)[:, None]
        u = self._joints(phi, clamp)
        grad = np.where(
            held[:, None], u @ (self.D.T @ self.Ks[1]).T, u[:, :n] @ (self.D[:n].T @ self.Ks[0]).T
        )
        Jx, Jy = -ell * sn, ell * c  # ∂r/∂φ_j
        lx, ly = lam[:, :1], lam[:, 1:]
        res = np.zeros((N, n + 3))
        res[:, :n] = grad - (lx * Jx + ly * Jy)
        res[:, n] = self.Ka * s - (lam[:, 0] * c.mean(1) + lam[:, 1] * sn.mean(1))
        A = np.zeros((N, n + 3, n + 3))
        idx = np.arange(n)
        A[:, :n, :n] = np.where(held[:, None, None], self.B[1], self.B[0])
        A[:, idx, idx] += ell * (lx * c + ly * sn)
        A[:, :n, n] = A[:, n, :n] = (lx * sn - ly * c) / n  # −λ·∂²r/∂φ_j∂s
        A[:, n, n] = self.Ka
        A[:, :n, n + 1], A[:, :n, n + 2] = -Jx, -Jy
        A[:, n, n + 1], A[:, n, n + 2] = -c.mean(1), -sn.mean(1)
        A[:, n + 1 :, : n + 1] = np.transpose(A[:, : n + 1, n + 1 :], (0, 2, 1))
        return res, A

    def solve(self, d, held) -> tuple[np.ndarray, np.ndarray]:
        """Equilibrium of every chain with its end at root-to-tip vectors ``d`` (N, 2) [µm],
        tips ``held`` (bool (N,)) at their rest direction; returns the force of each seta on
        its tip (N, 2) [µN] and its elastic energy (N,) [pJ]. Raises ``RuntimeError`` naming
        the setae whose chain found no equilibrium (a tip pulled beyond the chain's reach)."""
        d = np.asarray(d, float)
        held = np.broadcast_to(np.asarray(held, bool), (len(d),)).copy()
        phi, s, lam = self.phi.copy(), self.stretch.copy(), self.lam.copy()
        gone, new = self.held & ~held, held & ~self.held
        self.released = self._release(gone, phi, s, lam) if gone.any() else 0.0
        self.clamp[new] = self.section_angle(phi[new]) if new.any() else self.clamp[new]
        steps, todo = self._newton(phi, s, lam, d, held, self.clamp)
        if todo.any():
            self._refuse(d, np.flatnonzero(todo))
        self.iterations = steps
        self.phi, self.stretch, self.lam, self.held = phi, s, lam, held
        F, U = -lam, self.energy(phi, s, held)
        self._last = (d.copy(), F, U)
        return F, U

    def _release(self, gone, phi, s, lam) -> float:
        """Energy [pJ] the chains of setae ``gone`` let go as their face's clamp releases:
        the held chain's energy over that of the free chain relaxed with its end where it
        stood at the last solve (the links are massless: the chain jumps to its new
        equilibrium, booked as dissipated); updates ``phi``, ``s``, ``lam`` to that shape."""
        clamp = self.clamp[gone]
        ph, st, lm = phi[gone], s[gone], lam[gone]
        before = self._bending(self._joints(ph, clamp), True) + 0.5 * self.Ka * st * st
        if self._last is not None:
            free = np.zeros(len(ph), bool)
            todo = self._newton(ph, st, lm, self._last[0][gone], free, clamp)[1]
            if not todo.any():
                phi[gone], s[gone], lam[gone] = ph, st, lm
            else:  # not relaxed: the clamp's own energy only
                ph, st = phi[gone], s[gone]
        after = self._bending(self._joints(ph, clamp), False) + 0.5 * self.Ka * st * st
        return float(np.sum(before - after))

    def _newton(self, phi, s, lam, d, held, clamp):
        """Newton's iterations on (φ, s, λ) in place; returns their count and the setae still
        out of tolerance."""
        n = self.n
        f_tol = 1e-12 * max(self.EI / self.ell, self.Ka * self.L)
        x_tol = 1e-12 * self.L
        todo = np.ones(len(d), bool)
        for steps in range(_MAX_ITER):  # noqa: B007
            res, A = self._system(phi, s, lam, held, clamp)
            res[:, n + 1 :] = -(self._end(phi, s)[0] - d)
            err_f = np.abs(res[:, : n + 1]).max(1)
            err_x = np.abs(res[:, n + 1 :]).max(1)
            todo = (err_f > f_tol) | (err_x > x_tol)
            if not todo.any():
                return steps, todo
            step = np.linalg.solve(A[todo], -res[todo][..., None])[..., 0]
            # Keep a Newton step from turning a link by more than 0.2 rad (a fold's tangent).
            big = np.abs(step[:, :n]).max(1, keepdims=True)
            step *= np.minimum(1.0, 0.2 / np.maximum(big, 1e-300))
            phi[todo] += step[:, :n]
            s[todo] += step[:, n]
            lam[todo] += step[:, n + 1 :]
        return _MAX_ITER, todo

    def _refuse(self, d, bad) -> None:
        reach = float(np.hypot(*d[bad[0]])) / self.L
        why = (
            "the column is pressed nearly flat: a buckled pillar carries about its Euler "
            "load, so a force preload above it crushes it (press to a depth instead)"
            if reach < 0.5
            else "a tip pulled far beyond the chain's reach: the contact holds more than "
            "the chain can carry (a pull-off force far above the pillar's Ka·L, e.g. a "
            "face radius contact.R far above seta.r), not a time step"
            if reach > 2.0
            else "a tip pulled beyond the chain's reach or a time step too long"
        )
        raise RuntimeError(
            f"the elastica of setae {bad[:5].tolist()} found no equilibrium in "
            f"{_MAX_ITER} Newton iterations (end {reach:.2f} L from its root): {why}"
        )

    def nodes(self, root) -> np.ndarray:
        """Positions of the chain's joints (N, n + 1, 2) [µm] for roots (N, 2) [µm], at the
        last solve (for drawing)."""
        c, sn = np.cos(self.phi), np.sin(self.phi)
        steps = np.stack([c, sn], axis=-1) * (self.ell + self.stretch[:, None, None] / self.n)
        out = np.concatenate([np.zeros((len(c), 1, 2)), np.cumsum(steps, axis=1)], axis=1)
        return out + np.asarray(root)[:, None, :]
