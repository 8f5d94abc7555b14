"""The numbers behind the paper claims the studies call reproduced, against their closed forms
(not against the study's own formulas), and each claim's printed number is that number.

Closed forms (JKR 1971; Maugis 2000 §5.3), for R = 4 µm and w = 2√(γ1γ2):
Fc = 1.5πRw; the displacement-controlled end of contact carries −(5/9)Fc; at a fixed force,
a ∝ E*^(−1/3) and δ = a²/R − √(2πwa/E*) ∝ E*^(−2/3); δc = −(3/4)(π²w²R/E*²)^(1/3) ∝ w^(2/3).
"""

import math

import pytest

from gecko_agents.params import PAPER_TABLE1
from gecko_agents.studies import fig6_modulus, fig7_surface_energy, reproduce_paper
from gecko_agents.studies.common import num

# By hand: w = 2√(0.040·0.170) = 0.164924225 µN/µm, Fc = 1.5π·4·0.164924225 = 3.108748402 µN.
FC_PAPER = 3.108748402419646


def _fig6_rows():
    contacts = [PAPER_TABLE1.replace(**{"contact.E1": E}).contact for E in fig6_modulus.MODULI_MPA]
    return contacts, [fig6_modulus.contact_numbers(c) for c in contacts]


def test_fig6_push_off_claim_is_fc_for_every_modulus():
    contacts, rows = _fig6_rows()
    for r in rows:
        assert r["Fc_uN"] == pytest.approx(FC_PAPER, rel=1e-12)  # free of E*: exact
        assert r["force_end_uN"] == pytest.approx(-5 / 9 * FC_PAPER, rel=1e-12)
    claims, _ = fig6_modulus.build_claims(contacts, rows, rows)
    (push,) = [c for c in claims if c["figure"] == "Fig 6"]
    assert push["verdict"] == "reproduced"
    assert push["ours"].count(num(FC_PAPER, ".3f")) == 3
    assert push["ours"].count(num(-5 / 9 * FC_PAPER, ".3f")) == 3


def test_fig6b_deformation_claim_scales_as_e_star_to_the_minus_two_thirds():
    contacts, rows = _fig6_rows()
    E = [r["E_star_MPa"] for r in rows]
    for key in ("overlap_at_0_um", "overlap_at_1uN_um", "overlap_end_um"):
        for i in (1, 2):  # exact at a fixed force (module docstring): rounding only
            ratio = rows[i][key] / rows[0][key]
            assert ratio == pytest.approx((E[i] / E[0]) ** (-2 / 3), rel=1e-9), key
    claims, _ = fig6_modulus.build_claims(contacts, rows, rows)
    (deform,) = [c for c in claims if c["figure"] == "Fig 6b"]
    assert deform["verdict"] == "reproduced"
    for r in rows:
        assert num(r["overlap_at_0_um"], ".3f") in deform["ours"]


def test_fig6a_radius_trend_is_e_star_to_the_minus_one_third():
    """a(0.1 MPa)/a(10 MPa) at the same force is (E*(10)/E*(0.1))^(1/3) exactly (4.64 for
    E1 ×100, the floor term in E* shifting it by 6e-5), at −Fc, 0 and +1 µN alike."""
    contacts, rows = _fig6_rows()
    expected = (rows[2]["E_star_MPa"] / rows[0]["E_star_MPa"]) ** (1 / 3)
    assert expected == pytest.approx(100 ** (1 / 3), rel=1e-4)
    for key in ("a_pull_off_um", "a_at_0_um", "a_at_1uN_um"):
        assert rows[0][key] / rows[2][key] == pytest.approx(expected, rel=1e-12), key
    claims, _ = fig6_modulus.build_claims(contacts, rows, rows)
    (radius,) = [c for c in claims if c["figure"] == "Fig 6a"]
    assert radius["verdict"] == "trend reproduced"
    assert radius["ours"].startswith(f"a(0.1 MPa)/a(10 MPa) = {expected:.3f}, {expected:.3f}, ")


def test_fig7_claims_scale_as_w_and_w_to_the_two_thirds():
    """Fc ∝ w ∝ √γ1: γ1 4 → 100 mJ/m² multiplies it by exactly 5 and δc by 5^(2/3)."""
    rows = [
        fig7_surface_energy.contact_numbers(PAPER_TABLE1.replace(**{"contact.gamma1": g}).contact)
        for g in fig7_surface_energy.GAMMA1
    ]
    lo, mid, hi = rows
    assert mid["Fc_uN"] == pytest.approx(FC_PAPER, rel=1e-12)
    assert hi["Fc_uN"] / lo["Fc_uN"] == pytest.approx(5.0, rel=1e-12)
    assert hi["overlap_end_um"] / lo["overlap_end_um"] == pytest.approx(5 ** (2 / 3), rel=1e-12)
    claims, _ = fig7_surface_energy.build_claims(rows, rows)
    fig7a = next(c for c in claims if c["figure"] == "Fig 7a")
    assert "(×5.00)" in fig7a["ours"] and num(hi["Fc_uN"], ".3f") in fig7a["ours"]
    fig7b = next(c for c in claims if c["figure"] == "Fig 7b")
    assert f"(×{5 ** (2 / 3):.2f}" in fig7b["ours"]


def test_conclusion_4_floor_claims_against_fc_proportional_to_w():
    """Conclusion (4) on a rough 200-seta floor (quasi-static): a softer floor leaves E* within
    1e-4 (E2 ≫ E1) and the pull-off with it; halving γ2 scales every tip's Fc by √0.5 but
    not the load sharing exactly (δc ∝ w^(2/3) against the floor's σ): the array's pull-off
    falls by √0.5 within 1 % (measured 0.706 against 0.7071)."""
    (row,) = reproduce_paper.conclusion_rows(quick=True)
    assert row["verdict"] == "reproduced"
    ours = row["ours"]
    soft = float(ours.split("pull-off ×")[1].split(";")[0])
    weak = float(ours.split("mJ/m²: ×")[1].split(" ")[0])
    assert soft == pytest.approx(1.0, abs=1e-4)
    assert weak == pytest.approx(math.sqrt(0.5), rel=0.01)
