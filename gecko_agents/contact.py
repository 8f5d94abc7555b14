"""Tip contact laws: one small interface, one class per law, chosen by name in the parameters.

Units: µm, µN, µs, pJ (:mod:`gecko_agents.params`). Sign convention (everywhere): the overlap
δ > 0 when the tip sphere is pressed into the floor; the normal force P > 0 when the floor
pushes the tip away (compression) and P < 0 in adhesion (tension).

A law answers the few questions the time-stepped model asks of a contact, as LAMMPS's granular
sub-models do (``touch``, ``pulloff_distance``, ``calculate_forces``, ``set_fncrit``):

* :meth:`ContactLaw.radius` — contact radius a [µm] after a step of dt [µs] at overlap δ [µm]
  from the previous radius (an elastic law ignores both: a(δ) on its branch; a rate-dependent
  law integrates its edge's motion);
* :meth:`ContactLaw.force` — normal force P(a, δ) [µN];
* :meth:`ContactLaw.energy` — energy stored in the contact at (a, δ) counted from attachment
  [pJ] (∂U/∂δ = P), which a snap-off dissipates;
* :attr:`ContactLaw.attach_overlap` / :attr:`ContactLaw.detach_overlap` — a free tip attaches
  at δ ≥ δ_attach; an attached tip lets go below δ_detach, or (rate-dependent laws) once its
  radius has fallen to :attr:`ContactLaw.release_radius`;
* :attr:`ContactLaw.tangential_stiffness` — the stick spring of Coulomb friction [µN/µm];
* :attr:`ContactLaw.pull_off_force` — Fc [µN], which the adhesive friction cap μ|P + 2Fc| uses.

Each law gives the same formulas twice, kept side by side so that they cannot drift apart:
vectorized numpy methods (the general floor path, recording, energies) and scalar
``@staticmethod`` functions with ``k``, the law's constants, as last argument
(:attr:`ContactLaw.constants`, a float64 array) that the per-seta loop calls, compiled by numba
or interpreted (:mod:`gecko_agents.kernels`). ``tests/test_contact.py`` pins both forms of every
law to its closed form (:mod:`gecko_agents.jkr`) point by point.

Adding a law: write one subclass here with the methods above, register it in :data:`TIP_LAWS`,
add its tests. Nothing in the model changes.
"""

from __future__ import annotations

import math

import numpy as np

from . import jkr

__all__ = [
    "ContactLaw",
    "JKRSphere",
    "RateJKRSphere",
    "HertzSphere",
    "TIP_LAWS",
    "contact_law",
    "mindlin_stiffness",
]


def mindlin_stiffness(contact, a: float) -> float:
    """Tangential stick stiffness k_t = 8G*·a of a circular contact of radius a [µN/µm].

    Mindlin (1949, J Appl Mech 16:259); G* = ((2−ν1)/G1 + (2−ν2)/G2)⁻¹, G = E/(2(1+ν))
    (Johnson, Contact Mechanics, 1985, §7.2).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (E in MPa). a : contact radius [µm].
    """
    G1, G2 = contact.E1 / (2 * (1 + contact.nu1)), contact.E2 / (2 * (1 + contact.nu2))
    G_star = 1.0 / ((2 - contact.nu1) / G1 + (2 - contact.nu2) / G2)
    return 8.0 * G_star * a


class ContactLaw:
    """The interface (see the module docstring). Subclasses set the attributes in
    ``__init__`` and implement the vectorized and scalar methods."""

    name: str = ""
    rate_dependent: bool = False  # the radius is a state variable (crack kinetics)
    release_radius: float = 0.0  # a rate-dependent tip lets go at a ≤ this [µm]
    attach_overlap: float = 0.0  # δ at which a free tip attaches [µm]
    detach_overlap: float  # δ below which an attached tip lets go [µm]
    jump_radius: float  # contact radius at attachment [µm]
    pull_off_force: float  # Fc [µN] (0 without adhesion)
    tangential_stiffness: float  # Mindlin stick stiffness [µN/µm]
    zero_load_stiffness: float  # dP/dδ at P = 0 [µN/µm] (damping scale)
    constants: np.ndarray  # constants of the scalar functions

    def radius(self, delta, a_prev, dt: float):
        """Contact radius a [µm] after a step dt [µs] at overlaps δ [µm] from radii a_prev."""
        raise NotImplementedError

    def force(self, a, delta):
        """Normal force P [µN] at contact radius a [µm] and overlap δ [µm]."""
        raise NotImplementedError

    def energy(self, a, delta):
        """Energy stored in the contact at (a, δ), from attachment [pJ]."""
        raise NotImplementedError

    def stiffest(self, load: float) -> float:
        """Contact stiffness dP/dδ [µN/µm] at a compressive load [µN] (time-step bound)."""
        raise NotImplementedError

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        """Scalar :meth:`radius` for the per-seta loop."""
        raise NotImplementedError

    @staticmethod
    def force_scalar(a, delta, k):
        """Scalar :meth:`force`."""
        raise NotImplementedError

    @staticmethod
    def energy_scalar(a, delta, k):
        """Scalar :meth:`energy`."""
        raise NotImplementedError


class JKRSphere(ContactLaw):
    """An elastic sphere of radius R on a flat, JKR adhesion (paper eq 1–15; Johnson, Kendall &
    Roberts 1971, Proc R Soc A 324:301).

    The tip attaches at δ = 0 (no long-range force: it jumps in to P = −(8/9)Fc), follows the
    stable branch P(a) = 4E*a³/(3R) − √(8πwE*a³) (eq 7), δ(a) = a²/R − √(2πwa/E*) (eq 10), and
    lets go past δc = −(3/4)(π²w²R/E*²)^(1/3) where the branch ends (displacement control). A
    tip on a soft seta leaves its equilibrium earlier, at the fold of the spring–contact
    system; the model finds that dynamically.

    Where it lets go follows ``contact.detachment``: ``"fold"`` past δc (above), ``"delta_s"``
    past the paper's δs = −0.21·a0²/R (eq 8), ``"load_control"`` past the overlap where
    P = −Fc on the branch, δ_lc = −a_lc²/(3R) with a_lc = (9πwR²/(8E*))^(1/3) (Johnson 1985,
    §5.5). Radius, force and energy depend on δ alone (the branch).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], moduli [MPa], w [µN/µm]).
    """

    name = "sphere"

    def __init__(self, contact):
        R, w, E = contact.jkr_args()
        self.R, self.w, self.E_star = R, w, E
        self.pull_off_force = float(jkr.pull_off_force(R, w))
        self.ac = float(jkr.snap_off_radius(R, w, E))
        a0 = float(jkr.zero_load_contact_radius(R, w, E))
        a_lc = (9.0 * math.pi * w * R * R / (8.0 * E)) ** (1.0 / 3.0)
        self.detach_overlap = {
            "fold": float(jkr.snap_off_overlap(R, w, E)),
            "delta_s": -0.21 * a0 * a0 / R,
            "load_control": -(a_lc * a_lc) / (3.0 * R),
        }[getattr(contact, "detachment", "fold")]
        # U(a_jump) = 0: the radius where δ = 0 on the branch.
        self.jump_radius = float(np.cbrt((math.sqrt(2 * math.pi * w / E) * R) ** 2))
        self.a0 = a0
        self.tangential_stiffness = mindlin_stiffness(contact, a0)
        self.zero_load_stiffness = 2 * E * a0
        # k = (R, ac, 4E*/(3R), 8πwE*, w, E*, U(a_jump)); U(a_jump) from the scalar form itself.
        self.constants = np.array(
            [R, self.ac, 4.0 * E / (3.0 * R), 8.0 * math.pi * w * E, w, E, 0.0]
        )
        self.constants[6] = JKRSphere.energy_scalar(self.jump_radius, 0.0, self.constants)

    def stiffest(self, load: float) -> float:
        a = float(jkr.contact_radius_from_force(load, self.R, self.w, self.E_star))
        return 2 * self.E_star * a

    def radius(self, delta, a_prev=None, dt=0.0):
        """:func:`jkr.radius_from_overlap` (Ferrari's closed form + one Newton step), written
        with fewer temporaries for the hot path; the previous radius does not matter."""
        ac = self.ac
        d = delta * (self.R / (ac * ac))
        np.maximum(d, -3.0, out=d)
        disc = d * d
        disc *= d
        disc *= 1.0 / 27.0
        disc += 1.0
        np.sqrt(disc, out=disc)
        disc += 1.0
        A = np.cbrt(disc, out=disc)
        Bp = d / (3.0 * A)
        den = A * A
        den += d * (1.0 / 3.0)  # A·Bp = d/3
        den += Bp * Bp
        m = np.divide(2.0, den, out=den)
        inner = np.divide(2.0, m, out=Bp)
        np.sqrt(inner, out=inner)
        inner *= 4.0
        inner -= 2.0 * m
        np.maximum(inner, 0.0, out=inner)
        np.sqrt(inner, out=inner)
        m *= 2.0
        u = np.sqrt(m, out=m)
        u += inner
        u *= 0.5
        # One Newton step on u⁴ − 4u − d where 4u³ − 4 > 1e-3 (as jkr.radius_from_overlap).
        u2 = u * u
        f = u2 * u2
        f -= 4.0 * u
        f -= d
        fp = np.multiply(u2, u, out=u2)
        fp -= 1.0
        fp *= 4.0
        if fp.min() > 1e-3:
            f /= fp
            u -= f
        else:
            safe = fp > 1e-3
            u = np.where(safe, u - f / np.where(safe, fp, 1.0), u)
        np.maximum(u, 1.0, out=u)
        u *= u
        u *= ac
        return u

    def force(self, a, delta=None):
        """:func:`jkr.force_from_radius` (eq 7)."""
        a3 = a * a
        a3 *= a
        root = np.multiply(a3, 8.0 * math.pi * self.w * self.E_star)
        np.sqrt(root, out=root)
        a3 *= 4.0 * self.E_star / (3.0 * self.R)
        a3 -= root
        return a3

    def energy(self, a, delta=None):
        """:func:`jkr.contact_energy`: U(a) − U(a_jump), dU/dδ = P."""
        return jkr.contact_energy(a, self.R, self.w, self.E_star)

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        R, ac = k[0], k[1]
        d = delta * (R / (ac * ac))
        if d < -3.0:
            d = -3.0
        disc = math.sqrt(d * d * d * (1.0 / 27.0) + 1.0)
        A = np.cbrt(disc + 1.0)
        Bp = d / (3.0 * A)
        m = 2.0 / (A * A + d * (1.0 / 3.0) + Bp * Bp)
        inner = math.sqrt(2.0 / m) * 4.0 - 2.0 * m
        if inner < 0.0:
            inner = 0.0
        u = (math.sqrt(m * 2.0) + math.sqrt(inner)) * 0.5
        u2 = u * u
        fp = (u2 * u - 1.0) * 4.0
        if fp > 1e-3:
            u -= (u2 * u2 - 4.0 * u - d) / fp
        if u < 1.0:
            u = 1.0
        return (u * u) * ac

    @staticmethod
    def force_scalar(a, delta, k):
        a3 = a * a * a
        return a3 * k[2] - math.sqrt(a3 * k[3])

    @staticmethod
    def energy_scalar(a, delta, k):
        R, w, E = k[0], k[4], k[5]
        A = 4.0 * E / (3.0 * R)
        B = math.sqrt(8.0 * math.pi * w * E)
        C = math.sqrt(2.0 * math.pi * w / E)
        U = (
            2.0 * A * a**5 / (5.0 * R)
            - (A * C / 7.0 + 4.0 * B / (7.0 * R)) * a**3.5
            + math.pi * w * a * a
        )
        return U - k[6]


class HertzSphere(ContactLaw):
    """An elastic sphere on a flat without adhesion (Hertz 1882; paper eq 1–3; Johnson,
    Contact Mechanics, 1985, §4.2): a = √(Rδ), P = (4E*/3R)·a³ = (4/3)E*√R·δ^(3/2),
    U = (8/15)E*√R·δ^(5/2).

    The tip touches at δ = 0 and lets go when δ < 0; Fc = 0, so the adhesive friction cap
    μ|P + 2Fc| becomes Amontons' μP. The stick stiffness is Mindlin's at the radius the contact
    has under the load Fc_ref of the JKR law with the same materials (a Hertz contact has no
    zero-load radius), so that both laws share a time-step scale.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (w is not used).
    """

    name = "hertz"

    def __init__(self, contact):
        R, w, E = contact.jkr_args()
        self.R, self.E_star = R, E
        self.pull_off_force = 0.0
        self.detach_overlap = 0.0
        self.jump_radius = 0.0
        a_ref = float(jkr.hertz_contact_radius(jkr.pull_off_force(R, w), R, E))
        self.a0 = a_ref
        self.tangential_stiffness = mindlin_stiffness(contact, a_ref)
        self.zero_load_stiffness = 2 * E * a_ref
        self.constants = np.array([R, 4.0 * E / (3.0 * R), 8.0 * E / (15.0 * R * R)])

    def stiffest(self, load: float) -> float:
        return 2 * self.E_star * float(jkr.hertz_contact_radius(load, self.R, self.E_star))

    def radius(self, delta, a_prev=None, dt=0.0):
        return np.sqrt(np.maximum(delta, 0.0) * self.R)

    def force(self, a, delta=None):
        return (4.0 * self.E_star / (3.0 * self.R)) * a * a * a

    def energy(self, a, delta=None):
        return (8.0 * self.E_star / (15.0 * self.R * self.R)) * a**5

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        return math.sqrt(delta * k[0]) if delta > 0.0 else 0.0

    @staticmethod
    def force_scalar(a, delta, k):
        return k[1] * a * a * a

    @staticmethod
    def energy_scalar(a, delta, k):
        return k[2] * a**5


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
        # k = (R, ac, w, E*, v*, 1/n, v_close, δc, U(a_j, 0) + πw·a_j²)
        self.constants = np.array(
            [R, self.ac, w, E, self.v_star, 1.0 / self.n_exp, self.v_close, self.delta_c, 0.0]
        )
        self.constants[8] = self.energy_scalar(self.jump_radius, 0.0, self.constants)

    def radius(self, delta, a_prev, dt):
        k = self.constants
        return np.array(
            [
                self.radius_scalar(float(d), float(a), dt, k)
                for d, a in zip(np.ravel(delta), np.ravel(a_prev), strict=True)
            ]
        )

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
        R, ac, w, E, v_star, inv_n, v_close, delta_c = (
            k[0],
            k[1],
            k[2],
            k[3],
            k[4],
            k[5],
            k[6],
            k[7],
        )
        a = a_prev
        # Equilibrium radius on the stable branch (as JKRSphere.radius_scalar), if any.
        has_eq = delta >= delta_c
        a_eq = 0.0
        if has_eq:
            d = delta * (R / (ac * ac))
            disc = math.sqrt(d * d * d * (1.0 / 27.0) + 1.0)
            A = np.cbrt(disc + 1.0)
            Bp = d / (3.0 * A)
            m = 2.0 / (A * A + d * (1.0 / 3.0) + Bp * Bp)
            inner = math.sqrt(2.0 / m) * 4.0 - 2.0 * m
            if inner < 0.0:
                inner = 0.0
            u = (math.sqrt(m * 2.0) + math.sqrt(inner)) * 0.5
            u2 = u * u
            fp = (u2 * u - 1.0) * 4.0
            if fp > 1e-3:
                u -= (u2 * u2 - 4.0 * u - d) / fp
            if u < 1.0:
                u = 1.0
            a_eq = (u * u) * ac
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
        E, R = k[3], k[0]
        return 2.0 * E * a * delta - 2.0 * E * a * a * a / (3.0 * R)

    @staticmethod
    def energy_scalar(a, delta, k):
        R, w, E = k[0], k[2], k[3]
        UE = E * (a * delta * delta - 2.0 * a * a * a * delta / (3.0 * R) + a**5 / (5.0 * R * R))
        return UE - math.pi * w * a * a - k[8]


TIP_LAWS: dict[str, type[ContactLaw]] = {"sphere": JKRSphere, "hertz": HertzSphere}
"""Tip laws by the name ``params.tip`` selects."""


def contact_law(params) -> ContactLaw:
    """The contact law of a :class:`gecko_agents.params.SetaArray`: ``params.tip``, with crack
    kinetics (:class:`RateJKRSphere`) for a sphere of finite ``contact.crack_speed``."""
    if params.tip == "sphere" and math.isfinite(getattr(params.contact, "crack_speed", math.inf)):
        return RateJKRSphere(params.contact)
    return TIP_LAWS[params.tip](params.contact)
