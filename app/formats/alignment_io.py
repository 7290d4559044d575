"""Readers for horizontal curves: CSV with a header row, and LandXML 1.2 alignments, into columns.

Both return a :class:`CurveTable` (the curves as arrays), or raise :class:`AlignmentFormatError` naming the row
(CSV, 1-based, counting the header as row 1) or the element (LandXML) and what is wrong with it. Nothing is skipped
silently: a curve that cannot be read, or whose values no formula can use (a radius below 5 m, a superelevation or
grade beyond 20 %, a posted speed outside (0, 200] km/h: the bounds of :data:`engine.domain.BOUNDS`, the JSON form's
too), stops the whole file with its location.

CSV columns (header names, any order, case-insensitive): ``id``, ``radius_m``, ``superelevation_percent``
(optional, empty = derive it from the design standard's distribution), ``grade_percent`` (optional, default 0,
+ uphill in the direction of travel), ``posted_speed_kmh`` (optional, empty = none). The dialect (``,`` ``;`` or
tab between the fields, a decimal comma with ``;`` or tab, a UTF-8 byte-order mark, CRLF line ends) is detected
from the header and the first rows (:mod:`app.formats.csv_dialect`) and returned with the curves; errors name the
column as the header spells it.

LandXML 1.2 (:func:`read_landxml`): read whole by :mod:`app.formats.landxml` into the neutral records of
:mod:`engine.road.geometry`, each bend a row (:mod:`app.formats.road_file`): an arc's id is the Curve's ``name``
when present, else ``<alignment name>#<n>`` (n counts the alignment's Curves from 1); a bend made only of spirals
is ``<alignment name>#apex<m>``. The rows carry the bend's facts (:class:`BendTable`) and the answer the reading.
Parsing refuses what defusedxml refuses (no external entities, no entity expansion bombs; :mod:`app.formats.xmlsafe`).

Curve ids are 1-100 characters without control characters in every form (JSON, CSV, LandXML).
"""

from __future__ import annotations

import csv
import io
import math
import re
import unicodedata
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.formats.csv_dialect import CsvDialect, CsvDialectError, detect
from engine import InvalidRoad
from engine.road import check_columns

#: a synchronous request's curves: what interactive use needs (a road's or a district's curves answer in a fraction
#: of a second); larger work goes to a job (``app.alignments.schemas.MAX_JOB_CURVES``)
MAX_CURVES = 10_000
#: one limit for a curve id in every form (JSON, CSV, LandXML): 1-100 characters, none of them a control character
#: (C0, DEL, C1: NUL, ESC, CR, tab... would corrupt a CSV answer or a terminal) or an invisible format character
#: (Unicode category Cf: soft hyphen, zero-width space and joiners, direction marks, word joiner, BOM: "A" and
#: "A" + U+200B look the same and would be two curves), and at least one character that is not whitespace (a blank
#: id names nothing; the CSV reader strips its cells, so a blank cell there is empty)
CURVE_ID_MAX_CHARS = 100
_REFUSED_ID_CHARS = r"\x00-\x1f\x7f-\x9f\u00ad\u061c\u180e\u200b-\u200f\u202a-\u202e\u2060-\u2064\u2066-\u206f\ufeff"
#: the same rule as a pattern (JSON Schema / ECMA-262, Rust's regex and Python's re read it alike)
CURVE_ID_PATTERN = rf"^[^{_REFUSED_ID_CHARS}]*[^\s{_REFUSED_ID_CHARS}][^{_REFUSED_ID_CHARS}]*$"
CURVE_ID_REFUSED = re.compile(rf"[{_REFUSED_ID_CHARS}]")
CSV_REQUIRED = ("id", "radius_m")
CSV_OPTIONAL = ("superelevation_percent", "grade_percent", "posted_speed_kmh")


#: a road file's facts per row, beside the curve (:class:`BendTable`); codes as floats, nan for none
BEND_COLUMNS = (
    "distance_m",
    "bend_start_m",
    "bend_end_m",
    "direction",  # 0 left, 1 right
    "arc_length_m",
    "deflection_deg",
    "spiral_in_m",
    "spiral_out_m",
    "compound",  # 0/1
    "reverse",  # 0/1
    "grade_source",  # 0 request, 1 profile
    "grade_min_percent",
    "grade_max_percent",
    "superelevation_from",  # 0 the file's Superelevation, 1 its cross sections; nan: not from the file
)
DIRECTIONS = ("left", "right")
GRADE_SOURCES = ("request", "profile")
FILE_SUPERELEVATION = ("file", "cross-sections")


@dataclass(frozen=True)
class BendTable:
    """What a road file says of each row's bend (:data:`BEND_COLUMNS`, each an array of floats: distances and
    stations [m], deflection [deg], grades [%], codes; nan where none), from
    :func:`app.formats.road_file.curves_from_road_file`."""

    columns: dict[str, np.ndarray]

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def sliced(self, start: int, stop: int) -> BendTable:
        return BendTable({k: v[start:stop] for k, v in self.columns.items()})

    @staticmethod
    def empty(n: int) -> BendTable:
        """No file's facts (curves given as JSON or CSV): every column nan, the grade's source the request."""
        cols = {k: np.full(n, math.nan) for k in BEND_COLUMNS}
        cols["grade_source"] = np.zeros(n)
        return BendTable(cols)


@dataclass(frozen=True)
class CurveTable:
    """Curves as columns: ids, radius [m], superelevation [%] (nan: derive it), grade [%], posted speed [km/h]
    (nan: none) and station [m] (nan: none). The ids are a list, or one blob (:class:`app.formats.texts.Texts`) in
    a job's part."""

    ids: Sequence[str]
    radius_m: np.ndarray
    superelevation_percent: np.ndarray
    grade_percent: np.ndarray
    posted_speed_kmh: np.ndarray
    station_m: np.ndarray
    where: list[str] | None = None  # each curve's row or element in the document it came from (None: JSON)
    dialect: CsvDialect | None = None  # how a CSV document was written (None: not CSV)
    bends: BendTable | None = None  # a road file's facts of each curve's bend (None: not from a road file)
    reading: dict[str, Any] | None = None  # a road file's reading summary (the answer's ``reading``)

    def __len__(self) -> int:
        return len(self.ids)

    @property
    def bend_columns(self) -> BendTable:
        """:attr:`bends`, or the columns of no file's facts."""
        return self.bends if self.bends is not None else BendTable.empty(len(self))

    def sliced(self, start: int, stop: int) -> CurveTable:
        """Curves [start, stop) (a job's part)."""
        sl = slice(start, stop)
        return CurveTable(
            self.ids[sl],
            self.radius_m[sl],
            self.superelevation_percent[sl],
            self.grade_percent[sl],
            self.posted_speed_kmh[sl],
            self.station_m[sl],
            None if self.where is None else self.where[sl],
            self.dialect,
            None if self.bends is None else self.bends.sliced(start, stop),
            self.reading,
        )

    def key_rows(self) -> list[list[Any]]:
        """The curves as JSON-ready rows for the cache key (None for nan)."""

        def opt(a: np.ndarray) -> list[float | None]:
            return [None if math.isnan(x) else x for x in a.tolist()]

        return [
            list(row)
            for row in zip(
                self.ids,
                self.radius_m.tolist(),
                opt(self.superelevation_percent),
                self.grade_percent.tolist(),
                opt(self.posted_speed_kmh),
                opt(self.station_m),
                strict=True,
            )
        ]


class AlignmentFormatError(ValueError):
    """A file that cannot be read as curves; ``location`` says where (``"row 7"``, ``"Alignment 'A'..."``)."""

    def __init__(self, message: str, location: str | None = None, field: str | None = None) -> None:
        super().__init__(f"{location}: {message}" if location else message)
        self.location = location
        self.field = field


def _number(text: str | None, column: str, where: str, *, optional: bool = False) -> float | None:
    t = (text or "").strip()
    if t == "":
        if optional:
            return None
        raise AlignmentFormatError(f"{column} is empty", where, column)
    try:
        v = float(t)
    except ValueError:
        raise AlignmentFormatError(f"{column} is not a number: {t!r}", where, column) from None
    if not math.isfinite(v):
        raise AlignmentFormatError(f"{column} must be finite, got {t!r}", where, column)
    return v


def check_curve_id(cid: str, where: str, column: str) -> str:
    """The id, if it is 1-100 characters without control or invisible characters and not blank; else the error at
    this row / element."""
    problem = curve_id_problem(cid, column)
    if problem is not None:
        raise AlignmentFormatError(problem, where, column)
    return cid


def curve_id_problem(cid: str, column: str = "id") -> str | None:
    """Why ``cid`` is not a curve id (:data:`CURVE_ID_PATTERN`, said in words), or None: the one rule of every form
    (JSON, CSV, LandXML)."""
    if not cid:
        return f"{column} is empty"
    if len(cid) > CURVE_ID_MAX_CHARS:
        return f"{column} has {len(cid)} characters; at most {CURVE_ID_MAX_CHARS}"
    bad = CURVE_ID_REFUSED.search(cid)
    if bad:
        c = bad.group()
        kind = "an invisible format character" if unicodedata.category(c) == "Cf" else "the control character"
        return f"{column} contains {kind} U+{ord(c):04X} at position {bad.start() + 1}"
    if not cid.strip():
        return f"{column} is blank (only whitespace): it names no curve"
    return None


class _Collector:
    """Curves collected row by row (with where each came from), checked at the end against the domain's bounds on
    arrays; a curve out of bounds is reported at its row or element."""

    def __init__(
        self, columns: dict[str, str] | None = None, id_column: str = "id", max_curves: int = MAX_CURVES
    ) -> None:
        self.max_curves = max_curves
        self.ids: list[str] = []
        self.values: list[tuple[float, float, float, float, float]] = []  # r, e, grade, posted, station
        self.where: list[str] = []
        self.seen: set[str] = set()
        self.columns = columns or {}  # engine field -> the document's name for it
        self.id_column = id_column

    def add(self, cid: str, where: str, radius: float, e, grade: float, posted, station) -> None:
        if cid in self.seen:
            raise AlignmentFormatError(f"duplicate id {cid!r}", where, self.id_column)
        self.seen.add(cid)
        nan = math.nan
        opt = (nan if e is None else e, grade, nan if posted is None else posted, nan if station is None else station)
        self.ids.append(cid)
        self.values.append((radius, *opt))
        self.where.append(where)
        if len(self.ids) > self.max_curves:
            raise AlignmentFormatError(f"more than {self.max_curves} curves", where)

    def table(self, dialect: CsvDialect | None = None) -> CurveTable:
        a = np.array(self.values, dtype=float).reshape(-1, 5)
        t = CurveTable(self.ids, *(a[:, k].copy() for k in range(5)), where=self.where, dialect=dialect)
        return checked(t, self.columns)


def checked(t: CurveTable, columns: dict[str, str] | None = None) -> CurveTable:
    """``t`` if its columns are within the bounds of the JSON form; else the error at the curve's row or element
    (``t.where``), the column named as the document names it (``columns``: engine field -> the document's name)."""
    columns = columns or {}
    try:
        check_columns(t.radius_m, t.superelevation_percent, t.grade_percent, t.posted_speed_kmh)
    except InvalidRoad as exc:
        index, field = (exc.field or "").removeprefix("curves[").split("].", 1)
        column = columns.get(field, field)
        reason = str(exc).removeprefix(f"curves[{index}].").replace(field, column, 1)
        raise AlignmentFormatError(reason, t.where[int(index)] if t.where else None, column) from None
    return t


def _header(reader) -> tuple[dict[str, int], dict[str, str]]:
    """The header's columns: engine name -> position, and engine name -> the name as the header spells it."""
    try:
        header = next(reader)
    except csv.Error as exc:
        raise AlignmentFormatError(f"unreadable CSV: {exc}", "row 1") from None
    except StopIteration:
        header = []
    typed = [h.strip() for h in header]
    names = [h.lower() for h in typed]
    missing = [c for c in CSV_REQUIRED if c not in names]
    if missing:
        raise AlignmentFormatError(
            f"missing column(s) {', '.join(missing)}; the header must name {', '.join(CSV_REQUIRED)} "
            f"(optional: {', '.join(CSV_OPTIONAL)}) separated by ',', ';' or tabs; it reads {typed!r}"[:400],
            "row 1 (header)",
            missing[0],
        )
    unknown = [t for t, n in zip(typed, names, strict=True) if n not in CSV_REQUIRED + CSV_OPTIONAL]
    if unknown:
        raise AlignmentFormatError(
            f"unknown column(s) {', '.join(unknown)} (known: {', '.join(CSV_REQUIRED + CSV_OPTIONAL)})",
            "row 1 (header)",
            unknown[0],
        )
    dupes = sorted({t for t, n in zip(typed, names, strict=True) if names.count(n) > 1})
    if dupes:
        raise AlignmentFormatError(f"duplicate column(s) {', '.join(dupes)}", "row 1 (header)", dupes[0])
    return {n: i for i, n in enumerate(names)}, {n: t for n, t in zip(names, typed, strict=True)}


def _split_number_hint(row: list[str], n: int, dialect: CsvDialect) -> str:
    if dialect.separator == "," and len(row) > n:
        return (
            ": a decimal comma in a comma-separated file? Save it with ';' as the separator (as a decimal-comma "
            "spreadsheet does) or write the decimals with a point"
        )
    return ""


def read_csv(text: str, *, max_curves: int = MAX_CURVES) -> CurveTable:
    """Curves from CSV text with a header row (see the module docstring), in the dialect detected from its header
    and first rows (the table's ``dialect``); at most ``max_curves`` (a job's limit is larger than a request's)."""
    if not text.strip().lstrip("\ufeff"):
        raise AlignmentFormatError("the CSV is empty (a header row and at least one curve are needed)")
    try:
        dialect, text = detect(text, CSV_REQUIRED + CSV_OPTIONAL, ("radius_m", *CSV_OPTIONAL))
    except CsvDialectError as exc:
        raise AlignmentFormatError(str(exc).removeprefix(f"{exc.location}: "), exc.location, exc.field) from None
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=dialect.separator)
    idx, typed = _header(reader)
    curves = _Collector(typed, id_column=typed["id"], max_curves=max_curves)
    number = dialect.number

    def cell_number(cell: dict[str, str], name: str, where: str, optional: bool = False) -> float | None:
        if name not in cell:
            return None
        return number(cell[name], typed[name], where, optional=optional)

    try:
        for rownum, row in enumerate(reader, start=2):
            if not any(c.strip() for c in row):
                continue  # blank line (e.g. a trailing newline): not a curve
            where = f"row {rownum}"
            if len(row) != len(idx):
                hint = _split_number_hint(row, len(idx), dialect)
                raise AlignmentFormatError(f"has {len(row)} fields, the header has {len(idx)}{hint}", where)
            cell = {n: row[i] for n, i in idx.items()}
            grade = cell_number(cell, "grade_percent", where, optional=True)
            curves.add(
                check_curve_id(cell["id"].strip(), where, typed["id"]),
                where,
                cell_number(cell, "radius_m", where),
                cell_number(cell, "superelevation_percent", where, optional=True),
                0.0 if grade is None else grade,
                cell_number(cell, "posted_speed_kmh", where, optional=True),
                None,
            )
    except csv.Error as exc:
        raise AlignmentFormatError(f"unreadable CSV: {exc}", f"row {reader.line_num}") from None
    except CsvDialectError as exc:
        raise AlignmentFormatError(str(exc).removeprefix(f"{exc.location}: "), exc.location, exc.field) from None
    if not curves.ids:
        raise AlignmentFormatError("no curves after the header", "row 2")
    return curves.table(dialect)


@dataclass(frozen=True)
class CurveOverride:
    superelevation_percent: float | None = None
    grade_percent: float | None = None
    posted_speed_kmh: float | None = None


def read_landxml(
    text: str | bytes,
    *,
    superelevation_percent: float | None,
    grade_percent: float = 0.0,
    posted_speed_kmh: float | None = None,
    overrides: dict[str, CurveOverride] | None = None,
    max_curves: int = MAX_CURVES,
    profile: str | None = None,
) -> CurveTable:
    """The curves of a LandXML 1.2 document (:func:`app.formats.landxml.read_road_file`), assessed rows as
    :func:`app.formats.road_file.curves_from_road_file` makes them: the file's own grade and superelevation where it
    gives them, ``superelevation_percent`` / ``grade_percent`` / ``posted_speed_kmh`` (or ``overrides[curve id]``)
    where it does not. A curve left without a superelevation is derived from the design standard's distribution."""
    from app.formats.road_file import read_road_document  # here: it imports this module

    return read_road_document(
        "landxml",
        text,
        superelevation_percent=superelevation_percent,
        grade_percent=grade_percent,
        posted_speed_kmh=posted_speed_kmh,
        overrides=overrides,
        max_curves=max_curves,
        profile=profile,
    )
