"""Service speed (issue 8): each figure of a live uvicorn beside its ceiling measured in the same run (prints figures).

Starts its own uvicorn processes on free ports (waits for /healthz, stops them at the end) and measures:

* a cached ``POST /v1/srt`` on 1 worker with ``wrk -t2 -c32`` (req/s, p50/p99) against a raw ASGI app that reads the
  body and returns fixed bytes of the same size under the same server settings, with h11/asyncio and with
  httptools/uvloop; the same with ``If-None-Match`` (304);
* uncached ``POST /v1/srt`` (every request a new bank angle: a new cache key; each answer's ``X-Cache`` is checked)
  against the engine alone (``rollover_threshold`` on the same cases, in process);
* ``--workers 2`` against 1 worker: latency of one kept-alive connection (``wrk -t1 -c1``) for ``/healthz`` and a
  cached ``/v1/srt`` (Nagle + delayed ACK would add ~40 ms a request: app/http/netopts.py);
* the alignment at the synchronous limit (10,000 curves, every bank/grade pair distinct: 10,000 SRT solves; larger
  work goes to a job: ``bench/bench_jobs.py``): wall time, the server's peak RSS
  (VmHWM) and RSS after, the worst ``/healthz`` latency polled every 20 ms meanwhile from another process; against
  ``engine.assessment.assess_alignment`` alone in a fresh process;
* the largest synchronous sweep (10,000 cases, ``POST /v1/srt/sweep``): wall time and peak RSS, against
  ``engine.models.threshold.sweep`` alone in a fresh process;
* the per-request HTTP metrics' share (app.http.request_metrics): cached-hit and ``/healthz`` throughput with
  ``ROLLOVER_METRICS=true`` and ``false``.

The machine is shared by wrk and the server (2 cores here): the ceilings are measured the same way, so the ratios
compare like with like. The "issue 8 (before, reported)" column repeats the figures the issue gave before this work.

    python bench/bench_service.py [--duration 8] [--quick]

Needs wrk on the PATH (Debian: apt-get install wrk) and uvicorn[standard] (uvloop, httptools).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import httpx
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from app.formats.alignment_io import MAX_CURVES  # noqa: E402  (the synchronous limit the alignment run sits at)
from scripts.docblock import write_block  # noqa: E402

BTRAIN = "table16-btrain"
SRT_BODY = json.dumps({"vehicle": BTRAIN, "road": {"bank_percent": 4.0}}, separators=(",", ":"))

#: the figures issue 8 reported before this work, where the brief quotes them (None: not quoted; see the report)
BEFORE: dict[str, str] = {
    "cached h11": "1,294 req/s, p99 81 ms",
    "cached httptools": "1,664 req/s, p99 78 ms",
    "uncached": "354 req/s, p50 86 ms",
    "alignment": "9.9 s, 1.0 GB peak, ~930 MB after (100,000 curves, the synchronous limit then)",
    "sweep": "1.49 s, 294 MB (20,000 cases, the limit then)",
    "workers": "~40 ms a request (Nagle + delayed ACK)",
}

# -------------------------------------------------------------------------------------------- the raw ceiling


async def raw_app(scope, receive, send):
    """The ceiling: an ASGI app that reads the request body and answers fixed bytes (BENCH_RAW_BYTES long)."""
    if scope["type"] == "lifespan":
        while True:
            message = await receive()
            if message["type"] == "lifespan.startup":
                await send({"type": "lifespan.startup.complete"})
            elif message["type"] == "lifespan.shutdown":
                await send({"type": "lifespan.shutdown.complete"})
                return
    more = True
    while more:
        message = await receive()
        more = message.get("more_body", False)
    body = _RAW_BODY
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
    await send({"type": "http.response.start", "status": 200, "headers": headers})
    await send({"type": "http.response.body", "body": body})


_RAW_BODY = b"x" * int(os.environ.get("BENCH_RAW_BYTES", "1000"))

# ------------------------------------------------------------------------------------------------ the servers


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@dataclass
class Server:
    proc: subprocess.Popen
    port: int

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def status(self, field: str) -> int:
        """A field of /proc/<pid>/status of the server process (VmHWM, VmRSS) [bytes]."""
        for line in Path(f"/proc/{self.proc.pid}/status").read_text().splitlines():
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
        raise KeyError(field)


@contextlib.contextmanager
def server(
    app: str, *, http: str = "httptools", workers: int = 1, env: dict[str, str] | None = None
) -> Iterator[Server]:
    """uvicorn serving ``app`` on a free port (h11 pairs with the asyncio loop, httptools with uvloop)."""
    port = free_port()
    loop = "uvloop" if http == "httptools" else "asyncio"
    argv = [sys.executable, "-m", "uvicorn", app, "--host", "127.0.0.1", "--port", str(port), "--loop", loop,
            "--http", http, "--log-level", "warning", "--no-access-log"]  # fmt: skip
    if workers > 1:
        argv += ["--workers", str(workers)]
    if app.startswith("bench_service:"):
        argv += ["--app-dir", str(Path(__file__).parent)]
    full_env = {**os.environ, "ROLLOVER_CACHE_BACKEND": "memory", "ROLLOVER_LOG_LEVEL": "WARNING", **(env or {})}
    proc = subprocess.Popen(argv, cwd=ROOT, env=full_env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                if httpx.get(f"http://127.0.0.1:{port}/healthz", timeout=1).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if time.monotonic() > deadline or proc.poll() is not None:
                raise SystemExit(f"uvicorn {app} did not start")
            time.sleep(0.1)
        if workers > 1:  # every worker up: each answers /healthz once the parent has forked it
            time.sleep(2)
        yield Server(proc, port)
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


# ------------------------------------------------------------------------------------------------------- wrk

WRK_DONE = """
done = function(summary, latency, requests)
  local misses, others = 0, 0
  for _, t in ipairs(threads) do
    misses = misses + (t:get("misses") or 0)
    others = others + (t:get("others") or 0)
  end
  io.write(string.format('WRK_JSON {"requests":%d,"duration_us":%d,"p50_us":%d,"p99_us":%d,"max_us":%d,' ..
    '"status_errors":%d,"socket_errors":%d,"misses":%d,"others":%d}\\n', summary.requests, summary.duration,
    latency:percentile(50), latency:percentile(99), latency.max, summary.errors.status,
    summary.errors.connect + summary.errors.read + summary.errors.write + summary.errors.timeout, misses, others))
end
"""

WRK_THREADS = """
threads = {}
setup = function(thread)
  thread:set("tid", #threads)
  table.insert(threads, thread)
end
"""


def lua_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def fixed_post(path: str, body: str, headers: dict[str, str]) -> str:
    lines = [WRK_THREADS, 'wrk.method = "POST"', f"wrk.path = {lua_string(path)}", f"wrk.body = {lua_string(body)}"]
    lines += [f"wrk.headers[{lua_string(k)}] = {lua_string(v)}" for k, v in headers.items()]
    return "\n".join(lines) + WRK_DONE


def fixed_get(path: str) -> str:
    return f"{WRK_THREADS}\nwrk.path = {lua_string(path)}\n{WRK_DONE}"


#: a new bank angle per request (distinct across threads: thread k takes k, k + n, k + 2n, ...), X-Cache counted
VARYING_SRT = """
counter = 0
misses = 0
others = 0
request = function()
  local k = counter * NTHREADS + tid
  counter = counter + 1
  local bank = -15 + (k % 3000000) * 1e-5
  local body = string.format('{"vehicle":"VEHICLE","road":{"bank_percent":%.5f}}', bank)
  return wrk.format("POST", "/v1/srt", {["Content-Type"] = "application/json"}, body)
end
response = function(status, headers, body)
  if headers["x-cache"] == "miss" and status == 200 then misses = misses + 1 else others = others + 1 end
end
"""


@dataclass
class WrkResult:
    requests: int
    seconds: float
    p50_ms: float
    p99_ms: float
    max_ms: float
    status_errors: int
    socket_errors: int
    misses: int
    others: int

    @property
    def rps(self) -> float:
        return self.requests / self.seconds


def wrk(url: str, script: str, *, threads: int, connections: int, seconds: float) -> WrkResult:
    with tempfile.NamedTemporaryFile("w", suffix=".lua", delete=False) as f:
        f.write(script.replace("NTHREADS", str(threads)))
    try:
        done = subprocess.run(
            [
                "wrk",
                f"-t{threads}",
                f"-c{connections}",
                f"-d{max(1, round(seconds))}s",
                "--timeout",
                "10s",
                "-s",
                f.name,
                url,
            ],
            capture_output=True,
            text=True,
            check=True,
        )
    finally:
        os.unlink(f.name)
    line = next(x for x in done.stdout.splitlines() if x.startswith("WRK_JSON "))
    d = json.loads(line.removeprefix("WRK_JSON "))
    return WrkResult(
        d["requests"], d["duration_us"] / 1e6, d["p50_us"] / 1e3, d["p99_us"] / 1e3, d["max_us"] / 1e3,
        d["status_errors"], d["socket_errors"], d["misses"], d["others"],
    )  # fmt: skip


def fast_path_hits(url: str) -> float:
    text = httpx.get(url + "/metrics", timeout=10).text
    return sum(float(x.split()[-1]) for x in text.splitlines() if x.startswith("rollover_fast_path_hits_total "))


def cached_srt_run(srv: Server, args, *, etag: str | None = None, seconds: float | None = None) -> WrkResult:
    """wrk on one repeated /v1/srt body (answered by the fast path: checked on its counter)."""
    headers = {"Content-Type": "application/json"}
    if etag:
        headers["If-None-Match"] = etag
    script = fixed_post("/v1/srt", SRT_BODY, headers)
    before = fast_path_hits(srv.url)
    res = wrk(srv.url, script, threads=2, connections=32, seconds=seconds or args.duration)
    served = fast_path_hits(srv.url) - before
    if res.status_errors or res.socket_errors or served < res.requests:
        raise SystemExit(f"cached run: {res} but only {served:.0f} answered by the fast path")
    return res


def warm_srt(srv: Server) -> httpx.Response:
    """Two identical requests: the first computes, the second is a cache hit (and teaches the fast path)."""
    with httpx.Client(base_url=srv.url, timeout=60) as c:
        for expect in ("miss", "hit"):
            r = c.post("/v1/srt", content=SRT_BODY, headers={"content-type": "application/json"})
            if r.status_code != 200 or r.headers["x-cache"] != expect:
                raise SystemExit(f"warm-up: {r.status_code} X-Cache={r.headers.get('x-cache')} (expected {expect})")
    return r


# ---------------------------------------------------------------------------------------------- measurements

ROWS: list[tuple[str, str, str, str, str]] = []  # figure, rollover, ceiling, target, before


def row(figure: str, measured: str, ceiling: str, target: str, before: str | None = None) -> None:
    ROWS.append((figure, measured, ceiling, target, before or "not quoted"))
    print(f"  {figure}: {measured} | ceiling {ceiling} | {target}", flush=True)


def fmt(r: WrkResult) -> str:
    return f"{r.rps:,.0f} req/s, p50 {r.p50_ms:.2f} ms, p99 {r.p99_ms:.2f} ms"


def verdict(ok: bool) -> str:
    return "met" if ok else "NOT met"


def best(runs: list[WrkResult]) -> WrkResult:
    """The run with the highest throughput (the machine is shared: the others were slowed by something else)."""
    return max(runs, key=lambda r: r.rps)


def measure_cached(args) -> None:
    for http in ("h11", "httptools"):
        label = "h11/asyncio" if http == "h11" else "httptools/uvloop"
        with server("app.main:app", http=http) as srv:
            answer = warm_srt(srv)
            size, etag = len(answer.content), answer.headers["etag"]
            script = fixed_post("/v1/srt", SRT_BODY, {"Content-Type": "application/json"})
            with server("bench_service:raw_app", http=http, env={"BENCH_RAW_BYTES": str(size)}) as raw:
                wrk(raw.url, script, threads=2, connections=32, seconds=1)  # warm-up of both
                cached_srt_run(srv, args, seconds=1)
                hits, ceilings, not_modified = [], [], []
                for _ in range(args.rounds):  # alternated, so a burst of load elsewhere hits both alike
                    hits.append(cached_srt_run(srv, args))
                    ceilings.append(wrk(raw.url, script, threads=2, connections=32, seconds=args.duration))
                    not_modified.append(cached_srt_run(srv, args, etag=etag))
        hit, ceiling, nm = best(hits), best(ceilings), best(not_modified)
        share = hit.rps / ceiling.rps
        row(
            f"cached POST /v1/srt, 1 worker, {label}, wrk -t2 -c32 ({size} B answer)",
            fmt(hit),
            f"raw ASGI app, same bytes: {fmt(ceiling)}",
            f"{share:.0%} of raw (>= 25 %: {verdict(share >= 0.25)}); p99 <= 10 ms: {verdict(hit.p99_ms <= 10)}",
            BEFORE[f"cached {http}"],
        )
        share = nm.rps / ceiling.rps
        row(
            f"cached POST /v1/srt + If-None-Match -> 304, 1 worker, {label}, wrk -t2 -c32",
            fmt(nm),
            f"raw ASGI app, 200: {fmt(ceiling)}",
            f"{share:.0%} of raw (>= 25 %: {verdict(share >= 0.25)}); p99 <= 10 ms: {verdict(nm.p99_ms <= 10)}",
        )


def engine_srt_rate(seconds: float = 3.0) -> float:
    """Distinct single solves per second of the engine in process (the bank angles the uncached run sends)."""
    from engine import Case, Road
    from engine.models import rollover_threshold
    from engine.vehicle import get_preset

    base = Case(get_preset(BTRAIN))
    rollover_threshold(base)  # the calibrated model is built once per vehicle and stage (memoised), as in the app
    n, started = 0, time.perf_counter()
    while time.perf_counter() - started < seconds:
        rollover_threshold(base.replace(road=Road(bank_percent=-15 + (n % 3_000_000) * 1e-5 + 5e-6)))
        n += 1
    return n / (time.perf_counter() - started)


def _batch_cases(url: str) -> tuple[float, float]:
    """(engine calls, cases) of the server's coalesced one-threshold solves so far (``rollover_solve_batch_cases``)."""
    text = httpx.get(url + "/metrics", timeout=10).text
    values = {}
    for line in text.splitlines():
        name, _, value = line.partition(" ")
        if name in ("rollover_solve_batch_cases_count", "rollover_solve_batch_cases_sum"):
            values[name] = float(value)
    return values.get("rollover_solve_batch_cases_count", 0.0), values.get("rollover_solve_batch_cases_sum", 0.0)


def measure_uncached(args) -> None:
    script = WRK_THREADS + VARYING_SRT.replace("VEHICLE", BTRAIN) + WRK_DONE
    runs = {}
    for connections in (1, 32):  # each on a fresh server: every request a miss
        with server("app.main:app", http="httptools", env={"ROLLOVER_CACHE_MAX_ENTRIES": "1000000"}) as srv:
            warm_srt(srv)
            calls0, cases0 = _batch_cases(srv.url)
            res = wrk(srv.url, script, threads=min(2, connections), connections=connections, seconds=args.duration)
            calls, cases = _batch_cases(srv.url)
        if res.others or res.status_errors or res.misses != res.requests:
            raise SystemExit(f"uncached run: {res.misses} misses of {res.requests} answers ({res.others} others)")
        runs[connections] = res, (cases - cases0) / max(calls - calls0, 1.0)
    rate = engine_srt_rate()
    (alone, alone_batch), (crowd, crowd_batch) = runs[1], runs[32]
    row(
        "uncached POST /v1/srt (each request a new bank angle; every X-Cache checked: miss), 1 worker, "
        "httptools/uvloop, wrk -t2 -c32",
        f"{fmt(crowd)}; {crowd_batch:.1f} cases per engine call (app.compute.coalescer)",
        f"engine alone, one case at a time, in process: {rate:,.0f} solves/s",
        f"{crowd.rps / rate:.0%} of the engine; >= 500 req/s: {verdict(crowd.rps >= 500)}",
        BEFORE["uncached"],
    )
    row(
        "uncached POST /v1/srt, one connection (wrk -t1 -c1): a request alone is not held for company",
        f"{fmt(alone)}; {alone_batch:.1f} cases per engine call",
        f"engine alone: {1e3 / rate:.2f} ms a solve",
        "",
        "not quoted",
    )


def measure_workers(args) -> None:
    seconds = max(2.0, args.duration / 2)
    results: dict[tuple[int, str], WrkResult] = {}
    for workers in (1, 2):
        with server("app.main:app", http="httptools", workers=workers) as srv:
            with httpx.Client(base_url=srv.url, timeout=60) as c:  # each worker computes its own answer once
                for _ in range(20):
                    c.post("/v1/srt", content=SRT_BODY, headers={"content-type": "application/json"})
            for name, script in (
                ("/healthz", fixed_get("/healthz")),
                ("cached /v1/srt", fixed_post("/v1/srt", SRT_BODY, {"Content-Type": "application/json"})),
            ):
                wrk(srv.url, script, threads=1, connections=1, seconds=1)
                results[workers, name] = wrk(srv.url, script, threads=1, connections=1, seconds=seconds)
            script = fixed_post("/v1/srt", SRT_BODY, {"Content-Type": "application/json"})
            wrk(srv.url, script, threads=2, connections=32, seconds=2)  # every worker's own answer and fast path
            results[workers, "throughput"] = wrk(srv.url, script, threads=2, connections=32, seconds=args.duration)
    for name in ("/healthz", "cached /v1/srt"):
        two, one = results[2, name], results[1, name]
        row(
            f"{name}, one kept-alive connection (wrk -t1 -c1), --workers 2",
            fmt(two),
            f"1 worker: {fmt(one)}",
            f"no Nagle delay (p99 < 40 ms): {verdict(two.p99_ms < 40)}",
            BEFORE["workers"],
        )
    two, one = results[2, "throughput"], results[1, "throughput"]
    row(
        "cached POST /v1/srt, --workers 2, httptools/uvloop, wrk -t2 -c32",
        fmt(two),
        f"1 worker: {fmt(one)}",
        f"{two.rps / one.rps:.2f} x one worker's throughput",
    )


#: the /healthz poller's own process: it must not share an interpreter lock with the bench's client, which reads a
#: 72 MB answer in Python meanwhile (a thread beside it measured that client's pauses as the server's)
POLLER = """
import http.client, json, sys, threading, time
host, port = sys.argv[1], int(sys.argv[2])
stop = threading.Event()
threading.Thread(target=lambda: (sys.stdin.read(), stop.set()), daemon=True).start()
conn = http.client.HTTPConnection(host, port, timeout=30)
worst, polls, worst_at, start = 0.0, 0, 0.0, time.perf_counter()
print("ready", flush=True)
while not stop.is_set():
    t0 = time.perf_counter()
    conn.request("GET", "/healthz")
    r = conn.getresponse()
    r.read()
    if r.status != 200:
        raise SystemExit(f"/healthz answered {r.status}")
    took = time.perf_counter() - t0
    if took > worst:
        worst, worst_at = took, t0 - start
    polls += 1
    stop.wait(0.02)
print(json.dumps({"worst": worst, "polls": polls, "worst_at": worst_at}), flush=True)
"""


class HealthPoller:
    """Polls /healthz every 20 ms on its own connection, from its own process, while a long request runs; keeps the
    worst latency (and when it happened, in seconds from the poller's start)."""

    def __init__(self, url: str) -> None:
        self.url, self.worst, self.polls, self.worst_at = url, 0.0, 0, 0.0

    def __enter__(self) -> HealthPoller:
        host, port = self.url.removeprefix("http://").split(":")
        self._proc = subprocess.Popen(
            [sys.executable, "-c", POLLER, host, port], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
        )
        assert self._proc.stdout.readline().strip() == "ready"
        self.started = time.perf_counter()  # about the poller's own start (its clock's zero)
        return self

    def __exit__(self, *exc) -> None:
        out, _ = self._proc.communicate("", timeout=60)
        result = json.loads(out.strip().splitlines()[-1])
        self.worst, self.polls, self.worst_at = result["worst"], result["polls"], result["worst_at"]


def alignment_curves(n: int, seed: int = 8) -> dict[str, np.ndarray]:
    """n curves whose (superelevation, grade) pairs are all distinct: n SRT solves."""
    rng = np.random.default_rng(seed)
    return {
        "radius_m": np.round(rng.uniform(40, 800, n), 2),
        "superelevation_percent": np.round(rng.permutation(n) * (10.0 / n), 6),  # distinct values in [0, 10)
        "grade_percent": np.round(rng.uniform(-8, 8, n), 3),
        "posted_speed_kmh": rng.choice(np.arange(40.0, 111.0, 10.0), n),
    }


def in_fresh_process(code: str) -> dict:
    """Run ``code`` (which prints one JSON line) in a new interpreter; its result with its peak RSS [bytes]."""
    wrapper = code + "\nimport resource\nprint('PEAK', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)\n"
    done = subprocess.run([sys.executable, "-c", wrapper], cwd=ROOT, capture_output=True, text=True, check=True)
    lines = done.stdout.splitlines()
    out = json.loads(next(x for x in lines if x.startswith("{")))
    out["peak"] = int(next(x for x in lines if x.startswith("PEAK")).split()[1])
    return out


def mb(n: float) -> str:
    return f"{n / 2**20:,.0f} MB"


def measure_alignment(args) -> None:
    n = args.curves
    c = alignment_curves(n)
    curves = [
        {"id": f"C{i}", **{k: float(v[i]) for k, v in c.items()}} for i in range(n)
    ]  # fmt: skip
    pairs = len(set(zip(c["superelevation_percent"].tolist(), c["grade_percent"].tolist(), strict=True)))
    body = json.dumps({"vehicle": BTRAIN, "curves": curves}).encode()
    csv_wall, csv_size = None, 0
    for accept in ("application/json", "text/csv"):  # each on a fresh server: the CSV is solved, not cached
        with server("app.main:app", http="httptools") as srv:
            idle = srv.status("VmRSS")
            with HealthPoller(srv.url) as poller, httpx.Client(base_url=srv.url, timeout=300) as client:
                time.sleep(0.2)
                t0 = time.perf_counter()
                headers = {"content-type": "application/json", "accept": accept}
                r = client.post("/v1/alignments/assess", content=body, headers=headers)
                wall = time.perf_counter() - t0
                since = t0 - poller.started
                time.sleep(0.2)
            if r.status_code != 200 or r.headers["x-cache"] != "miss":
                raise SystemExit(f"alignment: {r.status_code} {r.text[:300]}")
            if accept == "text/csv":
                csv_wall, csv_size = wall, len(r.content)
                continue
            json_r, json_wall, json_since, worst, worst_at, polls = (
                r,
                wall,
                since,
                poller.worst,
                poller.worst_at,
                poller.polls,
            )
            rows = sum(len(v["rows"]) for v in r.json()["vehicles"])
            peak = srv.status("VmHWM")
            time.sleep(1.0)
            after = srv.status("VmRSS")
            json_idle = idle
    r, wall, since, idle = json_r, json_wall, json_since, json_idle
    engine = in_fresh_process(
        f"""
import json, time, numpy as np
from bench.bench_service import alignment_curves, BTRAIN
from engine.road import assess_alignment
from engine.case import Case
from engine.vehicle import get_preset
c = alignment_curves({n})
case = Case(get_preset(BTRAIN))
t0 = time.perf_counter()
out = assess_alignment(case, c["radius_m"], c["superelevation_percent"], c["grade_percent"], c["posted_speed_kmh"])
print(json.dumps({{"seconds": time.perf_counter() - t0, "distinct": int(out.distinct_cases)}}))
"""
    )
    row(
        f"POST /v1/alignments/assess, {n:,} curves ({pairs:,} distinct bank/grade pairs; {len(body) / 2**20:.0f} MB "
        f"request, {len(r.content) / 2**20:.1f} MB answer, {rows:,} rows), 1 worker",
        f"{wall:.2f} s; peak RSS {mb(peak)} (idle {mb(idle)}), {mb(after)} after; /healthz worst "
        f"{worst * 1e3:.0f} ms ({worst_at - since:.2f} s into the request) over {polls} polls; the same as CSV "
        f"(Accept: text/csv, {csv_size / 2**20:.0f} MB): {csv_wall:.2f} s, {csv_wall / wall:.2f}x the JSON",
        f"assess_alignment alone: {engine['seconds']:.2f} s ({engine['distinct']:,} solves), peak RSS "
        f"{mb(engine['peak'])}",
        f"<= 3 s: {verdict(wall <= 3)}; <= 400 MB: {verdict(peak <= 400 * 2**20)}; healthz <= 100 ms: "
        f"{verdict(worst <= 0.1)}; CSV like JSON (<= 1.1x): {verdict(csv_wall <= 1.1 * wall)}",
        BEFORE["alignment"],
    )


def measure_sweep(args) -> None:
    grid = {"bank_percent": [round(-10 + 0.2 * i, 1) for i in range(100)], "slope_percent": list(range(-10, 10)),
            "lateral_offset_m": [0.0, 0.1, 0.2, 0.3, 0.4]}  # fmt: skip
    cases = math.prod(len(v) for v in grid.values())
    body = json.dumps({"vehicle": BTRAIN, "rear_llt_limit": 0.6, "grid": grid}).encode()
    results = {}
    for accept in ("application/json", "text/csv"):
        with server("app.main:app", http="httptools") as srv:
            idle = srv.status("VmRSS")
            with httpx.Client(base_url=srv.url, timeout=300) as client:
                t0 = time.perf_counter()
                r = client.post("/v1/srt/sweep", content=body, headers={"content-type": "application/json",
                                                                         "accept": accept})  # fmt: skip
                wall = time.perf_counter() - t0
            if r.status_code != 200 or r.headers["x-cache"] != "miss":
                raise SystemExit(f"sweep: {r.status_code} {r.text[:300]}")
            results[accept] = (wall, srv.status("VmHWM"), idle, len(r.content), "content-length" not in r.headers)
    engine = in_fresh_process(
        f"""
import json, time
from engine.case import Case
from engine.models import sweep
from engine.vehicle import get_preset
case = Case(get_preset({BTRAIN!r}), rear_llt_limit=0.6)
t0 = time.perf_counter()
out = sweep(case, {grid!r})
print(json.dumps({{"seconds": time.perf_counter() - t0, "cases": len(out.srt)}}))
"""
    )
    for accept, (wall, peak, idle, size, streamed) in results.items():
        row(
            f"POST /v1/srt/sweep, {cases:,} cases, Accept: {accept} ({size / 2**20:.1f} MB answer, "
            f"{'streamed' if streamed else 'whole'}), 1 worker",
            f"{wall:.2f} s; peak RSS {mb(peak)} (idle {mb(idle)})",
            f"engine sweep alone: {engine['seconds']:.2f} s, peak RSS {mb(engine['peak'])}",
            f"{engine['seconds'] / wall:.0%} of the time in the engine",
            BEFORE["sweep"] if accept == "application/json" else None,
        )


def measure_instrumentator(args) -> None:
    runs: dict[tuple[str, str], list[WrkResult]] = {}
    healthz = fixed_get("/healthz")
    with (
        server("app.main:app", http="httptools", env={"ROLLOVER_METRICS": "true"}) as on,
        server("app.main:app", http="httptools", env={"ROLLOVER_METRICS": "false"}) as off,
    ):
        for srv in (on, off):
            warm_srt(srv)
            cached_srt_run(srv, args, seconds=1)
            wrk(srv.url, healthz, threads=2, connections=32, seconds=1)
        for _ in range(args.rounds):  # alternated, so a burst of load elsewhere hits both alike
            for metrics, srv in (("true", on), ("false", off)):
                runs.setdefault((metrics, "srt"), []).append(cached_srt_run(srv, args))
                runs.setdefault((metrics, "healthz"), []).append(
                    wrk(srv.url, healthz, threads=2, connections=32, seconds=args.duration)
                )
    for name, what in (("srt", "cached POST /v1/srt (fast path)"), ("healthz", "GET /healthz (routed)")):
        with_metrics, without = best(runs["true", name]), best(runs["false", name])
        row(
            f"{what}, 1 worker, httptools/uvloop, wrk -t2 -c32, ROLLOVER_METRICS=true",
            fmt(with_metrics),
            f"ROLLOVER_METRICS=false: {fmt(without)}",
            f"HTTP metrics' share: {1 - with_metrics.rps / without.rps:.0%} of the throughput",
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=8.0, help="seconds of each wrk run (8, as issue 8)")
    parser.add_argument("--curves", type=int, default=MAX_CURVES, help="curves of the alignment run")
    parser.add_argument("--rounds", type=int, default=2, help="alternated runs of the cached figures (best kept)")
    parser.add_argument("--quick", action="store_true", help="1-second runs, 1 round, 2,000 curves (a smoke run)")
    parser.add_argument(
        "--only", nargs="*", choices=["cached", "uncached", "workers", "alignment", "sweep", "instrumentator"]
    )
    parser.add_argument(
        "--write",
        action="store_true",
        help="put this run's table in docs/performance.md (whole runs only)",
    )
    args = parser.parse_args()
    if args.write and (args.only or args.quick):
        parser.error("--write records a whole run: leave out --only and --quick")
    if args.quick:
        args.duration, args.curves, args.rounds = 1.0, 2_000, 1
    if shutil.which("wrk") is None:
        raise SystemExit("wrk is not on the PATH (Debian: apt-get install wrk)")
    steps = {
        "cached": measure_cached,
        "uncached": measure_uncached,
        "workers": measure_workers,
        "alignment": measure_alignment,
        "sweep": measure_sweep,
        "instrumentator": measure_instrumentator,
    }
    load = os.getloadavg()[0]
    print(f"rollover service speed, {os.cpu_count()} CPUs, wrk runs of {args.duration:g} s", flush=True)
    for name in args.only or steps:
        print(f"{name} ...", flush=True)
        steps[name](args)
    print()
    print(f"{os.cpu_count()} CPUs shared by wrk, the server and anything else running: load average {load:.1f} at the")
    print(f"start, {os.getloadavg()[0]:.1f} at the end. Cached figures: best of {args.rounds} alternated runs.")
    print()
    table = [
        "| figure | rollover | ceiling (same run) | target | issue 8 (before, reported) |",
        "| --- | --- | --- | --- | --- |",
    ]
    table += [
        f"| {figure} | {measured} | {ceiling} | {target} | {before} |"
        for figure, measured, ceiling, target, before in ROWS
    ]
    print("\n".join(table))
    if args.write:
        write_table(table, load)


def write_table(table: list[str], load: float) -> None:
    """The run's table into docs/performance.md, between its markers, with the date and the machine's load."""
    doc = ROOT / "docs" / "performance.md"
    start, end = "<!-- bench_service:start -->", "<!-- bench_service:end -->"
    stamp = time.strftime("%Y-%m-%d", time.gmtime())
    block = f"Run of {stamp}, {os.cpu_count()} CPUs, load average {load:.1f} at the start.\n\n" + "\n".join(table)
    write_block(doc, start, end, block)
    print(f"wrote {doc.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
