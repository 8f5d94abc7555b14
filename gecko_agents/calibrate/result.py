"""The outcome of a calibration fit: values, uncertainties, identifiability, and its files.

Units: those of each free parameter (µm, µN/µm, MPa, …); observations in µN and µm.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from gecko_agents.calibrate.data import Data
from gecko_agents.output_paths import atomic_write_bytes


@dataclass
class FitResult:
    """Outcome of :func:`gecko_agents.calibrate.fit`.

    Attributes
    ----------
    values, stderr : fitted value and one standard error per free parameter (dicts by name);
        the standard error is NaN where none holds (on a bound, or zero residual degrees of
        freedom without stated uncertainties: see the module docstring).
    correlation : (k, k) correlation matrix in the order of ``names``.
    cost : ½ Σ (weighted residual)² at the optimum (scipy's convention).
    identifiable : name → bool (see the module docstring); ``notes`` says why not.
    """

    names: list
    values: dict
    stderr: dict
    correlation: np.ndarray
    cost: float
    identifiable: dict
    notes: dict
    bounds: dict
    observed: np.ndarray
    uncertainty: np.ndarray
    model: np.ndarray
    data: Data
    record: dict

    @property
    def residuals(self) -> np.ndarray:
        """(model − observed) / uncertainty at the optimum."""
        return (self.model - self.observed) / self.uncertainty

    def save(self, out) -> Path:
        """Write ``fit.json``, ``fit.png`` and ``residuals.png`` into directory ``out``."""
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(out / "fit.json", json.dumps(self.record, indent=2).encode())
        self._plots(out)
        return out

    def _plots(self, out: Path):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        d, c = self.data, self.data.columns
        x = {"preload": c.get("preload"), "curve": c.get("displacement")}.get(d.kind)
        label = {"preload": "preload [µN]", "curve": "plate above touch-down [µm]"}.get(d.kind)
        if x is None:
            x, label = np.arange(self.observed.size), "observation"
        else:
            x = np.tile(x, self.observed.size // x.size)
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        ax.errorbar(
            x, self.observed, yerr=self.uncertainty if d.err_given else None, fmt="o", label="data"
        )
        ax.plot(x, self.model, "s", mfc="none", label="model at the fit")
        ax.set_xlabel(label)
        ax.set_ylabel(
            {"preload": "pull-off [µN]", "curve": "normal force [µN]"}.get(
                d.kind, "value [µN or µm]"
            )
        )
        ax.set_title(
            ", ".join(f"{n} = {self.values[n]:.3g} ± {self.stderr[n]:.2g}" for n in self.names),
            fontsize=8,
        )
        ax.legend()
        fig.tight_layout()
        fig.savefig(out / "fit.png", dpi=120)
        plt.close(fig)
        fig, ax = plt.subplots(figsize=(5.5, 3.0))
        ax.axhline(0.0, color="grey", lw=0.8)
        ax.plot(x, self.residuals, "o")
        ax.set_xlabel(label)
        ax.set_ylabel("(model − data)/σ" if d.err_given else "model − data")
        fig.tight_layout()
        fig.savefig(out / "residuals.png", dpi=120)
        plt.close(fig)
