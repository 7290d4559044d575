"""The ``alignments.assess`` job: :mod:`app.alignments.service` (``POST /v1/alignments/assess``) at up to 1,000,000
rows, split into parts of curves.

A part is a range of curves for every vehicle (at most :data:`PART_ROWS` rows); a worker solves and renders it in
chunks of :data:`CHUNK_ROWS` rows (its progress reports) with the synchronous endpoint's own renderers, and keeps
per vehicle the rows as JSON and as CSV (compressed) and the summary of its curves. The answer opens each vehicle
with the summary over ALL curves: :func:`~app.alignments.service.merge_summaries` adds the parts' counts and takes
the smallest of their minimums, and the distinct SRT solves are counted over the whole alignment at submission
(:func:`~app.alignments.service.check_alignment`), not summed over the parts (two parts may share a pair).
"""

from __future__ import annotations

import io
import threading
from collections.abc import Iterator
from typing import Any

import numpy as np
import orjson
from cachetools import LRUCache
from pydantic import Field
from starlette.requests import Request

from app.alignments.rows import (
    JSON_VEHICLE_END,
    csv_columns,
    csv_header,
    csv_rows,
    json_head,
    json_rows,
    json_tail,
    json_vehicle_head,
    merge_summaries,
    summary,
)
from app.alignments.schemas import (
    AlignmentRequest,
    CurveId,
    CurveIn,
    CurveOverrideIn,
    LandXmlIn,
    keys_match_the_id_pattern,
)
from app.alignments.service import (
    AlignmentJob,
    check_alignment,
    resolve_alignment,
    resolve_alignment_refs,
    solve_alignment,
    validate_request_data,
)
from app.compute import solvers
from app.compute.cache import cache_key
from app.formats.alignment_io import CurveTable
from app.http.schemas import ABSENT, describe
from app.jobs.base import Fragments, Operation, PartContext, Prepared, ResolveContext
from app.settings import Settings
from app.vehicles.refs import vehicle_of_resolved
from engine.road import solve_bank_grade_pairs

#: a job's limits (the synchronous request's: 100,000 curves and rows, 16 M CSV and 64 M LandXML characters)
MAX_JOB_CURVES = 1_000_000
MAX_JOB_ROWS = 1_000_000
MAX_JOB_CSV_CHARS = 160_000_000
MAX_JOB_LANDXML_CHARS = 200_000_000
#: rows (curves x vehicles) per part, and per chunk of a part (a progress report, a cancellation point)
PART_ROWS = 50_000
CHUNK_ROWS = 5_000
_COLUMNS = ("radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh", "station_m")


class LandXmlJobIn(LandXmlIn):
    """A LandXML 1.2 document, as in the synchronous request, of up to 200,000,000 characters."""

    document: str = Field(
        min_length=1,
        max_length=MAX_JOB_LANDXML_CHARS,
        description=describe(
            "The LandXML 1.2 document (XML text; entities and DTDs are refused).", unit="-", symbol="-"
        ),
    )
    curve_overrides: dict[CurveId, CurveOverrideIn] | None = Field(
        None,
        max_length=MAX_JOB_CURVES,
        description=LandXmlIn.model_fields["curve_overrides"].description,
        json_schema_extra=keys_match_the_id_pattern,
    )


class AlignmentJobRequest(AlignmentRequest):
    """The alignment assessment's request (`POST /v1/alignments/assess`) at a job's size: at most 1,000,000 curves
    and 1,000,000 rows (curves x vehicles), CSV text of up to 160,000,000 characters, a LandXML document of up to
    200,000,000. Everything else is validated as the synchronous request is."""

    curves: list[CurveIn] = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_JOB_CURVES,
        description=describe(f"The curves (1-{MAX_JOB_CURVES}).", unit="per field", symbol="R, e, slope"),
    )
    csv: str = Field(
        None,
        json_schema_extra=ABSENT,
        min_length=1,
        max_length=MAX_JOB_CSV_CHARS,
        description=AlignmentRequest.model_fields["csv"].description,
    )
    landxml: LandXmlJobIn = Field(
        None, json_schema_extra=ABSENT, description=AlignmentRequest.model_fields["landxml"].description
    )


class PairMemo:
    """The SRTs of the (superelevation, grade) pairs this process has solved, per vehicle case: a part's chunks (and
    the next parts of the same job on this worker) solve only the pairs not seen yet. A pair's SRT does not depend on
    the batch it is solved in, so the answer is the synchronous one, byte for byte (the tests check it)."""

    def __init__(self, cases: int = 16) -> None:
        self.known: LRUCache = LRUCache(maxsize=cases)
        self._lock = threading.Lock()

    def __call__(self, case, pairs: np.ndarray) -> tuple[np.ndarray, dict[int, str]]:
        key = cache_key("pair-srt", case.to_dict())
        with self._lock:
            memo = self.known.get(key)
            if memo is None:
                memo = self.known[key] = {}
        rows = [tuple(p) for p in pairs.tolist()]
        todo = [i for i, p in enumerate(rows) if p not in memo]
        if todo:
            srt, errors = solve_bank_grade_pairs(case, pairs[todo], block_map=solvers.block_map)
            for j, i in enumerate(todo):
                memo[rows[i]] = (float(srt[j]), errors.get(j))
        found = [memo[p] for p in rows]
        return np.array([s for s, _ in found]), {i: e for i, (_, e) in enumerate(found) if e is not None}


PAIRS = PairMemo()


# ----------------------------------------------------------------------------------------- the hooks


def parse(data: Any):
    return validate_request_data(data, model=AlignmentJobRequest, max_curves=MAX_JOB_CURVES)


async def refs(request: Request, parsed, settings: Settings):
    """Saved vehicles, fleets and specs resolved as ``POST /v1/alignments/assess`` resolves them."""
    req, curves = parsed
    return await resolve_alignment_refs(request, req, settings), curves


def resolve(parsed, ctx: ResolveContext) -> AlignmentJob:
    """Presets and records (references were resolved by :func:`refs`) to the engine's inputs."""
    req, curves = parsed
    return resolve_alignment(req, curves, ctx.settings, max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS)


def pack_curves(t: CurveTable) -> bytes:
    """Curves as a compressed npz: the float64 columns, and the ids (and rows / elements) as JSON bytes; never a
    pickle (read back with ``allow_pickle=False``)."""
    buf = io.BytesIO()
    meta = np.frombuffer(orjson.dumps({"ids": t.ids, "where": t.where}), dtype=np.uint8)
    np.savez_compressed(buf, meta=meta, **{c: getattr(t, c).astype("<f8") for c in _COLUMNS})
    return buf.getvalue()


def unpack_curves(data: bytes) -> CurveTable:
    """:func:`pack_curves` read back and checked (raises ValueError for anything else)."""
    try:
        with np.load(io.BytesIO(data), allow_pickle=False) as z:
            meta = orjson.loads(z["meta"].tobytes())
            cols = [np.asarray(z[c], dtype="<f8") for c in _COLUMNS]
    except (OSError, KeyError, ValueError, orjson.JSONDecodeError) as exc:
        raise ValueError(f"the part's curves cannot be read: {exc}") from None
    ids, where = meta.get("ids"), meta.get("where")
    n = len(ids) if isinstance(ids, list) else -1
    if n < 1 or any(c.shape != (n,) for c in cols) or not all(isinstance(i, str) for i in ids):
        raise ValueError("the part's curves are inconsistent")
    if where is not None and (not isinstance(where, list) or len(where) != n):
        raise ValueError("the part's curve locations are inconsistent")
    return CurveTable(ids, *cols, where=where)


def split(job: AlignmentJob, part_rows: int) -> Prepared:
    distinct = check_alignment(job)  # refuses now what the synchronous endpoint would refuse for the whole request
    nv, n = len(job.vehicles), len(job.curves)
    per_part = max(1, part_rows // nv)
    parts = [(min(a + per_part, n) - a) * nv for a in range(0, n, per_part)]
    shared = {
        "resolved": job.resolved,
        "source": job.source,
        "curves": n,
        "distinct_srt_solves": distinct,
        "chunk_curves": max(1, CHUNK_ROWS // nv),
    }
    inputs = [pack_curves(job.curves.sliced(a, min(a + per_part, n))) for a in range(0, n, per_part)]
    etag = {"json": cache_key("alignments", job.resolved), "csv": cache_key("alignments-csv", job.resolved)}
    return Prepared(shared, list(zip(parts, inputs, strict=True)), etag)


def run_part(shared: dict[str, Any], data: bytes, ctx: PartContext) -> dict[str, Any]:
    curves = unpack_curves(data)
    resolved = shared["resolved"]
    vehicles = [vehicle_of_resolved(v) for v in resolved["vehicles"]]
    nv, n, step = len(vehicles), len(curves), shared["chunk_curves"]
    columns = csv_columns(resolved)
    summaries: list[list[dict[str, Any]]] = [[] for _ in range(nv)]
    for a in range(0, n, step):
        b = min(a + step, n)
        answer = solve_alignment(AlignmentJob(resolved, vehicles, curves.sliced(a, b), shared["source"]), PAIRS)
        for v in answer.vehicles:
            ctx.write("json", v.index, (b"," if a else b"") + json_rows(answer, v, 0, b - a))
            ctx.write("csv", v.index, csv_rows(answer, v, 0, b - a, columns))
            summaries[v.index].append(summary(v.columns))
        ctx.progress(b * nv)
    return {"summaries": [merge_summaries(s, 0) for s in summaries]}


def assemble(shared: dict[str, Any], metas: list[dict[str, Any]], fmt: str, fragments: Fragments) -> Iterator[bytes]:
    resolved = shared["resolved"]
    nv = len(resolved["vehicles"])
    if fmt == "csv":
        yield csv_header(resolved)
        for v in range(nv):
            for k in range(len(metas)):
                yield from fragments(k, v)
        return
    yield json_head(resolved, shared["curves"])
    for v in range(nv):
        total = merge_summaries([m["summaries"][v] for m in metas], shared["distinct_srt_solves"])
        yield json_vehicle_head(v, resolved["presets"][v], resolved["saved_ids"][v], total, first=v == 0)
        for k in range(len(metas)):
            if k:
                yield b","
            yield from fragments(k, v)
        yield JSON_VEHICLE_END
    yield json_tail()


OPERATION = Operation(
    name="alignments.assess",
    description="The alignment assessment of `POST /v1/alignments/assess` (`request`: its JSON request) at up to "
    f"{MAX_JOB_CURVES:,} curves and {MAX_JOB_ROWS:,} rows (curves x vehicles), in parts of {PART_ROWS:,} rows; "
    "JSON or CSV.",
    request_model=AlignmentJobRequest,
    unit="rows",
    part_units=PART_ROWS,
    csv=True,
    parse=parse,
    resolve=resolve,
    split=split,
    run_part=run_part,
    assemble=assemble,
    refs=refs,
)
