"""Physically impossible or out-of-domain inputs are refused before solving, naming the field."""

from __future__ import annotations

import dataclasses

import pytest

from engine.case import Case, LoadCase, Road
from engine.errors import InvalidInput, InvalidLoad, InvalidRoad, InvalidVehicle, MissingParameter, UnknownPreset
from engine.models.threshold import rollover_threshold, sweep
from engine.vehicle.presets import PRESETS, get_preset
from engine.vehicle.record import Vehicle

BTRAIN = PRESETS["table16-btrain"]


@pytest.mark.parametrize(
    "change,field",
    [
        (dict(weight_kn=0.0), "weight_kn"),
        (dict(suspension_stiffness_kn_per_m=-1800.0), "suspension_stiffness_kn_per_m"),
        (dict(tire_stiffness_kn_per_m=0.0), "tire_stiffness_kn_per_m"),
        (dict(fifth_wheel_stiffness_kn_per_m=-1.0), "fifth_wheel_stiffness_kn_per_m"),
        (dict(cg_height_above_chassis_m=float("nan")), "cg_height_above_chassis_m"),
        (dict(spring_separation_m=2.0), "spring_separation_m"),
        (dict(rear_track_m=2.0), "rear_track_m"),
        (dict(front_llt_ratio=1.2), "front_llt_ratio"),
        (dict(front_llt_ratio=0.0), "front_llt_ratio"),
        (dict(rear_tires_per_axle=3), "rear_tires_per_axle"),
        (dict(front_axles=0), "front_axles"),
        (dict(front_axle_to_cg_m=5.0), "front_axle_to_cg_m"),
        (dict(fifth_wheel_width_m=2.0), "fifth_wheel_width_m"),
        (dict(suspension_stiffness_kn_per_m=150.0), "suspension_stiffness_kn_per_m"),  # k_theta < W l12
    ],
)
def test_impossible_vehicle_is_refused_with_its_field(change, field):
    with pytest.raises(InvalidVehicle) as exc:
        rollover_threshold(Case(BTRAIN.replace(**change)))
    assert exc.value.field == field
    assert field in str(exc.value) or "stiffness" in str(exc.value)


def test_2d_vehicle_cannot_run_the_3d_model():
    with pytest.raises(MissingParameter, match="front_track_m") as exc:
        rollover_threshold(Case(PRESETS["table14-semitrailer"], "3d"))
    assert exc.value.field == "front_track_m"


@pytest.mark.parametrize(
    "kwargs,exc,field",
    [
        (dict(load=LoadCase(lateral_offset_m=0.93)), InvalidLoad, "load.lateral_offset_m"),
        (dict(load=LoadCase(vertical_offset_m=-1.4)), InvalidLoad, "load.vertical_offset_m"),
        (dict(load=LoadCase(longitudinal_offset_m=3.0)), InvalidLoad, "load.longitudinal_offset_m"),
        (dict(load=LoadCase(longitudinal_offset_m=-3.0)), InvalidLoad, "load.longitudinal_offset_m"),
        (dict(load=LoadCase(overweight_percent=-100.0)), InvalidLoad, "load.overweight_percent"),
        (dict(road=Road(bank_percent=35.0)), InvalidRoad, "road.bank_percent"),
        (dict(road=Road(slope_percent=float("inf"))), InvalidRoad, "road.slope_percent"),
        (dict(trailer_angle_deg=95.0), InvalidRoad, "trailer_angle_deg"),
        (dict(rear_llt_limit=0.0), InvalidLoad, "rear_llt_limit"),
        (dict(rear_llt_limit=1.5), InvalidLoad, "rear_llt_limit"),
        (dict(stage="half"), InvalidInput, "stage"),
        (dict(curve_points=1, include_curves=True), InvalidInput, "curve_points"),
    ],
)
def test_out_of_domain_case_is_refused(kwargs, exc, field):
    options = {k: kwargs.pop(k) for k in ("curve_points", "include_curves") if k in kwargs}
    with pytest.raises(exc) as info:
        rollover_threshold(Case(BTRAIN, **kwargs), **options)
    assert info.value.field == field


def test_models_refuse_effects_they_do_not_contain():
    with pytest.raises(InvalidRoad, match="rill") as info:
        rollover_threshold(Case(BTRAIN, "rill", road=Road(bank_percent=4)))
    assert info.value.field == "road.bank_percent"
    with pytest.raises(InvalidInput, match="2d") as info:
        rollover_threshold(Case(BTRAIN, "2d", road=Road(slope_percent=4)))
    assert info.value.field == "road.slope_percent"
    with pytest.raises(InvalidInput):
        rollover_threshold(Case(BTRAIN, "2d", stage="tires-suspension"))
    with pytest.raises(InvalidLoad):
        rollover_threshold(Case(BTRAIN, "gillespie", rear_llt_limit=0.6))


def test_a_vehicle_that_tips_at_rest_has_no_srt():
    # CG 0.5 m toward the outside on a 20 % adverse crossfall: the rear LLT passes 0.6 with no acceleration
    with pytest.raises(InvalidInput, match="at rest"):
        rollover_threshold(
            Case(BTRAIN, road=Road(bank_percent=-20), load=LoadCase(lateral_offset_m=0.5), rear_llt_limit=0.6)
        )


def test_unknown_preset_and_unknown_fields():
    with pytest.raises(UnknownPreset) as exc:
        get_preset("table99-rocket")
    assert "table16-btrain" in str(exc.value)
    with pytest.raises(InvalidVehicle, match="wings"):
        Vehicle.from_dict({**BTRAIN.to_dict(), "wings": 2})


@pytest.mark.parametrize("preset_id", sorted(PRESETS))
def test_a_vehicle_record_round_trips_through_its_dict(preset_id):
    """to_dict skips dataclasses.asdict's deep copy: safe only while every field is a number, a string or None."""
    vehicle = PRESETS[preset_id]
    data = vehicle.to_dict()
    assert data == dataclasses.asdict(vehicle) and list(data) == [f.name for f in dataclasses.fields(Vehicle)]
    assert all(v is None or isinstance(v, int | float | str) for v in data.values())
    assert Vehicle.from_dict(data) == vehicle


@pytest.mark.parametrize(
    "model,curves", [("3d", False), ("3d", True), ("2d", True), ("rigid-bank", False), ("chang", False)]
)
def test_a_result_dict_is_the_dataclass_dict_with_its_own_containers(model, curves):
    """RolloverResult.to_dict skips dataclasses.asdict's recursion: the same dict, in the same order, and the
    result's lists and dicts copied (a caller that edits the dict leaves the frozen result as it was)."""
    result = rollover_threshold(Case(BTRAIN, model=model, road=Road(bank_percent=2.0)), include_curves=curves)
    data = result.to_dict()
    expected = dataclasses.asdict(result)
    assert expected.pop("combination") is None  # the whole-combination model's detail, left out of other results
    assert data == expected and list(data) == list(expected)
    assert (data["curves"] is not None) == curves
    data["stage_values"]["x"] = data["parameters"]["x"] = 1.0
    data["notes"].append("edited")
    if curves:
        data["curves"]["ay_g"].append(9.0)
    assert result.to_dict() == expected and "edited" not in result.notes


def test_sweep_reports_refused_cases_per_row_and_keeps_the_others():
    res = sweep(Case(BTRAIN), {"lateral_offset_m": [0.0, 0.5, 1.0]})
    assert set(res.errors) == {2}  # 1.0 m is outside the 0.93 m half track
    assert "lateral_offset_m" in res.errors[2]
    rows = res.rows()
    assert rows[0]["srt"] == pytest.approx(rollover_threshold(Case(BTRAIN)).srt, rel=1e-10)
    assert rows[2]["srt"] is None and rows[2]["error"]
