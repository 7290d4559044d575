"""Rows of text put together from segments, with no Python work per cell.

A row layout is a list of *segments*: a constant (``bytes``: a separator, a JSON key, a line end), a column of
per-row texts (``list[bytes]``, one per row, or :class:`Slices` of one blob), numbers (:class:`Floats`), or
:class:`Codes` (a small table of texts and each row's index into it: a boolean, a category, an error, or anything
shared by many rows such as the cells that depend only on a row's SRT). :func:`write_rows` writes ``n`` rows of a
layout as one text: constants are merged, a small code table takes in the constants beside it (its texts are
written once, not once per row), two code columns side by side become one.

Numbers come as :class:`Floats` (a block of float columns, written as CSV or JSON). Two writers take a layout:

- the compiled one, ``app.formats._rowwriter`` (``app/formats/csrc/rowwriter.c``, built by ``setup.py`` where a C
  compiler is found), writes each number with Ryu's shortest digits in ``repr``'s layout and the rows without a
  Python object per cell, with the GIL released: a job's result is rendered on GET while the event loop sends it
  (``bench/bench_jobs.py``: the streaming figures of docs/jobs.md);
- the Python one (the reference, and what runs where the module was not built) writes the numbers with ``orjson``
  a whole block at a time (:func:`json_floats`, :func:`csv_floats`: a Python call per number would cost more than
  everything else it takes to write the row) and puts the rows together by slice assignment and one ``join``.

Both write the same bytes (tests/api/test_rowwriter.py, on random layouts and numbers of every magnitude).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import orjson

try:
    from app.formats import _rowwriter
except ImportError:  # built without a C compiler: the Python writer (the same text, slower)
    _rowwriter = None

#: a code table of at most this many texts takes in the constants beside it, and two such side by side are merged
SMALL_TABLE = 256


@dataclass(frozen=True)
class Codes:
    """A column given as each row's index (``codes``, integers) into ``texts``."""

    codes: np.ndarray
    texts: Sequence[bytes]

    def rows(self) -> list[bytes]:
        table = np.empty(len(self.texts), dtype=object)
        table[:] = list(self.texts)
        return table[self.codes].tolist()


@dataclass(frozen=True)
class Floats:
    """Consecutive float columns written as CSV fields joined by commas (:func:`csv_floats`), or one column as
    JSON numbers (``json``: :func:`json_floats`)."""

    columns: Sequence[np.ndarray]
    json: bool = False

    def rows(self) -> list[bytes]:
        if self.json:
            (values,) = self.columns
            return json_floats(values)
        return csv_floats(self.columns)

    def compiled(self) -> list[bytes | tuple | list[bytes]]:
        """The block as segments of the compiled writer: a column a segment (commas between for CSV). A JSON column
        with a value orjson writes otherwise than ``repr`` (the compiled writer's layout) comes written by orjson."""
        if self.json:
            (values,) = self.columns
            values = np.ascontiguousarray(values, dtype=np.float64)
            return [(1, values, 1)] if repr_safe(values) else [json_floats(values)]
        out: list[bytes | tuple | list[bytes]] = []
        for k, values in enumerate(self.columns):
            out += [b","] if k else []
            out.append((1, np.ascontiguousarray(values, dtype=np.float64), 0))
        return out


@dataclass(frozen=True)
class Slices:
    """A column of texts given as slices of one blob: row i's text is ``blob[starts[i]:ends[i]]``
    (:class:`app.formats.texts.Texts`: no bytes object per row for the compiled writer)."""

    blob: bytes
    starts: np.ndarray
    ends: np.ndarray

    def rows(self) -> list[bytes]:
        blob = self.blob
        return [blob[a:b] for a, b in zip(self.starts.tolist(), self.ends.tolist(), strict=True)]

    def compiled(self) -> tuple:
        return (2, self.blob, np.ascontiguousarray(self.starts, np.intp), np.ascontiguousarray(self.ends, np.intp))


Segment = bytes | list[bytes] | Codes | Floats | Slices


def _small(s: Segment) -> bool:
    return isinstance(s, Codes) and len(s.texts) <= SMALL_TABLE


def _absorbed(segments: Sequence[Segment]) -> list[Segment]:
    """The layout with consecutive constants merged and each constant taken into a small code table beside it (the
    one before it first)."""
    merged: list[Segment] = []
    for s in segments:
        if isinstance(s, bytes) and merged and isinstance(merged[-1], bytes):
            merged[-1] += s
        else:
            merged.append(s)
    out: list[Segment] = []
    for s in merged:
        last = out[-1] if out else None
        if isinstance(s, bytes) and _small(last):
            out[-1] = Codes(last.codes, [t + s for t in last.texts])
        elif _small(s) and isinstance(last, bytes):
            out[-1] = Codes(s.codes, [last + t for t in s.texts])
        else:
            out.append(s)
    return out


def _joined_codes(segments: list[Segment]) -> list[Segment]:
    """Two small code tables side by side made one (each pair of texts used written once)."""
    out: list[Segment] = []
    for s in segments:
        last = out[-1] if out else None
        if _small(s) and _small(last) and len(last.texts) * len(s.texts) <= SMALL_TABLE:
            k = len(s.texts)
            out[-1] = Codes(last.codes * k + s.codes, [a + b for a in last.texts for b in s.texts])
        else:
            out.append(s)
    return out


def write_rows(segments: Sequence[Segment], n: int, *, drop: int = 0) -> bytes:
    """``n`` rows of the layout ``segments`` as one text (each row its segments' texts in order), less its first
    ``drop`` bytes (a separator before the first row), by the compiled writer where it was built."""
    if n == 0:
        return b""
    layout = _joined_codes(_absorbed(segments))
    return _write_compiled(layout, n, drop) if _rowwriter is not None else _write_python(layout, n, drop)


def _write_compiled(layout: list[Segment], n: int, drop: int) -> bytes:
    items: list[bytes | tuple | list[bytes]] = []
    for s in layout:
        if isinstance(s, Floats):
            items += s.compiled()
        elif isinstance(s, Slices):
            items.append(s.compiled())
        elif isinstance(s, Codes):
            items.append((0, np.ascontiguousarray(s.codes, dtype=np.intp), tuple(s.texts)))
        else:
            items.append(s if isinstance(s, bytes | list) else list(s))
    return _rowwriter.write(items, n, drop)


def _write_python(layout: list[Segment], n: int, drop: int) -> bytes:
    """The rows put together by slice assignment and one ``join`` (the first ``drop`` bytes cut from the parts
    before the join, not by copying the text)."""
    width = len(layout)
    parts: list[bytes] = [b""] * (width * n)
    for j, s in enumerate(layout):
        if isinstance(s, bytes):
            parts[j::width] = [s] * n
            continue
        values = s.rows() if isinstance(s, Codes | Floats | Slices) else s
        if len(values) != n:
            raise ValueError(f"segment {j} has {len(values)} rows, not {n}")
        parts[j::width] = values
    k = 0
    while drop and k < len(parts):  # the text's first ``drop`` bytes, whichever parts they fall in
        cut = min(drop, len(parts[k]))
        parts[k], drop, k = parts[k][cut:], drop - cut, k + 1
    return b"".join(parts)


def json_floats(values: np.ndarray) -> list[bytes]:
    """Each float as orjson writes it (the shortest text that reads back to it; nan and infinities ``null``)."""
    if not len(values):
        return []
    return orjson.dumps(values.tolist())[1:-1].split(b",")


def repr_safe(block: np.ndarray) -> bool:
    """Whether orjson writes every value of ``block`` as ``repr`` does (nan aside): it does for every finite float in
    [1e-4, 1e16) in magnitude and for zero, and differs below and above (``0.00005`` for ``5e-05``, ``1e16`` for
    ``1e+16``) and for infinities (``null``)."""
    a = np.abs(block)  # a nan compares false: never a reason
    return not (np.any(a >= 1e16) or np.any((a < 1e-4) & (a != 0)))


def csv_floats(columns: Sequence[np.ndarray]) -> list[bytes]:
    """Consecutive float columns as the CSV fields of each row, joined by commas: each value as ``repr`` writes it,
    nan as an empty field (the table of :mod:`app.formats.tables`). One ``orjson`` call for the block; a block
    holding a value orjson writes otherwise than ``repr`` is written value by value."""
    block = np.column_stack([np.asarray(c, dtype=np.float64) for c in columns])
    if not len(block):
        return []
    if not repr_safe(block):
        return [
            ",".join("" if x != x else repr(x) for x in row).encode()  # x != x: nan
            for row in block.tolist()
        ]
    if block.shape[1] == 1:
        text = orjson.dumps(block[:, 0].tolist())[1:-1]
        sep = b","
    else:
        # orjson writes a C-ordered float64 array as it writes the same floats in lists (tested), without the
        # nested lists ``tolist`` would make (a list per row: most of the time)
        text = orjson.dumps(block, option=orjson.OPT_SERIALIZE_NUMPY)[2:-2]
        sep = b"],["
    if np.isnan(block).any():
        text = text.replace(b"null", b"")
    return text.split(sep)
