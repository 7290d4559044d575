"""Tables as CSV (RFC 4180, header row).

The batch endpoints (alignment assessment, sweep) answer JSON by default and CSV when ``Accept`` prefers ``text/csv``
(:mod:`app.http.negotiation`). Numbers are written with full precision (``repr``), booleans as ``true``/``false``, null
as an empty field; each SRT target becomes two columns, ``meets_<name>`` and ``margin_<name>_g`` (target names are
lower-case letters, digits and ``_``, so they are safe column names).

Text cells are neutralised against spreadsheet formula injection as OWASP recommends ("CSV Injection"): a text that
begins with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return is prefixed with a single quote, so a spreadsheet
shows it as text instead of evaluating it (a curve id ``=HYPERLINK(...)`` comes back as ``'=HYPERLINK(...)``);
every text cell is quoted, quotes inside doubled (RFC 4180). Numbers are never prefixed: ``-4.0`` stays a number.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

import orjson

#: the first characters that make a spreadsheet evaluate a cell (OWASP, CSV Injection)
FORMULA_PREFIXES = ("=", "+", "-", "@", "\t", "\r")


class Text(str):
    """A text cell: quoted in the CSV (numbers are not)."""


def _cell(value: Any) -> Any:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return Text("'" + value if value.startswith(FORMULA_PREFIXES) else value)
    return value


def _field(cell: Any) -> str:
    if isinstance(cell, Text):
        return '"' + cell.replace('"', '""') + '"'
    return str(cell)


def csv_field(value: Any) -> bytes:
    """One value as its CSV field (the rules of the module's docstring)."""
    return _field(_cell(value)).encode()


def csv_fields(values: Sequence[str]) -> list[bytes]:
    """The CSV field of each text of ``values`` (quoted, formula prefixes neutralised), in one ``join`` where no text
    holds a quote or begins with a formula prefix."""
    if not values:
        return []
    text = _text_column(values)
    fields = None if text is None else text.split(_SEP)
    if fields is None or len(fields) != len(values):  # a text holding the separator
        return [_text_field(v).encode() for v in values]
    return fields


def target_columns(names: Sequence[str]) -> list[str]:
    return [c for n in names for c in (f"meets_{n}", f"margin_{n}_g")]


def flatten_targets(row: dict[str, Any]) -> dict[str, Any]:
    """A row with a ``targets`` list -> the same row with ``meets_<name>`` / ``margin_<name>_g`` columns."""
    out = {k: v for k, v in row.items() if k != "targets"}
    for t in row.get("targets") or ():
        out[f"meets_{t['name']}"] = t["meets"]
        out[f"margin_{t['name']}_g"] = t["margin_g"]
    return out


def target_columns_of(checks_per_row: Sequence[Sequence[dict[str, Any]]]) -> dict[str, list[Any]]:
    """:func:`flatten_targets` for a table given column by column: the rows' ``targets`` lists (one per row, empty
    without an SRT) -> a ``meets_<name>`` and a ``margin_<name>_g`` column per target, None where a row has none."""
    out: dict[str, list[Any]] = {}
    # rows share their lists (one per distinct SRT): each distinct list is looked at once, the rows only gather
    keys = list(map(id, checks_per_row))
    distinct = dict(zip(keys, checks_per_row, strict=True))
    by_name: dict[str, tuple[dict[int, Any], dict[int, Any]]] = {}
    for k, checks in distinct.items():
        for c in checks:
            meets, margin = by_name.setdefault(c["name"], ({}, {}))
            if k not in meets:  # a row's first check of that name
                meets[k], margin[k] = c["meets"], c["margin_g"]
    for name, (meets, margin) in by_name.items():
        out[f"meets_{name}"] = list(map(meets.get, keys))
        out[f"margin_{name}_g"] = list(map(margin.get, keys))
    return out


def to_csv(columns: Sequence[str], rows: Iterable[dict[str, Any]]) -> bytes:
    """CSV text (UTF-8) with a header row; a column a row does not have is left empty."""
    return b"".join(to_csv_chunks(columns, [rows]))


def to_csv_chunks(columns: Sequence[str], chunks: Iterable[Iterable[dict[str, Any]]]) -> Iterator[bytes]:
    """:func:`to_csv` in chunks: the header row, then one chunk of CSV lines per chunk of rows."""
    yield csv_line(columns)
    for rows in chunks:
        yield csv_lines(columns, rows)


def csv_line(columns: Sequence[str]) -> bytes:
    """The header row (column names are identifiers: never formulas)."""
    return (",".join(columns) + "\r\n").encode()


def csv_lines(columns: Sequence[str], rows: Iterable[dict[str, Any]]) -> bytes:
    """CSV lines of ``rows`` (no header); a column a row does not have is left empty."""
    rows = rows if isinstance(rows, list) else list(rows)
    return csv_lines_of_columns([[row.get(c) for row in rows] for c in columns])


def csv_lines_of_columns(columns: Sequence[Sequence[Any]]) -> bytes:
    """CSV lines of a table given column by column (equal lengths; no header): the same text as :func:`csv_lines`
    of its rows, each column written at once (:func:`_csv_column`), the lines put together by slice assignment
    (as :func:`app.formats.segments.write_rows` puts JSON rows together): no Python work per row."""
    n = len(columns[0]) if columns else 0
    if not n:
        return b""
    width = len(columns)
    parts: list[bytes] = [b""] * (width * n)
    for j, values in enumerate(columns):
        if len(values) != n:
            return csv_lines_cellwise(columns)  # its zip(strict=True) says which
        text = _csv_column(values)
        if text is None:
            return csv_lines_cellwise(columns)
        start = b"" if j == 0 else b","
        end = b"\r\n" if j == width - 1 else b""
        parts[j::width] = (start + text.replace(_SEP, end + _SEP + start) + end).split(_SEP)
    return b"".join(parts)


#: the separator the columns' cells are joined with while the lines are made (a cell that holds it: cell by cell)
_SEP = b"\x01"
_NUMBER_KINDS = frozenset((float, int, bool))


def _csv_column(values: Sequence[Any]) -> bytes | None:
    """The CSV fields of one column joined by :data:`_SEP`, the same as :func:`_column_cells` writes them; None when
    a cell holds the separator. A column of numbers, booleans and nulls is written by one ``orjson.dumps``: orjson
    writes an int as ``str`` does, a bool as ``true``/``false``, and a float as ``repr`` does (the shortest text that
    reads back to it) except in exponent form and below 1e-4 (``0.00005`` for ``5e-05``): a column holding those, or a
    nan or an infinity (``null`` to orjson), is written cell by cell."""
    kinds = set(map(type, values))
    if kinds - {type(None)} <= _NUMBER_KINDS:
        text = orjson.dumps(values)[1:-1]
        nulls = text.count(b"null")
        plain = float not in kinds or (b"e" not in text and b"0.0000" not in text)
        if plain and nulls == values.count(None):
            return (text.replace(b"null", b"") if nulls else text).replace(b",", _SEP)
    elif kinds <= _TEXT_KINDS:
        text = _text_column(values)
        if text is not None:
            return text
    text = "\x01".join(_column_cells(values)).encode()
    return None if text.count(_SEP) != len(values) - 1 else text


_TEXT_KINDS = frozenset((str, Text))
#: a cell that begins with a formula prefix (after the separator, or first)
_FORMULA_START = re.compile("\x01[" + re.escape("".join(FORMULA_PREFIXES)) + "]")  # a literal first: a fast scan


def _text_column(values: Sequence[str]) -> bytes | None:
    """A column of texts (no None) joined by :data:`_SEP` as :func:`_text_field` writes each, in one ``join``; None
    when one holds a quote, the separator or begins with a formula prefix (then cell by cell). A column of few
    distinct texts (a vehicle's preset on every row) writes each of them once."""
    distinct = set(values)
    if len(distinct) * 4 <= len(values):
        fields = {v: _text_field(v) for v in distinct}
        return "\x01".join(map(fields.__getitem__, values)).encode()
    joined = "\x01".join(values)
    if (
        '"' in joined
        or joined.count("\x01") != len(values) - 1
        or joined.startswith(FORMULA_PREFIXES)
        or _FORMULA_START.search(joined)
    ):
        return None
    return ('"' + joined.replace("\x01", '"\x01"') + '"').encode()


def csv_lines_cellwise(columns: Sequence[Sequence[Any]]) -> bytes:
    """:func:`csv_lines_of_columns` made line by line from each cell's text (the reference it is tested against)."""
    cells = [_column_cells(values) for values in columns]
    if not cells or not cells[0]:
        return b""
    return ("\r\n".join(map(",".join, zip(*cells, strict=True))) + "\r\n").encode()


def _column_cells(values: Sequence[Any]) -> list[str]:
    """The CSV fields of one column: :func:`_field` of :func:`_cell` of each value, by the column's value types."""
    kinds = set(map(type, values)) - {type(None)}
    if kinds <= {float}:
        return ["" if v is None else repr(v) for v in values]
    if kinds <= {bool}:
        return ["" if v is None else "true" if v else "false" for v in values]
    if kinds <= {int}:
        return ["" if v is None else str(v) for v in values]
    if kinds <= {str, Text}:
        return ["" if v is None else _text_field(v) for v in values]
    return [_field(_cell(v)) for v in values]


def _text_field(value: str) -> str:
    """``_field(_cell(value))`` of a text."""
    text = "'" + value if value.startswith(FORMULA_PREFIXES) else value
    return '"' + text.replace('"', '""') + '"'
