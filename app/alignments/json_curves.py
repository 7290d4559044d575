"""A request's JSON curves read straight from the body's text into columns: the fast path of ``orjson.loads`` +
:func:`app.alignments.curves.curves_from_json` for the plain form (a flat list of flat objects with the known keys,
numbers as plain decimals), which a million-curve job almost always is.

``orjson`` makes a dict per curve and a Python object per field (a million curves: six million objects, about two
seconds of the submission, ``bench/bench_submission.py``). Here the text is read as bytes with numpy: one
``bytes.translate`` classes every byte (brackets, braces, commas, colons, quotes), the quotes pair into strings (the
body has no backslash, so no quote is escaped) and the structural characters inside strings are dropped. What is
left is a sequence of tokens that a valid list of flat objects spells in one way only (``[`` ``{`` key ``:`` value
(``,`` key ``:`` value)* ``}`` (``,`` ``{`` ...)* ``]``): every token's role follows from the token before it (a
string after a colon is a value, after ``{`` or ``,`` a key; a comma after ``}`` separates curves, after a value
members), and every role allows a few tokens after it, so the grammar is checked by two table look-ups over all
tokens at once (:data:`_ROLE`, :data:`_NEXT`). A value that is not a string lies between its colon and the next
token; every other gap must be whitespace, which one count checks (the bytes of the list less its whitespace are
exactly its structural characters, its strings and its values). Keys are compared byte for byte with the five
known names. Numbers are read a character position at a time over each column by
:func:`app.formats.decimals.decimals` (Clinger 1990, "How to read floating point numbers accurately", PLDI '90, the
fast path: a plain decimal of at most 15 significant digits is its exact significand divided by an exact power of
ten, the correctly rounded double, as ``orjson`` reads it), narrowed to JSON's syntax (no ``+``, no leading zero, a
digit on both sides of the point); a JSON integer ``-0`` is the int 0, so 0.0. Any other value (an exponent, more
digits) is read by ``orjson`` itself, all of a column's at once, and must be an int or a float. The ids are the only
Python strings made: their bytes gathered into one buffer, decoded once and split.

The list is read a piece of about a megabyte at a time (:data:`PIECE_BYTES`), cut just after a comma between two
curves (:func:`_cut`), each piece checked on its own as a list whose first token follows such a comma: a piece's
arrays stay in the processor's cache, which makes the whole about 1.35 times as fast as one pass over a hundred
megabytes. A job of a million curves (100 MiB), parsed in a fresh process: 1.8 s against 2.8-2.9 s the old way
(:func:`~app.formats.jsonpieces.loads_in_pieces`, then :func:`~app.alignments.curves.curves_from_json`), and
200 MiB of memory at the peak besides the body and the interpreter against 480 MiB; parsed and split in a warm
process 2.2-2.4 s against 3.1-3.2 s (``bench/bench_submission.py``; a shared two-core machine).

It never decides an error: whatever it does not take as plain (an escape anywhere in the body, a nested value, an
unknown or repeated key, ``true``, a string for a number, a syntax error, a check of
:func:`~app.alignments.curves.plainly_valid` that fails, more curves than allowed) gives None, and the caller parses
the body as before (``orjson``, :func:`~app.alignments.curves.curves_from_json`), which gives the value or reports
the exact error it always did. A table it does answer is that path's table, bit for bit
(``tests/jobs/test_json_curves.py`` compares them on generated documents). The rest of the document (all but the
list) is parsed by ``orjson`` with the list replaced by ``[]``, as :func:`app.formats.jsonpieces.loads_in_pieces`
does.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import orjson

from app.alignments.curves import plainly_valid
from app.formats.alignment_io import MAX_CURVES, CurveTable
from app.formats.decimals import decimals
from app.formats.jsonpieces import WHITESPACE, skip_whitespace

#: token kinds: what ``bytes.translate`` makes of each byte (0: anything else); a string is its opening quote
_LIST, _END, _OPEN, _CLOSE, _COMMA, _COLON, _STRING = range(1, 8)
#: the list is read a piece of about this many bytes at a time (its arrays, a few times as many bytes, stay in the
#: processor's cache: 1.6 s a million curves, 2.2 s in one piece)
PIECE_BYTES = 1 << 20
_SPACE = 0x80  # JSON's whitespace: not a token, counted
_KINDS = bytearray(256)
for _byte, _kind in zip(b'[]{},:"', range(1, 8), strict=True):
    _KINDS[_byte] = _kind
for _byte in WHITESPACE:
    _KINDS[_byte] = _SPACE
_KINDS = bytes(_KINDS)

#: roles of the tokens: the list's ``[``, a curve's ``{``, a key, a colon, a string value, a comma between members,
#: a curve's ``}``, a comma between curves, the list's ``]``
_R_LIST, _R_OPEN, _R_KEY, _R_COLON, _R_VALUE, _R_MEMBERS, _R_CLOSE, _R_CURVES, _R_END = range(9)
#: the role of a token from its kind and the kind of the token before it (255: no valid list has that pair)
_ROLE = np.full((8, 8), 255, dtype=np.uint8)  # [kind before, kind]
_ROLE[[_LIST, _COMMA], _OPEN] = _R_OPEN
_ROLE[[_OPEN, _COMMA], _STRING] = _R_KEY
_ROLE[_COLON, _STRING] = _R_VALUE
_ROLE[_STRING, _COLON] = _R_COLON
_ROLE[[_STRING, _COLON], _COMMA] = _R_MEMBERS  # after a colon: a value that is not a string lies between them
_ROLE[[_STRING, _COLON], _CLOSE] = _R_CLOSE
_ROLE[_CLOSE, _COMMA] = _R_CURVES
_ROLE[_CLOSE, _END] = _R_END
#: the kinds a role may be followed by (the list's ``]`` by none: it is the last token)
_NEXT = np.zeros((32, 8), dtype=bool)  # [role, kind after] (roles past _R_END: none, refused before)
for _role, _kinds in (
    (_R_LIST, [_OPEN]),
    (_R_OPEN, [_STRING]),
    (_R_KEY, [_COLON]),
    (_R_COLON, [_STRING, _COMMA, _CLOSE]),
    (_R_VALUE, [_COMMA, _CLOSE]),
    (_R_MEMBERS, [_STRING]),
    (_R_CLOSE, [_COMMA, _END]),
    (_R_CURVES, [_OPEN]),
):
    _NEXT[_role, _kinds] = True

#: the keys (app.alignments.curves._FIELDS), each of its own length, and whether a value may be null
_KEYS = ("id", "radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh")
_NULLABLE = (False, False, True, False, True)
_BY_LENGTH = np.full(32, -1, dtype=np.int64)
for _code, _key in enumerate(_KEYS):
    _BY_LENGTH[len(_key)] = _code
_IS_WHITESPACE = np.zeros(256, dtype=bool)
_IS_WHITESPACE[list(WHITESPACE)] = True


def read_json_curves(
    body: bytes, path: Sequence[str] = ("curves",), *, max_curves: int = MAX_CURVES
) -> tuple[Any, CurveTable] | None:
    """``(document, curves)``: the JSON document with the list at ``path`` (keys from the top object down) replaced
    by ``[]``, and that list's curves as the table :func:`~app.alignments.curves.curves_from_json` makes of it, at
    most ``max_curves``; None when the list is not of the plain form or any check fails (the caller then parses the
    body as before and reports what is wrong)."""
    if b"\\" in body:  # an escape: quotes no longer pair by position
        return None
    key = orjson.dumps(path[-1])
    if body.count(key) != 1:  # the key's text once in the whole body: the `[]` put in its place is that member
        return None
    opening = skip_whitespace(body, body.find(key) + len(key))
    if body[opening : opening + 1] != b":":
        return None
    opening = skip_whitespace(body, opening + 1)
    if body[opening : opening + 1] != b"[":
        return None
    try:
        found = _curves(body, opening, max_curves)
        if found is None:
            return None
        closing, table = found
        data = orjson.loads(body[:opening] + b"[]" + body[closing + 1 :])
        holder = data
        for name in path[:-1]:
            holder = holder[name]
        if type(holder) is not dict or holder.get(path[-1]) != []:
            return None
    except (orjson.JSONDecodeError, UnicodeDecodeError, TypeError, KeyError, IndexError, ValueError):
        return None  # on any doubt, the old path (which reports the error, if there is one)
    return data, table


def _curves(body: bytes, opening: int, max_curves: int) -> tuple[int, CurveTable] | None:
    """(position of the list's ``]``, its curves) for the list whose ``[`` is at ``opening``; None: not plain. Read
    a piece of about :data:`PIECE_BYTES` at a time (each piece's arrays stay in the processor's cache), cut after a
    comma between two curves (:func:`_cut`)."""
    ids: list[str] = []
    columns: list[list[np.ndarray]] = [[], [], [], []]
    lo, n = opening, 0
    while True:
        hi = _cut(body, lo)
        piece = _piece(body[lo:hi] if hi is not None else body[lo:], first=lo == opening, last=hi is None)
        if piece is None:
            return None
        piece_ids, piece_columns, closing = piece
        n += len(piece_ids)
        if n > max_curves:
            return None
        ids += piece_ids
        for column, values in zip(columns, piece_columns, strict=True):
            column.append(values)
        if hi is None:
            break
        lo = hi
    radius, e, grade, posted = (np.concatenate(c) for c in columns)
    table = plainly_valid(ids, radius, e, grade, posted)
    return None if table is None else (lo + closing, table)


def _cut(body: bytes, lo: int) -> int | None:
    """Where the piece from ``lo`` ends: just after the first comma between two curves (``}``, a comma, ``{``, with
    whitespace between) :data:`PIECE_BYTES` on; None when the list may end before (a ``]`` on the way) or there is no
    such comma: the rest of the body is the last piece. A cut inside a string (an id with ``},{`` in it) leaves the
    piece ending inside a string, which :func:`_piece` refuses: the body then takes the old path."""
    q = body.find(b"}", lo + PIECE_BYTES)
    if q < 0 or body.find(b"]", lo, q) >= 0:
        return None
    while q >= 0:
        comma = skip_whitespace(body, q + 1)
        if body[comma : comma + 1] == b",":
            brace = skip_whitespace(body, comma + 1)
            if body[brace : brace + 1] == b"{":
                return comma + 1
        nxt = body.find(b"}", q + 1)
        if nxt < 0 or body.find(b"]", q, nxt) >= 0:
            return None
        q = nxt
    return None


def _piece(body: bytes, *, first: bool, last: bool) -> tuple[list[str], list[np.ndarray], int] | None:
    """The curves of a piece of the list: (ids, [radius, superelevation, grade, posted speed], the position of the
    list's ``]`` in it when ``last``). The first piece begins with the list's ``[``, the others with a curve's
    ``{`` (after the comma that ended the piece before); the last ends with the list's ``]`` (what follows it is the
    rest of the document), the others with the comma after a curve. None: not plain."""
    buf = np.frombuffer(body, dtype=np.uint8)
    kinds = np.frombuffer(body.translate(_KINDS), dtype=np.uint8)
    at = np.flatnonzero(kinds.view(np.int8) > 0)  # the structural characters and quotes
    kind = kinds[at]
    quote = kind == _STRING
    in_string = np.bitwise_xor.accumulate(quote.view(np.uint8)).view(bool)  # an opening quote and what follows it
    outside = ~in_string
    if last:  # the list ends at its first `]` outside strings (a nested one: refused below)
        end = int(np.argmax(outside & (kind == _END))) if kind.size else 0
        if kind.size == 0 or kind[end] != _END or in_string[end]:
            return None
        at, kind, quote, in_string, outside = (x[: end + 1] for x in (at, kind, quote, in_string, outside))
    elif kind.size == 0 or in_string[-1] or at[-1] != len(body) - 1:  # cut after a comma outside strings
        return None
    quotes = at[quote]  # opening and closing in turn
    string_at, string_end = quotes[0::2], quotes[1::2]  # each string's opening quote, and its closing one
    token = outside ^ quote  # a string is one token (its opening quote); what lies inside strings none
    at, kind = at[token], kind[token]
    m = kind.size
    # the grammar: each token's role from the kind before it (a piece after the first: after a comma between
    # curves), and the kind after it allowed by that role
    role = np.empty(m, dtype=np.uint8)
    role[0] = _R_LIST if first else _ROLE[_COMMA, kind[0]]
    role[1:] = _ROLE.ravel()[(kind[:-1] << 3) | kind[1:]]
    if (
        role.max() > _R_END
        or role[0] != (_R_LIST if first else _R_OPEN)
        or role[-1] != (_R_END if last else _R_CURVES)
        or not _NEXT.ravel()[(role[:-1] << 3) | kind[1:]].all()
    ):
        return None
    opens = np.flatnonzero(kind == _OPEN)
    n = opens.size
    if n == 0:
        return None

    # the keys, each a known name exactly, at most once in its curve; id and radius_m in every curve
    strings = np.flatnonzero(kind == _STRING)
    string_role = role[strings]
    keys = strings[string_role == _R_KEY]
    key_at, key_end = string_at[string_role == _R_KEY] + 1, string_end[string_role == _R_KEY]
    code = _BY_LENGTH[np.minimum(key_end - key_at, _BY_LENGTH.size - 1)]
    if code.min() < 0:
        return None
    for c, name in enumerate(_KEYS):
        if not _equal(body, key_at[code == c], name.encode()).all():
            return None
    curve = np.repeat(np.arange(n), np.diff(np.searchsorted(keys, opens), append=keys.size))
    count = np.bincount(curve * len(_KEYS) + code, minlength=n * len(_KEYS)).reshape(n, len(_KEYS))
    if count.max() > 1 or not (count[:, 0].all() and count[:, 1].all()):
        return None

    # the values: a string (after its colon) or the text between the colon and the next token
    value = keys + 2
    is_string = kind[value] == _STRING
    if not (is_string == (code == 0)).all():  # the id a string, every other value not
        return None
    id_strings = np.flatnonzero(string_role == _R_VALUE)  # one per curve (checked), in order
    ids, id_whitespace = _ids(body, string_at[id_strings], string_end[id_strings])
    number = ~is_string
    starts, stops = at[keys[number] + 1] + 1, at[value[number]]
    number_code, number_curve = code[number], curve[number]

    # every other byte is whitespace: the piece's bytes less its whitespace are its tokens, strings and values
    closing = int(at[-1])
    whitespace = int(np.count_nonzero(kinds[: closing + 1] == _SPACE)) - id_whitespace
    if whitespace:
        starts, stops = _stripped(buf, starts, stops)
    if (starts >= stops).any():
        return None
    lengths = int((string_end - string_at + 1).sum()) + int((stops - starts).sum())
    if closing + 1 - whitespace != m - strings.size + lengths:
        return None

    columns = []
    for c, default in ((1, np.nan), (2, np.nan), (3, 0.0), (4, np.nan)):
        sel = number_code == c
        column = np.full(n, default)
        values = _numbers(body, buf, starts[sel], stops[sel], nullable=_NULLABLE[c])
        if values is None:
            return None
        column[number_curve[sel]] = values
        columns.append(column)
    return ids, columns, closing


def _equal(body: bytes, starts: np.ndarray, text: bytes) -> np.ndarray:
    """Whether ``body[s : s + len(text)] == text`` for each start ``s``: 8 bytes at a time (a view of the body with
    a stride of one byte: an unaligned 8-byte word at every position), the last word overlapping the one before."""
    k = len(text)
    equal = np.ones(starts.size, dtype=bool)
    if k < 8 or len(body) < k:
        buf = np.frombuffer(body, dtype=np.uint8)
        for j in range(k):
            equal &= buf[np.minimum(starts + j, buf.size - 1)] == text[j]
        return equal & (starts + k <= len(body))
    words = np.ndarray((len(body) - 7,), dtype="<u8", buffer=body, strides=(1,))
    for j in sorted({*range(0, k - 7, 8), k - 8}):
        equal &= words[np.minimum(starts + j, words.size - 1)] == int.from_bytes(text[j : j + 8], "little")
    return equal & (starts + k <= len(body))


def _stripped(buf: np.ndarray, starts: np.ndarray, stops: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The spans ``[starts, stops)`` less the whitespace at both ends."""
    starts, stops = starts.copy(), stops.copy()
    for edge, step, side in ((starts, 1, 0), (stops, -1, -1)):
        moving = np.arange(starts.size)
        while moving.size:
            s = starts[moving]
            e = stops[moving]
            moving = moving[(s < e) & _IS_WHITESPACE[buf[(s if side == 0 else e - 1)]]]
            edge[moving] += step
    return starts, stops


def _ids(body: bytes, opens: np.ndarray, closes: np.ndarray) -> tuple[list[str], int]:
    """The strings whose quotes are at ``opens`` and ``closes`` (one buffer of their texts, each with its closing
    quote, decoded at once and split at the quotes: no string has one inside) and the whitespace bytes in them."""
    buf = np.frombuffer(body, dtype=np.uint8)
    lengths = closes - opens  # the text and the closing quote
    first = np.cumsum(lengths) - lengths
    index = np.repeat(opens + 1 - first, lengths) + np.arange(int(lengths.sum()))
    text = buf[index].tobytes()
    whitespace = sum(text.count(w) for w in (b" ", b"\t", b"\n", b"\r"))
    ids = text.decode("utf-8").split('"')
    ids.pop()  # after the last quote
    return ids, whitespace


def _numbers(body: bytes, buf: np.ndarray, starts: np.ndarray, stops: np.ndarray, *, nullable: bool):
    """The values of a column's JSON numbers ``body[starts[i]:stops[i]]`` as ``orjson`` reads them, converted to
    float (nan for ``null`` when ``nullable``); None when one is not a number (or not finite as a float)."""
    values, plain, integral = decimals(buf, starts, stops, json=True)
    np.add(values, 0.0, out=values, where=plain & integral)  # the integer -0 is the int 0: 0.0, not -0.0
    odd = np.flatnonzero(~plain)
    if odd.size:
        null = (stops[odd] - starts[odd] == 4) & _equal(body, starts[odd], b"null")
        if null.any() and not nullable:
            return None
        values[odd[null]] = np.nan
        odd = odd[~null]
    if odd.size:  # the other numbers as orjson reads them (the whole document would be read so), all at once
        tokens = b",".join(body[s:e] for s, e in zip(starts[odd].tolist(), stops[odd].tolist(), strict=True))
        items = orjson.loads(b"[" + tokens + b"]")
        if len(items) != odd.size or not set(map(type, items)) <= {int, float}:
            return None
        try:
            values[odd] = np.array(items, dtype=float)
        except OverflowError:  # an integer past the float range
            return None
    return values
