"""A job's CSV curves read straight into columns: the fast path of :func:`app.formats.alignment_io.read_csv` for the
plain form (comma-separated, no quotes, one curve per line, ``\\n`` or ``\\r\\n``), which a million-curve job
almost always is.

The text is split once into its fields (``str.split``), each numeric column parsed by ``float`` over the whole
column at once (``map``: the same parser ``read_csv`` uses, so the same bits) into a numpy array, and checked with
numpy masks (finite, the bounds of the JSON form); the ids are checked on the whole column (empty, too long, control
characters, duplicates). No row object, no dict and no Python call per curve besides the ids' ``strip``.

It never decides an error: whatever it does not take as plain, or any check that fails, sends the text to
:func:`~app.formats.alignment_io.read_csv` (``None`` from :func:`read_csv_columns`), which reads it again and reports
the first bad line and field as it always does (and knows the dialects the fast path leaves to it). A table it does
answer is the table ``read_csv`` would answer (the job tests compare them), except that its ``where`` (each curve's
row, for error messages) is computed when asked for (:class:`RowNames`) instead of kept as a million strings.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from itertools import repeat
from typing import overload

import numpy as np

from app.formats.alignment_io import CSV_OPTIONAL, CSV_REQUIRED, CURVE_ID_MAX_CHARS, MAX_CURVES, CurveTable
from app.formats.csv_dialect import CsvDialect
from engine.errors import InvalidRoad
from engine.road import check_columns

#: what the plain form has no place for: quotes, control characters but the line ends (and a BOM: a dialect)
_NOT_PLAIN = re.compile(r'["\x00-\x09\x0b\x0c\x0e-\x1f\x7f-\x9f\ufeff]')


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


def _numbers(fields: list[str], *, optional: bool, empty: float) -> np.ndarray | None:
    """A numeric column (``float`` of each field; an empty one ``empty`` when ``optional``); None when a field is not
    a finite number (``read_csv`` says which)."""
    try:
        values = np.fromiter(map(float, fields), dtype=np.float64, count=len(fields))
    except ValueError:
        if not optional:
            return None
        try:
            values = np.array([float(f) if f.strip() else empty for f in fields], dtype=np.float64)
        except ValueError:
            return None
        given = np.fromiter((bool(f.strip()) for f in fields), dtype=bool, count=len(fields))
        if not np.all(np.isfinite(values[given])):
            return None
        return values
    if not np.all(np.isfinite(values)):
        return None
    return values


def read_csv_columns(text: str, *, max_curves: int = MAX_CURVES) -> CurveTable | None:
    """The curves of a plain CSV text as columns, or None when the text is not plain or does not pass a check (then
    :func:`~app.formats.alignment_io.read_csv` reads it and says why)."""
    line_ending = "LF"
    if "\r" in text:
        text = text.replace("\r\n", "\n")
        if "\r" in text:
            return None
        line_ending = "CRLF"
    if _NOT_PLAIN.search(text):
        return None
    head, sep, body = text.partition("\n")
    names = [h.strip().lower() for h in head.split(",")]
    known = CSV_REQUIRED + CSV_OPTIONAL
    if not sep or len(set(names)) != len(names) or not set(CSV_REQUIRED) <= set(names) <= set(known):
        return None
    lines = body.split("\n")
    while lines and not lines[-1].replace(",", "").strip():  # trailing blank rows (a final newline): not curves
        lines.pop()
    n, k = len(lines), len(names)
    if n == 0 or n > max_curves:
        return None
    if set(map(str.count, lines, repeat(",", n))) != {k - 1}:  # every line its k fields (not just k * n in all)
        return None
    fields = ",".join(lines).split(",")
    if len(fields) != n * k:
        return None
    del lines
    cols = {name: fields[j::k] for j, name in enumerate(names)}
    del fields
    ids = list(map(str.strip, cols["id"]))
    if not all(ids) or max(map(len, ids)) > CURVE_ID_MAX_CHARS or len(set(ids)) != n:
        return None
    nan = math.nan
    radius = _numbers(cols["radius_m"], optional=False, empty=nan)
    e = _numbers(cols["superelevation_percent"], optional=True, empty=nan) if "superelevation_percent" in cols else None
    grade = _numbers(cols["grade_percent"], optional=True, empty=0.0) if "grade_percent" in cols else None
    posted = _numbers(cols["posted_speed_kmh"], optional=True, empty=nan) if "posted_speed_kmh" in cols else None
    if radius is None or any(
        name in cols and a is None for name, a in zip(CSV_OPTIONAL, (e, grade, posted), strict=True)
    ):
        return None
    e = np.full(n, nan) if e is None else e
    grade = np.zeros(n) if grade is None else grade
    posted = np.full(n, nan) if posted is None else posted
    try:
        check_columns(radius, e, grade, posted)
    except InvalidRoad:
        return None
    # the plain form is the default dialect (comma, decimal point, no BOM), named in the answer as read_csv names it
    dialect = CsvDialect(line_ending=line_ending)
    return CurveTable(ids, radius, e, grade, posted, np.full(n, nan), where=RowNames(0, n), dialect=dialect)
