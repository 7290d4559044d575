"""The OpenAPI document as the service publishes it: stable operation ids, every error response as
``application/problem+json``, every request body's limit stated (and its 413 declared), the models of routes that
read their own body, and the optional bearer key of the computations that accept saved vehicles."""

from __future__ import annotations

from typing import Any

from fastapi import FastAPI
from fastapi.routing import APIRoute
from pydantic.json_schema import models_json_schema

from app.http.bodies import READ_BY_ROUTE
from app.http.bodylimit import DEFAULT_LIMIT, EXTENSION, describe_limit
from app.http.problems import PROBLEM_MEDIA_TYPE, error_responses
from app.http.responses import ANSWER_MODELS


def operation_id(route: APIRoute) -> str:
    """Stable operation ids ``<tag>-<route name>`` (e.g. ``srt-compute_srt``) for readable client methods."""
    return f"{route.tags[0]}-{route.name}" if route.tags else route.name


def problem_openapi(app: FastAPI) -> dict[str, Any]:
    """The generated spec with every error response moved to ``application/problem+json``."""
    if app.openapi_schema is not None:
        return app.openapi_schema
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
            if "401" in operation.get("responses", {}) and "security" not in operation:
                # accepts saved vehicles by id: the bearer key is optional (presets and records need none)
                operation["security"] = [{}, {"bearerAuth": []}]
            for code, response in operation.get("responses", {}).items():
                content = response.get("content", {})
                if code.isdigit() and int(code) >= 400 and "application/json" in content:
                    response["content"] = {PROBLEM_MEDIA_TYPE: content["application/json"]}
    app.openapi_schema = schema
    return schema
