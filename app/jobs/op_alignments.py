"""The ``alignments.assess`` job: :mod:`app.alignments.service` (``POST /v1/alignments/assess``) at up to 1,000,000
rows, split into parts of curves.

A part is a range of curves for every vehicle (at most :data:`PART_ROWS` rows); a worker solves it in chunks of
:data:`CHUNK_ROWS` rows (its progress reports, counting solved rows, and its cancellation points) and keeps per
vehicle the engine's result as typed columns (:data:`RESULT_SCHEMA`, :mod:`app.jobs.columns`) and the summary of its
curves; nothing is rendered then. ``GET /v1/jobs/{id}/result`` reads the columns back (checked: they come from the
store) and renders JSON or CSV from them with the synchronous endpoint's own renderers (:mod:`app.alignments.rows`),
streamed part by part: the same bytes. The answer opens each vehicle with the summary over ALL curves:
:func:`~app.alignments.rows.merge_summaries` adds the parts' counts and takes the smallest of their minimums, and
the distinct SRT solves are counted over the whole alignment at submission
(:func:`~app.alignments.service.check_alignment`), not summed over the parts (two parts may share a pair).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np
from pydantic import Field
from starlette.requests import Request

from app.alignments.advice import ADVICE_INPUTS, VehicleAdvice, advise, curve_places
from app.alignments.answer import AlignmentAnswer, VehicleAnswer, vehicle_answer
from app.alignments.json_curves import read_json_curves
from app.alignments.rows import (
    ROWS_PER_CHUNK,
    csv_columns,
    csv_header,
    csv_rows,
    json_head,
    json_rows,
    json_tail,
    json_vehicle_end,
    json_vehicle_head,
    merge_summaries,
    summary,
)
from app.alignments.schemas import (
    MAX_IFC_CHARS,
    MAX_JOB_CURVES,
    MAX_JOB_ROWS,
    AlignmentRequest,
    CurveId,
    CurveIn,
    CurveOverrideIn,
    IfcIn,
    LandXmlIn,
    keys_match_the_id_pattern,
)
from app.alignments.service import (
    AlignmentJob,
    assess_table,
    assessment_case,
    check_alignment,
    level_road_srt,
    resolve_alignment,
    resolve_assessment_request,
    validate_request_data,
)
from app.compute import solvers
from app.compute.resolved import ResolvedAlignment
from app.formats.alignment_io import BEND_COLUMNS, BendTable, CurveTable
from app.formats.texts import Texts, TextsError
from app.http.schemas import ABSENT, describe
from app.jobs.base import FragmentHeads, Fragments, Operation, PartContext, Prepared, ResolveContext
from app.jobs.columns import (
    ColumnsError,
    codes_within,
    header_length,
    pack_columns,
    read_header,
    require,
    strings,
    unpack_columns,
)
from app.jobs.csv_columns import read_csv_columns
from app.settings import Settings
from app.vehicles.resolve import vehicle_of_resolved
from engine.road import (
    GOVERNED_BY,
    AlignmentColumns,
    solve_bank_grade_pairs,
)

#: a job's limits (the synchronous request's: 10,000 curves and rows, 16 M CSV and 64 M LandXML characters); the
#: curves and rows in app.alignments.schemas, whose limit errors name them
MAX_JOB_CSV_CHARS = 160_000_000
MAX_JOB_LANDXML_CHARS = 200_000_000
#: an IFC file's bound stays the synchronous request's (a job lifts its curve and row limits): IfcOpenShell holds the
#: parsed file whole, an entity object for every line, 9-14 bytes of memory per byte of the file (peak RSS growth
#: parsing 10 MB and 34 MB files, measured): about 0.9 GB at 64 MB, some 2-3 GB at LandXML's 200 M
MAX_JOB_IFC_CHARS = MAX_IFC_CHARS
#: rows (curves x vehicles) per part, and per chunk of a part (a progress report, a cancellation point)
PART_ROWS = 50_000
CHUNK_ROWS = 10_000
_COLUMNS = ("radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh", "station_m")
#: a road file's bend columns (:class:`~app.formats.alignment_io.BendTable`), in a part's inputs and results: each
#: of the part's length, or all empty for curves that came as JSON or CSV
_BEND_SCHEMA = {name: "<f8" for name in BEND_COLUMNS}


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


class IfcJobIn(IfcIn):
    """An IFC 4.3 file, as in the synchronous request (the same bound on its size), with overrides for up to
    1,000,000 curves."""

    document: str = Field(
        min_length=1, max_length=MAX_JOB_IFC_CHARS, description=IfcIn.model_fields["document"].description
    )
    curve_overrides: dict[CurveId, CurveOverrideIn] | None = Field(
        None,
        max_length=MAX_JOB_CURVES,
        description=IfcIn.model_fields["curve_overrides"].description,
        json_schema_extra=keys_match_the_id_pattern,
    )


class AlignmentJobRequest(AlignmentRequest):
    """The alignment assessment's request (`POST /v1/alignments/assess`) at a job's size: at most 1,000,000 curves
    and 1,000,000 rows (curves x vehicles), CSV text of up to 160,000,000 characters, a LandXML document of up to
    200,000,000, an IFC file of up to 64,000,000 (as synchronously). Everything else is validated as the
    synchronous request is."""

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
    ifc: IfcJobIn = Field(None, json_schema_extra=ABSENT, description=AlignmentRequest.model_fields["ifc"].description)


# ----------------------------------------------------------------------------------------- the hooks


def parse(data: Any, curves: CurveTable | None = None):
    """The request validated as the synchronous one is (``curves``: already read from the text by
    :func:`read_body`, the request's list then empty)."""
    return validate_request_data(data, model=AlignmentJobRequest, max_curves=MAX_JOB_CURVES, curves=curves)


def read_body(body: bytes) -> tuple[dict[str, Any], CurveTable] | None:
    """The job's document (``request.curves`` empty) and its curves read from the text straight into columns
    (:func:`app.alignments.json_curves.read_json_curves`: no dict per curve) when it is an alignment job whose
    curves are of the plain form; None otherwise (the body is then parsed whole, and the curves by :func:`parse`)."""
    found = read_json_curves(body, ("request", "curves"), max_curves=MAX_JOB_CURVES)
    return found if found is not None and found[0].get("operation") == OPERATION.name else None


async def refs(request: Request, parsed, settings: Settings):
    """The request's vehicles (saved vehicles, fleets, specs...) resolved as ``POST /v1/alignments/assess`` resolves
    them: ``(VehicleRequest, curves)``."""
    req, curves = parsed
    return await resolve_assessment_request(request, req, settings), curves


def resolve(parsed, ctx: ResolveContext) -> AlignmentJob:
    """The request, its vehicles resolved by :func:`refs`, to the engine's inputs."""
    vr, curves = parsed
    req = vr.body
    fast = None
    if curves is None and req.csv is not None:  # the plain CSV form straight into columns; any other: read_csv's
        fast = curves = read_csv_columns(req.csv, max_curves=MAX_JOB_CURVES)
    job = resolve_alignment(vr, curves, ctx.settings, max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS)
    return job if fast is None else dataclasses.replace(job, source="csv")


#: a part's inputs (:mod:`app.jobs.columns`): its curves (ids in the meta), and the distinct (superelevation, grade)
#: pairs they use, sorted, with each vehicle's SRT on each (``pair_srt``: vehicle-major, nv x m) and the code of the
#: reason a pair has none (``pair_error``, into the meta's ``errors``; -1: solved), solved once for the whole job
#: the curve ids as one UTF-8 blob and each one's end in it (:class:`~app.formats.texts.Texts`: read back with no
#: Python string per id; in a JSON list they took 0.1 s per million to parse and check, at each read)
_ID_SCHEMA = {"id_text": "|u1", "id_end": "<i8"}
INPUT_SCHEMA = {
    "radius_m": "<f8",
    "superelevation_percent": "<f8",
    "grade_percent": "<f8",
    "posted_speed_kmh": "<f8",
    "station_m": "<f8",
    **_BEND_SCHEMA,
    "pair_superelevation_percent": "<f8",
    "pair_grade_percent": "<f8",
    "pair_srt": "<f8",
    "pair_error": "<i4",
    **_ID_SCHEMA,
}


@dataclass(frozen=True)
class PartInput:
    curves: CurveTable
    pairs: np.ndarray  # (m,) superelevation + 1j grade, sorted (the order of engine.road.bank_grade_pairs)
    srt: np.ndarray  # (nv, m) [g]
    error: np.ndarray  # (nv, m) codes into errors, -1: none
    errors: list[str]


def pack_input(t: CurveTable, pairs: np.ndarray, srt: np.ndarray, error: np.ndarray, errors: list[str]) -> bytes:
    """A part's inputs as columns (:data:`INPUT_SCHEMA`; ``pairs``: (m, 2); ``srt``, ``error``: (nv, m))."""
    columns = {c: getattr(t, c) for c in _COLUMNS} | _bend_columns(t)
    columns |= {
        "pair_superelevation_percent": pairs[:, 0],
        "pair_grade_percent": pairs[:, 1],
        "pair_srt": srt,
        "pair_error": error,
        **_id_columns(t),
    }
    return pack_columns(columns, INPUT_SCHEMA, {"errors": errors, "vehicles": int(srt.shape[0])})


def _bend_columns(t: CurveTable) -> dict[str, np.ndarray]:
    """The curves' bend columns to store (empty ones when they came from no road file)."""
    if t.bends is None:
        return {name: np.empty(0) for name in BEND_COLUMNS}
    return {name: t.bends[name] for name in BEND_COLUMNS}


def _bends(cols: dict[str, np.ndarray], n: int) -> BendTable | None:
    """The stored bend columns read back: all of the part's length, or all empty (none)."""
    if all(cols[name].size == 0 for name in BEND_COLUMNS):
        return None
    require(cols, BEND_COLUMNS, n)
    return BendTable({name: cols[name] for name in BEND_COLUMNS})


def _id_columns(t: CurveTable) -> dict[str, np.ndarray]:
    blob, ends = Texts.of(t.ids).stored()
    return {"id_text": blob, "id_end": ends}


def _ids(cols: dict[str, np.ndarray], n: int) -> Texts:
    """The part's curve ids read back (no Python string each: :class:`~app.formats.texts.Texts`), checked."""
    try:
        return Texts.read(cols["id_text"].data, cols["id_end"], n)
    except TextsError as exc:
        raise ColumnsError(f"the part's curve ids: {exc}") from None


def unpack_input(data: bytes) -> PartInput:
    """:func:`pack_input` read back and checked (raises :class:`~app.jobs.columns.ColumnsError`, a ValueError)."""
    cols, meta = unpack_columns(data, INPUT_SCHEMA)
    n, m, nv = cols["radius_m"].size, cols["pair_superelevation_percent"].size, meta.get("vehicles")
    if n < 1 or type(nv) is not int or nv < 1:
        raise ColumnsError("the part has no curves or no vehicles")
    require(cols, _COLUMNS, n)
    require(cols, ("pair_grade_percent",), m)
    require(cols, ("pair_srt", "pair_error"), nv * m)
    ids = _ids(cols, n)
    errors = strings(meta.get("errors"), len(meta.get("errors") or []), "the part's reasons")
    codes_within(cols["pair_error"], -1, len(errors) - 1, "pair_error")
    pairs = cols["pair_superelevation_percent"] + 1j * cols["pair_grade_percent"]
    if m > 1 and not np.all(pairs[1:] > pairs[:-1]):  # complex numbers compare by real, then imaginary part
        raise ColumnsError("the part's pairs are not sorted and distinct")
    t = CurveTable(ids, *(cols[c] for c in _COLUMNS), bends=_bends(cols, n))
    return PartInput(t, pairs, cols["pair_srt"].reshape(nv, m), cols["pair_error"].reshape(nv, m), errors)


def _gather(inputs: PartInput, v: int):
    """A ``solve_pairs`` for :func:`engine.road.assess_alignment` that takes vehicle ``v``'s SRTs from the job's
    table (solved once, at submission; the same bits: a pair's SRT does not depend on its batch); a pair not in the
    table (none should be) is solved."""
    keys, srt_table, error_table = inputs.pairs, inputs.srt[v], inputs.error[v]

    def solve_pairs(case, pairs: np.ndarray) -> tuple[np.ndarray, dict[int, str]]:
        q = pairs[:, 0] + 1j * pairs[:, 1]
        at = np.minimum(np.searchsorted(keys, q), max(keys.size - 1, 0))
        hit = keys[at] == q if keys.size else np.zeros(q.size, dtype=bool)
        srt = np.where(hit, srt_table[at] if keys.size else np.nan, np.nan)
        codes = np.where(hit, error_table[at] if keys.size else -1, -1)
        errors = {int(i): inputs.errors[codes[i]] for i in np.flatnonzero(codes >= 0)}
        if not hit.all():
            miss = np.flatnonzero(~hit)
            solved, why = solve_bank_grade_pairs(case, pairs[miss], block_map=solvers.block_map)
            srt[miss] = solved
            errors |= {int(miss[j]): e for j, e in why.items()}
        return srt, errors

    return solve_pairs


def split(job: AlignmentJob, part_rows: int) -> Prepared:
    """The parts' inputs: their curves and the SRTs of their pairs, every distinct pair of the job solved here, once
    per vehicle, in one batch (the workers only gather)."""
    found = check_alignment(job)  # refuses now what the synchronous endpoint would refuse for the whole request
    r, t = job.resolved, job.curves
    pairs, inverse, distinct = found.pairs, found.inverse, found.distinct
    cases = [assessment_case(r, vehicle) for vehicle in job.vehicles]
    srt = np.empty((len(cases), len(pairs)))
    solved_errors: list[dict[int, str]] = []
    for v, case in enumerate(cases):
        srt[v], why = solve_bank_grade_pairs(case, pairs, block_map=solvers.block_map)
        solved_errors.append(why)
    errors = sorted({msg for why in solved_errors for msg in why.values()})
    code = {msg: k for k, msg in enumerate(errors)}
    error = np.full(srt.shape, -1, dtype=np.int32)
    for v, why in enumerate(solved_errors):
        for i, msg in why.items():
            error[v, i] = code[msg]
    nv, n = len(job.vehicles), len(t)
    per_part = max(1, part_rows // nv)
    parts, inputs = [], []
    for a in range(0, n, per_part):
        b = min(a + per_part, n)
        used = np.unique(inverse[a:b])
        parts.append((b - a) * nv)
        inputs.append(pack_input(t.sliced(a, b), pairs[used], srt[:, used], error[:, used], errors))
    shared = {
        "resolved": job.resolved.to_json_dict(),
        "source": job.source,
        "curves": n,
        "distinct_srt_solves": distinct,
        "chunk_curves": max(1, CHUNK_ROWS // nv),
        # each vehicle's level-road SRT, which its rows' targets are judged on (None: refused)
        "level_srt": [_finite_or_none(level_road_srt(case)) for case in cases],
    }
    etag = {"json": job.resolved.key("alignments"), "csv": job.resolved.key("alignments-csv")}
    return Prepared(shared, list(zip(parts, inputs, strict=True)), etag)


#: a part's result for one vehicle (:mod:`app.jobs.columns`): the curves' stations, the engine's
#: :class:`~engine.road.AlignmentColumns` (the reasons ``error`` indexes in the meta) and the curves' ids
RESULT_SCHEMA = {
    "station_m": "<f8",
    **_BEND_SCHEMA,
    "radius_m": "<f8",
    "superelevation_percent": "<f8",
    "superelevation_derived": "|b1",
    "grade_percent": "<f8",
    "posted_speed_kmh": "<f8",
    "srt_g": "<f8",
    "rollover_speed_kmh": "<f8",
    "side_friction_speed_kmh": "<f8",
    "side_friction": "<f8",
    "side_friction_clamped": "|b1",
    "safe_speed_kmh": "<f8",
    "governed_by": "|i1",
    "margin_kmh": "<f8",
    "flagged": "|b1",
    "standard_min_radius_m": "<f8",
    "meets_standard_min_radius": "|i1",
    "error": "<i4",
    **_ID_SCHEMA,
}
_ENGINE_COLUMNS = [
    name for name in RESULT_SCHEMA if name != "station_m" and name not in _ID_SCHEMA and name not in _BEND_SCHEMA
]


def _joined(chunks: list[AlignmentColumns]) -> AlignmentColumns:
    """The columns of consecutive slices of curves as one (the reasons of ``error`` merged and renumbered)."""
    if len(chunks) == 1:
        return chunks[0]
    errors = sorted({e for c in chunks for e in c.errors})
    code = {e: k for k, e in enumerate(errors)}
    error = np.concatenate([np.array([-1, *(code[e] for e in c.errors)], dtype=np.int64)[c.error + 1] for c in chunks])
    arrays = {name: np.concatenate([getattr(c, name) for c in chunks]) for name in _ENGINE_COLUMNS if name != "error"}
    return AlignmentColumns(**arrays, error=error, errors=errors, distinct_cases=chunks[0].distinct_cases)


def pack_result(curves: CurveTable, cols: AlignmentColumns) -> bytes:
    """One vehicle's result over a part's curves as columns (:data:`RESULT_SCHEMA`)."""
    arrays = {"station_m": curves.station_m, **_bend_columns(curves)}
    arrays |= {name: getattr(cols, name) for name in _ENGINE_COLUMNS}
    return pack_columns(arrays | _id_columns(curves), RESULT_SCHEMA, {"errors": cols.errors})


def unpack_result(data: bytes) -> tuple[CurveTable, AlignmentColumns]:
    """:func:`pack_result` read back and checked: every column of one length, codes within their tables (raises
    :class:`~app.jobs.columns.ColumnsError`, a ValueError)."""
    cols, meta = unpack_columns(data, RESULT_SCHEMA)
    n = cols["radius_m"].size
    require(cols, [name for name in RESULT_SCHEMA if name not in _ID_SCHEMA and name not in _BEND_SCHEMA], n)
    ids = _ids(cols, n)
    errors = strings(meta.get("errors"), len(meta.get("errors") or []), "the part's reasons")
    codes_within(cols["governed_by"], 0, len(GOVERNED_BY) - 1, "governed_by")
    codes_within(cols["meets_standard_min_radius"], -1, 1, "meets_standard_min_radius")
    codes_within(cols["error"], -1, len(errors) - 1, "error")
    nan = np.full(n, np.nan)
    curves = CurveTable(
        ids,
        cols["radius_m"],
        nan,
        cols["grade_percent"],
        cols["posted_speed_kmh"],
        cols["station_m"],
        bends=_bends(cols, n),
    )
    engine_cols = {name: cols[name] for name in _ENGINE_COLUMNS}
    engine_cols["governed_by"] = engine_cols["governed_by"].astype(np.intp)
    engine_cols["meets_standard_min_radius"] = engine_cols["meets_standard_min_radius"].astype(np.intp)
    engine_cols["error"] = engine_cols["error"].astype(np.intp)
    return curves, AlignmentColumns(**engine_cols, errors=errors, distinct_cases=0)


def _finite_or_none(x: float) -> float | None:
    return None if math.isnan(x) else float(x)


def _level(shared: dict[str, Any], v: int) -> float:
    """Vehicle ``v``'s level-road SRT from the job's shared state, checked (it comes from the job store)."""
    levels = shared.get("level_srt")
    if not isinstance(levels, list) or not 0 <= v < len(levels):
        raise ColumnsError("the job's state has no level-road SRT per vehicle (a job of an earlier version)")
    value = levels[v]
    if value is None:
        return math.nan
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value <= 0:
        raise ColumnsError(f"the job's level-road SRT of vehicle {v} is not a positive number: {value!r}")
    return float(value)


def _part_answer(
    resolved: ResolvedAlignment, v: int, data: bytes, level: float, advice: VehicleAdvice, start: int
) -> tuple[AlignmentAnswer, VehicleAnswer]:
    """A part's stored result of vehicle ``v`` as the answer the renderers take (what
    :func:`app.alignments.service.solve_alignment` builds for those curves), with its slice of the vehicle's advice
    (its curves start at curve ``start`` of the alignment)."""
    curves, cols = unpack_result(data)
    answer = vehicle_answer(resolved, v, cols, level, advice.sliced(start, start + len(curves)))
    return AlignmentAnswer(resolved, curves, [answer]), answer


def _advice(resolved: ResolvedAlignment, datas: Iterator[bytes]) -> VehicleAdvice:
    """A vehicle's advice over the whole alignment (the profile and the shared signs run across the parts) from its
    parts' stored results, in order: what :func:`app.alignments.service.solve_alignment` computes from the whole
    columns, so the rows are the synchronous answer's."""
    gathered: dict[str, list[np.ndarray]] = {name: [] for name in (*ADVICE_INPUTS, "start", "length", "deflection")}
    for data in datas:
        curves, cols = unpack_result(data)
        for name in ADVICE_INPUTS:
            gathered[name].append(getattr(cols, name))
        start, length, deflection = curve_places(curves)
        gathered["start"].append(start)
        gathered["length"].append(length)
        gathered["deflection"].append(np.full(len(curves), np.nan) if deflection is None else deflection)
    joined = {name: np.concatenate(arrays) for name, arrays in gathered.items()}
    deflection = joined.pop("deflection")
    start, length = joined.pop("start"), joined.pop("length")
    columns = SimpleNamespace(**joined)
    return advise(resolved, columns, start, length, None if np.isnan(deflection).all() else deflection)


def run_part(shared: dict[str, Any], data: bytes, ctx: PartContext) -> dict[str, Any]:
    """Solve the part's curves in chunks (a progress report, a cancellation point each) and keep, per vehicle, the
    result as columns (section = vehicle) and the summary of its curves; nothing is rendered here."""
    inputs = unpack_input(data)
    curves = inputs.curves
    resolved = ResolvedAlignment.from_json_dict(shared["resolved"])
    cases = [assessment_case(resolved, vehicle_of_resolved(v)) for v in resolved.vehicles]
    nv, n, step = len(cases), len(curves), shared["chunk_curves"]
    if inputs.srt.shape[0] != nv:
        raise ColumnsError(f"the part's SRTs are of {inputs.srt.shape[0]} vehicles, the job has {nv}")
    gather = [_gather(inputs, v) for v in range(nv)]
    chunks: list[list[AlignmentColumns]] = [[] for _ in range(nv)]
    for a in range(0, n, step):
        t = curves.sliced(a, min(a + step, n))
        for v, case in enumerate(cases):  # the pairs' SRTs gathered from the job's table
            chunks[v].append(assess_table(case, resolved, t, gather[v]))
        ctx.progress(min(a + step, n) * nv)
    summaries = []
    for v in range(nv):
        cols = _joined(chunks[v])
        chunks[v] = []
        summaries.append(summary(cols))
        ctx.write("columns", v, pack_result(curves, cols))
    return {"summaries": summaries}


def _rows(metas: list[dict[str, Any]], k: int, v: int, n: int) -> None:
    """Part ``k`` holds ``n`` rows of vehicle ``v``, as its summary says (raises ValueError)."""
    if n != metas[k]["summaries"][v]["curves"]:
        raise ValueError(f"part {k} holds {n} rows of vehicle {v}, its summary says otherwise")


def _rendered(
    resolved: ResolvedAlignment,
    v: int,
    data: bytes,
    fmt: str,
    columns: list[str],
    level: float,
    rows: Callable[[int], None],
    advice: VehicleAdvice,
    first: int,
) -> Iterator[bytes]:
    """A part's rows of vehicle ``v`` rendered (JSON objects separated by commas, or CSV lines), in chunks, once its
    columns have read back checked (``rows``: checks their number; ``first``: the alignment's index of its first
    curve, ``advice``: the vehicle's over the whole alignment)."""
    answer, va = _part_answer(resolved, v, data, level, advice, first)
    n = len(answer.curves)
    rows(n)
    for start in range(0, n, ROWS_PER_CHUNK):
        stop = min(start + ROWS_PER_CHUNK, n)
        if fmt == "csv":
            yield csv_rows(answer, va, start, stop, columns)
        else:
            yield json_rows(answer, va, start, stop, comma=start > 0)


#: the bytes of a fragment looked at by :func:`check` (its columns' header; more when the header is longer)
_HEAD_BYTES = 16 * 1024


def check(shared: dict[str, Any], metas: list[dict[str, Any]], fragments: Fragments, heads: FragmentHeads) -> None:
    """What would make the result unusable, found before it is answered (raises ValueError): the vehicles'
    level-road SRTs in the job's state; the first part read back whole and checked (its seal: a result sealed under
    another secret, as after a rotation, fails here; its columns and their number of rows); and every other part's
    layout and number of rows from its first bytes (a part of another version or layout). Every part is read back
    whole and checked again as it is streamed (:func:`assemble`): one that fails then (changed since) ends the
    stream and fails the job. Reading every part whole here too cost a fifth of the time to stream a
    1,000,000-row CSV result (bench/bench_jobs.py)."""
    nv = len(ResolvedAlignment.from_json_dict(shared["resolved"]).vehicles)
    for v in range(nv):
        _level(shared, v)
    for k in range(len(metas)):
        for v in range(nv):
            if k == 0:
                curves, _ = unpack_result(b"".join(fragments(k, v)))
                _rows(metas, k, v, len(curves))
                continue
            head = heads(k, v, _HEAD_BYTES)
            if (needed := header_length(head)) > len(head):
                head = heads(k, v, needed)
            lengths, _ = read_header(head, RESULT_SCHEMA)
            _rows(metas, k, v, lengths["radius_m"])


def _read_ahead(fragments: Fragments, order: list[tuple[int, int]]) -> Iterator[bytes]:
    """The fragments of ``order`` read whole (their seals verified), each next one read in a thread while the one
    before it renders: the read's copies and HMAC release the GIL, as the compiled row writer does, so on two cores
    they overlap."""

    def read(k: int, v: int) -> bytes:
        return b"".join(fragments(k, v))

    if not order:
        return
    with ThreadPoolExecutor(max_workers=1) as pool:
        pending = pool.submit(read, *order[0])
        for following in [*order[1:], None]:
            data = pending.result()
            pending = None if following is None else pool.submit(read, *following)
            yield data


def assemble(shared: dict[str, Any], metas: list[dict[str, Any]], fmt: str, fragments: Fragments) -> Iterator[bytes]:
    """The answer rendered from the parts' columns with the synchronous endpoint's renderers
    (:mod:`app.alignments.rows`): the same bytes."""
    resolved = ResolvedAlignment.from_json_dict(shared["resolved"])
    nv = len(resolved.vehicles)
    columns = csv_columns(resolved)

    # each vehicle's parts read twice: once for its advice over the whole alignment, once to render them
    nk = len(metas)
    order = [(k, v) for v in range(nv) for _ in range(2) for k in range(nk)]
    read = _read_ahead(fragments, order)
    firsts = np.concatenate(([0], np.cumsum([m["summaries"][0]["curves"] for m in metas]))).tolist() if nv else []

    def vehicle(v: int) -> tuple[VehicleAdvice, Callable[[int], Iterator[bytes]]]:  # called in ``order``
        advice = _advice(resolved, (next(read) for _ in range(nk)))

        def part(k: int) -> Iterator[bytes]:
            data = next(read)
            rows = functools.partial(_rows, metas, k, v)
            return _rendered(resolved, v, data, fmt, columns, _level(shared, v), rows, advice, firsts[k])

        return advice, part

    if fmt == "csv":
        yield csv_header(resolved)
        for v in range(nv):
            _, part = vehicle(v)
            for k in range(nk):
                yield from part(k)
        return
    yield json_head(resolved, shared["curves"])
    for v in range(nv):
        total = merge_summaries([m["summaries"][v] for m in metas], shared["distinct_srt_solves"])
        advice, part = vehicle(v)
        yield json_vehicle_head(resolved, v, total, first=v == 0)
        for k in range(nk):
            if k:
                yield b","
            yield from part(k)
        yield json_vehicle_end(advice)
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
    stored="columns",
    check=check,
    read_body=read_body,
)
