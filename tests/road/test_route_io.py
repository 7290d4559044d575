"""GeoJSON and GPX route readers: what they return, every refusal with its location, and a route read end to end."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import app.formats.route_io as rio
from app.formats.route_io import RouteFormatError, read_geojson, read_gpx
from engine.route.detect import find_curves
from engine.route.geodesy import local_frame
from tests.synthetic_routes import Arc, Tangent, layout, to_lonlat


def line(coords):
    return {"type": "LineString", "coordinates": coords}


def feature(geometry, **props):
    return {"type": "Feature", "properties": props or None, "geometry": geometry}


def collection(*features):
    return {"type": "FeatureCollection", "features": list(features)}


STRAIGHT = [[10.0, 45.0], [10.001, 45.0], [10.002, 45.0]]


def test_feature_collection_parts_properties_and_repeated_points():
    doc = collection(
        feature(
            line([[10.0, 45.0, 100.0], [10.0, 45.0, 100.0], [10.001, 45.0, 101.0], [10.002, 45.0, 102.0]]),
            name="A1 km 3",
            superelevation_percent=6,
            posted_speed_kmh=80,
        ),
        {
            "type": "Feature",
            "id": "ramp",
            "properties": {},
            "geometry": {"type": "MultiLineString", "coordinates": [STRAIGHT, [[11.0, 46.0], [11.0, 46.001]]]},
        },
    )
    parts = read_geojson(doc)
    assert [p.source for p in parts] == ["features[0]", "features[1] part 0", "features[1] part 1"]
    a = parts[0]
    assert a.location == "features[0].geometry.coordinates"
    assert a.properties["superelevation_percent"] == 6 and a.properties["name"] == "A1 km 3"
    assert a.vertex_index.tolist() == [0, 2, 3]  # the repeated point (a receiver standing still) is dropped
    assert a.ele_m.tolist() == [100.0, 101.0, 102.0]
    # 0.002 deg of longitude on the 45 deg parallel: 2 * N cos(45) * pi / 180 * 0.001 (N the prime vertical)
    n = 6378137.0 / math.sqrt(1 - 0.00669437999014 * 0.5)
    assert a.length_m == pytest.approx(0.002 * math.pi / 180 * n * math.cos(math.radians(45)), rel=1e-6)
    assert parts[1].properties["id"] == "ramp" and parts[1].ele_m is None
    assert parts[2].location == "features[1].geometry.coordinates[1]"


def test_bare_geometry_feature_and_json_text():
    assert read_geojson(line(STRAIGHT))[0].source == "geometry"
    assert read_geojson(feature(line(STRAIGHT)))[0].source == "feature"
    assert read_geojson(json.dumps(collection(feature(line(STRAIGHT)))))[0].lat_deg.size == 3


@pytest.mark.parametrize(
    ("coords", "location", "message"),
    [
        ([[10.0, 45.0]], "features[0].geometry.coordinates", "at least 2 distinct"),
        ([[10.0, 45.0], [10.0, 45.0], [10.0, 45.0]], "features[0].geometry.coordinates", "all 3 vertices are the same"),
        ([[10.0, 45.0], ["10.1", 45.0]], "features[0].geometry.coordinates[1]", "in numbers"),
        ([[10.0, 45.0], [10.1]], "features[0].geometry.coordinates[1]", "position"),
        ([[10.0, 45.0], [10.1, 45.0, 1.0, 2.0]], "features[0].geometry.coordinates[1]", "position"),
        ([[10.0, 45.0], [10.1, float("nan")]], "features[0].geometry.coordinates[1]", "finite"),
        ([[10.0, 45.0], [10.1, 45.0, float("inf")]], "features[0].geometry.coordinates[1]", "height must be finite"),
        ([[45.0, 10.0], [45.0, 93.5]], "features[0].geometry.coordinates[1]", "swapped"),
        ([[10.0, 45.0], [190.0, 45.0]], "features[0].geometry.coordinates[1]", "longitude 190.0"),
        ([[10.0, 45.0], [10.001, 45.0], [10.2, 45.0]], "features[0].geometry.coordinates[2]", "jumps 15.7 km"),
        ([[10.0, 45.0], [True, 45.0]], "features[0].geometry.coordinates[1]", "in numbers"),
    ],
)
def test_geojson_vertex_refusals_name_the_vertex(coords, location, message):
    with pytest.raises(RouteFormatError, match=message) as e:
        read_geojson(collection(feature(line(coords))))
    assert e.value.location == location


@pytest.mark.parametrize(
    ("doc", "location", "message"),
    [
        # in a collection, a feature without a line is skipped (an OSM export's nodes): none left is the refusal
        (
            collection(feature({"type": "Point", "coordinates": [10.0, 45.0]})),
            "features",
            r"no LineString or MultiLineString feature \(features\[0\]: a Point is not a line\)",
        ),
        (collection(feature(None)), "features", "a null geometry is not a line"),
        (feature({"type": "Point", "coordinates": [10.0, 45.0]}), "geometry.type", "not a line"),
        (collection({"type": "Polygon"}), "features[0]", "Feature"),
        ({"type": "FeatureCollection", "features": []}, "features", "non-empty"),
        ({"type": "GeometryCollection", "geometries": []}, "type", "expected FeatureCollection"),
        (
            collection(feature(line(STRAIGHT), superelevation_percent=25)),
            "features[0].properties.superelevation_percent",
            r"\[-20, 20\]",
        ),
        (collection(feature(line(STRAIGHT), posted_speed_kmh=0)), "features[0].properties.posted_speed_kmh", "0, 200"),
        (collection(feature(line(STRAIGHT), name={"a": 1})), "features[0].properties.name", "string"),
        (
            {**collection(feature(line(STRAIGHT))), "crs": {"type": "name", "properties": {"name": "EPSG:3857"}}},
            "crs",
            "not WGS84",
        ),
        # a bare geometry or Feature: the location is the JSON path from the document itself
        ({"type": "MultiLineString", "coordinates": []}, "coordinates", "non-empty"),
        ({"type": "LineString", "coordinates": [[10.0, 45.0], [10.0, 95.0]]}, "coordinates[1]", "latitude"),
        (feature(line([[10.0, 45.0]])), "geometry.coordinates", "at least 2"),
    ],
)
def test_geojson_document_refusals(doc, location, message):
    with pytest.raises(RouteFormatError, match=message) as e:
        read_geojson(doc)
    assert e.value.location == location


def test_not_json_and_not_an_object():
    with pytest.raises(RouteFormatError, match="not JSON"):
        read_geojson("{nope")
    with pytest.raises(RouteFormatError, match="GeoJSON object"):
        read_geojson([1, 2])


def test_size_limits(monkeypatch):
    n = len(STRAIGHT)
    two = collection(feature(line(STRAIGHT)), feature(line(STRAIGHT)))
    assert len(read_geojson(two, max_vertices=2 * n)) == 2  # the limit is inclusive
    with pytest.raises(rio.RouteTooLarge, match=f"more than {2 * n - 1} vertices in the document") as e:
        read_geojson(two, max_vertices=2 * n - 1)  # the document's total, counted part by part
    assert e.value.location == "features[1].geometry.coordinates"
    with pytest.raises(rio.RouteTooLarge, match=f"more than {n - 1} vertices") as e:
        read_geojson(two, max_vertices=n - 1)  # one part alone is too long: refused before it is read
    assert e.value.location == "features[0].geometry.coordinates"
    gpx = "<gpx><trk><trkseg>" + "".join(f'<trkpt lat="45" lon="{10 + i * 1e-4}"/>' for i in range(5)) + "</trkseg>"
    gpx += "</trk></gpx>"
    assert len(read_gpx(gpx, max_vertices=5)) == 1
    with pytest.raises(rio.RouteTooLarge, match="more than 4 points"):
        read_gpx(gpx, max_vertices=4)
    assert rio.MAX_VERTICES == 100_000  # a job's document; the synchronous request's is app.routes.schemas'
    monkeypatch.setattr(rio, "MAX_LENGTH_M", 300.0)  # each STRAIGHT is 157 m
    with pytest.raises(RouteFormatError, match=r"longer than 0\.3 km"):
        read_geojson(collection(feature(line(STRAIGHT)), feature(line(STRAIGHT))))
    monkeypatch.setattr(rio, "MAX_PARTS", 1)
    with pytest.raises(RouteFormatError, match="more than 1 features"):
        read_geojson(collection(feature(line(STRAIGHT)), feature(line(STRAIGHT))))


GPX = """<?xml version="1.0" encoding="UTF-8"?>
<gpx version="1.1" creator="test" xmlns="http://www.topografix.com/GPX/1/1">
  <wpt lat="45.0" lon="10.0"><name>ignored</name></wpt>
  <trk><name>A1</name>
    <trkseg>
      <trkpt lat="45.0" lon="10.0"><ele>100.5</ele></trkpt>
      <trkpt lat="45.0" lon="10.0"><ele>100.5</ele></trkpt>
      <trkpt lat="45.0" lon="10.001"><ele>101</ele></trkpt>
      <trkpt lat="45.0" lon="10.002"></trkpt>
    </trkseg>
    <trkseg>
      <trkpt lat="45.1" lon="10.0"/><trkpt lat="45.1" lon="10.001"/>
    </trkseg>
  </trk>
  <rte><rtept lat="46.0" lon="11.0"/><rtept lat="46.001" lon="11.0"/></rte>
</gpx>"""


def test_gpx_tracks_segments_routes():
    parts = read_gpx(GPX, parts="all")
    assert [p.source for p in parts] == ["trk[1] 'A1' trkseg[1]", "trk[1] 'A1' trkseg[2]", "rte[1]"]
    a = parts[0]
    assert a.vertex_index.tolist() == [0, 2, 3]
    assert a.ele_m[:2].tolist() == [100.5, 101.0] and math.isnan(a.ele_m[2])
    assert a.properties == {"name": "A1"}
    assert parts[1].ele_m is None and parts[2].properties == {}


@pytest.mark.parametrize(
    ("body", "location", "message"),
    [
        (
            '<trk><trkseg><trkpt lon="10"/><trkpt lat="45" lon="10.1"/></trkseg></trk>',
            "trk[1] trkseg[1] trkpt[1]",
            "lat",
        ),
        (
            '<trk><name>X</name><trkseg><trkpt lat="45" lon="10"/><trkpt lat="45" lon="east"/></trkseg></trk>',
            "trk[1] 'X' trkseg[1] trkpt[2]",
            "not a number",
        ),
        # a segment without a line is skipped and listed: with nothing else, the file is refused naming it
        ('<trk><trkseg><trkpt lat="45" lon="10"/></trkseg></trk>', "GPX", r"trk\[1\] trkseg\[1\]: has 1 vertex"),
        ("<trk><trkseg></trkseg></trk>", "GPX", r"no track or route .*trk\[1\] trkseg\[1\]: has no points"),
        ('<rte><rtept lat="10" lon="45"/><rtept lat="95" lon="45"/></rte>', "rte[1] rtept[2]", "swapped"),
        ('<rte><rtept lat="45" lon="10"/><rtept lat="45" lon="11"/></rte>', "rte[1] rtept[2]", "jumps 78.8 km"),
        (
            '<rte><rtept lat="45" lon="10"><ele>high</ele></rtept><rtept lat="45" lon="10.1"/></rte>',
            "rte[1] rtept[1]",
            "ele",
        ),
        ("<trk><name>Y</name></trk>", "GPX", "trk\\[1\\] 'Y': has no trkseg"),
        ('<wpt lat="45" lon="10"/>', "GPX", "no trk or rte"),
    ],
)
def test_gpx_refusals_name_the_point(body, location, message):
    doc = f'<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1">{body}</gpx>'
    with pytest.raises(RouteFormatError, match=message) as e:
        read_gpx(doc)
    assert e.value.location == location


def test_gpx_malformed_foreign_and_entities():
    with pytest.raises(RouteFormatError, match="malformed") as e:
        read_gpx("<gpx><trk></gpx>")
    assert e.value.location.startswith("GPX line 1")
    with pytest.raises(RouteFormatError, match="not <gpx>"):
        read_gpx("<kml/>")
    bomb = '<?xml version="1.0"?><!DOCTYPE g [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;">]><gpx>&b;</gpx>'
    with pytest.raises(RouteFormatError, match="entities are not allowed"):
        read_gpx(bomb)


def test_a_gpx_track_read_end_to_end():
    # a 250 m radius right-hand curve of 300 m between tangents, every 10 m at 60 deg N, written as GPX and
    # read back through the reader, the plane frame and the curve finder
    x, y, _ = layout([Tangent(500), Arc(250, 300, "right"), Tangent(500)], 10.0)
    lon, lat = to_lonlat(x, y, 60.0, 25.0)
    pts = "".join(
        f'<trkpt lat="{b:.9f}" lon="{a:.9f}"><ele>{20 + 0.03 * i * 10:.2f}</ele></trkpt>'
        for i, (a, b) in enumerate(zip(lon, lat, strict=True))
    )
    doc = f'<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>{pts}</trkseg></trk></gpx>'
    part = read_gpx(doc)[0]
    frame = local_frame(part.lon_deg, part.lat_deg, part.ele_m)
    curves = find_curves(frame.x_m, frame.y_m, frame.z_m).curves
    assert len(curves) == 1
    c = curves[0]
    assert c.direction == "right" and c.radius_m == pytest.approx(250, rel=0.01)
    assert c.grade_percent == pytest.approx(3.0, abs=0.3)
    # 9 decimal places of a degree are 0.1 mm: the vertices are those of the design
    assert np.allclose(part.vertex_index, np.arange(lon.size))
