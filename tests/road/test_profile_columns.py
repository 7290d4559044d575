"""The LandXML profile read and evaluated for every point at once (app/formats/landxml.py ``_Reader.profile``,
held as columns; engine/road/geometry.py ``grades_over``) gives the very numbers of the point-by-point formulation
it replaced, which is kept below as the reference: random profiles of PVIs, symmetric and unsymmetric parabolas and
circular vertical curves, and ranges that straddle several vertical elements. And the design cross sections held as
columns give the superelevation the sorted records gave."""

from __future__ import annotations

import dataclasses
import math
import random

import numpy as np
import pytest

from app.formats.landxml import read_road_file
from engine.road import grades_over
from engine.road.geometry import (
    AlignmentGeometry,
    CrossSlope,
    HorizontalElement,
    Profile,
    SlopeColumns,
    VerticalSegment,
    bend_columns,
    grade_at,
    grade_range,
    superelevations,
)

# ---------------------------------------------------------------------------------------------- the reference


def scalar_segments(pts: list[Point]) -> tuple[VerticalSegment, ...]:
    """The point-by-point construction: (distance, elevation, length before, length after, radius) per point."""
    n = len(pts)
    grades = [(pts[i + 1][1] - pts[i][1]) / (pts[i + 1][0] - pts[i][0]) for i in range(n - 1)]
    reach_in, reach_out = [0.0] * n, [0.0] * n
    pieces: list[list[tuple[float, float, str, float, float, float | None]]] = [[] for _ in range(n)]
    for i in range(1, n - 1):
        d, _, before, after, radius = pts[i]
        g1, g2 = grades[i - 1], grades[i]
        if radius is not None:
            t1, t2 = math.atan(g1), math.atan(g2)
            tangent = radius * math.tan(abs(t2 - t1) / 2)
            before, after = tangent * math.cos(t1), tangent * math.cos(t2)
            pieces[i].append((d - before, d + after, "circular", g1, g2, radius))
        elif before > 0 or after > 0:
            g_mid = g1 + after * (g2 - g1) / (before + after)
            if before > 0:
                pieces[i].append((d - before, d, "parabolic", g1, g_mid, None))
            if after > 0:
                pieces[i].append((d, d + after, "parabolic", g_mid, g2, None))
        reach_in[i], reach_out[i] = before, after
    segments = []
    for i in range(n - 1):
        d, z = pts[i][0], pts[i][1]
        a, b = d + reach_out[i], pts[i + 1][0] - reach_in[i + 1]
        assert b >= a - 1e-9
        if b > a:
            segments.append(VerticalSegment("constant", a, b - a, z + grades[i] * (a - d), grades[i], grades[i]))
        for start, end, kind, g_in, g_out, radius in pieces[i + 1]:
            z_start = z + grades[i] * (start - d) if start < pts[i + 1][0] else pts[i + 1][1]
            segments.append(VerticalSegment(kind, start, end - start, z_start, g_in, g_out, radius))
    return tuple(segments)


def _table(profile: Profile) -> tuple[np.ndarray, ...]:
    segs = profile.segments
    start = np.array([x.start_distance_m for x in segs])
    length = np.array([x.length_m for x in segs])
    kind = np.array([0 if x.kind == "constant" or x.length_m <= 0 else 1 if x.kind == "parabolic" else 2 for x in segs])
    g0 = np.array([x.start_grade for x in segs])
    g1 = np.array([x.end_grade for x in segs])
    sin0 = np.sin(np.arctan(g0))
    radius = np.array([x.radius_m if x.radius_m else np.inf for x in segs])
    with np.errstate(divide="ignore"):
        from_grades = length / np.abs(np.sin(np.arctan(g1)) - sin0)
    radius = np.where(np.isinf(radius) & (kind == 2), from_grades, radius)
    sense = np.where(g1 >= g0, 1.0, -1.0)
    return start, length, kind, g0, g1, radius, sin0, sense


def scalar_grades_at(profile: Profile, distance_m: np.ndarray, *, from_before: bool = False) -> np.ndarray:
    start, length, kind, g0, g1, radius, sin0, sense = _table(profile)
    d = np.asarray(distance_m, dtype=float)
    k = np.clip(np.searchsorted(start, d, side="left" if from_before else "right") - 1, 0, len(start) - 1)
    u = np.clip(d - start[k], 0.0, length[k])
    with np.errstate(divide="ignore", invalid="ignore"):
        parabola = g0[k] + (g1[k] - g0[k]) * u / length[k]
        circle = np.tan(np.arcsin(np.clip(sin0[k] + sense[k] * u / radius[k], -1.0, 1.0)))
    return np.where(kind[k] == 0, g0[k], np.where(kind[k] == 1, parabola, circle))


def scalar_grade_ranges(profile: Profile, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each boundary inside a range evaluated for that range (as many evaluations as ranges times boundaries)."""
    seg_start = _table(profile)[0]
    ga, gb = scalar_grades_at(profile, a), scalar_grades_at(profile, b, from_before=True)
    lo, hi = np.minimum(ga, gb), np.maximum(ga, gb)
    bounds = seg_start[1:]
    first = np.searchsorted(bounds, a, side="right")
    stop = np.searchsorted(bounds, b, side="left")
    for t in range(int((stop - first).max(initial=0))):
        inside = first + t < stop
        k = np.minimum(first + t, len(bounds) - 1)
        for g in (scalar_grades_at(profile, bounds[k], from_before=True), scalar_grades_at(profile, bounds[k])):
            lo = np.where(inside, np.minimum(lo, g), lo)
            hi = np.where(inside, np.maximum(hi, g), hi)
    return lo, hi


# ---------------------------------------------------------------------------------------------- random profiles


Point = tuple[float, float, float, float, float | None]  # distance, elevation, length before, after, radius


def _random_points(rng: random.Random, n: int) -> tuple[list[str], list[Point]]:
    """(the ProfAlign's elements, the reference's points): PVIs 300-600 m apart, grades within +-8 %, each inner
    point a PVI, a symmetric or unsymmetric parabola or a circle, every curve short enough not to overlap."""
    xml, pts = [], []
    d, z = 0.0, 100.0
    for i in range(n):
        if i:
            step = round(rng.uniform(300.0, 600.0), 3)
            d, z = d + step, round(z + step * rng.uniform(-0.08, 0.08), 4)
        kind = "PVI" if i in (0, n - 1) else rng.choice(["PVI", "ParaCurve", "UnsymParaCurve", "CircCurve"])
        text = f"{d!r} {z!r}"
        if kind == "ParaCurve":
            length = round(rng.uniform(20.0, 250.0), 2)
            xml.append(f'<ParaCurve length="{length}">{text}</ParaCurve>')
            pts.append((d, z, 0.5 * length, 0.5 * length, None))
        elif kind == "UnsymParaCurve":
            lin, lout = round(rng.uniform(0.0, 140.0), 2), round(rng.uniform(0.0, 140.0), 2)
            xml.append(f'<UnsymParaCurve lengthIn="{lin}" lengthOut="{lout}">{text}</UnsymParaCurve>')
            pts.append((d, z, lin, lout, None))
        elif kind == "CircCurve":
            radius = round(rng.uniform(500.0, 1500.0), 1)  # tangent <= 1500 tan(8 %) < 150 m
            xml.append(f'<CircCurve radius="{rng.choice([-1, 1]) * radius}">{text}</CircCurve>')
            pts.append((d, z, 0.0, 0.0, radius))
        else:
            xml.append(f"<PVI>{text}</PVI>")
            pts.append((d, z, 0.0, 0.0, None))
    return xml, pts


def _document(elements: list[str], end_m: float) -> str:
    return (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        '<Units><Metric linearUnit="meter"/></Units><Alignments><Alignment name="A" staStart="0"><CoordGeom>'
        f'<Line length="{end_m!r}"/></CoordGeom><Profile><ProfAlign name="P">{"".join(elements)}</ProfAlign>'
        "</Profile></Alignment></Alignments></LandXML>"
    )


@pytest.mark.parametrize("seed", range(8))
def test_the_profile_read_at_once_is_the_point_by_point_one(seed):
    rng = random.Random(seed)
    elements, pts = _random_points(rng, rng.randint(2, 60))
    profile = read_road_file(_document(elements, pts[-1][0])).alignments[0].profiles[0]
    expected = scalar_segments(pts)
    assert {s.kind for s in expected} <= {"constant", "parabolic", "circular"}
    assert profile.segments == expected  # field by field, float by float
    # the segments tile the profile: each starts where the one before ends (up to the rounding of a sum)
    ends = [s.start_distance_m + s.length_m for s in profile.segments]
    assert [s.start_distance_m for s in profile.segments[1:]] == pytest.approx(ends[:-1], abs=1e-9)


def test_every_kind_of_vertical_point_occurs_in_the_random_profiles():
    kinds = set()
    for seed in range(8):
        rng = random.Random(seed)
        elements, _ = _random_points(rng, rng.randint(2, 60))
        kinds |= {e[1 : e.index(">" if e.startswith("<PVI") else " ")] for e in elements}
    assert kinds == {"PVI", "ParaCurve", "UnsymParaCurve", "CircCurve"}


@pytest.mark.parametrize("seed", range(8))
def test_grades_over_many_ranges_are_those_evaluated_range_by_range(seed):
    rng = random.Random(100 + seed)
    elements, pts = _random_points(rng, rng.randint(3, 60))
    profile = read_road_file(_document(elements, pts[-1][0])).alignments[0].profiles[0]
    total = pts[-1][0]
    nprng = np.random.default_rng(seed)
    a = nprng.uniform(0.0, total, 400)
    # ranges that start or end exactly at a segment's boundary
    bounds = np.array([s.start_distance_m for s in profile.segments[1:]] or [0.0])
    a[:40] = nprng.choice(bounds, 40)
    width = nprng.choice([0.0, 5.0, 100.0, 1500.0], 400) * nprng.uniform(0.0, 1.0, 400)  # up to several elements
    b = np.minimum(a + width, total)
    b[40:80] = np.maximum(a[40:80], nprng.choice(bounds, 40))
    mid = 0.5 * (a + b)
    lo, hi, at = grades_over(profile, a, b, mid)
    lo_ref, hi_ref = scalar_grade_ranges(profile, a, b)
    assert np.array_equal(lo, lo_ref) and np.array_equal(hi, hi_ref)
    assert np.array_equal(at, scalar_grades_at(profile, mid))
    # the reader's columns and the same segments as records (as another reader gives them) read alike
    assert type(profile.segments).__name__ == "SegmentColumns"
    as_records = Profile("P", tuple(profile.segments))
    for mine, theirs in zip(grades_over(as_records, a, b, mid), (lo, hi, at), strict=True):
        assert np.array_equal(mine, theirs)
    straddling = np.searchsorted(bounds, b, side="left") - np.searchsorted(bounds, a, side="right")
    assert straddling.max() >= 3  # some ranges cross several vertical elements
    # and a second formulation: the scalar functions, segment by segment (the ranges at a boundary included)
    for k in range(0, 400, 5):
        assert (lo[k], hi[k]) == pytest.approx(grade_range(profile, a[k], b[k]), rel=1e-12, abs=1e-15)
        assert at[k] == pytest.approx(grade_at(profile, mid[k]), rel=1e-12, abs=1e-15)


# ---------------------------------------------------------------------------------------------- cross slopes


def sorted_records_crossfall(slopes: tuple[CrossSlope, ...], cols) -> tuple[np.ndarray, np.ndarray]:
    """The cross sections' part of ``superelevations`` as it read records: sorted (stably) by distance, read back."""
    n = len(cols)
    mid = cols.arc_start_m + 0.5 * cols.arc_length_m
    value, source = np.full(n, np.nan), np.full(n, np.nan)
    slopes = sorted(slopes, key=lambda c: c.distance_m)
    d = np.array([c.distance_m for c in slopes])
    lo = np.searchsorted(d, cols.start_m, side="left")
    hi = np.searchsorted(d, cols.end_m, side="right")
    within = (hi > lo) & np.isnan(source)
    at = np.clip(mid, d[np.minimum(lo, len(d) - 1)], d[np.clip(hi - 1, 0, len(d) - 1)])
    right = np.interp(at, d, np.array([c.right_percent for c in slopes]))
    left = -np.interp(at, d, np.array([c.left_percent for c in slopes]))
    value = np.where(within, np.where(cols.direction == 0, right, left), value)
    return value, np.where(within, 1.0, source)


@pytest.mark.parametrize("seed", range(4))
def test_cross_slopes_as_columns_give_the_sorted_records_numbers(seed):
    rng = np.random.default_rng(seed)
    elements = []
    for _ in range(60):  # lines and arcs of either hand
        elements.append(HorizontalElement("line", float(rng.uniform(0.0, 80.0))))
        r = float(rng.uniform(100.0, 900.0))
        elements.append(HorizontalElement("arc", float(rng.uniform(5.0, 120.0)), r, r, rng.choice(["left", "right"])))
    total = sum(e.length_m for e in elements)
    # sections in no order, some at one distance twice, some bends with none
    d = rng.uniform(0.0, total, 300)
    d[::10] = d[1::10]
    left, right = rng.uniform(-8.0, 8.0, 300), rng.uniform(-8.0, 8.0, 300)
    records = tuple(map(CrossSlope, d.tolist(), left.tolist(), right.tolist()))
    columns = SlopeColumns(d, left, right)
    assert columns == records and columns[7] == records[7] and len(columns) == 300
    a = AlignmentGeometry("A", 0.0, tuple(elements), cross_slopes=columns)
    cols = bend_columns(a)
    value, source = superelevations(a, cols)
    expected_value, expected_source = sorted_records_crossfall(records, cols)
    assert np.array_equal(value, expected_value, equal_nan=True)
    assert np.array_equal(source, expected_source, equal_nan=True)
    assert (source == 1).sum() > 10 and np.isnan(source).sum() > 0  # bends with sections and bends without
    from_records = superelevations(dataclasses.replace(a, cross_slopes=records), cols)
    assert all(np.array_equal(x, y, equal_nan=True) for x, y in zip(from_records, (value, source), strict=True))
