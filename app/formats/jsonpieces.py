"""``orjson.loads`` of a large request without holding the interpreter for the whole parse.

An ``alignments.assess`` job of a million curves given as JSON is a body of more than a hundred megabytes (about
120 bytes a curve). ``orjson.loads`` parses it in one C call that holds the GIL for the whole parse: the event loop,
in another thread, cannot answer anything meanwhile, not even ``/healthz``. Nearly all of such a body is one list
(``curves``), so :func:`loads_in_pieces` parses the document around that list, then the list a slice of elements at a
time; between two slices the other threads run. (The synchronous alignment, at most 10,000 curves, is about a
megabyte: parsed at once or in a few slices.)

Where the list's elements begin and end is found by a lexical scan on numpy arrays (no Python per byte): the
quotes, then the brackets, braces and commas outside strings and their depth. The scan needs no escapes: a body with
a backslash anywhere is parsed at once, as is one without the list where it is expected, or with that key twice.

The answer is always ``orjson.loads(body)``'s: every piece is parsed by orjson itself, the pieces rebuild the
document exactly (the list's text is the pieces' texts joined by the commas between them, and each slice must give
as many elements as it has), and on any doubt -- a piece that does not parse, a count that does not match -- the
whole body is parsed at once, which gives orjson's own value or error. ``tests/api/test_jsonpieces.py`` checks it
against ``orjson.loads`` on generated documents, valid and not.

A body that is one long string instead (a LandXML, IFC or GPX document sent in a JSON field: ``landxml.document``,
60 MB of XML whose every quote is escaped) is :func:`loads_long_strings`: the strings of the body are walked (their
ends found by a regular expression run a slice at a time), each string longer than :data:`LONG_STRING_BYTES` is
replaced by a placeholder and the small rest parsed by orjson, and the long string is decoded by orjson a slice at a
time (``orjson.loads(b'"' + slice + b'"')``), cut only where no escape, surrogate pair or UTF-8 character is split,
so that the slices' values joined are the string's value. Same rule: any doubt, the whole body at once.

No call on the way works on the whole string at once. The slices are short (:data:`STRING_SLICE_BYTES`), and the
value is not made by joining the slices' values (one C call that allocates the whole value and fills it: 37-55 ms of
processor time for a 64-million-character document on the 2-core machine under load, most of it the page faults of
the fresh allocation) but by appending each slice's value in place as it is decoded (:func:`assembled`).
"""

from __future__ import annotations

import bisect
import re
import sys
import time
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

import numpy as np
import orjson

#: bodies shorter than this are parsed at once (a parse this short does not hold up the event loop noticeably) [bytes]
SPLIT_BYTES = 1 << 20
#: the list is parsed in slices of about this many bytes (an eighth of SPLIT_BYTES: short holds of the GIL) [bytes]
PIECE_BYTES = 128 * 1024
#: a key whose text (e.g. ``"curves"``) appears more often than this (as values, say) is not looked for [-]
MAX_KEY_TEXTS = 64

#: JSON's four whitespace bytes (RFC 8259, section 2)
WHITESPACE = b" \t\r\n"
_QUOTE, _BACKSLASH, _COMMA, _COLON = 0x22, 0x5C, 0x2C, 0x3A
_OPENS, _CLOSES = (0x7B, 0x5B), (0x7D, 0x5D)  # { [ and } ]


def skip_whitespace(body: bytes, pos: int) -> int:
    """The first position at or after ``pos`` that is not JSON whitespace (``len(body)`` at the end)."""
    while pos < len(body) and body[pos] in WHITESPACE:
        pos += 1
    return pos


class _Scan:
    """The structure of a JSON text without escapes: its structural characters outside strings and their depth."""

    def __init__(self, body: bytes) -> None:
        a = np.frombuffer(body, dtype=np.uint8)
        self.body = body
        self.quotes = np.flatnonzero(a == _QUOTE)
        marks = np.flatnonzero((a == 0x7B) | (a == 0x7D) | (a == 0x5B) | (a == 0x5D) | (a == _COMMA))
        outside = (np.searchsorted(self.quotes, marks) & 1) == 0  # an even number of quotes before it
        self.at = marks[outside]  # positions
        kind = a[self.at]
        step = np.isin(kind, _OPENS).astype(np.int64) - np.isin(kind, _CLOSES)
        self.depth = np.cumsum(step)  # the depth just after each
        self.kind = kind

    # the per-position look-ups below use bisect, not numpy: they run in Python loops, where a numpy call per step
    # would let go of the GIL and take it back each time and starve a waiting thread (see loads_in_pieces)

    def depth_at(self, pos: int) -> int:
        i = bisect.bisect_left(self.at, pos)
        return int(self.depth[i - 1]) if i else 0

    def member(self, key: str, depth: int, lo: int, hi: int) -> int | None:
        """Where the value of the one member ``key`` of the object at ``depth`` within ``[lo, hi)`` starts (None: not
        there, there twice, or the key's text found more than :data:`MAX_KEY_TEXTS` times: then each is not worth
        looking at, and the whole body is parsed at once)."""
        token = orjson.dumps(key)
        if self.body.count(token, lo, hi) > MAX_KEY_TEXTS:
            return None
        found, pos = [], self.body.find(token, lo, hi)
        while pos >= 0:
            opening = bisect.bisect_left(self.quotes, pos) % 2 == 0  # the token's first quote opens a string
            if opening and self.depth_at(pos) == depth:
                colon = skip_whitespace(self.body, pos + len(token))
                if colon < hi and self.body[colon] == _COLON:
                    found.append(skip_whitespace(self.body, colon + 1))
            pos = self.body.find(token, pos + 1, hi)
        return found[0] if len(found) == 1 else None

    def closing(self, opening: int) -> tuple[int, int] | None:
        """Index (into ``at``) of the bracket or brace at position ``opening`` and of the one that closes it."""
        i = int(np.searchsorted(self.at, opening))
        if i >= len(self.at) or self.at[i] != opening:
            return None
        after = np.flatnonzero(self.depth[i:] == self.depth[i] - 1)
        return (i, i + int(after[0])) if after.size else None


def _locate(body: bytes, path: Sequence[str]) -> tuple[int, int, np.ndarray] | None:
    """The list at ``path`` (keys from the top object down): its ``[``, its ``]`` and the commas between its
    elements (positions); None when the scan cannot say (an escape, no such list, a key twice)."""
    if body.find(b"\\") >= 0:
        return None
    scan = _Scan(body)
    start = skip_whitespace(body, 0)
    if start >= len(body) or body[start] != 0x7B:
        return None
    span = scan.closing(start)
    for depth, key in enumerate(path, start=1):
        if span is None:
            return None
        value = scan.member(key, depth, int(scan.at[span[0]]), int(scan.at[span[1]]))
        last = depth == len(path)
        if value is None or value >= len(body) or body[value] != (0x5B if last else 0x7B):
            return None
        span = scan.closing(value)
    if span is None:
        return None
    i, j = span
    inner = np.arange(i + 1, j)
    commas = inner[(scan.kind[i + 1 : j] == _COMMA) & (scan.depth[i + 1 : j] == scan.depth[i])]
    return int(scan.at[i]), int(scan.at[j]), scan.at[commas]


def loads_in_pieces(
    body: bytes, path: Sequence[str] = ("curves",), *, split_bytes: int = SPLIT_BYTES, piece_bytes: int = PIECE_BYTES
) -> Any:
    """``orjson.loads(body)`` (the same value, or the same ``orjson.JSONDecodeError``), the list at ``path`` of a large
    body parsed a slice of elements at a time (see the module's doc)."""
    found = _locate(body, path) if len(body) >= split_bytes else None
    if found is None:
        return loads_long_strings(body, split_bytes=split_bytes)
    opening, closing, commas = found
    try:
        data = orjson.loads(body[:opening] + b"[]" + body[closing + 1 :])
        holder = data
        for key in path[:-1]:
            holder = holder[key]
        if holder[path[-1]] != []:
            return orjson.loads(body)
        # element k lies between bounds[k] and bounds[k + 1]. Plain Python from here on: a numpy call in this loop
        # would let go of the GIL and take it back at once, and a thread waiting for the GIL (the event loop) would
        # starve, as it never sees the GIL held by one owner for a whole switch interval (CPython's convoy effect)
        bounds = [opening, *commas.tolist(), closing]
        items: list[Any] = []
        first, last = 0, len(bounds) - 1
        while first < last:
            stop = max(first + 1, min(last, bisect.bisect_left(bounds, bounds[first] + piece_bytes)))
            piece = orjson.loads(b"[" + body[bounds[first] + 1 : bounds[stop]] + b"]")
            if len(piece) != stop - first:  # an empty element (`[1,,2]`, `[1,]`): not the list it seemed
                return orjson.loads(body)
            items += piece
            first = stop
        holder[path[-1]] = items
        return data
    except (orjson.JSONDecodeError, TypeError, KeyError):
        return orjson.loads(body)  # orjson's own value or error for the whole body


#: a string value longer than this (its JSON text) is decoded a slice at a time by :func:`loads_long_strings` [bytes]
LONG_STRING_BYTES = 1 << 20
#: the slice of a long string decoded, or scanned for its end, in one call [bytes]: a few milliseconds at most (the
#: scan, a regular expression, is the slower: up to 20 ms of processor time for a MiB under load, under 5 ms for this)
STRING_SLICE_BYTES = 256 * 1024
#: a body with more strings than this before its long ones is parsed at once (walking them in Python would take
#: longer than the parse it spares) [-]
MAX_STRINGS = 20_000
#: a JSON string's text up to its closing quote or an escape cut by the slice's end (unrolled: no alternation per
#: character); ``match`` from just after the opening quote
_STRING_BODY = re.compile(rb'[^"\\]*(?:\\.[^"\\]*)*', re.DOTALL)
_HEX = frozenset(b"0123456789abcdefABCDEF")
#: a placeholder's text: a string no request holds (a NUL and a private-use character), numbered
_PLACEHOLDER = "\u0000\ue000long string %d\ue000"


def _string_end(body: bytes, start: int, step: int) -> int:
    """The position of the quote that closes the JSON string whose text starts at ``start`` (just after its opening
    quote); ``len(body)`` when none does. Scanned ``step`` bytes at a time, the interpreter let go between two."""
    pos, n = start, len(body)
    while pos < n:
        end = _STRING_BODY.match(body, pos, min(n, pos + step)).end()
        if end < n and body[end] == 0x22:
            return end
        if end == pos:  # a backslash at the slice's very end: take the escape with the next slice
            end = pos + 2 if pos + 1 < n else n
        pos = end
        time.sleep(0)
    return n


def _safe_cut(text: bytes, lo: int, hi: int, target: int) -> int | None:
    """A position in ``(lo, target]`` of a JSON string's text ``text[lo:hi]`` where it may be cut into two strings
    whose values joined are its value: not inside a UTF-8 character, an escape (``\\n``, ``\\u00e9``) or a
    surrogate pair (``\\ud83d\\ude00``). None: none found within 64 KiB below ``target``."""
    for c in range(target, max(lo, target - 65536), -1):
        if text[c] & 0xC0 == 0x80:  # a UTF-8 continuation byte
            continue
        b = text.rfind(b"\\", max(lo, c - 6), c)  # an escape is 6 bytes at most: the one c could be in begins here
        if b < 0:
            return c
        run = b  # the backslashes up to b: in pairs (b ends a "\\\\"), or b begins an escape
        while run > lo and text[run - 1] == 0x5C:
            run -= 1
        if (b - run) % 2 == 1:
            return c
        size = 6 if text[b + 1] == 0x75 else 2  # \uXXXX or \n, \", ...
        high = size == 6 and text[b + 2 : b + 4].lower() in (b"d8", b"d9", b"da", b"db")
        if c >= b + size and not high:  # after the escape, and not between the two halves of a surrogate pair
            return c
    return None


def _appends_in_place() -> bool:
    """Whether ``value += part`` on a local ``str`` nothing else refers to grows it in place here: CPython's
    specialised instruction (3.11 on) does (the string is reallocated, a large one by moving its pages, not copying
    them, and only the part is copied); under a trace or profile function (a debugger, coverage) CPython 3.11 runs
    the generic instruction, which makes a new string each time (a copy of all so far per part)."""
    return sys.implementation.name == "cpython" and sys.gettrace() is None and sys.getprofile() is None


def assembled(parts: Iterable[str]) -> str:
    """``"".join(parts)``, each part appended to the value in place as it comes (:func:`_appends_in_place`; else
    joined). A join is one C call that allocates the whole value and writes it, every page of the new allocation
    faulted in during that call: for a 64-million-character document 37-55 ms of processor time under load on the
    2-core machine, the interpreter's lock held throughout. Appended, each call faults only its part's pages. A
    part whose characters need a wider storage than the value so far (the first beyond ASCII, beyond Latin-1,
    beyond the BMP) makes a new value once, a copy of all so far: a document whose first such character comes late
    pays that copy (no worse than the join)."""
    if not _appends_in_place():
        return "".join(parts)
    value = ""
    for part in parts:
        value += part  # in place: `value` is a local nothing else refers to (the parts are not kept)
    return value


def _slice_values(text: bytes, step: int, lo: int, hi: int) -> Iterator[str]:
    """The values of ``text[lo:hi]``'s slices of about ``step`` bytes (see :func:`decode_string`), the interpreter
    let go after each."""
    while hi - lo > step:
        cut = _safe_cut(text, lo, hi, lo + step)
        if cut is None:
            raise ValueError("no place to cut the string")
        yield orjson.loads(b'"' + text[lo:cut] + b'"')
        lo = cut
        time.sleep(0)
    yield orjson.loads(b'"' + text[lo:hi] + b'"')


def decode_string(text: bytes, step: int = STRING_SLICE_BYTES, lo: int = 0, hi: int | None = None) -> str:
    """The value of the JSON string whose text (between its quotes) is ``text[lo:hi]``: ``orjson.loads(b'"' + text
    + b'"')``, decoded ``step`` bytes at a time, the interpreter let go between two slices, the slices' values
    :func:`assembled` (not joined in one call). Raises ``orjson.JSONDecodeError`` (or ValueError: no place to cut)
    where the text is not a string's."""
    return assembled(_slice_values(text, step, lo, len(text) if hi is None else hi))


def _put_back(data: Any, values: dict[str, str], depth: int = 0) -> int:
    """Replace in ``data``'s objects (a few levels down: where requests put their documents) every placeholder value
    by its string; the number replaced."""
    done = 0
    if isinstance(data, dict) and depth < 6:
        for key, value in data.items():
            if isinstance(value, str):
                if value in values:
                    data[key] = values[value]
                    done += 1
            else:
                done += _put_back(value, values, depth + 1)
    return done


def loads_long_strings(
    body: bytes,
    *,
    split_bytes: int = SPLIT_BYTES,
    string_bytes: int = LONG_STRING_BYTES,
    slice_bytes: int = STRING_SLICE_BYTES,
) -> Any:
    """``orjson.loads(body)`` (the same value, or the same ``orjson.JSONDecodeError``), its long string values (a
    document in a field) decoded a slice at a time (see the module's doc)."""
    if len(body) < split_bytes:
        return orjson.loads(body)
    spans: list[tuple[int, int]] = []  # (opening quote, closing quote) of each long string
    pos, strings = body.find(b'"'), 0
    while pos >= 0:  # pos: an opening quote (the text between two strings holds no quote)
        strings += 1
        if strings > MAX_STRINGS:
            return orjson.loads(body)
        end = _string_end(body, pos + 1, slice_bytes)
        if end >= len(body):
            return orjson.loads(body)  # an unclosed string: orjson's error
        if end - pos - 1 > string_bytes:
            spans.append((pos, end))
        pos = body.find(b'"', end + 1)
    if not spans:
        return orjson.loads(body)
    try:
        names = [_PLACEHOLDER % k for k in range(len(spans))]
        pieces, last = [], 0
        for name, (opening, closing) in zip(names, spans, strict=True):
            pieces += [body[last:opening], orjson.dumps(name)]
            last = closing + 1
        pieces.append(body[last:])
        if any(p.find(b"\\u0000") >= 0 for p in pieces[::2]):  # a NUL in the body's own strings: one could be a
            return orjson.loads(body)  # placeholder's text (a string with a NUL is written only as this escape)
        data = orjson.loads(b"".join(pieces))
        values = {name: decode_string(body, slice_bytes, o + 1, c) for name, (o, c) in zip(names, spans, strict=True)}
        # each placeholder found once, as a value (not: a long key, a long string in a list: the whole body at once)
        if _put_back(data, values) != len(spans):
            return orjson.loads(body)
        return data
    except (orjson.JSONDecodeError, ValueError):
        return orjson.loads(body)  # orjson's own value or error for the whole body
