"""POST /v1/srt/limits: the largest (or smallest) value of one parameter at which the SRT still meets a target."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import (
    EXAMPLE_PRESET,
    WARNINGS_DESCRIPTION,
    InputWarningOut,
    OutputModel,
    bounded,
    describe,
    shape_error,
)
from app.srt.schemas import LEVEL_ROAD_SRT_TEXT, TARGETS_OUT, TILT_OUT, SrtInputs, SrtTargets, TargetCheckOut
from engine.road import LIMIT_PARAMETERS

# "cg_height_above_chassis_m", "overweight_percent", "lateral_offset_m", "spring_separation_m"
LimitParameter = Literal[tuple(LIMIT_PARAMETERS)]  # type: ignore[valid-type]

#: parameter -> (unit, thesis symbol, where the request holds its current value)
PARAMETER_INFO = {
    "cg_height_above_chassis_m": ("m", "l12", "vehicle.cg_height_above_chassis_m"),
    "overweight_percent": ("%", "overweight", "load.overweight_percent"),
    "lateral_offset_m": ("m", "d1", "load.lateral_offset_m"),
    "spring_separation_m": ("m", "b", "vehicle.spring_separation_m"),
    "vertical_offset_m": ("m", "d3", "load.vertical_offset_m"),
}
DEFAULT_OVERWEIGHTS = [0.0, 5.0, 10.0, 15.0, 20.0]
MAX_TABLE_ROWS = 25
MAX_TABLE_OVERWEIGHT = 50.0

STATUS_TEXT = (
    "`found`: the SRT equals the target at `value` to the search's tolerance and is never below it (`value` meets "
    "the target); past it (above a `max` limit, below a `min` one) the target is missed. `always-met`: every value "
    "of the admissible range [`range_min`, `range_max`] meets the target; `value` is the range's end (or the last "
    "value at which the vehicle can still be solved) and the true limit lies beyond what the model admits. "
    "`never-met`: no value of the range meets the target; `value` is null."
)
OverweightValue = Annotated[float, Field(ge=-MAX_TABLE_OVERWEIGHT, le=MAX_TABLE_OVERWEIGHT)]
#: where the target SRT is applied: the level road (the targets' basis, default) or the request's own road
LimitOn = Literal["level_road", "road"]
LIMIT_ON_TEXT = describe(
    "Where the target SRT is applied while the limit is searched: `level_road` (default), the same vehicle, load, "
    "model and parameters on a level road, the basis every target is judged on (`targets[].judged_on`), so a found "
    "limit meets the target as a certifier reads it whatever the request's bank and slope; `road`, the request's "
    "own bank and slope: the limit for this curve's own threshold (on a bank it allows more than the targets do). "
    "The same on a level road.",
    unit="-",
)


class LimitsRequest(SrtInputs, SrtTargets):
    """The limit of one parameter for a target SRT, found exactly by a bracketed root finder (Brent) on the
    engine, and the same limit over a range of overweights (the exact counterpart of the TERNZ calculator's table
    of acceptable mass / load-height pairs). The other fields are the SRT request's: the base case."""

    model_config = ConfigDict(
        json_schema_extra={
            # the table runs over overweights: parameter = overweight_percent has none
            "not": {
                "required": ["parameter", "overweights_percent"],
                "properties": {"parameter": {"const": "overweight_percent"}},
            },
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "parameter": "cg_height_above_chassis_m",
                    "target_srt_g": 0.3,
                    "overweights_percent": [0, 5, 10, 15, 20],
                },
                {"vehicle": EXAMPLE_PRESET, "parameter": "lateral_offset_m", "target_srt_g": 0.3},
            ],
        }
    )

    parameter: LimitParameter = Field(
        description=describe(
            "The parameter to solve for: `cg_height_above_chassis_m` (largest CG height above the chassis, l12), "
            "`overweight_percent` (largest overweight), `lateral_offset_m` (largest lateral CG offset toward the "
            "outside of the turn, d1) or `spring_separation_m` (smallest lateral separation of the springs, b). "
            "The SRT falls as the first three grow and rises with the last.",
            unit="m or % (per parameter)",
            symbol="l12, overweight, d1, b",
        )
    )
    target_srt_g: float | None = bounded(
        "target_srt_g",
        None,
        text="The SRT the vehicle must still reach; null = the service's `general` target (0.35 g unless configured).",
        symbol="SRT target",
    )
    overweights_percent: list[OverweightValue] | None = Field(
        None,
        min_length=1,
        max_length=MAX_TABLE_ROWS,
        description=describe(
            f"Overweights for the table: the limit is solved again at each (1-{MAX_TABLE_ROWS} values in "
            f"[-{MAX_TABLE_OVERWEIGHT:g}, {MAX_TABLE_OVERWEIGHT:g}]). Null = 0, 5, 10, 15, 20 %; not allowed with "
            "`parameter` = `overweight_percent` (that has no table).",
            unit="%",
            symbol="overweight (Sec. 9.2)",
        ),
    )

    limit_on: LimitOn = Field("level_road", description=LIMIT_ON_TEXT)

    @model_validator(mode="after")
    def _no_table_over_itself(self) -> LimitsRequest:
        if self.parameter == "overweight_percent" and self.overweights_percent is not None:
            raise shape_error(
                "LimitsRequest",
                "overweights_percent",
                "the table runs over overweights: with parameter = overweight_percent there is none (leave "
                "overweights_percent out, or pick another parameter)",
            )
        return self


LimitStatus = Literal["found", "always-met", "never-met"]


class LimitOut(OutputModel):
    value: float | None = Field(
        description=describe(
            "The limit: the largest (`kind` max) or smallest (`kind` min) value meeting the target; null when "
            "`never-met`.",
            unit="`unit`",
            symbol="l12, overweight, d1 or b",
        )
    )
    status: LimitStatus = Field(description=describe(STATUS_TEXT, unit="-"))
    range_min: float = Field(
        description=describe("Lower end of the admissible range searched.", unit="`unit`", symbol="-")
    )
    range_max: float = Field(
        description=describe("Upper end of the admissible range searched.", unit="`unit`", symbol="-")
    )
    srt_at_limit: float | None = Field(
        description=describe(
            "SRT at `value` on the road the limit is searched on (`limit_on`): the target when `found`, above it "
            "when `always-met`, null when `never-met`.",
            unit="g",
            symbol="SRT",
        )
    )
    level_road_srt: float | None = Field(
        description=LEVEL_ROAD_SRT_TEXT + " With the parameter at `value`: `srt_at_limit` itself when `limit_on` is "
        "`level_road`; null without `value`."
    )
    road_srt: float | None = Field(
        description=describe(
            "SRT at `value` on the request's own road (its bank and slope): the curve's own threshold, as `srt` of "
            "POST /v1/srt; `srt_at_limit` itself when `limit_on` is `road`, `level_road_srt` on a level road; null "
            "without `value` or when the engine cannot solve that case.",
            unit="g",
            symbol="SRT",
        )
    )
    evaluations: int = Field(description=describe("SRT solves the search took.", unit="count"))
    tilt_table_angle_deg: float | None = Field(description=TILT_OUT + " Of `srt_at_limit`; null without it.")
    targets: list[TargetCheckOut] = Field(
        description=TARGETS_OUT + " Of `level_road_srt` (the parameter at `value`); empty without it."
    )


class LimitTableRowOut(OutputModel):
    overweight_percent: float = Field(
        description=describe("Overweight of this row.", unit="%", symbol="overweight (Sec. 9.2)")
    )
    value: float | None = Field(
        description=describe("The limit at this overweight; null when `never-met` or refused.", unit="`unit`")
    )
    status: Literal["found", "always-met", "never-met", "refused"] = Field(
        description=describe(STATUS_TEXT + " `refused`: the engine cannot solve this row (see `error`).", unit="-")
    )
    srt_at_limit: float | None = Field(
        description=describe(
            "SRT at `value` on the road the limit is searched on (`limit_on`).", unit="g", symbol="SRT"
        )
    )
    evaluations: int = Field(description=describe("SRT solves the search took.", unit="count"))
    error: str | None = Field(description=describe("Why the row was refused (null otherwise).", unit="-"))


class LimitsResult(OutputModel):
    """The limit of one parameter for a target SRT and, except for the overweight itself, its table over
    overweights."""

    parameter: LimitParameter = Field(description=describe("The parameter solved for.", unit="-"))
    kind: Literal["max", "min"] = Field(
        description=describe(
            "`max`: the SRT falls as the parameter grows, the limit is the largest acceptable value; `min`: the "
            "smallest.",
            unit="-",
        )
    )
    unit: str = Field(description=describe("Unit of `value`, `range_min`, `range_max` and `current_value`.", unit="-"))
    symbol: str = Field(description=describe("Thesis symbol of the parameter.", unit="-", symbol="l12, d1, b"))
    description: str = Field(description=describe("What the limit is.", unit="-"))
    target_srt_g: float = Field(description=describe("Target SRT.", unit="g", symbol="SRT target"))
    limit_on: LimitOn = Field(description=LIMIT_ON_TEXT)
    current_value: float = Field(
        description=describe("The parameter's value in the request (the base case).", unit="`unit`")
    )
    limit: LimitOut = Field(description=describe("The limit for the base case.", unit="see its fields"))
    table: list[LimitTableRowOut] | None = Field(
        description=describe(
            "The limit at each of `overweights_percent` (the rest of the base case unchanged); null for "
            "`parameter` = `overweight_percent`.",
            unit="see its fields",
        )
    )
    model: str = Field(description=describe("Model used.", unit="-"))
    stage: str | None = Field(description=describe("Stage (3d only).", unit="-", symbol="SRT_TS / SRT_3D"))
    warnings: list[InputWarningOut] = Field(description=WARNINGS_DESCRIPTION)
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))
