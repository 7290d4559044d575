"""The ``srt.sweep`` job: ``POST /v1/srt/sweep`` at up to 1,000,000 cases, split into parts of whole sub-grids.

The cases are the Cartesian product of the axes, the first varying slowest; fixing the first j axes to one value
each leaves a *block* of consecutive cases that is itself a grid (the last axes, whole). The block is the largest
such grid of at most :data:`PART_CASES` cases, and a part is a run of consecutive blocks. Each block goes through
the synchronous endpoint's own computation and rendering (:func:`_render_block`, the one boundary with
:mod:`app.srt.sweep_service`); its rows are kept as JSON and CSV fragments, in order. The answer's ``cases`` and
``refused`` count every block's.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import orjson
from pydantic import Field, model_validator
from starlette.requests import Request

from app.compute.resolved import ResolvedSweep
from app.http.schemas import describe, shape_error
from app.jobs.base import Fragments, Operation, PartContext, Prepared, ResolveContext
from app.settings import Settings
from app.srt.sweep_schemas import AXIS_ORDER, MAX_AXIS_VALUES, MAX_JOB_CASES, SweepGrid, SweepRequest
from app.srt.sweep_service import resolve_sweep, solve_sweep, sweep_answer, sweep_csv_chunks, sweep_json_chunks
from app.vehicles.resolve import VehicleRequest, resolve_request

#: a job's limit, MAX_JOB_CASES, is in app.srt.sweep_schemas (the synchronous request's 10,000 cases' error names it)
#: cases per part (and at most per block: one synchronous sweep's worth)
PART_CASES = 20_000
_ROWS_OPEN = b'"rows":['
_ROWS_CLOSE = b'],"engine_version":'


class SweepJobRequest(SweepRequest):
    """The sweep's request (`POST /v1/srt/sweep`) at a job's size: at most 1,000,000 cases (the product of the axes'
    lengths, 1-200 values each). Everything else is validated as the synchronous request is."""

    grid: SweepGrid = Field(
        description=describe(
            f"Axes to vary and their values (at least one axis, 1-{MAX_AXIS_VALUES} values each, and at most "
            f"{MAX_JOB_CASES:,} cases in all: the product of the axes' lengths; a larger grid is refused).",
            unit="per axis",
            symbol="Tables 17, 19",
        )
    )

    @model_validator(mode="after")
    def _grid_size(self) -> SweepJobRequest:  # replaces the synchronous request's check (same name), job-sized
        axes = self.grid.axes()
        if not axes:
            raise shape_error("SweepRequest", "grid", f"give at least one axis to vary: {', '.join(AXIS_ORDER)}")
        cases = math.prod(len(v) for v in axes.values())
        if cases > MAX_JOB_CASES:
            sizes = " x ".join(f"{len(v)} {a}" for a, v in axes.items())
            raise shape_error("SweepRequest", "grid", f"{sizes} = {cases} cases; at most {MAX_JOB_CASES} per job")
        return self


def _render_block(resolved: ResolvedSweep) -> tuple[bytes, bytes]:
    """The synchronous sweep's JSON and CSV bodies for one (sub-)grid: the one call into :mod:`app.srt.sweep_service`
    (to follow it when the sweep is rendered in chunks)."""
    answer = sweep_answer(resolved)  # one solve, both renderings
    return b"".join(sweep_json_chunks(answer)), b"".join(sweep_csv_chunks(answer))


def _cut(body: bytes) -> tuple[bytes, bytes, bytes]:
    """A SweepResult document -> (up to its rows list, opened; the rows; from the list's end)."""
    start, end = body.index(_ROWS_OPEN) + len(_ROWS_OPEN), body.rindex(_ROWS_CLOSE)
    return body[:start], body[start:end], body[end:]


def _blocks(grid: dict[str, tuple[float, ...]], part_cases: int) -> tuple[int, int]:
    """(j, block): the first j axes are fixed in a block of ``block`` cases (the others whole), block <= part_cases
    whenever the last axis alone allows it."""
    lengths = [len(v) for v in grid.values()]
    for j in range(len(lengths) + 1):
        block = math.prod(lengths[j:])
        if block <= part_cases or j == len(lengths) - 1:
            return j, block
    return len(lengths), 1


def parse(data: Any) -> SweepJobRequest:
    return SweepJobRequest.model_validate(data)


async def refs(request: Request, req: SweepJobRequest, settings: Settings) -> VehicleRequest[SweepJobRequest]:
    """The request's vehicle resolved as ``POST /v1/srt/sweep`` resolves it (:mod:`app.vehicles.resolve`)."""
    return await resolve_request(request, req, settings)


def resolve(vr: VehicleRequest[SweepJobRequest], ctx: ResolveContext) -> ResolvedSweep:
    return resolve_sweep(vr, ctx.settings)


def split(resolved: ResolvedSweep, part_cases: int) -> Prepared:
    grid = resolved.grid
    # the base case's refusals (a model the vehicle cannot use...) now, on the grid's first case
    solve_sweep(resolved.on({a: v[:1] for a, v in grid.items()}))
    j, block = _blocks(grid, part_cases)
    n_blocks = math.prod(len(v) for v in list(grid.values())[:j])
    per_part = max(1, part_cases // block)
    parts = []
    for first in range(0, n_blocks, per_part):
        count = min(per_part, n_blocks - first)
        parts.append((count * block, orjson.dumps({"first_block": first, "blocks": count})))
    shared = {"resolved": resolved.to_json_dict(), "fixed_axes": j}
    etag = {"json": resolved.key("srt-sweep"), "csv": resolved.key("srt-sweep-csv")}
    return Prepared(shared, parts, etag)


def run_part(shared: dict[str, Any], data: bytes, ctx: PartContext) -> dict[str, Any]:
    spec = orjson.loads(data)
    first, count = spec["first_block"], spec["blocks"]
    if not (isinstance(first, int) and isinstance(count, int) and first >= 0 and count >= 1):
        raise ValueError("the part's block range is invalid")
    resolved, j = ResolvedSweep.from_json_dict(shared["resolved"]), shared["fixed_axes"]
    grid = resolved.grid
    axes, lengths = list(grid), [len(v) for v in grid.values()]
    meta: dict[str, Any] = {"cases": 0, "refused": 0}
    for i in range(count):
        index = np.unravel_index(first + i, lengths[:j]) if j else ()
        sub = {a: ([grid[a][int(index[n])]] if n < j else grid[a]) for n, a in enumerate(axes)}
        body, csv = _render_block(resolved.on(sub))
        head, rows, tail = _cut(body)
        header, _, lines = csv.partition(b"\r\n")
        counts = orjson.loads(head + b"]}")
        meta["cases"] += counts["cases"]
        meta["refused"] += counts["refused"]
        if i == 0:
            meta.update(head=head.decode(), tail=tail.decode(), csv_header=(header + b"\r\n").decode())
        ctx.write("json", 0, (b"," if i else b"") + rows)
        ctx.write("csv", 0, lines)
        ctx.progress(meta["cases"])
    return meta


def assemble(shared: dict[str, Any], metas: list[dict[str, Any]], fmt: str, fragments: Fragments) -> Iterator[bytes]:
    if fmt == "csv":
        yield metas[0]["csv_header"].encode()
        for k in range(len(metas)):
            yield from fragments(k, 0)
        return
    head = orjson.loads(metas[0]["head"].encode() + b"]}")
    head["cases"] = sum(m["cases"] for m in metas)
    head["refused"] = sum(m["refused"] for m in metas)
    yield orjson.dumps(head)[:-2]  # '..."rows":[]}' -> '..."rows":['
    for k in range(len(metas)):
        if k:
            yield b","
        yield from fragments(k, 0)
    yield metas[0]["tail"].encode()


OPERATION = Operation(
    name="srt.sweep",
    description="The SRT over a grid of `POST /v1/srt/sweep` (`request`: its JSON request) at up to "
    f"{MAX_JOB_CASES:,} cases (the product of the axes' lengths), in parts of up to {PART_CASES:,} cases; JSON or "
    "CSV.",
    request_model=SweepJobRequest,
    unit="cases",
    part_units=PART_CASES,
    csv=True,
    parse=parse,
    resolve=resolve,
    split=split,
    run_part=run_part,
    assemble=assemble,
    refs=refs,
)
