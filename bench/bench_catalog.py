"""Latency of the catalog (saved vehicles) against a live uvicorn, on SQLite and optionally PostgreSQL (prints
figures only).

Starts `uvicorn app.main:app` on a free port with a key and a fresh database, then over one keep-alive
connection: `--n` POSTs of the Table 16 record, as many GETs, PUTs (If-Match) and listing pages of 50, and prints
median and p95 wall time as the client sees it. SQLite runs with synchronous=FULL (an fsync per commit).

    python bench/bench_catalog.py [--n 200] [--postgres postgresql+psycopg://postgres@127.0.0.1:5432/bench]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_api import free_port, start_server

KEY = "bench-key-" + "b" * 24
AUTH = {"Authorization": f"Bearer {KEY}"}


def timed(client: httpx.Client, method: str, path: str, **kwargs) -> tuple[float, httpx.Response]:
    t = time.perf_counter()
    r = client.request(method, path, **kwargs)
    return (time.perf_counter() - t) * 1000, r


def report(name: str, ms: list[float]) -> None:
    p95 = statistics.quantiles(ms, n=20)[-1] if len(ms) >= 20 else max(ms)
    print(f"  {name:<28} median {statistics.median(ms):7.2f} ms   p95 {p95:7.2f} ms   (n={len(ms)})")


def run(label: str, database_url: str, n: int) -> None:
    port = free_port()
    env = {**os.environ, "ROLLOVER_DATABASE_URL": database_url, "ROLLOVER_API_KEYS": KEY}
    proc = start_server(port, env)
    try:
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", headers=AUTH, timeout=30) as c:
            record = {k: v for k, v in c.get("/v1/vehicles/table16-btrain").json().items()
                      if k not in ("id", "title", "source", "models")}  # fmt: skip
            posts, gets, puts, pages, ids = [], [], [], [], []
            for i in range(n):
                ms, r = timed(c, "POST", "/v1/vehicles", json={"title": f"v{i}", "vehicle": record})
                assert r.status_code == 201, r.text
                posts.append(ms)
                ids.append(r.json()["id"])
            for vid in ids:
                ms, r = timed(c, "GET", f"/v1/vehicles/{vid}")
                assert r.status_code == 200
                gets.append(ms)
            for vid in ids:
                body = {"title": "changed", "vehicle": {**record, "cg_height_above_chassis_m": 1.5}}
                ms, r = timed(c, "PUT", f"/v1/vehicles/{vid}", json=body, headers={"If-Match": '"1"'})
                assert r.status_code == 200
                puts.append(ms)
            cursor = None
            while True:
                ms, r = timed(
                    c, "GET", "/v1/vehicles/saved", params={"limit": 50, **({"cursor": cursor} if cursor else {})}
                )
                pages.append(ms)
                cursor = r.json()["next_cursor"]
                if cursor is None:
                    break
        print(label)
        report("POST /v1/vehicles (record)", posts)
        report("GET /v1/vehicles/{id}", gets)
        report("PUT /v1/vehicles/{id}", puts)
        report("GET /v1/vehicles/saved (50)", pages)
    finally:
        proc.terminate()
        proc.wait(10)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=200, help="vehicles to save, read and replace")
    parser.add_argument("--postgres", help="an empty PostgreSQL database URL to measure as well")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        run("SQLite (WAL, synchronous=FULL), one uvicorn worker", f"sqlite:///{tmp}/bench.db", args.n)
    if args.postgres:
        run("PostgreSQL (psycopg 3), one uvicorn worker", args.postgres, args.n)


if __name__ == "__main__":
    main()
