"""The corner's singularity (gecko_agents.physics.wedge) against Williams' closed-form
eigen-equations (Williams 1952, J Appl Mech 19:526), which the module does not use: it
integrates the wedge's state equations instead. Complex roots of the closed form are found
here by scipy's fsolve on (Re λ, Im λ), the module's by the secant method on its own
determinant. Each range is taken at its ends and refused
just outside them, naming the parameter."""

import cmath
import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from gecko_agents.physics.wedge import NOT_SINGULAR, corner_eigenvalue, singularity_exponent


def _smallest_root(f, lo=1e-3, hi=1.0 - 1e-9, n=2000):
    """The smallest sign change of f on (lo, hi), refined by Brent's method; None if none."""
    xs = [lo + (hi - lo) * i / n for i in range(n + 1)]
    for a, b in zip(xs, xs[1:], strict=False):
        if f(a) * f(b) < 0:
            return brentq(f, a, b, xtol=1e-15)
    return None


def _williams_clamped_free(x, alpha, nu):
    """Williams' clamped–free wedge of angle α in plane strain, over real or complex λ:
    (3 − 4ν)·sin²(λα) − 4(1 − ν)² + λ²·sin²α = 0."""
    return (3 - 4 * nu) * cmath.sin(x * alpha) ** 2 - 4 * (1 - nu) ** 2 + (x * math.sin(alpha)) ** 2


def _bonded(alpha, nu):
    """The smallest real root of Williams' clamped–free equation in (0, 1), or None."""
    return _smallest_root(lambda x: _williams_clamped_free(x, alpha, nu).real)


def _bonded_complex(alpha, nu):
    """Williams' clamped–free roots off the real axis with 0 < Re λ < 1 (Im λ > 0), from
    fsolve on (Re λ, Im λ) started over a grid of the strip; the one of smallest Re λ, or
    None."""

    def parts(v):
        z = _williams_clamped_free(complex(*v), alpha, nu)
        return [z.real, z.imag]

    roots = []
    for re in np.linspace(0.05, 0.95, 10):
        for im in (0.05, 0.2, 0.5):
            v, _, ok, _ = fsolve(parts, [re, im], full_output=True, xtol=1e-14)
            if ok == 1 and 0 < v[0] < 1 and abs(v[1]) > 1e-7:
                roots.append(complex(v[0], abs(v[1])))
    return min(roots, key=lambda z: z.real, default=None)


def _frictionless(alpha):
    """A floor that holds the face without shear is the plane of symmetry of a free wedge
    of angle 2α in its symmetric mode: sin(2λα) + λ·sin 2α = 0 (any ν)."""
    return _smallest_root(lambda x: math.sin(2 * x * alpha) + x * math.sin(2 * alpha))


@pytest.mark.parametrize(
    ("angle", "nu"), [(90.0, 0.5), (90.0, 0.3), (70.0, 0.5), (135.0, 0.3), (150.0, 0.5),
                      (70.0, 0.0), (90.0, 0.0)]
)  # fmt: skip
def test_bonded_corner_is_williams_clamped_free_wedge(angle, nu):
    """Where Williams' clamped–free equation has only real roots in (0, 1), the bonded
    floor's smallest root is its smallest, to 1e-10 (both by Brent's method to 1e-13;
    measured 6e-15), and where it has none (70° and 90° at ν = 0) the corner is not
    singular; the square incompressible corner is λ = 0.5946 (1 − λ² = sin²(λπ/2))."""
    alpha = math.radians(angle)
    assert _bonded_complex(alpha, nu) is None
    exact = _bonded(alpha, nu)
    got = singularity_exponent(angle, nu, "bonded")
    if exact is None:
        assert got == NOT_SINGULAR
    else:
        assert got == pytest.approx(exact, abs=1e-10)
        assert corner_eigenvalue(angle, nu, "bonded").imag == 0.0
    if (angle, nu) == (90.0, 0.5):
        assert exact == pytest.approx(0.5946, abs=1e-4)


@pytest.mark.parametrize(
    ("angle", "nu"), [(110.0, 0.0), (115.0, 0.05), (120.0, 0.0), (120.0, 0.1), (125.0, 0.15),
                      (130.0, 0.2), (135.0, 0.1), (135.0, 0.25), (150.0, 0.3)]
)  # fmt: skip
def test_obtuse_bonded_corner_of_a_compressible_tip_has_williams_complex_root(angle, nu):
    """Obtuse rims at low ν: Williams' clamped–free equation has no real root in (0, 1) but
    a complex pair λ = ξ ± iη; the module finds it, to 1e-9 in both parts (measured 7e-16),
    and its stress exponent is ξ − 1 (120°, ν = 0.1: λ = 0.8004 ± 0.1327i)."""
    alpha = math.radians(angle)
    assert _bonded(alpha, nu) is None
    exact = _bonded_complex(alpha, nu)
    got = corner_eigenvalue(angle, nu, "bonded")
    assert got.real == pytest.approx(exact.real, abs=1e-9)
    assert got.imag == pytest.approx(exact.imag, abs=1e-9)
    assert singularity_exponent(angle, nu, "bonded") == got.real < NOT_SINGULAR
    if (angle, nu) == (120.0, 0.1):
        assert (round(got.real, 4), round(got.imag, 4)) == (0.8004, 0.1327)


@pytest.mark.parametrize("angle", [1.0, 5.0, 10.0, 30.0, 45.0])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_thin_bonded_corners_have_no_root_real_or_complex(angle, nu):
    """Williams' clamped–free equation has no root, real or complex, with 0 < Re λ < 1 for
    rims up to 45°, and the module finds none (a thin wedge's determinant is nearly constant
    in λ: a secant step that stalls there is not a root)."""
    alpha = math.radians(angle)
    assert _bonded(alpha, nu) is None and _bonded_complex(alpha, nu) is None
    assert corner_eigenvalue(angle, nu, "bonded") == complex(NOT_SINGULAR)


@pytest.mark.parametrize("nu", [0.0, 0.1, 0.25, 0.3, 0.45])
def test_bonded_half_plane_is_the_crack_on_a_rigid_floor(nu):
    """A 180° corner bonded to a rigid floor is an interface crack between the body and a
    rigid solid: λ = ½ + i·ln(3 − 4ν)/(2π) (Williams 1959, Bull Seismol Soc Am 49:199:
    ε = ln((1 − β)/(1 + β))/(2π) with Dundurs' β = −(κ − 1)/(κ + 1) on a rigid floor,
    κ = 3 − 4ν), to 1e-9."""
    got = corner_eigenvalue(180.0, nu, "bonded")
    assert got.real == pytest.approx(0.5, abs=1e-9)
    assert got.imag == pytest.approx(math.log(3.0 - 4.0 * nu) / (2.0 * math.pi), abs=1e-9)


@pytest.mark.parametrize(("angle", "nu"), [(135.0, 0.3), (120.0, 0.0), (180.0, 0.5), (90.0, 0.3)])
def test_frictionless_corner_is_the_symmetric_mode_of_a_wedge_twice_as_wide(angle, nu):
    """On a floor without friction the root is the symmetric mode of a free wedge of twice
    the angle, whatever ν: 270° (a 135° rim) gives Williams' 0.5445, 360° (180°) the crack's
    ½; to 1e-10 (measured 1e-15); a 90° rim (a free half-plane) is not singular."""
    exact = _frictionless(math.radians(angle))
    got = singularity_exponent(angle, nu, "frictionless")
    if exact is None:
        assert got == NOT_SINGULAR
    else:
        assert got == pytest.approx(exact, abs=1e-10)
    if angle == 135.0:
        assert exact == pytest.approx(0.5445, abs=1e-4)


def test_ranges_are_taken_at_their_ends_and_refused_outside():
    """angle in (0, 180] (180 taken, its next float and 0 refused; a 1e-6° sliver is not
    singular); ν in [0, 0.5] (0 taken, just below 0 and above ½ refused: at 60° ν = 0 has
    no real root, ν = ½ has one); floor one of bonded and frictionless. Each error names the
    parameter and its value."""
    assert singularity_exponent(180.0, 0.0, "frictionless") == pytest.approx(0.5, abs=1e-10)
    assert singularity_exponent(1e-6, 0.5, "bonded") == NOT_SINGULAR
    assert singularity_exponent(60.0, 0.0, "bonded") == NOT_SINGULAR
    assert singularity_exponent(60.0, 0.5, "bonded") == pytest.approx(
        _bonded(math.radians(60.0), 0.5), abs=1e-10
    )
    for kw, name in (
        ({"angle_deg": math.nextafter(180.0, 200.0)}, "angle_deg = 180.00000000000003"),
        ({"angle_deg": 0.0}, "angle_deg = 0.0"),
        ({"angle_deg": 90.0, "nu": -1e-12}, "nu = -1e-12"),
        ({"angle_deg": 90.0, "nu": math.nextafter(0.5, 1.0)}, "nu = 0.5000000000000001"),
        ({"angle_deg": 90.0, "floor": "Bonded"}, "floor = 'Bonded'"),
    ):
        with pytest.raises(ValueError, match=f"^{name} "):
            singularity_exponent(**kw)
