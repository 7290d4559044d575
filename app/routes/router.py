"""POST /v1/routes/assess: a route as geometry (GeoJSON or GPX) -> its curves, assessed; and its raw-file forms
/assess/gpx and /assess/geojson (the file as the body or the multipart part ``file``, the options in the query)."""

from __future__ import annotations

from typing import Annotated

import orjson
from fastapi import APIRouter, Query, Request, Response
from fastapi.exceptions import RequestValidationError
from pydantic import ValidationError
from starlette.concurrency import run_in_threadpool

from app.deps import CacheDep, SettingsDep
from app.formats.jsonpieces import loads_long_strings
from app.http.bodies import json_body, upload_body
from app.http.bodylimit import body_limit
from app.http.fastpath import replayable
from app.http.negotiation import GEOJSON_MEDIA_TYPE, WITH_GEOJSON, negotiate
from app.http.problems import VEHICLE_REF_CODES
from app.http.responses import ANSWER_MODELS, computed_response, table_responses
from app.http.strictjson import refuse_duplicate_keys
from app.routes.schemas import EXAMPLE_GEOJSON, EXAMPLE_GPX, ROUTE_BODY_LIMIT, RouteCurves, RouteRequest, RouteResult
from app.routes.service import assess_route, resolve_route_request
from app.routes.uploads import RouteUploadQuery, geojson_upload, gpx_upload

router = APIRouter(prefix="/v1/routes", tags=["routes"])


def parse_route_request(body: bytes) -> RouteRequest:
    """The JSON request validated (in a worker thread: a route document may be megabytes, its long strings decoded a
    slice at a time, :func:`app.formats.jsonpieces.loads_long_strings`)."""
    try:
        data = loads_long_strings(body)
    except orjson.JSONDecodeError as exc:
        raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": f"JSON: {exc}"}]) from None
    refuse_duplicate_keys(body, data)
    try:
        return RouteRequest.model_validate(data)
    except ValidationError as exc:
        raise RequestValidationError(
            [{**e, "loc": ("body", *e["loc"])} for e in exc.errors(include_url=False)]
        ) from None


_RESPONSES = table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES)
_RESPONSES[200] = {
    **_RESPONSES[200],
    "content": {
        **_RESPONSES[200]["content"],
        GEOJSON_MEDIA_TYPE: {"schema": {"$ref": "#/components/schemas/RouteCurves"}},
    },
    "description": "JSON by default; the curves as GeoJSON when `Accept` prefers `application/geo+json`; CSV (one "
    "row per vehicle and curve) when it prefers `text/csv`.",
}
ANSWER_MODELS.append(RouteCurves)  # published in components/schemas (the GeoJSON answer refers to it)


@router.post(
    "/assess",
    name="assess",
    response_model=RouteResult,
    responses=_RESPONSES,
    openapi_extra={**body_limit(ROUTE_BODY_LIMIT), **json_body(RouteRequest)},
)
@replayable("route", offers=WITH_GEOJSON)
async def assess(request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """The horizontal curves of a route given as geometry, each assessed like a curve of an alignment.

    The route (GeoJSON or GPX, WGS84) is developed into a plane frame that keeps its lengths and turning angles, split
    into tangents and curves (circular arcs with their spirals where resolved: radius, start and end chainage,
    deflection, direction, grade from the elevations; docs/routes.md says how and where it fails), and every curve
    is assessed for every vehicle: SRT on its superelevation and grade, rollover and side-friction speeds, the safe
    speed, the margin against the posted speed and the standard's minimum radius. JSON: `curves`, each with its
    geometry, vertices and assessment; GeoJSON with `Accept: application/geo+json`: the curves as a
    FeatureCollection (RFC 7946) with the same properties, ready for a GIS; CSV with `Accept: text/csv`: one row
    per vehicle and curve. Every answer carries `reading`: the file's format and writer, the parts read, and what was
    skipped and why (empty track segments, a router's `<rte>` beside its `<trk>` unless `parts` asks, features that
    are not lines, `maxspeed` values that are no speed). A curve outside the model's domain (a car park's or a
    junction's turn of a few metres) is a row with `error`, never a refusal of the document; a road without a curve
    answers 200 with none; grades from elevations are clipped to +/-20 % with `grade_clipped` (or ignored:
    `use_elevation` false); OSM ways that meet end to end are joined into one road and their `maxspeed` read.
    Geometry that cannot be read is a 422 naming the feature (or track) and the vertex. At most 10,000 rows (curves
    x vehicles) per request: a longer route goes to a job (`POST /v1/jobs`, `routes.assess`)."""
    req = await run_in_threadpool(parse_route_request, await request.body())
    accept = request.headers.get("accept")
    form = negotiate(accept, WITH_GEOJSON)
    return computed_response(
        await assess_route(cache, await resolve_route_request(request, req, settings), settings, form=form),
        vary_accept=True,
    )


UPLOAD = """

The body is the {what} itself (`--data-binary @{file}`), or the part `file` of a `multipart/form-data` body
(`-F file=@{file}`); the options are query parameters (`vehicle` repeated for several presets; the detection's
`noise_m`, `max_radius_m`, `min_deflection_deg` as plain parameters; `parts`, `use_elevation`, `grade_percent` as
they are). The same request as `POST /v1/routes/assess` with `{field}`: the same answer, byte for byte, and the same
cache entry. A rule the query's schema cannot state:
`side_friction_bound` only with `design_standard` `thesis-table21` (or alone)."""


@router.post(
    "/assess/gpx",
    name="assess_gpx",
    response_model=RouteResult,
    responses=_RESPONSES,
    openapi_extra=upload_body("application/gpx+xml", ROUTE_BODY_LIMIT, EXAMPLE_GPX, "GPX 1.1 document"),
    description=(assess.__doc__ or "").replace("\n    ", "\n")
    + UPLOAD.format(what="GPX 1.1 document", file="road.gpx", field="gpx"),
)
@replayable("route", offers=WITH_GEOJSON)
async def assess_gpx(
    request: Request, query: Annotated[RouteUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    req, field = await gpx_upload(request, query, ROUTE_BODY_LIMIT)
    form = negotiate(request.headers.get("accept"), WITH_GEOJSON)
    result = await assess_route(
        cache, await resolve_route_request(request, req, settings), settings, form=form, source_field=field
    )
    return computed_response(result, vary_accept=True)


@router.post(
    "/assess/geojson",
    name="assess_geojson",
    response_model=RouteResult,
    responses=_RESPONSES,
    openapi_extra=upload_body(
        GEOJSON_MEDIA_TYPE, ROUTE_BODY_LIMIT, orjson.dumps(EXAMPLE_GEOJSON).decode(), "GeoJSON document"
    ),
    description=(assess.__doc__ or "").replace("\n    ", "\n")
    + UPLOAD.format(what="GeoJSON document (RFC 7946)", file="road.geojson", field="geojson"),
)
@replayable("route", offers=WITH_GEOJSON)
async def assess_geojson(
    request: Request, query: Annotated[RouteUploadQuery, Query()], cache: CacheDep, settings: SettingsDep
) -> Response:
    req, field = await geojson_upload(request, query, ROUTE_BODY_LIMIT)
    form = negotiate(request.headers.get("accept"), WITH_GEOJSON)
    result = await assess_route(
        cache, await resolve_route_request(request, req, settings), settings, form=form, source_field=field
    )
    return computed_response(result, vary_accept=True)
