"""POST /v1/curve-speed (Eq. 9.1) and POST /v1/min-radius (Eqs. 9.2-9.3, Table 21) through HTTP."""

from __future__ import annotations

import math

import pytest

BTRAIN = "table16-btrain"


def post(client, path, body, status=200):
    r = client.post(path, json=body)
    assert r.status_code == status, r.text
    return r.json()


# ------------------------------------------------------------------------------------------ Eq. 9.1


@pytest.mark.parametrize(
    ("srt", "radius", "speed"),
    [
        # Table 18 (R = 80 m): rigid-like 0.4485 -> 67.5 km/h, 3D 0.3364 -> 58.5, 0.2528 -> 50.7
        (0.4485, 80.0, 67.5),
        (0.3364, 80.0, 58.5),
        (0.2528, 80.0, 50.7),
        # Table 20 (R = 120 m): USA 0.23 -> 59.2, New Zealand 0.22 -> 57.9, proposed model flat with rear
        # LLT 0.6: 0.202 -> 55.5, downhill 12 %, trailer angle 30 deg: 0.172 -> 51.2
        (0.23, 120.0, 59.2),
        (0.22, 120.0, 57.9),
        (0.202, 120.0, 55.5),
        (0.172, 120.0, 51.2),
    ],
)
def test_curve_speed_from_a_given_srt_matches_tables_18_and_20(shared_client, srt, radius, speed):
    out = post(shared_client, "/v1/curve-speed", {"radius_m": radius, "srt": srt})
    assert out["max_speed_kmh"] == pytest.approx(speed, abs=0.05)  # the tables round to 0.1 km/h
    assert out["srt"] == srt and out["srt_source"] == "given" and out["srt_result"] is None


def test_curve_speed_from_an_srt_request_uses_the_srt_on_that_bank(shared_client):
    # a banked curve: the SRT computed for the 8 % bank already contains the bank (Eq. 6.18), so
    # V = sqrt(127 SRT(bank) R) -- never sqrt(127 (SRT + e) R)
    road = {"bank_percent": 8.0, "slope_percent": 0.0}
    srt_banked = post(shared_client, "/v1/srt", {"vehicle": BTRAIN, "road": road, "rear_llt_limit": 0.6})["srt"]
    out = post(
        shared_client, "/v1/curve-speed", {"radius_m": 120.0, "vehicle": BTRAIN, "road": road, "rear_llt_limit": 0.6}
    )
    assert out["srt_source"] == "computed"
    assert out["srt"] == srt_banked == out["srt_result"]["srt"]
    assert out["max_speed_kmh"] == pytest.approx(math.sqrt(127 * srt_banked * 120.0), rel=1e-12)
    assert out["max_speed_kmh"] < math.sqrt(127 * (srt_banked + 0.08) * 120.0) - 5  # the bank not added again
    # Table 17: 0.285 g on an 8 % bank (LLT 0.6) -> about 65.9 km/h at 120 m
    assert out["max_speed_kmh"] == pytest.approx(math.sqrt(127 * 0.285 * 120.0), rel=0.01)


def test_curve_speed_from_the_3d_btrain_is_table18(shared_client):
    out = post(shared_client, "/v1/curve-speed", {"radius_m": 80.0, "vehicle": BTRAIN})
    assert out["max_speed_kmh"] == pytest.approx(58.5, rel=0.01)  # Table 18 with the engine's SRT (+-2 %)


def test_curve_speed_refuses_srt_together_with_road(shared_client):
    p = post(shared_client, "/v1/curve-speed", {"radius_m": 80, "srt": 0.3, "road": {"bank_percent": 6}}, 422)
    assert p["errors"][0]["field"] == "road"
    assert "bank" in p["errors"][0]["message"]


def test_curve_speed_needs_srt_or_vehicle(shared_client):
    p = post(shared_client, "/v1/curve-speed", {"radius_m": 80}, 422)
    assert p["errors"][0]["field"] == "srt"


@pytest.mark.parametrize("radius", [0, -5])
def test_curve_speed_refuses_a_non_positive_radius(shared_client, radius):
    p = post(shared_client, "/v1/curve-speed", {"radius_m": radius, "srt": 0.3}, 422)
    assert p["errors"][0]["field"] == "radius_m"


# --------------------------------------------------------------------------------- Eqs. 9.2 and 9.3

# Table 21 (AASHTO 2003 / DNER 1999 / DNIT 2009): design speed -> side-friction range (low, high)
TABLE21 = {
    30: (0.17, 0.28),
    40: (0.17, 0.23),
    50: (0.16, 0.19),
    60: (0.15, 0.17),
    70: (0.14, 0.15),
    80: (0.14, 0.14),
    90: (0.13, 0.14),
    100: (0.12, 0.13),
    110: (0.11, 0.12),
    120: (0.09, 0.11),
}


@pytest.mark.parametrize("speed", sorted(TABLE21))
@pytest.mark.parametrize("bound", ["low", "high", "mid"])
def test_side_friction_comes_from_table21(shared_client, speed, bound):
    lo, hi = TABLE21[speed]
    f = {"low": lo, "high": hi, "mid": (lo + hi) / 2}[bound]
    out = post(
        shared_client,
        "/v1/min-radius",
        {"design_speed_kmh": speed, "superelevation_percent": 6.0, "srt": 0.35, "side_friction_bound": bound},
    )
    assert out["side_friction"] == pytest.approx(f, abs=1e-12)
    assert out["side_friction_source"] == f"table21-{bound}"
    assert out["aashto_min_radius_m"] == pytest.approx(speed**2 / (127 * (0.06 + f)), rel=1e-12)  # Eq. 9.2


def test_side_friction_is_interpolated_linearly_between_tabulated_speeds(shared_client):
    # Table 21, low bound: 65 km/h is halfway between 60 (0.15) and 70 (0.14) -> 0.145; 75 km/h -> 0.14
    for speed, f in ((65.0, 0.145), (75.0, 0.14), (115.0, 0.10)):
        body = {"design_speed_kmh": speed, "superelevation_percent": 0, "srt": 0.3, "design_standard": "thesis-table21"}
        out = post(shared_client, "/v1/min-radius", body)
        assert out["side_friction"] == pytest.approx(f, abs=1e-12)
        assert out["side_friction_source"] == "table21-low"
    # AASHTO 2018 Table 3-7 (metric), the default: 55 km/h between 50 (0.19) and 60 (0.17) -> 0.18
    out = post(shared_client, "/v1/min-radius", {"design_speed_kmh": 55, "superelevation_percent": 0, "srt": 0.3})
    assert out["side_friction"] == pytest.approx(0.18, abs=1e-12)
    assert out["side_friction_source"] == "aashto-2018" and out["design_standard"] == "aashto-2018"


def test_side_friction_bound_alone_selects_table21(shared_client):
    # the requests of the previous version (a bound, no standard) keep their meaning: Table 21 at that bound
    body = {"design_speed_kmh": 60, "superelevation_percent": 8, "srt": 0.3, "side_friction_bound": "high"}
    out = post(shared_client, "/v1/min-radius", body)
    assert out["design_standard"] == "thesis-table21" and out["side_friction_source"] == "table21-high"
    assert out["side_friction"] == 0.17  # Table 21, 60 km/h, high end of 0.15-0.17
    p = post(shared_client, "/v1/min-radius", {**body, "design_standard": "dnit-1999"}, 422)
    assert p["errors"][0]["field"] == "side_friction_bound" and "thesis-table21" in p["detail"]


def test_min_radius_by_hand(shared_client):
    # V = 60 km/h, e = 8 %, f = 0.15 (Table 21 low), SRT = 0.285 g (Table 17, 8 % bank, LLT 0.6):
    # Eq. 9.2: 60^2 / (127 (0.08 + 0.15)) = 123.25 m; Eq. 9.3: 60^2 / (127 0.285) = 99.46 m -> side friction governs
    body = {"design_speed_kmh": 60, "superelevation_percent": 8, "srt": 0.285, "design_standard": "thesis-table21"}
    out = post(shared_client, "/v1/min-radius", body)
    assert out["side_friction_min_radius_m"] == pytest.approx(3600 / (127 * 0.23), rel=1e-12)
    assert out["side_friction_min_radius_m"] == pytest.approx(123.25, abs=0.01)
    assert out["aashto_min_radius_m"] == out["side_friction_min_radius_m"]  # the deprecated name, same value
    assert out["rollover_min_radius_m"] == pytest.approx(3600 / (127 * 0.285), rel=1e-12)
    assert out["governing_min_radius_m"] == out["side_friction_min_radius_m"]
    assert out["governed_by"] == "side-friction"


@pytest.mark.parametrize(
    ("standard", "speed", "e_max", "published"),
    [
        # AASHTO 2018 Table 3-7 (metric), e_max 8 %, as reproduced by NYSDOT HDM Exhibit M2-14: 60 km/h -> 113 m,
        # 100 km/h -> 394 m (rounded to the metre)
        ("aashto-2018", 60, 8, 113),
        ("aashto-2018", 100, 8, 394),
        # DNER/DNIT IPR-706 Quadro 5.4.3.2, e_max 8 %: 80 km/h -> 230 m, 120 km/h -> 595 m (rounded to 5 m)
        ("dnit-1999", 80, 8, 230),
        ("dnit-1999", 120, 8, 595),
    ],
)
def test_side_friction_radius_at_e_max_rounds_to_the_published_minimum(
    shared_client, standard, speed, e_max, published
):
    body = {"design_speed_kmh": speed, "superelevation_percent": e_max, "srt": 0.35, "design_standard": standard}
    out = post(shared_client, "/v1/min-radius", body)
    step = 1 if standard == "aashto-2018" else 5  # each table's own rounding
    assert step * round(out["side_friction_min_radius_m"] / step) == published


def test_rollover_governs_for_a_low_srt(shared_client):
    # SRT 0.172 g (Table 20, downhill 12 %, trailer angle 30 deg) at 80 km/h, e = 10 %, f = 0.14:
    # Eq. 9.2 -> 6400 / (127 0.24) = 209.97 m; Eq. 9.3 -> 6400 / (127 0.172) = 292.99 m
    out = post(shared_client, "/v1/min-radius", {"design_speed_kmh": 80, "superelevation_percent": 10, "srt": 0.172})
    assert out["rollover_min_radius_m"] == pytest.approx(6400 / (127 * 0.172), rel=1e-12)
    assert out["governing_min_radius_m"] == out["rollover_min_radius_m"]
    assert out["governed_by"] == "rollover"


def test_given_side_friction_is_used_outside_table21(shared_client):
    out = post(
        shared_client,
        "/v1/min-radius",
        {"design_speed_kmh": 140, "superelevation_percent": 8, "srt": 0.3, "side_friction": 0.08},
    )
    assert out["side_friction"] == 0.08 and out["side_friction_source"] == "given"
    assert out["aashto_min_radius_m"] == pytest.approx(140**2 / (127 * 0.16), rel=1e-12)


def test_speed_outside_table21_without_side_friction_is_a_422(shared_client):
    p = post(shared_client, "/v1/min-radius", {"design_speed_kmh": 140, "superelevation_percent": 8, "srt": 0.3}, 422)
    assert p["errors"][0]["field"] == "design_speed_kmh"
    assert "aashto-2018" in p["detail"] and "20-120 km/h" in p["detail"]
    body = {"design_speed_kmh": 25, "superelevation_percent": 8, "srt": 0.3, "design_standard": "dnit-1999"}
    p = post(shared_client, "/v1/min-radius", body, 422)
    assert p["errors"][0]["field"] == "design_speed_kmh" and "30-120 km/h" in p["detail"]
    p = post(shared_client, "/v1/min-radius", {**body, "design_standard": "thesis-table21"}, 422)
    assert "Table 21" in p["detail"]


def test_min_radius_computes_the_srt_on_the_superelevation(shared_client):
    # the SRT for Eq. 9.3 is the one on the curve's bank: superelevation 8 % -> road.bank_percent 8
    banked = post(shared_client, "/v1/srt", {"vehicle": BTRAIN, "road": {"bank_percent": 8.0}, "rear_llt_limit": 0.6})[
        "srt"
    ]
    out = post(
        shared_client,
        "/v1/min-radius",
        {"design_speed_kmh": 60, "superelevation_percent": 8, "vehicle": BTRAIN, "rear_llt_limit": 0.6},
    )
    assert out["srt"] == banked and out["srt_source"] == "computed"
    assert out["srt_result"]["srt"] == banked
    assert out["rollover_min_radius_m"] == pytest.approx(3600 / (127 * banked), rel=1e-12)


def test_min_radius_takes_no_bank_besides_the_superelevation(shared_client):
    # the SRT's bank is the superelevation: the schema's road has only the slope (a bank is refused by the spec)
    body = {"design_speed_kmh": 60, "superelevation_percent": 8, "vehicle": BTRAIN, "road": {"bank_percent": 8}}
    p = post(shared_client, "/v1/min-radius", body, 422)
    assert p["errors"][0]["field"] == "road.bank_percent"
    assert p["errors"][0]["message"].startswith("unknown field 'bank_percent'")
    road = shared_client.get("/openapi.json").json()["components"]["schemas"]["SlopeIn"]
    assert set(road["properties"]) == {"slope_percent"} and road["additionalProperties"] is False
    # a slope is taken as given: the SRT is the one on the 8 % bank with that grade
    body["road"] = {"slope_percent": -4}
    out = post(shared_client, "/v1/min-radius", body)
    srt = post(shared_client, "/v1/srt", {"vehicle": BTRAIN, "road": {"bank_percent": 8, "slope_percent": -4}})
    assert out["srt"] == srt["srt"]


def test_min_radius_with_an_unknown_preset_is_a_404(shared_client):
    body = {"design_speed_kmh": 60, "superelevation_percent": 8, "vehicle": "no-such-truck"}
    p = post(shared_client, "/v1/min-radius", body, 404)
    assert p["type"].endswith("unknown-preset")
