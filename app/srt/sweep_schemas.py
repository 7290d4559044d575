"""POST /v1/srt/sweep: the SRT over a grid of cases (the thesis's Tables 17 and 19 in one call)."""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import (
    ABSENT,
    EXAMPLE_PRESET,
    WARNINGS_DESCRIPTION,
    InputModel,
    InputWarningOut,
    OutputModel,
    describe,
    shape_error,
)
from app.srt.schemas import LEVEL_ROAD_SRT_TEXT, TARGETS_OUT, TILT_OUT, SrtInputs, SrtTargets, TargetCheckOut
from engine import BOUNDS

MAX_AXIS_VALUES = 200
#: a synchronous sweep's cases, the rows of its answer: the synchronous batch answers' one size (alignments: MAX_ROWS)
MAX_CASES = 10_000
#: an ``srt.sweep`` job's limit (:mod:`app.jobs.op_sweep`), named by the synchronous limit's error
MAX_JOB_CASES = 1_000_000
#: 8 axes x 200 values of up to ~25 characters, with the base case: 256 KiB is ample [bytes]
SWEEP_BODY_LIMIT = 256 * 1024

#: axis -> (unit, thesis symbol, text); the bounds are those of the same field of the SRT request
AXES: dict[str, tuple[str, str, str]] = {
    "bank_percent": ("%", "e, phi", "Bank (superelevation), + toward the inside of the curve."),
    "slope_percent": ("%", "slope", "Longitudinal grade, + uphill."),
    "trailer_angle_deg": ("deg", "psi", "Angle between the last two units (3d only)."),
    "lateral_offset_m": ("m", "d1", "Lateral CG offset, + toward the outside of the turn."),
    "longitudinal_offset_m": ("m", "d2", "Longitudinal CG offset, + toward the front."),
    "vertical_offset_m": ("m", "d3", "Vertical CG offset, + up."),
    "overweight_percent": ("%", "overweight", "Extra weight over the nominal W."),
    "rear_llt_limit": ("-", "LLTr", "Rear lateral load transfer at which the ramp stops."),
}
AXIS_ORDER = tuple(AXES)


def _values(name: str) -> Any:
    """The grid field of one axis: 1-200 values within the SRT request's bounds for that field."""
    unit, symbol, text = AXES[name]
    return Field(
        None,
        min_length=1,
        max_length=MAX_AXIS_VALUES,
        json_schema_extra=ABSENT,
        description=describe(
            f"{text} Values of this axis (1-{MAX_AXIS_VALUES}); leave the field out for no axis.",
            unit=unit,
            symbol=symbol,
        ),
    )


def _value(name: str) -> Any:
    return Annotated[float, Field(**BOUNDS[name].pydantic())]


BankValue = _value("bank_percent")
SlopeValue = _value("slope_percent")
AngleValue = _value("trailer_angle_deg")
D1Value = _value("lateral_offset_m")
D2Value = _value("longitudinal_offset_m")
D3Value = _value("vertical_offset_m")
OverweightValue = _value("overweight_percent")
LltValue = _value("rear_llt_limit")


class SweepGrid(InputModel):
    """The axes to vary (at least one) and their values. The cases are the Cartesian product of the axes, in
    this fixed order whatever their order in the request (a JSON object has none): `bank_percent`,
    `slope_percent`, `trailer_angle_deg`, `lateral_offset_m`, `longitudinal_offset_m`, `vertical_offset_m`,
    `overweight_percent`, `rear_llt_limit`; the first axis varies slowest. An axis overrides the base case's
    field of the same name."""

    # an axis is given (a list, never null) or left out, and no other field is allowed: at least one property is
    # at least one axis (minProperties, which generated clients parse, unlike an anyOf of required branches)
    model_config = ConfigDict(json_schema_extra={"minProperties": 1})

    bank_percent: list[BankValue] = _values("bank_percent")
    slope_percent: list[SlopeValue] = _values("slope_percent")
    trailer_angle_deg: list[AngleValue] = _values("trailer_angle_deg")
    lateral_offset_m: list[D1Value] = _values("lateral_offset_m")
    longitudinal_offset_m: list[D2Value] = _values("longitudinal_offset_m")
    vertical_offset_m: list[D3Value] = _values("vertical_offset_m")
    overweight_percent: list[OverweightValue] = _values("overweight_percent")
    rear_llt_limit: list[LltValue] = _values("rear_llt_limit")

    def axes(self) -> dict[str, list[float]]:
        """The given axes, in the product's order."""
        return {a: list(getattr(self, a)) for a in AXIS_ORDER if getattr(self, a) is not None}


class SweepRequest(SrtInputs, SrtTargets):
    """The SRT over a grid: the SRT request fields are the base case, `grid` the axes to vary (at most
    10,000 cases; a larger grid goes to a job: `POST /v1/jobs`, `srt.sweep`). Table 17 is bank x slope at a rear
    LLT limit of 0.6; Table 19 adds the trailer angle. `Accept: text/csv` answers the rows as CSV with a header row."""

    model_config = ConfigDict(
        json_schema_extra={
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "rear_llt_limit": 0.6,
                    "grid": {"bank_percent": [0, 4, 8], "slope_percent": [-12, -4, 0, 4, 12]},
                },
                {"vehicle": EXAMPLE_PRESET, "grid": {"overweight_percent": [0, 10, 20, 30]}},
            ]
        }
    )

    grid: SweepGrid = Field(
        description=describe(
            f"Axes to vary and their values (at least one axis, 1-{MAX_AXIS_VALUES} values each, and at most "
            f"{MAX_CASES:,} cases in all: the product of the axes' lengths; a larger grid goes to a job, `srt.sweep`).",
            unit="per axis",
            symbol="Tables 17, 19",
        )
    )

    @model_validator(mode="after")
    def _grid_size(self) -> SweepRequest:
        axes = self.grid.axes()
        if not axes:
            raise shape_error("SweepRequest", "grid", f"give at least one axis to vary: {', '.join(AXIS_ORDER)}")
        cases = math.prod(len(v) for v in axes.values())
        if cases > MAX_CASES:
            sizes = " x ".join(f"{len(v)} {a}" for a, v in axes.items())
            raise shape_error(
                "SweepRequest",
                "grid",
                f"{sizes} = {cases} cases; at most {MAX_CASES} per request; larger work goes to a job: POST "
                '/v1/jobs with {"operation": "srt.sweep", "request": <this request>} takes up to '
                f"{MAX_JOB_CASES:,} cases (docs/jobs.md)",
            )
        return self


def _row_axis(name: str) -> Any:
    unit, symbol, text = AXES[name]
    return Field(None, description=describe(f"{text} Present only when swept.", unit=unit, symbol=symbol))


class SweepRow(OutputModel):
    """One case: the swept axes' values (only those), then the results."""

    bank_percent: float | None = _row_axis("bank_percent")
    slope_percent: float | None = _row_axis("slope_percent")
    trailer_angle_deg: float | None = _row_axis("trailer_angle_deg")
    lateral_offset_m: float | None = _row_axis("lateral_offset_m")
    longitudinal_offset_m: float | None = _row_axis("longitudinal_offset_m")
    vertical_offset_m: float | None = _row_axis("vertical_offset_m")
    overweight_percent: float | None = _row_axis("overweight_percent")
    rear_llt_limit: float | None = _row_axis("rear_llt_limit")
    srt: float | None = Field(
        description=describe(
            "SRT of the case (on its bank and slope: the curve's threshold); null when refused (see `error`). The "
            "targets are judged on `level_road_srt`.",
            unit="g",
            symbol="SRT",
        )
    )
    level_road_srt: float | None = Field(
        description=LEVEL_ROAD_SRT_TEXT + " Of this row's case (its other axes' values); null when that case is "
        "refused (then `targets` is empty)."
    )
    roll_angle_deg: float | None = Field(
        description=describe(
            "Total body roll at the limit; null when refused or for the rigid closed forms.",
            unit="deg",
            symbol="theta_3D",
        )
    )
    tilt_table_angle_deg: float | None = Field(description=TILT_OUT + " Null when refused.")
    targets: list[TargetCheckOut] = Field(description=TARGETS_OUT + " Empty when refused.")
    error: str | None = Field(
        description=describe("Why the engine refused or could not solve the case (null otherwise).", unit="-")
    )


class SweepResult(OutputModel):
    """The SRT of every case of the grid; a case the engine refuses keeps its row, with `error`."""

    model: str = Field(description=describe("Model used.", unit="-"))
    stage: str | None = Field(description=describe("Stage (3d only).", unit="-", symbol="SRT_TS / SRT_3D"))
    axes: list[str] = Field(
        description=describe("The swept axes, in the product's order (the first varies slowest).", unit="-")
    )
    cases: int = Field(description=describe("Number of cases (rows).", unit="count"))
    refused: int = Field(description=describe("Cases without an SRT (rows with `error`).", unit="count"))
    warnings: list[InputWarningOut] = Field(description=WARNINGS_DESCRIPTION)
    rows: list[SweepRow] = Field(description=describe("One row per case, in the product's order.", unit="per field"))
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))
