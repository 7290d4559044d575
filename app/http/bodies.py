"""Request bodies a route reads itself, declared in its ``openapi_extra``: a JSON body validated off the event loop
(:func:`json_body`) and an uploaded file (:func:`upload_body`: the body itself, or the part ``file`` of a
``multipart/form-data`` body). Each route's body limit (:mod:`app.http.bodylimit`) is
declared with it."""

from __future__ import annotations

from typing import Any

from app.http.bodylimit import body_limit

#: request models read by their route itself (off the event loop), published in the spec by reference
READ_BY_ROUTE: list[type] = []


def json_body(model: type) -> dict[str, Any]:
    """``openapi_extra`` of a route that reads and validates its JSON body itself (in a worker thread: a large
    body would hold the event loop): the request body is the model's schema, added to the spec's components."""
    READ_BY_ROUTE.append(model)
    ref = {"$ref": f"#/components/schemas/{model.__name__}"}
    return {"requestBody": {"required": True, "content": {"application/json": {"schema": ref}}}}


def upload_body(media_type: str, limit: int, example: str | None = None, what: str = "file") -> dict[str, Any]:
    """OpenAPI ``requestBody`` of an upload operation (the route reads the body itself), with its body limit: the
    file as the body (``media_type``), or as the part ``file`` of a ``multipart/form-data`` body (``curl -F
    file=@...``). The limit applies to the whole request either way."""
    content: dict[str, Any] = {"schema": {"type": "string", "minLength": 1}}
    if example is not None:
        content["example"] = example
    form = {
        "schema": {
            "type": "object",
            "required": ["file"],
            "properties": {
                "file": {
                    "type": "string",
                    "contentMediaType": media_type,
                    "description": f"The {what} (its bytes, as a file part: `curl -F file=@...`).",
                }
            },
            "additionalProperties": False,
        },
        "encoding": {"file": {"contentType": f"{media_type}, application/octet-stream, text/plain"}},
    }
    return {
        "requestBody": {"required": True, "content": {media_type: content, "multipart/form-data": form}},
        **body_limit(limit),
    }
