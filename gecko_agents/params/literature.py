"""Parameter sets for published experiments the package is checked against, one named preset
each (``gecko_agents.studies.validation``, ``literature_comparison.md``).

Units as in :mod:`gecko_agents.params` (µm, µN, µs, MPa, µN/µm). Every value a preset takes
from its source says so; every other value is an assumption, marked as such with its reason.
The study shows how much each row's number moves when an assumed value spans its plausible
range. No preset here changes a default of :mod:`gecko_agents.params`, and none is tuned to
the number it is compared with. Not registered as run-file presets (only
:mod:`gecko_agents.params.presets` is).
"""

from __future__ import annotations

from gecko_agents.params import Array, Contact, Floor, Friction, Seta, SetaArray, Spatula
from gecko_agents.params.presets import PAPER_ARRAY
from gecko_agents.params.spatulae import Spatulae

__all__ = [
    "AUTUMN2006_SETA",
    "TOKAY_SETAL_DENSITY",
    "BOOTH2018_STIFF_MOUNT",
    "BOOTH2018_COMPLIANT_MOUNT",
    "BOOTH2018_COMPLIANCE_RATIO",
    "KIM_SITTI2007_THIN",
    "KIM_SITTI2007_THICK",
    "GRAVISH2010_SETA",
    "FRICTIONAL_SPATULA",
    "FRICTIONAL_SPHERE",
    "KRONER_PILLARS",
    "TOKAY_SETA",
]


AUTUMN2006_SETA = SetaArray(
    contact=Contact(E1=1600.0, nu1=0.3),
    seta=Seta(r=1.5, L=63.0, theta_deg=45.0),
    array=Array(count=1, pitch=4.0),
    floor=Floor(sigma=0.0),
)
"""A tokay gecko seta as a straight β-keratin rod, for the stiffness and effective modulus of
Autumn, Majidi, Groff, Dittmore & Fearing (2006, J Exp Biol 209:3558, doi:10.1242/jeb.02469).

Cited: E = 1.6 GPa = 1600 MPa, the setal keratin's bending modulus of *Gekko gecko* (Peattie,
Majidi, Corder & Full 2007, "Ancestrally high elastic modulus of gecko setal β-keratin"; its
abstract: "Gekko gecko (1.6 GPa +/- 0.15s.e.; n=24 setae)"; journal and pages not in the text
we read). Cited as a range (the text we could read does not give the geometry of the setae
Autumn et al. tested): r = 1.5 µm and L = 63 µm, the middles of the published tokay ranges
"ca. 2–4 μm in diameter and ca. 11–115 μm in length, depending on the location on the
subdigital pad" (Scientific Reports 2022, doi:10.1038/s41598-022-15698-2, introduction).
Assumed: θ = 45° between shaft and backing (no source read gives the shaft angle). The contact
fields are not used by these rows (stiffness only)."""

TOKAY_SETAL_DENSITY = 0.0144
"""Setae per µm² of a tokay toe pad [1/µm²] (14 400 per mm²). Assumed: a secondary web source
(enviroliteracy.org, "approximately 14,400 setae per sq[uare millimetre]"); the primary count
was not in a text we could read."""

_STRIP = {"seta.L": 5.0, "floor.sigma": 0.0, "backing.kind": "elastic"}

BOOTH2018_COMPLIANCE_RATIO = 3.1
"""Compliance of Booth et al.'s thickest backing layer over their thinnest: "210% more
compliant" = 3.1× (Booth, Bacca, McMeeking & Foster 2018; journal, volume and DOI are not in
the abstract we read; the package's misalignment study cites Adv Mater Interfaces 5:1800272)."""

BOOTH2018_STIFF_MOUNT = PAPER_ARRAY.replace(
    **_STRIP, **{"backing.drive": "uniform", "backing.handle_stiffness": 1000.0}
)
"""The misalignment pad of ``gecko_agents.studies.misalignment`` (the paper's polyurethane,
stubby L = 5 µm setae, flat floor, default 1.413 MPa strip pulled uniformly) on the package's
default 1000 µN/µm mount, the stiff end of the Booth et al. (2018) comparison. The mount
stiffness is an assumption (the package default; their layers' stiffness relative to their
fibres' is not in the abstract we could read); the misalignment angle is set per run."""

BOOTH2018_COMPLIANT_MOUNT = BOOTH2018_STIFF_MOUNT.replace(
    **{"backing.handle_stiffness": 1000.0 / BOOTH2018_COMPLIANCE_RATIO}
)
""":data:`BOOTH2018_STIFF_MOUNT` on a mount 3.1× as compliant (cited: Booth et al. 2018's
thickest layer is "210% more compliant" than their thinnest)."""

KIM_SITTI2007_THIN = PAPER_ARRAY.replace(
    **_STRIP, **{"backing.drive": "uniform", "backing.t_b": 160.0}
)
"""A pad of the paper's polyurethane setae on a 160 µm backing, pulled straight off through a
uniform handle, for Kim & Sitti (2007, Appl Phys Lett 91:161905; DOI not found in the text we read).
Cited: the "160μm thick backing layer" and the polyurethane. Assumed: the package's JKR
sphere tips (theirs are spatulated), L = 5 µm setae, the strip's default modulus."""

KIM_SITTI2007_THICK = KIM_SITTI2007_THIN.replace(**{"backing.t_b": 1120.0})
""":data:`KIM_SITTI2007_THIN` on Kim & Sitti's "1120 μm thick backing" (cited)."""

GRAVISH2010_SETA = PAPER_ARRAY.replace(
    **{"mechanics": "rod", "seta.L": 5.0, "floor.sigma": 0.3, "contact.crack_speed": 1.0}
)
"""The pull-speed seta of ``gecko_agents.studies.pull_speed`` with crack kinetics, for the
rate dependence of Gravish et al. (2010, J R Soc Interface 7:259, doi:10.1098/rsif.2009.0133).
Assumed: the reference crack speed v* = 1 µm/µs and n = 0.5 (the package's Greenwood–Johnson
default): neither gecko keratin nor their silicone is characterised in the text we read."""

FRICTIONAL_SPATULA = PAPER_ARRAY.replace(
    **{
        "mechanics": "rod",
        "floor.sigma": 0.0,
        "array.count": 1,
        "tip": "spatula",
        "friction.mu": 10.0,
    }
)
"""The frictional-adhesion seta of ``gecko_agents.studies.frictional_adhesion`` (rod, θ =
60°, flat floor) with the spatula film tip (package defaults b = 3 µm, h = 1 µm, ℓ0 = 3 µm,
all assumptions) and the nearly bonded pad μ = 10 of that study, for Autumn et al. (2006, J
Exp Biol 209:3569) and Gillies & Fearing (2014, J R Soc Interface 11:20140021)."""

FRICTIONAL_SPHERE = FRICTIONAL_SPATULA.replace(**{"tip": "sphere"})
""":data:`FRICTIONAL_SPATULA` with the paper's JKR sphere tip (R = 4 µm)."""

KRONER_PILLARS = PAPER_ARRAY.replace(
    **{
        **_STRIP,
        "seta.L": 1.95,
        "seta.r": 2.35,
        "seta.theta_deg": 90.0,
        "tip": "flat_punch",
        "contact.R": 2.35,
        "array.pitch": 9.4,
        "friction.mu": 0.5,
        "backing.drive": "uniform",
    }
)
"""Kroner et al.'s patterned PDMS structures (Leibniz INM; "structure diameters of 4.7μm and
heights of 0.82 μm and 1.95 μm", abstract) as vertical pillars with flat punches on the
misalignment study's strip and stiff mount. Cited: r = a = 2.35 µm and L = 1.95 µm (the taller
structures). Assumed: the paper's polyurethane and its w (their PDMS modulus and work of
adhesion are not in the abstract), a pitch of twice the diameter, μ = 0.5; the tilt and the
number of pillars (the probe's size) are set per run."""

TOKAY_SETA = SetaArray(
    contact=Contact(R=0.1, E1=1600.0, nu1=0.3, E2=70_000.0, nu2=0.25, w=0.05),
    seta=Seta(r=2.0, L=110.0, theta_deg=45.0, density=1.2e-3),
    array=Array(count=1, pitch=8.3),
    floor=Floor(sigma=0.0),
    friction=Friction(mu=0.29),
    mechanics="rod",
    tip="spatulae",
    spatula=Spatula(b=0.2, h=0.01, E_f=1600.0, length=0.2),
    spatulae=Spatulae(count=300),
)
"""One tokay gecko seta (*Gekko gecko*): a β-keratin shaft on a rigid mount, branching into
N spatula films (``tip = "spatulae"``), on a flat glass floor, for the single-seta and
single-spatula measurements of Autumn et al. (2000, Nature 405:681), Huber et al. (2005, PNAS
102:16293) and Autumn et al. (2006, J Exp Biol 209:3569).

Cited: a seta "branches into hundreds of 200-nm spatulae" (Hansen & Autumn 2005, PNAS 102:385,
abstract, https://pmc.ncbi.nlm.nih.gov/articles/PMC544316): b = 0.2 µm; spatulae "≈ 200 nm
wide and long" (Huber et al. 2005 as summarised at soft-matter.seas.harvard.edu, "Evidence for
capillarity contributions to gecko adhesion ..."): the pad length ℓ0 = 0.2 µm; the setal
keratin's modulus E = 1.6 GPa for *Gekko gecko* (Peattie, Majidi, Corder & Full 2007, abstract,
as :data:`AUTUMN2006_SETA`) for the shaft and the films; μ = 0.29, the setal arrays'
friction coefficient along their natural drag on PTFE (Autumn et al. 2006a, J Exp Biol
209:3558, Table 1, jeb.biologists.org/highwire/markup/1089599/expansion).
Cited range: N = 300 spatulae, inside "100 to 1000 spatulae" per seta (de.zxc.wiki/wiki/Spatula,
a translation of the German Wikipedia, a secondary source); h = 0.01 µm, the low end of its
spatula thickness "ten to 15 nanometers" (same source); L = 110 µm and r = 2.0 µm, inside the
tokay's "ca. 2–4 μm in diameter and ca. 11–115 μm in length" (Scientific Reports 2022,
doi:10.1038/s41598-022-15698-2, introduction; 110 µm is the length the literature quotes from
Autumn et al. 2000, whose text we did not read).
Assumed: w = 0.05 J/m² (a van der Waals work of adhesion of non-polar solids, 2γ with
γ ≈ 25 mJ/m²; no text we read gives the spatula's on glass; it is not taken from Huber's force,
which the validation compares with); θ = 45° between shaft and mount (as
:data:`AUTUMN2006_SETA`: the setae are curved and no text we read gives a straight shaft's
angle); the spatula body's radius R = 0.1 µm (half its width: the Hertz compression of a pressed
spatula); ν = 0.3 and the density of a polymer, 1.2 g/cm³; the pitch 8.3 µm of a patch,
1/√(:data:`TOKAY_SETAL_DENSITY`); a glass floor (E = 70 GPa,
ν = 0.25); rigid branches sharing the load equally
(:class:`gecko_agents.contact.spatulae.SpatulaeTip`)."""
