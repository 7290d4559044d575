"""POST /v1/routes/assess: a route as geometry (GeoJSON or GPX) -> its curves, assessed."""

from __future__ import annotations

import orjson
from fastapi import APIRouter, Request, Response
from fastapi.exceptions import RequestValidationError
from pydantic import ValidationError
from starlette.concurrency import run_in_threadpool

from ..bodylimit import body_limit
from ..deps import CacheDep, SettingsDep
from ..problems import VEHICLE_REF_CODES
from ..schemas.routes import ROUTE_BODY_LIMIT, RouteRequest, RouteResult
from ..service_routes import assess_route
from ..tables import wants_csv
from .common import computed_response, json_body, table_responses

router = APIRouter(prefix="/v1/routes", tags=["routes"])


def parse_route_request(body: bytes) -> RouteRequest:
    """The JSON request validated (in a worker thread: a route document may be megabytes)."""
    try:
        data = orjson.loads(body)
    except orjson.JSONDecodeError as exc:
        raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": f"JSON: {exc}"}]) from None
    try:
        return RouteRequest.model_validate(data)
    except ValidationError as exc:
        raise RequestValidationError(
            [{**e, "loc": ("body", *e["loc"])} for e in exc.errors(include_url=False)]
        ) from None


@router.post(
    "/assess",
    name="assess",
    response_model=RouteResult,
    responses=table_responses(400, 404, 422, 500, *VEHICLE_REF_CODES),
    openapi_extra={**body_limit(ROUTE_BODY_LIMIT), **json_body(RouteRequest)},
)
async def assess(request: Request, cache: CacheDep, settings: SettingsDep) -> Response:
    """The horizontal curves of a route given as geometry, each assessed like a curve of an alignment.

    The route (GeoJSON or GPX, WGS84) is developed into a plane frame that keeps its lengths and turning angles, split
    into tangents and curves (circular arcs with their spirals where resolved: radius, start and end chainage,
    deflection, direction, grade from the elevations; docs/routes.md says how and where it fails), and every curve
    is assessed for every vehicle: SRT on its superelevation and grade, rollover and side-friction speeds, the safe
    speed, the margin against the posted speed and the standard's minimum radius. JSON: a GeoJSON FeatureCollection
    of the curves with their assessment as properties (ready for a GIS); CSV with `Accept: text/csv`: one row per
    vehicle and curve. Geometry that cannot be read is a 422 naming the feature (or track) and the vertex."""
    req = await run_in_threadpool(parse_route_request, await request.body())
    csv = wants_csv(request.headers.get("accept"))
    return computed_response(await assess_route(cache, request, req, settings, csv=csv), vary_accept=True)
