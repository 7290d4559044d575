"""Write the sample files of examples/: one road with two curves, as CSV (three dialects), LandXML, GPX and GeoJSON.

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
same alignment in feet with its profile and superelevation, as a US design package exports it; the GPX track and the
GeoJSON line carry the vertices with their elevations.
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
from tests.synthetic_routes import Tangent, layout, spiral_curve, to_lonlat  # noqa: E402

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


def files() -> dict[str, bytes]:
    """name -> bytes of every sample file."""
    semicolon = csv_text(";", ",").replace("\n", "\r\n")  # as a decimal-comma spreadsheet saves "CSV UTF-8"
    return {
        "curves-comma.csv": csv_text(",", ".").encode(),
        "curves-semicolon.csv": b"\xef\xbb\xbf" + semicolon.encode(),
        "curves-tab.tsv": csv_text("\t", ".").encode(),
        "alignment.xml": landxml_text().encode(),
        "alignment-feet.xml": landxml_feet_text().encode(),
        "road.gpx": gpx_text().encode(),
        "road.geojson": geojson_text().encode(),
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
