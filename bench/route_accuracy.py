"""Accuracy of curve finding on synthetic routes laid on WGS84 (the table of docs/routes.md). Prints figures only.

Case classes: the noiseless mixed route of the tests (sharp, spiralled, flat and reverse curves) at 0/45/60/-35 deg
and 5/10/20 m spacing; noisy simple and spiralled curves inside the tests' class (circle-fit Cramér-Rao bound at
most 5 %/3) and some outside it; long noisy tangents (phantoms); grades. Noisy cases run over ``--seeds`` seeds.

Then the calibration of the stated uncertainty (``radius_std_m``) and of the conservative radius (``radius_lower_m``):
simple curves between 400 m tangents (the arc's ends are found by the method, as on a real track), short (25 deg) and
long (90 deg) arcs of radius 60, 200 and 800 m, vertices every 10 m with 1, 2, 3 and 5 m of white GPS noise,
``--tracks`` tracks per cell. Per cell: the observed scatter (standard deviation of the relative radius error), the
mean stated standard error, their ratio (target: within a factor 1.5), the standard deviation of the normalised
error (error / stated standard error, 1 when calibrated), the share of tracks whose ``radius_lower_m`` is at most
the true radius (target: at least 95 %) and the median of ``radius_lower_m`` / true radius (what the conservatism
costs), then the pooled figures. ``--quick`` runs only this part on a few tracks.

    python bench/route_accuracy.py [--seeds 10] [--tracks 40] [--quick]
"""

from __future__ import annotations

import argparse
import math
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


#: calibration cells: radii [m], deflections [deg], noise [m]; vertices every 10 m, 400 m tangents on each side
CAL_RADII = (60.0, 200.0, 800.0)
CAL_DEFLECTIONS = (25.0, 90.0)
CAL_NOISE = (1.0, 2.0, 3.0, 5.0)
CAL_SPACING = 10.0
CAL_TANGENT = 400.0


def calibration_cell(radius: float, deflection_deg: float, sigma: float, tracks: int, seed0: int = 1000) -> dict:
    """Errors, stated standard errors and lower bounds of one cell's tracks (the curve of largest deflection)."""
    length = radius * math.radians(deflection_deg)
    route = [Tangent(CAL_TANGENT), Arc(radius, length, "left"), Tangent(CAL_TANGENT)]
    err, std, covered, lower, missed = [], [], [], [], 0
    for k in range(tracks):
        found, _ = detect(route, CAL_SPACING, 45.0, noise=sigma, seed=seed0 + k)
        if not found.curves:
            missed += 1
            continue
        c = max(found.curves, key=lambda c: c.deflection_deg)
        err.append(c.radius_m / radius - 1.0)
        std.append((c.radius_std_m or 0.0) / radius)
        covered.append(c.radius_lower_m <= radius)
        lower.append(c.radius_lower_m / radius)
    return {"err": np.array(err), "std": np.array(std), "covered": np.array(covered), "lower": np.array(lower),
            "missed": missed}  # fmt: skip


def calibration(tracks: int) -> None:
    print()
    print(f"Calibration: simple curves, h {CAL_SPACING:g} m, {tracks} tracks per cell, tangents {CAL_TANGENT:g} m")
    head = f"| {'R m':>5} | {'D deg':>5} | {'sigma m':>7} | {'found':>5} | {'bias %':>7} | {'observed %':>10} | "
    head += f"{'stated %':>8} | {'ratio':>5} | {'sd(z)':>5} | {'lower <= R':>10} | {'lower / R':>9} |"
    print(head)
    print("|" + "|".join("-" * (len(c)) for c in head.split("|")[1:-1]) + "|")
    ratios, zs, cover, n_found, n_all, within = [], [], [], 0, 0, 0
    for radius in CAL_RADII:
        for deflection in CAL_DEFLECTIONS:
            for sigma in CAL_NOISE:
                cell = calibration_cell(radius, deflection, sigma, tracks)
                e, s, cv = cell["err"], cell["std"], cell["covered"]
                n_all += tracks
                n_found += e.size
                if e.size < 3:
                    print(f"| {radius:>5.0f} | {deflection:>5.0f} | {sigma:>7.0f} | {e.size:>5} | (too few found)")
                    continue
                observed = float(np.std(e, ddof=1))
                stated = float(np.mean(s))
                ratio = stated / observed if observed > 0 else math.inf
                z = e / np.where(s > 0, s, np.nan)
                sd_z = float(np.nanstd(z, ddof=1))
                ratios.append(ratio)
                zs.append(z)
                cover.append(cv)
                within += 1 / 1.5 <= ratio <= 1.5
                print(
                    f"| {radius:>5.0f} | {deflection:>5.0f} | {sigma:>7.0f} | {e.size:>5} | {100 * e.mean():>+7.2f} | "
                    f"{100 * observed:>10.2f} | {100 * stated:>8.2f} | {ratio:>5.2f} | {sd_z:>5.2f} | "
                    f"{100 * cv.mean():>9.1f}% | {np.median(cell['lower']):>9.3f} |"
                )
    z_all = np.concatenate(zs)
    cv_all = np.concatenate(cover)
    print(
        f"Overall: {n_found}/{n_all} tracks with the curve found; ratio stated/observed median "
        f"{np.median(ratios):.2f}, "
        f"range {min(ratios):.2f}-{max(ratios):.2f}, {within}/{len(ratios)} cells within a factor 1.5; "
        f"sd of the normalised error {np.nanstd(z_all, ddof=1):.2f}; radius_lower_m <= true radius in "
        f"{100 * cv_all.mean():.1f} % of the tracks (worst cell {100 * min(c.mean() for c in cover):.1f} %)"
    )


#: spiralled curves (R, arc, spiral length, noise) [m]: the bound is taken on the simple curve the noise makes of them
SPIRALLED = ((250.0, 300.0, 60.0, 2.5), (150.0, 100.0, 80.0, 2.0), (600.0, 400.0, 100.0, 3.0))


def spiralled_coverage(tracks: int) -> None:
    """Share of spiralled curves (600 m tangents, 10 m spacing) whose radius_lower_m is at most the arc's radius."""
    for radius, arc, spiral, sigma in SPIRALLED:
        err, cov = [], []
        for k in range(tracks):
            route = [Tangent(600.0), *spiral_curve(radius, arc, spiral, "left"), Tangent(600.0)]
            found, _ = detect(route, CAL_SPACING, 45.0, noise=sigma, seed=2000 + k)
            if found.curves:
                c = max(found.curves, key=lambda c: c.deflection_deg)
                err.append(c.radius_m / radius - 1.0)
                cov.append(c.radius_lower_m <= radius)
        print(
            f"Spiralled R {radius:g} arc {arc:g} Ls {spiral:g} sigma {sigma:g}: {len(err)}/{tracks} found, "
            f"bias {100 * np.mean(err):+.1f} %, radius_lower_m <= R in {100 * np.mean(cov):.0f} %"
        )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--tracks", type=int, default=40, help="tracks per calibration cell")
    ap.add_argument("--quick", action="store_true", help="only the calibration, 8 tracks per cell")
    args = ap.parse_args()
    if args.quick:
        calibration(8)
        spiralled_coverage(4)
        return
    seeds = args.seeds
    row("case class", "max |dR/R|", "max end error", "other")
    print(f"|{'-' * 60}|{'-' * 18}|{'-' * 16}|{'-' * 30}|")
    noiseless()
    noisy(NOISY, seeds, "noisy, in class:")
    spiral_noisy(seeds)
    outside = [(450, 400, "right", 10, 3.0, 45.0), (100, 200, "left", 10, 3.0, 45.0), (60, 120, "left", 10, 3.0, 0.0)]
    noisy(outside, seeds, "noisy, outside:")
    phantoms(seeds)
    grades(seeds)
    calibration(args.tracks)
    spiralled_coverage(20)


if __name__ == "__main__":
    main()
