"""Wall time of a 10,000-curve alignment assessment: the engine alone, the app in process, a live uvicorn.

Curves: radii uniform in 40-800 m, superelevation 0-12 % and grade -8..8 % in steps of 0.5 % (so about 800 of
the 825 bank/grade pairs occur: that many SRT solves), posted speeds 40-110 km/h. Every "miss" request carries
new curve ids (a new cache key, the same engine work); a "hit" repeats the previous request. Prints figures only.

    python bench/bench_alignments.py [--curves 10000] [--repeat 5] [--no-live]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from engine import Case  # noqa: E402
from engine.road import Curve, assess_curves  # noqa: E402
from engine.vehicle import get_preset  # noqa: E402

BTRAIN = "table16-btrain"
PATH = "/v1/alignments/assess"


def make_curves(n: int, seed: int = 1) -> list[dict]:
    rng = np.random.default_rng(seed)
    return [
        {
            "id": f"C{i}",
            "radius_m": round(float(rng.uniform(40, 800)), 2),
            "superelevation_percent": float(rng.choice(np.arange(0, 12.01, 0.5))),
            "grade_percent": float(rng.choice(np.arange(-8, 8.01, 0.5))),
            "posted_speed_kmh": float(rng.choice(np.arange(40, 111, 10))),
        }
        for i in range(n)
    ]


def renamed(curves: list[dict], tag: str) -> list[dict]:
    return [{**c, "id": f"{c['id']}{tag}"} for c in curves]


def as_csv(curves: list[dict]) -> str:
    head = "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\n"
    return head + "".join(
        f"{c['id']},{c['radius_m']},{c['superelevation_percent']},{c['grade_percent']},{c['posted_speed_kmh']}\n"
        for c in curves
    )


def as_landxml(curves: list[dict]) -> str:
    items = "".join(
        f'<Curve rot="cw" radius="{c["radius_m"]}" length="50" staStart="{100 * k}" name="{c["id"]}"/>'
        for k, c in enumerate(curves)
    )
    return (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        f'<Alignments><Alignment name="A"><CoordGeom>{items}</CoordGeom></Alignment></Alignments></LandXML>'
    )


def timed(fn: Callable[[], object], repeat: int) -> tuple[float, float]:
    samples = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        samples.append(time.perf_counter() - t0)
    return statistics.median(samples), min(samples)


def report(name: str, median: float, best: float, note: str = "") -> None:
    print(f"{name:62s} {median * 1e3:9.1f} {best * 1e3:9.1f}  {note}")


def bench_engine(curves: list[dict], repeat: int) -> None:
    vehicle = get_preset(BTRAIN)
    objs = [Curve(c["id"], c["radius_m"], c["superelevation_percent"], c["grade_percent"], c["posted_speed_kmh"])
            for c in curves]  # fmt: skip
    result = assess_curves(Case(vehicle), objs)
    m, b = timed(lambda: assess_curves(Case(vehicle), objs), repeat)
    report("engine.assessment.assess_curves (3d, LLT 1)", m, b, f"{result.distinct_cases} SRT solves")


def bench_http(post: Callable[..., object], curves: list[dict], repeat: int, label: str) -> None:
    counter = iter(range(10**9))

    def fresh() -> str:
        return f"-{time.time_ns()}-{next(counter)}"

    def check(r, cache: str, kind: str = "application/json"):
        if r.status_code != 200 or r.headers.get("x-cache") != cache or kind not in r.headers["content-type"]:
            raise SystemExit(f"{label}: {r.status_code} X-Cache={r.headers.get('x-cache')} {r.text[:300]}")
        return r

    cases = {
        "JSON curves": lambda cs: {"json": {"vehicle": BTRAIN, "curves": cs}},
        "JSON with csv text": lambda cs: {"json": {"vehicle": BTRAIN, "csv": as_csv(cs)}},
        "raw text/csv upload (/assess/csv)": lambda cs: {
            "path": f"{PATH}/csv?vehicle={BTRAIN}",
            "content": as_csv(cs).encode(),
            "headers": {"Content-Type": "text/csv"},
        },
        "raw LandXML upload (/assess/landxml, e/grade/speed defaults)": lambda cs: {
            "path": f"{PATH}/landxml?vehicle={BTRAIN}&superelevation_percent=6&grade_percent=-2&posted_speed_kmh=80",
            "content": as_landxml(cs).encode(),
            "headers": {"Content-Type": "application/xml"},
        },
    }
    for name, make in cases.items():
        last: dict = {}

        def miss(make=make, last=last):
            kw = make(renamed(curves, fresh()))
            last.clear()
            last.update(kw)
            check(post(kw.pop("path", PATH), **kw), "miss")

        def hit(last=last):
            kw = dict(last)
            check(post(kw.pop("path", PATH), **kw), "hit")

        m, b = timed(miss, repeat)
        report(f"{label} {name}: miss", m, b)
        m, b = timed(hit, repeat)
        report(f"{label} {name}: hit", m, b)
    kw = {"json": {"vehicle": BTRAIN, "curves": renamed(curves, fresh())}}
    check(post(PATH, **kw), "miss")
    m, b = timed(lambda: check(post(PATH, **kw, headers={"Accept": "text/csv"}), "miss", "text/csv"), 1)
    report(f"{label} JSON curves, answer as CSV: miss", m, b, "rendered from the cached JSON answer")
    m, b = timed(lambda: check(post(PATH, **kw, headers={"Accept": "text/csv"}), "hit", "text/csv"), repeat)
    report(f"{label} JSON curves, answer as CSV: hit", m, b)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--curves", type=int, default=10_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--no-live", action="store_true", help="skip the live uvicorn run")
    args = parser.parse_args()
    curves = make_curves(args.curves)
    print(f"{args.curves} curves, B-train (table16-btrain), 3d model; wall time [ms] over {args.repeat} runs")
    print(f"{'case':62s} {'median':>9s} {'best':>9s}")
    bench_engine(curves, args.repeat)

    warnings.filterwarnings("ignore", message="Using `httpx` with `starlette.testclient`")
    import structlog
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.settings import Settings

    structlog.configure(logger_factory=structlog.ReturnLoggerFactory())
    with TestClient(create_app(Settings(cache_backend="memory"))) as client:
        bench_http(client.post, curves, args.repeat, "in-process")

    if args.no_live:
        return
    import httpx
    from bench_api import free_port, start_server

    port = free_port()
    env = {**os.environ, "ROLLOVER_CACHE_BACKEND": "memory"}
    proc = start_server(port, env)
    try:
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=120) as client:
            bench_http(client.post, curves, args.repeat, "uvicorn")
    finally:
        proc.terminate()
        proc.wait(timeout=10)


if __name__ == "__main__":
    main()
