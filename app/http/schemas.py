"""Shared pieces of the schemas: strict model bases and field-description helpers."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError
from pydantic_core import InitErrorDetails, PydanticCustomError, PydanticUndefined

from engine import BOUNDS

#: the preset used in every request example
EXAMPLE_PRESET = "table16-btrain"


class InputModel(BaseModel):
    """Base of request bodies: unknown fields, NaN and infinities are refused, and types are strict (no
    coercion of ``0`` to ``false`` or ``"1.5"`` to ``1.5``: the body must match the published schema)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True)


class OutputModel(BaseModel):
    """Base of response bodies: a non-finite number from the engine is an error, never a JSON null."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)


def _integral(value: Any) -> Any:
    """JSON Schema's ``integer`` is any number with a zero fractional part: 41.0 is 41 (41.5 and "41" are not)."""
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return value


def json_int(**constraints: Any) -> Any:
    """An integer request field as JSON Schema defines one (strict otherwise: no strings, no fractions), with its
    constraints (``ge``, ``le``, ``multiple_of``) on the integer itself, so the published schema states them."""
    return Annotated[int, Field(**constraints), BeforeValidator(_integral)]


JsonInt = json_int()


def describe(text: str, *, unit: str, symbol: str | None = None) -> str:
    """A field description that always names the unit and the thesis symbol ("-" when there is none)."""
    return f"{text} Unit: {unit}. Thesis symbol: {symbol or '-'}."


def _absent_means_none(schema: dict[str, Any]) -> None:
    """A field that is either given (a value, never null) or left out: the schema has no ``default: null``."""
    schema.pop("default", None)


#: ``json_schema_extra`` of a non-nullable field whose absence the server reads as None (left out, not null)
ABSENT = _absent_means_none


def bounded(
    name: str, default: Any = PydanticUndefined, *, text: str, symbol: str | None = None, unit: str | None = None
):
    """A request field bounded by :data:`engine.domain.BOUNDS` ``name`` (the engine checks the same range)."""
    b = BOUNDS[name]
    extra = {"json_schema_extra": ABSENT} if default is None else {}
    return Field(
        default, description=describe(text, unit=unit or b.unit or "-", symbol=symbol), **b.pydantic(), **extra
    )


def shape_error(model: str, field: str, message: str, value: Any = None) -> ValidationError:
    """A request-shape rule broken (``model_validator``): a validation error located at ``field`` (dotted)."""
    return ValidationError.from_exception_data(
        model,
        [
            InitErrorDetails(
                type=PydanticCustomError("request_shape", message), loc=tuple(field.split(".")), input=value
            )
        ],
    )


def given(model: BaseModel, names: tuple[str, ...] | list[str]) -> list[str]:
    """The fields of ``names`` the request set explicitly (a default left out is not given)."""
    return [n for n in names if n in model.model_fields_set]


def exactly_one_schema(*names: str) -> dict[str, Any]:
    """JSON Schema: exactly one of these properties (``oneOf`` of ``required``)."""
    return {"oneOf": [{"required": [n]} for n in names]}


def not_together_schema(first: str, others: tuple[str, ...] | list[str]) -> dict[str, Any]:
    """JSON Schema: ``first`` excludes every one of ``others`` (one other: both never together, without an
    ``anyOf`` of one schema)."""
    if len(others) == 1:
        return {"not": {"required": [first, *others]}}
    return {"not": {"required": [first], "anyOf": [{"required": [o]} for o in others]}}


class InputWarningOut(OutputModel):
    """A value answered as given that reads plausibly in another unit too (a light trailer's 50 kN, or 50 t typed
    as kN): the field as typed and both readings (engine.vehicle.plausibility.ambiguous_reading)."""

    field: str = Field(description=describe("The input as the request names it (`vehicle.weight_kn`).", unit="-"))
    value: float = Field(description=describe("The value as given, in the field's unit.", unit="the field's"))
    unit: str = Field(description=describe("The field's unit: the reading the answer used.", unit="-"))
    other_unit: str = Field(description=describe("The unit the same number may have been typed in.", unit="-"))
    other_reading: float = Field(
        description=describe("The value in the field's unit if it was typed in `other_unit`.", unit="the field's")
    )
    message: str = Field(description=describe("Both readings, in words.", unit="-"))


WARNINGS_DESCRIPTION = describe(
    "Inputs answered as given that read plausibly in another unit too (empty when none): check them. A value "
    "implausible in its unit is refused instead (422 naming the likely slip).",
    unit="see its fields",
)
