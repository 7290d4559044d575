"""Grid sweeps (POST /v1/srt/sweep): the SRT over the Cartesian product of up to eight axes.

Same flow as :mod:`app.srt.service`: the fully resolved request (preset expanded, defaults and targets filled) is the
cache key; the engine runs in a worker thread. The sweep's answer is kept as the engine's arrays (:class:`SweepAnswer`)
and rendered to JSON or CSV in chunks, like the alignment assessment (:mod:`app.alignments.service`): the grid (at
most 10,000 cases) is rendered whole and cached as bytes (served by the fast path on a repeat); a larger grid goes to
a job (:mod:`app.jobs.op_sweep`), whose parts the same renderers write.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
import orjson
from starlette.concurrency import run_in_threadpool

from app.compute import solvers
from app.compute.cache import ResultCache
from app.compute.resolved import JUDGED_ON, ResolvedSweep
from app.compute.results import Computed, cached
from app.formats.tables import flatten_targets, target_columns, to_csv_chunks
from app.http.negotiation import CSV_TYPE, JSON_TYPE
from app.metrics import SOLVE_SECONDS
from app.settings import Settings
from app.srt.service import level_case, resolve_base_case, target_checks
from app.srt.sweep_schemas import SweepRequest
from app.vehicles.resolve import VehicleRequest
from engine import ENGINE_VERSION, Case
from engine.models import SweepResult as EngineSweep
from engine.models import sweep
from engine.road import tilt_table_angle_deg

ROWS_PER_CHUNK = 1_000


def resolve_sweep(vr: VehicleRequest[SweepRequest], settings: Settings) -> ResolvedSweep:
    req = vr.body
    case = resolve_base_case(req, vr.vehicles[0].vehicle, settings)
    grid = {a: tuple(v) for a, v in req.grid.axes().items()}
    return ResolvedSweep(case=case, grid=grid, warnings=vr.warnings or None)


@dataclass(frozen=True)
class SweepAnswer:
    """Every case of a grid as the engine's arrays (:class:`engine.models.SweepResult`) and the SRT targets they
    are checked against: rendered to JSON or CSV in chunks (:func:`sweep_json_chunks`, :func:`sweep_csv_chunks`)."""

    resolved: ResolvedSweep
    result: EngineSweep
    targets: tuple[tuple[str, float], ...]  # (name, target [g]) in the rows' order: increasing target, then name
    level_srt: np.ndarray  # (n_cases,) each row's level-road SRT (bank and slope zero) [g]; nan where it has none


#: the axes a level-road SRT sets to zero
ROAD_AXES = ("bank_percent", "slope_percent")


def level_srts(base: Case, grid: dict[str, list[float]], result: EngineSweep) -> np.ndarray:
    """Each row's level-road SRT (:func:`app.srt.service.level_case`: the row's case with bank and slope zero), nan
    where that case has none. A grid that sweeps neither bank nor slope around a level case is its own level grid;
    otherwise the level grid is the same grid with the road axes collapsed to [0] (one case per combination of the
    other axes, solved once) and each row reads the row of its other axes' values."""
    level = level_case(base)
    if level is base and not any(a in grid for a in ROAD_AXES):
        srt = result.srt.astype(float, copy=True)
        srt[list(result.errors)] = np.nan
        return srt
    level_grid = {a: ([0.0] if a in ROAD_AXES else list(v)) for a, v in grid.items()}
    flat = sweep(level, level_grid, block_map=solvers.block_map)
    srt = flat.srt.astype(float, copy=True)
    srt[list(flat.errors)] = np.nan
    shape = tuple(len(v) for v in grid.values())
    index = np.unravel_index(np.arange(len(result.srt)), shape)
    index = tuple(np.zeros_like(i) if a in ROAD_AXES else i for a, i in zip(grid, index, strict=True))
    return srt[np.ravel_multi_index(index, tuple(len(v) for v in level_grid.values()))]


def sweep_answer(resolved: ResolvedSweep) -> SweepAnswer:
    """Every case of the grid (blocking: called in a worker thread), as arrays."""
    started = time.perf_counter()
    base = resolved.case.case
    result = sweep(base, resolved.grid, block_map=solvers.block_map)
    level = level_srts(base, resolved.grid, result)
    SOLVE_SECONDS.labels("srt-sweep", base.model).observe(time.perf_counter() - started)
    order = tuple((c["name"], c["target_g"]) for c in target_checks(0.0, resolved.case.targets))
    return SweepAnswer(resolved, result, order, level)


def _sweep_rows(answer: SweepAnswer, start: int, stop: int) -> list[dict[str, Any]]:
    """Rows [start, stop) as SweepRow dicts in the schema's field order (the swept axes only, then the results); the
    target checks as :func:`app.srt.service.target_checks` makes them (SRT >= target, SRT - target), on arrays."""
    r = answer.result
    goals = np.array([goal for _, goal in answer.targets], dtype=float)
    srt, values, level = r.srt[start:stop], r.values[start:stop], answer.level_srt[start:stop]
    meets, margins = (level[:, None] >= goals).tolist(), (level[:, None] - goals).tolist()
    targets = [
        [
            {"name": n, "target_g": g, "meets": m, "margin_g": d, "judged_on": JUDGED_ON}
            for (n, g), m, d in zip(answer.targets, ms, ds, strict=True)
        ]
        for ms, ds in zip(meets, margins, strict=True)
    ]
    columns: dict[str, list[Any]] = {axis: values[:, k].tolist() for k, axis in enumerate(r.axes)}
    columns["srt"] = srt.tolist()
    columns["level_road_srt"] = level.tolist()
    columns["roll_angle_deg"] = [None if math.isnan(x) else x for x in r.roll_angle_deg[start:stop].tolist()]
    columns["tilt_table_angle_deg"] = tilt_table_angle_deg(srt).tolist()
    columns["targets"] = targets
    columns["error"] = [None] * (stop - start)
    for i, error in r.errors.items():  # a refused case: no SRT, no roll, no tilt angle, no checks; its reason
        if start <= i < stop:
            k = i - start
            columns["srt"][k] = columns["roll_angle_deg"][k] = columns["tilt_table_angle_deg"][k] = None
            columns["targets"][k], columns["error"][k] = [], error
    for k in np.flatnonzero(np.isnan(level)).tolist():  # its level-road case refused: no level SRT, no verdict
        columns["level_road_srt"][k], columns["targets"][k] = None, []
    keys = list(columns)
    return [dict(zip(keys, row, strict=True)) for row in zip(*columns.values(), strict=True)]


def _row_chunks(answer: SweepAnswer) -> Iterator[list[dict[str, Any]]]:
    n = len(answer.result.srt)
    for start in range(0, n, ROWS_PER_CHUNK):
        yield _sweep_rows(answer, start, min(start + ROWS_PER_CHUNK, n))


def sweep_json_chunks(answer: SweepAnswer) -> Iterator[bytes]:
    """The SweepResult JSON document in chunks of rows: byte for byte what pydantic writes for the same result
    (``SweepResult.model_dump_json(exclude_unset=True)``: a row holds the swept axes only)."""
    r = answer.result
    head = {
        "model": r.model,
        "stage": r.stage,
        "axes": list(r.axes),
        "cases": len(r.srt),
        "refused": len(r.errors),
        "warnings": list(answer.resolved.warnings or ()),
    }
    yield orjson.dumps(head)[:-1] + b',"rows":['
    for k, rows in enumerate(_row_chunks(answer)):
        yield (b"," if k else b"") + orjson.dumps(rows)[1:-1]
    yield b'],"engine_version":' + orjson.dumps(ENGINE_VERSION) + b"}"


def sweep_csv_chunks(answer: SweepAnswer) -> Iterator[bytes]:
    """The rows as one CSV table in chunks: the swept axes, the results, two columns per target, the error."""
    names = [name for name, _ in answer.targets]
    columns = [
        *answer.result.axes,
        "srt",
        "level_road_srt",
        "roll_angle_deg",
        "tilt_table_angle_deg",
        *target_columns(names),
        "error",
    ]
    return to_csv_chunks(columns, ([flatten_targets(row) for row in rows] for rows in _row_chunks(answer)))


def render_sweep(answer: SweepAnswer, csv: bool) -> Iterator[bytes]:
    return sweep_csv_chunks(answer) if csv else sweep_json_chunks(answer)


def solve_sweep(resolved: ResolvedSweep, csv: bool = False) -> bytes:
    """Every case of the grid (blocking) -> the whole SweepResult JSON document (or its CSV table)."""
    return b"".join(render_sweep(sweep_answer(resolved), csv))


async def compute_sweep(
    cache: ResultCache, vr: VehicleRequest[SweepRequest], settings: Settings, *, csv: bool
) -> Computed:
    """The sweep as a cached body (at most :data:`~app.srt.sweep_schemas.MAX_CASES` cases: built whole)."""
    resolved = resolve_sweep(vr, settings)
    operation, media_type = ("srt-sweep-csv", CSV_TYPE) if csv else ("srt-sweep", JSON_TYPE)

    async def produce() -> bytes:
        return await run_in_threadpool(solve_sweep, resolved, csv)

    return await cached(cache, operation, resolved, produce, media_type)
