"""The committed openapi/openapi.json: same as the app serves, valid, and carrying what clients rely on."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from openapi_spec_validator import validate

from app.main import create_app
from app.vehicle_forms.schemas import METADATA_FIELDS, VehicleRecord
from engine.vehicle.record import Vehicle

from .conftest import ROOT

SPEC_PATH = ROOT / "openapi" / "openapi.json"
COMMITTED = json.loads(SPEC_PATH.read_text(encoding="utf-8"))

OPERATIONS = {
    ("get", "/v1/vehicles"): "vehicles-list_vehicles",
    ("get", "/v1/vehicles/{id}"): "vehicles-get_vehicle",
    ("get", "/v1/combinations"): "combinations-list_combinations",
    ("get", "/v1/combinations/{id}"): "combinations-get_combination_preset",
    ("post", "/v1/combinations/build"): "combinations-build_combination",
    ("post", "/v1/srt"): "srt-compute_srt",
    ("post", "/v1/srt/limits"): "srt-limits",
    ("post", "/v1/srt/sweep"): "srt-sweep",
    ("post", "/v1/curve-speed"): "road-curve_speed",
    ("post", "/v1/advisory-speed"): "road-advisory_speed",
    ("post", "/v1/min-radius"): "road-min_radius",
    ("post", "/v1/vehicles/build"): "builder-build_vehicle",
    ("post", "/v1/vehicles/payload-table"): "builder-payload_table",
    ("get", "/v1/components"): "builder-components",
    ("get", "/v1/components/tyres"): "builder-tyres",
    ("get", "/v1/components/suspensions"): "builder-suspensions",
    ("get", "/v1/design-standards"): "standards-list_design_standards",
    ("get", "/v1/design-standards/{id}"): "standards-get_design_standard",
    ("post", "/v1/superelevation"): "standards-superelevation",
    ("post", "/v1/superelevation/table"): "standards-superelevation_table",
    ("post", "/v1/alignments/assess"): "alignments-assess",
    ("post", "/v1/alignments/assess/csv"): "alignments-assess_csv",
    ("post", "/v1/alignments/assess/landxml"): "alignments-assess_landxml",
    ("post", "/v1/alignments/assess/ifc"): "alignments-assess_ifc",
    ("post", "/v1/routes/assess"): "routes-assess",
    ("post", "/v1/routes/assess/gpx"): "routes-assess_gpx",
    ("post", "/v1/routes/assess/geojson"): "routes-assess_geojson",
    ("post", "/v1/jobs"): "jobs-submit",
    ("get", "/v1/jobs/{job_id}"): "jobs-status",
    ("get", "/v1/jobs/{job_id}/result"): "jobs-result",
    ("delete", "/v1/jobs/{job_id}"): "jobs-cancel",
    ("post", "/v1/plots/tire-loads"): "plots-tire_loads",
    ("post", "/v1/plots/llt"): "plots-llt",
    ("post", "/v1/plots/roll"): "plots-roll",
    ("post", "/v1/plots/cg-path"): "plots-cg_path",
    ("post", "/v1/plots/min-radius"): "plots-min_radius",
    ("post", "/v1/plots/speed-profile"): "plots-speed_profile",
    ("get", "/v1/models"): "models-list_models",
    ("get", "/healthz"): "health-healthz",
    ("get", "/metrics"): "health-metrics",
    ("post", "/v1/vehicles"): "catalog-create_vehicle",
    ("get", "/v1/vehicles/saved"): "catalog-list_saved_vehicles",
    ("put", "/v1/vehicles/{id}"): "catalog-replace_vehicle",
    ("delete", "/v1/vehicles/{id}"): "catalog-delete_vehicle",
    ("post", "/v1/fleets"): "catalog-create_fleet",
    ("get", "/v1/fleets"): "catalog-list_fleets",
    ("get", "/v1/fleets/{id}"): "catalog-get_fleet",
    ("put", "/v1/fleets/{id}"): "catalog-replace_fleet",
    ("delete", "/v1/fleets/{id}"): "catalog-delete_fleet",
    ("post", "/v1/dynamics/lane-change"): "dynamics-lane_change",
    ("post", "/v1/dynamics/frequency-response"): "dynamics-frequency_response",
    ("post", "/v1/dynamics/pulse-steer"): "dynamics-pulse_steer",
    ("post", "/v1/dynamics/stability"): "dynamics-stability",
    ("post", "/v1/dynamics/steady-turn"): "dynamics-steady_turn",
    ("post", "/v1/dynamics/low-speed-turn"): "dynamics-low_speed_turn",
    ("post", "/v1/pbs"): "pbs-pbs",
    ("post", "/v1/dynamics/plots/lane-change"): "dynamics-plot_lane_change",
    ("post", "/v1/dynamics/plots/frequency-response"): "dynamics-plot_frequency_response",
    ("post", "/v1/dynamics/plots/low-speed-turn"): "dynamics-plot_low_speed_turn",
}


def test_committed_spec_is_what_the_app_serves(client):
    served = client.get("/openapi.json").json()
    assert served == COMMITTED, "openapi/openapi.json drifted: run python scripts/export_openapi.py"
    # and the export script writes it byte for byte (sorted keys, stable)
    check = subprocess.run(
        [sys.executable, "scripts/export_openapi.py", "--check"], cwd=ROOT, capture_output=True, text=True
    )
    assert check.returncode == 0, check.stderr


def test_spec_is_valid_openapi():
    validate(COMMITTED)


def test_operation_ids_are_stable():
    found = {(m, p): op["operationId"] for p, item in COMMITTED["paths"].items() for m, op in item.items()}
    assert found == OPERATIONS


@pytest.mark.parametrize(("method", "path"), sorted(OPERATIONS))
def test_every_operation_declares_problem_details(method, path):
    responses = COMMITTED["paths"][path][method]["responses"]
    errors = {code: r for code, r in responses.items() if int(code) >= 400}
    assert "500" in errors
    if method == "post":
        assert {"400", "422"} <= set(errors)
        if OPERATIONS[(method, path)] not in LOOK_UP_NOTHING:
            assert "404" in errors
    for r in errors.values():
        assert list(r["content"]) == ["application/problem+json"]
        assert r["content"]["application/problem+json"]["schema"] == {"$ref": "#/components/schemas/Problem"}


#: POST operations that look nothing up (no preset, no saved vehicle): no 404
LOOK_UP_NOTHING = {"catalog-create_vehicle", "standards-superelevation", "standards-superelevation_table"}

#: computed operations without a vehicle -> the request model of their JSON body
ROAD_ONLY = {
    "/v1/superelevation": "SuperelevationRequest",
    "/v1/superelevation/table": "SuperelevationTableRequest",
    "/v1/vehicles/build": "BuildRequest",
    "/v1/combinations/build": "BuildCombinationRequest",
    "/v1/vehicles/payload-table": "PayloadTableRequest",
}
#: every computed operation with a vehicle (ETag, X-Cache) -> the request model of its JSON body
COMPUTED = {
    "/v1/srt": "SrtRequest",
    "/v1/curve-speed": "CurveSpeedRequest",
    "/v1/min-radius": "MinRadiusRequest",
    "/v1/advisory-speed": "AdvisorySpeedRequest",
    "/v1/srt/limits": "LimitsRequest",
    "/v1/srt/sweep": "SweepRequest",
    "/v1/alignments/assess": "AlignmentRequest",
    "/v1/routes/assess": "RouteRequest",
    "/v1/plots/tire-loads": "PlotRequest",
    "/v1/plots/llt": "PlotRequest",
    "/v1/plots/roll": "PlotRequest",
    "/v1/plots/cg-path": "PlotRequest",
    "/v1/plots/min-radius": "MinRadiusPlotRequest",
}
#: the dynamics operations (they take a combination: their examples use the B-double of Table 16's trailer)
DYNAMICS = {
    "/v1/dynamics/lane-change": "LaneChangeRequest",
    "/v1/dynamics/frequency-response": "FrequencyResponseRequest",
    "/v1/dynamics/pulse-steer": "PulseSteerRequest",
    "/v1/dynamics/stability": "StabilityRequest",
    "/v1/dynamics/steady-turn": "SteadyTurnRequest",
    "/v1/dynamics/low-speed-turn": "LowSpeedTurnRequest",
    "/v1/pbs": "PbsRequest",
    "/v1/dynamics/plots/lane-change": "LaneChangeRequest",
    "/v1/dynamics/plots/frequency-response": "FrequencyResponseRequest",
    "/v1/dynamics/plots/low-speed-turn": "LowSpeedTurnRequest",
}
#: the operations that answer an SVG image
PLOTS = {p for p in COMPUTED | DYNAMICS if "/plots/" in p}
#: the operations that answer CSV on `Accept: text/csv` (and say `Vary: Accept`)
TABLES = {
    "/v1/srt/sweep",
    "/v1/alignments/assess",
    "/v1/alignments/assess/csv",
    "/v1/alignments/assess/landxml",
    "/v1/alignments/assess/ifc",
    "/v1/superelevation/table",
    "/v1/vehicles/payload-table",
    "/v1/routes/assess",
    "/v1/routes/assess/gpx",
    "/v1/routes/assess/geojson",
}


@pytest.mark.parametrize("path", sorted(COMPUTED | ROAD_ONLY | DYNAMICS))
def test_computed_operations_declare_etag_and_x_cache(path):
    headers = COMMITTED["paths"][path]["post"]["responses"]["200"]["headers"]
    assert set(headers) == ({"ETag", "X-Cache", "Vary"} if path in TABLES else {"ETag", "X-Cache"})


@pytest.mark.parametrize("path", sorted(TABLES))
def test_table_operations_declare_json_and_csv(path):
    content = COMMITTED["paths"][path]["post"]["responses"]["200"]["content"]
    geojson = {"application/geo+json"} if path.startswith("/v1/routes/") else set()  # the route's curves for a GIS
    assert set(content) == {"application/json", "text/csv"} | geojson
    if geojson:
        assert content["application/geo+json"]["schema"] == {"$ref": "#/components/schemas/RouteCurves"}


@pytest.mark.parametrize("path", sorted(PLOTS))
def test_plot_operations_declare_svg_only(path):
    content = COMMITTED["paths"][path]["post"]["responses"]["200"]["content"]
    assert set(content) == {"image/svg+xml"}


@pytest.mark.parametrize("name", sorted(set(COMPUTED.values())))
def test_every_request_model_has_a_btrain_example(name):
    examples = COMMITTED["components"]["schemas"][name]["examples"]
    assert any(e.get("vehicle") == "table16-btrain" for e in examples)


@pytest.mark.parametrize("name", sorted(DYNAMICS.values()))
def test_every_dynamics_request_model_has_a_btrain_combination_example(name):
    examples = COMMITTED["components"]["schemas"][name]["examples"]
    assert any(e.get("vehicle") == "btrain-table16" for e in examples)


def test_examples_are_accepted_by_the_app(shared_client):
    paths = {name: path for path, name in (COMPUTED | ROAD_ONLY | DYNAMICS).items()}
    for name, path in paths.items():
        for example in COMMITTED["components"]["schemas"][name]["examples"]:
            r = shared_client.post(path, json=example)
            assert r.status_code == 200, (name, example, r.text)


def test_every_field_names_its_unit_and_thesis_symbol():
    missing = []
    for name, schema in COMMITTED["components"]["schemas"].items():
        if name in ("Problem", "FieldError"):  # RFC 9457 members, not physical quantities
            continue
        for field, prop in schema.get("properties", {}).items():
            text = prop.get("description", "")
            if "Unit:" not in text or "Thesis symbol:" not in text:
                missing.append(f"{name}.{field}")
    assert missing == []


def test_a_field_of_one_meaning_has_one_description():
    """The plaques' `units` (an option of every request that gives advisory speeds, and said back in one curve's
    answer and in an assessment's `advisory`) and the answers' `increment` mean the same wherever they are: each
    has one description (they read "The plaque's units." in one answer and "The plaques' units." in the other)."""
    schemas = create_app().openapi()["components"]["schemas"]
    units = {
        name: schema["properties"]["units"]["description"]
        for name, schema in schemas.items()
        if schema.get("properties", {}).get("units", {}).get("enum") == ["us", "metric"]
    }
    assert {"AdvisorySpeedRequest", "AdvisorySpeedResult", "AlignmentRequest", "AdvisoryOut"} <= set(units)
    assert len(set(units.values())) == 1, units
    answers = ("AdvisorySpeedResult", "AdvisoryOut")
    assert len({schemas[name]["properties"]["increment"]["description"] for name in answers}) == 1


def test_vehicle_record_schema_has_every_engine_field():
    # the record is the engine's Vehicle plus the ignored preset metadata: a new engine field must appear here
    engine_fields = set(Vehicle.__dataclass_fields__)
    assert set(VehicleRecord.model_fields) - set(METADATA_FIELDS) == engine_fields
    record = COMMITTED["components"]["schemas"]["VehicleRecord"]
    assert set(record["properties"]) - set(METADATA_FIELDS) == engine_fields
    assert record["additionalProperties"] is False


def test_create_app_is_deterministic():
    assert create_app().openapi() == create_app().openapi()
