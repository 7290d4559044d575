"""Pieces shared by the routers: the computed-response headers and their OpenAPI declaration."""

from __future__ import annotations

from typing import Any

from fastapi import Response

from ..problems import error_responses
from ..service import Computed

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


def computed_responses(*codes: int) -> dict[int | str, dict[str, Any]]:
    return {200: {"headers": CACHE_HEADERS}, **error_responses(*codes)}


def json_response(result: Computed) -> Response:
    return Response(
        content=result.body,
        media_type="application/json",
        headers={"ETag": result.etag, "X-Cache": "hit" if result.hit else "miss"},
    )
