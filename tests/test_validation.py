"""The literature comparison (gecko_agents.studies.validation): every row carries a source, the
text read and a verdict; assumed parameters are marked; every scored row's *ours* is recomputed
here from its preset (closed forms by hand, agent rows through the studies' own functions) and
must equal what the study reports."""

import json
import math

import numpy as np
import pytest

from gecko_agents.analysis.limit_curve import critical_angle
from gecko_agents.params import literature as lit
from gecko_agents.studies import frictional_adhesion as fa
from gecko_agents.studies import misalignment as mis
from gecko_agents.studies import pad_peel, pull_speed, reproduce_paper
from gecko_agents.studies import validation as val
from gecko_agents.studies.validation_rows import ROWS

SCORED = [
    r
    for r in ROWS
    if r["ours"] is not None
    and r["compare"] is not None
    and (r["theirs_value"] is not None or r["compare"] == "trend")
]


def test_every_row_carries_a_source_what_was_read_and_marked_parameters():
    assert len({r["id"] for r in ROWS}) == len(ROWS)
    assert len(SCORED) >= 8
    for r in ROWS:
        assert r["source"] and r["theirs"] and r["measured"] and r["read_at"], r["id"]
        if r in SCORED:
            assert r["quote"] and r["ours"] in val.OURS, r["id"]
            assert r["params"], r["id"]  # every number ours uses is listed, cited or assumed
        else:
            assert r["unscored"], r["id"]  # says why it is not scored
        for p in r["params"]:
            assert p["status"] in ("cited", "assumed") and p["why"], (r["id"], p["name"])
            if p.get("range") is not None:
                lo, hi = p["range"]
                assert lo < hi, (r["id"], p["name"])


def test_numbers_quoted_as_theirs_appear_in_the_text_read():
    for r in SCORED:
        if r["theirs_value"] is not None and r["compare"] == "value":
            assert format(r["theirs_value"], "g") in r["quote"], r["id"]


# Closed forms, recomputed by hand from the preset (eq 17–20) ----------------------------------
def _rod(p):
    r, L, E, th = p.seta.r, p.seta.L, p.contact.E1, math.radians(p.seta.theta_deg)
    Ka = math.pi * r**2 * E / L
    Kp = 3 * math.pi * r**4 * E / (4 * L**3)
    return Ka, Kp, th


def test_seta_stiffness_is_eq20_of_the_preset():
    Ka, Kp, th = _rod(lit.AUTUMN2006_SETA)
    ky = Kp * Ka / (Kp * math.sin(th) ** 2 + Ka * math.cos(th) ** 2)
    assert val.seta_stiffness()["value"] == pytest.approx(ky, rel=1e-12)


def test_anisotropy_is_the_ratio_of_compliances_along_the_two_diagonals():
    Ka, Kp, th = _rod(lit.AUTUMN2006_SETA)
    n = np.array([math.cos(th), -math.sin(th)])
    t = np.array([math.sin(th), math.cos(th)])
    C = np.outer(n, n) / Ka + np.outer(t, t) / Kp  # compliance of the rod's tip

    def k(d):
        d = np.asarray(d) / np.linalg.norm(d)
        return 1.0 / (d @ C @ d)

    ratio = k((1, -1)) / k((-1, -1))
    assert val.seta_anisotropy()["value"] == pytest.approx(ratio, rel=1e-9)
    assert val.directional_stiffness(lit.AUTUMN2006_SETA, (0, 1)) == pytest.approx(
        lit.AUTUMN2006_SETA.Ky, rel=1e-12
    )


def test_array_modulus_is_a_bed_of_springs():
    p = lit.AUTUMN2006_SETA
    e = p.Ky * lit.TOKAY_SETAL_DENSITY * p.seta.L * math.sin(math.radians(p.seta.theta_deg))
    assert val.array_modulus()["value"] == pytest.approx(1e3 * e, rel=1e-12)


def test_sensitivity_recomputes_at_both_ends_of_each_range():
    row = next(r for r in ROWS if r["id"] == "autumn2006a_k_seta")
    sens = {s["name"]: s["ours_at_ends"] for s in val.sensitivity(row, quick=True)}
    assert set(sens) == {"E", "r", "L", "theta"}
    assert sens["E"][1] / sens["E"][0] == pytest.approx(1750 / 1450, rel=1e-9)  # K ∝ E
    assert sens["r"][1] / sens["r"][0] == pytest.approx(5.0**4, rel=0.01)  # bending: K ∝ r⁴
    assert sens["L"][0] / sens["L"][1] == pytest.approx((130 / 30) ** 3, rel=0.01)  # ∝ 1/L³


def test_verdict_rules():
    base = {"compare": "value", "theirs_value": 10.0, "scatter": 1.0, "cause": ""}
    assert val.verdict(base, {"value": 10.5}, [])[0] == "agrees within the stated scatter"
    assert val.verdict(base, {"value": 13.0}, [])[0] == "disagrees"
    band = [{"status": "assumed", "ours_at_ends": [1.0, 100.0]}]
    assert val.verdict(base, {"value": 13.0}, band)[0] == "not comparable"
    cited = [{"status": "cited", "ours_at_ends": [1.0, 100.0]}]
    assert val.verdict(base, {"value": 13.0}, cited)[0] == "disagrees"
    trend = {**base, "compare": "trend", "scatter": None}
    assert val.verdict(trend, {"value": 2.0, "trend": 1.0}, [])[0] == "trend agrees"
    assert val.verdict(trend, {"value": 0.5, "trend": -0.5}, [])[0] == "disagrees"
    assert val.verdict(trend, {"value": 1.005, "trend": 0.005}, [])[0] == "disagrees"
    assert val.verdict({**base, "compare": None, "unscored": "x"}, None, [])[0] == "not scored"
    flat = next(r for r in ROWS if r["id"] == "kendall1971_flat_punch")
    assert val.flat_punch_ours() is None
    assert val.evaluate(flat, quick=True)["verdict"] == val.NOT_SCORED
    # Filled in later: one function gives ours; the row scores once their value is read.
    filled = {"value": 5.0, "text": "5 µN"}
    assert val.verdict(flat, filled, [])[0] == val.NOT_SCORED
    read = {**flat, "theirs_value": 5.2, "scatter": 0.5}
    assert val.verdict(read, filled, [])[0] == "agrees within the stated scatter"


def test_gravish_row_is_the_pull_speed_study_with_crack_kinetics():
    slow, fast = (pull_speed.run_point(1.0, v, 1, False)["pull_off_per_seta_uN"]
                  for v in (0.01, 0.1))  # fmt: skip
    assert val.gravish_rate(True)["value"] == pytest.approx(fast / slow, rel=1e-9)


def test_reproduce_beyond_writes_the_literature_comparison_beside_the_report(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(reproduce_paper, "run_scenarios", lambda base, args, log: {})
    monkeypatch.setattr(reproduce_paper, "conclusion_rows", lambda quick: [])
    monkeypatch.setattr(reproduce_paper, "run_scenario", lambda *a: calls.append(a[:2]))
    reproduce_paper.main(["--quick", "--beyond", "--jobs", "1", "--out", str(tmp_path)])
    assert calls == [("validation", ["--out", str(tmp_path), "--quick"])]
    calls.clear()
    reproduce_paper.main(["--quick", "--jobs", "1", "--out", str(tmp_path)])
    assert calls == []


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
        assert r["verdict"] in val.VERDICTS + (val.NOT_SCORED,), r["id"]
        assert r["source"] and r["reason"], r["id"]
        if r["verdict"] != val.NOT_SCORED:
            assert r["quote"] and math.isfinite(r["ours_value"]), r["id"]
    assert sum(r["verdict"] != val.NOT_SCORED for r in rows.values()) >= 8


@pytest.mark.slow
def test_closed_form_rows_in_the_report(report):
    _, rows = report
    assert rows["autumn2006a_k_seta"]["ours_value"] == pytest.approx(lit.AUTUMN2006_SETA.Ky)


@pytest.mark.slow
def test_frictional_adhesion_row(report):
    rel = [fa.run_point("spatula", 10.0, -fa.DRAG, b)[0] for b in (45.0, 90.0)]
    alpha = critical_angle([r["shear_at_release_uN"] for r in rel],
                           [r["adhesion_at_release_uN"] for r in rel])  # fmt: skip
    assert report[1]["autumn2006b_frictional_adhesion"]["ours_value"] == pytest.approx(alpha)


@pytest.mark.slow
def test_gillies_rows(report):
    s, j = (fa.run_point(t, 10.0, -fa.DRAG, 90.0)[0]["pull_off_uN"] for t in ("spatula", "sphere"))
    assert report[1]["gillies2014_smooth"]["ours_value"] == pytest.approx(s / j)
    s, j = (fa.patch_point(t, 1.0, 4, -1)["pull_off_per_seta_uN"] for t in ("spatula", "sphere"))
    assert report[1]["gillies2014_rough"]["ours_value"] == pytest.approx(s / j)


@pytest.mark.slow
def test_booth_row(report):
    k = lit.BOOTH2018_STIFF_MOUNT.backing.handle_stiffness
    stiff, compliant = (mis.run_point(200, 1.413, kh, 0.8)["pull_off_over_NFc"]
                        for kh in (k, k / lit.BOOTH2018_COMPLIANCE_RATIO))  # fmt: skip
    assert report[1]["booth2018_misalignment"]["ours_value"] == pytest.approx(compliant / stiff)


@pytest.mark.slow
def test_kendall_row(report):
    row, _ = pad_peel.run_point(200, 90.0, 0.5, 0.4)
    assert report[1]["kendall1975_peel"]["ours_value"] == pytest.approx(row["ratio_to_kendall"])


@pytest.mark.slow
def test_kim_sitti_row(report):
    from gecko_agents import protocol
    from gecko_agents.model import Model

    held = []
    for p in (lit.KIM_SITTI2007_THIN, lit.KIM_SITTI2007_THICK):
        m = Model(p.replace(**{"array.count": 40}), seed=1)
        h = m.run(protocol.preload_pull(0.2 * 40 * m.Fc, speed=0.05), progress=False)
        held.append(max(h["strip_setae_force_y_uN"]))
    assert report[1]["kim_sitti2007_backing"]["ours_value"] == pytest.approx(held[0] / held[1])


@pytest.mark.slow
def test_buckling_row_is_the_pillar_study_pressed_below_and_past_euler(report):
    from gecko_agents import protocol
    from gecko_agents.model import Model
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": 1})
    held, peaks = [], []
    for eps in (0.01, 0.2):
        h = Model(p, n_sim=1, seed=pd.SEED).run(
            protocol.press_pull(eps * p.seta.L, speed=pd.SPEED), progress=False
        )
        held.append(h.peak_pull_off)
        peaks.append(float(h["force_normal_uN"].max()))
    P_E = pd.euler_load("flat_punch", p.seta.L)
    assert peaks[0] < P_E < peaks[1]  # below and past buckling, as the row says
    row = report[1]["yague_isla2015_buckling"]
    assert row["ours_value"] == pytest.approx(held[1] / held[0])
    assert row["verdict"] == "disagrees"  # a loss of a few % where theirs is most of it


# The rows are data (gecko_agents/data/literature/validation.toml) ------------------------------
def test_rows_are_read_from_the_shipped_data_file(tmp_path):
    import tomllib

    from gecko_agents.data import LITERATURE_ROWS
    from gecko_agents.studies.validation_rows import load_rows

    assert load_rows(LITERATURE_ROWS) == ROWS
    pyproject = tomllib.loads((LITERATURE_ROWS.parents[3] / "pyproject.toml").read_text())
    globs = pyproject["tool"]["setuptools"]["package-data"]["gecko_agents.data"]
    data_dir = LITERATURE_ROWS.parents[1]
    assert any(LITERATURE_ROWS in data_dir.glob(g) for g in globs)  # it ships in the wheel
    bad = tmp_path / "rows.toml"
    bad.write_text('[[rows]]\nid = "x"\nsource = "s"\n')
    with pytest.raises(ValueError, match="'x' lacks the field"):
        load_rows(bad)
    one = ROWS[0]
    text = "".join(
        "[[rows]]\n" + "".join(f"{k} = {json.dumps(one[k])}\n" for k in
                               ("id", "source", "read_at", "quote", "measured", "theirs", "kind",
                                "cause"))
        for _ in range(2)
    )  # fmt: skip
    bad.write_text(text)
    with pytest.raises(ValueError, match="appears twice"):
        load_rows(bad)
