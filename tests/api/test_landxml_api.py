"""The LandXML endpoints answer a road-design file whole (issue 39): its units applied, its bends as rows with their
facts, `reading` in every answer, a straight road answered with no rows, the profile chosen by name, and the file's
faults refused by name.

Independent numbers: a curve of 200 ft is a curve of 60.96 m (0.3048 m the foot, by definition): the same request
with the curve given as JSON at 60.96 m must answer the same assessment. A public Novapoint export's rows against the
file's own text (its Curves' radius, staStart and delta, its PVIs and circular vertical curves).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.landxml_writer import Design, Element, Pvi, landxml
from tests.road.test_landxml_files import _circle_profile, _elements

BTRAIN = "table16-btrain"
PATH = "/v1/alignments/assess/landxml"
DATA = Path(__file__).resolve().parents[1] / "data" / "landxml"
FEET = Design(
    "F",
    0.0,
    [
        Element("Line", 100 * 0.3048),
        Element("Curve", 150 * 0.3048, 200 * 0.3048, 200 * 0.3048, "cw", "K1"),
        Element("Line", 100 * 0.3048),
    ],
)


def upload(client, doc: str, query: str, status: int = 200, **headers):
    r = client.post(f"{PATH}?{query}", content=doc.encode(), headers={"Content-Type": "application/xml", **headers})
    assert r.status_code == status, r.text
    return r


def test_a_curve_in_feet_is_assessed_at_its_radius_in_metres(shared_client):
    out = upload(shared_client, landxml(FEET, "foot"), f"vehicle={BTRAIN}&superelevation_percent=6").json()
    (row,) = out["vehicles"][0]["rows"]
    assert row["radius_m"] == pytest.approx(60.96, rel=1e-12) and row["station_m"] == pytest.approx(30.48, rel=1e-12)
    assert out["reading"]["linear_unit"] == "foot" and out["reading"]["superelevation_from"] == "request"
    body = {"vehicle": BTRAIN, "curves": [{"id": "K1", "radius_m": 60.96, "superelevation_percent": 6.0}]}
    (json_row,) = shared_client.post("/v1/alignments/assess", json=body).json()["vehicles"][0]["rows"]
    for name in ("srt_g", "rollover_speed_kmh", "side_friction_speed_kmh", "safe_speed_kmh"):
        assert row[name] == pytest.approx(json_row[name], rel=1e-9), name
    assert row["governed_by"] == json_row["governed_by"]
    assert row["deflection_deg"] == pytest.approx(math.degrees(150 / 200), rel=1e-12)
    assert (row["direction"], row["superelevation_source"], row["grade_source"]) == ("right", "given", "request")


def test_a_straight_road_answers_with_no_curves(shared_client):
    doc = landxml(Design("S", 0.0, [Element("Line", 800.0)]))
    out = upload(shared_client, doc, f"vehicle={BTRAIN}").json()
    assert out["curves"] == 0 and out["vehicles"][0]["rows"] == [] and out["reading"]["elements"] == {"Line": 1}
    csv = upload(shared_client, doc, f"vehicle={BTRAIN}", accept="text/csv").text
    assert csv.count("\r\n") == 1 and csv.startswith("vehicle_index,")  # the header alone


def test_the_profile_is_chosen_by_name_and_a_name_not_in_the_file_is_refused(shared_client):
    design = Design("P", 0.0, [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "cw", "K")],
                    pvis=[Pvi(0.0, 0.0), Pvi(200.0, 4.0)])  # fmt: skip
    doc = landxml(design).replace(
        '<ProfAlign name="Design">',
        '<ProfAlign name="Ground"><PVI>0 0</PVI><PVI>200 -10</PVI></ProfAlign><ProfAlign name="Design">',
    )
    q = f"vehicle={BTRAIN}&superelevation_percent=4"
    first = upload(shared_client, doc, q).json()
    assert first["vehicles"][0]["rows"][0]["grade_percent"] == pytest.approx(-5.0)
    chosen = upload(shared_client, doc, q + "&profile=Design").json()
    assert chosen["vehicles"][0]["rows"][0]["grade_percent"] == pytest.approx(2.0)
    assert chosen["reading"]["profile"] == "Design"
    p = upload(shared_client, doc, q + "&profile=Final", status=422).json()
    assert p["errors"][0]["field"] == "profile" and "'Final'" in p["errors"][0]["message"]


@pytest.mark.parametrize(
    ("edit", "field", "text"),
    [
        (('linearUnit="meter"', 'linearUnit="furlong"'), "body.linearUnit", "'furlong'"),
        (('rot="cw"', 'rot="clockwise"'), "body.rot", "'clockwise'"),
    ],
)
def test_a_unit_or_value_the_reader_does_not_know_is_a_422_naming_it(shared_client, edit, field, text):
    doc = landxml(FEET).replace(*edit)
    p = upload(shared_client, doc, f"vehicle={BTRAIN}", status=422).json()
    (error,) = p["errors"]
    assert error["field"] == field and text in error["message"]


def test_a_novapoint_file_answers_its_arcs_with_their_turn_and_grade(shared_client):
    # a public Trimble Novapoint export (tests/data/landxml/README.md): its left-hand arc written with a negative
    # delta and rot="ccw"; the expected numbers from the file's text (tests/road/test_landxml_files.py's helpers)
    doc = (DATA / "novapoint-inframodel-m14334.xml").read_bytes()
    out = upload(shared_client, doc.decode(), f"vehicle={BTRAIN}&superelevation_percent=4").json()
    rows = out["vehicles"][0]["rows"]
    curves = _elements(doc, "Curve")
    assert [r["direction"] for r in rows] == ["left" if c.get("rot") == "ccw" else "right" for c in curves]
    negative = [float(c.get("delta")) < 0 for c in curves]
    assert negative == [r["direction"] == "left" for r in rows] == [False, False, True]
    for row, c in zip(rows, curves, strict=True):
        assert row["radius_m"] == float(c.get("radius")) and row["station_m"] == float(c.get("staStart"))
        assert row["deflection_deg"] == pytest.approx(abs(float(c.get("delta"))), abs=1e-6)  # six decimals written
    # the grade at each arc's middle on the profile's PVIs and circular vertical curves (the arcs placed by their
    # lengths summed from the alignment's start, 0)
    _, _, grade = _circle_profile(doc)
    lengths = [float(e.get("length")) for e in _elements(doc, "CoordGeom")[0]]
    at = [i for i, e in enumerate(_elements(doc, "CoordGeom")[0]) if e.tag.endswith("}Curve")]
    middles = [sum(lengths[:i]) + lengths[i] / 2 for i in at]
    assert [r["grade_percent"] for r in rows] == pytest.approx([100 * grade(m) for m in middles], rel=1e-9)
    assert {r["grade_source"] for r in rows} == {"profile"}
    (application,) = _elements(doc, "Application")
    assert out["reading"]["writer"] == f"{application.get('version')} ({application.get('manufacturer')})"
    assert out["reading"]["linear_unit"] == "meter"


def test_a_curve_whose_delta_disagrees_with_its_length_and_radius_is_noted_or_refused(shared_client):
    # radius 100, length 50: the arc turns 0.5 rad = 28.6478898 deg; a delta of 28.60 (two decimals: +-0.005) is
    # 0.17 % off, noted, the row at the file's radius; a delta of 30 is 4.7 % off, refused naming the element
    curve = '<Curve name="K" rot="cw" radius="100.000000" length="50.000000" delta="{}"/>'
    doc = landxml(Design("D", 0.0, [Element("Line", 20.0), Element("Curve", 50.0, 100.0, 100.0, "cw", "K")]))
    start = doc.index("<Curve")
    end = doc.index("/>", start) + 2
    noted = doc[:start] + curve.format("28.60") + doc[end:]
    out = upload(shared_client, noted, f"vehicle={BTRAIN}&superelevation_percent=6").json()
    (row,) = out["vehicles"][0]["rows"]
    assert row["radius_m"] == 100.0 and row["arc_length_m"] == 50.0
    (note,) = out["reading"]["notes"]
    assert note.startswith("D: Alignment 'D' CoordGeom Curve #1 ('K')")
    assert "delta 28.60 (decimal degrees)" in note and f"{math.degrees(0.5):.9g}" in note
    p = upload(shared_client, doc[:start] + curve.format("30") + doc[end:], f"vehicle={BTRAIN}", status=422).json()
    (error,) = p["errors"]
    assert error["field"] == "body.delta" and error["location"] == "Alignment 'D' CoordGeom Curve #1 ('K')"
    assert "delta 30 (decimal degrees)" in error["message"] and f"{math.degrees(0.5):.9g}" in error["message"]
