"""The IFC 4.3 endpoint (`POST /v1/alignments/assess/ifc`, and `ifc` in the JSON request) answers as the LandXML
one does (/work/shared/DESIGN.md, "Road files ... answer alike"): the same alignment exported both ways gives the
same rows.

Independent numbers: examples/README.md's road (K1 radius 250.5 m, 60 m clothoids, 160 m of arc from chainage 300 m;
K2 radius 180 m, 50 m clothoids, 140 m of arc from chainage 830 m; +3.5 % grade; 7.5 % and 8 % design
superelevation), so a row's arc starts at 300 + 60 = 360 m and 830 + 50 = 880 m and its deflection is the arc's
plus each clothoid's angle, (arc + spiral) / R rad (a clothoid of length L ending at radius R turns L / 2R). The two
random files are written by two independent writers (tests/landxml_writer.py, tests/ifc_writer.py with
IfcOpenShell) from one design, and read by two independent readers.
"""

from __future__ import annotations

import math
import random
from pathlib import Path

import pytest

from engine.road.geometry import AlignmentGeometry, CrossSlope, HorizontalElement, Profile, VerticalSegment
from tests.ifc_writer import write_ifc
from tests.landxml_writer import Design, landxml
from tests.road.test_landxml_files import _design

BTRAIN = "table16-btrain"
PATH = "/v1/alignments/assess/ifc"
ROOT = Path(__file__).resolve().parents[2]
ROAD_IFC = (ROOT / "examples" / "road.ifc").read_bytes()
FEET_XML = (ROOT / "examples" / "alignment-feet.xml").read_bytes()
REFUSED = ROOT / "tests" / "data" / "ifc" / "Alignment-12d-1.ifc"  # IFC4X3_RC3 (tests/data/ifc/README.md)
#: the agreement asked of two readings of one design: the writers print shortest round-tripping digits, the feet
#: of the LandXML file are converted back (0.3048 m exactly), so only the rounding of those conversions is left
REL = 1e-9


def _post(client, path: str, content: bytes, query: str = f"vehicle={BTRAIN}", status: int = 200, **headers):
    r = client.post(f"{path}?{query}", content=content, headers=headers)
    assert r.status_code == status, r.text
    return r


def _same_rows(a: list[dict], b: list[dict], differ: frozenset[str] = frozenset()) -> None:
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        assert x.keys() == y.keys()
        for k in x:
            if k in differ:
                continue
            u, v = x[k], y[k]
            if isinstance(u, float) and isinstance(v, float):
                assert u == pytest.approx(v, rel=REL, abs=1e-9), (x["id"], k, u, v)
            else:
                assert u == v, (x["id"], k, u, v)


# ------------------------------------------------------------------------------------------ the endpoint


@pytest.mark.parametrize("content_type", ["application/x-step", "application/octet-stream", "text/plain", None])
def test_raw_body_and_multipart_give_the_same_answer(shared_client, content_type):
    headers = {} if content_type is None else {"Content-Type": content_type}
    raw = _post(shared_client, PATH, ROAD_IFC, **headers).json()
    r = shared_client.post(f"{PATH}?vehicle={BTRAIN}", files={"file": ("road.ifc", ROAD_IFC, "application/x-step")})
    assert r.status_code == 200, r.text
    assert r.json() == raw
    body = {"vehicle": BTRAIN, "ifc": {"document": ROAD_IFC.decode()}}
    assert shared_client.post("/v1/alignments/assess", json=body).json() == raw
    assert raw["reading"]["format"] == "IFC 4.3 (IFC4X3_ADD2)"
    assert raw["reading"]["writer"] == "rollover examples/make_examples.py 1"
    # examples/README.md: 3 lines, 4 clothoids, 2 arcs; one grade; the cant's 9 runs (constant and run-off)
    assert raw["reading"]["elements"] == {
        "IfcAlignmentHorizontalSegment.LINE": 3,
        "IfcAlignmentHorizontalSegment.CLOTHOID": 4,
        "IfcAlignmentHorizontalSegment.CIRCULARARC": 2,
        "IfcAlignmentVerticalSegment.CONSTANTGRADIENT": 1,
        "IfcAlignmentCantSegment.CONSTANTCANT": 5,
        "IfcAlignmentCantSegment.LINEARTRANSITION": 4,
    }


def test_the_example_road_in_ifc_and_in_landxml_gives_the_same_rows(shared_client):
    """examples/road.ifc and examples/alignment-feet.xml are one road (examples/README.md). Every field of every row
    agrees to 1e-9 but ``superelevation_source``: the LandXML file gives each curve's design superelevation as a
    `Superelevation` element (``file``), the IFC file as its cant, read as cross slopes (``cross-sections``);
    the values are the same (7.5 %, 8 %)."""
    ifc = _post(shared_client, PATH, ROAD_IFC).json()
    xml = _post(shared_client, "/v1/alignments/assess/landxml", FEET_XML).json()
    a, b = ifc["vehicles"][0]["rows"], xml["vehicles"][0]["rows"]
    _same_rows(a, b, differ=frozenset({"superelevation_source"}))
    assert [r["superelevation_source"] for r in a] == ["cross-sections"] * 2
    assert [r["superelevation_source"] for r in b] == ["file"] * 2
    k1, k2 = a
    assert (k1["id"], k1["direction"], k2["id"], k2["direction"]) == ("K1", "right", "K2", "left")
    assert k1["radius_m"] == pytest.approx(250.5, rel=1e-12) and k2["radius_m"] == pytest.approx(180.0, rel=1e-12)
    assert k1["station_m"] == pytest.approx(360.0, rel=1e-12) and k2["station_m"] == pytest.approx(880.0, rel=1e-12)
    assert k1["deflection_deg"] == pytest.approx(math.degrees((160 + 60) / 250.5), rel=1e-12)
    assert k2["deflection_deg"] == pytest.approx(math.degrees((140 + 50) / 180), rel=1e-12)
    assert (k1["spiral_in_m"], k1["spiral_out_m"], k2["spiral_in_m"]) == pytest.approx((60.0, 60.0, 50.0), rel=1e-12)
    assert [r["superelevation_percent"] for r in a] == pytest.approx([7.5, 8.0], rel=1e-12)
    assert [r["grade_percent"] for r in a] == pytest.approx([3.5, 3.5], rel=1e-12)
    assert ifc["reading"]["alignments"] == xml["reading"]["alignments"] == ["Example road (synthetic): two curves"]
    assert (ifc["reading"]["linear_unit"], xml["reading"]["linear_unit"]) == ("metre", "foot")


def test_a_refused_schema_is_a_422_naming_it(shared_client):
    p = _post(shared_client, PATH, REFUSED.read_bytes(), status=422).json()
    (e,) = p["errors"]
    assert e["field"] == "body.FILE_SCHEMA" and e["location"] == "HEADER"
    assert "'IFC4X3_RC3'" in e["message"] and "IFC4X3_ADD2" in e["message"]
    body = {"vehicle": BTRAIN, "ifc": {"document": REFUSED.read_text(encoding="utf-8", errors="replace")}}
    (e,) = shared_client.post("/v1/alignments/assess", json=body).json()["errors"]
    assert e["field"] == "ifc.document.FILE_SCHEMA" and "'IFC4X3_RC3'" in e["message"]


def test_a_bad_segment_is_a_422_naming_the_entity_and_the_attribute(shared_client):
    # the first clothoid's length made negative: the reader names the attribute, the segment and its entities
    lines = ROAD_IFC.decode().split("\n")
    k = next(i for i, line in enumerate(lines) if "IFCALIGNMENTHORIZONTALSEGMENT(" in line and ".CLOTHOID." in line)
    head, args = lines[k].split("(", 1)
    args = args.split(",")
    args[6] = "-" + args[6]  # SegmentLength, the 7th attribute
    lines[k] = head + "(" + ",".join(args)
    bad = "\n".join(lines)
    (e,) = _post(shared_client, PATH, bad.encode(), status=422).json()["errors"]
    assert e["field"] == "body.SegmentLength"
    assert "horizontal segment 2" in e["location"] and "IfcAlignmentHorizontalSegment" in e["location"]
    r = shared_client.post(f"{PATH}?vehicle={BTRAIN}", files={"file": ("road.ifc", bad.encode())})
    assert r.status_code == 422 and r.json()["errors"][0]["field"] == "file.SegmentLength"


def test_an_empty_body_and_not_an_ifc_file_are_refused(shared_client):
    (e,) = _post(shared_client, PATH, b"  \n", status=422).json()["errors"]
    assert e["field"] == "body" and "empty" in e["message"]
    (e,) = _post(shared_client, PATH, b"<LandXML/>", status=422).json()["errors"]
    assert e["field"] == "body" and "ISO-10303-21" in e["message"]


def test_exactly_one_document(shared_client):
    body = {"vehicle": BTRAIN, "ifc": {"document": ROAD_IFC.decode()}, "landxml": {"document": FEET_XML.decode()}}
    r = shared_client.post("/v1/alignments/assess", json=body)
    assert r.status_code == 422
    assert "give exactly one of curves, csv, landxml, ifc" in r.json()["errors"][0]["message"]


# ------------------------------------------------------------------------------ random alignments both ways


def as_geometry(design: Design, cross_slopes: list[tuple[float, float]]) -> AlignmentGeometry:
    """The LandXML writer's design as the IFC writer's records: the same elements, its PVIs and symmetric
    parabolas as constant-grade and parabolic segments (a parabola of length L centred on its PVI), and
    ``cross_slopes`` ((distance [m], slope [%]) pairs) as the cant."""
    side = {"cw": "right", "ccw": "left"}
    H = HorizontalElement
    elements = []
    for e in design.elements:
        if e.kind == "Line":
            elements.append(H("line", e.length_m))
        elif e.kind == "Curve":
            elements.append(H("arc", e.length_m, e.radius_start_m, e.radius_end_m, side[e.rot], name=e.name))
        else:
            elements.append(
                H("spiral", e.length_m, e.radius_start_m, e.radius_end_m, side[e.rot], spiral_type="clothoid")
            )
    p = design.pvis
    x = [v.station_m - design.start_station_m for v in p]
    z = [v.elevation_m for v in p]
    g = [(z[k + 1] - z[k]) / (x[k + 1] - x[k]) for k in range(len(p) - 1)]
    segments, d = [], 0.0
    for k in range(len(p) - 1):
        half = p[k + 1].curve_m / 2  # the parabola at the next PVI, if any
        end = x[k + 1] - half
        segments.append(VerticalSegment("constant", d, end - d, z[k] + g[k] * (d - x[k]), g[k], g[k]))
        if half:
            segments.append(VerticalSegment("parabolic", end, 2 * half, z[k + 1] - g[k] * half, g[k], g[k + 1]))
        d = x[k + 1] + half
    slopes = tuple(CrossSlope(d, s, s) for d, s in cross_slopes)
    return AlignmentGeometry(
        design.name,
        design.start_station_m,
        tuple(elements),
        profiles=(Profile("Design", tuple(segments)),),
        cross_slopes=slopes,
    )


def random_pair(seed: int, n_bends: int = 4) -> tuple[str, bytes, str]:
    """One random alignment (tests/road/test_landxml_files.py's ``_design``: lines, clothoids, arcs, bends of
    clothoids only, compound curves, PVIs with parabolas) with random cross slopes, as LandXML (feet, its cross
    slopes as CrossSects) and as IFC 4.3 (metres, as cant)."""
    rng = random.Random(seed)
    design = _design(rng, n_bends)
    total = sum(e.length_m for e in design.elements)
    samples, d = [], 0.0
    while d < total:
        s = round(rng.uniform(-10, 10), 3)
        if samples and s != samples[-1][1] and abs(s) == abs(samples[-1][1]):
            continue  # a reversal of equal magnitude, which IfcOpenShell's cant mapping cannot write
        samples.append((d, s))
        d += rng.uniform(10, 200)
    samples.append((total, samples[-1][1]))
    sections = [(design.start_station_m + d, s, s, 3.5) for d, s in samples]
    xml = landxml(Design(design.name, design.start_station_m, design.elements, design.pvis, [], sections), "foot")
    return design.name, write_ifc([as_geometry(design, samples)]).decode(), xml


@pytest.mark.parametrize("seed", range(3))
def test_random_alignments_written_both_ways_give_the_same_rows(shared_client, seed):
    name, ifc, xml = random_pair(seed)
    q = f"vehicle={BTRAIN}&vehicle=table23-semitrailer&posted_speed_kmh=80"
    a = _post(shared_client, PATH, ifc.encode(), q).json()
    b = _post(shared_client, "/v1/alignments/assess/landxml", xml.encode(), q).json()
    assert a["curves"] == b["curves"] > 0
    for va, vb in zip(a["vehicles"], b["vehicles"], strict=True):
        _same_rows(va["rows"], vb["rows"])
        assert {r["superelevation_source"] for r in va["rows"]} == {"cross-sections"}
        assert {r["grade_source"] for r in va["rows"]} == {"profile"}
    for k in ("alignments", "profile", "superelevation_from"):
        assert a["reading"][k] == b["reading"][k], k
    assert a["reading"]["alignments"] == [name]


def test_an_escaped_name_is_read_whole(shared_client):
    """ISO 10303-21 is 7-bit text; another character is written as its code in ``\\X2\\ ... \\X0\\`` (hex UTF-16)."""
    escaped = "Rodovia S\\X2\\00E3\\X0\\o Jos\\X2\\00E9\\X0\\"
    text = ROAD_IFC.decode().replace("Example road (synthetic): two curves", escaped)
    out = _post(shared_client, PATH, text.encode()).json()
    assert out["reading"]["alignments"] == ["Rodovia São José"] and out["curves"] == 2


@pytest.mark.parametrize("encoding", ["utf-8", "utf-8-sig", "latin-1"])
def test_raw_utf_8_or_latin_1_and_a_byte_order_mark_are_read(shared_client, encoding):
    """Some writers put UTF-8 or Latin-1 in strings anyway, and an editor may add a byte-order mark: the upload is
    read (app/formats/uploads.py ``decode_step``), its rows those of the plain file, and the name keeps every letter
    (IfcOpenShell's parser drops raw characters outside ASCII: "Rodovia So Jos"), which the reading notes."""
    plain = _post(shared_client, PATH, ROAD_IFC).json()
    assert plain["reading"]["alignments"] == ["Example road (synthetic): two curves"]
    assert not any("ASCII" in n for n in plain["reading"]["notes"])
    text = ROAD_IFC.decode().replace("Example road (synthetic): two curves", "Rodovia São José")
    out = _post(shared_client, PATH, text.encode(encoding)).json()
    assert out["curves"] == 2
    _same_rows(out["vehicles"][0]["rows"], plain["vehicles"][0]["rows"])
    assert out["reading"]["alignments"] == ["Rodovia São José"]
    assert "Rodovia São José: characters outside ASCII written as they are" in " ".join(out["reading"]["notes"])


def test_raw_characters_beyond_the_basic_plane_and_in_element_names_are_read_whole():
    """A raw character beyond the Basic Multilingual Plane is escaped as ``\\X4\\`` (eight hex digits), one in
    it as ``\\X2\\``: both come back as written, in the alignment's and a curve's name."""
    from app.formats.ifc_io import read_ifc

    text = ROAD_IFC.decode().replace("Example road (synthetic): two curves", "Estrada \U0001f69b Süd")
    road = read_ifc(text.encode("utf-8"))
    assert road.alignments[0].name == "Estrada \U0001f69b Süd"
    first = next(e.name for e in road.alignments[0].elements if e.name)
    text = ROAD_IFC.decode().replace(f"'{first}'", f"'{first} – Curva São'")
    assert next(e.name for e in read_ifc(text.encode()).alignments[0].elements if e.name) == f"{first} – Curva São"


def test_the_published_example_is_the_landxml_examples_road(shared_client):
    """The OpenAPI example (app/alignments/schemas.py) is the LandXML example's road: the same radii, sides and
    deflections (120 / 250 and 90 / 400 rad) and the same stations: K2 starts where K1 ends, 200 + 120 = 320 m (the
    LandXML example once wrote K2's staStart as 380, a station its lengths contradict)."""
    from app.alignments.schemas import ALIGNMENT_IFC_EXAMPLE, ALIGNMENT_LANDXML_EXAMPLE

    q = f"vehicle={BTRAIN}&superelevation_percent=6"
    a = _post(shared_client, PATH, ALIGNMENT_IFC_EXAMPLE.encode(), q).json()["vehicles"][0]["rows"]
    b = _post(shared_client, "/v1/alignments/assess/landxml", ALIGNMENT_LANDXML_EXAMPLE.encode(), q).json()
    _same_rows(a, b["vehicles"][0]["rows"])
    assert [(r["id"], r["direction"], r["radius_m"]) for r in a] == [("K1", "right", 250.0), ("K2", "left", 400.0)]
    assert [r["deflection_deg"] for r in a] == pytest.approx([math.degrees(120 / 250), math.degrees(90 / 400)])
    assert [r["station_m"] for r in a] == pytest.approx([200.0, 320.0], rel=1e-12)
