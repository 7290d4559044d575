"""The cache-hit fast path: an answer already known for the same request bytes is sent before any model is built.

A pure ASGI middleware in front of FastAPI, for the routes that opt in where they are defined (:func:`replayable` on
the endpoint: a computed POST whose answer is the cache's body for its ``ETag``). It keys the *raw* request (path,
query string, content type, the negotiated representation, body bytes) to the canonical cache key (the ``ETag``)
that the full path derived from it last time. When that key's body is still in the in-process cache, the answer
goes out at once: no routing, no JSON parsing, no validation, no thread hop. Otherwise the request goes through the
app as usual and, if its answer carries an ``ETag`` whose body the in-process cache now holds, the raw key is
remembered for next time.

A request with credentials (an ``Authorization`` header) is never answered from here nor remembered: it may name a
saved vehicle or a fleet, which its owner may edit and no other key may read, so the same bytes may mean another
record tomorrow or be refused to another caller. Its canonical key is derived again each time, from the record as
it is now (the full path still answers it from the cache). Nothing downstream has to say so: an answer that depends
on who asks cannot be computed without that header.

``If-None-Match`` with the current ``ETag`` is answered ``304 Not Modified`` (no body), on either path.
"""

from __future__ import annotations

import hashlib
from collections.abc import Awaitable, Callable, Iterable, MutableMapping
from dataclasses import dataclass
from typing import Any

from cachetools import LRUCache
from starlette.concurrency import run_in_threadpool

from app.compute import cache as cache_module
from app.http.bodylimit import replaying
from app.http.negotiation import negotiate
from app.http.route_table import api_routes
from app.metrics import CACHE_LOOKUPS, FAST_PATH_HITS

#: the form part of a raw key: one key per form a route negotiates
_FORM_KEYS = {"": b"", "json": b"", "csv": b"csv", "geojson": b"geojson"}

#: raw request -> canonical key remembered per process (a few hundred bytes each)
RAW_INDEX_ENTRIES = 65_536
#: bodies at least this long are hashed in a worker thread, not on the event loop [bytes]
HASH_IN_THREAD_BYTES = 256 * 1024

Scope = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[MutableMapping[str, Any]]]
Send = Callable[[MutableMapping[str, Any]], Awaitable[None]]


def _raw_key(head: tuple[bytes, ...], body: bytes) -> bytes:
    """BLAKE2b of the request's parts and body, separated by NUL bytes (the body is not copied to be hashed)."""
    h = hashlib.blake2b()
    for part in head:
        h.update(part)
        h.update(b"\0")
    h.update(body)
    return h.digest()


def _header(scope: Scope, name: bytes) -> bytes | None:
    for key, value in scope["headers"]:
        if key == name:
            return value
    return None


#: the attribute :func:`replayable` sets on a route's endpoint
REPLAY_ATTRIBUTE = "rollover_replay"


@dataclass(frozen=True)
class Replay:
    """A route's opt-in to the fast path (:func:`replayable`): the cache operation of its answer and the forms it
    negotiates from ``Accept`` (none: its answer has one form)."""

    operation: str
    offers: tuple[str, ...] = ()

    def form(self, accept: str) -> str:
        """The form of the answer to ``accept``, as the route itself negotiates it ("" for a route of one form)."""
        return negotiate(accept, self.offers) if self.offers else ""

    def operation_of(self, form: str) -> str:
        """The cache operation of the answer in ``form``: ``<operation>`` for JSON (or the one form), else
        ``<operation>-<form>`` (``alignments-csv``, ``route-geojson``), as the services name their keys."""
        return self.operation if form in ("", "json") else f"{self.operation}-{form}"


def replayable(operation: str, *, offers: tuple[str, ...] = ()) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Declare, on a computed POST route's endpoint, that a repeated request may be answered from its raw bytes: its
    200 answer is the result cache's body for its ``ETag`` (cached as ``operation``, see :meth:`Replay.operation_of`)
    and depends on the request's path, query, content type, ``Accept`` (negotiated among ``offers``, e.g.
    :data:`~app.http.negotiation.TABLE_FORMS`) and body alone (what depends on the caller's identity is never
    replayed, see the module). Routes without it always go through the app."""

    def declare(endpoint: Callable[..., Any]) -> Callable[..., Any]:
        setattr(endpoint, REPLAY_ATTRIBUTE, Replay(operation, tuple(offers)))
        return endpoint

    return declare


def replay_table(routes: Iterable[Any]) -> dict[str, Replay]:
    """path -> :class:`Replay` of the routes (an app's ``app.routes``) whose endpoint is :func:`replayable` (fixed
    POST paths: the raw key has no template)."""
    table = {}
    for route in api_routes(routes):
        replay = getattr(route.endpoint, REPLAY_ATTRIBUTE, None)
        if replay is None:
            continue
        if "POST" not in (route.methods or ()) or "{" in route.path:
            raise ValueError(f"{route.path}: only a fixed POST path can be replayed from its raw bytes")
        table[route.path] = replay
    return table


def etag_matches(if_none_match: bytes | None, etag: bytes) -> bool:
    """RFC 9110 weak comparison of If-None-Match against an entity tag (``*`` matches any)."""
    if not if_none_match:
        return False
    tags = [t.strip() for t in if_none_match.split(b",")]
    bare = etag.removeprefix(b"W/")
    return any(t == b"*" or t.removeprefix(b"W/") == bare for t in tags)


class FastPathMiddleware:
    """Answer a repeated computed request from the in-process cache before the app sees it."""

    def __init__(self, app, *, routes: Callable[[], dict[str, Replay]], cache: Callable[[], Any]) -> None:
        self.app = app
        self._routes = routes  # () -> path -> Replay of the replayable routes (read once, from the route table)
        self.routes: dict[str, Replay] | None = None
        self.cache = cache  # () -> the app's ResultCache (opened in the lifespan)
        self.index: LRUCache = LRUCache(maxsize=RAW_INDEX_ENTRIES)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] != "POST":
            if scope["type"] == "lifespan" and self.routes is None:
                self.routes = self._routes()  # at startup, not in the first request (see BodyLimitMiddleware)
            await self.app(scope, receive, send)
            return
        if self.routes is None:
            self.routes = self._routes()
        declared = self.routes.get(scope["path"])
        if declared is None:
            await self.app(scope, receive, send)
            return
        body = await _read_body(receive)
        if body is None:  # the client went away
            return
        inm = _header(scope, b"if-none-match")
        if _header(scope, b"authorization") is not None:  # may depend on who asks: never replayed (see the module)
            await self._through_app(scope, body, None, inm, receive, send)
            return
        accept = (_header(scope, b"accept") or b"").decode("latin-1")
        form = declared.form(accept)
        head = (
            cache_module.ENGINE_VERSION.encode(),  # part of every key (read here so a test's change is seen)
            scope["path"].encode(),
            scope.get("query_string", b""),
            _header(scope, b"content-type") or b"",
            _FORM_KEYS[form],  # every negotiated form has its own key
        )
        if len(body) < HASH_IN_THREAD_BYTES:
            raw_key = _raw_key(head, body)
        else:  # hashlib lets go of the GIL: in a thread, a 12 MB body's 25 ms are not the event loop's
            raw_key = await run_in_threadpool(_raw_key, head, body)
        known = self.index.get(raw_key)
        cache = self.cache()
        if known is not None and cache is not None:
            key, media_type, vary = known
            cached = cache.local.get(key)
            if cached is not None:
                FAST_PATH_HITS.inc()
                CACHE_LOOKUPS.labels(declared.operation_of(form), "local").inc()  # from the route table
                await _answer(send, cached, key, media_type, vary, not_modified=etag_matches(inm, f'"{key}"'.encode()))
                return
        await self._through_app(scope, body, raw_key, inm, receive, send)

    async def _through_app(self, scope: Scope, body: bytes, raw_key: bytes | None, inm, receive: Receive, send: Send):
        replay = replaying(body, receive)

        state: dict[str, Any] = {"not_modified": False}

        async def watch(message: MutableMapping[str, Any]) -> None:
            if message["type"] == "http.response.start":
                headers = dict(message.get("headers") or [])
                etag = headers.get(b"etag")
                if message["status"] == 200 and etag is not None:
                    key = etag.strip(b'"').decode()
                    cache = self.cache()
                    if raw_key is not None and cache is not None and key in cache.local:  # what can be replayed
                        media = headers.get(b"content-type", b"application/json").decode()
                        self.index[raw_key] = (key, media, b"vary" in headers)
                    if etag_matches(inm, etag):
                        state["not_modified"] = True
                        kept = [(k, v) for k, v in message["headers"] if k in (b"etag", b"x-cache", b"vary")]
                        message = {"type": "http.response.start", "status": 304, "headers": kept}
            elif message["type"] == "http.response.body" and state["not_modified"]:
                if message.get("more_body"):
                    return  # drop the body of a 304
                message = {"type": "http.response.body", "body": b""}
            await send(message)

        await self.app(scope, replay, watch)


async def _read_body(receive: Receive) -> bytes | None:
    chunks = []
    while True:
        message = await receive()
        if message["type"] != "http.request":
            return None
        chunks.append(message.get("body", b""))
        if not message.get("more_body", False):
            return b"".join(chunks)


async def _answer(send: Send, body: bytes, key: str, media_type: str, vary: bool, *, not_modified: bool) -> None:
    headers = [(b"etag", f'"{key}"'.encode()), (b"x-cache", b"hit")]
    if vary:
        headers.append((b"vary", b"Accept"))
    if not_modified:
        await send({"type": "http.response.start", "status": 304, "headers": headers})
        await send({"type": "http.response.body", "body": b""})
        return
    headers += [(b"content-type", media_type.encode()), (b"content-length", str(len(body)).encode())]
    await send({"type": "http.response.start", "status": 200, "headers": headers})
    await send({"type": "http.response.body", "body": body})
