"""Rows put together from segments (app.formats.segments: what the alignment answers, synchronous and as jobs, are
written with) against independent writers: orjson's JSON of the row dicts, and the CSV of app.formats.tables written
cell by cell, on columns of every kind: floats of every magnitude (exponent forms, below 1e-4, -0.0, nan,
infinities), code columns small and large side by side, texts that need escaping."""

from __future__ import annotations

import math

import numpy as np
import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.formats.segments import SMALL_TABLE, Codes, csv_floats, json_floats, write_rows
from app.formats.tables import csv_lines_cellwise

_FLOAT = st.floats(allow_nan=True, allow_infinity=True)
_JSONABLE = st.one_of(st.none(), st.booleans(), st.integers(-(2**53), 2**53), _FLOAT, st.text(max_size=6))


@st.composite
def _layouts(draw):
    """Fields of a row (name -> ("floats", array) | ("codes", codes, table)) and the row count."""
    n = draw(st.integers(0, 9))
    names = draw(st.lists(st.text(min_size=1, max_size=5), min_size=1, max_size=6, unique=True))
    fields = {}
    for name in names:
        if draw(st.booleans()):
            fields[name] = ("floats", np.array(draw(st.lists(_FLOAT, min_size=n, max_size=n)), dtype=np.float64))
        else:
            size = draw(st.sampled_from([1, 2, 3, SMALL_TABLE + 5]))
            table = [draw(_JSONABLE) for _ in range(min(size, 4))] + [k for k in range(size - min(size, 4))]
            codes = draw(st.lists(st.integers(0, size - 1), min_size=n, max_size=n))
            fields[name] = ("codes", np.array(codes, dtype=np.intp), table)
    return fields, n


@settings(max_examples=200, deadline=None)
@given(_layouts())
def test_json_rows_from_segments_are_orjsons_json_of_the_row_dicts(layout):
    fields, n = layout
    segments, expected = [], [dict() for _ in range(n)]
    for k, (name, spec) in enumerate(fields.items()):
        segments.append((b"{" if k == 0 else b",") + orjson.dumps(name) + b":")
        if spec[0] == "floats":
            segments.append(json_floats(spec[1]))
            values = spec[1].tolist()
        else:
            segments.append(Codes(spec[1], [orjson.dumps(x) for x in spec[2]]))
            values = [spec[2][c] for c in spec[1].tolist()]
        for row, value in zip(expected, values, strict=True):
            row[name] = value
    segments.append(b"}\n")
    assert write_rows(segments, n) == b"".join(orjson.dumps(r) + b"\n" for r in expected)


_SPECIAL = [0.0, -0.0, 1e-4, 9.99e-5, 1e16, 9.999999999999998e15, 5e-324, 1.7976931348623157e308, 0.1 + 0.2, 123.0]


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("width", [1, 3])
def test_csv_float_blocks_are_each_value_written_by_repr(seed, width):
    """csv_floats: each value as repr writes it (what the cell-by-cell CSV writes), nan empty; a block with a value
    orjson writes otherwise (exponent forms, below 1e-4, infinities) is written value by value, the same text."""
    rng = np.random.default_rng(seed)
    n = 200
    plain = rng.uniform(-1000, 1000, (n, width)) * np.pi
    plain[rng.random((n, width)) < 0.2] = np.nan
    wide = rng.uniform(-10, 10, (n, width)) * 10.0 ** rng.integers(-30, 30, (n, width))
    wide.flat[: len(_SPECIAL)] = _SPECIAL
    wide[5, 0] = -math.inf
    for block in (plain, wide):
        cells = [[None if math.isnan(x) else x for x in block[:, j].tolist()] for j in range(width)]
        expected = csv_lines_cellwise(cells).split(b"\r\n")[:-1]
        assert csv_floats([block[:, j] for j in range(width)]) == expected
    assert csv_floats([np.array([])]) == []


def test_small_code_tables_take_in_their_constants_and_join_their_neighbours():
    """The layout [a, ',', codes(2), ',', codes(3), '!'] writes each row as its parts, whatever is merged."""
    a = [b"x", b"y", b"z", b"w"]
    one, two = np.array([0, 1, 1, 0]), np.array([2, 0, 1, 2])
    text = write_rows([a, b",", Codes(one, [b"T", b"F"]), b",", Codes(two, [b"p", b"q", b"r"]), b"!"], 4)
    assert text == b"x,T,r!y,F,p!z,F,q!w,T,r!"
    big = Codes(np.array([3, 0]), [str(k).encode() for k in range(SMALL_TABLE + 1)])
    assert write_rows([b"<", big, b">", big, b"|"], 2) == b"<3>3|<0>0|"
    assert write_rows([b"a", [b"1"]], 0) == b""
    with pytest.raises(ValueError, match="segment 1 has 1 rows, not 2"):
        write_rows([b"a", [b"1"], b"b", [b"1", b"2"]], 2)
