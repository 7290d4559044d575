"""The shared Redis tier against a real redis-server (started by the ``redis_server`` fixture).

The fixture skips when the binary is missing on a developer machine and fails under CI (``CI`` set), where
``.ci/run`` installs redis-server with apt-get.
"""

from __future__ import annotations

import orjson
import pytest
from structlog.testing import capture_logs

from app.cache import REDIS_PREFIX
from app.settings import Settings

from .conftest import free_port, make_client

pytestmark = pytest.mark.redis

BODY = {"vehicle": "table16-btrain", "model": "gillespie"}


def redis_settings(url: str, **kw) -> Settings:
    return Settings(cache_backend="redis", redis_url=url, **kw)


def test_two_app_instances_share_results_through_redis(redis_server):
    settings = redis_settings(redis_server.url)
    with make_client(settings) as a, make_client(settings) as b:
        first = a.post("/v1/srt", json=BODY)
        assert first.status_code == 200 and first.headers["x-cache"] == "miss"
        # b has never computed it: its local LRU is empty, the hit comes from Redis
        second = b.post("/v1/srt", json=BODY)
        assert second.headers["x-cache"] == "hit"
        assert second.headers["etag"] == first.headers["etag"]
        assert second.content == first.content
        assert b.get("/healthz").json()["redis"] == "ok"


def test_values_are_stored_as_json_bytes_never_pickle(redis_server):
    with make_client(redis_settings(redis_server.url, redis_ttl_seconds=3600)) as c:
        r = c.post("/v1/srt", json=BODY)
    key = REDIS_PREFIX + r.headers["etag"].strip('"')
    raw = redis_server.client().get(key)
    assert raw is not None
    assert not raw.startswith(b"\x80")  # pickle protocol 2+ header
    assert raw == r.content  # exactly the response body
    assert orjson.loads(raw)["srt"] == r.json()["srt"]
    ttl = redis_server.client().ttl(key)
    assert 0 < ttl <= 3600


def test_unreachable_redis_keeps_the_service_answering_and_is_logged_once():
    # nothing listens on this port
    settings = redis_settings(f"redis://127.0.0.1:{free_port()}/0", redis_retry_seconds=0)
    with capture_logs() as logs, make_client(settings) as c:
        statuses = []
        for body in (BODY, BODY, {**BODY, "model": "navin"}):
            r = c.post("/v1/srt", json=body)
            statuses.append((r.status_code, r.headers["x-cache"]))
        health = c.get("/healthz").json()
    assert statuses == [(200, "miss"), (200, "hit"), (200, "miss")]  # the local LRU still serves
    assert health["status"] == "ok" and health["redis"] == "unavailable"
    assert [e["event"] for e in logs].count("redis_unavailable") == 1


def test_redis_going_down_and_coming_back(redis_server):
    settings = redis_settings(redis_server.url, redis_retry_seconds=0)
    with capture_logs() as logs, make_client(settings) as c:
        assert c.post("/v1/srt", json=BODY).headers["x-cache"] == "miss"
        port = redis_server.port
        redis_server.stop()
        r = c.post("/v1/srt", json={**BODY, "model": "navin"})
        assert r.status_code == 200 and r.headers["x-cache"] == "miss"
        assert c.post("/v1/srt", json=BODY).headers["x-cache"] == "hit"  # from the local tier
        from .conftest import RedisServer, _redis_binary

        again = RedisServer(_redis_binary(), port)
        try:
            r = c.post("/v1/srt", json={**BODY, "model": "winkler"})
            assert r.status_code == 200
            assert again.client().get(REDIS_PREFIX + r.headers["etag"].strip('"')) == r.content
        finally:
            again.stop()
    events = [e["event"] for e in logs]
    assert events.count("redis_unavailable") == 1 and events.count("redis_recovered") == 1
