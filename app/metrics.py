"""Prometheus metrics of the service: per request (:mod:`app.http.request_metrics`), engine, cache and jobs.

Defined once at import on the default registry, so several app instances in one process (tests) share them.
"""

from __future__ import annotations

from prometheus_client import Counter, Gauge, Histogram

HTTP_REQUESTS = Counter(
    "http_requests_total",
    "Requests by route (path template; none when no route matched), method and status class (2xx...).",
    ["handler", "method", "status"],
)
HTTP_REQUEST_SECONDS = Histogram(
    "http_request_duration_seconds",
    "Wall time of a request in the app, by route and method [s] (the raw-body fast path's hits are not here).",
    ["handler", "method"],
    buckets=(0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 30.0),
)
SOLVE_SECONDS = Histogram(
    "rollover_solve_seconds",
    "Wall time of one engine computation (cache misses only; solves handed over together each count their share) [s].",
    ["operation", "model"],
    buckets=(0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0),
)
SOLVE_BATCH_CASES = Histogram(
    "rollover_solve_batch_cases",
    "One-threshold solves handed to the engine together (app.compute.coalescer): cases per engine call [-].",
    buckets=(1, 2, 4, 8, 16, 32, 64),
)
CACHE_LOOKUPS = Counter(
    "rollover_cache_lookups_total",
    "Result-cache lookups by operation and outcome (hit tier: local or redis; miss).",
    ["operation", "result"],
)
ENGINE_ERRORS = Counter(
    "rollover_engine_errors_total",
    "Engine refusals (physically invalid input, singular mechanism, no convergence) by error class.",
    ["error"],
)
REDIS_FAILURES = Counter("rollover_redis_failures_total", "Redis calls that failed (the service went on without).")
CACHE_REJECTED = Counter(
    "rollover_cache_rejected_total",
    "Shared-cache entries refused as not ours or not whole (bad envelope or HMAC, wrong type); recomputed.",
)
FAST_PATH_HITS = Counter(
    "rollover_fast_path_hits_total",
    "Computed requests answered from the in-process cache by their raw bytes, before routing (not in http_*).",
)
JOBS = Counter(
    "rollover_jobs_total",
    "Jobs by operation and status reached: queued (submitted), done, failed, cancelled.",
    ["operation", "status"],
)
JOB_PART_SECONDS = Histogram(
    "rollover_job_part_seconds",
    "Wall time of one part of a job in a worker (solve, render and store) [s].",
    ["operation"],
    buckets=(0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0, 25.0, 50.0, 100.0, 250.0, 600.0),
)
JOB_PART_RETRIES = Counter(
    "rollover_job_part_retries_total",
    "Parts queued again because their worker stopped reporting (killed, out of memory, machine lost).",
    ["operation"],
)
JOBS_ACTIVE = Gauge(
    "rollover_jobs_active",
    "Jobs queued or running in this service's job store (read from the store when scraped).",
)
