"""Validated, frozen parameter sets; the paper's named presets are in :mod:`.presets`.

Unit system (the one used everywhere in gecko_agents)
-----------------------------------------------------
==========================  =========  ==================================================
quantity                    unit       note
==========================  =========  ==================================================
length                      µm
force                       µN
time                        µs
mass                        ng         = µN·µs²/µm, so F = m·a holds without factors
elastic modulus, pressure   MPa        = µN/µm²
stiffness                   µN/µm      = N/m
surface / adhesion energy   µN/µm      = J/m²  (40 mJ/m² is 0.04)
energy                      pJ         = µN·µm
density                     ng/µm³     = 10⁶ kg/m³  (polyurethane 1200 kg/m³ is 1.2e-3)
angles                      degrees    in parameter sets; radians inside formulas
==========================  =========  ==================================================

The pure functions in :mod:`gecko_agents.physics.jkr` and :mod:`gecko_agents.physics.beam` hold
in any consistent unit set; the parameter sets and the pymunk model use the table above.

Every dataclass validates itself on construction: a bad value raises ``ValueError`` naming the
field, the value and the allowed range, before anything is simulated.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from gecko_agents.params.backing import BACKING_DRIVES as BACKING_DRIVES
from gecko_agents.params.backing import BACKING_KINDS as BACKING_KINDS
from gecko_agents.params.backing import Backing
from gecko_agents.params.checks import (
    COUNT_MAX,
    DENSITY_RANGE,
    FRICTION_MAX,
    LENGTH_RANGE,
    MODULUS_RANGE,
    ROUGHNESS_MAX,
    SURFACE_ENERGY_MAX,
    check,
)
from gecko_agents.params.spatulae import Spatulae, check_spatulae
from gecko_agents.params.tips import FLAT_FACE_TIPS, Mushroom, check_tip_options
from gecko_agents.physics import beam, jkr
from gecko_agents.physics.friction import friction_cap

MECHANICS = ("linear", "rod", "elastica")
DETACHMENT_RULES = ("fold", "delta_s", "load_control")
SHEAR_COUPLINGS = ("none", "savkoor_briggs")
MIN_LINKS = 14
"""Fewest links of the elastica's bar chain: its three Euler loads within 2 % (``Seta.links``)."""
TIPS = ("sphere", "hertz", "spatula", "flat_punch", "mushroom", "spatulae")
"""Tip contact laws (``gecko_agents.contact.TIP_LAWS``): the adhesive JKR sphere of the
paper, a Hertz sphere without adhesion, a thin-film spatula that peels (:class:`Spatula`) or
the flat end of a pillar, a punch of radius ``contact.R`` (Kendall 1971, J Phys D 4:1186), or
a mushroom tip, a flange of radius ``contact.R`` on its stalk (:class:`Mushroom`), or a
branched seta ending in ``spatulae.count`` spatula films (:class:`Spatulae`)."""
FRICTION_LAWS = ("adhesive", "paper")
FLOOR_KINDS = ("gaussian", "self_affine", "probe")


# The range check and the physical ranges live in param_checks (one home, used by protocol too).
_check = check


@dataclass(frozen=True)
class Contact:
    """The tip sphere against the floor (JKR, paper eq 1–15).

    Attributes
    ----------
    R : tip sphere radius [µm] (the floor is flat, so R is also the equivalent radius); for
        ``tip = "flat_punch"`` the punch (face) radius a.
    E1 : Young's modulus of the seta material (tip and rod) [MPa].
    nu1 : Poisson's ratio of the seta material [-], in [0, 0.5).
    E2 : Young's modulus of the floor [MPa].
    nu2 : Poisson's ratio of the floor [-], in [0, 0.5).
    gamma1, gamma2 : surface energies of tip and floor [µN/µm = J/m²].
    w : work of adhesion [µN/µm]; ``None`` means the paper's rule w = 2√(γ1γ2) (eq 5 text).
    crack_speed : reference crack speed v* of the contact edge [µm/µs] (1 µm/µs = 1 m/s);
        ``inf`` (default) is the elastic JKR contact, exactly. Finite: the contact radius
        follows crack kinetics, G − w = w·(|ȧ|/v*)^n while the edge opens (Maugis & Barquins
        1978, J Phys D 11:1989; :class:`gecko_agents.contact.RateJKRSphere`).
    crack_exponent : n [-] in (0, 1]; 0.5 by default, the exponent of Greenwood & Johnson's
        (1981, Phil Mag A 43:697) viscoelastic crack theory, inside the 0.1–0.8 that elastomers
        show (Ciavarella 2021, J Adhes Sci Technol, reviews them).
    crack_closing_speed : speed at which the contact edge closes while G < w [µm/µs]; ``inf``
        (default) closes it at once, onto the equilibrium radius.
    detachment : where an elastic tip lets go: ``"fold"`` (default: past δc, the end of the
        stable JKR branch; a soft seta leaves at the fold of the spring–contact system, found
        dynamically), ``"delta_s"`` (the paper's rule: δ < δs = −0.21·a0²/R, eq 8) or
        ``"load_control"`` (at P = −Fc, δ < −a_lc²/(3R)). Rate-dependent contacts let go
        when the crack has run through (``"fold"`` only).
    shear_coupling : how the shear a sphere tip carries acts on its adhesion. ``"none"``
        (default; the paper's JKR): the contact radius follows the overlap alone, as a sliding
        contact's does (Vorvolakos & Chaudhury 2003, Langmuir 19:6778; Menga, Carbone & Dini 2018, J
        Mech Phys Solids 112:145, as corrected). ``"savkoor_briggs"``: the stick spring's mode-II
        release rate counts in Griffith's balance on a brittle interface (Savkoor & Briggs 1977,
        Proc R Soc A 356:103; :class:`gecko_agents.contact.ShearedJKRSphere`): shear shrinks the
        contact and lowers the tension it holds, the strongest coupling (real interfaces are tougher
        in shear, Johnson 1997, Proc R Soc A 453:163). Elastic contact (``crack_speed = inf``) with
        the ``"fold"`` detachment and a pad floor only.
    sigma0 : cohesive strength σ₀ of the interface [MPa], > 0; ``inf`` (default) is an
        interface without a strength limit (Kendall's punch). Finite: a flat face
        (``tip = "flat_punch"`` or ``"mushroom"``) pulls off at no more than its strength over
        its area (flaw tolerance; Tang, Hui & Glassmaker 2005, J R Soc Interface 2:505;
        :mod:`gecko_agents.physics.flaw_tolerance`).
    edge_opening : ``False`` (default): a bonded flat face lets go by its normal force alone.
        ``True``: the moment a bonded face of an elastica pillar carries moves its detachment,
        the edge opening where 3|M|/a − P reaches the edge-mode pull-off, under tension or
        compression (a buckled pillar), and the face bonds again only after its tip has left
        the floor (:mod:`gecko_agents.model.face_opening`; Paretkar et al. 2013, J R Soc
        Interface 10:20130171). Flat-faced tips with ``mechanics = "elastica"`` only.
    """

    R: float = 4.0
    E1: float = 1.413
    nu1: float = 0.3
    E2: float = 55_000.0
    nu2: float = 0.25
    gamma1: float = 0.040
    gamma2: float = 0.170
    w: float | None = None
    crack_speed: float = math.inf
    crack_exponent: float = 0.5
    crack_closing_speed: float = math.inf
    detachment: str = "fold"
    shear_coupling: str = "none"
    sigma0: float = math.inf
    edge_opening: bool = False

    def __post_init__(self):
        _check(self, "sigma0", 0.0, math.inf, hi_open=False)
        if not isinstance(self.edge_opening, bool):
            raise ValueError(f"Contact.edge_opening = {self.edge_opening!r} must be True or False")
        if self.shear_coupling not in SHEAR_COUPLINGS:
            raise ValueError(
                f"Contact.shear_coupling = {self.shear_coupling!r} must be one of {SHEAR_COUPLINGS}"
            )
        if self.shear_coupling != "none" and (
            math.isfinite(self.crack_speed) or self.detachment != "fold"
        ):
            raise ValueError(
                f"Contact.shear_coupling = {self.shear_coupling!r} needs the elastic contact "
                f"with the 'fold' detachment (crack_speed = inf, detachment = 'fold'); got "
                f"crack_speed = {self.crack_speed}, detachment = {self.detachment!r}"
            )
        _check(self, "crack_speed", 0.0, math.inf, hi_open=False)
        _check(self, "crack_exponent", 0.0, 1.0, hi_open=False)
        _check(self, "crack_closing_speed", 0.0, math.inf, hi_open=False)
        if self.detachment not in DETACHMENT_RULES:
            raise ValueError(
                f"Contact.detachment = {self.detachment!r} must be one of {DETACHMENT_RULES}"
            )
        if self.detachment != "fold" and math.isfinite(self.crack_speed):
            raise ValueError(
                f"Contact.detachment = {self.detachment!r} applies to the elastic "
                "contact (crack_speed = inf); a rate-dependent contact lets go "
                "when its crack has run through: use 'fold'"
            )
        _check(self, "R", *LENGTH_RANGE, lo_open=False, hi_open=False)
        for name in ("E1", "E2"):
            _check(self, name, *MODULUS_RANGE, lo_open=False, hi_open=False)
        for name in ("gamma1", "gamma2"):
            _check(self, name, 0.0, SURFACE_ENERGY_MAX, hi_open=False)
        for name in ("nu1", "nu2"):
            _check(self, name, 0.0, 0.5, lo_open=False)
        if self.w is not None:
            _check(self, "w", 0.0, 2 * SURFACE_ENERGY_MAX, hi_open=False)

    @property
    def work_of_adhesion(self) -> float:
        """w [µN/µm]: the override if given, else 2√(γ1γ2)."""
        if self.w is not None:
            return self.w
        return float(jkr.work_of_adhesion(self.gamma1, self.gamma2))

    @property
    def E_star(self) -> float:
        """Effective modulus E* [MPa] (paper, below eq 3)."""
        return float(jkr.effective_modulus(self.E1, self.nu1, self.E2, self.nu2))

    @property
    def pull_off_force(self) -> float:
        """Load-controlled JKR pull-off magnitude Fc = 1.5πRw [µN]."""
        return float(jkr.pull_off_force(self.R, self.work_of_adhesion))

    @property
    def snap_off_overlap(self) -> float:
        """Displacement-controlled end of the stable branch δc < 0 [µm]."""
        return float(jkr.snap_off_overlap(self.R, self.work_of_adhesion, self.E_star))

    def jkr_args(self) -> tuple[float, float, float]:
        """(R, w, E*) in the order the :mod:`jkr` functions take them."""
        return self.R, self.work_of_adhesion, self.E_star


@dataclass(frozen=True)
class Seta:
    """One seta: an inclined cantilever rod (paper eq 16–21), material E1 from :class:`Contact`.

    Attributes
    ----------
    r : rod **radius** [µm] (Table 1 gives a 3 µm diameter; NOTES.md on eq 16–19).
    L : rod length [µm].
    theta_deg : angle between the seta and the backing plate [degrees], in (0, 90]; 90 is a
        vertical pillar (its bending spring still acts: a slight tilt or a lateral tip force
        bends it; ``mechanics = "elastica"`` buckles at Euler's loads).
    density : material density [ng/µm³]; polyurethane ≈ 1.2e-3 (1200 kg/m³).
    links : links of the bar chain of ``mechanics = "elastica"`` [-], 14–200; 16 (default)
        puts the clamped–free, clamped–pinned and clamped–clamped buckling loads within
        1.3 % of the continuous column's, shear included, 14 within 2 % (they converge as
        1/n²; fewer links buckle far early: 2 at 0.41–0.59 × Euler;
        :mod:`gecko_agents.physics.columns`, :mod:`gecko_agents.physics.elastica`).
    imperfection : the elastica's initial crookedness [-], in (0, 0.1]: its stress-free shape
        is an arc whose tip lies imperfection·L to +x of the straight seta; it picks the side a
        vertical pillar buckles to. A straight chain (0) never leaves its straight branch, past
        Euler's load too, so it is refused. Default 1e-4 (the buckled column's force stays
        within 0.3 % of the perfect column's, ``tests/test_pillars.py``).
    """

    r: float = 1.5
    L: float = 20.0
    theta_deg: float = 30.0
    density: float = 1.2e-3
    links: int = 16
    imperfection: float = 1e-4

    def __post_init__(self):
        _check(self, "r", *LENGTH_RANGE, lo_open=False, hi_open=False)
        _check(self, "L", *LENGTH_RANGE, lo_open=False, hi_open=False)
        _check(self, "theta_deg", 0.0, 90.0, hi_open=False)
        _check(self, "density", *DENSITY_RANGE, lo_open=False, hi_open=False)
        _check(self, "links", MIN_LINKS, 200, lo_open=False, hi_open=False, integer=True)
        _check(self, "imperfection", 0.0, 0.1, hi_open=False)

    @property
    def theta(self) -> float:
        """θ [rad]."""
        return math.radians(self.theta_deg)


@dataclass(frozen=True)
class Array:
    """The array on the backing plate.

    Attributes
    ----------
    count : number of setae N [-] in the physical array (10⁷ in the paper, section 3.3.2).
    pitch : spacing between neighbouring roots [µm] (4 µm in the paper).
    """

    count: int = 1
    pitch: float = 4.0

    def __post_init__(self):
        _check(self, "count", 1, COUNT_MAX, lo_open=False, hi_open=False, integer=True)
        _check(self, "pitch", *LENGTH_RANGE, lo_open=False, hi_open=False)


@dataclass(frozen=True)
class Floor:
    """Rough floor: Gaussian heights (paper eq 28) or a self-affine (fractal) profile.

    Attributes
    ----------
    sigma : RMS height σ [µm], ≥ 0 (0 is a flat floor).
    correlation_length : Gaussian correlation length of the profile [µm], ≥ 0; 0 means an
        independent height under every seta, as in the paper. Only for ``kind="gaussian"``.
    seed : seed of the floor's ``numpy.random.Generator``.
    kind : ``"gaussian"`` (default; eq 28, :func:`gecko_agents.floor.make_profile`) or
        ``"self_affine"``: a continuous profile with PSD C(q) ∝ q^−(1+2H) between the cutoffs
        and flat below the long one (:func:`gecko_agents.floor.self_affine`; Persson et al.
        2005, J Phys Condens Matter 17:R1). A measured profile is not a parameter: pass it to
        the model as an object (``floor.for_array(..., measured=profile)``).
    hurst : Hurst exponent H [-], in (0, 1) (self-affine only).
    short_cutoff : short-wavelength cutoff λs [µm], > 0: no roughness below it; the profile's
        vertex spacing is λs/4 (self-affine only).
    long_cutoff : long-wavelength cutoff λL [µm], > short_cutoff: the PSD is flat (roll-off)
        for wavelengths above it (self-affine only).
    rms_slope : RMS slope of the self-affine profile [-], > 0, used instead of ``sigma``
        (then ``sigma`` must be 0); ``None`` (default): the profile has RMS height ``sigma``.
    probe_radius : radius R_p of a rigid spherical probe [µm] (``kind="probe"`` only: the
        floor is the probe, apex under the middle of the array, smooth, ``sigma = 0``;
        :mod:`gecko_agents.floor.probe`). Default 100 µm.

    The self-affine fields are ignored for ``kind="gaussian"``, so the defaults leave the
    Gaussian floor (and every history made with it) exactly as before.
    """

    sigma: float = 0.0
    correlation_length: float = 0.0
    seed: int = 0
    kind: str = "gaussian"
    hurst: float = 0.8
    short_cutoff: float = 2.0
    long_cutoff: float = 50.0
    rms_slope: float | None = None
    probe_radius: float = 100.0

    def __post_init__(self):
        _check(self, "sigma", 0.0, ROUGHNESS_MAX, lo_open=False, hi_open=False)
        _check(self, "probe_radius", *LENGTH_RANGE, lo_open=False, hi_open=False)
        if self.kind == "probe" and (self.sigma != 0 or self.correlation_length != 0):
            raise ValueError(
                f"Floor.kind = 'probe' is a smooth sphere: Floor.sigma = {self.sigma!r} and "
                f"Floor.correlation_length = {self.correlation_length!r} must both be 0"
            )
        _check(self, "correlation_length", 0.0, ROUGHNESS_MAX, lo_open=False, hi_open=False)
        _check(self, "seed", 0, 2**63, lo_open=False, integer=True)
        if self.kind not in FLOOR_KINDS:
            raise ValueError(f"Floor.kind = {self.kind!r} must be one of {FLOOR_KINDS}")
        _check(self, "hurst", 0.0, 1.0)
        _check(self, "short_cutoff", LENGTH_RANGE[0], ROUGHNESS_MAX, lo_open=False)
        # A profile spans a few long cutoffs at λs/4 vertex spacing: cap the ratio at 10⁶.
        _check(self, "long_cutoff", self.short_cutoff, 1e6 * self.short_cutoff, hi_open=False)
        if self.rms_slope is not None:
            _check(self, "rms_slope", 0.0)
            if self.kind != "self_affine":
                raise ValueError(
                    f"Floor.rms_slope = {self.rms_slope!r} applies to "
                    "kind='self_affine' only; use None"
                )
            if self.sigma != 0:
                raise ValueError(
                    f"Floor.rms_slope = {self.rms_slope!r} and Floor.sigma = "
                    f"{self.sigma!r}: give one of RMS height or RMS slope (set "
                    "sigma = 0 to use rms_slope)"
                )
        if self.kind == "self_affine" and self.correlation_length != 0:
            raise ValueError(
                f"Floor.correlation_length = {self.correlation_length!r} applies "
                "to kind='gaussian' only; it must be 0 for kind='self_affine'"
            )


@dataclass(frozen=True)
class Friction:
    """Coulomb friction at the tip.

    Attributes
    ----------
    mu : friction coefficient [-], ≥ 0 (0.2 in the paper, section 3.3.2).
    law : ``"adhesive"`` caps the tangential force at μ|P + 2Fc| (Thornton's JKR convention:
        a contact in tension still holds shear) or ``"paper"``: μ·max(P, 0) (eq 27).
    """

    mu: float = 0.2
    law: str = "adhesive"

    def __post_init__(self):
        _check(self, "mu", 0.0, FRICTION_MAX, lo_open=False, hi_open=False)
        if self.law not in FRICTION_LAWS:
            raise ValueError(f"Friction.law = {self.law!r} must be one of {FRICTION_LAWS}")

    def cap(self, P, Fc):
        """Largest tangential force magnitude [µN] for normal force(s) ``P`` [µN] and pull-off
        force ``Fc`` [µN]: :func:`gecko_agents.physics.friction.friction_cap` of this law."""
        return friction_cap(np.asarray(P), Fc, self.mu, self.law == "paper")


@dataclass(frozen=True)
class Spatula:
    """A thin-film spatula tip (``tip = "spatula"``, :class:`gecko_agents.contact.SpatulaTip`):
    an elastic film of width b and thickness h hanging from the tip centre and attached to the
    floor over a length ℓ, peeling by Kendall's energy balance (Kendall 1975, J Phys D 8:1449)
    with the pre-tension of Chen, Wu & Gao (2009, J R Soc Interface 6:529). Its work of adhesion
    is the contact's w (:class:`Contact`).

    Attributes
    ----------
    b : film width [µm]; default 3.0 µm = the seta's diameter 2r (Table 1: the film is as wide
        as the seta it ends).
    h : film thickness [µm]; default 1.0 µm, an assumption (no source gives the thickness of a
        spatula on this seta; a third of its width). b·h·E_f sets how far the film stretches.
    E_f : film modulus [MPa]; default 1.413 MPa, the paper's polyurethane (Table 1's E).
    length : attached length ℓ0 at first contact [µm]; default 3.0 µm, an assumption (a square
        pad b × b).
    interface : how the attached film holds on the floor. ``"sliding"`` (default): by friction
        (the pad's friction cap, :class:`Friction`), so a pull away from the pad stretches the
        attached film up to the cap and leaves it pre-tensioned (partial slip; Chen, Wu & Gao
        2009, J R Soc Interface 6:529; Labonte & Federle 2016, J R Soc Interface 13:20160373).
        ``"bonded"``: Kendall's (1975) assumption, the attached film never stretches (no
        pre-tension) until the whole pad slides past the cap.
    """

    b: float = 3.0
    h: float = 1.0
    E_f: float = 1.413
    length: float = 3.0
    interface: str = "sliding"

    def __post_init__(self):
        _check(self, "b", *LENGTH_RANGE)
        _check(self, "h", *LENGTH_RANGE)
        _check(self, "E_f", *MODULUS_RANGE)
        _check(self, "length", *LENGTH_RANGE)
        if self.interface not in ("sliding", "bonded"):
            raise ValueError(
                f"Spatula.interface = {self.interface!r} must be 'sliding' or 'bonded'"
            )


@dataclass(frozen=True)
class SetaArray:
    """Everything that defines a simulated array.

    ``mechanics`` is ``"linear"`` (the paper's 2×2 beam stiffness, eq 20–21), ``"rod"``
    (large rotation: a rigid rod on a rotary bending spring plus an axial spring) or
    ``"elastica"`` (a bar chain that bends and buckles as the elastica, for pillars:
    :mod:`gecko_agents.physics.elastica`; the time-stepped model's numpy kernel only). ``tip`` is
    the tip's contact law, one of :data:`TIPS` (:mod:`gecko_agents.contact`): ``"sphere"``
    (JKR, eq 1–15; the default), ``"hertz"`` (the same sphere without adhesion),
    ``"spatula"`` (a peeling thin film, parameters in ``spatula``, :class:`Spatula`) or
    ``"flat_punch"`` (a flat pillar end of radius ``contact.R``: Sneddon's stiffness,
    Kendall's pull-off; the elastic contact with a ``"fold"`` or ``"load_control"``
    detachment, which coincide for a punch).
    """

    contact: Contact = field(default_factory=Contact)
    seta: Seta = field(default_factory=Seta)
    array: Array = field(default_factory=Array)
    floor: Floor = field(default_factory=Floor)
    friction: Friction = field(default_factory=Friction)
    mechanics: str = "linear"
    tip: str = "sphere"
    spatula: Spatula = field(default_factory=Spatula)
    backing: Backing = field(default_factory=Backing)
    mushroom: Mushroom = field(default_factory=Mushroom)
    spatulae: Spatulae = field(default_factory=Spatulae)

    def __post_init__(self):
        for name, cls in _GROUPS.items():
            value = getattr(self, name)
            if not isinstance(value, cls):
                raise ValueError(
                    f"SetaArray.{name} = {value!r} must be a {cls.__name__}; to change one "
                    f"of its fields use replace(**{{'{name}.<field>': value}})"
                )
        if self.mechanics not in MECHANICS:
            raise ValueError(f"SetaArray.mechanics = {self.mechanics!r} must be one of {MECHANICS}")
        if self.tip not in TIPS:
            raise ValueError(f"SetaArray.tip = {self.tip!r} must be one of {TIPS}")
        if self.tip in FLAT_FACE_TIPS:
            _check_punch_contact(self.contact, self.tip)
            if self.floor.kind == "probe" and self.contact.R >= self.floor.probe_radius:
                raise ValueError(
                    f"Contact.R = {self.contact.R!r} µm (the face's radius) must be smaller "
                    f"than Floor.probe_radius = {self.floor.probe_radius!r} µm: a flat face as "
                    "wide as the probe cannot sit on it"
                )
        check_tip_options(self)
        check_spatulae(self)

    # Derived quantities used throughout ---------------------------------------------------
    @property
    def axial_stiffness(self) -> float:
        """Ka [µN/µm] (eq 17)."""
        return float(beam.axial_stiffness(self.seta.r, self.seta.L, self.contact.E1))

    @property
    def bending_stiffness(self) -> float:
        """Kp [µN/µm] (eq 19)."""
        return float(beam.bending_stiffness(self.seta.r, self.seta.L, self.contact.E1))

    @property
    def Ky(self) -> float:
        """Longitudinal (normal) stiffness Ky [µN/µm] (eq 20)."""
        return float(
            beam.longitudinal_stiffness(
                self.axial_stiffness, self.bending_stiffness, self.seta.theta
            )
        )

    @property
    def Kx(self) -> float:
        """Transverse stiffness Kx [µN/µm] (eq 21)."""
        return float(
            beam.transverse_stiffness(self.axial_stiffness, self.bending_stiffness, self.seta.theta)
        )

    def replace(self, **overrides) -> SetaArray:
        """A copy with some parameters changed.

        A group's fields as a dict, ``replace(floor={"sigma": 0.5}, mechanics="rod")``, or
        dotted, ``replace(**{"floor.sigma": 0.5})``; a whole group object replaces the group.
        Unknown names are refused, naming them.
        """
        groups: dict[str, dict] = {}
        top: dict = {}
        flat: dict = {}
        for key, value in overrides.items():
            if key in _GROUPS and isinstance(value, dict):
                flat.update({f"{key}.{name}": v for name, v in value.items()})
            else:
                flat[key] = value
        for key, value in flat.items():
            part, _, name = key.partition(".")
            if not name:
                if part not in {f.name for f in dataclasses.fields(self)}:
                    raise ValueError(f"unknown parameter {key!r}")
                top[part] = value
                continue
            if part not in _GROUPS:
                raise ValueError(f"unknown parameter group {part!r} in {key!r}")
            sub = getattr(self, part)
            if name not in {f.name for f in dataclasses.fields(sub)}:
                raise ValueError(f"unknown parameter {key!r}")
            groups.setdefault(part, {})[name] = value
        for part, vals in groups.items():
            top[part] = dataclasses.replace(getattr(self, part), **vals)
        return dataclasses.replace(self, **top)

    def to_dict(self) -> dict:
        """Plain nested dict of every parameter (for metadata.json)."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> SetaArray:
        """Inverse of :meth:`to_dict`."""
        return cls(
            contact=Contact(**d["contact"]),
            seta=Seta(**d["seta"]),
            array=Array(**d["array"]),
            floor=Floor(**d["floor"]),
            friction=Friction(**d["friction"]),
            mechanics=d["mechanics"],
            tip=d.get("tip", "sphere"),
            spatula=Spatula(**d.get("spatula", {})),
            backing=Backing(**d.get("backing", {})),
            mushroom=Mushroom(**d.get("mushroom", {})),
            spatulae=Spatulae(**d.get("spatulae", {})),
        )


def _check_punch_contact(c: Contact, tip: str = "flat_punch") -> None:
    """Refuse, naming the field, contact options a flat punch does not model (they belong to
    the sphere: crack kinetics, the Savkoor–Briggs coupling, the paper's δs rule, eq 8)."""
    for name, ok, allowed in (
        ("crack_speed", math.isinf(c.crack_speed), "inf"),
        ("shear_coupling", c.shear_coupling == "none", "'none'"),
        ("detachment", c.detachment != "delta_s", "'fold' or 'load_control'"),
    ):
        if not ok:
            raise ValueError(
                f"Contact.{name} = {getattr(c, name)!r} is a sphere tip's option; with "
                f"tip = {tip!r} it must be {allowed}"
            )


_GROUPS = {
    "contact": Contact,
    "seta": Seta,
    "array": Array,
    "floor": Floor,
    "friction": Friction,
    "spatula": Spatula,
    "backing": Backing,
    "mushroom": Mushroom,
    "spatulae": Spatulae,
}


def check_seed(seed, name: str = "seed") -> int:
    """``seed`` as a Python int, or ValueError naming ``name``.

    Accepts non-negative integers below 2⁶³ (Python or numpy); refuses bool, float (3.7 would
    silently become 3), strings and negative numbers: a seed is part of what a result means,
    so it is never coerced.
    """
    if isinstance(seed, np.integer):
        seed = int(seed)
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise ValueError(
            f"{name} = {seed!r} ({type(seed).__name__}) must be a non-negative integer"
        )
    if not 0 <= seed < 2**63:
        raise ValueError(f"{name} = {seed!r} is outside the allowed range [0, 2**63)")
    return seed


# The paper's named presets (params/presets.py, built from the classes above): this package's API.
from gecko_agents.params.presets import PAPER_ARRAY as PAPER_ARRAY  # noqa: E402
from gecko_agents.params.presets import PAPER_FIG5_READING as PAPER_FIG5_READING  # noqa: E402
from gecko_agents.params.presets import PAPER_TABLE1 as PAPER_TABLE1  # noqa: E402
