"""The vehicle builder over HTTP: POST /v1/vehicles/build, GET /v1/components, POST /v1/vehicles/payload-table.

A spec is turned into the engine's record by :func:`app.vehicle_forms.build.build_spec` (over
:func:`engine.builder.build_vehicle`), the one place that does it for the service (the build endpoint, a
``{"spec": ...}`` vehicle in any computation, a saved spec).
"""

from __future__ import annotations

import functools
from typing import Any

import orjson
from starlette.concurrency import run_in_threadpool

from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedBuild, ResolvedPayloadTable
from app.compute.results import Computed, cached
from app.formats.tables import Text, to_csv
from app.vehicle_forms.build import build_spec
from app.vehicle_forms.builder_schemas import (
    BuildRequest,
    BuildResult,
    ComponentLibrary,
    PayloadTableResult,
    SuspensionOut,
    TyreOut,
)
from app.vehicles.payload_schemas import PayloadTableRequest
from engine import ENGINE_VERSION
from engine.builder import (
    BuiltVehicle,
    CombinationSpec,
    PayloadTable,
    VehicleSpec,
    payload_table,
)
from engine.vehicle import NOT_FOUND, SUSPENSIONS, TYRES

PAYLOAD_CSV_COLUMNS = ("table", "load_height_m", "payload_mass_kg", "limit_value", "limit_status", "srt_g")


def build_result(built: BuiltVehicle) -> BuildResult:
    out = built.to_dict()
    out["derivation"] = {k: {n: v for n, v in d.items() if n != "field"} for k, d in out["derivation"].items()}
    return BuildResult.model_validate(out)


async def compute_build(cache: ResultCache, req: BuildRequest) -> Computed:
    spec = req.engine_spec()
    resolved = ResolvedBuild(spec=spec)

    async def produce() -> bytes:
        return build_result(build_spec(spec)).model_dump_json().encode()

    return await cached(cache, "vehicle-build", resolved, produce)


@functools.cache  # the library is fixed at import: built once, not per request
def component_library() -> ComponentLibrary:
    """Every library tyre and suspension with its values' sources, and what could not be sourced."""
    tyres = [
        TyreOut(
            id=t.id,
            title=t.title,
            size=t.size,
            loaded_radius_m=vars(t.loaded_radius_m),
            stiffness_kn_per_m=vars(t.stiffness_kn_per_m),
            rated_load_kg=None if t.rated_load_kg is None else vars(t.rated_load_kg),
        )
        for t in TYRES.values()
    ]
    suspensions = [
        SuspensionOut(
            id=s.id,
            title=s.title,
            kind=s.kind,
            stiffness_kn_per_m=vars(s.stiffness_kn_per_m),
            height_m=vars(s.height_m),
            spring_separation_m=vars(s.spring_separation_m),
            roll_stiffness_knm_per_rad=s.roll_stiffness_knm_per_rad,
        )
        for s in SUSPENSIONS.values()
    ]
    return ComponentLibrary(tyres=tyres, suspensions=suspensions, not_found=dict(NOT_FOUND))


# ----------------------------------------------------------------------------------------- payload table


def _payload_rows(table: PayloadTable) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    def row(r) -> dict[str, Any]:
        lim = r.limit
        return {
            "load_height_m": r.load_height_m,
            "payload_mass_kg": r.payload_mass_kg,
            "limit": {"value": lim.value, "status": lim.status, "srt_g": lim.srt_at_limit_g},
        }

    return [row(r) for r in table.by_load_height], [row(r) for r in table.by_payload_mass]


def payload_csv(table: PayloadTable) -> bytes:
    """Both tables in one CSV: ``table`` says which (``by_load_height``: the largest mass at each height;
    ``by_payload_mass``: the largest height at each mass)."""
    by_height, by_mass = _payload_rows(table)
    rows = [
        {
            "table": Text(name),
            "load_height_m": r["load_height_m"],
            "payload_mass_kg": r["payload_mass_kg"],
            "limit_value": r["limit"]["value"],
            "limit_status": Text(r["limit"]["status"]),
            "srt_g": r["limit"]["srt_g"],
        }
        for name, rows in (("by_load_height", by_height), ("by_payload_mass", by_mass))
        for r in rows
    ]
    return to_csv(PAYLOAD_CSV_COLUMNS, rows)


def _solve_payload_table(req: PayloadTableRequest, spec: VehicleSpec | CombinationSpec) -> PayloadTable:
    return payload_table(
        spec,
        req.target_srt_g,
        unit_index=req.unit_index,
        load_heights_m=req.load_heights_m,
        payload_masses_kg=req.payload_masses_kg,
        payload_index=req.payload_index,
        rows=req.rows,
    )


async def compute_payload_table(cache: ResultCache, req: PayloadTableRequest, csv: bool) -> Computed:
    spec = req.engine_spec()
    resolved = ResolvedPayloadTable.of(req, build=ResolvedBuild(spec=spec))

    async def produce() -> bytes:
        table = await run_in_threadpool(_solve_payload_table, req, spec)  # tens of 3D solves: off the event loop
        if csv:
            return payload_csv(table)
        by_height, by_mass = _payload_rows(table)
        out = PayloadTableResult(
            target_srt_g=table.target_srt_g,
            payload_index=table.payload_index,
            unit_index=table.unit_index,
            srt_of_spec_g=table.srt_at_spec_g,
            by_load_height=by_height,
            by_payload_mass=by_mass,
            engine_version=ENGINE_VERSION,
        )
        return orjson.dumps(out.model_dump())

    operation = "payload-table-csv" if csv else "payload-table"
    media = "text/csv; charset=utf-8" if csv else "application/json"
    return await cached(cache, operation, resolved, produce, media)
