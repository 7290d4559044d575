"""POST /v1/srt: the SRT request (vehicle, model, stage, road, trailer angle, load, LLT limit) and its result."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import ConfigDict, Discriminator, Field, StringConstraints, Tag, WithJsonSchema

from app.http.schemas import (
    EXAMPLE_PRESET,
    WARNINGS_DESCRIPTION,
    InputModel,
    InputWarningOut,
    OutputModel,
    bounded,
    describe,
    json_int,
)
from app.vehicle_forms.builder_schemas import SpecRef
from app.vehicle_forms.combination_builder_schemas import CombinationSpecRef
from app.vehicle_forms.combination_schemas import CombinationRef, LiftEventOut, RollCoupledUnitOut
from app.vehicle_forms.schemas import VehicleRecord
from engine import BOUNDS, DEFAULT_CURVE_POINTS, MAX_CURVE_POINTS
from engine.models import MODELS

# "3d", "2d", "rigid", "rigid-bank", "winkler", "rill", "chang", "gillespie", "navin"
ModelId = Literal[tuple(MODELS)]  # type: ignore[valid-type]
Stage = Literal["full", "tires-suspension"]


def _vehicle_kind(value: Any) -> str:
    if isinstance(value, str):
        return "id"
    if isinstance(value, SpecRef) or (isinstance(value, dict) and "spec" in value):
        return "spec"
    if isinstance(value, CombinationRef) or (isinstance(value, dict) and "combination" in value):
        return "combination"
    if isinstance(value, CombinationSpecRef) or (isinstance(value, dict) and "combination_spec" in value):
        return "combination_spec"
    return "record"


VehicleId = Annotated[
    str,
    Field(
        min_length=1,
        max_length=100,
        description="A preset id from GET /v1/vehicles (e.g. `table16-btrain`) or GET /v1/combinations (e.g. "
        "`btrain-table16`), or the id of one of the caller's saved vehicles (`veh_...`, with `Authorization: Bearer "
        "<key>`); an unknown id is a 404 naming it.",
    ),
]
VehicleRef = Annotated[
    Annotated[VehicleId, Tag("id")]
    | Annotated[VehicleRecord, Tag("record")]
    | Annotated[SpecRef, Tag("spec")]
    | Annotated[CombinationRef, Tag("combination")]
    | Annotated[CombinationSpecRef, Tag("combination_spec")],
    Discriminator(_vehicle_kind),
]
VEHICLE_DESCRIPTION = describe(
    "The vehicle: a preset id (`table14-semitrailer`, `table15-semitrailer`, `table16-btrain`, `table22-truck`, "
    "`table23-semitrailer`), a combination preset id (`tractor-semitrailer-table15`, `btrain-table16`, `adouble`, "
    "`truck-trailer`: GET /v1/combinations), a saved vehicle's id (`veh_...`, with the bearer key that saved it), a "
    'full vehicle record, a measurable spec `{"spec": {...}}` that the vehicle builder turns into a record (see '
    '`POST /v1/vehicles/build`), a whole combination `{"combination": {...}}` (units, axle groups, couplings), or a '
    'combination in measurable terms `{"combination_spec": {...}}` (see `POST /v1/combinations/build`).',
    unit="-",
    symbol="Tables 14-16, 22, 23",
)


class RoadIn(InputModel):
    """Road geometry at the curve."""

    bank_percent: float = bounded(
        "bank_percent",
        0.0,
        text="Superelevation (bank) e = 100 tan(phi), positive toward the inside of the curve.",
        symbol="e, phi (bank angle)",
    )
    slope_percent: float = bounded(
        "slope_percent",
        0.0,
        text="Longitudinal grade, positive uphill in the direction of travel, negative downhill.",
        symbol="slope (Table 17 columns; Px = W sin of the slope angle, Eq. 4.24)",
    )


class SlopeIn(InputModel):
    """The road's grade at the curve (where the bank is given elsewhere, e.g. as the superelevation)."""

    slope_percent: float = bounded(
        "slope_percent",
        0.0,
        text="Longitudinal grade, positive uphill in the direction of travel, negative downhill.",
        symbol="slope (Table 17 columns; Px = W sin of the slope angle, Eq. 4.24)",
    )


class LoadIn(InputModel):
    """Load case (Sec. 4.7, Fig. 46): CG offsets and overweight."""

    lateral_offset_m: float = bounded(
        "lateral_offset_m", 0.0, text="Lateral CG offset, positive toward the outside of the turn.", symbol="d1"
    )
    longitudinal_offset_m: float = bounded(
        "longitudinal_offset_m",
        0.0,
        text="Longitudinal CG offset, positive toward the front (CG at x = -a + d2, Table 8).",
        symbol="d2",
    )
    vertical_offset_m: float = bounded("vertical_offset_m", 0.0, text="Vertical CG offset, positive up.", symbol="d3")
    overweight_percent: float = bounded(
        "overweight_percent",
        0.0,
        text="Extra weight over the nominal W, same CG (weight used = W (1 + overweight/100)).",
        symbol="overweight (Sec. 9.2)",
    )


SRT_EXAMPLE: dict[str, Any] = {
    "vehicle": EXAMPLE_PRESET,
    "model": "3d",
    "stage": "full",
    "road": {"bank_percent": 0.0, "slope_percent": 0.0},
    "trailer_angle_deg": 0.0,
    "load": {"lateral_offset_m": 0.0, "longitudinal_offset_m": 0.0, "vertical_offset_m": 0.0, "overweight_percent": 0},
    "rear_llt_limit": 1.0,
}


class SrtOptions(InputModel):
    """The SRT request fields other than the vehicle and the road (shared with the alignment assessment, where
    each curve has its own bank and grade)."""

    model: ModelId | None = Field(
        None,
        description=describe(
            "Model id (see GET /v1/models); default `3d` for a vehicle record, `combination` (the whole-combination "
            "model) for a combination. With a combination, `3d` is the thesis's model of its last unit with the "
            "LLTf/LLTr the combination gives, `rigid` the rigid roll-coupled units.",
            unit="-",
            symbol="Chs. 2, 5, 6 models",
        ),
    )
    stage: Stage = Field(
        "full",
        description=describe(
            "3d only: `full` (tires, suspension, fifth wheel, chassis) or `tires-suspension` (first stage).",
            unit="-",
            symbol="SRT_TS / SRT_3D stages (Ch. 9)",
        ),
    )
    trailer_angle_deg: float = bounded(
        "trailer_angle_deg", 0.0, text="Angle between the last two units of the combination (3d only).", symbol="psi"
    )
    load: LoadIn = Field(
        default_factory=LoadIn, description=describe("CG offsets and overweight.", unit="m, %", symbol="d1, d2, d3")
    )
    rear_llt_limit: float = bounded(
        "rear_llt_limit",
        1.0,
        text="Rear lateral load transfer at which the load ramp stops; 1 = rear inner tire lift-off (Table 17 uses "
        "0.6). Closed-form models accept only 1.",
        unit="-",
        symbol="LLTr (Eq. 2.5)",
    )


class SrtInputs(SrtOptions):
    """Everything that determines one SRT (shared by /v1/srt, /v1/curve-speed and /v1/min-radius)."""

    vehicle: VehicleRef = Field(description=VEHICLE_DESCRIPTION)
    road: RoadIn = Field(
        default_factory=RoadIn, description=describe("Road bank and slope at the curve.", unit="%", symbol="e, slope")
    )


#: a target's name: lower-case letters, digits and underscores (it also names CSV columns)
TARGET_NAME_PATTERN = r"^[a-z][a-z0-9_]{0,39}$"
MAX_TARGETS = 10
Targets = Annotated[
    dict[Annotated[str, StringConstraints(pattern=TARGET_NAME_PATTERN)], Annotated[float, Field(gt=0, le=2)]],
    Field(min_length=1, max_length=MAX_TARGETS),
    WithJsonSchema(
        {
            "type": "object",
            "minProperties": 1,
            "maxProperties": MAX_TARGETS,
            "propertyNames": {"pattern": TARGET_NAME_PATTERN},
            "additionalProperties": {
                "type": "number",
                "exclusiveMinimum": BOUNDS["target_srt_g"].minimum,
                "maximum": BOUNDS["target_srt_g"].maximum,
            },
        }
    ),
]
TARGETS_DESCRIPTION = describe(
    "SRT targets to check the result against, name -> minimum SRT in g (1-10 entries; names in lower case, "
    "digits and `_`). They replace the service's defaults, which are `general` 0.35 g and `dangerous_goods` "
    "0.40 g (Australia's PBS scheme, New Zealand's SRT rule) unless the deployment configures others.",
    unit="g",
    symbol="SRT target",
)


class SrtTargets(InputModel):
    """The SRT targets a computed SRT is checked against."""

    targets: Targets | None = Field(None, description=TARGETS_DESCRIPTION)


class SrtRequest(SrtInputs, SrtTargets):
    """Static rollover threshold of one vehicle on one road with one load case."""

    model_config = ConfigDict(
        json_schema_extra={
            "examples": [
                {**SRT_EXAMPLE, "include_curves": False},
                {
                    "vehicle": EXAMPLE_PRESET,
                    "targets": {"general": 0.35, "dangerous_goods": 0.40, "tanker_fleet": 0.45},
                },
            ]
        }
    )

    include_curves: bool = Field(
        False,
        description=describe(
            "Also return the curves against ay/g from rest to the limit (2d and 3d models only).",
            unit="-",
            symbol="Figs. 92-97",
        ),
    )
    curve_points: json_int(ge=2, le=MAX_CURVE_POINTS) = Field(  # type: ignore[valid-type]
        DEFAULT_CURVE_POINTS,
        description=describe("Number of points of the curves (with include_curves).", unit="count", symbol="-"),
    )


# ------------------------------------------------------------------------------------------- output


class TireLoadsOut(OutputModel):
    """Tire normal loads at the limit (per side of each axle group, thesis numbering)."""

    front_outer_kn: float | None = Field(
        description=describe("Front outer tire load (null for the 2d model).", unit="kN", symbol="Fz1")
    )
    front_inner_kn: float | None = Field(
        description=describe("Front inner tire load (null for the 2d model).", unit="kN", symbol="Fz3")
    )
    rear_outer_kn: float = Field(description=describe("Rear outer tire load.", unit="kN", symbol="Fz17 (2D: Fz1)"))
    rear_inner_kn: float = Field(description=describe("Rear inner tire load.", unit="kN", symbol="Fz19 (2D: Fz3)"))


class CurvesOut(OutputModel):
    """Quantities against the lateral acceleration, from rest to the limit (one entry per `ay_g`)."""

    ay_g: list[float] = Field(description=describe("Lateral acceleration.", unit="g", symbol="ay/g"))
    fz_front_outer_kn: list[float] | None = Field(
        description=describe("Front outer tire load (null for 2d).", unit="kN", symbol="Fz1")
    )
    fz_front_inner_kn: list[float] | None = Field(
        description=describe("Front inner tire load (null for 2d).", unit="kN", symbol="Fz3")
    )
    fz_rear_outer_kn: list[float] = Field(description=describe("Rear outer tire load.", unit="kN", symbol="Fz17"))
    fz_rear_inner_kn: list[float] = Field(description=describe("Rear inner tire load.", unit="kN", symbol="Fz19"))
    llt_front: list[float] | None = Field(
        description=describe("Front lateral load transfer (null for 2d).", unit="-", symbol="LLTf")
    )
    llt_rear: list[float] = Field(description=describe("Rear lateral load transfer.", unit="-", symbol="LLTr"))
    roll_angle_deg: list[float] = Field(
        description=describe("Total body roll.", unit="deg", symbol="theta_3D (2D: theta1 + theta6 + theta8)")
    )
    cg_lateral_m: list[float] = Field(
        description=describe("Lateral CG distance from the outer tire.", unit="m", symbol="h1 (Eq. 6.1 / 5.1)")
    )
    cg_height_m: list[float] = Field(
        description=describe("CG height above the road.", unit="m", symbol="h2 (Eq. 6.2 / 5.2)")
    )


class TargetCheckOut(OutputModel):
    """Whether an SRT meets one target, and by how much."""

    name: str = Field(description=describe("Target name (`general`, `dangerous_goods` or the request's).", unit="-"))
    target_g: float = Field(description=describe("Minimum SRT the target asks for.", unit="g", symbol="SRT target"))
    meets: bool = Field(
        description=describe(
            "Whether the level-road SRT meets the target (level_road_srt >= target). Targets such as PBS's and New "
            "Zealand's are level-road SRTs: a bank raises the case's own `srt` but not the vehicle's verdict.",
            unit="-",
            symbol="SRT(e = 0, slope = 0) >= target",
        )
    )
    margin_g: float = Field(
        description=describe(
            "level_road_srt - target; negative when the target is missed.", unit="g", symbol="SRT(level) - target"
        )
    )
    judged_on: Literal["level_road_srt"] = Field(
        description=describe(
            "Which SRT the verdict is judged on: always `level_road_srt`, the SRT of the same vehicle, load, model "
            "and parameters with bank and slope set to zero.",
            unit="-",
        )
    )


TARGETS_OUT = describe(
    "The level-road SRT (`level_road_srt`: bank and slope set to zero, the rest of the case unchanged) checked "
    "against each target (the request's `targets`, else the service's defaults), in order of increasing target.",
    unit="g",
    symbol="SRT target",
)
LEVEL_ROAD_SRT_TEXT = describe(
    "SRT of the same vehicle, load, model and parameters on a level road (bank and slope set to zero): what the "
    "targets are judged on (`targets[].judged_on`). Equal to `srt` when the case is level.",
    unit="g",
    symbol="SRT(e = 0, slope = 0)",
)
TILT_OUT = describe(
    "Tilt-table angle equivalent to the SRT, atan(SRT): the angle at which a tilt test would tip a vehicle with "
    "this threshold. It is of the SRT beside it: on a banked or sloped road the curve's threshold; a tilt table "
    "measures the level-road one (`level_road_srt`, atan of which is its tilt angle).",
    unit="deg",
    symbol="atan(SRT)",
)


class SrtResult(OutputModel):
    """The static rollover threshold and the state of the vehicle at the limit."""

    srt: float = Field(
        description=describe(
            "Static rollover threshold of this case: lateral acceleration at the limit on this road (the bank and "
            "slope are included): the curve's threshold, what the curve speed and the rollover radius use. The "
            "targets are judged on `level_road_srt`, not on this.",
            unit="g",
            symbol="SRT = ay/g",
        )
    )
    level_road_srt: float = Field(
        description=LEVEL_ROAD_SRT_TEXT,
    )
    roll_angle_deg: float | None = Field(
        description=describe(
            "Total body roll at the limit (null for the rigid closed forms).", unit="deg", symbol="theta_3D"
        )
    )
    tilt_table_angle_deg: float = Field(description=TILT_OUT)
    targets: list[TargetCheckOut] = Field(description=TARGETS_OUT)
    model: str = Field(description=describe("Model used.", unit="-", symbol="-"))
    stage: str | None = Field(description=describe("Stage (3d only).", unit="-", symbol="SRT_TS / SRT_3D"))
    limit: str = Field(
        description=describe(
            "What ended the load ramp: `rear-inner-lift-off`, `rear-llt-limit`, `closed-form`, or for the "
            "combination model `rollover` (the largest ay the governing roll-coupled unit holds).",
            unit="-",
            symbol="Fz19 = 0 or LLTr = limit",
        )
    )
    rear_llt_limit: float = Field(description=describe("Rear LLT limit used.", unit="-", symbol="LLTr"))
    stage_values: dict[str, float] = Field(
        description=describe(
            "3d full stage: `srt_ts` (tires and suspension only) and `srt_3d` (full system).",
            unit="g",
            symbol="SRT_TS, SRT_3D (Ch. 9)",
        )
    )
    llt_front: float | None = Field(
        description=describe("Front lateral load transfer at the limit.", unit="-", symbol="LLTf")
    )
    llt_rear: float | None = Field(
        description=describe("Rear lateral load transfer at the limit.", unit="-", symbol="LLTr")
    )
    tire_loads: TireLoadsOut | None = Field(
        description=describe("Tire normal loads at the limit (null for closed forms).", unit="kN", symbol="Fz")
    )
    cg_lateral_m: float | None = Field(
        description=describe("Lateral CG distance from the outer tire at the limit.", unit="m", symbol="h1")
    )
    cg_height_m: float | None = Field(
        description=describe("CG height above the road at the limit.", unit="m", symbol="h2")
    )
    iterations: int | None = Field(description=describe("Solver iterations.", unit="count", symbol="-"))
    parameters: dict[str, float | None] = Field(
        description=describe(
            "Model-specific values (closed forms: the mapped symbols t, h, h0, ...; null where not defined).",
            unit="per entry (m, kN, kN m/rad, rad, deg)",
            symbol="Ch. 2 symbols",
        )
    )
    warnings: list[InputWarningOut] = Field(default_factory=list, description=WARNINGS_DESCRIPTION)
    notes: list[str] = Field(description=describe("Caveats the engine attached to this result.", unit="-"))
    curves: CurvesOut | None = Field(
        None,
        description=describe("Curves against ay/g (only with include_curves).", unit="see its fields", symbol="ay/g"),
    )
    roll_coupled_units: list[RollCoupledUnitOut] | None = Field(
        None,
        description=describe(
            "Combination model: each roll-coupled unit (units joined by fifth wheels or B-couplings; a pintle cuts "
            "the chain) with its SRT, what ended it, its roll angles, group and coupling states and lift-offs; "
            "`srt` is the lowest of them.",
            unit="see its fields",
        ),
    )
    governing_unit: int | None = Field(
        None, description=describe("Combination model: index of the governing (lowest) roll-coupled unit.", unit="-")
    )
    lift_sequence: list[LiftEventOut] | None = Field(
        None,
        description=describe("Combination model: every lift-off, in order of lateral acceleration.", unit="g"),
    )
    last_unit_front_llt_ratio: float | None = Field(
        None,
        description=describe(
            "Combination model: LLTf/LLTr of the last unit (its front support is the towing unit's group under its "
            "coupling) when its own group reaches the LLT limit: what the 3D model of the last unit takes.",
            unit="-",
            symbol="LLTf/LLTr",
        ),
    )
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))
