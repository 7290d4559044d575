"""Advisory speeds and the truck's speed profile beside an alignment assessment: prints timings (no assertions).
Run: ``python bench/bench_advisory.py [n_curves]`` (default 100,000).

Measures, on one alignment of n curves (radius 60-2,000 m, superelevation 0-8 %, grade -6..6 %, both in 0.5 % steps
and then unrounded, posted 50-110 km/h, curves 30-400 m long with tangents 0-800 m between them), for the B-train:

1. :func:`engine.road.curves.assess_alignment` (the SRT of every distinct bank/grade pair, Eq. 9.1 against side
   friction);
2. :func:`engine.road.advisory.advise_alignment` on its columns (every method's speed, the plaque's rounding, the
   shared signs, the treatment, the W1-13 rule and the speed profile);
3. the ratio 2 / 1 (the issue's target: at most +20 %).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine import Case
from engine.road import advise_alignment, assess_alignment
from engine.vehicle import PRESETS


def alignment(n: int, seed: int = 7, step: float = 0.5):
    """n curves; superelevation and grade rounded to ``step`` percent (0: not rounded, every pair distinct)."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(60.0, 2000.0, n)
    e = rng.uniform(0.0, 8.0, n)
    grade = rng.uniform(-6.0, 6.0, n)
    if step:
        e, grade = np.round(e / step) * step, np.round(grade / step) * step
    posted = rng.choice([50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0], n)
    length = rng.uniform(30.0, 400.0, n)
    gaps = rng.uniform(0.0, 800.0, n)
    start = np.cumsum(gaps + np.concatenate(([0.0], length[:-1])))
    return radius, e, grade, posted, start, length


def best_time(fn, repeat: int) -> tuple[float, object]:
    """The fastest of ``repeat`` runs (the machine is shared: the minimum is the least disturbed) and the result."""
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    case = Case(PRESETS["table16-btrain"], "3d")
    for label, step in (("coarse (e and grade in 0.5 % steps)", 0.5), ("continuous (every pair distinct)", 0.0)):
        radius, e, grade, posted, start, length = alignment(n, step=step)
        t_assess, cols = best_time(lambda: assess_alignment(case, radius, e, grade, posted), 3)  # noqa: B023
        t_advise, advice = best_time(lambda: advise_alignment(cols, start, length), 7)  # noqa: B023
        warned = int(advice.advisory.truck_rollover_warning.sum())
        print(f"{label}: {n:,} curves, {cols.distinct_cases:,} distinct bank/grade pairs")
        print(f"  assess_alignment: {t_assess:.3f} s (best of 3)")
        print(f"  advise_alignment (advisory + treatment + W1-13 + profile): {t_advise:.3f} s (best of 7)")
        print(f"  ratio: +{100 * t_advise / t_assess:.1f} % of the assessment")
        print(f"  profile points: {advice.profile.station_m.size:,}; W1-13 recommended on {warned:,} curves")


if __name__ == "__main__":
    main()
