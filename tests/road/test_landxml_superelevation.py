"""LandXML ``Superelevation`` elements read into an alignment's ranges: the usual shape (three children in order)
read by position and every other shape by the careful reading, in the file's order and places, each range's stations
made distances (the unit's definition, a station equation) and its nearer end first; refusals name the element."""

from __future__ import annotations

import pytest

from app.formats.alignment_io import AlignmentFormatError
from app.formats.landxml import read_road_file
from engine.road import SuperelevationRange

HEAD = (
    '<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
    '<Units><Imperial linearUnit="foot"/></Units><Alignments><Alignment name="A" staStart="1000"><CoordGeom>'
    '<Line length="100"/><Curve rot="cw" radius="600" length="100" name="C1"/><Line length="100"/>'
    '<Curve rot="ccw" radius="900" length="100" name="C2"/><Line length="100"/></CoordGeom>'
)
TAIL = "</Alignment></Alignments></LandXML>"
FT = 0.3048  # m per international foot (its definition)


def usual(sta, full, end):
    return (
        f"<Superelevation><FullSuperSta>{sta}</FullSuperSta><FullSuperelev>{full}</FullSuperelev>"
        f"<RunoffSta>{end}</RunoffSta></Superelevation>"
    )


def ranges(body: str) -> tuple:
    (a,) = read_road_file((HEAD + body + TAIL).encode()).alignments
    return tuple(a.superelevation)


def test_every_shape_in_the_files_order_and_places():
    body = (
        usual(1100, 6, 1200)
        # children out of order, white space around the numbers: the careful reading
        + "<Superelevation><FullSuperelev> 5 </FullSuperelev><RunoffSta>1400</RunoffSta>"
        "<FullSuperSta>1300</FullSuperSta></Superelevation>"
        # no FullSuperSta/RunoffSta: the element's own staStart/staEnd
        + '<Superelevation staStart="1090" staEnd="1210"><FullSuperelev>-2</FullSuperelev></Superelevation>'
        # another namespace
        + '<x:Superelevation xmlns:x="urn:x"><x:FullSuperSta>1400</x:FullSuperSta><x:FullSuperelev>4</x:FullSuperelev>'
        "<x:RunoffSta>1300</x:RunoffSta></x:Superelevation>" + usual(1150, 7, 1150)
    )
    # distances from the alignment's start station (1000 ft), in metres; a range's nearer end first
    expected = (
        SuperelevationRange(100 * FT, 200 * FT, 6.0, "Alignment 'A' Superelevation 1"),
        SuperelevationRange(300 * FT, 400 * FT, 5.0, "Alignment 'A' Superelevation 2"),
        SuperelevationRange(90 * FT, 210 * FT, -2.0, "Alignment 'A' Superelevation 3"),
        SuperelevationRange(300 * FT, 400 * FT, 4.0, "Alignment 'A' Superelevation 4"),
        SuperelevationRange(150 * FT, 150 * FT, 7.0, "Alignment 'A' Superelevation 5"),
    )
    got = ranges(body)
    assert [(r.where, r.full_percent) for r in got] == [(r.where, r.full_percent) for r in expected]
    for r, e in zip(got, expected, strict=True):
        assert (r.start_distance_m, r.end_distance_m) == pytest.approx(
            (e.start_distance_m, e.end_distance_m), rel=1e-12
        )


def test_a_station_equation_moves_the_ranges_after_it():
    equation = '<StaEquation staBack="1250" staAhead="5000" staInternal="1250"/>'
    got = ranges(equation + usual(1100, 6, 1200) + usual(5050, 5, 5150))
    # 5050 is 50 ft past the equation at 250 ft along
    ends = [x for r in got for x in (r.start_distance_m, r.end_distance_m)]
    assert ends == pytest.approx([100 * FT, 200 * FT, 300 * FT, 400 * FT], rel=1e-12)


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        (usual(1300, "x", 1400), "Superelevation 2: FullSuperelev is not a number: 'x'"),
        (usual(1300, "nan", 1400), "Superelevation 2: FullSuperelev must be finite, got 'nan'"),
        (usual("inf", 6, 1400), "Superelevation 2: FullSuperSta must be finite, got 'inf'"),
        (
            "<Superelevation><FullSuperSta>1300</FullSuperSta></Superelevation>",
            "Superelevation 2: has no <FullSuperelev>",
        ),
        ("<Superelevation><FullSuperelev>6</FullSuperelev></Superelevation>", "Superelevation 2: has no staStart"),
    ],
)
def test_a_refusal_names_the_element_among_usual_ones(bad, message):
    with pytest.raises(AlignmentFormatError) as e:
        ranges(usual(1100, 6, 1200) + bad + usual(1100, 6, 1200))
    assert message in str(e.value) and "Alignment 'A'" in str(e.value)
