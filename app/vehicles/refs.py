"""Vehicle references in a request -> engine records: preset ids, saved vehicles, builder specs and fleets.

A computation's ``vehicle`` (and the alignment's ``vehicles`` or ``fleet``) may be

* a preset id (``table16-btrain``): public; the service expands it itself;
* a full record: used as it is;
* ``{"spec": {...}}``: built into a record by :func:`engine.vehicle.builder.build_vehicle`;
* ``{"combination": {...}}``: a combination record, validated;
* ``{"combination_spec": {...}}``: built into a combination by :func:`engine.vehicle.builder.build_combination`;
* a saved vehicle's id (``veh_...``) or, in a batch, a fleet's id (``flt_...``): read from the catalog with the
  caller's bearer key (another key's or a deleted id is a 404 naming it), then as above.

:func:`resolve_vehicle_refs` replaces every saved id, fleet, spec and combination spec of a validated request by
the engine's :class:`~engine.vehicle.Vehicle` (or :class:`~engine.vehicle.Combination`) before the service sees it,
so the cache key is derived from the resolved record: editing a saved vehicle changes its key and never serves a
stale answer. Reading one needs the caller's bearer key,
so the raw-body fast path (:mod:`app.http.fastpath`), which never replays a request with credentials, never answers
such a request from its bytes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from fastapi import Request
from fastapi.security import HTTPAuthorizationCredentials
from fastapi.security.utils import get_authorization_scheme_param
from pydantic import BaseModel

from app.catalog import service as catalog
from app.catalog.auth import authenticate
from app.settings import Settings
from app.vehicle_forms.build import build_combination_spec, build_spec, combination_of
from app.vehicle_forms.builder_schemas import SpecRef
from app.vehicle_forms.combination_builder_schemas import CombinationSpecRef
from app.vehicle_forms.combination_schemas import CombinationRef
from engine.errors import UnknownPreset
from engine.vehicle import (
    COMBINATIONS,
    PRESETS,
    Combination,
    Vehicle,
    get_combination,
    get_preset,
)
from engine.vehicle.plausibility import check_record_plausible


@dataclass(frozen=True)
class SavedRef:
    """A saved vehicle resolved: its id (reported back in batch answers) and its engine record."""

    id: str
    vehicle: Vehicle | Combination


def vehicle_preset(preset_id: str) -> Vehicle | Combination:
    """The vehicle or combination preset with this id; :class:`UnknownPreset` listing both kinds of id otherwise."""
    if preset_id in COMBINATIONS:
        return get_combination(preset_id)
    if preset_id in PRESETS:
        return get_preset(preset_id)
    raise UnknownPreset(preset_id, sorted([*PRESETS, *COMBINATIONS]))


def resolve_vehicle(ref: Any) -> Vehicle | Combination:
    """A preset id -> the preset's record or combination (UnknownPreset -> 404); a record -> the engine record;
    ``{"combination": ...}`` -> the engine combination; an engine vehicle (a saved vehicle or a spec resolved by
    :func:`app.vehicles.refs.resolve_vehicle_refs`) as it is."""
    if isinstance(ref, Vehicle | Combination):
        return ref
    if isinstance(ref, SavedRef):
        return ref.vehicle
    if isinstance(ref, str):
        return vehicle_preset(ref)
    if isinstance(ref, CombinationRef):
        return combination_of(ref.combination.engine_dict(), None)
    if isinstance(ref, CombinationSpecRef):
        return build_combination_spec(ref.engine_spec(), None).combination
    vehicle = Vehicle.from_dict(ref.record())
    check_record_plausible(vehicle)  # a record typed over HTTP: its weight and stiffnesses in plausible units
    return vehicle


def vehicle_of_resolved(data: dict[str, Any]) -> Vehicle | Combination:
    """The engine vehicle of a resolved request's ``vehicles[i]`` (``to_dict()`` of a record, or of a combination:
    ``{"combination": {...}}``), as a batch (alignment, route, job part) rebuilds it."""
    if "combination" in data:
        return Combination.from_dict(data["combination"])
    return Vehicle.from_dict(data)


def _credentials(request: Request) -> HTTPAuthorizationCredentials | None:
    scheme, token = get_authorization_scheme_param(request.headers.get("authorization"))
    if scheme.lower() != "bearer" or not token:
        return None
    return HTTPAuthorizationCredentials(scheme=scheme, credentials=token)


class _Resolver:
    """Resolves the references of one request (the catalog opened and the key checked at most once)."""

    def __init__(self, request: Request, settings: Settings) -> None:
        self.request = request
        self.settings = settings
        self._owner: str | None = None

    async def owner(self) -> str:
        if self._owner is None:
            self._owner = authenticate(_credentials(self.request), self.settings)
        return self._owner

    @staticmethod
    def stored(id: str, body: dict[str, Any], where: str) -> SavedRef:
        """A stored vehicle body (a full record, ``{"spec": ...}``, ``{"combination": ...}`` or
        ``{"combination_spec": ...}``) as the engine's."""
        if "spec" in body:
            return SavedRef(id, build_spec(body["spec"], where).vehicle)
        if "combination_spec" in body:
            return SavedRef(id, build_combination_spec(body["combination_spec"], where).combination)
        if "combination" in body:
            return SavedRef(id, combination_of(body["combination"], where))
        return SavedRef(id, Vehicle.from_dict({k: v for k, v in body.items() if k in Vehicle.__dataclass_fields__}))

    async def one(self, ref: Any, where: str) -> Any:
        """A reference resolved: presets and records stay as they are, the rest become engine records."""
        if isinstance(ref, SpecRef):
            return build_spec(ref.engine_spec(), where).vehicle
        if isinstance(ref, CombinationRef):
            return combination_of(ref.combination.engine_dict(), where)
        if isinstance(ref, CombinationSpecRef):
            return build_combination_spec(ref.engine_spec(), where).combination
        if isinstance(ref, str) and ref.startswith(catalog.SAVED_VEHICLE_PREFIX):
            db = await catalog.catalog_db(self.request)
            return self.stored(ref, await catalog.resolve_saved_vehicle(db, await self.owner(), ref), where)
        return ref

    async def fleet(self, fleet_id: str) -> list[Any]:
        db = await catalog.catalog_db(self.request)
        members = await catalog.resolve_fleet(db, await self.owner(), fleet_id)
        return [id if body is None else self.stored(id, body, f"fleet[{i}]") for i, (id, body) in enumerate(members)]


async def resolve_vehicle_refs(request: Request, body: BaseModel, settings: Settings) -> BaseModel:
    """``body`` with its ``vehicle``, ``vehicles`` and ``fleet`` resolved (a copy when anything changed).

    A fleet becomes ``vehicles`` (its members in order). Raises the catalog's problems (401/403/404) for saved ids
    and fleets, and :class:`~engine.errors.InvalidVehicle` naming the spec field for a spec the builder refuses.
    """
    r = _Resolver(request, settings)
    update: dict[str, Any] = {}
    fields = type(body).model_fields
    if "vehicle" in fields and getattr(body, "vehicle", None) is not None:
        resolved = await r.one(body.vehicle, "vehicle")
        if resolved is not body.vehicle:
            update["vehicle"] = resolved
    if "vehicles" in fields and getattr(body, "vehicles", None) is not None:
        resolved_list = [await r.one(v, f"vehicles[{i}]") for i, v in enumerate(body.vehicles)]
        if any(a is not b for a, b in zip(resolved_list, body.vehicles, strict=True)):
            update["vehicles"] = resolved_list
    if "fleet" in fields and getattr(body, "fleet", None) is not None:
        update["vehicles"] = await r.fleet(body.fleet)
        update["fleet"] = None
    return body.model_copy(update=update) if update else body
