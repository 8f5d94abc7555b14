"""The frictional-adhesion study's set-up: its name, base array, preload, drag, plate speeds
and tips, shared by the study (:mod:`gecko_agents.studies.frictional_adhesion`) and its report
(:mod:`gecko_agents.studies.frictional_adhesion_report`). Units: µm, µN, µs."""

from __future__ import annotations

from gecko_agents import protocol
from gecko_agents.params import PAPER_ARRAY

__all__ = ["NAME", "BASE", "PRELOAD", "DRAG", "SPEED", "CONVERGENCE_SPEEDS", "TIPS"]

NAME = "frictional_adhesion"
BASE = PAPER_ARRAY.replace(**{"mechanics": "rod", "floor.sigma": 0.0, "array.count": 1})
PRELOAD = 0.2  # µN: a rod seta with a spatula folds flat under 1 µN at μ = 0.2
DRAG = 8.0  # µm
# µm/µs: the package's quasi-static plate speed. The film's pull-off converges as the plate slows
# (its contact dashpot adds a force ∝ v); at 0.05 µm/µs the releasing 90° pull-off was 8 % above
# its quasi-static value (the convergence table of the full run, speed_convergence.csv).
SPEED = protocol.DEFAULT_SPEED
# Plate speeds [µm/µs] of the convergence check: the 90° pulls of the spatula at μ = 10, both drags.
CONVERGENCE_SPEEDS = (0.05, 0.02, 0.01, 0.005, 0.0025)
TIPS = {  # the scenario's tip names: parameters and labels
    "sphere": ({"tip": "sphere"}, "sphere"),
    "sphere_sb": (
        {"tip": "sphere", "contact.shear_coupling": "savkoor_briggs"},
        "sphere, Savkoor–Briggs",
    ),
    "spatula": ({"tip": "spatula"}, "spatula"),
}
