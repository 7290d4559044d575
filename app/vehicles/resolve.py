"""A request's vehicle references -> engine records, in one step before the service.

A computation's ``vehicle`` (and an alignment's, a route's or an advisory's ``vehicles``, or a ``fleet``) may be

* a preset id (``table16-btrain``, ``btrain-table16``): the preset's record or combination;
* a full record: checked (its weight and stiffnesses in plausible units) and used as it is;
* ``{"spec": {...}}``: built into a record by :func:`engine.builder.build_vehicle`;
* ``{"combination": {...}}``: a combination, validated;
* ``{"combination_spec": {...}}``: built into a combination by :func:`engine.builder.build_combination`;
* a saved vehicle's id (``veh_...``) or a fleet's id (``flt_...``): read from the catalog with the caller's bearer
  key (:class:`app.catalog.service.SavedVehicles`, the catalog's one read; another key's or a deleted id is a 404
  naming it), then as above.

:func:`resolve_request` is the one step: the router calls it once with the validated request, and hands the
service a :class:`VehicleRequest`: the request **unchanged** and a :class:`ResolvedVehicle` per vehicle (in the
request's order; a fleet's members in the fleet's order), each with its engine record, where it was typed, its kind,
its preset or saved id and the warnings of a typed record. Nothing is written into the request, and no service
resolves a reference again. A new endpoint that takes a vehicle needs its schema field
(:data:`app.srt.schemas.VehicleRef`) and this call.

The cache key of an answer is derived from the engine records (never from the reference), so editing a saved
vehicle changes its key and never serves a stale answer. Reading one needs the caller's bearer key, so the raw-body
fast path (:mod:`app.http.fastpath`), which never replays a request with credentials, never answers such a request
from its bytes.

A job's worker rebuilds the vehicles of a stored resolved request from their records
(:func:`vehicle_of_resolved`): that is reading data back from the job store, checked as outside data.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, Generic, Literal, TypeVar

from fastapi import Request
from pydantic import BaseModel

from app.catalog.service import SavedVehicles
from app.settings import Settings
from app.vehicle_forms.build import build_combination_spec, build_spec, combination_of, dynamics_at
from app.vehicle_forms.builder_schemas import SpecRef
from app.vehicle_forms.combination_builder_schemas import CombinationSpecRef
from app.vehicle_forms.combination_schemas import CombinationRef
from app.vehicle_forms.schemas import VehicleRecord
from engine import UnknownPreset
from engine.dynamics import DynamicsData
from engine.vehicle import (
    COMBINATIONS,
    PRESETS,
    Combination,
    InputWarning,
    Vehicle,
    check_record_plausible,
    get_combination,
    get_preset,
    record_warnings,
)

#: the form a vehicle was given in (a saved vehicle is ``saved``, whatever its stored form)
RefKind = Literal["preset", "saved", "record", "spec", "combination", "combination_spec"]

Req = TypeVar("Req", bound=BaseModel)


@dataclass(frozen=True)
class ResolvedVehicle:
    """One vehicle of a request as the engine takes it.

    Attributes
    ----------
    where : str
        Where it was given, as the user typed it: ``vehicle``, ``vehicles[2]``, ``fleet[1]``.
    kind : str
        The form it was given in (:data:`RefKind`).
    vehicle : Vehicle or Combination
        The engine's record.
    preset : str or None
        The preset id, for a preset (also a fleet's preset member).
    saved_id : str or None
        The saved vehicle's id, for a saved vehicle (also a fleet's member).
    warnings : tuple of InputWarning
        A typed record's fields that read plausibly in another unit too
        (:func:`engine.vehicle.plausibility.record_warnings`, named ``<where>.<field>``), a saved record's likewise
        (a fleet's member: ``fleet[0].weight_kn``), and a typed or saved combination's ``last_unit_record``'s
        (``vehicle.combination.last_unit_record.weight_kn``); none for the other kinds (their weights are derived
        from masses in kg).
    dynamics : DynamicsData
        The data for the yaw-roll model a combination spec gives (its units' and groups' ``dynamics``, its groups'
        axle spacings), each value named where it was typed (``given_at``); empty for the other kinds. Not part of the
        record, so the static answers (keyed by the record) do not depend on it.
    """

    where: str
    kind: RefKind
    vehicle: Vehicle | Combination
    preset: str | None = None
    saved_id: str | None = None
    warnings: tuple[InputWarning, ...] = ()
    dynamics: DynamicsData = field(default_factory=DynamicsData)


@dataclass(frozen=True)
class VehicleRequest(Generic[Req]):
    """A validated request, unchanged, beside its resolved vehicles (what a service takes)."""

    body: Req
    vehicles: tuple[ResolvedVehicle, ...]

    @property
    def vehicle(self) -> ResolvedVehicle | None:
        """The request's single ``vehicle`` (None when it gives none: a curve speed with its SRT given)."""
        if len(self.vehicles) > 1:
            raise ValueError(f"the request has {len(self.vehicles)} vehicles, not one")
        return self.vehicles[0] if self.vehicles else None

    @property
    def engine_vehicles(self) -> list[Vehicle | Combination]:
        """The engine records, in order."""
        return [v.vehicle for v in self.vehicles]

    @property
    def warnings(self) -> tuple[dict[str, Any], ...]:
        """Every vehicle's input warnings, in order, as the answers write them (and their keys hold them: they
        depend on how and where a record was typed, not on the record alone)."""
        return tuple(dataclasses.asdict(w) for v in self.vehicles for w in v.warnings)


def vehicle_preset(preset_id: str) -> Vehicle | Combination:
    """The vehicle or combination preset with this id; :class:`UnknownPreset` listing both kinds of id otherwise."""
    if preset_id in COMBINATIONS:
        return get_combination(preset_id)
    if preset_id in PRESETS:
        return get_preset(preset_id)
    raise UnknownPreset(preset_id, sorted([*PRESETS, *COMBINATIONS]))


def vehicle_of_resolved(data: dict[str, Any]) -> Vehicle | Combination:
    """The engine vehicle of a stored resolved request's ``vehicles[i]`` (``to_dict()`` of a record, or of a
    combination: ``{"combination": {...}}``), as a job's worker rebuilds it from the job store."""
    if "combination" in data:
        return Combination.from_dict(data["combination"])
    return Vehicle.from_dict(data)


def _last_unit_warnings(c: Combination, where: str) -> tuple[InputWarning, ...]:
    """A typed combination's ``last_unit_record`` (a vehicle record, for the 3D model of its last unit) warns as a
    typed record does, named ``<where>.combination.last_unit_record.<field>``."""
    if c.last_unit_record is None:
        return ()
    return tuple(record_warnings(c.last_unit_record, f"{where}.combination.last_unit_record."))


def resolve_given(ref: Any, where: str) -> ResolvedVehicle:
    """A reference that needs no catalog (a preset id, a record, a spec, a combination or a combination spec)
    resolved; its errors name ``where`` (``vehicle.spec.rear.tyre.id``). A saved vehicle's id is an unknown preset
    here: :func:`resolve_request` reads those."""
    if isinstance(ref, str):
        return ResolvedVehicle(where, "preset", vehicle_preset(ref), preset=ref)
    if isinstance(ref, SpecRef):
        return ResolvedVehicle(where, "spec", build_spec(ref.engine_spec(), where).vehicle)
    if isinstance(ref, CombinationRef):
        c = combination_of(ref.combination.engine_dict(), where)
        return ResolvedVehicle(where, "combination", c, warnings=_last_unit_warnings(c, where))
    if isinstance(ref, CombinationSpecRef):
        built = build_combination_spec(ref.engine_spec(), where)
        return ResolvedVehicle(where, "combination_spec", built.combination, dynamics=dynamics_at(built, where))
    if isinstance(ref, VehicleRecord):
        vehicle = Vehicle.from_dict(ref.record())
        # typed over HTTP: its weight and stiffnesses in plausible units, a slip named where it was typed
        # (vehicles[1].weight_kn, answered as vehicles.1.weight_kn), not as the request's single vehicle
        check_record_plausible(vehicle, f"{where}.")
        warnings = tuple(record_warnings(vehicle, f"{where}."))
        return ResolvedVehicle(where, "record", vehicle, warnings=warnings)
    raise TypeError(f"{where}: not a vehicle reference: {type(ref).__name__}")


def _stored(id: str, body: dict[str, Any], where: str) -> ResolvedVehicle:
    """A saved vehicle's stored body (a full record, ``{"spec": ...}``, ``{"combination": ...}`` or
    ``{"combination_spec": ...}``, validated by the catalog as it was read) as the engine's record."""
    if "spec" in body:
        vehicle: Vehicle | Combination = build_spec(body["spec"], where).vehicle
    elif "combination_spec" in body:
        built = build_combination_spec(body["combination_spec"], where)
        dynamics = dynamics_at(built, where, saved_id=id)
        return ResolvedVehicle(where, "saved", built.combination, saved_id=id, dynamics=dynamics)
    elif "combination" in body:
        vehicle = combination_of(body["combination"], where)
        return ResolvedVehicle(where, "saved", vehicle, saved_id=id, warnings=_last_unit_warnings(vehicle, where))
    else:
        vehicle = Vehicle.from_dict({k: v for k, v in body.items() if k in Vehicle.__dataclass_fields__})
        # a record its owner typed when saving it: what reads plausibly in another unit too warns as a typed one does,
        # named where the request gives it (vehicles[1].weight_kn, fleet[0].weight_kn; the saved id is beside it)
        warnings = tuple(record_warnings(vehicle, f"{where}."))
        return ResolvedVehicle(where, "saved", vehicle, saved_id=id, warnings=warnings)
    return ResolvedVehicle(where, "saved", vehicle, saved_id=id)


def _refs(body: BaseModel) -> tuple[list[tuple[str, Any]], str | None]:
    """The request's references with where each sits, and its fleet id (None without)."""
    fields = type(body).model_fields
    refs: list[tuple[str, Any]] = []
    if "vehicle" in fields and getattr(body, "vehicle", None) is not None:
        refs.append(("vehicle", body.vehicle))  # type: ignore[attr-defined]
    if "vehicles" in fields and getattr(body, "vehicles", None) is not None:
        refs.extend((f"vehicles[{i}]", v) for i, v in enumerate(body.vehicles))  # type: ignore[attr-defined]
    fleet = getattr(body, "fleet", None) if "fleet" in fields else None
    return refs, fleet


async def resolve_request(request: Request, body: Req, settings: Settings) -> VehicleRequest[Req]:
    """The one step: ``body`` (unchanged) and its vehicles resolved (``vehicle``, then ``vehicles``, then a fleet's
    members in the fleet's order).

    Raises the catalog's problems (401/403/404 naming the id, 409 for a stored row that fails validation) for saved
    ids and fleets, :class:`~engine.errors.UnknownPreset` (404) for an unknown preset id, and
    :class:`~engine.errors.InvalidVehicle` naming the field for a spec, combination or record the engine refuses.
    """
    refs, fleet = _refs(body)
    catalog = SavedVehicles(request, settings)
    out: list[ResolvedVehicle] = []
    for where, ref in refs:
        if isinstance(ref, str) and catalog.is_saved_id(ref):
            out.append(_stored(ref, await catalog.vehicle(ref), where))
        else:
            out.append(resolve_given(ref, where))
    if fleet is not None:
        for i, (id, stored) in enumerate(await catalog.fleet(fleet)):
            where = f"fleet[{i}]"
            out.append(resolve_given(id, where) if stored is None else _stored(id, stored, where))
    return VehicleRequest(body, tuple(out))


def resolve_request_given(body: Req) -> VehicleRequest[Req]:
    """:func:`resolve_request` of a request without saved ids or a fleet (no catalog: a script, a test, a stored
    request of presets and records)."""
    refs, fleet = _refs(body)
    if fleet is not None:
        raise ValueError("a fleet needs the catalog: resolve_request")
    return VehicleRequest(body, tuple(resolve_given(ref, where) for where, ref in refs))
