"""The literature comparison's rows on pillars (mushroom and flat tips, buckling under preload),
in the form of :mod:`gecko_agents.studies.validation_rows` (which appends them to its rows)."""

from __future__ import annotations

PILLAR_ROWS: list[dict] = [
    {
        "id": "gorb2007_mushroom",
        "source": "Gorb S, Varenberg M, Peressadko A, Tuma J (2007). Biomimetic mushroom-shaped "
        "fibrillar adhesive microstructure. J R Soc Interface 4(13):271–275. "
        "doi:10.1098/rsif.2006.0164",
        "read_at": "https://pmc.ncbi.nlm.nih.gov/articles/PMC2359835",
        "quote": "Results revealed that pull-off force and peel strength of the structured "
        "specimens are more than twice those of the flat specimens.",
        "measured": "pull-off of mushroom-structured over flat specimens",
        "theirs": "more than twice",
        "theirs_value": 2.0,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": None,
        "params": [],
        "ours": None,
        "unscored": "needs a mushroom tip and a flat control (the designs issue)",
        "cause": "",
    },
    {
        "id": "delcampo2007_shape",
        "source": "del Campo A et al. (2007). Patterned surfaces with pillars with controlled 3D "
        "tip geometry mimicking bioattachment devices. Adv Mater. doi:10.1002/adma.200602476 "
        "(from the page's address; the other authors and volume:pages are not in the text we "
        "read)",
        "read_at": "http://onlinelibrary.wiley.com/doi/10.1002/adma.200602476/abstract",
        "quote": "This work provides the first experimental evidence of the influence of the "
        "contact shape on the adhesion of structured surfaces",
        "measured": "pull-off of pillars against their tip shape",
        "theirs": "no number in the text we read",
        "theirs_value": None,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": None,
        "params": [],
        "ours": None,
        "unscored": "no value in the text we read; needs the designs issue's tips",
        "cause": "",
    },
    {
        "id": "paretkar2011_buckling",
        "source": "Paretkar D et al. (2011), adhesion of mushroom pillars after buckling: "
        "not found with the search tools (title, journal and pages unknown)",
        "read_at": "—",
        "quote": "",
        "measured": "pull-off after the pillars buckle under preload",
        "theirs": "not read",
        "theirs_value": None,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": None,
        "params": [],
        "ours": None,
        "unscored": "source not read; needs buckling pillars (the designs issue)",
        "cause": "",
    },
    {
        "id": "yague_isla2015_buckling",
        "source": "Yagüe Isla P, Kroner E (2015). A novel bioinspired switchable adhesive with "
        "three distinct adhesive states. Adv Funct Mater 25(16):2444–2450. "
        "doi:10.1002/adfm.201500241 (read in place of Paretkar et al., not found)",
        "read_at": "https://pmc.ncbi.nlm.nih.gov/articles/PMC4553704",
        "quote": "At higher preload, all pillars form contact, resulting in high pull-off force. "
        "Even further loading leads to buckling induced detachment of the pillars which "
        "corresponds to extremely low pull-off force.",
        "measured": "pull-off of mushroom pillars against preload, up to buckling",
        "theirs": "extremely low pull-off after buckling (no number in the abstract)",
        "theirs_value": None,
        "scatter": None,
        "kind": "ratio [-]",
        "compare": "trend",
        "expect": "<1",
        # "extremely low pull-off": most of the adhesion lost; a loss under half is no match.
        "trend_resolution": 0.5,
        "params": [
            {
                "name": "pillar",
                "value": "polyurethane elastica, r = 1.5 µm, L = 15 µm, flat punch",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "their pillars' geometry and modulus are not in the text we read; the "
                "pillar-design study's pillar, a flat punch for their mushroom",
            },
            {
                "name": "preloads",
                "value": "0.5 and 3 × the clamped–clamped Euler load",
                "unit": "",
                "status": "assumed",
                "range": None,
                "why": "below and well past buckling, as their 'higher' and 'further' loading",
            },
        ],
        "ours": "buckled_preload",
        "cause": "the model's punch face stays bonded and flat while the column buckles, and the "
        "column straightens as it is pulled; their pillars detach as they buckle (the face "
        "tilts and peels from its edge), physics the model lacks.",
    },
]
