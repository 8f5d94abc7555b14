"""The contact-law interface (:class:`ContactLaw`) and the scalar helpers several laws share.

Units and sign conventions: :mod:`gecko_agents.contact`.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.physics._util import jitable
from gecko_agents.physics.friction import combined_shear_modulus, stick_stiffness

__all__ = [
    "ContactLaw",
    "K_ATTACH_RADIUS",
    "K_ATTACH_FILM",
    "branch_radius",
    "jitable",
    "mindlin_stiffness",
]

# Slots every tangential law (``tangential = True``) fills in its constants k: what the kernels
# give a tip on attachment, its state ``a`` (contact radius, or the film's attached length) [µm]
# and its free film's unstretched length s0 [µm] (0 for a law without a film). The other
# indices are each law's own, named in its module (``K_*``).
K_ATTACH_RADIUS = 5
K_ATTACH_FILM = 12


@jitable
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
    """Tangential stick stiffness k_t = 8G*·a of a circular contact of radius a [µN/µm] for the
    materials of ``contact``: :func:`gecko_agents.physics.friction.stick_stiffness` with
    :func:`~gecko_agents.physics.friction.combined_shear_modulus` (Mindlin 1949, J Appl Mech
    16:259; Johnson, Contact Mechanics, 1985, §7.2).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (E in MPa). a : contact radius [µm].
    """
    G_star = combined_shear_modulus(contact.E1, contact.nu1, contact.E2, contact.nu2)
    return float(stick_stiffness(a, G_star))


class ContactLaw:
    """The interface (see the module docstring). Subclasses set the attributes in
    ``__init__`` and implement the vectorized and scalar methods."""

    name: str = ""
    rate_dependent: bool = False  # the radius is a state variable (crack kinetics)
    tangential: bool = False  # the law takes the tip's tangential position (step_scalar)
    film: bool = False  # a peeling film: anchor = peel front, a = attached length (recorded)
    # A flat face (the punch): bonded, it holds the tip's direction (the elastica's clamp),
    # and its radius is the face's, a = R (no sphere items in the diagnostics).
    flat_face: bool = False
    # A tangential law's contact damping also acts while the tip slides (the spatula's film);
    # False: only while it sticks, as the sphere's stick spring (kernels, :mod:`.loop`).
    damp_sliding: bool = True
    # Where a tip's detachment starts, for a law with more than one way to let go (the
    # mushroom's "edge" or "centre"), recorded with each detachment; "" for the others.
    release_mode: str = ""
    label: str = ""  # how error messages name the law's parameters ("tip = <name>" if empty)
    max_tension: float = math.nan  # largest tension a tip can hold [µN] (nan: Fc)
    # The energy balance's tolerance in units of history.ENERGY_RTOL: 1, or 2 for a law with a
    # known first-order (∝ dt) error in its energy books, stated where the law sets it.
    energy_tolerance_factor: float = 1.0
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

    def release_force(self) -> float:
        """Normal force P [µN] at the detach overlap δ_detach on the law's own branch: what a
        tip that lets go by passing δ_detach holds there, whatever a step's overshoot past it
        (JKR's fold δ_c: −5/9·Fc, Johnson, Kendall & Roberts 1971; a punch: its pull-off).
        NaN for a law whose tips let go otherwise (a radius with kinetics, a peeling film)."""
        if self.rate_dependent or self.tangential:
            return math.nan
        d = np.array([self.detach_overlap], float)
        return float(self.force(self.radius(d, None, 0.0), d)[0])

    def energy(self, a, delta):
        """Energy stored in the contact at (a, δ), from attachment [pJ]."""
        raise NotImplementedError

    def stiffness(self, a, delta):
        """Normal contact stiffness dP/dδ [µN/µm] at contact radii ``a`` [µm] and overlaps
        ``delta`` [µm] (arrays), what the linearly implicit step
        (:mod:`gecko_agents.model.implicit`) treats implicitly; it clamps the value to
        [0, :meth:`stiffest` at 5 Fc]. Default: the stiffness at zero load everywhere, a
        scale, for a law that does not give its own."""
        return np.full(np.shape(a), float(self.zero_load_stiffness))

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
