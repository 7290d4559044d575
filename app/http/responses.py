"""A computed answer as an HTTP response (its body with its ETag and X-Cache) and its OpenAPI declaration."""

from __future__ import annotations

from typing import Any

from fastapi import Response

from app.compute.results import Computed
from app.http.problems import error_responses

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


#: answer models a route renders itself under another media type (e.g. GeoJSON), published by reference
ANSWER_MODELS: list[type] = []


def table_answer(result: Computed) -> Response:
    """A table's answer (JSON or CSV by ``Accept``, so ``Vary: Accept``): the body with its headers."""
    return computed_response(result, vary_accept=True)
