"""The vehicle builder: POST /v1/vehicles/build, POST /v1/vehicles/payload-table and the component library."""

from __future__ import annotations

from fastapi import APIRouter, Request, Response

from app.deps import CacheDep
from app.http.fastpath import replayable
from app.http.negotiation import TABLE_FORMS, wants_csv
from app.http.problems import error_responses
from app.http.responses import computed_response, computed_responses, json_response, table_responses
from app.vehicle_forms.builder_schemas import (
    BuildRequest,
    BuildResult,
    ComponentLibrary,
    PayloadTableResult,
    SuspensionOut,
    TyreOut,
)
from app.vehicles.builder_service import component_library, compute_build, compute_payload_table
from app.vehicles.payload_schemas import PayloadTableRequest

router = APIRouter(prefix="/v1", tags=["builder"])


@router.post(
    "/vehicles/build",
    name="build_vehicle",
    response_model=BuildResult,
    responses=computed_responses(400, 404, 422, 500),
)
@replayable("vehicle-build")
async def build(body: BuildRequest, cache: CacheDep) -> Response:
    """The full vehicle record a measurable spec describes (unit type, axle groups with their tyres and suspension,
    tare and payloads with deck and load heights, front-unit data), with the derivation of every record field: its
    value, how it was obtained (`given`, `computed`, `library`, `default`) and the source. The same spec is
    accepted as `"vehicle": {"spec": {...}}` by every computation. A spec the builder cannot build is a 422 naming
    the spec field and the physical reason (docs/vehicles.md)."""
    return json_response(await compute_build(cache, body))


@router.post(
    "/vehicles/payload-table",
    name="payload_table",
    response_model=PayloadTableResult,
    responses=table_responses(400, 404, 422, 500),
)
@replayable("payload-table", offers=TABLE_FORMS)
async def payload_table(body: PayloadTableRequest, request: Request, cache: CacheDep) -> Response:
    """The acceptable payload table of a built vehicle for an SRT target (TERNZ's results page): the largest payload
    mass at each load height and the largest load height at each payload mass, each a root of SRT - target found
    with the 3D model (Brent's method on a bracket). JSON, or CSV with `Accept: text/csv`."""
    csv = wants_csv(request.headers.get("accept"))
    return computed_response(await compute_payload_table(cache, body, csv), vary_accept=True)


@router.get("/components", name="components", response_model=ComponentLibrary, responses=error_responses(500))
def components() -> ComponentLibrary:
    """The tyre and suspension library a spec can name (`tyre.id`, `suspension.type`), every value with its unit and
    source, and what was looked for and could not be sourced."""
    return component_library()


@router.get("/components/tyres", name="tyres", response_model=list[TyreOut], responses=error_responses(500))
def tyres() -> list[TyreOut]:
    """The library's tyres (use an `id` as `tyre.id` in a spec), each value with its source."""
    return component_library().tyres


@router.get(
    "/components/suspensions", name="suspensions", response_model=list[SuspensionOut], responses=error_responses(500)
)
def suspensions() -> list[SuspensionOut]:
    """The library's suspensions (use an `id` as `suspension.type` in a spec), each value with its source."""
    return component_library().suspensions
