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

A law that needs the tip's tangential position (:attr:`ContactLaw.tangential`, the thin-film
:class:`SpatulaTip`) answers one question instead of ``radius``/``force``: ``step_scalar`` takes
the tip's offset from its peel front along the floor and its height, and returns both force
components and the new contact state (front shift, attached length, pre-tension, stored
energy, dissipation); the kernels call it per seta on pad floors. The sphere laws never reach
that branch, so their histories are unchanged.

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
    "SpatulaTip",
    "TIP_LAWS",
    "contact_law",
    "bounds",
    "mindlin_stiffness",
]


try:  # the scalar forms call it from inside numba-compiled code too
    from numba.extending import register_jitable as _jitable
except ImportError:  # numba is optional: then it is a plain function

    def _jitable(fn):
        return fn


@_jitable
def branch_radius(delta, R, ac):
    """Scalar :func:`jkr.radius_from_overlap`: contact radius on the stable JKR branch [µm]
    at overlap δ [µm] (clipped to δc), for R [µm] and the snap-off radius a_c [µm] (eq 10
    inverted by Ferrari's method plus one Newton step)."""
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
    tangential: bool = False  # the law takes the tip's tangential position (step_scalar)
    max_tension: float = math.nan  # largest tension a tip can hold [µN] (nan: Fc)
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
        return branch_radius(delta, k[0], k[1])

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
        E, R = k[3], k[0]
        return 2.0 * E * a * delta - 2.0 * E * a * a * a / (3.0 * R)

    @staticmethod
    def energy_scalar(a, delta, k):
        R, w, E = k[0], k[2], k[3]
        UE = E * (a * delta * delta - 2.0 * a * a * a * delta / (3.0 * R) + a**5 / (5.0 * R * R))
        return UE - math.pi * w * a * a - k[8]


try:  # the film's helpers are called from the compiled loop, so they are compiled too
    from numba import njit as _njit
except ImportError:  # pragma: no cover

    def _njit(**kwargs):
        return lambda f: f


@_njit(cache=True)
def _film_force(dx, zf, s0, K):
    """Tension F [µN] of the free film from the peel front to its end at horizontal offset dx
    and height zf [µm] (chord s = √(dx² + zf²)), unstretched length s0 [µm], K = E_f·h·b [µN]:
    F = K(s − s0)/s0 while taut, 0 while slack (a film carries no compression)."""
    s = math.sqrt(dx * dx + zf * zf)
    e = s - s0
    return (K * e / s0 if e > 0.0 else 0.0), s


@_njit(cache=True)
def _film_energy(dx, z, ell, p0, s0, k):
    """Energy the spatula contact stores [pJ], counted from attachment: free film
    ½K(s − s0)²/s0 + pre-strain of the attached film ℓ·P0²/(2K) + surface energy of the
    peeled film w·b·(ℓ0 − ℓ) + Hertz compression of the tip (8/15)E*√R·δ^(5/2)."""
    R, b, w, ell0, K, hz_u = k[0], k[1], k[4], k[5], k[6], k[8]
    zf = z - R if z > R else 0.0
    s = math.sqrt(dx * dx + zf * zf)
    e = s - s0
    U = 0.5 * K * e * e / s0 if e > 0.0 else 0.0
    U += ell * p0 * p0 / (2.0 * K) + w * b * (ell0 - ell)
    d = R - z
    if d > 0.0:
        U += hz_u * d * d * math.sqrt(d)
    return U


@_njit(cache=True)
def _release_rate(dx, zf, p0, s0, k):
    """Energy release rate per width g [µN/µm] of the peel front (−∂U/∂c per width, c the
    peeled length): g·b = −F cos φ + (F + F²/2K)/(1 + ε0) + P0²/(2K), ε0 = P0/K, cos φ = −dx/s.
    P0 = 0 is Kendall's F(1 − cos φ) + F²/(2E_f·h·b) (Kendall 1975, J Phys D 8:1449, eq 4 per
    width); to second order in the strains it is Chen, Wu & Gao's
    F(1 − cos φ) + (F − P0)²/(2E_f·h·b) (2009, J R Soc Interface 6:529)."""
    b, K = k[1], k[6]
    F, s = _film_force(dx, zf, s0, K)
    cos_phi = -dx / s if s > 0.0 else 0.0
    return (-F * cos_phi + (F + F * F / (2.0 * K)) / (1.0 + p0 / K) + p0 * p0 / (2.0 * K)) / b


@_njit(cache=True)
def _friction_cap(z, ell, k):
    """Friction cap of the attached pad [µN]: ``adhesive`` μ(P_c + 2Fc·ℓ/ℓ0) (Thornton's
    μ|P + 2Fc| with the adhesion of what is still attached) or ``paper`` μ·P_c (eq 27). P_c ≥ 0
    is the compression of the tip body: the film's pull acts at the peel front (Kendall's
    picture), the pad behind the front carries no normal load but its adhesion."""
    R, ell0, hz_f, mu, paper, Fc = k[0], k[5], k[7], k[9], k[10], k[11]
    d = R - z
    Pc = hz_f * d * math.sqrt(d) if d > 0.0 else 0.0
    if paper > 0.0:
        return mu * Pc
    return mu * (Pc + 2.0 * Fc * ell / ell0)


class SpatulaTip(ContactLaw):
    """A thin elastic film (spatula) of width b, thickness h, modulus E_f that hangs from the
    tip centre and is attached to the floor over a length ℓ (a state variable), peeling by an
    energy balance (Kendall 1975, J Phys D 8:1449) with the pre-tension dragging puts into the
    attached film (Chen, Wu & Gao 2009, J R Soc Interface 6:529). Pad floors only.

    Geometry (x along the floor, positive where the setae lean): the attached pad extends from
    the peel front towards +x (the film continues the seta's lean); the free film runs from the
    front to the bottom of the tip body (height z_f = max(z − R, 0) above the floor, z the tip
    centre's), chord s = √(dx² + z_f²), unstretched length s0, tension F = E_f·h·b(s − s0)/s0
    while taut (0 while slack). The peel angle φ between the free film and the floor away from
    the pad is cos φ = −dx/s, dx = x_tip − x_front: a tip pulled back over −x peels at small φ,
    a tip pushed over its pad at φ > 90°. On attachment (δ ≥ 0) the front sits under the tip,
    ℓ = ℓ0, s0 = h (the film turns under the tip body within its thickness), no pre-tension:
    the film then holds the pressed tip tangentially with stiffness E_f·b (K/s0).

    Every step, at the tip's position (a quasi-static front: the energy balance holds at the
    end of each step):

    1. **Slide.** The film pulls the front along the floor with F·|dx|/s; the pad slides towards
       the tip while that exceeds the friction cap, to where it equals it: adhesive
       μ(P_c + 2Fc·ℓ/ℓ0) — friction acts on what is still attached (Thornton's μ|P + 2Fc| with
       P_c ≥ 0 the tip body's compression: the film's pull acts at the front, the pad behind
       it carries only its adhesion; Fc = w·b) — or paper: μ·P_c (eq 27). Sliding away from
       the pad stretches the attached film: the pre-tension rises, P0² += 2K·cap·Δ/ℓ (the
       friction work at most), up to the cap.
    2. **Peel.** The front advances by dc (ℓ −= dc, s0 += dc/(1 + ε0): the pre-strained
       attached film enters the free film) to where the energy release rate per width
       g = [−F cos φ + (F + F²/2K)/(1 + ε0) + P0²/(2K)]/b equals w; if it still exceeds w at
       ℓ = 0 the film has peeled off: the tip lets go. With P0 = 0 the balance is Kendall's
       (F/b)(1 − cos φ) + (F/b)²/(2E_f·h) = w (eq 4 per width); to second order in the strains
       it is Chen, Wu & Gao's G = P(1 − cos φ) + (P − P0)²/(2E_f·h) (per width).
    3. **Forces.** On the tip: −F·(dx, z)/s from the film plus the Hertz compression
       (4/3)E*√R·δ^(3/2) of the tip body while δ = R − z > 0 (pressing).

    Stored energy U = ½K(s − s0)²/s0 + ℓP0²/(2K) + w·b(ℓ0 − ℓ) + (8/15)E*√R·δ^(5/2) [pJ] from
    attachment (K = E_f·h·b); a step's slide and peel dissipate U_before − U_after ≥ 0 at the
    tip's position (Coulomb work, and the release rate in excess of w), a release dissipates
    what is left.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], E* [MPa], w [µN/µm]).
    spatula : :class:`gecko_agents.params.Spatula` (b, h, length [µm], E_f [MPa]).
    friction : :class:`gecko_agents.params.Friction` (μ, law).
    """

    name = "spatula"
    tangential = True
    max_tension = math.inf  # a film at a small peel angle holds many w·b

    def __init__(self, contact, spatula, friction):
        R, w, E = contact.jkr_args()
        b, h, E_f, ell0 = spatula.b, spatula.h, spatula.E_f, spatula.length
        self.R, self.w, self.E_star = R, w, E
        self.b, self.h, self.E_f, self.ell0 = b, h, E_f, ell0
        self.K = E_f * h * b
        # Fc: the 90° peel force of an inextensible film, w·b (Kendall 1975).
        self.pull_off_force = w * b
        self.attach_overlap = 0.0
        # Backstop: a tip 3(ℓ0 + R) above the floor has stretched its film far past Kendall.
        self.detach_overlap = -3.0 * (ell0 + R)
        self.jump_radius = ell0
        self.a0 = ell0
        # The film's stiffness on attachment, K/h = E_f·b: the stiffest it gets (s0 ≥ h).
        self.s_attach = h
        self.tangential_stiffness = self.K / h
        self.zero_load_stiffness = self.K / h
        # k = (R, b, h, E_f, w, ℓ0, K, (4/3)E*√R, (8/15)E*√R, μ, paper, Fc, s0 on attachment)
        self.constants = np.array(
            [
                R,
                b,
                h,
                E_f,
                w,
                ell0,
                self.K,
                4.0 * E * math.sqrt(R) / 3.0,
                8.0 * E * math.sqrt(R) / 15.0,
                friction.mu,
                1.0 if friction.law == "paper" else 0.0,
                self.pull_off_force,
                h,
            ]
        )

    def stiffest(self, load: float) -> float:
        return 2 * self.E_star * float(jkr.hertz_contact_radius(load, self.R, self.E_star))

    def kendall_force(self, phi):
        """Steady peel force F [µN] of the film at peel angle φ [rad] without pre-tension:
        the root of (F/b)(1 − cos φ) + (F/b)²/(2E_f·h) = w (Kendall 1975, eq 4 per width)."""
        c = 1.0 - np.cos(phi)
        Eh = self.E_f * self.h
        return self.b * Eh * (np.sqrt(c * c + 2.0 * self.w / Eh) - c)

    def energy(self, a, delta):
        raise NotImplementedError("SpatulaTip stores its energy in the state (state.uc)")

    @staticmethod
    def step_scalar(dx, z, ell, p0, s0, k):
        """One step of the film at the tip's offset dx = x_tip − x_front and height z = y_tip −
        floor [µm] from state (ℓ, P0, s0). Returns (P, T, shift, ℓ, P0, s0, U, dissipation,
        slid): normal force P [µN] (> 0 compressive), tangential force on the tip T [µN]
        (along +x), front displacement along +x [µm], the new state, the stored energy U [pJ],
        U_before − U_after [pJ] and whether the pad slid (1.0) or not (0.0)."""
        R, K, hz_f = k[0], k[6], k[7]
        zf = z - R if z > R else 0.0  # height of the film's end (the tip body's bottom)
        U0 = _film_energy(dx, z, ell, p0, s0, k)
        shift = 0.0
        slid = 0.0
        # 1. Slide: the pad moves towards the tip while the film's pull exceeds the cap.
        F, s = _film_force(dx, zf, s0, K)
        Fh = F * abs(dx) / s if s > 0.0 else 0.0
        cap = _friction_cap(z, ell, k)
        if Fh > cap:
            sgn = 1.0 if dx > 0.0 else -1.0
            lo, hi = 0.0, abs(dx)
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                dm = dx - sgn * mid
                Fm, sm = _film_force(dm, zf, s0, K)
                if Fm * abs(dm) / sm > cap:
                    lo = mid
                else:
                    hi = mid
            if dx < 0.0 and ell > 0.0:  # pulled away from the pad: friction pre-stretches it
                p2 = p0 * p0 + 2.0 * K * cap * hi / ell
                p0 = min(math.sqrt(p2), cap) if cap > p0 else p0
            shift = sgn * hi
            dx -= shift
            slid = 1.0
        # 2. Peel: advance the front until g = w; a film still above w at ℓ = 0 has let go.
        w = k[4]
        if ell > 0.0 and _release_rate(dx, zf, p0, s0, k) > w:
            grow = 1.0 / (1.0 + p0 / K)
            if _release_rate(dx - ell, zf, p0, s0 + ell * grow, k) > w:
                dc = ell
            else:
                lo, hi = 0.0, ell
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    if _release_rate(dx - mid, zf, p0, s0 + mid * grow, k) > w:
                        lo = mid
                    else:
                        hi = mid
                dc = hi
            dx -= dc
            shift += dc
            s0 += dc * grow
            ell -= dc
            if ell < 1e-9 * k[5]:
                ell = 0.0
        # 3. Forces on the tip and the energy left.
        F, s = _film_force(dx, zf, s0, K)
        d = R - z
        P = hz_f * d * math.sqrt(d) if d > 0.0 else 0.0
        T = 0.0
        if s > 0.0:
            P -= F * zf / s
            T = -F * dx / s
        U = _film_energy(dx, z, ell, p0, s0, k)
        return P, T, shift, ell, p0, s0, U, U0 - U, slid


TIP_LAWS: dict[str, type[ContactLaw]] = {
    "sphere": JKRSphere,
    "hertz": HertzSphere,
    "spatula": SpatulaTip,
}
"""Tip laws by the name ``params.tip`` selects."""


def bounds(law: ContactLaw) -> dict:
    """What :func:`gecko_agents.history.invariant_violations` may assume of a law's histories:
    the largest tension one tip holds [µN] (inf for a rate-dependent contact, whose crack lags),
    the overlap below which no tip stays attached [µm], and whether the law is rate dependent."""
    tension = math.inf if law.rate_dependent else law.pull_off_force
    if not math.isnan(law.max_tension):  # the law's own bound (a film holds many w·b)
        tension = law.max_tension
    return {"max_tension_uN": tension, "detach_overlap_um": law.detach_overlap,
            "rate_dependent": bool(law.rate_dependent)}  # fmt: skip


def contact_law(params) -> ContactLaw:
    """The contact law of a :class:`gecko_agents.params.SetaArray`: ``params.tip``, with crack
    kinetics (:class:`RateJKRSphere`) for a sphere of finite ``contact.crack_speed``."""
    if params.tip == "sphere" and math.isfinite(getattr(params.contact, "crack_speed", math.inf)):
        return RateJKRSphere(params.contact)
    if params.tip == "spatula":
        return SpatulaTip(params.contact, params.spatula, params.friction)
    return TIP_LAWS[params.tip](params.contact)
