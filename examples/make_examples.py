"""Write the sample files of examples/: one road with two curves, as CSV (three dialects), LandXML, IFC 4.3, GPX and
GeoJSON.

    python examples/make_examples.py            # (re)write the files beside this script
    python examples/make_examples.py --check    # exit 1 if a committed file differs from what this writes

The road is laid out exactly (tests/synthetic_routes.py: tangents, clothoid spirals and circular arcs integrated
in a plane, then laid on the WGS84 ellipsoid keeping every segment's length and turning angle), so the radii the
route assessment should find are known:

* K1: a right-hand curve of radius 250.5 m (60 m spirals, 160 m of arc), from chainage 300 m;
* K2: a left-hand curve of radius 180 m (50 m spirals, 140 m of arc), from chainage 830 m;
* tangents of 300 m, 250 m and 300 m around them; a steady +3.5 % grade; a vertex every 10 m (a GIS
  centreline; no GPS noise), near Curitiba (PR, Brazil): a made-up road, not a survey.

The CSV files list the same two curves with a design superelevation, the grade and a posted speed; the LandXML
alignment has the same elements (lines, spirals, curves with their stations and points); alignment-feet.xml is the
same alignment in feet with its profile and superelevation, as a US design package exports it; the IFC 4.3 file has
them too, with the grade as its profile and the superelevation as its cant; the GPX track and the GeoJSON line carry
the vertices with their elevations.

Two more show the road as devices and OSM exports write it (docs/routes.md, "Files as devices and OSM write them"):

* ``drive.gpx``: a drive as a GPS download holds it: an empty ``ACTIVE LOG`` track first (as GPSBabel writes a
  Garmin download), then the track: a car park's 90-degree turn of radius 4 m (:data:`MANOEUVRE`) and 100 m of
  tangent before the road, and a router's ``<rte>`` of the turn points beside it;
* ``osm-ways.geojson``: the road as an Overpass export of OSM ``highway`` ways, split in three where tags change
  (inside K1 and between the curves), each with its ``maxspeed`` (:data:`WAYS`).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from tests.landxml_writer import Design, Element, Pvi, landxml  # noqa: E402
from tests.synthetic_routes import Arc, Tangent, layout, spiral_curve, to_lonlat  # noqa: E402

NAME = "Example road (synthetic): two curves"
LAT0, LON0 = -25.4300, -49.0200  # the first vertex
HEADING_DEG = 60.0  # of the first tangent, counter-clockwise from east
SPACING_M = 10.0
GRADE_PERCENT = 3.5
ELE0_M = 880.0

#: the curves: id, radius [m], arc length [m], spiral length [m], direction, superelevation [%], posted speed [km/h]
CURVES = [
    ("K1", 250.5, 160.0, 60.0, "right", 7.5, 70.0),
    ("K2", 180.0, 140.0, 50.0, "left", 8.0, 60.0),
]
TANGENTS_M = (300.0, 250.0, 300.0)

#: drive.gpx: a car park's turn before the road: tangent [m], radius [m], deflection [deg], tangent to the road [m]
MANOEUVRE = (40.0, 4.0, 90.0, 100.0)
#: osm-ways.geojson: each way's last vertex (index every SPACING_M; the last way runs to the end) and tags
WAYS = [
    (40, {"maxspeed": "45 mph"}),  # ends at 400 m: inside K1's arc (360-520 m)
    (70, {"maxspeed": "70"}),  # ends at 700 m: on the tangent between the curves
    (None, {"maxspeed": "BR:rural"}),  # an implicit limit: no number
]


def elements() -> list:
    out: list = [Tangent(TANGENTS_M[0])]
    for (_, r, arc, spiral, direction, _, _), tangent in zip(CURVES, TANGENTS_M[1:], strict=True):
        out += [*spiral_curve(r, arc, spiral, direction), Tangent(tangent)]
    return out


def curve_starts() -> list[float]:
    """Chainage [m] where each curve (its entry spiral) starts."""
    s, starts = TANGENTS_M[0], []
    for (_, _, arc, spiral, *_), tangent in zip(CURVES, TANGENTS_M[1:], strict=True):
        starts.append(s)
        s += 2 * spiral + arc + tangent
    return starts


def vertices() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """lon [deg], lat [deg], elevation [m] every SPACING_M along the road."""
    x, y, s = layout(elements(), SPACING_M, heading_deg=HEADING_DEG)
    lon, lat = to_lonlat(x, y, LAT0, LON0)
    return np.round(lon, 7), np.round(lat, 7), np.round(ELE0_M + GRADE_PERCENT / 100 * s, 2)


def _num(v: float) -> str:
    return f"{v:g}"


def csv_text(separator: str, decimal: str) -> str:
    rows = [("id", "radius_m", "superelevation_percent", "grade_percent", "posted_speed_kmh")]
    for cid, r, _, _, _, e, v in CURVES:
        rows.append((cid, *(_num(x).replace(".", decimal) for x in (r, e, GRADE_PERCENT, v))))
    return "".join(separator.join(row) + "\n" for row in rows)


def landxml_text() -> str:
    """The alignment as LandXML 1.2: Line, Spiral, Curve elements with stations and their points (northing
    easting in a local plane frame, metres)."""
    x, y, s = layout(elements(), 0.5, heading_deg=HEADING_DEG)

    def at(station: float) -> str:
        return f"{np.interp(station, s, y):.3f} {np.interp(station, s, x):.3f}"

    def center(station: float, r: float, direction: str) -> str:
        i = round(station / 0.5)
        dx, dy = x[i + 1] - x[i], y[i + 1] - y[i]
        n = math.hypot(dx, dy)
        side = 1.0 if direction == "left" else -1.0  # the centre lies to the left of a left-hand curve
        cx, cy = x[i] - side * r * dy / n, y[i] + side * r * dx / n
        return f"{cy:.3f} {cx:.3f}"

    items, sta = [], 0.0

    def line(length: float) -> None:
        nonlocal sta
        items.append(
            f'      <Line staStart="{sta:g}" length="{length:g}"><Start>{at(sta)}</Start>'
            f"<End>{at(sta + length)}</End></Line>"
        )
        sta += length

    line(TANGENTS_M[0])
    for (cid, r, arc, spiral, direction, _, _), tangent in zip(CURVES, TANGENTS_M[1:], strict=True):
        rot = "cw" if direction == "right" else "ccw"
        items.append(
            f'      <Spiral staStart="{sta:g}" length="{spiral:g}" radiusStart="INF" radiusEnd="{r:g}" rot="{rot}" '
            f'spiType="clothoid" name="{cid}-TS"><Start>{at(sta)}</Start><End>{at(sta + spiral)}</End></Spiral>'
        )
        sta += spiral
        items.append(
            f'      <Curve staStart="{sta:g}" length="{arc:g}" radius="{r:g}" rot="{rot}" name="{cid}">'
            f"<Start>{at(sta)}</Start><Center>{center(sta, r, direction)}</Center><End>{at(sta + arc)}</End></Curve>"
        )
        sta += arc
        items.append(
            f'      <Spiral staStart="{sta:g}" length="{spiral:g}" radiusStart="{r:g}" radiusEnd="INF" rot="{rot}" '
            f'spiType="clothoid" name="{cid}-ST"><Start>{at(sta)}</Start><End>{at(sta + spiral)}</End></Spiral>'
        )
        sta += spiral
        line(tangent)
    body = "\n".join(items)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2" date="2026-01-01" time="00:00:00">\n'
        '  <Units><Metric linearUnit="meter" areaUnit="squareMeter" volumeUnit="cubicMeter" '
        'angularUnit="decimal degrees" directionUnit="decimal degrees"/></Units>\n'
        "  <Alignments>\n"
        f'    <Alignment name="{NAME}" length="{sta:g}" staStart="0">\n'
        "     <CoordGeom>\n"
        f"{body}\n"
        "     </CoordGeom>\n"
        "    </Alignment>\n"
        "  </Alignments>\n"
        "</LandXML>\n"
    )


def ifc_bytes() -> bytes:
    """The alignment as IFC 4.3 (IFC4X3_ADD2), written with IfcOpenShell (tests/ifc_writer.py): the same lines,
    clothoids and arcs as the LandXML file, the +3.5 % grade as the profile, and the cross slope as a cant: -2 %
    (one-way crossfall, falling to the right) on the tangents, run off along the spirals to the full
    superelevation on the arcs (K1, right-hand: -7.5 %; K2, left-hand: +8 %)."""
    from engine.road import AlignmentGeometry, CrossSlope, HorizontalElement, Profile, VerticalSegment
    from tests.ifc_writer import write_ifc

    H = HorizontalElement
    els = [H("line", TANGENTS_M[0])]
    slopes, s = [CrossSlope(0.0, -2.0, -2.0)], TANGENTS_M[0]
    for (cid, r, arc, spiral, direction, e, _), tangent in zip(CURVES, TANGENTS_M[1:], strict=True):
        els += [
            H("spiral", spiral, math.inf, r, direction, spiral_type="clothoid", name=f"{cid}-TS"),
            H("arc", arc, r, r, direction, name=cid),
            H("spiral", spiral, r, math.inf, direction, spiral_type="clothoid", name=f"{cid}-ST"),
            H("line", tangent),
        ]
        full = e if direction == "left" else -e  # + rising from left to right: toward a left-hand curve's outside
        for d, slope in ((s, -2.0), (s + spiral, full), (s + spiral + arc, full), (s + 2 * spiral + arc, -2.0)):
            slopes.append(CrossSlope(d, slope, slope))
        s += 2 * spiral + arc + tangent
    slopes.append(CrossSlope(s, -2.0, -2.0))
    grade = GRADE_PERCENT / 100
    profile = Profile("design", (VerticalSegment("constant", 0.0, s, ELE0_M, grade, grade),))
    road = AlignmentGeometry(NAME, 0.0, tuple(els), profiles=(profile,), cross_slopes=tuple(slopes))
    return write_ifc([road], application=("rollover examples/make_examples.py", "1"), stable=True)


def landxml_feet_text() -> str:
    """The same road as a design package in the US writes it: LandXML in international feet, stations only on the
    alignment (the elements' from their lengths), the steady grade as a profile (two PVIs) and each curve's design
    superelevation as a ``Superelevation`` element over its arc (tests/landxml_writer.py)."""
    rot = {"right": "cw", "left": "ccw"}
    items = [Element("Line", TANGENTS_M[0])]
    supers, sta = [], TANGENTS_M[0]
    for (cid, r, arc, spiral, direction, e, _), tangent in zip(CURVES, TANGENTS_M[1:], strict=True):
        items += [
            Element("Spiral", spiral, math.inf, r, rot[direction], f"{cid}-TS"),
            Element("Curve", arc, r, r, rot[direction], cid),
            Element("Spiral", spiral, r, math.inf, rot[direction], f"{cid}-ST"),
            Element("Line", tangent),
        ]
        supers.append((sta + spiral, sta + spiral + arc, e))
        sta += 2 * spiral + arc + tangent
    profile = [Pvi(0.0, ELE0_M), Pvi(sta, ELE0_M + GRADE_PERCENT / 100 * sta)]
    design = Design(NAME, 0.0, items, profile, supers)
    return landxml(design, "foot", application="rollover examples/make_examples.py")


def gpx_text() -> str:
    lon, lat, ele = vertices()
    points = "\n".join(
        f'      <trkpt lat="{la:.7f}" lon="{lo:.7f}"><ele>{el:.2f}</ele></trkpt>'
        for lo, la, el in zip(lon.tolist(), lat.tolist(), ele.tolist(), strict=True)
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<gpx version="1.1" creator="rollover examples/make_examples.py" xmlns="http://www.topografix.com/GPX/1/1">\n'
        f"  <trk>\n    <name>{NAME}</name>\n    <trkseg>\n{points}\n    </trkseg>\n  </trk>\n</gpx>\n"
    )


def geojson_text() -> str:
    lon, lat, ele = vertices()
    points = zip(lon.tolist(), lat.tolist(), ele.tolist(), strict=True)
    coords = ",\n".join(f"        [{lo:.7f}, {la:.7f}, {el:.2f}]" for lo, la, el in points)
    props = json.dumps({"name": NAME})
    return (
        '{\n  "type": "FeatureCollection",\n  "features": [\n    {\n      "type": "Feature",\n'
        f'      "properties": {props},\n'
        '      "geometry": {\n        "type": "LineString",\n        "coordinates": [\n'
        f"{coords}\n        ]\n      }}\n    }}\n  ]\n}}\n"
    )


def drive_text() -> str:
    """The road as a GPS download: an empty track, the drive (a car park's turn, then the road) with elevations, and
    a router's turn points as a route."""
    lead, r, deflection, approach = MANOEUVRE
    turn = Arc(r, math.radians(deflection) * r, "left")
    els = [Tangent(lead), turn, Tangent(approach), *elements()]
    x, y, s = layout(els, 2.0, heading_deg=HEADING_DEG - deflection)
    lon, lat = to_lonlat(x, y, LAT0, LON0)
    ele = ELE0_M + GRADE_PERCENT / 100 * np.maximum(s - (lead + turn.length_m + approach), 0.0)
    points = "\n".join(
        f'      <trkpt lat="{la:.8f}" lon="{lo:.8f}"><ele>{el:.2f}</ele></trkpt>'
        for lo, la, el in zip(lon.tolist(), lat.tolist(), ele.tolist(), strict=True)
    )
    start = lead + turn.length_m + approach  # where the road begins
    turns = [0.0, lead, *(start + c for c in curve_starts()), float(s[-1])]
    rte = "\n".join(
        f'    <rtept lat="{np.interp(t, s, lat):.8f}" lon="{np.interp(t, s, lon):.8f}"><name>{k + 1}</name></rtept>'
        for k, t in enumerate(turns)
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<gpx version="1.1" creator="rollover examples/make_examples.py (a drive as a GPS download)" '
        'xmlns="http://www.topografix.com/GPX/1/1">\n'
        "  <trk>\n    <name>ACTIVE LOG</name>\n    <trkseg>\n    </trkseg>\n  </trk>\n"
        f"  <trk>\n    <name>{NAME}: a drive</name>\n    <trkseg>\n{points}\n    </trkseg>\n  </trk>\n"
        f"  <rte>\n    <name>{NAME}: turn points</name>\n{rte}\n  </rte>\n</gpx>\n"
    )


def osm_ways_text() -> str:
    """The road as an Overpass export of OSM ways (vertices without elevation, as OSM has none)."""
    lon, lat, _ = vertices()
    features, first = [], 0
    for k, (last, tags) in enumerate(WAYS):
        end = lon.size - 1 if last is None else last
        coords = [[lo, la] for lo, la in zip(lon[first : end + 1].tolist(), lat[first : end + 1].tolist(), strict=True)]
        props = {"@id": f"way/{k + 1}", "highway": "secondary", "name": NAME, "ref": "PR-000", **tags}
        geometry = {"type": "LineString", "coordinates": coords}
        features.append({"type": "Feature", "properties": props, "geometry": geometry, "id": f"way/{k + 1}"})
        first = end
    doc = {
        "type": "FeatureCollection",
        "generator": "rollover examples/make_examples.py (as overpass-turbo exports)",
        "copyright": "A made-up road (examples/README.md), not OpenStreetMap data.",
        "features": features,
    }
    return json.dumps(doc, indent=1) + "\n"


def files() -> dict[str, bytes]:
    """name -> bytes of every sample file."""
    semicolon = csv_text(";", ",").replace("\n", "\r\n")  # as a decimal-comma spreadsheet saves "CSV UTF-8"
    return {
        "curves-comma.csv": csv_text(",", ".").encode(),
        "curves-semicolon.csv": b"\xef\xbb\xbf" + semicolon.encode(),
        "curves-tab.tsv": csv_text("\t", ".").encode(),
        "alignment.xml": landxml_text().encode(),
        "road.ifc": ifc_bytes(),
        "alignment-feet.xml": landxml_feet_text().encode(),
        "road.gpx": gpx_text().encode(),
        "road.geojson": geojson_text().encode(),
        "drive.gpx": drive_text().encode(),
        "osm-ways.geojson": osm_ways_text().encode(),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed files instead of writing")
    args = parser.parse_args()
    stale = []
    for name, data in files().items():
        path = HERE / name
        if args.check:
            if not path.exists() or path.read_bytes() != data:
                stale.append(name)
        else:
            path.write_bytes(data)
    if stale:
        print(f"stale: {', '.join(stale)} (run python examples/make_examples.py)", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
