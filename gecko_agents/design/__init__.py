"""Design search: the best fibre array for a surface, a material and a fabrication process.

``gecko-agents design DESIGN.toml`` (or :func:`run_design` on :func:`load_design`) searches a
space of pillar arrays with Optuna, screening each design with the package's fast models
(:mod:`~gecko_agents.design.screen`: closed forms, the quasi-static solver and, on a backing
layer, the field model), confirms the
best ones with the time-stepped engine (:mod:`~gecko_agents.design.confirm`) and reports them
(:mod:`~gecko_agents.design.report`). The tables of tip kinds, knobs, objectives and
constraints are in :mod:`~gecko_agents.design.space`.

Design file
-----------
::

    description = "flat punch or sphere pillars on the measured Dektak scan"
    seed = 0                       # the sampler's seed and the first floor seed, [0, 2³² − 1]
    trials = 200                   # screening trials
    confirm = 4                    # best designs confirmed with the engine
    objectives = ["pull_off_per_area", "spread"]   # of space.OBJECTIVES

    [material]
    E_MPa = 1.413                  # pillar modulus [MPa]
    nu = 0.3
    w_J_per_m2 = 0.165             # work of adhesion [J/m² = µN/µm]

    [surface]
    kind = "measured"              # measured | gaussian | self_affine | flat
    file = "dektak"                # measured: the packaged scan or a path (relative to here)
    # sigma_um, correlation_length_um, hurst, short_cutoff_um, long_cutoff_um: generated floors

    [test]
    probe = "flat"                 # flat | sphere (the probe is then the surface: kind = "flat")
    probe_radius_um = 100.0
    preload_kPa = 10.0             # pressure on the backing (required)
    pull_speed_um_per_us = 0.05
    misalignment_spread_deg = 0.0  # spread over backing tilts −a, 0, +a (screen)
    release_tilt_deg = 1.0         # the tilt a gripper releases with (release_force)
    floor_seeds = 3                # floors the screen averages over
    pillars = 20                   # pillars in the screened row
    engine_pillars = 5             # pillars in an engine run
    engine_seeds = 2               # engine runs per confirmed design

    [space]                        # each knob a number (fixed) or [low, high] (searched)
    tip = ["flat_punch", "sphere"] # of space.TIP_KINDS
    backing = "rigid"              # rigid | elastic | layer (or a list)
    radius_um = [1.0, 5.0]
    aspect_ratio = [1.0, 6.0]
    lean_deg = 90.0
    fill_fraction = [0.05, 0.4]    # or spacing_um
    # backing_thickness_um, backing_modulus_MPa: with backing = "elastic" or "layer"

    [constraints]                  # all optional
    min_radius_um = 1.0
    max_aspect_ratio = 6.0
    min_gap_um = 2.0
    no_buckling_below_kPa = 20.0
    max_preload_kPa = 50.0

    [quick]                        # --quick: trials, confirm and [quick.test] merged in
    trials = 20

Every key, type and range is checked, the quick variant too, every corner of the space is
built as a parameter set, and a fabrication bound that leaves no design (a radius, an aspect
ratio or a gap no corner of the space reaches) is refused before the first trial; errors are
:class:`~gecko_agents.runfiles.schema.RunFileError` naming the file, the key, the value and the
allowed range. The output folder, its lock and a ``--storage`` URL are checked before the
first trial too (:mod:`~gecko_agents.design.folder`).
"""

from __future__ import annotations

from gecko_agents.design.schema import DesignSpec, load_design
from gecko_agents.design.study import run_design

__all__ = ["DesignSpec", "load_design", "run_design"]
