"""Whole-combination roll model benchmark and report: prints figures (no assertions).

Run: ``python bench/bench_combination.py``. Prints, for each combination preset:

1. the time of one whole-combination SRT (:func:`engine.models.combination.solve_combination`: every roll-coupled
   unit from rest to its limit) on a level road and on a 6 % and a 10 % bank, min and median over repeated solves
   and the min of a cold one (the vehicle's first solve: no regime of its elements cached yet), beside the time of one
   3D solve of the thesis's B-train trailer measured just before in the same run (the ceiling the issue sets is
   2 ms), and the ratio of the mins;
2. the time per curve of :func:`engine.models.evaluate_arrays` over 100,000 distinct random bank/grade pairs (bank
   -2..10 %, grade -8..8 %, on a 0.01 % grid: the 0.1 % grid holds only 19,481 distinct pairs) for each preset, beside
   the single unit's 3D batch (``table16-btrain``) over the same pairs in the same rounds (the issue's target: a
   combination over many curves as fast per curve as a single unit), min and median over the rounds, and, from one
   more pass after the rounds, how much of a combination's curve went to the factors and solves of its roll
   equations on their tree (:mod:`engine.models.roll_tree`, every row's in one column operation) and how many a
   curve needs;
3. each roll-coupled unit's SRT, what ended it, its lift-off sequence, and LLTf/LLTr of the last unit (for
   ``tractor-semitrailer-table15`` beside the 0.57 that the thesis's Ch. 8 reports from TruckSim), and on a 6 % and a
   10 % bank the SRT of the stepped solution beside the reference solution's
   (:mod:`engine.models.combination_reference`, a general nonlinear equilibrium).

``--quick``: 5,000 pairs, one round and fewer repeats. The machine's load moves every figure: compare a row with its
ceiling in the same run, not with another run's.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np

from engine import Case, get_preset, rollover_threshold
from engine.models import combination, evaluate_arrays, reference_srt, roll_tree, solve_combination
from engine.vehicle import COMBINATIONS


def timeit(fn, repeat: int) -> list[float]:
    fn()
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return out


def ms(times: list[float]) -> str:
    return f"min {min(times) * 1e3:6.3f} ms, median {statistics.median(times) * 1e3:6.3f} ms"


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
    rounds = 1 if quick else 3
    arrays = pairs(n)
    cases = {"table16-btrain (single unit, 3D batch)": Case(get_preset("table16-btrain"))}
    cases.update({cid: Case(c, model="combination") for cid, c in COMBINATIONS.items()})
    took: dict[str, list[float]] = {k: [] for k in cases}
    refused: dict[str, int] = {}
    for _ in range(rounds):  # the ceiling and every preset in each round: a load that comes and goes hits all
        for k, case in cases.items():
            t, refused[k] = per_curve(case, arrays)
            took[k].append(t)
    print(f"{n:,} distinct bank/grade pairs through evaluate_arrays, time per curve over {rounds} round(s):")
    single = min(next(iter(took.values())))
    for k, ts in took.items():
        ratio = "" if k.startswith("table16") else f"  ({min(ts) / single:4.2f} x the single unit)"
        print(f"  {k:40s} min {min(ts) * 1e6:6.1f} us, median {statistics.median(ts) * 1e6:6.1f} us{ratio}; "
              f"{refused[k]} refused")  # fmt: skip
    print("  of which in the factors and solves of the roll equations on their tree (one more pass, timed per call):")
    for k, case in cases.items():
        if not k.startswith("table16"):
            spent, factors, solves, total = tree_share(case, arrays)
            print(f"  {k:40s} {spent * 1e6:6.1f} us of {total * 1e6:6.1f} us, {factors:5.1f} factors and "
                  f"{solves:5.1f} solves per curve")  # fmt: skip
    print()


def tree_share(case: Case, arrays: dict[str, np.ndarray]) -> tuple[float, float, float, float]:
    """Seconds per curve spent in roll_tree's factor and solve during one evaluate_arrays call, the factors and
    solves per curve (a call on columns of m rows counts m), and the call's seconds per curve (the two functions
    wrapped for that pass only)."""
    spent, counts = 0.0, {"factor": 0, "solve": 0}
    real = {name: getattr(roll_tree, name) for name in counts}

    def timed(name):
        def call(*args):
            nonlocal spent
            t0 = time.perf_counter()
            try:
                return real[name](*args)
            finally:
                spent += time.perf_counter() - t0
                first = args[2][0] if name == "solve" else args[1][0]
                counts[name] += 1 if isinstance(first, float) else len(first)

        return call

    for name in counts:
        setattr(roll_tree, name, timed(name))
    try:
        total, _refused = per_curve(case, arrays)
    finally:
        for name, fn in real.items():
            setattr(roll_tree, name, fn)
    n = len(arrays["bank_percent"])
    return spent / n, counts["factor"] / n, counts["solve"] / n, total


def scalar_times(quick: bool) -> None:
    reps = 20 if quick else 200
    btrain = Case(get_preset("table16-btrain"))

    def cold(c, bank):  # the first solve of a vehicle: no regime of its elements built yet
        combination._shared_regimes.cache_clear()
        solve_combination(c, bank_percent=bank)

    print("One whole-combination SRT, beside one 3D solve of the Table 16 trailer (both stages) timed just before it")
    print("(cold: the first solve of the vehicle, before any of its regimes' pieces and tables is cached):")
    for cid, c in COMBINATIONS.items():
        for bank in (0.0, 6.0, 10.0):
            ceiling = timeit(lambda: rollover_threshold(btrain), reps // 2)
            t = timeit(lambda c=c, bank=bank: solve_combination(c, bank_percent=bank), reps)
            first = timeit(lambda c=c, bank=bank: cold(c, bank), reps // 4)
            ratio = min(t) / min(ceiling)
            print(f"  {cid:28s} bank {bank:4.1f} %: {ms(t)}, cold min {min(first) * 1e3:6.3f} ms  | 3D solve "
                  f"{ms(ceiling)}  ({ratio:4.2f} x)")  # fmt: skip
    print()


def main() -> None:
    quick = "--quick" in sys.argv[1:]
    scalar_times(quick)
    many_curves(quick)
    for cid, c in COMBINATIONS.items():
        print(f"{cid}:")
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
            print(f"  bank {bank:4.1f} %: stepped vs reference SRT {diff}")
        print()


if __name__ == "__main__":
    main()
