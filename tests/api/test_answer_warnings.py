"""Every JSON answer computed from a typed vehicle record carries its input warnings (issue 40 item 5).

A light trailer's record typed with ``weight_kn`` 50 reads plausibly as 50 kN (a 5.1 t trailer) and as 50 t typed in
the wrong unit (490.3 kN): neither reading can be refused (:data:`engine.vehicle.plausibility.RANGES`), so every
answer computed from it names the field as the user typed it and both readings, as ``POST /v1/srt`` does
(tests/api/test_plausibility.py). A preset in the same request warns of nothing.
"""

from __future__ import annotations

import pytest

from app.routes.schemas import EXAMPLE_GEOJSON
from app.settings import Settings
from tests.jobs.conftest import run

from .conftest import a_spec, make_client

G = 9.80665  # standard gravity [m/s^2] (CGPM 1901): 50 t typed as kN reads as 50 x g kN
CURVES = [
    {"id": "A", "radius_m": 180.0, "superelevation_percent": 6.0, "posted_speed_kmh": 60.0},
    {"id": "B", "radius_m": 400.0, "superelevation_percent": 4.0, "posted_speed_kmh": 80.0},
]


def light_trailer(client, weight_kn: float = 50.0) -> dict:
    """The thesis's Table 23 semitrailer as a typed record, its weight a light trailer's (or tonnes typed as kN)."""
    record = client.get("/v1/vehicles/table23-semitrailer").json()
    for k in ("id", "title", "source", "models"):
        record.pop(k)
    return {**record, "weight_kn": weight_kn}


def assert_weight_warning(warnings: list[dict], field: str, weight: float = 50.0) -> None:
    (w,) = warnings
    assert w["field"] == field and w["value"] == weight and w["unit"] == "kN"
    assert w["other_unit"] == "tonnes" and w["other_reading"] == pytest.approx(weight * G, rel=1e-12)
    assert f"{weight:g} kN as given" in w["message"] and f"{weight:g} tonnes typed as kN" in w["message"]


def test_an_alignment_names_the_vehicle_and_the_field_per_vehicle(shared_client):
    body = {"vehicles": ["table16-btrain", light_trailer(shared_client)], "curves": CURVES}
    r = shared_client.post("/v1/alignments/assess", json=body)
    assert r.status_code == 200, r.text
    first, second = r.json()["vehicles"]
    assert first["warnings"] == []
    assert_weight_warning(second["warnings"], "vehicles[1].weight_kn")


def test_the_warning_names_the_field_as_typed_whatever_was_cached_first(shared_client):
    # the same record as `vehicle` and as `vehicles[0]`: the same computation, two different field names; and the
    # record built from a spec would warn of nothing. Each answer must name its own (the warnings are in the key).
    record = light_trailer(shared_client)
    r1 = shared_client.post("/v1/alignments/assess", json={"vehicles": [record], "curves": CURVES})
    r2 = shared_client.post("/v1/alignments/assess", json={"vehicle": record, "curves": CURVES})
    assert_weight_warning(r1.json()["vehicles"][0]["warnings"], "vehicles[0].weight_kn")
    assert_weight_warning(r2.json()["vehicles"][0]["warnings"], "vehicle.weight_kn")


def test_a_weight_plausible_only_in_kn_warns_of_nothing(shared_client):
    body = {"vehicle": light_trailer(shared_client, 392.13), "curves": CURVES}  # Table 23's own weight
    r = shared_client.post("/v1/alignments/assess", json=body)
    assert r.status_code == 200 and r.json()["vehicles"][0]["warnings"] == [], r.text


def test_a_route_names_the_field_per_vehicle(shared_client):
    body = {
        "vehicles": [light_trailer(shared_client), "table16-btrain"],
        "geojson": EXAMPLE_GEOJSON,
        "superelevation_percent": 6.0,
    }
    r = shared_client.post("/v1/routes/assess", json=body)
    assert r.status_code == 200, r.text
    first, second = r.json()["vehicles"]
    assert_weight_warning(first["warnings"], "vehicles[0].weight_kn")
    assert second["warnings"] == []


@pytest.mark.parametrize("part_size", [1, 1000])
def test_an_alignment_job_carries_them_byte_for_byte_as_the_synchronous_answer(part_size):
    with make_client(Settings(jobs_part_size=part_size)) as c:
        req = {"vehicles": ["table16-btrain", light_trailer(c)], "curves": CURVES}
        location, status = run(c, "alignments.assess", req)
        assert status["status"] == "done"
        job = c.get(location + "/result")
        sync = c.post("/v1/alignments/assess", json=req)
    assert job.status_code == sync.status_code == 200
    assert job.content == sync.content and job.headers["etag"] == sync.headers["etag"]
    assert_weight_warning(job.json()["vehicles"][1]["warnings"], "vehicles[1].weight_kn")


def test_a_route_job_carries_them_byte_for_byte_as_the_synchronous_answer():
    with make_client() as c:
        req = {"vehicles": [light_trailer(c)], "geojson": EXAMPLE_GEOJSON, "superelevation_percent": 6.0}
        location, status = run(c, "routes.assess", req)
        assert status["status"] == "done"
        job = c.get(location + "/result")
        sync = c.post("/v1/routes/assess", json=req)
    assert job.status_code == sync.status_code == 200 and job.content == sync.content
    assert_weight_warning(job.json()["vehicles"][0]["warnings"], "vehicles[0].weight_kn")


def test_the_limits_carry_them(shared_client):
    body = {"vehicle": light_trailer(shared_client), "parameter": "cg_height_above_chassis_m"}
    r = shared_client.post("/v1/srt/limits", json=body)
    assert r.status_code == 200, r.text
    assert_weight_warning(r.json()["warnings"], "vehicle.weight_kn")
    preset = shared_client.post("/v1/srt/limits", json={**body, "vehicle": "table23-semitrailer"})
    assert preset.status_code == 200 and preset.json()["warnings"] == [], preset.text


SWEEP_GRID = {"bank_percent": [0.0, 4.0], "overweight_percent": [0.0, 10.0]}


def test_a_sweep_carries_them_and_its_job_the_same_bytes():
    with make_client() as c:
        req = {"vehicle": light_trailer(c), "grid": SWEEP_GRID}
        sync = c.post("/v1/srt/sweep", json=req)
        assert sync.status_code == 200, sync.text
        assert_weight_warning(sync.json()["warnings"], "vehicle.weight_kn")
        location, status = run(c, "srt.sweep", req)
        assert status["status"] == "done"
        job = c.get(location + "/result")
    assert job.status_code == 200 and job.content == sync.content


def test_the_advisory_speed_names_each_vehicle(shared_client):
    curve = {"radius_m": 150.0, "superelevation_percent": 6.0, "deflection_deg": 40.0, "posted_speed_kmh": 100.0}
    body = {**curve, "vehicles": ["table16-btrain", light_trailer(shared_client)]}
    r = shared_client.post("/v1/advisory-speed", json=body)
    assert r.status_code == 200, r.text
    assert_weight_warning(r.json()["warnings"], "vehicles[1].weight_kn")


@pytest.mark.parametrize(
    ("path", "extra"),
    [
        ("/v1/srt", {}),
        ("/v1/curve-speed", {"radius_m": 200.0}),
        ("/v1/min-radius", {"design_speed_kmh": 80.0, "superelevation_percent": 6.0}),
    ],
)
def test_a_record_built_from_a_spec_and_the_same_record_typed_answer_apart(path, extra):
    """The same engine record, once built from a spec (its weight from masses in kg: nothing to warn of) and once
    typed as a record (50 kN, or 50 t?): each answer says its own, whichever was asked (and cached) first."""
    with make_client() as c:
        # the schema's example semitrailer lightened to a 3 t tare and a 2 t payload
        spec = a_spec()["spec"]
        spec["tare"]["mass_kg"], spec["payloads"][0]["mass_kg"] = 3000.0, 2000.0
        built = c.post("/v1/vehicles/build", json={"spec": spec})
        assert built.status_code == 200, built.text
        record = built.json()["vehicle"]
        assert 34.33 < record["weight_kn"] < 101.9  # a light trailer's weight: plausible in kN and in tonnes
        from_spec = c.post(path, json={"vehicle": {"spec": spec}, **extra})
        typed = c.post(path, json={"vehicle": record, **extra})
    assert from_spec.status_code == typed.status_code == 200, (from_spec.text, typed.text)

    def warnings(r):
        out = r.json()
        return out["warnings"] if "warnings" in out else out["srt_result"]["warnings"]

    assert warnings(from_spec) == []
    assert_weight_warning(warnings(typed), "vehicle.weight_kn", record["weight_kn"])


def test_a_saved_record_and_a_fleet_member_warn_where_the_request_gives_them(tmp_path):
    key = "owner-key-" + "a" * 24
    settings = Settings(cache_backend="memory", database_url=f"sqlite:///{tmp_path / 'c.db'}", api_keys=key)
    auth = {"Authorization": f"Bearer {key}"}
    with make_client(settings) as c:
        saved = c.post("/v1/vehicles", json={"title": "light trailer", "vehicle": light_trailer(c)}, headers=auth)
        assert saved.status_code == 201, saved.text
        vid = saved.json()["id"]
        fleet = c.post("/v1/fleets", json={"title": "f", "vehicles": ["table16-btrain", vid]}, headers=auth)
        assert fleet.status_code == 201, fleet.text
        srt = c.post("/v1/srt", json={"vehicle": vid}, headers=auth)
        alignment = c.post("/v1/alignments/assess", json={"fleet": fleet.json()["id"], "curves": CURVES}, headers=auth)
    assert srt.status_code == alignment.status_code == 200, (srt.text, alignment.text)
    assert_weight_warning(srt.json()["warnings"], "vehicle.weight_kn")
    first, second = alignment.json()["vehicles"]
    assert first["warnings"] == [] and second["saved_vehicle_id"] == vid
    assert_weight_warning(second["warnings"], "fleet[1].weight_kn")


def test_a_combinations_last_unit_record_warns_named_inside_the_combination(shared_client):
    # Table 15's tractor-semitrailer typed in full, its last unit's record (used by the 3D model) weighing 50
    combination = shared_client.get("/v1/combinations/tractor-semitrailer-table15").json()["combination"]
    combination["last_unit_record"]["weight_kn"] = 50.0
    vehicle = {"combination": combination}
    srt = shared_client.post("/v1/srt", json={"vehicle": vehicle, "model": "3d"})
    assert srt.status_code == 200, srt.text
    assert_weight_warning(srt.json()["warnings"], "vehicle.combination.last_unit_record.weight_kn")
    body = {"vehicles": ["table16-btrain", vehicle], "model": "3d", "curves": CURVES}
    alignment = shared_client.post("/v1/alignments/assess", json=body)
    assert alignment.status_code == 200, alignment.text
    assert_weight_warning(
        alignment.json()["vehicles"][1]["warnings"], "vehicles[1].combination.last_unit_record.weight_kn"
    )


def test_a_routes_geojson_names_them_as_a_foreign_member(shared_client):
    body = {"vehicles": ["table16-btrain", light_trailer(shared_client)], "geojson": EXAMPLE_GEOJSON,
            "superelevation_percent": 6.0}  # fmt: skip
    r = shared_client.post("/v1/routes/assess", json=body, headers={"accept": "application/geo+json"})
    assert r.status_code == 200 and r.json()["type"] == "FeatureCollection", r.text
    assert_weight_warning(r.json()["warnings"], "vehicles[1].weight_kn")
