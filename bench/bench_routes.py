"""Wall time of curve finding on a long route: 500 km at 10 m vertex spacing (50,000 vertices).

The route alternates tangents of 200-1500 m with curves: radius log-uniform in 60-2000 m, deflection 10-90 deg,
a third of them with clothoid transitions (Ls = 0.3 sqrt(R) ... of order 20-130 m). It is laid on WGS84 at 45 deg N
(tests/synthetic_routes.py; needs the test extra's geographiclib) and timed through

* ``engine.route.find_curves`` on the plane coordinates, without noise, with 3 m of white GPS-like noise and with
  3 m of noise correlated over 50 m along the track (a receiver's drift: Gauss-Markov);
* ``engine.route.geodesy.local_frame`` + ``find_curves`` from longitude/latitude (the app's path);
* ``app.formats.route_io.read_geojson`` of the same route as a GeoJSON LineString (parsed dict).

Prints figures only (median of the repeats) and how the curves found compare with the design (found, missed, phantom,
the radius error of the long and of the short arcs, how often the lower radius bound holds the true radius);
``--write`` puts both tables in docs/routes.md ("Speed" and the accuracy on this route), between their markers.

    python bench/bench_routes.py [--km 500] [--spacing 10] [--repeat 3] [--write]
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.formats.route_io import read_geojson  # noqa: E402
from engine.route import find_curves, local_frame  # noqa: E402
from scripts.docblock import replace_block  # noqa: E402
from tests.synthetic_routes import Arc, Tangent, gauss_markov, layout, spiral_curve, to_lonlat  # noqa: E402

#: an arc at least this long is a "long" one in the accuracy table: ten vertices at 10 m [m]
LONG_ARC_M = 100.0


def design(km: float, seed: int = 3) -> list:
    rng = np.random.default_rng(seed)
    elements, total = [], 0.0
    while total < km * 1000:
        elements.append(Tangent(float(rng.uniform(200, 1500))))
        r = float(math.exp(rng.uniform(math.log(60), math.log(2000))))
        defl = math.radians(float(rng.uniform(10, 90)))
        side = "left" if rng.random() < 0.5 else "right"
        if rng.random() < 1 / 3:
            ls = 0.3 * math.sqrt(r) * 10
            arc = max(r * defl - ls, 20.0)
            elements.extend(spiral_curve(r, arc, ls, side))
        else:
            elements.append(Arc(r, r * defl, side))
        total = sum(e.length_m for e in elements)
    elements.append(Tangent(1000))
    return elements


def designed_curves(elements: list) -> list[tuple[float, float, float, float]]:
    """(start, end chainage, radius, arc length) of each designed curve: a run of non-tangent elements, its radius
    the sharpest arc's and its arc length that arc's [m]."""
    out, s, run = [], 0.0, None
    for el in elements:
        if isinstance(el, Tangent):
            if run is not None:
                out.append((run[0], s, run[1], run[2]))
                run = None
        elif isinstance(el, Arc):
            start = s if run is None else run[0]
            if run is None or el.radius_m < run[1]:
                run = (start, el.radius_m, el.length_m)
        elif run is None:  # a spiral opens the curve
            run = (s, math.inf, 0.0)
        s += el.length_m
    return out


def accuracy(curves: list[tuple[float, float, float, float]], s: np.ndarray, res) -> dict:
    """The curves found (``res``) against the designed ones (:func:`designed_curves`): each found curve is placed on
    the designed curve its vertices overlap most, by their design chainage ``s`` (not by its own chainage, which a
    noisy track stretches); one that overlaps none is a phantom."""
    starts, ends = np.array([c[0] for c in curves]), np.array([c[1] for c in curves])
    hits: dict[int, list] = {}
    phantoms = 0
    for c in res.curves:
        a, b = s[c.start_index], s[c.end_index]
        overlap = np.minimum(ends, b) - np.maximum(starts, a)
        k = int(np.argmax(overlap))
        if overlap[k] > 0:
            hits.setdefault(k, []).append(c)
        else:
            phantoms += 1
    errors: dict[str, list[float]] = {"long": [], "short": []}
    held = []
    for k, found in hits.items():
        _, _, radius, arc = curves[k]
        c = min(found, key=lambda f: f.radius_m)  # a curve found in pieces: its sharpest piece
        errors["long" if arc >= LONG_ARC_M else "short"].append(abs(c.radius_m - radius) / radius * 100)
        if arc >= LONG_ARC_M and c.radius_std_m is not None:  # None: no standard error, so no bound to judge
            held.append(c.radius_lower_m <= radius)
    return {
        "found": len(res.curves),
        "missed": len(curves) - len(hits),
        "split": sum(1 for f in hits.values() if len(f) > 1),
        "phantoms": phantoms,
        "errors": errors,
        "held": held,
        "length_error_m": res.length_m - s[-1],
    }


def _errors(values: list[float]) -> str:
    if not values:
        return "none"
    return f"{statistics.median(values):.2f} / {max(values):.1f} % ({len(values)})"


def accuracy_row(what: str, a: dict) -> str:
    held = f"{sum(a['held']) / len(a['held']) * 100:.0f} % of {len(a['held'])}" if a["held"] else "no bound (exact)"
    return (
        f"| {what} | {a['found']} | {a['missed']} | {a['split']} | {a['phantoms']} | {_errors(a['errors']['long'])} | "
        f"{_errors(a['errors']['short'])} | {held} | {a['length_error_m']:+.0f} m |"
    )


def timed(fn, repeat: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


DOC = ROOT / "docs" / "routes.md"
START, END = "<!-- bench_routes:start -->", "<!-- bench_routes:end -->"
ACCURACY_START, ACCURACY_END = "<!-- bench_routes_accuracy:start -->", "<!-- bench_routes_accuracy:end -->"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--km", type=float, default=500.0)
    ap.add_argument("--spacing", type=float, default=10.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--write", action="store_true", help="put this run's table in docs/routes.md (default size only)")
    args = ap.parse_args()
    if args.write and (args.km != 500.0 or args.spacing != 10.0):
        ap.error("--write records the default route: leave out --km and --spacing")
    load = os.getloadavg()[0]
    els = design(args.km)
    x, y, s = layout(els, args.spacing, ds=0.5)
    curves = designed_curves(els)
    rng = np.random.default_rng(1)
    xn, yn = x + rng.normal(0, 3.0, x.size), y + rng.normal(0, 3.0, y.size)
    # a receiver's drift: Gauss-Markov errors of 3 m correlated over 50 m along the track (docs/routes.md)
    rho = math.exp(-args.spacing / 50.0)
    xc, yc = x + gauss_markov(rng, x.size, 3.0, rho), y + gauss_markov(rng, y.size, 3.0, rho)
    lon, lat = to_lonlat(x, y, 45.0)
    geojson = {"type": "LineString", "coordinates": np.column_stack((lon, lat)).tolist()}
    route = f"{args.km:g} km at {args.spacing:g} m ({x.size - 1:,} segments, {len(curves)} designed curves)"
    print(f"route: {route}")
    rows: list[tuple[str, float, str]] = []
    accuracies: list[str] = []

    def judged(what: str, res) -> None:
        accuracies.append(accuracy_row(what, accuracy(curves, s, res)))
        print(accuracies[-1])

    def row(what: str, seconds: float, found: str) -> None:
        rows.append((what, seconds, found))
        print(f"{what:<52} {seconds * 1000:8.1f} ms  ({found})")

    t, res = timed(lambda: find_curves(x, y), args.repeat)
    row("find_curves, no noise", t, f"{len(res.curves)} curves")
    judged("no noise", res)
    t, res = timed(lambda: find_curves(xn, yn), args.repeat)
    row(
        "find_curves, 3 m white noise",
        t,
        f"{len(res.curves)} curves, sigma estimated {res.noise_m:.2f} m, detection scale "
        f"{res.detection_smoothing_m:.0f} m",
    )
    judged("3 m white noise", res)
    t, res = timed(lambda: find_curves(xc, yc), args.repeat)
    row(
        "find_curves, 3 m noise correlated over 50 m",
        t,
        f"{len(res.curves)} curves, sigma estimated {res.noise_m:.2f} m, correlation length {res.noise_corr_m:.0f} m",
    )
    judged("3 m noise correlated over 50 m", res)

    def from_lonlat():
        f = local_frame(lon, lat)
        return find_curves(f.x_m, f.y_m)

    t, res = timed(from_lonlat, args.repeat)
    row("local_frame + find_curves (lon/lat, no noise)", t, f"{len(res.curves)} curves")
    t, parts = timed(lambda: read_geojson(geojson), args.repeat)
    row("read_geojson (parsed dict)", t, f"{parts[0].lon_deg.size:,} vertices")
    if args.write:
        stamp = time.strftime("%Y-%m-%d", time.gmtime())
        table = [
            f"{route}, median of {args.repeat} runs each, run of {stamp} (`python bench/bench_routes.py --write`), "
            f"{os.cpu_count()} CPUs, load average {load:.1f} at the start.",
            "",
            "| step | wall time | found |",
            "| --- | --- | --- |",
            *(f"| {what} | {seconds:.2f} s | {found} |" for what, seconds, found in rows),
        ]
        long = sum(1 for c in curves if c[3] >= LONG_ARC_M)
        judged_table = [
            f"{route}, {long} of them with an arc of at least {LONG_ARC_M:g} m; run of {stamp} "
            "(`python bench/bench_routes.py --write`).",
            "",
            "| track | curves found | designed curves missed | found in pieces | phantoms | radius error, long arcs: "
            "median / max (curves) | radius error, shorter arcs | lower radius bound <= true radius, long arcs | "
            "route length error |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
            *accuracies,
        ]
        text = replace_block(DOC.read_text(encoding="utf-8"), START, END, "\n".join(table))
        DOC.write_text(replace_block(text, ACCURACY_START, ACCURACY_END, "\n".join(judged_table)), encoding="utf-8")
        print(f"wrote {DOC.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
