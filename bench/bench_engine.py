"""Engine benchmark: prints timings (no assertions). Run: ``python bench/bench_engine.py``.

Measures
--------
1. one 3D SRT solve (one stage, the chassis constant already calibrated), fast path: median and p95;
2. one full ``rollover_threshold`` call (both stages, with the calibration solves), fast path;
3. the same solve on the Davies reference path (full 6 x 22 cut-set system per iteration);
4. the Table 17 (4 x 7 x 12 = 336 cases) and Table 19 (9 x 7 x 5 = 315 cases) grids, 651 cases, by
   :func:`engine.models.threshold.sweep` (batched numpy fast path);
5. many one-threshold cases handed over together (:func:`engine.models.threshold.rollover_thresholds`, as the service's
   coalescer does) against the same cases one at a time;
6. where the time of one fast solve goes (per iteration: geometry, closures + limit, group statics).
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine import Case, Road
from engine.models import (
    BATCH_ROWS,
    MIN_ARRAY_CASES,
    evaluate_arrays,
    rollover_threshold,
    rollover_thresholds,
    stage_model,
    sweep,
    trailer3d,
    trailer3d_davies,
)
from engine.vehicle import PRESETS

BTRAIN = PRESETS["table16-btrain"]
TABLE17 = {
    "trailer_angle_deg": [0, 10, 20, 30],
    "bank_percent": [0, 2, 4, 6, 8, 10, 12],
    "slope_percent": [9, 8, 6, 4, 2, 0, -2, -4, -6, -8, -10, -12],
}
TABLE19 = {
    "lateral_offset_m": [-0.16, -0.12, -0.08, -0.04, 0, 0.04, 0.08, 0.12, 0.16],
    "longitudinal_offset_m": [-1.5, -1.0, -0.5, 0, 0.5, 1.0, 1.5],
    "vertical_offset_m": [-0.2, -0.1, 0, 0.1, 0.2],
}


def timeit(fn, repeat: int) -> list[float]:
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


def report(label: str, samples: list[float], unit: float = 1e3, suffix: str = "ms") -> None:
    s = sorted(samples)
    p95 = s[min(len(s) - 1, int(0.95 * len(s)))]
    print(
        f"{label:<58} median {statistics.median(s) * unit:8.3f} {suffix}   p95 {p95 * unit:8.3f} {suffix}"
        f"   (n={len(s)})"
    )


def main() -> None:
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs")
    m = stage_model(Case(BTRAIN), "full")
    case = trailer3d.SolverCase(
        weight=BTRAIN.weight_kn, bank=0.04, slope=-0.04, psi=0.17, d1=0.04, d2=0.0, d3=0.0, llt_limit=1.0
    )
    sol = trailer3d.solve(m, case)
    print(f"B-train SRT_3D on 4 % bank, 4 % downhill, 10 deg: {sol.ay:.4f} g in {sol.iterations} iterations")
    report("one 3D SRT solve, one stage, fast path", timeit(lambda: trailer3d.solve(m, case), 400))
    report("rollover_threshold(3d): both stages + calibrations", timeit(lambda: rollover_threshold(Case(BTRAIN)), 200))
    report(
        "rollover_threshold(3d, include_curves, 41 points)",
        timeit(lambda: rollover_threshold(Case(BTRAIN), include_curves=True), 20),
    )
    report(
        "rollover_threshold(2d), Table 14",
        timeit(lambda: rollover_threshold(Case(PRESETS["table14-semitrailer"], "2d")), 200),
    )
    report(
        "one 3D SRT solve, Davies reference path",
        timeit(lambda: trailer3d.solve(m, case, forces=trailer3d_davies.davies_forces_at), 5),
    )

    def grids():
        a = sweep(Case(BTRAIN, rear_llt_limit=0.6), TABLE17)
        b = sweep(Case(BTRAIN), TABLE19)
        return a, b

    a, b = grids()
    n = a.srt.size + b.srt.size
    print(f"grids: {a.srt.size} + {b.srt.size} = {n} cases, {len(a.errors) + len(b.errors)} refused")
    report(f"Tables 17 + 19 grids ({n} cases), sweep", timeit(grids, 15))

    # a large batch in blocks of BATCH_ROWS rows (the default) against one pass over every row: same bits, faster
    rng = np.random.default_rng(8)
    rows = 100_000
    arrays = {"bank_percent": rng.uniform(-8, 12, rows), "slope_percent": rng.uniform(-9, 9, rows)}
    blocks = timeit(lambda: evaluate_arrays(Case(BTRAIN), arrays), 2)
    one_pass = timeit(lambda: evaluate_arrays(Case(BTRAIN), arrays, batch_rows=rows), 2)
    report(f"{rows:,} distinct bank/grade cases, blocks of {BATCH_ROWS:,} rows (evaluate_arrays)", blocks, 1, "s")
    report(f"{rows:,} distinct bank/grade cases, one pass (ceiling to beat)", one_pass, 1, "s")
    # the same blocks on threads (app.compute.solvers: block_map=a pool's map): numpy lets go of the GIL, the same bits
    threads = max(1, min(4, len(os.sched_getaffinity(0))))
    with ThreadPoolExecutor(threads) as pool:
        on_threads = timeit(lambda: evaluate_arrays(Case(BTRAIN), arrays, block_map=pool.map), 2)
        same = evaluate_arrays(Case(BTRAIN), arrays, block_map=pool.map)[0].tobytes()
    assert same == evaluate_arrays(Case(BTRAIN), arrays)[0].tobytes(), "threaded blocks changed the bits"
    report(f"{rows:,} distinct bank/grade cases, the blocks on {threads} threads (block_map)", on_threads, 1, "s")

    # many one-threshold cases handed over together (app.compute.coalescer): on arrays from MIN_ARRAY_CASES cases of one
    # vehicle and stage, against the same cases one at a time (the ceiling to beat)
    print(f"many cases, rollover_thresholds (on arrays from {MIN_ARRAY_CASES} cases) against one at a time:")
    for k in (8, 16, 32, 64):
        cases = [Case(BTRAIN, road=Road(bank_percent=float(b))) for b in rng.uniform(-4, 10, k)]
        together = timeit(lambda cases=cases: rollover_thresholds(cases), 15)
        alone = timeit(lambda cases=cases: [rollover_threshold(c) for c in cases], 15)
        report(f"  {k} B-train cases, rollover_thresholds", together)
        report(f"  {k} B-train cases, one at a time", alone)

    # where the time of one fast solve goes
    state = sol.state
    geo = trailer3d.geometry(m, case, state.rear, state.front, state.theta27)
    cl = trailer3d.chassis_loads(m, case, geo, sol.ay, sol.loads.t28)
    from engine.models import group_statics

    per = {
        "geometry (Eqs. 4.2-4.19, 6.1-6.2)": lambda: trailer3d.geometry(
            m, case, state.rear, state.front, state.theta27
        ),
        "closures + limit (3 chassis evaluations, 2x2 solve)": lambda: trailer3d.solve_loads(m, case, geo),
        "group statics (both groups)": lambda: (
            group_statics(m.rear, geo.rear, *cl.rear_load),
            group_statics(m.front, geo.front, *cl.front_load),
        ),
        "whole iteration (forces_at + compliance laws)": lambda: trailer3d.next_state(
            m, case, *trailer3d.forces_at(m, case, state)[2:]
        ),
    }
    print(f"per iteration ({sol.iterations} iterations per solve):")
    for label, fn in per.items():
        report("  " + label, timeit(fn, 2000), unit=1e6, suffix="us")


if __name__ == "__main__":
    main()
