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
    (what, why) for everything read but not used)."""

    format: str
    alignments: tuple[AlignmentGeometry, ...]
    linear_unit: str = "meter"
    writer: str | None = None
    skipped: tuple[tuple[str, str], ...] = ()
