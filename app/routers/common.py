"""Pieces shared by the routers: the computed-response headers and their OpenAPI declaration."""

from __future__ import annotations

from typing import Any

from fastapi import Response

from app.compute.results import Computed
from app.problems import error_responses

CACHE_HEADERS: dict[str, Any] = {
    "ETag": {
        "description": "The cache key: engine version, operation and SHA-256 of the canonical resolved request.",
        "schema": {"type": "string"},
    },
    "X-Cache": {
        "description": "`hit` when the result came from the cache, `miss` when it was computed.",
        "schema": {"type": "string", "enum": ["hit", "miss"]},
    },
}


VARY_HEADER = {
    "description": "`Accept`: the answer is JSON or CSV depending on it.",
    "schema": {"type": "string"},
}


def computed_responses(*codes: int) -> dict[int | str, dict[str, Any]]:
    return {200: {"headers": CACHE_HEADERS}, **error_responses(*codes)}


def table_responses(*codes: int) -> dict[int | str, dict[str, Any]]:
    """A computed answer that is JSON by default and CSV when ``Accept`` prefers ``text/csv``."""
    return {
        200: {
            "headers": {**CACHE_HEADERS, "Vary": VARY_HEADER},
            "content": {"text/csv": {"schema": {"type": "string"}}},
            "description": "JSON by default; CSV (header row, one row per case) when `Accept` prefers `text/csv`.",
        },
        **error_responses(*codes),
    }


def computed_response(result: Computed, *, vary_accept: bool = False) -> Response:
    """The body with its media type, ETag and X-Cache (and ``Vary: Accept`` for negotiated answers)."""
    headers = {"ETag": result.etag, "X-Cache": "hit" if result.hit else "miss"}
    if vary_accept:
        headers["Vary"] = "Accept"
    return Response(content=result.body, media_type=result.media_type, headers=headers)


def json_response(result: Computed) -> Response:
    return Response(
        content=result.body,
        media_type="application/json",
        headers={"ETag": result.etag, "X-Cache": "hit" if result.hit else "miss"},
    )


#: request models read by their route itself (off the event loop), published in the spec by reference
READ_BY_ROUTE: list[type] = []
#: answer models a route renders itself under another media type (e.g. GeoJSON), published by reference
ANSWER_MODELS: list[type] = []


def json_body(model: type) -> dict[str, Any]:
    """``openapi_extra`` of a route that reads and validates its JSON body itself (in a worker thread: a large
    body would hold the event loop): the request body is the model's schema, added to the spec's components."""
    READ_BY_ROUTE.append(model)
    ref = {"$ref": f"#/components/schemas/{model.__name__}"}
    return {"requestBody": {"required": True, "content": {"application/json": {"schema": ref}}}}
