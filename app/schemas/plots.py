"""The plot endpoints (SVG): the thesis's figures for one vehicle and load case."""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from engine.domain import DEFAULT_CURVE_POINTS, MAX_CURVE_POINTS
from engine.models import MODELS
from engine.road import FRICTION_BOUNDS, TABLE21_SPEEDS_KMH

from .common import EXAMPLE_PRESET, bounded, describe, json_int, shape_error
from .srt import SRT_EXAMPLE, VEHICLE_DESCRIPTION, SrtInputs, SrtOptions, VehicleRef

#: the models with curves against ay/g
CurveModelId = Literal[tuple(m.id for m in MODELS.values() if m.curves)]  # type: ignore[valid-type]
V_MIN, V_MAX = float(TABLE21_SPEEDS_KMH[0]), float(TABLE21_SPEEDS_KMH[-1])
MAX_SPEED_POINTS = 181


class PlotRequest(SrtInputs):
    """The SRT request of the plotted case (2d or 3d model: the closed forms have no curves against ay/g) and
    the number of points of the curves, from rest to the limit."""

    model_config = ConfigDict(json_schema_extra={"examples": [{**SRT_EXAMPLE, "curve_points": 41}]})

    model: CurveModelId = Field(  # type: ignore[assignment]
        "3d",
        description=describe(
            "A model with curves against ay/g: `3d` (default) or `2d` (the closed forms have none).",
            unit="-",
            symbol="Chs. 5, 6 models",
        ),
    )
    curve_points: json_int(ge=2, le=MAX_CURVE_POINTS) = Field(  # type: ignore[valid-type]
        DEFAULT_CURVE_POINTS,
        description=describe("Points of each curve, from ay = 0 to the limit.", unit="count"),
    )


class MinRadiusPlotRequest(SrtOptions):
    """Minimum radius against design speed for one superelevation (thesis Figs. 108-114): AASHTO/DNIT Eq. 9.2
    with Table 21's side friction, and rollover Eq. 9.3 with the vehicle's SRT on that bank and slope."""

    model_config = ConfigDict(
        json_schema_extra={
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "superelevation_percent": 8.0,
                    "rear_llt_limit": 0.6,
                    "speed_min_kmh": 30.0,
                    "speed_max_kmh": 120.0,
                },
                {
                    "vehicle": EXAMPLE_PRESET,
                    "superelevation_percent": 4.0,
                    "slope_percent": -4.0,
                    "rear_llt_limit": 0.6,
                    "load": {"vertical_offset_m": 0.5},
                    "side_friction_bound": "mid",
                },
            ]
        }
    )

    vehicle: VehicleRef = Field(description=VEHICLE_DESCRIPTION)
    superelevation_percent: float = bounded(
        "design_superelevation_percent",
        text="Superelevation of the curves: the e of Eq. 9.2 and the bank of the SRT of Eq. 9.3.",
        symbol="e (Eq. 9.2)",
    )
    slope_percent: float = bounded(
        "slope_percent", 0.0, text="Grade of the SRT's case, + uphill.", symbol="slope (Eq. 4.24)"
    )
    speed_min_kmh: float = Field(
        V_MIN,
        ge=V_MIN,
        le=V_MAX,
        description=describe("Lowest design speed plotted (Table 21 covers 30-120 km/h).", unit="km/h", symbol="V"),
    )
    speed_max_kmh: float = Field(
        V_MAX,
        ge=V_MIN,
        le=V_MAX,
        description=describe("Highest design speed plotted; above speed_min_kmh.", unit="km/h", symbol="V"),
    )
    points: json_int(ge=2, le=MAX_SPEED_POINTS) = Field(  # type: ignore[valid-type]
        19,
        description=describe("Design speeds plotted, evenly spaced (19: every 5 km/h over 30-120).", unit="count"),
    )
    side_friction_bound: Literal[FRICTION_BOUNDS] = Field(  # type: ignore[valid-type]
        "low",
        description=describe(
            "Where to read Table 21's side-friction range: `low` (default, the conservative one), `mid` or `high`.",
            unit="-",
            symbol="f range (Table 21)",
        ),
    )

    @model_validator(mode="after")
    def _speed_range(self) -> MinRadiusPlotRequest:
        if self.speed_max_kmh <= self.speed_min_kmh:
            raise shape_error(
                "MinRadiusPlotRequest",
                "speed_max_kmh",
                f"must be above speed_min_kmh ({self.speed_min_kmh} km/h)",
                self.speed_max_kmh,
            )
        return self
