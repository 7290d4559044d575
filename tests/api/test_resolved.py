"""The typed resolved requests (app/compute/resolved.py): their JSON form reads back as the same object, a stored
form of another shape is refused, and their cache keys are the keys of the dicts the services resolved before
(written out here by hand), so no cached answer or ETag changes."""

from __future__ import annotations

import dataclasses

import orjson
import pytest

from app.alignments.service import _digest, parse_json_request, resolve_alignment
from app.compute.cache import cache_key
from app.compute.resolved import (
    CurvesDigest,
    ResolvedAlignment,
    ResolvedLimits,
    ResolvedRoute,
    ResolvedSweep,
    RouteDocument,
)
from app.routes.schemas import RouteRequest
from app.routes.service import _document_digest, resolved_route
from app.settings import Settings
from app.srt.limits_schemas import LimitsRequest
from app.srt.limits_service import resolve_limits
from app.srt.service import resolve_case
from app.srt.sweep_schemas import SweepRequest
from app.srt.sweep_service import resolve_sweep
from app.vehicles.resolve import resolve_request_given, vehicle_preset
from engine.road.profile import DECELERATION_MPS2

BTRAIN = "table16-btrain"
SEMI = "table23-semitrailer"
CURVES = [
    {"id": "C1", "radius_m": 120.0, "superelevation_percent": 6.0, "grade_percent": -2.0, "posted_speed_kmh": 60.0},
    {"id": "C2", "radius_m": 300.0, "posted_speed_kmh": 80.0},
]
ROUTE = {
    "type": "FeatureCollection",
    "features": [
        {
            "type": "Feature",
            "properties": {},
            "geometry": {"type": "LineString", "coordinates": [[0.0, 45.0], [0.001, 45.0], [0.002, 45.001]]},
        }
    ],
}


def _assessment_dict(presets: list[str], **options) -> dict:
    """The assessment part of the dict ``resolved_assessment`` returned (before the types), defaults filled."""
    return {
        "vehicles": [vehicle_preset(p).to_dict() for p in presets],
        "presets": presets,
        "saved_ids": [None] * len(presets),
        "model": None,
        "stage": "full",
        "trailer_angle_deg": 0.0,
        "load": {
            "lateral_offset_m": 0.0,
            "longitudinal_offset_m": 0.0,
            "vertical_offset_m": 0.0,
            "overweight_percent": 0.0,
        },
        "rear_llt_limit": 1.0,
        "design_standard": "aashto-2018",
        "side_friction_bound": None,
        "max_superelevation_percent": None,
        "targets": Settings().default_targets(),
        # in the key since every row carries its advisory speed and the truck's profile (issue 43)
        "units": "us",
        "desired_speed_kmh": None,
        "deceleration_mps2": DECELERATION_MPS2,
        **options,
    }


def _alignment(body: dict) -> ResolvedAlignment:
    req, table = parse_json_request(orjson.dumps(body))
    return resolve_alignment(resolve_request_given(req), table, Settings()).resolved


def test_an_alignments_key_is_the_key_of_the_dict_it_replaces():
    body = {"vehicles": [BTRAIN, SEMI], "curves": CURVES, "max_superelevation_percent": 8.0, "rear_llt_limit": 0.6}
    body |= {"targets": {"a": 0.3, "b": 0.25}}
    resolved = _alignment(body)
    req, table = parse_json_request(orjson.dumps(body))
    old = _assessment_dict([BTRAIN, SEMI], max_superelevation_percent=8.0, rear_llt_limit=0.6)
    old |= {"targets": {"a": 0.3, "b": 0.25}, "curves": {"count": 2, "sha256": _digest(table)}}
    assert old["load"].keys() == req.load.model_dump().keys()  # the hand-written load is the request's
    for op in ("alignments", "alignments-csv", "alignment-answer"):
        assert resolved.key(op) == cache_key(op, old)
    assert resolved.to_json_dict() == old  # and so a job's stored state is what it was


def test_the_csv_dialect_is_in_the_key_only_when_the_curves_came_as_csv():
    text = "id;radius_m;superelevation_percent\r\nC1;120,5;6\r\nC2;80;4,5\r\n"
    resolved = _alignment({"vehicle": BTRAIN, "csv": text})
    dialect = {"separator": ";", "decimal": ",", "bom": False, "line_ending": "CRLF"}
    assert resolved.csv_dialect == dialect
    old = {**_assessment_dict([BTRAIN]), "curves": dataclasses.asdict(resolved.curves), "csv_dialect": dialect}
    assert resolved.key("alignments") == cache_key("alignments", old)
    by_json = _alignment({"vehicle": BTRAIN, "curves": CURVES})
    assert by_json.csv_dialect is None and "csv_dialect" not in by_json.to_json_dict()


def test_a_routes_key_is_the_key_of_the_dict_it_replaces():
    req = RouteRequest.model_validate({"vehicle": BTRAIN, "geojson": ROUTE, "superelevation_percent": 5.0})
    resolved = resolved_route(resolve_request_given(req), Settings())
    route = {
        "format": "geojson",
        "sha256": _document_digest(req),
        "superelevation_percent": 5.0,
        "posted_speed_kmh": None,
        "detection": req.detection.model_dump(),
        # in the key since the GPX parts read and the use of elevations became options (issue 39)
        "parts": None,
        "use_elevation": True,
        "grade_percent": None,
    }
    old = {**_assessment_dict([BTRAIN], max_superelevation_percent=req.max_superelevation_percent), "route": route}
    for op in ("route", "route-csv", "route-geojson"):
        assert resolved.key(op) == cache_key(op, old)


def _case_dict(req, targets: dict | None = None) -> dict:
    """What the keys held of an SRT request's case before the types: the case's dict beside the targets."""
    targets = Settings().default_targets() if targets is None else targets
    return {
        **resolve_case(req, resolve_request_given(req).vehicles[0].vehicle).to_dict(),
        "targets": targets,
        "targets_judged_on": "level_road_srt",
    }


def test_a_sweeps_and_a_limits_key_are_the_keys_of_the_dicts_they_replace():
    settings = Settings()
    sweep = SweepRequest.model_validate({"vehicle": BTRAIN, "grid": {"slope_percent": [0, 4], "bank_percent": [2]}})
    old = {"case": _case_dict(sweep), "grid": {"bank_percent": [2.0], "slope_percent": [0.0, 4.0]}}
    resolved = resolve_sweep(resolve_request_given(sweep), settings)
    assert list(resolved.grid) == ["bank_percent", "slope_percent"] and resolved.cases == 2
    for op in ("srt-sweep", "srt-sweep-csv", "srt-sweep-answer"):
        assert resolved.key(op) == cache_key(op, old)
    limits = LimitsRequest.model_validate({"vehicle": BTRAIN, "parameter": "cg_height_above_chassis_m"})
    old = {
        "case": _case_dict(limits),
        "parameter": "cg_height_above_chassis_m",
        "target_srt_g": settings.srt_target_general_g,
        "overweights_percent": [0.0, 5.0, 10.0, 15.0, 20.0],
        # where the target is applied: added when the default moved to the level road, so an answer searched on
        # the request's road under the old key is never served for the new default
        "limit_on": "level_road",
    }
    assert resolve_limits(resolve_request_given(limits), settings).key("srt-limits") == cache_key("srt-limits", old)


def _samples() -> list:
    alignment = _alignment({"vehicles": [BTRAIN, SEMI], "curves": CURVES, "targets": {"x": 0.3}})
    csv = _alignment({"vehicle": BTRAIN, "csv": "id,radius_m,superelevation_percent\nC1,120,6\n"})
    req = RouteRequest.model_validate({"vehicle": BTRAIN, "geojson": ROUTE, "max_superelevation_percent": 8.0})
    route = resolved_route(resolve_request_given(req), Settings())
    sweep_req = SweepRequest.model_validate({"vehicle": BTRAIN, "grid": {"bank_percent": [0, 2]}})
    sweep = resolve_sweep(resolve_request_given(sweep_req), Settings())
    limits_req = LimitsRequest.model_validate({"vehicle": BTRAIN, "parameter": "overweight_percent"})
    limits = resolve_limits(resolve_request_given(limits_req), Settings())
    return [alignment, csv, route, sweep, limits]


@pytest.mark.parametrize("index", range(5), ids=["alignment", "csv", "route", "sweep", "limits"])
def test_the_json_form_reads_back_as_the_same_request_with_the_same_key(index):
    resolved = _samples()[index]
    stored = orjson.loads(orjson.dumps(resolved.to_json_dict()))  # as a job's state comes back from the store
    again = type(resolved).from_json_dict(stored)
    assert again == resolved
    assert again.key("x") == resolved.key("x") and again.to_json_dict() == resolved.to_json_dict()


def test_the_types_are_frozen_and_typed():
    alignment = _samples()[0]
    assert isinstance(alignment.curves, CurvesDigest) and isinstance(alignment.vehicles, tuple)
    with pytest.raises(dataclasses.FrozenInstanceError):
        alignment.model = "rigid"  # type: ignore[misc]
    route = _samples()[2]
    assert isinstance(route, ResolvedRoute) and isinstance(route.route, RouteDocument)


def _broken(data: dict, path: tuple, value) -> dict:
    out = orjson.loads(orjson.dumps(data))
    where = out
    for p in path[:-1]:
        where = where[p]
    if value is KeyError:
        del where[path[-1]]
    else:
        where[path[-1]] = value
    return out


@pytest.mark.parametrize(
    ("cls", "index", "path", "value", "words"),
    [
        (ResolvedAlignment, 0, ("targets",), KeyError, "targets: Field required"),
        (ResolvedAlignment, 0, ("presets",), "table16-btrain", "presets"),
        (ResolvedAlignment, 0, ("vehicles", 0), [1, 2], "vehicles.0"),
        (ResolvedAlignment, 0, ("curves", "count"), "2", "curves.count"),
        (ResolvedAlignment, 0, ("max_superelevation_percent",), True, "max_superelevation_percent"),
        (ResolvedAlignment, 0, ("surprise",), 1, "surprise"),
        (ResolvedAlignment, 0, ("saved_ids",), [None], "saved ids"),  # one per vehicle
        (ResolvedRoute, 2, ("route", "sha256"), None, "route.sha256"),
        (ResolvedSweep, 3, ("grid", "bank_percent"), [0, "2"], "grid.bank_percent.1"),
        (ResolvedLimits, 4, ("target_srt_g",), KeyError, "target_srt_g"),
    ],
)
def test_a_stored_form_of_another_shape_is_a_value_error_naming_the_field(cls, index, path, value, words):
    data = _broken(_samples()[index].to_json_dict(), path, value)
    with pytest.raises(ValueError, match=cls.__name__) as raised:
        cls.from_json_dict(data)
    assert words in str(raised.value)


@pytest.mark.parametrize("data", [None, [], "resolved", {"grid": {}}])
def test_a_stored_form_that_is_not_an_object_of_the_fields_is_refused(data):
    with pytest.raises(ValueError, match="the stored request is not a ResolvedSweep"):
        ResolvedSweep.from_json_dict(data)
