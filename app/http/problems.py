"""RFC 9457 problem details for every error the service returns (``application/problem+json``).

Mapping:

==========================================  ======  ===================================================
cause                                       status  type
==========================================  ======  ===================================================
body is not JSON                            400     ``urn:rollover:problem:malformed-request``
request fails the schema                    422     ``urn:rollover:problem:validation-error``
unknown vehicle preset                      404     ``urn:rollover:problem:unknown-preset``
engine InvalidVehicle / MissingParameter    422     ``...:invalid-vehicle`` / ``...:missing-parameter``
engine InvalidRoad / InvalidLoad            422     ``...:invalid-road`` / ``...:invalid-load``
CSV / LandXML curves that cannot be read    422     ``urn:rollover:problem:invalid-alignment``
request body over the operation's limit     413     ``urn:rollover:problem:body-too-large``
engine MechanismSingular                    422     ``...:mechanism-singular``
engine ConvergenceError                     422     ``...:no-convergence``
no route / method (Starlette)               404/405 ``about:blank``
anything else (a bug)                       500     ``urn:rollover:problem:internal-error`` (logged)
==========================================  ======  ===================================================

Validation errors and engine input errors carry ``errors``: one entry per offending field with its
dotted name (``road.bank_percent``, ``vehicle.weight_kn``), the reason and the error type; an uploaded
file's error also says where in the file (``location``: ``row 7``, ``Alignment 'A' CoordGeom Curve #3 ('K1')``).
"""

from __future__ import annotations

import json
import re
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from pydantic import BaseModel, ConfigDict, Field
from starlette.exceptions import HTTPException as StarletteHTTPException

from app.logs import get_logger
from app.metrics import ENGINE_ERRORS
from engine.errors import (
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
        description="For an uploaded CSV or LandXML document: where in it (`row 7`, `row 1 (header)`, "
        "`Alignment 'A' CoordGeom Curve #3 ('K1')`, `LandXML line 4, column 2`).",
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
    """Curves in a CSV or LandXML document that cannot be read: the request field holding the document
    (``csv``, ``landxml.document``; ``body`` for a raw upload), the column or attribute, and where in the file."""

    def __init__(self, message: str, *, source: str, location: str | None, column: str | None) -> None:
        super().__init__(f"{source} {location}: {message}" if location else f"{source}: {message}")
        self.reason = message
        self.source = source
        self.location = location
        self.column = column


class InvalidRoute(InvalidAlignment):
    """A route document (``geojson`` or ``gpx``) that cannot be read: ``location`` names the feature or track and
    the vertex (``features[0].geometry.coordinates[17]``, ``trk[1] 'A1' trkseg[1] trkpt[18]``)."""


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


async def _validation_handler(request: Request, exc: RequestValidationError) -> JSONResponse:
    errors = list(exc.errors())
    if any(e.get("type") in ("json_invalid", "json_type") for e in errors):
        msg = "; ".join(str(e.get("msg")) for e in errors)
        return problem_response(request, 400, "malformed-request", "Malformed request body", msg)
    items = [
        {
            "field": _dotted(e.get("loc", ())),
            "message": str(e.get("msg")),
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
        400: "Malformed request body (not JSON).",
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
