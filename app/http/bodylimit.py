"""Request-body size limits per route: an oversized body is refused with 413 before it is read.

A pure ASGI middleware in front of the app: a ``Content-Length`` over the route's limit is answered 413 at once
(nothing of the body is read); a chunked body (no ``Content-Length``) is counted as it streams in and refused as
soon as it passes the limit. Each route declares its limit, sized to the largest request it accepts, with
:func:`body_limit` in its ``openapi_extra`` (``x-body-limit-bytes``); routes without one get
:data:`DEFAULT_LIMIT`. The middleware reads the limits from the routes (:func:`route_limits`); the OpenAPI document
states the same limits in each operation's description and declares the 413 (:func:`spec_limits` reads them back).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Iterable, MutableMapping
from typing import Any

from app.http.route_table import api_routes

KIB, MIB = 1024, 1024 * 1024

#: the default limit: one vehicle record with its case and targets is about 2 KB
DEFAULT_LIMIT = 64 * KIB
#: the OpenAPI extension that carries a route's limit
EXTENSION = "x-body-limit-bytes"


def body_limit(limit: int) -> dict[str, int]:
    """``openapi_extra`` of a route whose body may be larger than :data:`DEFAULT_LIMIT` [bytes]."""
    return {EXTENSION: limit}


def spec_limits(spec: dict[str, Any]) -> dict[str, int]:
    """path -> limit [bytes] of every operation with a body in an OpenAPI document (the declared ``x-body-limit-
    bytes``, else the default): the numbers :func:`route_limits` gives the middleware."""
    return {
        path: op.get(EXTENSION, DEFAULT_LIMIT)
        for path, item in spec.get("paths", {}).items()
        for op in item.values()
        if isinstance(op, dict) and "requestBody" in op
    }


def route_limits(routes: Iterable[Any]) -> dict[str, int]:
    """path -> limit [bytes] of every documented route with a body (an app's ``app.routes``): what
    :func:`spec_limits` reads from the OpenAPI document, read from the routes' own declarations (a body parameter, or
    a ``requestBody`` in ``openapi_extra``; the limit from :func:`body_limit`, else the default)."""
    limits = {}
    for route in api_routes(routes):
        extra = route.openapi_extra or {}
        if route.include_in_schema and (route.body_field is not None or "requestBody" in extra):
            limits[route.path_format] = extra.get(EXTENSION, DEFAULT_LIMIT)
    return limits


def describe_limit(limit: int) -> str:
    if limit >= MIB:
        return f"{limit / MIB:g} MiB ({limit} bytes)"
    return f"{limit / KIB:g} KiB ({limit} bytes)"


def too_large(limit: int) -> str:
    return f"the request body exceeds this operation's limit of {describe_limit(limit)}"


Scope = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[MutableMapping[str, Any]]]
Send = Callable[[MutableMapping[str, Any]], Awaitable[None]]


def replaying(body: bytes, receive: Receive) -> Receive:
    """A ``receive`` for the app behind a middleware that has read the whole body: the body once, as one message,
    then the server's own ``receive`` (a disconnect, or what follows the request)."""
    replayed = False

    async def replay() -> MutableMapping[str, Any]:
        nonlocal replayed
        if not replayed:
            replayed = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replay


class BodyLimitMiddleware:
    """Refuse a body over its route's limit: at once from ``Content-Length``, or as soon as a chunked body passes
    it (a chunked body is read here, never more than the limit, and handed to the app whole)."""

    def __init__(
        self, app: Callable[[Scope, Receive, Send], Awaitable[None]], limits: Callable[[], dict[str, int]], problem
    ) -> None:
        self.app = app
        self._limits = limits  # () -> {path: bytes}, read once; any other path gets DEFAULT_LIMIT
        self.limits: dict[str, int] | None = None
        self.problem = problem  # (status, detail, instance) -> problem+json bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            if scope["type"] == "lifespan" and self.limits is None:
                # read at startup, not in the first request: the route table is expanded then (FastAPI builds an
                # included router's routes lazily, some 75 ms for this app; the first request would pay it)
                self.limits = self._limits()
            await self.app(scope, receive, send)
            return
        if self.limits is None:
            self.limits = self._limits()
        limit = self.limits.get(scope["path"], DEFAULT_LIMIT)
        declared = next((v for k, v in scope["headers"] if k == b"content-length"), None)
        if declared is not None:
            if not declared.isdigit() or int(declared) > limit:
                await self._refuse(scope, send, limit)
                return
            await self.app(scope, receive, send)  # the server delivers no more than the declared length
            return
        # chunked: read it here, bounded by the limit, then hand the app the whole body
        chunks, size = [], 0
        while True:
            message = await receive()
            if message["type"] != "http.request":  # the client went away
                return
            size += len(message.get("body", b""))
            if size > limit:
                await self._refuse(scope, send, limit)
                return
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                break
        await self.app(scope, replaying(b"".join(chunks), receive), send)

    async def _refuse(self, scope: Scope, send: Send, limit: int) -> None:
        body = self.problem(413, too_large(limit), scope["path"])
        await send(
            {
                "type": "http.response.start",
                "status": 413,
                "headers": [
                    (b"content-type", b"application/problem+json"),
                    (b"content-length", str(len(body)).encode()),
                    (b"connection", b"close"),
                ],
            }
        )
        await send({"type": "http.response.body", "body": body})
