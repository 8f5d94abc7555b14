"""The validity items' limits (:mod:`gecko_agents.diagnostics` states each item's reason and
source), read by :func:`~gecko_agents.diagnostics.diagnose` and the markdown table."""

__all__ = ["LIMITS"]

LIMITS = {
    "a_over_R": ("≤", 0.1),
    "tabor": ("≥", 5.0),
    "linear_deflection": ("≤", 0.1),
    "quasi_static": ("≤", 0.05),
    "time_step": ("≤", 1.0),
    "touched": ("≥", 1.0),
    "crack_deborah": ("≤", 100.0),
    "records": ("≤", 0.05),
    "release_step": ("≤", 0.02),
    "pillars_meet": ("≥", 1.0),
    "probe_curvature": ("≤", 0.1),
    "probe_scale": ("≤", 1.0),
}
"""Item → (relation, limit); the reasons and sources are in the module docstring."""
