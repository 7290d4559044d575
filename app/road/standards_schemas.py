"""Design standards: the ``design_standard`` option of the road endpoints, GET /v1/design-standards and
POST /v1/superelevation."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import (
    ABSENT,
    InputModel,
    OutputModel,
    bounded,
    describe,
    json_int,
    not_together_schema,
    shape_error,
)
from engine import BOUNDS
from engine.road import DEFAULT_DESIGN_STANDARD, FRICTION_BOUNDS, STANDARDS

__all__ = [
    "DEFAULT_DESIGN_STANDARD",
    "DesignOptions",
    "StandardList",
    "StandardOut",
    "SuperelevationRequest",
    "SuperelevationTableRequest",
]
DesignStandardId = Literal[tuple(STANDARDS)]  # type: ignore[valid-type]
FrictionBound = Literal[FRICTION_BOUNDS]  # type: ignore[valid-type]

STANDARD_TEXT = describe(
    "The design standard whose side friction (and minimum radii, superelevation distribution) apply: "
    "`aashto-2018` (default: AASHTO Green Book 7th ed., Table 3-7, 20-120 km/h), `dnit-1999` (DNER/DNIT IPR-706, "
    "Quadros 5.4.3.1-5.4.3.2, 30-120 km/h) or `thesis-table21` (the thesis's Table 21 range, read at "
    "`side_friction_bound`, 30-120 km/h). A request that gives `side_friction_bound` without `design_standard` "
    "means `thesis-table21` (the only standard with a range to read). The design speeds accepted are the "
    "standard's range. See GET /v1/design-standards.",
    unit="-",
    symbol="f_max (Eq. 9.2)",
)
BOUND_TEXT = describe(
    "`thesis-table21` only: where to read Table 21's range, `low` (default: smaller f, larger radius), `mid` or "
    "`high`. Given alone it selects `thesis-table21`; refused with another `design_standard`, which has a single "
    "f_max per speed.",
    unit="-",
    symbol="f range (Table 21)",
)
#: side_friction_bound never with a design_standard other than thesis-table21 (alone, it selects thesis-table21)
BOUND_ONLY_WITH_TABLE21 = {
    "not": {
        "required": ["side_friction_bound", "design_standard"],
        "properties": {"design_standard": {"not": {"const": "thesis-table21"}}},
    }
}


class DesignOptions(InputModel):
    """The design standard of a road calculation."""

    design_standard: DesignStandardId = Field(DEFAULT_DESIGN_STANDARD, description=STANDARD_TEXT)
    side_friction_bound: FrictionBound = Field(None, description=BOUND_TEXT, json_schema_extra=ABSENT)  # type: ignore[assignment]

    @model_validator(mode="after")
    def _bound_for_table21_only(self):
        if self.side_friction_bound is not None and "design_standard" not in self.model_fields_set:
            self.design_standard = "thesis-table21"  # the bound alone names the only standard that has one
        if self.side_friction_bound is not None and self.design_standard != "thesis-table21":
            raise shape_error(
                type(self).__name__,
                "side_friction_bound",
                f"side_friction_bound applies to design_standard thesis-table21 only; {self.design_standard} has a "
                "single f_max per design speed",
                self.side_friction_bound,
            )
        return self

    @property
    def bound(self) -> str | None:
        """The Table 21 bound in force (``low`` unless given) for thesis-table21, else None."""
        if self.design_standard != "thesis-table21":
            return None
        return self.side_friction_bound or "low"


# --------------------------------------------------------------------------------- superelevation


class SuperelevationRequest(DesignOptions):
    """The design superelevation of a curve by the standard's distribution (AASHTO Method 5; DNIT's formula)."""

    model_config = ConfigDict(
        json_schema_extra={
            **BOUND_ONLY_WITH_TABLE21,
            "examples": [
                {
                    "design_standard": "aashto-2018",
                    "design_speed_kmh": 80,
                    "radius_m": 400,
                    "max_superelevation_percent": 8,
                },
                {
                    "design_standard": "dnit-1999",
                    "design_speed_kmh": 80,
                    "radius_m": 1000,
                    "max_superelevation_percent": 8,
                },
            ],
        }
    )

    design_speed_kmh: float = bounded("speed_kmh", text="Design speed of the curve.", symbol="V")
    radius_m: float = bounded("radius_m", text="Curve radius; at least the standard's R_min.", symbol="R")
    max_superelevation_percent: float = bounded(
        "max_superelevation_percent", text="The road's maximum superelevation e_max.", symbol="e_max"
    )


class SuperelevationResult(OutputModel):
    superelevation_percent: float = Field(
        description=describe("Design superelevation of the curve (unrounded).", unit="%", symbol="e")
    )
    side_friction: float = Field(
        description=describe("Side friction it leaves at the design speed, V^2/(127 R) - e/100.", unit="-", symbol="f")
    )
    f_max: float = Field(description=describe("The standard's f_max at the design speed.", unit="-", symbol="f_max"))
    min_radius_m: float = Field(
        description=describe("R_min for e_max (Eq. 9.2, unrounded: where e reaches e_max).", unit="m", symbol="R_min")
    )
    method: str = Field(description=describe("The distribution method and its source.", unit="-"))
    design_standard: str = Field(description=describe("The standard.", unit="-"))
    design_speed_kmh: float = Field(description=describe("Design speed.", unit="km/h", symbol="V"))
    radius_m: float = Field(description=describe("Curve radius.", unit="m", symbol="R"))
    max_superelevation_percent: float = Field(description=describe("e_max.", unit="%", symbol="e_max"))


# ------------------------------------------------------------------------------------ the list


class StandardOut(OutputModel):
    """One design standard, its citation and its tables."""

    id: str = Field(description=describe("Id, the `design_standard` of the road endpoints.", unit="-"))
    title: str = Field(description=describe("What it is.", unit="-"))
    citation: str = Field(description=describe("Full citation (document, edition, tables).", unit="-"))
    table: str = Field(description=describe("The table(s) the values come from.", unit="-"))
    speeds_kmh: list[float] = Field(description=describe("Tabulated design speeds.", unit="km/h", symbol="V"))
    f_max: list[float] = Field(
        description=describe(
            "Maximum side friction at each tabulated speed (linear in between).", unit="-", symbol="f_max"
        )
    )
    speed_range_kmh: list[float] = Field(
        description=describe("Lowest and highest design speed the standard covers.", unit="km/h")
    )
    max_superelevations_percent: list[float] = Field(
        description=describe("The e_max values the standard tabulates.", unit="%", symbol="e_max")
    )
    min_radius_table: dict[str, dict[str, float]] = Field(
        description=describe(
            "Published, rounded minimum radii by e_max then design speed (only the cells a source gave; elsewhere "
            "R_min is Eq. 9.2).",
            unit="m",
            symbol="R_min",
        )
    )
    superelevation_method: str | None = Field(
        description=describe("The superelevation distribution, or null (thesis-table21 has none).", unit="-")
    )
    side_friction_bounds: list[str] | None = Field(
        description=describe("thesis-table21 only: the bounds its range can be read at.", unit="-")
    )
    notes: str = Field(description=describe("Sources used and what could not be verified.", unit="-"))


class StandardList(OutputModel):
    """The design standards the road endpoints accept."""

    default: str = Field(description=describe("The standard a request that names none is designed to.", unit="-"))
    standards: list[StandardOut] = Field(description=describe("Every known standard.", unit="-"))


# ------------------------------------------------------------------------- superelevation table

MAX_TABLE_RADII = 500
#: default radii of the table: R_min to this multiple of it, geometrically spaced
TABLE_RADIUS_SPAN = 20.0
DEFAULT_TABLE_POINTS = 25


class SuperelevationTableRequest(DesignOptions):
    """The design superelevation over a set of radii at one design speed and e_max (the standard's distribution,
    as in the Green Book's and IPR-706's superelevation tables): the given `radii_m`, or `points` radii spaced
    geometrically from R_min to `radius_max_m`."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [BOUND_ONLY_WITH_TABLE21, not_together_schema("radii_m", ("radius_max_m", "points"))],
            "examples": [
                {"design_standard": "aashto-2018", "design_speed_kmh": 80, "max_superelevation_percent": 8},
                {
                    "design_standard": "dnit-1999",
                    "design_speed_kmh": 60,
                    "max_superelevation_percent": 8,
                    "radii_m": [125, 150, 200, 300, 500, 1000],
                },
            ],
        }
    )

    design_speed_kmh: float = bounded("speed_kmh", text="Design speed.", symbol="V")
    max_superelevation_percent: float = bounded(
        "max_superelevation_percent", text="The road's maximum superelevation e_max.", symbol="e_max"
    )
    radii_m: list[Annotated[float, Field(ge=BOUNDS["radius_m"].minimum, le=BOUNDS["radius_m"].maximum)]] = Field(
        None,
        min_length=1,
        max_length=MAX_TABLE_RADII,
        json_schema_extra=ABSENT,
        description=describe(
            f"Radii to tabulate (1-{MAX_TABLE_RADII}), each at least the standard's R_min (422 naming it). Not "
            "with `radius_max_m`/`points`.",
            unit="m",
            symbol="R",
        ),
    )  # type: ignore[assignment]
    radius_max_m: float = Field(
        None,
        gt=0,
        le=BOUNDS["radius_m"].maximum,
        json_schema_extra=ABSENT,
        description=describe(
            f"Largest radius of the default range (default {TABLE_RADIUS_SPAN:g} R_min); above R_min.",
            unit="m",
            symbol="R",
        ),
    )  # type: ignore[assignment]
    points: json_int(ge=2, le=MAX_TABLE_RADII) = Field(  # type: ignore[valid-type]
        DEFAULT_TABLE_POINTS,
        description=describe("Radii of the default range, spaced geometrically from R_min.", unit="count"),
    )

    @model_validator(mode="after")
    def _radii_or_range(self):
        if self.radii_m is not None and ({"radius_max_m", "points"} & self.model_fields_set):
            name = "radius_max_m" if "radius_max_m" in self.model_fields_set else "points"
            raise shape_error(
                type(self).__name__, name, f"{name} sets the default range of radii: not with radii_m", None
            )
        return self


class SuperelevationRow(OutputModel):
    radius_m: float = Field(description=describe("Curve radius.", unit="m", symbol="R"))
    superelevation_percent: float = Field(description=describe("Design superelevation.", unit="%", symbol="e"))
    side_friction: float = Field(
        description=describe("Side friction left at the design speed, V^2/(127 R) - e/100.", unit="-", symbol="f")
    )


class SuperelevationTableResult(OutputModel):
    design_standard: str = Field(description=describe("The standard.", unit="-"))
    method: str = Field(description=describe("The distribution method and its source.", unit="-"))
    design_speed_kmh: float = Field(description=describe("Design speed.", unit="km/h", symbol="V"))
    max_superelevation_percent: float = Field(description=describe("e_max.", unit="%", symbol="e_max"))
    f_max: float = Field(description=describe("The standard's f_max at the design speed.", unit="-", symbol="f_max"))
    min_radius_m: float = Field(description=describe("R_min for e_max (Eq. 9.2, unrounded).", unit="m", symbol="R_min"))
    rows: list[SuperelevationRow] = Field(description=describe("One row per radius, in the order given.", unit="-"))
