"""Convergence of the linearly implicit step (:mod:`gecko_agents.model.implicit`) to the
explicit step for each tip law.

One seta of the paper's Table 1 on a flat floor, pressed and pulled at 0.02 µm/µs (four times
the default plate speed, so each run is seconds); the error of a run is the larger relative
error of its pull-off force and its release displacement
(:func:`gecko_agents.bench.pull_off_and_release`) against the explicit step at its default
dt. The implicit step is first order (backward Euler on a linear spring, Hairer & Wanner,
Solving Ordinary Differential Equations II, 2nd ed. 1996, §IV.7), so halving its dt should
halve that error.
"""

import math
import warnings

import pytest

from gecko_agents import protocol
from gecko_agents.bench import _wp_error, pull_off_and_release
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_TABLE1

SPEED = 0.02  # plate speed [µm/µs]
FACTORS = (20.0, 10.0, 5.0)  # implicit steps in explicit default steps
# The spatula runs at the same factors since its books are a return mapping (SpatulaTip):
# pull-off and release 0.70 %, 0.42 %, 0.22 % from the explicit step at 20, 10, 5 dt0, books
# 2.2 %, 1.3 %, 0.70 % (its tolerance 4 %; 2026-11-26). Before, its books carried an error ∝
# its plate travel per step (4.3 % at 10 dt0 at this speed) and it ran at four times shorter steps.
# The sphere's pull-off and release are located at the explicit step's length from 2 explicit
# steps up (ImplicitStep.substeps: a tip past its load-controlled pull-off), so its error
# there is that of the located step (0.024 %, 0.021 %, 0.009 % at 20, 10, 5 dt0 against the
# explicit step at dt0/4; 0.28 %, 0.11 %, 0.046 % before); the scheme's own order shows
# below dt0, against the explicit step at dt0/4 (no step is located there).
SPHERE_FACTORS = (1.0, 0.5, 0.25)

ROD = PAPER_TABLE1.replace(mechanics="rod")
LAWS = {
    "sphere": (ROD, protocol.press_pull(0.1, SPEED)),
    # Hertz has no adhesion: its error is the release's alone. The rod seta pressed 0.1 µm
    # slides off its tip at once, so the 60° linear seta pressed to 0.1 µN (the bench's case).
    "hertz": (
        PAPER_TABLE1.replace(**{"seta.theta_deg": 60.0, "tip": "hertz"}),
        protocol.preload_pull(0.1, SPEED),
    ),
    "spatula": (ROD.replace(tip="spatula"), protocol.press_pull(0.1, SPEED)),
    "crack kinetics": (
        ROD.replace(**{"contact.crack_speed": 1.0}),
        protocol.press_pull(0.1, SPEED),
    ),
}


def _measure(params, proto, **kw) -> dict:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warnings of the contact radius
        kw = {"integrator": "explicit"} | kw
        h = Model.from_options(params, n_sim=1, **kw, numerics=Numerics(record_every=1)).run(
            proto, progress=False
        )
    pull, release = pull_off_and_release(h)
    return {"pull_off": pull, "release": release}


# The sphere (four runs at and below the explicit step) and crack kinetics are the slow tier.
SLOW_LAWS = ("sphere", "crack kinetics")


@pytest.mark.parametrize(
    "law", [pytest.param(k, marks=pytest.mark.slow) if k in SLOW_LAWS else k for k in LAWS]
)
def test_pull_off_converges_at_first_order(law):
    """The implicit step's error falls with dt at an observed order ≥ 0.7 over 20 → 5
    explicit steps (first order: 1; measured 1.0 Hertz, 0.84 spatula, 0.74
    crack kinetics, whose pull-off is not yet in its asymptotic range at 20×: its order
    there rises from 0.5 at 40× to 0.9 at 2.5×; the sphere 1.41 over 1 → 0.25 against
    the explicit step at dt0/4, ``SPHERE_FACTORS``), each halving lowers it, and at the
    shortest step it is below 1 % (0.003 % sphere, 0.20 % Hertz, 0.22 % spatula, 0.26 %
    crack kinetics measured)."""
    params, proto = LAWS[law]
    factors = SPHERE_FACTORS if law == "sphere" else FACTORS
    dt0 = Model(params, n_sim=1, numerics=Numerics(integrator="explicit")).dt
    ref = _measure(params, proto, dt=dt0 / 4) if law == "sphere" else _measure(params, proto)
    errors = [_wp_error(_measure(params, proto, integrator="implicit", dt=f * dt0), ref)
              for f in factors]  # fmt: skip
    slopes = [math.log2(errors[i] / errors[i + 1]) for i in range(len(factors) - 1)]
    order = math.log(errors[0] / errors[-1]) / math.log(factors[0] / factors[-1])
    print(f"{law}: errors {errors} at {factors} × dt0, slopes {slopes}, order {order:.2f}")
    assert all(a > b for a, b in zip(errors, errors[1:], strict=False)), (errors, slopes)
    assert order >= 0.7, (errors, slopes, order)
    assert errors[-1] < 0.01, errors
