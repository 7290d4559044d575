"""The SVG renderer and the CSV / LandXML curve readers (no HTTP)."""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ET

import pytest

from app.formats.alignment_io import AlignmentFormatError, CurveOverride, read_csv, read_landxml
from app.formats.svg import Marker, Panel, Series, line_chart, nice_ticks

NS = {"s": "http://www.w3.org/2000/svg"}


def test_nice_ticks_cover_the_range_with_round_steps():
    # (0.3364 - 0) / 5 = 0.067 rounds up to a step of 0.1
    assert nice_ticks(0, 0.3364) == pytest.approx([0, 0.1, 0.2, 0.3, 0.4])
    t = nice_ticks(-3.2, 187.0)
    assert t[0] <= -3.2 and t[-1] >= 187.0
    steps = {round(b - a, 9) for a, b in itertools.pairwise(t)}
    assert len(steps) == 1


def test_chart_parses_and_holds_its_series_markers_and_labels():
    svg = line_chart(
        "Tire normal loads",
        "lateral acceleration ay/g [-]",
        [
            Panel(
                "normal load [kN]",
                [
                    Series("Fz1", [0, 0.1, 0.2], [50, 60, 70]),
                    Series("Fz3 <inner>", [0, 0.1, 0.2], [50, 40, 30], dashed=True),
                ],
                [Marker(0.2, "SRT_3D = 0.200")],
            ),
            Panel("LLT [-]", [Series("LLTr", [0, 0.1, 0.2], [0, 0.5, 1.0])]),
        ],
        caption="Fz1, Fz3: front outer and inner tire normal loads (thesis Fig. 92).",
    )
    root = ET.fromstring(svg)
    series = {g.get("data-name"): g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "series"}
    assert set(series) == {"Fz1", "Fz3 <inner>", "LLTr"}
    line = series["Fz1"].find("s:polyline", NS)
    assert [float(v) for v in line.get("data-y").split()] == [50, 60, 70]
    assert len(line.get("points").split()) == 3
    texts = " ".join(t.text or "" for t in root.iter("{http://www.w3.org/2000/svg}text"))
    assert "lateral acceleration ay/g [-]" in texts and "normal load [kN]" in texts and "Fig. 92" in texts
    markers = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "marker"]
    assert float(markers[0].get("data-x")) == 0.2


def test_chart_refuses_empty_data():
    with pytest.raises(ValueError):
        line_chart("t", "x", [Panel("y", [])])


CSV_OK = (
    "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\nC1,120,6,-4,60\nC2,350,4,,80\nC3,90,8,2,\n\n"
)


def test_csv_reads_curves_with_optional_columns():
    t = read_csv(CSV_OK)
    assert t.ids == ["C1", "C2", "C3"] and t.where == ["row 2", "row 3", "row 4"]
    assert (t.radius_m[0], t.grade_percent[0], t.posted_speed_kmh[0]) == (120, -4, 60)
    assert t.grade_percent[1] == 0.0 and math.isnan(t.posted_speed_kmh[2])
    minimal = read_csv("ID, Radius_m ,superelevation_percent\nA,100,2\n")
    assert minimal.grade_percent[0] == 0.0
    # without a superelevation (column or cell) the curve's is left to the design standard's distribution
    derived = read_csv("id,radius_m,superelevation_percent\nA,100,\n")
    assert math.isnan(derived.superelevation_percent[0]) and math.isnan(
        read_csv("id,radius_m\nA,100\n").superelevation_percent[0]
    )


@pytest.mark.parametrize(
    "text,where,field",
    [
        ("id,superelevation_percent\nA,2\n", "row 1 (header)", "radius_m"),
        ("id,radius_m,superelevation_percent\nA,abc,2\n", "row 2", "radius_m"),
        ("id,radius_m,superelevation_percent\nA,100,2\nB,100\n", "row 3", None),
        ("id,radius_m,superelevation_percent\nA,100,2\nA,200,3\n", "row 3", "id"),
        ("id,radius_m,superelevation_percent,wind\nA,100,2,3\n", "row 1 (header)", "wind"),
        ("id,radius_m,superelevation_percent\n", "row 2", None),
        ("", None, None),
    ],
)
def test_csv_errors_name_the_row_and_column(text, where, field):
    with pytest.raises(AlignmentFormatError) as exc:
        read_csv(text)
    assert exc.value.location == where
    assert exc.value.field == field


LANDXML = """<?xml version="1.0"?>
<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">
  <Alignments>
    <Alignment name="BR-101" length="1500" staStart="0">
      <CoordGeom>
        <Line staStart="0" length="200"><Start>0 0</Start><End>0 200</End></Line>
        <Curve rot="cw" radius="250" length="120" staStart="200" name="K1"><Start>0 200</Start></Curve>
        <Spiral rot="ccw" length="60" radiusStart="INF" radiusEnd="400.5" staStart="320"/>
        <Curve rot="ccw" radius="400.5" length="90" staStart="380"/>
      </CoordGeom>
    </Alignment>
  </Alignments>
</LandXML>"""


def test_landxml_curves_with_defaults_and_overrides():
    got = read_landxml(
        LANDXML,
        superelevation_percent=6.0,
        grade_percent=-2.0,
        posted_speed_kmh=80,
        overrides={"BR-101#2": CurveOverride(superelevation_percent=4.0, grade_percent=3.0)},
    )
    assert got.ids == ["K1", "BR-101#2"]
    assert list(got.radius_m) == [250, 400.5] and list(got.superelevation_percent) == [6.0, 4.0]
    assert list(got.grade_percent) == [-2.0, 3.0] and list(got.station_m) == [200, 380]
    assert list(got.posted_speed_kmh) == [80, 80]
    assert got.where[1] == "Alignment 'BR-101' CoordGeom Curve #2 ('BR-101#2')"
    derive = read_landxml(LANDXML, superelevation_percent=None)  # left to the design standard's distribution
    assert all(math.isnan(e) for e in derive.superelevation_percent)


@pytest.mark.parametrize(
    "doc,kwargs,match",
    [
        (
            "<LandXML><Alignments><Alignment name='A'><CoordGeom><Curve staStart='1'/></CoordGeom></Alignment>"
            "</Alignments></LandXML>",
            {"superelevation_percent": 4},
            "Curve #1 .* has no radius",
        ),
        (
            "<LandXML><Alignments><Alignment name='A'><CoordGeom><Curve radius='-5'/></CoordGeom></Alignment>"
            "</Alignments></LandXML>",
            {"superelevation_percent": 4},
            r"Curve #1 \('A#1'\): radius must be positive \(or INF\), got '-5'",
        ),
        ("<LandXML><Alignments><Alignment", {"superelevation_percent": 4}, "malformed XML"),
        ("<Foo/>", {"superelevation_percent": 4}, "not <LandXML>"),
        (LANDXML, {"superelevation_percent": 4, "overrides": {"K9": CurveOverride(grade_percent=1)}}, "K9"),
        (
            '<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "aaaa">]><LandXML>&a;</LandXML>',
            {"superelevation_percent": 4},
            "entities",
        ),
    ],
)
def test_landxml_errors_name_the_element(doc, kwargs, match):
    with pytest.raises(AlignmentFormatError, match=match):
        read_landxml(doc, **kwargs)
