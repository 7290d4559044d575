"""Shared pieces of the schemas: strict model bases and field-description helpers."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict

#: the preset used in every request example
EXAMPLE_PRESET = "table16-btrain"


class InputModel(BaseModel):
    """Base of request bodies: unknown fields, NaN and infinities are refused, and types are strict (no
    coercion of ``0`` to ``false`` or ``"1.5"`` to ``1.5``: the body must match the published schema)."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True)


class OutputModel(BaseModel):
    """Base of response bodies: a non-finite number from the engine is an error, never a JSON null."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)


def describe(text: str, *, unit: str, symbol: str | None = None) -> str:
    """A field description that always names the unit and the thesis symbol ("-" when there is none)."""
    return f"{text} Unit: {unit}. Thesis symbol: {symbol or '-'}."
