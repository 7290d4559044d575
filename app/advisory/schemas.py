"""POST /v1/advisory-speed: the advisory speed of one curve, each method's speed, the treatment and the W1-13 rule."""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import (
    ABSENT,
    EXAMPLE_PRESET,
    WARNINGS_DESCRIPTION,
    InputModel,
    InputWarningOut,
    OutputModel,
    bounded,
    describe,
    shape_error,
)
from app.road.standards_schemas import BOUND_ONLY_WITH_TABLE21, DesignOptions
from app.srt.schemas import VEHICLE_DESCRIPTION, SrtOptions, VehicleRef
from engine.road import (
    BODY_ROLL_DEG_PER_G,
    DECELERATION_MPS2,
    MAX_TRUCK_DECELERATION_MPS2,
    MIN_DEFLECTION_DEG,
    REACTION_TIME_S,
    ROLLOVER_MARGIN_KMH,
    SPEED_RANGE_KMH,
)

MAX_VEHICLES = 10
_LO, _HI = SPEED_RANGE_KMH

# One meaning, one text: the option in every request that takes it (one curve's, an assessment's of curves) and the
# answers that say which applied (one curve's, an assessment's `advisory`)
UNITS_DESCRIPTION = describe(
    "The advisory plaques' units: `us` shows multiples of 5 mph (TxDOT: +1 mph, rounded down to 5 mph); `metric` "
    "multiples of 10 km/h (rounded down: assumed).",
    unit="-",
)
INCREMENT_DESCRIPTION = describe(
    "The advisory plaques' increment: 5 with `us` (mph), 10 with `metric` (km/h).", unit="mph or km/h (by `units`)"
)


def _speed(text: str, symbol: str, default=None):
    extra = {"json_schema_extra": ABSENT} if default is None else {}
    return Field(default, ge=_LO, le=_HI, description=describe(text, unit="km/h", symbol=symbol), **extra)


class AdvisorySpeedRequest(SrtOptions, DesignOptions):
    """One curve (its sharpest component for a compound or spiralled curve), the posted and approach speeds and
    optionally the vehicles whose rollover is checked."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [
                BOUND_ONLY_WITH_TABLE21,
                {"not": {"required": ["vehicle", "vehicles"]}},
            ],
            "examples": [
                {
                    "radius_m": 150.0,
                    "superelevation_percent": 6.0,
                    "deflection_deg": 40.0,
                    "posted_speed_kmh": 100.0,
                    "vehicle": EXAMPLE_PRESET,
                },
                {
                    "radius_m": 150.0,
                    "superelevation_percent": 6.0,
                    "grade_percent": -4.0,
                    "posted_speed_kmh": 90.0,
                    "tangent_speed_kmh": 95.0,
                    "measured_car_speed_kmh": 72.0,
                    "units": "metric",
                    "vehicles": [EXAMPLE_PRESET, "table23-semitrailer"],
                },
            ],
        }
    )

    radius_m: float = bounded(
        "radius_m",
        text="Radius of the curve, or of the sharpest component of a compound or spiralled curve (FHWA-SA-11-22's "
        "critical portion; TxDOT Design Method, Step 1).",
        symbol="R",
    )
    superelevation_percent: float = bounded(
        "design_superelevation_percent",
        text="Superelevation of that component; also the bank of the vehicles' SRT.",
        symbol="e",
    )
    grade_percent: float = bounded(
        "slope_percent", 0.0, text="Grade along travel (+ uphill); also the slope of the vehicles' SRT.", symbol="slope"
    )
    deflection_deg: float = Field(
        None,
        gt=0,
        le=180,
        json_schema_extra=ABSENT,
        description=describe(
            f"Total deflection angle of the curve. Below {MIN_DEFLECTION_DEG:g} deg the answer notes that such a "
            "curve rarely justifies warning signs (TxDOT, GPS Method).",
            unit="deg",
            symbol="Delta",
        ),
    )  # type: ignore[assignment]
    posted_speed_kmh: float = _speed(f"Posted (regulatory) speed, {_LO:g}-{_HI:g} km/h.", "V_posted", ...)
    tangent_speed_kmh: float = _speed(
        f"Speed on the approach tangent (85th percentile), {_LO:g}-{_HI:g} km/h; default the posted speed. Places "
        "the advance warning sign.",
        "V_t",
    )  # type: ignore[assignment]
    measured_car_speed_kmh: float = _speed(
        "Average speed of free-flowing passenger cars measured at mid-curve (at least 125 cars: TxDOT Direct "
        "Method); when given, the Direct Method sets the advisory speed.",
        "V_c",
    )  # type: ignore[assignment]
    vehicle: VehicleRef = Field(
        None,
        json_schema_extra=ABSENT,
        description=VEHICLE_DESCRIPTION + " Its rollover speed on this curve is checked (give `vehicle` or `vehicles`, "
        "or neither: no rollover check).",
    )  # type: ignore[assignment]
    vehicles: list[VehicleRef] = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_VEHICLES,
        description=describe(
            f"Several vehicles (1-{MAX_VEHICLES}), each checked; the warning is recommended if any needs it.", unit="-"
        ),
    )  # type: ignore[assignment]
    units: Literal["us", "metric"] = Field("us", description=UNITS_DESCRIPTION)
    increment: float = Field(
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "The plaque's increment, if stated: 5 with `us` (mph), 10 with `metric` (km/h); any other is refused.",
            unit="mph or km/h (by `units`)",
        ),
    )  # type: ignore[assignment]
    deceleration_mps2: float = Field(
        DECELERATION_MPS2,
        gt=0,
        description=describe(
            "Braking rate for the advance sign's distance: default 10 ft/s^2 (MUTCD 11e Table 2C-3's basis, as "
            f"transcribed: unverified); at most {MAX_TRUCK_DECELERATION_MPS2:.3f} (15 ft/s^2, NCHRP Report 774's "
            "emergency braking for trucks in curves).",
            unit="m/s^2",
            symbol="d",
        ),
    )
    reaction_time_s: float = Field(
        REACTION_TIME_S,
        ge=0,
        le=10,
        description=describe("Reaction time before braking (MUTCD 11e Table 2C-3: 2.5 s, unverified).", unit="s"),
    )
    rollover_margin_kmh: float = Field(
        ROLLOVER_MARGIN_KMH,
        ge=0,
        le=50,
        description=describe(
            "This service's W1-13 margin: the warning is recommended where a vehicle's rollover speed less this "
            "margin falls below the advisory speed shown.",
            unit="km/h",
        ),
    )
    body_roll_deg_per_g: float = Field(
        BODY_ROLL_DEG_PER_G,
        ge=0,
        le=20,
        description=describe(
            "Body-roll allowance of the ball-bank conversion (the ball reads atan(f) plus the body's roll); the "
            "default is assumed.",
            unit="deg/g",
        ),
    )

    @model_validator(mode="after")
    def _one_vehicle_field(self) -> AdvisorySpeedRequest:
        if self.vehicle is not None and self.vehicles is not None:
            raise shape_error("AdvisorySpeedRequest", "vehicles", "give vehicle or vehicles, not both")
        return self


class MethodOut(OutputModel):
    id: str = Field(description=describe("The method.", unit="-"))
    speed_kmh: float | None = Field(
        description=describe("Its speed before rounding (null: not computed, see `source`).", unit="km/h")
    )
    source: str = Field(description=describe("Where it comes from, and whether it was verified.", unit="-"))
    legacy: bool = Field(description=describe("A legacy criterion (not the current primary method).", unit="-"))
    verified: bool = Field(description=describe("Read in its primary text (false: unverified).", unit="-"))
    vehicle: int | None = Field(description=describe("Index into the request's vehicles (rollover only).", unit="-"))


class TreatmentOut(OutputModel):
    devices: list[str] = Field(description=describe("Devices by the posted-advisory difference.", unit="-"))
    speed_difference_mph: float = Field(description=describe("Posted minus advisory speed.", unit="mph"))
    advance_sign_distance_m: float = Field(
        description=describe(
            "Distance before the curve for the advance warning sign: reaction distance plus braking from the tangent "
            "speed to the advisory speed at `deceleration_mps2` (Table 2C-3's basis; unverified).",
            unit="m",
        )
    )
    source: str = Field(description=describe("The table and its status.", unit="-"))


class VehicleCheckOut(OutputModel):
    vehicle: int = Field(description=describe("Index into the request's vehicles.", unit="-"))
    srt: float = Field(description=describe("SRT on this curve's bank and grade.", unit="g", symbol="SRT"))
    rollover_speed_kmh: float = Field(description=describe("sqrt(127 SRT R).", unit="km/h", symbol="V (Eq. 9.1)"))
    recommended: bool = Field(description=describe("W1-13 recommended for this vehicle.", unit="-"))


class RolloverWarningOut(OutputModel):
    recommended: bool = Field(description=describe("W1-13 recommended (any vehicle).", unit="-"))
    rule: str = Field(description=describe("The rule (this service's).", unit="-"))
    vehicles: list[VehicleCheckOut] = Field(description=describe("One per vehicle.", unit="see its fields"))


class AdvisorySpeedResult(OutputModel):
    advisory_speed_kmh: float = Field(
        description=describe("The advisory speed shown on the plaque (a multiple of the increment).", unit="km/h")
    )
    advisory_speed_mph: float | None = Field(description=describe("The same in mph (with `us`).", unit="mph"))
    units: Literal["us", "metric"] = Field(description=UNITS_DESCRIPTION)
    increment: float = Field(description=INCREMENT_DESCRIPTION)
    governed_by: str = Field(description=describe("The method whose speed is shown.", unit="-"))
    methods: list[MethodOut] = Field(description=describe("Every method's speed with its source.", unit="-"))
    treatment: TreatmentOut = Field(description=describe("The sign treatment.", unit="see its fields"))
    truck_rollover_warning: RolloverWarningOut = Field(
        description=describe("The truck rollover warning (W1-13).", unit="see its fields")
    )
    notes: list[str] = Field(description=describe("What the answer could not verify or apply.", unit="-"))
    warnings: list[InputWarningOut] = Field(description=WARNINGS_DESCRIPTION)
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))


class AdvisoryOptions(InputModel):
    """The advisory-speed and speed-profile options of an assessment of curves (alignments and routes): each assessed
    curve carries its advisory speed, treatment, W1-13 rule and the truck's profile figures."""

    units: Literal["us", "metric"] = Field("us", description=UNITS_DESCRIPTION)
    desired_speed_kmh: float = _speed(
        "The truck's speed on the tangents where a curve has no posted speed (a curve's posted speed is its "
        "tangent's otherwise). Without it, an alignment with a curve without posted speed has no profile (each row "
        "says why).",
        "V_d",
    )
    deceleration_mps2: float = Field(
        DECELERATION_MPS2,
        gt=0,
        description=describe(
            "The truck's braking rate into a curve in the speed profile: default 10 ft/s^2 (MUTCD 11e Table 2C-3's "
            f"basis, as transcribed: unverified); at most {MAX_TRUCK_DECELERATION_MPS2:.3f} (15 ft/s^2, NCHRP Report "
            "774's emergency braking for trucks in curves).",
            unit="m/s^2",
            symbol="d",
        ),
    )
