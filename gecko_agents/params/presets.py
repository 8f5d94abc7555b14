"""The paper's named parameter presets, each a documented :class:`SetaArray` constant.

Every upper-case :class:`SetaArray` here is a preset that run files and ``gecko-agents params``
name (:data:`gecko_agents.runfiles.schema.PRESETS`); the string after each assignment is its
documentation (:func:`gecko_agents.runfiles.schema.preset_docs`). Re-exported by
:mod:`gecko_agents.params`.
"""

from __future__ import annotations

from gecko_agents.params import Array, Contact, Floor, Friction, Seta, SetaArray

__all__ = ["PAPER_TABLE1", "PAPER_ARRAY", "PAPER_FIG5_READING"]


PAPER_TABLE1 = SetaArray(
    contact=Contact(R=4.0, E1=1.413, nu1=0.3, E2=55_000.0, nu2=0.25, gamma1=0.040, gamma2=0.170),
    seta=Seta(r=1.5, L=20.0, theta_deg=30.0),
    array=Array(count=1, pitch=4.0),
    floor=Floor(sigma=0.0),
    friction=Friction(mu=0.2),
)
"""Single seta of the paper's Table 1 (Fig 8).

Table 1: slope 30°, diameter 3 µm (→ rod radius r = 1.5 µm, NOTES.md), length 20 µm, ν = 0.3,
E = 1.413 MPa, "adhesive energy" 40 mJ/m² read as the seta's surface energy γ1; the floor is the
55 GPa, ν = 0.25, γ2 = 170 mJ/m² plane of section 3.1.1, and w = 2√(γ1γ2) = 0.1649 J/m² (the
paper's own rule). Tip radius R = 4 µm from section 3.1.1 (Table 1 gives none). μ = 0.2 from
section 3.3.2. The alternative reading that matches Fig 5 (w = 0.080 J/m²) is
:data:`PAPER_FIG5_READING`.
"""

PAPER_ARRAY = SetaArray(
    contact=PAPER_TABLE1.contact,
    seta=Seta(r=1.5, L=20.0, theta_deg=60.0),
    array=Array(count=10_000_000, pitch=4.0),
    floor=Floor(sigma=1.0, correlation_length=0.0, seed=0),
    friction=Friction(mu=0.2),
)
"""The array of section 3.3.2 (Fig 10–11).

10⁷ setae on 1 cm² at 4 µm pitch (count and pitch kept separate: a square 4 µm pitch would give
6.25×10⁶, NOTES.md), θ = 60°, E = 1.413 MPa, ν = 0.3, γ1 = 40 mJ/m², floor 55 GPa, ν = 0.25,
γ2 = 170 mJ/m², μ = 0.2, roughness "mean square error 1" read as RMS height σ = 1 µm with an
independent height under each seta (eq 28). Rod r = 1.5 µm, L = 20 µm and R = 4 µm carried over
from Table 1 and section 3.1.1, which the array section does not restate.
"""

PAPER_FIG5_READING = PAPER_TABLE1.replace(**{"contact.w": 0.080})
"""Table 1 with w = 0.080 J/m², the work of adhesion that Fig 5's −1.5 µN pull-off at R = 4 µm
implies (= 2 × 40 mJ/m², i.e. w = 2γ1; NOTES.md)."""
