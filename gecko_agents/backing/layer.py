"""A backing layer: the seta roots on the free surface of an elastic layer bonded to the
holder, coupled through its thickness.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`); the layer is
``params.backing``'s t_b, E_b, nu_b with ``kind = "layer"``.

The layer (plane strain: the simulated row stands for an infinite set of identical rows
b = ``array.pitch`` apart) is bonded to the holder, the kinematic body the protocol moves
(``World.plate``). Each seta pushes its root up (towards the holder) with the normal force
P_i [µN], spread over its cell (a strip as wide as the pitch); the roots then sit w = C·P
above where a rigid plate holds them, C the layer's compliance between the roots
(:func:`gecko_agents.physics.layer.row_compliance`, the surface Green's function of a layer on
a rigid base). Only the normal load and displacement are coupled: the layer's shear
compliance under the setae's tangential pull is left out (the roots keep their abscissae).

The layer is massless: its waves (√(E_b/ρ_b) ≈ 34 µm/µs for the paper's polyurethane) cross it
in microseconds, a step's travel of the holder being nanometres. So every step the roots are
put where the layer's elasticity and the setae balance, for the tips where the step evaluates
the forces (x₀ + v₀·dt, semi-implicit Euler): with the seta spring's normal stiffness K_yy
and damper c, P = P₀ − (K_yy + c/dt)·w + (c/dt)·w_prev, so

    (I + k̃·C)·w = C·(P₀ + (c/dt)·w_prev),   k̃ = K_yy + c/dt,

one precomputed matrix, exact for the linear seta (eq 16–21). For the rod (nonlinear) the
same matrix is the Newton step's, iterated to 1e-10 of the layer's displacement scale.

Explicit step only (``integrator = "auto"`` gives it,
:func:`gecko_agents.model.implicit.check_integrator`): the implicit step's Jacobian holds each
tip's root fixed, and the long step then loads the layer a step behind the tips. Measured (20
setae, L = 5 µm, press 0.3 µm and pull at 0.05 µm/µs): on a 10 µm layer the energy balance
missed by 11 % of the run's energy, on a 1000 µm layer the run diverged; the explicit step
closes it within 1 %.

Energy: elastic = setae (at the displaced roots) + contacts + the layer's ½·P·w; the seta
dampers dissipate against the roots' velocity (the setae's bookkeeping books them against the
holder's; :meth:`LayerBacking.advance` moves them onto the roots', with the damper's force
averaged over the step as the layer's energy ½(P_n + P_{n−1})·Δw takes it); the force on the
holder is the setae's pull, which the massless layer passes on whole.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import fft

from gecko_agents.physics import layer

__all__ = ["LAYER_ARRAYS", "LAYER_COLUMNS", "LayerBacking", "ToeplitzSolver"]

LAYER_COLUMNS = ("layer_front_x_um", "layer_deflection_max_um", "layer_energy_pJ")
"""Columns the layer adds to ``history.csv``: the detachment front (abscissa [µm] of the
attached seta farthest from the centre; NaN while none is attached), the largest |w| [µm] of
the roots and the layer's elastic energy [pJ]."""

LAYER_ARRAYS = ("layer_deflection_um",)
"""Per-record arrays in ``History.backing``: the roots' displacement w [µm] (n_records, n),
positive towards the holder (the layer compressed)."""

_ROD_ITERATIONS = 20


class ToeplitzSolver:
    """A symmetric Toeplitz matrix T (first column ``column``): T·x by a zero-padded FFT and
    T·x = y by conjugate gradients preconditioned with T. Chan's optimal circulant (Chan
    1988, SIAM J Sci Stat Comput 9:766: c_k = ((n − k)·t_k + k·t_{n−k})/n, positive definite
    where T is), each O(n log n); an FFT, so no BLAS threads."""

    def __init__(self, column):
        t = np.asarray(column, float)
        self.n = n = t.size
        self._m = 2 * n
        self._eig = fft.rfft(np.concatenate([t, [0.0], t[:0:-1]]))
        k = np.arange(n)
        self._pre = fft.rfft(((n - k) * t + k * t[(n - k) % n]) / n).real

    def __call__(self, x) -> np.ndarray:
        """T·x."""
        return fft.irfft(fft.rfft(x, self._m) * self._eig, self._m)[: self.n]

    def solve(self, y, x0, rtol: float = 1e-9, maxiter: int = 500) -> np.ndarray:
        """x with T·x = y, from ``x0``, to a residual of ``rtol``·|y|."""
        x = x0.copy()
        r = y - self(x)
        stop = rtol * float(np.sqrt(y @ y)) + 1e-300
        z = fft.irfft(fft.rfft(r) / self._pre, self.n)
        p, rz = z.copy(), float(r @ z)
        for _ in range(maxiter):
            if float(np.sqrt(r @ r)) <= stop:
                return x
            q = self(p)
            alpha = rz / float(p @ q)
            x += alpha * p
            r -= alpha * q
            z = fft.irfft(fft.rfft(r) / self._pre, self.n)
            rz, rz_old = float(r @ z), rz
            p = z + (rz / rz_old) * p
        raise RuntimeError(f"the layer's solve did not converge in {maxiter} iterations")


class LayerBacking:
    """The elastic layer of ``params.backing`` (``kind = "layer"``) under the setae, bonded to
    the holder (``world.plate``); the backing of a :class:`gecko_agents.model.Model` (its
    ``model.backing``; the interface is
    :class:`gecko_agents.backing.rigid.RigidBacking`'s). The numpy kernel and the batch
    contact only; ``mechanics = "linear"`` or ``"rod"``.

    Attributes
    ----------
    column : C's first column [µm/µN] (C is Toeplitz).
    w : the roots' displacement at the last step [µm].
    P : the normal force of each seta on the layer at the last step [µN].
    """

    kind = "layer"
    rigid = False
    implicit = False  # the module docstring says why
    loops = False
    contacts = ("batch",)
    mechanics = ("linear", "rod")

    def __init__(self, setup, world, state, physics, spring_force):
        p = setup.params
        if p.backing.leader_arm:
            raise ValueError(
                f"Backing.leader_arm = {p.backing.leader_arm!r} µm needs kind = 'elastic' (the "
                "layer backing, kind = 'layer', has no leader arm)"
            )
        bk, pitch = p.backing, p.array.pitch
        self.world, self.state, self.physics, self.n = world, state, physics, setup.n
        self.spring_force, self.linear = spring_force, p.mechanics == "linear"
        self.K, self.dt = setup.seta.K, setup.dt  # the explicit step: dt stays
        # C is Toeplitz (the roots are evenly spaced): its first column is the kernel.
        self.column = (
            layer.line_kernel(pitch * np.arange(self.n), bk.t_b, bk.E_b, bk.nu_b, pitch) / pitch
        )
        self._c = setup.seta.c_seta
        self._k_eff = float(self.K[1, 1]) + self._c / self.dt
        self._C = ToeplitzSolver(self.column)
        self._A = ToeplitzSolver(np.eye(1, self.n)[0] + self._k_eff * self.column)
        self.w = np.zeros(self.n)
        self.w_prev = np.zeros(self.n)
        self._w_older = np.zeros(self.n)
        self.P = np.zeros(self.n)
        self._Fdy_prev = np.zeros(self.n)
        self.geometry = {}
        self.info = {
            "thickness_um": bk.t_b,
            "modulus_MPa": bk.E_b,
            "poisson": bk.nu_b,
            "width_um": pitch,
            "self_compliance_um_per_uN": float(self.column[0]),
            "uniform_compliance_um_per_uN": float(self._C(np.ones(self.n)).max()),
            "confined_modulus_MPa": layer.confined_modulus(bk.E_b, bk.nu_b),
        }

    @property
    def compliance(self) -> np.ndarray:
        """C (n, n) [µm/µN], dense (:func:`gecko_agents.physics.layer.row_compliance`)."""
        i = np.arange(self.n)
        return self.column[np.abs(i[:, None] - i[None, :])]

    # ------------------------------------------------------------------ stepping
    def _normal_force(self, hx, hy, w, vpy):
        """Upward force [µN] of each seta on its root (spring + damper) with the roots at
        w [µm] above the rigid plate's place, the tips where the step evaluates them."""
        s, wd = self.state, self.world
        x, y = s.xy
        if self.linear:  # eq 16–21: F = −K·u, u the deflection
            K = self.K
            ux = x - hx - wd.rest_dx
            uy = y - hy - wd.rest_dy - w
            Fy = -K[1, 0] * ux - K[1, 1] * uy
        else:
            roots = np.column_stack((hx + wd.root_dx, hy + wd.root_dy + w))
            Fy = self.spring_force(np.column_stack((x, y)), roots)[0][:, 1]
        v_root = vpy + (w - self.w_prev) / self.dt
        return -Fy + self._c * (s.pv[3] - v_root)

    def roots(self, hx, hy, vpx, vpy, dt):
        """The roots where the layer and the setae balance for this step's tips (module
        docstring), as per-seta "plates" for the seta springs (root minus its offset), and
        their velocities [µm/µs]; the holder at (``hx``, ``hy``) [µm] moving at (``vpx``,
        ``vpy``) [µm/µs], the step ``dt`` [µs] (the explicit step's, ``self.dt``)."""
        self._w_older, self.w_prev, w = self.w_prev, self.w, self.w
        rod = not self.linear
        P = self._normal_force(hx, hy, w, vpy)
        for _ in range(_ROD_ITERATIONS if rod else 1):
            rhs = P + self._k_eff * w  # (I + k̃C)·w_new = C·rhs: exact for the linear seta
            guess = 2.0 * w - self._w_older if not rod else w  # the last two steps' trend
            new = self._A.solve(self._C(rhs), guess)
            P = rhs - self._k_eff * new
            done = np.abs(new - w).max() <= 1e-10 * (np.abs(new).max() + 1e-12)
            w = new
            if rod:
                P = self._normal_force(hx, hy, w, vpy)
            if done:
                break
        self.w, self.P = w, P
        return hx, hy + w, vpx, vpy + (w - self.w_prev) / self.dt

    def step_limit(self) -> float | None:
        """No bound of its own (the layer runs with the explicit step)."""
        return None

    def hold(self, state) -> None:
        """Nothing to keep: the layer took its roots' forces in :meth:`roots`."""

    def advance(self, dt, hx, hy, vpx, vpy, on_plate):
        """After the tips' step ``dt`` [µs]: the seta dampers' dissipation moved from the
        holder's velocity onto the roots' (Σ F_d,y·(w − w_prev)); the force on the holder is
        the setae's ``on_plate`` [µN], passed on whole by the massless layer."""
        Fdy = self.state.F_damp_seta[1]
        self.physics.diss += 0.5 * float((Fdy + self._Fdy_prev) @ (self.w - self.w_prev))
        self._Fdy_prev = Fdy.copy()
        return on_plate

    # ------------------------------------------------------------------ state
    def front_x(self) -> float:
        """Abscissa [µm] of the attached seta farthest from the row's centre (NaN if none)."""
        att = np.flatnonzero(self.state.attached)
        if not att.size:
            return math.nan
        x = self.world.root_dx[att]
        return float(x[np.argmax(np.abs(x))])

    def root_positions(self, handle) -> np.ndarray:
        """Root positions (N, 2) [µm] with the holder at ``handle`` (x, y) [µm], the roots
        displaced by the layer as at the last step."""
        return np.column_stack(
            (handle[0] + self.world.root_dx, handle[1] + self.world.root_dy + self.w)
        )

    def energy(self) -> float:
        """The layer's elastic energy ½·P·w = ½·wᵀC⁻¹w [pJ] at the last step."""
        return 0.5 * float(self.P @ self.w)

    def kinetic_energy(self, tips: float) -> float:
        """Kinetic energy [pJ]: the tips' (``tips``); the layer is massless."""
        return tips

    def record(self) -> tuple[dict, dict]:
        """(scalar columns, per-record arrays) at a record (:data:`LAYER_COLUMNS`,
        :data:`LAYER_ARRAYS`)."""
        scalars = dict(
            zip(
                LAYER_COLUMNS,
                (self.front_x(), float(np.abs(self.w).max()), self.energy()),
                strict=True,
            )
        )
        return scalars, {"layer_deflection_um": self.w.copy()}
