"""Probes over a pad (gecko_agents.physics.pad_probe): the sphere's closed form at centimetre
radii, the tilt's rise across the pad, rough and measured floors added to them, and the
refusals."""

import math

import numpy as np
import pytest

from gecko_agents.physics import pad_field, pad_probe

FIELD = pad_field.PadField(n=64, pitch=4.0, radius=1.5, stiffness=0.45, release_force=4.66,
                           thickness=160.0, modulus=1.413, poisson=0.3)  # fmt: skip


@pytest.mark.parametrize("R", [50.0, 1e4, 3e4])
def test_a_sphere_of_any_radius_is_its_sag(R):
    """A sphere of radius R_p over the pad: h = √(R_p² − r²) − R_p, which is −r²/(2R_p) to
    twice r⁴/(8R_p³) for r ≪ R_p (centimetres over a 0.25 mm pad), −R_p beyond its equator."""
    x, y = FIELD.positions()
    r = np.hypot(x, y)
    h = pad_probe.pad_heights(FIELD, R)
    sag = np.where(r < R, np.sqrt(np.maximum(R * R - r * r, 0.0)) - R, -R)
    np.testing.assert_allclose(h, sag - sag.max(), rtol=0, atol=1e-9 * R)
    if R > 1e3:
        np.testing.assert_allclose(h, -(r * r - (r * r).min()) / (2 * R), rtol=0,
                                   atol=r.max() ** 4 / (4 * R**3))  # fmt: skip


def test_a_tilt_rises_across_the_pad_and_a_floor_adds_to_it():
    """A flat tilted 0.4°: the far edge lies tan(0.4°)·(n − 1)·s below the first; a rough
    floor (RMS 0.2 µm, H = 0.8) adds its heights, max h stays 0; the same seed gives the
    same floor, another seed another."""
    h = pad_probe.pad_heights(FIELD, math.inf, 0.4)
    assert h.max() == 0.0
    assert h.min() == pytest.approx(-math.tan(math.radians(0.4)) * 63 * 4.0, rel=1e-12)
    z = pad_probe.rough_floor(FIELD, 0.2, 0.8, seed=3)
    assert z.std() == pytest.approx(0.2, rel=1e-12) and abs(z.mean()) < 1e-12
    np.testing.assert_array_equal(z, pad_probe.rough_floor(FIELD, 0.2, 0.8, seed=3))
    assert not np.array_equal(z, pad_probe.rough_floor(FIELD, 0.2, 0.8, seed=4))
    hz = pad_probe.pad_heights(FIELD, math.inf, 0.4, z)
    np.testing.assert_allclose(hz, h + z - (h + z).max(), rtol=0, atol=1e-12)


def test_the_shipped_afm_map_is_a_floor():
    """The WSxM AFM map (600 nm, heights in nm) read through SurfaceTopography, its plane
    removed, sampled at the fibres: nanometre heights, finite, mean plane about 0."""
    pytest.importorskip("SurfaceTopography")
    z = pad_probe.map_floor(FIELD)
    assert z.shape == (64, 64) and np.all(np.isfinite(z))
    assert 1e-4 < z.std() < 1e-2  # µm: nanometres


@pytest.mark.parametrize(
    ("kw", "match"),
    [({"rms_height": 0.0}, "rms_height"), ({"rms_height": math.nan}, "rms_height"),
     ({"hurst": 0.0}, "hurst"), ({"hurst": 1.5}, "hurst")],
)  # fmt: skip
def test_bad_floor_refused(kw, match):
    pytest.importorskip("SurfaceTopography")
    with pytest.raises(ValueError, match=rf"^{match} = "):
        pad_probe.rough_floor(FIELD, **({"rms_height": 0.1} | kw))
    with pytest.raises(ValueError, match="floor must be"):
        pad_probe.pad_heights(FIELD, math.inf, 0.0, np.zeros((3, 3)))


@pytest.mark.parametrize("probe", ["sphere 1 cm", "rough", "afm"])
def test_pad_solution_on_these_probes_is_the_event_to_event_one(probe):
    """A 24 × 24 field pressed to 0.2 N·F_r by a 1 cm sphere, a flat on a rough floor (RMS
    50 nm) or on the AFM map, pulled off at the pad tolerances: the event-to-event pull-off
    and contact within 0.5 %."""
    from gecko_agents.physics import layer_field as lf

    field = pad_field.PadField(**{**FIELD.__dict__, "n": 24})
    if probe != "sphere 1 cm":
        pytest.importorskip("SurfaceTopography")
    floor = None
    if probe == "rough":
        floor = pad_probe.rough_floor(field, 0.05)
    elif probe == "afm":
        floor = pad_probe.map_floor(field)
    h = pad_probe.pad_heights(field, 1e4 if probe == "sphere 1 cm" else math.inf, 0.0, floor)
    P = 0.2 * 24 * 24 * field.release_force
    small = lf.LayerField(**{**FIELD.__dict__, "n": 24})
    exact = lf.press_pull(small, h, P, resolution=1e-6)
    got = pad_field.press_pull_pad(field, h, P, **pad_field.PAD_TOLERANCES)
    assert got.pull_off == pytest.approx(exact.pull_off, rel=5e-3)
    assert got.attached_max == exact.attached_max
