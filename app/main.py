"""The FastAPI application: ``create_app()`` factory and the module-level ``app`` that uvicorn serves.

uvicorn app.main:app --host 127.0.0.1 --port 8000
"""

from __future__ import annotations

import gc
from contextlib import asynccontextmanager

from fastapi import FastAPI
from fastapi_offline import FastAPIOffline
from starlette.concurrency import run_in_threadpool

from app.advisory import router as advisory_router
from app.alignments import router as alignments_router
from app.catalog import router as catalog_router
from app.catalog.service import close_catalog, install_catalog_handlers, open_catalog
from app.compute import solvers
from app.compute.cache import make_cache
from app.dynamics import router as dynamics_router
from app.http.bodylimit import BodyLimitMiddleware, route_limits
from app.http.fastpath import FastPathMiddleware, replay_table
from app.http.netopts import set_nodelay_on_listening_sockets
from app.http.openapi import operation_id, problem_openapi
from app.http.problems import install_problem_handlers, problem_bytes
from app.http.request_metrics import HttpMetricsMiddleware
from app.http.strictjson import StrictJsonMiddleware, json_routes
from app.jobs import router as jobs_router
from app.jobs.service import open_jobs
from app.logs import configure_logging, get_logger
from app.meta.router import health_router, models_router
from app.metrics import JOBS_ACTIVE
from app.page import install_page, install_redoc
from app.plots import router as plots_router
from app.road import router as road_router
from app.road import standards_router
from app.routes import router as routes_router
from app.settings import Settings, get_settings
from app.srt import router as srt_router
from app.vehicles import builder_router, combination_router
from app.vehicles import router as vehicles_router
from engine import ENGINE_VERSION

DESCRIPTION = """\
Static rollover threshold (SRT) of heavy vehicles and the curve design that follows from it: the maximum speed on
a curve (Eq. 9.1) and the minimum radius for a design speed (Eqs. 9.2-9.3) to a named design standard (AASHTO
2018 by default, DNIT 1999, or the thesis's Table 21).

Units are SI except road practice: speeds in km/h, superelevation and grade in %, SRT in g. Every field names its
unit and its thesis symbol. Errors are RFC 9457 problem details (`application/problem+json`). Computed responses
carry `ETag` (the cache key) and `X-Cache: hit|miss`.
"""

TAGS = [
    {"name": "vehicles", "description": "The thesis presets (Tables 14, 15, 16, 22, 23) as full vehicle records."},
    {
        "name": "combinations",
        "description": "Combination presets (tractor-semitrailer, B-double, A-double, truck and trailer): every unit, "
        "axle group and coupling of a roll-coupled chain, each value with its source; usable as `vehicle` anywhere.",
    },
    {
        "name": "catalog",
        "description": "Saved vehicles and named fleets of the caller's bearer key (`ROLLOVER_API_KEYS`), in a "
        "SQLite or PostgreSQL database; changes need `If-Match` (optimistic concurrency).",
    },
    {
        "name": "builder",
        "description": "A vehicle described by what an engineer can measure (axle groups, tyres, suspension type, "
        "tare, payloads with deck and load heights), built into the full record with the source of every field; "
        "the component library; the acceptable payload table.",
    },
    {"name": "srt", "description": "Static rollover threshold with the 3D, 2D or a closed-form model."},
    {"name": "road", "description": "Curve design: maximum speed (Eq. 9.1) and minimum radius (Eqs. 9.2-9.3)."},
    {
        "name": "standards",
        "description": "Road-design standards (AASHTO 2018, DNIT 1999, the thesis's Table 21): their side-friction "
        "tables and minimum radii with citations, and the superelevation distribution (AASHTO Method 5, DNIT).",
    },
    {
        "name": "alignments",
        "description": "Batch assessment of a road alignment's horizontal curves (JSON, CSV or LandXML 1.2, in a "
        "JSON request or uploaded as they are): safe speed against rollover (Eq. 9.1) and side friction "
        "(the design standard's f_max), margin against the posted speed.",
    },
    {
        "name": "routes",
        "description": "A route as geometry (GeoJSON or GPX, WGS84): its horizontal curves found and assessed "
        "like an alignment's; the answer a GeoJSON FeatureCollection for a GIS, or CSV.",
    },
    {
        "name": "plots",
        "description": "The thesis's figures for one case, as SVG: tire loads, LLT, roll and CG path against ay/g "
        "(Figs. 85-87, 92-97), minimum radius against design speed (Figs. 108-114).",
    },
    {
        "name": "jobs",
        "description": "Long batches as jobs (alignments of up to 1,000,000 rows, sweeps of up to 1,000,000 cases): "
        "submit, follow the progress, fetch the result (the synchronous answer, byte for byte), cancel.",
    },
    {
        "name": "dynamics",
        "description": "The combination in motion, a linear yaw-roll model: lane change (rearward amplification, "
        "high-speed transient offtracking), frequency response, pulse steer (yaw damping), stability against speed, "
        "steady turn, low-speed 90 degree turn. Indicative screening, not a certification.",
    },
    {
        "name": "pbs",
        "description": "Performance-Based Standards screening of a combination: value, limits by level with their "
        "sources (unverified where the rules could not be read), the standards not judged.",
    },
    {"name": "models", "description": "The available models, their equations and references."},
    {"name": "health", "description": "Liveness and Prometheus metrics."},
]


#: every router, in the order they match: the catalog's GET /v1/vehicles/saved before the presets' GET /v1/vehicles/{id}
ROUTERS = (
    catalog_router.router,
    builder_router.router,
    vehicles_router.router,
    combination_router.router,
    srt_router.router,
    road_router.router,
    advisory_router.router,
    standards_router.router,
    alignments_router.router,
    routes_router.router,
    dynamics_router.router,
    dynamics_router.pbs_router,
    plots_router.router,
    jobs_router.router,
    models_router,
    health_router,
)


def _active_jobs(jobs) -> float:
    try:
        return float(jobs.active_count())
    except Exception:  # a closed backend (tests make many apps) or Redis down: unknown
        return float("nan")


_frozen = False


def _freeze_startup_objects() -> None:
    """What the first startup made (modules, models, schemas, the routes) lives as long as the process: moved out of
    the collector's way (gc.freeze), so a batch's 100,000 rows do not make each full collection walk all of it again.
    Once per process: a test session starts many apps, and a later freeze would keep the earlier ones' cycles."""
    global _frozen
    if not _frozen:
        _frozen = True
        gc.freeze()


def create_app(settings: Settings | None = None) -> FastAPI:
    """Build the app with ``settings`` (tests), or the settings read from the environment."""

    @asynccontextmanager
    async def lifespan(app: FastAPI):
        app.state.cache = cache = make_cache(app.state.settings)
        solvers.configure(app.state.settings.solve_threads)
        log = get_logger("rollover.app")
        nodelay = set_nodelay_on_listening_sockets()  # see app.http.netopts: --workers would otherwise wait ~40 ms
        log.info("startup", engine_version=ENGINE_VERSION, cache_backend=cache.backend, tcp_nodelay_sockets=nodelay)
        if cache.redis is not None:
            await cache.ping()  # logs redis_unavailable once if it is down; the service starts anyway
        await open_catalog(app, app.state.settings)  # opens and migrates the database when ROLLOVER_API_KEYS is set
        app.state.jobs = jobs = open_jobs(app.state.settings)  # in-process threads, or Redis + RQ workers
        JOBS_ACTIVE.set_function(lambda: _active_jobs(jobs))
        _freeze_startup_objects()
        try:
            yield
        finally:
            await run_in_threadpool(jobs.close)
            await close_catalog(app)
            await cache.aclose()
            app.state.cache = None

    # the interactive docs (/docs, /redoc) with Swagger UI and ReDoc served from the fastapi-offline package's
    # own copies (under /static-offline-docs): they work on an isolated network, no CDN
    app = FastAPIOffline(
        title="rollover",
        version=ENGINE_VERSION,
        summary="Static rollover threshold of heavy vehicles, maximum curve speed and minimum curve radius.",
        description=DESCRIPTION,
        openapi_tags=TAGS,
        # pyproject.toml's license; an SPDX expression for a license not on the SPDX list is LicenseRef-<name>
        license_info={"name": "Proprietary", "identifier": "LicenseRef-Proprietary"},
        generate_unique_id_function=operation_id,
        swagger_ui_parameters={"validatorUrl": None},  # Swagger UI's validator badge is an image from another host
        redoc_url=None,  # served by install_redoc: fastapi-offline's, with a policy that keeps ReDoc's logo offline
        lifespan=lifespan,
    )
    app.state.settings = settings if settings is not None else get_settings()
    configure_logging(app.state.settings.log_level)
    app.state.cache = None
    install_problem_handlers(app)
    install_catalog_handlers(app)
    for router in ROUTERS:
        app.include_router(router)
    install_page(app)  # GET / (the calculator page) and /web/ (its assets); not in the OpenAPI document
    install_redoc(app)
    # innermost: JSON bodies read strictly (content type, encoding, nesting, keys), counted by the metrics
    app.add_middleware(StrictJsonMiddleware, routes=lambda: json_routes(app.routes))
    if app.state.settings.metrics:  # ROLLOVER_METRICS=false: no per-request HTTP metrics (bench/bench_service.py)
        app.add_middleware(HttpMetricsMiddleware)
    # outermost first: the body limit, then the cache-hit fast path, then the metrics and the app
    app.add_middleware(FastPathMiddleware, routes=lambda: replay_table(app.routes), cache=lambda: app.state.cache)
    app.add_middleware(BodyLimitMiddleware, limits=lambda: route_limits(app.routes), problem=problem_bytes)
    app.openapi = lambda: problem_openapi(app)  # type: ignore[method-assign]  # built on first use, once per process
    return app


app = create_app()
