"""GET /v1/models and GET /healthz."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from app.http.schemas import OutputModel, describe


class ModelInfoOut(OutputModel):
    id: str = Field(description=describe("Model id, the `model` of the POST endpoints.", unit="-"))
    name: str = Field(description=describe("Model name.", unit="-"))
    equation: str = Field(description=describe("Equation numbers in the thesis.", unit="-", symbol="Eq."))
    reference: str = Field(description=describe("Who published it.", unit="-"))
    takes: list[str] = Field(
        description=describe(
            "Road and load inputs the model accounts for (it refuses the others when non-zero).", unit="-"
        )
    )
    combination_takes: list[str] = Field(
        description=describe(
            "Road and load inputs the model accounts for when the vehicle is a combination (the whole-combination "
            "model solves the combination itself; a record model sees its last unit).",
            unit="-",
        )
    )
    summary: str = Field(description=describe("One line on the mechanics.", unit="-"))
    curves: bool = Field(description=describe("Whether the model can return curves against ay/g.", unit="-"))
    default: bool = Field(
        description=describe(
            "Whether this is the default model of a vehicle record (a combination's default is `combination`).",
            unit="-",
        )
    )


class Health(OutputModel):
    status: Literal["ok"] = Field(description=describe("Always `ok` while the service answers.", unit="-"))
    engine_version: str = Field(description=describe("Engine version.", unit="-"))
    cache_backend: Literal["memory", "redis"] = Field(description=describe("Configured cache backend.", unit="-"))
    redis: Literal["ok", "unavailable"] | None = Field(
        description=describe(
            "Shared cache state (null with the memory backend); the service answers either way.", unit="-"
        )
    )
    cache_entries: int = Field(description=describe("Entries in the in-process cache.", unit="count"))
