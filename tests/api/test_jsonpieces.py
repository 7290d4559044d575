"""app.formats.jsonpieces.loads_in_pieces: orjson.loads(body), value or error, whatever the body."""

from __future__ import annotations

import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.formats import jsonpieces
from app.formats.jsonpieces import MAX_KEY_TEXTS, PIECE_BYTES, _locate, loads_in_pieces

#: texts full of what the scan looks at: quotes are escaped by orjson (so a backslash appears: the whole-body path),
#: commas, brackets, braces, colons, the key itself, whitespace
_TEXT = st.text(alphabet=st.sampled_from(list(',[]{}:"curves \n\té')), max_size=8)
_SCALAR = st.one_of(st.none(), st.booleans(), st.integers(-(2**40), 2**40), st.floats(allow_nan=False), _TEXT)
_JSON = st.recursive(
    _SCALAR, lambda inner: st.lists(inner, max_size=4) | st.dictionaries(_TEXT, inner, max_size=4), max_leaves=12
)
_WS = st.sampled_from(["", " ", "\n", " \t\r\n "])


def _pieces(body: bytes):
    return loads_in_pieces(body, ("curves",), split_bytes=0, piece_bytes=1)  # every element its own piece


def _same(body: bytes) -> None:
    try:
        want = orjson.loads(body)
    except orjson.JSONDecodeError as exc:
        with pytest.raises(orjson.JSONDecodeError) as got:
            _pieces(body)
        assert str(got.value) == str(exc)
        return
    assert _pieces(body) == want


@st.composite
def _documents(draw) -> bytes:
    """A JSON object with a ``curves`` list (or not), laid out with random whitespace (no escapes in the keys)."""
    ws = draw(_WS)
    members = draw(st.dictionaries(st.sampled_from(["vehicle", "model", "x", "curve", "curvess"]), _JSON, max_size=3))
    items = draw(st.lists(_JSON, max_size=8))
    text = [f"{ws}{orjson.dumps(k).decode()}{ws}:{ws}{orjson.dumps(v).decode()}" for k, v in members.items()]
    if draw(st.booleans()):
        listed = f"{ws},{ws}".join(orjson.dumps(i).decode() for i in items)
        text.insert(draw(st.integers(0, len(text))), f'{ws}"curves"{ws}:{ws}[{ws}{listed}{ws}]{ws}')
    return ("{" + ",".join(text) + "}" + ws).encode()


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(_documents())
def test_a_valid_document_gives_orjsons_value(body):
    _same(body)


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(_documents(), st.data())
def test_a_broken_document_gives_orjsons_error_or_value(body, data):
    """A byte changed, removed or added anywhere (a comma doubled, a bracket lost, a quote opened...)."""
    at = data.draw(st.integers(0, len(body)))
    byte = data.draw(st.sampled_from([b",", b"]", b"[", b"{", b"}", b'"', b":", b" ", b"", b"\\", b"x", b"\xff"]))
    cut = data.draw(st.integers(0, 1))
    _same(body[:at] + byte + body[at + cut :])


@pytest.mark.parametrize(
    "body",
    [
        b'{"curves":[1,2,]}',  # a trailing comma: the last slice is empty
        b'{"curves":[1,,2]}',
        b'{"curves":[,1]}',
        b'{"curves":[]}',
        b'{"curves":[ ]}',
        b'{"curves":[1],"curves":[2,3]}',  # twice: orjson's last one, by the whole-body path
        b'{"a":{"curves":[9]},"curves":[1,{"curves":[2]}]}',  # nested lists of the same name are not it
        b'{"a":"\\"curves\\":[5]","curves":[1]}',  # an escape anywhere: the whole-body path
        b'{"x":"curves","curves":["curves",":","[",","]}',
        b'{"curves":[1,2]} trailing',
        b'{"curves":[1,2]',
        b'{"curves":',
        b'{"curves"',
        b'{"curves":{"a":1}}',
        b'["curves",[1,2]]',
        b"",
        b'{"curves":["\xff"]}',  # not UTF-8
    ],
)
def test_edge_cases(body):
    _same(body)


def test_the_list_is_found_by_its_path():
    body = b'{"operation":"alignments.assess", "request" : {"vehicle":"b","curves":[{"id":"a,b"}, {"id":"]"}]}}'
    found = _locate(body, ("request", "curves"))
    assert found is not None and body[found[0] : found[0] + 1] == b"[" and body[found[1]] == ord("]")
    assert [body[c] for c in found[2]] == [ord(",")]  # the one comma between the two curves
    assert loads_in_pieces(body, ("request", "curves"), split_bytes=0, piece_bytes=1) == orjson.loads(body)
    assert _locate(body, ("curves",)) is None  # not at the top


def test_a_large_body_is_parsed_in_short_calls(monkeypatch):
    """12 MB of curves: no orjson call is given more than a slice of about PIECE_BYTES (orjson holds the GIL for a
    whole call: 0.1-0.3 s for the whole body; bench/bench_service.py measures /healthz meanwhile)."""
    curves = [{"id": f"C{i}", "radius_m": 100.0 + i, "superelevation_percent": 6.0, "grade_percent": 1.5}
              for i in range(150_000)]  # fmt: skip
    body = orjson.dumps({"vehicle": "table16-btrain", "curves": curves})
    sizes: list[int] = []
    real = orjson.loads
    monkeypatch.setattr(jsonpieces.orjson, "loads", lambda b: sizes.append(len(b)) or real(b))
    assert loads_in_pieces(body) == {"vehicle": "table16-btrain", "curves": curves}
    assert len(body) > 80 * PIECE_BYTES and len(sizes) > 80
    assert max(sizes) < PIECE_BYTES + 200  # a slice ends at the first element past PIECE_BYTES


def test_a_key_text_repeated_everywhere_is_not_looked_for():
    """``"curves"`` as a value in every curve: past MAX_KEY_TEXTS the list is not looked for (each occurrence would
    cost a look-up), and the body is parsed at once, to the same value."""
    curves = [{"id": f"C{i}", "note": "curves", "radius_m": 100.0 + i} for i in range(MAX_KEY_TEXTS + 1)]
    body = orjson.dumps({"vehicle": "x", "curves": curves})
    assert _locate(body, ("curves",)) is None
    assert _pieces(body) == orjson.loads(body)
    assert _locate(orjson.dumps({"vehicle": "x", "curves": curves[:-2]}), ("curves",)) is not None
