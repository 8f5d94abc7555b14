"""The corner's singularity (gecko_agents.physics.wedge) against Williams' closed-form
eigen-equations (Williams 1952, J Appl Mech 19:526), which the module does not use: it
integrates the wedge's state equations instead. Each range is taken at its ends and refused
just outside them, naming the parameter."""

import math

import pytest
from scipy.optimize import brentq

from gecko_agents.physics.wedge import NOT_SINGULAR, singularity_exponent


def _smallest_root(f, lo=1e-3, hi=1.0 - 1e-9, n=2000):
    """The smallest sign change of f on (lo, hi), refined by Brent's method; None if none."""
    xs = [lo + (hi - lo) * i / n for i in range(n + 1)]
    for a, b in zip(xs, xs[1:], strict=False):
        if f(a) * f(b) < 0:
            return brentq(f, a, b, xtol=1e-15)
    return None


def _bonded(alpha, nu):
    """Williams' clamped–free wedge of angle α in plane strain:
    (3 − 4ν)·sin²(λα) = 4(1 − ν)² − λ²·sin²α."""
    return _smallest_root(
        lambda x: (3 - 4 * nu) * math.sin(x * alpha) ** 2 - 4 * (1 - nu) ** 2
        + (x * math.sin(alpha)) ** 2
    )  # fmt: skip


def _frictionless(alpha):
    """A floor that holds the face without shear is the plane of symmetry of a free wedge
    of angle 2α in its symmetric mode: sin(2λα) + λ·sin 2α = 0 (any ν)."""
    return _smallest_root(lambda x: math.sin(2 * x * alpha) + x * math.sin(2 * alpha))


@pytest.mark.parametrize(
    ("angle", "nu"), [(90.0, 0.5), (90.0, 0.3), (70.0, 0.5), (135.0, 0.3), (150.0, 0.5),
                      (70.0, 0.0), (150.0, 0.3)]
)  # fmt: skip
def test_bonded_corner_is_williams_clamped_free_wedge(angle, nu):
    """The bonded floor's smallest root is that of Williams' clamped–free equation, to 1e-10
    (both roots by Brent's method to 1e-13; measured 6e-15), and where that equation has no
    real root in (0, 1) (70° at ν = 0, 150° at ν = 0.3) the corner is not singular; the
    square incompressible corner is λ = 0.5946 (1 − λ² = sin²(λπ/2))."""
    exact = _bonded(math.radians(angle), nu)
    got = singularity_exponent(angle, nu, "bonded")
    if exact is None:
        assert got == NOT_SINGULAR
    else:
        assert got == pytest.approx(exact, abs=1e-10)
    if (angle, nu) == (90.0, 0.5):
        assert exact == pytest.approx(0.5946, abs=1e-4)


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
