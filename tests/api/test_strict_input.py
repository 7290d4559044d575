"""Mistaken input refused and named (issue 40 item 5): the content type, the encoding, the nesting and the keys of a
JSON body, read the same on every operation that takes one (app.http.strictjson), and curve ids that are blank or
hold an invisible character, refused in JSON as in CSV (app.formats.alignment_io.curve_id_problem).

Each case failed before: a JSON body sent as text/plain was a 422 "Input should be a valid dictionary" (or, on an
operation that reads its body itself, parsed anyway); {"vehicle": a, "vehicle": b} answered for b; a body that is
not UTF-8 or nested 5,000 deep was "There was an error parsing the body" with no position on the operations FastAPI
parses; " " and "A\u200b" were curve ids in JSON.
"""

from __future__ import annotations

import json

import orjson
import pytest
from fastapi.exceptions import RequestValidationError
from hypothesis import given, settings
from hypothesis import strategies as st

from app.http import strictjson
from app.http.strictjson import duplicate_key, refuse_duplicate_keys, too_deep

#: one operation of each kind: FastAPI parses the body (srt, vehicles/build, curve-speed, catalog-free), or the route
#: reads it itself (alignments, routes, jobs)
PARSED = ["/v1/srt", "/v1/vehicles/build", "/v1/curve-speed", "/v1/combinations/build", "/v1/min-radius"]
SELF_READ = ["/v1/alignments/assess", "/v1/routes/assess", "/v1/jobs"]
CURVE = {"radius_m": 200.0, "superelevation_percent": 2.0}


@pytest.mark.parametrize("path", PARSED + SELF_READ)
@pytest.mark.parametrize("content_type", ["text/plain", "application/x-www-form-urlencoded", "text/csv"])
def test_a_json_body_with_another_content_type_is_a_415_naming_it(shared_client, path, content_type):
    r = shared_client.post(path, content=b'{"vehicle": "table16-btrain"}', headers={"content-type": content_type})
    assert r.status_code == 415, r.text
    p = r.json()
    assert p["type"] == "urn:rollover:problem:unsupported-media-type"
    assert f"Content-Type {content_type!r}" in p["detail"] and "application/json" in p["detail"]


@pytest.mark.parametrize("content_type", ["application/json; charset=utf-8", "application/merge-patch+json"])
def test_json_under_its_own_types_is_read(shared_client, content_type):
    r = shared_client.post("/v1/srt", content=b'{"vehicle": "table16-btrain"}', headers={"content-type": content_type})
    assert r.status_code == 200, r.text


def test_a_body_without_a_content_type_is_named_as_such(shared_client):
    r = shared_client.post("/v1/srt", content=b'{"vehicle": "table16-btrain"}')
    assert r.status_code == 415 and r.json()["detail"].startswith("no Content-Type: "), r.text


@pytest.mark.parametrize("path", PARSED + SELF_READ)
def test_a_key_given_twice_is_refused_naming_it(shared_client, path):
    body = b'{"vehicle": "table16-btrain", "radius_m": 100, "vehicle": "table23-semitrailer"}'
    r = shared_client.post(path, content=body, headers={"content-type": "application/json"})
    assert r.status_code == 400, r.text
    assert r.json()["type"] == "urn:rollover:problem:malformed-request"
    assert "the key 'vehicle' appears twice" in r.json()["detail"]


def test_a_key_given_twice_deep_inside_is_refused_on_a_self_read_body(shared_client):
    curves = ", ".join(f'{{"id": "{cid}", "radius_m": 200.0, "radius_m": 20.0}}' for cid in "AB")
    text = '{"vehicle": "table16-btrain", "curves": [' + curves
    r = shared_client.post(
        "/v1/alignments/assess", content=(text + "]}").encode(), headers={"content-type": "application/json"}
    )
    assert r.status_code == 400 and "'radius_m' appears twice" in r.json()["detail"], r.text


@pytest.mark.parametrize("path", PARSED + SELF_READ)
@pytest.mark.parametrize(
    ("body", "where"),
    [
        (b'{"vehicle": "\xff\xfe"}', "line 1 column 1 (char 0)"),  # not UTF-8 (orjson reports the document start)
        (b"[" * 5000 + b"]" * 5000, "line 1 column 1026 (char 1025)"),  # past orjson's 1024 levels
        (b'{"vehicle": ', "line 1 column 13 (char 12)"),
    ],
    ids=["encoding", "nesting", "truncated"],
)
def test_a_body_that_does_not_parse_is_a_400_with_a_position(shared_client, path, body, where):
    r = shared_client.post(path, content=body, headers={"content-type": "application/json"})
    assert r.status_code == 400, r.text
    p = r.json()
    assert p["type"] == "urn:rollover:problem:malformed-request" and where in p["detail"], p


def test_a_body_too_deep_for_pythons_parser_is_a_400_with_a_position(shared_client):
    # 1000 levels: orjson reads it (its limit is 1024), Python's parser (FastAPI's) stops short of it
    body = b"[" * 1000 + b"]" * 1000
    r = shared_client.post("/v1/srt", content=body, headers={"content-type": "application/json"})
    assert r.status_code == 400, r.text
    assert "nested too deeply" in r.json()["detail"] and "line 1 column 901 (char 900)" in r.json()["detail"]


def test_the_duplicate_key_helpers_agree_with_a_plain_count():
    assert duplicate_key(b'{"a": 1, "b": {"c": 2, "c": 3}}') == "c"
    assert duplicate_key(b'{"a": 1, "b": [{"a": 2}, {"a": 3}]}') is None  # the same key in different objects
    # escapes: the count from the bytes cannot be trusted, the second parse decides; a ':' inside a string is not a
    # member
    refuse_duplicate_keys(b'{"a\\"": 1, "a": "x:y"}', {'a"': 1, "a": "x:y"})
    assert too_deep(b'["[[[", [[1]]]', 2) == "line 1 column 10 (char 9)"
    assert too_deep(b"[[1]]", 2) is None


@pytest.mark.parametrize(
    ("cid", "words"),
    [
        (" ", "is blank"),
        ("\u00a0\u2003", "is blank"),  # no-break and em spaces
        ("A\u200b", "invisible format character U+200B at position 2"),  # zero-width space
        ("\u200d", "invisible format character U+200D at position 1"),  # zero-width joiner
        ("\ufeffA", "invisible format character U+FEFF at position 1"),
        ("A\u202e", "invisible format character U+202E at position 2"),  # right-to-left override
    ],
)
def test_a_blank_or_invisible_curve_id_is_refused_in_json_as_in_csv(shared_client, cid, words):
    body = {"vehicle": "table16-btrain", "curves": [{"id": "ok", **CURVE}, {"id": cid, **CURVE}]}
    r = shared_client.post("/v1/alignments/assess", json=body)
    assert r.status_code == 422, r.text
    e = r.json()["errors"][0]
    assert e["field"] == "curves.1.id" and words in e["message"], e
    csv = f"id,radius_m,superelevation_percent\nok,200,2\n{cid},200,2\n"
    r = shared_client.post(
        "/v1/alignments/assess/csv?vehicle=table16-btrain", content=csv.encode(), headers={"content-type": "text/csv"}
    )
    assert r.status_code == 422, r.text
    detail = r.json()["detail"]
    assert ("is empty" if not cid.strip() else words) in detail, detail


_KEYS = st.sampled_from(["a", "b", "c:d", 'q"', "id"])
_JSON = st.recursive(
    st.none() | st.integers(-5, 5) | st.sampled_from(["x", "y:z", "\\", "é"]),
    lambda inner: st.lists(inner, max_size=3) | st.lists(st.tuples(_KEYS, inner), max_size=4),
    max_leaves=12,
)


def _text(value) -> str:
    """JSON text of a generated value; a list of (key, value) pairs is an object written with the keys as given
    (possibly repeated)."""
    if isinstance(value, list) and value and all(isinstance(p, tuple) for p in value):
        return "{" + ", ".join(f"{json.dumps(k)}: {_text(v)}" for k, v in value) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_text(v) for v in value) + "]"
    return json.dumps(value, ensure_ascii=False)


@settings(max_examples=400, deadline=None)
@given(_JSON)
def test_the_fast_duplicate_check_agrees_with_a_second_parse(value):
    """refuse_duplicate_keys (colons counted in the body and in orjson's re-serialisation) refuses exactly the
    documents in which Python's parser, with a hook on every object, finds a key twice."""
    body = _text(value).encode()
    expected = duplicate_key(body)
    try:
        refuse_duplicate_keys(body, orjson.loads(body))
        assert expected is None, body
    except RequestValidationError as exc:
        assert expected is not None and repr(expected) in exc.errors()[0]["msg"], body


@pytest.mark.parametrize("piece", [3, strictjson.SLICE])
def test_the_colon_count_is_fooled_neither_by_a_colon_written_as_an_escape_nor_by_long_strings(monkeypatch, piece):
    """The fast check counts colons a slice at a time and counts a long string's colons without writing it; a colon
    written ``\\u003a`` in the body is one in the parsed string and not in the body's count, so such a body goes to
    the second parse (else a dropped member and that colon would balance)."""
    monkeypatch.setattr(strictjson, "SLICE", piece)
    body = b'{"a": 1, "a": "x\\u003ay", "doc": "' + b"<p:q/>" * 10 + b'"}'
    assert duplicate_key(body) == "a"
    with pytest.raises(RequestValidationError):
        refuse_duplicate_keys(body, orjson.loads(body))
    doc = '<a xmlns:x=\\"urn:x:y\\">\\n</a>' * 40  # a document as JSON writes it: escapes, colons
    for members, duplicate in (('"n": 1', None), ('"n": 1, "n": 2', "n")):
        body = ('{"vehicle": "v", "landxml": {"document": "' + doc + '", ' + members + "}}").encode()
        assert duplicate_key(body) == duplicate
        if duplicate is None:
            refuse_duplicate_keys(body, orjson.loads(body))
        else:
            with pytest.raises(RequestValidationError, match="'n' appears twice"):
                refuse_duplicate_keys(body, orjson.loads(body))


@pytest.mark.parametrize("escape", [b"\\u003a", b"\\u003A"])
def test_a_colon_escaped_in_either_case_goes_to_the_second_parse(escape):
    body = b'{"a": 1, "a": "x' + escape + b'y"}'
    with pytest.raises(RequestValidationError, match="'a' appears twice"):
        refuse_duplicate_keys(body, orjson.loads(body))


def test_a_document_with_every_angle_bracket_escaped_is_checked_by_the_count(monkeypatch):
    """``\\u003c`` for ``<`` (as some encoders write every ``<`` of an XML document) is no colon: the colon count
    decides, with no second parse of the whole body (Python's parser: about a second on 64 MB), and a key twice is
    still refused."""
    doc = '\\u003ca xmlns:x=\\"urn:x:y\\"/\\u003e' * 40
    second = []
    real = strictjson.duplicate_key
    monkeypatch.setattr(strictjson, "duplicate_key", lambda b: second.append(1) or real(b))
    for members, duplicate in (('"n": 1', None), ('"n": 1, "n": 2', "n")):
        body = ('{"vehicle": "v", "landxml": {"document": "' + doc + '", ' + members + "}}").encode()
        assert real(body) == duplicate
        if duplicate is None:
            refuse_duplicate_keys(body, orjson.loads(body))
            assert second == []
        else:
            with pytest.raises(RequestValidationError, match="'n' appears twice"):
                refuse_duplicate_keys(body, orjson.loads(body))


@pytest.mark.parametrize(
    ("path", "content_type", "body", "where"),
    [
        ("/v1/alignments/assess/csv", "text/csv", b"id,radius_m\nA\xff,200\n", "byte 13, 0xFF"),
        ("/v1/alignments/assess/landxml", "application/xml", b"<?xml version='1.0'?><x>\xff</x>", "byte 24"),
        ("/v1/routes/assess/gpx", "application/gpx+xml", b"<gpx>\xff</gpx>", "byte 5, 0xFF"),
        ("/v1/routes/assess/geojson", "application/geo+json", b'{"type": "\xff"}', "line 1 column 1 (char 0)"),
    ],
)
def test_an_upload_that_is_not_utf8_says_where(shared_client, path, content_type, body, where):
    """Uploads name the position of a byte that is not UTF-8 too (the XML ones said only 'neither UTF-8 nor ...')."""
    r = shared_client.post(f"{path}?vehicle=table16-btrain", content=body, headers={"content-type": content_type})
    assert r.status_code == 422 and where in r.json()["detail"], r.text
