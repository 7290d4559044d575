"""JSON rows written column by column: a table (field name -> values) as JSON objects, byte for byte what
``orjson.dumps`` writes for the same rows, without a dict per row (a 100,000-row alignment answer is 76 MB)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import orjson


class RawJson(list):
    """A column of values already written as JSON (one ``bytes`` each, as orjson writes them: no raw control
    character), for :func:`json_template` and :func:`json_objects`."""


#: the types orjson writes without a comma inside: a column of only these is written in one call, split at its commas
_PLAIN = frozenset((float, int, bool, type(None)))


def _json_column(values: Sequence[Any], glue: bytes) -> bytes:
    """The JSON of each of ``values`` (``orjson.dumps(v)``: a float nan or infinity is ``null``), joined by ``glue``.
    A column of numbers, booleans and nulls is written in one call and its commas replaced."""
    if isinstance(values, RawJson):
        return glue.join(values)
    if values and set(map(type, values)) <= _PLAIN:
        return orjson.dumps(values)[1:-1].replace(b",", glue)
    return glue.join(map(orjson.dumps, values))


def json_template(fragments: Sequence[bytes], columns: Sequence[Sequence[Any]], before_row: bytes = b"") -> bytes:
    """Rows of the template ``fragments[0] value_0 fragments[1] value_1 ... fragments[-1]`` (the values of row i the
    JSON of ``columns[j][i]``, :func:`_json_column`), each preceded by ``before_row``, in one text. Each column is
    written at once and cut into its rows at a byte orjson never writes (JSON escapes control characters); the rows
    are put together by slice assignment, with no Python work per row."""
    if len(fragments) != len(columns) + 1:
        raise ValueError(f"{len(columns)} columns need {len(columns) + 1} fragments, not {len(fragments)}")
    n = len(columns[0]) if columns else 0
    if not n:
        return b""
    width = len(columns)
    parts: list[bytes] = [b""] * (width * n)  # row by row, value by value
    for j, values in enumerate(columns):
        if len(values) != n:
            raise ValueError(f"column {j} has {len(values)} values, not {n}")
        start = before_row + fragments[0] if j == 0 else fragments[j]
        end = fragments[-1] if j == width - 1 else b""
        parts[j::width] = (start + _json_column(values, end + b"\x01" + start) + end).split(b"\x01")
    return b"".join(parts)


def _json_rows_text(columns: Mapping[str, Sequence[Any]], before_row: bytes) -> bytes:
    """The rows of ``columns`` as JSON objects, each preceded by ``before_row``, in one text."""
    keys = [orjson.dumps(name) + b":" for name in columns]
    fragments = [b"{" + keys[0], *(b"," + k for k in keys[1:]), b"}"] if keys else [b"{}"]
    return json_template(fragments, list(columns.values()), before_row)


def json_objects(columns: Mapping[str, Sequence[Any]]) -> bytes:
    """A table given column by column (field name -> equal-length values, in field order) as JSON objects separated
    by commas: byte for byte ``orjson.dumps([dict(zip(names, row)) for row in zip(*columns.values())])`` without its
    brackets (a chunk of a streamed JSON list; a 100,000-row alignment answer is 76 MB), without a dict per row
    (:func:`json_template`). A :class:`RawJson` column is taken as written."""
    return _json_rows_text(columns, b",")[1:]
