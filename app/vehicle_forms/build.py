"""A vehicle form -> the engine's record: the one place the service builds a spec, a combination spec or a
combination, re-pointing the engine's errors at where the form sits in the request.

A ``{"spec": ...}`` is built by :func:`engine.builder.build_vehicle`, a ``{"combination_spec": ...}`` by
:func:`engine.builder.build_combination`, a ``{"combination": ...}`` is validated by
:func:`engine.vehicle.validate_combination`. The build endpoints, the resolution of a computation's vehicle
(:mod:`app.vehicles.resolve`) and the catalog's checks of a saved vehicle all call these.
"""

from __future__ import annotations

from typing import Any

from engine import InvalidInput
from engine.builder import (
    BuiltCombination,
    BuiltVehicle,
    CombinationSpec,
    VehicleSpec,
    build_combination,
    build_vehicle,
)
from engine.vehicle import Combination, check_record_plausible, validate_combination


def at_field(exc: InvalidInput, prefix: str | None) -> InvalidInput:
    """The engine's error with its field under ``prefix`` (``spec.rear.tyre.id`` -> ``vehicle.spec.rear.tyre.id``)."""
    if not prefix:
        return exc
    return type(exc)(str(exc), field=f"{prefix}.{exc.field}" if exc.field else prefix, value=exc.value)


def build_spec(spec: VehicleSpec | dict[str, Any], where: str | None = None) -> BuiltVehicle:
    """The built vehicle a spec describes; its errors name ``<where>.spec.<field>`` (``spec.<field>`` alone when
    ``where`` is None: the spec is the request's own)."""
    try:
        engine_spec = spec if isinstance(spec, VehicleSpec) else VehicleSpec.from_dict(spec)
        return build_vehicle(engine_spec)
    except InvalidInput as e:
        raise at_field(e, where) from e


def build_combination_spec(spec: CombinationSpec | dict[str, Any], where: str | None = None) -> BuiltCombination:
    """The built combination a spec describes; its errors name ``<where>.combination_spec.<field>``
    (``combination_spec.<field>`` when ``where`` is None: the spec is the request's own)."""
    try:
        engine_spec = spec if isinstance(spec, CombinationSpec) else CombinationSpec.from_dict(spec)
        return build_combination(engine_spec)
    except InvalidInput as e:
        raise at_field(e, where) from e


def combination_of(data: dict[str, Any], where: str | None) -> Combination:
    """The engine's combination of a ``combination`` object, validated; its errors name ``<where>.combination.<...>``
    (``combination.<...>`` when ``where`` is None: the request's own vehicle)."""
    try:
        c = Combination.from_dict(data)
        validate_combination(c)
        if c.last_unit_record is not None:  # typed like any record: the same unit-slip bounds (issue 40 item 5)
            check_record_plausible(c.last_unit_record, "combination.last_unit_record.")
    except InvalidInput as e:
        raise at_field(e, where) from e
    return c
