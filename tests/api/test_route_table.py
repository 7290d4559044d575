"""What the middlewares read from the route table agrees with the published document and with the services: the
replayable routes are the computed POST operations, and each one's declared cache operation is the one its ETag
names in every form it negotiates."""

from __future__ import annotations

import orjson
import pytest

from app.http.fastpath import replay_table
from app.main import create_app

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
    if "example" in body:  # a raw upload: the file, the preset (and a LandXML's superelevation) in the query
        query = "vehicle=table16-btrain" + ("&superelevation_percent=6" if media == "application/xml" else "")
        return f"{path}?{query}", body["example"].encode(), media
    name = body["schema"]["$ref"].rsplit("/", 1)[1]
    return path, orjson.dumps(SPEC["components"]["schemas"][name]["examples"][0]), media


@pytest.mark.parametrize(("path", "form"), [(p, f) for p, r in sorted(TABLE.items()) for f in (r.offers or ("",))])
def test_each_declared_operation_is_the_one_its_etag_names(client, path, form):
    url, body, media = example_request(path)
    r = client.post(url, content=body, headers={"content-type": media, "accept": ACCEPT[form]})
    assert r.status_code == 200, r.text
    assert r.headers["etag"].strip('"').split(":")[1] == TABLE[path].operation_of(form)
