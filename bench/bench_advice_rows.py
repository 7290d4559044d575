"""The advice's cost in an alignment assessment as the service runs it: :func:`app.alignments.service.solve_alignment`
(the engine's assessment, and since issue 43 the advisory speeds, treatment and speed profile of every vehicle) and
the JSON and CSV answers rendered (:func:`app.alignments.rows.render`), at n curves placed along a road (a road
file's stations, so the profile runs), one vehicle (the Table 16 B-train, 3D model). Prints figures only (best of
--repeat runs).

Run it in this tree and in a tree of the commit before the advice (``git archive <commit> | tar -x -C DIR``, the
compiled row writer copied beside) to compare: the issue's target is at most +20 % at 100,000 curves.

    python bench/bench_advice_rows.py [--curves 100000] [--repeat 3] [--continuous]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path.cwd()))

from app.alignments.rows import render
from app.alignments.schemas import MAX_JOB_CURVES, MAX_JOB_ROWS, AlignmentRequest
from app.alignments.service import resolve_alignment, solve_alignment
from app.formats.alignment_io import BendTable, CurveTable
from app.settings import Settings


def road(n: int, seed: int = 7, continuous: bool = False) -> CurveTable:
    """n curves along a road: radius 60-2,000 m, superelevation and grade in 0.5 % steps (``continuous``: unrounded,
    every pair distinct), posted 50-110 km/h, arcs 30-400 m with tangents 0-800 m between them
    (bench/bench_advisory.py's alignment)."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(60.0, 2000.0, n)
    e = rng.uniform(0.0, 8.0, n)
    grade = rng.uniform(-6.0, 6.0, n)
    if not continuous:
        e, grade = np.round(e * 2) / 2, np.round(grade * 2) / 2
    posted = rng.choice([50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0], n)
    length = rng.uniform(30.0, 400.0, n)
    start = np.cumsum(rng.uniform(0.0, 800.0, n) + np.concatenate(([0.0], length[:-1])))
    bends = BendTable.empty(n)
    bends.columns.update(
        distance_m=start - start[0],
        bend_start_m=start,
        bend_end_m=start + length,
        arc_length_m=length,
        deflection_deg=np.degrees(length / radius),
        direction=rng.integers(0, 2, n).astype(float),
    )
    ids = [f"C{i}" for i in range(n)]
    return CurveTable(ids, radius, e, grade, posted, start.copy(), bends=bends)


def best(repeat: int, fn) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--curves", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--continuous", action="store_true", help="every bank/grade pair distinct")
    args = ap.parse_args()
    table = road(args.curves, continuous=args.continuous)
    req = AlignmentRequest.model_validate({"vehicle": "table16-btrain", "curves": [{"id": "x", "radius_m": 100.0}]})
    job = resolve_alignment(req, table, Settings(), max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS)
    answer = solve_alignment(job)
    t_solve = best(args.repeat, lambda: solve_alignment(job))
    t_json = best(args.repeat, lambda: b"".join(render(answer, False)))
    t_csv = best(args.repeat, lambda: b"".join(render(answer, True)))
    size_json, size_csv = len(b"".join(render(answer, False))), len(b"".join(render(answer, True)))
    pairs = "every bank/grade pair distinct" if args.continuous else "bank and grade in 0.5 % steps"
    print(f"{args.curves:,} curves ({pairs}), one vehicle (best of {args.repeat})")
    print(f"  solve_alignment: {t_solve:.3f} s")
    print(f"  render JSON: {t_json:.3f} s ({size_json / 1e6:.1f} MB); solve + JSON: {t_solve + t_json:.3f} s")
    print(f"  render CSV: {t_csv:.3f} s ({size_csv / 1e6:.1f} MB); solve + CSV: {t_solve + t_csv:.3f} s")


if __name__ == "__main__":
    main()
