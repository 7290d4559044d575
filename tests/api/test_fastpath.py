"""The cache-hit fast path: a repeated request is answered from the in-process cache by its raw bytes, before
routing; If-None-Match with the current ETag is a 304."""

from __future__ import annotations

import asyncio
import hashlib
import threading
from types import SimpleNamespace

import orjson
import pytest

import app.alignments.router
import app.srt.router
from app.http import fastpath
from app.http.fastpath import FastPathMiddleware, Replay, etag_matches

BODY = b'{"vehicle": "table16-btrain", "model": "rigid"}'
JSON = {"content-type": "application/json"}


def test_a_repeated_request_is_answered_before_routing(client, monkeypatch):
    first = client.post("/v1/srt", content=BODY, headers=JSON)
    assert first.status_code == 200 and first.headers["x-cache"] == "miss"

    def must_not_run(*args, **kwargs):
        raise AssertionError("the route ran: the fast path did not answer")

    monkeypatch.setattr(app.srt.router, "compute_srt", must_not_run)
    again = client.post("/v1/srt", content=BODY, headers=JSON)
    assert again.status_code == 200 and again.headers["x-cache"] == "hit"
    assert again.content == first.content and again.headers["etag"] == first.headers["etag"]
    assert again.headers["content-type"] == first.headers["content-type"]
    # the same request written differently is other bytes: it goes through the app (here: the broken route)
    other = client.post("/v1/srt", content=BODY.replace(b": ", b":"), headers=JSON)
    assert other.status_code == 500


def test_a_large_body_is_keyed_off_the_event_loop_the_same_way(client, monkeypatch):
    """A body past HASH_IN_THREAD_BYTES is hashed in a worker thread (to the key it would have on the loop): a
    repeated 4,000-curve alignment is answered by the fast path; one byte changed is not."""
    curves = [
        {"id": f"curve-{i:06d}", "radius_m": 150.0 + i, "superelevation_percent": 6.0, "grade_percent": -1.25}
        for i in range(4_000)
    ]
    body = orjson.dumps({"vehicle": "table16-btrain", "curves": curves})
    assert len(body) > fastpath.HASH_IN_THREAD_BYTES
    hashed: list[str] = []
    real = fastpath._raw_key
    monkeypatch.setattr(fastpath, "_raw_key", lambda *a: hashed.append(threading.current_thread().name) or real(*a))
    first = client.post("/v1/alignments/assess", content=body, headers=JSON)
    assert first.status_code == 200 and first.headers["x-cache"] == "miss"
    assert hashed and hashed[0] != threading.main_thread().name  # the TestClient's loop runs in the main thread
    head = (b"x", b"/p", b"", b"", b"")
    assert real(head, body) == hashlib.blake2b(b"\0".join((*head, body))).digest()
    monkeypatch.setattr(app.alignments.router, "compute_alignment", None)  # the route would fail
    again = client.post("/v1/alignments/assess", content=body, headers=JSON)
    assert again.status_code == 200 and again.headers["x-cache"] == "hit" and again.content == first.content
    other = client.post("/v1/alignments/assess", content=body.replace(b"curve-", b"Curve-"), headers=JSON)
    assert other.status_code == 500


def test_the_representation_and_the_query_are_part_of_the_raw_key(client):
    sweep = b'{"vehicle": "table16-btrain", "model": "rigid", "grid": {"bank_percent": [0, 4]}}'
    as_json = client.post("/v1/srt/sweep", content=sweep, headers=JSON)
    as_csv = client.post("/v1/srt/sweep", content=sweep, headers={**JSON, "accept": "text/csv"})
    again_json = client.post("/v1/srt/sweep", content=sweep, headers=JSON)
    again_csv = client.post("/v1/srt/sweep", content=sweep, headers={**JSON, "accept": "text/csv"})
    assert as_json.headers["content-type"].startswith("application/json")
    assert as_csv.headers["content-type"].startswith("text/csv")
    assert again_json.content == as_json.content and again_csv.content == as_csv.content
    assert again_json.headers["x-cache"] == again_csv.headers["x-cache"] == "hit"
    assert again_csv.headers["vary"] == "Accept"
    text = b"id,radius_m,superelevation_percent\nK1,150,6\n"
    path = "/v1/alignments/assess/csv?vehicle=table16-btrain"
    a = client.post(path + "&rear_llt_limit=1", content=text, headers={"content-type": "text/csv"})
    b = client.post(path + "&rear_llt_limit=0.6", content=text, headers={"content-type": "text/csv"})
    assert a.json()["vehicles"][0]["rows"][0]["srt_g"] != b.json()["vehicles"][0]["rows"][0]["srt_g"]


@pytest.mark.parametrize("warm", [False, True])
def test_if_none_match_with_the_current_etag_is_a_304(client, warm):
    first = client.post("/v1/srt", content=BODY, headers=JSON)
    etag = first.headers["etag"]
    if not warm:  # the full path (a fresh raw key: same meaning, other bytes)
        r = client.post("/v1/srt", content=BODY + b" ", headers={**JSON, "if-none-match": etag})
    else:  # the fast path
        r = client.post("/v1/srt", content=BODY, headers={**JSON, "if-none-match": f'W/"x", {etag}'})
    assert r.status_code == 304 and r.content == b"" and r.headers["etag"] == etag
    stale = client.post("/v1/srt", content=BODY, headers={**JSON, "if-none-match": '"1.0.0:srt:old"'})
    assert stale.status_code == 200 and stale.content == first.content


def test_etag_comparison_is_rfc_9110_weak_comparison():
    assert etag_matches(b'"a"', b'"a"') and etag_matches(b'W/"a"', b'"a"') and etag_matches(b"*", b'"a"')
    assert etag_matches(b'"b", "a"', b'"a"') and not etag_matches(b'"b"', b'"a"') and not etag_matches(None, b'"a"')


def test_an_answer_marked_not_reusable_is_never_served_by_its_bytes():
    """A request with credentials (it may name a saved vehicle, which its owner may edit) is derived again every
    time."""
    calls = []

    async def inner(scope, receive, send):
        calls.append(scope["path"])
        await receive()
        await send({"type": "http.response.start", "status": 200, "headers": [(b"etag", b'"1:srt:k"')]})
        await send({"type": "http.response.body", "body": b"{}"})

    cache = SimpleNamespace(local={"1:srt:k": b"{}"})
    routes = {"/saved": Replay("srt"), "/preset": Replay("srt")}
    mw = FastPathMiddleware(inner, routes=lambda: routes, cache=lambda: cache)

    async def call(path):
        sent = []

        async def receive():
            return {"type": "http.request", "body": b"{}", "more_body": False}

        async def send(m):
            sent.append(m)

        headers = [(b"authorization", b"Bearer some-key")] if path == "/saved" else []
        scope = {"type": "http", "method": "POST", "path": path, "headers": headers, "query_string": b""}
        await mw(scope, receive, send)
        return sent

    for _ in range(3):
        asyncio.run(call("/saved"))
        asyncio.run(call("/preset"))
    assert calls.count("/saved") == 3 and calls.count("/preset") == 1


def test_tcp_nodelay_is_set_on_listening_sockets_and_inherited_without_leaking_descriptors():
    import os
    import socket

    from app.http.netopts import set_nodelay_on_listening_sockets

    listening = socket.socket(socket.AF_INET, socket.SOCK_STREAM)  # proto 0, as uvicorn --workers binds it
    listening.bind(("127.0.0.1", 0))
    listening.listen()
    before = len(os.listdir("/proc/self/fd"))
    try:
        assert set_nodelay_on_listening_sockets() >= 1
        assert len(os.listdir("/proc/self/fd")) == before  # every duplicate closed, sockets or not
        assert listening.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY)
        client = socket.create_connection(listening.getsockname())
        accepted, _ = listening.accept()
        assert accepted.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY)  # Linux copies it to the connection
        accepted.close()
        client.close()
    finally:
        listening.close()
