"""What the middlewares and handlers read from the route table agrees with the published document and with the
services: the replayable routes are the computed POST operations, each one's declared cache operation is the one its
ETag names in every form it negotiates, the body limits and the documented paths are the document's; the document
itself is built on first use, once per process."""

from __future__ import annotations

import orjson
import pytest

from app.http.bodylimit import route_limits, spec_limits
from app.http.fastpath import replay_table
from app.http.openapi import build_document
from app.http.route_table import documented_paths
from app.main import create_app
from app.settings import Settings

APP = create_app()
SPEC = APP.openapi()
TABLE = replay_table(APP.routes)
ACCEPT = {"": "application/json", "json": "application/json", "csv": "text/csv", "geojson": "application/geo+json"}


def computed_posts(spec: dict) -> set[str]:
    """The POST operations whose 200 answer declares the cache's ETag."""
    return {
        path
        for path, item in spec["paths"].items()
        if "ETag" in item.get("post", {}).get("responses", {}).get("200", {}).get("headers", {})
    }


def test_the_replayable_routes_are_the_computed_operations():
    assert set(TABLE) == computed_posts(SPEC)


def example_request(path: str) -> tuple[str, bytes, str]:
    """(url, body, content type) of the operation's published example."""
    content = SPEC["paths"][path]["post"]["requestBody"]["content"]
    media, body = next(iter(content.items()))
    if "example" in body:  # a raw upload: the file, the preset (and a document's superelevation) in the query
        documents = ("application/xml", "application/x-step", "application/gpx+xml", "application/geo+json")
        query = "vehicle=table16-btrain" + ("&superelevation_percent=6" if media in documents else "")
        return f"{path}?{query}", body["example"].encode(), media
    name = body["schema"]["$ref"].rsplit("/", 1)[1]
    return path, orjson.dumps(SPEC["components"]["schemas"][name]["examples"][0]), media


@pytest.mark.parametrize(("path", "form"), [(p, f) for p, r in sorted(TABLE.items()) for f in (r.offers or ("",))])
def test_each_declared_operation_is_the_one_its_etag_names(client, path, form):
    url, body, media = example_request(path)
    r = client.post(url, content=body, headers={"content-type": media, "accept": ACCEPT[form]})
    assert r.status_code == 200, r.text
    assert r.headers["etag"].strip('"').split(":")[1] == TABLE[path].operation_of(form)


def test_the_body_limits_of_the_routes_are_the_documents():
    assert route_limits(APP.routes) == spec_limits(SPEC)


def test_the_documented_paths_of_the_routes_are_the_documents():
    methods = {"get", "put", "post", "delete", "patch", "head", "options", "trace"}
    assert documented_paths(APP.routes) == {
        path: {m.upper() for m in item if m in methods} for path, item in SPEC["paths"].items()
    }


@pytest.mark.slow
def test_the_document_is_built_on_first_use_and_once_per_process():
    from fastapi.testclient import TestClient

    fresh = create_app(Settings(cache_backend="memory", metrics=False))
    with TestClient(fresh) as client:
        assert client.get("/healthz").status_code == 200
        assert fresh.openapi_schema is None  # started and answering without it
        assert client.get("/openapi.json").json() == SPEC
    assert fresh.openapi_schema is SPEC  # the same settings-independent document: built once, shared
    assert build_document(create_app()) == SPEC  # and building it again gives the same


def test_the_middlewares_read_their_tables_at_startup_not_in_the_first_request():
    """The lifespan reaches each middleware before any request: the body limits and the replay table are read then
    (the route table's expansion, some 75 ms, is not the first request's)."""
    from fastapi.testclient import TestClient

    from app.http.bodylimit import BodyLimitMiddleware
    from app.http.fastpath import FastPathMiddleware

    with TestClient(create_app(Settings(cache_backend="memory"))) as c:
        layers, node = {}, c.app.middleware_stack
        while node is not None:
            layers[type(node)] = node
            node = getattr(node, "app", None)
        assert layers[BodyLimitMiddleware].limits == route_limits(c.app.routes)
        assert layers[FastPathMiddleware].routes is not None and set(layers[FastPathMiddleware].routes) == set(TABLE)
