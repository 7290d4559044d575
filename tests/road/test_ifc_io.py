"""IFC 4.3 alignments read into the neutral road geometry (app/formats/ifc_io.py).

Expected values come from outside the reader: the records written by tests/ifc_writer.py (round trips), the STEP
text of the files IfcOpenShell's own authoring API (``ifcopenshell.api.alignment``, ``ifcopenshell.api.unit``)
writes when the tests run, parsed here with regular expressions, the units' definitions (1 ft = 0.3048 m, 1 US
survey foot = 1200/3937 m: NIST SP 811 appendix B) and closed forms. The one public file kept
(tests/data/ifc/README.md names its source and licence) is a release candidate the reader refuses.
"""

from __future__ import annotations

import itertools
import math
import random
import re
from pathlib import Path
from typing import Any

import pytest

from app.formats.alignment_io import AlignmentFormatError
from app.formats.ifc_io import read_ifc
from engine.road.geometry import (
    AlignmentGeometry,
    CrossSlope,
    HorizontalElement,
    Profile,
    StationEquation,
    VerticalSegment,
)
from tests.ifc_writer import write_ifc

DATA = Path(__file__).resolve().parent.parent / "data" / "ifc"
REL = 1e-9

# -- the STEP text, read independently of IfcOpenShell ----------------------------------------------------------

_ENTITY = re.compile(r"^#(\d+)\s*=\s*([A-Z0-9_]+)\s*\((.*)\)\s*;\s*$", re.MULTILINE)


def _split(args: str) -> list[str]:
    """Top-level comma-separated arguments of a STEP entity (parentheses and quoted strings kept whole)."""
    out, depth, quoted, cur = [], 0, False, ""
    for ch in args:
        if ch == "'":
            quoted = not quoted
        elif not quoted and ch == "(":
            depth += 1
        elif not quoted and ch == ")":
            depth -= 1
        elif not quoted and depth == 0 and ch == ",":
            out.append(cur.strip())
            cur = ""
            continue
        cur += ch
    out.append(cur.strip())
    return out


def _step(text: str) -> dict[int, tuple[str, list[str]]]:
    return {int(m[1]): (m[2], _split(m[3])) for m in _ENTITY.finditer(text)}


def _ref(s: str) -> int:
    return int(s.lstrip("#"))


def _num(s: str) -> float:
    return float(re.sub(r"^[A-Z]+\((.*)\)$", r"\1", s))


def _nested_segments(step, layout_type: str) -> list[list[str]]:
    """The design parameters' arguments of every segment nested in the (first) layout of ``layout_type``, in the
    nesting order of the file's IFCRELNESTS."""
    layout = next(i for i, (t, _) in step.items() if t == layout_type)
    out = []
    for t, a in step.values():
        if t == "IFCRELNESTS" and _ref(a[4]) == layout:
            for r in re.findall(r"#(\d+)", a[5]):
                seg_type, seg = step[int(r)]
                if seg_type == "IFCALIGNMENTSEGMENT":
                    out.append(step[_ref(seg[7])][1])
    return out


def _rel(a: float, b: float, rel: float = REL) -> bool:
    return a == b or abs(a - b) <= rel * max(abs(a), abs(b))


# -- round trips ------------------------------------------------------------------------------------------------


def _random_alignment(rng: random.Random, name: str) -> AlignmentGeometry:
    """Lines, arcs with clothoids in and out (and now and then a bend of two clothoids only), a profile of grades
    joined by parabolas and circular arcs, and a cant of cross slopes, in metres."""
    H = HorizontalElement
    elements: list[HorizontalElement] = [H("line", rng.uniform(20, 400))]
    for _ in range(rng.randint(1, 4)):
        r = rng.uniform(40, 3000)
        side = rng.choice(("left", "right"))
        ls = rng.uniform(10, 150)
        elements.append(H("spiral", ls, math.inf, r, side, spiral_type="clothoid"))
        if rng.random() < 0.8:
            elements.append(H("arc", rng.uniform(5, 500), r, r, side))
        elements.append(H("spiral", rng.uniform(10, 150), r, math.inf, side, spiral_type="clothoid"))
        elements.append(H("line", rng.uniform(20, 400)))
    total = sum(e.length_m for e in elements)

    segments, d, z, g = [], 0.0, rng.uniform(-50, 2000), rng.uniform(-0.08, 0.08)
    while d < total:
        length = min(rng.uniform(50, 400), total - d)
        kind = rng.choice(("constant", "parabolic", "circular"))
        if kind == "constant":
            segments.append(VerticalSegment("constant", d, length, z, g, g))
            z += g * length
        elif kind == "parabolic":
            g1 = rng.uniform(-0.08, 0.08)
            segments.append(VerticalSegment("parabolic", d, length, z, g, g1))
            z += (g + g1) / 2 * length
            g = g1
        else:  # a circular arc of this horizontal length from grade g: R (sin t1 - sin t0) = length
            g1 = rng.uniform(-0.08, 0.08)
            t0, t1 = math.atan(g), math.atan(g1)
            if abs(math.sin(t1) - math.sin(t0)) < 1e-3:
                continue
            radius = length / abs(math.sin(t1) - math.sin(t0))
            segments.append(VerticalSegment("circular", d, length, z, g, g1, radius))
            z += rng.uniform(-1, 1)  # the reader keeps the start heights as written
            g = g1
        d += length

    slopes, d = [], 0.0
    while d < total:
        s = round(rng.uniform(-10, 10), 3)
        slopes.append(CrossSlope(d, s, s))
        d += rng.uniform(10, 200)
    slopes.append(CrossSlope(total, slopes[-1].left_percent, slopes[-1].left_percent))

    start = rng.uniform(-1000, 10000)
    eq_d = rng.uniform(0.2, 0.8) * total
    equations = (StationEquation(eq_d, start + eq_d, start + eq_d + rng.uniform(-500, 500)),)
    return AlignmentGeometry(
        name,
        start,
        tuple(elements),
        station_equations=equations,
        profiles=(Profile("design", tuple(segments)),),
        cross_slopes=tuple(slopes),
    )


def _same(read: AlignmentGeometry, written: AlignmentGeometry) -> None:
    assert read.name == written.name
    assert _rel(read.start_station_m, written.start_station_m)
    assert len(read.elements) == len(written.elements)
    for r, w in zip(read.elements, written.elements, strict=True):
        assert (r.kind, r.direction, r.spiral_type, r.name) == (w.kind, w.direction, w.spiral_type, w.name), r.where
        assert _rel(r.length_m, w.length_m), r.where
        for a, b in ((r.radius_start_m, w.radius_start_m), (r.radius_end_m, w.radius_end_m)):
            assert (math.isinf(a) and math.isinf(b)) or _rel(a, b), r.where
    assert len(read.station_equations) == len(written.station_equations)
    for r, w in zip(read.station_equations, written.station_equations, strict=True):
        assert _rel(r.distance_m, w.distance_m) and _rel(r.station_back_m, w.station_back_m)
        assert _rel(r.station_ahead_m, w.station_ahead_m)
    assert [p.name for p in read.profiles] == [p.name for p in written.profiles]
    for rp, wp in zip(read.profiles, written.profiles, strict=True):
        assert len(rp.segments) == len(wp.segments)
        for r, w in zip(rp.segments, wp.segments, strict=True):
            assert r.kind == w.kind
            for a, b in zip(
                (r.start_distance_m, r.length_m, r.start_elevation_m, r.start_grade, r.end_grade),
                (w.start_distance_m, w.length_m, w.start_elevation_m, w.start_grade, w.end_grade),
                strict=True,
            ):
                assert _rel(a, b) or abs(a - b) < 1e-12, (r, w)
            assert (r.radius_m is None) == (w.radius_m is None) and (r.radius_m is None or _rel(r.radius_m, w.radius_m))
    assert len(read.cross_slopes) == len(written.cross_slopes)
    for r, w in zip(read.cross_slopes, written.cross_slopes, strict=True):
        assert _rel(r.distance_m, w.distance_m) or abs(r.distance_m - w.distance_m) < 1e-9
        assert _rel(r.left_percent, w.left_percent) and _rel(r.right_percent, w.right_percent)


@pytest.mark.parametrize("unit", ["metre", "foot", "us survey foot"])
@pytest.mark.parametrize("seed", range(4))
def test_random_alignments_round_trip(seed: int, unit: str) -> None:
    rng = random.Random(seed)
    written = [_random_alignment(rng, f"road {seed}-{k}") for k in range(2)]
    road = read_ifc(write_ifc(written, unit=unit))
    assert road.format == "IFC 4.3 (IFC4X3_ADD2)"
    assert road.linear_unit == {"metre": "metre", "foot": "FOOT", "us survey foot": "US SURVEY FOOT"}[unit]
    assert road.writer == "rollover tests/ifc_writer.py 1"
    assert len(road.alignments) == 2
    for r, w in zip(road.alignments, written, strict=True):
        _same(r, w)
    # each layout's closing zero-length segment is listed, nothing else
    assert len(road.skipped) == 3 * 2
    assert all("zero-length segment (the closing segment" in why for _, why in road.skipped)
    # the segments read, by type: the records' own elements (every spiral a clothoid) and profile segments, and one
    # cant segment between each two cross slopes (the writer's CONSTANTCANT where both are equal)
    counts = dict(road.elements)
    kinds = {"line": "LINE", "arc": "CIRCULARARC", "spiral": "CLOTHOID"}
    vkinds = {"constant": "CONSTANTGRADIENT", "parabolic": "PARABOLICARC", "circular": "CIRCULARARC"}
    for kind, name in kinds.items():
        n = sum(e.kind == kind for a in written for e in a.elements)
        assert counts.get(f"IfcAlignmentHorizontalSegment.{name}", 0) == n, kind
    for kind, name in vkinds.items():
        n = sum(s.kind == kind for a in written for p in a.profiles for s in p.segments)
        assert counts.get(f"IfcAlignmentVerticalSegment.{name}", 0) == n, kind
    cant = sum(len(a.cross_slopes) - 1 for a in written)
    assert (
        counts.get("IfcAlignmentCantSegment.CONSTANTCANT", 0) + counts["IfcAlignmentCantSegment.LINEARTRANSITION"]
        == cant
    )


def test_several_profiles_each_in_a_child_alignment() -> None:
    """Two profiles over one horizontal (IFC CT 4.1.4.4.1.2: each vertical in a child IfcAlignment) read as two
    profiles of the one alignment, in order."""
    H = HorizontalElement
    p1 = Profile("existing ground", (VerticalSegment("constant", 0.0, 300.0, 10.0, 0.01, 0.01),))
    p2 = Profile("design", (VerticalSegment("parabolic", 0.0, 300.0, 12.0, 0.04, -0.02),))
    a = AlignmentGeometry(
        "two profiles", 0.0, (H("line", 100.0), H("arc", 200.0, 250.0, 250.0, "left")), profiles=(p1, p2)
    )
    road = read_ifc(write_ifc([a]))
    assert [p.name for p in road.alignments[0].profiles] == ["existing ground", "design"]
    assert road.alignments[0].profiles[1].segments[0].end_grade == -0.02


def test_feet_and_metres_give_the_same_records() -> None:
    """The same road written in metres and in feet reads to the same SI records (1e-9 relative)."""
    written = [_random_alignment(random.Random(11), "twin")]
    metric = read_ifc(write_ifc(written, unit="metre")).alignments[0]
    feet = read_ifc(write_ifc(written, unit="foot")).alignments[0]
    _same(feet, metric)


# -- files IfcOpenShell's authoring API writes ------------------------------------------------------------------
#
# ifcopenshell.api.alignment and ifcopenshell.api.unit write these files when the tests run: a writer other than
# the project's (tests/ifc_writer.py) and than the reader. The expected values are read from the written STEP text
# (the entity lines, with the regular expressions above), and where the input has a closed form, from that too.


def _ifcopenshell_file(unit: str) -> Any:
    """An IFC 4.3 file with a project, made with IfcOpenShell's API: lengths in metres, or in a conversion-based
    foot with plane angles in a conversion-based degree (``ifcopenshell.api.unit.add_conversion_based_unit``)."""
    import ifcopenshell.api.project
    import ifcopenshell.api.root
    import ifcopenshell.api.unit

    f = ifcopenshell.api.project.create_file(version="IFC4X3")
    ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="rollover tests")
    if unit == "metre":
        units = [ifcopenshell.api.unit.add_si_unit(f, unit_type="LENGTHUNIT")]
    else:
        units = [ifcopenshell.api.unit.add_conversion_based_unit(f, name=name) for name in ("foot", "degree")]
    ifcopenshell.api.unit.assign_unit(f, units=units)
    return f


def _plan(f: Any, alignment: Any, segments: tuple[tuple[str, float, float, float], ...]) -> None:
    """Appends horizontal segments (PredefinedType, start radius, end radius, length) with create_layout_segment,
    each starting where IfcOpenShell's geometry ends the one before (the placement matrix it returns)."""
    import ifcopenshell.api.alignment as al

    layout = al.get_horizontal_layout(alignment)
    point, direction = (0.0, 0.0), 0.0
    for kind, r0, r1, length in segments:
        end = al.create_layout_segment(
            f,
            layout,
            f.createIfcAlignmentHorizontalSegment(
                StartPoint=f.createIfcCartesianPoint(point),
                StartDirection=direction,
                StartRadiusOfCurvature=r0,
                EndRadiusOfCurvature=r1,
                SegmentLength=length,
                PredefinedType=kind,
            ),
        )
        point, direction = (float(end[0][3]), float(end[1][3])), math.atan2(float(end[1][0]), float(end[0][0]))


def _circle_length(radius: float, g0: float, g1: float) -> float:
    """The horizontal length of a vertical circular arc of signed radius (+ sag) between grades g0 and g1."""
    return radius * (math.sin(math.atan(g1)) - math.sin(math.atan(g0)))


def _profile(f: Any, layout: Any, height: float, segments: tuple) -> None:
    """Appends vertical segments (PredefinedType, horizontal length, start grade, end grade, radius or None) to an
    IfcAlignmentVertical, each starting at the distance and height where IfcOpenShell's geometry ends the one
    before."""
    import ifcopenshell.api.alignment as al

    distance = 0.0
    for kind, length, g0, g1, radius in segments:
        end = al.create_layout_segment(
            f,
            layout,
            f.createIfcAlignmentVerticalSegment(
                StartDistAlong=distance,
                HorizontalLength=length,
                StartHeight=height,
                StartGradient=g0,
                EndGradient=g1,
                RadiusOfCurvature=radius,
                PredefinedType=kind,
            ),
        )
        distance, height = float(end[0][3]), float(end[1][3])


def _turn(a: AlignmentGeometry) -> float:
    """The change of direction along the alignment as read [rad, + left]: curvature is linear in length along a
    line, an arc and a clothoid, and a cosine transition's is symmetric about its middle, so each turns its length
    times the mean of its end curvatures."""

    def k(r: float) -> float:
        return 0.0 if math.isinf(r) else 1.0 / r

    return sum(
        e.length_m * (k(e.radius_start_m) + k(e.radius_end_m)) / 2 * (1 if e.direction == "left" else -1)
        for e in a.elements
    )


def _plane_angle(step) -> float:
    """Radians per plane angle unit: 1, or the conversion factor of the file's conversion-based PLANEANGLEUNIT."""
    for t, a in step.values():
        if t == "IFCCONVERSIONBASEDUNIT" and a[1] == ".PLANEANGLEUNIT.":
            factor, si = step[_ref(a[3])][1]
            assert step[_ref(si)] == ("IFCSIUNIT", ["*", ".PLANEANGLEUNIT.", "$", ".RADIAN."])
            return _num(factor)
    return 1.0


def _station_referents(step) -> list[tuple[float, dict[str, float]]]:
    """(DistanceAlong, Pset_Stationing's lengths) of each STATION IfcReferent, by distance: IfcReferent >
    IfcLinearPlacement > IfcAxis2PlacementLinear > IfcPointByDistanceExpression, and IfcRelDefinesByProperties >
    IfcPropertySet 'Pset_Stationing' > IfcPropertySingleValue."""
    psets: dict[int, dict[str, float]] = {}
    for t, a in step.values():
        if t == "IFCRELDEFINESBYPROPERTIES" and step[_ref(a[5])][1][2] == "'Pset_Stationing'":
            props = [step[int(r)][1] for r in re.findall(r"#(\d+)", step[_ref(a[5])][1][4])]
            values = {p[0].strip("'"): _num(p[2]) for p in props if p[2].startswith("IFCLENGTHMEASURE(")}
            psets.update((int(r), values) for r in re.findall(r"#(\d+)", a[4]))
    out = []
    for i, (t, a) in step.items():
        if t == "IFCREFERENT" and a[7] == ".STATION.":
            placement = step[_ref(a[5])]
            assert placement[0] == "IFCLINEARPLACEMENT"
            axis = step[_ref(placement[1][1])][1]
            point = step[_ref(axis[0])]
            assert point[0] == "IFCPOINTBYDISTANCEEXPRESSION"
            out.append((_num(point[1][0]), psets[i]))
    return sorted(out, key=lambda x: x[0])


def _written_by_ifcopenshell(text: str) -> str:
    """The header's originating system (FILE_NAME's sixth argument), after checking the schema the reader needs."""
    assert "FILE_SCHEMA(('IFC4X3_ADD2'));" in text
    m = re.search(r"FILE_NAME\('[^']*','[^']*',\([^)]*\),\([^)]*\),'[^']*','([^']*)','[^']*'\);", text)
    assert m is not None and m[1].startswith("IfcOpenShell ")
    return m[1]


#: a road: 200 m straight, a clothoid into a right-hand arc of 250 m (IFC: radius -250), the clothoid out, 340 m
ROAD_PLAN = (
    ("LINE", 0.0, 0.0, 200.0),
    ("CLOTHOID", 0.0, -250.0, 60.0),
    ("CIRCULARARC", -250.0, -250.0, 140.0),
    ("CLOTHOID", -250.0, 0.0, 60.0),
    ("LINE", 0.0, 0.0, 340.0),
)
#: its profile: -2 %, a circular sag (R +8000 m) to +1.5 %, a circular crest (R -6000 m) to -1 %, 800 m in all
_SAG, _CREST = _circle_length(8000.0, -0.02, 0.015), _circle_length(-6000.0, 0.015, -0.01)
ROAD_PROFILE = (
    ("CONSTANTGRADIENT", 150.0, -0.02, -0.02, None),
    ("CIRCULARARC", _SAG, -0.02, 0.015, 8000.0),
    ("CONSTANTGRADIENT", 450.0 - _SAG, 0.015, 0.015, None),
    ("CIRCULARARC", _CREST, 0.015, -0.01, -6000.0),
    ("CONSTANTGRADIENT", 200.0 - _CREST, -0.01, -0.01, None),
)


@pytest.fixture(scope="module")
def ifcopenshell_road() -> str:
    import ifcopenshell.api.alignment as al

    f = _ifcopenshell_file("metre")
    a = al.create(f, "IfcOpenShell road", include_vertical=True)
    _plan(f, a, ROAD_PLAN)
    _profile(f, al.get_vertical_layout(a), 50.0, ROAD_PROFILE)
    return f.to_string()


def test_ifcopenshell_road_clothoid_and_arc_to_the_right_circular_sag_and_crest(ifcopenshell_road: str) -> None:
    """An alignment IfcOpenShell's API writes segment by segment (its PI method writes no transition curves): a
    line, a clothoid and an arc turning right (negative radii), and a profile with a circular sag and crest."""
    text = ifcopenshell_road
    writer = _written_by_ifcopenshell(text)
    step = _step(text)
    road = read_ifc(text.encode())
    assert road.format == "IFC 4.3 (IFC4X3_ADD2)" and road.writer == writer
    assert "IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.)" in text and road.linear_unit == "metre"
    (a,) = road.alignments
    assert a.name == "IfcOpenShell road"
    written = _nested_segments(step, "IFCALIGNMENTHORIZONTAL")
    h = [x for x in written if _num(x[6]) > 0]
    assert [e.kind for e in a.elements] == ["line", "spiral", "arc", "spiral", "line"]
    for e, x in zip(a.elements, h, strict=True):
        r0, r1 = _num(x[4]), _num(x[5])
        assert e.length_m == _num(x[6])
        assert (e.radius_start_m, e.radius_end_m) == (abs(r0) or math.inf, abs(r1) or math.inf)
        assert e.direction == (None if r0 == r1 == 0 else "left" if r0 + r1 > 0 else "right")
        assert e.spiral_type == ("clothoid" if x[8] == ".CLOTHOID." else None)
    assert [e.direction for e in a.elements if e.kind != "line"] == ["right"] * 3
    # a second route: the turn of the elements read is the change of direction IfcOpenShell's geometry computed,
    # from the first segment's StartDirection to the closing (zero-length) segment's
    assert _num(written[-1][6]) == 0 and len(written) == len(h) + 1
    turn = (_num(written[-1][3]) - _num(h[0][3])) * _plane_angle(step)
    assert math.isclose(_turn(a), turn, rel_tol=1e-9) and turn == pytest.approx(-(60 / 250 + 140 / 250), rel=1e-12)
    v = [x for x in _nested_segments(step, "IFCALIGNMENTVERTICAL") if _num(x[3]) > 0]
    (p,) = a.profiles
    assert [s.kind for s in p.segments] == ["constant", "circular", "constant", "circular", "constant"]
    for s, x in zip(p.segments, v, strict=True):
        assert (s.start_distance_m, s.length_m, s.start_elevation_m) == (_num(x[2]), _num(x[3]), _num(x[4]))
        assert (s.start_grade, s.end_grade) == (_num(x[5]), _num(x[6]))
        assert s.radius_m == (None if x[7] == "$" else abs(_num(x[7])))
    assert _num(v[1][7]) > 0 > _num(v[3][7])  # IFC's signs: + a sag, - a crest
    # each layout's closing segment listed, nothing else; no STATION referent: start station 0, said
    assert len(road.skipped) == 2 and all("closing segment" in why for _, why in road.skipped)
    assert "IFCREFERENT(" not in text and a.start_station_m == 0.0 and a.notes


def test_ifcopenshell_second_profile_moves_both_into_child_alignments() -> None:
    """``add_vertical_layout`` on an alignment that has a profile moves it into a child alignment and puts the new
    one in another (IFC CT 4.1.4.4.1.2, a horizontal layout reused): both read as profiles of the one alignment,
    in the order of the child alignments' entity ids, every value from the text."""
    import ifcopenshell.api.alignment as al

    f = _ifcopenshell_file("metre")
    a = al.create(f, "IfcOpenShell two profiles")
    _plan(f, a, (("LINE", 0.0, 0.0, 100.0), ("CIRCULARARC", 300.0, 300.0, 200.0)))
    _profile(f, al.add_vertical_layout(f, a), 20.0, (("CONSTANTGRADIENT", 300.0, 0.01, 0.01, None),))
    second = (("PARABOLICARC", 300.0, 0.03, -0.01, 300.0 / -0.04),)
    _profile(f, al.add_vertical_layout(f, a), 21.0, second)
    text = f.to_string()
    step = _step(text)
    road = read_ifc(text.encode())
    (read,) = road.alignments  # the child alignments are not read as alignments of their own
    nests = {_ref(x[4]): re.findall(r"#(\d+)", x[5]) for t, x in step.values() if t == "IFCRELNESTS"}
    children = sorted(
        int(r)
        for t, x in step.values()
        if t == "IFCRELAGGREGATES" and step[_ref(x[4])][1][2] == "'IfcOpenShell two profiles'"
        for r in re.findall(r"#(\d+)", x[5])
    )
    assert len(children) == 2 and all(step[c][0] == "IFCALIGNMENT" for c in children)
    layouts = [int(r) for c in children for r in nests[c] if step[int(r)][0] == "IFCALIGNMENTVERTICAL"]
    assert len(layouts) == 2 and len(read.profiles) == 2
    for profile, layout in zip(read.profiles, layouts, strict=True):
        segments = [step[_ref(step[int(r)][1][7])][1] for r in nests[layout]]
        (x,) = [x for x in segments if _num(x[3]) > 0]
        (s,) = profile.segments
        assert (s.start_distance_m, s.length_m, s.start_elevation_m) == (_num(x[2]), _num(x[3]), _num(x[4]))
        assert (s.kind, s.start_grade, s.end_grade) == (
            {".CONSTANTGRADIENT.": "constant", ".PARABOLICARC.": "parabolic"}[x[8]],
            _num(x[5]),
            _num(x[6]),
        )
    assert [p.segments[0].kind for p in read.profiles] == ["constant", "parabolic"]


#: a railway: a left-hand bend of R 1000 m between clothoids and a right-hand one of R 800 m between cosine
#: transitions (IFC's COSINECURVE), 1040 m in all
RAIL_PLAN = (
    ("LINE", 0.0, 0.0, 100.0),
    ("CLOTHOID", 0.0, 1000.0, 80.0),
    ("CIRCULARARC", 1000.0, 1000.0, 200.0),
    ("CLOTHOID", 1000.0, 0.0, 80.0),
    ("LINE", 0.0, 0.0, 150.0),
    ("COSINECURVE", 0.0, -800.0, 90.0),
    ("CIRCULARARC", -800.0, -800.0, 150.0),
    ("COSINECURVE", -800.0, 0.0, 90.0),
    ("LINE", 0.0, 0.0, 100.0),
)
#: its cant (kind, length, start left, start right, end left, end right) [m]: the outer rail raised 0.06 m on the
#: left-hand bend and 0.09 m on the right-hand one, the inner rail on the profile, in linear transitions along the
#: clothoids and cosine ones along the cosine transitions. (A cant turning about the axis, the rails at -x and +x,
#: makes IfcOpenShell 0.9's geometry for a LINEARTRANSITION cant divide by zero: its mean height does not change.)
RAIL_CANT = (
    ("CONSTANTCANT", 100.0, 0.0, 0.0, 0.0, 0.0),
    ("LINEARTRANSITION", 80.0, 0.0, 0.0, 0.0, 0.06),
    ("CONSTANTCANT", 200.0, 0.0, 0.06, 0.0, 0.06),
    ("LINEARTRANSITION", 80.0, 0.0, 0.06, 0.0, 0.0),
    ("CONSTANTCANT", 150.0, 0.0, 0.0, 0.0, 0.0),
    ("COSINECURVE", 90.0, 0.0, 0.0, 0.09, 0.0),
    ("CONSTANTCANT", 150.0, 0.09, 0.0, 0.09, 0.0),
    ("COSINECURVE", 90.0, 0.09, 0.0, 0.0, 0.0),
    ("CONSTANTCANT", 100.0, 0.0, 0.0, 0.0, 0.0),
)


@pytest.fixture(scope="module")
def ifcopenshell_rail() -> str:
    import ifcopenshell.api.alignment as al

    f = _ifcopenshell_file("metre")
    a = al.create(f, "IfcOpenShell rail", include_vertical=True, include_cant=True)
    _plan(f, a, RAIL_PLAN)
    _profile(f, al.get_vertical_layout(a), 10.0, (("CONSTANTGRADIENT", 1040.0, 0.004, 0.004, None),))
    cant = al.get_cant_layout(a)
    cant.RailHeadDistance = 1.435  # create() writes 1.0 and takes no rail head distance: set on the entity
    distance = 0.0
    for kind, length, left0, right0, left1, right1 in RAIL_CANT:
        al.create_layout_segment(
            f,
            cant,
            f.createIfcAlignmentCantSegment(
                StartDistAlong=distance,
                HorizontalLength=length,
                StartCantLeft=left0,
                EndCantLeft=left1,
                StartCantRight=right0,
                EndCantRight=right1,
                PredefinedType=kind,
            ),
        )
        distance += length
    # the start station before the start of the stationing (-0+153.1), and a station equation 500 m along
    al.add_stationing_referent(f, "start", a, 0.0, -153.1)
    al.add_stationing_referent(f, "equation", a, 500.0, 1000.0, incoming_station=-153.1 + 500.0)
    return f.to_string()


def test_ifcopenshell_rail_cant_cosine_transitions_and_stationing(ifcopenshell_rail: str) -> None:
    """A railway alignment IfcOpenShell's API writes: bends both ways (clothoids, cosine transitions), a cant of
    0.06 and 0.09 m on a rail head distance of 1.435 m (``create(include_cant=True)`` writes 1.0, set on the
    entity) with linear and cosine transitions, a start station of -153.1 m and a station equation
    (``add_stationing_referent``: Pset_Stationing ``Station`` and ``IncomingStation``)."""
    text = ifcopenshell_rail
    _written_by_ifcopenshell(text)
    step = _step(text)
    road = read_ifc(text.encode())
    (a,) = road.alignments
    assert len(road.skipped) == 3 and all("closing segment" in why for _, why in road.skipped)  # one a layout
    written = _nested_segments(step, "IFCALIGNMENTHORIZONTAL")
    h = [x for x in written if _num(x[6]) > 0]
    assert len(a.elements) == len(h) == 9
    types = {".LINE.": None, ".CIRCULARARC.": None, ".CLOTHOID.": "clothoid", ".COSINECURVE.": "cosinecurve"}
    for e, x in zip(a.elements, h, strict=True):
        r0, r1 = _num(x[4]), _num(x[5])
        assert (e.length_m, e.radius_start_m, e.radius_end_m) == (_num(x[6]), abs(r0) or math.inf, abs(r1) or math.inf)
        assert e.direction == (None if r0 == r1 == 0 else "left" if r0 + r1 > 0 else "right")
        assert e.spiral_type == types[x[8]]
    assert [e.direction for e in a.elements if e.kind == "arc"] == ["left", "right"]
    turn = (_num(written[-1][3]) - _num(h[0][3])) * _plane_angle(step)
    assert math.isclose(_turn(a), turn, rel_tol=1e-9)
    # cant: the plane through both rails, 100 tan(asin((right - left) / RailHeadDistance)) at each segment's ends
    (rhd,) = [_num(x[7]) for t, x in step.values() if t == "IFCALIGNMENTCANT"]
    assert rhd == 1.435
    c = [x for x in _nested_segments(step, "IFCALIGNMENTCANT") if _num(x[3]) > 0]
    assert [x[8] for x in c] == [f".{k[0]}." for k in RAIL_CANT]
    ends = set()
    for x in c:
        d0, d1 = _num(x[2]), _num(x[2]) + _num(x[3])
        for d, left, right in ((d0, _num(x[4]), _num(x[6])), (d1, _num(x[5]), _num(x[7]))):
            expected = 100 * math.tan(math.asin((right - left) / rhd))
            at = [s for s in a.cross_slopes if _rel(s.distance_m, d)]
            assert at and all(s.left_percent == s.right_percent == expected for s in at), (d, expected)
            ends.add(d)
    assert all(any(_rel(s.distance_m, d) for d in ends) for s in a.cross_slopes)
    # banked toward each bend's inside: + (rising left to right) on the left-hand bend, - on the right-hand one
    assert max(s.left_percent for s in a.cross_slopes) > 0 > min(s.left_percent for s in a.cross_slopes)
    assert [s.left_percent > 0 for s in a.cross_slopes if s.left_percent] == [True, True, False, False]
    # stations: the referent at distance 0 gives the start station, the one 500 m along an equation
    (d0, start), (d1, equation) = _station_referents(step)
    assert (d0, d1) == (0.0, 500.0) and a.start_station_m == start["Station"] == -153.1
    assert a.station_equations == (StationEquation(d1, equation["IncomingStation"], equation["Station"]),)
    assert equation["IncomingStation"] == pytest.approx(-153.1 + 500.0, rel=1e-15) and not a.notes


#: a road in feet laid out by the PI method (no transitions): points of intersection, circular curve radii, the
#: profile's points of vertical intersection and symmetric parabolic curve lengths [ft], and its start station
FT_PIS = ((1000.0, 1000.0), (3400.0, 1000.0), (5000.0, 2800.0), (7200.0, 2300.0), (8600.0, 3600.0))
FT_RADII = (1200.0, 950.0, 1500.0)
FT_PVIS = ((0.0, 500.0), (2000.0, 540.0), (4500.0, 505.0), (7000.0, 535.0), (8600.0, 515.0))
FT_CURVES = (800.0, 1000.0, 1200.0)
FT_START = 1000.0


@pytest.fixture(scope="module")
def ifcopenshell_road_in_feet() -> str:
    import ifcopenshell.api.alignment as al

    f = _ifcopenshell_file("foot")
    name = "IfcOpenShell road in feet"
    al.create_by_pi_method(f, name, FT_PIS, FT_RADII, FT_PVIS, FT_CURVES, start_station=FT_START)
    return f.to_string()


def test_ifcopenshell_road_in_feet_by_the_pi_method(ifcopenshell_road_in_feet: str) -> None:
    """A road IfcOpenShell's ``create_by_pi_method`` lays out in a conversion-based foot
    (``add_conversion_based_unit(name="foot")``: 0.3048 of a metre, as an ``IfcReal``) with angles in degrees: three
    circular curves between tangents, three symmetric parabolic vertical curves, a start station of 10+00 ft.
    Checked against the file's text and against the closed forms of the PI method (tangent length R tan(D/2), arc
    length R D; a parabola starts L/2 before its PVI)."""
    text = ifcopenshell_road_in_feet
    _written_by_ifcopenshell(text)
    step = _step(text)
    # the unit from the text: IFCCONVERSIONBASEDUNIT(.., .LENGTHUNIT., 'foot', #m); #m = 0.3048 of a METRE
    (unit,) = [x for t, x in step.values() if t == "IFCCONVERSIONBASEDUNIT" and x[1] == ".LENGTHUNIT."]
    factor, si = step[_ref(unit[3])][1]
    assert step[_ref(si)] == ("IFCSIUNIT", ["*", ".LENGTHUNIT.", "$", ".METRE."])
    foot = _num(factor)
    assert foot == 0.3048  # the international foot (NIST SP 811, appendix B)
    road = read_ifc(text.encode())
    assert road.linear_unit == unit[2].strip("'") == "foot"
    (a,) = road.alignments
    written = _nested_segments(step, "IFCALIGNMENTHORIZONTAL")
    h = [x for x in written if _num(x[6]) > 0]
    assert [e.kind for e in a.elements] == ["line", "arc"] * 3 + ["line"] and len(h) == 7
    for e, x in zip(a.elements, h, strict=True):
        assert math.isclose(e.length_m, _num(x[6]) * foot, rel_tol=REL)
        assert e.radius_start_m == e.radius_end_m and math.isclose(
            e.radius_start_m, (abs(_num(x[4])) or math.inf) * foot, rel_tol=REL
        )
    # the PI method's closed forms, in feet: each curve's deflection D from the two tangents' bearings
    bearings = [math.atan2(q[1] - p[1], q[0] - p[0]) for p, q in itertools.pairwise(FT_PIS)]
    legs = [math.dist(p, q) for p, q in itertools.pairwise(FT_PIS)]
    deflections = [math.remainder(b1 - b0, math.tau) for b0, b1 in itertools.pairwise(bearings)]
    tangents = [r * math.tan(abs(d) / 2) for r, d in zip(FT_RADII, deflections, strict=True)]
    lines = [leg - t0 - t1 for leg, t0, t1 in zip(legs, [0.0, *tangents], [*tangents, 0.0], strict=True)]
    arcs = [r * abs(d) for r, d in zip(FT_RADII, deflections, strict=True)]
    expected = [*itertools.chain.from_iterable(zip(lines, arcs, strict=False)), lines[-1]]
    for e, length in zip(a.elements, expected, strict=True):
        assert math.isclose(e.length_m, length * foot, rel_tol=1e-9), e.where
    arcs_read = [e for e in a.elements if e.kind == "arc"]
    assert [e.direction for e in arcs_read] == ["left" if d > 0 else "right" for d in deflections]
    assert [e.direction for e in arcs_read] == ["left", "right", "left"]
    # the turn read against the directions the PI method wrote, in the file's degrees, from the first tangent to the
    # last (IfcOpenShell 0.9 writes the closing segment's StartDirection in radians whatever the angle unit)
    assert _plane_angle(step) == pytest.approx(math.pi / 180, rel=1e-12)
    turn = (_num(h[-1][3]) - _num(h[0][3])) * _plane_angle(step)
    assert math.isclose(_turn(a), turn, rel_tol=1e-9) and math.isclose(turn, sum(deflections), rel_tol=1e-9)
    # profile: from the text, and from the PVIs (grades between them; a curve from PVI - L/2 to PVI + L/2)
    v = [x for x in _nested_segments(step, "IFCALIGNMENTVERTICAL") if _num(x[3]) > 0]
    (p,) = a.profiles
    assert [s.kind for s in p.segments] == ["constant", "parabolic"] * 3 + ["constant"] and len(v) == 7
    for s, x in zip(p.segments, v, strict=True):
        for got, ft in ((s.start_distance_m, x[2]), (s.length_m, x[3]), (s.start_elevation_m, x[4])):
            assert math.isclose(got, _num(ft) * foot, rel_tol=REL, abs_tol=1e-12)
        assert (s.start_grade, s.end_grade) == (_num(x[5]), _num(x[6]))
    grades = [(z1 - z0) / (x1 - x0) for (x0, z0), (x1, z1) in itertools.pairwise(FT_PVIS)]
    for i, (s, length) in enumerate(zip(p.segments[1::2], FT_CURVES, strict=True), start=1):
        x, z = FT_PVIS[i]
        assert math.isclose(s.start_distance_m, (x - length / 2) * foot, rel_tol=1e-9)
        assert math.isclose(s.length_m, length * foot, rel_tol=1e-9)
        assert math.isclose(s.start_elevation_m, (z - grades[i - 1] * length / 2) * foot, rel_tol=1e-9)
        assert s.start_grade == pytest.approx(grades[i - 1], rel=1e-9)
        assert s.end_grade == pytest.approx(grades[i], rel=1e-9)
    # the start station: Pset_Stationing's Station (in feet) of the referent at distance 0
    ((d, pset),) = _station_referents(step)
    assert d == 0.0 and pset["Station"] == FT_START
    assert math.isclose(a.start_station_m, FT_START * foot, rel_tol=REL)


# -- a public file ---------------------------------------------------------------------------------------------


def test_release_candidate_file_refused_by_schema_name() -> None:
    """12d Model's IFC4X3_RC3 alignment (bSI InfraRoom unit test) is refused, naming its schema."""
    data = (DATA / "Alignment-12d-1.ifc").read_bytes()
    assert b"FILE_SCHEMA (('IFC4X3_RC3'))" in data
    with pytest.raises(AlignmentFormatError, match="IFC4X3_RC3") as exc:
        read_ifc(data)
    assert exc.value.field == "FILE_SCHEMA" and exc.value.location == "HEADER"


# -- refusals and edge cases ------------------------------------------------------------------------------------


def _one(*elements: HorizontalElement, **kw) -> str:
    return write_ifc([AlignmentGeometry("A", 0.0, elements, **kw)]).decode()


def _read(text: str):
    return read_ifc(text.encode())


H = HorizontalElement


@pytest.mark.parametrize(
    ("data", "match"),
    [
        (b"", "not an IFC file"),
        (b"<?xml version='1.0'?><LandXML/>", "not an IFC file"),
        (b"ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('IFC2X3'));\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n", "'IFC2X3'"),
        (b"ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('IFC4X3_ADD1'));\nENDSEC;\n", "'IFC4X3_ADD1'"),
        (b"ISO-10303-21;\nHEADER;\nENDSEC;\n", "names no schema"),
    ],
)
def test_not_ifc_4_3(data: bytes, match: str) -> None:
    with pytest.raises(AlignmentFormatError, match=match):
        read_ifc(data)


def test_viennese_bend_refused_by_name() -> None:
    text = _one(H("line", 50.0), H("spiral", 60.0, math.inf, 400.0, "left", spiral_type="clothoid"))
    text = text.replace(".CLOTHOID.", ".VIENNESEBEND.")
    with pytest.raises(AlignmentFormatError, match="VIENNESEBEND") as exc:
        _read(text)
    assert exc.value.field == "PredefinedType"
    assert re.search(r"#\d+ IfcAlignmentHorizontalSegment", exc.value.location)


def test_other_transition_types_read_by_name() -> None:
    text = _one(H("spiral", 60.0, math.inf, 400.0, "right", spiral_type="blosscurve"))
    (e,) = _read(text).alignments[0].elements
    assert (e.kind, e.spiral_type, e.direction, e.radius_end_m) == ("spiral", "blosscurve", "right", 400.0)


def test_clothoid_through_an_inflection_split_where_its_curvature_is_zero() -> None:
    """A clothoid from +300 m to -600 m over 90 m: curvature linear in length, zero at 90 (1/300) / (1/300 + 1/600)
    = 60 m; a left spiral of 60 m ending straight and a right one of 30 m."""
    text = _one(H("line", 10.0), H("spiral", 90.0, 300.0, 600.0, "left", spiral_type="clothoid"))
    # make the end radius change side: the writer wrote +300 and +600
    text = re.sub(r"(IFCALIGNMENTHORIZONTALSEGMENT\([^;]*,300\.,)600\.", r"\1-600.", text)
    a, b = _read(text).alignments[0].elements[1:]
    assert (a.direction, a.radius_start_m, a.radius_end_m) == ("left", 300.0, math.inf)
    assert (b.direction, b.radius_start_m, b.radius_end_m) == ("right", math.inf, 600.0)
    assert math.isclose(a.length_m, 60.0, rel_tol=1e-12) and math.isclose(b.length_m, 30.0, rel_tol=1e-12)


def test_other_transition_changing_side_refused() -> None:
    text = _one(H("spiral", 90.0, 300.0, 600.0, "left", spiral_type="sinecurve"))
    text = re.sub(r"(IFCALIGNMENTHORIZONTALSEGMENT\([^;]*,300\.,)600\.", r"\1-600.", text)
    with pytest.raises(AlignmentFormatError, match="SINECURVE transition whose radii change side"):
        _read(text)


@pytest.mark.parametrize(
    ("edit", "field", "match"),
    [
        # a LINE with a radius
        (lambda t: t.replace(",0.,0.,100.,$,.LINE.)", ",0.,250.,100.,$,.LINE.)"), "EndRadiusOfCurvature", "LINE"),
        # a length that is text (IfcOpenShell reads it without complaint)
        (lambda t: t.replace(",0.,0.,100.,$,.LINE.)", ",0.,0.,'100',$,.LINE.)"), "SegmentLength", "not a number"),
        (lambda t: t.replace(",0.,0.,100.,$,.LINE.)", ",0.,0.,-100.,$,.LINE.)"), "SegmentLength", "negative"),
        # an enumeration value the schema does not define
        (lambda t: t.replace(".LINE.)", ".STRAIGHT.)", 1), "PredefinedType", "not a value the schema defines"),
        # an arc whose two radii differ
        (lambda t: t.replace("250.,250.,", "250.,260.,"), "EndRadiusOfCurvature", "CIRCULARARC"),
    ],
)
def test_bad_horizontal_values_named(edit, field: str, match: str) -> None:
    text = _one(H("line", 100.0), H("arc", 50.0, 250.0, 250.0, "left"))
    changed = edit(text)
    assert changed != text
    with pytest.raises(AlignmentFormatError, match=match) as exc:
        _read(changed)
    assert exc.value.field == field
    assert "IfcAlignmentHorizontalSegment" in exc.value.location and "IfcAlignment 'A'" in exc.value.location


def test_units() -> None:
    text = _one(H("line", 100.0))
    # millimetres: an SI prefix
    mm = text.replace("IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.)", "IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.)")
    road = _read(mm)
    assert road.linear_unit == "millimetre" and road.alignments[0].elements[0].length_m == 0.1
    # a foot whose factor is a US survey foot's is refused: the two differ by 2e-6
    ft = write_ifc([AlignmentGeometry("A", 0.0, (H("line", 100.0),))], unit="foot").decode()
    wrong = ft.replace("IFCLENGTHMEASURE(0.3048)", f"IFCLENGTHMEASURE({1200 / 3937!r})")
    assert wrong != ft
    with pytest.raises(AlignmentFormatError, match="names its unit 'FOOT'") as exc:
        _read(wrong)
    assert exc.value.field == "ConversionFactor"
    # a unit of another name takes the file's own factor (a chain of 20.1168 m)
    chain = ft.replace("'FOOT'", "'CHAIN'").replace("IFCLENGTHMEASURE(0.3048)", "IFCLENGTHMEASURE(20.1168)")
    road = _read(chain)
    assert road.linear_unit == "CHAIN"
    assert math.isclose(road.alignments[0].elements[0].length_m, 100.0 / 0.3048 * 20.1168, rel_tol=REL)
    # no unit assignment
    none = re.sub(r"IFCPROJECT\(([^;]*),#(\d+)\);", r"IFCPROJECT(\1,$);", text)
    assert none != text
    with pytest.raises(AlignmentFormatError, match="length unit is unknown"):
        _read(none)


def test_vertical_clothoid_skips_the_profile_and_says_so() -> None:
    p = Profile("design", (VerticalSegment("parabolic", 0.0, 100.0, 10.0, 0.01, 0.03),))
    text = _one(H("line", 100.0), profiles=(p,)).replace(".PARABOLICARC.", ".CLOTHOID.")
    road = _read(text)
    assert road.alignments[0].profiles == ()
    assert any("vertical CLOTHOID" in why for _, why in road.skipped)
    # the skipped profile's segments are not counted as read; the line is
    assert dict(road.elements) == {"IfcAlignmentHorizontalSegment.LINE": 1}


def test_vertical_arc_radius_checked_against_its_grades() -> None:
    """A circular sag from -1 % to +1 % over 100 m has R = 100 / (sin atan 0.01 - sin atan -0.01) = 5000.25 m; a
    crest's sign on it is refused."""
    r = 100.0 / (math.sin(math.atan(0.01)) - math.sin(math.atan(-0.01)))
    p = Profile("design", (VerticalSegment("circular", 0.0, 100.0, 10.0, -0.01, 0.01, r),))
    text = _one(H("line", 100.0), profiles=(p,))
    assert _read(text).alignments[0].profiles[0].segments[0].radius_m == pytest.approx(r, rel=REL)
    flipped = re.sub(r"(-0\.01,0\.01,)([0-9.]+)", r"\1-\2", text)
    assert flipped != text
    with pytest.raises(AlignmentFormatError, match="crest") as exc:
        _read(flipped)
    assert exc.value.field == "RadiusOfCurvature"


def test_no_alignment() -> None:
    with pytest.raises(AlignmentFormatError, match="no IfcAlignment"):
        read_ifc(write_ifc([]))


def test_example_road_is_the_readme_road() -> None:
    """examples/road.ifc is the road examples/README.md describes: K1 right-hand R 250.5 m (60 m spirals, 160 m of
    arc) from chainage 300 m, K2 left-hand R 180 m (50 m spirals, 140 m of arc) from 830 m, tangents of 300, 250
    and 300 m, +3.5 % from 880 m, full superelevation 7.5 % and 8 % (banked toward each curve's inside)."""
    road = read_ifc((Path(__file__).resolve().parents[2] / "examples" / "road.ifc").read_bytes())
    (a,) = road.alignments
    arcs = {e.name: e for e in a.elements if e.kind == "arc"}
    assert (arcs["K1"].direction, arcs["K1"].radius_start_m, arcs["K1"].length_m) == ("right", 250.5, 160.0)
    assert (arcs["K2"].direction, arcs["K2"].radius_start_m, arcs["K2"].length_m) == ("left", 180.0, 140.0)
    starts, s = {}, a.start_station_m
    for e in a.elements:
        starts.setdefault(e.name, s)
        s += e.length_m
    assert (starts["K1-TS"], starts["K2-TS"], s) == (300.0, 830.0, 1370.0)
    (p,) = a.profiles
    assert (p.segments[0].start_elevation_m, p.segments[0].start_grade) == (880.0, 0.035)
    # on the arcs: K1 (right) -7.5 % rising left to right, i.e. banked down to the right, its inside; K2 (left) +8 %
    on_k1 = [c.left_percent for c in a.cross_slopes if 360.0 <= c.distance_m <= 520.0]
    on_k2 = [c.left_percent for c in a.cross_slopes if 880.0 <= c.distance_m <= 1020.0]
    assert on_k1 == pytest.approx([-7.5, -7.5], rel=1e-12) and on_k2 == pytest.approx([8.0, 8.0], rel=1e-12)


def test_entities_of_the_wrong_kind_named() -> None:
    """IfcOpenShell keeps whatever the file wrote where an entity belongs; the reader names the attribute."""
    text = _one(H("line", 100.0))
    # a segment's DesignParameters pointing at its own start point (an IfcCartesianPoint)
    m = re.search(r"#(\d+)=IFCALIGNMENTHORIZONTALSEGMENT\(\$,\$,#(\d+),", text)
    assert m is not None
    seg = re.search(rf"(#\d+=IFCALIGNMENTSEGMENT\([^;]*,)#{m[1]}\);", text)
    assert seg is not None
    bad = text.replace(seg[0], f"{seg[1]}#{m[2]});")
    with pytest.raises(AlignmentFormatError, match=r"must be an IfcAlignmentHorizontalSegment.*IfcCartesianPoint") as e:
        _read(bad)
    assert e.value.field == "DesignParameters"
    # the project's units a string
    bad = re.sub(r"(IFCPROJECT\([^;]*),#(\d+)\);", r"\1,'metres');", text)
    with pytest.raises(AlignmentFormatError, match="no UnitsInContext") as e:
        _read(bad)
    assert e.value.field == "UnitsInContext"


def test_station_from_pset_stationing_checked() -> None:
    a = AlignmentGeometry("A", 1234.5, (H("line", 100.0),))
    text = write_ifc([a]).decode()
    assert _read(text).alignments[0].start_station_m == 1234.5
    bad = text.replace("IFCLENGTHMEASURE(1234.5)", "IFCLABEL('1+234.5')")
    assert bad != text
    with pytest.raises(AlignmentFormatError, match="Station is not a number") as e:
        _read(bad)
    assert e.value.field == "Station" and "IfcReferent" in e.value.location


def test_a_file_the_parser_cannot_read() -> None:
    """A header that names IFC4X3_ADD2 and a data section cut off mid-entity."""
    with pytest.raises(AlignmentFormatError, match="unreadable IFC file: the parser could not read"):
        read_ifc(b"ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('IFC4X3_ADD2'));\nENDSEC;\nDATA;\n#1=IFCPROJECT(\n")


def test_alignment_given_only_as_geometry_refused() -> None:
    """IfcOpenShell's create_as_polyline writes an IfcAlignment with a polyline and no layouts: nothing to read."""
    import ifcopenshell.api.alignment
    import ifcopenshell.api.project
    import ifcopenshell.api.root
    import ifcopenshell.api.unit

    f = ifcopenshell.api.project.create_file(version="IFC4X3")
    ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="p")
    ifcopenshell.api.unit.assign_unit(f, units=[f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE")])
    points = [f.createIfcCartesianPoint(p) for p in ((0.0, 0.0), (100.0, 0.0), (200.0, 50.0))]
    ifcopenshell.api.alignment.create_as_polyline(f, "poly", points)
    with pytest.raises(AlignmentFormatError, match="only as geometry") as e:
        read_ifc(f.to_string().encode())
    assert e.value.location.startswith("IfcAlignment 'poly'")
