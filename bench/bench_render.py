"""Rendering an alignment answer in process: JSON and CSV (app.alignments.rows.render, what the synchronous answer
and a job's result are written with) by the compiled row writer (app.formats._rowwriter) and by the Python writer
that stands in for it where it was not built, beside writers in C of the same rows measured in the same run:
orjson's JSON of the rows as dicts (the same bytes, the dicts made before the clock starts) and the csv
module's writer of the rows as lists (a reference: it writes booleans as True/False). The dicts and lists are made
before the clock starts.

A last line times what a writer built on orjson pays before it places a single separator: the row's 13 float cells
written by orjson as one array and split into rows, its rate given as the CSV answer's size over that time (the
ceiling of the Python writer's CSV; the compiled writer does not use orjson).

The curves are bench_jobs' synthetic ones (fixed seed), one vehicle (the Table 16 B-train, 3D model). Prints figures
only (best of --repeat runs).

    python bench/bench_render.py [--curves 100000] [--repeat 5]
"""

from __future__ import annotations

import argparse
import csv
import io
import sys
import time
from pathlib import Path

import numpy as np
import orjson

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from bench_jobs import curves_csv  # noqa: E402

from app.alignments.rows import csv_columns, render, rows  # noqa: E402
from app.alignments.schemas import MAX_JOB_CURVES, MAX_JOB_ROWS, AlignmentRequest  # noqa: E402
from app.alignments.service import resolve_alignment, solve_alignment  # noqa: E402
from app.formats import segments  # noqa: E402
from app.formats.tables import flatten_targets  # noqa: E402
from app.settings import Settings  # noqa: E402
from app.vehicles.resolve import resolve_request_given  # noqa: E402


def best(repeat: int, fn) -> tuple[float, int]:
    times, size = [], 0
    for _ in range(repeat):
        t0 = time.perf_counter()
        size = fn()
        times.append(time.perf_counter() - t0)
    return min(times), size


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--curves", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    req = AlignmentRequest.model_validate({"vehicle": "table16-btrain", "csv": curves_csv(args.curves)})
    # a job's size (the synchronous request stops at 10,000 curves): what a job's result is rendered at
    answer = solve_alignment(
        resolve_alignment(
            resolve_request_given(req), None, Settings(), max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS
        )
    )
    v = answer.vehicles[0]
    dicts = rows(answer, v, 0, len(answer.curves))
    columns = csv_columns(answer.resolved)
    lists = [[r.get(c) for c in columns] for r in map(flatten_targets, dicts)]

    def ours(fmt_csv: bool, compiled: bool = True):
        def run() -> int:
            saved = segments._rowwriter
            segments._rowwriter = saved if compiled else None
            try:
                return sum(map(len, render(answer, fmt_csv)))
            finally:
                segments._rowwriter = saved

        return run

    def c_csv() -> int:
        out = io.StringIO()
        csv.writer(out).writerows(lists)
        return len(out.getvalue())

    c = v.columns
    names = ["radius_m", "superelevation_percent", "grade_percent", "srt_g", "rollover_speed_kmh"]
    names += ["side_friction_speed_kmh", "side_friction", "safe_speed_kmh", "posted_speed_kmh", "margin_kmh"]
    names += ["standard_min_radius_m"]
    cells = [answer.curves.station_m, *(getattr(c, name) for name in names), v.tilt_deg[v.pair_of_row]]
    block = np.column_stack(cells)

    n = args.curves
    csv_secs, csv_size = best(args.repeat, ours(True))

    def floats_only() -> int:
        orjson.dumps(block, option=orjson.OPT_SERIALIZE_NUMPY)[2:-2].split(b"],[")
        return csv_size  # the rate is the CSV answer's size over this time

    compiled = "compiled writer" if segments._rowwriter is not None else "compiled writer NOT BUILT: Python"
    figures = [
        (f"JSON, app.alignments.rows, {compiled}", *best(args.repeat, ours(False))),
        ("JSON, app.alignments.rows, Python writer", *best(args.repeat, ours(False, compiled=False))),
        ("JSON, orjson.dumps of the row dicts (made beforehand)", *best(args.repeat, lambda: len(orjson.dumps(dicts)))),
        (f"CSV, app.alignments.rows, {compiled}", csv_secs, csv_size),
        ("CSV, app.alignments.rows, Python writer", *best(args.repeat, ours(True, compiled=False))),
        ("CSV, csv.writer of the row lists (reference)", *best(args.repeat, c_csv)),
        (f"CSV floor: orjson of the {block.shape[1]} float cells, split in rows", *best(args.repeat, floats_only)),
    ]
    print(f"{n:,} rows of one vehicle, best of {args.repeat}:")
    for name, secs, size in figures:
        print(f"  {name:60s} {size / 2**20:6.1f} MiB in {secs:.3f} s: {size / 2**20 / secs:5.0f} MiB/s, "
              f"{secs / n * 1e6:.2f} us a row")  # fmt: skip


if __name__ == "__main__":
    main()
