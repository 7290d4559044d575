"""The OpenAPI document as the service publishes it: stable operation ids, every error response as
``application/problem+json``, every request body's limit stated (and its 413 declared), the models of routes that
read their own body, and the optional bearer key of the computations that accept saved vehicles.

The document is built when it is first asked for (``GET /openapi.json``, which ``/docs`` and ``/redoc`` load, or
``app.openapi()``), not at start-up: nothing else reads it (the body limits, the fast path and the catalog's ``Allow``
read the route table, :mod:`app.http.route_table`). Building it takes about a second, so it is built once per process
for every app whose document would be the same (:func:`document_key`: the metadata and the route table; no setting
changes either today) and shared by them, read-only.
"""

from __future__ import annotations

import threading
from typing import Any

import orjson
from fastapi import FastAPI
from fastapi.routing import APIRoute
from pydantic.json_schema import models_json_schema

from app.http.bodies import READ_BY_ROUTE
from app.http.bodylimit import DEFAULT_LIMIT, EXTENSION, describe_limit
from app.http.problems import PROBLEM_MEDIA_TYPE, error_responses
from app.http.responses import ANSWER_MODELS
from app.http.route_table import api_routes


def operation_id(route: APIRoute) -> str:
    """Stable operation ids ``<tag>-<route name>`` (e.g. ``srt-compute_srt``) for readable client methods."""
    return f"{route.tags[0]}-{route.name}" if route.tags else route.name


#: the documents built in this process, by :func:`document_key` (a test session makes about a hundred apps)
_DOCUMENTS: dict[tuple[Any, ...], dict[str, Any]] = {}
_BUILDING = threading.Lock()


def document_key(app: FastAPI) -> tuple[Any, ...]:
    """What the app's document is built from: its metadata, its documented routes (path, methods, operation id and the
    endpoint: the route's declaration is the endpoint's decorator, made once per process) and the models published by
    reference. Two apps with equal keys have equal documents."""
    metadata = orjson.dumps(
        [app.title, app.version, app.summary, app.description, app.openapi_tags, app.servers, app.openapi_version],
        option=orjson.OPT_SORT_KEYS,
    )
    routes = tuple(
        (r.path_format, tuple(sorted(r.methods or ())), r.unique_id, r.endpoint)
        for r in api_routes(app.routes)
        if r.include_in_schema  # the others (the page, the docs pages: made per app) are not in it
    )
    return metadata, routes, tuple(READ_BY_ROUTE), tuple(ANSWER_MODELS)


def problem_openapi(app: FastAPI) -> dict[str, Any]:
    """The app's document (:func:`build_document`), built once per process for every app with the same
    :func:`document_key`. Shared: never change the dict it returns."""
    if app.openapi_schema is None:
        key = document_key(app)
        with _BUILDING:  # two first requests at once build it once
            document = _DOCUMENTS.get(key)
            if document is None:
                document = _DOCUMENTS[key] = build_document(app)
        app.openapi_schema = document
    return app.openapi_schema


def build_document(app: FastAPI) -> dict[str, Any]:
    """The generated spec with every error response moved to ``application/problem+json``."""
    schema = FastAPI.openapi(app)
    # the models of routes that read their body themselves (app.http.bodies.json_body), with what they use
    _, defs = models_json_schema(
        [(m, "validation") for m in READ_BY_ROUTE] + [(m, "serialization") for m in ANSWER_MODELS],
        ref_template="#/components/schemas/{model}",
    )
    components = schema.setdefault("components", {}).setdefault("schemas", {})
    for name, definition in defs.get("$defs", {}).items():
        components.setdefault(name, definition)
    for path_item in schema.get("paths", {}).values():
        for operation in path_item.values():
            if "requestBody" in operation:  # every body has a limit: state it, and declare the 413
                limit = operation.setdefault(EXTENSION, DEFAULT_LIMIT)
                text = f"Body limit: {describe_limit(limit)}; a larger body is refused with 413 before it is read."
                operation["description"] = f"{operation.get('description', '').rstrip()}\n\n{text}".lstrip()
                operation["responses"].setdefault(
                    "413",
                    {
                        "description": error_responses(413)[413]["description"],
                        "content": {"application/json": {"schema": {"$ref": "#/components/schemas/Problem"}}},
                    },
                )
            if list(operation.get("requestBody", {}).get("content", {})) == ["application/json"]:
                # app.http.strictjson: another content type is a 415 (FastAPI's own body parameter or not)
                operation["responses"].setdefault(
                    "415",
                    {
                        "description": error_responses(415)[415]["description"],
                        "content": {"application/json": {"schema": {"$ref": "#/components/schemas/Problem"}}},
                    },
                )
            if "401" in operation.get("responses", {}) and "security" not in operation:
                # accepts saved vehicles by id: the bearer key is optional (presets and records need none)
                operation["security"] = [{}, {"bearerAuth": []}]
            operation.setdefault("security", [])  # public: no key is read (said, not left to a default)
            _require_headers(operation)
            for code, response in operation.get("responses", {}).items():
                content = response.get("content", {})
                if code.isdigit() and int(code) >= 400 and "application/json" in content:
                    response["content"] = {PROBLEM_MEDIA_TYPE: content["application/json"]}
    schema["servers"] = SERVERS
    return schema


#: the document's servers: the service itself, wherever it is deployed (a relative URL: the paths are relative to
#: where the document is served; OpenAPI 3.1, section 4.8.5)
SERVERS = [{"url": "/", "description": "This service: the paths are relative to the host that serves this document."}]
#: ``openapi_extra`` of a route whose header parameters the server requires although the handler reads them itself
#: (to answer 428, not FastAPI's 422): ``{REQUIRED_HEADERS: ["If-Match"]}``
REQUIRED_HEADERS = "x-required-headers"


def required_headers(*names: str) -> dict[str, list[str]]:
    """``openapi_extra`` declaring ``names`` as required header parameters in the document (the handler answers
    their absence itself: ``If-Match`` missing on a change is a 428)."""
    return {REQUIRED_HEADERS: list(names)}


def _require_headers(operation: dict[str, Any]) -> None:
    names = {n.lower() for n in operation.pop(REQUIRED_HEADERS, ())}
    for parameter in operation.get("parameters", ()):
        if parameter.get("in") == "header" and parameter.get("name", "").lower() in names:
            parameter["required"] = True
            parameter["schema"] = {"type": "string", "minLength": 1, "title": parameter["name"]}
