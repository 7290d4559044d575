"""The ``routes.assess`` job: :mod:`app.routes.service` (``POST /v1/routes/assess``) as a background job.

A route is one part: its curves are found along the whole polyline (a curve may span what would be a part's
boundary) and the answer's summaries are over all of them. It is quick (500 km of route in about 2 s), so the job
exists for the caller who submits many routes, wants to poll rather than hold a connection, or fetches both JSON
and CSV of one solve. The geometry is read at submission, so a document that cannot be read is a 422 at ``POST
/v1/jobs`` (fields under ``request.``), never a failed job; the vehicles (presets, records, saved vehicles and
fleets of the caller, specs) are resolved there too, and the stored job holds their records only.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import orjson
from starlette.requests import Request

from app.compute.resolved import ResolvedRoute
from app.jobs.base import Fragments, Operation, PartContext, Prepared, ResolveContext
from app.routes.schemas import RouteRequest
from app.routes.service import (
    MAX_JOB_ROWS,
    curve_table,
    find_route_curves,
    read_route,
    render_route,
    resolve_route_request,
    resolved_route,
)
from app.settings import Settings
from app.vehicles.resolve import VehicleRequest


def parse(data: Any) -> RouteRequest:
    return RouteRequest.model_validate(data)


async def refs(request: Request, req: RouteRequest, settings: Settings) -> VehicleRequest[RouteRequest]:
    """The request's vehicles (saved vehicles, fleets, specs...) resolved as ``POST /v1/routes/assess`` resolves
    them."""
    return await resolve_route_request(request, req, settings)


@dataclass(frozen=True)
class RouteJob:
    """A resolved route job: the request without its vehicle references (a worker rebuilds it, as JSON), the resolved
    assessment and the document's number of vertices (the job's units)."""

    request: dict[str, Any]
    resolved: ResolvedRoute
    vertices: int


def resolve(vr: VehicleRequest[RouteRequest], ctx: ResolveContext) -> RouteJob:
    """The route request without its vehicle references (a worker rebuilds it) and the resolved assessment."""
    req = vr.body
    resolved = resolved_route(vr, ctx.settings)
    read = read_route(req, synchronous=False)  # reading refuses bad geometry now (a 422)
    parts = read.parts
    vertices = sum(int(p.lon_deg.size) for p in parts)
    if (
        req.superelevation_percent is None
        and req.max_superelevation_percent is None
        and any(p.properties.get("superelevation_percent") is None for p in parts)
    ):
        # the synchronous request refuses a found curve without a superelevation: with no default for it the
        # curves are found now, so that such a job is refused here (the same 422), not failed by its worker
        curve_table(req, find_route_curves(req, read))
    stored = req.model_dump(mode="json", exclude={"vehicle", "vehicles", "fleet"}, exclude_unset=True)
    return RouteJob(stored, resolved, vertices)


def split(job: RouteJob, part_units: int) -> Prepared:
    resolved = job.resolved
    shared = {"request": job.request, "resolved": resolved.to_json_dict(), "vertices": job.vertices}
    etag = {"json": resolved.key("route"), "csv": resolved.key("route-csv")}
    return Prepared(shared, [(job.vertices, b"{}")], etag)


def request_of(shared: dict[str, Any], resolved: ResolvedRoute) -> RouteRequest:
    """The stored request validated again, its vehicles given as the resolved records (the worker solves those)."""
    return RouteRequest.model_validate({**shared["request"], "vehicles": list(resolved.vehicles)})


def run_part(shared: dict[str, Any], data: bytes, ctx: PartContext) -> dict[str, Any]:
    if orjson.loads(data) != {}:
        raise ValueError("a route job has a single part without inputs of its own")
    resolved = ResolvedRoute.from_json_dict(shared["resolved"])
    req = request_of(shared, resolved)
    bodies = render_route(req, resolved, ("json", "csv"), max_rows=MAX_JOB_ROWS)
    ctx.write("json", 0, bodies["json"])
    ctx.write("csv", 0, bodies["csv"])
    ctx.progress(shared["vertices"])
    return {"bytes": {form: len(body) for form, body in bodies.items()}}


def assemble(shared: dict[str, Any], metas: list[dict[str, Any]], fmt: str, fragments: Fragments) -> Iterator[bytes]:
    yield from fragments(0, 0)


OPERATION = Operation(
    name="routes.assess",
    description="The route assessment of `POST /v1/routes/assess` (`request`: its JSON request, `parts` and "
    "`use_elevation` included) as a job: the geometry is read at submission (a 422 when it cannot be), the curves are "
    "found and assessed by a worker, a curve outside the model's domain as a row with `error`, a road without a "
    "curve as an answer without curves; the answer's `reading` says what was read and skipped; one part; JSON or "
    "CSV.",
    request_model=RouteRequest,
    unit="vertices",
    part_units=1,
    csv=True,
    parse=parse,
    resolve=resolve,
    split=split,
    run_part=run_part,
    assemble=assemble,
    refs=refs,
)
