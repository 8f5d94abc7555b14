"""Per-seta state of the time-stepped model: named arrays over one contiguous block.

Units: µm, µN, µs (:mod:`gecko_agents.params`). Every array has shape (N,), seta i in column i.
The floats live in one ``(ROWS, N)`` block so that the per-seta loop works on contiguous rows
(the compiled kernel indexes it with the row constants below: ``S[AC, i]`` is seta i's contact
radius); everything else reads them through the named views of :class:`SetaState`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SetaState", "ROWS"]

ROWS = (
    "px",
    "py",
    "vx",
    "vy",
    "x",
    "y",
    "fx",
    "fy",
    "dmpx",
    "dmpy",
    "ax",
    "ay",
    "a",
    "xi",
    "P",
    "Ft",
    "delta",
    "jump",
    "ux",
    "uy",
    "fdx",
    "fdy",
    "s0",
    "p0",
    "uc",
)
"""Row names of the block, in order (see :class:`SetaState` for their meaning)."""

(
    PX,
    PY,
    VX,
    VY,
    X,
    Y,
    FX,
    FY,
    DMPX,
    DMPY,
    AX,
    AY,
    AC,
    XI,
    P,
    FT,
    DELTA,
    JUMP,
    UX,
    UY,
    FDX,
    FDY,
    S0,
    P0,
    UC,
) = range(len(ROWS))


class SetaState:
    """The state of N setae between steps.

    Float views (shape (N,) each, or (2, N) for the paired ones), all into ``block``:

    * ``pv`` (4, N): tip position (px, py) [µm] and velocity (vx, vy) [µm/µs] at the start of
      the step, as pymunk holds them;
    * ``xy`` (2, N): where the forces are evaluated, x + v·dt [µm] (semi-implicit Euler);
    * ``F`` (2, N): total force on each tip [µN]; ``F_damp_contact`` (2, N): its contact
      damping part; ``F_damp_seta`` (2, N): the seta's damping relative to the plate;
    * ``anchor`` (2, N): stick anchor of an attached tip [µm]: on the floor in the pad
      floors' batch kernels; the tip-centre position where its stick spring is unstretched on
      continuous floors and in the callback path;
    * ``a``: contact radius [µm]; ``xi``: stick-spring stretch [µm] (tangential);
    * ``P``: normal contact force [µN] (> 0 compressive); ``Ft``: tangential contact force [µN];
    * ``delta``: overlap δ [µm] (> 0 pressed; NaN without a candidate floor);
    * ``jump``: overlap at which an attached tip started to run away from its equilibrium
      [µm] (NaN while it follows it);
    * ``u`` (2, N): linear seta's tip displacement from rest, or the rod's root-to-tip vector
      [µm];
    * film tips (:class:`gecko_agents.contact.SpatulaTip`): ``anchor`` is the peel front,
      ``a`` the attached length ℓ [µm], ``s0`` the free film's unstretched length [µm], ``p0``
      the pre-tension of the attached film [µN], ``uc`` the energy the contact stores [pJ],
      ``xi`` the tip body's stick anchor relative to the front [µm] (its Coulomb friction on
      the Hertz compression; the stick offset is the tip's offset from the front minus it);
    * sheared spheres (:class:`gecko_agents.contact.ShearedJKRSphere`): ``anchor`` is where
      the tip attached, ``a`` the contact radius, ``xi`` the stick anchor relative to it [µm],
      ``p0`` the tip's tangential displacement ξ from that anchor [µm] and ``s0`` and ``uc``
      the energy the contact stores [pJ].

    Flags (bool (N,)): ``attached``, ``slip`` (attached and sliding), ``candidate`` (pymunk
    reports the tip's sensor touching its floor), ``candidate_step`` (the copy a step used).
    """

    def __init__(self, n: int):
        self.n = n
        self.block = S = np.zeros((len(ROWS), n))
        self.pv = S[PX : VY + 1]
        self.xy = S[X : Y + 1]
        self.F = S[FX : FY + 1]
        self.F_damp_contact = S[DMPX : DMPY + 1]
        self.anchor = S[AX : AY + 1]
        self.a, self.xi, self.P, self.Ft = S[AC], S[XI], S[P], S[FT]
        self.delta, self.jump = S[DELTA], S[JUMP]
        self.u = S[UX : UY + 1]
        self.F_damp_seta = S[FDX : FDY + 1]
        self.s0, self.p0, self.uc = S[S0], S[P0], S[UC]
        self.jump[:] = np.nan
        self.delta[:] = np.nan
        self.attached = np.zeros(n, dtype=bool)
        self.slip = np.zeros(n, dtype=bool)
        self.candidate = np.zeros(n, dtype=bool)
        self.candidate_step = np.zeros(n, dtype=bool)
        self.external_force = np.zeros((n, 2))

    def velocity(self) -> np.ndarray:
        """Tip velocities (N, 2) at the start of the last step [µm/µs]."""
        return np.column_stack([self.pv[2], self.pv[3]])
