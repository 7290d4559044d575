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
from dataclasses import dataclass, field
from typing import Literal

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


@dataclass(frozen=True)
class Profile:
    """A vertical profile (LandXML ``ProfAlign``; IFC ``IfcAlignmentVertical``): its segments in order of distance."""

    name: str
    segments: tuple[VerticalSegment, ...]


@dataclass(frozen=True)
class SuperelevationRange:
    """The full superelevation of a curve between two distances (LandXML ``Superelevation``): ``full_percent`` is
    + when the road is banked toward the inside of the curve."""

    start_distance_m: float
    end_distance_m: float
    full_percent: float
    where: str = ""


@dataclass(frozen=True)
class CrossSlope:
    """The cross slopes at one distance (LandXML design ``CrossSect``; IFC cant): the left lane's and the right
    lane's slope in percent, each signed + rising from left to right (see the module's conventions)."""

    distance_m: float
    left_percent: float
    right_percent: float


@dataclass(frozen=True)
class AlignmentGeometry:
    """One alignment as read from a file, in SI units (see the module's conventions)."""

    name: str
    start_station_m: float
    elements: tuple[HorizontalElement, ...]
    station_equations: tuple[StationEquation, ...] = ()
    profiles: tuple[Profile, ...] = ()
    superelevation: tuple[SuperelevationRange, ...] = ()
    cross_slopes: tuple[CrossSlope, ...] = ()
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
    lengths = np.array([e.length_m for e in alignment.elements], dtype=float)
    return np.concatenate(([0.0], np.cumsum(lengths)))


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


def _runs(elements: tuple[HorizontalElement, ...]) -> list[list[int]]:
    """The runs of consecutive curved elements that turn one way with no straight point between them: a run ends
    at a line, where the direction changes, and where two spirals meet at an infinite radius."""
    runs: list[list[int]] = []
    current: list[int] = []
    for k, e in enumerate(elements):
        straight = e.kind == "line" or (math.isinf(e.radius_start_m) and math.isinf(e.radius_end_m))
        if straight or e.length_m <= 0.0:
            if current:
                runs.append(current)
            current = []
            continue
        if current:
            prev = elements[current[-1]]
            straight_between = math.isinf(prev.radius_end_m) and math.isinf(e.radius_start_m)
            if prev.direction != e.direction or straight_between:
                runs.append(current)
                current = []
        current.append(k)
    if current:
        runs.append(current)
    return runs


def bends(alignment: AlignmentGeometry) -> list[Bend]:
    """The alignment's assessed rows, in order of distance (see :class:`Bend`).

    Each run of curved elements between straight points (lines, or spirals meeting at an infinite radius) that
    turns one way gives one row per circular arc; the spirals before the first arc are its ``spiral_in``, those
    after an arc (up to the next arc or the run's end) its ``spiral_out``, so every element is in exactly one row and
    the rows' deflections add up to the run's. A run without an arc is one row at its smallest radius. Runs that
    meet with no straight element between them and turn opposite ways are reverse curves.
    """
    elements = alignment.elements
    starts = element_distances(alignment)
    runs = _runs(elements)
    out: list[Bend] = []
    for r_index, run in enumerate(runs):
        direction = elements[run[0]].direction or "left"
        before = runs[r_index - 1] if r_index > 0 else None
        after = runs[r_index + 1] if r_index + 1 < len(runs) else None
        reverse_in = before is not None and before[-1] + 1 == run[0] and elements[before[-1]].direction != direction
        reverse_out = after is not None and run[-1] + 1 == after[0] and elements[after[0]].direction != direction
        reverse = reverse_in or reverse_out
        if not any(elements[k].kind == "arc" for k in run):
            out.append(_spiral_bend(elements, starts, run, direction, reverse))
            continue
        groups: list[list[int]] = []
        for k in run:  # each arc takes the spirals before it (first arc only) and after it
            last_arc = next((j for j in reversed(groups[-1]) if elements[j].kind == "arc"), None) if groups else None
            if elements[k].kind == "arc" and last_arc is not None:
                # an arc split in two by the file (at a station of its own) continues at the same radius
                same = last_arc == k - 1 and _same_radius(elements[k].radius_start_m, elements[last_arc].radius_start_m)
                if same:
                    groups[-1].append(k)
                else:
                    groups.append([k])
            elif not groups:
                groups.append([k])
            else:
                groups[-1].append(k)
        compound = len(groups) > 1
        for g_index, group in enumerate(groups):
            arcs_of = [k for k in group if elements[k].kind == "arc"]
            arc = arcs_of[0]
            spiral_in = sum(elements[k].length_m for k in group if k < arc)
            spiral_out = sum(elements[k].length_m for k in group if k > arcs_of[-1])
            deflection = sum(element_deflection_rad(elements[k]) for k in group)
            out.append(
                Bend(
                    direction=direction,
                    radius_m=elements[arc].radius_start_m,
                    start_m=float(starts[group[0]]),
                    end_m=float(starts[group[-1] + 1]),
                    arc_start_m=float(starts[arc]),
                    arc_length_m=sum(elements[k].length_m for k in arcs_of),
                    spiral_in_m=spiral_in,
                    spiral_out_m=spiral_out,
                    deflection_deg=math.degrees(deflection),
                    compound=compound,
                    # the row that meets the opposite bend
                    reverse=(g_index == 0 and reverse_in) or (g_index == len(groups) - 1 and reverse_out),
                    elements=tuple(group),
                )
            )
    return out


def _spiral_bend(
    elements: tuple[HorizontalElement, ...], starts: np.ndarray, run: list[int], direction: Direction, reverse: bool
) -> Bend:
    """A run of spirals: assessed at its smallest radius, found at an element's end (a clothoid's radius is monotone
    along it); the apex is the first point where it is reached."""
    radius, apex = math.inf, float(starts[run[0]])
    for k in run:
        for r, d in ((elements[k].radius_start_m, starts[k]), (elements[k].radius_end_m, starts[k + 1])):
            if r < radius:
                radius, apex = r, float(d)
    start, end = float(starts[run[0]]), float(starts[run[-1] + 1])
    return Bend(
        direction=direction,
        radius_m=radius,
        start_m=start,
        end_m=end,
        arc_start_m=apex,
        arc_length_m=0.0,
        spiral_in_m=apex - start,
        spiral_out_m=end - apex,
        deflection_deg=math.degrees(sum(element_deflection_rad(elements[k]) for k in run)),
        compound=False,
        reverse=reverse,
        elements=tuple(run),
    )


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
    """The least and greatest grade (ratios) over ``[start_m, end_m]``: every segment's grade is monotone, so the
    extremes are at the range's ends or at the segment boundaries inside it (both sides of a jump)."""
    values: list[float] = []
    for s in profile.segments:
        a, b = max(start_m, s.start_distance_m), min(end_m, s.start_distance_m + s.length_m)
        if a <= b:
            values.extend(_segment_grade(s, np.array([a, b])).tolist())
    if not values:
        g = grade_at(profile, 0.5 * (start_m + end_m))
        return g, g
    return min(values), max(values)


def covers(profile: Profile, start_m: float, end_m: float, tolerance_m: float = 1e-6) -> bool:
    """Whether the profile covers ``[start_m, end_m]`` (within ``tolerance_m``, for rounding in the file)."""
    a, b = profile_range_m(profile)
    return a - tolerance_m <= start_m and end_m <= b + tolerance_m


# ---------------------------------------------------------------------------------------------- superelevation

SuperelevationFrom = Literal["file", "cross-sections"]


def bend_superelevation(alignment: AlignmentGeometry, bend: Bend) -> tuple[float, SuperelevationFrom] | None:
    """The bend's superelevation [%] and where it came from, or None when the file gives none over it.

    A ``SuperelevationRange`` (the file's own statement) wins: the one containing the arc's middle, else the one
    overlapping the bend most. Else the cross slopes of the sections within the bend: the outside lane's slope,
    signed toward the inside (see the module's conventions; a normal crown kept through the curve is negative),
    linearly interpolated at the arc's middle (the apex of a spiral-only bend) between the sections around it
    (the nearest section where the middle is outside them)."""
    mid = bend.arc_middle_m
    ranges = alignment.superelevation
    if ranges:
        containing = [r for r in ranges if r.start_distance_m <= mid <= r.end_distance_m]
        if containing:
            return containing[0].full_percent, "file"
        overlap = [
            (min(r.end_distance_m, bend.end_m) - max(r.start_distance_m, bend.start_m), r.full_percent) for r in ranges
        ]
        best = max(overlap)
        if best[0] > 0.0:
            return best[1], "file"
    sections = [c for c in alignment.cross_slopes if bend.start_m <= c.distance_m <= bend.end_m]
    if not sections:
        return None
    sections.sort(key=lambda c: c.distance_m)
    d = np.array([c.distance_m for c in sections])
    if bend.direction == "left":  # outside: the right lane; rising left to right is banked toward the inside
        e = np.array([c.right_percent for c in sections])
    else:
        e = -np.array([c.left_percent for c in sections])
    return float(np.interp(mid, d, e)), "cross-sections"
