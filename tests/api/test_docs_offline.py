"""The interactive API docs load everything from the service itself: no CDN, so they work offline."""

from __future__ import annotations

import re

import pytest


@pytest.mark.parametrize("page", ["/docs", "/redoc"])
def test_the_docs_pages_reference_only_the_services_own_assets(shared_client, page):
    r = shared_client.get(page)
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    urls = re.findall(r"""(?:src|href|url)\s*[=:]\s*['"]([^'"]+)['"]""", r.text)
    assert urls, r.text
    for url in urls:
        assert not re.match(r"^(https?:)?//", url), f"{page} loads {url} from another host"
    # every asset the page names is served, and is the real thing (not an empty placeholder)
    for url in urls:
        if url.startswith("/static-offline-docs/"):
            asset = shared_client.get(url)
            assert asset.status_code == 200 and len(asset.content) > 1000, url
    assert any(u.endswith(".js") for u in urls)


def test_the_spec_the_docs_load_is_the_apps(shared_client):
    page = shared_client.get("/docs").text
    assert "/openapi.json" in page
    assert shared_client.get("/openapi.json").json()["info"]["title"] == "rollover"
