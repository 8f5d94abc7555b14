"""The literature comparison (gecko_agents.studies.validation): every row carries a source, the
text read, its kind and how a magnitude agrees; assumed parameters are marked; every scored
row's *ours* is recomputed here from its preset (closed forms by hand, agent runs through the
studies' own functions or a closed-form oracle) and must equal what the study reports."""

import json
import math

import numpy as np
import pytest

from gecko_agents.params import literature as lit
from gecko_agents.studies import pad_peel, reproduce_paper
from gecko_agents.studies import validation as val
from gecko_agents.studies import validation_ours as vo
from gecko_agents.studies.validation_rows import KINDS, ROWS, load_rows

SCORED = [r for r in ROWS if r["status"] == "scored"]


def test_every_row_carries_a_source_what_was_read_its_kind_and_marked_parameters():
    assert len(SCORED) >= 20
    assert sum(r["kind"] == "experiment" for r in SCORED) >= 12
    for r in ROWS:
        assert r["source"] and r["theirs"] and r["measured"] and r["read_at"], r["id"]
        assert r["kind"] in KINDS, r["id"]
        if r in SCORED:
            assert r["ours"] in vo.OURS, r["id"]
            assert r["params"], r["id"]  # every number ours uses is listed, cited or assumed
            if r["kind"] != "self-consistency":
                assert r["quote"], r["id"]
        else:
            assert r["unscored"], r["id"]  # says why it is not scored
        for p in r["params"]:
            assert p["status"] in ("cited", "cited range", "assumed") and p["why"], p["name"]
            if p.get("range") is not None:
                lo, hi = p["range"]
                assert lo < hi, (r["id"], p["name"])


def test_numbers_quoted_as_theirs_appear_in_the_text_read():
    direct = [r for r in SCORED if r["scatter_why"] == "their s.e.m."]
    assert len(direct) >= 2
    for r in direct:
        assert format(r["theirs_value"], "g") in r["quote"], r["id"]
        assert format(r["scatter"], "g") in r["quote"], r["id"]


def test_propagated_scatter_is_the_quadrature_of_the_quoted_s_e_m():
    """0.11 ± 0.004 over 0.08 ± 0.004 (Table 1) and the PTFE friction 0.29 ± 0.01 over 0.24 ±
    0.004: the ratio's s.e.m. is ratio·√((s₁/m₁)² + (s₂/m₂)²)."""
    rows = {r["id"]: r for r in ROWS}
    table = {
        "autumn2006a_anisotropy": (0.11, 0.004, 0.08, 0.004),
        "autumn2006a_vertical_along": (0.08, 0.003, 0.08, 0.004),
        "autumn2006a_ptfe_friction": (0.29, 0.01, 0.24, 0.004),
    }
    for rid, (m1, s1, m2, s2) in table.items():
        ratio = m1 / m2
        assert rows[rid]["theirs_value"] == pytest.approx(ratio, rel=2e-3)
        sem = ratio * math.hypot(s1 / m1, s2 / m2)
        assert rows[rid]["scatter"] == pytest.approx(sem, rel=0.02)


def test_a_closed_form_row_computes_ours_at_the_values_it_lists():
    for r in SCORED:
        if r["ours"] not in vo.CLOSED_FORM:
            continue
        fn = vo.OURS[r["ours"]]
        for p in r["params"]:
            if p["range"] is not None:
                at_value = fn(True, **{p["name"]: p["value"]})["value"]
                assert at_value == pytest.approx(fn(True)["value"], rel=1e-12), (r["id"], p["name"])


# Closed forms, recomputed by hand from the preset (eq 17–20) ----------------------------------
def _rod(p):
    r, L, E, th = p.seta.r, p.seta.L, p.contact.E1, math.radians(p.seta.theta_deg)
    Ka = math.pi * r**2 * E / L
    Kp = 3 * math.pi * r**4 * E / (4 * L**3)
    return Ka, Kp, th


def test_seta_stiffness_is_eq20_of_the_preset():
    Ka, Kp, th = _rod(lit.AUTUMN2006_SETA)
    ky = Kp * Ka / (Kp * math.sin(th) ** 2 + Ka * math.cos(th) ** 2)
    assert vo.seta_stiffness()["value"] == pytest.approx(ky, rel=1e-12)


def test_directional_ratios_are_ratios_of_compliances_along_the_diagonals():
    Ka, Kp, th = _rod(lit.AUTUMN2006_SETA)
    n = np.array([math.cos(th), -math.sin(th)])
    t = np.array([math.sin(th), math.cos(th)])
    C = np.outer(n, n) / Ka + np.outer(t, t) / Kp  # compliance of the rod's tip

    def k(d):
        d = np.asarray(d) / np.linalg.norm(d)
        return 1.0 / (d @ C @ d)

    assert vo.seta_anisotropy()["value"] == pytest.approx(k((1, -1)) / k((-1, -1)), rel=1e-9)
    assert vo.seta_vertical_along()["value"] == pytest.approx(k((0, 1)) / k((-1, -1)), rel=1e-9)
    # At θ = 45° the +45° load is pure bending and the −45° one pure stretch.
    assert k((-1, -1)) == pytest.approx(Kp, rel=1e-9)
    assert k((1, -1)) == pytest.approx(Ka, rel=1e-9)


def test_array_modulus_is_a_bed_of_springs():
    p = lit.AUTUMN2006_SETA
    e = p.Ky * lit.TOKAY_SETAL_DENSITY * p.seta.L * math.sin(math.radians(p.seta.theta_deg))
    assert vo.array_modulus()["value"] == pytest.approx(1e3 * e, rel=1e-12)


def test_sensitivity_recomputes_at_both_ends_and_at_every_corner():
    row = next(r for r in ROWS if r["id"] == "autumn2006a_k_seta")
    sens = {s["name"]: s["ours_at_ends"] for s in val.sensitivity(row, quick=True)}
    assert set(sens) == {"E", "r", "L", "theta", "turn", "all together"}
    assert sens["E"][1] / sens["E"][0] == pytest.approx(1750 / 1450, rel=1e-9)  # K ∝ E
    assert sens["r"][1] / sens["r"][0] == pytest.approx(2.0**4, rel=0.01)  # bending: K ∝ r⁴
    # Bending-dominated ∝ 1/L³, less the axial compliance of the short seta (eq 20 by hand):
    assert sens["L"][0] / sens["L"][1] == pytest.approx((115 / 11) ** 3, rel=0.02)
    for L, k in zip((11.0, 115.0), sens["L"], strict=True):
        Ka, Kp, th = _rod(lit.AUTUMN2006_SETA.replace(**{"seta.L": L}))
        assert k == pytest.approx(Kp * Ka / (Kp * math.sin(th) ** 2 + Ka * math.cos(th) ** 2))
    corners = [vo.seta_stiffness(r=2.0, L=11.0, theta=th, turn=t)["value"]
               for th in (30.0, 60.0) for t in (-90.0, 90.0)]  # fmt: skip  # E is cited: kept
    assert sens["all together"][1] == pytest.approx(max(corners), rel=1e-12)


# Verdicts by magnitude ---------------------------------------------------------------------------
def _row(**over):
    base = {"id": "x", "status": "scored", "compare": "value", "theirs_value": 10.0,
            "scatter": None, "scatter_why": None, "band": None, "band_why": "why",
            "min_effect": None, "expect": None, "unscored": None, "tolerance": None,
            "tolerance_why": None, "bounded": False}  # fmt: skip
    return {**base, **over}


def test_value_verdicts_by_scatter_band_and_assumed_ranges():
    sem = _row(scatter=1.0, scatter_why="s.e.m.")
    assert val.verdict(sem, {"value": 10.5}, [])[0] == val.AGREES_SCATTER
    assert val.verdict(sem, {"value": 13.0}, [])[0] == val.DISAGREES_MAGNITUDE
    span = [{"status": "cited range", "ours_at_ends": [1.0, 100.0]}]
    assert val.verdict(sem, {"value": 13.0}, span)[0] == val.NOT_COMPARABLE
    cited = [{"status": "cited", "ours_at_ends": [1.0, 100.0]}]
    assert val.verdict(sem, {"value": 13.0}, cited)[0] == val.DISAGREES_MAGNITUDE
    band = _row(band=2.0)
    assert val.verdict(band, {"value": 19.9}, [])[0] == val.AGREES_BAND
    assert val.verdict(band, {"value": 5.01}, [])[0] == val.AGREES_BAND
    assert val.verdict(band, {"value": 4.9}, [])[0] == val.DISAGREES_MAGNITUDE


def test_trend_verdicts_need_the_sign_and_the_stated_size():
    ratio = _row(compare="trend", expect=">1", theirs_value=1.43, band=2.0)
    assert val.verdict(ratio, {"value": 1.25}, [])[0] == val.TREND_AGREES  # ln 1.25/ln 1.43 = 0.62
    assert val.verdict(ratio, {"value": 1.05}, [])[0] == val.DISAGREES_MAGNITUDE  # 0.14
    assert val.verdict(ratio, {"value": 3.0}, [])[0] == val.DISAGREES_MAGNITUDE  # 3.1
    assert val.verdict(ratio, {"value": 0.8}, [])[0] == val.DISAGREES_SIGN
    assert val.verdict(ratio, {"value": 1.005}, [])[0] == val.DISAGREES_MAGNITUDE  # no effect
    words = _row(compare="trend", expect="<1", theirs_value=None, min_effect=0.3)
    assert val.verdict(words, {"value": 0.6}, [])[0] == val.TREND_AGREES  # a 40 % drop
    assert val.verdict(words, {"value": 0.8}, [])[0] == val.DISAGREES_MAGNITUDE
    assert val.verdict(words, {"value": 1.2}, [])[0] == val.DISAGREES_SIGN
    # A size in words met only at an end of an unread parameter: not comparable.
    spans = [{"status": "assumed", "ours_at_ends": [1.0, 0.0]}]
    assert val.verdict(words, {"value": 1.0}, spans)[0] == val.NOT_COMPARABLE
    assert val.verdict(words, {"value": 1.0}, [{**spans[0], "status": "cited"}])[0] == (
        val.DISAGREES_MAGNITUDE
    )
    slope = _row(compare="trend", expect=">0", theirs_value=None, min_effect=0.01)
    assert val.verdict(slope, {"value": 0.4}, [])[0] == val.TREND_AGREES
    with pytest.raises(ValueError, match="expect"):
        val.effect(_row(expect="up"), 1.0)


def test_magnitude_verdicts_by_tolerance_and_on_the_nearer_bound():
    tol = _row(tolerance=0.25, tolerance_why="none stated")
    assert val.verdict(tol, {"value": 12.5}, [])[0] == val.AGREES_TOLERANCE
    assert val.verdict(tol, {"value": 7.4}, [])[0] == val.DISAGREES_MAGNITUDE
    # Φ = 0.97: the band is ±25 % of 1 − Φ = 0.03, not of Φ (which would accept Φ > 0.73).
    phi = _row(theirs_value=0.97, tolerance=0.25, tolerance_why="w", bounded=True)
    assert val.half_width(phi) == pytest.approx(0.0075)
    assert val.verdict(phi, {"value": 0.975}, [])[0] == val.AGREES_TOLERANCE
    assert val.verdict(phi, {"value": 1.0}, [])[0] == val.DISAGREES_MAGNITUDE
    low = _row(theirs_value=0.2, tolerance=0.25, tolerance_why="w", bounded=True)
    assert val.half_width(low) == pytest.approx(0.05)  # below 1/2: on Φ itself


def _scored(rid, verdict, kind="experiment", compare="value", measurement=None, source="s"):
    return {"id": rid, "kind": kind, "compare": compare, "in_words": False, "verdict": verdict,
            "measurement": measurement or rid, "source": source,
            "quick_may_differ": False}  # fmt: skip


def test_headline_counts_magnitude_rows_and_each_measurement_once():
    rows = [
        _scored("a", val.AGREES_TOLERANCE, measurement="table 1"),
        _scored("b", val.DISAGREES_MAGNITUDE, measurement="table 1"),
        _scored("c", val.AGREES_SCATTER, source="t"),
        _scored("d", val.NOT_COMPARABLE, source="u"),
        _scored("e", val.TREND_AGREES, compare="trend"),
        _scored("f", val.AGREES_BAND, kind="self-consistency"),
        {**_scored("g", val.AGREES_BAND), "in_words": True},  # 'preload-independent'
    ]
    h = val.headline(rows)
    assert (h["magnitude_rows"], h["magnitude_agree"]) == (3, 2)
    assert (h["measurements"], h["measurements_agree"]) == (2, 1)  # table 1 fails as a whole
    assert (h["papers"], h["not_comparable"]) == (2, 1)
    assert (h["trend_rows"], h["trend_agree"]) == (2, 2)  # words and directions, apart


def test_quick_sized_rows_are_agent_runs_that_the_report_marks():
    assert vo.QUICK_SIZED <= set(vo.OURS)
    assert not vo.QUICK_SIZED & vo.CLOSED_FORM


def test_the_rows_hold_magnitudes_from_independent_papers():
    """At least 12 magnitude rows from 6 papers, each at its source's stated geometry."""
    mag = [r for r in SCORED if val.is_magnitude(r)]
    assert len(mag) >= 12 and len({r["source"] for r in mag}) >= 6
    for r in mag:
        assert (r["scatter"] is None) != (r["tolerance"] is None), r["id"]
        assert r["band"] is None, r["id"]


def test_rows_not_scored_say_why_and_are_counted_apart():
    assert val.verdict(_row(status="pending", unscored="p"), None, [])[0] == "pending"
    assert val.verdict(_row(status="out of scope", unscored="o"), None, [])[0] == "out of scope"
    rows = [{"kind": "experiment", "verdict": val.TREND_AGREES},
            {"kind": "experiment", "verdict": val.NOT_COMPARABLE},
            {"kind": "model", "verdict": "pending"},
            {"kind": "self-consistency", "verdict": val.AGREES_BAND}]  # fmt: skip
    c = val.counts(rows)
    assert c["scored"] == {"experiment": 1, "model": 0, "self-consistency": 1}
    assert c["model"] == {"pending": 1}


def test_gravish_is_out_of_scope_and_kendall_1975_checks_the_pad_against_itself():
    rows = {r["id"]: r for r in ROWS}
    assert rows["gravish2010_rate"]["status"] == "out of scope"
    assert "stick–slip" in rows["gravish2010_rate"]["unscored"]
    assert rows["kendall1975_peel"]["kind"] == "self-consistency"
    assert rows["gillies2014_smooth"]["kind"] == "model"
    b = next(p for p in rows["gillies2014_smooth"]["params"] if p["name"] == "b")
    assert b["value"] == 2 * lit.FRICTIONAL_SPHERE.contact.R  # film as wide as the sphere


# The rows are data (gecko_agents/data/literature/validation.toml) ------------------------------
def test_rows_are_read_from_the_shipped_data_file(tmp_path):
    import tomllib

    from gecko_agents.data import LITERATURE_ROWS

    assert load_rows(LITERATURE_ROWS) == ROWS
    pyproject = tomllib.loads((LITERATURE_ROWS.parents[3] / "pyproject.toml").read_text())
    globs = pyproject["tool"]["setuptools"]["package-data"]["gecko_agents.data"]
    data_dir = LITERATURE_ROWS.parents[1]
    assert any(LITERATURE_ROWS in data_dir.glob(g) for g in globs)  # it ships in the wheel


def _write(path, row: dict, extra: str = "") -> None:
    fields = "".join(f"{k} = {json.dumps(v)}\n" for k, v in row.items() if v is not None)
    path.write_text('[sources]\ns = "S"\n[params.p]\nname = "E"\nvalue = 1.0\nunit = "MPa"\n'
                    'status = "cited"\nwhy = "w"\n' + extra + "[[rows]]\n" + fields)  # fmt: skip


def test_the_loader_refuses_incomplete_or_contradictory_rows(tmp_path):
    f = tmp_path / "rows.toml"
    ok = {"id": "x", "source": "s", "kind": "self-consistency", "read_at": "a", "quote": "q",
          "measured": "m", "theirs": "t", "quantity": "k", "cause": "c", "compare": "value",
          "theirs_value": 1.0, "band": 2.0, "band_why": "w", "ours": "seta_stiffness",
          "uses": ["p"]}  # fmt: skip
    _write(f, ok)
    assert load_rows(f)[0]["params"][0]["name"] == "E"
    magnitude = {**ok, "kind": "experiment", "band": None, "tolerance": 0.25,
                 "tolerance_why": "none stated"}  # fmt: skip
    _write(f, magnitude)
    assert load_rows(f)[0]["measurement"] == "x"  # its own measurement by default
    refused = (
        ({"kind": "guess"}, "kind"),
        ({"source": "nope"}, "source"),
        ({"uses": ["q"]}, "uses"),
        ({"band": None}, "how a magnitude"),
        ({"band": 0.5}, "factor > 1"),
        ({"status": "pending"}, "says why"),
        ({"theirs_value": None}, "min_effect"),
        ({"band_why": None}, "reason"),
        ({"kind": "experiment"}, "not a factor band"),
        ({"band": None, "tolerance": 1.5, "tolerance_why": "w"}, "must be in"),
        ({"band": None, "tolerance": 0.25}, "tolerance_why"),
        ({"theirs_value": 2.0, "bounded": True}, "bounded"),
    )
    for bad, match in refused:
        _write(f, {**ok, **bad})
        with pytest.raises(ValueError, match=match):
            load_rows(f)
    _write(f, {k: v for k, v in ok.items() if k != "quote"})
    with pytest.raises(ValueError, match="lacks the field"):
        load_rows(f)


def test_one_model_number_never_scores_two_observations(tmp_path):
    f = tmp_path / "rows.toml"
    row = {"source": "s", "kind": "self-consistency", "read_at": "a", "quote": "q",
           "measured": "m", "theirs": "t", "quantity": "k", "cause": "c", "compare": "value",
           "theirs_value": 1.0, "band": 2.0, "band_why": "w", "ours": "seta_stiffness"}  # fmt: skip
    _write(f, {"id": "x", **row}, extra="[[rows]]\n" + "".join(
        f"{k} = {json.dumps(v)}\n" for k, v in {"id": "y", **row}.items()))  # fmt: skip
    with pytest.raises(ValueError, match="one model number"):
        load_rows(f)
    scored = [r for r in ROWS if r["status"] == "scored"]
    assert len({r["ours"] for r in scored}) == len(scored)


def test_reproduce_beyond_writes_the_literature_comparison_beside_the_report(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(reproduce_paper, "run_scenarios", lambda base, args, log, *setup: {})
    monkeypatch.setattr(reproduce_paper, "conclusion_rows", lambda quick: [])
    monkeypatch.setattr(reproduce_paper, "run_scenario", lambda *a: calls.append(a[:2]))
    reproduce_paper.main(["--quick", "--beyond", "--jobs", "1", "--out", str(tmp_path)])
    assert calls == [("validation", ["--out", str(tmp_path), "--quick"])]
    calls.clear()
    reproduce_paper.main(["--quick", "--jobs", "1", "--out", str(tmp_path)])
    assert calls == []


# Agent rows against closed-form oracles ----------------------------------------------------------
@pytest.mark.slow
def test_ptfe_friction_of_a_coulomb_tip_is_its_mu_both_ways():
    out = vo.ptfe_friction(True, mu=0.3)
    assert out["value"] == pytest.approx(1.0, abs=0.01)
    assert "0.300 along over 0.300" in out["text"]


@pytest.mark.slow
def test_kendall_punch_row_is_kendalls_pull_off():
    """Over the tip law's closed form: Kendall's with the study's σ₀ (the Dugdale punch)."""
    assert vo.kendall_punch()["value"] == pytest.approx(1.0, abs=0.02)


@pytest.mark.slow
def test_pillar_radius_row_is_kendalls_inverse_square_root():
    """Pull-off per area at a fixed area fraction ∝ √(8πE*w a³)/a² ∝ a^(−1/2): ×√10 from 25 to
    2.5 µm."""
    assert vo.greiner_radius()["value"] == pytest.approx(math.sqrt(10.0), rel=0.02)


@pytest.mark.slow
def test_buckling_rows_press_below_and_past_euler_under_force_control():
    for aspect, past in ((5.0, 1.5), (2.4, 1.1)):
        ratio, held, peak, P_E = vo.buckled_ratio(aspect, past)
        assert peak[0] < P_E < peak[1]  # below and past buckling, as the rows say
        assert peak[1] == pytest.approx(past * P_E, rel=0.05)  # the force the row states
        assert ratio == pytest.approx(held[1] / held[0])


# The quick report; each agent row recomputed through the studies' own functions ------------
@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("validation")
    val.main(["--quick", "--out", str(out)])
    return out, {r["id"]: r for r in json.loads((out / f"{val.NAME}.json").read_text())["rows"]}


@pytest.mark.slow
def test_quick_report_rows_and_files(report):
    out, rows = report
    assert set(rows) == {r["id"] for r in ROWS}
    for f in (".md", ".png", ".csv"):
        assert (out / f"{val.NAME}{f}").is_file()
    for r in rows.values():
        assert r["verdict"] in val.VERDICTS + tuple(val.UNSCORED.values()), r["id"]
        assert r["source"] and r["reason"], r["id"]
        if r["verdict"] in val.VERDICTS or r["ours"]:  # a pending row may show ours
            assert math.isfinite(r["ours_value"]), r["id"]
    meta = json.loads((out / "metadata.json").read_text())
    assert sum(meta["verdicts"]["scored"].values()) >= 20
    h = meta["headline"]
    assert h == val.headline(list(rows.values()))
    assert h["magnitude_rows"] + h["not_comparable"] >= 12 and h["papers"] >= 6
    # Rows run smaller in --quick are marked, and only those.
    assert {r["id"] for r in rows.values() if r["quick_may_differ"]} == {
        r["id"] for r in ROWS if val.quick_may_differ(r)
    }
    assert {r["id"] for r in ROWS if r["ours"] in vo.QUICK_SIZED} <= {
        r["id"] for r in ROWS if val.quick_may_differ(r)
    }
    assert rows["autumn2006a_k_seta"]["ours_value"] == pytest.approx(lit.AUTUMN2006_SETA.Ky)


@pytest.mark.slow
def test_backing_rows_are_scored_on_the_layer_backing(report):
    """Kim & Sitti and Booth (aligned) are scored on the layer backing's field model at pad
    scale: the thinner layer holds at least as much (its edge takes less of the load)."""
    from gecko_agents.studies import pad_scale

    for rid in ("kim_sitti2007_backing", "booth2018_aligned"):
        row = report[1][rid]
        assert row["verdict"] not in ("pending", "not scored")
        assert math.isfinite(row["ours_value"]) and row["ours_value"] >= 1.0
    assert report[1]["kim_sitti2007_backing"]["ours_value"] == pytest.approx(
        pad_scale.kim_sitti_pad(quick=True)["value"], rel=1e-12
    )


@pytest.mark.slow
def test_booth_rows(report):
    from gecko_agents.studies import pad_scale

    expected = pad_scale.booth_pad_misaligned(quick=True)["value"]
    assert report[1]["booth2018_misalignment"]["ours_value"] == pytest.approx(expected, rel=1e-12)


@pytest.mark.slow
def test_kendall_row(report):
    rows = [pad_peel.run_point(200, psi, 0.5, 0.4)[0]["ratio_to_kendall"] for psi in (30.0, 90.0)]
    worst = max(rows, key=lambda x: abs(math.log(x)))
    assert report[1]["kendall1975_peel"]["ours_value"] == pytest.approx(worst)


def test_kendall_angle_law_is_one_for_a_film_that_follows_it(monkeypatch):
    """Peel forces F/b = w/(1 − cos ψ) at the measured angles give exactly 1 (w drops out)."""
    w = 0.37
    rows = tuple(
        {"psi_measured_deg": psi, "F_per_width_uN_per_um": w / (1 - math.cos(math.radians(psi))),
         "ratio_to_kendall": 1.0, "n": 10}
        for psi in (31.0, 97.0)
    )  # fmt: skip
    monkeypatch.setattr(vo, "peel_rows", lambda quick: rows)
    assert vo.kendall_angle_law()["value"] == pytest.approx(1.0, rel=1e-12)
    assert vo.kendall_peel()["value"] == pytest.approx(1.0)


def test_two_level_floor_puts_every_other_pillar_a_step_lower():
    from gecko_agents.model import Model
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": 6})
    prof = vo.two_level_profile(6, p.array.pitch, p.seta.L, 0.5)
    m = Model(p, n_sim=6, seed=0, floor_profile=prof)
    under = np.interp(m.world.rest_dx, m.world.profile.x, m.world.profile.y)
    np.testing.assert_allclose(under, [0.0, -0.5, 0.0, -0.5, 0.0, -0.5], atol=1e-12)


@pytest.mark.slow
def test_two_heights_row_holds_all_pillars_only_after_the_high_preload():
    """Low preload: the 5 long flat punches hold their pull-off F_K each (Kendall's with the
    study's σ₀, the Dugdale punch); high: all 10 (the plate reads a little less than 10 F_K:
    the short pillars are stretched less when the long ones let go)."""
    from gecko_agents.physics import flaw_tolerance
    from gecko_agents.studies import pillar_designs as pd

    c = pd.params_for("flat_punch", 5.0, "flat").contact
    F_K = float(flaw_tolerance.punch_pull_off(c.R, c.work_of_adhesion, c.E_star, c.sigma0))
    low, high = vo.two_height_pull_offs()
    assert low == pytest.approx(5 * F_K, rel=0.03)
    assert 7.5 * F_K < high <= 10 * F_K
    assert vo.two_heights()["value"] == pytest.approx(high / low)


# Magnitude rows at the sources' own geometry (closed forms) ----------------------------------
def test_tang_rows_are_the_bonded_square_corner():
    """Φ = 0.83·χ^−(1 − λ), λ the bonded incompressible 90° corner's root (r^−0.405)."""
    from gecko_agents.physics import flaw_tolerance as ft
    from gecko_agents.physics.wedge import singularity_exponent
    from gecko_agents.studies import validation_magnitudes as vm

    lam = singularity_exponent(90.0, 0.5, "bonded")
    for fn, (E, w, s0, a) in ((vm.tang_pdms_fibril, (1.0, 0.05, 0.1, 100.0)),
                              (vm.tang_keratin_fibril, (2000.0, 0.05, 20.0, 10.0))):  # fmt: skip
        chi = float(ft.flaw_parameter(a, s0, E / 0.75, w))
        assert fn()["value"] == pytest.approx(0.83 * chi ** -(1.0 - lam), rel=1e-9)


def test_aksak_rows_take_the_centre_stress_uniform():
    """A 45° rim is not singular: the tip lets go from its centre at σ₀ (Φ = 1 exactly), or by
    Griffith's penny crack where a defect of radius c is put in the face."""
    from gecko_agents.studies import validation_magnitudes as vm

    for fn in (vm.aksak_phi_chi5, vm.aksak_phi_chi40, vm.aksak_gamma_beta11):
        assert fn()["value"] == pytest.approx(1.0, rel=1e-12)
    k, chi, c = vm.AKSAK, 40.0, 0.3
    Es = k["E"] / (1 - k["nu"] ** 2)
    w = k["sigma0"] ** 2 * k["a"] / (2 * math.pi * Es * chi)
    griffith = math.sqrt(math.pi * Es * w / (2 * c)) / k["sigma0"]
    assert vm.aksak_phi(1.1, chi, defect=c)["value"] == pytest.approx(min(1.0, griffith))


def test_del_campo_ratio_is_aksaks_eq3_with_the_packages_release_forces():
    """Under a sphere much larger than a fibril the array holds π·n·R·F²/k, so the ratio is
    (F_m/F_c)²·k_c/k_m; with Aksak et al.'s Γc = 0.74 for the mushroom and equal stiffnesses it
    is their e = (0.74/0.83)²β⁴χ^(2·0.4) = 2.27χ^0.8 (their printed constant)."""
    from gecko_agents.physics.wedge import singularity_exponent
    from gecko_agents.studies import validation_magnitudes as vm

    f = vm.del_campo_fibrils()
    assert f["ratio"] == pytest.approx((f["F_m"] / f["F_c"]) ** 2 * f["k_c"] / f["k_m"])
    d, chi = vm.DEL_CAMPO, 33.6  # Aksak et al.'s χ for these pillars
    beta = d["a_t"] / d["a"]
    assert f["F_m"] == pytest.approx(math.pi * d["a_t"] ** 2)  # σ₀ = 1 MPa over the flange
    alpha = 1.0 - singularity_exponent(90.0, 0.5, "bonded")
    F_c = 0.83 * chi**-alpha * math.pi * d["a"] ** 2
    assert f["F_c"] == pytest.approx(F_c, rel=2e-3)  # χ printed to 3 digits
    assert (0.74 / 0.83) ** 2 * beta**4 == pytest.approx(2.27, rel=2e-3)
    # The calibration point is reproduced exactly; the mushroom row is the ratio's number.
    assert vm.del_campo_mushroom()["value"] == pytest.approx(0.7 * f["ratio"])


@pytest.mark.slow
def test_paretkar_rows_tell_round_edges_from_end_flaps():
    """Below buckling both faces hold their pull-off (Kendall's with the study's σ₀, the
    Dugdale punch); pressed by 70 % of L the face that opens at its edge (round edge) holds
    nothing, the face kept bonded (end flaps) all of it."""
    from gecko_agents.physics import flaw_tolerance
    from gecko_agents.studies import pillar_designs as pd
    from gecko_agents.studies import validation_magnitudes as vm

    c = pd.params_for("flat_punch", 2.4, "flat").contact
    r = vm.PARETKAR["r"]
    F_K = float(flaw_tolerance.punch_pull_off(r, c.work_of_adhesion, c.E_star, c.sigma0))
    for edge in (True, False):
        assert vm.paretkar_pull_off(edge, vm.PARETKAR["below"]) == pytest.approx(F_K, rel=0.01)
    assert vm.paretkar_round_edges(press=0.7)["value"] == 0.0
    assert vm.paretkar_end_flaps(press=0.7)["value"] == pytest.approx(1.0, abs=0.01)
