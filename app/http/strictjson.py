"""JSON request bodies read strictly, the same on every operation that takes one: the content type, the encoding,
the nesting and the keys.

A pure ASGI middleware (:class:`StrictJsonMiddleware`) in front of the routes whose body is JSON (FastAPI's body
parameter, or a ``requestBody`` of ``application/json`` only, :func:`app.http.bodies.json_body`):

* a body sent with another ``Content-Type`` (``text/plain``, curl's default ``application/x-www-form-urlencoded``)
  is refused 415 naming the type it came with and the one the operation reads (before: a 422 "Input should be a
  valid dictionary" that never said why), and so is a body without one on an operation FastAPI parses (it read such
  a body as bytes: the same 422); the operations that read their body themselves read it as JSON, as before;
* a body FastAPI would parse (the small ones: at most the route's body limit, 64 KiB by default) is parsed here
  first by ``orjson``: a body that is not UTF-8, nested deeper than orjson's 1024 levels or not JSON is a 400
  ``malformed-request`` with orjson's reason and position (``line 1 column 1026 (char 1025)``), where FastAPI said
  "There was an error parsing the body" with no position for the first two;
* an object naming a key twice is refused 400 naming the key (:func:`duplicate_key`): JSON parsers keep the last
  (RFC 8259, section 4: "the names within an object SHOULD be unique"; the behaviour of one that is not is
  unpredictable), so ``{"vehicle": "a", "vehicle": "b"}`` would have answered for b with no word of a.

The routes that read their JSON body themselves (alignments, routes and jobs: up to 256 MiB, parsed a slice at a
time in a worker thread) get the content type checked here and call :func:`refuse_duplicate_keys` on what they
parsed. Cache hits answered from the raw bytes (:mod:`app.http.fastpath`) never reach this: their bytes were
accepted here the first time.
"""

from __future__ import annotations

import json
import re
from collections.abc import Awaitable, Callable, Iterable, MutableMapping
from dataclasses import dataclass
from typing import Any

import orjson
from fastapi.exceptions import RequestValidationError

from app.http.bodylimit import replaying
from app.http.route_table import api_routes

Scope = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[MutableMapping[str, Any]]]
Send = Callable[[MutableMapping[str, Any]], Awaitable[None]]

JSON_TYPE = "application/json"
_BODY_METHODS = {"POST", "PUT", "PATCH"}
#: a nesting level named in the refusal of a body too deep for Python's JSON parser (which FastAPI uses: it stops
#: near the interpreter's recursion limit, 1000 frames, where orjson reads 1024 levels); the deepest request the
#: schemas describe is under 10 levels [-]
MAX_DEPTH = 900


@dataclass(frozen=True)
class JsonRoute:
    """A route whose request body is JSON: its path pattern and methods, and whether FastAPI parses the body
    (``parsed``; False: the route reads it itself)."""

    pattern: re.Pattern[str]
    methods: frozenset[str]
    parsed: bool


def json_routes(routes: Iterable[Any]) -> list[JsonRoute]:
    """The routes of ``routes`` (an app's ``app.routes``) whose request body is JSON: a body parameter, or a
    ``requestBody`` whose only media type is ``application/json``. Upload routes (CSV, XML, multipart) are left
    alone."""
    found = []
    for route in api_routes(routes):
        extra = route.openapi_extra or {}
        content = extra.get("requestBody", {}).get("content", {})
        if route.body_field is not None or list(content) == [JSON_TYPE]:
            methods = frozenset(route.methods or ()) & _BODY_METHODS
            found.append(JsonRoute(route.path_regex, methods, route.body_field is not None))
    return found


def is_json(content_type: str) -> bool:
    """Whether a ``Content-Type`` value is JSON: ``application/json`` or any ``application/...+json`` (RFC 6839),
    parameters (``; charset=utf-8``) aside."""
    media = content_type.split(";", 1)[0].strip().lower()
    return media == JSON_TYPE or (media.startswith("application/") and media.endswith("+json"))


class DuplicateKey(ValueError):
    def __init__(self, key: str) -> None:
        super().__init__(key)
        self.key = key


def _unique_pairs(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise DuplicateKey(key)
        out[key] = value
    return out


def duplicate_key(body: bytes | str) -> str | None:
    """The first key an object of the JSON text ``body`` names twice (in the order the parser closes objects);
    None when every object's keys are unique. ``body`` must be valid JSON (parse it first: this only looks at keys)."""
    try:
        json.loads(body, object_pairs_hook=_unique_pairs)
    except DuplicateKey as exc:
        return exc.key
    return None


def too_deep(body: bytes, limit: int) -> str | None:
    """Where the JSON text ``body`` first nests deeper than ``limit`` arrays and objects, as orjson says a position
    (``line 1 column 990 (char 989)``); None when it never does. A plain walk over the bytes (strings and their
    escapes skipped): only run when a parse has already failed for its depth."""
    depth, line, column, in_string, escaped = 0, 1, 0, False, False
    for i, c in enumerate(body):
        column += 1
        if in_string:
            if escaped:
                escaped = False
            elif c == 0x5C:
                escaped = True
            elif c == 0x22:
                in_string = False
        elif c == 0x22:
            in_string = True
        elif c in (0x5B, 0x7B):
            depth += 1
            if depth > limit:
                return f"line {line} column {column} (char {i})"
        elif c in (0x5D, 0x7D):
            depth -= 1
        elif c == 0x0A:
            line, column = line + 1, 0
    return None


#: bytes (or characters) per call of a count over a body or a long string: a call over a 64 MB document holds the
#: interpreter's lock for tens of milliseconds, and the event loop waits that long
SLICE = 1 << 20


def _count(text: bytes | str, sub: bytes | str) -> int:
    """``text.count(sub)`` a :data:`SLICE` at a time (``sub`` one character: no occurrence spans two slices)."""
    return sum(text.count(sub, k, k + SLICE) for k in range(0, len(text), SLICE))  # type: ignore[arg-type]


def _contains(text: bytes, sub: bytes) -> bool:
    """``sub in text`` a :data:`SLICE` at a time (the slices overlap by ``len(sub) - 1``)."""
    step = SLICE
    return any(text.find(sub, k, k + step + len(sub) - 1) >= 0 for k in range(0, len(text), step))


def _long_strings_left_out(data: Any, depth: int = 0) -> tuple[Any, int]:
    """``data`` with the long strings of its objects (a document sent in a JSON field: ``landxml.document``, ``gpx``,
    ``csv``) replaced by ``""``, and the colons those strings held: ``orjson.dumps`` of the first has, plus the
    second, exactly the colons of ``orjson.dumps(data)``, without writing tens of MB in one call. Only objects are
    looked into (a few levels: where the requests put their documents), not arrays (a list of curves)."""
    if isinstance(data, str):
        return ("", _count(data, ":")) if len(data) > SLICE else (data, 0)
    if isinstance(data, dict) and depth < 4:
        out, colons = {}, 0
        for key, value in data.items():
            out[key], n = _long_strings_left_out(value, depth + 1)
            colons += n
        return out, colons
    return data, 0


def refuse_duplicate_keys(body: bytes, data: Any) -> None:
    """Raise a 400 ``malformed-request`` (a ``json_invalid`` validation error) naming the key when an object of the
    JSON ``body`` names a key twice; ``data`` is what the body parsed to (``orjson.loads``, where the last of two
    wins).

    The colons are counted: every member of an object has one, and a string holds the rest, written as a colon (a
    colon needs no escape) or as the escape ``\\u003a`` (``\\u003A``); ``orjson.dumps(data)`` writes the same
    strings (every colon as a colon) less those of any member a duplicate dropped, and one colon per member left. So
    where the body has neither escape (no colon written as one; ``\\u003c`` for ``<``, as some encoders write every
    ``<`` of an XML document, is not one), the two counts are equal exactly when nothing was dropped: counts
    and a ``dumps``, about 1.5 ms for a megabyte of curves, where walking the parsed objects took 15-20 ms; a long
    string (a document in a field) is counted a slice at a time, not written. Otherwise the body is parsed again to
    find the key (:func:`duplicate_key`)."""
    if not _contains(body, b"\\u003a") and not _contains(body, b"\\u003A"):
        light, colons = _long_strings_left_out(data)
        if _count(body, b":") == orjson.dumps(light).count(b":") + colons:
            return
    key = duplicate_key(body)
    if key is not None:
        raise RequestValidationError([{"type": "json_invalid", "loc": ("body",), "msg": duplicate_message(key)}])


def duplicate_message(key: str) -> str:
    return (
        f"JSON: the key {key!r} appears twice in one object; each key may appear once (RFC 8259 section 4: a "
        f"parser would keep only the last, silently)"
    )


def malformed(body: bytes) -> str | None:
    """Why the JSON ``body`` cannot be read as FastAPI would read it, with a position; None when it can. orjson reads
    first (its reasons name the position for bad UTF-8 and nesting as well); a body only Python's parser reads
    (``NaN``, ``Infinity``) goes on, for the schema to refuse the field by name as before."""
    try:
        orjson.loads(body)
    except orjson.JSONDecodeError as exc:
        try:
            json.loads(body)
        except (ValueError, RecursionError):  # JSONDecodeError, UnicodeDecodeError; deeper than both read
            return f"JSON: {exc}"
    try:
        key = duplicate_key(body)
    except RecursionError:  # orjson reads 1024 levels, Python's parser (FastAPI's) fewer
        return _too_deep(body)
    return None if key is None else duplicate_message(key)


def _too_deep(body: bytes) -> str:
    return f"JSON: nested too deeply to parse (more than {MAX_DEPTH} levels: {too_deep(body, MAX_DEPTH) or 'in it'})"


def _problem(status: int, slug: str, title: str, detail: str, instance: str) -> bytes:
    body = {"type": f"urn:rollover:problem:{slug}", "title": title, "status": status, "detail": detail}
    return orjson.dumps({**body, "instance": instance})


def _header(scope: Scope, name: bytes) -> str | None:
    for key, value in scope["headers"]:
        if key == name:
            return value.decode("latin-1")
    return None


class StrictJsonMiddleware:
    """See the module's doc. ``routes`` is read once, at startup (the route table is complete then)."""

    def __init__(self, app: Callable[[Scope, Receive, Send], Awaitable[None]], routes: Callable[[], list[JsonRoute]]):
        self.app = app
        self._routes = routes
        self.routes: list[JsonRoute] | None = None

    def _route(self, scope: Scope) -> JsonRoute | None:
        if self.routes is None:
            self.routes = self._routes()
        method, path = scope["method"], scope["path"]
        return next((r for r in self.routes if method in r.methods and r.pattern.match(path)), None)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope["method"] not in _BODY_METHODS:
            if scope["type"] == "lifespan" and self.routes is None:
                self.routes = self._routes()
            await self.app(scope, receive, send)
            return
        route = self._route(scope)
        if route is None or _header(scope, b"content-length") == "0":
            await self.app(scope, receive, send)
            return
        content_type = _header(scope, b"content-type")
        if (content_type is None and route.parsed) or (content_type is not None and not is_json(content_type)):
            given = (
                "no Content-Type" if content_type is None else f"Content-Type {content_type.split(';', 1)[0].strip()!r}"
            )
            detail = f"{given}: this operation reads a JSON body; send it with Content-Type: {JSON_TYPE}"
            await self._answer(send, 415, "unsupported-media-type", "Unsupported Media Type", detail, scope["path"])
            return
        if not route.parsed:  # the route parses its (large) body itself, off the event loop
            await self.app(scope, receive, send)
            return
        chunks = []
        while True:
            message = await receive()
            if message["type"] != "http.request":
                return  # the client went away
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        if body:
            detail = malformed(body)
            if detail is not None:
                await self._answer(send, 400, "malformed-request", "Malformed request body", detail, scope["path"])
                return
        await self.app(scope, replaying(body, receive), send)

    @staticmethod
    async def _answer(send: Send, status: int, slug: str, title: str, detail: str, instance: str) -> None:
        body = _problem(status, slug, title, detail, instance)
        headers = [(b"content-type", b"application/problem+json"), (b"content-length", str(len(body)).encode())]
        await send({"type": "http.response.start", "status": status, "headers": headers})
        await send({"type": "http.response.body", "body": body})
