"""Route files as devices, routers and OSM exports write them (tests/data/routes/README.md names each file's source).

Every expected number is computed here from the file's own text by another route than the reader's: the points are
counted with a regular expression over the raw GPX (not its XML tree), the OSM ways' shared nodes are found in the
GeoJSON parsed by :mod:`json`, and the ``maxspeed`` conversions use the mile's and the nautical mile's definitions.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from app.formats.route_io import (
    MILE_M,
    NAUTICAL_MILE_M,
    RouteFormatError,
    join_ways,
    maxspeed_kmh,
    read_geojson,
    read_geojson_document,
    read_gpx_document,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "routes"

_POINT = re.compile(r'<(trkpt|rtept)\s+lat="([^"]+)"\s+lon="([^"]+)"')


def raw_segments(text: str, tag: str = "trkseg") -> list[list[tuple[str, str]]]:
    """Each ``<trkseg>`` (or ``<rte>``) of the raw text as its (lat, lon) strings, by regular expression."""
    out = []
    for body in re.findall(rf"<{tag}>(.*?)</{tag}>", text, re.S):
        out.append([(la, lo) for _, la, lo in _POINT.findall(body)])
    return out


def distinct(points: list[tuple[str, str]]) -> int:
    """Points left when consecutive repeats are dropped."""
    return sum(1 for i, p in enumerate(points) if i == 0 or p != points[i - 1])


def creator(text: str) -> str:
    return re.search(r'<gpx[^>]*\screator="([^"]*)"', text, re.S).group(1)


# --------------------------------------------------------------------------------------------- GPX


def test_a_gpsbabel_garmin_download_skips_its_empty_active_log_and_reads_the_rest():
    text = (DATA / "cerknicko-jezero.gpx").read_text()
    segs = raw_segments(text)
    read = read_gpx_document(text)
    assert read.format == "GPX 1.0" and read.writer == creator(text) == "GPSBabel - http://www.gpsbabel.org"
    empty = [i for i, s in enumerate(segs) if distinct(s) < 2]
    assert empty == [0]  # GPSBabel's empty "ACTIVE LOG" track
    wpt = len(re.findall(r"<wpt\s", text))
    assert wpt == 7 and [w for w, _ in read.skipped] == ["trk[1] 'ACTIVE LOG' trkseg[1]", f"wpt ({wpt})"]
    assert "has no points" in read.skipped[0][1] and read.elements["wpt"] == wpt
    assert [p.lon_deg.size for p in read.parts] == [distinct(s) for s in segs if distinct(s) >= 2]
    assert read.elements["trkpt"] == sum(len(s) for s in segs) and read.elements["trkseg"] == len(segs)


def test_a_garmin_device_track_is_read_whole():
    text = (DATA / "around-visnjan-with-car.gpx").read_text()
    (seg,) = raw_segments(text)
    read = read_gpx_document(text)
    assert read.writer == creator(text) == "eTrex 20x" and read.format == "GPX 1.1"
    assert read.skipped == [] and [p.lon_deg.size for p in read.parts] == [distinct(seg)]
    lats = np.array([float(la) for la, _ in seg])
    kept = read.parts[0].vertex_index
    assert np.array_equal(read.parts[0].lat_deg, lats[kept])


def test_an_empty_second_segment_is_skipped():
    text = (DATA / "track-with-empty-segment.gpx").read_text()
    segs = raw_segments(text)
    read = read_gpx_document(text)
    assert [len(s) for s in segs] == [9, 0]
    assert [p.lon_deg.size for p in read.parts] == [distinct(segs[0])]
    assert [w for w, _ in read.skipped] == ["trk[1] '2013-07-06T14:59:00Z' trkseg[2]"]


def test_a_routers_rte_beside_its_trk_is_skipped_unless_asked():
    text = (DATA / "sampleGraphHopper.gpx").read_text()
    (trk,) = raw_segments(text)
    (rte,) = raw_segments(text, "rte")
    assert (len(trk), len(rte)) == (60, 10)
    default = read_gpx_document(text)
    assert default.writer == "Graphhopper"
    assert [p.source for p in default.parts] == ["trk[1] 'GraphHopper Track' trkseg[1]"]
    assert default.parts[0].lon_deg.size == distinct(trk) == 59  # the last point is written twice
    ((what, why),) = default.skipped
    assert what == "rte[1]" and "turn points" in why and "parts=rte" in why
    both = read_gpx_document(text, parts="all")
    assert [p.lon_deg.size for p in both.parts] == [distinct(trk), distinct(rte)] and both.skipped == []
    only = read_gpx_document(text, parts="rte")
    assert [p.source for p in only.parts] == ["rte[1]"] and only.skipped == [("trk[1] 'GraphHopper Track' trkseg[1]",
                                                                               "parts=rte")]  # fmt: skip


def test_only_empty_parts_or_the_wrong_parts_are_refused_saying_so():
    empty = '<gpx version="1.1"><trk><name>ACTIVE LOG</name><trkseg></trkseg></trk><trk><name>B</name></trk></gpx>'
    with pytest.raises(RouteFormatError, match="no track or route with at least 2 distinct points") as e:
        read_gpx_document(empty)
    assert "trk[1] 'ACTIVE LOG' trkseg[1]: has no points" in str(e.value) and "trk[2] 'B': has no trkseg" in str(
        e.value
    )
    rte_only = '<gpx version="1.1"><rte><rtept lat="45" lon="10"/><rtept lat="45.001" lon="10"/></rte></gpx>'
    assert [p.source for p in read_gpx_document(rte_only).parts] == ["rte[1]"]  # no track: its route is read
    with pytest.raises(RouteFormatError, match="parts=trk: the file has no track") as e:
        read_gpx_document(rte_only, parts="trk")
    assert e.value.field == "parts"


# ------------------------------------------------------------------------------------------ maxspeed


@pytest.mark.parametrize(
    ("value", "kmh"),
    [
        ("50", 50.0),
        ("50 mph", 50 * 1.609344),  # the international mile: 1760 yd of 0.9144 m
        ("30mph", 30 * 1.609344),
        ("10 knots", 10 * 1.852),  # the international nautical mile: 1852 m
        ("80 km/h", 80.0),
        (120, 120.0),
    ],
)
def test_maxspeed_numbers_and_units(value, kmh):
    assert MILE_M == 1760 * 0.9144 and NAUTICAL_MILE_M == 1852.0
    got, why = maxspeed_kmh(value)
    assert why is None and got == pytest.approx(kmh, rel=1e-12)


@pytest.mark.parametrize(
    ("value", "words"),
    [
        ("none", "no numeric limit"),
        ("walk", "walking"),
        ("signals", "variable"),
        ("DE:urban", "country's implicit"),
        ("RU:rural", "country's implicit"),
        ("50;30", "several values"),
        ("fast", "not a number"),
        ("250", "outside (0, 200]"),
        ("0", "outside"),
    ],
)
def test_maxspeed_that_is_not_a_speed_says_why(value, words):
    got, why = maxspeed_kmh(value)
    assert got is None and words in why


def test_maxspeed_becomes_the_posted_speed_or_is_listed_as_skipped():
    def way(x0, maxspeed, **extra):
        coords = [[x0, 45.0], [x0 + 0.001, 45.0]]
        return {"type": "Feature", "properties": {"highway": "primary", "maxspeed": maxspeed, **extra},
                "geometry": {"type": "LineString", "coordinates": coords}}  # fmt: skip

    doc = {
        "type": "FeatureCollection",
        "generator": "osmtogeojson",
        "features": [
            way(10.0, "40 mph", name="A"),
            way(11.0, "DE:urban", name="B"),
            way(12.0, "50", name="C", posted_speed_kmh=70),  # the document's own posted speed wins
            {
                "type": "Feature",
                "properties": {"highway": "traffic_signals"},
                "geometry": {"type": "Point", "coordinates": [10.0, 45.0]},
            },
        ],
    }
    read = read_geojson_document(doc)
    assert read.writer == "osmtogeojson" and read.elements == {"LineString": 3, "Point": 1}
    posted = [p.properties.get("posted_speed_kmh") for p in read.parts]
    assert posted[0] == pytest.approx(40 * 1.609344) and posted[1] is None and posted[2] == 70
    assert [w for w, _ in read.skipped] == ["features[1].properties.maxspeed 'DE:urban'", "features[3]"]
    assert "a Point is not a line" in read.skipped[1][1]


# ------------------------------------------------------------------------------------------ OSM ways


def test_an_overpass_export_is_joined_into_roads_at_the_ways_shared_ends():
    raw = json.loads((DATA / "n240-markerwaardweg.overpass.geojson").read_text())
    feats = raw["features"]
    read = read_geojson_document(raw)
    assert read.writer == raw["generator"] == "overpass-ide"
    ways = [w for p in read.parts for w in (p.ways or (p.source,))]
    # every feature is in exactly one road
    assert sorted(w.removesuffix(" reversed") for w in ways) == sorted(f"features[{i}]" for i in range(len(feats)))
    vertices = sum(len(f["geometry"]["coordinates"]) for f in feats)
    joins = len(feats) - len(read.parts)
    assert sum(p.lon_deg.size for p in read.parts) == vertices - joins  # each shared node once (no repeats here)
    for p in read.parts:
        if p.ways is None:
            continue
        # consecutive ways of a road share the node where one ends and the next begins (in travel order)
        ends = []
        for w in p.ways:
            c = feats[int(re.search(r"\d+", w).group())]["geometry"]["coordinates"]
            ends.append((c[-1], c[0]) if w.endswith("reversed") else (c[0], c[-1]))
        assert all(ends[k][1] == ends[k + 1][0] for k in range(len(ends) - 1))
        first, last = ends[0][0], ends[-1][1]
        assert [p.lon_deg[0], p.lat_deg[0]] == first and [p.lon_deg[-1], p.lat_deg[-1]] == last
    # read by hand from the file: way/6576244 (features[2]) ends where way/6576246 (features[3]) starts, which ends
    # where way/6576247 (features[4], no maxspeed) starts; the one-way carriageway way/583363712 -> 583363710 ->
    # 142046796 -> 6576250 (features[18], [17], [14], [5]) runs in its drawn direction
    by_way = {w.removesuffix(" reversed"): (p, w) for p in read.parts for w in (p.ways or ())}
    road = by_way["features[2]"][0]
    assert by_way["features[3]"][0] is road and by_way["features[4]"][0] is road
    oneway = by_way["features[18]"][0]
    order = [w for w in oneway.ways if w in ("features[18]", "features[17]", "features[14]", "features[5]")]
    assert order == ["features[18]", "features[17]", "features[14]", "features[5]"]
    # the ways' own maxspeed stays on their own vertices
    spans = {props.get("@id"): props.get("posted_speed_kmh") for _, _, props in road.spans}
    assert spans["way/6576247"] is None and spans["way/6576246"] == 80.0


def _way(coords, **props):
    return {"type": "Feature", "properties": {"highway": "secondary", **props},
            "geometry": {"type": "LineString", "coordinates": coords}}  # fmt: skip


A, B, C, D = [10.0, 45.0], [10.001, 45.0], [10.002, 45.0], [10.002, 45.001]


@pytest.mark.parametrize(
    ("features", "roads"),
    [
        # end to end, same name: one road; drawn head to head (neither one-way): one road, one way reversed
        ([_way([A, B], name="X"), _way([B, C], name="X")], 1),
        ([_way([A, B], name="X"), _way([C, B], name="X")], 1),
        # head to head and one of them one-way: not a continuation in travel order
        ([_way([A, B], name="X", oneway="yes"), _way([C, B], name="X")], 2),
        # different roads meeting end to end stay apart; an unnamed continuation is unique: joined
        ([_way([A, B], name="X", ref="N1"), _way([B, C], name="Y", ref="N2")], 2),
        ([_way([A, B], name="X"), _way([B, C])], 1),
        # a junction: three ways end at B; the one with the same name continues
        ([_way([A, B], name="X"), _way([B, C], name="X"), _way([B, D], name="Z")], 2),
        # a junction where two continue the name: ambiguous, nothing joined there
        ([_way([A, B], name="X"), _way([B, C], name="X"), _way([B, D], name="X")], 3),
    ],
)
def test_which_ways_are_joined(features, roads):
    parts = read_geojson({"type": "FeatureCollection", "features": features})
    assert len(parts) == roads
    assert sum(p.lon_deg.size for p in parts) == sum(len(f["geometry"]["coordinates"]) for f in features) - (
        len(features) - roads
    )


def test_a_line_without_highway_is_never_joined():
    doc = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "X"}, "geometry": {"type": "LineString", "coordinates": [A, B]}},
        {"type": "Feature", "properties": {"name": "X"}, "geometry": {"type": "LineString", "coordinates": [B, C]}},
    ]}  # fmt: skip
    parts = read_geojson(doc)
    assert len(parts) == 2 and join_ways(parts) == parts
    assert all(p.ways is None and p.spans is None for p in parts)
    assert math.isclose(parts[0].length_m + parts[1].length_m, sum(p.length_m for p in parts))
