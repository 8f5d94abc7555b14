"""The linearly implicit step (:mod:`gecko_agents.model.implicit`) against the explicit one.

A single rod seta of the paper's Table 1 pressed 0.1 µm onto a flat floor and pulled off:
the pull-off force (the largest adhesion) and the release displacement (plate travel from the
deepest plate position to the snap-off) of the implicit step against the explicit step's.
"""

import hashlib
import math
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose
from test_model import SPEED, STUBBY, _curve_error, _dense

from gecko_agents import floor, protocol
from gecko_agents import quasistatic as qs
from gecko_agents.analysis.pull import pull_off
from gecko_agents.bench import pull_off_and_release
from gecko_agents.history import STATE_FREE, STATE_SLIP, energy_balance_error
from gecko_agents.model import Model, Numerics
from gecko_agents.model.implicit import implicit_time_step
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1
from gecko_agents.physics import beam

ROD = PAPER_TABLE1.replace(mechanics="rod")
SPATULA = PAPER_ARRAY.replace(**{"tip": "spatula", "mechanics": "rod", "floor.sigma": 0.0})
BONDED_SPATULA = SPATULA.replace(**{"spatula.interface": "bonded"})


def _pull(params, speed, **kw):
    """(pull-off force [µN], release displacement [µm], steps, history) of a press-pull."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(params, n_sim=1, **({"record_every": 1, "integrator": "explicit"} | kw))
        h = m.run(protocol.press_pull(0.1, speed), progress=False)
    assert len(h.detachments["plate_y_um"]) == 1, "the tip should let go once"
    return (*pull_off_and_release(h), h.meta["n_steps"], h)


def _hash(h) -> str:
    digest = hashlib.sha256()
    for k in sorted(h.columns):
        digest.update(np.ascontiguousarray(h[k]).tobytes())
    for k in sorted(h.detachments):
        digest.update(np.ascontiguousarray(h.detachments[k]).tobytes())
    return digest.hexdigest()


def test_auto_is_the_default_and_picks_the_verified_integrator():
    """The default ``"auto"`` runs the implicit step bit for bit on the rigid plate, and the
    explicit one where the implicit step is not verified (callback contact, the elastica); the
    spatula and the elastic backing run implicitly."""
    p = ROD.replace(**{"array.count": 3})
    runs = []
    for kw in ({"integrator": "auto"}, {"integrator": "implicit"}):
        h = Model(p, **kw).run(protocol.press_pull(0.05, 0.02), progress=False)
        runs.append((_hash(h), h.meta["integrator"]))
    assert runs[0] == runs[1] and runs[0][1] == "implicit"
    auto = {"integrator": "auto"}
    assert (
        Model.from_options(p, **auto, numerics=Numerics(contact="callback")).integrator
        == "explicit"
    )
    assert Model(p.replace(mechanics="elastica"), n_sim=1, **auto).integrator == "explicit"
    assert Model(p.replace(**{"backing.kind": "elastic"}), **auto).integrator == "implicit"
    assert Model(p.replace(tip="spatula"), **auto).integrator == "implicit"


def test_bad_integrator_and_dt_are_refused():
    with pytest.raises(ValueError, match="integrator = 'rk4'"):
        Model(ROD, n_sim=1, numerics=Numerics(integrator="rk4"))
    with pytest.raises(ValueError, match="needs contact = 'batch', got 'callback'"):
        Model(ROD, n_sim=1, numerics=Numerics(integrator="implicit", contact="callback"))
    with pytest.raises(ValueError, match="dt = -1"):
        Model(ROD, n_sim=1, numerics=Numerics(integrator="implicit", dt=-1.0))
    # No stability bound: a step 50 times the explicit one is accepted.
    dt0 = Model(ROD, n_sim=1, numerics=Numerics(integrator="explicit")).dt
    assert Model(ROD, n_sim=1, numerics=Numerics(integrator="implicit", dt=50 * dt0)).dt == 50 * dt0


@pytest.fixture(scope="module")
def explicit_reference():
    """The explicit step's pull-off and release at three plate speeds [µm/µs]."""
    return {v: _pull(ROD, v)[:3] for v in (0.0025, 0.005, 0.01)}


@pytest.mark.slow
@pytest.mark.parametrize("speed", [0.0025, 0.005, 0.01])
def test_pull_off_and_release_within_half_a_percent(explicit_reference, speed):
    """Event location at the default implicit step: the snap-off (its force and where it
    happens) within 0.5 % of the explicit step's, in a fifth of its steps or fewer (event
    location takes explicit-length steps at the touch-down and the snap-off: 7.5× fewer
    steps measured at 0.005 µm/µs, fewer at faster pulls, whose runs are shorter)."""
    f_ref, d_ref, n_ref = explicit_reference[speed]
    f, d, n, h = _pull(ROD, speed, integrator="implicit")
    assert abs(f - f_ref) <= 0.005 * f_ref, (f, f_ref)
    assert abs(d - d_ref) <= 0.005 * d_ref, (d, d_ref)
    print(f"{speed} µm/µs: {n_ref / n:.2f}× fewer steps")
    assert n <= n_ref / 5, (n, n_ref)
    assert h.meta["integrator"] == "implicit"


@pytest.mark.slow
def test_release_converges_at_first_order_as_dt_falls():
    """The implicit step's release displacement approaches a converged reference (the
    explicit step at dt0/4; at dt0/8 it moves by 0.00025 µm) as dt falls from dt0 to dt0/4,
    where no step is located (the scheme itself), at an observed order ≥ 0.7 (first order:
    1; 1.22 and 1.58 measured). Longer steps locate the release at dt0
    (:meth:`ImplicitStep.substeps`: a tip past its pull-off or reaching it within two
    steps), so at 10, 20 and 40 dt0 its error is at most the error at dt0 plus one step of
    dt0's plate travel, the resolution of a located release (0.0035, 0.0015, 0.0015 µm
    measured against 0.0035 µm; 0.013 µm at 40 dt0 while only the tip's speed located it)."""
    speed = 0.02
    dt0 = Model(ROD, n_sim=1, numerics=Numerics(integrator="explicit")).dt
    _, d_ref, _, _ = _pull(ROD, speed, dt=dt0 / 4)
    factors = (1.0, 0.5, 0.25)
    errors = [abs(_pull(ROD, speed, integrator="implicit", dt=f * dt0)[1] - d_ref) for f in factors]
    slopes = [math.log(errors[i] / errors[i + 1]) / math.log(2.0) for i in range(2)]
    overall = math.log(errors[0] / errors[-1]) / math.log(4.0)
    assert errors[0] > errors[1] > errors[2] and overall >= 0.7, (
        f"release errors {errors} µm at {factors} × dt0: slopes {slopes}, overall {overall}"
    )
    for f in (10.0, 20.0, 40.0):
        err = abs(_pull(ROD, speed, integrator="implicit", dt=f * dt0)[1] - d_ref)
        assert err <= errors[0] + speed * dt0, (f, err, errors[0])  # + one located step


def test_stiff_contact_runs_stably_at_the_default_step():
    """A contact 100 times stiffer (E₁ × 100) at its default implicit step, 10 times the
    explicit step its contact allows (3.75 × its stability bound 2/ω_max): no blow-up, the JKR
    pull-off (independent of E) within 1 %, the tip lets go once, the books close."""
    p = ROD.replace(**{"contact.E1": 100 * ROD.contact.E1})
    m = Model(p, n_sim=1, numerics=Numerics(integrator="implicit"))
    assert m.dt > 1.9 * 2.0 / m.omega_max
    # Recorded at the default interval: recorded every step, the snap-off's books show for
    # one step a swing of 3 % of the run's energy that the next step takes back.
    f, d, n, h = _pull(p, 0.005, integrator="implicit", record_every=None)
    fc = Model(p, n_sim=1, numerics=Numerics(integrator="explicit")).Fc
    assert abs(f - fc) <= 0.01 * fc, (f, fc)
    assert np.all(np.isfinite(h["energy_kinetic_pJ"]))


def test_energy_books_close_with_the_scheme_dissipation():
    """Between events, the implicit step's books close: plate work = elastic + kinetic +
    dissipated (the scheme's own dissipation booked), the run's balance within 5 % of its
    energy scale (events cost ∝ dt, module docstring) and within the explicit tolerance at
    a quarter of the default step."""
    f, d, n, h = _pull(ROD, 0.01, integrator="implicit")
    assert energy_balance_error(h) < 0.05
    assert h.meta["implicit_dissipated_pJ"] > 0.0
    dt = Model(ROD, n_sim=1, numerics=Numerics(integrator="implicit")).dt / 4
    assert energy_balance_error(_pull(ROD, 0.01, integrator="implicit", dt=dt)[3]) < 0.02


_RUN_FILE = """preset = "PAPER_TABLE1"
[params]
mechanics = "rod"
"seta.L" = 5.0
[model]
n_sim = 1
integrator = "{integrator}"
[protocol]
preset = "press_pull"
depth_um = 0.1
speed_um_per_us = 0.01
"""


def test_run_file_chooses_the_integrator(tmp_path, capsys):
    """A run file's ``[model] integrator`` reaches the model and its metadata; a value not
    in ``INTEGRATORS`` is refused when the file loads, naming the key, value and choices."""
    import json

    from gecko_agents import cli
    from gecko_agents.runfiles import run as runfile

    path = tmp_path / "implicit.toml"
    path.write_text(_RUN_FILE.format(integrator="implicit"))
    assert runfile.read_run_file(path).model["integrator"] == "implicit"
    out = tmp_path / "out"
    assert cli.main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    meta = json.loads((out / "metadata.json").read_text())
    assert meta["integrator"] == "implicit" and meta["implicit_dissipated_pJ"] > 0.0
    bad = tmp_path / "bad.toml"
    bad.write_text(_RUN_FILE.format(integrator="rk4"))
    with pytest.raises(runfile.RunFileError, match=r"\[model\] integrator.*rk4.*'implicit'"):
        runfile.read_run_file(bad)
    assert cli.main(["run", str(bad), "--out", str(tmp_path / "o2"), "--no-progress"]) == 2
    assert "integrator" in capsys.readouterr().err and not (tmp_path / "o2").exists()


def test_run_file_sets_the_step_near_events(tmp_path, capsys):
    """``[model] event_dt_us`` reaches the model (its event step at most that, recorded in
    ``meta["event_dt_us"]``); a negative one is refused when the file loads, and one the
    explicit step cannot take when the model is built, both naming the key."""
    import json

    from gecko_agents import cli
    from gecko_agents.runfiles import run as runfile

    text = _RUN_FILE.format(integrator="implicit") + ""
    path = tmp_path / "event.toml"
    path.write_text(text.replace("n_sim = 1\n", "n_sim = 1\nevent_dt_us = 0.2\n"))
    assert runfile.read_run_file(path).model["event_dt"] == 0.2
    out = tmp_path / "out"
    assert cli.main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    assert 0.0 < json.loads((out / "metadata.json").read_text())["event_dt_us"] <= 0.2
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("n_sim = 1\n", "n_sim = 1\nevent_dt_us = -1.0\n"))
    with pytest.raises(runfile.RunFileError, match=r"\[model\] event_dt_us.*-1.0.*> 0 µs"):
        runfile.read_run_file(bad)
    explicit = tmp_path / "explicit.toml"
    explicit.write_text(
        _RUN_FILE.format(integrator="explicit").replace(
            "n_sim = 1\n", "n_sim = 1\nevent_dt_us = 0.3\n"
        )
    )
    with pytest.raises(runfile.RunFileError, match=r"\[model\] event_dt_us.*explicit step"):
        runfile.read_run_file(explicit).build_model()


def test_a_change_of_step_is_booked_exactly(monkeypatch):
    """Steps alternating between dt and dt/5 all run long (event location's switch, here
    forced on every other step), dt the segment's step (``dt_base``: at 0.01 µm/µs the travel
    cap's 10 explicit steps, as :meth:`ImplicitStep.substeps` takes them): the books still
    close within the explicit tolerance (:data:`gecko_agents.history.ENERGY_RTOL`, 2 %;
    0.29 pJ of 23 pJ measured, 0.22 pJ at a constant step). Without the switch term,
    ½v·F'·(dt_prev − dt), they are off by 3.8 pJ (16 %)."""
    from gecko_agents.model.implicit import ImplicitStep

    calls = []

    def alternate(self, vp):
        calls.append(None)
        k = 5 if len(calls) % 2 else 1
        self.set_dt(self.dt_base / k)
        return k

    monkeypatch.setattr(ImplicitStep, "substeps", alternate)
    f, d, n, h = _pull(ROD, 0.01, integrator="implicit")
    assert energy_balance_error(h) <= 0.02
    assert h.meta["dt_us"] == Model(ROD, n_sim=1, numerics=Numerics(integrator="implicit")).dt


# A stubby rod seta (L = 5 µm) pressed and dragged at 0.1 µm/µs, as tests/test_model.py's
# explicit slide: under the implicit step it slides past its onset for ~60 steps.
_STUBBY = ROD.replace(**{"seta.L": 5.0})


def _drag(params, kernel, depth=0.3):
    """History of one stubby seta pressed to ``depth`` [µm] and dragged 8 µm along +x under
    the implicit step, recorded every step with its seta's columns."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a/R of the pressed tip is beyond the JKR range
        m = Model(
            params,
            record_setae=True,
            numerics=Numerics(kernel=kernel, integrator="implicit", record_every=1),
        )
        return m.run(
            [protocol.PressTo(depth, 0.05), protocol.Move(dx=8.0, speed=0.1)], progress=False
        )


@pytest.mark.parametrize("kernel", ["numpy", "python"])
def test_a_dragged_tip_slides_at_its_cap_and_books_the_coulomb_work(kernel):
    """Once it slides steadily the tip's friction is the Coulomb cap μ|P + 2Fc| (the adhesive
    cap, Thornton 1991) and the energy dissipated is the Coulomb work Σ cap·Δx, nothing more:
    the scheme's own dissipation (F' − F) is nil in a steady slide. Measured: 2.0e-4 of the
    Coulomb work on 58 steps (the explicit step's test in test_model.py, at a tenth of this
    step: 8e-7)."""
    h = _drag(_STUBBY, kernel)
    Fc = _STUBBY.contact.pull_off_force
    slide = np.flatnonzero(h.setae["state"][:, 0] == STATE_SLIP)
    k = slide[slide > slide[0] + 20]  # past the onset of sliding (20 steps, ~18 µs)
    assert k.size > 50 and np.all(np.diff(k) == 1), "the tip must slide steadily"
    x, P = h.setae["tip_x_um"][k, 0], h.setae["force_normal_uN"][k, 0]
    cap = _STUBBY.friction.mu * np.abs(P + 2 * Fc)
    # The return mapping sets the sliding friction to the cap: equal to rounding.
    np.testing.assert_allclose(-h.setae["force_tangential_uN"][k, 0], cap, rtol=1e-12)
    coulomb = np.sum(0.5 * (cap[1:] + cap[:-1]) * np.diff(x))
    dissipated = h["energy_dissipated_pJ"][k[-1]] - h["energy_dissipated_pJ"][k[0]]
    assert coulomb > 0.0
    # 0.2 % as the explicit test: P still settles by 1e-4 over the window (the trapezoid's
    # error) and the scheme books its F' − F as dissipated.
    assert dissipated == pytest.approx(coulomb, rel=2e-3)
    assert energy_balance_error(h) < 0.02  # the run's books, jump-in and slide onset included


def test_a_tip_in_tension_holds_no_shear_under_the_paper_cap():
    """Under the paper's cap μ·max(P, 0) (eq 27) a tip in tension holds no shear. On the step
    a tip jumps in (P = −8/9 Fc, its stick offset ξ = 0 under a cap of 0) the kernel's trial
    force is 0 and it marks the tip sticking, but the implicit step's stick spring and damper
    at the step's end would hold k_t·dt·v₁ + c_t·Δv: the tip slides instead, its friction 0
    (``ImplicitStep._stick_past_cap``). 20 stubby linear setae on the rough floor of
    tests/test_oracles_hand.py, recorded every step: without it, each seta's jump-in record
    (19 of them) sticks in tension holding up to 5.5e-5 µN."""
    p = PAPER_ARRAY.replace(
        **{"array.count": 20, "seta.L": 5.0, "floor.sigma": 0.3, "friction.law": "paper"}
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the linear seta leaves its small-deflection range
        m = Model(p, record_setae=True, numerics=Numerics(integrator="implicit", record_every=1))
        h = m.run(protocol.press_pull(0.5, speed=0.02), progress=False)
    P, state = h.setae["force_normal_uN"], h.setae["state"]
    tension = (state != STATE_FREE) & (P < 0.0)
    assert tension.sum() > 1000  # most records of the pull
    assert np.all(state[tension] == STATE_SLIP)
    assert np.all(h.setae["force_tangential_uN"][tension] == 0.0)


# A rough continuous floor of planar facets, one under each seta, at Gaussian heights and
# random slopes; the pitch leaves each tip on its facet while it slides (μ = 0: up to 13 µm
# along a facet at the pull-off's tension).
FACETS = STUBBY.replace(**{"array.count": 6, "array.pitch": 40.0, "friction.mu": 0.0})
FACET_HALF_WIDTH = 16.0  # [µm]


def _facet_floor(params, h, s):
    """A continuous floor whose line under seta i's resting tip abscissa X_i is y = h_i +
    s_i·(x − X_i) for |x − X_i| ≤ FACET_HALF_WIDTH (heights ``h`` [µm], slopes ``s`` [-]),
    straight joins between facets, sampled every 0.05 µm (a sampled line is the line)."""
    n, L = params.array.count, params.seta.L
    X = (np.arange(n) - (n - 1) / 2) * params.array.pitch
    X += beam.rest_tip_offset(L, params.seta.theta)[0]
    margin = 50.0 + 3 * L  # the model's floor margin (gecko_agents.model.world)
    w = FACET_HALF_WIDTH
    bx = np.concatenate(
        [[X[0] - margin], np.ravel(np.column_stack([X - w, X + w])), [X[-1] + margin]]
    )
    ends = np.ravel(np.column_stack([h - s * w, h + s * w]))
    by = np.concatenate([[ends[0]], ends, [ends[-1]]])
    dx = 0.05
    x = bx[0] + dx * np.arange(int(np.ceil((bx[-1] - bx[0]) / dx)) + 1)
    return floor.Profile(x=x, y=np.interp(x, bx, by), spacing=dx, source="facets")


def _facet_quasistatic(params, K, heights, slopes, plate_y):
    """Total quasi-static normal force [µN] of the setae on their facets along ``plate_y``.

    Frictionless (μ = 0), the contact force on seta i is P·n alone, n = (−sin α, cos α) the
    facet's normal (tan α = s_i), so its tip centre sits at p = p0 + P·K⁻¹n (K the linear
    seta's 2×2 stiffness, eq 20–21) and its overlap is δ = R − n·(p − q) = δ_g − P·nᵀK⁻¹n,
    δ_g = R − cos α·(Y + rest_dy − h_i) that of the resting tip at plate height Y. That is the
    quasi-static seta free to slide on a flat floor (eq 25, ``lateral="free"``: δ = h + R −
    p0_y − P/K_y) with K_y → k_eff = 1/(nᵀK⁻¹n) (``stiffness_scale``) at the plate height
    Y' = cos α·(Y + rest_dy − h_i) − rest_dy."""
    K = np.asarray(K)
    Kinv = np.linalg.inv(K)
    Ky = K[1, 1] - K[0, 1] * K[1, 0] / K[0, 0]  # eq 20: the free seta's normal stiffness
    rest_dy = beam.rest_tip_offset(params.seta.L, params.seta.theta)[1]
    total = np.zeros_like(plate_y)
    for h, s in zip(heights, slopes, strict=True):
        a = math.atan(s)
        n = np.array([-math.sin(a), math.cos(a)])
        k_eff = 1.0 / (n @ Kinv @ n)
        y = math.cos(a) * (plate_y + rest_dy - h) - rest_dy
        q = qs.solve(params, np.zeros(1), y, lateral="free", stiffness_scale=k_eff / Ky)
        total += q.force_normal
    return total


@pytest.mark.slow
@pytest.mark.parametrize("factor", [None, 20.0])
def test_rough_continuous_floor_matches_quasistatic_curve(factor):
    """A 6-seta press-pull on a continuous floor of sloped facets (the contact normals of
    :class:`ImplicitStep`'s continuous branch; 4 setae touch) with the implicit step at its
    default (10 explicit steps) and at 20 explicit steps follows the quasi-static curve of
    :func:`_facet_quasistatic`. Measured at the default step: pull-off +1.1 %, retraction
    0.13 µN (1.1 % of the pull-off), approach 0.22 µN (the explicit step: +1.0 %, 0.12,
    0.23 µN); the same oracle without the slopes (k_eff = K_y, cos α = 1) is 22 % off."""
    p = FACETS
    rng = np.random.default_rng(3)
    heights = rng.normal(0.0, p.floor.sigma, p.array.count)
    slopes = rng.uniform(-0.25, 0.25, p.array.count)
    prof = _facet_floor(p, heights, slopes)
    dt = (
        None
        if factor is None
        else factor * Model(p, floor_profile=prof, numerics=Numerics(integrator="explicit")).dt
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, floor_profile=prof, numerics=Numerics(integrator="implicit", dt=dt))
        h = m.run(protocol.press_pull(0.5, speed=SPEED), progress=False)
    assert not m.world.pads and m._implicit.normal is not None
    sub = 10
    y_dense = _dense(h["plate_y_um"], sub)
    q = _facet_quasistatic(p, m.K, heights, slopes, y_dense)
    pull_off = -q.min()
    # Pull-off within 2 %, as on the pad floor (tests/test_model.py): the dampers' force at
    # the 0.02 µm/µs pull (+1.0 % with the explicit step).
    assert_allclose(h.peak_pull_off, pull_off, rtol=0.02)
    err = _curve_error(h, q, y_dense, sub)
    turn = int(np.argmin(h["plate_y_um"]))
    # Retraction: within 2 % of the pull-off, the pad-floor test's bound (events may lag by
    # 0.1 µm of plate travel, _curve_error).
    assert err[turn:].max() < 0.02 * pull_off
    # Approach: below one jump-in's pull, (8/9)Fc < Fc, as in the pad-floor test.
    assert err[:turn].max() < p.contact.pull_off_force


@pytest.mark.parametrize(
    "slope",
    [pytest.param(-0.5, marks=pytest.mark.slow), 0.5, pytest.param(1.0, marks=pytest.mark.slow)],
)
def test_steep_facet_with_friction_matches_the_explicit_step(slope):
    """One seta on a facet of slope −0.5, 0.5 or 1 (45°) with friction (μ = 0.5: the tip
    sticks, so the normal and the stick stiffness enter the implicit Jacobian in the facet's
    frame): at its default step the implicit step pulls off within 0.5 % of the explicit
    step's force and lets go within 0.5 % of the pull's plate travel of where it does
    (measured: −0.02 %, −0.02 %, +0.18 %; 0.000 %, 0.11 %, 0.12 % of 14.3, 3.2, 4.5 µm;
    7.5–8.3× fewer steps)."""
    p = FACETS.replace(**{"array.count": 1, "friction.mu": 0.5})
    prof = _facet_floor(p, np.zeros(1), np.full(1, slope))
    runs = []
    for integrator in ("explicit", "implicit"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = Model(p, floor_profile=prof, numerics=Numerics(integrator=integrator))
            h = m.run(protocol.press_pull(0.5, speed=SPEED), progress=False)
        assert len(h.detachments["plate_y_um"]) == 1
        runs.append((h.peak_pull_off, h.detachments["plate_y_um"][0], h["plate_y_um"].min()))
    (f_ref, y_ref, deepest), (f, y, _) = runs
    # Half a percent, the bound for an event against the explicit reference.
    assert abs(f - f_ref) <= 0.005 * f_ref, (f, f_ref)
    assert abs(y - y_ref) <= 0.005 * (y_ref - deepest), (y, y_ref, deepest)


@pytest.mark.slow
def test_drag_over_a_rough_continuous_floor_matches_the_explicit_step():
    """Ten setae pressed to 3 µN on a self-affine floor (σ = 0.3 µm, cutoffs 2 and 20 µm,
    μ = 0: the tips slide over its slopes), dragged 10 µm and pulled off, recorded every
    step: at its default step the implicit step pulls off within 0.5 % of the explicit
    step's force (+0.12 % measured; +0.67 % while only the tips' speed located the escapes
    from their folds). The drag is mostly located (6 570 of 7 164 steps: the sliding tips
    run faster than twice the plate speed), 1.7× fewer steps than the explicit step's
    12 396."""
    p = STUBBY.replace(
        **{"array.count": 10, "friction.mu": 0.0, "floor.kind": "self_affine",
           "floor.sigma": 0.3, "floor.short_cutoff": 2.0, "floor.long_cutoff": 20.0}
    )  # fmt: skip
    pull = []
    for integrator in ("explicit", "implicit"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = Model(p, numerics=Numerics(integrator=integrator, record_every=1))
            h = m.run(protocol.drag_pull(3.0, 10.0, 90.0, speed=SPEED), progress=False)
        assert not m.world.pads and len(h.detachments["seta"]) == 10
        pull.append(h.peak_pull_off)
    # Half a percent, the bound for an event against the explicit reference.
    assert abs(pull[1] - pull[0]) <= 0.005 * pull[0], pull


@pytest.mark.slow
def test_gripping_dragged_spatula_pulls_off_as_the_explicit_step():
    """The spatula seta (μ = 10) pressed to 0.2 µN, dragged 8 µm and pulled off at 90° at
    0.005 µm/µs, recorded every step: at its default step (``implicit_time_step``: 19
    explicit steps within the travel cap) the implicit
    step pulls off within 0.5 % of the explicit step's force (+0.20 % measured with the
    film's own Jacobian, ``SpatulaTip.jacobian``, +0.11 % at ten explicit steps; +4.5 % at
    ten with the bounds K/h + k_t along the floor while the pad held and K/h + 2E*·√(Rδ)
    across it, a damper dt·(K' − K))."""
    p = SPATULA.replace(**{"friction.mu": 10.0})
    pull = []
    for integrator in ("explicit", "implicit"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # validity warning of the contact radius
            m = Model(p, n_sim=1, seed=7, numerics=Numerics(integrator=integrator, record_every=1))
            h = m.run(protocol.drag_pull(0.2, 8.0, 90.0, speed=0.005), progress=False)
        pull.append(pull_off(h).adhesion)
    assert m.dt == implicit_time_step(None, m.omega_max)  # the default step
    # Half a percent, the bound for an event against the explicit reference.
    assert abs(pull[1] - pull[0]) <= 0.005 * pull[0], pull


def _film_force_on_tip(law, k, dx, delta, s0, xa):
    """(T, P) [µN]: the spatula's force on the tip (``step_scalar``), its front held."""
    P, T, shift = law.step_scalar(dx, law.R - delta, law.ell0, 0.0, s0, xa, k)[:3]
    assert shift == 0.0  # the front held: neither peel nor slide
    return np.array([T, P])


@pytest.mark.parametrize(
    ("dx", "delta", "s0", "xa", "mu"),
    [
        (-0.5, -0.3, 0.57, 0.0, 10.0),  # lifted, the film taut at φ = 31°
        (0.4, -0.2, 0.44, 0.0, 10.0),  # lifted over its pad, taut at 153° (φ from the floor)
        (-1.2, 0.1, 1.0, -1.21, 10.0),  # pressed, the film taut along the floor, body sticks
        (0.3, 0.1, 1.0, 0.0, 0.0),  # pressed, the film slack, the body slides (no cap)
        (0.2, -0.1, 0.5, 0.0, 10.0),  # lifted, the film slack: no force, no stiffness
    ],
)
def test_spatula_jacobian_is_the_derivative_of_its_force(dx, delta, s0, xa, mu):
    """``SpatulaTip.jacobian`` is −∂(T, P)/∂(x, y) of the law's own force (``step_scalar``)
    by central differences, at states where the bonded front holds (μ = 10 keeps the pad,
    and the pressed body, from sliding; the release rate is below w: no peel)."""
    from gecko_agents.contact import contact_law

    law = contact_law(BONDED_SPATULA.replace(**{"friction.mu": mu}))
    k = law.constants
    kxx, kxy, kyy = (float(q[0]) for q in law.jacobian([dx], [delta], [s0], [xa]))
    e = 1e-6  # µm
    jx = (_film_force_on_tip(law, k, dx + e, delta, s0, xa)
          - _film_force_on_tip(law, k, dx - e, delta, s0, xa)) / (2 * e)  # fmt: skip
    jy = (_film_force_on_tip(law, k, dx, delta - e, s0, xa)
          - _film_force_on_tip(law, k, dx, delta + e, s0, xa)) / (2 * e)  # fmt: skip
    # Central differences: truncation ~e²·F''' (≪ 1e-6 µN/µm here) and rounding ~1e-16·F/e
    # (~1e-10): 1e-6 relative plus 1e-7 µN/µm absolute (for the zero entries).
    assert_allclose([[kxx, kxy], [kxy, kyy]], -np.column_stack([jx, jy]), rtol=1e-6, atol=1e-7)


@pytest.mark.slow
def test_spatula_books_close_at_the_default_step_with_the_papers_friction_law():
    """A spatula seta (Table 1, rod) pressed to 1 µN, dragged 0.5 µm and pulled at 90° with the
    paper's friction law, whose pad slides at no pull (cap μ·max(P, 0) = 0 on the pad): at
    the default implicit step (measured at ten explicit steps) its energy books close to
    0.19 % of the run's energy scale (explicit step 0.08 %). While the law booked each
    slide's trial release (the overshoot ½k·Δx² of the film's stiffness k = K/s0 over the
    tip's step Δx, which no force of the step put in, ∝ dt) they closed to 4.75 % (0.57 %
    explicit), past the spatula's 4 % (ENERGY_RTOL × its energy_tolerance_factor)."""
    p = PAPER_TABLE1.replace(**{"mechanics": "rod", "tip": "spatula", "friction.law": "paper"})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # validity warning of the contact radius
        m = Model(p, n_sim=1, numerics=Numerics(record_every=1))
        h = m.run(protocol.drag_pull(1.0, 0.5, 90.0, protocol.DEFAULT_SPEED), progress=False)
    assert m.integrator == "implicit" and m.dt == implicit_time_step(None, m.omega_max)
    # A quarter of ENERGY_RTOL: 2.5 times the 0.19 % measured, a tenth of the 4.75 % before.
    assert energy_balance_error(h) < 0.005


def test_sliding_pad_has_no_tangential_stiffness_in_the_jacobian():
    """A pad that slides (the paper's law: cap 0, so a taut film pulled away from its pad drags
    it along) holds no force against the tip's motion along the floor: its tangent ∂T/∂x is 0
    (central differences of ``step_scalar``, the front free), and so is the Jacobian's x row
    given the pad's length and pre-tension; the front held (no ``ell``), it is the film's."""
    from gecko_agents.contact import contact_law

    law = contact_law(BONDED_SPATULA.replace(**{"friction.law": "paper", "spatula.interface":
                                                 "sliding"}))  # fmt: skip
    k = law.constants
    dx, delta, s0 = -0.5, -0.3, 0.5  # lifted, the film taut at φ = 31°: it pulls the pad
    e = 1e-6  # µm
    T = [law.step_scalar(dx + q, law.R - delta, law.ell0, 0.0, s0, dx, k)[1] for q in (e, -e)]
    assert T[0] == T[1] == 0.0  # the pad slid until the film pulls no more along the floor
    kxx, kxy, _ = (float(q[0]) for q in law.jacobian([dx], [delta], [s0], [dx], [law.ell0], [0.0]))
    assert kxx == 0.0 and kxy == 0.0
    held = law.jacobian([dx], [delta], [s0], [dx])[0][0]
    assert held > 0.0  # the front held: the film's own K/s0 along its chord


@pytest.mark.slow
def test_sliding_pad_pulls_off_as_the_explicit_step():
    """A spatula seta at the paper's μ = 0.2 pushed 8 µm over its pad (it slides) and pulled
    at 60°: at the default implicit step its pull-off is 0.5938 against the explicit step's
    0.5933 µN (+0.08 %); with the front held in the Jacobian while the pad slid (a damper
    dt·K/s0 along the floor) it was 0.5833 µN (−1.7 %)."""
    from gecko_agents.studies import frictional_adhesion as fa

    p = fa.BASE.replace(**{"tip": "spatula", "friction.mu": 0.2})
    prot = protocol.drag_pull(fa.PRELOAD, fa.DRAG, 60.0, speed=fa.SPEED)
    pull = []
    for integrator in ("explicit", "implicit"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # validity warning of the contact radius
            h = Model(p, seed=1, numerics=Numerics(integrator=integrator, record_every=1)).run(
                prot, progress=False
            )
        pull.append(pull_off(h, fa.DRAG).adhesion)
    # Half a percent, the bound for an event against the explicit reference.
    assert abs(pull[1] - pull[0]) <= 0.005 * pull[0], pull


def _dx_for_pull(law, zf, s0, pull):
    """Tip offset dx < 0 from the front (the tip behind it, the film taut at height zf) at
    which the film's horizontal pull on the front, F·|dx|/s with F = K(s − s0)/s0, is
    ``pull`` [µN] (brentq on the closed form)."""
    from scipy.optimize import brentq

    def H(dx):
        s = math.hypot(dx, zf)
        return law.K * (s - s0) / s0 * -dx / s - pull

    return brentq(H, -20.0, -math.sqrt(s0 * s0 - zf * zf) - 1e-12, xtol=1e-15)


@pytest.mark.parametrize("interface", ["bonded", "sliding"])
def test_a_pad_slides_in_the_jacobian_where_its_pull_passes_its_cap(interface):
    """Adhesive friction, μ = 0.5: the pad's cap is μ·2w·b (the whole pad attached), and a
    film at 22° from the floor (z_f = 0.2 µm, s0 = 0.5 µm, far below the peel: g ≪ w) pulls
    on the front with H = F·|dx|/s. Bonded, at 0.95 of the cap the law's step holds the
    front and the Jacobian is the film's (the front held); at 1.05 the front slides and
    holds the tip at the cap (∂T/∂x = 0, central differences) and the Jacobian's x row is
    0. A sliding pad whose locked pre-tension P0 = 1.2·cap exceeds the pull holds it pulled
    (H = 1.1·cap, between the cap and P0) and slides pushed over itself (−H past the cap)."""
    from gecko_agents.contact import contact_law

    law = contact_law(SPATULA.replace(**{"friction.mu": 0.5, "spatula.interface": interface}))
    k, ell, zf, s0 = law.constants, law.ell0, 0.2, 0.5
    cap = 0.5 * 2.0 * law.w * law.b
    cases = [(0.95, 0.0, False), (1.05, 0.0, True)]
    if interface == "sliding":  # (with P0 = 0 a pull stretches the pad: partial slip)
        cases = [(1.1, 1.2 * cap, False)]
    for share, p0, slides in cases:
        dx = _dx_for_pull(law, zf, s0, share * cap)
        out = law.step_scalar(dx, law.R + zf, ell, p0, s0, dx, k)
        assert (out[2] != 0.0) == slides  # the front moved: the pad slid
        kxx, kxy, kyy = (float(q[0]) for q in law.jacobian([dx], [-zf], [s0], [dx], [ell], [p0]))
        held = [float(q[0]) for q in law.jacobian([dx], [-zf], [s0], [dx])]
        assert kyy == held[2]
        if slides:
            assert kxx == kxy == 0.0
            e = 1e-6
            T = [law.step_scalar(dx + q, law.R + zf, ell, p0, s0, dx + q, k)[1] for q in (e, -e)]
            assert T[0] == pytest.approx(cap, rel=1e-12) and T[1] == pytest.approx(cap, rel=1e-12)
            # the state the slide left sits at the cap: still sliding
            x_new = dx - out[2]
            assert law.jacobian([x_new], [-zf], [s0], [x_new], [ell], [p0])[0][0] == 0.0
        else:
            assert [kxx, kxy] == held[:2] and kxx > 0.0
    if interface == "sliding":  # pushed over the pad: the same pull reversed slides
        dx = -_dx_for_pull(law, zf, s0, 1.1 * cap)
        assert law.step_scalar(dx, law.R + zf, ell, 1.2 * cap, s0, dx, k)[2] != 0.0
        assert law.jacobian([dx], [-zf], [s0], [dx], [ell], [1.2 * cap])[0][0] == 0.0


@pytest.mark.parametrize("share", [0.9, 1.1])
def test_the_pressed_body_sticks_in_the_jacobian_below_its_coulomb_cap(share):
    """A spatula tip pressed δ = 0.1 µm (its film slack, μ = 0.2) with its body's stick
    offset ξ at ``share`` of its Coulomb cap, k_t|ξ| = share·μ·P_c, P_c = (4/3)E*√R·δ^(3/2)
    (Hertz): below the cap the body sticks and the Jacobian's kxx is its stick spring k_t,
    −∂T/∂x by central differences of the law's force; above it the body slides at the cap
    (∂T/∂x = 0) and so it does at the state the slide left (k_t|ξ| = μ·P_c): kxx = 0."""
    from gecko_agents.contact import contact_law

    law = contact_law(BONDED_SPATULA.replace(**{"friction.mu": 0.2}))
    k, delta, s0, dx = law.constants, 0.1, 1.0, 0.3
    R, _, E = law.R, law.w, law.E_star
    cap = 0.2 * 4.0 / 3.0 * E * math.sqrt(R) * delta**1.5
    xa = dx - share * cap / law.tip_stiffness
    kxx = float(law.jacobian([dx], [delta], [s0], [xa])[0][0])
    e = 1e-7  # µm, well inside the stick range (ξ = 0.1·cap/k_t from the cap)
    T = [_film_force_on_tip(law, k, dx + q, delta, s0, xa)[0] for q in (e, -e)]
    assert kxx == pytest.approx(-(T[0] - T[1]) / (2 * e), rel=1e-6, abs=1e-9)
    assert kxx == (law.tip_stiffness if share < 1.0 else 0.0)
    xa_after = law.step_scalar(dx, law.R - delta, law.ell0, 0.0, s0, xa, k)[6]
    assert float(law.jacobian([dx], [delta], [s0], [xa_after])[0][0]) == (
        law.tip_stiffness if share < 1.0 else 0.0
    )
