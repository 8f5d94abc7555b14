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

A law that needs the tip's tangential position (:attr:`ContactLaw.tangential`: the thin-film
:class:`SpatulaTip`, the sheared sphere :class:`ShearedJKRSphere`) answers one question instead of
``radius``/``force``: ``step_scalar`` takes the tip's offset from its peel front along the floor and
its height, and returns both force components and the new contact state (front shift, attached
length, pre-tension, stored energy, dissipation); the kernels call it per seta on pad floors. The
JKR, crack-kinetics and Hertz spheres never reach that branch, so their histories are unchanged.

Each law gives the same formulas twice, kept side by side so that they cannot drift apart:
vectorized numpy methods (the general floor path, recording, energies) and scalar
``@staticmethod`` functions with ``k``, the law's constants, as last argument
(:attr:`ContactLaw.constants`, a float64 array read by the named indices ``K_*`` of each law's
module; the slots every tangential law fills on attachment are ``base.K_ATTACH_RADIUS`` and
``base.K_ATTACH_FILM``) that the per-seta loop calls, compiled by numba or interpreted
(:mod:`gecko_agents.model.step_numpy`). ``tests/test_contact.py`` pins both forms of every law to
its closed form (:mod:`gecko_agents.physics.jkr`) point by point. Formulas the laws share with
the rest of the model have one home in :mod:`gecko_agents.physics` (the friction cap and
Mindlin's stick stiffness: :mod:`gecko_agents.physics.friction`), compiled where called.

Layout: :mod:`.base` (interface, shared scalar helpers), one module per law (:mod:`.jkr_sphere`,
:mod:`.rate_jkr`, :mod:`.hertz`, :mod:`.flat_punch`, :mod:`.mushroom`, :mod:`.spatula`,
:mod:`.spatulae` (N films on a branched seta), :mod:`.sheared_jkr`) and
:mod:`.registry` (names).
Adding a law: write one module with a subclass of :class:`ContactLaw`, register it in
:data:`TIP_LAWS`, add its tests. Nothing in the model changes.
"""

from gecko_agents.contact.base import ContactLaw, branch_radius, mindlin_stiffness
from gecko_agents.contact.flat_punch import FlatPunch
from gecko_agents.contact.hertz import HertzSphere
from gecko_agents.contact.jkr_sphere import JKRSphere
from gecko_agents.contact.mushroom import MushroomTip
from gecko_agents.contact.rate_jkr import RateJKRSphere
from gecko_agents.contact.registry import TIP_LAWS, bounds, contact_law
from gecko_agents.contact.sheared_jkr import ShearedJKRSphere
from gecko_agents.contact.spatula import SpatulaTip
from gecko_agents.contact.spatulae import SpatulaeTip

__all__ = [
    "ContactLaw",
    "JKRSphere",
    "RateJKRSphere",
    "HertzSphere",
    "FlatPunch",
    "MushroomTip",
    "SpatulaTip",
    "SpatulaeTip",
    "ShearedJKRSphere",
    "TIP_LAWS",
    "contact_law",
    "bounds",
    "mindlin_stiffness",
    "branch_radius",
]
