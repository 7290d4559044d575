"""Typed columns as compact bytes, and read back checked: what a job's part keeps (its inputs, its result).

A blob is ``RCOLS`` (5 bytes), a version (uint16 LE), the length of a JSON header (uint32 LE), the header, then the
columns' raw little-endian values one after the other. The header says ``{"columns": [[name, dtype, length], ...],
"meta": {...}}``; the reader is given the names and dtypes it expects (:data:`Schema`) and refuses anything else:
another magic or version, a header that does not parse, a column missing, extra or of another dtype, lengths that
do not add up to the blob's size. Everything read from the job store is untrusted (sealed, but a bug or an old
deployment may have written it), so a blob that does not read raises :class:`ColumnsError` (a ``ValueError``),
never anything else, and the arrays it returns are read-only views of the blob (no copy).

No pickle, no compression (the values are floats: zlib gains little on them and costs more than the rest).
"""

from __future__ import annotations

import struct
from collections.abc import Mapping
from typing import Any

import numpy as np
import orjson

MAGIC = b"RCOLS"
VERSION = 1
_HEAD = struct.Struct("<5sHI")
#: the dtypes a blob may hold (little-endian, fixed size)
DTYPES = frozenset(("<f8", "<i8", "<i4", "|i1", "|u1", "|b1"))

#: column name -> dtype (one of :data:`DTYPES`), in the blob's order
Schema = Mapping[str, str]


class ColumnsError(ValueError):
    """A blob that is not the columns expected (corrupt, truncated, another version or layout)."""


def pack_columns(columns: Mapping[str, np.ndarray], schema: Schema, meta: dict[str, Any] | None = None) -> bytes:
    """``columns`` (1-D arrays, the names and dtypes of ``schema``, in its order) and a JSON-able ``meta`` as bytes."""
    if list(columns) != list(schema):
        raise ValueError(f"columns {list(columns)} are not the schema's {list(schema)}")
    arrays = [
        np.ascontiguousarray(np.asarray(columns[name]).reshape(-1), dtype=dtype) for name, dtype in schema.items()
    ]
    header = orjson.dumps(
        {"columns": [[n, d, a.size] for (n, d), a in zip(schema.items(), arrays, strict=True)], "meta": meta or {}}
    )
    return b"".join([_HEAD.pack(MAGIC, VERSION, len(header)), header, *(a.tobytes() for a in arrays)])


def header_length(prefix: bytes | memoryview) -> int:
    """The bytes a blob's magic, version and header take (what :func:`read_header` needs of it), from its first
    bytes; raises :class:`ColumnsError` when those are not a columns blob's."""
    if len(prefix) < _HEAD.size:
        raise ColumnsError("the columns are truncated (no header)")
    magic, version, size = _HEAD.unpack_from(prefix)
    if magic != MAGIC:
        raise ColumnsError("not a columns blob (bad magic)")
    if version != VERSION:
        raise ColumnsError(f"columns of version {version}, this reader knows {VERSION}")
    return _HEAD.size + size


def read_header(prefix: bytes | memoryview, schema: Schema) -> tuple[dict[str, int], dict[str, Any]]:
    """Each column's length and the meta of a :func:`pack_columns` blob of ``schema``, from its first
    :func:`header_length` bytes or more (the values are not looked at); raises :class:`ColumnsError` for another
    magic, version or layout, or a header that does not parse."""
    start = header_length(prefix)
    if start > len(prefix):
        raise ColumnsError("the columns' header is truncated")
    try:
        header = orjson.loads(bytes(prefix[_HEAD.size : start]))
    except orjson.JSONDecodeError as exc:
        raise ColumnsError(f"the columns' header does not parse: {exc}") from None
    specs = header.get("columns") if isinstance(header, dict) else None
    meta = header.get("meta") if isinstance(header, dict) else None
    if not isinstance(specs, list) or not isinstance(meta, dict):
        raise ColumnsError("the columns' header is not {columns, meta}")
    expected = [[n, d] for n, d in schema.items()]
    if [s[:2] if isinstance(s, list) and len(s) == 3 else None for s in specs] != expected:
        raise ColumnsError(f"the columns are {[s[:2] for s in specs if isinstance(s, list)]}, not {expected}")
    lengths: dict[str, int] = {}
    for name, _, length in specs:
        if type(length) is not int or length < 0:
            raise ColumnsError(f"column {name!r} has no valid length")
        lengths[name] = length
    return lengths, meta


def unpack_columns(data: bytes, schema: Schema) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """The columns (read-only views of ``data``) and the meta of a :func:`pack_columns` blob of ``schema``; raises
    :class:`ColumnsError` for anything else."""
    if not isinstance(data, bytes | bytearray | memoryview):
        raise ColumnsError("the columns are truncated (no header)")
    lengths, meta = read_header(data, schema)
    out: dict[str, np.ndarray] = {}
    offset = header_length(data)
    for name, dtype in schema.items():
        dt = np.dtype(dtype)
        end = offset + lengths[name] * dt.itemsize
        if end > len(data):
            raise ColumnsError(f"column {name!r} is truncated")
        out[name] = np.frombuffer(data, dtype=dt, count=lengths[name], offset=offset)
        offset = end
    if offset != len(data):
        raise ColumnsError(f"{len(data) - offset} bytes after the last column")
    for name, dtype in schema.items():
        if dtype == "|b1" and out[name].view(np.uint8).max(initial=0) > 1:
            raise ColumnsError(f"column {name!r} holds a boolean that is neither 0 nor 1")
    return out, meta


def require(columns: Mapping[str, np.ndarray], names: list[str] | tuple[str, ...], n: int) -> None:
    """Each of ``names`` has ``n`` values (raises :class:`ColumnsError`)."""
    for name in names:
        if columns[name].shape != (n,):
            raise ColumnsError(f"column {name!r} has {columns[name].size} values, not {n}")


def codes_within(values: np.ndarray, low: int, high: int, name: str) -> None:
    """Every code of ``values`` is in [low, high] (raises :class:`ColumnsError`: it would index out of a table)."""
    if values.size and (int(values.min()) < low or int(values.max()) > high):
        raise ColumnsError(f"column {name!r} holds a code outside [{low}, {high}]")


def strings(value: Any, n: int, name: str) -> list[str]:
    """``value`` (from a blob's meta) as a list of ``n`` strings (raises :class:`ColumnsError`)."""
    if not isinstance(value, list) or len(value) != n or set(map(type, value)) - {str}:
        raise ColumnsError(f"{name} is not a list of {n} strings")
    return value
