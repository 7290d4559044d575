"""A LandXML ``Curve``'s ``delta`` and ``chord``, written beside its ``radius`` and ``length``, are compared with
them (issue 39: a wrong number from the user's own file is worse than a refusal; nothing dropped silently).

Independent route: the rounding each written number allows is taken from its text with :mod:`decimal` (half a unit
of its exponent), and the agreement decided by interval bounds (the least and greatest length/radius and chord over
the box of rounded values) rather than the reader's propagated derivatives; the angle's unit from its definition
(pi/200 rad the grad, dd.mm.ss by its digits). Every public export in tests/data/landxml is checked this way from its
own text, within the rounding alone (the reader allows a millionth more, ARC_AGREEMENT: not needed by any of them),
and must be read without a note.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from decimal import Decimal
from pathlib import Path

import pytest

from app.formats.alignment_io import AlignmentFormatError
from app.formats.landxml import read_road_file

DATA = Path(__file__).resolve().parents[1] / "data" / "landxml"
RAD = {"radians": 1.0, "grads": math.pi / 200, "decimal degrees": math.pi / 180}


def _half(text: str) -> float:
    return 0.5 * 10.0 ** Decimal(text.strip()).as_tuple().exponent


def _dms_rad(text: str) -> tuple[float, float]:
    """(value, half a unit in its last decimal) [rad] of a ``decimal dd.mm.ss`` text, from its digits."""
    whole, _, frac = text.strip().lstrip("-").partition(".")
    frac4 = (frac + "0000")[:4]
    seconds = float(frac4[2:] + "." + frac[4:]) if frac[4:] else float(frac4[2:])
    deg = int(whole) + int(frac4[:2]) / 60 + seconds / 3600
    k = len(frac)
    half = 0.5 if k == 0 else 0.5 * (10 ** (2 - k) / 60 if k <= 2 else 10 ** (4 - k) / 3600)
    return math.radians(deg), math.radians(half)


def _theta_bounds(r: str, length: str) -> tuple[float, float]:
    R, L, hr, hl = float(r), float(length), _half(r), _half(length)
    return (L - hl) / (R + hr), (L + hl) / (R - hr)


def delta_agrees(curve: ET.Element, unit: str) -> bool:
    d = curve.get("delta")
    if unit == "decimal dd.mm.ss":
        value, half = _dms_rad(d)
    else:
        value, half = abs(float(d)) * RAD[unit], _half(d) * RAD[unit]
    lo, hi = _theta_bounds(curve.get("radius"), curve.get("length"))
    return value + half >= lo and value - half <= hi


def chord_agrees(curve: ET.Element) -> bool:
    R, L = float(curve.get("radius")), float(curve.get("length"))
    hr, hl = _half(curve.get("radius")), _half(curve.get("length"))
    # the chord 2 R sin(L/2R) over the box's corners (monotone in each of R and L on an arc of less than a half turn,
    # which every arc here is: the corners bound it)
    assert (L + hl) / (R - hr) < math.pi
    corners = [2 * (R + a) * math.sin((L + b) / (2 * (R + a))) for a in (-hr, hr) for b in (-hl, hl)]
    c, hc = float(curve.get("chord")), _half(curve.get("chord"))
    return c + hc >= min(corners) and c - hc <= max(corners)


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


@pytest.mark.parametrize("path", sorted(DATA.glob("*.xml")), ids=lambda p: p.name)
def test_every_public_export_agrees_within_its_rounding_and_is_read_without_a_note(path):
    doc = path.read_bytes()
    root = ET.fromstring(doc)
    system = next((e for e in root.iter() if _local(e.tag) in ("Metric", "Imperial")), None)
    unit = system.get("angularUnit", "decimal degrees") if system is not None else "decimal degrees"
    curves = [e for e in root.iter() if _local(e.tag) == "Curve" and e.get("radius") and e.get("length")]
    deltas = [c for c in curves if c.get("delta") is not None]
    chords = [c for c in curves if c.get("chord") is not None]
    assert all(delta_agrees(c, unit) for c in deltas)
    assert all(chord_agrees(c) for c in chords)
    road = read_road_file(doc)
    assert [n for a in road.alignments for n in a.notes] == []


def test_the_public_exports_hold_curves_with_delta_and_chord():
    # the test above is no test of the comparison unless the files write the attributes it compares
    counts = {"delta": 0, "chord": 0, "negative delta": 0}
    for path in DATA.glob("*.xml"):
        for c in ET.fromstring(path.read_bytes()).iter():
            if _local(c.tag) == "Curve" and c.get("radius") and c.get("length"):
                counts["delta"] += c.get("delta") is not None
                counts["chord"] += c.get("chord") is not None
                counts["negative delta"] += float(c.get("delta") or 0) < 0 and c.get("rot") == "ccw"
    assert counts["delta"] >= 6 and counts["chord"] >= 8 and counts["negative delta"] >= 1


def doc(*curves: str, angular: str = "decimal degrees", linear: str = "meter") -> str:
    """An alignment of the given Curve attribute strings, each named C1, C2, ... and preceded by a line."""
    items = "".join(f'<Line length="10"/><Curve name="C{k}" {c}/>' for k, c in enumerate(curves, start=1))
    return (
        '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        f'<Units><Metric linearUnit="{linear}" angularUnit="{angular}"/></Units>'
        f'<Alignments><Alignment name="A" staStart="0"><CoordGeom>{items}</CoordGeom></Alignment></Alignments>'
        "</LandXML>"
    )


#: radius and length to six decimals (their rounding negligible beside a delta's or chord's); written as whole numbers
#: they allow +-0.5 each, which is +-0.0075 rad (0.43 deg) of length/radius
R6 = 'radius="100.000000" length="50.000000"'
# radius 100, length 50: the arc turns 0.5 rad = 28.6478897565... deg = 31.8309886... grad; its chord 200 sin(0.25)
DEG = math.degrees(0.5)
GRAD = 0.5 * 200 / math.pi
CHORD = 200 * math.sin(0.25)


def notes(text: str) -> list[str]:
    return [n for a in read_road_file(text).alignments for n in a.notes]


@pytest.mark.parametrize(
    "attrs",
    [
        f'rot="cw" radius="100" length="50" delta="{DEG:.6f}"',
        f'rot="ccw" radius="100" length="50" delta="-{DEG:.6f}"',  # Novapoint: negative on a left-hand arc
        'rot="cw" radius="100" length="50" delta="28.6"',  # one decimal: 28.6 +- 0.05 holds 28.648
        f'rot="cw" radius="100" length="50" chord="{CHORD:.6f}"',
        f'rot="cw" radius="100.000" length="50.000" delta="{DEG:.3f}" chord="{CHORD:.3f}"',
    ],
)
def test_a_delta_or_chord_that_agrees_within_its_decimals_is_read_silently(attrs):
    assert notes(doc(attrs)) == []


def test_delta_in_grads_and_in_dd_mm_ss_is_compared_in_its_unit():
    assert notes(doc(f'rot="cw" radius="100" length="50" delta="{GRAD:.6f}"', angular="grads")) == []
    # 28.6478897565 deg = 28 deg 38 min 52.403 s
    assert notes(doc('rot="cw" radius="100" length="50" delta="28.3852403"', angular="decimal dd.mm.ss")) == []
    # the degrees' number in a file in grads: 10 % off, refused naming the unit it was read in
    with pytest.raises(AlignmentFormatError) as e:
        read_road_file(doc(f'rot="cw" radius="100" length="50" delta="{DEG:.6f}"', angular="grads"))
    assert e.value.field == "delta" and "(grads)" in str(e.value) and f"{GRAD:.9g}" in str(e.value)
    # a second off in dd.mm.ss (52.4 -> 53.4 s: 2.8e-4 deg), beyond the 0.05 s its last decimal allows
    (note,) = notes(doc(f'rot="cw" {R6} delta="28.38534"', angular="decimal dd.mm.ss"))
    assert "Curve #1 ('C1')" in note and "28.38534" in note and f"{DEG:.9g}" in note


def test_a_small_disagreement_is_a_note_naming_the_curve_and_both_values_and_the_curve_read_by_length_and_radius():
    # 28.60 written with two decimals allows +-0.005: 28.648 is 0.048 away (0.17 %)
    text = doc(f'rot="cw" {R6} delta="{DEG:.6f}"', f'rot="cw" {R6} delta="28.60"')
    (note,) = notes(text)
    assert note.startswith("Alignment 'A' CoordGeom Curve #2 ('C2')")
    assert "delta 28.60 (decimal degrees)" in note and f"{DEG:.9g}" in note and "length and radius" in note
    (a,) = read_road_file(text).alignments
    arcs = [(e.radius_start_m, e.length_m) for e in a.elements if e.kind == "arc"]
    assert arcs == [(100.0, 50.0), (100.0, 50.0)]


def test_a_chord_that_disagrees_is_noted_and_one_grossly_off_refused():
    (note,) = notes(doc(f'rot="cw" {R6} chord="49.6"'))  # 0.24 % off
    assert "Curve #1 ('C1')" in note and "chord 49.6" in note and f"{CHORD:.9g}" in note
    with pytest.raises(AlignmentFormatError) as e:
        read_road_file(doc(f'rot="cw" {R6} chord="52"'))  # 5 % off
    assert e.value.field == "chord" and "Curve #1 ('C1')" in e.value.location and "52" in str(e.value)


def test_a_delta_grossly_off_is_refused_naming_the_element_the_attribute_and_both_values():
    with pytest.raises(AlignmentFormatError) as e:
        read_road_file(doc(f'rot="cw" {R6} delta="{DEG:.6f}"', f'rot="ccw" {R6} delta="-30"'))
    assert e.value.field == "delta" and e.value.location == "Alignment 'A' CoordGeom Curve #2 ('C2')"
    assert "delta -30 (decimal degrees)" in str(e.value) and f"{DEG:.9g}" in str(e.value)


def test_the_rounding_is_the_written_numbers_not_a_fixed_tolerance():
    # the same 0.048 deg (0.17 %) is within a delta of one decimal (+-0.05) and beyond one of two (+-0.005); and
    # radius and length written as whole numbers (+-0.5 each: +-0.43 deg of length/radius) allow it too
    assert notes(doc(f'rot="cw" {R6} delta="28.6"')) == []
    assert len(notes(doc(f'rot="cw" {R6} delta="28.60"'))) == 1
    assert notes(doc('rot="cw" radius="100" length="50" delta="28.60"')) == []
    assert notes(doc('rot="cw" radius="1.00e2" length="5.0e1" delta="28.60"')) == []  # the same, in exponents
    assert len(notes(doc('rot="cw" radius="1.00000e2" length="5.00000e1" delta="28.60"'))) == 1


def test_feet_compare_the_chord_in_the_files_unit():
    # radius 100 ft, length 50 ft: the same angle, the chord 200 sin(0.25) ft
    assert notes(doc(f'rot="cw" {R6} chord="{CHORD:.6f}"', linear="foot")) == []
    (note,) = notes(doc(f'rot="cw" {R6} chord="49.6"', linear="foot"))
    assert "(foot)" in note


def test_many_disagreements_are_noted_up_to_a_count_then_counted():
    text = doc(*[f'rot="cw" {R6} delta="28.60"'] * 25)
    got = notes(text)
    assert len(got) == 21 and "Curve #20 ('C20')" in got[19] and got[20].startswith("and 5 more Curves")


@pytest.mark.parametrize(
    ("attrs", "angular", "field", "text"),
    [
        (f'rot="cw" {R6} delta="twenty"', "decimal degrees", "delta", "'twenty'"),
        (f'rot="cw" {R6} chord="nan"', "decimal degrees", "chord", "'nan'"),
        (f'rot="cw" {R6} delta="{DEG:.6f}"', "gons", "angularUnit", "'gons'"),
    ],
)
def test_a_delta_or_chord_that_cannot_be_compared_is_refused_by_name(attrs, angular, field, text):
    # a delta is read now wherever it is written: one that is no number, or in a unit LandXML does not define, is
    # refused as a Curve's length given by delta alone is
    with pytest.raises(AlignmentFormatError) as e:
        read_road_file(doc(attrs, angular=angular))
    assert e.value.field == field and text in str(e.value)
