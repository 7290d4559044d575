"""The request of POST /v1/vehicles/payload-table: a single unit's builder spec or a combination's, a target."""

from __future__ import annotations

from typing import Annotated

from pydantic import ConfigDict, Field, model_validator

from app.http.schemas import (
    ABSENT,
    InputModel,
    describe,
    exactly_one_schema,
    json_int,
    not_together_schema,
    shape_error,
)
from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC, MAX_PAYLOADS, VehicleSpecIn
from app.vehicle_forms.combination_builder_schemas import CombinationSpecIn
from engine import builder as eb
from engine import builder as ec


class PayloadTableRequest(InputModel):
    """The acceptable payload table of a built vehicle (as TERNZ's results page shows it): for an SRT target, the
    largest payload mass at each load height and the largest load height at each payload mass, each solved with
    the engine on a level road with the nominal load case (the basis every SRT target is judged on): the 3D model's
    SRT for a single unit (`spec`), the governing SRT of the whole-combination model for a combination
    (`combination_spec`, the payload of its unit `unit_index`)."""

    model_config = ConfigDict(
        json_schema_extra={
            "allOf": [exactly_one_schema("spec", "combination_spec"), not_together_schema("unit_index", ["spec"])],
            "examples": [{"spec": EXAMPLE_SPEC, "target_srt_g": 0.45, "rows": 4}],
        }
    )

    spec: VehicleSpecIn = Field(  # type: ignore[valid-type]
        None,
        json_schema_extra=ABSENT,
        description=describe("A single unit's measurable spec (docs/vehicles.md).", unit="see its fields"),
    )
    combination_spec: CombinationSpecIn = Field(  # type: ignore[valid-type]
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "A combination's measurable spec (`POST /v1/combinations/build`), instead of `spec`.", unit="see its fields"
        ),
    )
    unit_index: json_int(ge=0, le=10) = Field(  # type: ignore[valid-type]
        None,
        json_schema_extra=ABSENT,
        description=describe(
            "With `combination_spec`: which unit's payload varies (default the last unit that carries one).", unit="-"
        ),
    )
    target_srt_g: float = Field(gt=0, lt=2, description=describe("The SRT to meet.", unit="g", symbol="SRT target"))
    payload_index: json_int(ge=0, lt=MAX_PAYLOADS) = Field(  # type: ignore[valid-type]
        0, description=describe("Which payload of the unit varies (a deck load).", unit="-")
    )
    load_heights_m: list[Annotated[float, Field(gt=0, le=10)]] | None = Field(
        None,
        min_length=1,
        max_length=20,
        description=describe(
            "Load heights of the first table (each above the deck); default `rows` heights up to the spec's.",
            unit="m",
        ),
    )
    payload_masses_kg: list[Annotated[float, Field(gt=0, le=200_000)]] | None = Field(
        None,
        min_length=1,
        max_length=20,
        description=describe("Payload masses of the second table; default `rows` masses up to the spec's.", unit="kg"),
    )
    rows: json_int(ge=1, le=20) = Field(  # type: ignore[valid-type]
        5, description=describe("Rows of each default table.", unit="count")
    )

    @model_validator(mode="after")
    def _one_vehicle(self) -> PayloadTableRequest:
        if (self.spec is None) == (self.combination_spec is None):
            field = "spec" if self.spec is None else "combination_spec"
            raise shape_error(
                "PayloadTableRequest", field, "give exactly one of spec (a single unit) and combination_spec"
            )
        if self.unit_index is not None and self.combination_spec is None:
            raise shape_error(
                "PayloadTableRequest", "unit_index", "unit_index selects a unit of a combination_spec; a spec has none"
            )
        return self

    def engine_spec(self) -> eb.VehicleSpec | ec.CombinationSpec:
        if self.combination_spec is not None:
            return ec.CombinationSpec.from_dict(self.combination_spec.model_dump(exclude_unset=True))
        return eb.VehicleSpec.from_dict(self.spec.model_dump(exclude_unset=True))
