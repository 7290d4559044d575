"""The optional data of the yaw-roll model as HTTP fields, generated from its one definition
(:data:`engine.dynamics.UNIT_DATA_DOCS`, :data:`engine.dynamics.GROUP_DATA_DOCS`: description, unit and bounds of
each field), so that the dynamics requests' ``dynamics`` field, a combination spec's units and axle groups and the
page all offer the same fields with the same bounds.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, create_model

from app.http.schemas import InputModel, describe
from engine.dynamics import GROUP_DATA_DOCS, UNIT_DATA_DOCS

#: a group's axle spacing is the combination spec's group field ``axle_spacing_m``: not repeated in its ``dynamics``
SPEC_GROUP_OWN_FIELDS = ("axle_spacing_m",)


def optional_field(text: str, unit: str, low: Any, high: float | None = None) -> tuple[Any, Any]:
    """An optional number in [low, high], or an optional choice when ``low`` is the tuple of choices."""
    if isinstance(low, tuple):
        return (
            Literal[low] | None,
            Field(None, description=describe(text + " (the default when left out).", unit=unit)),
        )  # type: ignore[valid-type]
    return (
        float | None,
        Field(None, ge=low, le=high, description=describe(text + " (estimated when left out).", unit=unit)),
    )


def unit_fields() -> dict[str, tuple[Any, Any]]:
    """Every optional per-unit field of the yaw-roll model."""
    return {name: optional_field(*doc) for name, doc in UNIT_DATA_DOCS.items()}


def group_fields(exclude: tuple[str, ...] = ()) -> dict[str, tuple[Any, Any]]:
    """Every optional per-group field of the yaw-roll model, but ``exclude``."""
    return {name: optional_field(*doc) for name, doc in GROUP_DATA_DOCS.items() if name not in exclude}


#: a combination spec unit's ``dynamics``
UnitDynamicsSpec = create_model(
    "UnitDynamicsSpec",
    __base__=InputModel,
    __doc__="For the yaw-roll model only (the static answers do not use it): each field optional, estimated when "
    "left out (the dynamics answers' `parameters` say how).",
    **unit_fields(),
)
#: a combination spec axle group's ``dynamics`` (its axle spacing is the group's ``axle_spacing_m``)
GroupDynamicsSpec = create_model(
    "GroupDynamicsSpec",
    __base__=InputModel,
    __doc__="For the yaw-roll model only: each field optional, estimated (or the default tyre) when left out; the "
    "group's axle spacing is its `axle_spacing_m`.",
    **group_fields(SPEC_GROUP_OWN_FIELDS),
)
