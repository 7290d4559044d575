"""Request bodies over their route's limit are refused with a 413 problem before they are read."""

from __future__ import annotations

import asyncio

import orjson
import pytest

from app.alignments.schemas import ALIGNMENT_JSON_LIMIT, CSV_UPLOAD_LIMIT, IFC_UPLOAD_LIMIT, LANDXML_UPLOAD_LIMIT
from app.http.bodylimit import DEFAULT_LIMIT, BodyLimitMiddleware, spec_limits
from app.http.problems import problem_bytes
from app.main import create_app

APP = create_app()


def run_middleware(path: str, headers: list[tuple[bytes, bytes]], chunks: list[bytes]):
    """Drive the middleware with a body delivered in ``chunks``; record what was read and what was answered."""
    reads, sent, reached = [], [], []

    async def inner(scope, receive, send):  # the app behind: reads the whole body, answers 200
        body = b""
        while True:
            m = await receive()
            body += m.get("body", b"")
            if not m.get("more_body"):
                break
        reached.append(body)
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})

    async def receive():
        i = len(reads)
        reads.append(i)
        return {"type": "http.request", "body": chunks[i], "more_body": i < len(chunks) - 1}

    async def send(message):
        sent.append(message)

    mw = BodyLimitMiddleware(inner, lambda: spec_limits(APP.openapi()), problem_bytes)
    scope = {"type": "http", "method": "POST", "path": path, "headers": headers}
    asyncio.run(mw(scope, receive, send))
    return reads, sent, reached


def test_a_declared_length_over_the_limit_is_refused_without_reading_anything():
    # the 114 MiB body of the issue: nothing of it is read
    reads, sent, reached = run_middleware("/v1/srt", [(b"content-length", str(114 * 2**20).encode())], [b"x"])
    assert reads == [] and reached == []
    assert sent[0]["status"] == 413
    problem = orjson.loads(sent[1]["body"])
    assert problem["type"] == "urn:rollover:problem:body-too-large" and problem["status"] == 413
    assert "64 KiB (65536 bytes)" in problem["detail"] and problem["instance"] == "/v1/srt"
    assert (b"content-type", b"application/problem+json") in sent[0]["headers"]


def test_a_chunked_body_is_refused_as_soon_as_it_passes_the_limit():
    chunks = [b"x" * 10_000] * 100  # 1 MB in 100 chunks, no Content-Length
    reads, sent, reached = run_middleware("/v1/srt", [], chunks)
    assert len(reads) == DEFAULT_LIMIT // 10_000 + 1  # read up to the chunk that passes 64 KiB, not one more
    assert reached == [] and sent[0]["status"] == 413


def test_a_chunked_body_under_the_limit_reaches_the_app_whole():
    chunks = [b'{"vehicle": ', b'"table16-btrain"}']
    _, sent, reached = run_middleware("/v1/srt", [], chunks)
    assert reached == [b"".join(chunks)] and sent[0]["status"] == 200


def test_a_garbled_content_length_is_refused():
    _, sent, reached = run_middleware("/v1/srt", [(b"content-length", b"12abc")], [b"{}"])
    assert reached == [] and sent[0]["status"] == 413


@pytest.mark.parametrize(
    ("path", "limit"),
    [
        ("/v1/srt", DEFAULT_LIMIT),
        ("/v1/curve-speed", DEFAULT_LIMIT),
        ("/v1/alignments/assess", ALIGNMENT_JSON_LIMIT),
        ("/v1/alignments/assess/csv", CSV_UPLOAD_LIMIT),
        ("/v1/alignments/assess/landxml", LANDXML_UPLOAD_LIMIT),
        ("/v1/alignments/assess/ifc", IFC_UPLOAD_LIMIT),
    ],
)
def test_each_route_has_the_limit_it_declares_in_the_spec(path, limit):
    assert spec_limits(APP.openapi())[path] == limit
    op = APP.openapi()["paths"][path]["post"]
    assert f"({limit} bytes)" in op["description"]
    assert op["responses"]["413"]["content"]["application/problem+json"]


def test_every_operation_with_a_body_declares_its_limit_and_the_413():
    for path, item in APP.openapi()["paths"].items():
        for method, op in item.items():
            if "requestBody" in op:
                limit = op["x-body-limit-bytes"]
                assert f"({limit} bytes)" in op["description"] and "413" in op["responses"], (method, path)


def test_through_http_a_large_srt_body_is_a_413_and_a_large_alignment_is_not(shared_client):
    big = b'{"vehicle": "table16-btrain", "pad": "' + b"x" * (DEFAULT_LIMIT + 1) + b'"}'
    r = shared_client.post("/v1/srt", content=big, headers={"content-type": "application/json"})
    assert r.status_code == 413 and r.headers["content-type"] == "application/problem+json"
    # the same size is within the alignment's limit: it is read and refused for its content (422), not its size
    r = shared_client.post("/v1/alignments/assess", content=big, headers={"content-type": "application/json"})
    assert r.status_code == 422
