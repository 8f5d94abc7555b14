"""A rigid spherical probe on discrete fibrils coupled through an elastic half-space backing.

The model of the spherical-probe test of Bettscheider, Yu, Foster, McMeeking, Arzt, Hensel &
Booth, "Breakdown of continuum models for spherical probe adhesion tests on micropatterned
surfaces", J Mech Phys Solids (2021), article 104365, and of the open MATLAB code that
accompanies it, ``github.com/jamieabooth/sphericalprobe`` (MIT). What was read: the code in
full (its compliance matrix, its press and pull loops, its lattices and its strength
extraction) and the paper's title, authors, journal, highlights and abstract in library
catalogue records; the full text of the paper was not available, so the equations below are
re-derived from the code, and none of its code is used here. Its README credits the model to
Noderer et al. 2007 (Proc R Soc A, doi:10.1098/rspa.2007.1891), Guidoni et al. 2010 (J Mech
Phys Solids 58:1571, doi:10.1016/j.jmps.2010.07.009) and Bacca et al. 2016 (J Mech Phys
Solids 96:428, doi:10.1016/j.jmps.2016.04.008).

The model (units µm, µN, MPa = µN/µm²; compression positive, as in
:mod:`gecko_agents.physics.fibril_probe`):

* Fibril i, a vertical cylinder of radius c and length L at (x_i, y_i), is a linear spring of
  compliance L/(πc²E) (:func:`fibril_compliance`), bonded to the probe from the moment the
  probe's surface reaches its tip until its tension reaches the release force F_r (a fixed
  strength: "independent of the tip geometry", the code's README says).
* Its root stands on an elastic half-space (the backing, same E and ν in the code). The
  half-space couples the fibrils: a force f_j on fibril j's root lowers fibril i's root by
  f_j·(1 − ν²)/(πE·r_ij) (Boussinesq's point load at distance r_ij), and fibril i's own force
  lowers its root by the mean of that displacement over its base disc loaded uniformly,
  f_i·16(1 − ν²)/(3π²E·c) (:func:`halfspace_compliance`). So the tips move by w = C·f with
  C = diag(L/(πc²E)) + C_b.
* The probe, pressed a depth d past touching the highest tip, has its surface at d + h_i
  below tip i's rest position, h_i ≤ 0 the probe's height there (the code takes the parabola
  h_i = −r_i²/(2R_p), :func:`parabolic_heights`). Attached fibrils follow it,
  w_A = d + h_A, so f_A = (C_AA)⁻¹(d + h_A) = a·d + b, linear in d between events.
* Pressing (d grows, force control to the preload P): a free fibril j attaches when the
  probe's surface reaches its tip, d + h_j ≥ (C_jA f_A) — the backing under a pressed
  neighbourhood sinks and lowers the free tips around it. No fibril lets go while pressing.
* Pulling (d falls): a fibril lets go when its tension −f_i reaches F_r; the others then
  share its load (several may follow at once); none attaches again. The pull-off is the
  largest tension −Σf on the probe.

The code steps the probe in small increments and takes the largest force it samples; here the
press and the pull go from event to event (the next attachment or release is where a linear
function of d crosses zero), so the result has no step error. With C_b = 0 (a rigid backing)
the model is the independent-fibril closed form of :mod:`gecko_agents.physics.fibril_probe`
with weights 1, exactly.

The code's further step — finding the strain at release that makes the model's saturated
pull-off (the pull-off once a larger preload no longer raises it) meet a measured one, and the
effective work of adhesion n·F_r²/(2k) it reports (:func:`effective_work_of_adhesion`) — is
the inverse of :func:`probe_test`; it is not ported.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gecko_agents.physics import beam

__all__ = [
    "ProbeTest",
    "effective_work_of_adhesion",
    "fibril_compliance",
    "halfspace_compliance",
    "hex_lattice",
    "parabolic_heights",
    "probe_test",
    "saturation_pull_off_continuum",
    "square_lattice",
]


def _positive(name: str, value) -> float:
    value = float(value)
    if not np.isfinite(value) or value <= 0.0:
        raise ValueError(f"{name} = {value!r} must be a finite number in (0, inf)")
    return value


def hex_lattice(pitch: float, extent: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions [µm] of a hexagonal lattice of fibrils, one at the origin, nearest neighbours
    ``pitch`` apart, all within ``extent`` of the origin (areal density 2/(√3·pitch²)).

    Parameters
    ----------
    pitch : centre-to-centre spacing [µm], > 0. extent : radius of the patch [µm], > 0.
    """
    p, e = _positive("pitch", pitch), _positive("extent", extent)
    m = int(np.ceil(2.0 * e / p)) + 1  # rows j reach ±e at |j| ≤ 2e/(√3p); i shifts by j/2
    i, j = np.meshgrid(np.arange(-2 * m, 2 * m + 1), np.arange(-m, m + 1), indexing="ij")
    x = p * (i + 0.5 * j).ravel()
    y = p * (0.5 * np.sqrt(3.0) * j).ravel()
    keep = x * x + y * y <= e * e * (1.0 + 1e-12)
    return x[keep], y[keep]


def square_lattice(pitch: float, extent: float) -> tuple[np.ndarray, np.ndarray]:
    """Positions [µm] of a square lattice of fibrils, one at the origin, ``pitch`` apart, all
    within ``extent`` of the origin (areal density 1/pitch²).

    Parameters
    ----------
    pitch : spacing [µm], > 0. extent : radius of the patch [µm], > 0.
    """
    p, e = _positive("pitch", pitch), _positive("extent", extent)
    m = int(np.ceil(e / p))
    i, j = np.meshgrid(np.arange(-m, m + 1), np.arange(-m, m + 1), indexing="ij")
    x, y = p * i.ravel().astype(float), p * j.ravel().astype(float)
    keep = x * x + y * y <= e * e * (1.0 + 1e-12)
    return x[keep], y[keep]


def parabolic_heights(x, y, probe_radius: float) -> np.ndarray:
    """Heights h = −(x² + y²)/(2R_p) [µm] of a probe of radius R_p below its apex at the
    origin: the sphere near its apex, as the ``sphericalprobe`` code takes it.

    Parameters
    ----------
    x, y : fibril positions [µm]. probe_radius : R_p [µm], > 0.
    """
    R = _positive("probe_radius", probe_radius)
    x, y = np.asarray(x, float), np.asarray(y, float)
    return -(x * x + y * y) / (2.0 * R)


def fibril_compliance(length: float, radius: float, modulus: float) -> float:
    """Axial compliance L/(πc²E) of a cylindrical fibril [µm/µN] (a bar in tension): the
    inverse of the seta's axial stiffness, :func:`gecko_agents.physics.beam.axial_stiffness`.

    Parameters
    ----------
    length : L [µm], > 0. radius : c [µm], > 0. modulus : E [MPa = µN/µm²], > 0.
    """
    L, c, E = (
        _positive("length", length),
        _positive("radius", radius),
        _positive("modulus", modulus),
    )
    return 1.0 / float(beam.axial_stiffness(c, L, E))


def halfspace_compliance(x, y, radius: float, modulus: float, poisson: float) -> np.ndarray:
    """Compliance matrix [µm/µN] of fibril roots on an elastic half-space (the backing).

    Off the diagonal, Boussinesq's surface displacement a distance r_ij from a point force,
    (1 − ν²)/(πE·r_ij): the downward displacement W(1 + ν){2(1 − ν) + cos²θ}/(2πEr) of a
    point load W on a half-space (Boussinesq 1885, as given in A. E. H. Love's article
    "Elasticity", Encyclopaedia Britannica, 11th ed., 1911, §72) at the surface, θ = 90°. On
    the diagonal, the mean of that displacement over a disc of radius c carrying the force
    uniformly, 16(1 − ν²)/(3π²E·c) (the value in Bettscheider et al.'s code; its double
    integral is checked by quadrature in ``tests/test_probe_booth.py``).

    Parameters
    ----------
    x, y : root positions [µm] (distinct). radius : fibril radius c [µm], > 0.
    modulus : backing's Young's modulus E [MPa], > 0. poisson : its Poisson ratio ν, in
    [0, 0.5].
    """
    c, E = _positive("radius", radius), _positive("modulus", modulus)
    nu = float(poisson)
    if not 0.0 <= nu <= 0.5:
        raise ValueError(f"poisson = {nu!r} must be in [0, 0.5]")
    x, y = np.asarray(x, float), np.asarray(y, float)
    r = np.hypot(x[:, None] - x[None, :], y[:, None] - y[None, :])
    np.fill_diagonal(r, np.inf)
    if np.any(r < 2.0 * c):
        raise ValueError(f"fibrils of radius {c} µm overlap: roots closer than 2c = {2 * c} µm")
    C = (1.0 - nu * nu) / (np.pi * E * r)
    np.fill_diagonal(C, 16.0 * (1.0 - nu * nu) / (3.0 * np.pi**2 * E * c))
    return C


def effective_work_of_adhesion(areal_density: float, stiffness: float, release_force: float):
    """Elastic energy per area stored in the fibrils at release, W_eff = n·F_r²/(2k) [µN/µm =
    J/m²] (the code's strength metric, for its square and hexagonal n).

    Parameters
    ----------
    areal_density : n [1/µm²]. stiffness : fibril stiffness k [µN/µm]. release_force : F_r
    [µN].
    """
    return areal_density * release_force**2 / (2.0 * stiffness)


def saturation_pull_off_continuum(probe_radius, areal_density, stiffness, release_force):
    """Saturated pull-off [µN] of a rigid sphere on a continuum of independent fibrils on a
    rigid backing: π·n·R_p·F_r²/k = 2πR_p·W_eff.

    Derived here: on pulling, with fibrils attached out to radius a and the outermost at F_r,
    the fibril at r carries the tension F_r − k(a² − r²)/(2R_p), so the probe feels
    F(a) = nπa²F_r − nπka⁴/(4R_p), largest at a² = 2R_pF_r/k (the code's starting contact
    radius) where it is πnR_pF_r²/k; a preload reaching that radius, itself πnR_pF_r²/k,
    saturates it. The discrete lattice tends to it as the contact holds many fibrils.

    Parameters
    ----------
    probe_radius : R_p [µm]. areal_density : n [1/µm²]. stiffness : k [µN/µm].
    release_force : F_r [µN].
    """
    return np.pi * areal_density * probe_radius * release_force**2 / stiffness


@dataclass(frozen=True)
class ProbeTest:
    """Result of :func:`probe_test`.

    Attributes
    ----------
    pull_off : largest tension on the probe [µN] (0 if none).
    depth_max : depth at the preload [µm].
    attached_max : fibrils attached at the preload.
    depth, force, attached : the path through its events: depth d [µm], force on the probe
        [µN, compression positive], fibrils attached; pressing then pulling.
    """

    pull_off: float
    depth_max: float
    attached_max: int
    depth: np.ndarray
    force: np.ndarray
    attached: np.ndarray


def _check(heights, compliance, release_force, preload):
    h = np.asarray(heights, float)
    C = np.asarray(compliance, float)
    if h.ndim != 1 or h.size == 0 or not np.all(np.isfinite(h)):
        raise ValueError(f"heights must be a non-empty 1-D array of finite values, got {h!r}")
    if C.shape != (h.size, h.size) or not np.all(np.isfinite(C)):
        raise ValueError(f"compliance must be a finite {h.size}×{h.size} matrix, got {C.shape}")
    if not np.allclose(C, C.T, rtol=1e-12, atol=0.0) or np.any(np.diag(C) <= 0.0):
        raise ValueError("compliance must be symmetric with a positive diagonal")
    return h, C, _positive("release_force", release_force), _positive("preload", preload)


def _split(C, A, h):
    """f_A = a·d + b for the attached set A (C_AA·f_A = d + h_A)."""
    sol = np.linalg.solve(C[np.ix_(A, A)], np.column_stack([np.ones(A.size), h[A]]))
    return sol[:, 0], sol[:, 1]


def _press(h, C, preload, tol, path):
    """Press from first touch to ``preload``; returns (attached mask, depth)."""
    att = h >= h.max() - tol
    d = -float(h.max())
    while True:
        A = np.flatnonzero(att)
        a, b = _split(C, A, h)
        d_pre = (preload - b.sum()) / a.sum()  # Σa = 1ᵀC⁻¹1 > 0: the force grows with d
        free = np.flatnonzero(~att)
        if free.size:
            CfA = C[np.ix_(free, A)]
            slope, gap0 = 1.0 - CfA @ a, h[free] - CfA @ b  # gap to the probe: slope·d + gap0
            with np.errstate(divide="ignore", invalid="ignore"):
                roots = np.where(slope > 0.0, -gap0 / slope, np.inf)
        else:
            roots = np.array([np.inf])
        if d_pre <= roots.min():
            path.append((d_pre, preload, A.size))
            return att, d_pre
        d = max(d, float(roots.min()))
        path.append((d, float(a.sum() * d + b.sum()), A.size))
        touched = slope * d + gap0 >= -tol
        touched[np.argmin(roots)] = True
        att[free[touched]] = True


def _pull(h, C, att, d, release_force, path):
    """Pull until every fibril has let go; returns the largest tension [µN]."""
    best, ftol = 0.0, 1e-9 * release_force
    while att.any():
        A = np.flatnonzero(att)
        a, b = _split(C, A, h)
        f = a * d + b
        over = f < -release_force - ftol
        if over.any():  # an unstable state after a release: the next ones follow at once
            att[A[over]] = False
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            d_rel = np.where(a > 0.0, (-release_force - b) / a, -np.inf)
        d = min(d, float(d_rel.max()))
        force = float(a.sum() * d + b.sum())
        best = max(best, -force)
        path.append((d, force, A.size))
        going = a * d + b <= -release_force + ftol
        going[np.argmax(d_rel)] = True
        att[A[going]] = False
    path.append((d, 0.0, 0))
    return best


def probe_test(heights, compliance, release_force: float, preload: float) -> ProbeTest:
    """Press a rigid probe onto fibrils to ``preload`` and pull it off (module docstring).

    Parameters
    ----------
    heights : probe height h_i ≤ 0 over each fibril's tip [µm] (:func:`parabolic_heights`
        or :func:`gecko_agents.floor.probe.probe_heights`). compliance : N×N symmetric
        matrix [µm/µN] with w = C·f for the tips of attached fibrils: the fibrils'
        compliances on its diagonal plus the backing's (:func:`halfspace_compliance`; zero for
        a rigid backing). release_force : tension F_r at which a fibril lets go [µN], > 0.
        preload : compressive force the press reaches [µN], > 0.
    """
    h, C, F_r, P = _check(heights, compliance, release_force, preload)
    tol = 1e-12 * (np.ptp(h) + F_r * float(np.max(np.diag(C))))
    path: list[tuple[float, float, int]] = []
    att, d_max = _press(h, C, P, tol, path)
    n_max = int(att.sum())
    best = _pull(h, C, att, d_max, F_r, path)
    d, F, n = (np.array(v) for v in zip(*path, strict=True))
    return ProbeTest(best, d_max, n_max, d, F, n.astype(int))
