"""The vehicle builder over HTTP: a spec anywhere a vehicle is, POST /v1/vehicles/build, the component library and
the acceptable payload table.

The expected records are the thesis's own presets (Tables 15, 16, 22, 23), restated in measurable terms in
tests/engine/test_builder.py; the expected SRTs are the presets' SRTs through POST /v1/srt.
"""

from __future__ import annotations

import csv
import io
from dataclasses import asdict

import pytest

from tests.engine.test_builder import RESTATED

from .conftest import a_spec


def spec_json(preset_id: str) -> dict:
    return asdict(RESTATED[preset_id])


def post(client, path, body, status=200, **headers):
    r = client.post(path, json=body, headers=headers)
    assert r.status_code == status, r.text
    return r


@pytest.mark.parametrize("preset_id", sorted(RESTATED))
def test_a_restated_thesis_table_builds_its_preset_and_its_srt(shared_client, preset_id):
    built = post(shared_client, "/v1/vehicles/build", {"spec": spec_json(preset_id)}).json()
    preset = shared_client.get(f"/v1/vehicles/{preset_id}").json()
    for name, value in built["vehicle"].items():
        assert value == pytest.approx(preset[name], rel=1e-12) if isinstance(value, float) else value == preset[name]
    assert set(built["derivation"]) >= set(built["vehicle"]) - {"chassis_torsional_stiffness_knm2_per_rad"}
    for d in built["derivation"].values():
        assert d["method"] in ("given", "computed", "library", "default") and d["source"]
    by_spec = post(shared_client, "/v1/srt", {"vehicle": {"spec": spec_json(preset_id)}}).json()["srt"]
    by_preset = post(shared_client, "/v1/srt", {"vehicle": preset_id}).json()["srt"]
    assert by_spec == pytest.approx(by_preset, rel=1e-12)


def test_a_spec_is_a_vehicle_everywhere(shared_client):
    spec = a_spec()
    record = post(shared_client, "/v1/vehicles/build", spec).json()["vehicle"]
    srt = post(shared_client, "/v1/srt", {"vehicle": record}).json()["srt"]
    assert post(shared_client, "/v1/srt", {"vehicle": spec}).json()["srt"] == srt
    speed = post(shared_client, "/v1/curve-speed", {"vehicle": spec, "radius_m": 100}).json()
    assert speed["max_speed_kmh"] == pytest.approx((127 * srt * 100) ** 0.5)  # Eq. 9.1 with the built SRT
    curves = [{"id": "C1", "radius_m": 150, "superelevation_percent": 4}]
    rows = post(shared_client, "/v1/alignments/assess", {"vehicles": [spec, record], "curves": curves}).json()
    a, b = (v["rows"][0]["srt_g"] for v in rows["vehicles"])
    assert a == b
    svg = post(shared_client, "/v1/plots/roll", {"vehicle": spec}).text
    assert "built vehicle" in svg


def test_a_spec_given_to_a_test_shares_nothing_with_another():
    """A test that changes the spec it was given (its tare, its tyre, one of its payloads) changes no other test's
    spec, no other payload of its own and not the schema's example (the OpenAPI document's example of the build
    request): the expected values are the example's literals (8,000 kg tare, 22,000 kg payload in two halves)."""
    from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC

    mine = a_spec(payloads=2)["spec"]
    mine["tare"]["mass_kg"] = 1.0
    mine["rear"]["tyre"]["id"] = "another"
    mine["payloads"][0]["mass_kg"] = 1.0
    assert mine["payloads"][1]["mass_kg"] == 11000.0
    theirs = a_spec()["spec"]
    assert theirs["tare"]["mass_kg"] == EXAMPLE_SPEC["tare"]["mass_kg"] == 8000.0
    assert theirs["rear"]["tyre"] == EXAMPLE_SPEC["rear"]["tyre"] == {"id": "thesis-michelin-xza"}
    assert theirs["payloads"][0]["mass_kg"] == EXAMPLE_SPEC["payloads"][0]["mass_kg"] == 22000.0


@pytest.mark.parametrize(
    ("change", "field", "words"),
    [
        ({"payloads": [{"mass_kg": 22000.0, "deck_height_m": 1.25, "load_height_m": 1.0}]},
         "vehicle.spec.payloads.0.load_height_m", "above the deck"),
        ({"tare": {"mass_kg": -8000.0, "cg_height_m": 1.2, "cg_from_kingpin_m": 6.5}},
         "vehicle.spec.tare.mass_kg", "above 0"),
        ({"rear": {"axles": 3, "tyres_per_axle": 3, "track_m": 1.86, "centre_from_kingpin_m": 10.0}},
         "vehicle.spec.rear.tyres_per_axle", "2"),
    ],
)  # fmt: skip
def test_a_spec_the_builder_refuses_names_the_field(shared_client, change, field, words):
    body = {"vehicle": {"spec": {**a_spec()["spec"], **change}}}
    p = post(shared_client, "/v1/srt", body, 422).json()
    assert p["errors"][0]["field"] == field and words in p["detail"]
    loc = p["errors"][0]["loc"]  # the path into the body, each name once (no union tag)
    assert loc[0] == "body" and ".".join(str(x) for x in loc[1:]) == field
    # the build endpoint names the same field, from its own body
    p = post(shared_client, "/v1/vehicles/build", body["vehicle"], 422).json()
    assert p["errors"][0]["field"] == field.removeprefix("vehicle.")


def test_an_unknown_component_lists_the_known_ones(shared_client):
    spec = a_spec()["spec"]
    spec["rear"] = {**spec["rear"], "suspension": {"type": "air-bag"}}
    p = post(shared_client, "/v1/vehicles/build", {"spec": spec}, 422).json()
    library = shared_client.get("/v1/components/suspensions").json()
    assert p["errors"][0]["field"] == "spec.rear.suspension.type"
    assert all(s["id"] in p["detail"] for s in library)


def test_every_library_value_has_its_source(shared_client):
    lib = shared_client.get("/v1/components").json()
    assert lib["tyres"] == shared_client.get("/v1/components/tyres").json()
    values = [t[k] for t in lib["tyres"] for k in ("loaded_radius_m", "stiffness_kn_per_m") if t[k]]
    values += [s[k] for s in lib["suspensions"] for k in ("stiffness_kn_per_m", "height_m", "spring_separation_m")]
    assert values and all(v["source"] and v["unit"] for v in values)
    for s in lib["suspensions"]:  # Eq. 2.11: k_theta = kLs b^2 / 2
        kls, b = s["stiffness_kn_per_m"]["value"], s["spring_separation_m"]["value"]
        assert s["roll_stiffness_knm_per_rad"] == pytest.approx(kls * b**2 / 2)
    # every library id builds
    for t in lib["tyres"]:
        spec = a_spec()["spec"]
        spec["rear"] = {**spec["rear"], "tyre": {"id": t["id"]}}
        post(shared_client, "/v1/vehicles/build", {"spec": spec})


def test_the_payload_table_meets_the_target_and_is_monotone(shared_client):
    body = {**a_spec(), "target_srt_g": 0.5, "rows": 4}
    out = post(shared_client, "/v1/vehicles/payload-table", body).json()
    target = 0.5
    for row in out["by_load_height"] + out["by_payload_mass"]:
        lim = row["limit"]
        if lim["status"] == "found":
            assert lim["srt_g"] == pytest.approx(target, abs=2e-4)
        else:
            assert lim["status"] == "always-met" and lim["srt_g"] >= target
    masses = [r["limit"]["value"] for r in out["by_load_height"]]
    heights = [r["limit"]["value"] for r in out["by_payload_mass"]]
    assert masses == sorted(masses, reverse=True) and heights == sorted(heights, reverse=True)  # higher -> lighter
    assert any(r["limit"]["status"] == "found" for r in out["by_load_height"])
    # the found limits check out: the vehicle at the limit has the target SRT (a spec with that payload)
    row = next(r for r in out["by_load_height"] if r["limit"]["status"] == "found")
    spec = a_spec()["spec"]
    spec["payloads"] = [
        {**spec["payloads"][0], "mass_kg": row["limit"]["value"], "load_height_m": row["load_height_m"]}
    ]
    assert post(shared_client, "/v1/srt", {"vehicle": {"spec": spec}}).json()["srt"] == pytest.approx(target, abs=2e-4)
    text = post(shared_client, "/v1/vehicles/payload-table", body, accept="text/csv").text
    table = list(csv.DictReader(io.StringIO(text)))
    assert [float(t["limit_value"]) for t in table if t["table"] == "by_load_height"] == masses


def test_a_schema_error_in_a_spec_has_its_path_once_in_loc(shared_client):
    spec = a_spec()["spec"]
    spec["rear"] = {**spec["rear"], "tyre": {"id": 5}}  # not a string
    p = post(shared_client, "/v1/srt", {"vehicle": {"spec": spec}}, 422).json()
    e = p["errors"][0]
    assert e["field"] == "vehicle.spec.rear.tyre.id"
    assert e["loc"] == ["body", "vehicle", "spec", "rear", "tyre", "id"]  # pydantic's union tag left out
