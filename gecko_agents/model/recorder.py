"""What a run records, kept apart from the stepping: rows of scalars, per-seta arrays, events.

The recorder reads the model's public, documented state (:class:`gecko_agents.model.Model`'s
``time``, ``plate_position``, ``reaction``, ``state``, its energy methods and what its
``backing`` records) and never writes into it. Units and column names:
:mod:`gecko_agents.history`.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.history import (
    FILM_FIELDS,
    PER_SETA_FIELDS,
    SCALAR_COLUMNS,
    STATE_FREE,
    STATE_SLIP,
    STATE_STICK,
    History,
)

__all__ = ["Recorder", "DETACHMENT_FIELDS"]

DETACHMENT_FIELDS = (
    "seta",
    "time_us",
    "plate_x_um",
    "plate_y_um",
    "overlap_um",
    "release_overlap_um",
    "force_uN",
)


class Recorder:
    """Collects a row every time :meth:`record` is called and detachments as they happen.

    Parameters
    ----------
    per_seta : also record the per-seta arrays :data:`~gecko_agents.history.PER_SETA_FIELDS`.
    film : with ``per_seta``, also the film tip's :data:`~gecko_agents.history.FILM_FIELDS`
        (its peel front is the state's ``anchor``, its attached length the state's ``a``).
    mode : the contact law's ``release_mode`` (where its tips' detachment starts); if not
        empty, each detachment also records it as ``mode``.
    """

    def __init__(self, per_seta: bool, film: bool = False, mode: str = ""):
        self.rows = {c: [] for c in SCALAR_COLUMNS}
        fields = PER_SETA_FIELDS + (FILM_FIELDS if film else ())
        self.per = {f: [] for f in fields} if per_seta else {}
        self.det = {k: [] for k in DETACHMENT_FIELDS + (("mode",) if mode else ())}
        self.mode = mode
        # The backing's columns and per-record arrays, as its record() names them (none for
        # the rigid plate).
        self.backing_rows: dict[str, list] = {}
        self.backing_arrays: dict[str, list] = {}
        self.max_ke = self.max_el = 0.0

    def record(self, m, work: float, dissipated: float) -> dict:
        """One row from model ``m`` after a step; ``work`` and ``dissipated`` are the run's
        cumulative plate work and dissipated energy [pJ]. Returns the row of
        :data:`~gecko_agents.history.SCALAR_COLUMNS` (the backing's columns are kept beside
        it: its front is NaN while nothing is attached)."""
        s = m.state
        px, py = m.plate_position
        total = np.add.reduce  # np.sum's reduction, without its wrapper
        el = float(total(m.spring_energies()) + total(m.contact_energies()) + m.backing_energy())
        ke = m.kinetic_energy()
        reaction = m.reaction
        row = {
            "time_us": m.time,
            "plate_x_um": px,
            "plate_y_um": py,
            "force_normal_uN": float(total(s.P)),
            "force_tangential_uN": float(total(s.Ft)),
            "plate_force_x_uN": float(reaction[0]),
            "plate_force_y_uN": float(reaction[1]),
            "n_attached": np.count_nonzero(s.attached),
            "n_sliding": np.count_nonzero(s.slip & s.attached),
            "energy_elastic_pJ": el,
            "energy_kinetic_pJ": ke,
            "energy_dissipated_pJ": dissipated + m.damping_half_step(),
            "work_plate_pJ": work,
        }
        for k, val in row.items():
            self.rows[k].append(val)
        scalars, arrays = m.backing.record()
        for k, val in scalars.items():
            self.backing_rows.setdefault(k, []).append(val)
        for k, val in arrays.items():
            self.backing_arrays.setdefault(k, []).append(np.array(val))
        self.max_ke = max(self.max_ke, ke)
        self.max_el = max(self.max_el, el)
        if self.per:
            state = np.where(s.attached, np.where(s.slip, STATE_SLIP, STATE_STICK), STATE_FREE)
            vals = {
                "tip_x_um": s.xy[0],
                "tip_y_um": s.xy[1],
                "force_normal_uN": s.P,
                "force_tangential_uN": s.Ft,
                "overlap_um": m.overlaps(),
                "state": state.astype(np.int8),
            }
            if "film_front_x_um" in self.per:
                vals["film_front_x_um"] = np.where(s.attached, s.anchor[0], np.nan)
                vals["film_attached_um"] = np.where(s.attached, s.a, np.nan)
            for f, series in self.per.items():
                series.append(np.array(vals[f]))
        return row

    def note_detachments(self, time: float, plate_position, events) -> None:
        """Detachments of one step: ``events`` holds (seta, overlap [µm], release overlap [µm],
        force [µN]) per tip that let go: the overlap at that step (−∞ if its floor left the
        sensor's reach), where it started to run away from its equilibrium, its last force."""
        px, py = plate_position
        for i, overlap, release, force in events:
            self.det["seta"].append(i)
            self.det["time_us"].append(time)
            self.det["plate_x_um"].append(px)
            self.det["plate_y_um"].append(py)
            self.det["overlap_um"].append(overlap)
            self.det["release_overlap_um"].append(release)
            self.det["force_uN"].append(force)
            if self.mode:
                self.det["mode"].append(self.mode)

    def history(self, params, seed: int, geometry: dict, meta: dict) -> History:
        """The recorded :class:`~gecko_agents.history.History`."""
        rows = self.rows | self.backing_rows
        scalars = {k: np.asarray(v, dtype=float) for k, v in rows.items()}
        setae = {k: np.asarray(v) for k, v in self.per.items()}
        det = {k: np.asarray(v) for k, v in self.det.items()}
        # Quasi-static measure: peak kinetic over peak elastic energy of the run.
        meta = dict(meta, max_kinetic_to_elastic=self.max_ke / max(self.max_el, 1e-300))
        backing = {k: np.asarray(v) for k, v in self.backing_arrays.items()}
        return History(params, seed, scalars, setae, geometry, det, meta, backing)
