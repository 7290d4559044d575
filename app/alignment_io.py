"""Readers for horizontal curves: CSV with a header row, and LandXML 1.2 alignments.

Both return :class:`engine.assessment.Curve` records, or raise :class:`AlignmentFormatError` naming the row
(CSV, 1-based, counting the header as row 1) or the element (LandXML) and what is wrong with it. Nothing
is skipped silently: a curve that cannot be read, or whose values no formula can use (a radius of 0, a
superelevation or grade beyond 20 %, a posted speed outside (0, 200] km/h: the bounds of
:func:`engine.assessment.check_curve`), stops the whole file with its location.

CSV columns (header names, any order, case-insensitive): ``id``, ``radius_m``, ``superelevation_percent``,
``grade_percent`` (optional, default 0, + uphill in the direction of travel), ``posted_speed_kmh``
(optional, empty = none).

LandXML 1.2: every ``CoordGeom/Curve`` of every ``Alignment`` is a horizontal curve; its ``radius`` is
required, ``staStart`` (station) and ``name`` are reported. LandXML keeps superelevation and grade in
other elements whose use varies between design packages, so they are supplied per curve (keyed by the
curve id) or as defaults. The curve id is the Curve's ``name`` when present, else
``<alignment name>#<n>`` (n counts the alignment's curves from 1). Parsing uses defusedxml (no external
entities, no entity expansion bombs).
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections import Counter
from dataclasses import dataclass

from defusedxml import ElementTree as SafeET
from defusedxml.common import DefusedXmlException

from engine.assessment import Curve, check_curve
from engine.errors import InvalidRoad

MAX_CURVES = 100_000
#: one limit for a curve id in every form (JSON, CSV, LandXML): 1-100 characters, none of them a control character
#: (C0, DEL, C1: NUL, ESC, CR, tab... would corrupt a CSV answer or a terminal)
CURVE_ID_MAX_CHARS = 100
CURVE_ID_PATTERN = r"^[^\x00-\x1f\x7f-\x9f]+$"
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f]")
CSV_REQUIRED = ("id", "radius_m", "superelevation_percent")
CSV_OPTIONAL = ("grade_percent", "posted_speed_kmh")


class AlignmentFormatError(ValueError):
    """A file that cannot be read as curves; ``location`` says where (``"row 7"``, ``"Alignment 'A'..."``)."""

    def __init__(self, message: str, location: str | None = None, field: str | None = None) -> None:
        super().__init__(f"{location}: {message}" if location else message)
        self.location = location
        self.field = field


def _number(text: str, column: str, where: str, *, optional: bool = False) -> float | None:
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
    """The id, if it is 1-100 characters without control characters; else the error at this row / element."""
    if not cid:
        raise AlignmentFormatError(f"{column} is empty", where, column)
    if len(cid) > CURVE_ID_MAX_CHARS:
        raise AlignmentFormatError(f"{column} has {len(cid)} characters; at most {CURVE_ID_MAX_CHARS}", where, column)
    bad = _CONTROL.search(cid)
    if bad:
        raise AlignmentFormatError(
            f"{column} contains the control character U+{ord(bad.group()):04X} at position {bad.start() + 1}",
            where,
            column,
        )
    return cid


def _checked(curve: Curve, where: str, columns: dict[str, str] | None = None) -> Curve:
    """The curve, if every formula can use it (the engine's bounds, the JSON form's); else the error here, naming
    the column (``columns`` renames the engine's fields to the document's, e.g. LandXML's ``radius``)."""
    try:
        check_curve(curve, 0)
    except InvalidRoad as exc:
        field = (exc.field or "").rsplit(".", 1)[-1] or None
        column = (columns or {}).get(field, field)
        reason = str(exc).removeprefix("curves[0].")
        if field and column != field:
            reason = reason.replace(field, column, 1)
        raise AlignmentFormatError(reason, where, column) from None
    return curve


def read_csv(text: str) -> list[Curve]:
    """Curves from CSV text with a header row (see the module docstring)."""
    if not text.strip():
        raise AlignmentFormatError("the CSV is empty (a header row and at least one curve are needed)")
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except csv.Error as exc:
        raise AlignmentFormatError(f"unreadable CSV: {exc}", "row 1") from None
    names = [h.strip().lower() for h in header]
    missing = [c for c in CSV_REQUIRED if c not in names]
    if missing:
        raise AlignmentFormatError(
            f"missing column(s) {', '.join(missing)}; the header must name {', '.join(CSV_REQUIRED)} "
            f"(optional: {', '.join(CSV_OPTIONAL)})",
            "row 1 (header)",
            missing[0],
        )
    unknown = [n for n in names if n not in CSV_REQUIRED + CSV_OPTIONAL]
    if unknown:
        raise AlignmentFormatError(f"unknown column(s) {', '.join(unknown)}", "row 1 (header)", unknown[0])
    dupes = {n for n in names if names.count(n) > 1}
    if dupes:
        raise AlignmentFormatError(f"duplicate column(s) {', '.join(sorted(dupes))}", "row 1 (header)")
    idx = {n: i for i, n in enumerate(names)}
    curves: list[Curve] = []
    seen: set[str] = set()
    try:
        for rownum, row in enumerate(reader, start=2):
            if not any(c.strip() for c in row):
                continue  # blank line (e.g. a trailing newline): not a curve
            where = f"row {rownum}"
            if len(row) != len(names):
                raise AlignmentFormatError(f"has {len(row)} fields, the header has {len(names)}", where)
            cid = check_curve_id(row[idx["id"]].strip(), where, "id")
            if cid in seen:
                raise AlignmentFormatError(f"duplicate id {cid!r}", where, "id")
            seen.add(cid)
            grade = (
                _number(row[idx["grade_percent"]], "grade_percent", where, optional=True)
                if "grade_percent" in idx
                else None
            )
            posted = (
                _number(row[idx["posted_speed_kmh"]], "posted_speed_kmh", where, optional=True)
                if "posted_speed_kmh" in idx
                else None
            )
            curves.append(
                _checked(
                    Curve(
                        id=cid,
                        radius_m=_number(row[idx["radius_m"]], "radius_m", where),
                        superelevation_percent=_number(
                            row[idx["superelevation_percent"]], "superelevation_percent", where
                        ),
                        grade_percent=0.0 if grade is None else grade,
                        posted_speed_kmh=posted,
                    ),
                    where,
                )
            )
            if len(curves) > MAX_CURVES:
                raise AlignmentFormatError(f"more than {MAX_CURVES} curves", where)
    except csv.Error as exc:
        raise AlignmentFormatError(f"unreadable CSV: {exc}", f"row {reader.line_num}") from None
    if not curves:
        raise AlignmentFormatError("no curves after the header", "row 2")
    return curves


@dataclass(frozen=True)
class CurveOverride:
    superelevation_percent: float | None = None
    grade_percent: float | None = None
    posted_speed_kmh: float | None = None


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def read_landxml(
    text: str | bytes,
    *,
    superelevation_percent: float | None,
    grade_percent: float = 0.0,
    posted_speed_kmh: float | None = None,
    overrides: dict[str, CurveOverride] | None = None,
) -> list[tuple[Curve, float | None]]:
    """Curves (with their start station [m], or None) from a LandXML 1.2 document.

    ``superelevation_percent`` / ``grade_percent`` / ``posted_speed_kmh`` apply to every curve unless
    ``overrides[curve id]`` gives its own. A curve left without a superelevation is an error naming it.
    """
    overrides = dict(overrides or {})
    try:
        root = SafeET.fromstring(text)
    except DefusedXmlException as exc:
        raise AlignmentFormatError(f"refused: {exc.__class__.__name__} (entities are not allowed)", "LandXML") from None
    except SafeET.ParseError as exc:
        line, col = getattr(exc, "position", (None, None))
        raise AlignmentFormatError(f"malformed XML: {exc}", f"LandXML line {line}, column {col}") from None
    if _local(root.tag) != "LandXML":
        raise AlignmentFormatError(f"the root element is <{_local(root.tag)}>, not <LandXML>", "LandXML")
    out: list[tuple[Curve, float | None]] = []
    alignments = [e for e in root.iter() if _local(e.tag) == "Alignment"]
    if not alignments:
        raise AlignmentFormatError("no <Alignment> element", "LandXML")
    for a_index, alignment in enumerate(alignments, start=1):
        a_name = alignment.get("name") or f"alignment {a_index}"
        geoms = [e for e in alignment if _local(e.tag) == "CoordGeom"]
        n = 0
        for geom in geoms:
            for el in geom:
                if _local(el.tag) != "Curve":
                    continue
                n += 1
                cid = el.get("name") or f"{a_name}#{n}"
                where = f"Alignment {a_name[:CURVE_ID_MAX_CHARS]!r} CoordGeom Curve #{n}"
                cid = check_curve_id(cid, where, "name")
                where = f"{where} ({cid!r})"
                r_text = el.get("radius")
                if r_text is None:
                    raise AlignmentFormatError("has no radius attribute", where, "radius")
                radius = _number(r_text, "radius", where)
                sta = el.get("staStart")
                station = _number(sta, "staStart", where) if sta is not None else None
                ov = overrides.pop(cid, CurveOverride())
                e = ov.superelevation_percent if ov.superelevation_percent is not None else superelevation_percent
                if e is None:
                    raise AlignmentFormatError(
                        "no superelevation: give superelevation_percent as a default or for this curve id",
                        where,
                        "superelevation_percent",
                    )
                g = ov.grade_percent if ov.grade_percent is not None else grade_percent
                v = ov.posted_speed_kmh if ov.posted_speed_kmh is not None else posted_speed_kmh
                out.append((_checked(Curve(cid, radius, e, g, v), where, {"radius_m": "radius"}), station))
                if len(out) > MAX_CURVES:
                    raise AlignmentFormatError(f"more than {MAX_CURVES} curves", where)
    if not out:
        raise AlignmentFormatError("no CoordGeom/Curve element in any alignment", "LandXML")
    if overrides:
        raise AlignmentFormatError(
            f"overrides name curves that are not in the file: {', '.join(sorted(overrides))}", "curve_overrides"
        )
    counts = Counter(c.id for c, _ in out)  # not list.count per id: that is quadratic in the number of curves
    dupes = sorted(i for i, n in counts.items() if n > 1)
    if dupes:
        raise AlignmentFormatError(f"duplicate curve names {', '.join(dupes)}", "LandXML")
    return out
