"""The advice's cost in an alignment assessment as the service runs it: :func:`app.alignments.service.solve_alignment`
(the engine's assessment, and since issue 43 the advisory speeds, treatment and speed profile of every vehicle) and
the JSON and CSV answers rendered (:func:`app.alignments.rows.render`), at n curves placed along a road (a road
file's stations, so the profile runs), one vehicle (the Table 16 B-train, 3D model). Prints figures only (best of
--repeat runs).

Run it in this tree and in a tree of the commit before the advice (``git archive <commit> | tar -x -C DIR``, the
compiled row writer copied beside) to compare: the issue's target is at most +20 % at 100,000 curves.

``--base COMMIT`` also times the advice alone beside the vehicle's assessment alone (``assess_table``), in the same
process and alternately, round by round: this tree's :func:`app.alignments.advice.advise` and COMMIT's (its
engine/road/profile.py, engine/road/advisory.py and app/alignments/advice.py read by ``git show``, the rest of this
tree), the two in turn first after the assessment, after a round not counted (the first calls after the first
assessment grow the heap: fresh pages in whichever runs first), and checks that the two give the same arrays;
beside each time, the minor page faults a call (fresh pages the kernel maps and zeroes on first touch: at 100,000
curves every new whole-road array is such pages, which cost more than the arithmetic on them).

    python bench/bench_advice_rows.py [--curves 100000] [--repeat 3] [--continuous] [--base COMMIT]
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import time
import types
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path.cwd()))

from app.alignments.advice import advise
from app.alignments.rows import render
from app.alignments.schemas import MAX_JOB_CURVES, MAX_JOB_ROWS, AlignmentRequest
from app.alignments.service import assess_table, assessment_case, resolve_alignment, solve_alignment
from app.formats.alignment_io import BendTable, CurveTable
from app.settings import Settings
from app.vehicles.resolve import resolve_request_given


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


def base_advise(commit: str):
    """COMMIT's :func:`app.alignments.advice.advise`: its advice modules (profile, advisory, the app's columns) run
    from their text at COMMIT, each bound to the one before (the rest of the code is this tree's)."""

    def load(name: str, path: str, **bound):
        text = subprocess.run(["git", "show", f"{commit}:{path}"], capture_output=True, text=True, check=True).stdout
        module = types.ModuleType(name)
        module.__file__ = f"{commit}:{path}"
        sys.modules[name] = module  # (dataclasses look their module up)
        exec(compile(text, module.__file__, "exec"), module.__dict__)
        module.__dict__.update(bound)  # its imports of the modules before, replaced by COMMIT's
        return module

    profile = load("base_profile", "engine/road/profile.py")
    advisory = load("base_advisory", "engine/road/advisory.py", prof=profile)
    return load("base_advice", "app/alignments/advice.py", advise_alignment=advisory.advise_alignment).advise


def same_advice(a, b) -> bool:
    """Two VehicleAdvice's arrays equal byte for byte, their lists equal."""
    for name in a.__dataclass_fields__:
        x, y = getattr(a, name), getattr(b, name)
        if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
            if x is None or y is None or x.dtype != y.dtype or x.shape != y.shape or x.tobytes() != y.tobytes():
                return False
        elif x != y:
            return False
    return True


def paired(job, base: str, repeat: int) -> None:
    """The advice alone beside the assessment alone, this tree's and ``base``'s, alternately (best of ``repeat``)."""
    r = job.resolved
    case = assessment_case(r, job.vehicles[0])
    cols = assess_table(case, r, job.curves, None)
    places = job.curve_places()
    old = base_advise(base)
    same = same_advice(advise(r, cols, *places), old(r, cols, *places))
    stages = {
        "assessment (assess_table)": lambda: assess_table(case, r, job.curves, None),
        "advice, this tree": lambda: advise(r, cols, *places),
        f"advice, {base}": lambda: old(r, cols, *places),
    }
    times = {k: [] for k in stages}
    faults = dict.fromkeys(stages, 0)  # the process's minor page faults: fresh pages touched (mapped and zeroed)
    names = list(stages)
    for fn in stages.values():  # a round not counted: the first calls after the first assessment grow the heap (an
        fn()  # A/A run showed ~1,800 page faults in whichever advice ran first, ~200 a call averaged over 9 rounds)
    for i in range(repeat):
        # the two advices in turn first after the assessment, round by round: the first one after it takes the
        # pages the assessment handed back (fresh pages), whichever tree it is
        for k in names if i % 2 == 0 else [names[0], names[2], names[1]]:
            fn = stages[k]
            f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
            t0 = time.perf_counter()
            fn()
            times[k].append(time.perf_counter() - t0)
            faults[k] += resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    t = {k: min(v) for k, v in times.items()}
    assess = t["assessment (assess_table)"]
    print(f"  advice alone beside the assessment alone (alternately, best of {repeat}; minor page faults a call):")
    for k, v in t.items():
        added = "" if v is assess else f" ({100.0 * v / assess:+.0f} % of the assessment)"
        print(f"    {k}: {1e3 * v:.1f} ms{added}; {faults[k] / repeat:,.0f} page faults")
    print(f"    the two advices' arrays identical: {same}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--curves", type=int, default=100_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--continuous", action="store_true", help="every bank/grade pair distinct")
    ap.add_argument("--base", help="a commit whose advice to time beside this tree's (git show)")
    args = ap.parse_args()
    table = road(args.curves, continuous=args.continuous)
    req = AlignmentRequest.model_validate({"vehicle": "table16-btrain", "curves": [{"id": "x", "radius_m": 100.0}]})
    settings = Settings()
    vr = resolve_request_given(req)
    job = resolve_alignment(vr, table, settings, max_curves=MAX_JOB_CURVES, max_rows=MAX_JOB_ROWS)
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
    if args.base:
        paired(job, args.base, max(args.repeat, 7))


if __name__ == "__main__":
    main()
