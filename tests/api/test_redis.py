"""The shared Redis tier against a real redis-server (started by the ``redis_server`` fixture).

The fixture skips when the binary is missing on a developer machine and fails under CI (``CI`` set), where
``.ci/run`` installs redis-server with apt-get.
"""

from __future__ import annotations

import hashlib
import hmac

import orjson
import pytest
from structlog.testing import capture_logs

from app.compute.cache import REDIS_PREFIX, seal
from app.settings import Settings

from .conftest import free_port, make_client

pytestmark = pytest.mark.redis

BODY = {"vehicle": "table16-btrain", "model": "gillespie"}


SECRET = "a-deployment-secret-for-the-tests"


def redis_settings(url: str, **kw) -> Settings:
    return Settings(cache_backend="redis", redis_url=url, cache_secret=SECRET, **kw)


def sealed_body(raw: bytes, key: str) -> bytes:
    """The body inside a Redis value, checked independently of app.compute.cache: magic, HMAC-SHA256 with the deployment
    secret over key NUL media type NUL body, media type, NUL, body."""
    assert raw.startswith(b"ROLLOVER1")
    mac, rest = raw[9:41], raw[41:]
    media, _, body = rest.partition(b"\0")
    expected = hmac.new(SECRET.encode(), b"\0".join((key.encode(), media, body)), hashlib.sha256).digest()
    assert hmac.compare_digest(mac, expected)
    return body


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


def test_values_are_sealed_json_bytes_never_pickle(redis_server):
    with make_client(redis_settings(redis_server.url, redis_ttl_seconds=3600)) as c:
        r = c.post("/v1/srt", json=BODY)
    etag = r.headers["etag"].strip('"')
    raw = redis_server.client().get(REDIS_PREFIX + etag)
    assert raw is not None
    assert not raw.startswith(b"\x80")  # pickle protocol 2+ header
    assert sealed_body(raw, etag) == r.content  # exactly the response body, under an HMAC of the key
    assert orjson.loads(sealed_body(raw, etag))["srt"] == r.json()["srt"]
    ttl = redis_server.client().ttl(REDIS_PREFIX + etag)
    assert 0 < ttl <= 3600


@pytest.mark.parametrize(
    "poison",
    [
        b"GARBAGE<script>alert(1)</script>",  # not an envelope at all
        b"ROLLOVER1" + b"\0" * 32 + b"application/json\0" + b'{"srt": 9.99}',  # an envelope with a forged MAC
        "sealed-with-another-secret",
        "truncated",
    ],
)
def test_a_poisoned_entry_is_never_served_and_is_replaced(redis_server, poison):
    """Whatever sits in Redis under a key the service reads is served only if it carries this deployment's HMAC
    of that key and body: otherwise it is logged once with its key, dropped, recomputed and rewritten."""
    settings = redis_settings(redis_server.url)
    with make_client(settings) as a:
        good = a.post("/v1/srt", json=BODY)
    etag = good.headers["etag"].strip('"')
    r = redis_server.client()
    if poison == "sealed-with-another-secret":
        poison = seal(b"another deployment's secret", etag, "application/json", b'{"srt": 9.99}')
    elif poison == "truncated":
        poison = r.get(REDIS_PREFIX + etag)[:-5]
    r.set(REDIS_PREFIX + etag, poison)
    with capture_logs() as logs, make_client(settings) as b:  # a fresh worker: its local tier is empty
        served = [b.post("/v1/srt", json=BODY) for _ in range(2)]
    assert served[0].status_code == 200 and served[0].headers["x-cache"] == "miss"
    assert served[0].content == good.content
    assert served[1].headers["x-cache"] == "hit" and served[1].content == good.content  # from the local tier
    rejected = [e for e in logs if e["event"] == "cache_entry_rejected"]
    assert len(rejected) == 1 and rejected[0]["key"] == REDIS_PREFIX + etag
    assert sealed_body(r.get(REDIS_PREFIX + etag), etag) == good.content  # rewritten


@pytest.mark.parametrize("path", ["/v1/curve-speed", "/v1/min-radius"])
def test_a_poisoned_inner_srt_key_cannot_break_the_road_endpoints(redis_server, path):
    body = (
        {"radius_m": 80, "vehicle": "table16-btrain"}
        if path == "/v1/curve-speed"
        else {"design_speed_kmh": 60, "superelevation_percent": 0, "vehicle": "table16-btrain"}
    )
    settings = redis_settings(redis_server.url)
    r = redis_server.client()
    with make_client(settings) as a:
        good = a.post(path, json=body)
        inner = a.post("/v1/srt", json={"vehicle": "table16-btrain"})
    for key in r.keys(REDIS_PREFIX + "*"):
        r.set(key, b"GARBAGE")
    with make_client(settings) as b:
        again = b.post(path, json=body)
        srt = b.post("/v1/srt", json={"vehicle": "table16-btrain"})
    assert again.status_code == 200 and again.content == good.content
    assert srt.status_code == 200 and srt.content == inner.content


def test_a_key_of_the_wrong_redis_type_is_a_bad_entry_not_a_redis_outage(redis_server):
    settings = redis_settings(redis_server.url)
    with make_client(settings) as a:
        etag = a.post("/v1/srt", json=BODY).headers["etag"].strip('"')
    r = redis_server.client()
    r.delete(REDIS_PREFIX + etag)
    r.hset(REDIS_PREFIX + etag, "field", "value")  # GET on a hash: WRONGTYPE
    with capture_logs() as logs, make_client(settings) as b:
        first = b.post("/v1/srt", json=BODY)
        other = b.post("/v1/srt", json={**BODY, "model": "navin"})  # Redis must still be in use
    assert first.status_code == 200 and other.status_code == 200
    events = [e["event"] for e in logs]
    assert "redis_unavailable" not in events and events.count("cache_entry_rejected") == 1
    assert r.type(REDIS_PREFIX + etag) == b"string"  # replaced by a sealed value
    assert r.get(REDIS_PREFIX + other.headers["etag"].strip('"')) is not None


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
            etag = r.headers["etag"].strip('"')
            assert sealed_body(again.client().get(REDIS_PREFIX + etag), etag) == r.content
        finally:
            again.stop()
    events = [e["event"] for e in logs]
    assert events.count("redis_unavailable") == 1 and events.count("redis_recovered") == 1


def test_recovery_needs_one_good_call_even_with_stale_pooled_connections(redis_server):
    """Pooled connections die with the server: after a failure the pool is dropped, so the first call after the
    retry delay opens a fresh connection and succeeds, and redis_recovered is logged only after it did."""
    import asyncio
    import time

    from app.compute.cache import make_cache
    from app.logs import configure_logging

    configure_logging()
    settings = redis_settings(redis_server.url, redis_retry_seconds=0.2)

    async def scenario():
        cache = make_cache(settings)
        await asyncio.gather(*(cache.set(f"k{i}", b"{}") for i in range(8)))  # several pooled connections
        port = redis_server.port
        redis_server.stop()
        assert (await cache.get("nothing-local")).tier is None  # fails: Redis is down
        from .conftest import RedisServer, _redis_binary

        again = RedisServer(_redis_binary(), port)
        try:
            time.sleep(0.25)  # past the retry delay
            await cache.set("after", b"{}")  # the first call after the delay: must reach the new server
            assert again.client().get(REDIS_PREFIX + "after") is not None
            assert (await cache.get("after")).tier == "local"
            cache.local.clear()
            assert (await cache.get("after")).tier == "redis"
        finally:
            await cache.aclose()
            again.stop()

    with capture_logs() as logs:
        asyncio.run(scenario())
    events = [e["event"] for e in logs]
    assert events.count("redis_unavailable") == 1 and events.count("redis_recovered") == 1
    assert events.index("redis_recovered") > events.index("redis_unavailable")
