"""engine.road.geometry's numerics against closed forms: stations are the start station plus the sum of the
lengths (and a station equation restarts them), a clothoid turns L/(2R) from a tangent (curvature linear in length,
its integral the mean curvature times L), a symmetric parabola's grade at its middle is the mean of its tangent
grades (grade linear in distance), a circular vertical curve's sin(angle) is linear in distance (dx = R cos d(theta)),
and the cross slope rule of the module's conventions (a normal crown through a curve is adverse: negative)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.road.geometry import (
    AlignmentGeometry,
    CrossSlope,
    ElementColumns,
    HorizontalElement,
    Profile,
    RangeColumns,
    StationEquation,
    SuperelevationRange,
    VerticalSegment,
    bend_superelevation,
    bends,
    covers,
    distance_at,
    element_distances,
    grade_at,
    grade_range,
    grade_ranges,
    grades_at,
    station_at,
)

INF = math.inf


def line(length):
    return HorizontalElement("line", length)


def arc(length, r, d="left"):
    return HorizontalElement("arc", length, r, r, d)


def spiral(length, r1, r2, d="left"):
    return HorizontalElement("spiral", length, r1, r2, d, spiral_type="clothoid")


def alignment(*elements, start=0.0, equations=(), **kw):
    return AlignmentGeometry("A", start, tuple(elements), station_equations=tuple(equations), **kw)


def test_stations_sum_the_lengths_from_the_start_station():
    a = alignment(line(100.0), arc(50.0, 300.0), line(25.5), start=1000.0)
    assert element_distances(a).tolist() == [0.0, 100.0, 150.0, 175.5]
    assert station_at(a, element_distances(a)).tolist() == [1000.0, 1100.0, 1150.0, 1175.5]


def test_a_station_equation_restarts_the_written_stations():
    # at 120 m along, the station written back (1120) is replaced by 1200 ahead
    a = alignment(line(100.0), arc(50.0, 300.0), start=1000.0, equations=[StationEquation(120.0, 1120.0, 1200.0)])
    assert station_at(a, [0.0, 119.0, 120.0, 150.0]).tolist() == [1000.0, 1119.0, 1200.0, 1230.0]
    assert distance_at(a, [1000.0, 1119.0, 1200.0, 1230.0]).tolist() == [0.0, 119.0, 120.0, 150.0]


def test_an_arc_with_clothoids_in_and_out():
    ls, r, la = 60.0, 400.0, 100.0
    a = alignment(line(200.0), spiral(ls, INF, r), arc(la, r), spiral(ls, r, INF), line(50.0))
    (b,) = bends(a)
    assert (b.direction, b.radius_m, b.spiral_in_m, b.spiral_out_m) == ("left", r, ls, ls)
    assert (b.start_m, b.arc_start_m, b.arc_length_m, b.end_m) == (200.0, 260.0, la, 420.0)
    # each clothoid from/to a tangent turns L/(2R); the arc L/R
    assert b.deflection_deg == pytest.approx(math.degrees(la / r + 2 * ls / (2 * r)), rel=1e-12)
    assert not b.compound and not b.reverse


def test_a_bend_of_two_clothoids_is_assessed_at_its_apex():
    # the Aplitop bend of ROAD-FILES.md: INF -> 1103.68 -> INF, no arc
    r = 1103.68
    a = alignment(line(10.0), spiral(80.0, INF, r, "right"), spiral(120.0, r, INF, "right"), line(10.0))
    (b,) = bends(a)
    assert (b.radius_m, b.arc_start_m, b.arc_length_m, b.spiral_in_m, b.spiral_out_m) == (r, 90.0, 0.0, 80.0, 120.0)
    assert b.deflection_deg == pytest.approx(math.degrees(80.0 / (2 * r) + 120.0 / (2 * r)), rel=1e-12)
    assert b.direction == "right"


def test_compound_and_reverse_curves_are_separate_rows():
    r1, r2, ls = 300.0, 500.0, 40.0
    # compound: arc R1, clothoid R1 -> R2, arc R2; then straight into a right-hand arc: a reverse curve
    a = alignment(arc(50.0, r1), spiral(ls, r1, r2), arc(70.0, r2), arc(30.0, 250.0, "right"))
    b1, b2, b3 = bends(a)
    assert (b1.radius_m, b2.radius_m, b3.radius_m) == (r1, r2, 250.0)
    assert b1.compound and b2.compound and not b3.compound
    assert b2.reverse and b3.reverse and b1.reverse is False
    # the clothoid between radii turns L (1/R1 + 1/R2) / 2, counted once (with the arc it leaves)
    assert b1.spiral_out_m == ls and b2.spiral_in_m == 0.0
    assert b1.deflection_deg == pytest.approx(math.degrees(50.0 / r1 + ls * (1 / r1 + 1 / r2) / 2), rel=1e-12)
    assert b2.arc_start_m == 50.0 + ls


def test_spirals_meeting_at_a_straight_point_are_two_bends():
    a = alignment(spiral(50.0, INF, 200.0), spiral(50.0, 200.0, INF), spiral(50.0, INF, 300.0, "right"))
    b = bends(a)
    assert [x.radius_m for x in b] == [200.0, 300.0]
    assert b[0].reverse and b[1].reverse


def test_elements_held_as_columns_are_the_same_records_and_the_same_bends():
    # the form a reader of a large file gives: every field of every record comes back, and the numerics agree
    els = (
        HorizontalElement("line", 200.0, station_m=1000.0, name="L1", where="e1"),
        HorizontalElement("spiral", 60.0, INF, 400.0, "left", 1200.0, "clothoid", None, "e2"),
        HorizontalElement("arc", 100.0, 400.0, 400.0, "left", None, None, "C1", "e3"),
        HorizontalElement("spiral", 60.0, 400.0, INF, "left", None, "bloss", None, "e4"),
        HorizontalElement("arc", 30.0, 250.0, 250.0, "right", 1460.0, None, "C2", "e5"),
    )
    cols = ElementColumns.of(els)
    assert len(cols) == 5 and tuple(cols) == els and cols == els and cols[2] == els[2] and cols[-1] == els[-1]
    assert cols[1:3] == els[1:3] and ElementColumns.of(cols) is cols
    with pytest.raises(IndexError):
        cols[5]
    as_records, as_columns = alignment(*els, start=1000.0), AlignmentGeometry("A", 1000.0, cols)
    assert bends(as_columns) == bends(as_records) and len(bends(as_records)) == 2
    assert element_distances(as_columns).tolist() == element_distances(as_records).tolist() == [
        0.0, 200.0, 260.0, 360.0, 420.0, 450.0,
    ]  # fmt: skip


def _profile(*segments):
    return Profile("P", tuple(segments))


def test_symmetric_parabola_mid_grade_is_the_mean_of_its_tangents():
    g1, g2, length = 0.06, -0.04, 200.0
    p = _profile(VerticalSegment("parabolic", 100.0, length, 50.0, g1, g2))
    assert grade_at(p, 200.0) == pytest.approx((g1 + g2) / 2, abs=1e-15)
    assert grade_range(p, 150.0, 250.0) == pytest.approx((g1 + (g2 - g1) * 0.75, g1 + (g2 - g1) * 0.25))


def test_circular_vertical_curve_is_exact():
    # a sag of radius 5000 m from -3 % : sin(theta) = sin(theta0) + x / R
    r, g0, x = 5000.0, -0.03, 180.0
    t0 = math.atan(g0)
    g_end = math.tan(math.asin(math.sin(t0) + 300.0 / r))
    p = _profile(VerticalSegment("circular", 0.0, 300.0, 0.0, g0, g_end, r))
    assert grade_at(p, x) == pytest.approx(math.tan(math.asin(math.sin(t0) + x / r)), rel=1e-12)
    # and the same with the radius computed from its grades and length
    q = _profile(VerticalSegment("circular", 0.0, 300.0, 0.0, g0, g_end))
    assert grade_at(q, x) == pytest.approx(grade_at(p, x), rel=1e-12)


def test_grade_range_sees_a_break_without_a_vertical_curve():
    p = _profile(
        VerticalSegment("constant", 0.0, 100.0, 0.0, 0.02, 0.02),
        VerticalSegment("constant", 100.0, 100.0, 2.0, -0.05, -0.05),
    )
    assert grade_range(p, 50.0, 150.0) == (-0.05, 0.02)
    assert grade_at(p, 100.0) == -0.05
    assert covers(p, 0.0, 200.0) and not covers(p, 150.0, 250.0)


@pytest.mark.parametrize(
    ("start", "end", "expected"),
    [
        (100.0, 150.0, (-0.05, -0.05)),  # starts at the PVI: the road over it is all at -5 %
        (60.0, 100.0, (0.0, 0.016)),  # ends at the PVI: the parabola's grades 0.04 (1 - u/100), u = 60..100
        (60.0, 150.0, (-0.05, 0.016)),  # the PVI inside: both sides of the break
        (100.0, 100.0, (-0.05, 0.0)),  # no length, at the PVI: the grades either side of that point
    ],
)
def test_a_range_ending_at_a_pvi_without_a_vertical_curve_takes_the_grade_on_its_own_side(start, end, expected):
    """The least and greatest grade over a curve are those of the road on it: a break in grade exactly at a curve's
    end leaves the grade beyond the end out (the road there is not on the curve). Closed forms: a parabola from
    +4 % to 0 % over 100 m (grade linear in the distance), then -5 % from the PVI at 100 m with no vertical curve;
    the scalar and the array form give the same."""
    p = _profile(
        VerticalSegment("parabolic", 0.0, 100.0, 0.0, 0.04, 0.0),
        VerticalSegment("constant", 100.0, 100.0, 2.0, -0.05, -0.05),
    )
    assert grade_range(p, start, end) == pytest.approx(expected, abs=1e-15)
    lo, hi = grade_ranges(p, np.array([start]), np.array([end]))
    assert (lo[0], hi[0]) == pytest.approx(expected, abs=1e-15)


def test_superelevation_range_wins_over_cross_slopes():
    a = alignment(
        line(100.0),
        arc(100.0, 300.0, "right"),
        line(100.0),
        superelevation=(SuperelevationRange(90.0, 210.0, 6.0),),
        cross_slopes=(CrossSlope(150.0, 2.0, -2.0),),
    )
    (b,) = bends(a)
    assert bend_superelevation(a, b) == (6.0, "file")


@pytest.mark.parametrize(
    "given",
    [
        [(300.0, 420.0, 5.0), (90.0, 150.0, 7.0), (90.0, 210.0, 6.0)],
        [(300.0, 420.0, 5.0), (90.0, 210.0, 6.0), (90.0, 150.0, 7.0)],
        [(90.0, 210.0, 6.0), (300.0, 420.0, 5.0), (-0.0, 60.0, 3.0), (0.0, 60.0, 2.0)],
    ],
)
def test_superelevation_ranges_as_columns_are_the_records(given):
    # a reader's columns (RangeColumns) against the records they stand for: the same sequence, and every bend given
    # the same range (ties of start broken by the order given, as a stable sort of the records breaks them)
    records = tuple(SuperelevationRange(s, e, f, f"R{k}") for k, (s, e, f) in enumerate(given))
    columns = RangeColumns(*(np.array(c) for c in zip(*given, strict=True)), [r.where for r in records])
    assert columns == records and records == columns and list(columns) == list(records) and len(columns) == len(given)
    assert columns[-1] == records[-1] and columns[1:] == records[1:]
    elements = (line(100.0), arc(100.0, 300.0, "right"), line(100.0), arc(100.0, 300.0), line(100.0))
    as_records = alignment(*elements, superelevation=records)
    as_columns = alignment(*elements, superelevation=columns)
    got = [bend_superelevation(as_columns, b) for b in bends(as_columns)]
    assert got == [bend_superelevation(as_records, b) for b in bends(as_records)]
    # the first bend's middle (150 m) lies in both ranges from 90 m: the one of them given last wins
    assert got[0] == (next(f for s, e, f in reversed(given) if s == 90.0), "file")
    assert got[1] == (5.0, "file")


@pytest.mark.parametrize("direction", ["left", "right"])
def test_a_normal_crown_through_a_curve_is_adverse(direction):
    # normal crown: the left lane rises to the centreline (+2 % left to right), the right lane falls (-2 %)
    crown = tuple(CrossSlope(d, 2.0, -2.0) for d in (110.0, 150.0, 190.0))
    a = alignment(line(100.0), arc(100.0, 300.0, direction), line(100.0), cross_slopes=crown)
    (b,) = bends(a)
    assert bend_superelevation(a, b) == (-2.0, "cross-sections")


def test_a_banked_section_is_positive_on_either_hand_and_interpolated_at_the_middle():
    # banked toward the inside: a left curve's surface rises left to right (+), a right curve's falls (-)
    left = alignment(
        line(100.0), arc(100.0, 300.0), cross_slopes=(CrossSlope(120.0, 4.0, 4.0), CrossSlope(170.0, 8.0, 8.0))
    )
    right = alignment(line(100.0), arc(100.0, 300.0, "right"), cross_slopes=(CrossSlope(150.0, -6.0, -6.0),))
    assert bend_superelevation(left, bends(left)[0]) == (pytest.approx(4.0 + 4.0 * 30 / 50), "cross-sections")
    assert bend_superelevation(right, bends(right)[0]) == (6.0, "cross-sections")
    nothing = alignment(line(100.0), arc(100.0, 300.0), cross_slopes=(CrossSlope(20.0, 2.0, -2.0),))
    assert bend_superelevation(nothing, bends(nothing)[0]) is None


def test_a_straight_road_has_no_bends():
    assert bends(alignment(line(100.0), line(50.0))) == []
    assert np.isclose(element_distances(alignment(line(100.0), line(50.0)))[-1], 150.0)


def test_an_arc_split_in_two_by_the_file_is_one_row():
    # Civil 3D writes one arc as two Curves of the same radius (to the 12th digit): one bend, not a compound curve
    a = alignment(line(10.0), arc(40.0, 800.000000001404), arc(11.0, 799.999999999896), line(10.0))
    (b,) = bends(a)
    assert (b.arc_length_m, b.compound, b.elements) == (51.0, False, (1, 2))
    assert b.deflection_deg == pytest.approx(math.degrees(51.0 / 800.0), rel=1e-11)


def test_the_array_forms_agree_with_dense_sampling():
    # a profile of every kind: a tangent, a parabola, a sag circle, a jump without a curve, a crest circle
    t0 = math.atan(-0.03)
    sag_end = math.tan(math.asin(math.sin(t0) + 120.0 / 4000.0))
    crest_t0 = math.atan(0.05)
    crest_end = math.tan(math.asin(math.sin(crest_t0) - 150.0 / 3000.0))
    p = _profile(
        VerticalSegment("constant", 0.0, 100.0, 0.0, 0.02, 0.02),
        VerticalSegment("parabolic", 100.0, 80.0, 2.0, 0.02, -0.03),
        VerticalSegment("circular", 180.0, 120.0, 1.0, -0.03, sag_end, 4000.0),
        VerticalSegment("constant", 300.0, 50.0, 1.0, 0.05, 0.05),
        VerticalSegment("circular", 350.0, 150.0, 3.0, 0.05, crest_end, 3000.0),
    )
    rng = np.random.default_rng(3)
    a = rng.uniform(0, 480, 200)
    b = np.minimum(a + rng.uniform(0, 200, 200), 500.0)
    np.testing.assert_allclose(grades_at(p, a), [grade_at(p, x) for x in a], rtol=1e-12, atol=1e-15)
    lo, hi = grade_ranges(p, a, b)
    for k in range(len(a)):
        assert (lo[k], hi[k]) == pytest.approx(grade_range(p, a[k], b[k]), rel=1e-12, abs=1e-15)
        # every grade sampled inside the range lies between them
        inner = grades_at(p, np.linspace(a[k], b[k], 101)[1:-1])
        assert lo[k] - 1e-12 <= inner.min() and inner.max() <= hi[k] + 1e-12
