"""The typed requests of the single answers (SRT, curve speed, minimum radius, plots, superelevation, builds, payload
tables: app/compute/resolved.py). Their keys are the keys of the dicts the services hashed before the types (written
out here from the requests, as the services wrote them), checked through the ETag each endpoint answers, so no cached
answer or ETag changes; their JSON form reads back as the same object; and a request field missing from a key is
caught (the key guarantee: everything an answer depends on is in it)."""

from __future__ import annotations

import dataclasses

import orjson
import pytest

from app.compute.cache import cache_key
from app.compute.resolved import (
    ResolvedBuild,
    ResolvedCase,
    ResolvedCurveSpeed,
    ResolvedMinRadius,
    ResolvedPayloadTable,
    ResolvedSrt,
    ResolvedSuperelevation,
    ResolvedSuperelevationTable,
    ResolvedSweep,
)
from app.plots.schemas import MinRadiusPlotRequest
from app.road.schemas import CurveSpeedRequest, MinRadiusRequest
from app.road.standards_schemas import SuperelevationRequest, SuperelevationTableRequest
from app.settings import Settings
from app.srt.schemas import SrtRequest
from app.srt.service import resolve_case, resolve_srt
from app.srt.sweep_schemas import SweepRequest
from app.srt.sweep_service import resolve_sweep
from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC, BuildRequest
from app.vehicles.payload_schemas import PayloadTableRequest
from app.vehicles.resolve import resolve_request_given, vehicle_preset
from engine.case import Road

BTRAIN = "table16-btrain"
TARGETS = {"general": 0.35, "nz": 0.4}


def _vehicle(req):
    """The request's engine vehicle, resolved as the service resolves it."""
    return resolve_request_given(req).vehicles[0].vehicle


def _srt_dict(req, *, targets=None, curves: bool = False, points: int | None = None, road: Road | None = None) -> dict:
    """``srt_key`` as the services wrote it: the case's dict, the curve fields, the targets and what they are judged
    on."""
    return {
        **resolve_case(req, _vehicle(req), road=road).to_dict(),
        "include_curves": curves,
        "curve_points": points if curves else None,
        "targets": Settings().default_targets() if targets is None else targets,
        "targets_judged_on": "level_road_srt",
    }


def _etag(client, path: str, body: dict) -> str:
    response = client.post(path, json=body)
    assert response.status_code == 200, response.text
    return response.headers["etag"].strip('"')


def test_the_srt_key_is_the_dict_it_replaces(client):
    body = {"vehicle": BTRAIN, "road": {"bank_percent": 4.0}, "include_curves": True, "curve_points": 21}
    req = SrtRequest.model_validate(body)
    assert _etag(client, "/v1/srt", body) == cache_key("srt", _srt_dict(req, curves=True, points=21))
    body = {"vehicle": BTRAIN, "curve_points": 21, "targets": TARGETS}  # without curves the points change nothing
    req = SrtRequest.model_validate(body)
    assert _etag(client, "/v1/srt", body) == cache_key("srt", _srt_dict(req, targets=TARGETS))
    assert _etag(client, "/v1/srt", body | {"curve_points": 41}) == cache_key("srt", _srt_dict(req, targets=TARGETS))


def test_the_curve_speed_and_min_radius_keys_are_the_dicts_they_replace(client):
    body = {"vehicle": BTRAIN, "radius_m": 150.0, "road": {"bank_percent": 3.0}}
    req = CurveSpeedRequest.model_validate(body)
    old = {"radius_m": 150.0, "srt": None, "srt_request": _srt_dict(req)}
    assert _etag(client, "/v1/curve-speed", body) == cache_key("curve-speed", old)
    given = {"srt": 0.4, "radius_m": 150.0}
    assert _etag(client, "/v1/curve-speed", given) == cache_key("curve-speed", given | {"srt_request": None})

    body = {"vehicle": BTRAIN, "design_speed_kmh": 80.0, "superelevation_percent": 6.0, "targets": TARGETS}
    req = MinRadiusRequest.model_validate(body)
    old = {
        "design_speed_kmh": 80.0,
        "superelevation_percent": 6.0,
        "side_friction": None,
        "design_standard": req.design_standard,
        "side_friction_bound": None,
        "srt": None,
        "srt_request": _srt_dict(req, targets=TARGETS, road=Road(bank_percent=6.0)),  # on the curve's bank
    }
    assert _etag(client, "/v1/min-radius", body) == cache_key("min-radius", old)


def test_the_plot_keys_are_the_dicts_they_replace(client):
    body = {"vehicle": BTRAIN, "curve_points": 31}
    req = SrtRequest.model_validate(body)
    old = {"srt_request": _srt_dict(req, curves=True, points=31), "figure": "roll", "label": BTRAIN}
    old["svg_version"] = 2
    assert _etag(client, "/v1/plots/roll", body) == cache_key("plot-roll", old)
    body = {"vehicle": BTRAIN, "superelevation_percent": 4.0, "speed_min_kmh": 40, "speed_max_kmh": 80}
    response = client.post("/v1/plots/min-radius", json=body)
    assert response.status_code == 200, response.text
    req = SrtRequest.model_validate({"vehicle": BTRAIN})
    old = {
        "srt_request": _srt_dict(req, road=Road(bank_percent=4.0)),
        "speeds_kmh": list(MinRadiusPlotRequest.model_validate(body).speeds),
        "design_standard": "aashto-2018",
        "side_friction_bound": None,
        "label": BTRAIN,
        "svg_version": 2,
    }
    assert response.headers["etag"].strip('"') == cache_key("plot-min-radius", old)


def test_the_superelevation_keys_are_the_request_dumps_they_replace(client):
    body = {"design_speed_kmh": 70.0, "radius_m": 250.0, "max_superelevation_percent": 8.0}
    old = SuperelevationRequest.model_validate(body).model_dump(mode="json")
    assert _etag(client, "/v1/superelevation", body) == cache_key("superelevation", old)
    body = {"design_speed_kmh": 70.0, "max_superelevation_percent": 8.0, "radii_m": [200.0, 400.0]}
    old = SuperelevationTableRequest.model_validate(body).model_dump(mode="json")
    assert _etag(client, "/v1/superelevation/table", body) == cache_key("superelevation-table", old)


def test_the_build_and_payload_table_keys_are_the_dicts_they_replace(client):
    body = {"spec": EXAMPLE_SPEC}
    old = {"spec": BuildRequest.model_validate(body).engine_spec().to_dict()}
    assert _etag(client, "/v1/vehicles/build", body) == cache_key("vehicle-build", old)
    body = {"spec": EXAMPLE_SPEC, "target_srt_g": 0.45, "rows": 3}
    req = PayloadTableRequest.model_validate(body)
    old = req.model_dump(mode="json", exclude={"spec", "combination_spec"}) | {"spec": req.engine_spec().to_dict()}
    assert _etag(client, "/v1/vehicles/payload-table", body) == cache_key("payload-table", old)


@pytest.mark.parametrize(
    ("request_type", "resolved_type", "renamed"),
    [
        (SuperelevationRequest, ResolvedSuperelevation, {}),
        (SuperelevationTableRequest, ResolvedSuperelevationTable, {}),
        (PayloadTableRequest, ResolvedPayloadTable, {"spec": "build", "combination_spec": "build"}),
    ],
)
def test_every_field_of_a_request_is_in_its_key(request_type, resolved_type, renamed):
    """A field added to the request and forgotten in its typed form would give two answers one key: caught here."""
    fields = {f.name for f in dataclasses.fields(resolved_type)}
    assert {renamed.get(name, name) for name in request_type.model_fields} <= fields


def _single_samples() -> list:
    req = SrtRequest.model_validate({"vehicle": BTRAIN, "road": {"slope_percent": 2.0}})
    srt = resolve_srt(resolve_case(req, _vehicle(req)), TARGETS, include_curves=True, curve_points=11)
    payload = PayloadTableRequest.model_validate({"spec": EXAMPLE_SPEC, "target_srt_g": 0.45, "rows": 3})
    return [
        srt.base,
        srt,
        ResolvedCurveSpeed(radius_m=100.0, srt=None, srt_request=srt),
        ResolvedMinRadius(
            design_speed_kmh=60.0,
            superelevation_percent=4.0,
            side_friction=None,
            design_standard="aashto-2018",
            side_friction_bound=None,
            srt=0.35,
            srt_request=None,
        ),
        ResolvedBuild(spec=payload.engine_spec()),
        ResolvedPayloadTable(
            build=ResolvedBuild(spec=payload.engine_spec()),
            unit_index=None,
            target_srt_g=0.45,
            payload_index=0,
            load_heights_m=(1.0, 2.0),
            payload_masses_kg=None,
            rows=3,
        ),
    ]


@pytest.mark.parametrize("index", range(6), ids=["case", "srt", "curve-speed", "min-radius", "build", "payload"])
def test_a_single_answers_json_form_reads_back_as_the_same_request(index):
    resolved = _single_samples()[index]
    if isinstance(resolved, ResolvedPayloadTable):  # its JSON form is flat, as the request's: not read back
        assert resolved.to_json_dict()["spec"] == resolved.build.spec.to_dict()
        return
    stored = orjson.loads(orjson.dumps(resolved.to_json_dict()))
    again = type(resolved).from_json_dict(stored)
    assert again == resolved and again.key("x") == resolved.key("x")


def _sweep_form() -> dict:
    req = SweepRequest.model_validate({"vehicle": BTRAIN, "grid": {"bank_percent": [0, 2]}})
    return orjson.loads(orjson.dumps(resolve_sweep(resolve_request_given(req), Settings()).to_json_dict()))


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda case: case.pop("targets"), "case: Value error, the stored request is not a ResolvedCase: targets"),
        (lambda case: case.update(targets={"general": "0.35"}), "targets: Input should be a valid number"),
        (lambda case: case.update(targets_judged_on="srt"), "targets_judged_on is not 'level_road_srt'"),
        (lambda case: case.pop("vehicle"), "ResolvedCase: case: KeyError('vehicle')"),
        (lambda case: case["vehicle"].update(wheel_count=6), "unknown vehicle field(s): wheel_count"),
        (lambda case: case.pop("stage"), "the fields"),  # a missing field the engine would have defaulted
        (lambda case: case.update(surprise=1), "the fields"),
    ],
)
def test_a_stored_sweep_whose_base_case_is_of_another_shape_is_refused_naming_it(change, words):
    data = _sweep_form()
    change(data["case"])
    with pytest.raises(ValueError, match="the stored request is not a ResolvedSweep: case") as raised:
        ResolvedSweep.from_json_dict(data)
    assert words in str(raised.value)


def test_a_stored_sweep_reads_back_its_base_case_typed():
    again = ResolvedSweep.from_json_dict(_sweep_form())
    assert isinstance(again.case, ResolvedCase) and again.case.case.vehicle == vehicle_preset(BTRAIN)
    assert again.case.targets == Settings().default_targets()


@pytest.mark.parametrize("data", [None, [], {"spec": {}, "combination_spec": {}}, {"other": {}}])
def test_a_stored_build_of_another_shape_is_refused(data):
    with pytest.raises(ValueError, match="the stored request is not a ResolvedBuild"):
        ResolvedBuild.from_json_dict(data)


def test_an_srt_without_curves_keeps_no_points():
    req = SrtRequest.model_validate({"vehicle": BTRAIN})
    assert (
        ResolvedSrt(base=ResolvedCase(case=resolve_case(req, _vehicle(req)), targets={}), curve_points=41).curve_points
        is None
    )


def test_of_takes_each_field_from_the_request_and_refuses_what_neither_gives():
    req = SuperelevationTableRequest.model_validate(
        {"design_speed_kmh": 70.0, "max_superelevation_percent": 8.0, "radii_m": [200.0, 400.0]}
    )
    table = ResolvedSuperelevationTable.of(req)
    assert table.radii_m == (200.0, 400.0) and table.points == req.points  # a list kept as a tuple (frozen, hashable)
    with pytest.raises(TypeError, match="no field"):
        ResolvedSuperelevationTable.of(req, radius_m=1.0)
    with pytest.raises(AttributeError, match="radius_m"):  # the table request has no single radius
        ResolvedSuperelevation.of(req)
