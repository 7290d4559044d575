"""The app's route table as the middlewares and handlers read it: every FastAPI route, included routers expanded.

FastAPI 0.165 keeps an included router as one lazy entry of ``app.routes`` and expands it where it is used (matching,
the OpenAPI document); :func:`api_routes` expands it the same way (``fastapi.routing.iter_route_contexts``), and reads
``app.routes`` as it is on a FastAPI that lists every route there.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Any

from fastapi import routing


def api_routes(routes: Iterable[Any]) -> Iterator[Any]:
    """The FastAPI routes of ``routes`` (an app's ``app.routes``), each with its full ``path``, ``methods``,
    ``endpoint``, ``openapi_extra``, ``include_in_schema`` and ``body_field``; mounts and plain Starlette routes left
    out."""
    expand = getattr(routing, "iter_route_contexts", None)
    for route in expand(list(routes)) if expand is not None else routes:
        if isinstance(getattr(route, "original_route", route), routing.APIRoute):
            yield route


def documented_paths(routes: Iterable[Any]) -> dict[str, set[str]]:
    """path template -> the methods the OpenAPI document declares for it (upper case): the routes in the schema,
    as the document lists them, without building it."""
    paths: dict[str, set[str]] = {}
    for route in api_routes(routes):
        if route.include_in_schema:
            paths.setdefault(route.path_format, set()).update(route.methods or ())
    return paths
