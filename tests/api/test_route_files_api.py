"""POST /v1/routes/assess on routes as devices, routers and OSM write them: curves outside the model's domain are rows
with ``error`` (never a refusal of the document), a road without a curve is a 200, grades from elevations are
clipped to the domain with a flag or ignored (``use_elevation``), GPX parts are chosen (``parts``), OSM ways are
joined and their ``maxspeed`` read, and every answer carries its ``reading``.

Expected values: the synthetic routes are laid out exactly (tests/synthetic_routes.py: radii, lengths, a linear
elevation whose least-squares grade is its slope); the domain's bounds are :data:`engine.domain.BOUNDS`'s; a curve's
assessment is compared with ``POST /v1/alignments/assess`` of the same radius (the alignment endpoint, another entry);
the files' facts are read from their text (tests/data/routes/README.md).
"""

from __future__ import annotations

import csv
import io
import math
import re
from pathlib import Path

import pytest

from engine.domain import BOUNDS
from tests.synthetic_routes import Arc, Tangent, layout, to_lonlat

PATH = "/v1/routes/assess"
BTRAIN = "table16-btrain"
DATA = Path(__file__).resolve().parents[1] / "data" / "routes"
MIN_RADIUS_M = BOUNDS["radius_m"].minimum  # 5 m: the model's smallest radius
MAX_GRADE = BOUNDS["slope_percent"].maximum  # 20 %


def post(client, body, status=200, path=PATH, **headers):
    r = client.post(path, json=body, headers=headers)
    assert r.status_code == status, r.text
    return r


def upload(client, name, query="", status=200, **headers):
    kind = "geojson" if name.endswith("geojson") else "gpx"
    media = "application/geo+json" if kind == "geojson" else "application/gpx+xml"
    r = client.post(
        f"{PATH}/{kind}?vehicle={BTRAIN}&superelevation_percent=4&posted_speed_kmh=50{query}",
        content=(DATA / name).read_bytes(),
        headers={"content-type": media, **headers},
    )
    assert r.status_code == status, r.text
    return r


def coords(elements, spacing_m=1.0, grade=None, lat0=45.0):
    x, y, s = layout(elements, spacing_m)
    lon, lat = to_lonlat(x, y, lat0)
    if grade is None:
        return [[float(a), float(b)] for a, b in zip(lon, lat, strict=True)]
    return [[float(a), float(b), 100.0 + grade * float(c)] for a, b, c in zip(lon, lat, s, strict=True)]


def collection(*lines, **props):
    return {
        "type": "FeatureCollection",
        "features": [
            {"type": "Feature", "properties": props, "geometry": {"type": "LineString", "coordinates": c}}
            for c in lines
        ],
    }


#: a long road with a 4 m junction turn among three road curves (R 400, 250, 600 m)
JUNCTION = [
    Tangent(1500),
    Arc(400, 300, "left"),
    Tangent(1500),
    Arc(4, 2 * math.pi * 4 / 4, "right"),
    Tangent(1500),
    Arc(250, 250, "right"),
    Tangent(1500),
    Arc(600, 400, "left"),
    Tangent(1500),
]


def test_a_4m_junction_in_a_long_route_is_one_error_row_and_the_rest_assessed(shared_client):
    body = {"vehicle": BTRAIN, "superelevation_percent": 6, "posted_speed_kmh": 60,
            "geojson": collection(coords(JUNCTION))}  # fmt: skip
    out = post(shared_client, body).json()
    curves = out["curves"]
    assert [round(c["radius_m"]) for c in curves] == [400, 4, 250, 600]  # the layout's radii, found exactly
    errors = [c for c in curves if c["assessment"]["error"] is not None]
    assert [c["id"] for c in errors] == [curves[1]["id"]]
    bad = errors[0]["assessment"]
    assert "outside the model's domain" in bad["error"] and f"[{MIN_RADIUS_M:g}," in bad["error"]
    assert bad["flagged"] is True and bad["radius_m"] == pytest.approx(4.0, rel=1e-3)
    for name in ("srt_g", "rollover_speed_kmh", "side_friction_speed_kmh", "side_friction", "safe_speed_kmh",
                 "margin_kmh", "governed_by", "tilt_table_angle_deg"):  # fmt: skip
        assert bad[name] is None, name
    assert bad["superelevation_percent"] == 6.0 and bad["meets_standard_min_radius"] is False
    summary = out["vehicles"][0]["summary"]
    assert summary["curves"] == 4 and summary["refused"] == 1
    # the others: assessed as the alignment endpoint assesses a curve of the same radius
    rows = [{"id": c["id"], "radius_m": c["radius_lower_m"], "superelevation_percent": 6, "posted_speed_kmh": 60}
            for c in curves if c is not errors[0]]  # fmt: skip
    ref = post(shared_client, {"vehicle": BTRAIN, "curves": rows}, path="/v1/alignments/assess").json()
    got = [c["assessment"]["safe_speed_kmh"] for c in curves if c is not errors[0]]
    assert got == [r["safe_speed_kmh"] for r in ref["vehicles"][0]["rows"]]
    assert summary["min_safe_speed_kmh"] == min(got)
    # CSV and GeoJSON carry the same four curves, the error row with empty speeds
    table = list(csv.DictReader(io.StringIO(post(shared_client, body, accept="text/csv").text)))
    assert len(table) == 4 and table[1]["error"] and table[1]["safe_speed_kmh"] == ""
    assert table[1]["side_friction_speed_kmh"] == ""
    geo = post(shared_client, body, accept="application/geo+json").json()
    assert [f["properties"]["assessment"]["error"] is not None for f in geo["features"]] == [False, True, False, False]


def test_a_road_without_a_curve_answers_200_with_none(shared_client):
    body = {"vehicle": BTRAIN, "superelevation_percent": 6, "geojson": collection(coords([Tangent(2000)], 10.0))}
    out = post(shared_client, body).json()
    assert out["curves"] == [] and out["vehicles"][0]["summary"]["curves"] == 0
    assert out["reading"]["superelevation_from"] is None and out["parts"][0]["curves"] == 0
    text = post(shared_client, body, accept="text/csv").text
    assert len(text.strip().splitlines()) == 1  # the header only
    geo = post(shared_client, body, accept="application/geo+json").json()
    assert geo["features"] == [] and geo["reading"]["format"] == "GeoJSON"


CURVE = [Tangent(300), Arc(300, 300, "left"), Tangent(300)]


@pytest.mark.parametrize("grade", [0.10, 0.25, -0.3])
def test_grades_from_elevations_are_clipped_to_the_domain_with_a_flag(shared_client, grade):
    # a linear elevation: its least-squares grade over any stretch is its slope (a closed form), to within the
    # frame's scale at the track's height above the ellipsoid (distances grow by 1 + h/R: h < 500 m, under 1e-4)
    body = {"vehicle": BTRAIN, "superelevation_percent": 6, "geojson": collection(coords(CURVE, 2.0, grade))}
    out = post(shared_client, body).json()
    (c,) = out["curves"]
    assert c["grade_percent"] == pytest.approx(100 * grade, rel=1e-4) and c["grade_source"] == "elevations"
    clipped = abs(100 * grade) > MAX_GRADE
    assert c["grade_clipped"] is clipped
    used = math.copysign(MAX_GRADE, grade) if clipped else c["grade_percent"]
    assert c["assessment"]["grade_percent"] == pytest.approx(used, abs=1e-12)
    assert out["reading"]["profile"] == "elevations"


def test_use_elevation_false_takes_the_requests_grade(shared_client):
    doc = collection(coords(CURVE, 2.0, 0.25))
    base = {"vehicle": BTRAIN, "superelevation_percent": 6, "geojson": doc, "use_elevation": False}
    for given, expected in (({}, 0.0), ({"grade_percent": -3.0}, -3.0)):
        out = post(shared_client, {**base, **given}).json()
        (c,) = out["curves"]
        assert c["grade_percent"] is None and c["grade_source"] == "request" and c["grade_clipped"] is False
        assert c["assessment"]["grade_percent"] == expected and out["reading"]["profile"] is None
    post(shared_client, {**base, "grade_percent": 25}, 422)  # the request's own grade is bounded as everywhere


# ---------------------------------------------------------------------------------------- real files


def test_a_gpsbabel_download_with_an_empty_active_log(shared_client):
    text = (DATA / "cerknicko-jezero.gpx").read_text()
    out = upload(shared_client, "cerknicko-jezero.gpx").json()
    reading = out["reading"]
    assert reading["format"] == "GPX 1.0" and reading["writer"] == "GPSBabel - http://www.gpsbabel.org"
    assert reading["skipped"][0]["what"] == "trk[1] 'ACTIVE LOG' trkseg[1]"
    assert reading["elements"]["trkpt"] == len(re.findall(r"<trkpt\s", text))
    _rows_outside_the_domain_are_errors_and_the_rest_assessed(out)


def test_a_garmin_drive_with_a_car_park_manoeuvre(shared_client):
    out = upload(shared_client, "around-visnjan-with-car.gpx").json()
    assert out["reading"]["writer"] == "eTrex 20x"
    assert _rows_outside_the_domain_are_errors_and_the_rest_assessed(out) >= 1


def _rows_outside_the_domain_are_errors_and_the_rest_assessed(out) -> int:
    """Every curve whose conservative radius is below the domain's bound is an error row, every other is assessed
    (or refused for its own SRT reason, never for the domain); the number of error rows."""
    outside = 0
    for c in out["curves"]:
        a = c["assessment"]
        if c["radius_lower_m"] < MIN_RADIUS_M:
            outside += 1
            assert "outside the model's domain" in a["error"] and a["safe_speed_kmh"] is None and a["flagged"]
        else:
            assert a["error"] is None or "domain" not in a["error"]
            assert a["safe_speed_kmh"] is not None or a["error"] is not None
        assert c["assessment"]["grade_percent"] <= MAX_GRADE
    assert out["vehicles"][0]["summary"]["refused"] >= outside
    return outside


def test_a_routers_gpx_is_read_once_unless_parts_asks(shared_client):
    default = upload(shared_client, "sampleGraphHopper.gpx").json()["reading"]
    assert default["alignments"] == ["trk[1] 'GraphHopper Track' trkseg[1]"] and default["writer"] == "Graphhopper"
    assert [s["what"] for s in default["skipped"]] == ["rte[1]"]
    both = upload(shared_client, "sampleGraphHopper.gpx", "&parts=all").json()
    assert both["reading"]["alignments"] == ["trk[1] 'GraphHopper Track' trkseg[1]", "rte[1]"]
    assert both["reading"]["skipped"] == [] and [p["vertices"] for p in both["parts"]] == [59, 10]
    rte = upload(shared_client, "sampleGraphHopper.gpx", "&parts=rte").json()["reading"]
    assert rte["alignments"] == ["rte[1]"]
    upload(shared_client, "sampleGraphHopper.gpx", "&parts=lines", status=422)


def test_a_gpx_with_only_empty_parts_or_without_the_parts_asked_is_a_422(shared_client):
    empty = '<gpx version="1.1"><trk><name>ACTIVE LOG</name><trkseg></trkseg></trk></gpx>'
    p = post(shared_client, {"vehicle": BTRAIN, "superelevation_percent": 6, "gpx": empty}, 422).json()
    assert "no track or route" in p["detail"] and "ACTIVE LOG" in p["detail"]
    rte = '<gpx version="1.1"><rte><rtept lat="45" lon="10"/><rtept lat="45.001" lon="10"/></rte></gpx>'
    p = post(shared_client, {"vehicle": BTRAIN, "superelevation_percent": 6, "gpx": rte, "parts": "trk"}, 422).json()
    assert p["errors"][0]["field"] == "parts" and "no track" in p["errors"][0]["message"]


def test_an_overpass_export_is_assessed_as_roads_with_its_maxspeed(shared_client):
    out = upload(shared_client, "n240-markerwaardweg.overpass.geojson", "&max_superelevation_percent=8").json()
    reading = out["reading"]
    assert reading["writer"] == "overpass-ide" and reading["elements"]["LineString"] == 28
    joined = [p for p in out["parts"] if p["ways"]]
    assert sum(len(p["ways"]) for p in joined) + len(out["parts"]) - len(joined) == 28
    # every way of the export carries maxspeed 80 or 50 (or none): a curve's posted speed is one of them
    assert {c["assessment"]["posted_speed_kmh"] for c in out["curves"]} <= {80.0, 50.0}


def test_a_bend_across_two_osm_ways_is_one_curve_and_takes_the_larger_posted_speed(shared_client):
    x = coords([Tangent(300), Arc(200, 250, "left"), Tangent(300)], 5.0)
    mid = len(x) // 2  # inside the arc: the ways meet in the middle of the bend
    a, b = x[: mid + 1], x[mid:]

    def way(c, **props):
        return {"type": "Feature", "properties": {"highway": "primary", **props},
                "geometry": {"type": "LineString", "coordinates": c}}  # fmt: skip

    body = {"vehicle": BTRAIN, "superelevation_percent": 6}
    one = {
        "type": "FeatureCollection",
        "features": [way(a, name="X", maxspeed="30 mph"), way(b, name="X", maxspeed="40")],
    }
    out = post(shared_client, {**body, "geojson": one}).json()
    (c,) = out["curves"]
    assert c["radius_m"] == pytest.approx(200, rel=1e-3) and not c["truncated"]
    assert c["assessment"]["posted_speed_kmh"] == pytest.approx(max(30 * 1.609344, 40.0))
    assert out["parts"][0]["ways"] == ["features[0]", "features[1]"]
    # two roads meeting there (different names): the bend is cut where the ways end
    two = {"type": "FeatureCollection", "features": [way(a, name="X"), way(b, name="Y")]}
    cut = post(shared_client, {**body, "geojson": two}).json()
    assert len(cut["parts"]) == 2 and all(c["truncated"] for c in cut["curves"])


# ------------------------------------------------------------------------------------------- examples/

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def example(client, name, query=""):
    kind = "geojson" if name.endswith("geojson") else "gpx"
    media = "application/geo+json" if kind == "geojson" else "application/gpx+xml"
    r = client.post(
        f"{PATH}/{kind}?vehicle={BTRAIN}&superelevation_percent=7.5&posted_speed_kmh=60{query}",
        content=(EXAMPLES / name).read_bytes(),
        headers={"content-type": media},
    )
    assert r.status_code == 200, r.text
    return r.json()


def test_the_drive_example_reads_as_a_gps_download(shared_client):
    # examples/README.md: an empty ACTIVE LOG, a car park's 90-degree turn of R 4 m, then K1 (R 250.5 m) and K2
    # (R 180 m) 140 m further on (40 m + 6.3 m of turn + 100 m before the road), a router's <rte> beside the track
    out = example(shared_client, "drive.gpx")
    assert [s["what"] for s in out["reading"]["skipped"]] == [
        "trk[1] 'ACTIVE LOG' trkseg[1]",
        "rte[1] 'Example road (synthetic): two curves: turn points'",
    ]
    turn, k1, k2 = out["curves"]
    assert (
        turn["radius_m"] == pytest.approx(4.0, rel=1e-2) and "outside the model's domain" in turn["assessment"]["error"]
    )
    assert k1["radius_m"] == pytest.approx(250.5, rel=1e-3) and k2["radius_m"] == pytest.approx(180.0, rel=1e-3)
    lead = 40 + math.radians(90) * 4 + 100
    assert k1["start_m"] == pytest.approx(lead + 300, abs=2) and k2["start_m"] == pytest.approx(lead + 830, abs=2)
    assert k1["grade_percent"] == pytest.approx(3.5, rel=1e-3) and k1["assessment"]["error"] is None
    # read with its turn points, the router's straight lines between them make up curves that are not on the road
    both = example(shared_client, "drive.gpx", "&parts=all")
    assert len(both["curves"]) > 3 and both["reading"]["skipped"][0]["what"] == "trk[1] 'ACTIVE LOG' trkseg[1]"


def test_the_osm_ways_example_is_one_road_with_each_ways_maxspeed(shared_client):
    # examples/README.md: three ways (split inside K1 and between the curves): 45 mph, 70, BR:rural
    out = example(shared_client, "osm-ways.geojson")
    (part,) = out["parts"]
    assert part["ways"] == ["features[0]", "features[1]", "features[2]"]
    k1, k2 = out["curves"]
    assert k1["radius_m"] == pytest.approx(250.5, rel=1e-3) and not k1["truncated"]
    # K1 lies on the first two ways: the larger of 45 mph (1.609344 km each) and 70 km/h
    assert k1["assessment"]["posted_speed_kmh"] == pytest.approx(max(45 * 1.609344, 70.0))
    # K2's way says BR:rural (no number): the request's 60 km/h, and the reading says why
    assert k2["assessment"]["posted_speed_kmh"] == 60.0
    ((skipped),) = out["reading"]["skipped"]
    assert skipped["what"] == "features[2].properties.maxspeed 'BR:rural'" and "implicit" in skipped["why"]
