"""RFC 9457 problem details for every error the service returns (``application/problem+json``).

Mapping:

==========================================  =======  ===================================================
cause                                       status   type
==========================================  =======  ===================================================
body is not JSON (or names a key twice)     400      ``urn:rollover:problem:malformed-request``
JSON body sent as another content type      415      ``urn:rollover:problem:unsupported-media-type``
request fails the schema                    422      ``urn:rollover:problem:validation-error``
unknown vehicle preset                      404      ``urn:rollover:problem:unknown-preset``
engine InvalidVehicle / MissingParameter    422      ``...:invalid-vehicle`` / ``...:missing-parameter``
engine InvalidRoad / InvalidLoad            422      ``...:invalid-road`` / ``...:invalid-load``
CSV / LandXML / IFC curves unreadable       422      ``urn:rollover:problem:invalid-alignment``
request body over the operation's limit     413      ``urn:rollover:problem:body-too-large``
engine MechanismSingular                    422      ``...:mechanism-singular``
engine ConvergenceError                     422      ``...:no-convergence``
no route / method (Starlette)               404/405  ``about:blank``
anything else (a bug)                       500      ``urn:rollover:problem:internal-error`` (logged)
==========================================  =======  ===================================================

Validation errors and engine input errors carry ``errors``: one entry per offending field with its
dotted name as the user typed it (``road.bank_percent``, ``vehicle.weight_kn``), the reason and the error type (an
unknown field's reason names the nearest known field at that location: :func:`unknown_field_message`); an uploaded
file's error also says where in the file (``location``: ``row 7``, ``Alignment 'A' CoordGeom Curve #3 ('K1')``).
"""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Mapping, Sequence
from types import UnionType
from typing import Annotated, Any, Union, get_args, get_origin

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field, RootModel, Tag
from starlette.exceptions import HTTPException as StarletteHTTPException

from app.logs import get_logger
from app.metrics import ENGINE_ERRORS
from engine import (
    ConvergenceError,
    InvalidInput,
    InvalidLoad,
    InvalidRoad,
    InvalidVehicle,
    MechanismSingular,
    MissingParameter,
    UnknownPreset,
)

PROBLEM_MEDIA_TYPE = "application/problem+json"
TYPE_PREFIX = "urn:rollover:problem:"

#: engine input-error class -> problem type slug (most specific first)
_INPUT_TYPES: tuple[tuple[type[InvalidInput], str, str], ...] = (
    (MissingParameter, "missing-parameter", "The model needs a vehicle field that the record leaves null"),
    (InvalidVehicle, "invalid-vehicle", "The vehicle record is physically impossible or inconsistent"),
    (InvalidRoad, "invalid-road", "The road or speed input is outside the model's domain"),
    (InvalidLoad, "invalid-load", "The load case is impossible for this vehicle or model"),
    (InvalidInput, "invalid-input", "An input is outside the model's domain"),
)


class FieldError(BaseModel):
    """One offending input."""

    model_config = ConfigDict(extra="forbid")

    field: str = Field(description="Dotted name of the offending input, e.g. `road.bank_percent`.")
    message: str = Field(description="Why it was refused.")
    type: str = Field(description="Short error code (pydantic's error type, or the engine's error class).")
    loc: list[str | int] = Field(description="Location of the input in the request (`body`, `path`, ...).")
    location: str | None = Field(
        None,
        description="For an uploaded CSV, LandXML or IFC document: where in it (`row 7`, `row 1 (header)`, "
        "`Alignment 'A' CoordGeom Curve #3 ('K1')`, `LandXML line 4, column 2`, `IfcAlignment 'A' (#14) horizontal "
        "segment 2 (#32 IfcAlignmentSegment, #31 IfcAlignmentHorizontalSegment)`, `HEADER`).",
    )


class Problem(BaseModel):
    """RFC 9457 problem details."""

    model_config = ConfigDict(extra="allow")

    type: str = Field("about:blank", description="URI identifying the problem type.")
    title: str = Field(description="Short summary of the problem type.")
    status: int = Field(description="HTTP status code.")
    detail: str | None = Field(None, description="Explanation specific to this occurrence.")
    instance: str | None = Field(None, description="The request path that produced the problem.")
    errors: list[FieldError] | None = Field(None, description="The offending inputs, when the problem has any.")
    known: list[str] | None = Field(None, description="For an unknown preset: the known preset ids.")


class InvalidAlignment(ValueError):
    """Curves in a CSV, LandXML or IFC document that cannot be read: the request field holding the document
    (``csv``, ``landxml.document``, ``ifc.document``; ``body`` for a raw upload), the column or attribute, and where in
    the file."""

    def __init__(self, message: str, *, source: str, location: str | None, column: str | None) -> None:
        super().__init__(f"{source} {location}: {message}" if location else f"{source}: {message}")
        self.reason = message
        self.source = source
        self.location = location
        self.column = column


class InvalidRoute(InvalidAlignment):
    """A route document (``geojson`` or ``gpx``) that cannot be read: ``location`` names the feature or track and
    the vertex (``features[0].geometry.coordinates[17]``, ``trk[1] 'A1' trkseg[1] trkpt[18]``)."""


def as_a_job(message: str, operation: str, document: str, limits: str) -> str:
    """A synchronous size limit's ``message``, with how to send the work instead: the job ``operation``, how its
    ``document`` goes in the job's request, and the job's ``limits`` (docs/jobs.md)."""
    return (
        f'{message}; larger work goes to a job: POST /v1/jobs with {{"operation": "{operation}", "request": <this '
        f"request as JSON, {document}>}} takes up to {limits} (docs/jobs.md)"
    )


def request_error(field: str, message: str, value: Any = None) -> RequestValidationError:
    """A 422 validation problem for a rule that only the service can check (e.g. after reading a document),
    located at ``field`` (dotted) in the body."""
    return RequestValidationError(
        [{"type": "value_error", "loc": ("body", *field.split(".")), "msg": message, "input": value}]
    )


def problem_bytes(status: int, detail: str, instance: str) -> bytes:
    """The 413 problem+json body the body-limit middleware answers with (before routing, outside the handlers)."""
    body = {
        "type": TYPE_PREFIX + "body-too-large",
        "title": "Content Too Large",  # RFC 9110's name of 413
        "status": status,
        "detail": detail,
        "instance": instance,
    }
    return json.dumps(body).encode()


def problem_response(
    request: Request,
    status: int,
    slug: str | None,
    title: str,
    detail: str | None = None,
    *,
    headers: dict[str, str] | None = None,
    **extra: Any,
) -> JSONResponse:
    body: dict[str, Any] = {
        "type": TYPE_PREFIX + slug if slug else "about:blank",
        "title": title,
        "status": status,
        "instance": request.url.path,
    }
    if detail is not None:
        body["detail"] = detail
    body.update({k: v for k, v in extra.items() if v is not None})
    return JSONResponse(body, status_code=status, media_type=PROBLEM_MEDIA_TYPE, headers=headers)


VEHICLE_TAGS = ("id", "record", "spec", "combination", "combination_spec")


def _is_vehicle(before: list[str]) -> bool:
    """Whether the path ``before`` ends at a vehicle reference (``vehicle``, or ``vehicles.<i>``)."""
    if before[-1:] == ["vehicle"]:
        return True
    return len(before) >= 2 and before[-2] == "vehicles" and before[-1].isdigit()


def _untagged(loc: tuple[Any, ...] | list[Any]) -> list[Any]:
    """``loc`` without the union tag pydantic puts after a vehicle: (body, vehicle, record, weight_kn) -> (body,
    vehicle, weight_kn); (body, vehicles, 1, spec, spec, rear) -> (body, vehicles, 1, spec, rear)."""
    head = 1 if loc and str(loc[0]) in ("body", "query", "path", "header") else 0
    parts = [str(p) for p in loc[head:]]
    kept = [p for i, p in enumerate(loc[head:]) if not (parts[i] in VEHICLE_TAGS and _is_vehicle(parts[:i]))]
    return [*loc[:head], *kept]


def _dotted(loc: tuple[Any, ...] | list[Any]) -> str:
    parts = [str(p) for p in _untagged(loc)]
    if parts and parts[0] in ("body", "query", "path", "header"):
        parts = parts[1:]
    return ".".join(parts) or "body"


def engine_field(field: str | None) -> str | None:
    """Engine field names are record names for the vehicle; prefix them so they point into the request."""
    if field is None:
        return None
    from engine.vehicle import FIELD_DOCS

    return f"vehicle.{field}" if field in FIELD_DOCS else field


# ------------------------------------------------------------------------------- unknown fields


def _stripped(tp: Any) -> tuple[Any, str | None]:
    """``tp`` without ``Annotated`` layers, and the discriminated-union tag they carry (``Tag("spec")``), if any."""
    tag = None
    while get_origin(tp) is Annotated:
        tag = next((m.tag for m in tp.__metadata__ if isinstance(m, Tag)), tag)
        tp = tp.__origin__
    return tp, tag


def _is_model(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def models_at(tp: Any, path: list[Any] | tuple[Any, ...]) -> list[type[BaseModel]]:
    """The pydantic models that can hold the object at ``path`` (a validation error's ``loc`` below the body) of a
    value of type ``tp``: through model fields (by name or alias), list items, dict values, and unions (a path step
    naming a member's tag or class, as pydantic's locations do, picks that member; otherwise every member is
    followed). Empty where the path leaves the models (a ``dict[str, Any]`` field, a value parsed later)."""
    tp, _ = _stripped(tp)
    origin = get_origin(tp)
    if origin in (Union, UnionType):
        members = [_stripped(m) for m in get_args(tp) if m is not type(None)]
        if path and isinstance(path[0], str):
            for member, tag in members:
                if path[0] in (tag, getattr(member, "__name__", None)):
                    return models_at(member, path[1:])
        return [m for member, _ in members for m in models_at(member, path)]
    if _is_model(tp) and issubclass(tp, RootModel):  # e.g. a union of job submissions: its members' fields
        return models_at(tp.model_fields["root"].annotation, path)
    if not path:
        return [tp] if _is_model(tp) else []
    key, rest = path[0], path[1:]
    if _is_model(tp):
        field = next((f for n, f in tp.model_fields.items() if key in (n, f.alias)), None)
        return [] if field is None else models_at(field.annotation, rest)
    args = get_args(tp)
    if origin in (list, tuple, set, frozenset, Sequence) and args and isinstance(key, int):
        return models_at(args[0], rest)
    if origin in (dict, Mapping) and len(args) == 2:
        return models_at(args[1], rest)
    return []


def nearest_field(models: list[type[BaseModel]], name: str) -> str | None:
    """The known field name (or alias) of ``models`` closest to the unknown ``name`` (difflib's ratio >= 0.6), if
    any."""
    known = sorted({k for m in models for n, f in m.model_fields.items() for k in (n, f.alias) if k})
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return close[0] if close else None


def _body_type(request: Request) -> Any:
    """The body model of the operation that refused the request: its declared body, or the model a route that reads
    its body itself declares (:func:`app.http.bodies.json_body`); None when neither is known."""
    route = request.scope.get("route")
    params = getattr(getattr(route, "dependant", None), "body_params", None) or []
    if len(params) == 1:
        return params[0].field_info.annotation
    from app.http.bodies import READ_BY_ROUTE

    extra = getattr(route, "openapi_extra", None) or {}
    schema = extra.get("requestBody", {}).get("content", {}).get("application/json", {}).get("schema", {})
    name = str(schema.get("$ref", "")).rsplit("/", 1)[-1]
    return next((m for m in READ_BY_ROUTE if m.__name__ == name), None) if name else None


def unknown_field_message(request: Request, loc: tuple[Any, ...] | list[Any]) -> str:
    """The message of an ``extra_forbidden`` error in the body (``loc`` starts with ``body``): the unknown name and
    the nearest known one at that location (``unknown field 'superelevation_percnt': did you mean
    'superelevation_percent'?``); no suggestion when nothing is close or the location's model is not known here. (A
    query parameter's keeps pydantic's message.)"""
    name = str(loc[-1])
    root = _body_type(request)
    guess = None if root is None else nearest_field(models_at(root, list(loc[1:-1])), name)
    return f"unknown field {name!r}" + ("" if guess is None else f": did you mean {guess!r}?")


_BOUND_ERRORS = ("less_than_equal", "less_than", "greater_than", "greater_than_equal")


def _with_unit_slip(e: dict[str, Any]) -> str:
    """A vehicle record field's bound error with the likely unit slip added (``rear_track_m`` = 1860: ``1860 m: in
    millimetres? (1860 millimetres would be 1.86 m)``), when multiplying by the slip's factor brings the value inside
    the field's bounds; the message as it is otherwise."""
    from engine.vehicle import FIELD_DOCS, RECORD_SLIPS, unit_slip

    msg, loc, value = str(e.get("msg")), tuple(e.get("loc", ())), e.get("input")
    if e.get("type") not in _BOUND_ERRORS or "record" not in loc or not loc or str(loc[-1]) not in FIELD_DOCS:
        return msg
    if isinstance(value, bool) or not isinstance(value, int | float):
        return msg
    doc = FIELD_DOCS[str(loc[-1])]
    slip = unit_slip(float(value), doc.minimum, doc.maximum, RECORD_SLIPS.get(doc.unit, ()))
    if slip is None or slip[1] <= doc.minimum:  # the bounds are open below: a value at the minimum is refused too
        return msg
    return f"{msg}; {value:g} {doc.unit}: in {slip[0]}? ({value:g} {slip[0]} would be {slip[1]:g} {doc.unit})"


def _message(request: Request, e: dict[str, Any]) -> str:
    loc = tuple(e.get("loc", ()))
    if e.get("type") == "extra_forbidden" and loc[:1] == ("body",):
        return unknown_field_message(request, loc)
    return _with_unit_slip(e)


async def _validation_handler(request: Request, exc: RequestValidationError) -> JSONResponse:
    errors = list(exc.errors())
    if any(e.get("type") in ("json_invalid", "json_type") for e in errors):
        msg = "; ".join(str(e.get("msg")) for e in errors)
        return problem_response(request, 400, "malformed-request", "Malformed request body", msg)
    items = [
        {
            "field": _dotted(e.get("loc", ())),
            "message": _message(request, e),
            "type": str(e.get("type")),
            "loc": [p if isinstance(p, int) else str(p) for p in _untagged(e.get("loc", ()))],
        }
        for e in errors
    ]
    detail = "; ".join(f"{i['field']}: {i['message']}" for i in items)
    return problem_response(request, 422, "validation-error", "Request validation failed", detail, errors=items)


async def _unknown_preset_handler(request: Request, exc: UnknownPreset) -> JSONResponse:
    return problem_response(request, 404, "unknown-preset", "Unknown vehicle preset", str(exc), known=exc.known)


async def _input_handler(request: Request, exc: InvalidInput) -> JSONResponse:
    slug, title = next((s, t) for cls, s, t in _INPUT_TYPES if isinstance(exc, cls))
    ENGINE_ERRORS.labels(type(exc).__name__).inc()
    field = engine_field(exc.field)
    errors = None
    if field is not None:
        field = re.sub(r"\[(\d+)\]", r".\1", field)  # spec.payloads[0].x -> spec.payloads.0.x, as pydantic's paths
        loc = ["body", *(int(p) if p.isdigit() else p for p in field.split("."))]
        errors = [{"field": field, "message": str(exc), "type": slug, "loc": loc}]
    return problem_response(request, 422, slug, title, str(exc), errors=errors)


async def _route_handler(request: Request, exc: InvalidRoute) -> JSONResponse:
    field, loc = exc.source, ["body", *exc.source.split(".")]  # `gpx`, `geojson`, or a job's `request.geojson`
    if exc.source in ("body", "file"):  # an uploaded file (the body, or the multipart part): `location` says where
        field = exc.source if exc.column is None else f"{exc.source}.{exc.column}"
        loc = ["body"] if exc.source == "body" else ["body", "file"]
    elif exc.source.split(".")[-1] == "geojson" and exc.location:  # a JSON path into the document: a request field
        path = re.sub(r"\[(\d+)\]", r".\1", exc.location)
        field = f"{exc.source}.{path}"
        loc = [*loc, *(int(p) if p.isdigit() else p for p in path.split("."))]
    error = {"field": field, "message": exc.reason, "type": "invalid-route", "loc": loc, "location": exc.location}
    return problem_response(request, 422, "invalid-route", "The route cannot be read", str(exc), errors=[error])


async def _alignment_handler(request: Request, exc: InvalidAlignment) -> JSONResponse:
    field = exc.source if exc.column is None else f"{exc.source}.{exc.column}"
    loc = ["body"] if exc.source == "body" else ["body", *exc.source.split(".")]
    error = {"field": field, "message": exc.reason, "type": "invalid-alignment", "loc": loc, "location": exc.location}
    return problem_response(
        request, 422, "invalid-alignment", "The curves cannot be read from the document", str(exc), errors=[error]
    )


async def _singular_handler(request: Request, exc: MechanismSingular) -> JSONResponse:
    ENGINE_ERRORS.labels(type(exc).__name__).inc()
    return problem_response(
        request, 422, "mechanism-singular", "The mechanism's statics are singular for this input", str(exc)
    )


async def _convergence_handler(request: Request, exc: ConvergenceError) -> JSONResponse:
    ENGINE_ERRORS.labels(type(exc).__name__).inc()
    return problem_response(
        request,
        422,
        "no-convergence",
        "The solution did not converge (the vehicle is probably beyond its static stability limit)",
        str(exc),
        iterations=exc.iterations,
        residual=exc.residual,
    )


async def http_handler(request: Request, exc: StarletteHTTPException) -> JSONResponse:
    """A Starlette HTTP error (404, 405, ...) as a problem (``about:blank``, the status phrase as its title); the
    catalog wraps it to complete ``Allow``."""
    from http import HTTPStatus

    try:
        title = HTTPStatus(exc.status_code).phrase
    except ValueError:
        title = "Error"
    detail = exc.detail if isinstance(exc.detail, str) and exc.detail != title else None
    return problem_response(
        request, exc.status_code, None, title, detail, headers=getattr(exc, "headers", None) or None
    )


async def _internal_handler(request: Request, exc: Exception) -> JSONResponse:
    get_logger("rollover.app").error("unhandled_exception", path=request.url.path, method=request.method, exc_info=exc)
    return problem_response(
        request, 500, "internal-error", "Internal server error", "The error was logged; this is a bug to report."
    )


def install_problem_handlers(app: FastAPI) -> None:
    app.add_exception_handler(RequestValidationError, _validation_handler)
    app.add_exception_handler(UnknownPreset, _unknown_preset_handler)
    app.add_exception_handler(InvalidInput, _input_handler)
    app.add_exception_handler(InvalidRoute, _route_handler)
    app.add_exception_handler(InvalidAlignment, _alignment_handler)
    app.add_exception_handler(MechanismSingular, _singular_handler)
    app.add_exception_handler(ConvergenceError, _convergence_handler)
    app.add_exception_handler(StarletteHTTPException, http_handler)
    app.add_exception_handler(Exception, _internal_handler)


#: OpenAPI ``responses`` entries; :func:`app.http.openapi.problem_openapi` moves their schema to problem+json
def error_responses(*codes: int) -> dict[int | str, dict[str, Any]]:
    text = {
        400: "Malformed request body (not JSON, or an object naming a key twice; the `detail` says where).",
        415: "A JSON body sent with another `Content-Type`, or none (the `detail` names it).",
        404: "Unknown vehicle preset (the problem lists the known ids).",
        422: "Validation error (the problem's `errors` name each field and the reason), or the engine refused "
        "the input as physically invalid, found the mechanism singular or did not converge.",
        413: "Request body over this operation's limit (stated in the description); refused before it is read.",
        500: "Internal error (a bug; logged, never a stack trace).",
        401: "A saved vehicle or fleet is named without a valid bearer key (`Authorization: Bearer <key>`).",
        403: "A saved vehicle or fleet is named, but the deployment configures no `ROLLOVER_API_KEYS`.",
        409: "A saved vehicle or fleet named fails validation where it is stored (logged, not used).",
        503: "The database of saved vehicles is unavailable or locked; retry.",
    }
    return {c: {"model": Problem, "description": text[c]} for c in codes}


#: the extra problems of an operation that accepts saved vehicles (``veh_...``) or fleets by id
VEHICLE_REF_CODES = (401, 403, 409, 503)
