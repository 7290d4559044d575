"""Vehicle builder: prints a worked example and timings (no assertions). Run: ``python bench/bench_builder.py``.

Prints
------
1. a tri-axle semi-trailer (illustrative inputs, not a published vehicle) built from measurable data: every
   record field with its method and explanation, the masses behind the CG and the notes;
2. its SRT, and the Table 16 B-train restated as a spec against the preset (the same record: equal SRTs);
3. the acceptable payload table for 0.35 g (TERNZ's results page), with SRT solves per limit;
4. timings: one build, one build + SRT, one payload table (median of repeats).

No published vehicle states enough data (masses, CG heights, tyre and suspension properties) to compare a built
vehicle with a measured SRT; see docs/vehicles.md, Sec. 7.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from engine import Case
from engine.builder import G_M_PER_S2, VehicleSpec, build_vehicle, payload_table
from engine.models import rollover_threshold
from engine.vehicle import PRESETS

EXAMPLE = {
    "unit_type": "semitrailer",
    "rear": {
        "axles": 3,
        "tyres_per_axle": 4,
        "track_m": 1.86,
        "centre_from_kingpin_m": 8.7,
        "axle_spacing_m": 1.31,
        "tyre": {"id": "thesis-michelin-xza", "size": "11R22.5"},
        "suspension": {"type": "thesis-steel-leaf"},
        "rated_load_kg": 22500,
    },
    "front": {"axles": 2, "tyres_per_axle": 4, "track_m": 1.86},
    "tare": {"mass_kg": 8000, "cg_height_m": 1.1, "cg_from_kingpin_m": 6.0},
    "deck": {"front_from_kingpin_m": -1.0, "length_m": 13.0},
    "payloads": [{"mass_kg": 26000, "deck_height_m": 1.4, "load_height_m": 4.0, "distribution": "uniform"}],
}

BTRAIN = {
    "unit_type": "btrain-rear",
    "rear": {
        "axles": 3,
        "tyres_per_axle": 4,
        "track_m": 1.86,
        "centre_from_kingpin_m": 4.26,
        "tyre": {"loaded_radius_m": 0.499, "stiffness_kn_per_m": 840.0},
        "suspension": {"stiffness_kn_per_m": 1800.0, "height_m": 0.205, "spring_separation_m": 0.95},
    },
    "front": {"axles": 2, "tyres_per_axle": 4, "track_m": 1.86, "centre_from_kingpin_m": 0.15},
    "tare": {"mass_kg": 355.22e3 / G_M_PER_S2, "cg_height_m": 0.499 + 0.205 + 1.356, "cg_from_kingpin_m": 3.0},
}


def median_ms(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1000 * statistics.median(times)


def main() -> None:
    spec = VehicleSpec.from_dict(EXAMPLE)
    built = build_vehicle(spec)
    print("1. record fields of the example semi-trailer")
    for d in built.derivation.values():
        value = "null" if d.value is None else f"{d.value:.6g}"
        print(f"   {d.field:42s} {value:>10s} {d.unit:11s} {d.method:9s} {d.explanation}")
    for m in built.masses:
        print(
            f"   mass {m.name:12s} {m.mass_kg:8.0f} kg at {m.cg_height_m:.3f} m high, "
            f"{m.cg_from_kingpin_m:.3f} m: {m.explanation}"
        )
    print(
        f"   composite: {built.gross_mass_kg:.0f} kg, CG {built.cg_height_m:.4f} m high, "
        f"{built.cg_from_kingpin_m:.4f} m behind the kingpin"
    )
    print(
        f"   static loads: kingpin {built.group_loads_kg['front']:.0f} kg, "
        f"rear group {built.group_loads_kg['rear']:.0f} kg"
    )
    for n in built.notes:
        print(f"   note: {n}")

    print("2. SRT")
    print(f"   example semi-trailer: {rollover_threshold(Case(built.vehicle, '3d')).srt:.4f} g")
    restated = build_vehicle(VehicleSpec.from_dict(BTRAIN)).vehicle
    preset = PRESETS["table16-btrain"]
    print(
        f"   Table 16 restated: {rollover_threshold(Case(restated, '3d')).srt:.6f} g; preset: "
        f"{rollover_threshold(Case(preset, '3d')).srt:.6f} g; records equal: {restated == preset}"
    )

    print("3. acceptable payload table, target 0.35 g")
    table = payload_table(spec, 0.35)
    print(f"   at the spec's own mass and load height: {table.srt_at_spec_g:.4f} g")
    for row in table.by_load_height:
        lim = row.limit
        value = "-" if lim.value is None else f"{lim.value:.0f} kg"
        print(
            f"   load height {row.load_height_m:.2f} m: largest payload {value:>9s} "
            f"({lim.status}, {lim.evaluations} solves)"
        )
    for row in table.by_payload_mass:
        lim = row.limit
        value = "-" if lim.value is None else f"{lim.value:.3f} m"
        print(
            f"   payload {row.payload_mass_kg:7.0f} kg: largest load height {value:>8s} "
            f"({lim.status}, {lim.evaluations} solves)"
        )

    print("4. timings (median)")
    print(f"   build: {median_ms(lambda: build_vehicle(spec), 200):.3f} ms")
    build_and_solve = lambda: rollover_threshold(Case(build_vehicle(spec).vehicle, "3d"))  # noqa: E731
    print(f"   build + SRT: {median_ms(build_and_solve, 50):.2f} ms")
    print(f"   payload table (5 + 5 rows): {median_ms(lambda: payload_table(spec, 0.35), 5):.0f} ms")


if __name__ == "__main__":
    main()
