"""Per-request HTTP metrics: ``http_requests_total`` and ``http_request_duration_seconds``.

The names and labels are the ones prometheus-fastapi-instrumentator gave (``handler`` the route's path template,
``method``, ``status`` grouped as ``2xx``...), so dashboards and alerts keep working. It replaced that package:
the instrumentator found a request's route by matching the request against every route again, which cost a routed
``GET /healthz`` a third of its throughput and multiplied its p99 when it was measured against this module. Here the
route is the one the router already chose (``scope["route"]``, set by FastAPI), read after the app answered; what
these metrics cost today is the "HTTP metrics' share" of ``python bench/bench_service.py``.

A path no route matched is counted as ``handler="none"`` (so a scan of random paths cannot create a series per
path); ``GET /metrics`` itself is not counted. Cache hits answered by the raw-body fast path never reach this
middleware: they are ``rollover_fast_path_hits_total``.
"""

from __future__ import annotations

import time
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any

from app.metrics import HTTP_REQUEST_SECONDS, HTTP_REQUESTS

Scope = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[MutableMapping[str, Any]]]
Send = Callable[[MutableMapping[str, Any]], Awaitable[None]]

#: paths whose requests are not counted
EXCLUDED = frozenset({"/metrics"})


class HttpMetricsMiddleware:
    def __init__(self, app: Callable[[Scope, Receive, Send], Awaitable[None]]) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = 500  # what the server sends when the app raises before starting its answer

        async def send_and_watch(message: MutableMapping[str, Any]) -> None:
            nonlocal status
            if message["type"] == "http.response.start":
                status = message["status"]
            await send(message)

        try:
            await self.app(scope, receive, send_and_watch)
        finally:
            handler = getattr(scope.get("route"), "path", None) or "none"
            if handler not in EXCLUDED:
                method = scope["method"]
                HTTP_REQUESTS.labels(handler, method, f"{status // 100}xx").inc()
                HTTP_REQUEST_SECONDS.labels(handler, method).observe(time.perf_counter() - started)
