"""The backing the setae stand on: :class:`Backing` (rigid plate or elastic strip).

Units: µm, MPa, ng/µm³, µN/µm (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

from dataclasses import dataclass

from gecko_agents.params.checks import DENSITY_RANGE, LENGTH_RANGE, MODULUS_RANGE, check

__all__ = ["Backing", "BACKING_KINDS", "BACKING_DRIVES"]

_check = check


BACKING_KINDS = ("rigid", "elastic", "layer")
BACKING_DRIVES = ("uniform", "peel_end")


@dataclass(frozen=True)
class Backing:
    """The backing the setae stand on (:mod:`gecko_agents.backing.elastic`).

    ``kind = "rigid"`` (default) is the kinematic plate of the paper: every root follows the
    plate's motion (equal load sharing). ``kind = "elastic"`` is a strip in plane strain made of
    a chain of rigid links joined by pivots and rotary springs (Euler–Bernoulli bending), the
    roots riding on the chain; it is pulled through a handle spring by the protocol's plate
    motion, at one end (``drive = "peel_end"``) or over its whole length (``"uniform"``).

    Width convention: the simulated row of setae is one row of a square lattice, so the strip is
    as wide as the row spacing, b = ``array.pitch``; its bending stiffness is
    EI = E_b·b·t_b³ / (12(1 − ν_b²)) [µN·µm²] (plane strain plate, Timoshenko & Woinowsky-Krieger
    1959, Theory of Plates and Shells, eq 3) and its mass per length ρ_b·b·t_b [ng/µm].

    ``kind = "layer"`` is an elastic layer of thickness ``t_b``, modulus ``E_b`` and Poisson
    ratio ``nu_b`` bonded to the holder, the roots on its free surface coupled through it
    (:mod:`gecko_agents.backing.layer`; ν_b in [0, 0.5), the incompressible limit being the
    field model's, :mod:`gecko_agents.physics.layer`); the strip's other fields are unused.

    Attributes
    ----------
    kind : ``"rigid"``, ``"elastic"`` or ``"layer"``.
    t_b : strip (or layer) thickness [µm]; default 50 µm, an assumption in the range of the
        backing layers of polyurethane microfibre adhesives (tens to hundreds of µm, Murphy,
        Aksak & Sitti 2009, Small 5:170).
    E_b : strip modulus [MPa]; default 1.413 MPa, the paper's polyurethane (Table 1's E), the
        setae and backing being cast in one piece.
    nu_b : strip Poisson ratio [-]; default 0.3 (Table 1's ν).
    density : strip density [ng/µm³]; polyurethane ≈ 1.2e-3 (1200 kg/m³).
    spacing : link length ℓ of the chain [µm]; 0 (default) means the coarsest allowed, λ/4
        (and at least 4 links). Refused by the model when coarser than a quarter of the bending
        length
        λ = (4EI/k_f)^(1/4) (beam on an elastic foundation of the setae, k_f = K_y/pitch
        [µN/µm²]; Hetényi 1946, Beams on Elastic Foundation, ch. 2).
    handle_stiffness : stiffness k_h of the handle spring [µN/µm] (the machine or tendon
        compliance), total over the strip; default 1000 µN/µm (a load cell much stiffer than
        the array).
    drive : ``"uniform"`` (the handle pulls every link with k_h/n_links) or ``"peel_end"`` (the
        handle pulls the +x end of the strip).
    damping_ratio : damping ratio of the rotary springs and the handle spring [-]; default 0.3.
    leader_arm : length of a rigid leader arm from the strip's +x end to where the handle
        pulls [µm] (``drive = "peel_end"``, aligned); default 0, none.
    peel_angle_deg : the peel angle the leader arm's handle holds [degrees], in (0, 180);
        default 90.
    misalignment_deg : angle between backing and floor at contact [degrees]; default 0
        (aligned). The strip and the handle that holds it are turned by it about the strip's
        centre, counter-clockwise: a positive angle lifts the +x end, so the −x edge touches
        first. A few tenths of a degree turn a pull into a peel (Booth et al. found ~0.1°
        enough; Bacca, Booth, Turner & McMeeking 2016, J Mech Phys Solids 96:428). Within
        ±10° (the setae keep their rest direction in the floor's frame, a small-angle
        assumption); only with ``kind = "elastic"``.
    """

    kind: str = "rigid"
    t_b: float = 50.0
    E_b: float = 1.413
    nu_b: float = 0.3
    density: float = 1.2e-3
    spacing: float = 0.0
    handle_stiffness: float = 1000.0
    drive: str = "uniform"
    damping_ratio: float = 0.3
    misalignment_deg: float = 0.0
    leader_arm: float = 0.0
    peel_angle_deg: float = 90.0

    def __post_init__(self):
        if self.kind not in BACKING_KINDS:
            raise ValueError(f"Backing.kind = {self.kind!r} must be one of {BACKING_KINDS}")
        if self.drive not in BACKING_DRIVES:
            raise ValueError(f"Backing.drive = {self.drive!r} must be one of {BACKING_DRIVES}")
        _check(self, "t_b", *LENGTH_RANGE, lo_open=False, hi_open=False)
        _check(self, "E_b", *MODULUS_RANGE, lo_open=False, hi_open=False)
        _check(self, "nu_b", -1.0, 0.5, hi_open=True)
        _check(self, "density", *DENSITY_RANGE, lo_open=False, hi_open=False)
        if self.spacing != 0.0:
            _check(self, "spacing", *LENGTH_RANGE, lo_open=False, hi_open=False)
        _check(self, "handle_stiffness", 0.0, 1e12)
        _check(self, "damping_ratio", 0.0, 10.0, lo_open=False)
        _check(self, "misalignment_deg", -10.0, 10.0, lo_open=False, hi_open=False)
        _check(self, "leader_arm", 0.0, 1e6, lo_open=False, hi_open=False)
        _check(self, "peel_angle_deg", 0.0, 180.0)
        if self.leader_arm and self.kind != "elastic":
            raise ValueError(
                f"Backing.leader_arm = {self.leader_arm!r} µm needs kind = 'elastic' (the rigid "
                f"plate has no strip to extend), got kind = {self.kind!r}"
            )
        if self.leader_arm and (self.drive != "peel_end" or self.misalignment_deg):
            raise ValueError(
                f"Backing.leader_arm = {self.leader_arm!r} µm needs Backing.drive = 'peel_end' "
                f"(got {self.drive!r}) and Backing.misalignment_deg = 0 (got "
                f"{self.misalignment_deg!r})"
            )
        if self.kind == "layer" and not self.nu_b >= 0.0:
            raise ValueError(
                f"Backing.nu_b = {self.nu_b!r} must be in [0, 0.5) with kind = 'layer' (the "
                "layer's Green's function, gecko_agents.physics.layer)"
            )
        if self.misalignment_deg != 0.0 and self.kind != "elastic":
            raise ValueError(
                f"Backing.misalignment_deg = {self.misalignment_deg!r} needs kind = 'elastic' "
                f"(the rigid plate is level), got kind = {self.kind!r}"
            )

    def bending_stiffness(self, width: float) -> float:
        """EI of a strip of width ``width`` [µm] in plane strain [µN·µm²]."""
        return self.E_b * width * self.t_b**3 / (12.0 * (1.0 - self.nu_b**2))
