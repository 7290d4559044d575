"""Saved vehicles (``/v1/vehicles``: POST, GET ``/saved``, PUT and DELETE ``/{id}``) and fleets (``/v1/fleets``).

Every operation needs ``Authorization: Bearer <key>`` (one of ``ROLLOVER_API_KEYS``) and sees only that key's
rows. ``GET /v1/vehicles`` (the preset list) and ``GET /v1/vehicles/{id}`` (a preset, or a saved vehicle with
its key) are in ``app.vehicles.router``. Changes need ``If-Match`` with the ETag of the version they replace.
"""

from __future__ import annotations

from typing import Annotated, Any

import orjson
from fastapi import APIRouter, Depends, Header, Path, Query, Request, Response
from pydantic import BaseModel
from starlette.exceptions import HTTPException as StarletteHTTPException

from app.catalog import service as catalog
from app.catalog.auth import BearerDep, OwnerDep, authenticate
from app.catalog.schemas import (
    EXAMPLE_FLEET_ID,
    EXAMPLE_VEHICLE_ID,
    FLEET_ID_PATTERN,
    Fleet,
    FleetPage,
    FleetWrite,
    PageQuery,
    SavedVehicle,
    SavedVehiclePage,
    SavedVehicleWritten,
    VehicleWrite,
)
from app.deps import SettingsDep
from app.http.openapi import required_headers
from app.http.problems import Problem
from app.http.route_table import documented_paths

router = APIRouter(tags=["catalog"])

SECURITY_NOTE = (
    " Needs `Authorization: Bearer <key>` (`bearerAuth`); another key's ids answer 404; without any "
    "`ROLLOVER_API_KEYS` configured the catalog answers 403."
)

# --------------------------------------------------------------------------------------- OpenAPI responses
_ETAG = {"ETag": {"description": 'The version of the stored row, strong (`"3"`); send it in `If-Match`.',
                  "schema": {"type": "string"}}}  # fmt: skip
_LOCATION = {"Location": {"description": "Path of the new resource.", "schema": {"type": "string"}}}
_PROBLEMS: dict[int, tuple[str, dict[str, Any] | None]] = {
    400: ("Malformed request body (not JSON).", None),
    401: (
        "No bearer key, or not one of this deployment's keys (`WWW-Authenticate: Bearer`).",
        {"WWW-Authenticate": {"description": '`Bearer realm="rollover"`.', "schema": {"type": "string"}}},
    ),
    403: ("Saving vehicles is disabled: the deployment sets no `ROLLOVER_API_KEYS`.", None),
    404: (
        "No such saved vehicle or fleet for this key (missing, deleted or another key's), or a fleet member "
        "that does not exist (the problem's `errors` name `vehicles.<i>`).",
        None,
    ),
    405: (
        "A preset id: presets are read-only.",
        {"Allow": {"description": "`GET`.", "schema": {"type": "string"}}},
    ),
    409: (
        "`limit-reached`: the key has as many vehicles / fleets as `ROLLOVER_CATALOG_MAX_VEHICLES` / "
        "`ROLLOVER_CATALOG_MAX_FLEETS` allow; `vehicle-in-use`: fleets use the vehicle (listed in `fleets`); "
        "`stored-record-invalid`: the stored row fails validation (logged, not served; `ETag` given so it can "
        "be replaced or deleted).",
        None,
    ),
    412: ("`If-Match` does not match the current version.", None),
    413: ("The vehicle is larger than `ROLLOVER_CATALOG_MAX_VEHICLE_BYTES` as stored JSON.", None),
    422: (
        "Validation error: the problem's `errors` name each field (`vehicle.<field>` for an engine refusal of "
        "the record, `vehicles.<i>` for a fleet member, `id` for a malformed path id, `cursor`); "
        "`too-many-members` over `ROLLOVER_CATALOG_MAX_FLEET_MEMBERS`.",
        None,
    ),
    428: ("`If-Match` is missing (a change must name the version it replaces, or `*`).", None),
    500: ("Internal error (a bug; logged, never a stack trace).", None),
    503: (
        "The database is unavailable or locked; retry.",
        {"Retry-After": {"description": "Seconds to wait [s].", "schema": {"type": "string"}}},
    ),
}


def problem_responses(*codes: int) -> dict[int | str, dict[str, Any]]:
    """OpenAPI ``responses`` for the catalog's problem codes (moved to problem+json by the app)."""
    out: dict[int | str, dict[str, Any]] = {}
    for code in codes:
        text, headers = _PROBLEMS[code]
        out[code] = {"model": Problem, "description": text, **({"headers": headers} if headers else {})}
    return out


def success(code: int, description: str, headers: dict[str, Any] | None = None) -> dict[int | str, dict[str, Any]]:
    return {code: {"description": description, **({"headers": headers} if headers else {})}}


def _json(model: BaseModel, status: int = 200, headers: dict[str, str] | None = None) -> Response:
    return Response(orjson.dumps(model.model_dump(mode="json")), status, headers, media_type="application/json")


def _saved(saved: SavedVehicle, status: int = 200) -> Response:
    headers = {"ETag": catalog.etag(saved.version)}
    if status == 201:
        headers["Location"] = f"/v1/vehicles/{saved.id}"
    return _json(saved, status, headers)


def _fleet(fleet: Fleet, status: int = 200) -> Response:
    headers = {"ETag": catalog.etag(fleet.version)}
    if status == 201:
        headers["Location"] = f"/v1/fleets/{fleet.id}"
    return _json(fleet, status, headers)


# ------------------------------------------------------------------------------------------- parameters
VehicleIdPath = Annotated[
    str,
    Path(description="A saved vehicle's id (`veh_...`). A preset id is read-only here (405); any other id names "
                     "no saved vehicle (404).",
         examples=[EXAMPLE_VEHICLE_ID], max_length=100),
]  # fmt: skip
FleetIdPath = Annotated[
    str, Path(description="A fleet's id (`flt_...`).", pattern=FLEET_ID_PATTERN, examples=[EXAMPLE_FLEET_ID])
]
IfMatchRequired = Annotated[
    str | None,
    Header(
        alias="If-Match",
        description='The `ETag` of the version being replaced (`"3"`), or `*` for whatever is current. Required: '
        "428 when missing, 412 when it is not the current version.",
    ),
]
IfMatchOptional = Annotated[
    str | None,
    Header(alias="If-Match", description="Optional: when given, 412 unless it is the current version's `ETag`."),
]
PageDep = Annotated[PageQuery, Query()]


async def writable_vehicle_owner(
    id: VehicleIdPath, credentials: BearerDep, settings: SettingsDep, request: Request
) -> str:
    """PUT/DELETE /v1/vehicles/{id}: a path of its own (`/v1/vehicles/saved`, `/v1/vehicles/build`...) answers
    405 with its `Allow`; a preset is read-only (405, whoever asks); then the key (403/401); then an id that
    cannot be a saved vehicle's is 404."""
    if f"/v1/vehicles/{id}" in documented_paths(request.app.routes):
        raise StarletteHTTPException(405)
    if id in catalog.PRESETS:
        raise catalog.read_only_preset(id)
    owner = authenticate(credentials, settings)
    catalog.check_saved_vehicle_id(id)
    return owner


WritableOwnerDep = Annotated[str, Depends(writable_vehicle_owner)]

# ------------------------------------------------------------------------------------------- vehicles
VEHICLE_WRITE = problem_responses(400, 401, 403, 404, 405, 412, 413, 422, 428, 500, 503)


@router.post(
    "/v1/vehicles",
    name="create_vehicle",
    status_code=201,
    response_model=SavedVehicleWritten,
    responses={
        **success(201, "Saved; `Location` is its path, `ETag` its version (1).", {**_LOCATION, **_ETAG}),
        **problem_responses(400, 401, 403, 409, 413, 422, 500, 503),
    },
)
async def create_vehicle(body: VehicleWrite, owner: OwnerDep, request: Request, settings: SettingsDep) -> Response:
    """Save a vehicle under the caller's key: a full vehicle record (checked like `POST /v1/srt` checks one; a
    record without the 3D fields is accepted for the 2D and closed-form models) or a builder spec
    `{"spec": {...}}`. Answers 201 with its `id`, `Location` and `ETag`."""
    db = await catalog.catalog_db(request)
    return _saved(await catalog.create_vehicle(db, owner, body, settings), 201)


@router.get(
    "/v1/vehicles/saved",
    name="list_saved_vehicles",
    response_model=SavedVehiclePage,
    responses=problem_responses(401, 403, 422, 500, 503),
)
async def list_saved_vehicles(owner: OwnerDep, request: Request, page: PageDep) -> Response:
    """The caller's saved vehicles, oldest first, `limit` per page; follow `next_cursor` until it is null
    (keyset pagination on creation time and id: stable while vehicles are added). The cursor is opaque: pass
    `next_cursor` of the previous page as it is (anything else is a 422 naming `cursor`)."""
    db = await catalog.catalog_db(request)
    return _json(await catalog.list_vehicles(db, owner, page.cursor, page.limit))


@router.put(
    "/v1/vehicles/{id}",
    name="replace_vehicle",
    response_model=SavedVehicleWritten,
    responses={**success(200, "Replaced; `ETag` is the new version.", _ETAG), **VEHICLE_WRITE},
    openapi_extra=required_headers("If-Match"),  # the handler answers its absence: 428, not FastAPI's 422
)
async def replace_vehicle(
    id: VehicleIdPath,
    body: VehicleWrite,
    owner: WritableOwnerDep,
    request: Request,
    settings: SettingsDep,
    if_match: IfMatchRequired = None,
) -> Response:
    """Replace a saved vehicle (title and vehicle) if `If-Match` names its current version; the version goes up
    by one. Presets are read-only (405)."""
    db = await catalog.catalog_db(request)
    return _saved(await catalog.replace_vehicle(db, owner, id, body, if_match, settings))


@router.delete(
    "/v1/vehicles/{id}",
    name="delete_vehicle",
    status_code=204,
    response_class=Response,
    responses={
        **success(204, "Deleted."),
        **problem_responses(401, 403, 404, 405, 409, 412, 422, 500, 503),
    },
)
async def delete_vehicle(
    id: VehicleIdPath, owner: WritableOwnerDep, request: Request, if_match: IfMatchOptional = None
) -> Response:
    """Delete a saved vehicle. Refused with 409 `vehicle-in-use` naming the fleets while a fleet has it as a
    member (remove it from them first). `If-Match` is optional. Presets are read-only (405)."""
    db = await catalog.catalog_db(request)
    await catalog.remove_vehicle(db, owner, id, if_match)
    return Response(status_code=204)


# --------------------------------------------------------------------------------------------- fleets
@router.post(
    "/v1/fleets",
    name="create_fleet",
    status_code=201,
    response_model=Fleet,
    responses={
        **success(201, "Created; `Location` is its path, `ETag` its version (1).", {**_LOCATION, **_ETAG}),
        **problem_responses(400, 401, 403, 404, 409, 422, 500, 503),
    },
)
async def create_fleet(body: FleetWrite, owner: OwnerDep, request: Request, settings: SettingsDep) -> Response:
    """Create a named fleet: the caller's saved vehicles and presets, in order, each at most once. A saved id
    that is missing or another key's is a 404 naming `vehicles.<i>`."""
    db = await catalog.catalog_db(request)
    return _fleet(await catalog.create_fleet(db, owner, body, settings), 201)


@router.get(
    "/v1/fleets", name="list_fleets", response_model=FleetPage, responses=problem_responses(401, 403, 422, 500, 503)
)
async def list_fleets(owner: OwnerDep, request: Request, page: PageDep) -> Response:
    """The caller's fleets, oldest first, `limit` per page; follow `next_cursor` until it is null. The cursor is
    opaque: pass `next_cursor` of the previous page as it is (anything else is a 422 naming `cursor`)."""
    db = await catalog.catalog_db(request)
    return _json(await catalog.list_fleets(db, owner, page.cursor, page.limit))


@router.get(
    "/v1/fleets/{id}",
    name="get_fleet",
    response_model=Fleet,
    responses={**success(200, "The fleet; `ETag` is its version.", _ETAG),
               **problem_responses(401, 403, 404, 409, 422, 500, 503)},
)  # fmt: skip
async def get_fleet(id: FleetIdPath, owner: OwnerDep, request: Request) -> Response:
    """One of the caller's fleets."""
    db = await catalog.catalog_db(request)
    return _fleet(await catalog.read_fleet(db, owner, id))


@router.put(
    "/v1/fleets/{id}",
    name="replace_fleet",
    response_model=Fleet,
    responses={**success(200, "Replaced; `ETag` is the new version.", _ETAG),
               **problem_responses(400, 401, 403, 404, 412, 422, 428, 500, 503)},
    openapi_extra=required_headers("If-Match"),
)  # fmt: skip
async def replace_fleet(
    id: FleetIdPath,
    body: FleetWrite,
    owner: OwnerDep,
    request: Request,
    settings: SettingsDep,
    if_match: IfMatchRequired = None,
) -> Response:
    """Replace a fleet's title and members if `If-Match` names its current version."""
    db = await catalog.catalog_db(request)
    return _fleet(await catalog.replace_fleet(db, owner, id, body, if_match, settings))


@router.delete(
    "/v1/fleets/{id}",
    name="delete_fleet",
    status_code=204,
    response_class=Response,
    responses={**success(204, "Deleted."), **problem_responses(401, 403, 404, 412, 422, 500, 503)},
)
async def delete_fleet(
    id: FleetIdPath, owner: OwnerDep, request: Request, if_match: IfMatchOptional = None
) -> Response:
    """Delete a fleet (its vehicles stay). `If-Match` is optional."""
    db = await catalog.catalog_db(request)
    await catalog.remove_fleet(db, owner, id, if_match)
    return Response(status_code=204)


for _route in router.routes:  # every catalog operation says how it is authorised
    _route.description += SECURITY_NOTE  # type: ignore[attr-defined]
