"""POST /v1/curve-speed (Eq. 9.1) and POST /v1/min-radius (Eqs. 9.2 and 9.3, f from a design standard)."""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import ABSENT, EXAMPLE_PRESET, OutputModel, bounded, describe, given, shape_error
from app.road.standards_schemas import BOUND_ONLY_WITH_TABLE21, DesignOptions
from app.srt.schemas import (
    LEVEL_ROAD_SRT_TEXT,
    VEHICLE_DESCRIPTION,
    SlopeIn,
    SrtInputs,
    SrtResult,
    SrtTargets,
    VehicleRef,
)
from engine.road import FRICTION_BOUNDS, STANDARDS

SRT_FIELDS = ("vehicle", "model", "stage", "road", "trailer_angle_deg", "load", "rear_llt_limit", "targets")
#: either a given SRT (and none of the SRT request fields) or a vehicle (the SRT is computed), never both
#: (inside allOf, where client generators keep the object model and still publish the rule)
SRT_OR_VEHICLE_SCHEMA = {
    "allOf": [
        {
            "oneOf": [
                {"required": ["srt"], "not": {"anyOf": [{"required": [f]} for f in SRT_FIELDS]}},
                {"required": ["vehicle"], "not": {"required": ["srt"]}},
            ]
        }
    ]
}


def check_srt_source(req: SrtInputs, model: str) -> None:
    """Either ``srt`` or the SRT request fields, never both (a given SRT already holds the bank)."""
    if req.srt is None and req.vehicle is None:
        raise shape_error(model, "srt", "give either srt (g) or vehicle (with the other SRT request fields)")
    if req.srt is None:
        return
    extra = given(req, SRT_FIELDS)
    if extra == ["targets"]:
        raise shape_error(
            model,
            "targets",
            "targets are checked against a computed SRT (the embedded srt_result); with a given srt there is none: "
            "leave targets out, or give the SRT request fields instead of srt",
        )
    if extra:
        raise shape_error(
            model,
            extra[0],
            f"{extra[0]} cannot be combined with srt: a given SRT already is the SRT on this curve's bank and slope "
            "(give either srt or the SRT request fields)",
        )


_GIVEN_SRT_TEXT = (
    "A known SRT for this curve's bank and slope (it already contains the bank: nothing is added to it). "
    "Give either `srt` or `vehicle` (with the other SRT request fields)."
)
_OPTIONAL_VEHICLE = VEHICLE_DESCRIPTION + " Give either `vehicle` (the SRT is computed) or `srt`."
SrtSource = Literal["given", "computed"]


class CurveSpeedRequest(SrtInputs, SrtTargets):
    """Maximum speed on a curve before rollover, V = sqrt(127 SRT R) (Eq. 9.1), from a given SRT or from the
    SRT request fields (the SRT is then computed for `road`'s bank and slope)."""

    model_config = ConfigDict(
        json_schema_extra={
            **SRT_OR_VEHICLE_SCHEMA,
            "examples": [
                {"radius_m": 80.0, "vehicle": EXAMPLE_PRESET, "model": "3d", "road": {"bank_percent": 0.0}},
                {"radius_m": 80.0, "srt": 0.3364},
            ],
        }
    )

    radius_m: float = bounded("radius_m", text="Curve radius.", symbol="R (Eq. 9.1)")
    srt: float = bounded("srt_g", None, text=_GIVEN_SRT_TEXT, symbol="SRT")
    vehicle: VehicleRef = Field(None, description=_OPTIONAL_VEHICLE, json_schema_extra=ABSENT)  # type: ignore[assignment]

    @model_validator(mode="after")
    def _srt_or_vehicle(self) -> CurveSpeedRequest:
        check_srt_source(self, "CurveSpeedRequest")
        return self


class MinRadiusRequest(SrtInputs, SrtTargets, DesignOptions):
    """Minimum curve radius for a design speed and superelevation: the side-friction radius of Eq. 9.2 with the
    design standard's f_max (or a given f), the rollover radius of Eq. 9.3 with the vehicle's SRT on that bank and
    slope, and the governing (larger) one. When the SRT is computed, the bank is `superelevation_percent`. Without
    a given `side_friction`, the design speed must lie in the standard's range (422 naming it)."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [*SRT_OR_VEHICLE_SCHEMA["allOf"], BOUND_ONLY_WITH_TABLE21],
            "examples": [
                {"design_speed_kmh": 60.0, "superelevation_percent": 8.0, "vehicle": EXAMPLE_PRESET, "model": "3d"},
                {
                    "design_speed_kmh": 80.0,
                    "superelevation_percent": 8.0,
                    "vehicle": EXAMPLE_PRESET,
                    "design_standard": "dnit-1999",
                },
                {"design_speed_kmh": 60.0, "superelevation_percent": 8.0, "srt": 0.285, "side_friction": 0.15},
            ],
        }
    )

    design_speed_kmh: float = bounded("speed_kmh", text="Design speed.", symbol="V")
    superelevation_percent: float = bounded(
        "design_superelevation_percent",
        text="Superelevation of the curve; also the bank of the computed SRT.",
        symbol="e (Eq. 9.2)",
    )
    side_friction: float | None = bounded(
        "side_friction",
        None,
        text="Design side-friction factor; when null it is the design standard's f_max at the design speed "
        "(linear between the tabulated speeds).",
        unit="-",
        symbol="f (Eq. 9.2)",
    )
    srt: float = bounded("srt_g", None, text=_GIVEN_SRT_TEXT, symbol="SRT")
    vehicle: VehicleRef = Field(None, description=_OPTIONAL_VEHICLE, json_schema_extra=ABSENT)  # type: ignore[assignment]

    road: SlopeIn = Field(
        default_factory=SlopeIn,
        description=describe(
            "The grade of the SRT's case (its bank is `superelevation_percent`).", unit="%", symbol="slope"
        ),
    )

    @model_validator(mode="after")
    def _srt_source(self) -> MinRadiusRequest:
        check_srt_source(self, "MinRadiusRequest")
        return self


class CurveSpeedResult(OutputModel):
    max_speed_kmh: float = Field(
        description=describe("Maximum speed before rollover, sqrt(127 SRT R).", unit="km/h", symbol="V (Eq. 9.1)")
    )
    radius_m: float = Field(description=describe("Curve radius.", unit="m", symbol="R"))
    srt: float = Field(
        description=describe(
            "SRT used (on this curve's bank and slope): the curve's threshold. The targets (in `srt_result`) are "
            "judged on `level_road_srt`.",
            unit="g",
            symbol="SRT",
        )
    )
    level_road_srt: float | None = Field(
        description=LEVEL_ROAD_SRT_TEXT + " Null with a given `srt` (there are no targets then)."
    )
    srt_source: SrtSource = Field(description=describe("`given` in the request or `computed`.", unit="-"))
    srt_result: SrtResult | None = Field(
        description=describe("The SRT computation, when the SRT was computed.", unit="see its fields", symbol="SRT")
    )
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))


_F_SOURCES = ("given", *(i for i in STANDARDS if i != "thesis-table21"), *(f"table21-{b}" for b in FRICTION_BOUNDS))
SideFrictionSource = Literal[_F_SOURCES]  # type: ignore[valid-type]


class MinRadiusResult(OutputModel):
    side_friction_min_radius_m: float = Field(
        description=describe(
            "Side-friction minimum radius V^2 / (127 (0.01 e + f)), with the standard's f_max or the given f.",
            unit="m",
            symbol="Rmin (Eq. 9.2)",
        )
    )
    aashto_min_radius_m: float = Field(
        deprecated=True,
        description=describe(
            "Deprecated (removed in the next version): the same value as `side_friction_min_radius_m`, under its "
            "old name (Eq. 9.2 is not only AASHTO's).",
            unit="m",
            symbol="Rmin (Eq. 9.2)",
        ),
    )
    rollover_min_radius_m: float = Field(
        description=describe("Rollover minimum radius V^2 / (127 SRT).", unit="m", symbol="Rmin (Eq. 9.3)")
    )
    governing_min_radius_m: float = Field(
        description=describe("The larger of the two minimum radii.", unit="m", symbol="max(Eq. 9.2, Eq. 9.3)")
    )
    governed_by: Literal["side-friction", "rollover"] = Field(
        description=describe("Which criterion gives the governing radius.", unit="-", symbol="Eq. 9.2 / Eq. 9.3")
    )
    side_friction: float = Field(description=describe("Side-friction factor used.", unit="-", symbol="f"))
    side_friction_source: SideFrictionSource = Field(
        description=describe(
            "`given`, or the table f was read from: a standard's id, or `table21-<bound>` for thesis-table21.",
            unit="-",
        )
    )
    design_standard: str = Field(description=describe("The design standard of the request.", unit="-"))
    design_speed_kmh: float = Field(description=describe("Design speed.", unit="km/h", symbol="V"))
    superelevation_percent: float = Field(description=describe("Superelevation.", unit="%", symbol="e"))
    srt: float = Field(
        description=describe(
            "SRT used (on this bank and slope): the curve's threshold, what Eq. 9.3 uses. The targets (in "
            "`srt_result`) are judged on `level_road_srt`.",
            unit="g",
            symbol="SRT",
        )
    )
    level_road_srt: float | None = Field(
        description=LEVEL_ROAD_SRT_TEXT + " Null with a given `srt` (there are no targets then)."
    )
    srt_source: SrtSource = Field(description=describe("`given` in the request or `computed`.", unit="-"))
    srt_result: SrtResult | None = Field(
        description=describe("The SRT computation, when the SRT was computed.", unit="see its fields", symbol="SRT")
    )
    engine_version: str = Field(description=describe("Engine version (part of the cache key).", unit="-"))
