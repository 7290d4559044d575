"""A job's CSV curves read straight into columns: the fast path of :func:`app.formats.alignment_io.read_csv` for the
plain form (comma-separated, no quotes, one curve per line, ``\\n`` or ``\\r\\n``), which a million-curve job
almost always is.

The text is read as bytes with numpy, without a Python object per field: the separators are found at once (every line
must have its k - 1 commas), and each numeric column is parsed a character position at a time over all its fields
(:func:`app.formats.decimals.decimals`). A field of the plain decimal form ``[+-]digits[.digits]`` with at most 15
significant digits is its integer significand M, read exactly, divided by 10^f (f its digits after the point, at most
22): both are exact doubles, so IEEE division rounds the quotient correctly, and that is the double ``float`` returns
for the text, bit for bit (Clinger 1990, "How to read floating point numbers accurately", PLDI '90, the fast path;
Python's ``float`` rounds correctly, Gay's dtoa). Any other field (an exponent, spaces, underscores, more digits, other
characters) is read by ``float`` itself, alone, so the table is always ``read_csv``'s. Only the ids become Python
strings (stripped, checked: empty, too long, duplicates).

It never decides an error: whatever it does not take as plain, or any check that fails, sends the text to
:func:`~app.formats.alignment_io.read_csv` (``None`` from :func:`read_csv_columns`), which reads it again and reports
the first bad line and field as it always does (and knows the dialects the fast path leaves to it). A table it does
answer is the table ``read_csv`` would answer (the job tests compare them), except that its ``where`` (each curve's
row, for error messages) is computed when asked for (:class:`RowNames`) instead of kept as a million strings.

Why bytes and numpy: a million curves as ``str.split`` fields are five million Python strings (about 300 MB) and
``float`` of four million of them, most of the submission's time (``bench/bench_jobs.py``).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import overload

import numpy as np

from app.formats.alignment_io import (
    CSV_OPTIONAL,
    CSV_REQUIRED,
    CURVE_ID_MAX_CHARS,
    CURVE_ID_REFUSED,
    MAX_CURVES,
    CurveTable,
)
from app.formats.csv_dialect import CsvDialect
from app.formats.decimals import decimals
from engine import InvalidRoad
from engine.road import check_columns

#: what the plain form has no place for: quotes, control characters but the line ends (and a BOM: a dialect)
_NOT_PLAIN = re.compile(r'["\x00-\x09\x0b\x0c\x0e-\x1f\x7f-\x9f\ufeff]')
#: the same, for ASCII bytes (the line ends are ``\n`` by then)
_NOT_PLAIN_BYTE = np.zeros(256, dtype=bool)
_NOT_PLAIN_BYTE[[*range(0x00, 0x0A), *range(0x0B, 0x20), 0x22, 0x7F]] = True

_COMMA, _NEWLINE = (ord(c) for c in ",\n")
#: a column with more fields than this (or 1/64 of them) not plain is read by float over its strings at once
_FEW_ODD = 64
#: the numeric columns: (name, may be empty, the value of an empty field), as read_csv reads them
_NUMERIC = (
    ("radius_m", False, math.nan),
    ("superelevation_percent", True, math.nan),
    ("grade_percent", True, 0.0),
    ("posted_speed_kmh", True, math.nan),
)


class RowNames(Sequence[str]):
    """``row <n>`` of the curves of a plain CSV (the first curve on row 2, one curve per line), made when asked for."""

    def __init__(self, start: int, stop: int) -> None:
        self.start, self.stop = start, stop

    def __len__(self) -> int:
        return self.stop - self.start

    @overload
    def __getitem__(self, i: int) -> str: ...
    @overload
    def __getitem__(self, i: slice) -> RowNames: ...
    def __getitem__(self, i):
        if isinstance(i, slice):
            a, b, step = i.indices(len(self))
            if step != 1:
                return [self[k] for k in range(a, b, step)]
            return RowNames(self.start + a, self.start + max(a, b))
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        return f"row {self.start + i + 2}"


def _numbers(
    buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, *, optional: bool, empty: float
) -> np.ndarray | None:
    """A numeric column: ``float`` of each field ``buf[starts[i]:ends[i]]`` (an empty or blank one ``empty`` when
    ``optional``); None when a field is not a finite number (``read_csv`` says which). Plain decimals are read a
    character position at a time over the whole column (:func:`decimals`); the others by ``float``."""
    n = starts.size
    values, plain, _ = decimals(buf, starts, ends)
    odd = np.flatnonzero(~plain)
    if odd.size > max(_FEW_ODD, n // 64):  # a column of another form (spaces after the commas, exponents): float
        return _floats(_fields(buf, starts, ends), optional=optional, empty=empty)  # over its strings at once
    for i in odd.tolist():  # the odd field: float's own reading of it
        value = _float(buf[starts[i] : ends[i]].tobytes().decode(), optional=optional, empty=empty)
        if value is None:
            return None
        values[i] = value
    return values


def _float(field: str, *, optional: bool, empty: float) -> float | None:
    """``float(field)`` (``empty`` for a blank field when ``optional``); None when it is not a finite number."""
    try:
        value = float(field)
    except ValueError:
        return empty if optional and not field.strip() else None
    return value if math.isfinite(value) else None


def _floats(fields: list[str], *, optional: bool, empty: float) -> np.ndarray | None:
    """:func:`_numbers` of a column given as strings: ``float`` over all of them in one ``map``."""
    try:
        values = np.fromiter(map(float, fields), dtype=np.float64, count=len(fields))
    except ValueError:
        out = [_float(f, optional=optional, empty=empty) for f in fields]
        return None if None in out else np.array(out, dtype=np.float64)
    return values if np.all(np.isfinite(values)) else None


def _trailing_blank_lines(body: str) -> str:
    """``body`` less its trailing lines of nothing but commas and spaces (a final newline, an empty row): not curves."""
    end = len(body)
    while end > 0:
        start = body.rfind("\n", 0, end) + 1
        if body[start:end].replace(",", "").strip():
            break
        end = start - 1
    return body[: max(end, 0)]


def read_csv_columns(text: str, *, max_curves: int = MAX_CURVES) -> CurveTable | None:
    """The curves of a plain CSV text as columns, or None when the text is not plain or does not pass a check (then
    :func:`~app.formats.alignment_io.read_csv` reads it and says why)."""
    line_ending = "LF"
    if "\r" in text:
        text = text.replace("\r\n", "\n")
        if "\r" in text:
            return None
        line_ending = "CRLF"
    if not text.isascii() and _NOT_PLAIN.search(text):  # ASCII: the bytes are checked below
        return None
    head, sep, body = text.partition("\n")
    names = [h.strip().lower() for h in head.split(",")]
    known = CSV_REQUIRED + CSV_OPTIONAL
    if not sep or len(set(names)) != len(names) or not set(CSV_REQUIRED) <= set(names) <= set(known):
        return None
    data = (_trailing_blank_lines(body) + "\n").encode()
    buf = np.frombuffer(data, dtype=np.uint8)
    if np.any(_NOT_PLAIN_BYTE[buf]) or _NOT_PLAIN_BYTE[np.frombuffer(head.encode(), dtype=np.uint8)].any():
        return None
    k = len(names)
    separators = np.flatnonzero((buf == _COMMA) | (buf == _NEWLINE))
    n = separators.size // k
    if n == 0 or n > max_curves or separators.size != n * k:
        return None
    ends = separators.reshape(n, k)
    kinds = buf[ends]  # every line its k - 1 commas and its newline
    if not (np.all(kinds[:, -1] == _NEWLINE) and np.all(kinds[:, :-1] == _COMMA)):
        return None

    def field(name: str) -> tuple[np.ndarray, np.ndarray]:  # (start, end) of a column's fields in buf
        j = names.index(name)
        if j:
            return ends[:, j - 1] + 1, ends[:, j]
        starts = np.empty(n, dtype=ends.dtype)
        starts[0], starts[1:] = 0, ends[:-1, -1] + 1
        return starts, ends[:, 0]

    ids = list(map(str.strip, _fields(buf, *field("id"))))
    if not all(ids) or max(map(len, ids)) > CURVE_ID_MAX_CHARS or len(set(ids)) != n:
        return None
    if CURVE_ID_REFUSED.search(" ".join(ids)):  # a control or invisible character: read_csv says which
        return None
    nan = math.nan
    columns: dict[str, np.ndarray] = {}
    for name, optional, empty in _NUMERIC:
        if name in names:
            values = _numbers(buf, *field(name), optional=optional, empty=empty)
            if values is None:
                return None
            columns[name] = values
    radius = columns["radius_m"]
    e = columns.get("superelevation_percent", np.full(n, nan))
    grade = columns.get("grade_percent", np.zeros(n))
    posted = columns.get("posted_speed_kmh", np.full(n, nan))
    try:
        check_columns(radius, e, grade, posted)
    except InvalidRoad:
        return None
    # the plain form is the default dialect (comma, decimal point, no BOM), named in the answer as read_csv names it
    dialect = CsvDialect(line_ending=line_ending)
    return CurveTable(ids, radius, e, grade, posted, np.full(n, nan), where=RowNames(0, n), dialect=dialect)


def _fields(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> list[str]:
    """The fields ``buf[starts[i]:ends[i]]`` as strings: the bytes of the column (each field with the separator after
    it) taken at once, decoded and split."""
    mark = np.zeros(buf.size + 1, dtype=np.int8)
    mark[starts] += 1
    mark[ends + 1] -= 1
    inside = np.cumsum(mark[:-1], dtype=np.int8).view(bool)  # each field and its separator (0 or 1: no overlap)
    column = buf[inside].tobytes().decode()
    return column[:-1].replace("\n", ",").split(",")
