"""Accuracy of curve finding on synthetic routes laid on WGS84 (the tables of docs/routes.md). Prints figures.

Case classes: the noiseless mixed route of the tests (sharp, spiralled, flat and reverse curves) at 0/45/60/-35 deg
and 5/10/20 m spacing; noisy simple and spiralled curves inside the tests' class (circle-fit Cramér-Rao bound at
most 5 %/3) and some outside it; long noisy tangents (phantoms); grades. Noisy cases run over ``--seeds`` seeds.

Then the calibration of the stated uncertainty (``radius_std_m``) and of the conservative radius (``radius_lower_m``):
simple curves between 400 m tangents (the arc's ends are found by the method, as on a real track), short (25 deg) and
long (90 deg) arcs of radius 60, 200 and 800 m, and spiralled curves (clothoid-arc-clothoid: R 150 m with a 100 m arc
and 80 m spirals, R 250 / 300 / 60 m, R 600 / 400 / 100 m) between 600 m tangents, vertices every 10 m with 1, 2, 3
and 5 m of white GPS noise, ``--tracks`` tracks per cell. Per cell: the mean relative radius error (bias), the
observed scatter (its standard deviation), the mean stated standard error, their ratio (target: within a factor
1.5), the standard deviation of the normalised error (error / stated standard error, 1 when calibrated), the share
of tracks whose ``radius_lower_m`` is at most the true (arc's) radius (target: at least 95 %) and the median of
``radius_lower_m`` / true radius (what the conservatism costs), then the pooled figures of each kind.
Then the same figures for the simple cells at 2 and 3 m with the noise correlated along the track (Gauss-Markov,
each axis its own sequence, correlated over :data:`CORRELATED_M` = 50 m: tests/synthetic_routes.gauss_markov through
the tests' ``detect(corr_m=)``), which the stated uncertainty must also cover (engine/route/noise.py).
``--quick`` runs only the calibration on 8 tracks. ``--write`` stores the calibration's figures in
bench/route_calibration.json and puts the tables rendered from them (:func:`render_table`,
:func:`render_correlated`) in docs/routes.md between their markers; tests/engine/test_route_calibration_doc.py checks
that the doc is that rendering.

    python bench/route_accuracy.py [--seeds 10] [--tracks 40] [--quick] [--write]
    python bench/route_accuracy.py --correlated 100 [--tracks 40]   # only: the correlated cells at another length
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from scripts.docblock import replace_block  # noqa: E402
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
#: spiralled cells (R, arc, spiral length) [m] at the same noise, 600 m tangents: the bound is on the arc's radius
SPIRALLED = ((150.0, 100.0, 80.0), (250.0, 300.0, 60.0), (600.0, 400.0, 100.0))
SPIRAL_TANGENT = 600.0
#: the figures of the last ``--write`` run, from which the table of docs/routes.md is rendered
FIGURES = ROOT / "bench" / "route_calibration.json"
DOC = ROOT / "docs" / "routes.md"
START, END = "<!-- route_accuracy:start -->", "<!-- route_accuracy:end -->"
CORR_START, CORR_END = "<!-- route_accuracy_correlated:start -->", "<!-- route_accuracy_correlated:end -->"
#: the correlated cells: the simple curves at these noise levels, correlated over CORRELATED_M along the track
CORRELATED_M = 50.0
CORRELATED_NOISE = (2.0, 3.0)


def _white(route: list, sigma: float, seed: int):
    return detect(route, CAL_SPACING, 45.0, noise=sigma, seed=seed)[0]


def calibration_cell(route: list, radius: float, sigma: float, tracks: int, seed0: int, track=_white) -> dict:
    """Errors, stated standard errors and lower bounds of one cell's tracks (the curve of largest deflection);
    ``track(route, sigma, seed)`` finds the curves of one noisy track (white noise by default)."""
    err, std, covered, lower, missed = [], [], [], [], 0
    for k in range(tracks):
        found = track(route, sigma, seed0 + k)
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


def cell_figures(cell: dict, tracks: int) -> dict:
    """One cell's row: found, mean bias, observed scatter, mean stated error, their ratio, sd of the normalised
    error, coverage (share with radius_lower_m <= R) and the median of radius_lower_m / R; None where too few."""
    e, s, cv = cell["err"], cell["std"], cell["covered"]
    out = {"tracks": tracks, "found": int(e.size), "covered": int(cv.sum())}
    if e.size < 3:
        return out
    observed = float(np.std(e, ddof=1))
    stated = float(np.mean(s))
    z = e / np.where(s > 0, s, np.nan)
    out.update(
        bias=float(e.mean()),
        observed=observed,
        stated=stated,
        ratio=stated / observed if observed > 0 else math.inf,
        sd_z=float(np.nanstd(z, ddof=1)),
        coverage=float(cv.mean()),
        lower=float(np.median(cell["lower"])),
        z=[round(float(v), 4) for v in z if np.isfinite(v)],
    )
    return out


def correlated_cells(tracks: int, corr_m: float) -> list[dict]:
    """The simple cells at :data:`CORRELATED_NOISE` with the noise correlated over ``corr_m`` along the track."""

    def track(route: list, sigma: float, seed: int):
        return detect(route, CAL_SPACING, 45.0, noise=sigma, seed=seed, corr_m=corr_m)[0]

    cells = []
    for radius in CAL_RADII:
        for deflection in CAL_DEFLECTIONS:
            route = [Tangent(CAL_TANGENT), Arc(radius, radius * math.radians(deflection), "left"), Tangent(CAL_TANGENT)]
            for sigma in CORRELATED_NOISE:
                cell = calibration_cell(route, radius, sigma, tracks, 3000, track)
                key = {"kind": "correlated", "radius_m": radius, "deflection_deg": deflection, "sigma_m": sigma,
                       "corr_m": corr_m}  # fmt: skip
                cells.append(key | cell_figures(cell, tracks))
    return cells


def calibration(tracks: int) -> dict:
    """Every calibration cell, simple and spiralled, as stored in :data:`FIGURES` (the normalised errors kept for
    the pooled figures)."""
    cells = []
    for radius in CAL_RADII:
        for deflection in CAL_DEFLECTIONS:
            length = radius * math.radians(deflection)
            route = [Tangent(CAL_TANGENT), Arc(radius, length, "left"), Tangent(CAL_TANGENT)]
            for sigma in CAL_NOISE:
                cell = calibration_cell(route, radius, sigma, tracks, 1000)
                key = {"kind": "simple", "radius_m": radius, "deflection_deg": deflection, "sigma_m": sigma}
                cells.append(key | cell_figures(cell, tracks))
    for radius, arc, spiral in SPIRALLED:
        route = [Tangent(SPIRAL_TANGENT), *spiral_curve(radius, arc, spiral, "left"), Tangent(SPIRAL_TANGENT)]
        deflection = math.degrees((arc + spiral) / radius)
        for sigma in CAL_NOISE:
            cell = calibration_cell(route, radius, sigma, tracks, 2000)
            key = {"kind": "spiralled", "radius_m": radius, "arc_m": arc, "spiral_m": spiral,
                   "deflection_deg": round(deflection, 1), "sigma_m": sigma}  # fmt: skip
            cells.append(key | cell_figures(cell, tracks))
    return {"tracks": tracks, "spacing_m": CAL_SPACING, "cells": cells,
            "correlated": correlated_cells(tracks, CORRELATED_M)}  # fmt: skip


def _pooled(cells: list[dict]) -> str:
    rated = [c for c in cells if "ratio" in c]
    ratios = [c["ratio"] for c in rated]
    within = sum(1 / 1.5 <= r <= 1.5 for r in ratios)
    z = np.array([v for c in rated for v in c["z"]], dtype=float)
    found = sum(c["found"] for c in cells)
    covered = sum(c["covered"] for c in cells)
    worst = min(rated, key=lambda c: c["coverage"])
    return (
        f"{found}/{sum(c['tracks'] for c in cells)} tracks with the curve found; stated/observed median "
        f"{np.median(ratios):.2f} (range {min(ratios):.2f}-{max(ratios):.2f}), {within} of {len(rated)} cells within "
        f"a factor 1.5; sd of the normalised error {np.nanstd(z, ddof=1):.2f}; `radius_lower_m` at most the true "
        f"radius in {100 * covered / max(found, 1):.1f} % of the tracks (worst cell {100 * worst['coverage']:.1f} %)"
    )


def render_table(figures: dict) -> str:
    """The calibration block of docs/routes.md (between its markers) from a run's stored figures."""
    head = "| curve | R m | D deg | sigma m | found | bias % | observed % | stated % | ratio | sd(z) | lower <= R "
    head += "| lower / R |"
    lines = [f"{figures['tracks']} tracks per cell, vertices every {figures['spacing_m']:g} m, run of "
             f"{figures['date']} (`python bench/route_accuracy.py --write`).", "", head,
             "|" + "|".join("---" for _ in head.split("|")[1:-1]) + "|"]  # fmt: skip
    for c in figures["cells"]:
        curve = "simple" if c["kind"] == "simple" else f"arc {c['arc_m']:g}, Ls {c['spiral_m']:g}"
        lead = f"| {curve} | {c['radius_m']:g} | {c['deflection_deg']:g} | {c['sigma_m']:g} | {c['found']} |"
        lines.append(_cell_row(lead, c))
    simple = [c for c in figures["cells"] if c["kind"] == "simple"]
    spiralled = [c for c in figures["cells"] if c["kind"] == "spiralled"]
    lines += ["", f"Simple curves: {_pooled(simple)}.", "", f"Spiralled curves: {_pooled(spiralled)}."]
    return "\n".join(lines)


def _cell_row(lead: str, c: dict) -> str:
    """A cell's table row: its ``lead`` (the curve, the noise, how many found) and its figures, or that too few
    tracks had the curve found to give them."""
    if "ratio" not in c:
        return lead + " (too few found) | | | | | | |"
    return (
        f"{lead} {100 * c['bias']:+.2f} | {100 * c['observed']:.2f} | {100 * c['stated']:.2f} | {c['ratio']:.2f} | "
        f"{c['sd_z']:.2f} | {100 * c['coverage']:.1f} % | {c['lower']:.3f} |"
    )


def render_correlated(figures: dict) -> str:
    """The correlated block of docs/routes.md (between its markers) from a run's stored figures."""
    cells = figures["correlated"]
    head = (
        "| curve | R m | D deg | sigma m | L m | found | bias % | observed % | stated % | ratio | sd(z) | lower <= R "
    )
    head += "| lower / R |"
    lines = [f"{figures['tracks']} tracks per cell, vertices every {figures['spacing_m']:g} m, Gauss-Markov noise "
             f"correlated over L along the track, run of {figures['date']} (`python bench/route_accuracy.py "
             "--write`).", "", head, "|" + "|".join("---" for _ in head.split("|")[1:-1]) + "|"]  # fmt: skip
    for c in cells:
        lead = f"| simple | {c['radius_m']:g} | {c['deflection_deg']:g} | {c['sigma_m']:g} | {c['corr_m']:g} |"
        lead += f" {c['found']} |"
        lines.append(_cell_row(lead, c))
    lines += ["", f"Correlated noise: {_pooled(cells)}."]
    return "\n".join(lines)


def write_doc(text: str, correlated_text: str) -> None:
    """The rendered blocks into docs/routes.md, each between its markers."""
    doc = replace_block(DOC.read_text(encoding="utf-8"), START, END, text)
    DOC.write_text(replace_block(doc, CORR_START, CORR_END, correlated_text), encoding="utf-8")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--tracks", type=int, default=40, help="tracks per calibration cell")
    ap.add_argument("--quick", action="store_true", help="only the calibration, 8 tracks per cell")
    ap.add_argument(
        "--write", action="store_true", help=f"store the calibration in {FIGURES.name} and its table in docs/routes.md"
    )
    ap.add_argument(
        "--correlated", type=float, metavar="L", help="only: simple cells with the noise correlated over L metres"
    )
    args = ap.parse_args()
    if args.correlated:
        figures = {"tracks": args.tracks, "spacing_m": CAL_SPACING, "date": time.strftime("%Y-%m-%d", time.gmtime()),
                   "correlated": correlated_cells(args.tracks, args.correlated)}  # fmt: skip
        print(render_correlated(figures))
        return
    if args.write and args.quick:
        ap.error("--write records a whole calibration: leave out --quick")
    if not args.quick:
        seeds = args.seeds
        row("case class", "max |dR/R|", "max end error", "other")
        print(f"|{'-' * 60}|{'-' * 18}|{'-' * 16}|{'-' * 30}|")
        noiseless()
        noisy(NOISY, seeds, "noisy, in class:")
        spiral_noisy(seeds)
        outside = [
            (450, 400, "right", 10, 3.0, 45.0),
            (100, 200, "left", 10, 3.0, 45.0),
            (60, 120, "left", 10, 3.0, 0.0),
        ]
        noisy(outside, seeds, "noisy, outside:")
        phantoms(seeds)
        grades(seeds)
        print()
    figures = calibration(8 if args.quick else args.tracks)
    figures["date"] = time.strftime("%Y-%m-%d", time.gmtime())
    text, correlated_text = render_table(figures), render_correlated(figures)
    print(text)
    print()
    print(correlated_text)
    if args.write:
        FIGURES.write_text(json.dumps(figures, indent=1) + "\n", encoding="utf-8")
        write_doc(text, correlated_text)
        print(f"wrote {FIGURES.relative_to(ROOT)} and {DOC.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
