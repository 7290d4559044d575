"""GET /healthz and GET /metrics (Prometheus text format)."""

from __future__ import annotations

import os

from fastapi import APIRouter, Response
from prometheus_client import CONTENT_TYPE_LATEST, REGISTRY, CollectorRegistry, generate_latest

from app.deps import CacheDep
from app.http.problems import error_responses
from app.schemas.meta import Health
from engine import ENGINE_VERSION

router = APIRouter(tags=["health"])


@router.get("/healthz", response_model=Health, responses=error_responses(500))
async def healthz(cache: CacheDep) -> Health:
    """Liveness and cache state. Always 200 while the service answers, Redis or not."""
    redis = await cache.ping()
    return Health(
        status="ok",
        engine_version=ENGINE_VERSION,
        cache_backend=cache.backend,
        redis=None if redis is None else ("ok" if redis else "unavailable"),
        cache_entries=len(cache.local),
    )


@router.get(
    "/metrics",
    response_class=Response,
    responses={
        200: {
            "description": "Prometheus text exposition format.",
            "content": {CONTENT_TYPE_LATEST.split(";")[0]: {"schema": {"type": "string"}}},
        },
        **error_responses(500),
    },
)
def metrics() -> Response:
    """Prometheus metrics: HTTP requests (app.http.request_metrics), engine solve time, cache lookups, jobs."""
    registry = REGISTRY
    if "PROMETHEUS_MULTIPROC_DIR" in os.environ:  # several uvicorn workers: aggregate their files
        from prometheus_client import multiprocess

        registry = CollectorRegistry()
        multiprocess.MultiProcessCollector(registry)
    return Response(generate_latest(registry), media_type=CONTENT_TYPE_LATEST)
