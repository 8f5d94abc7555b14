"""Data shipped with the package, each folder with its provenance and licence (README.md).

* ``paper_figures/`` — numbers the source paper's text states for its figures (Fig 8, 10, 11);
* ``surfaces/`` — two measured surfaces: a stylus-profilometer line scan (Dektak,
  ``dektak_profile.csv``) and an AFM map (WSxM, ``wsxm_afm.top``);
* ``literature/`` — the published measurements of the literature comparison
  (``validation.toml``: sources, quotes, addresses read, values, scatter and parameters).
"""

from pathlib import Path

DATA_DIR = Path(__file__).resolve().parent
PAPER_FIGURES = DATA_DIR / "paper_figures"
"""The paper's figure readings (CSV, units in the column names)."""
SURFACES = DATA_DIR / "surfaces"
"""Measured surfaces (provenance and licence in ``surfaces/README.md``)."""
DEKTAK_PROFILE = SURFACES / "dektak_profile.csv"
"""A stylus-profilometer line scan (x, height; see ``surfaces/README.md``)."""
WSXM_AFM = SURFACES / "wsxm_afm.top"
"""An AFM height map in WSxM format (see ``surfaces/README.md``)."""
LITERATURE = DATA_DIR / "literature"
"""Published measurements, as read (provenance in ``literature/README.md``)."""
LITERATURE_ROWS = LITERATURE / "validation.toml"
"""The rows of the literature comparison (TOML; ``gecko_agents.studies.validation_rows``)."""
