"""Accuracy of curve finding on synthetic routes laid on WGS84 (the table of docs/routes.md). Prints figures only.

Case classes: the noiseless mixed route of the tests (sharp, spiralled, flat and reverse curves) at 0/45/60/-35 deg
and 5/10/20 m spacing; noisy simple and spiralled curves inside the tests' class (circle-fit Cramér-Rao bound at
most 5 %/3) and some outside it; long noisy tangents (phantoms); grades. Noisy cases run over ``--seeds`` seeds.

    python bench/route_accuracy.py [--seeds 10]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tests.engine.test_geometry import LATITUDES, NOISY, ROUTE, ROUTE_CURVES, circle_crb, detect  # noqa: E402
from tests.synthetic_routes import Arc, Tangent, spiral_curve  # noqa: E402


def row(name: str, radius: str, chainage: str, other: str = "") -> None:
    print(f"| {name:<58} | {radius:>16} | {chainage:>14} | {other:<28} |")


def noiseless() -> None:
    errs, ends, spir, count = [], [], [], 0
    for lat in LATITUDES:
        for spacing in (5.0, 10.0, 20.0):
            found, _ = detect(ROUTE, spacing, lat)
            count += len(found.curves) != len(ROUTE_CURVES)
            for c, (r, _, start, end, ls, _, _) in zip(found.curves, ROUTE_CURVES, strict=False):
                errs.append(abs(c.radius_m / r - 1))
                ends.append(max(abs(c.start_m - start), abs(c.end_m - end)))
                if ls:
                    spir.append(max(abs(c.spiral_in_m - ls), abs(c.spiral_out_m - ls)))
    row(
        "no noise: R 60-2000, spirals, reverse; 4 lat x 5/10/20 m",
        f"{100 * max(errs):.3f} %",
        f"{max(ends):.1f} m",
        f"spiral {max(spir):.1f} m; wrong count {count}",
    )


def noisy(cases, seeds: int, label: str) -> None:
    for radius, length, direction, spacing, sigma, lat in cases:
        errs, ends, phantoms = [], [], 0
        for seed in range(seeds):
            route = [Tangent(700), Arc(radius, length, direction), Tangent(700)]
            found, _ = detect(route, spacing, lat, noise=sigma, seed=seed)
            phantoms += max(len(found.curves) - 1, 0)
            if not found.curves:
                errs.append(np.inf)
                continue
            c = max(found.curves, key=lambda c: c.deflection_deg)
            errs.append(abs(c.radius_m / radius - 1))
            ends.append(max(abs(c.start_m - 700), abs(c.end_m - 700 - length)))
        crb = circle_crb(radius, length, spacing, sigma) / radius
        row(
            f"{label} R {radius} L {length} h {spacing:g} s {sigma:g} (CRB {100 * crb:.1f} %)",
            f"{100 * max(errs):.1f} % (rms {100 * np.sqrt(np.mean(np.square(errs))):.1f})",
            f"{max(ends):.0f} m",
            f"phantoms {phantoms}/{seeds}",
        )


def spiral_noisy(seeds: int) -> None:
    errs, ends = [], []
    for seed in range(seeds):
        route = [Tangent(800), *spiral_curve(1500, 1000, 100, "right"), Tangent(800)]
        found, _ = detect(route, 10.0, 60.0, noise=3.0, seed=seed)
        c = found.curves[0]
        errs.append(abs(c.radius_m / 1500 - 1))
        ends.append(max(abs(c.start_m - 800), abs(c.end_m - 1900)))
    row("noisy spiralled R 1500 Lc 1000 Ls 100 h 10 s 3", f"{100 * max(errs):.1f} %", f"{max(ends):.0f} m")


def phantoms(seeds: int) -> None:
    n = 0
    for seed in range(seeds):
        for spacing, sigma in ((5.0, 3.0), (10.0, 3.0), (20.0, 2.0)):
            found, _ = detect([Tangent(10_000)], spacing, 45.0, noise=sigma, seed=100 + seed)
            n += len(found.curves)
    row(f"phantoms: {3 * seeds} noisy 10 km tangents (5/10/20 m, 2-3 m)", "", "", f"{n} curves found")


def grades(seeds: int) -> None:
    route = [Tangent(600), Arc(250, 300, "left"), Tangent(600)]
    worst = 0.0
    for seed in range(seeds):
        for noise in (0.0, 2.0):
            found, _ = detect(
                route, 5.0, 45.0, noise=noise, seed=seed, z_of_s=lambda s: 100 + 0.05 * s, z_noise=0.5 if noise else 0
            )
            worst = max(worst, abs(found.curves[0].grade_percent - 5.0))
    g1, g2, s0, length = -0.04, 0.04, 300.0, 800.0

    def sag(s):
        u = np.clip(s - s0, 0.0, length)
        return 200.0 + g1 * s + (g2 - g1) * u**2 / (2 * length)

    found, _ = detect([Tangent(600), Arc(250, 300, "right"), Tangent(600)], 5.0, 0.0, z_of_s=sag)
    vc = abs(found.curves[0].grade_percent - 100 * (g1 + (g2 - g1) * (750.0 - s0) / length))  # at the middle
    row("grades: 5 % straight (0/2 m noise, z 0.5 m); sag curve", "", "", f"{worst:.3f} / {vc:.3f} pp")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=10)
    seeds = ap.parse_args().seeds
    row("case class", "max |dR/R|", "max end error", "other")
    print(f"|{'-' * 60}|{'-' * 18}|{'-' * 16}|{'-' * 30}|")
    noiseless()
    noisy(NOISY, seeds, "noisy, in class:")
    spiral_noisy(seeds)
    outside = [(450, 400, "right", 10, 3.0, 45.0), (100, 200, "left", 10, 3.0, 45.0), (60, 120, "left", 10, 3.0, 0.0)]
    noisy(outside, seeds, "noisy, outside:")
    phantoms(seeds)
    grades(seeds)


if __name__ == "__main__":
    main()
