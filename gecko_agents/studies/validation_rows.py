"""The published measurements of the literature comparison (:mod:`gecko_agents.studies.
validation`): one dict per row, the source cited in full, the text we read (``quote``, word for
word as the search tools returned it, with the address it came from), their value as printed,
and the parameters our number uses, each cited or assumed with the reason and, where a number,
its plausible range (the study recomputes ours at both ends).

Nothing here is computed; ``ours`` names the function of the study that computes our number
(``None``: the row is not scored, ``unscored`` says why). ``compare`` is ``"value"`` (their
number against ours, within their stated scatter) or ``"trend"`` (the direction: ``expect``
says which side of 1 ours must fall, as theirs does). Units as printed in ``kind``.
"""

from __future__ import annotations

from gecko_agents.studies.validation_pillar_rows import PILLAR_ROWS

AUTUMN2006A = (
    "Autumn K, Majidi C, Groff RE, Dittmore A, Fearing R (2006). Effective elastic modulus of "
    "isolated gecko setal arrays. J Exp Biol 209:3558–3568. doi:10.1242/jeb.02469"
)
AUTUMN2006A_TABLE = (
    "https://jeb.biologists.org/highwire/markup/1089599/expansion (Table 1 of the article)"
)
AUTUMN2006A_ABSTRACT = (
    "https://journals.biologists.com/jeb/article/209/18/3558/16105/"
    "Effective-elastic-modulus-of-isolated-gecko-setal"
)
TABLE_QUOTE = (
    "Along natural drag path and curvature (+45°)Vertical (0°)Against natural drag path and "
    "curvature (−45°) [...] Setal stiffness (kseta) (N m−1)\nLoading0.08±0.0040.08±0.0030.11±"
    "0.004 [...] Values are means ± s.e.m."
)
AUTUMN2006B = (
    "Autumn K, Dittmore A, Santos D, Spenko M, Cutkosky M (2006). Frictional adhesion: a new "
    "angle on gecko attachment. J Exp Biol 209:3569. doi:10.1242/jeb.02486"
)
GILLIES = (
    "Gillies AG, Fearing RS (2014). Simulation of synthetic gecko arrays shearing on rough "
    "surfaces. J R Soc Interface 11:20140021. doi:10.1098/rsif.2014.0021"
)
GILLIES_QUOTE = (
    "on sinusoidal surfaces with amplitudes much larger than the nanoscale features, "
    "spatula-shaped features can increase adhesive forces by 2.5 times on smooth surfaces and "
    "10 times on rough surfaces."
)
GILLIES_URL = (
    "https://studylib.net/doc/18535535/simulation-of-synthetic-gecko-arrays-shearing-on-rough-su..."  # noqa: E501
)

_E = {
    "name": "E",
    "value": 1600.0,
    "unit": "MPa",
    "status": "cited",
    "range": [1450.0, 1750.0],
    "why": "setal β-keratin of Gekko gecko, 1.6 GPa ± 0.15 s.e. (Peattie, Majidi, Corder & "
    "Full 2007, abstract); range ± 1 s.e.",
}
_R = {
    "name": "r",
    "value": 3.0,
    "unit": "µm",
    "status": "assumed",
    "range": [1.0, 5.0],
    "why": "seta radius: the geometry Autumn et al. used is not in the text we read; a seta "
    "is '2-10 um wide' (Harvard soft-matter wiki, a secondary source)",
}
_L = {
    "name": "L",
    "value": 80.0,
    "unit": "µm",
    "status": "assumed",
    "range": [30.0, 130.0],
    "why": "seta length: 'Each 30–130 µm long seta' (Autumn et al. 2000, Nature 405:681, "
    "abstract); the middle of that range",
}
_THETA = {
    "name": "theta",
    "value": 45.0,
    "unit": "deg",
    "status": "assumed",
    "range": [30.0, 60.0],
    "why": "shaft angle to the backing: no text we read gives it",
}
_STRAIGHT = {
    "name": "shape",
    "value": "straight rod (eq 16–21)",
    "unit": "",
    "status": "assumed",
    "range": None,
    "why": "the package's seta; the real seta is curved and branched",
}
_DIRECTION = {
    "name": "direction",
    "value": "+45° = backing moved down and towards −x",
    "unit": "",
    "status": "assumed",
    "range": None,
    "why": "'along natural drag path' read as the gripping drag of this package (the "
    "plate moving −x pulls the seta back along its shaft); read the other way, ours is the "
    "inverse and the trend reverses",
}

ROWS: list[dict] = [
    {
        "id": "autumn2006a_k_seta",
        "source": AUTUMN2006A,
        "read_at": AUTUMN2006A_TABLE,
        "quote": TABLE_QUOTE,
        "measured": "stiffness of one seta, isolated arrays compressed vertically (loading)",
        "theirs": "0.08 ± 0.003 N/m (mean ± s.e.m.)",
        "theirs_value": 0.08,
        "scatter": 0.003,
        "kind": "seta stiffness [N/m]",
        "compare": "value",
        "params": [_E, _R, _L, _THETA, _STRAIGHT],
        "ours": "seta_stiffness",
        "cause": "k ∝ E r⁴/L³ (eq 19–20): the geometry we had to assume sets our number to "
        "within four decades; a straight rod has no curvature.",
    },
    {
        "id": "autumn2006a_anisotropy",
        "source": AUTUMN2006A,
        "read_at": AUTUMN2006A_TABLE,
        "quote": TABLE_QUOTE,
        "measured": "seta stiffness compressed against / along the natural drag path (−45° over "
        "+45°)",
        "theirs": "0.11 ± 0.004 over 0.08 ± 0.004 N/m (×1.4)",
        "theirs_value": 0.11 / 0.08,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [_THETA, _R, _L, _STRAIGHT, _DIRECTION],
        "ours": "seta_anisotropy",
        "cause": "a straight rod compressed along its shaft is axially stiff (Ka/Kp = 4L²/r²), "
        "so the direction that loads the shaft is orders of magnitude stiffer; the curved real "
        "seta bends either way, hence their mild ×1.4.",
    },
    {
        "id": "autumn2006a_E_eff",
        "source": AUTUMN2006A,
        "read_at": AUTUMN2006A_ABSTRACT,
        "quote": "Eeff of setal arrays during vertical and +45°compression (along the natural "
        "path of drag of the setae) were 83±4.0 kPa and 86±4.4 kPa (means ± s.e.m.), "
        "respectively.",
        "measured": "effective elastic modulus of the array, vertical compression",
        "theirs": "83 ± 4.0 kPa (mean ± s.e.m.)",
        "theirs_value": 83.0,
        "scatter": 4.0,
        "kind": "array modulus [kPa]",
        "compare": "value",
        "params": [
            _E,
            _R,
            _L,
            _THETA,
            {
                "name": "D",
                "value": 0.0144,
                "unit": "1/µm²",
                "status": "assumed",
                "range": [0.005, 0.02],
                "why": "setal density 14 400/mm² (a secondary web "
                "source, enviroliteracy.org); the array's own count is not in the text we "
                "read",
            },
            {
                "name": "E_eff formula",
                "value": "K_y·D·L sin θ",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "Hooke's law for a bed of "
                "springs of height L sin θ (our derivation; the paper's own formula is not "
                "in the text we read)",
            },
        ],
        "ours": "array_modulus",
        "cause": "as the seta stiffness, times an assumed density and height.",
    },
    {
        "id": "autumn2006b_frictional_adhesion",
        "source": AUTUMN2006B,
        "read_at": "https://jeb.biologists.org/content/jexbio/209/18/3569/F2.large.jpg (abstract)",
        "quote": "We found that adhesion depended directly on shear force, and was independent "
        "of detachment angle. [...] The linear relation between adhesion and shear force is "
        "consistent with a critical angle of release in live gecko toes and isolated setal "
        "arrays, and also with our prior observations of single setae.",
        "measured": "adhesion against shear at release (setal arrays, toes): linear, a critical "
        "angle α*",
        "theirs": "adhesion linear in shear (the abstract gives no value of α*)",
        "theirs_value": None,
        "scatter": None,
        "kind": "critical angle α* [deg]",
        "compare": "trend",
        "expect": ">0",
        "params": [
            {
                "name": "tip",
                "value": "spatula film",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "the package's peeling film (b = 3 µm, h = 1 µm, "
                "ℓ0 = 3 µm: package defaults, not gecko spatulae)",
            },
            {
                "name": "mu",
                "value": 10.0,
                "unit": "-",
                "status": "assumed",
                "range": [0.2, 10.0],
                "why": "the nearly bonded pad of the frictional-adhesion study; 0.2 is the paper's",
            },
            {
                "name": "drag",
                "value": "8 µm gripping, preload 0.2 µN, θ = 60°",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "the frictional-adhesion study's load–drag–pull",
            },
        ],
        "ours": "frictional_adhesion",
        "cause": "our α* is the shaft angle at release of one rod seta with a film tip, not a "
        "property of an array; the abstract's own α* could not be read, so only the linear "
        "trend is compared.",
    },
    {
        "id": "kendall1975_peel",
        "source": "Kendall K (1975). Thin-film peeling — the elastic term. J Phys D Appl Phys "
        "8:1449. doi:10.1088/0022-3727/8/13/005",
        "read_at": "https://www.synapsesocial.com/papers/69d91c3eccb0bba5a56841f0 (abstract)",
        "quote": "An energy balance shows that the force required to peel an elastic film from a "
        "rigid substrate depends not only on the adhesive surface energy but also on an elastic "
        "deformation term. [...] Experiments using rubber peeling from glass over a range of "
        "peel angles support the theory.",
        "measured": "peel force per width against peel angle (rubber on glass)",
        "theirs": "F/b = w/(1 − cos ψ) (plus the elastic term) supported by experiment over a "
        "range of angles; no number in the abstract",
        "theirs_value": 1.0,
        "scatter": None,
        "kind": "F/b over Kendall's w_eff/(1 − cos ψ) [-]",
        "compare": "trend",
        "expect": "falls",
        "params": [
            {
                "name": "pad",
                "value": "pad_peel study (240 setae full, 300 quick, "
                "elastic strip 1.413 MPa × 50 µm)",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "the package's pad; their rubber film is not a fibrillar pad",
            },
            {
                "name": "w_eff",
                "value": "measured in the run",
                "unit": "µN/µm",
                "status": "cited",
                "range": None,
                "why": "Kendall's w is the work of "
                "separation per area; the run's own dissipation per detached area",
            },
        ],
        "ours": "kendall_peel",
        "cause": "a pad of discrete setae is not a continuous film: the work of separation "
        "w_eff is the run's own, and the peeled arm bends.",
    },
    {
        "id": "kendall1971_flat_punch",
        "source": "Kendall K (1971). The adhesion and surface energy of elastic solids. J Phys D "
        "Appl Phys 4:1186. DOI not found",
        "read_at": "http://globalauthorid.com/WebPortal/ArticleView?wd=03E459076164F53E3B17DDE64"
        "33651BDFC924CF6827EE83B10945D7208A6D4BE (a reference list only)",
        "quote": "K. Kendall, “The Adhesion and Surface Energy of Elastic Solids,” J. Phys. D. "
        "Appl. Phys., 4, 1186 (1971).",
        "measured": "pull-off of a flat punch against its radius",
        "theirs": "not read (the abstract and text were not reachable with the search tools)",
        "theirs_value": None,
        "scatter": None,
        "kind": "pull-off [µN]",
        "compare": "value",
        "params": [],
        "ours": "flat_punch_ours",
        "unscored": "source not read; our number needs the flat_punch tip (the designs issue): "
        "fill validation.flat_punch_ours, then the row is scored against the value read",
        "cause": "",
    },
    {
        "id": "booth2018_misalignment",
        "source": "Booth JA, Bacca M, McMeeking RM, Foster KL (2018). Benefit of backing-layer "
        "compliance in fibrillar adhesive patches — resistance to peel propagation in the "
        "presence of interfacial misalignment. Journal, volume and DOI not in the abstract we "
        "read (the package's misalignment study cites Adv Mater Interfaces 5:1800272)",
        "read_at": "https://discovery.researcher.life/topic/compliant-layers/6778720?page=5",
        "quote": "for misalignment angles on the order of just 0.1°, peel‐like detachments are "
        "observed. The thickest backing layer, being 210% more compliant than the thinnest, "
        "yields a 43% increase in the adhesive strength at a misalignment angle of 0.4°.",
        "measured": "pull-off at 0.4° misalignment, backing 3.1× more compliant over the stiffest",
        "theirs": "+43 % (×1.43) for 210 % more compliant",
        "theirs_value": 1.43,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [
            {
                "name": "compliance ratio",
                "value": 3.1,
                "unit": "-",
                "status": "cited",
                "range": None,
                "why": "'210% more compliant'",
            },
            {
                "name": "angle",
                "value": "0.4° (400 setae); quick: 0.8° on 200 setae, the same rise across the pad",
                "unit": "",
                "status": "cited",
                "range": None,
                "why": "their angle",
            },
            {
                "name": "k_stiff",
                "value": 1000.0,
                "unit": "µN/µm",
                "status": "assumed",
                "range": [500.0, 2000.0],
                "why": "the stiff mount is the package default; "
                "the compliance is the mount's, not a layer's (their layers' stiffness "
                "relative to the fibres' is not in the abstract)",
            },
        ],
        "ours": "booth_misalignment",
        "cause": "our compliance is a handle spring per length between a rigid holder and a "
        "bending strip, theirs a thicker elastic layer deforming at the detachment front.",
    },
    {
        "id": "kim_sitti2007_backing",
        "source": "Kim S et al. (2007; 'Kim & Sitti' in the issue, the author list is not in the "
        "text we read). Effect of backing layer thickness on adhesion "
        "of single-level elastomer fiber arrays. Appl Phys Lett 91(16):161905. DOI not found "
        "in the text we read",
        "read_at": "https://experts.illinois.edu/en/publications/effect-of-backing-layer-"
        "thickness-on-adhesion-of-single-level-ela",
        "quote": "Polyurethane microfiber arrays with spatulated tips on a 160 μm thick backing "
        "layer show nine times greater adhesion strength (around 22 N cm2) than those with a "
        "1120 μm thick backing. A theoretical model is proposed to explain this difference in "
        "which very thin backing layers promote equal load sharing, maximizing adhesion, while "
        "very thick backings can lead to reduced adhesion due to edge stress concentration.",
        "measured": "adhesion strength, 160 µm over 1120 µm backing",
        "theirs": "nine times (×9)",
        "theirs_value": 9.0,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [
            {
                "name": "t_b",
                "value": "160 / 1120",
                "unit": "µm",
                "status": "cited",
                "range": None,
                "why": "their backings",
            },
            {
                "name": "tip",
                "value": "JKR sphere, L = 5 µm setae, uniform handle",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "theirs are spatulated; the strip is the package's",
            },
        ],
        "ours": "kim_sitti_backing",
        "cause": "our backing is a bending strip pulled through a uniform handle: its thickness "
        "only sets its bending stiffness, and there is no through-thickness elasticity, hence "
        "no edge stress concentration (their proposed mechanism).",
    },
    {
        "id": "gillies2014_smooth",
        "source": GILLIES,
        "read_at": GILLIES_URL,
        "quote": GILLIES_QUOTE,
        "measured": "adhesion of spatula over sphere tips, smooth surface (their simulation)",
        "theirs": "2.5 times",
        "theirs_value": 2.5,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [
            {
                "name": "b",
                "value": 3.0,
                "unit": "µm",
                "status": "assumed",
                "range": [1.5, 6.0],
                "why": "film width = the seta's diameter (package "
                "default); their tip sizes are not in the abstract",
            },
            {
                "name": "R",
                "value": 4.0,
                "unit": "µm",
                "status": "assumed",
                "range": None,
                "why": "the paper's sphere",
            },
            {
                "name": "protocol",
                "value": "8 µm gripping drag, 90° pull, μ = 10",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "the frictional-adhesion study's; they sheared arrays",
            },
        ],
        "ours": "gillies_smooth",
        "cause": "our sphere (R = 4 µm) holds Fc = 1.5πRw = 3.1 µN, our film's 90° peel only "
        "w·b = 0.49 µN plus its pre-tension: tip sizes, not shapes, are compared; theirs were "
        "matched, ours are package defaults.",
    },
    {
        "id": "gillies2014_rough",
        "source": GILLIES,
        "read_at": GILLIES_URL,
        "quote": GILLIES_QUOTE,
        "measured": "adhesion of spatula over sphere tips, rough surface (their simulation)",
        "theirs": "10 times",
        "theirs_value": 10.0,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [
            {
                "name": "floor",
                "value": "Gaussian pads, σ = 1 µm",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "their sinusoidal surfaces' amplitudes are not in the abstract",
            },
            {
                "name": "count",
                "value": "16 setae (quick 4)",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "the frictional-adhesion study's patch",
            },
        ],
        "ours": "gillies_rough",
        "cause": "as on smooth floors, and each of our setae meets its own flat pad (eq 28), "
        "so roughness only staggers the heights.",
    },
    {
        "id": "gravish2010_rate",
        "source": "Gravish N, Wilkinson M, Sponberg S, Parness A, Esparza N, Soto D, Yamaguchi T, "
        "Broide M, Cutkosky M, Creton C, Autumn K (2010). Rate-dependent frictional adhesion in "
        "natural and synthetic gecko setae. J R Soc Interface 7:259–269. "
        "doi:10.1098/rsif.2009.0133",
        "read_at": "https://pmc.ncbi.nlm.nih.gov/articles/PMC2842608 (abstract)",
        "quote": "friction and adhesion forces increased at the onset of sliding and continued "
        "to increase with shear speed from 500 nm s−1 to 158 mm s−1.",
        "measured": "adhesion against sliding speed (setal arrays)",
        "theirs": "increases from 500 nm/s to 158 mm/s (no factor in the abstract)",
        "theirs_value": None,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": ">1",
        "params": [
            {
                "name": "v_star",
                "value": 1.0,
                "unit": "µm/µs",
                "status": "assumed",
                "range": [0.1, 10.0],
                "why": "crack speed of the tip's material: not characterised in the text we read",
            },
            {
                "name": "speeds",
                "value": "0.01 → 0.1 µm/µs (10 → 100 mm/s), pull-off",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "inside their range; ours is a pull, theirs a slide",
            },
        ],
        "ours": "gravish_rate",
        "cause": "our rate dependence is viscoelastic crack kinetics of the tip (Maugis & "
        "Barquins 1978), theirs a population of stick–slip events while sliding.",
    },
    {
        "id": "autumn2000_critical_angle",
        "source": "Autumn K, Liang YA, Hsieh ST, Zesch W, Chan WP, Kenny TW, Fearing R, Full RJ "
        "(2000). Adhesive force of a single gecko foot-hair. Nature 405:681–685. "
        "doi:10.1038/35015073",
        "read_at": "https://ideas.repec.org/a/nat/nature/v405y2000i6787d10.1038_35015073.html",
        "quote": "Suitably orientated setae reduced the forces necessary to peel the toe by "
        "simply detaching above a critical angle with the substratum.",
        "measured": "critical detachment angle of a single seta",
        "theirs": "a critical angle (its value is not in the abstract we read)",
        "theirs_value": None,
        "scatter": None,
        "kind": "critical angle α* [deg]",
        "compare": None,
        "params": [],
        "ours": None,
        "unscored": "the angle's value is not in the text we read (reviews quote ≈30°; our "
        "spatula seta's α* is in the frictional-adhesion row)",
        "cause": "",
    },
]
ROWS += PILLAR_ROWS  # the pillar rows (studies/validation_pillar_rows.py)
