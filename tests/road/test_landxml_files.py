"""LandXML read whole: public exports of five design tools (tests/data/landxml/README.md names each file's
repository, path and licence), a file in feet against its metric twin, a round trip through our own writer
(tests/landxml_writer.py), and the refusals.

Every expected value comes from the file's own numbers by another route than the reader's: the unit's definition
(foot = 0.3048 m, US survey foot = 1200/3937 m), the sum of the element lengths before a curve, the file's own
`delta`, `dir` and `chord` attributes (which the reader does not read), the arc's points, the PVI grades with the
textbook parabola (grade linear over the curve) or the circle through both tangents, and the cross sections' points.
"""

from __future__ import annotations

import itertools
import math
import random
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from app.formats.alignment_io import AlignmentFormatError, read_landxml
from app.formats.landxml import read_road_file
from engine.road.geometry import grades_at
from tests.landxml_writer import Design, Element, Pvi, landxml

DATA = Path(__file__).resolve().parents[1] / "data" / "landxml"
FT = 0.3048  # international foot, exactly (1959)
US_FT = 1200.0 / 3937.0  # US survey foot, exactly


def _file(name: str) -> bytes:
    # every file's licence is settled (tests/data/landxml/README.md): a missing file fails, it is not skipped
    return (DATA / name).read_bytes()


def _elements(doc: bytes, tag: str) -> list[ET.Element]:
    return [e for e in ET.fromstring(doc).iter() if e.tag.rsplit("}", 1)[-1] == tag]


def _bend(t, name: str) -> np.ndarray:
    return t.bends[name]


def parabola_grade(pvis: list[tuple[float, float, float]], x: float) -> float:
    """The textbook profile: tangents between PVIs (station, elevation), a symmetric parabola of length L centred on
    an interior PVI, over which the grade changes linearly from the grade in to the grade out."""
    grades = [(b[1] - a[1]) / (b[0] - a[0]) for a, b in itertools.pairwise(pvis)]
    for i in range(1, len(pvis) - 1):
        s, _, length = pvis[i]
        if length and s - length / 2 <= x <= s + length / 2:
            return grades[i - 1] + (grades[i] - grades[i - 1]) * (x - (s - length / 2)) / length
    k = max(i for i in range(len(grades)) if pvis[i][0] <= x or i == 0)
    return grades[k]


def _pvis(doc: bytes) -> list[tuple[float, float, float]]:
    prof = _elements(doc, "ProfAlign")[0]
    out = []
    for e in prof:
        tag = e.tag.rsplit("}", 1)[-1]
        if tag in ("PVI", "ParaCurve"):
            s, z = (float(v) for v in e.text.split()[:2])
            out.append((s, z, float(e.get("length", 0.0))))
    return out


# ------------------------------------------------------------------------------------ public files


def test_civil3d_2023_in_feet():
    doc = _file("civil3d-2023-main-road-ft.xml")
    t = read_landxml(doc, superelevation_percent=None)
    lines = [float(e.get("length")) for e in _elements(doc, "Line")]
    curves = _elements(doc, "Curve")
    lengths = [float(c.get("length")) for c in curves]
    # two bends: the first Curve, and the arc of R 800 ft the file splits in two (R differs in the 12th digit)
    assert len(t) == 2 and t.ids == ["Main Road#1", "Main Road#2"]
    assert t.radius_m[0] == pytest.approx(float(curves[0].get("radius")) * FT, rel=1e-12)
    assert t.radius_m[1] == pytest.approx(800.0 * FT, rel=1e-11)
    # no element has a staStart: the stations are the sums of the lengths before them (the alignment starts at 0)
    starts_ft = [lines[0], lines[0] + lengths[0] + lines[1]]
    assert t.station_m == pytest.approx(np.array(starts_ft) * FT, rel=1e-12)
    assert _bend(t, "arc_length_m") == pytest.approx(np.array([lengths[0], lengths[1] + lengths[2]]) * FT, rel=1e-12)
    # the file's own delta [decimal degrees] of each arc
    deltas = [float(c.get("delta")) for c in curves]
    assert _bend(t, "deflection_deg") == pytest.approx([deltas[0], deltas[1] + deltas[2]], rel=1e-9)
    assert list(_bend(t, "direction")) == [0.0, 0.0]  # rot="ccw": left
    # the grade at each bend's middle from the PVI grades (a ratio: the unit cancels)
    pvis = _pvis(doc)
    for k, (s, length) in enumerate(zip(starts_ft, [lengths[0], lengths[1] + lengths[2]], strict=True)):
        assert t.grade_percent[k] == pytest.approx(100 * parabola_grade(pvis, s + length / 2), rel=1e-9)
    assert list(_bend(t, "grade_source")) == [1.0, 1.0]
    r = t.reading
    assert (r["linear_unit"], r["writer"], r["profile"]) == (
        "foot",
        "Autodesk Civil 3D 2023 (Autodesk, Inc.)",
        "Main Road Layout",
    )
    assert r["elements"]["Curve"] == 3 and r["elements"]["Line"] == 5
    assert any("ProfSurf" in s["what"] for s in r["skipped"])  # the ground line is listed, not used
    assert r["superelevation_from"] == "standard" and np.isnan(t.superelevation_percent).all()


def test_openroads_in_us_survey_feet():
    doc = _file("openroads-indot-twin-branch-usft.xml")
    t = read_landxml(doc, superelevation_percent=4.0)
    (align,) = _elements(doc, "Alignment")
    (curve,) = _elements(doc, "Curve")
    line = float(_elements(doc, "Line")[0].get("length"))
    radius, length = float(curve.get("radius")), float(curve.get("length"))
    assert t.radius_m[0] == pytest.approx(radius * US_FT, rel=1e-12)
    # the station: the alignment's staStart plus the line before the arc; the distance: the line alone
    assert t.station_m[0] == pytest.approx((float(align.get("staStart")) + line) * US_FT, rel=1e-12)
    assert _bend(t, "distance_m")[0] == pytest.approx(line * US_FT, rel=1e-12)
    # the deflection against the file's chord: chord = 2 R sin(delta / 2)
    delta = math.radians(_bend(t, "deflection_deg")[0])
    assert 2 * radius * math.sin(delta / 2) == pytest.approx(float(curve.get("chord")), rel=1e-9)
    middle = float(align.get("staStart")) + line + length / 2
    assert t.grade_percent[0] == pytest.approx(100 * parabola_grade(_pvis(doc), middle), rel=1e-9)
    # the file gives no superelevation: the request's, and the row says so
    assert t.superelevation_percent[0] == 4.0 and np.isnan(_bend(t, "superelevation_from")[0])
    assert t.reading["superelevation_from"] == "request" and t.reading["linear_unit"] == "USSurveyFoot"


def _vertical_circle(p1, p2, p3, radius) -> tuple[float, float, float, float]:
    """The circle of ``radius`` tangent to the lines p1-p2 and p2-p3 [(station, elevation)] on the side the grade
    turns to (below both on a crest, above on a sag): its centre's station, the sign of its arc (-1 the upper arc,
    +1 the lower) and the stations of its two tangent points (the feet of the perpendiculars from the centre)."""
    grades = [(b[1] - a[1]) / (b[0] - a[0]) for a, b in ((p1, p2), (p2, p3))]
    side = -1.0 if grades[1] < grades[0] else 1.0
    normals = [np.array([-g, 1.0]) / math.hypot(1.0, g) for g in grades]  # the upward normals
    offsets = [n @ np.array(a) + side * radius for n, a in zip(normals, (p1, p2), strict=True)]
    centre = np.linalg.solve(np.array(normals), np.array(offsets))
    feet = [centre - (n @ centre - n @ np.array(a)) * n for n, a in zip(normals, (p1, p2), strict=True)]
    return float(centre[0]), side, float(feet[0][0]), float(feet[1][0])


def _circle_grade(p1, p2, p3, radius, x) -> float:
    """The grade at x on the vertical circle of :func:`_vertical_circle`, by the circle's equation: the upper arc
    y = yc + sqrt(R^2 - (x - xc)^2) on a crest, the lower arc y = yc - sqrt(...) on a sag."""
    xc, side, _, _ = _vertical_circle(p1, p2, p3, radius)
    return side * (x - xc) / math.sqrt(radius**2 - (x - xc) ** 2)


def test_3dwin_junction_arc_with_circular_vertical_curves():
    doc = _file("3dwin-inframodel-y10.xml")
    t = read_landxml(doc, superelevation_percent=None)
    (curve,) = _elements(doc, "Curve")
    assert t.radius_m[0] == float(curve.get("radius"))
    assert t.station_m[0] == float(curve.get("staStart"))
    # its dir (in grads, as the file's angularUnit says: 400 a circle) turns by the deflection
    turn_grads = float(curve.get("dirEnd")) - float(curve.get("dirStart"))
    assert _bend(t, "deflection_deg")[0] == pytest.approx(turn_grads * 360 / 400, rel=1e-6)
    # the bend's middle lies on the crest CircCurve (radius written -750: its sign marks the crest)
    pts = [(float(e.text.split()[0]), float(e.text.split()[1])) for e in _elements(doc, "ProfAlign")[0]]
    s0 = float(curve.get("staStart"))
    middle = s0 + float(curve.get("length")) / 2
    expected = _circle_grade(pts[1], pts[2], pts[3], 750.0, middle)
    assert t.grade_percent[0] == pytest.approx(100 * expected, rel=1e-9)
    assert t.reading["writer"] == "3D-Win 6.6.4 (Novatron Oy)"


def test_aplitop_arc_from_its_points_and_the_crown_kept_through_it():
    doc = _file("aplitop-mdt-demo2.xml")
    t = read_landxml(doc, superelevation_percent=7.0)
    (curve,) = _elements(doc, "Curve")
    start, center, end = (
        np.array([float(v) for v in curve.find(f"{{*}}{p}").text.split()]) for p in ("Start", "Center", "End")
    )
    radius = float(np.linalg.norm(start - center))
    # the angle between the radii to the start and the end (under half a turn here)
    angle = math.acos((start - center) @ (end - center) / (radius * float(np.linalg.norm(end - center))))
    line = _elements(doc, "Line")[0]
    a, b = (np.array([float(v) for v in line.find(f"{{*}}{p}").text.split()]) for p in ("Start", "End"))
    assert t.radius_m[0] == pytest.approx(radius, rel=1e-12)
    assert _bend(t, "arc_length_m")[0] == pytest.approx(radius * angle, rel=1e-9)
    assert t.station_m[0] == pytest.approx(float(np.linalg.norm(b - a)), rel=1e-12)
    # the sections through the (left-hand) curve keep a crown: the outside (right) lane falls 0.050 m over 2.5 m
    assert t.superelevation_percent[0] == pytest.approx(100 * (46.375 - 46.425) / 2.5, rel=1e-9)
    assert _bend(t, "superelevation_from")[0] == 1.0 and t.reading["superelevation_from"] == "cross-sections"
    middle = t.station_m[0] + radius * angle / 2
    assert t.grade_percent[0] == pytest.approx(100 * parabola_grade(_pvis(doc), middle), rel=1e-9)
    assert t.reading["format"] == "LandXML 1.0"


def _local(el: ET.Element) -> str:
    return el.tag.rsplit("}", 1)[-1]


def _circle_profile(doc: bytes):
    """The first ProfAlign of PVIs and CircCurves (length, radius) as (points, radii by point index, grade at x):
    tangents between the points, each interior CircCurve the circle of :func:`_vertical_circle` between its tangent
    points."""
    pts, radii = [], {}
    for i, e in enumerate(_elements(doc, "ProfAlign")[0]):
        pts.append(tuple(float(v) for v in e.text.split()[:2]))
        if _local(e) == "CircCurve":
            radii[i] = float(e.get("radius"))
    grades = [(b[1] - a[1]) / (b[0] - a[0]) for a, b in itertools.pairwise(pts)]
    circles = {i: _vertical_circle(pts[i - 1], pts[i], pts[i + 1], r) for i, r in radii.items()}

    def grade(x: float) -> float:
        for i, (_, _, t1, t2) in circles.items():
            if t1 <= x <= t2:
                return _circle_grade(pts[i - 1], pts[i], pts[i + 1], radii[i], x)
        return grades[max([k for k in range(len(grades)) if pts[k][0] <= x], default=0)]

    return pts, radii, grade


def _tag_counts(doc: bytes) -> dict[str, int]:
    """The elements the reading counts, counted in the file's text: CoordGeom's and ProfAlign's children."""
    counts: dict[str, int] = {}
    for parent in ("CoordGeom", "ProfAlign"):
        for p in _elements(doc, parent):
            counts[parent] = counts.get(parent, 0) + 1
            for e in p:
                counts[_local(e)] = counts.get(_local(e), 0) + 1
    counts.pop("CoordGeom")  # the reading counts the profiles, not the element lists
    return counts


def test_novapoint_arcs_turn_as_rot_and_the_signed_delta_say_over_circular_vertical_curves():
    doc = _file("novapoint-inframodel-m14334.xml")
    t = read_landxml(doc, superelevation_percent=None)
    (align,) = _elements(doc, "Alignment")
    (geom,) = _elements(doc, "CoordGeom")
    elements, curves = list(geom), _elements(doc, "Curve")
    lengths = np.array([float(e.get("length")) for e in elements])
    # every element's staStart as written is the alignment's staStart plus the lengths before it, to the rounding of
    # the six decimals written (half a millionth for each number added and for the staStart itself)
    running = float(align.get("staStart")) + np.r_[0.0, np.cumsum(lengths)[:-1]]
    written = np.array([float(e.get("staStart")) for e in elements])
    assert (np.abs(written - running) <= 0.5e-6 * (np.arange(len(elements)) + 2)).all()
    at = [i for i, e in enumerate(elements) if _local(e) == "Curve"]
    assert t.ids == [f"{align.get('name')}#{k}" for k in range(1, len(curves) + 1)]
    assert t.station_m == pytest.approx(written[at], rel=1e-12)  # the station as written
    assert _bend(t, "distance_m") == pytest.approx(running[at], rel=1e-12)  # the distance: the lengths summed
    assert t.radius_m == pytest.approx([float(c.get("radius")) for c in curves], rel=1e-12)
    assert _bend(t, "arc_length_m") == pytest.approx(lengths[at], rel=1e-12)
    # the direction three ways: rot, the sign of delta (Novapoint signs it: -25.85 with rot="ccw") and the turn from
    # the radius to Start to the radius to End about Center (points written northing easting: x east, y north)
    left = []
    for c in curves:
        (n0, e0), (n1, e1), (nc, ec) = (
            (float(v) for v in c.find(f"{{*}}{p}").text.split()[:2]) for p in ("Start", "End", "Center")
        )
        counterclockwise = (e0 - ec) * (n1 - nc) - (n0 - nc) * (e1 - ec) > 0
        assert counterclockwise == (c.get("rot") == "ccw") == (float(c.get("delta")) < 0)
        left.append(counterclockwise)
    assert left.count(True) == 1  # the file's one left-hand arc, the one with the negative delta
    assert list(_bend(t, "direction")) == [0.0 if k else 1.0 for k in left]
    # the deflection: |delta|, in decimal degrees as the file's angularUnit says (delta and length/radius each
    # written to six decimals: 0.5e-6 deg, and 0.5e-6 m / 110 m in radians, apart at most)
    assert _elements(doc, "Metric")[0].get("angularUnit") == "decimal degrees"
    assert _bend(t, "deflection_deg") == pytest.approx([abs(float(c.get("delta"))) for c in curves], abs=1e-6)
    # the profile: PVIs and CircCurves. Each CircCurve's length is its arc, R |atan g2 - atan g1|, to the rounding of
    # its points' six decimals: the radius is the circle's (the reader does not read the length)
    pts, radii, grade = _circle_profile(doc)
    for i, r in radii.items():
        (x0, z0), (x1, z1), (x2, z2) = pts[i - 1 : i + 2]
        arc = r * abs(math.atan((z2 - z1) / (x2 - x1)) - math.atan((z1 - z0) / (x1 - x0)))
        rounding = r * (1e-6 / (x1 - x0) + 1e-6 / (x2 - x1)) + 0.5e-6
        assert abs(arc - float(_elements(doc, "ProfAlign")[0][i].get("length"))) <= rounding
    # the grade at each arc's middle, and the least and greatest over it (on a fine grid with both ends), the arc
    # placed by the lengths summed (its written staStart differs in the sixth decimal: 2e-8 % of grade on R 5000 m)
    starts, ends = running[at], running[at] + lengths[at]
    assert t.grade_percent == pytest.approx([100 * grade(s) for s in (starts + ends) / 2], rel=1e-9)
    over = [[100 * grade(x) for x in np.linspace(s, e, 2001)] for s, e in zip(starts, ends, strict=True)]
    assert _bend(t, "grade_min_percent") == pytest.approx([min(g) for g in over], rel=1e-9)
    assert _bend(t, "grade_max_percent") == pytest.approx([max(g) for g in over], rel=1e-9)
    assert list(_bend(t, "grade_source")) == [1.0] * len(curves)
    # two of the three middles lie on a vertical circle, one on a tangent: both kinds are held
    on_circle = [any(v[2] <= m <= v[3] for v in map(lambda i: _vertical_circle(*pts[i - 1 : i + 2], radii[i]), radii))
                 for m in (starts + ends) / 2]  # fmt: skip
    assert on_circle == [True, False, True]
    (application,) = _elements(doc, "Application")
    r = t.reading
    assert r["writer"] == f"{application.get('version')} ({application.get('manufacturer')})"
    assert r["linear_unit"] == _elements(doc, "Metric")[0].get("linearUnit") == "meter"
    assert r["profile"] == _elements(doc, "ProfAlign")[0].get("name") and r["elements"] == _tag_counts(doc)
    assert r["superelevation_from"] == "standard" and r["skipped"] == []


def test_novapoint_straight_road_with_a_profile_from_before_its_start():
    doc = _file("novapoint-inframodel-y3-straight.xml")
    t = read_landxml(doc, superelevation_percent=None)
    assert len(t) == 0 and t.reading["elements"] == _tag_counts(doc) == {
        "Line": 1,
        "ProfAlign": 1,
        "PVI": 2,
        "CircCurve": 1,
    }
    # its profile starts 1.5 m before the alignment (staStart 0: a station is a distance) over a sag circle
    pts, _, grade = _circle_profile(doc)
    (align,) = _elements(doc, "Alignment")
    assert float(align.get("staStart")) == 0.0 and pts[0][0] < 0.0
    (profile,) = read_road_file(doc).alignments[0].profiles
    xs = np.linspace(pts[0][0], pts[-1][0], 1001)
    np.testing.assert_allclose(grades_at(profile, xs), [grade(x) for x in xs], rtol=1e-9, atol=1e-15)


def test_a_writer_naming_itself_in_its_version_is_named_once():
    # Novapoint writes <Application name="Novapoint" version="Novapoint 21.05.FP4d ...">: read as name + version it
    # was "Novapoint Novapoint 21.05..."; a version that only begins with the name's letters keeps the name
    doc = landxml(Design("W", 0.0, [Element("Line", 10.0)]))
    for version, expected in [
        ("Novapoint 21.05.FP4d", "Novapoint 21.05.FP4d (Trimble)"),
        ("Novapoint", "Novapoint (Trimble)"),
        ("Novapoint2", "Novapoint Novapoint2 (Trimble)"),
    ]:
        app = f'<Application name="Novapoint" version="{version}" manufacturer="Trimble"/>'
        written = doc.replace('<Application name="tests/landxml_writer.py" version="1"/>', app)
        assert app in written and read_road_file(written).writer == expected


def test_a_clothoid_bend_turns_as_the_file_says():
    doc = _file("mac999-clothoid-sample-m.xml")
    t = read_landxml(doc, superelevation_percent=None)
    spirals, (curve,) = _elements(doc, "Spiral"), _elements(doc, "Curve")
    lines = [float(e.get("length")) for e in _elements(doc, "Line")]
    ls = [float(s.get("length")) for s in spirals]
    # the row's turn: the file's delta of the arc plus each clothoid's own theta (both in decimal degrees)
    expected = float(curve.get("delta")) + sum(float(s.get("theta")) for s in spirals)
    assert _bend(t, "deflection_deg")[0] == pytest.approx(expected, rel=1e-11)
    # theta is L/(2R) from a tangent: the closed form the reader's deflection uses
    assert float(spirals[0].get("theta")) == pytest.approx(
        math.degrees(ls[0] / (2 * float(curve.get("radius")))), rel=1e-11
    )
    assert (_bend(t, "spiral_in_m")[0], _bend(t, "spiral_out_m")[0]) == (ls[0], ls[1])
    assert t.station_m[0] == lines[0] + ls[0] and _bend(t, "bend_start_m")[0] == lines[0]
    assert _bend(t, "bend_end_m")[0] == pytest.approx(lines[0] + sum(ls) + float(curve.get("length")), rel=1e-12)


# ------------------------------------------------------------------------------------ closed forms


def _design(rng: random.Random, n_bends: int = 4) -> Design:
    """A random metric alignment: lines, bends of clothoid + arc + clothoid (some without an arc, some compound),
    a profile with parabolic vertical curves, and the full superelevation of each arc."""
    elements: list[Element] = []
    station0 = rng.uniform(0, 5000)
    s = station0
    supers = []
    k = 0
    for _ in range(n_bends):
        line = rng.uniform(50, 400)
        elements.append(Element("Line", line))
        s += line
        rot = rng.choice(["cw", "ccw"])
        r = rng.uniform(60, 3000)
        ls = rng.uniform(20, 120)
        shape = rng.choice(["arc", "arc", "spirals", "compound"])
        elements.append(Element("Spiral", ls, math.inf, r, rot))
        s += ls
        if shape == "spirals":
            elements.append(Element("Spiral", ls, r, math.inf, rot))
            s += ls
            continue
        k += 1
        arc = rng.uniform(20, 300)
        elements.append(Element("Curve", arc, r, r, rot, name=f"C{k}"))
        supers.append((s, s + arc, round(rng.uniform(-2, 10), 3)))
        s += arc
        if shape == "compound":
            r2 = r * rng.uniform(1.3, 2.0)
            elements.append(Element("Spiral", ls, r, r2, rot))
            s += ls
            k += 1
            arc2 = rng.uniform(20, 200)
            elements.append(Element("Curve", arc2, r2, r2, rot, name=f"C{k}"))
            supers.append((s, s + arc2, round(rng.uniform(-2, 10), 3)))
            s += arc2
            r = r2
        elements.append(Element("Spiral", ls, r, math.inf, rot))
        s += ls
    elements.append(Element("Line", 100.0))
    s += 100.0
    # PVIs every ~400 m over the whole alignment, parabolas of 100-200 m, grades within +-8 %
    pvis = [Pvi(station0, 500.0)]
    x = station0
    while x + 800 < s:
        x += rng.uniform(350, 450)
        pvis.append(
            Pvi(x, pvis[-1].elevation_m + rng.uniform(-0.08, 0.08) * (x - pvis[-1].station_m), rng.uniform(100, 200))
        )
    pvis.append(Pvi(s, pvis[-1].elevation_m + rng.uniform(-0.08, 0.08) * (s - pvis[-1].station_m)))
    return Design("R", station0, elements, pvis, supers)


def _rows(t) -> np.ndarray:
    cols = [t.radius_m, t.station_m, t.grade_percent, t.superelevation_percent]
    cols += [t.bends[c] for c in ("distance_m", "bend_start_m", "bend_end_m", "arc_length_m", "deflection_deg")]
    cols += [t.bends[c] for c in ("spiral_in_m", "spiral_out_m", "grade_min_percent", "grade_max_percent")]
    return np.array(cols, dtype=float)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("unit", ["foot", "USSurveyFoot", "kilometer"])
def test_a_file_in_feet_and_its_metric_twin_give_the_same_rows(seed, unit):
    design = _design(random.Random(seed))
    metric = read_landxml(landxml(design, "meter"), superelevation_percent=None)
    other = read_landxml(landxml(design, unit), superelevation_percent=None)
    assert metric.ids == other.ids
    np.testing.assert_allclose(_rows(other), _rows(metric), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("unit", ["meter", "foot"])
def test_round_trip_reads_back_the_design(seed, unit):
    design = _design(random.Random(seed))
    t = read_landxml(landxml(design, unit, element_stations=seed % 2 == 0), superelevation_percent=None)
    arcs = [e for e in design.elements if e.kind == "Curve"]
    bends = [e for e in arcs]  # every arc is a row; a bend of spirals is a row too
    n_spiral_bends = sum(
        1
        for a, b in zip(design.elements, design.elements[1:], strict=False)
        if a.kind == b.kind == "Spiral" and math.isinf(a.radius_start_m) and math.isinf(b.radius_end_m)
    )
    assert len(t) == len(bends) + n_spiral_bends
    arc_rows = [i for i, cid in enumerate(t.ids) if "#apex" not in cid]
    assert [t.ids[i] for i in arc_rows] == [a.name for a in arcs]
    # radii and stations: the design's, the station the sum of the lengths before the arc
    starts = np.cumsum([design.start_station_m] + [e.length_m for e in design.elements])
    arc_starts = [starts[i] for i, e in enumerate(design.elements) if e.kind == "Curve"]
    np.testing.assert_allclose(t.radius_m[arc_rows], [a.radius_start_m for a in arcs], rtol=1e-12)
    np.testing.assert_allclose(t.station_m[arc_rows], arc_starts, rtol=1e-12)
    # the superelevation: each arc's full superelevation (a Superelevation element over it)
    np.testing.assert_allclose(t.superelevation_percent[arc_rows], [e for _, _, e in design.superelevation], rtol=1e-12)
    # the grade at each bend's middle: the textbook parabola on the design's PVIs
    pvis = [(p.station_m, p.elevation_m, p.curve_m) for p in design.pvis]
    middles = (t.bends["bend_start_m"] + t.bends["bend_end_m"]) / 2
    expected = [100 * parabola_grade(pvis, m) for m in middles]
    np.testing.assert_allclose(t.grade_percent, expected, rtol=1e-9, atol=1e-12)
    # a bend of two clothoids from and to a tangent turns 2 L / (2 R)
    for i, cid in enumerate(t.ids):
        if "#apex" in cid:
            assert t.bends["deflection_deg"][i] == pytest.approx(
                math.degrees(t.bends["spiral_in_m"][i] / t.radius_m[i]), rel=1e-12
            )


def test_a_station_equation_shifts_the_stations_after_it():
    design = Design("E", 1000.0, [Element("Line", 200.0), Element("Curve", 100.0, 300.0, 300.0, "cw", "K")])
    doc = landxml(design).replace(
        "<CoordGeom>", '<StaEquation staBack="1150" staAhead="2000" staInternal="1150"/><CoordGeom>'
    )
    t = read_landxml(doc, superelevation_percent=4.0)
    # the arc starts 200 m along: 50 m past the equation at 150 m, so at station 2000 + 50
    assert (t.station_m[0], t.bends["distance_m"][0]) == (2050.0, 200.0)
    assert t.reading["elements"]["StaEquation"] == 1


def test_cross_sections_that_disagree_with_a_superelevation_element_lose_and_are_reported():
    design = Design(
        "X",
        0.0,
        [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "ccw", "K"), Element("Line", 100.0)],
        superelevation=[(100.0, 200.0, 6.0)],
        cross_sections=[(150.0, 2.0, -2.0, 3.5)],  # a normal crown: -2 % on the outside lane
    )
    t = read_landxml(landxml(design), superelevation_percent=None)
    assert t.superelevation_percent[0] == 6.0 and t.bends["superelevation_from"][0] == 0.0
    (note,) = [s for s in t.reading["skipped"] if "cross sections" in s["what"]]
    assert "-2.00 %" in note["why"] and "6.00 %" in note["why"] and "element is used" in note["why"]
    alone = Design("X", 0.0, design.elements, cross_sections=design.cross_sections)
    assert read_landxml(landxml(alone), superelevation_percent=7.0).superelevation_percent[0] == pytest.approx(-2.0)


def test_a_profile_not_covering_a_bend_leaves_its_grade_to_the_request():
    design = Design(
        "P",
        0.0,
        [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "cw", "K"), Element("Line", 100.0)],
        pvis=[Pvi(0.0, 10.0), Pvi(150.0, 13.0)],  # ends in the middle of the arc
    )
    t = read_landxml(landxml(design), superelevation_percent=4.0, grade_percent=-3.0)
    assert (t.grade_percent[0], t.bends["grade_source"][0]) == (-3.0, 0.0)
    assert np.isnan(t.bends["grade_min_percent"][0])


def test_profiles_are_chosen_by_name():
    design = Design(
        "P",
        0.0,
        [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "cw", "K")],
        pvis=[Pvi(0.0, 0.0), Pvi(200.0, 4.0)],
    )
    doc = landxml(design).replace(
        '<ProfAlign name="Design">',
        '<ProfAlign name="Ground"><PVI>0 0</PVI><PVI>200 -10</PVI></ProfAlign><ProfAlign name="Design">',
    )
    first = read_landxml(doc, superelevation_percent=4.0)
    assert first.grade_percent[0] == pytest.approx(-5.0) and first.reading["profile"] == "Ground"
    assert any("'Design'" in s["what"] for s in first.reading["skipped"])
    chosen = read_landxml(doc, superelevation_percent=4.0, profile="Design")
    assert chosen.grade_percent[0] == pytest.approx(2.0) and chosen.reading["profile"] == "Design"
    with pytest.raises(AlignmentFormatError, match=r"no profile .* named 'Final'; the file's: 'Design', 'Ground'"):
        read_landxml(doc, superelevation_percent=4.0, profile="Final")


def test_a_straight_road_has_no_curves():
    t = read_landxml(landxml(Design("S", 0.0, [Element("Line", 500.0)])), superelevation_percent=None)
    assert len(t) == 0 and t.reading["elements"] == {"Line": 1}


def test_unsymmetric_parabola_grade_under_its_pvi():
    # g1 = +4 %, g2 = -2 %, lengthIn 60, lengthOut 140: the grade under the PVI is g1 + Lo (g2 - g1) / (Li + Lo)
    doc = landxml(
        Design(
            "U", 0.0, [Element("Line", 300.0), Element("Curve", 0.002, 400.0, 400.0, "cw", "K"), Element("Line", 300.0)]
        )
    )
    profile = (
        '<Profile><ProfAlign name="U"><PVI>0 0</PVI><UnsymParaCurve lengthIn="60" lengthOut="140">300.001 12.00004'
        "</UnsymParaCurve><PVI>600.002 6.0</PVI></ProfAlign></Profile>"
    )
    t = read_landxml(doc.replace("</CoordGeom>", "</CoordGeom>" + profile), superelevation_percent=4.0)
    g1, g2 = 12.00004 / 300.001, (6.0 - 12.00004) / 300.001
    assert t.grade_percent[0] == pytest.approx(100 * (g1 + 140 * (g2 - g1) / 200), rel=1e-6)


# ------------------------------------------------------------------------------------ refusals


@pytest.mark.parametrize(
    ("edit", "where", "field", "message"),
    [
        (('linearUnit="meter"', 'linearUnit="furlong"'), "Units/Metric", "linearUnit", "linearUnit 'furlong' is not"),
        ((' linearUnit="meter"', ""), "Units/Metric", "linearUnit", "has no linearUnit attribute"),
        (('spiType="clothoid"', 'spiType="cubic"'), "CoordGeom Spiral #1", "spiType", "spiType 'cubic' is not read"),
        (('rot="cw"', 'rot="left"'), "CoordGeom Spiral #1", "rot", "rot must be 'cw' or 'ccw', got 'left'"),
        (('radiusEnd="300.0"', 'radiusEnd="-300"'), "CoordGeom Spiral #1", "radiusEnd", "radiusEnd must be positive"),
    ],
)
def test_unknown_units_and_elements_are_refused_by_name(edit, where, field, message):
    design = Design(
        "A",
        0.0,
        [
            Element("Line", 100.0),
            Element("Spiral", 50.0, math.inf, 300.0, "cw"),
            Element("Curve", 50.0, 300.0, 300.0, "cw"),
        ],
    )
    doc = landxml(design).replace(*edit)
    with pytest.raises(AlignmentFormatError) as exc:
        read_road_file(doc)
    assert where in exc.value.location and exc.value.field == field and message in str(exc.value)


@pytest.mark.parametrize("unit", ["foot", "USSurveyFoot", "millimeter"])
def test_cross_sections_in_feet_give_the_slopes_in_metres(unit):
    # a left-hand then a right-hand curve, banked 6 % and 4 % toward their insides by the sections through them
    elements = [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "ccw", "L"), Element("Line", 100.0)]
    elements += [Element("Curve", 100.0, 250.0, 250.0, "cw", "R"), Element("Line", 100.0)]
    sections = [(150.0, 6.0, 6.0, 3.5), (350.0, -4.0, -4.0, 3.65)]
    rows = [read_landxml(landxml(Design("X", 0.0, elements, cross_sections=sections), u), superelevation_percent=None)
            for u in ("meter", unit)]  # fmt: skip
    for t in rows:
        np.testing.assert_allclose(t.superelevation_percent, [6.0, 4.0], rtol=1e-9)
        assert list(t.bends["superelevation_from"]) == [1.0, 1.0]


def test_an_irregular_line_counts_for_the_stations_and_is_listed():
    design = Design("I", 0.0, [Element("Line", 100.0), Element("Curve", 50.0, 200.0, 200.0, "cw", "K")])
    # a polyline of 3-4-5: 5 m long, before the line
    doc = landxml(design).replace(
        "<CoordGeom>", "<CoordGeom><IrregularLine><PntList2D>0 0 3 4</PntList2D></IrregularLine>"
    )
    t = read_landxml(doc, superelevation_percent=4.0)
    assert t.station_m[0] == pytest.approx(105.0, rel=1e-12)
    assert any("IrregularLine" in s["what"] for s in t.reading["skipped"])


def test_more_curves_than_the_limit_are_refused_at_the_first_one_past_it():
    arcs = [Element("Curve", 50.0, 100.0 + k, 100.0 + k, "cw", f"K{k}") for k in range(3)]
    with pytest.raises(AlignmentFormatError, match="more than 2 curves") as exc:
        read_landxml(landxml(Design("M", 0.0, arcs)), superelevation_percent=4.0, max_curves=2)
    assert exc.value.location == "Alignment 'M' CoordGeom Curve #3 ('K2')"


def _slopes_one_by_one(xs: list[float]) -> tuple[float, float] | None:
    """A section's lane slopes [%] point by point, as the reader computed them one section at a time before they
    were computed on arrays: the nearest point on each side (the first of equals), the centreline's elevation the
    last point at offset 0, else interpolated; None when a side has no point."""
    left = right = zc = None
    for x, z in zip(xs[0::2], xs[1::2], strict=False):
        if x < 0 and (left is None or x > left[0]):
            left = (x, z)
        elif x > 0 and (right is None or x < right[0]):
            right = (x, z)
        elif x == 0:
            zc = z
    if left is None or right is None:
        return None
    (xl, zl), (xr, zr) = left, right
    if zc is None:
        zc = zl + (zr - zl) * (0 - xl) / (xr - xl)
    return 100.0 * (zc - zl) / (0 - xl), 100.0 * (zr - zc) / xr


def test_the_sections_slopes_on_arrays_are_those_of_each_section_read_alone():
    from app.formats.landxml import _slopes

    rng = np.random.default_rng(39)
    sections = []
    for _ in range(400):  # ties, several points at 0, one-sided sections, an odd number at the end
        k = int(rng.integers(0, 9))
        xs = [float(v) for p in zip(rng.choice([-7.0, -3.5, -3.5, 0.0, 0.0, 3.5, 3.5, 7.0], k),
                                    rng.normal(100.0, 0.2, k), strict=True) for v in p]  # fmt: skip
        sections.append(xs + ([5.0] if rng.random() < 0.2 else []))
    got = _slopes(np.array([v for xs in sections for v in xs]), np.array([len(xs) for xs in sections]))
    for xs, (left, right) in zip(sections, got.tolist(), strict=True):
        expected = _slopes_one_by_one(xs)
        if expected is None:
            assert math.isnan(left) and math.isnan(right)
        else:
            assert (left, right) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def _superelevation_element(rng: random.Random) -> str:
    """A Superelevation as writers write it, now and then with what only the careful reading judges: a child
    missing, blank, not a number, not finite or twice (the first counts), a namespace prefix, the stations only as
    attributes."""
    prefix = rng.choice(["", "", "", "l:"])
    sta = rng.uniform(0, 300)
    texts = {"FullSuperSta": f"{sta:.3f}", "FullSuperelev": f"{rng.uniform(-8, 8):.2f}", "RunoffSta": f"{sta + 20:g}"}
    odd = ["", " ", "x", "inf", "nan", " 1_0 ", "1e400", "\n12.5\t", None]
    parts = []
    for name, text in texts.items():
        if rng.random() < 0.15:
            text = rng.choice(odd)
        if text is not None:
            tag = (prefix if rng.random() < 0.5 else "") + name
            parts.append(f"<{tag}>{text}</{tag}>")
        if rng.random() < 0.05:
            parts.append(f"<{name}>{rng.uniform(0, 9):.1f}</{name}>")
    rng.shuffle(parts)
    attrs = rng.choice(['staStart="5" staEnd="295"', 'staStart="5"', "", 'staStart="a" staEnd="9"'])
    return f'<Superelevation {attrs} xmlns:l="urn:x">{"".join(parts)}</Superelevation>'


@pytest.mark.parametrize("seed", range(60))
def test_superelevation_elements_read_alike_by_the_quick_and_the_careful_reading(monkeypatch, seed):
    """The common Superelevation (its three children plain finite numbers) is read in one pass over its children;
    whatever else by the careful reading that names each refusal. Both give the same ranges, or the same refusal
    word for word (the careful reading alone: a fourth child name no element has sends every element to it)."""
    from app.formats import landxml as module

    rng = random.Random(seed)
    design = Design("S", 0.0, [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "cw", "K")])
    elements = "".join(_superelevation_element(rng) for _ in range(rng.randint(1, 6)))
    doc = landxml(design).replace("</CoordGeom>", "</CoordGeom>" + elements)

    def outcome():
        try:
            rf = read_road_file(doc)
            return [a.superelevation for a in rf.alignments], rf.elements
        except AlignmentFormatError as exc:
            return str(exc), exc.location, exc.field

    quick = outcome()
    monkeypatch.setattr(module, "_SUPERELEVATION", (*module._SUPERELEVATION, "NoSuchChild"))
    assert outcome() == quick
    assert "malformed" not in str(quick[0])  # (the documents are well-formed: what is compared is the reading)
