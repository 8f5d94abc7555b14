"""The contact step of :class:`gecko_agents.model.step_numpy.NumpyStep` on a continuous floor
(a polyline: generated, self-affine, probe or measured), and the per-contact reference path
(``contact = "callback"``): each tip against its nearest floor segment, the tip law's normal
force along the segment's normal and the stick spring with its Coulomb cap along its tangent
(the return mapping of :mod:`gecko_agents.model.step_numpy`).

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["FloorContact"]


class FloorContact:
    """The continuous floor's methods of :class:`~gecko_agents.model.step_numpy.NumpyStep`
    (which holds the state, law, world and constants they read)."""

    def geometry(self, ps, x, y):
        """Nearest floor point (qx, qy), unit normal (nx, ny) from floor to tip and overlap δ
        of tip centres (x, y) (each (k,)) against floor segments ``ps`` [µm]."""
        w, R = self.world, self.c.R
        if w.pads:  # horizontal pads: the normal is vertical
            qy = w.h[ps]
            return x, qy, np.zeros(ps.size), np.ones(ps.size), R - (y - qy)
        A, B = w.seg_a[ps], w.seg_b[ps]
        abx, aby = B[:, 0] - A[:, 0], B[:, 1] - A[:, 1]
        t = ((x - A[:, 0]) * abx + (y - A[:, 1]) * aby) / (abx * abx + aby * aby)
        t = np.clip(t, 0.0, 1.0)
        qx, qy = A[:, 0] + t * abx, A[:, 1] + t * aby
        dx, dy = x - qx, y - qy
        dist = np.sqrt(dx * dx + dy * dy)
        inv = 1.0 / np.maximum(dist, 1e-300)
        return qx, qy, dx * inv, dy * inv, R - dist

    def _trial_stretch(self, ti, x, y, n_x, n_y, new):
        """Trial stretch ξ [µm] of the stick springs of attached tips ``ti`` (centres x, y
        [µm], contact normals n = (n_x, n_y), t = (n_y, −n_x); ``new``: attached this step).

        A tip is a sphere that does not rotate, so the floor's material point under it moves
        against it at the centre's velocity: its tangential displacement is the centre's,
        Δr·t, and ξ grows by that: ξ = ξ_old + (r − r_old)·t. Where the floor is flat this is
        (r − anchor)·t, the anchor a = r_old − ξ_old·t_old being where the spring would be
        unstretched; where the tip crosses a facet edge (t_old ≠ t) the nearest floor point
        may jump, but the tip has not slid: ξ = (r − a)·t + ξ_old·(1 − t_old·t) (t_old·t =
        n_old·n). A new contact starts at ξ = 0 (a = r). On a pad (n = (0, 1) throughout)
        this is the pad path's ξ = x − anchor_x to the last bit.

        The increment of the tangential spring by the contact's relative tangential
        displacement in each step is the distinct element method's (Cundall & Strack 1979,
        Géotechnique 29:47; only its abstract was read here). Units: µm throughout."""
        s = self.s
        xi = (x - s.anchor[0, ti]) * n_y - (y - s.anchor[1, ti]) * n_x
        turn = 1.0 - (self.normal[0, ti] * n_x + self.normal[1, ti] * n_y)
        xi += np.where(new, 0.0, s.xi[ti]) * turn
        return xi

    def contact(self, tips, x, y, vx, vy, ps):
        """Contact of ``tips`` (positions x, y, velocities vx, vy, each (k,)) with segments
        ``ps``: the general (and reference) form, any floor, one or many tips.

        Updates the attach/detach state, stick anchors and per-seta records of those tips and
        adds the contact force to ``state.F``; returns it (fx, fy). Tangent t = (n_y, −n_x).
        """
        s, c, law = self.s, self.c, self.law
        if law.tangential:
            raise ValueError(
                f"{law.label or f'tip = {law.name!r}'} needs a pad floor "
                "(floor.correlation_length = 0) and "
                "contact='batch'"
            )
        qx, qy, nx, ny, delta = self.geometry(ps, x, y)
        att0 = s.attached[tips]
        new = ~att0 & (delta >= law.attach_overlap)
        if self.opening is None:
            gone = att0 & (delta < c.detach)
        else:
            gone = self.opening.screen(tips, delta, att0)
        if law.rate_dependent:  # the crack has run through
            gone |= att0 & (s.a[tips] <= c.release)
        att = (att0 | new) & ~gone
        s.delta[tips] = delta
        if np.any(gone):
            self.detach(tips[:0], tips[gone], s.delta)
        if np.any(new):  # the stick spring starts unstretched at the tip's centre
            s.anchor[0, tips[new]] = x[new]
            s.anchor[1, tips[new]] = y[new]
        k = tips.size
        fx, fy = np.zeros(k), np.zeros(k)
        i = np.flatnonzero(att)
        if i.size:
            ti = tips[i]
            n_x, n_y = nx[i], ny[i]
            a_old = s.a[ti]
            a = law.radius(delta[i], a_old, c.dt)
            Pi = law.force(a, delta[i])
            if law.rate_dependent:  # work of the moving edge, ∫(G − w)·2πa·|da| ≥ 0
                was = ~new[i]
                self.diss += float(
                    np.sum((law.energy(a_old, delta[i]) - law.energy(a, delta[i]))[was])
                )
            vn = vx[i] * n_x + vy[i] * n_y
            vt = vx[i] * n_y - vy[i] * n_x
            xi = self._trial_stretch(ti, x[i], y[i], n_x, n_y, new[i])
            cap = self.friction.cap(Pi, c.Fc)
            trial = -c.k_t * xi
            sl = np.abs(trial) > cap
            xi_new = np.where(sl, np.sign(xi) * cap / c.k_t, xi)
            # Return mapping: slide the anchor so the stick spring holds exactly the cap.
            s.anchor[0, ti] = x[i] - xi_new * n_y
            s.anchor[1, ti] = y[i] + xi_new * n_x
            # Coulomb work of the slip: the anchor slides |ξ − ξ_new| against the cap.
            self.diss += float(np.sum(cap * np.abs(xi - xi_new)))
            dn = -c.c_n * vn
            dt_ = np.where(sl, 0.0, -c.c_t * vt)
            ft = np.where(sl, -c.k_t * xi_new, trial) + dt_
            fn = Pi + dn
            fx[i] = fn * n_x + ft * n_y
            fy[i] = fn * n_y - ft * n_x
            s.F_damp_contact[0, ti] += dn * n_x + dt_ * n_y
            s.F_damp_contact[1, ti] += dn * n_y - dt_ * n_x
            s.P[ti], s.Ft[ti], s.slip[ti] = Pi, ft, sl
            self.normal[0, ti], self.normal[1, ti] = n_x, n_y
            s.a[ti], s.xi[ti] = a, xi_new
            # Attachment starts the branch at U = 0: book the difference.
            jumped = ti[new[i]]
            if jumped.size:
                self.diss -= float(np.sum(self.contact_energy(jumped)))
        s.attached[tips] = att
        s.F[0, tips] += fx
        s.F[1, tips] += fy
        return fx, fy

    def contact_general(self):
        """Continuous floor: the contact of every tip that has a candidate segment, in bulk."""
        s = self.s
        s.F_damp_contact.fill(0.0)
        self.any_contact_damping = True
        s.delta.fill(np.nan)
        pt, ps, dup = self.world.pair_arrays()
        cand = s.candidate_step
        cand.fill(False)
        cand[pt] = True
        self.lost(cand)
        if pt.size == 0:
            return
        x, y = s.xy
        if dup:
            # Several candidate segments: keep each tip's nearest floor point.
            delta = self.geometry(ps, x[pt], y[pt])[4]
            order = np.lexsort((-delta, pt))
            keep = order[np.unique(pt[order], return_index=True)[1]]
            pt, ps = pt[keep], ps[keep]
        self.contact(pt, x[pt], y[pt], s.pv[2, pt], s.pv[3, pt], ps)
