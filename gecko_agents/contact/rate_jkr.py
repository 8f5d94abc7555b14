"""The JKR sphere with crack kinetics at its contact edge: :class:`RateJKRSphere`."""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.contact.base import branch_radius
from gecko_agents.contact.jkr_sphere import JKRSphere
from gecko_agents.physics import jkr

__all__ = ["RateJKRSphere"]

# Indices of RateJKRSphere.constants (k), what the scalar functions read.
K_R = 0  # tip radius R [µm]
K_AC = 1  # snap-off radius a_c [µm]
K_W = 2  # work of adhesion w [µN/µm]
K_E = 3  # effective modulus E* [MPa]
K_V_OPEN = 4  # crack opening speed v* [µm/µs]
K_INV_N = 5  # 1/n, the crack exponent's inverse [-]
K_V_CLOSE = 6  # crack closing speed [µm/µs]
K_DELTA_C = 7  # snap-off overlap δc [µm]
K_U_JUMP = 8  # U(a_j, 0) + πw·a_j² [pJ]: the energy is 0 at attachment


class RateJKRSphere(JKRSphere):
    """A JKR sphere whose contact edge moves at a finite speed: crack kinetics (Maugis &
    Barquins 1978, J Phys D 11:1989; Greenwood & Johnson 1981, Phil Mag A 43:697; Maugis,
    *Contact, Adhesion and Rupture of Elastic Solids*, 2000, ch 5).

    The radius a is a state variable. At any (a, δ) the sphere carries (flat punch + Hertz)

        P(a, δ) = 2E*aδ − 2E*a³/(3R),     U_E(a, δ) = E*(aδ² − 2a³δ/(3R) + a⁵/(5R²)),

    and its edge sees the energy release rate G = ∂U_E/∂a / (2πa) = E*(a²/R − δ)²/(2πa); G = w
    is the elastic JKR branch. Where a²/R − δ > √(2πwa/E*) (G > w, the edge in tension) the
    crack opens, ȧ = −v*·((G − w)/w)^(1/n); elsewhere it closes onto the equilibrium radius, at
    once or at ``crack_closing_speed``·((w − G)/w)^(1/n). The stored energy is
    U = U_E − πwa², counted from attachment (a_j at δ = 0, as :class:`JKRSphere`); a moving
    edge dissipates ∫(G − w)·2πa·|da| ≥ 0, which the kernels book as
    U(a_old, δ) − U(a_new, δ). The tip lets go once a ≤ :attr:`release_radius` = 1 % of a0,
    where it carries < 1 % of its zero-load contact stiffness: the crack has run through; a step
    that would shrink a by more than 10 % (a runaway the time step cannot resolve) sets a = 0,
    a snap-off; as a backstop it also lets go once stretched past 20·|δc|.

    Integration (per time step, at the step's δ): linearly implicit Euler — one Newton step of
    backward Euler on f(a) = a − a_prev + dt·v*·((G(a) − w)/w)^(1/n) from a_prev, clipped to
    [a_eq(δ), a_prev] while an equilibrium exists (δ ≥ δc), to [0, a_prev] otherwise; an explicit
    step where ∂G/∂a ≤ 0 (the edge then runs away whatever the scheme). Implicit because the
    rate law is stiff where G − w is large (ȧ/a ≫ 1/dt as a → 0); the clip keeps the radius
    from stepping past the equilibrium it relaxes to. v* = ∞ is :class:`JKRSphere`.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` with a finite ``crack_speed`` [µm/µs],
        ``crack_exponent`` n and ``crack_closing_speed`` [µm/µs].
    """

    name = "sphere (crack kinetics)"
    rate_dependent = True
    # Its edge jumps closed during a jump-in's ring-down: a first-order error of 0.7–2 % of the
    # run's energy at the default step, halving with dt.
    energy_tolerance_factor = 2.0

    def __init__(self, contact):
        super().__init__(contact)
        self.v_star = float(contact.crack_speed)
        self.n_exp = float(contact.crack_exponent)
        self.v_close = float(contact.crack_closing_speed)
        self.release_radius = 0.01 * self.a0
        self.delta_c = float(jkr.snap_off_overlap(self.R, self.w, self.E_star))
        # A slow crack holds the tip past δc; stretched beyond 20·|δc| (an effective work of
        # adhesion ~90 w: far outside what the rate law is meant for) it lets go regardless.
        self.detach_overlap = 20.0 * self.delta_c
        R, w, E = self.R, self.w, self.E_star
        k = self.constants = np.zeros(9)
        k[K_R], k[K_AC], k[K_W], k[K_E] = R, self.ac, w, E
        k[K_V_OPEN], k[K_INV_N], k[K_V_CLOSE] = self.v_star, 1.0 / self.n_exp, self.v_close
        k[K_DELTA_C] = self.delta_c
        k[K_U_JUMP] = self.energy_scalar(self.jump_radius, 0.0, k)

    def radius(self, delta, a_prev, dt):
        k = self.constants
        return np.array(
            [
                self.radius_scalar(float(d), float(a), dt, k)
                for d, a in zip(np.ravel(delta), np.ravel(a_prev), strict=True)
            ]
        )

    def stiffness(self, a, delta):
        """∂P/∂δ = 2E*a at the step's radius: the crack edge does not move within a step
        (Barquins & Maugis 1981's P(a, δ), the force differentiated at fixed a)."""
        return 2.0 * self.E_star * np.asarray(a, dtype=float)

    def force(self, a, delta):
        E, R = self.E_star, self.R
        return 2.0 * E * a * delta - 2.0 * E * a * a * a / (3.0 * R)

    def energy(self, a, delta):
        k = self.constants
        return np.array(
            [
                self.energy_scalar(float(x), float(d), k)
                for x, d in zip(np.ravel(a), np.ravel(delta), strict=True)
            ]
        )

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        R, ac, w, E = k[K_R], k[K_AC], k[K_W], k[K_E]
        v_star, inv_n, v_close, delta_c = k[K_V_OPEN], k[K_INV_N], k[K_V_CLOSE], k[K_DELTA_C]
        a = a_prev
        # Equilibrium radius on the stable branch, if any.
        has_eq = delta >= delta_c
        a_eq = 0.0
        if has_eq:
            a_eq = branch_radius(delta, R, ac)
        g = a * a / R - delta
        opening = a > 0.0 and g > math.sqrt(2.0 * math.pi * w * a / E)
        if not opening:
            if not has_eq:
                return a
            if v_close == math.inf or a >= a_eq or g <= 0.0:
                return a_eq  # (g ≤ 0: the edge is in compression, it closes at once)
            G = E * g * g / (2.0 * math.pi * a)
            a_new = a + dt * v_close * ((w - G) / w) ** inv_n
            return a_new if a_new < a_eq else a_eq
        G = E * g * g / (2.0 * math.pi * a)
        x = (G - w) / w
        rate = v_star * x**inv_n
        dG = E * g * (3.0 * a * a / R + delta) / (2.0 * math.pi * a * a)
        fprime = 1.0 + dt * v_star * inv_n * x ** (inv_n - 1.0) * dG / w
        step = dt * rate
        if dG > 0.0:
            step /= fprime
        if step > 0.1 * a:
            # The edge runs through faster than the time step resolves: a snap-off. Releasing
            # now books the stored energy exactly (as the elastic snap-off does) instead of
            # integrating an unresolved runaway to first order.
            return 0.0
        a_new = a - step
        lo = a_eq if has_eq else 0.0
        if a_new < lo:
            a_new = lo
        return a_new

    @staticmethod
    def force_scalar(a, delta, k):
        E, R = k[K_E], k[K_R]
        return 2.0 * E * a * delta - 2.0 * E * a * a * a / (3.0 * R)

    @staticmethod
    def energy_scalar(a, delta, k):
        R, w, E = k[K_R], k[K_W], k[K_E]
        UE = E * (a * delta * delta - 2.0 * a * a * a * delta / (3.0 * R) + a**5 / (5.0 * R * R))
        return UE - math.pi * w * a * a - k[K_U_JUMP]
