"""Wall time of a 1,000,000-curve alignment job on the Redis backend with two worker processes, and the same job on
one worker (the reference, measured in the same run); the workers' peak RSS; the result's streaming throughput.

Starts its own redis-server (free port, no persistence), uvicorn (the API, ROLLOVER_JOBS_BACKEND=redis) and
``python -m app.jobs.worker`` processes, all on 127.0.0.1, and stops them at the end. The curves are synthetic: a
fixed seed, random radius (40-1,500 m), superelevation (-2 to 10 %, 0.1 % steps) and grade (-8 to 8 %, 0.1 % steps),
so about 19,000 distinct bank/grade pairs, posted speeds 40-110 km/h; one vehicle (the Table 16 B-train, 3D model).

    python bench/bench_jobs.py [--curves 1000000] [--workers 2]
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import numpy as np
import orjson

ROOT = Path(__file__).resolve().parents[1]
SECRET = "bench-secret-0123456789abcdef"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def curves_csv(n: int, seed: int = 2024) -> str:
    rng = np.random.default_rng(seed)
    radius = np.round(rng.uniform(40, 1500, n), 1)
    e = np.round(rng.uniform(-2, 10, n), 1)
    g = np.round(rng.uniform(-8, 8, n), 1)
    v = rng.choice([40, 50, 60, 70, 80, 90, 100, 110], n)
    lines = ["id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh"]
    lines += [f"C{i},{radius[i]},{e[i]},{g[i]},{v[i]}" for i in range(n)]
    return "\n".join(lines) + "\n"


def rss_kb(pid: int) -> int:
    """Peak resident set size (VmHWM) of a process [kB]."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
    return 0


def wait_port(port: int, timeout: float = 30) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            return
        except OSError:
            time.sleep(0.1)
    raise RuntimeError(f"nothing listens on {port}")


def start(cmd: list[str], env: dict[str, str]) -> subprocess.Popen:
    return subprocess.Popen(
        cmd, cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True
    )


def stop(p: subprocess.Popen) -> None:
    if p.poll() is None:
        os.killpg(p.pid, signal.SIGTERM)
        try:
            p.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


def run_job(api: str, body: bytes, env: dict[str, str], n_workers: int) -> dict:
    workers = [
        start([sys.executable, "-m", "app.jobs.worker", "--name", f"bench{k}-{time.time_ns()}"], env)
        for k in range(n_workers)
    ]
    time.sleep(2.0)  # imported and listening
    peaks = dict.fromkeys(range(n_workers), 0)
    with httpx.Client(base_url=api, timeout=600) as c:
        t0 = time.perf_counter()
        r = c.post("/v1/jobs", content=body, headers={"content-type": "application/json"})
        submitted = time.perf_counter() - t0
        assert r.status_code == 202, r.text
        location = r.headers["location"]
        while True:
            for k, w in enumerate(workers):
                peaks[k] = max(peaks[k], rss_kb(w.pid))
            s = c.get(location).json()
            if s["status"] in ("done", "failed", "cancelled"):
                break
            time.sleep(0.25)
        wall = time.perf_counter() - t0
        assert s["status"] == "done", s
        results = {}
        for fmt, accept in (("json", "application/json"), ("csv", "text/csv")):
            t1, size = time.perf_counter(), 0
            with c.stream("GET", location + "/result", headers={"accept": accept}) as res:
                for chunk in res.iter_bytes():
                    size += len(chunk)
            results[fmt] = (size, time.perf_counter() - t1)
        c.delete(location)
    for w in workers:
        stop(w)
    return {"wall": wall, "submit": submitted, "peaks": peaks, "results": results, "parts": s["parts"]["total"]}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--curves", type=int, default=1_000_000)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    redis_bin = shutil.which("redis-server")
    if redis_bin is None:
        sys.exit("redis-server is needed (apt-get install redis-server)")
    rport, aport = free_port(), free_port()
    env = {
        **os.environ,
        "ROLLOVER_JOBS_BACKEND": "redis",
        "ROLLOVER_REDIS_URL": f"redis://127.0.0.1:{rport}/0",
        "ROLLOVER_CACHE_SECRET": SECRET,
        "ROLLOVER_LOG_LEVEL": "WARNING",
    }
    procs = [start([redis_bin, "--port", str(rport), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no"], env)]
    try:
        wait_port(rport)
        procs.append(
            start([sys.executable, "-m", "uvicorn", "app.main:app", "--host", "127.0.0.1", "--port", str(aport)], env)
        )
        wait_port(aport)
        text = curves_csv(args.curves)
        body = orjson.dumps({"operation": "alignments.assess", "request": {"vehicle": "table16-btrain", "csv": text}})
        pairs = len({tuple(line.split(",")[2:4]) for line in text.splitlines()[1:]})
        print(f"# {args.curves:,} curves ({pairs:,} distinct bank/grade pairs), request {len(body) / 2**20:.1f} MiB")
        print()
        print(
            "| workers | parts | wall time [s] | submit [s] | curves/s | peak RSS per worker [MiB] | JSON result | CSV "
            "result |"
        )
        print("| --- | --- | --- | --- | --- | --- | --- | --- |")
        for n in (args.workers, 1):
            out = run_job(f"http://127.0.0.1:{aport}", body, env, n)
            peaks = ", ".join(f"{v / 1024:.0f}" for v in out["peaks"].values())
            cells = []
            for fmt in ("json", "csv"):
                size, secs = out["results"][fmt]
                cells.append(f"{size / 2**20:.0f} MiB in {secs:.1f} s ({size / 2**20 / secs:.0f} MiB/s)")
            rate = args.curves / out["wall"]
            row = f"| {n} | {out['parts']} | {out['wall']:.1f} | {out['submit']:.1f} | {rate:,.0f} | {peaks} | "
            print(row + f"{cells[0]} | {cells[1]} |", flush=True)
    finally:
        for p in reversed(procs):
            stop(p)


if __name__ == "__main__":
    main()
