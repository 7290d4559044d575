"""Requests and answers of the dynamics endpoints and the PBS screening.

The optional dynamic data (``dynamics``: per unit and per axle group) follow from the engine's one definition
(:data:`engine.dynamics.parameters.UNIT_DATA_DOCS`, :data:`~engine.dynamics.parameters.GROUP_DATA_DOCS`): each field
is added there once and appears here, in the cache key and in the answer's ``parameters``.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import ConfigDict, Field, create_model

from app.http.schemas import InputModel, OutputModel, describe
from app.srt.schemas import VEHICLE_DESCRIPTION, VehicleRef
from app.vehicle_forms.dynamic_data_schemas import group_fields, unit_fields
from engine.dynamics import LANE_CHANGE_AMPLITUDE_G, LANE_CHANGE_SPEED_KMH, PULSE_STEER_SPEED_KMH

RaDefinition = Literal["cg", "axle"]


def d(text: str, unit: str = "-") -> str:
    """A description naming its unit (no thesis symbol: the dynamics are beyond the thesis)."""
    return describe(text, unit=unit)


def f(default: Any = ..., text: str = "", unit: str = "-", **kw: Any) -> Any:
    return Field(default, description=d(text, unit), **kw)


UNIT_ID = (str, Field(min_length=1, max_length=40, description=d("The unit's id in the combination.")))
UnitDataIn = create_model(
    "UnitDataIn",
    __base__=InputModel,
    __doc__="Optional data of one unit; what is left out is estimated (the answer's `parameters` say how).",
    unit=UNIT_ID,
    **unit_fields(),
)
GroupDataIn = create_model(
    "GroupDataIn",
    __base__=InputModel,
    __doc__="Optional data of one axle group; what is left out is estimated.",
    unit=UNIT_ID,
    group=(str, Field(min_length=1, max_length=40, description=d("The group's id in its unit."))),
    **group_fields(),
)


class DynamicsDataIn(InputModel):
    """What the motion needs beyond the combination description; each field optional (estimated otherwise)."""

    units: list[UnitDataIn] = Field(default_factory=list, max_length=8, description=d("Per unit."))  # type: ignore[valid-type]
    groups: list[GroupDataIn] = Field(default_factory=list, max_length=16, description=d("Per axle group."))  # type: ignore[valid-type]


class DynamicsInputs(InputModel):
    """The vehicle (a combination) and its optional dynamic data."""

    vehicle: VehicleRef = Field(
        description=VEHICLE_DESCRIPTION + " The dynamics need a combination (units, groups, couplings): a "
        "combination preset id or description."
    )
    dynamics: DynamicsDataIn | None = f(
        None, "Optional inertias, extents, cornering coefficients and axle spacings; each left out is estimated."
    )


def _speed(default: float, text: str) -> Any:
    return f(default, text, "km/h", ge=5.0, le=200.0)


RA_TEXT = (
    "Rearward amplification of the rearmost unit's CG (`cg`) or of the rearmost axle (`axle`) over the steer "
    "axle's lateral acceleration."
)


class LaneChangeRequest(DynamicsInputs):
    speed_kmh: float = _speed(88.0, "Forward speed (default unverified: not read in the PBS rules).")
    frequency_hz: float = f(0.4, "Frequency of the one sine period of the steer axle's lateral acceleration.", "Hz",
                            ge=0.05, le=3.0)  # fmt: skip
    amplitude_g: float = f(0.15, "Amplitude of the steer axle's lateral acceleration (default unverified: not read "
                           "in the PBS rules).", "g", ge=0.01, le=0.6)  # fmt: skip
    ra_definition: RaDefinition = f("cg", RA_TEXT)
    include_history: bool = f(False, "Time histories (every 0.02 s) in the answer.")

    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16", "speed_kmh": 88.0}]})


class FrequencyResponseRequest(DynamicsInputs):
    speed_kmh: float = _speed(88.0, "Forward speed.")
    frequencies_hz: list[float] | None = f(
        None, "Frequencies at which to evaluate RA (default 60 from 0.1 to 3 Hz, logarithmic).", "Hz",
        min_length=1, max_length=400,
    )  # fmt: skip
    ra_definition: RaDefinition = f("cg", RA_TEXT)

    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16", "speed_kmh": 88.0}]})


class PulseSteerRequest(DynamicsInputs):
    speed_kmh: float = _speed(100.0, "Forward speed (default unverified: not read in the PBS rules).")

    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16", "speed_kmh": 100.0}]})


class StabilityRequest(DynamicsInputs):
    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16"}]})


class SteadyTurnRequest(DynamicsInputs):
    radius_m: float = f(..., "Path radius of the steer axle.", "m", ge=10.0, le=10000.0)
    speed_kmh: float = f(..., "Forward speed (from 0.5 km/h: a crawl).", "km/h", ge=0.5, le=200.0)

    model_config = ConfigDict(
        json_schema_extra={"examples": [{"vehicle": "btrain-table16", "radius_m": 200.0, "speed_kmh": 60.0}]}
    )


class LowSpeedTurnRequest(DynamicsInputs):
    path_step_m: float = f(1.0, "Spacing of the corner paths' points along the steer axle's travel.", "m",
                           ge=0.1, le=10.0)  # fmt: skip

    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16"}]})


PBS_DEFAULT = " The default is unverified (a value as commonly cited, not read in the rules): set the rules' value."


class PbsRequest(DynamicsInputs):
    ra_definition: RaDefinition = f("cg", RA_TEXT)
    lane_change_speed_kmh: float = _speed(LANE_CHANGE_SPEED_KMH, "The lane change's forward speed." + PBS_DEFAULT)
    lane_change_amplitude_g: float = f(LANE_CHANGE_AMPLITUDE_G, "The lane change's amplitude of the steer axle's "
                                       "lateral acceleration." + PBS_DEFAULT, "g", ge=0.01, le=0.6)  # fmt: skip
    pulse_steer_speed_kmh: float = _speed(PULSE_STEER_SPEED_KMH, "The pulse steer's forward speed." + PBS_DEFAULT)

    model_config = ConfigDict(json_schema_extra={"examples": [{"vehicle": "btrain-table16"}]})


# ----------------------------------------------------------------------------------------- answers


class ScreeningOut(OutputModel):
    screening: Literal[True] = f(True, "Always true: an indicative screening by a linear model, not a certification.")
    note: str = f(..., "What the answer is: an indicative screening, not a certification.")
    validity: list[str] = f(..., "Lift-off, instability and other limits of the linear model's validity.")
    parameters: dict[str, Any] = f(
        ..., "The inertias, extents, cornering stiffnesses and damping used, each with `value`, `unit` and `source` "
        "(given, a preset's source, or `estimated: formula; source`)."
    )  # fmt: skip
    stable: bool = f(..., "False when a mode grows at this speed: the measures are then null.")
    stability_limit_kmh: float | None = f(None, "Where unstable: the speed from which.", "km/h")
    engine_version: str = f(..., "The engine's version (part of every cache key).")


class RollCoupledOut(OutputModel):
    units: list[str] = f(..., "The units that roll together (joined by fifth wheels or B-couplings).")
    peak_load_transfer_ratio: float | None = f(
        None, "Peak |LTR| of the roll-coupled unit: its groups' load transfer over their load."
    )
    srt_g: float | None = f(None, "Its static SRT (the whole-combination model).", "g")


class UnitPeakOut(OutputModel):
    unit: str = f(..., "The unit's id.")
    peak_lateral_acceleration_g: float = f(..., "Peak lateral acceleration at the sprung CG (yaw plane).", "g")
    peak_roll_angle_deg: float = f(..., "Peak roll of the sprung mass.", "deg")


class LaneChangeResult(ScreeningOut):
    speed_kmh: float = f(..., "Forward speed.", "km/h")
    frequency_hz: float = f(..., "Frequency of the lane change.", "Hz")
    amplitude_g: float = f(..., "Amplitude of the steer axle's lateral acceleration.", "g")
    ra_definition: RaDefinition = f(..., RA_TEXT)
    rearward_amplification: float | None = f(..., "Peak rear over peak steer-axle lateral acceleration.")
    high_speed_transient_offtracking_m: float | None = f(
        ..., "The rearmost axle's lateral overshoot beyond the steer axle's final path (definition unverified).", "m"
    )
    max_path_deviation_m: float | None = f(
        None, "Largest lateral distance between the rearmost axle's path and the steer axle's at the same station.", "m"
    )
    steer_axle_lateral_offset_m: float | None = f(
        ..., "The steer axle's lateral displacement at the end of the period, A/(2 pi f^2).", "m"
    )
    roll_coupled_units: list[RollCoupledOut] = f(..., "Per roll-coupled unit.")
    units: list[UnitPeakOut] = f(..., "Per unit.")
    time_step_s: float = f(..., "Time step of the exact discretisation.", "s")
    history: dict[str, Any] | None = f(None, "Time histories (`time_s`, `steer_deg`, `lateral_acceleration_g` per "
                                       "unit, `rear_offtracking_m`), when asked for.")  # fmt: skip


class FrequencyResponseResult(ScreeningOut):
    speed_kmh: float = f(..., "Forward speed.", "km/h")
    ra_definition: RaDefinition = f(..., RA_TEXT)
    frequencies_hz: list[float] = f(..., "The frequencies.", "Hz")
    rearward_amplification: list[float] | None = f(..., "RA at each frequency (same length).")
    worst_frequency_hz: float | None = f(..., "Frequency of the largest RA in 0.1-3 Hz.", "Hz")
    worst_rearward_amplification: float | None = f(..., "The largest RA in 0.1-3 Hz.")


class EigenOut(OutputModel):
    real: float = f(..., "Real part.", "1/s")
    imag: float = f(..., "Imaginary part.", "rad/s")


class ModeOut(OutputModel):
    damping_ratio: float = f(..., "-Re / |lambda| of the least-damped oscillatory mode.")
    frequency_hz: float = f(..., "Its damped frequency.", "Hz")
    shape: dict[str, dict[str, float]] = f(
        ..., "Articulations and unit rolls, `magnitude` normalised to the largest and `phase_deg`."
    )


class PulseSteerResult(ScreeningOut):
    speed_kmh: float = f(..., "Forward speed.", "km/h")
    yaw_damping_ratio: float | None = f(
        ..., "The rearmost articulation's damping from successive same-sign peaks, delta/sqrt(4 pi^2 + delta^2)."
    )
    articulation: str | None = f(..., "Which articulation was measured.")
    least_damped_mode: ModeOut | None = f(..., "The least-damped oscillatory mode.")
    eigenvalues: list[EigenOut] = f(..., "Every eigenvalue of the reduced state.")


class StabilityResult(ScreeningOut):
    sway_critical_speed_kmh: float | None = f(
        ..., "Lowest speed at which an oscillatory mode (trailer sway) reaches zero damping; null: stable to "
        "`max_speed_kmh`.", "km/h",
    )  # fmt: skip
    divergence_speed_kmh: float | None = f(
        ..., "Lowest speed at which a real mode diverges; null: stable to `max_speed_kmh`.", "km/h"
    )
    max_speed_kmh: float = f(..., "The highest speed examined.", "km/h")


class AxlePathOut(OutputModel):
    unit: str = f(..., "The unit's id.")
    group: str = f(..., "The group's id.")
    path_radius_m: float = f(..., "Path radius of the group's centre.", "m")
    offtracking_m: float = f(..., "Steer axle's radius less this group's.", "m")


class UnitTurnOut(OutputModel):
    unit: str = f(..., "The unit's id.")
    articulation_deg: float | None = f(..., "Yaw of the unit ahead less this unit's (null for the first).", "deg")
    roll_angle_deg: float = f(..., "Sprung mass roll (+ toward the inside of the turn).", "deg")
    load_transfer_ratio: float | None = f(..., "Of its roll-coupled unit.")


class SteadyTurnResult(ScreeningOut):
    radius_m: float = f(..., "Path radius of the steer axle.", "m")
    speed_kmh: float = f(..., "Forward speed.", "km/h")
    lateral_acceleration_g: float | None = f(..., "Steady lateral acceleration.", "g")
    steer_deg: float | None = f(..., "Road-wheel steer angle.", "deg")
    axles: list[AxlePathOut] = f(..., "Per axle group.")
    units: list[UnitTurnOut] = f(..., "Per unit.")
    roll_coupled_units: list[dict[str, Any]] = f(..., "Per roll-coupled unit: `units`, `load_transfer_ratio`, `srt_g`.")


class LowSpeedTurnResult(ScreeningOut):
    swept_path_width_m: float = f(..., "12.5 m less the smallest distance of any unit's body from the turn centre.",
                                  "m")  # fmt: skip
    tail_swing_m: float = f(..., "Largest outward swing of any unit's outside rear corner.", "m")
    frontal_swing_m: float = f(..., "The prime mover's outside front corner beyond the outer steer tyre's path.", "m")
    units: list[dict[str, Any]] = f(..., "Per unit: `tail_swing_m`, `frontal_swing_m`.", "m")
    paths: list[dict[str, Any]] = f(..., "Per unit and corner: `points_m` [[x, y]], turn centre at the origin.", "m")
    steer_axle_radius_m: float = f(..., "Radius of the steer axle's centre on the arc.", "m")
    not_judged: list[str] = f(..., "Measures of the turn this model cannot judge.")


class PbsLimitOut(OutputModel):
    level: int = f(..., "PBS level (1-4).")
    limit: float | None = f(..., "The limit, in the standard's unit; null: the limit could not be read in the rules' "
                               "text, so none is given.")  # fmt: skip
    sense: Literal["min", "max"] = f(..., "`min`: the value must be at least the limit; `max`: at most.")
    source: str = f(..., "The text the limit was read in; or, where `verified` is false, that it could not be read.")
    verified: bool = f(..., "Whether the limit was read in a primary text (false: `limit` is null).")


class PbsStandardOut(OutputModel):
    id: str = f(..., "The standard's id.")
    value: float | None = f(..., "The vehicle's value (null: unstable or not measurable).")
    unit: str = f(..., "The value's unit.")
    limits: list[PbsLimitOut] = f(..., "Per level.")
    level: int | None = f(..., "Best level met, from verified limits only (null: no verified limit, or none met).")
    source: str = f(..., "The rules and what the standard applies to.")
    note: str = f(..., "Why a value is missing, if it is.")


class PbsResult(ScreeningOut):
    standards: list[PbsStandardOut] = f(..., "Every standard this model judges.")
    rules_version: str = f(..., "The rules the standards come from.")
    not_judged: list[str] = f(..., "Standards this model does not judge.")
    length_m: float = f(..., "Overall length (estimated extents where not given).", "m")
    network_level_by_length: dict[str, Any] = f(..., "The lowest level whose length limit (Class A, Class B) admits "
                                                "the vehicle, the limits and their source.")  # fmt: skip
    other_limits: list[dict[str, Any]] = f(..., "Other schemes' limits, with their sources.")
    conditions: dict[str, Any] = f(..., "The manoeuvres' speeds, frequency and amplitude used; `verified` (false: the "
                                   "rules' values could not be read), `unverified_defaults_used` (the request's "
                                   "options left at their unverified defaults) and `source`.")  # fmt: skip
