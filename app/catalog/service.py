"""Saved vehicles and fleets: the rules between the HTTP routes and the database.

For the computations, one read: :class:`SavedVehicles` of a request (its database and the caller's owner id from its
bearer key, each opened at most once; its user is the vehicles feature's resolver, :mod:`app.vehicles.resolve`).
Its :meth:`~SavedVehicles.vehicle` and :meth:`~SavedVehicles.fleet` are

* :func:`resolve_saved_vehicle` ``(db, owner, id) -> dict``: the stored vehicle body, usable as the ``vehicle``
  of any request (a full record, ``{"spec": {...}}``, ``{"combination": {...}}`` or ``{"combination_spec": ...}``);
* :func:`resolve_fleet` ``(db, owner, id) -> list[(id, dict | None)]``: the members in order, each with its id:
  a preset with None, a saved vehicle with its stored body.

Both refuse a missing, deleted or other owner's id with a 404 problem naming it, and a stored row that fails
validation with a 409 problem (logged, never served).

What is checked, on write and again on every read (a row is never trusted because it is in the database):

* a record: the :class:`~app.vehicle_forms.schemas.VehicleRecord` schema, then the engine's
  ``validate_vehicle(..., model="3d")``; a record without the 3D fields (``MissingParameter``) is checked as a
  2D record instead, so a 2D vehicle may be saved; any other engine refusal is a 422 naming ``vehicle.<field>``;
* a spec: :func:`validate_spec`: the builder's schema and the build itself (422 naming ``vehicle.spec.<field>``);
* the stored body's size (canonical JSON) against ``ROLLOVER_CATALOG_MAX_VEHICLE_BYTES`` (413).

Deleting a saved vehicle that a fleet uses is refused with 409 ``vehicle-in-use`` naming the fleets (the safe
choice: a fleet never silently loses a member; the database's foreign key enforces it too).
"""

from __future__ import annotations

import base64
import dataclasses
import math
import re
import secrets
import threading
from collections.abc import Callable
from datetime import datetime
from typing import Any, TypeVar

import orjson
from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from fastapi.security import HTTPAuthorizationCredentials
from fastapi.security.utils import get_authorization_scheme_param
from sqlalchemy.exc import OperationalError
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException as StarletteHTTPException

from app.catalog.auth import CatalogDisabled, NotAuthenticated, authenticate
from app.catalog.schemas import (
    FLEET_ID_PATTERN,
    SAVED_VEHICLE_ID_PATTERN,
    TITLE_MAX_LENGTH,
    Fleet,
    FleetPage,
    FleetWrite,
    SavedCombination,
    SavedCombinationSpec,
    SavedRecord,
    SavedSpec,
    SavedVehicle,
    SavedVehiclePage,
    SavedVehicleWritten,
    VehicleWrite,
)
from app.db import Database, repo
from app.db import upgrade as upgrade_database
from app.http.problems import http_handler, problem_response
from app.http.route_table import documented_paths
from app.http.schemas import InputWarningOut
from app.logs import get_logger
from app.settings import Settings
from app.vehicle_forms.build import build_combination_spec, build_spec, combination_of
from app.vehicle_forms.builder_schemas import SpecRef, VehicleSpecIn
from app.vehicle_forms.combination_builder_schemas import CombinationSpecRef
from app.vehicle_forms.combination_schemas import CombinationRef
from app.vehicle_forms.schemas import VehicleRecord
from engine import InvalidVehicle, MissingParameter
from engine.models import get_model
from engine.vehicle import COMBINATIONS, PRESETS, Vehicle, check_record_plausible, record_warnings

SAVED_VEHICLE_ID = re.compile(SAVED_VEHICLE_ID_PATTERN)
FLEET_ID = re.compile(FLEET_ID_PATTERN)
SAVED_VEHICLE_PREFIX = "veh_"
FLEET_PREFIX = "flt_"

#: the builder-spec stub's bounds: a JSON object of at most this many bytes [bytes] ...
SPEC_MAX_BYTES = 64 * 2**10
#: ... nested at most this deep [levels]
SPEC_MAX_DEPTH = 32

_log = get_logger("rollover.catalog")
T = TypeVar("T")


def new_id(prefix: str) -> str:
    """An unguessable id: ``prefix`` + 22 url-safe base64 characters (128 random bits). A preset id never has
    the ``veh_`` / ``flt_`` prefix, so the two can never collide."""
    return prefix + secrets.token_urlsafe(16)


def etag(version: int) -> str:
    """The strong ETag of a saved row: its version, quoted (``"3"``)."""
    return f'"{version}"'


# ------------------------------------------------------------------------------------------------ problems
class CatalogProblem(Exception):
    """An RFC 9457 problem raised by the catalog (``status``, type ``slug``, ``title``, ``detail``, extras)."""

    def __init__(
        self, status: int, slug: str, title: str, detail: str, *, headers: dict[str, str] | None = None, **extra: Any
    ) -> None:
        super().__init__(detail)
        self.status, self.slug, self.title, self.detail = status, slug, title, detail
        self.headers = headers
        self.extra = extra


def _field_error(field: str, message: str, type_: str) -> dict[str, Any]:
    loc: list[str | int] = ["body", *(int(p) if p.isdigit() else p for p in field.split("."))]
    return {"field": field, "message": message, "type": type_, "loc": loc}


def not_found(table: str, id: str) -> CatalogProblem:
    what = "saved vehicle" if table == "vehicle" else table
    return CatalogProblem(
        404,
        "not-found",
        f"No such {what}",
        f"no {what} {id!r} for this key (it does not exist, was deleted, or belongs to another key)",
        id=id,
    )


def invalid_path_id(id: str, pattern: str, what: str) -> RequestValidationError:
    """The 422 of a path id that cannot be a saved id (the validation-error problem naming ``id``)."""
    return RequestValidationError(
        [
            {
                "type": "string_pattern_mismatch",
                "loc": ("path", "id"),
                "msg": f"{id!r} is not a {what} id (pattern {pattern})",
                "input": id,
            }
        ]
    )


def read_only_preset(id: str) -> CatalogProblem:
    return CatalogProblem(
        405,
        "read-only",
        "Presets are read-only",
        f"{id!r} is a thesis preset: it can be read (GET) but not changed or deleted; save a copy with "
        "POST /v1/vehicles",
        headers={"Allow": "GET"},
    )


def precondition_required() -> CatalogProblem:
    return CatalogProblem(
        428,
        "precondition-required",
        "If-Match is required",
        "send the ETag of the version you are replacing in If-Match (from the GET, POST or last PUT), or "
        '"*" to replace whatever is current',
    )


def _version_mismatch(current: int) -> CatalogProblem:
    return CatalogProblem(
        412,
        "precondition-failed",
        "The resource changed since your ETag",
        f"If-Match does not match the current version ({etag(current)}); GET it again and reapply your change",
    )


def _limit_reached(table: str, limit: int) -> CatalogProblem:
    setting = "ROLLOVER_CATALOG_MAX_VEHICLES" if table == "vehicles" else "ROLLOVER_CATALOG_MAX_FLEETS"
    return CatalogProblem(
        409,
        "limit-reached",
        "Limit reached",
        f"this key already has {limit} {'saved vehicles' if table == 'vehicles' else 'fleets'}, the limit "
        f"{setting}; delete some first",
        limit={"setting": setting, "max": limit},
    )


def _in_use(id: str, fleets: list[str]) -> CatalogProblem:
    return CatalogProblem(
        409,
        "vehicle-in-use",
        "The saved vehicle is a member of fleets",
        f"saved vehicle {id!r} is a member of fleet(s) {', '.join(fleets)}: remove it from them "
        "(PUT /v1/fleets/{id}) or delete them first",
        fleets=fleets,
    )


def _missing_members(missing: list[tuple[int, str]]) -> CatalogProblem:
    errors = [_field_error(f"vehicles.{i}", f"no saved vehicle {v!r} for this key", "not-found") for i, v in missing]
    return CatalogProblem(
        404,
        "not-found",
        "A fleet member does not exist",
        "; ".join(f"{e['field']}: {e['message']}" for e in errors),
        errors=errors,
    )


def _invalid_row(table: str, id: str, reason: str, version: Any = None) -> CatalogProblem:
    """A stored row that fails validation: logged, answered with a 409 (never a 500, never served)."""
    reason = reason if len(reason) <= 500 else reason[:500] + "..."
    _log.error("catalog_invalid_row", table=table, id=id, reason=reason)
    headers = {"ETag": etag(version)} if isinstance(version, int) and version >= 1 else None
    return CatalogProblem(
        409,
        "stored-record-invalid",
        "The stored record fails validation",
        f"the stored {table} {id!r} fails validation and is not served ({reason}); it was logged: replace it "
        "(PUT with If-Match) or delete it",
        headers=headers,
        id=id,
    )


async def _catalog_problem_handler(request: Request, exc: CatalogProblem) -> JSONResponse:
    return problem_response(request, exc.status, exc.slug, exc.title, exc.detail, headers=exc.headers, **exc.extra)


async def _disabled_handler(request: Request, exc: CatalogDisabled) -> JSONResponse:
    return problem_response(
        request,
        403,
        "catalog-disabled",
        "Saving vehicles is disabled",
        "saving vehicles is disabled: the deployment sets no ROLLOVER_API_KEYS",
    )


async def _unauthenticated_handler(request: Request, exc: NotAuthenticated) -> JSONResponse:
    challenge = 'Bearer realm="rollover"' + (f', error="{exc.error}"' if exc.error else "")
    detail = (
        "the bearer key is not one of this deployment's keys"
        if exc.error
        else "saved vehicles and fleets need Authorization: Bearer <key>"
    )
    return problem_response(
        request, 401, "unauthorized", "Authentication required", detail, headers={"WWW-Authenticate": challenge}
    )


async def _database_down_handler(request: Request, exc: OperationalError) -> JSONResponse:
    _log.error("catalog_database_unavailable", path=request.url.path, error=type(exc.orig).__name__)
    return problem_response(
        request,
        503,
        "database-unavailable",
        "The catalog database is unavailable",
        "the database did not answer or is locked; retry shortly",
        headers={"Retry-After": "5"},
    )


_HTTP_METHODS = {"get", "put", "post", "delete", "patch", "head", "options", "trace"}


def documented_methods(app: FastAPI, path: str) -> set[str]:
    """The methods the OpenAPI document declares for the resource at ``path`` (a literal path such as
    ``/v1/vehicles/saved`` wins over a template such as ``/v1/vehicles/{id}``), read from the route table; empty when
    none matches."""
    paths = documented_paths(app.routes)
    for template in sorted(paths, key=lambda t: t.count("{")):
        pattern = re.sub(r"\\\{[^/]*?\\\}", "[^/]+", re.escape(template))
        if re.fullmatch(pattern, path):
            return {m for m in paths[template] if m.lower() in _HTTP_METHODS}
    return set()


async def _http_handler_with_full_allow(request: Request, exc: StarletteHTTPException) -> JSONResponse:
    """Starlette's 405 lists only the methods of the *first* route matching the path; the catalog puts several
    routes on one path (``/v1/vehicles``: GET presets, POST save), so ``Allow`` lists what the spec declares."""
    if exc.status_code == 405:
        allowed = documented_methods(request.app, request.url.path)
        if allowed:
            exc.headers = {**(exc.headers or {}), "Allow": ", ".join(sorted(allowed))}
    return await http_handler(request, exc)


def install_catalog_handlers(app: FastAPI) -> None:
    """Map the catalog's errors to problem details (call after :func:`app.http.problems.install_problem_handlers`)."""
    app.add_exception_handler(StarletteHTTPException, _http_handler_with_full_allow)
    app.add_exception_handler(CatalogProblem, _catalog_problem_handler)
    app.add_exception_handler(CatalogDisabled, _disabled_handler)
    app.add_exception_handler(NotAuthenticated, _unauthenticated_handler)
    app.add_exception_handler(OperationalError, _database_down_handler)


# ------------------------------------------------------------------------------------------- the database
def open_database(settings: Settings) -> Database:
    """Open ``ROLLOVER_DATABASE_URL`` and migrate it to the newest revision (blocking)."""
    db = Database(settings.database_url)
    revision = upgrade_database(db)
    _log.info("catalog_database", url=db.safe_url, dialect=db.dialect, revision=revision)
    return db


_open_lock = threading.Lock()


def _ensure_database(app: FastAPI) -> Database:
    with _open_lock:
        db = getattr(app.state, "db", None)
        if db is None:
            db = app.state.db = open_database(app.state.settings)
        return db


async def catalog_db(request: Request) -> Database:
    """The app's catalog database (opened and migrated in the lifespan; here when a test transport skipped it).
    Call it only after the caller is authenticated: without keys the catalog never touches the disk."""
    db = getattr(request.app.state, "db", None)
    return db if db is not None else await run_in_threadpool(_ensure_database, request.app)


async def open_catalog(app: FastAPI, settings: Settings) -> None:
    """Lifespan start: open and migrate the database when the catalog is enabled (some key configured)."""
    if settings.api_key_list() and getattr(app.state, "db", None) is None:
        app.state.db = await run_in_threadpool(open_database, settings)


async def close_catalog(app: FastAPI) -> None:
    """Lifespan end: release the database's connections."""
    db = getattr(app.state, "db", None)
    app.state.db = None
    if db is not None:
        await run_in_threadpool(db.dispose)


async def _run(fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
    """A repository call in a worker thread, its errors as problems."""
    try:
        return await run_in_threadpool(fn, *args, **kwargs)
    except repo.NotFound as e:
        raise not_found(e.table, e.id) from None
    except repo.VersionMismatch as e:
        raise _version_mismatch(e.current) from None
    except repo.LimitReached as e:
        raise _limit_reached(e.table, e.limit) from None
    except repo.MissingMembers as e:
        raise _missing_members(e.missing) from None


# ------------------------------------------------------------------------------------- vehicle validation
def validate_spec(spec: dict[str, Any]) -> None:
    """A stored or sent builder spec checked as the builder reads it: the request schema, then the build itself
    (:func:`app.vehicle_forms.build.build_spec`: the physics, the component library, the ratings).

    Raises :class:`~engine.errors.InvalidVehicle` naming ``vehicle.spec.<field>`` (a 422 problem), or pydantic's
    ``ValidationError`` (a ``ValueError``) for a stored spec that no longer fits the schema.
    """
    if not isinstance(spec, dict):
        raise InvalidVehicle("spec must be a JSON object", field="vehicle.spec", value=type(spec).__name__)
    size = len(orjson.dumps(spec))
    if size > SPEC_MAX_BYTES:
        raise InvalidVehicle(
            f"spec is {size} bytes as JSON, more than the {SPEC_MAX_BYTES} a spec may have",
            field="vehicle.spec",
            value=size,
        )
    VehicleSpecIn.model_validate(spec)
    build_spec(spec, "vehicle")


def _check_json(value: Any, field: str, depth: int = 0) -> None:
    """Only finite numbers (the parser accepts NaN and Infinity, which JSON cannot store), integers within 64 bits,
    and bounded nesting."""
    if depth > SPEC_MAX_DEPTH:
        raise InvalidVehicle(f"nested deeper than {SPEC_MAX_DEPTH} levels", field=field)
    if isinstance(value, float) and not math.isfinite(value):
        raise InvalidVehicle(f"{value} is not a finite number", field=field, value=str(value))
    if isinstance(value, int) and not -(2**63) <= value < 2**64:  # what JSON tools (and orjson) can store
        raise InvalidVehicle("integer outside the 64-bit range", field=field, value=str(value))
    children = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for key, item in children:
        _check_json(item, f"{field}.{key}", depth + 1)


def check_record(record: dict[str, Any]) -> None:
    """The engine's checks of a full record: as a 3D vehicle, or as a 2D one when it lacks the 3D fields.

    Raises :class:`~engine.errors.InvalidVehicle` naming the field (never ``MissingParameter``).
    """
    vehicle = Vehicle.from_dict(record)
    check_record_plausible(vehicle)  # a weight or stiffness in another unit (31.5 t typed as kN), named as typed
    try:
        get_model("3d").validate(vehicle)
    except MissingParameter:
        get_model("2d").validate(vehicle)  # a 2D record may be saved; its own physics still checked


def check_combination(data: dict[str, Any]) -> None:
    """The engine's checks of a combination (:func:`engine.vehicle.validate_combination`), errors under
    ``vehicle.combination``."""
    combination_of(data, "vehicle")


def check_combination_spec(spec: dict[str, Any]) -> None:
    """The combination builder's checks (it builds the combination), errors under ``vehicle.combination_spec``."""
    build_combination_spec(spec, "vehicle")


def _kind_and_body(
    vehicle: VehicleRecord | SpecRef | CombinationRef | CombinationSpecRef,
) -> tuple[str, dict[str, Any]]:
    if isinstance(vehicle, CombinationSpecRef):
        spec = vehicle.combination_spec.model_dump(mode="json", exclude_unset=True)  # as sent
        _check_json(spec, "vehicle.combination_spec")
        check_combination_spec(spec)
        return "combination_spec", {"combination_spec": spec}
    if isinstance(vehicle, CombinationRef):
        data = vehicle.combination.engine_dict()
        check_combination(data)
        return "combination", {"combination": data}
    if isinstance(vehicle, SpecRef):
        spec = vehicle.spec.model_dump(mode="json", exclude_unset=True)  # as sent: what was left out stays out
        _check_json(spec, "vehicle.spec")
        validate_spec(spec)
        return "spec", {"spec": spec}
    record = vehicle.record()
    check_record(record)
    return "record", record


def prepare_vehicle(vehicle: VehicleRecord | SpecRef | CombinationRef, settings: Settings) -> tuple[str, str]:
    """``(kind, JSON text)`` to store for a vehicle the caller sent, after every check (422, 413)."""
    kind, body = _kind_and_body(vehicle)
    text = orjson.dumps(body, option=orjson.OPT_SORT_KEYS)
    limit = settings.catalog_max_vehicle_bytes
    if len(text) > limit:
        raise CatalogProblem(
            413,
            "too-large",
            "The vehicle is too large to save",
            f"the vehicle is {len(text)} bytes as stored JSON, more than ROLLOVER_CATALOG_MAX_VEHICLE_BYTES ({limit})",
            limit={"setting": "ROLLOVER_CATALOG_MAX_VEHICLE_BYTES", "max": limit},
            errors=[_field_error("vehicle", f"{len(text)} bytes, at most {limit}", "too-large")],
        )
    return kind, text.decode()


def _stored_body(kind: str, text: str) -> dict[str, Any]:
    """A stored body parsed and checked exactly as on write; ValueError/TypeError saying why not."""
    body = orjson.loads(text)
    if kind == "record":
        record = VehicleRecord.model_validate(body).record()
        if body != record:
            raise ValueError("the stored record is not in the form the service writes")
        check_record(record)
        return record
    if kind == "spec":
        if not isinstance(body, dict) or set(body) != {"spec"}:
            raise ValueError('a stored spec must be {"spec": {...}}')
        _check_json(body["spec"], "vehicle.spec")
        validate_spec(body["spec"])
        return body
    if kind == "combination":
        if not isinstance(body, dict) or set(body) != {"combination"}:
            raise ValueError('a stored combination must be {"combination": {...}}')
        check_combination(CombinationRef.model_validate(body).combination.engine_dict())
        return body
    if kind == "combination_spec":
        if not isinstance(body, dict) or set(body) != {"combination_spec"}:
            raise ValueError('a stored combination spec must be {"combination_spec": {...}}')
        _check_json(body["combination_spec"], "vehicle.combination_spec")
        spec = CombinationSpecRef.model_validate(body)  # the schema's bounds, then the builder's checks
        check_combination_spec(spec.combination_spec.model_dump(mode="json", exclude_unset=True))
        return body
    raise ValueError(f"unknown kind {kind!r}")


def _check_row_fields(title: Any, version: Any) -> None:
    if not isinstance(title, str) or not 1 <= len(title) <= TITLE_MAX_LENGTH:
        raise ValueError("title is not a string of 1-200 characters")
    if not isinstance(version, int) or isinstance(version, bool) or version < 1:
        raise ValueError(f"version {version!r} is not a positive integer")


def decode_vehicle(stored: repo.StoredVehicle) -> SavedVehicle:
    """A stored row as the API answers it, validated; :func:`_invalid_row` (409, logged) when it fails."""
    try:
        _check_row_fields(stored.title, stored.version)
        body = _stored_body(stored.kind, stored.body)
        if stored.kind == "spec":
            vehicle = SavedSpec(spec=body["spec"])
        elif stored.kind == "combination":
            vehicle = SavedCombination(combination=body["combination"])
        elif stored.kind == "combination_spec":
            vehicle = SavedCombinationSpec(combination_spec=body["combination_spec"])
        else:
            vehicle = SavedRecord(**body)
        return SavedVehicle(
            id=stored.id,
            title=stored.title,
            kind=stored.kind,
            vehicle=vehicle,
            version=stored.version,
            created_at=stored.created_at,
            updated_at=stored.updated_at,
        )
    except (ValueError, TypeError) as exc:  # orjson, pydantic and engine errors are ValueErrors
        raise _invalid_row("vehicle", stored.id, f"{type(exc).__name__}: {exc}", stored.version) from None


async def _read_one(fn: Callable[..., T], table: str, *args: Any) -> T:
    try:
        return await _run(fn, *args)
    except (ValueError, TypeError) as exc:  # a column the driver cannot convert (e.g. a damaged timestamp)
        raise _invalid_row(table, args[-1], f"{type(exc).__name__}: {exc}") from None


async def _read_page(fn: Callable[..., repo.Page], table: str, db: Database, owner: str, **kwargs: Any) -> repo.Page:
    """A listing page. A typed column the driver cannot convert (only possible by writing into a SQLite file
    outside the service: PostgreSQL checks the types) fails the whole page: a logged 409, never a 500."""
    try:
        return await _run(fn, db, owner, **kwargs)
    except (ValueError, TypeError) as exc:
        raise _invalid_row(table, f"(a row of this {table} listing)", f"{type(exc).__name__}: {exc}") from None


# ------------------------------------------------------------------------------------- vehicles: service
def check_saved_vehicle_id(id: str) -> None:
    """A path id that cannot be a saved vehicle's names none: 404, as an unknown well-formed id (the path
    ``/v1/vehicles/{id}`` also serves presets, so its spec cannot state the saved ids' pattern)."""
    if not SAVED_VEHICLE_ID.match(id):
        raise CatalogProblem(
            404,
            "not-found",
            "No such saved vehicle",
            f"{id!r} is neither a preset nor a saved vehicle id (pattern {SAVED_VEHICLE_ID_PATTERN})",
            id=id,
        )


def expected_versions(if_match: str | None, *, required: bool) -> frozenset[int] | None:
    """The versions an ``If-Match`` header accepts (strong comparison, RFC 9110 13.1.1): ``None`` for ``*``
    (any current version) or when the header is absent and not ``required``; 428 when absent and required.
    Weak or malformed entries match nothing."""
    if if_match is None or not if_match.strip():
        if required:
            raise precondition_required()
        return repo.ANY
    if if_match.strip() == "*":
        return repo.ANY
    versions = set()
    for tag in if_match.split(","):
        m = re.fullmatch(r'"([0-9]{1,9})"', tag.strip())
        if m:
            versions.add(int(m.group(1)))
    return frozenset(versions)


def input_warnings(kind: str, text: str) -> list[InputWarningOut]:
    """The input warnings of a vehicle as saved (``kind``, its stored JSON ``text``), named as the request names
    the field (``vehicle.weight_kn``): a typed record's, or a combination's ``last_unit_record``'s (as
    app.vehicles.resolve warns of them in a computation); none for a builder spec (the builder computes its
    weights)."""
    body = orjson.loads(text)
    if kind == "record":
        found = record_warnings(Vehicle.from_dict(body), "vehicle.")
    elif kind == "combination":
        last = combination_of(body["combination"], "vehicle").last_unit_record
        found = [] if last is None else record_warnings(last, "vehicle.combination.last_unit_record.")
    else:
        found = []
    return [InputWarningOut(**dataclasses.asdict(w)) for w in found]


def _written(stored: repo.StoredVehicle) -> SavedVehicleWritten:
    saved = decode_vehicle(stored)
    return SavedVehicleWritten(**dict(saved), warnings=input_warnings(stored.kind, stored.body))


async def create_vehicle(db: Database, owner: str, body: VehicleWrite, settings: Settings) -> SavedVehicleWritten:
    kind, text = prepare_vehicle(body.vehicle, settings)
    stored = await _run(
        repo.insert_vehicle,
        db,
        owner,
        new_id(SAVED_VEHICLE_PREFIX),
        title=body.title,
        kind=kind,
        body=text,
        max_count=settings.catalog_max_vehicles,
    )
    return _written(stored)


async def read_vehicle(db: Database, owner: str, id: str) -> SavedVehicle:
    return decode_vehicle(await _read_one(repo.get_vehicle, "vehicle", db, owner, id))


async def replace_vehicle(
    db: Database, owner: str, id: str, body: VehicleWrite, if_match: str | None, settings: Settings
) -> SavedVehicleWritten:
    expected = expected_versions(if_match, required=True)
    kind, text = prepare_vehicle(body.vehicle, settings)
    stored = await _run(repo.update_vehicle, db, owner, id, expected=expected, title=body.title, kind=kind, body=text)
    return _written(stored)


async def remove_vehicle(db: Database, owner: str, id: str, if_match: str | None) -> None:
    expected = expected_versions(if_match, required=False)
    try:
        await _run(repo.delete_vehicle, db, owner, id, expected=expected)
    except repo.InUse as e:
        raise _in_use(id, e.fleets) from None


# ------------------------------------------------------------------------------------------- pagination
def encode_cursor(created_at: datetime, id: str) -> str:
    """An opaque cursor: the (created_at, id) of the last row of a page, base64url of a JSON pair."""
    raw = orjson.dumps([created_at.isoformat(), id])
    return base64.urlsafe_b64encode(raw).decode().rstrip("=")


def decode_cursor(cursor: str | None, id_pattern: re.Pattern[str]) -> tuple[datetime, str] | None:
    """The position a cursor encodes; a 422 naming ``cursor`` when it is not one this service wrote."""
    if cursor is None:
        return None
    try:
        created, id = orjson.loads(base64.urlsafe_b64decode(cursor + "=" * (-len(cursor) % 4)))
        at = datetime.fromisoformat(created)
        if at.tzinfo is None or not isinstance(id, str) or not id_pattern.match(id):
            raise ValueError(cursor)
    except (ValueError, TypeError) as exc:  # binascii.Error and orjson's errors are ValueErrors
        raise RequestValidationError(
            [
                {
                    "type": "value_error",
                    "loc": ("query", "cursor"),
                    "msg": "not a cursor of this listing (pass next_cursor of the previous page as it is)",
                    "input": cursor,
                }
            ]
        ) from exc
    return at, id


async def list_vehicles(db: Database, owner: str, cursor: str | None, limit: int) -> SavedVehiclePage:
    after = decode_cursor(cursor, SAVED_VEHICLE_ID)
    page = await _read_page(repo.list_vehicles, "vehicle", db, owner, after=after, limit=limit)
    items, unreadable = [], []
    for stored in page.rows:
        try:
            items.append(decode_vehicle(stored))
        except CatalogProblem:  # logged by _invalid_row
            unreadable.append(stored.id)
    last = page.rows[-1] if page.rows and page.more else None
    return SavedVehiclePage(
        items=items, next_cursor=encode_cursor(last.created_at, last.id) if last else None, unreadable=unreadable
    )


# --------------------------------------------------------------------------------------- fleets: service
def check_fleet_id(id: str) -> None:
    if not FLEET_ID.match(id):
        raise invalid_path_id(id, FLEET_ID_PATTERN, "fleet")


def prepare_members(ids: list[str], settings: Settings) -> list[repo.Member]:
    """The members of a fleet request: saved-vehicle ids (existence is checked in the write transaction) and
    preset ids. 422 naming ``vehicles`` (over the limit) or ``vehicles.<i>`` (malformed, repeated); 404 naming
    ``vehicles.<i>`` for an unknown preset."""
    limit = settings.catalog_max_fleet_members
    if len(ids) > limit:
        raise CatalogProblem(
            422,
            "too-many-members",
            "Too many vehicles in the fleet",
            f"vehicles has {len(ids)} members, more than ROLLOVER_CATALOG_MAX_FLEET_MEMBERS ({limit})",
            limit={"setting": "ROLLOVER_CATALOG_MAX_FLEET_MEMBERS", "max": limit},
            errors=[_field_error("vehicles", f"{len(ids)} members, at most {limit}", "too-many-members")],
        )
    invalid, unknown, first = [], [], {}
    for i, member in enumerate(ids):
        if member in first:
            invalid.append((i, f"repeats vehicles.{first[member]} ({member!r}); each vehicle at most once"))
        elif member.startswith(SAVED_VEHICLE_PREFIX) and not SAVED_VEHICLE_ID.match(member):
            invalid.append((i, f"{member!r} is not a saved vehicle id (pattern {SAVED_VEHICLE_ID_PATTERN})"))
        elif not member.startswith(SAVED_VEHICLE_PREFIX) and member not in PRESETS and member not in COMBINATIONS:
            known = ", ".join(sorted([*PRESETS, *COMBINATIONS]))
            unknown.append((i, f"unknown vehicle preset {member!r}; known presets: {known}"))
        first.setdefault(member, i)
    if invalid:
        raise RequestValidationError(
            [{"type": "value_error", "loc": ("body", "vehicles", i), "msg": msg, "input": ids[i]} for i, msg in invalid]
        )
    if unknown:
        errors = [_field_error(f"vehicles.{i}", msg, "unknown-preset") for i, msg in unknown]
        detail = "; ".join(f"{e['field']}: {e['message']}" for e in errors)
        raise CatalogProblem(
            404,
            "not-found",
            "A fleet member does not exist",
            detail,
            errors=errors,
            known=sorted([*PRESETS, *COMBINATIONS]),
        )
    return [repo.Member(m, None) if m.startswith(SAVED_VEHICLE_PREFIX) else repo.Member(None, m) for m in ids]


def _member_id(member: repo.Member) -> str:
    return member.vehicle_id if member.vehicle_id is not None else str(member.preset_id)


def decode_fleet(stored: repo.StoredFleet) -> Fleet:
    try:
        _check_row_fields(stored.title, stored.version)
        for member in stored.members:
            if (member.vehicle_id is None) == (member.preset_id is None):
                raise ValueError("a member row names both or neither of a saved vehicle and a preset")
            if member.vehicle_id is not None and not SAVED_VEHICLE_ID.match(member.vehicle_id):
                raise ValueError(f"member {member.vehicle_id!r} is not a saved vehicle id")
        return Fleet(
            id=stored.id,
            title=stored.title,
            vehicles=[_member_id(m) for m in stored.members],
            version=stored.version,
            created_at=stored.created_at,
            updated_at=stored.updated_at,
        )
    except (ValueError, TypeError) as exc:
        raise _invalid_row("fleet", stored.id, f"{type(exc).__name__}: {exc}", stored.version) from None


async def create_fleet(db: Database, owner: str, body: FleetWrite, settings: Settings) -> Fleet:
    members = prepare_members(body.vehicles, settings)
    stored = await _run(
        repo.insert_fleet,
        db,
        owner,
        new_id(FLEET_PREFIX),
        title=body.title,
        members=members,
        max_count=settings.catalog_max_fleets,
    )
    return decode_fleet(stored)


async def read_fleet(db: Database, owner: str, id: str) -> Fleet:
    return decode_fleet(await _read_one(repo.get_fleet, "fleet", db, owner, id))


async def replace_fleet(
    db: Database, owner: str, id: str, body: FleetWrite, if_match: str | None, settings: Settings
) -> Fleet:
    expected = expected_versions(if_match, required=True)
    members = prepare_members(body.vehicles, settings)
    stored = await _run(repo.update_fleet, db, owner, id, expected=expected, title=body.title, members=members)
    return decode_fleet(stored)


async def remove_fleet(db: Database, owner: str, id: str, if_match: str | None) -> None:
    await _run(repo.delete_fleet, db, owner, id, expected=expected_versions(if_match, required=False))


async def list_fleets(db: Database, owner: str, cursor: str | None, limit: int) -> FleetPage:
    page = await _read_page(repo.list_fleets, "fleet", db, owner, after=decode_cursor(cursor, FLEET_ID), limit=limit)
    items, unreadable = [], []
    for stored in page.rows:
        try:
            items.append(decode_fleet(stored))
        except CatalogProblem:
            unreadable.append(stored.id)
    last = page.rows[-1] if page.rows and page.more else None
    return FleetPage(
        items=items, next_cursor=encode_cursor(last.created_at, last.id) if last else None, unreadable=unreadable
    )


# ------------------------------------------------------------------------------- for the computations
async def resolve_saved_vehicle(db: Database, owner: str, id: str) -> dict[str, Any]:
    """The stored vehicle body of saved vehicle ``id`` of ``owner``, validated, usable as a request's ``vehicle``.

    Parameters
    ----------
    db : Database
        The catalog database (:func:`catalog_db` of the request).
    owner : str
        The caller's owner id (:func:`app.catalog.auth.authenticate` of the request's bearer key).
    id : str
        A saved vehicle id (``veh_...``).

    Returns
    -------
    dict
        A full vehicle record (every engine field, null where it gives none), or ``{"spec": {...}}`` for a
        builder spec (the builder turns it into a record).

    Raises
    ------
    CatalogProblem
        404 naming ``id`` when it is missing, deleted or another key's (also for a malformed id); 409 when the
        stored row fails validation (logged).
    """
    if not SAVED_VEHICLE_ID.match(id):
        raise not_found("vehicle", id)
    saved = await read_vehicle(db, owner, id)
    return saved.vehicle.model_dump()


async def resolve_fleet(db: Database, owner: str, id: str) -> list[tuple[str, dict[str, Any] | None]]:
    """The members of fleet ``id`` of ``owner``, in order, as ``(id, body)``: a preset as ``(preset id, None)``, a
    saved vehicle as its id and its stored body (as :func:`resolve_saved_vehicle` returns it). Fleet and members
    are read in one transaction.

    Raises
    ------
    CatalogProblem
        404 naming ``id`` when the fleet is missing, deleted or another key's; 409 when the fleet or one of
        its saved vehicles fails validation (logged).
    """
    if not FLEET_ID.match(id):
        raise not_found("fleet", id)
    stored, vehicles = await _read_one(repo.get_fleet_with_vehicles, "fleet", db, owner, id)
    fleet = decode_fleet(stored)
    out: list[tuple[str, dict[str, Any] | None]] = []
    for member in stored.members:
        if member.preset_id is not None:
            out.append((member.preset_id, None))
            continue
        saved = vehicles.get(str(member.vehicle_id))
        if saved is None:  # the foreign key forbids it; refuse rather than drop a member
            raise _invalid_row("fleet", fleet.id, f"member {member.vehicle_id!r} is missing")
        decoded = decode_vehicle(saved)
        out.append((decoded.id, decoded.vehicle.model_dump()))
    return out


def _credentials(request: Request) -> HTTPAuthorizationCredentials | None:
    scheme, token = get_authorization_scheme_param(request.headers.get("authorization"))
    if scheme.lower() != "bearer" or not token:
        return None
    return HTTPAuthorizationCredentials(scheme=scheme, credentials=token)


class SavedVehicles:
    """The catalog's one read for the computations: the saved vehicles and fleets of the request's bearer key, as
    their stored bodies (validated as on every read). The key is checked and the database opened on the first read
    only, at most once per request; a request without a saved id or a fleet never touches either."""

    def __init__(self, request: Request, settings: Settings) -> None:
        self._request = request
        self._settings = settings
        self._owner: str | None = None

    @staticmethod
    def is_saved_id(ref: str) -> bool:
        """Whether a vehicle id names a saved vehicle (``veh_...``) rather than a preset."""
        return ref.startswith(SAVED_VEHICLE_PREFIX)

    async def _open(self) -> tuple[Database, str]:
        db = await catalog_db(self._request)  # first: a catalog that is off (or down) says so before any key is asked
        if self._owner is None:
            self._owner = authenticate(_credentials(self._request), self._settings)
        return db, self._owner

    async def vehicle(self, id: str) -> dict[str, Any]:
        """:func:`resolve_saved_vehicle` of the caller's key (401/403 without a valid one, 404 naming ``id``)."""
        db, owner = await self._open()
        return await resolve_saved_vehicle(db, owner, id)

    async def fleet(self, id: str) -> list[tuple[str, dict[str, Any] | None]]:
        """:func:`resolve_fleet` of the caller's key (401/403 without a valid one, 404 naming ``id``)."""
        db, owner = await self._open()
        return await resolve_fleet(db, owner, id)
