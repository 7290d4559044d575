"""Design standards: GET /v1/design-standards[/{id}], POST /v1/superelevation and its table."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Path, Request, Response

from app.deps import CacheDep
from app.http.fastpath import replayable
from app.http.negotiation import TABLE_FORMS, wants_csv
from app.http.problems import error_responses, problem_response
from app.http.responses import computed_response, computed_responses, json_response, table_responses
from app.road.standards_schemas import (
    StandardList,
    StandardOut,
    SuperelevationRequest,
    SuperelevationResult,
    SuperelevationTableRequest,
    SuperelevationTableResult,
)
from app.road.standards_service import (
    compute_superelevation,
    compute_superelevation_table,
    get_standard_out,
    list_standards,
)
from engine.road import STANDARDS

router = APIRouter(prefix="/v1", tags=["standards"])


@router.get(
    "/design-standards", name="list_design_standards", response_model=StandardList, responses=error_responses(500)
)
def list_design_standards() -> StandardList:
    """The design standards accepted as `design_standard` by the road endpoints, each with its full citation, its
    f_max by design speed, the design speeds it covers, its published minimum radii and its superelevation
    distribution; and the default."""
    return list_standards()


@router.get(
    "/design-standards/{id}",
    name="get_design_standard",
    response_model=StandardOut,
    responses={
        **error_responses(422, 500),
        404: {**error_responses(404)[404], "description": "Unknown standard (the problem lists the known ids)."},
    },
)
def get_design_standard(
    id: Annotated[str, Path(max_length=100, description="Standard id, e.g. `aashto-2018`.", examples=["dnit-1999"])],
    request: Request,
) -> StandardOut | Response:
    """One design standard with its citation and tables."""
    if id not in STANDARDS:
        return problem_response(
            request,
            404,
            "unknown-design-standard",
            "Unknown design standard",
            f"no design standard {id!r}; known: {', '.join(STANDARDS)}",
            known=list(STANDARDS),
        )
    return get_standard_out(id)


@router.post(
    "/superelevation",
    name="superelevation",
    response_model=SuperelevationResult,
    responses=computed_responses(400, 422, 500),
)
@replayable("superelevation")
async def superelevation(body: SuperelevationRequest, cache: CacheDep) -> Response:
    """Design superelevation of a curve by the standard's distribution: AASHTO Method 5 (Green Book Secs.
    3.3.5-3.3.6, with the standard's running speeds) or DNIT's e = e_max (2 R_min/R - R_min^2/R^2), with the side
    friction it leaves and R_min for e_max. A radius below R_min is a 422 naming R_min; at R_min the answer is
    e_max. `thesis-table21` has no distribution (422)."""
    return json_response(await compute_superelevation(cache, body))


@router.post(
    "/superelevation/table",
    name="superelevation_table",
    response_model=SuperelevationTableResult,
    responses=table_responses(400, 422, 500),
)
@replayable("superelevation-table", offers=TABLE_FORMS)
async def superelevation_table(body: SuperelevationTableRequest, request: Request, cache: CacheDep) -> Response:
    """The design superelevation and the side friction it leaves over a set of radii, for one design speed and
    e_max (JSON, or CSV when `Accept` prefers `text/csv`)."""
    csv = wants_csv(request.headers.get("accept"))
    return computed_response(await compute_superelevation_table(cache, body, csv), vary_accept=True)
