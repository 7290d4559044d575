"""An assessed alignment rendered: its rows as dicts, as JSON (byte for byte what pydantic would write for the
AlignmentResult, written column by column) and as CSV, in chunks of :data:`ROWS_PER_CHUNK` rows; and the vehicles'
summaries.

One renderer for every answer made of assessed curves: the synchronous alignment answer, an
``alignments.assess`` job's parts (:mod:`app.jobs.op_alignments`), and the route answer's rows
(:mod:`app.routes.service`: :func:`rows`, :func:`summary`, :func:`csv_columns`).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import orjson

from app.alignments.advice import VehicleAdvice, advisory_head, treatment_devices
from app.alignments.answer import AlignmentAnswer, VehicleAnswer
from app.formats.alignment_io import DIRECTIONS, FILE_SUPERELEVATION, GRADE_SOURCES, BendTable
from app.formats.segments import Codes, Floats, Segment, Slices, write_rows
from app.formats.tables import (
    FORMULA_PREFIXES,
    Text,
    csv_field,
    csv_fields,
    csv_line,
    target_columns,
    target_columns_of,
)
from app.formats.texts import Texts
from engine import ENGINE_VERSION
from engine.road import GOVERNED_BY, TREATMENTS, AlignmentColumns

if TYPE_CHECKING:
    from app.compute.resolved import ResolvedAlignment, ResolvedAssessment

#: rows written a call (a chunk of the stream): enough that the layout's setup (a few hundred microseconds) is
#: spread thin, small enough that a chunk stays in cache (bench/bench_jobs.py: 4,000 rows streamed a 1,000,000-row
#: CSV result in 1.07 s against 1.18 s with 1,000, and 16,000 gained 2 % more)
ROWS_PER_CHUNK = 4_000


ROW_COLUMNS = (
    "id",
    "station_m",
    "distance_m",
    "bend_start_m",
    "bend_end_m",
    "direction",
    "radius_m",
    "arc_length_m",
    "deflection_deg",
    "spiral_in_m",
    "spiral_out_m",
    "compound",
    "reverse",
    "superelevation_percent",
    "superelevation_source",
    "grade_percent",
    "grade_source",
    "grade_min_percent",
    "grade_max_percent",
    "srt_g",
    "level_road_srt",
    "tilt_table_angle_deg",
)


SPEED_COLUMNS = (
    "rollover_speed_kmh",
    "side_friction_speed_kmh",
    "side_friction",
    "side_friction_clamped",
    "safe_speed_kmh",
    "governed_by",
    "posted_speed_kmh",
    "margin_kmh",
    "flagged",
    "standard_min_radius_m",
    "meets_standard_min_radius",
    "error",
)

#: the advisory speed, treatment, W1-13 rule and speed profile figures of each row (:mod:`app.alignments.advice`)
ADVICE_COLUMNS = (
    "advisory_speed_kmh",
    "treatment_devices",
    "truck_rollover_warning",
    "approach_speed_kmh",
    "required_deceleration_mps2",
    "profile_reason",
)

#: a row's ``treatment.source`` and ``truck_rollover_warning.rule``: short, the full texts once in the answer's
#: ``advisory`` (per row they would double a large answer)
TREATMENT_ROW_SOURCE = "MUTCD 11e Table 2C-4, unverified (advisory.treatment_source)"
W1_13_ROW_RULE = "this service's, not a manual's (advisory.truck_rollover_warning_rule)"


def _opt(values: np.ndarray) -> list[float | None]:
    """The column as a list, None where it is nan (only those cells are looked at again: most columns have none)."""
    out = values.tolist()
    for i in np.flatnonzero(np.isnan(values)).tolist():
        out[i] = None
    return out


def rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> list[dict[str, Any]]:
    """Rows [start, stop) of one vehicle, as CurveRow dicts in the schema's field order (the route answer's
    assessments are these rows too)."""
    columns = _row_columns(answer, v, start, stop)
    names = list(columns)
    return [dict(zip(names, values, strict=True)) for values in zip(*columns.values(), strict=True)]


def _row_columns(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int) -> dict[str, list[Any]]:
    """Rows [start, stop) of one vehicle, column by column (CurveRow's fields in the schema's order)."""
    c, t, sl, a = v.columns, answer.curves, slice(start, stop), v.advice
    b = t.bend_columns.sliced(start, stop)

    def coded(codes: np.ndarray, values: Sequence[Any]) -> list[Any]:
        return [values[k] for k in codes.tolist()]

    return {
        "id": t.ids[sl],
        "station_m": _opt(t.station_m[sl]),
        "distance_m": _opt(b["distance_m"]),
        "bend_start_m": _opt(b["bend_start_m"]),
        "bend_end_m": _opt(b["bend_end_m"]),
        "direction": coded(_nan_codes(b["direction"]), _DIRECTION),
        "radius_m": c.radius_m[sl].tolist(),
        "arc_length_m": _opt(b["arc_length_m"]),
        "deflection_deg": _opt(b["deflection_deg"]),
        "spiral_in_m": _opt(b["spiral_in_m"]),
        "spiral_out_m": _opt(b["spiral_out_m"]),
        "compound": coded(_nan_codes(b["compound"]), _FLAG),
        "reverse": coded(_nan_codes(b["reverse"]), _FLAG),
        "superelevation_percent": c.superelevation_percent[sl].tolist(),
        "superelevation_source": coded(_e_source(c.superelevation_derived[sl], b), _SOURCE),
        "grade_percent": c.grade_percent[sl].tolist(),
        "grade_source": coded(b["grade_source"].astype(np.intp), GRADE_SOURCES),
        "grade_min_percent": _opt(b["grade_min_percent"]),
        "grade_max_percent": _opt(b["grade_max_percent"]),
        "srt_g": _opt(c.srt_g[sl]),
        "level_road_srt": [v.level] * (stop - start),
        "tilt_table_angle_deg": [v.tilt[p] for p in v.pair_of_row[sl].tolist()],
        "targets": [v.checks[p] for p in v.pair_of_row[sl].tolist()],
        "rollover_speed_kmh": _opt(c.rollover_speed_kmh[sl]),
        "side_friction_speed_kmh": c.side_friction_speed_kmh[sl].tolist(),
        "side_friction": c.side_friction[sl].tolist(),
        "side_friction_clamped": c.side_friction_clamped[sl].tolist(),
        "safe_speed_kmh": _opt(c.safe_speed_kmh[sl]),
        "governed_by": [GOVERNED_BY[g] for g in c.governed_by[sl].tolist()],
        "posted_speed_kmh": _opt(c.posted_speed_kmh[sl]),
        "margin_kmh": _opt(c.margin_kmh[sl]),
        "flagged": c.flagged[sl].tolist(),
        "standard_min_radius_m": _opt(c.standard_min_radius_m[sl]),
        "meets_standard_min_radius": [None if m < 0 else bool(m) for m in c.meets_standard_min_radius[sl].tolist()],
        "error": [None if k < 0 else c.errors[k] for k in c.error[sl].tolist()],
        "advisory_speed_kmh": _opt(a.advisory_speed_kmh[sl]),
        "treatment": [_TREATMENT_OUT[k + 1] for k in a.treatment[sl].tolist()],
        "truck_rollover_warning": [_WARNING_OUT[int(w)] for w in a.truck_rollover_warning[sl].tolist()],
        "approach_speed_kmh": _opt(a.approach_speed_kmh[sl]),
        "required_deceleration_mps2": _opt(a.required_deceleration_mps2[sl]),
        "profile_reason": [None if k < 0 else a.reasons[k] for k in a.reason[sl].tolist()],
    }


def flatten_advice(row: dict[str, Any]) -> dict[str, Any]:
    """A row of :func:`rows` with its advice as the CSV's cells (:data:`ADVICE_COLUMNS`): the treatment's devices
    joined by ``;`` (empty: none), the W1-13 recommendation as a boolean."""
    out = {k: v for k, v in row.items() if k not in ("treatment", "truck_rollover_warning")}
    out["treatment_devices"] = ";".join(row["treatment"]["devices"]) or None
    out["truck_rollover_warning"] = row["truck_rollover_warning"]["recommended"]
    return out


def summary(c: AlignmentColumns) -> dict[str, Any]:
    """A vehicle's summary over the curves of ``c`` (the ``summary`` of the answer)."""
    margins, safe = c.margin_kmh[~np.isnan(c.margin_kmh)], c.safe_speed_kmh[~np.isnan(c.safe_speed_kmh)]
    return {
        "curves": len(c),
        "flagged": int(c.flagged.sum()),
        "below_standard_min_radius": int((c.meets_standard_min_radius == 0).sum()),
        "refused": int((c.error >= 0).sum()),
        "distinct_srt_solves": c.distinct_cases,
        "governed_by_rollover": int((c.governed_by == 1).sum()),
        "governed_by_side_friction": int((c.governed_by == 2).sum()),
        "min_margin_kmh": float(margins.min()) if margins.size else None,
        "min_safe_speed_kmh": float(safe.min()) if safe.size else None,
    }


def merge_summaries(parts: list[dict[str, Any]], distinct_srt_solves: int) -> dict[str, Any]:
    """The summary of a vehicle over all the curves from the summaries of consecutive slices of them (a job's parts):
    counts add up, minimums are the smallest (None where a slice has none); the distinct SRT solves are those of the
    whole alignment (``distinct_srt_solves``, from :func:`check_alignment`), not the sum of the slices'."""
    out = dict(parts[0])
    for p in parts[1:]:
        for name, value in p.items():
            if name.startswith("min_"):
                known = [x for x in (out[name], value) if x is not None]
                out[name] = min(known) if known else None
            else:
                out[name] += value
    out["distinct_srt_solves"] = distinct_srt_solves
    return out


def default_model(vehicles: Sequence[dict[str, Any]]) -> str:
    """The model a request that names none is solved with: ``3d`` for records, ``combination`` for combinations,
    ``default`` for a mix of both (each vehicle with its own)."""
    kinds = {"combination" if "combination" in v else "3d" for v in vehicles}
    return kinds.pop() if len(kinds) == 1 else "default"


def json_head(resolved: ResolvedAlignment, curves: int) -> bytes:
    """The AlignmentResult document up to its ``vehicles`` list (opened)."""
    r = resolved
    model = r.model or default_model(r.vehicles)
    head = {
        "model": model,
        "stage": r.stage if model == "3d" else None,
        "design_standard": r.design_standard,
        "side_friction_bound": r.side_friction_bound,
        "max_superelevation_percent": r.max_superelevation_percent,
        "curves": curves,
        "csv_dialect": r.csv_dialect,  # in the key (resolve_alignment) only when the curves came as CSV
        "reading": r.reading,  # in the key only when the curves came from a road file
        "advisory": advisory_head(r),
    }
    return orjson.dumps(head)[:-1] + b',"vehicles":['


def json_vehicle_head(resolved: ResolvedAssessment, index: int, summary: dict[str, Any], *, first: bool) -> bytes:
    """One vehicle's entry up to its ``rows`` list (opened); closed by :func:`json_vehicle_end`."""
    vehicle = {
        "index": index,
        "preset": resolved.presets[index],
        "saved_vehicle_id": resolved.saved_ids[index],
        "warnings": resolved.vehicle_warnings(index),
        "summary": summary,
    }
    return (b"" if first else b",") + orjson.dumps(vehicle)[:-1] + b',"rows":['


def json_vehicle_end(a: VehicleAdvice) -> bytes:
    """Closes a vehicle's ``rows`` and entry with its ``speed_profile`` (a point per station, written a column at a
    time) and the profile's notes."""
    n = len(a.station_m)
    points = b""
    if n:
        f = _json_column
        layout = _json_layout([("station_m", f(a.station_m)), ("speed_kmh", f(a.speed_kmh))])
        points = write_rows(layout, n, drop=1)
    return b'],"speed_profile":[' + points + b'],"speed_profile_notes":' + orjson.dumps(a.notes) + b"}"


def _json_ids(ids: Sequence[str]) -> Segment | tuple[Segment, ...]:
    """Each id as a JSON string. Ids kept as one blob (:class:`Texts`, a job's part) that need no escape (no quote,
    backslash or control character: orjson escapes only those) are their slices between quotes; others, one
    ``orjson`` call cut at the ``","`` between two strings (inside a JSON string a quote is always escaped, so that
    sequence is only ever between two)."""
    if isinstance(ids, Texts):
        span = ids.span()
        if not ((span == 0x22) | (span == 0x5C) | (span < 0x20)).any():
            return _quoted(ids)
        ids = list(ids)
    return (b'"' + orjson.dumps(ids)[2:-2].replace(b'","', b'"\x01"') + b'"').split(b"\x01")


def _quoted(ids: Texts) -> tuple[Segment, ...]:
    """Each text of ``ids`` between double quotes, as it is in the blob."""
    return (b'"', Slices(ids.blob, ids.starts, ids.ends), b'"')


_FORMULA_BYTES = np.frombuffer("".join(FORMULA_PREFIXES).encode(), np.uint8)


def _csv_ids(ids: Sequence[str]) -> tuple[Segment, ...]:
    """Each id as its CSV field (:func:`app.formats.tables.csv_fields`: quoted, quotes doubled, a formula prefix
    neutralised). Ids kept as one blob (:class:`Texts`) with no quote and no formula prefix are their slices between
    quotes."""
    if isinstance(ids, Texts):
        span = ids.span()
        if not (span == 0x22).any() and not np.isin(ids.first_bytes(), _FORMULA_BYTES).any():
            return _quoted(ids)
        ids = list(ids)
    return (csv_fields(ids),)


_SOURCE = ("given", "derived", *FILE_SUPERELEVATION)  # by :func:`_e_source`
_DIRECTION = (None, *DIRECTIONS)  # by :func:`_nan_codes`
_FLAG = (None, False, True)  # by :func:`_nan_codes`


def _nan_codes(values: np.ndarray) -> np.ndarray:
    """A code column kept as floats (nan: none) as indices into a table whose first text is null."""
    return np.where(np.isnan(values), 0, np.nan_to_num(values) + 1).astype(np.intp)


def _e_source(derived: np.ndarray, b: BendTable) -> np.ndarray:
    """Each row's index into :data:`_SOURCE`: the file's (its superelevation or cross sections), else given or
    derived."""
    f = b["superelevation_from"]
    return np.where(np.isnan(f), derived.astype(np.intp), 2 + np.nan_to_num(f)).astype(np.intp)


_MEETS = (None, False, True)  # by meets_standard_min_radius + 1
#: a row's ``treatment`` by its code + 1 (code -1: no posted speed, no devices) and ``truck_rollover_warning``
_TREATMENT_OUT = [{"devices": treatment_devices(k), "source": TREATMENT_ROW_SOURCE} for k in range(-1, len(TREATMENTS))]
_WARNING_OUT = [{"recommended": w, "rule": W1_13_ROW_RULE} for w in (False, True)]
_TREATMENT_CSV = [";".join(treatment_devices(k)) or None for k in range(-1, len(TREATMENTS))]


def _json_layout(fields: list[tuple[str, Segment | tuple[Segment, ...]]]) -> list[Segment]:
    """An object per row: each field's key before its value (a segment, or a tuple of them), the row opened with
    ``,{`` (the comma before a row)."""
    out: list[Segment] = []
    for k, (name, value) in enumerate(fields):
        out += [
            (b",{" if k == 0 else b",") + orjson.dumps(name) + b":",
            *(value if isinstance(value, tuple) else [value]),
        ]
    return [*out, b"}"]


def _json_codes(codes: np.ndarray, values: Any) -> Codes:
    return Codes(codes, [orjson.dumps(x) for x in values])


def _json_column(values: np.ndarray) -> Floats:
    return Floats([values], json=True)


def json_rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int, *, comma: bool = False) -> bytes:
    """Rows [start, stop) of one vehicle as JSON objects separated by commas (no brackets; ``comma``: one before the
    first too, for a chunk that follows another): ``orjson.dumps`` of :func:`rows`, byte for byte (tested), written
    a column at a time (:mod:`app.formats.segments`): the texts, flags and the target checks (every row with an SRT
    is judged on the one level-road SRT) written once and gathered by code."""
    c, t, sl, a = v.columns, answer.curves, slice(start, stop), v.advice
    b = t.bend_columns.sliced(start, stop)
    pairs = v.pair_of_row[sl]
    judged = (v.srts[pairs] >= 0).astype(np.intp)
    f = _json_column
    fields: list[tuple[str, Segment | tuple[Segment, ...]]] = [
        ("id", _json_ids(t.ids[sl])),
        ("station_m", f(t.station_m[sl])),
        ("distance_m", f(b["distance_m"])),
        ("bend_start_m", f(b["bend_start_m"])),
        ("bend_end_m", f(b["bend_end_m"])),
        ("direction", _json_codes(_nan_codes(b["direction"]), _DIRECTION)),
        ("radius_m", f(c.radius_m[sl])),
        ("arc_length_m", f(b["arc_length_m"])),
        ("deflection_deg", f(b["deflection_deg"])),
        ("spiral_in_m", f(b["spiral_in_m"])),
        ("spiral_out_m", f(b["spiral_out_m"])),
        ("compound", _json_codes(_nan_codes(b["compound"]), _FLAG)),
        ("reverse", _json_codes(_nan_codes(b["reverse"]), _FLAG)),
        ("superelevation_percent", f(c.superelevation_percent[sl])),
        ("superelevation_source", _json_codes(_e_source(c.superelevation_derived[sl], b), _SOURCE)),
        ("grade_percent", f(c.grade_percent[sl])),
        ("grade_source", _json_codes(b["grade_source"].astype(np.intp), GRADE_SOURCES)),
        ("grade_min_percent", f(b["grade_min_percent"])),
        ("grade_max_percent", f(b["grade_max_percent"])),
        ("srt_g", f(c.srt_g[sl])),
        ("level_road_srt", orjson.dumps(v.level)),
        ("tilt_table_angle_deg", f(v.tilt_deg[pairs])),
        ("targets", Codes(judged, [b"[]", orjson.dumps(v.level_checks)])),
        ("rollover_speed_kmh", f(c.rollover_speed_kmh[sl])),
        ("side_friction_speed_kmh", f(c.side_friction_speed_kmh[sl])),
        ("side_friction", f(c.side_friction[sl])),
        ("side_friction_clamped", _json_codes(c.side_friction_clamped[sl].astype(np.intp), (False, True))),
        ("safe_speed_kmh", f(c.safe_speed_kmh[sl])),
        ("governed_by", _json_codes(c.governed_by[sl], GOVERNED_BY)),
        ("posted_speed_kmh", f(c.posted_speed_kmh[sl])),
        ("margin_kmh", f(c.margin_kmh[sl])),
        ("flagged", _json_codes(c.flagged[sl].astype(np.intp), (False, True))),
        ("standard_min_radius_m", f(c.standard_min_radius_m[sl])),
        ("meets_standard_min_radius", _json_codes(c.meets_standard_min_radius[sl] + 1, _MEETS)),
        ("error", _json_codes(c.error[sl] + 1, [None, *c.errors])),
        ("advisory_speed_kmh", f(a.advisory_speed_kmh[sl])),
        ("treatment", _json_codes(a.treatment[sl] + 1, _TREATMENT_OUT)),
        ("truck_rollover_warning", _json_codes(a.truck_rollover_warning[sl].astype(np.intp), _WARNING_OUT)),
        ("approach_speed_kmh", f(a.approach_speed_kmh[sl])),
        ("required_deceleration_mps2", f(a.required_deceleration_mps2[sl])),
        ("profile_reason", _json_codes(a.reason[sl] + 1, [None, *a.reasons])),
    ]
    return write_rows(_json_layout(fields), stop - start, drop=0 if comma else 1)


def json_tail() -> bytes:
    return b'],"engine_version":' + orjson.dumps(ENGINE_VERSION) + b"}"


def json_chunks(answer: AlignmentAnswer) -> Iterator[bytes]:
    """The AlignmentResult JSON document, in chunks of rows (byte for byte the document pydantic would write)."""
    yield json_head(answer.resolved, len(answer.curves))
    n = len(answer.curves)
    for k, v in enumerate(answer.vehicles):
        yield json_vehicle_head(answer.resolved, v.index, summary(v.columns), first=k == 0)
        for start in range(0, n, ROWS_PER_CHUNK):
            yield json_rows(answer, v, start, min(start + ROWS_PER_CHUNK, n), comma=start > 0)
        yield json_vehicle_end(v.advice)
    yield json_tail()


def target_names(resolved: ResolvedAssessment) -> list[str]:
    """The targets in the order of their CSV columns (by threshold, then name)."""
    return [n for n, _ in sorted(resolved.targets.items(), key=lambda kv: (kv[1], kv[0]))]


def csv_columns(resolved: ResolvedAssessment) -> list[str]:
    names = target_names(resolved)
    return [
        "vehicle_index",
        "vehicle_preset",
        "vehicle_saved_id",
        *ROW_COLUMNS,
        *target_columns(names),
        *SPEED_COLUMNS,
        *ADVICE_COLUMNS,
    ]


def csv_header(resolved: ResolvedAssessment) -> bytes:
    """The CSV answer's header row."""
    return csv_line(csv_columns(resolved))


def _csv_codes(codes: np.ndarray, values: Any) -> Codes:
    return Codes(codes, [csv_field(x) for x in values])


def _csv_checks(v: VehicleAnswer, names: list[str]) -> bytes:
    """The ``meets_<name>,margin_<name>_g`` fields of a row with an SRT, in the columns' order (empty where the level
    SRT has no check of that name: no level SRT), as :func:`app.formats.tables.target_columns_of` flattens them."""
    flat = target_columns_of([v.level_checks])
    return b",".join(csv_field(flat.get(column, [None])[0]) for column in target_columns(names))


def csv_rows(answer: AlignmentAnswer, v: VehicleAnswer, start: int, stop: int, columns: list[str]) -> bytes:
    """CSV lines of rows [start, stop) of one vehicle (``columns``: :func:`csv_columns`): the cells of :func:`rows`
    as :func:`app.formats.tables.csv_lines` writes them (tested), written a block of number columns at a time
    (:mod:`app.formats.segments`); the vehicle's fields, the level-road SRT and the target checks written once."""
    c, t, sl, a = v.columns, answer.curves, slice(start, stop), v.advice
    b = t.bend_columns.sliced(start, stop)
    f = Floats
    pairs = v.pair_of_row[sl]
    names = target_names(answer.resolved)
    vehicle = [v.index, None if v.preset is None else Text(v.preset), None if v.saved_id is None else Text(v.saved_id)]
    checks = _csv_checks(v, names)
    segments: list[Segment] = [
        b",".join(map(csv_field, vehicle)) + b",",
        *_csv_ids(t.ids[sl]),
        b",",
        f([t.station_m[sl], b["distance_m"], b["bend_start_m"], b["bend_end_m"]]),
        b",",
        _csv_codes(_nan_codes(b["direction"]), _DIRECTION),
        b",",
        f([c.radius_m[sl], b["arc_length_m"], b["deflection_deg"], b["spiral_in_m"], b["spiral_out_m"]]),
        b",",
        _csv_codes(_nan_codes(b["compound"]), _FLAG),
        b",",
        _csv_codes(_nan_codes(b["reverse"]), _FLAG),
        b",",
        f([c.superelevation_percent[sl]]),
        b",",
        _csv_codes(_e_source(c.superelevation_derived[sl], b), _SOURCE),
        b",",
        f([c.grade_percent[sl]]),
        b",",
        _csv_codes(b["grade_source"].astype(np.intp), GRADE_SOURCES),
        b",",
        f([b["grade_min_percent"], b["grade_max_percent"], c.srt_g[sl]]),
        b"," + csv_field(v.level) + b",",
        f([v.tilt_deg[pairs]]),
        Codes((v.srts[pairs] >= 0).astype(np.intp), [b"," * len(names) * 2, b"," + checks if names else b""]),
        b",",
        f([c.rollover_speed_kmh[sl], c.side_friction_speed_kmh[sl], c.side_friction[sl]]),
        b",",
        _csv_codes(c.side_friction_clamped[sl].astype(np.intp), (False, True)),
        b",",
        f([c.safe_speed_kmh[sl]]),
        b",",
        _csv_codes(c.governed_by[sl], GOVERNED_BY),
        b",",
        f([c.posted_speed_kmh[sl], c.margin_kmh[sl]]),
        b",",
        _csv_codes(c.flagged[sl].astype(np.intp), (False, True)),
        b",",
        f([c.standard_min_radius_m[sl]]),
        b",",
        _csv_codes(c.meets_standard_min_radius[sl] + 1, _MEETS),
        b",",
        _csv_codes(c.error[sl] + 1, [None, *c.errors]),
        b",",
        f([a.advisory_speed_kmh[sl]]),
        b",",
        _csv_codes(a.treatment[sl] + 1, _TREATMENT_CSV),
        b",",
        _csv_codes(a.truck_rollover_warning[sl].astype(np.intp), (False, True)),
        b",",
        f([a.approach_speed_kmh[sl], a.required_deceleration_mps2[sl]]),
        b",",
        _csv_codes(a.reason[sl] + 1, [None, *a.reasons]),
        b"\r\n",
    ]
    return write_rows(segments, stop - start)


def csv_chunks(answer: AlignmentAnswer) -> Iterator[bytes]:
    """One CSV table in chunks: a row per vehicle and curve, the vehicle's index and preset first."""
    columns = csv_columns(answer.resolved)
    yield csv_line(columns)
    n = len(answer.curves)
    for v in answer.vehicles:
        for start in range(0, n, ROWS_PER_CHUNK):
            yield csv_rows(answer, v, start, min(start + ROWS_PER_CHUNK, n), columns)


def render(answer: AlignmentAnswer, csv: bool) -> Iterator[bytes]:
    return csv_chunks(answer) if csv else json_chunks(answer)
