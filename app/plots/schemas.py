"""The plot endpoints (SVG): the thesis's figures for one vehicle and load case."""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from app.alignments.schemas import ALIGNMENT_LANDXML_EXAMPLE, AlignmentRequest
from app.http.schemas import ABSENT, EXAMPLE_PRESET, bounded, describe, json_int, shape_error
from app.road.standards_schemas import BOUND_ONLY_WITH_TABLE21, DesignOptions
from app.srt.schemas import SRT_EXAMPLE, VEHICLE_DESCRIPTION, SrtInputs, SrtOptions, VehicleRef
from engine import BOUNDS, DEFAULT_CURVE_POINTS, MAX_CURVE_POINTS
from engine.models import MODELS
from engine.road import get_standard

#: the models with curves against ay/g
CurveModelId = Literal[tuple(m.id for m in MODELS.values() if m.curves)]  # type: ignore[valid-type]
MAX_SPEED_POINTS = 181
#: spacing of the plotted design speeds when `points` is not given [km/h]
SPEED_STEP_KMH = 5.0


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


class MinRadiusPlotRequest(SrtOptions, DesignOptions):
    """Minimum radius against design speed for one superelevation (thesis Figs. 108-114): the side-friction radius
    of Eq. 9.2 with the design standard's f_max, and the rollover radius of Eq. 9.3 with the vehicle's SRT on that
    bank and slope. The speeds plotted lie in the standard's range (its whole range by default)."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [BOUND_ONLY_WITH_TABLE21],
            "examples": [
                {"vehicle": EXAMPLE_PRESET, "superelevation_percent": 8.0, "rear_llt_limit": 0.6},
                {
                    "vehicle": EXAMPLE_PRESET,
                    "superelevation_percent": 4.0,
                    "slope_percent": -4.0,
                    "rear_llt_limit": 0.6,
                    "load": {"vertical_offset_m": 0.5},
                    "design_standard": "thesis-table21",
                    "side_friction_bound": "mid",
                    "speed_min_kmh": 30.0,
                    "speed_max_kmh": 120.0,
                },
            ],
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
        None,
        gt=0,
        le=BOUNDS["speed_kmh"].maximum,
        json_schema_extra=ABSENT,
        description=describe(
            "Lowest design speed plotted; default the standard's lowest (GET /v1/design-standards). Inside the "
            "standard's range.",
            unit="km/h",
            symbol="V",
        ),
    )  # type: ignore[assignment]
    speed_max_kmh: float = Field(
        None,
        gt=0,
        le=BOUNDS["speed_kmh"].maximum,
        json_schema_extra=ABSENT,
        description=describe(
            "Highest design speed plotted, above speed_min_kmh; default the standard's highest.",
            unit="km/h",
            symbol="V",
        ),
    )  # type: ignore[assignment]
    points: json_int(ge=2, le=MAX_SPEED_POINTS) = Field(  # type: ignore[valid-type]
        None,
        json_schema_extra=ABSENT,
        description=describe(
            f"Design speeds plotted, evenly spaced; default one every {SPEED_STEP_KMH:g} km/h (at least 2).",
            unit="count",
        ),
    )

    @model_validator(mode="after")
    def _speed_range(self) -> MinRadiusPlotRequest:
        # (that the speeds lie in the standard's range is the engine's check: app.plots.service.plot_min_radius)
        v0, v1 = self.speed_min_kmh, self.speed_max_kmh
        if v0 is not None and v1 is not None and v1 <= v0:
            raise shape_error("MinRadiusPlotRequest", "speed_max_kmh", f"must be above speed_min_kmh ({v0:g} km/h)", v1)
        return self

    @property
    def speeds(self) -> tuple[float, float, int]:
        """The plotted design speeds: lowest, highest [km/h] and how many."""
        lo, hi = get_standard(self.design_standard, self.bound).speed_range_kmh
        v0 = lo if self.speed_min_kmh is None else self.speed_min_kmh
        v1 = hi if self.speed_max_kmh is None else self.speed_max_kmh
        n = self.points if self.points is not None else max(2, round((v1 - v0) / SPEED_STEP_KMH) + 1)
        return v0, v1, min(n, MAX_SPEED_POINTS)


class SpeedProfilePlotRequest(AlignmentRequest):
    """The alignment assessment's request (`POST /v1/alignments/assess`): the curves need stations (a road file)
    for a speed profile; a JSON or CSV list has none (a 422 saying so)."""

    model_config = ConfigDict(
        json_schema_extra={
            **AlignmentRequest.model_config["json_schema_extra"],
            "examples": [
                {
                    "vehicle": EXAMPLE_PRESET,
                    "landxml": {
                        "document": ALIGNMENT_LANDXML_EXAMPLE,
                        "superelevation_percent": 6.0,
                        "posted_speed_kmh": 80.0,
                    },
                    "units": "metric",
                }
            ],
        }
    )
