"""An unknown (misspelled) field is answered with the nearest known name at that location (issue 23 item 5).

The expected suggestions are the field names of the request schemas (DESIGN.md's contract names); the message
format is the contract's: ``unknown field '<typed>': did you mean '<known>'?``, or ``unknown field '<typed>'`` when
no known name is close (difflib ratio below 0.6).
"""

from __future__ import annotations

import pytest

from app.http.problems import models_at, nearest_field
from app.srt.schemas import LoadIn, RoadIn, SrtRequest

BTRAIN = "table16-btrain"
CURVE = {"id": "C1", "radius_m": 200.0, "superelevation_percent": 6.0}


def unknown(client, path, body):
    r = client.post(path, json=body)
    assert r.status_code == 422, r.text
    p = r.json()
    assert p["type"] == "urn:rollover:problem:validation-error"
    return {e["field"]: e for e in p["errors"] if e["type"] == "extra_forbidden"}, p


@pytest.mark.parametrize(
    ("path", "body", "field", "message"),
    [
        (
            "/v1/min-radius",
            {"vehicle": BTRAIN, "design_speed_kmh": 60, "superelevation_percnt": 6},
            "superelevation_percnt",
            "unknown field 'superelevation_percnt': did you mean 'superelevation_percent'?",
        ),
        (
            "/v1/srt",
            {"vehicle": BTRAIN, "road": {"bank_percnt": 6}},
            "road.bank_percnt",
            "unknown field 'bank_percnt': did you mean 'bank_percent'?",
        ),
        (
            "/v1/srt",
            {"vehicle": BTRAIN, "load": {"overweight_pct": 5}},
            "load.overweight_pct",
            "unknown field 'overweight_pct': did you mean 'overweight_percent'?",
        ),
        (
            "/v1/srt",
            {"vehicle": BTRAIN, "modle": "3d"},
            "modle",
            "unknown field 'modle': did you mean 'model'?",
        ),
        (
            "/v1/curve-speed",
            {"vehicle": BTRAIN, "radius": 100},
            "radius",
            "unknown field 'radius': did you mean 'radius_m'?",
        ),
        (
            "/v1/srt/sweep",
            {"vehicle": BTRAIN, "grid": {"bank_percnt": [0, 4]}},
            "grid.bank_percnt",
            "unknown field 'bank_percnt': did you mean 'bank_percent'?",
        ),
        (  # a vehicle record inside the vehicle union: the record's names
            "/v1/srt",
            {"vehicle": {"weight_kN": 100}},
            "vehicle.weight_kN",
            "unknown field 'weight_kN': did you mean 'weight_kn'?",
        ),
        (  # a builder spec, nested two models deep inside the vehicle union
            "/v1/srt",
            {"vehicle": {"spec": {"tare": {"mas_kg": 7500}}}},
            "vehicle.spec.tare.mas_kg",
            "unknown field 'mas_kg': did you mean 'mass_kg'?",
        ),
        (
            "/v1/vehicles/build",
            {"spec": {"tare": {"cg_heigth_m": 1.1}}},
            "spec.tare.cg_heigth_m",
            "unknown field 'cg_heigth_m': did you mean 'cg_height_m'?",
        ),
        (  # a whole combination: the field is named as typed (no union tag doubled in it)
            "/v1/srt",
            {"vehicle": {"combination": {"unitz": []}}},
            "vehicle.combination.unitz",
            "unknown field 'unitz': did you mean 'units'?",
        ),
        (  # a route that reads its body itself (the alignment): the declared model, a list item
            "/v1/alignments/assess",
            {"vehicle": BTRAIN, "curves": [{"id": "C1", "radus_m": 200.0}]},
            "curves.0.radus_m",
            "unknown field 'radus_m': did you mean 'radius_m'?",
        ),
        (
            "/v1/alignments/assess",
            {"vehicle": BTRAIN, "curves": [CURVE], "design_standrad": "aashto-2018"},
            "design_standrad",
            "unknown field 'design_standrad': did you mean 'design_standard'?",
        ),
        (  # a job submission (a union of operations) and its inner request
            "/v1/jobs",
            {"operation": "srt.sweep", "requets": {}},
            "requets",
            "unknown field 'requets': did you mean 'request'?",
        ),
        (
            "/v1/jobs",
            {"operation": "srt.sweep", "request": {"vehicle": BTRAIN, "grdi": {"bank_percent": [0]}}},
            "request.grdi",
            "unknown field 'grdi': did you mean 'grid'?",
        ),
    ],
)
def test_an_unknown_field_names_the_nearest_known_one(shared_client, path, body, field, message):
    errors, p = unknown(shared_client, path, body)
    assert field in errors, errors
    assert errors[field]["message"] == message
    assert message in p["detail"]


@pytest.mark.parametrize(
    ("path", "body", "field"),
    [
        ("/v1/srt", {"vehicle": BTRAIN, "colour": "red"}, "colour"),
        ("/v1/srt", {"vehicle": BTRAIN, "road": {"wind": 3}}, "road.wind"),
        ("/v1/vehicles/build", {"spec": {"tare": {"zzz": 1}}}, "spec.tare.zzz"),
    ],
)
def test_no_suggestion_when_nothing_is_close(shared_client, path, body, field):
    errors, _ = unknown(shared_client, path, body)
    name = field.rsplit(".", 1)[-1]
    assert errors[field]["message"] == f"unknown field {name!r}"


def test_the_suggestion_is_a_name_of_that_location_not_of_another_model():
    # 'slope_percent' is a road field, 'lateral_offset_m' a load field: each location knows only its own
    assert nearest_field(models_at(SrtRequest, ["road"]), "slope_prcent") == "slope_percent"
    assert nearest_field(models_at(SrtRequest, ["load"]), "slope_prcent") == "overweight_percent"  # the load's own
    assert nearest_field(models_at(SrtRequest, ["load"]), "lateral_ofset_m") == "lateral_offset_m"
    assert models_at(SrtRequest, ["road"]) == [RoadIn] and models_at(SrtRequest, ["load"]) == [LoadIn]
    assert models_at(SrtRequest, ["targets"]) == []  # a dict of numbers holds no model
