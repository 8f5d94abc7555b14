"""The thin-film (spatula) tip peeling by Kendall's energy balance: :class:`SpatulaTip`."""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.contact.base import (
    K_ATTACH_FILM,
    K_ATTACH_RADIUS,
    ContactLaw,
    mindlin_stiffness,
)
from gecko_agents.physics import jkr
from gecko_agents.physics._util import register_jitables
from gecko_agents.physics.friction import friction_cap

__all__ = ["SpatulaTip"]

# Indices of SpatulaTip.constants (k), what the scalar functions read; k[K_ATTACH_RADIUS] and
# k[K_ATTACH_FILM] are the attached length ℓ0 and the free film's length s0 = h the kernels give
# a tip on attachment, as for every tangential law (:mod:`.base`).
K_R = 0  # tip radius R [µm]
K_B = 1  # film width b [µm]
K_H = 2  # film thickness h [µm]
K_EF = 3  # film modulus E_f [MPa]
K_W = 4  # work of adhesion w [µN/µm]
K_ELL0 = K_ATTACH_RADIUS  # attached length at first contact ℓ0 [µm]
K_FILM = 6  # film stiffness K = E_f·h·b [µN]
K_HERTZ_P = 7  # (4/3)E*√R [µN/µm^(3/2)]: the tip body's compression P_c = k·δ^(3/2)
K_HERTZ_U = 8  # (8/15)E*√R [µN/µm^(3/2)]: its energy k·δ^(5/2)
K_MU = 9  # friction coefficient μ [-]
K_PAPER = 10  # 1.0: the paper's friction cap μ·max(P, 0), 0.0: the adhesive μ|P + 2Fc|
K_FC = 11  # Kendall's 90° peel force w·b, the pad's Fc [µN]
K_BONDED = 13  # 1.0: spatula.interface = "bonded", 0.0: "sliding"
K_KT = 14  # the tip body's stick stiffness k_t [µN/µm]


try:  # the film's helpers are called from the compiled loop, so they are compiled too
    from numba import njit as _njit

    register_jitables()
except ImportError:  # pragma: no cover

    def _njit(**kwargs):
        return lambda f: f


@_njit(cache=True)
def _film_force(dx, zf, s0, K):
    """Tension F [µN] of the free film from the peel front to its end at horizontal offset dx
    and height zf [µm] (chord s = √(dx² + zf²)), unstretched length s0 [µm], K = E_f·h·b [µN]:
    F = K(s − s0)/s0 while taut, 0 while slack (a film carries no compression)."""
    s = math.sqrt(dx * dx + zf * zf)
    e = s - s0
    return (K * e / s0 if e > 0.0 else 0.0), s


@_njit(cache=True)
def _film_energy(dx, z, ell, p0, s0, k):
    """Energy the spatula contact stores [pJ], counted from attachment: free film
    ½K(s − s0)²/s0 + pre-strain of the attached film m·P0²/(2K) over its material length
    m = ℓ/(1 + ε0) = ℓK/(K + P0) (ℓ its floor length) + surface energy w·b·(ℓ0 − ℓ) of the
    floor it no longer covers + Hertz compression of the tip (8/15)E*√R·δ^(5/2)."""
    R, b, w, ell0, K, hz_u = k[K_R], k[K_B], k[K_W], k[K_ELL0], k[K_FILM], k[K_HERTZ_U]
    zf = z - R if z > R else 0.0
    s = math.sqrt(dx * dx + zf * zf)
    e = s - s0
    U = 0.5 * K * e * e / s0 if e > 0.0 else 0.0
    U += ell * p0 * p0 / (2.0 * (K + p0)) + w * b * (ell0 - ell)
    d = R - z
    if d > 0.0:
        U += hz_u * d * d * math.sqrt(d)
    return U


@_njit(cache=True)
def _release_rate(dx, zf, p0, s0, k):
    """Energy release rate per width g [µN/µm] of the peel front (−∂U/∂c per width, c the
    peeled floor length, the tip held): the front's advance dc hands the material
    dc/(1 + ε0) of the pre-strained pad (ε0 = P0/K) to the free film, so
    g·b = −F cos φ + (F + F²/2K + P0²/2K)/(1 + ε0), cos φ = −dx/s. P0 = 0 is Kendall's
    F(1 − cos φ) + F²/(2E_f·h·b) (Kendall 1975, J Phys D 8:1449, eq 4 per width); to second
    order in the strains it is Chen, Wu & Gao's F(1 − cos φ) + (F − P0)²/(2E_f·h·b) (2009,
    J R Soc Interface 6:529)."""
    b, K = k[K_B], k[K_FILM]
    F, s = _film_force(dx, zf, s0, K)
    cos_phi = -dx / s if s > 0.0 else 0.0
    return (-F * cos_phi + (F + (F * F + p0 * p0) / (2.0 * K)) / (1.0 + p0 / K)) / b


@_njit(cache=True)
def _hertz_compression(z, k):
    """Hertz compression P_c = (4/3)E*√R·δ^(3/2) [µN] of the tip body at height z [µm] of its
    centre above the floor, δ = R − z > 0 (Hertz 1882; Johnson, Contact Mechanics, 1985, eq
    4.22); 0 while the body does not touch."""
    d = k[K_R] - z
    return k[K_HERTZ_P] * d * math.sqrt(d) if d > 0.0 else 0.0


@_njit(cache=True)
def _friction_cap(z, ell, k):
    """Friction cap of the attached pad [µN]: the cap of an unloaded contact
    (:func:`gecko_agents.physics.friction.friction_cap` at P = 0) times the fraction ℓ/ℓ0 still
    attached: ``adhesive`` μ·2Fc·ℓ/ℓ0, the adhesion part of Thornton's μ|P + 2Fc| (Fc = w·b), or
    ``paper`` 0 (eq 27's μ·max(P, 0) with no load on the pad). The pad carries no normal load:
    the film's pull acts at the peel front (Kendall's picture) and the Hertz compression P_c on
    the tip body, whose own friction μ·P_c is ``_tip_stick``'s (counted once, there)."""
    return friction_cap(0.0, k[K_FC], k[K_MU], k[K_PAPER] > 0.0) * ell / k[K_ELL0]


@_njit(cache=True)
def _tip_stick(xi, cap, kt):
    """Coulomb stick/slip of the pressed tip body (return mapping, as the sphere's, kernels
    module docstring): trial stick offset ξ [µm] from its anchor on a spring k_t [µN/µm]
    (Mindlin 1949), cap μ·P_c [µN] (Amontons–Coulomb on the compressive Hertz load). Returns
    (ξ_new, tangential force −k_t·ξ_new on the tip [µN], Coulomb work cap·|ξ − ξ_new| of the
    slip [pJ], 1.0 if it slid while pressed else 0.0)."""
    if abs(xi * kt) > cap:
        xin = math.copysign(cap / kt, xi)
        return xin, -kt * xin, cap * abs(xi - xin), (1.0 if cap > 0.0 else 0.0)
    return xi, -kt * xi, 0.0, 0.0


@_njit(cache=True)
def _pull_on_front(dx, zf, s0, K):
    """Horizontal pull of the free film on the peel front [µN], > 0 away from the pad (the tip
    behind the front, dx < 0), < 0 towards it (the tip over its pad)."""
    F, s = _film_force(dx, zf, s0, K)
    return -F * dx / s if s > 0.0 else 0.0


@_njit(cache=True)
def _slide_excess(dx, hi, zf, s0, K, cap):
    """Energy [pJ] the free film releases as the whole pad slides ``hi`` [µm] towards the tip
    at the tip's offset dx and film height zf [µm] (unstretched length s0 [µm], K = E_f·h·b
    [µN]) beyond the slide's Coulomb work cap·hi (cap [µN], the pull it slides to).

    The slide is a return mapping, as the tip body's stick/slip (:func:`_tip_stick`): the
    step's trial (the tip moved, the pad held) stretches the film past the cap, the pad
    slides back to where the pull is the cap, and the force the step applies is the cap's.
    The work done on the film is the cap's, so the slide dissipates the Coulomb work cap·hi
    (as :func:`_tip_stick` books cap·|ξ − ξ_new|); the trial's overshoot, ½k·hi² for a
    film of horizontal stiffness k, was never put in by a force of the step: booked as
    dissipated, it over-counted the books by ½k·|Δx|/cap a step (1.0 % of a pushed pad's
    drag at 0.001 µm a step, 10 % at 0.01 µm: first order in the step, the model's balance
    off by 1.6 % of a 15 µm push at the explicit step, 12 % at the implicit one).

    Used for the pad pushed over itself, the bonded pad and the slide that ends a stretch
    (``_stretch``), not for a pad whose cap c·ℓ fell below its locked pre-tension P0 (the pad
    peeled shorter): its slide is no trial overshoot of the tip's step but a jump at a fixed
    tip, the pull falling from ≈ P0 to c·ℓ (a seta's gripping drag pulled off at 60°, μ = 10,
    tests/test_frictional_adhesion.py: the pad slid 1.14 µm in one step while the tip moved
    0.003 µm), whose release is dissipated as the slip runs; booked as the Coulomb work alone
    it left 0.31 pJ, 6.6 % of that run's energy scale, out of the books."""
    s_a = math.sqrt(dx * dx + zf * zf)
    d = dx - hi if dx > 0.0 else dx + hi
    s_b = math.sqrt(d * d + zf * zf)
    e_a = max(s_a - s0, 0.0)
    e_b = max(s_b - s0, 0.0)
    return 0.5 * K * (e_a * e_a - e_b * e_b) / s0 - cap * hi


@_njit(cache=True)
def _slide_to_cap(dx, zf, s0, K, cap):
    """Distance [µm] the whole pad slides towards the tip so that the film's horizontal pull
    equals the friction cap (bisection on the front's shift; 0 if the pull is below it)."""
    lo, hi = 0.0, abs(dx)
    sgn = 1.0 if dx > 0.0 else -1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if abs(_pull_on_front(dx - sgn * mid, zf, s0, K)) > cap:
            lo = mid
        else:
            hi = mid
    return hi


@_njit(cache=True)
def _stretched_pretension(ell, p0, K, v):
    """Pre-tension [µN] of a pad of floor length ℓ and pre-tension P0 stretched by v [µm],
    material m = ℓK/(K + P0) kept: K((ℓ + v)/m − 1) = P0 + (K + P0)·v/ℓ."""
    return p0 + (K + p0) * v / ell


@_njit(cache=True)
def _stretch_to_balance(dx, zf, ell, p0, s0, K, v_max):
    """Stretch v [µm] of the attached pad (material fixed, far end held) at which the free
    film's horizontal pull on the front equals the pad's tension there,
    H(dx + v) = P0 + (K + P0)·v/ℓ (bisection on [0, v_max])."""
    lo, hi = 0.0, v_max
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _pull_on_front(dx + mid, zf, s0, K) > _stretched_pretension(ell, p0, K, mid):
            lo = mid
        else:
            hi = mid
    return hi


@_njit(cache=True)
def _contract(ell, m, p_new, K):
    """Floor length [µm] the pad uncovers as it contracts from its front, its material m
    [µm] kept, to the pre-tension p_new [µN]: ℓ − m(1 + p_new/K)."""
    return ell - m * (1.0 + p_new / K)


@_njit(cache=True)
def _stretch(dx, zf, ell, p0, s0, K, c):
    """The pad pulled away from itself beyond its pre-tension (H > P0, dx < 0): it stretches
    (material kept, far end held) until H = P0 or P0 reaches the cap c·ℓ, then the whole pad
    slides towards the tip to where H = cap. Returns (stretch, slide [µm] towards the tip,
    ℓ, P0, slid) (``_slide``)."""
    rate = (K + p0) / ell - c  # d(P0 − cap)/dv
    v_cap = (c * ell - p0) / rate if rate > 0.0 else math.inf  # P0 reaches the cap
    if v_cap < -dx and _pull_on_front(dx + v_cap, zf, s0, K) >= c * (ell + v_cap):
        ell += v_cap
        p0 = c * ell
        hi = _slide_to_cap(dx + v_cap, zf, s0, K, p0)
        return v_cap, hi, ell, p0, (1.0 if hi > 0.0 else 0.0)
    v = _stretch_to_balance(dx, zf, ell, p0, s0, K, min(v_cap, -dx))
    return v, 0.0, ell + v, _stretched_pretension(ell, p0, K, v), 0.0


@_njit(cache=True)
def _stretch_booked(dx, zf, z, ell, p0, s0, k, c):
    """:func:`_stretch` of the pad pulled away from itself (tip offset dx, film height zf, tip
    height z [µm], cap c [µN] per µm of pad) with its books: (stretch + slide [µm] towards the
    tip, ℓ, P0, slid, excess [pJ]), excess the trial's release beyond what the stretch v
    dissipates, w·b·v (the floor it newly covers), and the slide its Coulomb work at the cap
    P0 = c·ℓ (:func:`_slide_excess`); 0 for a pad whose cap fell below its locked
    pre-tension (v < 0: a jump at a fixed tip, whose release is dissipated)."""
    u_a = _film_energy(dx, z, ell, p0, s0, k)
    v, hi, ell, p0, slid = _stretch(dx, zf, ell, p0, s0, k[K_FILM], c)
    excess = 0.0
    if v >= 0.0:
        excess = u_a - _film_energy(dx + v, z, ell, p0, s0, k) - k[K_W] * k[K_B] * v
        if hi > 0.0:
            excess += _slide_excess(dx + v, hi, zf, s0, k[K_FILM], p0)
    return v + hi, ell, p0, slid, excess


@_njit(cache=True)
def _slide(dx, zf, z, ell, p0, s0, k):
    """The attached pad under the free film's horizontal pull H: returns (dx, shift, ℓ, P0,
    slid, excess), excess [pJ] the trial's release beyond what a stretch or slide driven by
    the tip's step dissipates (w·b per length of floor the stretch newly covers, the Coulomb
    work of a slide at the cap, :func:`_slide_excess`; class docstring, "Stored energy").

    The pad is a length ℓ of floor [µm] covered by film material m = ℓ/(1 + ε0), uniformly
    pre-strained ε0 = P0/K (K = E_f·h·b); its friction cap is proportional to the floor it
    covers (:func:`_friction_cap`, c·ℓ).

    Partial slip (shear lag): a film held on the floor by friction, not bonded, carries the pull
    into its attached part, which stretches: the front is free to move and the attached film's
    tension at the front rises to H (Chen, Wu & Gao 2009, J R Soc Interface 6:529, their
    pre-tension P0 carried by the attached pad; Labonte & Federle 2016, J R Soc Interface
    13:20160373, and Gouravaraju, Sauer & Gautam 2021, J Adhes 97:952: sliding pre-stretches
    the pad, which then peels like an inextensible tape). Stretched uniformly (far end held),
    the front moving v towards the tip, the pad covers ℓ + v of floor with the same material:
    P0 = K((ℓ + v)/m − 1) = P0_old + (K + P0_old)·v/ℓ. v solves H(dx + v) = P0 (bisection)
    while P0 stays under the cap c(ℓ + v). Past the cap the whole pad slides towards the tip to
    where H = cap (Coulomb), with P0 = cap.

    Adhesion is per floor area (w, as in the peel): the floor the pad newly covers as it
    stretches gives up w·b·v, which is dissipated (the stretch is driven by the pull, not by
    the adhesion: an advancing edge keeps none of w), and a pad that contracts must pay w·b
    per length of floor it uncovers, as a peel would (Griffith 1921, Phil Trans R Soc A
    221:163: its front recedes only if the pre-strain energy released, P0 per length [µN],
    exceeds w·b). So friction and the front's
    adhesion lock the pre-tension when the pull falls (it is kept through the pull-off); a pad
    whose P0 exceeds c·ℓ + w·b (its cap fallen as it peeled shorter) contracts from its front
    to P0 = c·ℓ + w·b. Pushed over the pad past the cap, the pad slides towards +x; its
    friction spent, only the front's adhesion holds it: P0 relaxes to w·b.

    Energy: the film does work ∫H dv on the front, the attached film stores ∫P0 dv: a stretch
    dissipates ∫(H − P0) dv + w·b·v ≥ 0, of which the step books w·b·v (H = P0 at its end:
    ∫(H − P0) dv is the trial's overshoot, ``excess``); a contraction releases
    ∫P0 dv ≥ (c·ℓ + w·b)·v and pays w·b·v (:func:`_film_energy` at the tip's position).
    """
    K = k[K_FILM]
    c = _friction_cap(z, 1.0, k)  # the cap per floor length of pad [µN/µm] (it is ∝ ℓ)
    shift = 0.0
    slid = 0.0
    excess = 0.0
    if ell <= 0.0:
        return dx, shift, ell, p0, slid, excess
    m = ell * K / (K + p0)  # the pad's material (unstretched) length [µm]
    wb = k[K_W] * k[K_B]  # what the front's adhesion holds against a recession [µN]
    if p0 > c * ell + wb:  # friction and the front's adhesion can no longer hold P0
        p0 = (c * m + wb) / (1.0 - c * m / K)  # P0 = c·ℓ + w·b with ℓ = m(1 + P0/K)
        v = _contract(ell, m, p0, K)
        dx -= v
        shift += v
        ell -= v
    H = _pull_on_front(dx, zf, s0, K)
    if k[K_BONDED] > 0.0:  # bonded (Kendall): no stretch; the whole pad slides past the cap
        if abs(H) > c * ell:
            hi = _slide_to_cap(dx, zf, s0, K, c * ell)
            excess = _slide_excess(dx, hi, zf, s0, K, c * ell)
            shift = -hi if dx < 0.0 else hi
            dx -= shift
            slid = 1.0
        return dx, shift, ell, p0, slid, excess
    if H > p0:  # pulled away from the pad beyond the locked pre-tension: it stretches
        v, ell, p0, slid, excess = _stretch_booked(dx, zf, z, ell, p0, s0, k, c)
        dx += v
        shift -= v
    elif H < 0.0 and -H > c * ell:  # pushed over the pad past the cap: it slides
        hi = _slide_to_cap(dx, zf, s0, K, c * ell)
        excess = _slide_excess(dx, hi, zf, s0, K, c * ell)
        dx -= hi
        shift += hi
        slid = 1.0
        if p0 > wb:  # sliding, only the front's adhesion holds the pre-tension: it relaxes
            p0 = wb
            v = _contract(ell, m, p0, K)
            dx -= v
            shift += v
            ell -= v
    return dx, shift, ell, p0, slid, excess


class SpatulaTip(ContactLaw):
    """A thin elastic film (spatula) of width b, thickness h, modulus E_f that hangs from the
    tip centre and is attached to the floor over a length ℓ (a state variable), peeling by an
    energy balance (Kendall 1975, J Phys D 8:1449) with the pre-tension dragging puts into the
    attached film (Chen, Wu & Gao 2009, J R Soc Interface 6:529). Pad floors only.

    Geometry (x along the floor, positive where the setae lean): the attached pad extends from
    the peel front towards +x (the film continues the seta's lean); the free film runs from the
    front to the bottom of the tip body (height z_f = max(z − R, 0) above the floor, z the tip
    centre's), chord s = √(dx² + z_f²), unstretched length s0, tension F = E_f·h·b(s − s0)/s0
    while taut (0 while slack). The peel angle φ between the free film and the floor away from
    the pad is cos φ = −dx/s, dx = x_tip − x_front: a tip pulled back over −x peels at small φ,
    a tip pushed over its pad at φ > 90°. On attachment (δ ≥ 0) the front sits under the tip,
    ℓ = ℓ0, s0 = h (the film turns under the tip body within its thickness), no pre-tension,
    and so does the tip body's stick anchor (ξ = 0): the film (E_f·b = K/s0 once taut) and the
    body's stick spring k_t then hold the pressed tip tangentially.

    Every step, at the tip's position (a quasi-static front: the energy balance holds at the
    end of each step):

    1. **Slide** (``_slide``). The film pulls the front along the floor with H = F·|dx|/s
       against the pad's friction cap: adhesive μ·2Fc·ℓ/ℓ0 — friction acts on what is still
       attached, at zero and tensile load too (the adhesion part of Thornton's μ|P + 2Fc|,
       Fc = w·b: the film's pull acts at the front and the compression on the tip body, so the
       pad behind the front carries only its adhesion), an adhesion-controlled friction
       τ_eff·b·ℓ with τ_eff = 2μw/ℓ0 — or paper: none (eq 27's μ·max(P, 0), the pad carrying
       no load). With ``spatula.interface = "sliding"`` (default) a pull away from the pad
       stretches the attached film (partial slip) until its tension at the front, the
       pre-tension P0, balances H; friction keeps P0 when the pull falls. Past the cap the
       whole pad slides. ``"bonded"`` (Kendall's film): no stretch, P0 = 0, the pad slides as
       a whole past the cap.
    2. **Peel.** The front advances by dc of floor (ℓ −= dc, s0 += dc/(1 + ε0): the
       pre-strained attached film enters the free film) to where the energy release rate per
       width g = [−F cos φ + (F + F²/2K + P0²/2K)/(1 + ε0)]/b equals w; if it still exceeds w at
       ℓ = 0 the film has peeled off: the tip lets go. With P0 = 0 the balance is Kendall's
       (F/b)(1 − cos φ) + (F/b)²/(2E_f·h) = w (eq 4 per width); to second order in the strains
       it is Chen, Wu & Gao's G = P(1 − cos φ) + (P − P0)²/(2E_f·h) (per width).
    3. **Forces.** On the tip: −F·(dx, z)/s from the film plus the Hertz compression
       P_c = (4/3)E*√R·δ^(3/2) of the tip body while δ = R − z > 0 (pressing).
    4. **Tip friction** (``_tip_stick``). The pressed tip body holds tangentially by its
       own Coulomb friction, capped at μ·P_c (Amontons–Coulomb on the compressive part of the
       normal load, both friction laws), on a stick spring k_t = 8G*·a (Mindlin 1949, at the
       radius of :class:`~gecko_agents.contact.HertzSphere`'s reference) from its anchor
       (state ``xi``, relative to the front): the return mapping of the sphere's stick/slip.
       It acts beside the film's force, as the compression acts beside the film's pull. The
       friction of a spatula contact is thus split by where each load acts: the pad against
       its adhesion, the tip body against its compression; neither is counted twice (together
       they are the former single cap μ(P_c + 2Fc·ℓ/ℓ0)).

    Stored energy U = ½K(s − s0)²/s0 + mP0²/(2K) + w·b(ℓ0 − ℓ) + (8/15)E*√R·δ^(5/2) + ½k_t·ξ²
    [pJ] from attachment (K = E_f·h·b; ℓ the floor the pad covers, m = ℓ/(1 + ε0) its
    material). Each step is a return mapping, as the tip body's stick/slip: the trial (the
    tip moved, front and pad held) overshoots, the front and pad move back to balance at the
    tip's position, and the force the step applies is the balanced one; so a process driven
    by the tip's step dissipates its resistance times its displacement, not the trial's
    release U_before − U_after (the overshoot's energy, ½k·Δx² a step for a film of stiffness
    k, was never put in by a force of the step; booked, it is an error ∝ dt that is ten times
    the explicit step's at the implicit step's length). A stretch v dissipates w·b·v (the
    floor it newly covers; H = P0 at its end), a slide of the whole pad its Coulomb work
    cap·|slide| (``_slide_excess``), a peel that stops where g = w nothing beyond the surface
    energy w·b·dc that U keeps, the tip body's slip its Coulomb work μ·P_c·|Δξ| (as the
    sphere's). The trial's release is kept where the step is no overshoot of the tip's motion:
    a contraction (the pad's cap fallen as it peeled shorter), the slide of a pad whose cap
    fell below its locked pre-tension (a jump at a fixed tip, ``_slide_excess``) and the
    last peel (ℓ → 0); a release dissipates what is left. A spatula seta pressed to 1 µN,
    dragged 0.5 µm and pulled at 90° with the paper's friction law (its pad slides freely, cap
    0): energy-balance error 0.57 % → 0.08 % of the run's energy scale at the explicit step,
    4.75 % → 0.19 % at the implicit step's default (ten explicit steps); the forces are
    unchanged.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], E* [MPa], w [µN/µm]).
    spatula : :class:`gecko_agents.params.Spatula` (b, h, length [µm], E_f [MPa]).
    friction : :class:`gecko_agents.params.Friction` (μ, law).
    """

    name = "spatula"
    tangential = True
    film = True
    max_tension = math.inf  # a film at a small peel angle holds many w·b
    # As the last of a stretched pad peels, the film's force falls by 4–17 % a step while the
    # tip springs back fast: the explicit step's work on the tip, F·Δx with F from the step's
    # start, is off by ½ΔF·Δx a step, a first-order error of up to 2.1 % of the run's energy
    # at the default step that halves with dt (test_spatula).
    energy_tolerance_factor = 2.0

    def __init__(self, contact, spatula, friction):
        R, w, E = contact.jkr_args()
        b, h, E_f, ell0 = spatula.b, spatula.h, spatula.E_f, spatula.length
        self.R, self.w, self.E_star = R, w, E
        self.b, self.h, self.E_f, self.ell0 = b, h, E_f, ell0
        self.K = E_f * h * b
        # Fc: the 90° peel force of an inextensible film, w·b (Kendall 1975).
        self.pull_off_force = w * b
        self.attach_overlap = 0.0
        # Backstop: a tip 3(ℓ0 + R) above the floor has stretched its film far past Kendall.
        self.detach_overlap = -3.0 * (ell0 + R)
        self.jump_radius = ell0
        self.a0 = ell0
        # The tip body's stick spring: Mindlin's at the radius a Hertz contact of these
        # materials has under the JKR pull-off force, as HertzSphere's (a Hertz contact has no
        # zero-load radius). It sets how far the pressed body creeps before it slides
        # (μ·P_c/k_t), not the force at which it slides.
        a_ref = float(jkr.hertz_contact_radius(jkr.pull_off_force(R, w), R, E))
        self.tip_stiffness = kt = mindlin_stiffness(contact, a_ref)
        # The film's stiffness on attachment, K/h = E_f·b, the stiffest it gets (s0 ≥ h), in
        # parallel with the tip body's stick spring: the stiffest tangential spring of a tip.
        self.s_attach = h
        self.tangential_stiffness = self.K / h + self.tip_stiffness
        self.zero_load_stiffness = self.K / h
        k = self.constants = np.zeros(K_KT + 1)
        k[K_R], k[K_B], k[K_H], k[K_EF], k[K_W], k[K_ELL0] = R, b, h, E_f, w, ell0
        k[K_FILM], k[K_FC], k[K_ATTACH_FILM], k[K_KT] = self.K, self.pull_off_force, h, kt
        k[K_HERTZ_P] = 4.0 * E * math.sqrt(R) / 3.0
        k[K_HERTZ_U] = 8.0 * E * math.sqrt(R) / 15.0
        k[K_MU], k[K_PAPER] = friction.mu, 1.0 if friction.law == "paper" else 0.0
        k[K_BONDED] = 1.0 if getattr(spatula, "interface", "sliding") == "bonded" else 0.0

    def stiffest(self, load: float) -> float:
        return 2 * self.E_star * float(jkr.hertz_contact_radius(load, self.R, self.E_star))

    def stiffness(self, a, delta):
        """Normal stiffness of the tip [µN/µm], an upper bound: the tip body's Hertz
        compression 2E*·√(Rδ) (Johnson 1985, eq 4.23 differentiated; 0 while δ ≤ 0) plus the
        film at its stiffest, E_f·b = K/h (a film hanging straight down from the tip)."""
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return 2.0 * self.E_star * np.sqrt(self.R * d) + self.K / self.h

    def jacobian(self, dx, delta, s0, xa, ell=None, p0=None):
        """Stiffness −∂F/∂x of the attached tips' contact force, the front held [µN/µm]:
        (kxx, kxy, kyy) arrays, the linearly implicit step's Jacobian
        (:mod:`gecko_agents.model.implicit`); ``dx`` the tips' offset from their front,
        ``delta`` their overlap R − z, ``s0`` the free film's unstretched length, ``xa`` the
        tip body's stick anchor relative to the front [µm], as the step left them.

        The derivative of step 3's forces (class docstring) at the tip's position: the free
        film's tension F = K(s − s0)/s0 along its chord e = (dx, z_f)/s gives
        (K/s0)·e eᵀ + (F/s)·(I − e eᵀ) while taut, 0 while slack (a bar's material stiffness
        EA/l along it plus its geometric stiffness F/l across it, as in the Oasys GSA theory
        manual, "Bar and rod elements"), its y row and column 0 while the tip is pressed
        (z_f = max(z − R, 0) fixed there); the Hertz compression adds 2E*·√(Rδ) to kyy
        (Johnson 1985, eq 4.23 differentiated) and the pressed body's stick spring k_t to kxx
        while it sticks (k_t|ξ| below μ·P_c, ξ = dx − xa). The front's peel and the pad's slide
        lower the tangent further (a steady peel holds Kendall's force): the front held is an
        upper bound of the tangent, exact while the front stands. Not the bounds the implicit
        step took before, :meth:`stiffness` K/h + 2E*·√(Rδ) along n and
        ``tangential_stiffness`` K/h + k_t along t while the pad does not slide: in the
        implicit step a Jacobian K' above the tangent K adds a damper dt·(K' − K), and those
        held a seta pulled off at 0.005 µm/µs after a gripping drag (μ = 10, its pad slid in
        0.1 % of the pull's steps, at μ = 0.2 in 21 %) 4.5 % above the explicit step at ten
        explicit steps (0.46 % per explicit step of dt): 4.2 % with the tangential bound
        alone, 0.7 % with the normal one alone, 0.10 % with this Jacobian.

        With the pads' length ``ell`` [µm] and pre-tension ``p0`` [µN], a pad that slides
        (its film's horizontal pull H at its cap c·ℓ, pulled: at max(c·ℓ, P0); the paper's
        law: any pull, cap 0) drops the film's x row and column: the front follows the tip
        along the floor at that pull, ∂F/∂x = 0 (the sliding branch's tangent, as the tip
        body's stick spring drops out while it slides). Held there, the front made a damper
        dt·K/s0 along the floor that a sliding pad does not have: a seta at μ = 0.2 pushed
        8 µm over its pad and pulled at 60° released at 0.583 against the explicit step's
        0.593 µN (−1.7 %) at the default implicit step."""
        dx, d, s0, xa = (np.asarray(q, dtype=float) for q in (dx, delta, s0, xa))
        zf = np.maximum(-d, 0.0)  # z − R, z = R − δ the tip centre's height
        s = np.sqrt(dx * dx + zf * zf)
        taut = s > s0
        safe = np.where(s > 0.0, s, 1.0)
        ex, ey = dx / safe, zf / safe
        ka = np.where(taut, self.K / s0, 0.0)  # along the chord
        kg = np.where(taut, self.K * (s - s0) / (s0 * safe), 0.0)  # across it: F/s
        lifted = zf > 0.0
        kxx = ka * ex * ex + kg * ey * ey
        kxy = np.where(lifted, (ka - kg) * ex * ey, 0.0)
        k = self.constants
        if ell is not None:  # a sliding pad: the front follows the tip along the floor
            H = -np.where(taut, self.K * (s - s0) / s0, 0.0) * ex  # pull on the front [µN]
            cap = _friction_cap(0.0, np.asarray(ell, dtype=float), k)
            if k[K_BONDED] == 0.0:  # pulled, it slides at the pre-tension it locked, if above
                cap = np.where(H > 0.0, np.maximum(cap, p0), cap)
            sliding = taut & (np.abs(H) >= (1.0 - 1e-9) * cap)
            kxx = np.where(sliding, 0.0, kxx)
            kxy = np.where(sliding, 0.0, kxy)
        kyy = np.where(lifted, ka * ey * ey + kg * ex * ex, 0.0)
        dp = np.maximum(d, 0.0)
        kyy = kyy + 2.0 * self.E_star * np.sqrt(self.R * dp)
        cap = k[K_MU] * k[K_HERTZ_P] * dp * np.sqrt(dp)  # μ·P_c [µN]
        # A slid body sits at the cap (k_t|ξ| = μ·P_c to rounding): the margin tells it apart.
        stick = self.tip_stiffness * np.abs(dx - xa) < (1.0 - 1e-9) * cap
        return kxx + np.where(stick, self.tip_stiffness, 0.0), kxy, kyy

    def energy(self, a, delta):
        raise NotImplementedError("SpatulaTip stores its energy in the state (state.uc)")

    @staticmethod
    def step_scalar(dx, z, ell, p0, s0, xa, k):
        """One step of the film at the tip's offset dx = x_tip − x_front and height z = y_tip −
        floor [µm] from state (ℓ, P0, s0, xa), xa the tip body's stick anchor − x_front [µm]
        (the stick offset is ξ = dx − xa). Returns (P, T, shift, ℓ, P0, s0, xa, U,
        dissipation, slid): normal force P [µN] (> 0 compressive), tangential force on the tip
        T [µN] (along +x: the film's and the tip body's friction), front displacement along +x
        [µm], the new state, the stored energy U [pJ], the energy dissipated [pJ] and whether
        the pad or the pressed tip body slid (1.0) or not (0.0)."""
        R, K, mu, kt = k[K_R], k[K_FILM], k[K_MU], k[K_KT]
        zf = z - R if z > R else 0.0  # height of the film's end (the tip body's bottom)
        xi = dx - xa  # the tip body's trial stick offset
        U0 = _film_energy(dx, z, ell, p0, s0, k)
        # 1. Slide: pre-tension by partial slip, then the whole pad while the cap is exceeded.
        dx, shift, ell, p0, slid, excess = _slide(dx, zf, z, ell, p0, s0, k)
        # 2. Peel: advance the front until g = w; a film still above w at ℓ = 0 has let go.
        w = k[K_W]
        if ell > 0.0 and _release_rate(dx, zf, p0, s0, k) > w:
            grow = 1.0 / (1.0 + p0 / K)
            if _release_rate(dx - ell, zf, p0, s0 + ell * grow, k) > w:
                dc = ell
            else:
                lo, hi = 0.0, ell
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    if _release_rate(dx - mid, zf, p0, s0 + mid * grow, k) > w:
                        lo = mid
                    else:
                        hi = mid
                dc = hi
            u_a = _film_energy(dx, z, ell, p0, s0, k)
            dx -= dc
            shift += dc
            s0 += dc * grow
            ell -= dc
            if ell < 1e-9 * k[K_ELL0]:
                ell = 0.0
            else:  # the front stopped where g = w: it dissipates nothing beyond w·b·dc
                excess += u_a - _film_energy(dx, z, ell, p0, s0, k)
        # 3. The film's forces on the tip and the tip body's compression.
        F, s = _film_force(dx, zf, s0, K)
        Pc = _hertz_compression(z, k)
        P = Pc
        T = 0.0
        if s > 0.0:
            P -= F * zf / s
            T = -F * dx / s
        # 4. The pressed tip body's own friction, capped at μ·P_c (Amontons: no adhesion).
        xi, Tb, coulomb, body_slid = _tip_stick(xi, friction_cap(Pc, 0.0, mu, True), kt)
        T += Tb
        if body_slid > 0.0:
            slid = 1.0
        U = _film_energy(dx, z, ell, p0, s0, k)
        de = U0 - U + coulomb - excess
        U += 0.5 * kt * xi * xi
        return P, T, shift, ell, p0, s0, dx - xi, U, de, slid
