"""The vehicle record, in and out, generated from the engine's one definition of its fields.

Each field's type, bounds, unit, thesis symbol and description come from :data:`engine.vehicle.FIELD_DOCS`, so
the published schema states exactly the ranges the engine checks (the engine also checks what a schema cannot say:
track = axle width, springs inside the track, the CG below the tallest legal vehicle, no spring compressed to
nothing, roll stiffness above W l12, ... and answers 422 naming the field).
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import Field, create_model

from app.http.schemas import InputModel, OutputModel, describe, json_int
from engine.vehicle import FIELD_DOCS, FieldDoc

#: preset metadata that GET /v1/vehicles/{id} adds to a record (accepted and ignored in a posted record)
METADATA_FIELDS = ("id", "title", "source", "models")


def _type(doc: FieldDoc, required: bool, bounded: bool = True) -> Any:
    """The field's type, its range inside it (so an optional field's bounds apply to the number, not the null)."""
    base: Any = int if doc.integer else float
    if bounded:
        low = {"gt": doc.minimum} if doc.exclusive_minimum else {"ge": doc.minimum}
        bounds = {**low, "le": doc.maximum, **({"multiple_of": 2} if doc.even else {})}
        base = json_int(**bounds) if doc.integer else Annotated[float, Field(**bounds)]
    return base if required else base | None


def _text(doc: FieldDoc, extra: str = "") -> str:
    return describe(f"{doc.description}{extra} Range: {doc.bounds}.", unit=doc.unit, symbol=doc.symbol)


def _record_field(name: str, doc: FieldDoc) -> tuple[Any, Any]:
    if doc.required:
        return _type(doc, True), Field(description=_text(doc))
    return _type(doc, False), Field(None, description=_text(doc, " Null when the table does not give it."))


_IGNORED = describe("Preset metadata from GET /v1/vehicles/{id}; accepted and ignored.", unit="-")


class _RecordBase(InputModel):
    """A full vehicle record (the last unit of a combination, or a rigid truck). Same fields as
    ``GET /v1/vehicles/{id}`` returns; the preset metadata (``id``, ``title``, ``source``, ``models``) is accepted
    and ignored so a fetched preset can be edited and posted back."""

    def record(self) -> dict[str, Any]:
        """The engine record (metadata dropped)."""
        return self.model_dump(exclude=set(METADATA_FIELDS))


VehicleRecord = create_model(
    "VehicleRecord",
    __base__=_RecordBase,
    __doc__=_RecordBase.__doc__,
    **{name: _record_field(name, doc) for name, doc in FIELD_DOCS.items()},
    id=(str | None, Field(None, max_length=200, description=_IGNORED)),
    title=(str | None, Field(None, max_length=500, description=_IGNORED)),
    source=(str | None, Field(None, max_length=500, description=_IGNORED)),
    models=(list[str] | None, Field(None, max_length=20, description=_IGNORED)),
)


class _PresetBase(OutputModel):
    """A thesis preset: its id, title, source table, the models it suits, and its full record."""

    id: str = Field(description=describe("Preset id, usable as `vehicle` in the POST endpoints.", unit="-"))
    title: str = Field(description=describe("What the vehicle is.", unit="-"))
    source: str = Field(description=describe("Where the thesis gives it.", unit="-"))
    models: list[str] = Field(description=describe("Model ids the record has the fields for.", unit="-"))


VehiclePreset = create_model(
    "VehiclePreset",
    __base__=_PresetBase,
    __doc__=_PresetBase.__doc__,
    **{
        name: (
            _type(doc, doc.required, bounded=False),
            Field(description=describe(doc.description, unit=doc.unit, symbol=doc.symbol)),
        )
        for name, doc in FIELD_DOCS.items()
    },
)
