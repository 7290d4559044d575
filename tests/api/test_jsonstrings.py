"""app.formats.jsonpieces.loads_long_strings and decode_string: a document sent in a JSON field decoded a slice at a
time gives ``json.loads``'s string and ``orjson.loads``'s value or error, whatever the escapes and the cuts."""

from __future__ import annotations

import json

import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.formats import jsonpieces, uploads
from app.formats.jsonpieces import decode_string, loads_long_strings

#: characters whose JSON text is an escape, two or three UTF-8 bytes, or a surrogate pair (astral), and XML's
_CHARS = st.sampled_from(list('"\\/<>=: ab\n\t\r\x08\x0c\x00\x1féø€\u2028\ud7ff\ue000\uffff😀𝄞\U0010ffff'))
_SHORT = {'"': '\\"', "\\": "\\\\", "/": "\\/", "\n": "\\n", "\t": "\\t", "\r": "\\r", "\x08": "\\b", "\x0c": "\\f"}


def _u(code: int, upper: bool) -> str:
    return f"\\u{code:04X}" if upper else f"\\u{code:04x}"


@st.composite
def _encoded(draw) -> tuple[str, bytes]:
    """A string and a JSON text of it (between the quotes), each character written one of the ways JSON allows:
    as itself (where it may be), its short escape, or ``\\uXXXX`` (a surrogate pair beyond the BMP), hex in either
    case."""
    chars = draw(st.lists(_CHARS, max_size=120))
    out = []
    for c in chars:
        ways = ["u"] + (["short"] if c in _SHORT else []) + (["raw"] if c not in '"\\' and c >= " " else [])
        way = draw(st.sampled_from(ways))
        if way == "raw":
            out.append(c)
        elif way == "short":
            out.append(_SHORT[c])
        elif ord(c) > 0xFFFF:
            v = ord(c) - 0x10000
            out.append(_u(0xD800 + (v >> 10), draw(st.booleans())) + _u(0xDC00 + (v & 0x3FF), draw(st.booleans())))
        else:
            out.append(_u(ord(c), draw(st.booleans())))
    return "".join(chars), "".join(out).encode()


@settings(max_examples=500, deadline=None)
@given(_encoded(), st.integers(12, 40))
def test_a_string_decoded_in_slices_is_json_loads_string(encoded, step):
    """Every slice at least 12 bytes (an escaped surrogate pair, the longest thing never cut): a cut is always
    found."""
    value, text = encoded
    assert json.loads(b'"' + text + b'"') == value  # the encoding is JSON's
    assert decode_string(text, step) == value


@pytest.mark.parametrize("in_place", [True, False], ids=["appended", "joined"])
def test_slices_of_ever_wider_characters_make_json_loads_string(monkeypatch, in_place):
    """The value grows slice by slice: slices that need a wider storage than the value so far (ASCII, then Latin-1,
    the BMP, beyond it; and back) make the same string as ``json.loads``, appended in place or (under a trace
    function, as coverage runs) joined at the end."""
    monkeypatch.setattr(jsonpieces, "_appends_in_place", lambda: in_place)
    value = "a" * 40 + "é" * 30 + "b" * 40 + "€" * 30 + "c" * 40 + "😀" * 30 + "d" * 40 + "é" + "e" * 40
    text = orjson.dumps(value)[1:-1]
    for step in (12, 13, 40, 64, len(text) - 1, len(text)):
        assert decode_string(text, step) == value == json.loads(b'"' + text + b'"')


@pytest.mark.parametrize("in_place", [True, False], ids=["appended", "joined"])
def test_an_upload_decoded_in_chunks_is_its_text(monkeypatch, in_place):
    """An XML upload (app/formats/uploads.py) is decoded a chunk at a time and its parts assembled the same way:
    every cut through a UTF-8 character (two, three or four bytes), the byte-order mark dropped, is ``bytes.decode``'s
    text."""
    monkeypatch.setattr(jsonpieces, "_appends_in_place", lambda: in_place)
    doc = '<?xml version="1.0"?><LandXML name="' + "a" * 9 + "Vegløp" + "b" * 9 + "€" * 5 + "c" * 9 + '😀">' + "d" * 9
    data = "\ufeff".encode() + doc.encode()
    for chunk in range(1, 14):
        monkeypatch.setattr(uploads, "DECODE_CHUNK", chunk)
        assert uploads.decode_xml(data) == data.decode("utf-8-sig") == doc


@pytest.mark.parametrize(
    "text",
    [b"\\ud83d", b"\\ude00", b"ab\\ud83d\\u0041", b"\x01", b"a\xff", b"\xe2\x82", b"\\x41", b"\\u12", b"ab\\"],
    ids=["lone-high", "lone-low", "high-then-bmp", "control", "bad-utf8", "truncated-utf8", "bad-escape", "short-u",
         "trailing-backslash"],
)  # fmt: skip
def test_a_string_json_refuses_is_refused_in_slices(text):
    body = b'"' + b"x" * 30 + text + b"y" * 30 + b'"'
    with pytest.raises(orjson.JSONDecodeError):
        orjson.loads(body)
    with pytest.raises((orjson.JSONDecodeError, ValueError)):
        decode_string(body[1:-1], 12)


def _same(body: bytes) -> None:
    def mine():
        return loads_long_strings(body, split_bytes=0, string_bytes=8, slice_bytes=12)

    try:
        want = orjson.loads(body)
    except orjson.JSONDecodeError as exc:
        with pytest.raises(orjson.JSONDecodeError) as got:
            mine()
        assert str(got.value) == str(exc)
        return
    assert mine() == want


_SCALAR = st.one_of(st.none(), st.booleans(), st.integers(-1000, 1000), _encoded().map(lambda e: e[1]))


@st.composite
def _documents(draw) -> bytes:
    """JSON text of objects and lists whose strings (values and keys) are written with random escapes: many longer
    than the ``string_bytes`` of :func:`_same` (long ones), in objects, in lists, as keys."""

    def value(depth: int) -> str:
        kind = draw(st.sampled_from(["scalar", "object", "list"] if depth < 3 else ["scalar"]))
        if kind == "object":
            keys = draw(st.lists(_SCALAR.filter(lambda s: isinstance(s, bytes)), max_size=3))
            return "{" + ",".join(f'"{k.decode()}":{value(depth + 1)}' for k in keys) + "}"
        if kind == "list":
            return "[" + ",".join(value(depth + 1) for _ in range(draw(st.integers(0, 3)))) + "]"
        s = draw(_SCALAR)
        return f'"{s.decode()}"' if isinstance(s, bytes) else json.dumps(s)

    keys = draw(st.lists(st.sampled_from(["vehicle", "landxml", "document", "gpx", "x"]), max_size=4))
    return ("{" + ",".join(f'"{k}" : {value(1)}' for k in keys) + "}").encode()


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(_documents())
def test_a_document_gives_orjsons_value(body):
    _same(body)


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(_documents(), st.data())
def test_a_damaged_document_gives_orjsons_value_or_error(body, data):
    """A byte put in, taken out or replaced anywhere (an unclosed string, bad UTF-8, a control character, a lone
    surrogate, a broken escape): orjson's own value or error."""
    at = data.draw(st.integers(0, len(body)))
    byte = data.draw(st.sampled_from([b'"', b"\\", b"\xff", b"\xc3", b"\x01", b"u", b"{", b",", b""]))
    cut = data.draw(st.integers(0, 1))
    _same(body[:at] + byte + body[at + cut :])


def test_a_long_string_as_a_key_in_a_list_or_twice_gives_orjsons_value():
    long = 'é<"x"/>' * 10
    for doc in ({long: 1}, {"a": [long, {"b": long}]}, {"a": {"b": {"c": {"d": {"e": {"f": {"g": long}}}}}}}):
        _same(orjson.dumps(doc))
    _same(b'{"a":"' + long.replace('"', '\\"').encode() + b'","a":1}')  # the long one dropped by the key twice
    _same(b'{"a":1,"a":"' + long.replace('"', '\\"').encode() + b'"}')
    # a NUL in the body's own strings (a placeholder holds one): parsed at once, to the same value
    _same(orjson.dumps({"a": long, "b": "\x00\ue000long string 0\ue000"}))


def test_a_large_document_in_a_field_is_decoded_in_short_calls(monkeypatch):
    """A 24 MB LandXML in ``landxml.document`` (every quote escaped, ``<`` written ``\\u003c`` as some encoders do):
    no orjson call is given more than a slice of about STRING_SLICE_BYTES (orjson holds the GIL for a whole call:
    50-100 ms for the whole body), and the value is orjson's."""
    doc = '<?xml version="1.0"?><LandXML>' + '<Curve rot="cw" radius="250" length="50"/>' * 500_000 + "</LandXML>"
    body = orjson.dumps({"vehicle": "table16-btrain", "landxml": {"document": doc, "profile": None}})
    body = body.replace(b"<", b"\\u003c")
    sizes: list[int] = []
    real = orjson.loads
    monkeypatch.setattr(jsonpieces.orjson, "loads", lambda b: sizes.append(len(b)) or real(b))
    assert loads_long_strings(body) == {"vehicle": "table16-btrain", "landxml": {"document": doc, "profile": None}}
    assert len(body) > 20 * jsonpieces.STRING_SLICE_BYTES and len(sizes) > 20
    assert max(sizes) <= jsonpieces.STRING_SLICE_BYTES + 2  # the slice and its two quotes
