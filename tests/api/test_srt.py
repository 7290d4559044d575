"""POST /v1/srt through HTTP, against numbers from the thesis and closed forms worked by hand."""

from __future__ import annotations

import math

import pytest

BTRAIN = "table16-btrain"


def srt(client, **body):
    r = client.post("/v1/srt", json={"vehicle": BTRAIN, **body})
    assert r.status_code == 200, r.text
    return r.json()


def test_rigid_btrain_is_half_track_over_cg_height(shared_client):
    # Eq. 2.6 with Table 16: t/2 = 0.93 m, h = lr + ls + l12 = 0.499 + 0.205 + 1.356 = 2.06 m -> 0.4515 g;
    # Ch. 9 quotes 0.451 for the rigid B-train
    out = srt(shared_client, model="rigid")
    assert out["srt"] == pytest.approx(0.93 / 2.06, rel=1e-9)
    assert out["srt"] == pytest.approx(0.451, abs=5e-4)
    assert out["limit"] == "closed-form" and out["roll_angle_deg"] is None
    assert out["parameters"]["h"] == pytest.approx(2.06)


def test_rigid_bank_adds_the_superelevation_once(shared_client):
    # Eq. 2.8: SRT = t/2h + e, e = tan(bank) = 0.06 on a 6 % bank
    out = srt(shared_client, model="rigid-bank", road={"bank_percent": 6.0})
    assert out["srt"] == pytest.approx(0.93 / 2.06 + 0.06, rel=1e-9)


def test_rigid_lateral_offset_shortens_the_half_track(shared_client):
    # Eq. 2.6 with t/2 - d1: (0.93 - 0.1) / 2.06
    out = srt(shared_client, model="rigid", load={"lateral_offset_m": 0.1})
    assert out["srt"] == pytest.approx(0.83 / 2.06, rel=1e-9)


def test_3d_btrain_matches_chapter_9(shared_client):
    # Ch. 9: the developed 3D model gives SRT 0.3364 g for the B-train (stage 1, tires + suspension: 0.3792 g),
    # roll 5.8 deg; LLTf/LLTr = 0.7 at the limit. Tolerances: 2 % on the SRT, 1 deg on the roll.
    out = srt(shared_client)
    assert out["model"] == "3d" and out["stage"] == "full"
    assert out["srt"] == pytest.approx(0.3364, rel=0.02)
    first_stage = srt(shared_client, stage="tires-suspension")  # solved on its own: the same first stage
    assert out["stage_values"]["srt_ts"] == pytest.approx(first_stage["srt"], rel=1e-12)
    assert out["stage_values"]["srt_ts"] == pytest.approx(0.3792, rel=0.02)
    assert out["stage_values"]["srt_ts"] > out["srt"]  # the fifth wheel and chassis lower the threshold
    assert out["roll_angle_deg"] == pytest.approx(5.8, abs=1.0)
    assert out["limit"] == "rear-inner-lift-off"
    assert out["llt_rear"] == pytest.approx(1.0, abs=1e-6)
    assert out["llt_front"] == pytest.approx(0.7 * out["llt_rear"], abs=1e-3)
    tl = out["tire_loads"]
    assert tl["rear_inner_kn"] == pytest.approx(0.0, abs=1e-6)  # Fz19 = 0: the rear inner tire lifts off
    # all four loads together carry the weight: W = 355.22 kN (Table 16) on a flat road, ay normal to it
    total = tl["front_outer_kn"] + tl["front_inner_kn"] + tl["rear_outer_kn"] + tl["rear_inner_kn"]
    assert total == pytest.approx(355.22, rel=1e-6)
    # h2 below the static CG height 2.06 m (the body rolls), h1 below the half track 0.93 m
    assert out["cg_height_m"] < 2.06 and out["cg_lateral_m"] < 0.93
    assert out["curves"] is None
    assert out["engine_version"]


def test_tires_suspension_stage(shared_client):
    out = srt(shared_client, stage="tires-suspension")
    assert out["stage"] == "tires-suspension"
    assert out["srt"] == pytest.approx(0.3792, rel=0.02)  # Ch. 9 stage 1


@pytest.mark.parametrize(
    ("bank", "slope", "expected"),
    [
        # Table 17 (B-train, rear LLT limit 0.6, trailer angle 0): flat 0.202; bank 8 % 0.285
        (0.0, 0.0, 0.202),
        (8.0, 0.0, 0.285),
    ],
)
def test_rear_llt_limit_reproduces_table17(shared_client, bank, slope, expected):
    out = srt(shared_client, road={"bank_percent": bank, "slope_percent": slope}, rear_llt_limit=0.6)
    assert out["srt"] == pytest.approx(expected, rel=0.02)
    assert out["limit"] == "rear-llt-limit"
    assert out["llt_rear"] == pytest.approx(0.6, abs=1e-6)


def test_2d_model_on_table14(shared_client):
    # Ch. 7: the developed 2D model gives 0.376 g for the Table 14 semi-trailer (Adams: 0.374)
    r = shared_client.post("/v1/srt", json={"vehicle": "table14-semitrailer", "model": "2d"})
    assert r.status_code == 200, r.text
    out = r.json()
    assert out["srt"] == pytest.approx(0.376, rel=0.03)
    assert out["llt_front"] is None and out["tire_loads"]["front_outer_kn"] is None
    assert out["tire_loads"]["rear_outer_kn"] == pytest.approx(250.0, rel=1e-6)  # W of Table 14 on one group


def test_curves_run_from_rest_to_the_limit(shared_client):
    out = srt(shared_client, include_curves=True, curve_points=11)
    c = out["curves"]
    assert len(c["ay_g"]) == 11
    for name in ("fz_front_outer_kn", "fz_rear_inner_kn", "llt_front", "llt_rear", "roll_angle_deg", "cg_height_m"):
        assert len(c[name]) == 11
    assert c["ay_g"][0] == 0.0 and c["ay_g"][-1] == pytest.approx(out["srt"])
    assert c["llt_rear"][0] == pytest.approx(0.0, abs=1e-9) and c["llt_rear"][-1] == pytest.approx(1.0, abs=1e-6)
    assert c["roll_angle_deg"][-1] == pytest.approx(out["roll_angle_deg"])
    assert c["cg_lateral_m"][0] == pytest.approx(0.93)  # at rest the CG is at the half track
    assert all(b >= a for a, b in zip(c["roll_angle_deg"], c["roll_angle_deg"][1:], strict=False))


def test_closed_form_with_curves_is_a_422_naming_the_field(shared_client):
    r = shared_client.post("/v1/srt", json={"vehicle": BTRAIN, "model": "rill", "include_curves": True})
    assert r.status_code == 422
    assert r.json()["errors"][0]["field"] == "include_curves"


def test_full_record_and_the_preset_id_give_the_same_result(shared_client):
    record = shared_client.get(f"/v1/vehicles/{BTRAIN}").json()
    for k in ("id", "title", "source", "models"):
        record.pop(k)
    a = shared_client.post("/v1/srt", json={"vehicle": record})
    b = shared_client.post("/v1/srt", json={"vehicle": BTRAIN})
    assert a.json() == b.json()


def test_a_higher_cg_lowers_the_srt(shared_client):
    # Ch. 9 sensitivity: raising the CG 4 cm costs about 0.01 g
    base = srt(shared_client)["srt"]
    up = srt(shared_client, load={"vertical_offset_m": 0.04})["srt"]
    assert base - up == pytest.approx(0.01, abs=0.005)


@pytest.mark.parametrize("model", ["winkler", "rill", "chang", "gillespie", "navin"])
def test_every_closed_form_answers_below_the_rigid_bound(shared_client, model):
    out = srt(shared_client, model=model)
    # roll compliance moves the CG outward, so each model is below the rigid t/2h = 0.4515
    assert 0.2 < out["srt"] < 0.93 / 2.06
    assert math.isfinite(out["roll_angle_deg"]) and out["roll_angle_deg"] > 0


def test_engine_notes_are_passed_on(shared_client):
    # d2 = -1.5 m puts the B-train's CG at a - d2 = 4.5 m, behind the rear group (L = 4.26 m): the engine
    # answers and attaches a note about the kingpin uplift (Eq. 4.27)
    behind = srt(shared_client, load={"longitudinal_offset_m": -1.5})
    assert behind["notes"] and "behind the rear axle group" in behind["notes"][0]
    assert srt(shared_client)["notes"] == []
