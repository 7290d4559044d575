"""An alignment's geometry as road-design files describe it, in SI units: the horizontal elements (lines, circular
arcs, spirals), stations, the vertical profile and the superelevation.

This module is the neutral form every reader produces (LandXML 1.2 and IFC 4.3 in :mod:`app.formats`): a reader
converts the file's units (feet, US survey feet, gradians...) and its sign conventions into these records, and the
pure numerics that follow (where each bend starts and ends, its deflection, the grade over it, its superelevation)
work on them alone, whatever file they came from.

Conventions
-----------
- Lengths, stations and elevations in metres; grades as ratios (rise over run, + uphill in the direction of
  increasing station); cross slopes and superelevation in percent.
- ``distance`` is the distance along the alignment from its start (the internal station), ``station`` the station as
  the file writes it (they differ by the alignment's start station and by any station equation).
- A horizontal element's ``direction`` is the side its centre of curvature lies on, looking ahead: ``"left"``
  (LandXML ``rot="ccw"``; IFC a positive radius) or ``"right"`` (``rot="cw"``; IFC negative); None for a line.
- A radius of ``math.inf`` is a straight end (a line's both ends; a spiral's tangent end).
- A cross slope is signed across the whole road: + when the surface rises from left to right, looking ahead. On a
  curve, the superelevation is the slope of the outside lane toward the inside: ``+slope`` on a left-hand curve,
  ``-slope`` on a right-hand one, so a normal crown kept through a curve (adverse crossfall) is negative.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Literal, TypeVar

import numpy as np

ElementKind = Literal["line", "arc", "spiral"]
Direction = Literal["left", "right"]
VerticalKind = Literal["constant", "parabolic", "circular"]


@dataclass(frozen=True)
class HorizontalElement:
    """One element of the horizontal alignment (LandXML ``Line``/``Curve``/``Spiral``; IFC
    ``IfcAlignmentHorizontalSegment``).

    ``radius_start_m``/``radius_end_m``: ``inf`` on a straight end (a line: both; an arc: both equal);
    ``station_m``: the start station as the file writes it, None where the file gives none (the stations are then
    computed from the alignment's start station and the element lengths); ``spiral_type``: the file's name of the
    transition (``"clothoid"``, ``"bloss"``, ...; None for lines and arcs); ``where``: where it is in the file, for
    messages (``"Alignment 'A' CoordGeom element 3 (Spiral)"``).
    """

    kind: ElementKind
    length_m: float
    radius_start_m: float = math.inf
    radius_end_m: float = math.inf
    direction: Direction | None = None
    station_m: float | None = None
    spiral_type: str | None = None
    name: str | None = None
    where: str = ""


_KINDS: tuple[ElementKind, ...] = ("line", "arc", "spiral")
_Record = TypeVar("_Record")
_DIRECTIONS: tuple[Direction | None, ...] = ("left", "right", None)  # by code 0, 1, -1


class _Columns(Sequence[_Record]):
    """What the column forms (:class:`ElementColumns`, :class:`SegmentColumns`, :class:`SlopeColumns`,
    :class:`RangeColumns`) share: a sequence of records, each made by the subclass's ``_one(i)`` when it is asked
    for, equal to any sequence of the same records (a tuple of records included), hashed as that tuple."""

    __slots__ = ()
    #: what one entry is called in an index error, and many in the repr
    _noun: str = "entry"
    _plural: str = "entries"

    def _one(self, i: int) -> _Record:
        raise NotImplementedError

    def _same_lengths(self) -> None:
        sizes = {len(getattr(self, k)) for k in self.__slots__}
        if len(sizes) > 1:
            raise ValueError(f"columns of different lengths: {sorted(sizes)}")

    def __getitem__(self, i):  # type: ignore[override]
        if isinstance(i, slice):
            return tuple(self._one(k) for k in range(*i.indices(len(self))))
        n = len(self)
        if not -n <= i < n:
            raise IndexError(f"{self._noun} index out of range")
        return self._one(i % n)

    def __iter__(self) -> Iterator[_Record]:
        return (self._one(k) for k in range(len(self)))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sequence) or isinstance(other, str):
            return NotImplemented
        return len(self) == len(other) and all(a == b for a, b in zip(self, other, strict=True))

    def __hash__(self) -> int:
        return hash(tuple(self))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({len(self)} {self._plural})"


class ElementColumns(_Columns[HorizontalElement]):
    """An alignment's horizontal elements held as columns, one entry per element: a sequence of
    :class:`HorizontalElement` (each made when it is asked for) that the numerics read as arrays
    (:func:`element_columns`). A reader of a large file gives an alignment its elements in this form: a million
    records would take seconds to make and hold the interpreter's lock while they are freed.

    ``kind``: 0 line, 1 arc, 2 spiral; ``direction``: 0 left, 1 right, -1 none; ``station_m``: nan where the file
    gives none; ``length_m``, ``radius_start_m``, ``radius_end_m`` [m] as in :class:`HorizontalElement`;
    ``spiral_type``, ``name``, ``where``: lists (None where there is none).
    """

    _noun, _plural = "element", "elements"
    __slots__ = (
        "direction",
        "kind",
        "length_m",
        "name",
        "radius_end_m",
        "radius_start_m",
        "spiral_type",
        "station_m",
        "where",
    )  # fmt: skip

    def __init__(self, kind, length_m, radius_start_m, radius_end_m, direction, station_m, spiral_type, name, where):
        self.kind = np.asarray(kind, dtype=np.int8)
        self.length_m = np.asarray(length_m, dtype=float)
        self.radius_start_m = np.asarray(radius_start_m, dtype=float)
        self.radius_end_m = np.asarray(radius_end_m, dtype=float)
        self.direction = np.asarray(direction, dtype=np.int8)
        self.station_m = np.asarray(station_m, dtype=float)
        # (a list given is kept, not copied)
        self.spiral_type, self.name, self.where = (
            x if isinstance(x, list) else list(x) for x in (spiral_type, name, where)
        )
        self._same_lengths()

    @classmethod
    def of(cls, elements: Sequence[HorizontalElement]) -> ElementColumns:
        """Records as columns."""
        if isinstance(elements, ElementColumns):
            return elements
        el = elements
        return cls(
            [_KINDS.index(e.kind) for e in el],
            [e.length_m for e in el],
            [e.radius_start_m for e in el],
            [e.radius_end_m for e in el],
            [1 if e.direction == "right" else 0 if e.direction == "left" else -1 for e in el],
            [math.nan if e.station_m is None else e.station_m for e in el],
            [e.spiral_type for e in el],
            [e.name for e in el],
            [e.where for e in el],
        )

    def __len__(self) -> int:
        return len(self.kind)

    def _one(self, i: int) -> HorizontalElement:
        sta = float(self.station_m[i])
        return HorizontalElement(
            _KINDS[self.kind[i]],
            float(self.length_m[i]),
            float(self.radius_start_m[i]),
            float(self.radius_end_m[i]),
            _DIRECTIONS[self.direction[i]],
            None if math.isnan(sta) else sta,
            self.spiral_type[i],
            self.name[i],
            self.where[i],
        )


def element_columns(alignment: AlignmentGeometry) -> ElementColumns:
    """The alignment's elements as columns (:class:`ElementColumns`), whichever form it holds them in."""
    return ElementColumns.of(alignment.elements)


@dataclass(frozen=True)
class StationEquation:
    """A station equation (LandXML ``StaEquation``): at ``distance_m`` along the alignment the written station jumps
    from ``station_back_m`` to ``station_ahead_m``."""

    distance_m: float
    station_back_m: float
    station_ahead_m: float


@dataclass(frozen=True)
class VerticalSegment:
    """One piece of the vertical profile over ``[start_distance_m, start_distance_m + length_m]`` (horizontal
    length): a constant grade, a parabola (the grade changes linearly from ``start_grade`` to ``end_grade``) or a
    circular arc of ``radius_m``. Grades are ratios, + uphill with increasing distance."""

    kind: VerticalKind
    start_distance_m: float
    length_m: float
    start_elevation_m: float
    start_grade: float
    end_grade: float
    radius_m: float | None = None


_VERTICAL_KINDS: tuple[VerticalKind, ...] = ("constant", "parabolic", "circular")


class SegmentColumns(_Columns[VerticalSegment]):
    """A profile's segments held as columns, one entry per segment: a sequence of :class:`VerticalSegment` (each
    made when it is asked for) that the grades read as arrays (as :class:`ElementColumns` for the horizontal
    elements): a long road's profile has tens of thousands of segments, and records would be made, walked by the
    garbage collector and read back into arrays at every use.

    ``kind``: 0 constant, 1 parabolic, 2 circular; ``radius_m``: nan where the segment has none; the other columns
    as in :class:`VerticalSegment`."""

    _noun, _plural = "segment", "segments"
    __slots__ = ("end_grade", "kind", "length_m", "radius_m", "start_distance_m", "start_elevation_m", "start_grade")

    def __init__(self, kind, start_distance_m, length_m, start_elevation_m, start_grade, end_grade, radius_m):
        self.kind = np.asarray(kind, dtype=np.int8)
        self.start_distance_m = np.asarray(start_distance_m, dtype=float)
        self.length_m = np.asarray(length_m, dtype=float)
        self.start_elevation_m = np.asarray(start_elevation_m, dtype=float)
        self.start_grade = np.asarray(start_grade, dtype=float)
        self.end_grade = np.asarray(end_grade, dtype=float)
        self.radius_m = np.asarray(radius_m, dtype=float)
        self._same_lengths()

    def __len__(self) -> int:
        return len(self.kind)

    def _one(self, i: int) -> VerticalSegment:
        r = float(self.radius_m[i])
        return VerticalSegment(
            _VERTICAL_KINDS[self.kind[i]],
            float(self.start_distance_m[i]),
            float(self.length_m[i]),
            float(self.start_elevation_m[i]),
            float(self.start_grade[i]),
            float(self.end_grade[i]),
            None if math.isnan(r) else r,
        )


@dataclass(frozen=True)
class Profile:
    """A vertical profile (LandXML ``ProfAlign``; IFC ``IfcAlignmentVertical``): its segments in order of distance
    (a tuple of records, or, from a reader of a large file, the same as :class:`SegmentColumns`)."""

    name: str
    segments: Sequence[VerticalSegment]


@dataclass(frozen=True)
class SuperelevationRange:
    """The full superelevation of a curve between two distances (LandXML ``Superelevation``): ``full_percent`` is
    + when the road is banked toward the inside of the curve."""

    start_distance_m: float
    end_distance_m: float
    full_percent: float
    where: str = ""


class RangeColumns(_Columns[SuperelevationRange]):
    """Superelevation ranges held as columns, one entry per range: a sequence of :class:`SuperelevationRange` (each
    made when it is asked for) that :func:`superelevations` reads as arrays (a design file has one per curve: a
    long road's hundreds of thousands of records would be made, sorted and read back). ``where``: any sequence of
    the ranges' places (a reader may make each when it is asked for)."""

    _noun, _plural = "superelevation range", "ranges"
    __slots__ = ("end_distance_m", "full_percent", "start_distance_m", "where")

    def __init__(self, start_distance_m, end_distance_m, full_percent, where: Sequence[str]):
        self.start_distance_m = np.asarray(start_distance_m, dtype=float)
        self.end_distance_m = np.asarray(end_distance_m, dtype=float)
        self.full_percent = np.asarray(full_percent, dtype=float)
        self.where = where
        self._same_lengths()

    def __len__(self) -> int:
        return len(self.start_distance_m)

    def _one(self, i: int) -> SuperelevationRange:
        return SuperelevationRange(
            float(self.start_distance_m[i]), float(self.end_distance_m[i]), float(self.full_percent[i]), self.where[i]
        )


@dataclass(frozen=True)
class CrossSlope:
    """The cross slopes at one distance (LandXML design ``CrossSect``; IFC cant): the left lane's and the right
    lane's slope in percent, each signed + rising from left to right (see the module's conventions)."""

    distance_m: float
    left_percent: float
    right_percent: float


class SlopeColumns(_Columns[CrossSlope]):
    """Cross slopes held as columns, one entry per section: a sequence of :class:`CrossSlope` (each made when it is
    asked for) that :func:`superelevations` reads as arrays (as :class:`ElementColumns` for the elements): a long
    road's design cross sections are hundreds of thousands, and records would be made, sorted and read back."""

    _noun, _plural = "cross slope", "sections"
    __slots__ = ("distance_m", "left_percent", "right_percent")

    def __init__(self, distance_m, left_percent, right_percent):
        self.distance_m = np.asarray(distance_m, dtype=float)
        self.left_percent = np.asarray(left_percent, dtype=float)
        self.right_percent = np.asarray(right_percent, dtype=float)
        self._same_lengths()

    def __len__(self) -> int:
        return len(self.distance_m)

    def _one(self, i: int) -> CrossSlope:
        return CrossSlope(float(self.distance_m[i]), float(self.left_percent[i]), float(self.right_percent[i]))


@dataclass(frozen=True)
class AlignmentGeometry:
    """One alignment as read from a file, in SI units (see the module's conventions)."""

    name: str
    start_station_m: float
    #: a tuple of records, or (a reader of a large file) the same as :class:`ElementColumns`
    elements: Sequence[HorizontalElement]
    station_equations: tuple[StationEquation, ...] = ()
    profiles: tuple[Profile, ...] = ()
    #: a tuple of records, or (a reader of a large file) the same as :class:`RangeColumns`
    superelevation: Sequence[SuperelevationRange] = ()
    #: a tuple of records, or (a reader of a large file) the same as :class:`SlopeColumns`
    cross_slopes: Sequence[CrossSlope] = ()
    where: str = ""
    notes: tuple[str, ...] = field(default=())


@dataclass(frozen=True)
class RoadFile:
    """What a reader made of one road-design file: its alignments in SI units and the facts the answer's ``reading``
    summary reports (``format`` such as ``"LandXML 1.2"`` or ``"IFC4X3_ADD2"``; ``writer``: the application that
    wrote it, where the file says; ``linear_unit``: the file's length unit as the file names it; ``skipped``:
    (what, why) for everything read but not used; ``elements``: how many of each of the file's element types were
    read)."""

    format: str
    alignments: tuple[AlignmentGeometry, ...]
    linear_unit: str = "meter"
    writer: str | None = None
    skipped: tuple[tuple[str, str], ...] = ()
    #: (the file's name for an element type, how many were read), e.g. ("Spiral", 4)
    elements: tuple[tuple[str, int], ...] = ()


# ---------------------------------------------------------------------------------------------- stations


def element_distances(alignment: AlignmentGeometry) -> np.ndarray:
    """The distance along the alignment [m] at the start of each element and at the end of the last (``n + 1``
    values): the cumulative sum of the element lengths, from 0 at the alignment's start."""
    return np.concatenate(([0.0], np.cumsum(element_columns(alignment).length_m)))


def station_at(alignment: AlignmentGeometry, distance_m: np.ndarray | float) -> np.ndarray:
    """The station as the file writes it [m] at each distance along [m]: the alignment's start station plus the
    distance, restarted at each station equation's ahead station past its distance (an equation applies from its
    distance on; at the distance itself the station ahead is written)."""
    d = np.asarray(distance_m, dtype=float)
    station = alignment.start_station_m + d
    for eq in sorted(alignment.station_equations, key=lambda q: q.distance_m):
        station = np.where(d >= eq.distance_m, eq.station_ahead_m + (d - eq.distance_m), station)
    return station


def distance_at(alignment: AlignmentGeometry, station_m: np.ndarray | float) -> np.ndarray:
    """The distance along [m] of each written station [m] (the inverse of :func:`station_at`): a station is taken
    in the last station range (between two equations) that contains it, so a station written twice (an equation
    that steps back) is read as the later one, as a station equation's "ahead" side is the one in force."""
    s = np.asarray(station_m, dtype=float)
    eqs = sorted(alignment.station_equations, key=lambda q: q.distance_m)
    distance = s - alignment.start_station_m
    for eq in eqs:
        ahead = eq.distance_m + (s - eq.station_ahead_m)
        distance = np.where(ahead >= eq.distance_m, ahead, distance)
    return distance


# ---------------------------------------------------------------------------------------------- bends


@dataclass(frozen=True)
class Bend:
    """One assessed row of an alignment: a circular arc with the spirals leading into and out of it, or a bend made
    only of spirals (assessed at its smallest radius; its ``apex`` is where that radius is).

    Distances along the alignment [m]: ``start_m``/``end_m`` the bend's (spirals included), ``arc_start_m`` where the
    arc starts (a spiral-only bend: its apex), ``arc_length_m`` (0 for a spiral-only bend). ``radius_m``: the
    governing radius; ``deflection_deg``: the change of direction over the row's elements (Sum L/R over arcs,
    L (1/R1 + 1/R2)/2 over each spiral); ``compound``: the arc shares its bend with arcs of another radius;
    (consecutive arcs of one radius, as a file splits an arc at a station, are one row);
    ``reverse``: the row joins, with no line between, a bend turning the other way; ``elements``: the indices of
    the alignment's elements in the row."""

    direction: Direction
    radius_m: float
    start_m: float
    end_m: float
    arc_start_m: float
    arc_length_m: float
    spiral_in_m: float
    spiral_out_m: float
    deflection_deg: float
    compound: bool
    reverse: bool
    elements: tuple[int, ...]

    @property
    def middle_m(self) -> float:
        """The middle of the bend, spirals included [m]: where its grade is read."""
        return 0.5 * (self.start_m + self.end_m)

    @property
    def arc_middle_m(self) -> float:
        """The middle of the arc [m] (a spiral-only bend: its apex): where its cross slope is read."""
        return self.arc_start_m + 0.5 * self.arc_length_m


#: arcs whose radii differ by less than this (relative) are one arc split by the file (rounding in its digits)
SAME_RADIUS_RELATIVE = 1e-9


def _same_radius(a: float, b: float) -> bool:
    return abs(a - b) <= SAME_RADIUS_RELATIVE * max(a, b)


def _curvature(r: float) -> float:
    return 0.0 if math.isinf(r) else 1.0 / r


def element_deflection_rad(e: HorizontalElement) -> float:
    """The change of direction over one element [rad], unsigned: 0 on a line, L/R on an arc, and on a clothoid
    (curvature linear in length) the mean curvature times the length, L (1/R1 + 1/R2)/2, which is L/(2R) from or
    to a tangent."""
    if e.kind == "line":
        return 0.0
    return e.length_m * 0.5 * (_curvature(e.radius_start_m) + _curvature(e.radius_end_m))


@dataclass(frozen=True)
class BendColumns:
    """The alignment's rows (:class:`Bend`) as arrays, one entry per row: what :func:`bend_columns` computes on the
    elements' arrays (a million elements in a fraction of a second). ``direction``: 0 left, 1 right;
    ``first_element``/``last_element``: the row's elements' indices; ``arc_element``: its first arc's (-1 for a bend
    made only of spirals)."""

    direction: np.ndarray
    radius_m: np.ndarray
    start_m: np.ndarray
    end_m: np.ndarray
    arc_start_m: np.ndarray
    arc_length_m: np.ndarray
    spiral_in_m: np.ndarray
    spiral_out_m: np.ndarray
    deflection_deg: np.ndarray
    compound: np.ndarray
    reverse: np.ndarray
    first_element: np.ndarray
    arc_element: np.ndarray
    last_element: np.ndarray

    def __len__(self) -> int:
        return len(self.radius_m)

    def bend(self, i: int) -> Bend:
        """Row ``i`` as a :class:`Bend`."""
        return Bend(
            direction="left" if self.direction[i] == 0 else "right",
            radius_m=float(self.radius_m[i]),
            start_m=float(self.start_m[i]),
            end_m=float(self.end_m[i]),
            arc_start_m=float(self.arc_start_m[i]),
            arc_length_m=float(self.arc_length_m[i]),
            spiral_in_m=float(self.spiral_in_m[i]),
            spiral_out_m=float(self.spiral_out_m[i]),
            deflection_deg=float(self.deflection_deg[i]),
            compound=bool(self.compound[i]),
            reverse=bool(self.reverse[i]),
            elements=tuple(range(int(self.first_element[i]), int(self.last_element[i]) + 1)),
        )


def _first_and_last(groups: np.ndarray, positions: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """For non-decreasing group numbers ``groups`` of the sorted ``positions``: each group's first and last
    position (-1 for a group of none), ``n`` groups."""
    first, last = np.full(n, -1), np.full(n, -1)
    if len(groups):
        head = np.r_[True, groups[1:] != groups[:-1]]
        tail = np.r_[groups[1:] != groups[:-1], True]
        first[groups[head]] = positions[head]
        last[groups[tail]] = positions[tail]
    return first, last


def bend_columns(alignment: AlignmentGeometry) -> BendColumns:
    """The alignment's rows, in order of distance (see :class:`Bend`), as arrays.

    Runs of curved elements turning one way with no straight point between them (a line, a zero length, or two
    spirals meeting at an infinite radius end a run; so does a change of direction) give one row per circular arc:
    the spirals before the run's first arc are its ``spiral_in``, those after an arc (up to the next arc or the run's
    end) its ``spiral_out``, so every element is in exactly one row and the rows' deflections add up to the run's;
    consecutive arcs of one radius (a file's split) are one row. A run without an arc is one row at its smallest
    radius. Rows of a run with several are ``compound``; a run that meets a run turning the other way with no
    straight element between them is a reverse curve (its row at that end is ``reverse``).
    """
    el = element_columns(alignment)
    n = len(el)
    kind, length, r1, r2, dirn = el.kind, el.length_m, el.radius_start_m, el.radius_end_m, el.direction
    starts = np.concatenate(([0.0], np.cumsum(length)))
    is_arc = kind == 1
    straight = (kind == 0) | (np.isinf(r1) & np.isinf(r2)) | (length <= 0.0)
    curved = ~straight
    brk = np.ones(n, dtype=bool)
    brk[1:] = straight[:-1] | (dirn[1:] != dirn[:-1]) | (np.isinf(r2[:-1]) & np.isinf(r1[1:]))
    run_start = curved & brk
    positions = np.arange(n)
    run_first = np.maximum.accumulate(np.where(run_start, positions, 0))
    arcs_upto = np.cumsum(is_arc)
    arcs_before = (arcs_upto - is_arc) - (arcs_upto[run_first] - is_arc[run_first])  # in the run, before this one
    same_as_before = np.zeros(n, dtype=bool)
    rel = SAME_RADIUS_RELATIVE * np.maximum(r1[1:], r1[:-1])
    with np.errstate(invalid="ignore"):  # inf - inf where neither is an arc
        same_radius = np.abs(r1[1:] - r1[:-1]) <= rel
    same_as_before[1:] = is_arc[1:] & is_arc[:-1] & ~run_start[1:] & same_radius
    group_start = curved & (run_start | (is_arc & (arcs_before > 0) & ~same_as_before))
    idx = np.flatnonzero(curved)
    g = (np.cumsum(group_start) - 1)[idx]
    runs = (np.cumsum(run_start) - 1)[idx]
    ng = int(g[-1]) + 1 if len(g) else 0
    first, last = _first_and_last(g, idx, ng)
    arc_mask = is_arc[idx]
    first_arc, last_arc = _first_and_last(g[arc_mask], idx[arc_mask], ng)
    with np.errstate(over="ignore", divide="ignore"):  # a radius too small to invert is refused by the bounds later
        curvature = np.where(np.isinf(r1), 0.0, 1.0 / r1) + np.where(np.isinf(r2), 0.0, 1.0 / r2)
    deflection = np.where(kind == 0, 0.0, length * 0.5 * curvature)  # L/R on an arc, L (1/R1 + 1/R2)/2 on a spiral
    turn = np.bincount(g, weights=deflection[idx], minlength=ng)
    arc_length = np.bincount(g, weights=np.where(is_arc, length, 0.0)[idx], minlength=ng)
    has_arc = first_arc >= 0
    fa, la = np.where(has_arc, first_arc, 0), np.where(has_arc, last_arc, 0)
    radius = np.where(has_arc, r1[fa], np.inf)
    arc_start = np.where(has_arc, starts[fa], np.nan)
    spiral_in = np.where(has_arc, starts[fa] - starts[first], 0.0)
    spiral_out = np.where(has_arc, starts[last + 1] - starts[la + 1], 0.0)
    for k in np.flatnonzero(~has_arc).tolist():  # spirals only: the smallest radius, at an element's end
        best, apex = math.inf, float(starts[first[k]])
        for j in range(int(first[k]), int(last[k]) + 1):
            for r, d in ((r1[j], starts[j]), (r2[j], starts[j + 1])):
                if r < best:
                    best, apex = float(r), float(d)
        radius[k], arc_start[k] = best, apex
        spiral_in[k], spiral_out[k] = apex - starts[first[k]], starts[last[k] + 1] - apex
    # per run: its groups, its ends, and whether it meets a run turning the other way with nothing straight between
    run_of_group = runs[np.r_[True, g[1:] != g[:-1]]] if len(g) else np.empty(0, dtype=int)
    nr = int(runs[-1]) + 1 if len(runs) else 0
    groups_in_run = np.bincount(run_of_group, minlength=nr)
    run_first_el, run_last_el = _first_and_last(runs, idx, nr)
    meets_next = np.zeros(nr, dtype=bool)
    if nr > 1:
        meets_next[:-1] = (run_last_el[:-1] + 1 == run_first_el[1:]) & (
            dirn[run_last_el[:-1]] != dirn[run_first_el[1:]]
        )
    reverse_out, reverse_in = meets_next, np.r_[False, meets_next[:-1]] if nr else meets_next
    first_of_run = np.r_[True, run_of_group[1:] != run_of_group[:-1]] if ng else np.empty(0, dtype=bool)
    last_of_run = np.r_[run_of_group[1:] != run_of_group[:-1], True] if ng else np.empty(0, dtype=bool)
    return BendColumns(
        direction=dirn[first].astype(np.int8) if ng else np.empty(0, np.int8),
        radius_m=radius,
        start_m=starts[first] if ng else np.empty(0),
        end_m=starts[last + 1] if ng else np.empty(0),
        arc_start_m=arc_start,
        arc_length_m=arc_length,
        spiral_in_m=spiral_in,
        spiral_out_m=spiral_out,
        deflection_deg=np.degrees(turn),
        compound=has_arc & (groups_in_run[run_of_group] > 1),
        reverse=(first_of_run & reverse_in[run_of_group]) | (last_of_run & reverse_out[run_of_group]),
        first_element=first,
        arc_element=first_arc,
        last_element=last,
    )


def bends(alignment: AlignmentGeometry) -> list[Bend]:
    """The alignment's rows as :class:`Bend` records (:func:`bend_columns`)."""
    cols = bend_columns(alignment)
    return [cols.bend(i) for i in range(len(cols))]


# ---------------------------------------------------------------------------------------------- profile


def _segment_grade(s: VerticalSegment, d: np.ndarray) -> np.ndarray:
    """The grade (ratio) of one vertical segment at distances ``d`` inside it."""
    if s.kind == "constant" or s.length_m <= 0.0:
        return np.full_like(d, s.start_grade)
    u = np.clip(d - s.start_distance_m, 0.0, s.length_m)
    if s.kind == "parabolic":  # y'' constant: the grade is linear in the horizontal distance
        return s.start_grade + (s.end_grade - s.start_grade) * u / s.length_m
    # circular: the tangent's angle theta, with dx = R cos(theta) dtheta, so sin(theta) changes linearly with x:
    # sin(theta) = sin(theta0) + x / R on a sag, - x / R on a crest (exact)
    t0 = math.atan(s.start_grade)
    t1 = math.atan(s.end_grade)
    radius = s.radius_m if s.radius_m else s.length_m / abs(math.sin(t1) - math.sin(t0))
    sign = 1.0 if s.end_grade >= s.start_grade else -1.0
    sin_t = np.clip(math.sin(t0) + sign * u / radius, -1.0, 1.0)
    return np.tan(np.arcsin(sin_t))


def profile_range_m(profile: Profile) -> tuple[float, float]:
    """The distances [m] the profile covers: from its first segment's start to its last segment's end."""
    first, last = profile.segments[0], profile.segments[-1]
    return first.start_distance_m, last.start_distance_m + last.length_m


def grade_at(profile: Profile, distance_m: float) -> float:
    """The profile's grade (ratio, + uphill) at a distance along [m] (in the segment that starts at or before it;
    at a segment's end the next one's)."""
    starts = [s.start_distance_m for s in profile.segments]
    k = max(0, int(np.searchsorted(starts, distance_m, side="right")) - 1)
    return float(_segment_grade(profile.segments[k], np.array([distance_m]))[0])


def grade_range(profile: Profile, start_m: float, end_m: float) -> tuple[float, float]:
    """The least and greatest grade (ratios) over ``[start_m, end_m]``: of the road inside the range, so of every
    segment overlapping it over a length (a segment that only touches an end carries none of the range's road).
    Every segment's grade is monotone, so the extremes are at the range's ends or at the segment boundaries inside
    it (both sides of a jump). At a PVI without a vertical curve the grade jumps: exactly at a range's end only the
    grade on the range's side applies (the other is the road beyond it), strictly inside both do; a range of no
    length at a jump takes both (the grades either side of the one point)."""
    values: list[float] = []
    point = start_m == end_m
    for s in profile.segments:
        if not s.length_m > 0.0:  # a segment of no length carries no road
            continue
        a, b = max(start_m, s.start_distance_m), min(end_m, s.start_distance_m + s.length_m)
        if a < b or (point and a == b):
            values.extend(_segment_grade(s, np.array([a, b])).tolist())
    if not values:
        g = grade_at(profile, 0.5 * (start_m + end_m))
        return g, g
    return min(values), max(values)


def covers(profile: Profile, start_m: float, end_m: float, tolerance_m: float = 1e-6) -> bool:
    """Whether the profile covers ``[start_m, end_m]`` (within ``tolerance_m``, for rounding in the file)."""
    a, b = profile_range_m(profile)
    return a - tolerance_m <= start_m and end_m <= b + tolerance_m


def _segment_table(profile: Profile) -> tuple[np.ndarray, ...]:
    """The profile's segments as arrays: start, length, kind (0 constant, 1 parabola, 2 circle), start and end
    grade, the circle's radius, the sine of its start angle and its sense (+1 sag, -1 crest)."""
    segs = profile.segments
    if isinstance(segs, SegmentColumns):  # the columns as they are (the records made from them hold the same floats)
        start, length, g0, g1 = segs.start_distance_m, segs.length_m, segs.start_grade, segs.end_grade
        kind = np.where(length <= 0, 0, segs.kind)
        radius = np.where(np.isnan(segs.radius_m) | (segs.radius_m == 0), np.inf, segs.radius_m)
    else:  # a column per field, each a list of floats (not a tuple per segment: as many containers for the garbage
        # collector to walk, in a process that may hold a parsed document)
        start = np.array([x.start_distance_m for x in segs], dtype=float)
        length = np.array([x.length_m for x in segs], dtype=float)
        kind = np.array(
            [0 if x.kind == "constant" or x.length_m <= 0 else 1 if x.kind == "parabolic" else 2 for x in segs]
        )
        g0 = np.array([x.start_grade for x in segs], dtype=float)
        g1 = np.array([x.end_grade for x in segs], dtype=float)
        radius = np.array([x.radius_m if x.radius_m else np.inf for x in segs], dtype=float)
    sin0 = np.sin(np.arctan(g0))
    with np.errstate(divide="ignore"):  # R = L / |sin(theta1) - sin(theta0)| where the file gave none
        from_grades = length / np.abs(np.sin(np.arctan(g1)) - sin0)
    radius = np.where(np.isinf(radius) & (kind == 2), from_grades, radius)
    sense = np.where(g1 >= g0, 1.0, -1.0)
    return start, length, kind, g0, g1, radius, sin0, sense


def _grades_in(table: tuple[np.ndarray, ...], d: np.ndarray, from_before: bool) -> np.ndarray:
    """:func:`grades_at` on a profile's :func:`_segment_table` (built once by a caller that asks several times)."""
    start, length, kind, g0, g1, radius, sin0, sense = table
    k = np.clip(np.searchsorted(start, d, side="left" if from_before else "right") - 1, 0, len(start) - 1)
    u = np.clip(d - start[k], 0.0, length[k])
    with np.errstate(divide="ignore", invalid="ignore"):
        parabola = g0[k] + (g1[k] - g0[k]) * u / length[k]
        circle = np.tan(np.arcsin(np.clip(sin0[k] + sense[k] * u / radius[k], -1.0, 1.0)))
    return np.where(kind[k] == 0, g0[k], np.where(kind[k] == 1, parabola, circle))


def grades_at(profile: Profile, distance_m: np.ndarray, *, from_before: bool = False) -> np.ndarray:
    """:func:`grade_at` at many distances (ratios); ``from_before``: at a segment's start, the grade at the end of
    the segment before it (the left limit), as the end of a range takes it."""
    return _grades_in(_segment_table(profile), np.asarray(distance_m, dtype=float), from_before)


def grade_ranges(profile: Profile, start_m: np.ndarray, end_m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`grade_range` over many ranges: the grades at each range's ends, each taken from inside the range (at
    a jump the start's from the segment after it, the end's from the segment before it), and at both sides of every
    segment boundary strictly inside it (every segment's grade is monotone)."""
    return _ranges_in(_segment_table(profile), np.asarray(start_m, dtype=float), np.asarray(end_m, dtype=float))


def grades_over(
    profile: Profile, start_m: np.ndarray, end_m: np.ndarray, at_m: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`grade_ranges` over ``[start_m, end_m]`` and :func:`grades_at` at ``at_m`` (the same numbers) from one
    reading of the profile's segments (a long profile has tens of thousands)."""
    table = _segment_table(profile)
    lo, hi = _ranges_in(table, np.asarray(start_m, dtype=float), np.asarray(end_m, dtype=float))
    return lo, hi, _grades_in(table, np.asarray(at_m, dtype=float), False)


def _ranges_in(table: tuple[np.ndarray, ...], a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`grade_ranges` on a profile's :func:`_segment_table`."""
    ga, gb = _grades_in(table, a, False), _grades_in(table, b, True)
    lo, hi = np.minimum(ga, gb), np.maximum(ga, gb)
    bounds = table[0][1:]
    if not len(bounds):
        return lo, hi
    # both sides of every boundary, once each; a range then takes those of the boundaries inside it
    at_bound = (_grades_in(table, bounds, True), _grades_in(table, bounds, False))
    first = np.searchsorted(bounds, a, side="right")
    stop = np.searchsorted(bounds, b, side="left")
    for t in range(int((stop - first).max(initial=0))):
        inside = first + t < stop
        k = np.minimum(first + t, len(bounds) - 1)
        for side in at_bound:
            g = side[k]
            lo = np.where(inside, np.minimum(lo, g), lo)
            hi = np.where(inside, np.maximum(hi, g), hi)
    return lo, hi


def covers_many(profile: Profile, start_m: np.ndarray, end_m: np.ndarray, tolerance_m: float = 1e-6) -> np.ndarray:
    """:func:`covers` for many ranges."""
    a, b = profile_range_m(profile)
    return (a - tolerance_m <= np.asarray(start_m)) & (np.asarray(end_m) <= b + tolerance_m)


# ---------------------------------------------------------------------------------------------- superelevation

SuperelevationFrom = Literal["file", "cross-sections"]


def superelevations(alignment: AlignmentGeometry, cols: BendColumns) -> tuple[np.ndarray, np.ndarray]:
    """Each row's superelevation [%] from the file and where it came from (0: a ``SuperelevationRange``, 1: the
    cross slopes; nan: none, and the value nan).

    A ``SuperelevationRange`` (the file's own statement) wins: the one containing the arc's middle (the apex of a
    spiral-only bend), else of the ranges beside that point the one overlapping the bend most. Else the cross slopes
    of the sections within the bend: the outside lane's slope, signed toward the inside (see the module's
    conventions; a normal crown kept through the curve is negative), linearly interpolated at the arc's middle
    between the sections around it (the nearest section where the middle is outside them)."""
    n = len(cols)
    mid = cols.arc_start_m + 0.5 * cols.arc_length_m
    value, source = np.full(n, np.nan), np.full(n, np.nan)
    ranges = alignment.superelevation
    if len(ranges) and n:
        if isinstance(ranges, RangeColumns):  # in order of start, ranges with one start as given (as sorted() does)
            order = np.argsort(ranges.start_distance_m, kind="stable")
            rs, re, full = ranges.start_distance_m[order], ranges.end_distance_m[order], ranges.full_percent[order]
        else:
            ranges = sorted(ranges, key=lambda r: r.start_distance_m)
            rs = np.array([r.start_distance_m for r in ranges])
            re = np.array([r.end_distance_m for r in ranges])
            full = np.array([r.full_percent for r in ranges])
        k = np.searchsorted(rs, mid, side="right") - 1
        kc = np.clip(k, 0, len(rs) - 1)
        contained = (k >= 0) & (mid <= re[kc])
        best, best_overlap = np.full(n, -1), np.zeros(n)
        for cand in (kc, np.clip(k + 1, 0, len(rs) - 1), np.clip(k - 1, 0, len(rs) - 1)):
            overlap = np.minimum(re[cand], cols.end_m) - np.maximum(rs[cand], cols.start_m)
            better = overlap > best_overlap
            best, best_overlap = np.where(better, cand, best), np.where(better, overlap, best_overlap)
        pick = np.where(contained, kc, best)
        found = pick >= 0
        value = np.where(found, full[np.maximum(pick, 0)], np.nan)
        source = np.where(found, 0.0, np.nan)
    slopes = alignment.cross_slopes
    if not isinstance(slopes, SlopeColumns):
        slopes = SlopeColumns(
            [c.distance_m for c in slopes], [c.left_percent for c in slopes], [c.right_percent for c in slopes]
        )
    if len(slopes) and n:
        order = np.argsort(slopes.distance_m, kind="stable")  # in order of distance, sections at one distance as given
        d = slopes.distance_m[order]
        lo = np.searchsorted(d, cols.start_m, side="left")
        hi = np.searchsorted(d, cols.end_m, side="right")
        within = (hi > lo) & np.isnan(source)
        at = np.clip(mid, d[np.minimum(lo, len(d) - 1)], d[np.clip(hi - 1, 0, len(d) - 1)])
        # a left-hand curve's outside lane is the right one: rising left to right is banked toward the inside
        right = np.interp(at, d, slopes.right_percent[order])
        left = -np.interp(at, d, slopes.left_percent[order])
        value = np.where(within, np.where(cols.direction == 0, right, left), value)
        source = np.where(within, 1.0, source)
    return value, source


def _one_row(b: Bend) -> BendColumns:
    def a(x: float) -> np.ndarray:
        return np.array([x], dtype=float)

    return BendColumns(
        np.array([0 if b.direction == "left" else 1], np.int8),
        a(b.radius_m), a(b.start_m), a(b.end_m), a(b.arc_start_m), a(b.arc_length_m), a(b.spiral_in_m),
        a(b.spiral_out_m), a(b.deflection_deg), np.array([b.compound]), np.array([b.reverse]),
        np.array([b.elements[0]]), np.array([-1]), np.array([b.elements[-1]]),
    )  # fmt: skip


def bend_superelevation(alignment: AlignmentGeometry, bend: Bend) -> tuple[float, SuperelevationFrom] | None:
    """One bend's superelevation [%] and where it came from (:func:`superelevations`), or None when the file gives
    none over it."""
    value, source = superelevations(alignment, _one_row(bend))
    if np.isnan(source[0]):
        return None
    return float(value[0]), ("file", "cross-sections")[int(source[0])]
