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

from collections.abc import Iterable, Iterator, Sequence
from typing import Any

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
    names = {check["name"] for checks in checks_per_row for check in checks}
    for name in names:
        by_name = [next((c for c in checks if c["name"] == name), None) for checks in checks_per_row]
        out[f"meets_{name}"] = [None if c is None else c["meets"] for c in by_name]
        out[f"margin_{name}_g"] = [None if c is None else c["margin_g"] for c in by_name]
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
    of its rows, each column written at once (a column of numbers or of booleans without one call per cell)."""
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
