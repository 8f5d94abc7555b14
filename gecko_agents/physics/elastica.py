"""A pillar that can buckle: the discrete elastica of a clamped column (Hencky's bar chain).

The seta of ``mechanics = "elastica"``: a chain of n rigid links of length ℓ = L/n joined by
rotary springs, with an axial spring at the tip, clamped at its root at the rest angle −θ to
+x. Its links are massless: at every step the chain is in equilibrium with its root on the
backing and its end at the tip body (whose mass carries the dynamics, as for the other setae),
found by Newton's method from the previous step's shape. The tip's rotation is free (a sphere
or a tip off the floor) or held in the direction its face bonded in (a flat punch bonded to the
floor, whose face cannot tilt: :class:`gecko_agents.contact.FlatPunch`); a face that lets go
releases what its clamp stored (booked as dissipated, as a snap-off's contact energy).

Bending: the joint springs are k = EI/ℓ between links and 2EI/ℓ at a clamped end (the clamp
and its mirror image make a joint of a chain twice as long), I = πr⁴/4: Hencky's bar-chain
discretisation of the elastica. Its critical loads converge on Euler's as 1/n² (measured by
``tests/test_pillars.py``'s linear stability of the chain: with 16 links the clamped–free,
clamped–pinned and clamped–clamped columns buckle 0.1 %, 0.8 % and 1.3 % below
π²EI/(4L²), 2.046π²EI/L² and 4π²EI/L², the continuous values of Timoshenko & Gere, Theory of
Elastic Stability, 2nd ed., 1961, ch. 2). Axial: one spring Ka = πr²E/L (eq 17) along the
last link. An initially crooked column picks the side it buckles to: the stress-free chain
is a circular arc whose tip lies ``imperfection``·L to +x of the straight column (for a
vertical pillar the branch would otherwise be a coin toss decided by rounding).

Unknowns per seta: absolute link angles φ_1..φ_n, the axial stretch s and the force λ the tip
body applies to the chain's end (the seta pushes the tip with −λ). Energy
V = Σ ½k_j(ψ_j − ψ⁰_j)² + ½Ka·s² (+ ½k_c(φ_n − φ_b)² with the tip held, φ_b the direction
of its face when it bonded), ψ_j = φ_j − φ_{j−1};
end r(q) = Σ ℓ(cos φ_j, sin φ_j) + s(cos φ_n, sin φ_n). Equilibrium: ∇V = Jᵀλ, r(q) = d.

Units: µm, µN, MPa; angles in radians.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Elastica", "DEFAULT_LINKS"]

DEFAULT_LINKS = 16
"""Links of the chain: 16 put the three Euler loads within 1.3 % (see the module docstring)."""

_MAX_ITER = 200  # a snap of the chain between branches takes many 0.2 rad steps


class Elastica:
    """The bar-chain elastica of N setae (module docstring), warm-started step to step.

    Parameters
    ----------
    n_setae : N. L : seta length [µm]. r : seta radius [µm]. E : seta modulus [MPa].
    theta : rest angle to the backing [rad]. links : n. imperfection : rest tip offset of
    the crooked column over L [-].
    """

    def __init__(self, n_setae, L, r, E, theta, links=DEFAULT_LINKS, imperfection=1e-3):
        self.n, self.N = int(links), int(n_setae)
        self.L, self.ell = float(L), float(L) / links
        self.EI = E * math.pi * r**4 / 4.0
        self.Ka = E * math.pi * r * r / L
        n = self.n
        k = np.full(n + 1, self.EI / self.ell)  # k[0] root, k[j] between links j and j+1
        k[0] = 2.0 * self.EI / self.ell
        k[n] = 2.0 * self.EI / self.ell  # tip clamp (used where the tip is held)
        self.k = k
        # Crooked rest shape: a circular arc of curvature κ, tip offset ≈ ½κL² = imperfection·L
        # towards +x (the chain turns counter-clockwise from −θ).
        kappa = 2.0 * imperfection / L
        s_mid = (np.arange(n) + 0.5) * self.ell
        self.phi_rest = -theta + kappa * s_mid
        self.root_angle = -theta
        self.phi = np.tile(self.phi_rest, (self.N, 1))
        self.stretch = np.zeros(self.N)
        self.lam = np.zeros((self.N, 2))
        # The held tips and the direction their face was bonded in [rad]: a face bonds in the
        # direction it touches in (no energy jump), lets go of what the clamp then stores.
        self.held = np.zeros(self.N, bool)
        self.clamp = np.full(self.N, self.phi_rest[-1])
        self.released = 0.0  # clamp energy let go by tips released in the last solve [pJ]
        self._last = None  # (d, force, energy) of the last solve: what a record asks again
        self.iterations = 0  # Newton iterations of the last solve (largest over setae)

    @classmethod
    def of(cls, params, n_setae: int) -> Elastica:
        """The chains of ``n_setae`` setae of a :class:`gecko_agents.params.SetaArray`."""
        s = params.seta
        return cls(n_setae, s.L, s.r, params.contact.E1, s.theta, s.links, s.imperfection)

    def peek(self, d) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`solve` at ``d`` with the tips held as in the last solve, leaving the chain's
        state as it was (forces and energies at positions other than the step's)."""
        last = self._last
        if last is not None and np.array_equal(last[0], d):  # the step's own positions
            return last[1], last[2]
        kept = (self.phi, self.stretch, self.lam, self.iterations, self.held, self.clamp.copy(),
                self.released, last)  # fmt: skip
        try:
            return self.solve(d, self.held)
        finally:
            (self.phi, self.stretch, self.lam, self.iterations, self.held, self.clamp,
             self.released, self._last) = kept  # fmt: skip

    # ------------------------------------------------------------------ geometry
    def _end(self, phi, s):
        c, sn = np.cos(phi), np.sin(phi)
        x = self.ell * c.sum(1) + s * c[:, -1]
        y = self.ell * sn.sum(1) + s * sn[:, -1]
        return np.column_stack([x, y]), c, sn

    def rest_end(self) -> np.ndarray:
        """Root-to-tip vector of the stress-free chain [µm], shape (2,)."""
        c, s = np.cos(self.phi_rest), np.sin(self.phi_rest)
        return np.array([self.ell * c.sum(), self.ell * s.sum()])

    def energy(self, phi, s, held) -> np.ndarray:
        """V of each seta [pJ] (module docstring)."""
        psi = np.diff(np.column_stack([np.full(len(phi), self.root_angle), phi]), axis=1)
        psi0 = np.diff(np.concatenate([[self.root_angle], self.phi_rest]))
        V = 0.5 * np.sum(self.k[:-1] * (psi - psi0) ** 2, axis=1) + 0.5 * self.Ka * s * s
        tip = phi[:, -1] - self.clamp
        return V + np.where(held, 0.5 * self.k[-1] * tip * tip, 0.0)

    # ------------------------------------------------------------------ Newton
    def _system(self, phi, s, lam, d, held):
        N, n = phi.shape
        end, c, sn = self._end(phi, s)
        psi = np.diff(np.column_stack([np.full(N, self.root_angle), phi]), axis=1)
        psi0 = np.diff(np.concatenate([[self.root_angle], self.phi_rest]))
        tau = self.k[:-1] * (psi - psi0)  # joint torques τ_1..τ_n
        grad = tau.copy()
        grad[:, :-1] -= tau[:, 1:]
        kc = np.where(held, self.k[-1], 0.0)
        grad[:, -1] += kc * (phi[:, -1] - self.clamp)
        ell = np.full((N, n), self.ell)
        ell[:, -1] += s
        Jx, Jy = -ell * sn, ell * c  # ∂r/∂φ_j
        res = np.zeros((N, n + 3))
        res[:, :n] = grad - (lam[:, :1] * Jx + lam[:, 1:] * Jy)
        res[:, n] = self.Ka * s - (lam[:, 0] * c[:, -1] + lam[:, 1] * sn[:, -1])
        res[:, n + 1 :] = -(end - d)
        A = np.zeros((N, n + 3, n + 3))
        idx = np.arange(n)
        diag = self.k[:-1] + np.append(self.k[1:-1], 0.0)
        A[:, idx, idx] = diag + ell * (lam[:, :1] * c + lam[:, 1:] * sn)
        A[:, idx[-1], idx[-1]] += kc
        A[:, idx[:-1], idx[1:]] = -self.k[1:-1]
        A[:, idx[1:], idx[:-1]] = -self.k[1:-1]
        cross = lam[:, 0] * sn[:, -1] - lam[:, 1] * c[:, -1]  # −λ·∂²r/∂φ_n∂s
        A[:, n - 1, n] = A[:, n, n - 1] = cross
        A[:, n, n] = self.Ka
        A[:, :n, n + 1], A[:, :n, n + 2] = -Jx, -Jy
        A[:, n, n + 1], A[:, n, n + 2] = -c[:, -1], -sn[:, -1]
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
        beta = phi[gone, -1] - self.clamp[gone]
        self.released = float(np.sum(0.5 * self.k[-1] * beta * beta))
        self.clamp[new] = phi[new, -1]
        n = self.n
        f_tol = 1e-12 * max(self.EI / self.ell, self.Ka * self.L)
        x_tol = 1e-12 * self.L
        steps = 0
        for _ in range(_MAX_ITER):
            res, A = self._system(phi, s, lam, d, held)
            err_f = np.abs(res[:, : n + 1]).max(1)
            err_x = np.abs(res[:, n + 1 :]).max(1)
            todo = (err_f > f_tol) | (err_x > x_tol)
            if not todo.any():
                break
            step = np.linalg.solve(A[todo], -res[todo][..., None])[..., 0]
            # Keep a Newton step from turning a link by more than 0.2 rad (a fold's tangent).
            big = np.abs(step[:, :n]).max(1, keepdims=True)
            step *= np.minimum(1.0, 0.2 / np.maximum(big, 1e-300))
            phi[todo] += step[:, :n]
            s[todo] += step[:, n]
            lam[todo] += step[:, n + 1 :]
            steps += 1
        else:
            bad = np.flatnonzero(todo)
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
        self.iterations = steps
        self.phi, self.stretch, self.lam, self.held = phi, s, lam, held
        F, U = -lam, self.energy(phi, s, held)
        self._last = (d.copy(), F, U)
        return F, U

    def nodes(self, root) -> np.ndarray:
        """Positions of the chain's joints (N, n + 1, 2) [µm] for roots (N, 2) [µm], at the
        last solve (for drawing)."""
        c, sn = np.cos(self.phi), np.sin(self.phi)
        steps = np.stack([c, sn], axis=-1) * self.ell
        steps[:, -1] *= 1.0 + self.stretch[:, None] / self.ell
        out = np.concatenate([np.zeros((len(c), 1, 2)), np.cumsum(steps, axis=1)], axis=1)
        return out + np.asarray(root)[:, None, :]
