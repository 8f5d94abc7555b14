"""Tip contact laws: one small interface, one class per law, chosen by name in the parameters.

Units: µm, µN, µs, pJ (:mod:`gecko_agents.params`). Sign convention (everywhere): the overlap
δ > 0 when the tip sphere is pressed into the floor; the normal force P > 0 when the floor
pushes the tip away (compression) and P < 0 in adhesion (tension).

A law answers the few questions the time-stepped model asks of a contact, as LAMMPS's granular
sub-models do (``touch``, ``pulloff_distance``, ``calculate_forces``, ``set_fncrit``):

* :meth:`ContactLaw.radius` — contact radius a(δ) on the law's branch [µm];
* :meth:`ContactLaw.force` — normal force P(a) [µN];
* :meth:`ContactLaw.energy` — energy stored in the contact from touch-down to radius a [pJ]
  (dU/dδ = P), which a snap-off dissipates;
* :attr:`ContactLaw.attach_overlap` / :attr:`ContactLaw.detach_overlap` — a free tip attaches
  at δ ≥ δ_attach; an attached tip lets go below δ_detach;
* :attr:`ContactLaw.tangential_stiffness` — the stick spring of Coulomb friction [µN/µm];
* :attr:`ContactLaw.pull_off_force` — Fc [µN], which the adhesive friction cap μ|P + 2Fc| uses.

Each law gives the same formulas twice, kept side by side so that they cannot drift apart:
vectorized numpy methods (the general floor path, recording, energies) and scalar
``@staticmethod`` functions of ``(x, k)`` with ``k`` the law's constants
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

__all__ = ["ContactLaw", "JKRSphere", "HertzSphere", "TIP_LAWS", "contact_law", "mindlin_stiffness"]


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
    attach_overlap: float = 0.0  # δ at which a free tip attaches [µm]
    detach_overlap: float  # δ below which an attached tip lets go [µm]
    jump_radius: float  # contact radius at attachment [µm]
    pull_off_force: float  # Fc [µN] (0 without adhesion)
    tangential_stiffness: float  # Mindlin stick stiffness [µN/µm]
    zero_load_stiffness: float  # dP/dδ at P = 0 [µN/µm] (damping scale)
    constants: np.ndarray  # constants of the scalar functions

    def radius(self, delta: np.ndarray) -> np.ndarray:
        """Contact radius a [µm] at overlaps δ [µm] (δ ≥ δ_detach)."""
        raise NotImplementedError

    def force(self, a: np.ndarray) -> np.ndarray:
        """Normal force P [µN] at contact radius a [µm]."""
        raise NotImplementedError

    def energy(self, a: np.ndarray) -> np.ndarray:
        """Energy stored in the contact at radius a, from attachment [pJ]."""
        raise NotImplementedError

    def stiffest(self, load: float) -> float:
        """Contact stiffness dP/dδ [µN/µm] at a compressive load [µN] (time-step bound)."""
        raise NotImplementedError

    @staticmethod
    def radius_scalar(delta: float, k: np.ndarray) -> float:
        """Scalar :meth:`radius` for the per-seta loop."""
        raise NotImplementedError

    @staticmethod
    def force_scalar(a: float, k: np.ndarray) -> float:
        """Scalar :meth:`force`."""
        raise NotImplementedError

    @staticmethod
    def energy_scalar(a: float, k: np.ndarray) -> float:
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

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], moduli [MPa], w [µN/µm]).
    """

    name = "sphere"

    def __init__(self, contact):
        R, w, E = contact.jkr_args()
        self.R, self.w, self.E_star = R, w, E
        self.pull_off_force = float(jkr.pull_off_force(R, w))
        self.detach_overlap = float(jkr.snap_off_overlap(R, w, E))
        self.ac = float(jkr.snap_off_radius(R, w, E))
        # U(a_jump) = 0: the radius where δ = 0 on the branch.
        self.jump_radius = float(np.cbrt((math.sqrt(2 * math.pi * w / E) * R) ** 2))
        a0 = float(jkr.zero_load_contact_radius(R, w, E))
        self.a0 = a0
        self.tangential_stiffness = mindlin_stiffness(contact, a0)
        self.zero_load_stiffness = 2 * E * a0
        # k = (R, ac, 4E*/(3R), 8πwE*, w, E*, U(a_jump)); U(a_jump) from the scalar form itself.
        self.constants = np.array(
            [R, self.ac, 4.0 * E / (3.0 * R), 8.0 * math.pi * w * E, w, E, 0.0]
        )
        self.constants[6] = self.energy_scalar(self.jump_radius, self.constants)

    def stiffest(self, load: float) -> float:
        a = float(jkr.contact_radius_from_force(load, self.R, self.w, self.E_star))
        return 2 * self.E_star * a

    def radius(self, delta):
        """:func:`jkr.radius_from_overlap` (Ferrari's closed form + one Newton step), written
        with fewer temporaries for the hot path."""
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

    def force(self, a):
        """:func:`jkr.force_from_radius` (eq 7)."""
        a3 = a * a
        a3 *= a
        root = np.multiply(a3, 8.0 * math.pi * self.w * self.E_star)
        np.sqrt(root, out=root)
        a3 *= 4.0 * self.E_star / (3.0 * self.R)
        a3 -= root
        return a3

    def energy(self, a):
        """:func:`jkr.contact_energy`: U(a) − U(a_jump), dU/dδ = P."""
        return jkr.contact_energy(a, self.R, self.w, self.E_star)

    @staticmethod
    def radius_scalar(delta, k):
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
    def force_scalar(a, k):
        a3 = a * a * a
        return a3 * k[2] - math.sqrt(a3 * k[3])

    @staticmethod
    def energy_scalar(a, k):
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

    def radius(self, delta):
        return np.sqrt(np.maximum(delta, 0.0) * self.R)

    def force(self, a):
        return (4.0 * self.E_star / (3.0 * self.R)) * a * a * a

    def energy(self, a):
        return (8.0 * self.E_star / (15.0 * self.R * self.R)) * a**5

    @staticmethod
    def radius_scalar(delta, k):
        return math.sqrt(delta * k[0]) if delta > 0.0 else 0.0

    @staticmethod
    def force_scalar(a, k):
        return k[1] * a * a * a

    @staticmethod
    def energy_scalar(a, k):
        return k[2] * a**5


TIP_LAWS: dict[str, type[ContactLaw]] = {"sphere": JKRSphere, "hertz": HertzSphere}
"""Tip laws by the name ``params.tip`` selects."""


def contact_law(params) -> ContactLaw:
    """The contact law of a :class:`gecko_agents.params.SetaArray` (``params.tip``)."""
    return TIP_LAWS[params.tip](params.contact)
