"""The compiled row writer (app.formats._rowwriter, app/formats/csrc/rowwriter.c) against independent writers:
Python's ``repr`` for every CSV number (random bit patterns: every exponent, subnormals, nan and infinities; powers
of two and ten; integers; decimals of few digits, the writer's shortcut, and the edges of that shortcut), orjson for
every JSON number, and the Python writer of app.formats.segments for whole layouts (the two must write the same
bytes: the Python writer is what runs where the module was not built).

Where the module was not built (no C compiler), these tests skip; under CI=true they fail: the deployment image and
CI build it (setup.py, the Dockerfile's build stage)."""

from __future__ import annotations

import math
import os

import numpy as np
import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.formats import segments
from app.formats.segments import SMALL_TABLE, Codes, Floats, Slices, write_rows


@pytest.fixture(scope="module")
def rowwriter():
    if segments._rowwriter is None:
        if os.environ.get("CI") == "true":
            pytest.fail("app.formats._rowwriter was not built: setup.py needs a C compiler and Python's headers")
        pytest.skip("app.formats._rowwriter was not built here (no C compiler): the Python writer runs")
    return segments._rowwriter


def _lines(rowwriter, values: np.ndarray, mode: int) -> list[bytes]:
    return rowwriter.write([(1, np.ascontiguousarray(values, dtype=np.float64), mode), b"\n"], len(values), 0).split(
        b"\n"
    )[:-1]


def _repr(x: float) -> bytes:
    return b"" if math.isnan(x) else repr(x).encode()


def _samples(rng: np.random.Generator) -> dict[str, np.ndarray]:
    n = 100_000
    k = rng.integers(0, 7, n)
    edges = np.array([1e-4, 1e16, 1e12, 1e15, 0.0005, 0.5, 999_999_999_999.999, 2.0**53, 2.0**53 + 2, 9.5, 0.1 + 0.2])
    return {
        "random bit patterns": rng.integers(0, 2**64, 4 * n, dtype=np.uint64).view(np.float64),
        "subnormals": rng.integers(0, 2**52, n, dtype=np.uint64).view(np.float64),
        "powers of two": np.ldexp(1.0, np.arange(-1074, 1024)),
        "powers of ten": 10.0 ** np.arange(-323, 309),
        "integers": rng.integers(-(2**53), 2**53, n).astype(np.float64),
        "0 to 6 decimals": np.round(rng.uniform(-2000, 2000, n) * 10.0**k) / 10.0**k,
        "0 to 6 decimals, small": np.round(rng.uniform(0, 1, n) * 10.0**k) / 10.0**k,
        "edges and their neighbours": np.concatenate(
            [edges, np.nextafter(edges, 0), np.nextafter(edges, np.inf), -edges]
        ),
        "special": np.array([0.0, -0.0, math.nan, -math.nan, math.inf, -math.inf, 5e-324, 1.7976931348623157e308]),
    }


@pytest.mark.parametrize("seed", [1, 2])
def test_csv_numbers_are_written_as_repr_writes_them(rowwriter, seed):
    """Mode 0: each float as ``repr`` (positional in [1e-4, 1e16), else ``1e-05``/``1e+16``), nan an empty field."""
    for name, values in _samples(np.random.default_rng(seed)).items():
        got = _lines(rowwriter, values, 0)
        expected = [_repr(x) for x in values.tolist()]
        bad = [(x, g, e) for x, g, e in zip(values.tolist(), got, expected, strict=True) if g != e]
        assert not bad, f"{name}: {len(bad)} differ, e.g. {bad[:3]}"


@pytest.mark.parametrize("seed", [1, 2])
def test_json_numbers_are_written_as_orjson_writes_them(rowwriter, seed):
    """Mode 1, on the values the compiled writer is given JSON numbers of (segments.repr_safe: orjson and repr agree
    there): orjson's text, nan and infinities ``null``."""
    for name, values in _samples(np.random.default_rng(seed)).items():
        a = np.abs(values)
        values = np.concatenate([values[(a == 0) | ((a >= 1e-4) & (a < 1e16))], [math.nan, math.inf, -math.inf]])
        expected = orjson.dumps(values.tolist())[1:-1].split(b",")
        assert _lines(rowwriter, values, 1) == expected, name


_FLOAT = st.floats(allow_nan=True, allow_infinity=True)
_SHORT = st.integers(-(10**9), 10**9).flatmap(lambda m: st.sampled_from([m / 10**k for k in range(5)]))
_TEXT = st.binary(max_size=6)


@st.composite
def _layouts(draw):
    """A layout of every segment kind (constants, per-row texts as bytes and as slices of a blob, small and large
    code tables, CSV float blocks and
    JSON float columns, of numbers of every magnitude and of few decimals), its row count and a drop."""
    n = draw(st.integers(0, 12))
    layout = []
    for _ in range(draw(st.integers(1, 8))):
        kind = draw(st.sampled_from(["constant", "texts", "slices", "codes", "csv", "json"]))
        if kind == "constant":
            layout.append(draw(_TEXT))
        elif kind == "slices":
            blob = draw(st.binary(max_size=30))
            bounds = [sorted(draw(st.lists(st.integers(0, len(blob)), min_size=2, max_size=2))) for _ in range(n)]
            layout.append(Slices(blob, np.array([a for a, _ in bounds], np.intp), np.array([b for _, b in bounds])))
        elif kind == "texts":
            layout.append(draw(st.lists(_TEXT, min_size=n, max_size=n)))
        elif kind == "codes":
            size = draw(st.sampled_from([1, 2, 3, SMALL_TABLE + 3]))
            texts = [draw(_TEXT) for _ in range(min(size, 3))] + [b"%d" % k for k in range(size - min(size, 3))]
            codes = draw(st.lists(st.integers(0, size - 1), min_size=n, max_size=n))
            layout.append(Codes(np.array(codes, dtype=np.intp), texts))
        else:
            width = 1 if kind == "json" else draw(st.integers(1, 3))
            columns = [
                np.array(draw(st.lists(st.one_of(_FLOAT, _SHORT), min_size=n, max_size=n)), dtype=np.float64)
                for _ in range(width)
            ]
            layout.append(Floats(columns, json=kind == "json"))
    return layout, n, draw(st.integers(0, 3))


@settings(max_examples=300, deadline=None)
@given(_layouts())
def test_the_compiled_writer_writes_what_the_python_writer_writes(rowwriter, layout):
    segments_, n, drop = layout
    compiled = write_rows(segments_, n, drop=drop)
    saved = segments._rowwriter
    segments._rowwriter = None
    try:
        python = write_rows(segments_, n, drop=drop)
    finally:
        segments._rowwriter = saved
    assert compiled == python


def test_a_json_column_outside_repr_s_range_is_written_by_orjson(rowwriter):
    """orjson writes 5e-05 as 0.00005: such a column is not given to the compiled writer."""
    column = np.array([5e-05, 1e16, 1.5, math.nan])
    expected = b"".join(b"[" + x + b"]" for x in orjson.dumps(column.tolist())[1:-1].split(b","))
    assert expected.startswith(b"[0.00005]")
    assert write_rows([b"[", Floats([column], json=True), b"]"], 4) == expected
    assert write_rows([Floats([column]), b";"], 4) == b"5e-05;1e+16;1.5;;"


def test_bad_layouts_are_refused(rowwriter):
    n = 2
    floats = np.array([1.0, 2.0])
    with pytest.raises(ValueError, match="segment 1 has 1 rows, not 2"):
        rowwriter.write([b"a", [b"1"]], n, 0)
    with pytest.raises(ValueError, match="segment 0 has 3 rows, not 2"):
        rowwriter.write([(1, np.array([1.0, 2.0, 3.0]), 0)], n, 0)
    with pytest.raises(ValueError, match="a code outside its table"):
        rowwriter.write([(0, np.array([0, 2], dtype=np.intp), (b"x", b"y"))], n, 0)
    with pytest.raises(ValueError, match="a code outside its table"):
        rowwriter.write([(0, np.array([-1, 0], dtype=np.intp), (b"x",))], n, 0)
    with pytest.raises(TypeError, match="values must be a buffer of 8-byte items"):
        rowwriter.write([(1, np.array([1, 2], dtype=np.int64), 0)], n, 0)
    with pytest.raises(TypeError, match="codes must be a buffer"):
        rowwriter.write([(0, floats.astype(np.int32), (b"x",))], n, 0)
    with pytest.raises((ValueError, BufferError), match="contiguous"):
        rowwriter.write([(1, np.array([1.0, 0, 2.0])[::2], 0)], n, 0)
    with pytest.raises(TypeError, match="must be bytes"):
        rowwriter.write([["1", "2"]], n, 0)
    with pytest.raises(TypeError, match="must be bytes, a list of bytes"):
        rowwriter.write([3.5], n, 0)
    with pytest.raises(ValueError, match="mode must be 0"):
        rowwriter.write([(1, floats, 2)], n, 0)
    with pytest.raises(ValueError, match=r"row 1: \[2, 4\) is not a range of the blob's 3 bytes"):
        rowwriter.write([(2, b"abc", np.array([0, 2], np.intp), np.array([1, 4], np.intp))], n, 0)
    with pytest.raises(ValueError, match=r"row 0: \[2, 1\) is not a range"):
        rowwriter.write([(2, b"abc", np.array([2, 0], np.intp), np.array([1, 1], np.intp))], n, 0)
    with pytest.raises(TypeError, match="the blob must be bytes"):
        rowwriter.write([(2, "abc", np.array([0, 0], np.intp), np.array([1, 1], np.intp))], n, 0)
    assert rowwriter.write([(2, b"abc", np.array([0, 1], np.intp), np.array([1, 3], np.intp)), b";"], n, 0) == (
        b"a;bc;"
    )
    assert rowwriter.write([b"ab", (1, floats, 0)], n, 3) == b".0ab2.0"
    assert rowwriter.write([b"ab", (1, floats, 0)], n, 99) == b""
    assert rowwriter.write([b"ab"], 0, 0) == b""
