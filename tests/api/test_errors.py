"""Every error is an RFC 9457 problem (application/problem+json) that names the field and the reason."""

from __future__ import annotations

import pytest

import engine.models.threshold
from engine.errors import ConvergenceError, MechanismSingular

BTRAIN = "table16-btrain"


def problem(r, status):
    assert r.status_code == status, r.text
    assert r.headers["content-type"] == "application/problem+json"
    p = r.json()
    assert p["status"] == status and p["title"] and p["type"]
    return p


@pytest.mark.parametrize(
    ("body", "field", "reason"),
    [
        ({"vehicle": BTRAIN, "road": {"bank_percent": 25}}, "road.bank_percent", "less than or equal to 20"),
        ({"vehicle": BTRAIN, "model": "4d"}, "model", "'3d'"),
        ({"vehicle": BTRAIN, "rear_llt_limit": 0}, "rear_llt_limit", "greater than 0"),
        ({"vehicle": BTRAIN, "trailer_angle_deg": "ten"}, "trailer_angle_deg", "valid number"),
        ({"vehicle": BTRAIN, "load": {"overweight_percent": 80}}, "load.overweight_percent", "less than or equal"),
        ({"vehicle": BTRAIN, "colour": "red"}, "colour", "unknown field 'colour'"),
        ({"model": "3d"}, "vehicle", "Field required"),
        ({"vehicle": {"weight_kn": -1}}, "vehicle.weight_kn", "greater than 0"),
        ({"vehicle": BTRAIN, "include_curves": 1}, "include_curves", "valid boolean"),
    ],
)
def test_validation_errors_name_the_field_and_the_reason(shared_client, body, field, reason):
    p = problem(shared_client.post("/v1/srt", json=body), 422)
    assert p["type"] == "urn:rollover:problem:validation-error"
    fields = {e["field"]: e["message"] for e in p["errors"]}
    assert field in fields, fields
    assert reason in fields[field]


@pytest.mark.parametrize("raw", [b'{"radius_m": NaN, "srt": 0.3}', b'{"radius_m": 80, "srt": Infinity}'])
def test_non_finite_numbers_are_refused(shared_client, raw):
    r = shared_client.post("/v1/curve-speed", content=raw, headers={"content-type": "application/json"})
    p = problem(r, 422)
    assert p["errors"][0]["field"] in ("radius_m", "srt")


def test_malformed_json_is_a_400(shared_client):
    r = shared_client.post("/v1/srt", content=b'{"vehicle": ', headers={"content-type": "application/json"})
    p = problem(r, 400)
    assert p["type"] == "urn:rollover:problem:malformed-request"


def test_unknown_preset_in_a_post_is_a_404(shared_client):
    p = problem(shared_client.post("/v1/srt", json={"vehicle": "table99"}), 404)
    assert "table16-btrain" in p["known"]


def test_missing_parameter_for_the_model_is_a_422_naming_the_field(shared_client):
    # Table 14 is a 2D vehicle: the 3d model needs the front group it leaves null
    p = problem(shared_client.post("/v1/srt", json={"vehicle": "table14-semitrailer", "model": "3d"}), 422)
    assert p["type"] == "urn:rollover:problem:missing-parameter"
    assert p["errors"][0]["field"] == "vehicle.front_track_m"
    assert "front_track_m" in p["detail"]


def test_physically_impossible_record_is_a_422_naming_the_field(shared_client):
    record = shared_client.get(f"/v1/vehicles/{BTRAIN}").json()
    record["rear_track_m"] = 2.0  # differs from rear_axle_width_m 1.86: not representable (Sec. 4.1.1)
    p = problem(shared_client.post("/v1/srt", json={"vehicle": record}), 422)
    assert p["type"] == "urn:rollover:problem:invalid-vehicle"
    assert p["errors"][0]["field"] == "vehicle.rear_track_m"


def test_impossible_load_is_a_422_naming_the_field(shared_client):
    # d1 beyond the half track (0.93 m) puts the CG outside the tires
    p = problem(shared_client.post("/v1/srt", json={"vehicle": BTRAIN, "load": {"lateral_offset_m": 1.0}}), 422)
    assert p["type"] == "urn:rollover:problem:invalid-load"
    assert p["errors"][0]["field"] == "load.lateral_offset_m"


def test_a_model_that_ignores_the_bank_refuses_it(shared_client):
    body = {"vehicle": BTRAIN, "model": "rigid", "road": {"bank_percent": 4}}
    p = problem(shared_client.post("/v1/srt", json=body), 422)
    assert p["type"] == "urn:rollover:problem:invalid-road"
    assert p["errors"][0]["field"] == "road.bank_percent"


def test_stage_applies_to_3d_only(shared_client):
    body = {"vehicle": BTRAIN, "model": "2d", "stage": "tires-suspension"}
    p = problem(shared_client.post("/v1/srt", json=body), 422)
    assert p["errors"][0]["field"] == "stage"


@pytest.mark.parametrize(
    ("exc", "slug"),
    [
        (ConvergenceError("the geometry iteration did not converge", iterations=50, residual=1e-3), "no-convergence"),
        (MechanismSingular("Fz19 is not determined by the statics"), "mechanism-singular"),
    ],
)
def test_engine_arithmetic_errors_are_422_with_their_message(client, monkeypatch, exc, slug):
    def failing(*args, **kwargs):
        raise exc

    # the solve behind app.compute.coalescer
    monkeypatch.setattr(engine.models.threshold, "rollover_threshold", failing)
    p = problem(client.post("/v1/srt", json={"vehicle": BTRAIN}), 422)
    assert p["type"] == f"urn:rollover:problem:{slug}"
    assert p["detail"] == str(exc)


def test_an_unexpected_exception_is_a_500_problem_without_a_stack_trace(client, monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("secret internal state")

    monkeypatch.setattr(engine.models.threshold, "rollover_threshold", broken)
    p = problem(client.post("/v1/srt", json={"vehicle": BTRAIN}), 500)
    assert p["type"] == "urn:rollover:problem:internal-error"
    assert "secret" not in str(p) and "Traceback" not in str(p)


def test_wrong_method_is_a_405_problem(shared_client):
    r = shared_client.get("/v1/srt")
    p = problem(r, 405)
    assert r.headers["allow"] == "POST" and p["type"] == "about:blank"
