"""The pad floor's contact step of :class:`gecko_agents.model.step_numpy.NumpyStep`: each tip
over its own flat pad (a rough floor drawn per seta, eq 28), vectorized over the setae: the
overlaps, the tip law's normal force and state changes, and the stick spring with its Coulomb
cap (the return mapping of :mod:`gecko_agents.model.step_numpy`).

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import numpy as np

from gecko_agents.physics.friction import friction_cap

__all__ = ["PadContact"]


class PadContact:
    """The pad-floor methods of :class:`~gecko_agents.model.step_numpy.NumpyStep` (which
    holds the state, law, world and constants they read)."""

    def _pad_overlaps(self):
        """Every tip against its own horizontal pad: (pad heights, tip x, overlap δ = R − (y − h)
        written into ``state.delta``, this step's candidate flags, attached flags)."""
        s = self.s
        h = self.world.h
        x, y = s.xy
        d = s.delta
        np.subtract(y, h, out=d)
        np.subtract(self.c.R, d, out=d)  # δ = R − (y − h)
        cand = s.candidate_step
        np.copyto(cand, s.candidate)
        return h, x, d, cand, s.attached

    def contact_pads(self):
        """Pad floor, batch path: every tip against its own horizontal pad, in bulk.

        The same physics as :meth:`contact` with n = (0, 1), t = (1, 0), q = (x, h): works on
        whole rows when every tip is attached and gathers the attached tips otherwise."""
        s, c, law = self.s, self.c, self.law
        if law.tangential:
            return self.contact_pads_tangential()
        n = s.n
        h, x, d, cand, att = self._pad_overlaps()
        all_att, new = self._pad_state_changes(x, h, d, cand, att)
        n_att = n if all_att else int(np.count_nonzero(att))
        Fdmp = s.F_damp_contact
        if n_att == 0:
            if self.any_contact_damping:
                Fdmp.fill(0.0)
                self.any_contact_damping = False
            return
        vx, vy = s.pv[2], s.pv[3]
        if n_att == n:
            ia = None
            da, xa, vta, vna, anc = d, x, vx, vy, s.anchor[0]
        else:
            ia = np.flatnonzero(att)
            da, xa, vta, vna, anc = d[ia], x[ia], vx[ia], vy[ia], s.anchor[0, ia]
        a_old = s.a if ia is None else s.a[ia]
        a = law.radius(da, a_old, c.dt)
        P = law.force(a, da)
        if law.rate_dependent:  # work of the moving edge, ∫(G − w)·2πa·|da| ≥ 0
            was = np.ones(a.size, bool) if new is None else ~(new if ia is None else new[ia])
            self.diss += float(np.sum((law.energy(a_old, da) - law.energy(a, da))[was]))
        xi = xa - anc
        xi_new, ft, dtg, sl = self._coulomb(P, xi, vta)
        dn = vna * -c.c_n
        if ia is None:
            np.subtract(x, xi_new, out=s.anchor[0])
            s.F[0] += ft
            s.F[1] += P + dn
            Fdmp[0], Fdmp[1] = dtg, dn
            s.P[:], s.Ft[:], s.a[:], s.xi[:] = P, ft, a, xi_new
            s.slip[:] = sl
        else:
            s.anchor[0, ia] = xa - xi_new
            s.F[0, ia] += ft
            s.F[1, ia] += P + dn
            Fdmp.fill(0.0)
            Fdmp[0, ia], Fdmp[1, ia] = dtg, dn
            s.P[ia], s.Ft[ia], s.a[ia], s.xi[ia] = P, ft, a, xi_new
            s.slip[ia] = sl
        self.any_contact_damping = True
        if new is not None:  # attachment starts the branch at U = 0: book the difference
            self.diss -= float(np.sum(self.contact_energy(np.flatnonzero(new))))

    def _pad_state_changes(self, x, h, d, cand, att):
        """Snap-offs, lost candidates and attachments of a pad step (``att`` updated in
        place); returns (every tip attached, the new attachments or None)."""
        s, c, law = self.s, self.c, self.law
        all_att, all_cand = bool(att.all()), bool(cand.all())
        if self.opening is None:
            lo = d < c.detach
        else:
            lo = self.opening.screen(slice(None), d, att)
        if law.rate_dependent:  # the crack has run through
            lo |= s.a <= c.release
        gone = lo if all_att else lo & att
        if all_cand:
            lost = None
        else:
            lost = att & ~cand
            gone &= cand
        if gone.any() or (lost is not None and lost.any()):
            self.detach(
                np.flatnonzero(lost) if lost is not None else np.zeros(0, np.int64),
                np.flatnonzero(gone),
                d,
            )
            all_att = False
        new = None
        if not all_att:
            new = d >= law.attach_overlap
            new &= cand
            new &= ~att
            if new.any():
                att |= new
                s.anchor[0, new] = x[new]
                s.anchor[1, new] = h[new]
            else:
                new = None
        return all_att, new

    def _coulomb(self, P, xi, vta):
        """Stick or slip of attached tips under normal forces ``P`` [µN] at tangential offsets
        ``xi`` [µm] from their anchors, tangential speeds ``vta`` [µm/µs]: the friction cap
        (the paper's μ·max(P, 0), eq 27, or μ·|P + 2Fc|), the new offsets, the tangential
        forces, their damping and which tips slide; the slip's Coulomb work is dissipated."""
        c = self.c
        k_t = c.k_t
        cap = friction_cap(P, c.Fc, c.mu, c.paper)
        trial = xi * -k_t
        sl = np.abs(trial) > cap
        any_sl = bool(sl.any())
        dtg = vta * -c.c_t
        if any_sl:
            xi_new = np.where(sl, np.copysign(cap / k_t, xi), xi)
            # Coulomb work of the slip: the anchor slides |ξ − ξ_new| against the cap.
            self.diss += float(np.sum((cap * np.abs(xi - xi_new))[sl]))
            dtg[sl] = 0.0
            ft = np.where(sl, -k_t * xi_new, trial)
            ft += dtg
        else:
            xi_new = xi
            ft = trial
            ft += dtg
        return xi_new, ft, dtg, sl

    def contact_pads_tangential(self):
        """Pad floor, a law that takes the tip's tangential position (the spatula): per seta,
        the law's ``step_scalar`` at the tip's offset from its front and height above its pad,
        in the order of :func:`gecko_agents.model.step_loop.pad_loop` (which compiles the same
        loop).

        Attachment at δ ≥ 0 puts the front and the tip body's stick anchor (``xi``, relative
        to the front) under the tip (ℓ = ℓ0, s0 = h, no pre-tension, ξ = 0); a tip lets go
        when its film has peeled off (ℓ = 0), past δ_detach or without a candidate floor, and
        its stored energy (the stick spring's included) is dissipated. Contact damping acts
        on attached tips."""
        s, c, law = self.s, self.c, self.law
        h, x, d, cand, att = self._pad_overlaps()
        lost = np.flatnonzero(att & ~cand)
        gone = np.flatnonzero(att & cand & (d < c.detach))
        if lost.size or gone.size:
            self.detach(lost, gone, d)
        new = ~att & cand & (d >= law.attach_overlap)
        if new.any():
            att |= new
            s.anchor[0, new], s.anchor[1, new] = x[new], h[new]
            s.a[new], s.s0[new], s.p0[new], s.uc[new] = law.ell0, law.s_attach, 0.0, 0.0
            s.xi[new] = 0.0  # the tip body's stick anchor, under the tip with the front
        Fdmp = s.F_damp_contact
        Fdmp.fill(0.0)
        self.any_contact_damping = True
        k = law.constants
        step = law.step_scalar
        peeled = []
        for i in np.flatnonzero(att):
            P, T, shift, ell, p0, s0, xa, U, diss, slid = step(
                x[i] - s.anchor[0, i], s.xy[1, i] - h[i], s.a[i], s.p0[i], s.s0[i], s.xi[i], k
            )
            # Attachment starts the contact at U = 0: book the energy it starts with.
            self.diss += -U if new[i] else diss
            s.anchor[0, i] += shift
            s.a[i], s.p0[i], s.s0[i], s.xi[i], s.uc[i] = ell, p0, s0, xa, U
            if ell <= 0.0:
                peeled.append(i)
                continue
            dtg = -c.c_t * s.pv[2, i] if law.damp_sliding or slid == 0.0 else 0.0
            dn = -c.c_n * s.pv[3, i]
            s.F[0, i] += T + dtg
            s.F[1, i] += P + dn
            Fdmp[0, i], Fdmp[1, i] = dtg, dn
            s.P[i], s.Ft[i], s.slip[i] = P, T, slid > 0.0
        if peeled:
            self.detach(np.zeros(0, np.int64), np.array(peeled), d)

    # ------------------------------------------------------------------ after the forces
