"""Whole-combination roll model benchmark and report: prints figures (no assertions).

Run: ``python bench/bench_combination.py``. Prints, for each combination preset:

1. the time of one whole-combination SRT (:func:`engine.models.combination.solve_combination`: every roll-coupled
   unit from rest to its limit), median and p95 over repeated solves, beside the time of one 3D solve of the thesis's
   B-train trailer in the same run (the ceiling the issue sets is 2 ms);
2. each roll-coupled unit's SRT, what ended it, its lift-off sequence, and LLTf/LLTr of the last unit (for
   ``tractor-semitrailer-table15`` beside the 0.57 that the thesis's Ch. 8 reports from TruckSim);
3. on a 6 % and a 10 % bank, the SRT of the stepped solution beside the reference solution's
   (:mod:`engine.models.combination_reference`, a general nonlinear equilibrium), and the time of the banked solve;
4. the time per curve of :func:`engine.models.evaluate_arrays` over 100,000 distinct random bank/grade pairs (bank
   -2..10 %, grade -8..8 %, on a 0.01 % grid: the 0.1 % grid holds only 19,481 distinct pairs) for each preset, beside
   the single unit's 3D batch (``table16-btrain``) over the same pairs in the same run (the issue's target: a
   combination over many curves as fast per curve as a single unit). ``--quick``: 5,000 pairs and fewer repeats.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np

from engine import Case, get_preset, rollover_threshold
from engine.models.combination import solve_combination
from engine.models.combination_reference import reference_srt
from engine.models.threshold import evaluate_arrays
from engine.vehicle.combination_presets import COMBINATIONS


def timeit(fn, repeat: int) -> list[float]:
    fn()
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


def ms(times: list[float]) -> str:
    times = sorted(times)
    return f"median {statistics.median(times) * 1e3:6.2f} ms, p95 {times[int(0.95 * (len(times) - 1))] * 1e3:6.2f} ms"


def pairs(n: int, seed: int = 0) -> dict[str, np.ndarray]:
    """n distinct (bank, grade) pairs, bank -2..10 %, grade -8..8 %, on a 0.01 % grid."""
    rng = np.random.default_rng(seed)
    banks, grades = 1201, 1601
    cells = rng.choice(banks * grades, size=n, replace=False)
    return {"bank_percent": -2.0 + (cells // grades) * 0.01, "slope_percent": -8.0 + (cells % grades) * 0.01}


def per_curve(case: Case, arrays: dict[str, np.ndarray]) -> tuple[float, int]:
    """Seconds per row of one evaluate_arrays call, and how many rows it refused."""
    t0 = time.perf_counter()
    _srt, _roll, errors = evaluate_arrays(case, arrays)
    return (time.perf_counter() - t0) / len(arrays["bank_percent"]), len(errors)


def many_curves(quick: bool) -> None:
    n = 5_000 if quick else 100_000
    arrays = pairs(n)
    single, bad = per_curve(Case(get_preset("table16-btrain")), arrays)
    print(f"{n:,} distinct bank/grade pairs through evaluate_arrays, time per curve:")
    print(f"  {'table16-btrain (single unit, 3D batch)':40s} {single * 1e6:7.1f} us  ({bad} refused)")
    for cid, c in COMBINATIONS.items():
        took, bad = per_curve(Case(c, model="combination"), arrays)
        print(f"  {cid:40s} {took * 1e6:7.1f} us  ({took / single:4.2f} x the single unit; {bad} refused)")
    print()


def main() -> None:
    quick = "--quick" in sys.argv[1:]
    reps = 10 if quick else 1
    btrain = Case(get_preset("table16-btrain"))
    print(
        "3D solve of the Table 16 trailer (both stages), for scale:",
        ms(timeit(lambda: rollover_threshold(btrain), 50 // reps)),
    )
    print()
    many_curves(quick)
    for cid, c in COMBINATIONS.items():
        print(f"{cid}: {ms(timeit(lambda c=c: solve_combination(c), 200 // reps))} per whole-combination SRT")
        detail = solve_combination(c)
        for r in detail.roll_coupled_units:
            lifts = ", ".join(f"{e.unit}/{e.group} {e.ay_g:.3f}" for e in r.lift_sequence)
            print(f"  {'+'.join(r.units):30s} SRT {r.srt:.4f} g  lift-offs: {lifts}")
            print(f"  {'':30s} {r.ended_by}")
        if detail.last_unit_front_llt_ratio is not None:
            extra = "  (thesis Ch. 8, TruckSim: 0.57)" if cid == "tractor-semitrailer-table15" else ""
            print(f"  LLTf/LLTr of the last unit: {detail.last_unit_front_llt_ratio:.3f}{extra}")
        for bank in (6.0, 10.0):
            model = [r.srt for r in solve_combination(c, bank_percent=bank).roll_coupled_units]
            exact = reference_srt(c, bank_percent=bank)
            diff = ", ".join(f"{m:.6f} vs {e:.6f}" for m, e in zip(model, exact, strict=True))
            took = ms(timeit(lambda c=c, bank=bank: solve_combination(c, bank_percent=bank), 50 // reps))
            print(f"  bank {bank:4.1f} %: stepped vs reference SRT {diff}; {took}")
        print()


if __name__ == "__main__":
    main()
