"""The combination in motion: timing of a whole PBS screening and of a lane change beside the static SRT, the
measures' convergence in the time step, and every preset's measures. Prints figures only (no assertions).

Run: ``python bench/bench_dynamics.py [--blas-threads N] [--repeat 30]``.

1. the times (min and median over ``--repeat`` runs, after one warm-up) of: the static SRT of the A-double
   (``rollover_threshold(Case(adouble))``, the whole-combination model), the assembly of its yaw-roll model, one
   single lane change (88 km/h, 0.4 Hz, 0.15 g; time step 0.02 s), a pulse steer, the low-speed turn, and a whole
   PBS screening (:func:`engine.dynamics.pbs.screen`: the model's assembly, the static SRT, the lane change, the
   pulse steer and the low-speed turn);
2. the lane change's RA, HSTO and peak LTR, the pulse steer's yaw damping and the low-speed turn's swept path at
   halved steps, so the default step's error can be read off;
3. every combination preset's measures.

``--blas-threads N`` sets ``OPENBLAS_NUM_THREADS`` (and ``OMP_NUM_THREADS``) before numpy loads: on a small,
loaded machine OpenBLAS's threads cost far more than they bring on these 20 x 20 matrices (compare the two runs).
The machine's load moves every figure: compare rows of one run, not of two.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ARGS = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ARGS.add_argument("--blas-threads", type=int, default=None)
ARGS.add_argument("--repeat", type=int, default=30)
OPTS = ARGS.parse_args()
if OPTS.blas_threads is not None:  # before numpy loads
    os.environ["OPENBLAS_NUM_THREADS"] = os.environ["OMP_NUM_THREADS"] = str(OPTS.blas_threads)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine import Case, rollover_threshold  # noqa: E402
from engine.dynamics import (  # noqa: E402
    build,
    lane_change,
    low_speed_turn,
    pulse_steer,
    screen,
    stability,
)
from engine.models import solve_combination  # noqa: E402
from engine.vehicle import COMBINATIONS  # noqa: E402


def timed(fn, repeat: int) -> tuple[float, float]:
    fn()
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return min(out) * 1e3, statistics.median(out) * 1e3


def main() -> None:
    c = COMBINATIONS["adouble"]
    n = OPTS.repeat
    print(f"BLAS threads: {os.environ.get('OPENBLAS_NUM_THREADS', 'library default')}; {n} runs each\n")
    model = build(c)
    srts = [u.srt for u in solve_combination(c).roll_coupled_units]
    rows = [
        ("static SRT, whole-combination model", lambda: rollover_threshold(Case(c))),
        ("yaw-roll model assembly", lambda: build(c)),
        ("lane change (88 km/h, 0.4 Hz, 0.15 g, dt 0.02 s)", lambda: lane_change(model, 88.0, srt_g=srts)),
        ("pulse steer (100 km/h, 20 s, dt 0.01 s)", lambda: pulse_steer(model, 100.0)),
        ("low-speed 90 degree turn (step 0.1 m)", lambda: low_speed_turn(model, path_every_m=5.0)),
        ("whole PBS screening (assembly included)", lambda: screen(build(c))),
    ]
    print("A-double                                         min [ms]  median [ms]")
    for name, fn in rows:
        lo, med = timed(fn, n)
        print(f"  {name:<46} {lo:8.2f}  {med:10.2f}")

    print("\nLane change against the time step (A-double, 88 km/h)")
    print("  dt [s]    RA         HSTO [m]   peak LTR (dolly+trailer2)  steer offset [m]")
    for dt in (0.04, 0.02, 0.01, 0.005, 0.0025):
        lc = lane_change(model, 88.0, dt=dt)
        ltr = lc.roll_coupled_units[-1]["peak_load_transfer_ratio"]
        print(f"  {dt:<8} {lc.rearward_amplification:.5f}   {lc.high_speed_transient_offtracking_m:.5f}    "
              f"{ltr:.5f}                    {lc.steer_axle_lateral_offset_m:.5f}")  # fmt: skip
    print("  (A/(2 pi f^2) = 1.46373 m)")
    print("\nPulse steer yaw damping against the time step (A-double, 100 km/h)")
    for dt in (0.02, 0.01, 0.005, 0.0025):
        print(f"  dt {dt:<7} {pulse_steer(model, 100.0, dt=dt).yaw_damping_ratio:.5f}")
    print("\nLow-speed swept path against the step (A-double)")
    for step in (0.4, 0.2, 0.1, 0.05, 0.025):
        ls = low_speed_turn(model, step_m=step, path_every_m=5.0)
        print(f"  step {step:<6} m  swept {ls.swept_path_width_m:.4f} m  tail {ls.tail_swing_m:.4f} m  "
              f"frontal {ls.frontal_swing_m:.4f} m")  # fmt: skip

    print("\nEvery preset (indicative screening)")
    print("  preset                        SRT [g]  RA     HSTO [m]  yaw damping  swept [m]  tail [m]  frontal [m]"
          "  sway/divergence [km/h]")  # fmt: skip
    for cid, comb in COMBINATIONS.items():
        m = build(comb)
        sc = screen(m)
        v = {s.id: (s.value if s.value is not None else float("nan")) for s in sc.standards}
        st = stability(m)
        print(f"  {cid:<29} {v['srt']:.3f}    {v['rearward_amplification']:.3f}  "
              f"{v['high_speed_transient_offtracking']:.3f}     {v['yaw_damping']:.3f}        "
              f"{v['low_speed_swept_path']:.3f}      {v['tail_swing']:.3f}     {v['frontal_swing']:.3f}        "
              f"{st.sway_critical_speed_kmh}/{st.divergence_speed_kmh}")  # fmt: skip


if __name__ == "__main__":
    main()
