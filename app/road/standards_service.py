"""Design standards: their list (GET /v1/design-standards) and the superelevation distribution
(POST /v1/superelevation, POST /v1/superelevation/table), over :mod:`engine.road.standards`."""

from __future__ import annotations

import numpy as np
import orjson

from app.compute.cache import ResultCache
from app.compute.resolved import ResolvedSuperelevation, ResolvedSuperelevationTable
from app.compute.results import Computed, cached
from app.formats.tables import to_csv
from app.road.standards_schemas import (
    DEFAULT_DESIGN_STANDARD,
    TABLE_RADIUS_SPAN,
    StandardList,
    StandardOut,
    SuperelevationRequest,
    SuperelevationResult,
    SuperelevationTableRequest,
    SuperelevationTableResult,
)
from engine import InvalidRoad
from engine.road import (
    FRICTION_BOUNDS,
    STANDARDS,
    DesignStandard,
    get_standard,
    min_radius_m,
    superelevation_percent,
    superelevation_table,
)

TABLE_COLUMNS = ("radius_m", "superelevation_percent", "side_friction")


def standard_out(std: DesignStandard) -> StandardOut:
    """The published description of one standard (``thesis-table21`` at its default bound)."""
    return StandardOut(
        id=std.id,
        title=std.title,
        citation=std.citation,
        table=std.table,
        speeds_kmh=list(std.speeds_kmh),
        f_max=list(std.f_max),
        speed_range_kmh=list(std.speed_range_kmh),
        max_superelevations_percent=list(std.max_superelevations_percent),
        min_radius_table={f"{e:g}": {f"{v:g}": r for v, r in row.items()} for e, row in std.min_radius_table.items()},
        superelevation_method=std.superelevation_method,
        side_friction_bounds=list(FRICTION_BOUNDS) if std.bound else None,
        notes=std.notes,
    )


def list_standards() -> StandardList:
    return StandardList(default=DEFAULT_DESIGN_STANDARD, standards=[standard_out(s) for s in STANDARDS.values()])


def get_standard_out(standard_id: str) -> StandardOut:
    """One standard by id (an unknown id is refused naming the known ones: a 404 from the router)."""
    return standard_out(get_standard(standard_id))


async def compute_superelevation(cache: ResultCache, req: SuperelevationRequest) -> Computed:
    resolved = ResolvedSuperelevation.of(req)

    async def produce() -> bytes:
        r = superelevation_percent(
            req.design_standard, req.design_speed_kmh, req.radius_m, req.max_superelevation_percent
        )
        out = SuperelevationResult(
            superelevation_percent=r.superelevation_percent,
            side_friction=r.side_friction,
            f_max=r.f_max,
            min_radius_m=r.min_radius_m,
            method=r.method,
            design_standard=r.standard,
            design_speed_kmh=req.design_speed_kmh,
            radius_m=req.radius_m,
            max_superelevation_percent=req.max_superelevation_percent,
        )
        return out.model_dump_json().encode()

    return await cached(cache, "superelevation", resolved, produce)


def table_radii(req: SuperelevationTableRequest) -> np.ndarray:
    """The radii of the table: the given ones, or ``points`` geometrically spaced from R_min to ``radius_max_m``
    (default :data:`TABLE_RADIUS_SPAN` R_min) [m]."""
    if req.radii_m is not None:
        return np.asarray(req.radii_m, dtype=float)
    r_min = min_radius_m(
        req.design_standard, req.design_speed_kmh, req.max_superelevation_percent, tabulated=False
    ).radius_m
    r_max = TABLE_RADIUS_SPAN * r_min if req.radius_max_m is None else req.radius_max_m
    if r_max <= r_min:
        raise InvalidRoad(
            f"radius_max_m {r_max:g} m must be above R_min {r_min:.4g} m of {req.design_standard} at "
            f"{req.design_speed_kmh:g} km/h and e_max {req.max_superelevation_percent:g} %",
            field="radius_max_m",
            value=r_max,
        )
    return np.geomspace(r_min, r_max, req.points)


async def compute_superelevation_table(cache: ResultCache, req: SuperelevationTableRequest, csv: bool) -> Computed:
    resolved = ResolvedSuperelevationTable.of(req)

    async def produce() -> bytes:
        t = superelevation_table(
            req.design_standard, req.design_speed_kmh, req.max_superelevation_percent, table_radii(req)
        )
        rows = [
            {"radius_m": float(r), "superelevation_percent": float(e), "side_friction": float(f)}
            for r, e, f in zip(t.radius_m, t.superelevation_percent, t.side_friction, strict=True)
        ]
        if csv:
            return to_csv(TABLE_COLUMNS, rows)
        out = SuperelevationTableResult(
            design_standard=req.design_standard,
            method=t.method,
            design_speed_kmh=req.design_speed_kmh,
            max_superelevation_percent=req.max_superelevation_percent,
            f_max=t.f_max,
            min_radius_m=t.min_radius_m,
            rows=rows,
        )
        return orjson.dumps(out.model_dump())

    operation = "superelevation-table-csv" if csv else "superelevation-table"
    media = "text/csv; charset=utf-8" if csv else "application/json"
    return await cached(cache, operation, resolved, produce, media)
