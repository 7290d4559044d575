"""CSV dialects as spreadsheets save them: the separator, the decimal mark, a byte-order mark and the line ends.

A spreadsheet in a decimal-comma locale (Portuguese, German, French, ...) saves "CSV" with ``;`` between the
fields and a comma in the numbers (``C1;250,5;8``), often with a UTF-8 byte-order mark and CRLF line ends; an
English-locale one writes ``C1,250.5,8``; "Text (tab delimited)" puts a tab between the fields. The dialect is
detected once per file, never guessed per row:

* the **byte-order mark** (U+FEFF) at the start of the text is noted and dropped (it is not part of the first
  column's name);
* a first line ``sep=;`` (``sep=,``, ``sep=`` and a tab), which Excel reads as the file's separator and some
  programs write so that Excel opens their files in any locale, sets the separator and is dropped: the header is
  the line after it, row 1, as the spreadsheet shows it (Excel does not show that line);
* the **line ending** is that of the header line (``CRLF``, ``LF`` or ``CR``; the reader accepts any of them);
* the **separator** (``,``, ``;`` or a tab) is the one that splits the header line into the most known column
  names (a tie: the one that occurs most often in the header; no separator at all: ``,``);
* the **decimal mark** is ``.`` with a ``,`` separator (a decimal comma there would split the number in two); with
  ``;`` or a tab it is the mark of the first number that has one (in the numeric columns, from the first data row
  on: a file of whole numbers has none, and reads the same either way).

Every number is then read with the file's decimal mark, and a number written with the other mark (a file that mixes
them) is refused with its row and column, and where the file's mark was read (``1.250,5`` in a decimal-comma file
is a thousands separator, ``250,5`` in a comma-separated file a split number): a wrong number is never read
silently. Errors are :class:`CsvDialectError` naming the row (1-based, the header is row 1) and the column as the
header spells it.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Iterable
from dataclasses import dataclass

SEPARATORS = (",", ";", "\t")
BOM = "\ufeff"
_SEPARATOR_NAMES = {",": "','", ";": "';'", "\t": "a tab"}


class CsvDialectError(ValueError):
    """A file whose dialect cannot be read, or a number written in another dialect than the file's."""

    def __init__(self, message: str, location: str | None = None, field: str | None = None) -> None:
        super().__init__(f"{location}: {message}" if location else message)
        self.location = location
        self.field = field


@dataclass(frozen=True)
class CsvDialect:
    """How a CSV file is written: ``separator`` (``,`` ``;`` or ``\\t``), ``decimal`` (``.`` or ``,``), whether it
    began with a UTF-8 byte-order mark, and its line ending (``CRLF``, ``LF``, ``CR``). ``evidence`` says where the
    decimal mark was read (``row 2, radius_m '250,5'``), for the messages."""

    separator: str = ","
    decimal: str = "."
    bom: bool = False
    line_ending: str = "LF"
    evidence: str | None = None

    def as_dict(self) -> dict[str, str | bool]:
        return {"separator": self.separator, "decimal": self.decimal, "bom": self.bom, "line_ending": self.line_ending}

    def describe(self) -> str:
        dec = "decimal comma" if self.decimal == "," else "decimal point"
        return f"{_SEPARATOR_NAMES[self.separator]}-separated with a {dec}"

    def number(self, text: str | None, column: str, where: str, *, optional: bool = False) -> float | None:
        """A cell as a finite number in this dialect; None for an empty optional cell; else the error at ``where``
        naming ``column``."""
        t = (text or "").strip()
        if t == "":
            if optional:
                return None
            raise CsvDialectError(f"{column} is empty", where, column)
        if self.decimal == ",":
            if "." in t:
                raise CsvDialectError(
                    f"{column} {t!r} has a '.', but this file writes decimals with a comma ({self.evidence}): write "
                    "every number with a decimal comma and no thousands separator (1250,5)",
                    where,
                    column,
                )
            t = t.replace(",", ".")
        elif "," in t:
            if self.separator == ",":
                hint = (
                    "a decimal comma in a comma-separated file: save the file with ';' as the separator (as a "
                    "decimal-comma spreadsheet does) or write the decimals with a point"
                )
            else:
                hint = f"a decimal comma, but this file writes decimals with a point ({self.evidence})"
            raise CsvDialectError(f"{column} is not a number: {t!r} ({hint})", where, column)
        try:
            v = float(t)
        except ValueError:
            raise CsvDialectError(f"{column} is not a number: {(text or '').strip()!r}", where, column) from None
        if not math.isfinite(v):
            raise CsvDialectError(f"{column} must be finite, got {(text or '').strip()!r}", where, column)
        return v


def _line_ending(text: str) -> str:
    i = next((k for k, ch in enumerate(text) if ch in "\r\n"), -1)
    if i < 0:
        return "LF"
    if text[i] == "\n":
        return "LF"
    return "CRLF" if text[i + 1 : i + 2] == "\n" else "CR"


def _header_line(text: str) -> str:
    return next(iter(io.StringIO(text, newline="")), "")


def _split(line: str, separator: str) -> list[str]:
    try:
        return next(csv.reader([line.rstrip("\r\n")], delimiter=separator), [])
    except csv.Error:
        return [line]


def _separator(header: str, known: Iterable[str]) -> str:
    names = set(known)
    scores = []
    for sep in SEPARATORS:
        fields = [f.strip().lower() for f in _split(header, sep)]
        scores.append((sum(f in names for f in fields), header.count(sep), -SEPARATORS.index(sep), sep))
    best = max(scores)
    return best[3] if best[0] or best[1] else ","


def _sep_line(line: str) -> str | None:
    """The separator a first line ``sep=X`` names (None: the line is not one); another X than the known separators
    is refused."""
    text = line.rstrip("\r\n")
    if not text.lower().startswith("sep="):
        return None
    sep = text[4:]
    if sep not in SEPARATORS:
        raise CsvDialectError(
            f"the first line {text!r} names the separator {sep!r}; a file may be separated by ',', ';' or tabs",
            "the sep= line",
        )
    return sep


def detect(text: str, known_columns: Iterable[str], numeric_columns: Iterable[str]) -> tuple[CsvDialect, str]:
    """The dialect of CSV ``text`` (see the module) and the text without its byte-order mark.

    ``known_columns`` are the header names the reader knows (they choose the separator), ``numeric_columns`` those
    whose cells are numbers (they show the decimal mark)."""
    bom = text.startswith(BOM)
    body = text[1:] if bom else text
    header = _header_line(body)
    forced = _sep_line(header)
    if forced is not None:
        body = body[len(header) :]
        header = _header_line(body)
    sep = forced or _separator(header, known_columns)
    ending = _line_ending(body)
    if sep == ",":
        return CsvDialect(",", ".", bom, ending), body
    names = [f.strip() for f in _split(header, sep)]
    numeric = set(numeric_columns)
    columns = [(i, n) for i, n in enumerate(names) if n.lower() in numeric]
    reader = csv.reader(io.StringIO(body, newline=""), delimiter=sep)
    try:
        next(reader, None)
        for rownum, row in enumerate(reader, start=2):  # up to the first number with a decimal mark
            for i, name in columns:
                cell = row[i].strip() if i < len(row) else ""
                for mark in (",", "."):
                    if mark in cell:
                        return CsvDialect(sep, mark, bom, ending, f"row {rownum}, {name} {cell!r}"), body
    except csv.Error as exc:
        raise CsvDialectError(f"unreadable CSV: {exc}", f"row {reader.line_num}") from None
    return CsvDialect(sep, ".", bom, ending), body
