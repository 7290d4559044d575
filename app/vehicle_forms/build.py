"""A vehicle form -> the engine's record: the one place the service builds a spec, a combination spec or a
combination, re-pointing the engine's errors at where the form sits in the request.

A ``{"spec": ...}`` is built by :func:`engine.builder.build_vehicle`, a ``{"combination_spec": ...}`` by
:func:`engine.builder.build_combination`, a ``{"combination": ...}`` is validated by
:func:`engine.vehicle.validate_combination`. The build endpoints, the resolution of a computation's vehicle
(:mod:`app.vehicles.resolve`) and the catalog's checks of a saved vehicle all call these.
"""

from __future__ import annotations

import re
from typing import Any

from engine import InvalidInput, InvalidVehicle
from engine.builder import (
    BuiltCombination,
    BuiltVehicle,
    CombinationSpec,
    VehicleSpec,
    build_combination,
    build_vehicle,
)
from engine.dynamics import DynamicsData
from engine.dynamics import resolve as resolve_dynamics
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
        built = build_combination(engine_spec)
        if built.dynamics:
            check_dynamics(built.combination, built.dynamics)
        return built
    except InvalidInput as e:
        raise at_field(e, where) from e


def check_dynamics(c: Combination, data: DynamicsData) -> None:
    """Refuse dynamic data the yaw-roll model refuses (a yaw inertia below the point-mass bound of the unit's own
    masses, a rear extent that leaves an axle outside its unit, a tyre type beside a coefficient...), naming the field
    where it was typed: the spec is refused when built or saved, not first when a dynamics answer needs it."""
    try:
        resolve_dynamics(c, data)
    except InvalidVehicle as e:
        raise typed_field(e, data) from e


_ENGINE_PATH = r"dynamics\.((?:units|groups)\[[^\]]+\]\.\w+)"
_ENGINE_FIELD = re.compile(_ENGINE_PATH + "$")
_ENGINE_PATHS = re.compile(_ENGINE_PATH)


def saved_place(where: str, saved_id: str, path: str) -> str:
    """Where a value stored in a saved vehicle sits, as the request gives it: the request's field that holds the
    saved id (``vehicle``), then the stored path, said to be the saved vehicle's
    (``vehicle (saved vehicle veh_...: combination_spec.units[1].dynamics.width_m)``). The user typed the id, not
    ``vehicle.combination_spec...``: no such path is in the request."""
    return f"{where} (saved vehicle {saved_id}: {path})"


def field_of(place: str) -> str:
    """The request's field of a place where a value was given: the place itself, or for a :func:`saved_place` the
    field that holds the saved id (an error's ``field``: a path into the request)."""
    return place.split(" (saved vehicle ", 1)[0]


def typed_field(exc: InvalidVehicle, data: DynamicsData) -> InvalidVehicle:
    """The yaw-roll model's error on a given value (``dynamics.units[<unit id>].<field>``) at the field where the
    value was typed (``data.given_at``), its message naming every given value by where it was typed; the error
    unchanged when not a given value's."""
    m = _ENGINE_FIELD.match(exc.field or "")
    if m is None or m.group(1) not in data.given_at:
        return exc
    message = _ENGINE_PATHS.sub(lambda k: data.given_at.get(k.group(1), k.group(0)), str(exc))
    return InvalidVehicle(message, field=field_of(data.given_at[m.group(1)]), value=exc.value)


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


def dynamics_at(built: BuiltCombination, where: str | None, saved_id: str | None = None) -> DynamicsData:
    """The built combination's data for the yaw-roll model, each value named where the request typed it
    (``vehicle.combination_spec.units[1].dynamics.width_m``), or for a saved vehicle's spec where the request gave
    its id (:func:`saved_place`)."""
    data = built.dynamics
    if not where:
        return data
    if saved_id is not None:
        return DynamicsData(
            data.units, data.groups, {k: saved_place(where, saved_id, v) for k, v in data.given_at.items()}
        )
    return DynamicsData(data.units, data.groups, {k: f"{where}.{v}" for k, v in data.given_at.items()})
