"""What the service says about itself: GET /healthz, GET /metrics (Prometheus text format) and GET /v1/models (the
available models with their equation numbers and references)."""

from __future__ import annotations

import os

from fastapi import APIRouter, Response
from prometheus_client import CONTENT_TYPE_LATEST, REGISTRY, CollectorRegistry, generate_latest

from app.deps import CacheDep
from app.http.problems import error_responses
from app.meta.schemas import Health, ModelInfoOut
from engine import ENGINE_VERSION
from engine.models import MODELS

health_router = APIRouter(tags=["health"])
models_router = APIRouter(prefix="/v1/models", tags=["models"])


@health_router.get("/healthz", response_model=Health, responses=error_responses(500))
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


@health_router.get(
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


@models_router.get("", response_model=list[ModelInfoOut], responses=error_responses(500))
def list_models() -> list[ModelInfoOut]:
    """Every model id accepted by `model`, with the thesis equations, the reference and the inputs it uses."""
    return [
        ModelInfoOut(
            id=m.id,
            name=m.name,
            equation=m.equation,
            reference=m.reference,
            takes=list(m.takes),
            combination_takes=list(m.combination_takes if m.solve_combination is not None else m.takes),
            summary=m.summary,
            curves=m.curves,
            default=m.id == "3d",
        )
        for m in MODELS.values()
    ]
