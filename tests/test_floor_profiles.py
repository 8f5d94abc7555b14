"""Real floors: self-affine synthesis, measured profiles and their readers, floor statistics."""

import json
import math

import extras
import numpy as np
import pytest

from gecko_agents import floor
from gecko_agents.data import SURFACES
from gecko_agents.floor import readers as profiles
from gecko_agents.params import PAPER_ARRAY, Floor

DATA = SURFACES
DEKTAK = DATA / "dektak_profile.csv"
WSXM = DATA / "wsxm_afm.top"
NEEDS_ST = extras.reason("topography")


def _st():
    return pytest.importorskip("SurfaceTopography", reason=NEEDS_ST)


# --- self-affine synthesis ------------------------------------------------------------------


def _synth(seed, H=0.8, **kw):
    args = dict(hurst=H, rms_height=0.5, short_cutoff=2.0, long_cutoff=50.0)
    args.update(kw)
    # 4000 vertices at 0.5 µm: the whole periodic box, so the periodogram needs no window.
    return floor.self_affine(0.0, 1999.5, np.random.default_rng(seed), **args)


def test_self_affine_rms_height_and_slope_within_2_percent_over_seeds():
    ms = np.mean([np.mean(_synth(s).y ** 2) for s in range(30)])
    assert abs(math.sqrt(ms) - 0.5) < 0.02 * 0.5
    p = [_synth(s, rms_height=None, rms_slope=0.2) for s in range(30)]
    ms_slope = np.mean([np.mean((np.diff(q.y) / np.diff(q.x)) ** 2) for q in p])
    assert abs(math.sqrt(ms_slope) - 0.2) < 0.02 * 0.2


@pytest.mark.parametrize("H", [0.3, 0.8])
def test_self_affine_psd_slope_between_cutoffs(H):
    lam_s, lam_l = 2.0, 50.0
    cs = []
    for s in range(20):
        q, c = floor.psd(_synth(s, H=H, long_cutoff=lam_l), window=None)
        cs.append(c)
    c = np.mean(cs, axis=0)
    m = (q > 2 * np.pi / lam_l) & (q < 2 * np.pi / lam_s)
    slope = np.polyfit(np.log(q[m]), np.log(c[m]), 1)[0]
    assert abs(slope - (-(1 + 2 * H))) < 0.05 * (1 + 2 * H)
    # Flat below the long cutoff (roll-off): no power-law rise there.
    lo = (q > 0) & (q < 0.5 * 2 * np.pi / lam_l)
    assert abs(np.polyfit(np.log(q[lo]), np.log(c[lo]), 1)[0]) < 0.3
    # Nothing above the short cutoff.
    assert np.all(c[q > 1.001 * 2 * np.pi / lam_s] < 1e-20)


def test_self_affine_psd_normalisation_against_the_closed_form_integral():
    # ⟨h²⟩ = (1/π) ∫₀^∞ C dq (SurfaceTopography convention): with C0 found from the closed
    # form integral of the requested spectrum, the mean periodogram must match C0·q^−(1+2H).
    H, lam_s, lam_l, rms = 0.7, 2.0, 50.0, 0.5
    q_s, q_l = 2 * np.pi / lam_s, 2 * np.pi / lam_l
    integral = q_l ** (-2 * H) + (q_l ** (-2 * H) - q_s ** (-2 * H)) / (2 * H)
    c0 = rms**2 * np.pi / integral
    cs = [floor.psd(_synth(s, H=H), window=None) for s in range(20)]
    q, c = cs[0][0], np.mean([c for _, c in cs], axis=0)
    m = (q > 2 * q_l) & (q < q_s / 2)
    ratio = np.mean(c[m] / (c0 * q[m] ** (-1 - 2 * H)))
    assert abs(ratio - 1) < 0.05


def test_self_affine_same_seed_same_profile():
    a, b, c = _synth(5), _synth(5), _synth(6)
    assert np.array_equal(a.y, b.y) and np.array_equal(a.x, b.x)
    assert not np.array_equal(a.y, c.y)


def test_self_affine_psd_convention_matches_surface_topography():
    st = _st()
    from SurfaceTopography import UniformLineScan

    p = _synth(1)
    n = p.y.size
    line = UniformLineScan(p.y, n * p.spacing, periodic=True)
    q_st, c_st = line.power_spectrum_from_profile(resampling_method=None, window="None")
    q, c = floor.psd(p, window=None)
    k = min(q_st.size, q.size)
    assert st is not None
    np.testing.assert_allclose(q_st[1:k], q[1:k], rtol=1e-12)
    np.testing.assert_allclose(c_st[1:k], c[1:k], rtol=1e-9, atol=1e-12 * c.max())


def test_self_affine_bad_input_names_the_parameter():
    rng = np.random.default_rng(0)
    kw = dict(rms_height=1.0, short_cutoff=2.0, long_cutoff=50.0)
    for H in (0.0, 1.0, -0.2, 1.5):
        with pytest.raises(ValueError, match="hurst"):
            floor.self_affine(0, 100, rng, hurst=H, **kw)
    with pytest.raises(ValueError, match="long_cutoff"):
        floor.self_affine(0, 100, rng, hurst=0.5, rms_height=1.0, short_cutoff=5, long_cutoff=2)
    with pytest.raises(ValueError, match="exactly one"):
        floor.self_affine(0, 100, rng, hurst=0.5, rms_slope=0.1, **kw)
    with pytest.raises(ValueError, match="short_cutoff"):
        floor.self_affine(0, 100, rng, hurst=0.5, spacing=2.0, **kw)
    with pytest.raises(TypeError, match="Generator"):
        floor.self_affine(0, 100, 42, hurst=0.5, **kw)


# --- parameters and the floor under an array ------------------------------------------------


def test_floor_params_kind_and_validation():
    assert Floor().kind == "gaussian"
    with pytest.raises(ValueError, match=r"Floor\.kind = 'fractal'"):
        Floor(kind="fractal")
    with pytest.raises(ValueError, match=r"Floor\.hurst = 1\.2 .*\(0\.0, 1\.0\)"):
        Floor(kind="self_affine", hurst=1.2)
    with pytest.raises(ValueError, match=r"Floor\.long_cutoff"):
        Floor(kind="self_affine", short_cutoff=10.0, long_cutoff=5.0)
    with pytest.raises(ValueError, match=r"Floor\.short_cutoff"):
        Floor(kind="self_affine", short_cutoff=0.0)
    with pytest.raises(ValueError, match=r"Floor\.rms_slope"):
        Floor(kind="self_affine", sigma=1.0, rms_slope=0.1)
    with pytest.raises(ValueError, match=r"Floor\.correlation_length"):
        Floor(kind="self_affine", correlation_length=3.0)
    # Old metadata (no kind field) still loads, as a Gaussian floor.
    d = PAPER_ARRAY.to_dict()
    for k in ("kind", "hurst", "short_cutoff", "long_cutoff", "rms_slope"):
        d["floor"].pop(k)
    assert PAPER_ARRAY.from_dict(d) == PAPER_ARRAY


def test_for_array_gaussian_default_is_the_floor_of_before():
    xc = 4.0 * np.arange(12)
    for ell in (0.0, 3.0):
        fp = Floor(sigma=0.7, correlation_length=ell)
        a = floor.for_array(fp, xc, 4.0, 30.0, np.random.default_rng(2))
        b = floor.make_profile(0.7, ell, 12, 4.0, xc, 30.0, np.random.default_rng(2))
        assert np.array_equal(a.x, b.x) and np.array_equal(a.y, b.y)


def test_for_array_self_affine_by_parameter():
    xc = 4.0 * np.arange(10)
    fp = Floor(kind="self_affine", sigma=0.4, hurst=0.6, short_cutoff=2.0, long_cutoff=20.0)
    p = floor.for_array(fp, xc, 4.0, 30.0, np.random.default_rng(3))
    assert p.pad_heights is None and p.spacing == 0.5
    assert p.x[0] == xc[0] - 30.0 and p.x[-1] >= xc[-1] + 30.0
    q = floor.self_affine(
        -30.0,
        66.0,
        np.random.default_rng(3),
        hurst=0.6,
        rms_height=0.4,
        short_cutoff=2.0,
        long_cutoff=20.0,
    )
    assert np.array_equal(p.y, q.y)
    fs = Floor(kind="self_affine", rms_slope=0.1, short_cutoff=2.0, long_cutoff=20.0)
    assert floor.for_array(fs, xc, 4.0, 30.0, np.random.default_rng(3)).y.std() > 0


def test_flat_measured_profile_gives_the_flat_floor_exactly():
    # A flat Gaussian floor with correlation length ℓ (vertices every ℓ/8) and a flat measured
    # profile sampled at ℓ/8 must give the same polyline under the array.
    xc, margin, ell = 4.0 * np.arange(7) + 1.3, 25.0, 4.0
    flat = floor.for_array(
        Floor(sigma=0.0, correlation_length=ell), xc, 4.0, margin, np.random.default_rng(0)
    )
    scan = floor.from_profile(np.arange(0, 400.0, 0.5), np.zeros(800), spacing=ell / 8)
    meas = floor.for_array(Floor(), xc, 4.0, margin, np.random.default_rng(0), measured=scan)
    assert np.array_equal(meas.x, flat.x) and np.array_equal(meas.y, flat.y)
    assert np.all(flat.y == 0.0)


def test_flat_measured_profile_reproduces_the_flat_floor_history():
    from gecko_agents import model, protocol

    ell = 4.0
    p = PAPER_ARRAY.replace(
        **{"floor.sigma": 0.0, "floor.correlation_length": ell, "mechanics": "rod", "seta.L": 5.0}
    )
    prot = protocol.press_pull(0.2)
    h_flat = model.Model(p, n_sim=2).run(prot, progress=False)
    scan = floor.from_profile(np.arange(0, 600.0, 0.5), np.zeros(1200), spacing=ell / 8)
    h_meas = model.Model(p, n_sim=2, floor_profile=scan).run(prot, progress=False)
    for col in ("force_normal_uN", "plate_y_um"):
        assert np.array_equal(h_flat[col], h_meas[col])


def test_measured_profile_shorter_than_the_array_is_refused():
    scan = floor.from_profile(np.linspace(0, 50, 101), np.zeros(101), source="short.csv")
    with pytest.raises(ValueError, match=r"short\.csv.*50 µm long.*needs"):
        floor.for_array(
            Floor(), 4.0 * np.arange(20), 4.0, 30.0, np.random.default_rng(0), measured=scan
        )


# --- from_profile ---------------------------------------------------------------------------


def test_from_profile_units_detrend_resampling():
    x_nm = np.linspace(0, 20_000, 401)  # 20 µm in nm
    h_nm = 3.0 * x_nm / 1000 + 50.0 * np.sin(2 * np.pi * x_nm / 4000)  # tilt + 4 µm wave
    p = floor.from_profile(x_nm, h_nm, unit="nm", spacing=0.01)
    assert p.spacing == 0.01 and p.x[0] == 0 and abs(p.x[-1] - 20.0) < 1e-9
    # 50 nm amplitude = 0.05 µm; the tilt is gone (the sine's own trend over 5 periods is 0).
    assert abs(np.sqrt(np.mean(p.y**2)) - 0.05 / np.sqrt(2)) < 1e-3
    m = floor.from_profile(x_nm, h_nm, unit="nm", height_unit="nm", detrend="mean")
    assert abs(m.y.mean()) < 1e-12 and np.ptp(m.y) > 0.05  # tilt kept
    mm = floor.from_profile([0, 1e-3, 2e-3], [0, 1e-6, 0], unit="mm", detrend="none")
    np.testing.assert_allclose(mm.x, [0, 1, 2]) and np.testing.assert_allclose(mm.y, [0, 1e-3, 0])


def test_from_profile_bad_input_names_the_problem():
    x = np.linspace(0, 10, 11)
    with pytest.raises(ValueError, match=r"h has 1 NaN.*index 3.*scan\.csv"):
        floor.from_profile(x, np.where(x == 3, np.nan, 0.0), source="scan.csv")
    with pytest.raises(ValueError, match=r"strictly increasing: x\[4\]"):
        floor.from_profile(np.r_[x[:5], x[4], x[6:]], np.zeros(11))
    with pytest.raises(ValueError, match=r"unit = 'furlong'"):
        floor.from_profile(x, np.zeros(11), unit="furlong")
    with pytest.raises(ValueError, match=r"height_unit = 'px'"):
        floor.from_profile(x, np.zeros(11), height_unit="px")
    with pytest.raises(ValueError, match="detrend"):
        floor.from_profile(x, np.zeros(11), detrend="quadratic")
    with pytest.raises(ValueError, match="11 points but h has 10"):
        floor.from_profile(x, np.zeros(10))


# --- plain text reader ----------------------------------------------------------------------


def test_text_round_trip_to_1e_12(tmp_path):
    p = _synth(9)
    f = profiles.write_text(tmp_path / "p.csv", p)
    x, h, ux, uh = profiles.read_columns(f)
    assert (ux, uh) == ("um", "um")
    np.testing.assert_allclose(x, p.x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(h, p.y, rtol=0, atol=1e-12)
    q = profiles.read_text(f, detrend="none")
    np.testing.assert_allclose(q.y, p.y, rtol=0, atol=1e-12)


def test_dektak_loads_without_the_extra():
    x, h, ux, uh = profiles.read_columns(DEKTAK)
    # The file's own numbers (header block skipped): 9 600 rows, first and last as written.
    assert x.size == h.size == 9600
    assert (x[0], h[0], x[1], h[1]) == (0.0, -0.00933, 0.2, -0.0076)
    assert (x[-1], h[-1]) == (1499.8, 16.58112)
    assert floor.length_factor(ux) == 1.0 and floor.length_factor(uh) == 1.0  # µm
    p = profiles.read_text(DEKTAK)
    assert p.y.size == 9600 and abs(p.spacing - 1499.8 / 9599) < 1e-12
    # The ~16 µm tilt (slope 0.011) is gone (fitted on the scan's own points, then resampled).
    assert abs(np.polyfit(p.x, p.y, 1)[0]) < 1e-6


def test_text_reader_units_from_header_or_argument(tmp_path):
    f = tmp_path / "nm.txt"
    f.write_text("# AFM line\nx_nm h_nm\n0 1.0\n1000 2.0\n2000 1.0\n")
    x, h, ux, uh = profiles.read_columns(f)
    assert (ux, uh) == ("nm", "nm")
    p = profiles.read_text(f, detrend="none")
    np.testing.assert_allclose(p.x, [0, 1, 2]) and np.testing.assert_allclose(
        p.y, [1e-3, 2e-3, 1e-3]
    )
    bare = tmp_path / "bare.dat"
    bare.write_text("0 0\n1 1\n2 0\n")
    with pytest.raises(ValueError, match=r"no length unit.*bare\.dat.*unit='um'"):
        profiles.read_columns(bare)
    assert profiles.read_columns(bare, unit="mm")[2] == "mm"
    with pytest.raises(ValueError, match=r"unit = 'mm' contradicts the unit 'nm'"):
        profiles.read_columns(f, unit="mm")


def test_text_reader_refuses_bad_files(tmp_path):
    with pytest.raises(ValueError, match=r"cannot read profile file .*missing\.csv"):
        profiles.read_text(tmp_path / "missing.csv")
    junk = tmp_path / "junk.csv"
    junk.write_text("hello\nworld\n")
    with pytest.raises(ValueError, match=r"junk\.csv.* not a two-column profile"):
        profiles.read_text(junk, unit="um")
    gap = tmp_path / "gap.csv"
    gap.write_text("x [um], h [um]\n0, 0\n1, nan\n2, 0\n")
    with pytest.raises(ValueError, match=r"NaN.*gap\.csv"):
        profiles.read_text(gap)


# --- SurfaceTopography reader (optional extra) ----------------------------------------------


def test_dektak_through_surface_topography_gives_the_same_heights():
    _st()
    a = profiles.read_text(DEKTAK)
    b = profiles.read_topography(DEKTAK)
    assert b.y.size == 9600
    np.testing.assert_allclose(b.x, a.x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.y, a.y, rtol=0, atol=1e-12)


def test_wsxm_afm_map_loads_in_micrometres():
    _st()
    x, y, h = profiles.read_map(WSXM)
    assert h.shape == (256, 256)
    assert abs(x[-1] + (x[1] - x[0]) - 0.6) < 1e-12  # 600 nm scan → 0.6 µm
    # Areal RMS height about the mean (SurfaceTopography's Sq / rms_height_from_area):
    # 3.153 nm in its own tests.
    sq = np.sqrt(np.mean((h - h.mean()) ** 2))
    assert abs(sq - 3.153e-3) < 0.0005e-3
    r = profiles.read_topography(WSXM, row=17, detrend="none")
    np.testing.assert_allclose(r.y, h[:, 17], rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match=r"row = None.*256 × 256 map"):
        profiles.read_topography(WSXM)
    with pytest.raises(ValueError, match=r"row = 256"):
        profiles.read_topography(WSXM, row=256)


def test_surface_topography_reader_refuses_unreadable_file(tmp_path):
    _st()
    bad = tmp_path / "noise.sdf"
    bad.write_bytes(b"\x00\x01garbage" * 10)
    with pytest.raises(ValueError, match=r"cannot read .*noise\.sdf"):
        profiles.read_topography(bad)


def test_missing_extra_gives_the_install_hint(monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_st(name, *args, **kwargs):
        if name.startswith("SurfaceTopography"):
            raise ImportError("No module named 'SurfaceTopography'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_st)
    with pytest.raises(ImportError, match=r"pip install 'gecko_agents\[topography\]'"):
        profiles.read_topography(WSXM, row=0)


# --- statistics -----------------------------------------------------------------------------


def test_statistics_closed_forms_and_json():
    # A sine of amplitude A and wavelength λ: RMS height A/√2, RMS slope (2πA/λ)/√2.
    A, lam = 0.2, 10.0
    x = np.arange(0, 400, 0.05)
    p = floor.from_profile(x, A * np.sin(2 * np.pi * x / lam), detrend="none")
    s = floor.statistics(p)
    assert abs(s["rms_height_um"] - A / np.sqrt(2)) < 1e-3 * A
    assert abs(s["rms_slope"] - 2 * np.pi * A / lam / np.sqrt(2)) < 1e-3
    json.dumps(s)  # JSON-friendly
    # A self-affine floor: the fitted exponent between the cutoffs is close to H.
    hs = [
        floor.statistics(_synth(k, H=0.7), fit_wavelengths=(4.0, 25.0))["hurst"] for k in range(8)
    ]
    assert abs(np.mean(hs) - 0.7) < 0.1
    pads = floor.make_profile(
        1.0, 0.0, 50, 4.0, 4.0 * np.arange(50), 10.0, np.random.default_rng(0)
    )
    sp = floor.statistics(pads)
    assert sp["kind"] == "pads" and sp["hurst"] is None
    json.dumps(sp)


def test_floor_panel_is_written(tmp_path):
    from gecko_agents.render.floor_plots import plot_floor

    out = plot_floor(_synth(0), tmp_path / "floor.png", title="self-affine")
    assert (tmp_path / "floor.png").stat().st_size > 10_000 and len(out.axes) == 2


def test_run_metadata_carries_the_floor_statistics():
    from gecko_agents import model, protocol

    p = PAPER_ARRAY.replace(
        **{"floor.kind": "self_affine", "floor.sigma": 0.2, "mechanics": "rod", "seta.L": 5.0}
    )
    m = model.Model(p, n_sim=2)
    h = m.run(protocol.press_pull(0.2, speed=0.05), progress=False)
    st = h.meta["floor_statistics"]
    y = m.profile.y
    assert st["rms_height_um"] == pytest.approx(float(np.sqrt(np.mean((y - y.mean()) ** 2))))
    assert st["hurst"] is not None and 0.0 < st["hurst"] < 1.5


def test_a_line_inside_the_data_block_is_refused_or_read_past_never_dropping_rows(tmp_path):
    rows = [f"{0.1 * i:.1f} {0.01 * np.sin(i):.5f}" for i in range(200)]
    junk = tmp_path / "junk.txt"
    junk.write_text("\n".join(rows[:100] + ["-- scan paused --"] + rows[100:]) + "\n")
    with pytest.raises(ValueError, match=r"line 101: '-- scan paused --'"):
        profiles.read_columns(junk, unit="um")
    commented = tmp_path / "commented.txt"
    commented.write_text("\n".join(rows[:100] + ["# scan paused", ""] + rows[100:]) + "\n")
    x, h, _, _ = profiles.read_columns(commented, unit="um")
    assert x.size == 200 and x[-1] == pytest.approx(19.9) and x[100] == pytest.approx(10.0)


def test_heights_beyond_any_floor_under_setae_are_refused_naming_the_range():
    x = np.linspace(0.0, 100.0, 50)
    with pytest.raises(ValueError, match=r"span 6.\d+e\+08 µm .*\[0, 10000\] µm"):
        floor.from_profile(x, 3e8 * np.sin(x), unit="um", source="probe")
    assert floor.from_profile(x, 1e3 * np.sin(x), unit="um").y.size == 50  # 2 mm: accepted


def test_the_dektak_scan_is_read_on_its_true_grid_against_an_independent_slope():
    # The file prints x to 0.1 µm while the stylus samples every 1500 µm / 9600 = 0.15625 µm
    # (header: Length 1500.0 um; 9600 rows). Independently of the reader: the height column
    # on that grid, least-squares line removed, RMS of the forward differences over Δ.
    import csv

    with SURFACES.joinpath("dektak_profile.csv").open(encoding="latin-1") as f:
        rows = list(csv.reader(f))
    start = next(i for i, r in enumerate(rows) if r and r[0].startswith("Lateral")) + 1
    h = np.array([float(r[1]) for r in rows[start:] if r and r[0].strip()])
    assert h.size == 9600
    dx = 1500.0 / 9600
    k = np.arange(h.size) * dx
    h = h - np.polyval(np.polyfit(k, h, 1), k)
    slope = np.sqrt(np.mean((np.diff(h) / dx) ** 2))
    stats = floor.statistics(profiles.read_text(DATA / "dektak_profile.csv"))
    # Mean spacing of the printed end points vs the header's: 1499.8/9599 vs 0.15625 (3e-5).
    assert stats["rms_slope"] == pytest.approx(slope, rel=1e-4)
    assert stats["rms_height_um"] == pytest.approx(np.sqrt(np.mean(h**2)), rel=1e-4)
    x, *_ = profiles.read_columns(DATA / "dektak_profile.csv")
    assert set(np.round(np.diff(x), 6)) == {0.1, 0.2}  # as printed
    assert profiles.printed_resolution(x) == pytest.approx(0.1)
    # A genuinely non-uniform scan is left as it is.
    xs = np.cumsum(np.r_[0.0, np.tile([0.1, 0.5], 50)])
    assert np.array_equal(profiles.uniform_grid(xs), xs)
