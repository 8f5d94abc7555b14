"""*Ours* for the literature comparison (:mod:`gecko_agents.studies.validation`): one function
per kind of row, each returning ``{"value": …, "text": …}`` (``values``: more than one number
drawn) computed from the presets of :mod:`gecko_agents.params.literature` or a study's own base
parameters with the package's closed forms and agent runs. A row names its function in the
data file (``ours``); the function's keyword arguments are the names of the row's ranged
parameters, so the study recomputes ours at both ends of each range.

Ratios are what the source compares (theirs over theirs), so a row's verdict reads the value's
side of 1 as the direction. Units: µm, µN, µs, MPa; stiffness µN/µm = N/m.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from gecko_agents import protocol
from gecko_agents.analysis.limit_curve import critical_angle
from gecko_agents.analysis.pull import plate_pull_off, pull_off, release_point
from gecko_agents.floor import Profile, from_profile
from gecko_agents.model import Model, Numerics
from gecko_agents.params import literature as lit
from gecko_agents.physics import beam, curved_rod, flaw_tolerance
from gecko_agents.studies import frictional_adhesion as fa
from gecko_agents.studies import gecko_seta, pad_peel
from gecko_agents.studies import misalignment as mis
from gecko_agents.studies import validation_magnitudes as magnitudes
from gecko_agents.studies.pad_scale import booth_pad_aligned, booth_pad_misaligned, kim_sitti_pad

# --- closed forms on a tokay seta (AUTUMN2006_SETA) ------------------------------------------
_SETA_KEYS = {"E": "contact.E1", "r": "seta.r", "L": "seta.L", "theta": "seta.theta_deg"}


def tokay_seta(**assumed):
    """:data:`~gecko_agents.params.literature.AUTUMN2006_SETA` with values overridden by
    row-parameter name (E [MPa], r [µm], L [µm], theta [deg]; ``turn`` is read by
    :func:`directional_stiffness`)."""
    over = {_SETA_KEYS[k]: v for k, v in assumed.items() if k in _SETA_KEYS}
    return lit.AUTUMN2006_SETA.replace(**over)


def directional_stiffness(params, direction, turn: float = 0.0) -> float:
    """Stiffness of a seta [µN/µm = N/m] along the unit vector of ``direction`` (x along the
    backing towards the lean, y up), the tip free to move across it: 1/(dᵀ C d) with C the
    tip compliance: the straight rod's K⁻¹ (:func:`gecko_agents.physics.beam.stiffness_matrix`,
    eq 16–21; d = (0, 1) is eq 20's K_y) or, where the shaft turns by ``turn`` [deg] from root
    to tip, the circular arc's (:func:`gecko_agents.physics.curved_rod.curved_rod_compliance`,
    the same chord angle θ and length L)."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    if turn == 0.0:
        K = beam.stiffness_matrix(
            params.axial_stiffness, params.bending_stiffness, params.seta.theta
        )
        return float(1.0 / (d @ np.linalg.solve(K, d)))
    r, L, E = params.seta.r, params.seta.L, params.contact.E1
    C = curved_rod.curved_rod_compliance(
        L, E * math.pi * r**4 / 4.0, E * math.pi * r**2, params.seta.theta, math.radians(turn)
    )
    return float(1.0 / (d @ C @ d))


ALONG, AGAINST, VERTICAL = (-1.0, -1.0), (1.0, -1.0), (0.0, 1.0)
"""Autumn et al.'s three loadings as directions of the backing's motion: +45° (down and towards
−x, the gripping drag), −45° (down and towards +x) and vertical."""


def seta_stiffness(quick: bool = True, turn: float = 0.0, **assumed) -> dict:
    """K_y [N/m] for the tokay seta (Autumn et al. 2006a's vertical loading): eq 20 for the
    straight rod, the arc's vertical stiffness where the shaft turns by ``turn`` [deg]."""
    p = tokay_seta(**assumed)
    k = p.Ky if turn == 0.0 else directional_stiffness(p, VERTICAL, turn)
    shape = "eq 20, K_y of a straight rod" if turn == 0.0 else f"an arc turning {turn:g}°"
    return {"value": k, "text": f"{k:.3g} N/m ({shape})"}


def seta_anisotropy(quick: bool = True, turn: float = 0.0, **assumed) -> dict:
    """Stiffness loaded against over along the natural drag path (−45° over +45°)."""
    p = tokay_seta(**assumed)
    along = directional_stiffness(p, ALONG, turn)
    against = directional_stiffness(p, AGAINST, turn)
    return {
        "value": against / along,
        "text": f"×{against / along:.3g} ({against:.3g} over {along:.3g} N/m)",
    }


def seta_vertical_along(quick: bool = True, turn: float = 0.0, **assumed) -> dict:
    """Stiffness loaded vertically over along the natural drag path (0° over +45°)."""
    p = tokay_seta(**assumed)
    vertical = directional_stiffness(p, VERTICAL, turn)
    along = directional_stiffness(p, ALONG, turn)
    return {
        "value": vertical / along,
        "text": f"×{vertical / along:.3g} ({vertical:.3g} over {along:.3g} N/m)",
    }


def array_modulus(
    quick: bool = True, D: float = lit.TOKAY_SETAL_DENSITY, turn: float = 0.0, **assumed
) -> dict:
    """E_eff = K_y·D·h [kPa]: a bed of springs of density D [1/µm²] and height h, the shaft's
    vertical reach (L sin θ straight; the arc's chord L·sinc(turn/2) sin θ)
    (σ = K_y·D·δ, ε = δ/h)."""
    p = tokay_seta(**assumed)
    k = seta_stiffness(quick, turn, **assumed)["value"]
    chord = p.seta.L * float(np.sinc(math.radians(turn) / (2.0 * math.pi)))
    e = k * D * chord * math.sin(p.seta.theta) * 1e3  # MPa → kPa
    return {"value": e, "text": f"{e:.3g} kPa"}


CLOSED_FORM = {
    "seta_stiffness",
    "seta_anisotropy",
    "seta_vertical_along",
    "array_modulus",
} | magnitudes.CLOSED_FORM
"""Rows whose ours is a closed form: their sensitivity is computed in ``--quick`` too, at every
corner of their ranged parameters together."""


# --- one seta: load, drag, pull ----------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def gripping_pull(params, beta: float, count: int = 1) -> tuple[float, float, float]:
    """The frictional-adhesion study's load–drag–pull (preload ``count`` × fa.PRELOAD, the
    gripping drag −fa.DRAG, pull at ``beta`` [deg] at the quasi-static plate speed): (adhesion,
    shear) at the release point and the pull-off [µN] (:mod:`gecko_agents.analysis.pull`).
    Cached: the runs are deterministic, and two rows share the spatula's 90° pull."""
    prot = protocol.drag_pull(fa.PRELOAD * count, -fa.DRAG, beta, speed=fa.SPEED)
    h = Model(params, seed=1, numerics=Numerics(record_every=1)).run(prot, progress=False)
    rel = release_point(h, -fa.DRAG)
    return rel.adhesion, rel.shear, pull_off(h, -fa.DRAG).adhesion


def frictional_adhesion(quick: bool = True, mu: float | None = None) -> dict:
    """The slope of adhesion on shear at the spatula seta's gripping releases over pull
    angles (> 0: adhesion rises with shear), and their critical angle α* [deg]."""
    p = (
        lit.FRICTIONAL_SPATULA
        if mu is None
        else lit.FRICTIONAL_SPATULA.replace(**{"friction.mu": mu})
    )
    betas = (45.0, 90.0) if quick else (15.0, 30.0, 45.0, 60.0, 75.0, 90.0)
    rel = [gripping_pull(p, b) for b in betas]
    shear = np.array([r[1] for r in rel])
    adhesion = np.array([r[0] for r in rel])
    alpha = critical_angle(shear, adhesion)
    slope = float(np.polyfit(shear, adhesion, 1)[0]) if len(set(shear)) > 1 else math.nan
    pts = ", ".join(f"{s:.2f}/{a:.2f}" for s, a in zip(shear, adhesion, strict=True))
    return {
        "value": slope,
        "text": f"slope {slope:.2f}, α* = {alpha:.0f}°; adhesion/shear at release over pulls "
        f"at {', '.join(f'{b:g}' for b in betas)}°: {pts} µN",
    }


def ptfe_friction(quick: bool = True, mu: float | None = None) -> dict:
    """μ_eff along over against the natural drag path of a seta without adhesion: pressed to
    fa.PRELOAD, dragged fa.DRAG each way; μ_eff = mean |shear| over mean load on the drag's
    second half (the tip sliding)."""
    p = lit.FRICTIONAL_SPHERE.replace(**{"tip": "hertz", "friction.mu": 0.2 if mu is None else mu})
    mus = []
    for dx in (-fa.DRAG, fa.DRAG):  # along (the gripping drag, −x), then against
        prot = [protocol.Press(fa.PRELOAD, fa.SPEED), protocol.Move(dx=dx, speed=fa.SPEED)]
        h = Model(p, seed=1, numerics=Numerics(record_every=1)).run(prot, progress=False)
        x = h["plate_x_um"]
        late = np.abs(x - x[0]) >= 0.5 * fa.DRAG
        mus.append(
            float(np.abs(h["force_tangential_uN"][late]).mean() / h["force_normal_uN"][late].mean())
        )
    along, against = mus
    return {
        "value": along / against,
        "text": f"×{along / against:.3f} (μ_eff {along:.3f} along over {against:.3f})",
    }


def gillies_smooth(quick: bool = True, b: float = 8.0) -> dict:
    """90° pull-off after the gripping drag: spatula film of width ``b`` [µm] over sphere, one
    seta, flat floor."""
    s = gripping_pull(lit.FRICTIONAL_SPATULA.replace(**{"spatula.b": b}), 90.0)[2]
    j = gripping_pull(lit.FRICTIONAL_SPHERE, 90.0)[2]
    return {"value": s / j, "text": f"×{s / j:.2f} ({s:.2f} over {j:.2f} µN, b = {b:g} µm)"}


def gillies_rough(quick: bool = True, b: float = 8.0) -> dict:
    """As :func:`gillies_smooth` on a patch of setae, each on its own pad at a Gaussian height
    of RMS 1 µm (eq 28); pull-off per seta."""
    count = 4 if quick else 16
    rough = {"array.count": count, "floor.sigma": 1.0, "floor.correlation_length": 0.0}
    spatula = lit.FRICTIONAL_SPATULA.replace(**{"spatula.b": b})
    s, j = (
        gripping_pull(p.replace(**rough), 90.0, count)[2] / count
        for p in (spatula, lit.FRICTIONAL_SPHERE)
    )
    return {
        "value": s / j,
        "text": f"×{s / j:.2f} ({s:.2f} over {j:.2f} µN per seta, {count} setae, b = {b:g} µm)",
    }


# --- pads on a strip --------------------------------------------------------------------------
@functools.lru_cache(maxsize=2)
def peel_rows(quick: bool) -> tuple[dict, dict]:
    """The pad_peel study's steady peels at 30° and 90° (:func:`pad_peel.run_point`; quick: 200
    setae at 0.5 µm/µs over 40 % of the pad, full: 240 at 0.2 µm/µs over all of it). Cached:
    two rows read them."""
    n, speed, frac = (200, 0.5, 0.4) if quick else (240, 0.2, 1.0)
    return tuple(pad_peel.run_point(n, psi, speed, frac)[0] for psi in (30.0, 90.0))


def kendall_peel(quick: bool = True) -> dict:
    """Peel force per width at 30° and 90° on the pad_peel study's pad over Kendall's
    w_eff/(1 − cos ψ) with the run's own w_eff (:func:`pad_peel.steady_peel`); the value is the
    ratio farther from 1."""
    rows = peel_rows(quick)
    f30, f90 = (r["F_per_width_uN_per_um"] for r in rows)
    ratios = [r["ratio_to_kendall"] for r in rows]
    worst = max(ratios, key=lambda x: abs(math.log(x)))
    return {
        "value": worst,
        "values": ratios,
        "text": f"F/b = {f30:.3g} µN/µm at {rows[0]['psi_measured_deg']:.0f}°, {f90:.3g} at "
        f"{rows[1]['psi_measured_deg']:.0f}°; over Kendall with the run's w_eff: "
        f"{ratios[0]:.2f} and {ratios[1]:.2f} ({rows[0]['n']} setae)",
    }


def kendall_angle_law(quick: bool = True) -> dict:
    """The peel force's angle dependence against Kendall's law: F(ψ₁)/F(ψ₂) over
    (1 − cos ψ₂)/(1 − cos ψ₁) at the measured angles of :func:`peel_rows` (w drops out)."""
    low, high = peel_rows(quick)
    ours = low["F_per_width_uN_per_um"] / high["F_per_width_uN_per_um"]
    psi1, psi2 = (math.radians(r["psi_measured_deg"]) for r in (low, high))
    law = (1.0 - math.cos(psi2)) / (1.0 - math.cos(psi1))
    return {
        "value": ours / law,
        "text": f"×{ours / law:.3f} (F ratio {ours:.3g} over Kendall's "
        f"{law:.3g} at {math.degrees(psi1):.0f}° and {math.degrees(psi2):.0f}°)",
    }


def pad_pull_off(params, n: int, angle: float, preload: float = mis.PRELOAD) -> float:
    """Pull-off / (N·Fc) of ``n`` setae on the elastic strip of ``params`` tilted by ``angle``
    [deg]: pressed to ``preload`` × N·Fc, pulled straight up (the misalignment study's)."""
    p = params.replace(**{"array.count": n, "backing.misalignment_deg": angle})
    m = Model(p, seed=1)
    h = m.run(protocol.preload_pull(preload * n * m.Fc, speed=mis.SPEED), progress=False)
    return float(max(h["strip_setae_force_y_uN"]) / (n * m.Fc))


def _booth_mounts(k_stiff: float | None):
    stiff, compliant = lit.BOOTH2018_STIFF_MOUNT, lit.BOOTH2018_COMPLIANT_MOUNT
    if k_stiff is not None:
        stiff = stiff.replace(**{"backing.handle_stiffness": k_stiff})
        compliant = stiff.replace(
            **{"backing.handle_stiffness": k_stiff / lit.BOOTH2018_COMPLIANCE_RATIO}
        )
    return stiff, compliant


def booth_misalignment(quick: bool = True, k_stiff: float | None = None) -> dict:
    """Pull-off on the 3.1× compliant mount over the stiff one at 0.4° (quick: 0.8° on half
    the pad, the same rise)."""
    n, angle = (200, 0.8) if quick else (400, 0.4)
    stiff, compliant = _booth_mounts(k_stiff)
    s, c = pad_pull_off(stiff, n, angle), pad_pull_off(compliant, n, angle)
    return {
        "value": c / s,
        "text": f"×{c / s:.3f} ({c:.3f} over {s:.3f} N·Fc, {n} setae at {angle:g}°)",
    }


def booth_aligned(quick: bool = True, k_stiff: float | None = None) -> dict:
    """Pull-off on the stiff mount over the 3.1× compliant one, aligned."""
    n = 200 if quick else 400
    stiff, compliant = _booth_mounts(k_stiff)
    s, c = pad_pull_off(stiff, n, 0.0), pad_pull_off(compliant, n, 0.0)
    return {"value": s / c, "text": f"×{s / c:.4f} ({s:.4f} over {c:.4f} N·Fc, {n} setae)"}


def _layer_pull_off(n: int, t: float) -> float:
    """Pull-off over N·F_r of an n×n field of the backing-layer study's pillars on a layer of
    thickness ``t`` [µm] (E = 1.413 MPa, the paper's polyurethane), pressed by a flat probe and
    pulled off (:func:`gecko_agents.studies.backing_layer.field_point`)."""
    from gecko_agents.studies import backing_layer as bl

    return bl.field_point(n, t, 1.413, "flat")[0]["pull_off_over_NFr"]


def kim_sitti_backing(quick: bool = True) -> dict:
    """Pull-off of a fibre field on a 160 µm layer over that on a 1120 µm one (the layer
    backing's field model, flat probe, aligned)."""
    n = 10 if quick else 50
    thin, thick = _layer_pull_off(n, 160.0), _layer_pull_off(n, 1120.0)
    return {
        "value": thin / thick,
        "text": f"×{thin / thick:.3f} ({thin:.3f} over {thick:.3f} N·F_r, {n}×{n} fibres)",
    }


def booth_layer_aligned(quick: bool = True, t: float = 100.0) -> dict:
    """Pull-off, aligned, on a layer of thickness ``t`` [µm] over that on one 3.1× as thick
    (3.1× as compliant: a thin layer's compliance ∝ t), the layer backing's field model."""
    n = 10 if quick else 50
    thin, thick = _layer_pull_off(n, t), _layer_pull_off(n, 3.1 * t)
    return {
        "value": thin / thick,
        "text": f"×{thin / thick:.4f} ({thin:.4f} over {thick:.4f} N·F_r, {n}×{n} fibres)",
    }


def kroner_flat_misalignment(quick: bool = True, n: float | None = None) -> dict:
    """Pull-off of Kroner et al.'s structures (:data:`~gecko_agents.params.literature.
    KRONER_PILLARS`) on a flat floor tilted 0.2° over aligned."""
    n = int(n) if n is not None else (100 if quick else 200)
    tilted = pad_pull_off(lit.KRONER_PILLARS, n, 0.2)
    aligned = pad_pull_off(lit.KRONER_PILLARS, n, 0.0)
    return {
        "value": tilted / aligned,
        "text": f"×{tilted / aligned:.3f} ({tilted:.3f} over {aligned:.3f} N·Fc, {n} pillars)",
    }


def kroner_flat_more_misaligned(quick: bool = True) -> dict:
    """Pull-off of the same structures on a floor tilted 0.4° over 0.2° (100 pillars)."""
    n = 100
    more = pad_pull_off(lit.KRONER_PILLARS, n, 0.4)
    less = pad_pull_off(lit.KRONER_PILLARS, n, 0.2)
    return {
        "value": more / less,
        "text": f"×{more / less:.3f} ({more:.3f} over {less:.3f} N·Fc, {n} pillars)",
    }


def kroner_flat_preload(quick: bool = True) -> dict:
    """Pull-off of the same structures, aligned, pressed to 0.4 over 0.1 N·Fc."""
    n = 100
    high = pad_pull_off(lit.KRONER_PILLARS, n, 0.0, preload=0.4)
    low = pad_pull_off(lit.KRONER_PILLARS, n, 0.0, preload=0.1)
    return {
        "value": high / low,
        "text": f"×{high / low:.4f} ({high:.4f} over {low:.4f} N·Fc, {n} pillars)",
    }


def kroner_sphere_preload(quick: bool = True) -> dict:
    """The spherical-probe study's row (5 flat-punch pillars under R_p = 30 µm, rigid backing):
    pull-off after a 1 µN preload over after 0.1 µN."""
    from gecko_agents.studies import probe_test

    low, high = (
        probe_test.run_point("flat punch, rigid backing", 5, 30.0, f)[0]["pull_off_uN"]
        for f in (0.1, 1.0)
    )
    return {"value": high / low, "text": f"×{high / low:.3f} ({high:.3f} over {low:.3f} µN)"}


# --- pillars: buckling and Kendall's punch ------------------------------------------------------
BELOW_BUCKLING = 0.5
"""The force preload below buckling, × the clamped–clamped Euler load."""


@functools.lru_cache(maxsize=8)
def buckled_ratio(aspect: float, past: float) -> tuple[float, list[float], list[float], float]:
    """Pull-off of one vertical flat-punch pillar of the pillar-design study (L/2r = ``aspect``)
    pressed under force control to :data:`BELOW_BUCKLING` and to ``past`` × its Euler load P_E:
    (past over below, pull-offs [µN], largest pressing forces [µN], P_E [µN]). A buckled
    elastica carries little more than its Euler load: above about 2 P_E (L/2r = 5) or 1.2 P_E
    (L/2r = 2.4) the model finds no equilibrium (the column is pressed flat)."""
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", aspect, "flat").replace(**{"array.count": 1})
    P_E = pd.euler_load("flat_punch", p.seta.L)
    held, peak = [], []
    for f in (BELOW_BUCKLING, past):
        h = Model(p, n_sim=1, seed=pd.SEED).run(
            protocol.preload_pull(f * P_E, speed=pd.SPEED), progress=False
        )
        held.append(h.peak_pull_off)
        peak.append(float(h["force_normal_uN"].max()))
    return held[1] / held[0], held, peak, P_E


def _buckled(aspect: float, past: float) -> dict:
    ratio, held, peak, P_E = buckled_ratio(aspect, past)
    return {
        "value": ratio,
        "text": f"×{ratio:.3f} ({held[1]:.2f} µN after a {peak[1]:.2f} µN "
        f"preload over {held[0]:.2f} µN after {peak[0]:.2f} µN; P_E = {P_E:.3g} µN, "
        f"L/2r = {aspect:g})",
    }


def buckled_preload(quick: bool = True) -> dict:
    """:func:`buckled_ratio` of the pillar-design study's L/2r = 5 pillar, pressed to 1.5 P_E."""
    return _buckled(5.0, 1.5)


TWO_HEIGHTS = {"n": 10, "step": 0.5, "low": 0.5, "high": 4.0, "speed": 0.02}
"""Yagüe Isla & Kroner's two pillar heights on the pillar-design study's pillars (L = 15 µm):
10 pillars, every other one 0.5 µm shorter; preloads 0.5 µN (below the 1.7 µN that brings the
short ones into contact) and 4 µN (all in contact, each below its Euler load); pressed and
pulled at 0.02 µm/µs (at the study's 0.05 the low-preload run's energy balance is off by 4.8 %
of its energy scale, past the 4 % the invariants allow)."""


def two_level_profile(n: int, pitch: float, L: float, step: float) -> Profile:
    """A floor of two levels under ``n`` vertical pillars ``pitch`` apart: 0 under the even
    pillars, −``step`` [µm] under the odd ones, as a pillar ``step`` shorter would stand
    above a flat floor (its own compliance, (L − step)/L of the others', aside). Laid out for
    the model's floor: from the first tip less the model's margin 50 µm + 3L
    (:class:`gecko_agents.model.world.World`; :func:`two_heights` checks the levels under the
    tips), sampled every 0.05 µm."""
    margin = 50.0 + 3.0 * L
    x = np.arange(0.0, 2.0 * margin + (n - 1) * pitch + 0.05, 0.05)
    k = np.rint((x - margin) / pitch)
    h = np.where(k % 2 == 1, -step, 0.0)
    return from_profile(x, h, detrend="none", spacing=0.05, source="two pillar heights")


@functools.lru_cache(maxsize=1)
def two_height_pull_offs() -> tuple[float, float]:
    """Pull-offs [µN] (the plate's vertical force) of pillars of two heights
    (:data:`TWO_HEIGHTS`) after the low and after the high preload."""
    from gecko_agents.studies import pillar_designs as pd

    c = TWO_HEIGHTS
    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": c["n"]})
    prof = two_level_profile(c["n"], p.array.pitch, p.seta.L, c["step"])
    held = []
    for preload in (c["low"], c["high"]):
        m = Model(p, n_sim=c["n"], seed=pd.SEED, floor_profile=prof)
        under = np.interp(m.world.rest_dx, m.world.profile.x, m.world.profile.y)
        want = np.where(np.arange(c["n"]) % 2 == 1, -c["step"], 0.0)
        if not np.allclose(under, want, atol=1e-9):
            raise RuntimeError(f"two_heights: floor levels {under} under the tips, not {want}")
        h = m.run(protocol.preload_pull(preload, speed=c["speed"]), progress=False)
        held.append(plate_pull_off(h))
    return held[0], held[1]


def two_heights(quick: bool = True) -> dict:
    """:func:`two_height_pull_offs`: after the high preload over after the low one."""
    low, high = two_height_pull_offs()
    c = TWO_HEIGHTS
    return {
        "value": high / low,
        "text": f"×{high / low:.3f} ({high:.2f} µN after "
        f"{c['high']:g} µN over {low:.2f} µN after {c['low']:g} µN)",
    }


def kendall_punch(quick: bool = True) -> dict:
    """Pull-off of one vertical flat-punch pillar (pillar-design study, L/2r = 5) pressed 5 %
    of L, over its tip law's closed form: Kendall's √(8πE*wa³) with the study's interface
    strength σ₀ as Maugis's Dugdale punch (:func:`gecko_agents.physics.flaw_tolerance.
    punch_pull_off`; Kendall's exactly at σ₀ = inf)."""
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": 1})
    h = Model(p, n_sim=1, seed=pd.SEED).run(
        protocol.press_pull(0.05 * p.seta.L, speed=pd.SPEED), progress=False
    )
    a, w, E_star = p.contact.jkr_args()
    F_c = float(flaw_tolerance.punch_pull_off(a, w, E_star, p.contact.sigma0))
    return {
        "value": h.peak_pull_off / F_c,
        "text": f"×{h.peak_pull_off / F_c:.4f} ({h.peak_pull_off:.3f} over {F_c:.3f} µN)",
    }


def pillar_strength(r: float, L: float) -> float:
    """Pull-off per area of backing [MPa] of one vertical flat-punch pillar of the pillar-design
    study's polyurethane, radius r [µm] (punch radius r, pitch 8r/3 as the study's 4 µm for
    1.5 µm) and length L [µm], pressed 5 % of L and pulled straight off."""
    from gecko_agents.studies import pillar_designs as pd

    pitch = 8.0 * r / 3.0
    p = pd.BASE.replace(
        **{
            "tip": "flat_punch",
            "seta.r": r,
            "contact.R": r,
            "seta.L": L,
            "array.count": 1,
            "array.pitch": pitch,
        }
    )
    h = Model(p, n_sim=1, seed=pd.SEED).run(
        protocol.press_pull(0.05 * L, speed=pd.SPEED), progress=False
    )
    return h.peak_pull_off / pitch**2


def greiner_radius(quick: bool = True) -> dict:
    """Pull-off per area of pillars of radius 2.5 µm over 25 µm, both L/2r = 1."""
    small, large = pillar_strength(2.5, 5.0), pillar_strength(25.0, 50.0)
    return {
        "value": small / large,
        "text": f"×{small / large:.3f} ({1e3 * small:.1f} over "
        f"{1e3 * large:.1f} kPa; Kendall's a^(−1/2) gives ×{math.sqrt(10):.3f})",
    }


def greiner_aspect(quick: bool = True) -> dict:
    """Pull-off per area of pillars of radius 2.5 µm, L/2r = 5 over L/2r = 1."""
    tall, short = pillar_strength(2.5, 25.0), pillar_strength(2.5, 5.0)
    return {
        "value": tall / short,
        "text": f"×{tall / short:.4f} ({1e3 * tall:.2f} over {1e3 * short:.2f} kPa)",
    }


def kroner_flat_misaligned_preload(quick: bool = True) -> dict:
    """Pull-off of Kroner et al.'s structures on a floor tilted 0.2°, pressed to 0.4 over
    0.1 N·Fc."""
    n = 100
    high = pad_pull_off(lit.KRONER_PILLARS, n, 0.2, preload=0.4)
    low = pad_pull_off(lit.KRONER_PILLARS, n, 0.2, preload=0.1)
    return {
        "value": high / low,
        "text": f"×{high / low:.3f} ({high:.3f} over {low:.3f} N·Fc, {n} pillars, 0.2°)",
    }


def kroner_sphere_over_flat(quick: bool = True) -> dict:
    """The spherical-probe study's 5 flat-punch pillars pressed to 1 µN: pull-off under the
    R_p = 30 µm probe over on a flat floor (the plate's vertical force both)."""
    from gecko_agents.studies import probe_test

    sphere = probe_test.run_point("flat punch, rigid backing", 5, 30.0, 1.0)[0]["pull_off_uN"]
    p = probe_test.PILLARS.replace(**{"array.count": 5, "floor.kind": "gaussian"})
    h = Model(p, n_sim=5, seed=probe_test.SEED).run(
        protocol.preload_pull(1.0, speed=probe_test.SPEED), progress=False
    )
    flat = plate_pull_off(h)
    return {
        "value": sphere / flat,
        "text": f"×{sphere / flat:.3f} ({sphere:.2f} over {flat:.2f} µN)",
    }


OURS = {
    f.__name__: f
    for f in (
        seta_stiffness,
        seta_anisotropy,
        seta_vertical_along,
        array_modulus,
        frictional_adhesion,
        ptfe_friction,
        gillies_smooth,
        gillies_rough,
        kendall_peel,
        kendall_angle_law,
        booth_misalignment,
        booth_aligned,
        booth_layer_aligned,
        kim_sitti_backing,
        kroner_flat_misalignment,
        kroner_flat_preload,
        kroner_sphere_preload,
        kroner_flat_misaligned_preload,
        kroner_flat_more_misaligned,
        kroner_sphere_over_flat,
        greiner_radius,
        greiner_aspect,
        buckled_preload,
        kendall_punch,
        two_heights,
        kim_sitti_pad,
        booth_pad_misaligned,
        booth_pad_aligned,
    )
} | magnitudes.OURS
"""The functions a row's ``ours`` may name (with the magnitude rows' of
:mod:`gecko_agents.studies.validation_magnitudes`)."""
OURS |= gecko_seta.OURS  # the gecko seta's rows ("gecko_*"): :mod:`.gecko_seta`
QUICK_SIZED = {
    "frictional_adhesion",
    "gillies_rough",
    "kendall_peel",
    "kendall_angle_law",
    "booth_misalignment",
    "booth_aligned",
    "booth_layer_aligned",
    "kim_sitti_backing",
    "kroner_flat_misalignment",
    "kim_sitti_pad",
    "booth_pad_misaligned",
    "booth_pad_aligned",
}
"""Rows whose ours runs smaller (fewer setae, fewer pulls, a shorter peel) in ``--quick``: their
quick verdict may differ from the full run's, and the report marks it."""
