"""app.alignments.json_curves: a JSON curves list read from the text is the table ``orjson.loads`` +
``curves_from_json`` make of it, bit for bit, and anything it does not take as plain (any syntax error, an odd value, a
check that fails) is left to that path (None), which answers exactly as before."""

from __future__ import annotations

import math

import numpy as np
import orjson
import pytest

from app.alignments import json_curves
from app.alignments.curves import curves_from_json
from app.alignments.json_curves import read_json_curves
from app.formats.alignment_io import MAX_CURVES
from app.jobs.service import parse_submission
from tests.api.conftest import make_client

COLUMNS = ("radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh", "station_m")
#: JSON's whitespace, and runs of it
_SPACES = ["", "", " ", "\n", "\t", "\r\n", " \n\t  "]
#: characters of the ids: ASCII, the structural ones of JSON, others of 2, 3 and 4 bytes in UTF-8
_ID_CHARS = [*"abcXYZ019 _-.,:[]{}/'", "é", "ß", "中", "€", "\U0001f69b", "\u2028"]


def same(a, b) -> None:
    """Two tables are equal bit for bit (-0.0 and nan included)."""
    assert a.ids == b.ids
    for name in COLUMNS:
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype == np.float64, name
        assert np.array_equal(x.view(np.int64), y.view(np.int64)), name
    assert a.where is b.where is None and a.dialect is b.dialect is None


def old(body: bytes, path=("curves",), max_curves: int = MAX_CURVES):
    data = orjson.loads(body)
    for key in path:
        data = data[key]
    return curves_from_json(data, max_curves)


def _number(rng: np.random.Generator, low: float, high: float) -> str:
    """A JSON number in [low, high]: an integer or a decimal of 0-17 digits after the point, sometimes ``-0``,
    an exponent or a long integer (which the fast path hands to orjson)."""
    x = rng.uniform(low, high)
    kind = rng.integers(0, 10)
    if kind == 0:
        return str(int(x))
    if kind == 1:
        return repr(float(x))  # 15-17 significant digits
    if kind == 2:
        return f"{x:.3e}"  # an exponent
    if kind == 3 and low <= 0 <= high:
        return rng.choice(["-0", "-0.0", "0", "0.000"])
    return f"{x:.{rng.integers(0, 18)}f}"


def _ident(rng: np.random.Generator, i: int) -> str:
    return "".join(rng.choice(_ID_CHARS, rng.integers(0, 6))) + str(i)


def _document(rng: np.random.Generator, n: int, *, path=("curves",)) -> bytes:
    """A request of ``n`` random curves, laid out with random whitespace and key orders, optional keys left out or
    null."""
    sp = lambda: rng.choice(_SPACES)  # noqa: E731
    curves = []
    for i in range(n):
        members = {"id": orjson.dumps(_ident(rng, i)).decode(), "radius_m": _number(rng, 5, 100_000)}
        for key, low, high, nullable in (
            ("superelevation_percent", -20, 20, True),
            ("grade_percent", -20, 20, False),
            ("posted_speed_kmh", 1, 200, True),
        ):
            choice = rng.integers(0, 4)
            if choice == 0:
                continue
            members[key] = "null" if nullable and choice == 1 else _number(rng, low, high)
        keys = list(members)
        rng.shuffle(keys)
        inner = f"{sp()},{sp()}".join(f'"{k}"{sp()}:{sp()}{members[k]}' for k in keys)
        curves.append(f"{{{sp()}{inner}{sp()}}}")
    listed = f"[{sp()}" + f"{sp()},{sp()}".join(curves) + f"{sp()}]"
    doc = listed
    for key in reversed(path):
        doc = f'{{{sp()}"vehicle":{sp()}"table16-btrain",{sp()}"{key}"{sp()}:{sp()}{doc}{sp()}}}'
    return (doc + sp()).encode()


@pytest.fixture(params=[json_curves.PIECE_BYTES, 1, 40], ids=["one-piece", "a-piece-a-curve", "pieces"])
def pieces(request, monkeypatch):
    """The list read in one piece, or cut after every curve, or after every few (cuts after a comma between
    curves, never inside a string, which the ids' braces and commas would mislead a plain search into)."""
    monkeypatch.setattr(json_curves, "PIECE_BYTES", request.param)
    return request.param


@pytest.mark.parametrize("seed", range(40))
def test_a_plain_list_is_the_old_paths_table_bit_for_bit(seed, pieces):
    rng = np.random.default_rng(seed)
    body = _document(rng, int(rng.integers(1, 60)))
    found = read_json_curves(body)
    assert found is not None, body
    data, table = found
    same(table, old(body))
    assert data == {**orjson.loads(body), "curves": []}  # the rest of the document, as orjson reads it


def test_numbers_of_every_plain_length_are_read_as_orjson_reads_them():
    """Decimals of 0-17 digits after the point (more than 15 significant ones: orjson's own reading), negative
    ones, -0 (an integer: 0.0) and -0.0, integers up to 2^63."""
    rng = np.random.default_rng(7)
    texts = ["-0", "-0.0", "0", "0.0", "5", "15", "-20", "20.000000000000000", "-19.99999999999999999"]
    texts += [f"{x:.{d}f}" for d in range(18) for x in rng.uniform(-20, 20, 40)]
    texts += [f"{x:.{d}f}" for d in range(18) for x in rng.uniform(-1, 1, 40) * 10.0 ** rng.integers(-6, 1, 40)]
    curves = ",".join(f'{{"id":"c{i}","radius_m":100,"grade_percent":{t}}}' for i, t in enumerate(texts))
    body = f'{{"curves":[{curves}]}}'.encode()
    found = read_json_curves(body, max_curves=len(texts))
    assert found is not None
    same(found[1], old(body, max_curves=len(texts)))
    assert math.copysign(1, found[1].grade_percent[0]) == 1 and math.copysign(1, found[1].grade_percent[1]) == -1
    big = b'{"curves":[{"id":"a","radius_m":9223372036854775807},{"id":"b","radius_m":12345678901234567890.5}]}'
    assert read_json_curves(big) is None  # beyond the bounds: left to the old path, which reports it
    long = b'{"curves":[{"id":"a","radius_m":12345.678901234567},{"id":"b","radius_m":99999.99999999999999}]}'
    same(read_json_curves(long)[1], old(long))


def test_a_job_reads_its_curves_from_the_text_into_the_same_request(monkeypatch):
    rng = np.random.default_rng(3)
    body = b'{ "operation" : "alignments.assess" ,\n "request": ' + _document(rng, 200) + b"}"
    assert read_json_curves(body, ("request", "curves"), max_curves=1_000_000) is not None
    op, (req, table) = parse_submission(body)
    monkeypatch.setattr("app.jobs.op_alignments.read_json_curves", lambda *a, **k: None)
    op_before, (req_before, table_before) = parse_submission(body)
    assert op is op_before and req == req_before
    same(table, table_before)


#: lists the fast path must leave to orjson and curves_from_json: syntax errors of every kind, odd values, curves
#: that fail a check (each with the curve "B" before it, valid)
_B = '{"id":"B","radius_m":100}'
_NOT_PLAIN = [
    # syntax
    '[{"id":"A" "radius_m":100}]',
    '[{"id":"A","radius_m" 100}]',
    '[{"id":"A","radius_m":100,}]',
    '[{"id":"A","radius_m":100},]',
    '[{"id":"A","radius_m":100} {"id":"C","radius_m":100}]',
    '[,{"id":"A","radius_m":100}]',
    '[{"id":"A",,"radius_m":100}]',
    '[{"id":"A","radius_m"::100}]',
    '[{"id":"A","radius_m":}]',
    '[{"id":"A":"B","radius_m":100}]',
    '[{"id":"A","radius_m":100 7}]',
    '[{"id":"A", x "radius_m":100}]',
    '[{"id":"A","radius_m":100}}]',
    '[{{"id":"A","radius_m":100}}]',
    '[{"id":"A","radius_m":100}}',
    '[{"id":"A,"radius_m":100}]',
    '[{"id":"A","radius_m":100}]]',
    '[{"id":"A","radius_m":100\x0b}]',
    '[{"id":"A","radius_m":100\u00a0}]',
    '[{"id":"A","radius_m":100}{}]',
    '[{"id":"A"},"radius_m":100}]',  # every token's role fits the token before it: only the grammar's order refuses it
    '[{"id":"A","radius_m":100},"id":"C","radius_m":200}]',
    '[{"radius_m":100,"id"}]',
    "[{}]",
    "[]",
    "[[]]",
    # numbers JSON has no place for, and values that are not numbers
    '[{"id":"A","radius_m":0100}]',
    '[{"id":"A","radius_m":100.}]',
    '[{"id":"A","radius_m":.5e3}]',
    '[{"id":"A","radius_m":+100}]',
    '[{"id":"A","radius_m":NaN}]',
    '[{"id":"A","radius_m":Infinity}]',
    '[{"id":"A","radius_m":-}]',
    '[{"id":"A","radius_m":1.2.3}]',
    '[{"id":"A","radius_m":0x10}]',
    '[{"id":"A","radius_m":1_000}]',
    '[{"id":"A","radius_m":--100}]',
    '[{"id":"A","radius_m":- 100}]',
    '[{"id":"A","radius_m":true}]',
    '[{"id":"A","radius_m":100,"grade_percent":false}]',
    '[{"id":"A","radius_m":"100"}]',
    '[{"id":1,"radius_m":100}]',
    '[{"id":null,"radius_m":100}]',
    '[{"id":"A","radius_m":null}]',
    '[{"id":"A","radius_m":100,"grade_percent":null}]',
    '[{"id":"A","radius_m":[100]}]',
    '[{"id":"A","radius_m":{"v":100}}]',
    '[{"id":"A","radius_m":1e999}]',
    # keys
    '[{"id":"A","radius_m":100,"radius_m":200}]',
    '[{"id":"A","radius_m":100,"bogus":1}]',
    '[{"id":"A","ID":"B","radius_m":100}]',
    '[{"id":"A","radius_M":100}]',
    '[{"id":"A"}]',
    '[{"radius_m":100}]',
    # the checks of curves_from_json
    '[{"id":"B","radius_m":200}]',  # a duplicate id (of B)
    '[{"id":"","radius_m":100}]',
    '[{"id":"' + "x" * 101 + '","radius_m":100}]',
    '[{"id":"A\x7f","radius_m":100}]',
    '[{"id":"A\x01","radius_m":100}]',
    '[{"id":"A\\u0041","radius_m":100}]',  # an escape: the whole body is orjson's
    '[{"id":"A","radius_m":4.99}]',
    '[{"id":"A","radius_m":100,"superelevation_percent":20.5}]',
    '[{"id":"A","radius_m":100,"grade_percent":-20.01}]',
    '[{"id":"A","radius_m":100,"posted_speed_kmh":0}]',
    '[{"id":"A","radius_m":100,"posted_speed_kmh":-0.0}]',
]


def _with_b(listed: str) -> str:
    return listed.replace("[", "[" + _B + ",", 1) if listed not in ("[]", "[[]]") else listed


@pytest.mark.parametrize("listed", _NOT_PLAIN)
def test_anything_not_plain_is_left_to_the_old_path(listed, pieces):
    body = ('{"vehicle":"table16-btrain","curves":' + _with_b(listed) + "}").encode()
    assert read_json_curves(body) is None


def test_a_document_that_is_no_plain_request_is_left_to_orjson(pieces):
    ok = '{"curves":[' + _B + "]}"
    assert read_json_curves(ok.encode()) is not None
    for body in [
        ok + "x",  # after the document
        ok[:-1],  # unterminated
        '{"curves":[' + _B + '],"curves":[]}',  # the key twice
        '{"x":{"curves":[' + _B + "]}}",  # not where the path says
        '{"curves":[' + _B + '],"note":"\\n"}',  # an escape elsewhere
        '{"curves" [' + _B + "]}",
        '{"curves":"[' + _B + ']"}',
        '["curves",[' + _B + "]]",
    ]:
        assert read_json_curves(body.encode()) is None, body
    many = "[" + ",".join(f'{{"id":"c{i}","radius_m":100}}' for i in range(11)) + "]"
    assert read_json_curves(('{"curves":' + many + "}").encode(), max_curves=10) is None
    assert read_json_curves(('{"curves":' + many + "}").encode(), max_curves=11) is not None


def _answer(client, body: bytes, monkeypatch, fast: bool):
    with monkeypatch.context() as m:
        if not fast:
            m.setattr("app.jobs.op_alignments.read_json_curves", lambda *a, **k: None)
        r = client.post("/v1/jobs", content=body, headers={"content-type": "application/json"})
    return r.status_code, r.json()


def test_the_job_endpoint_answers_what_it_did_before_for_every_list_left_to_it(monkeypatch):
    """The 422 problem (its fields, messages and types) with the fast path and without it: the same."""
    with make_client() as c:
        for listed in _NOT_PLAIN:
            request = '{"vehicle":"table16-btrain","superelevation_percent":2,"curves":' + _with_b(listed) + "}"
            body = ('{"operation":"alignments.assess","request":' + request + "}").encode()
            fast, before = _answer(c, body, monkeypatch, True), _answer(c, body, monkeypatch, False)
            assert fast == before, listed
            assert fast[0] in (400, 422), (listed, fast)  # malformed JSON: 400; a bad curve: 422
        assert c.app.state.jobs.active_count() == 0  # no job was created


def test_a_plain_job_refused_for_the_rest_of_its_request_names_the_same_fields(monkeypatch):
    """The curves plain and valid, the request not (an unknown vehicle field, a second source of curves)."""
    listed = "[" + _B + "]"
    with make_client() as c:
        for request in [
            '{"vehicle":"table16-btrain","bogus":1,"curves":' + listed + "}",
            '{"vehicle":"table16-btrain","csv":"id,radius_m","curves":' + listed + "}",
            '{"curves":' + listed + "}",
        ]:
            body = ('{"operation":"alignments.assess","request":' + request + "}").encode()
            assert read_json_curves(body, ("request", "curves")) is not None
            fast, before = _answer(c, body, monkeypatch, True), _answer(c, body, monkeypatch, False)
            assert fast == before and fast[0] == 422, (request, fast)


def test_a_long_list_is_read_in_pieces_cut_between_curves(monkeypatch):
    """Cut after every curve or so: many pieces, the same table; a cut that falls inside an id (one with ``},{`` in
    it) is refused by the piece, and the old path reads the body."""
    rng = np.random.default_rng(5)
    body = _document(rng, 300)
    read = []
    monkeypatch.setattr(json_curves, "PIECE_BYTES", 64)
    monkeypatch.setattr(
        json_curves, "_piece", lambda *a, _piece=json_curves._piece, **k: read.append(1) or _piece(*a, **k)
    )
    found = read_json_curves(body)
    assert found is not None and len(read) > 10
    same(found[1], old(body))
    trap = b'{"curves":[' + b",".join(b'{"id":"x%d},{","radius_m":100}' % i for i in range(50)) + b"]}"
    assert read_json_curves(trap) is None
    monkeypatch.setattr(json_curves, "PIECE_BYTES", 1 << 20)
    same(read_json_curves(trap)[1], old(trap))  # in one piece: read


#: bytes a mutation puts in: JSON's structural characters and whitespace, parts of numbers, keys and literals, a
#: vertical tab, a byte of a two-byte UTF-8 character alone, DEL and NUL
_MUTATIONS = [*b'{}[],:" \n0123456789-+.eEnulltrueidradius_m', 0x0B, 0xC3, 0xA9, 0x7F, 0x00]


@pytest.mark.parametrize("seed", range(4))
def test_a_mutated_document_is_refused_or_read_as_orjson_and_curves_from_json_read_it(seed, pieces):
    """A byte replaced, put in or taken out, once or twice: the fast path answers only for a document that orjson
    parses and whose curves curves_from_json accepts, and then with their table (60,000 such documents were
    checked by hand, none answered otherwise)."""
    rng = np.random.default_rng(seed)
    for _ in range(150):
        body = bytearray(_document(rng, int(rng.integers(1, 6))))
        for _ in range(int(rng.integers(1, 3))):
            pos, byte = int(rng.integers(0, len(body))), int(rng.choice(_MUTATIONS))
            match int(rng.integers(0, 3)):
                case 0:
                    body[pos] = byte
                case 1:
                    body.insert(pos, byte)
                case _:
                    del body[pos]
        found = read_json_curves(bytes(body))
        if found is not None:
            data = orjson.loads(bytes(body))  # raises if the fast path took a document that is not JSON
            same(found[1], curves_from_json(data["curves"], MAX_CURVES))  # raises if it took invalid curves
            assert found[0] == {**data, "curves": []}
