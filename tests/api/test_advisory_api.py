"""POST /v1/advisory-speed through HTTP: the plaque's speed and rounding, the methods and their labels, the rollover
speed against POST /v1/curve-speed (the same Eq. 9.1 by another route), the W1-13 rule, caching, and the 422s.

Expected numbers: TxDOT Direct Method (x 0.97, +1 mph, down to 5 mph); the W1-13 rule as stated in the answer;
Table 2C-4 bands (5/10/15/20 mph) as transcribed; the request bounds (10-130 km/h, 15 ft/s^2, 5 mph / 10 km/h).
"""

from __future__ import annotations

import pytest

BTRAIN = "table16-btrain"
MPH = 1.609344
CURVE = {"radius_m": 150.0, "superelevation_percent": 6.0, "deflection_deg": 40.0, "posted_speed_kmh": 100.0}


def post(client, body, status=200, path="/v1/advisory-speed"):
    r = client.post(path, json=body)
    assert r.status_code == status, r.text
    return r


def test_answer_shape_rounding_and_labels(client):
    r = post(client, {**CURVE, "vehicle": BTRAIN})
    assert r.headers["x-cache"] == "miss" and r.headers["etag"].startswith('"')
    out = r.json()
    assert out["advisory_speed_mph"] % 5 == 0
    assert out["advisory_speed_kmh"] == pytest.approx(out["advisory_speed_mph"] * MPH)
    methods = {(m["id"], m["vehicle"]): m for m in out["methods"]}
    design = methods[("design-method", None)]
    assert design["speed_kmh"] is None and design["verified"] is False and "unverified" in design["source"]
    assert out["governed_by"] == "ball-bank-2009" and methods[("ball-bank-2009", None)]["legacy"] is True
    # +1 mph, down to 5 mph, of the governing method's speed
    raw_mph = methods[("ball-bank-2009", None)]["speed_kmh"] / MPH
    assert out["advisory_speed_mph"] == 5 * ((raw_mph + 1) // 5)
    # Table 2C-4 band of the posted-advisory difference
    diff = 100.0 / MPH - out["advisory_speed_mph"]
    assert out["treatment"]["speed_difference_mph"] == pytest.approx(diff)
    assert ("chevron alignment signs" in out["treatment"]["devices"]) is (diff >= 20)
    assert "unverified" in out["treatment"]["source"]
    assert post(client, {**CURVE, "vehicle": BTRAIN}).headers["x-cache"] == "hit"


def test_direct_method_governs_when_a_car_speed_is_measured(client):
    out = post(client, {**CURVE, "measured_car_speed_kmh": 44.0 / 0.97 * MPH}).json()
    assert out["governed_by"] == "txdot-direct"
    assert out["advisory_speed_mph"] == 45.0  # 44.0 mph trucks, +1, down to 45
    assert out["truck_rollover_warning"]["vehicles"] == []


def test_rollover_speed_is_curve_speeds_and_the_w1_13_rule(client):
    body = {**CURVE, "grade_percent": -4.0, "vehicles": [BTRAIN, "table23-semitrailer"], "rollover_margin_kmh": 0.0}
    out = post(client, body).json()
    shown = out["advisory_speed_kmh"]
    for check in out["truck_rollover_warning"]["vehicles"]:
        ref = body["vehicles"][check["vehicle"]]
        cs = post(
            client,
            {"radius_m": 150.0, "vehicle": ref, "road": {"bank_percent": 6.0, "slope_percent": -4.0}},
            path="/v1/curve-speed",
        ).json()
        assert check["rollover_speed_kmh"] == pytest.approx(cs["max_speed_kmh"], rel=1e-12)
        assert check["recommended"] is (check["rollover_speed_kmh"] < shown)
    # a margin wider than the rollover speed's lead over the advisory recommends the warning
    lead = min(c["rollover_speed_kmh"] for c in out["truck_rollover_warning"]["vehicles"]) - shown
    wide = post(client, {**body, "rollover_margin_kmh": min(50.0, max(lead + 1.0, 0.0))}).json()
    assert wide["truck_rollover_warning"]["recommended"] is (lead + 1.0 <= 50.0)
    assert "this service's rule" in wide["truck_rollover_warning"]["rule"]


def test_metric_plaque(client):
    out = post(client, {**CURVE, "units": "metric", "increment": 10}).json()
    assert out["advisory_speed_mph"] is None and out["increment"] == 10
    assert out["advisory_speed_kmh"] % 10 == 0


@pytest.mark.parametrize(
    ("extra", "field"),
    [
        ({"posted_speed_kmh": 131.0}, "posted_speed_kmh"),
        ({"posted_speed_kmh": 9.0}, "posted_speed_kmh"),
        ({"tangent_speed_kmh": 140.0}, "tangent_speed_kmh"),
        ({"deceleration_mps2": 4.6}, "deceleration_mps2"),  # above 15 ft/s^2 = 4.572 m/s^2
        ({"increment": 10}, "increment"),  # us: 5 mph
        ({"units": "metric", "increment": 5}, "increment"),  # metric: 10 km/h
        ({"vehicle": BTRAIN, "vehicles": [BTRAIN]}, "vehicles"),
    ],
)
def test_refusals_name_the_field(client, extra, field):
    r = post(client, {**CURVE, **extra}, status=422)
    assert any(e["field"] == field for e in r.json()["errors"]), r.text


def test_a_vehicle_the_model_cannot_use_is_named_by_its_place_in_vehicles(client):
    # the 3d model needs the front axle of table14-semitrailer, which its record leaves null
    r = post(client, {**CURVE, "vehicles": [BTRAIN, "table14-semitrailer"]}, status=422)
    assert r.json()["errors"][0]["field"] == "vehicles.1.front_track_m"
