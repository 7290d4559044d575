"""app.jobs.columns: typed columns as bytes, read back checked (the store is untrusted)."""

from __future__ import annotations

import numpy as np
import pytest

from app.jobs.columns import ColumnsError, codes_within, pack_columns, require, strings, unpack_columns

SCHEMA = {"x": "<f8", "flag": "|b1", "code": "|i1", "n": "<i4"}


def _cols(n: int = 5) -> dict[str, np.ndarray]:
    return {
        "x": np.array([0.1, -0.0, np.nan, np.inf, 1e300])[:n],
        "flag": np.array([True, False, True, False, True])[:n],
        "code": np.array([0, 1, 2, 1, 0])[:n],
        "n": np.array([-1, 0, 5, 7, 2**31 - 1])[:n],
    }


def test_columns_round_trip_bit_for_bit_with_their_meta():
    blob = pack_columns(_cols(), SCHEMA, {"ids": ["a", "b"]})
    cols, meta = unpack_columns(blob, SCHEMA)
    assert meta == {"ids": ["a", "b"]}
    for name, values in _cols().items():
        assert cols[name].dtype == np.dtype(SCHEMA[name])
        assert cols[name].tobytes() == values.astype(SCHEMA[name]).tobytes()
    require(cols, list(SCHEMA), 5)
    empty, _ = unpack_columns(pack_columns(_cols(0), SCHEMA), SCHEMA)
    assert all(a.size == 0 for a in empty.values())


@pytest.mark.parametrize(
    "damage",
    [
        lambda b: b[:3],
        lambda b: b[:-1],
        lambda b: b + b"\x00",
        lambda b: b"ZCOLS" + b[5:],
        lambda b: b[:5] + b"\x02\x00" + b[7:],
        lambda b: b[:7] + b"\xff\xff\xff\x00" + b[11:],  # a header longer than the blob
        lambda b: b[:11] + b"x" + b[12:],  # a header that does not parse
        lambda b: b[:11] + b"[" + b[12:],  # nor as an object
    ],
)
def test_a_damaged_blob_raises_columns_error_and_nothing_else(damage):
    with pytest.raises(ColumnsError):
        unpack_columns(damage(pack_columns(_cols(), SCHEMA)), SCHEMA)


def test_another_layout_or_a_boolean_that_is_not_0_or_1_is_refused():
    blob = pack_columns(_cols(), SCHEMA)
    with pytest.raises(ColumnsError, match="not"):
        unpack_columns(blob, {**SCHEMA, "x": "<i8"})
    with pytest.raises(ColumnsError):
        unpack_columns(blob, {"x": "<f8"})
    raw = bytearray(blob)
    at = raw.index(np.array([True, False, True, False, True]).tobytes())
    raw[at] = 2
    with pytest.raises(ColumnsError, match="boolean"):
        unpack_columns(bytes(raw), SCHEMA)


def test_lengths_codes_and_strings_are_checked():
    cols, _ = unpack_columns(pack_columns(_cols(), SCHEMA), SCHEMA)
    with pytest.raises(ColumnsError):
        require(cols, ["x"], 4)
    codes_within(cols["code"], 0, 2, "code")
    with pytest.raises(ColumnsError):
        codes_within(cols["code"], 0, 1, "code")
    assert strings(["a"], 1, "ids") == ["a"]
    for bad in (None, ["a", 1], ["a"] * 2, "ab"):
        with pytest.raises(ColumnsError):
            strings(bad, 2 if bad != ["a"] * 2 else 3, "ids")
