"""The spatula's books of one step and its attachment, by independent routes (fast).

A step that stretches the pad to its cap and slides it (and may then peel it) is booked against
the film's force integrated along the path (scipy's quadrature) and against the dissipation
the law's class docstring states for each process; a tip lowered onto the floor attaches
where its body touches it, with the whole pad, as the film model places it."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from gecko_agents.contact import contact_law
from gecko_agents.contact.base import K_ATTACH_FILM, K_ATTACH_RADIUS
from gecko_agents.contact.spatula import _stretch_booked
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY

SPATULA = PAPER_ARRAY.replace(**{"tip": "spatula", "mechanics": "rod", "floor.sigma": 0.0})


def film_pull(x, zf, s0, K):
    """Horizontal pull [µN] of a taut film on its peel front, the tip at offset x < 0 behind
    the front and height zf above the floor [µm]: tension K(s − s0)/s0 (Hooke, K = E_f·h·b
    [µN], chord s = √(x² + zf²)) times its horizontal direction cosine |x|/s; 0 while slack."""
    s = math.hypot(x, zf)
    return K * (s - s0) / s0 * -x / s if s > s0 else 0.0


def stretch_and_slide(dx, zf, ell, p0, s0, K, c):
    """The stretch v and slide [µm] of a pad (floor length ℓ, pre-tension P0 [µN], cap c per
    µm of floor [µN/µm]) pulled by a taut film from a tip at dx < 0: its material m = ℓ/(1 +
    P0/K) kept, the pad covering ℓ + v carries K((ℓ + v)/m − 1), which meets the cap c(ℓ + v)
    at ℓ + v = K·m/(K − c·m); then the whole pad slides towards the tip until the pull is that
    cap (root of the pull by Brent's method). Returns (v, slide, P0(v) along the stretch)."""
    m = ell / (1.0 + p0 / K)
    v = K * m / (K - c * m) - ell
    cap = c * (ell + v)
    assert v > 0.0 and film_pull(dx + v, zf, s0, K) > cap  # it stretches to the cap, then slides
    slide = brentq(lambda u: film_pull(dx + v + u, zf, s0, K) - cap, 0.0, -(dx + v), xtol=1e-15)
    return v, slide, lambda u: K * ((ell + u) / m - 1.0)


@pytest.mark.parametrize(("p0", "zf"), [(0.0, 0.0), (0.0, 0.3), (0.05, 0.3), (0.05, 1.5)], ids=str)
def test_a_stretch_then_slide_books_both_overshoots_by_quadrature(p0, zf):
    """A pad pulled in one step far past its cap (the tip 1.6 µm behind its front, s0 = h)
    stretches until its pre-tension reaches the cap, then slides whole to where the film's
    pull is the cap. The step is a return mapping: what the trial released beyond what the
    stretch (w·b·v) and the slide (its Coulomb work) dissipate is the excess, the stretch's
    ∫(H − P0) dv plus the slide's ∫(H − cap) du (class docstring, "Stored energy"), both
    integrated here along the path with the film's pull H from Hooke's law: 0.25–0.37 pJ
    and 0.35–1.8 pJ, so neither part may drop out of the books."""
    law = contact_law(SPATULA)
    k, K, s0, ell = law.constants, law.K, law.h, law.ell0
    c = 0.2 * 2.0 * law.w * law.b / law.ell0  # μ·2w·b per ℓ0 of pad (μ = 0.2) [µN/µm]
    dx = -1.6
    v, slide, pretension = stretch_and_slide(dx, zf, ell, p0, s0, K, c)
    cap = c * (ell + v)
    stretch_excess = quad(lambda u: film_pull(dx + u, zf, s0, K) - pretension(u), 0.0, v)[0]
    slide_excess = quad(lambda u: film_pull(dx + v + u, zf, s0, K) - cap, 0.0, slide)[0]
    assert stretch_excess > 0.1 and slide_excess > 0.1  # both parts matter in the books

    shift, ell_new, p0_new, slid, excess = _stretch_booked(dx, zf, law.R + zf, ell, p0, s0, k, c)
    assert shift == pytest.approx(v + slide, rel=1e-12)
    assert ell_new == pytest.approx(ell + v, rel=1e-12)
    assert p0_new == pytest.approx(cap, rel=1e-12) and slid == 1.0
    assert excess == pytest.approx(stretch_excess + slide_excess, rel=1e-9)


@pytest.mark.parametrize(
    ("dx", "zf"), [(-1.6, 0.3), (-1.0, 1.5)], ids=["stretch-slide", "stretch-slide-peel"]
)
def test_a_step_that_stretches_slides_and_peels_dissipates_the_floor_and_coulomb_work(dx, zf):
    """One step of the law with the tip |dx| behind its front and zf above the floor (its body
    off the floor, no friction of its own): the pad stretches to its cap, slides whole and,
    at zf = 1.5 µm (a steep film, g > w after the slide), peels. By the class docstring's
    books the step dissipates w·b·v (the floor the stretch newly covers) plus the slide's
    Coulomb work cap·slide and nothing for a peel that stops where g = w: the stored
    energy's drop beyond that is the overshoots', which the step must not book as
    dissipated, whichever process follows the slide (v and the slide from the film's
    closed form and Brent's method, not from the law)."""
    law = contact_law(SPATULA)
    k, K, s0, ell = law.constants, law.K, law.h, law.ell0
    c = 0.2 * 2.0 * law.w * law.b / law.ell0  # the adhesive law's pad cap per µm (μ = 0.2)
    v, slide, _ = stretch_and_slide(dx, zf, ell, 0.0, s0, K, c)
    cap = c * (ell + v)
    P, T, shift, ell_new, p0_new, s0_new, xa, U, de, slid = law.step_scalar(
        dx, law.R + zf, ell, 0.0, s0, dx, k
    )
    peeled = ell + v - ell_new  # floor the front gave up after the slide [µm]
    assert slid == 1.0 and p0_new == pytest.approx(cap, rel=1e-12)
    assert shift == pytest.approx(peeled - v - slide, rel=1e-12, abs=1e-12)
    if zf > 1.0:
        assert peeled > 0.1  # it peeled a good part of the pad
        # The material peeled, dc/(1 + P0/K), joined the free film.
        assert s0_new == pytest.approx(s0 + peeled / (1.0 + cap / K), rel=1e-12)
    else:
        assert peeled == 0.0 and s0_new == s0
    assert de == pytest.approx(law.w * law.b * v + cap * slide, rel=1e-9)


@pytest.mark.parametrize(
    ("dx", "zf"), [(-1.6, 0.3), (-1.0, 1.5), (-0.5, 2.0)], ids=["slide", "peel", "steep peel"]
)
def test_the_forces_after_a_step_are_the_films_at_its_new_front(dx, zf):
    """After a step that slides and peels, the tip (its body off the floor) carries only the
    film's tension along the chord from its new front: Hooke's K(s − s0)/s0 over the chord
    s = √((dx − shift)² + zf²), the tip fixed and the front moved by the returned shift, with
    the returned free length s0."""
    law = contact_law(SPATULA)
    k, K, s0, ell = law.constants, law.K, law.h, law.ell0
    P, T, shift, _, _, s0_new, _, _, _, _ = law.step_scalar(dx, law.R + zf, ell, 0.0, s0, dx, k)
    x = dx - shift  # the tip's offset from the front where the step left it [µm]
    chord = math.hypot(x, zf)
    tension = K * (chord - s0_new) / s0_new if chord > s0_new else 0.0
    assert tension > 0.0
    # The same formula at the same numbers: measured within 9e-16 relative.
    assert T == pytest.approx(film_pull(x, zf, s0_new, K), rel=1e-12)
    assert P == pytest.approx(-tension * zf / chord, rel=1e-12)


def test_a_spatula_tip_attaches_where_its_body_touches_with_its_whole_pad():
    """The film hangs from the tip centre and turns under the body within its thickness
    (s0 = h): it reaches the floor when the body does, δ = R − z = 0, where the body's Hertz
    compression (4/3)E*√R·δ^(3/2) (Johnson 1985, eq 4.22) starts. So a tip attaches at
    δ = 0, with the whole pad (ℓ = ℓ0, the film's length on the floor, ``spatula.length``)
    and no force or stored energy (the books count from attachment); pressed ε further,
    it carries Hertz's force at ε."""
    law = contact_law(SPATULA)
    k = law.constants
    ell0 = SPATULA.spatula.length
    assert law.jump_radius == law.a0 == k[K_ATTACH_RADIUS] == ell0
    assert k[K_ATTACH_FILM] == law.s_attach == SPATULA.spatula.h
    d0 = law.attach_overlap
    P, T, shift, ell, p0, s0, xa, U, de, slid = law.step_scalar(
        0.0, law.R - d0, law.jump_radius, 0.0, law.s_attach, 0.0, k
    )
    assert (P, T, shift, ell, p0, s0, U) == (0.0, 0.0, 0.0, ell0, 0.0, law.s_attach, 0.0)
    for eps in (0.01, 0.1):
        P = law.step_scalar(0.0, law.R - d0 - eps, ell0, 0.0, law.s_attach, 0.0, k)[0]
        assert P == pytest.approx(4.0 / 3.0 * law.E_star * math.sqrt(law.R) * eps**1.5, rel=1e-12)


def test_a_spatula_tip_lowered_onto_the_floor_attaches_at_first_touch():
    """A seta lowered onto a flat floor (h = 0) by the numpy kernel, which reads the law's
    attachment overlap: its tip stays free while its body is above the floor (z > R) and
    attaches at the first step where it touches (z ≤ R, δ ≥ 0), with its whole pad ℓ0 and
    the free film at its thickness h; a free tip holds the pad's length ℓ0 from the start."""
    m = Model(SPATULA, n_sim=1, seed=7, numerics=Numerics(kernel="numpy"))
    R, ell0, h = SPATULA.contact.R, SPATULA.spatula.length, SPATULA.spatula.h
    assert m.state.a[0] == ell0
    heights, attached = [], []
    for _ in range(8):
        m.step((0.0, -0.05))
        heights.append(float(m.state.xy[1, 0]))  # the tip centre where the step's forces act
        attached.append(bool(m.attached[0]))
        if attached[-1]:
            assert m.state.a[0] == ell0 and m.state.s0[0] == h
    heights = np.array(heights)
    first = attached.index(True)
    assert first >= 2 and not any(attached[:first]) and all(attached[first:])
    assert np.all(heights[:first] > R) and heights[first] <= R
