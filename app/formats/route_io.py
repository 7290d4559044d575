"""Readers for route geometry: GeoJSON (RFC 7946) and GPX 1.1 (1.0 alike) -> WGS84 longitude/latitude/elevation lines.

:func:`read_gpx_document` and :func:`read_geojson_document` return a :class:`RouteRead`: the :class:`RoutePart` parts
read (one per GeoJSON ``LineString`` or ``MultiLineString`` part or joined OSM road, one per GPX track segment or
route) with each part's source label, properties and vertices, and what the answer's ``reading`` reports (format,
writer, the elements by type, and every part, feature or tag skipped with the reason); :func:`read_gpx` and
:func:`read_geojson` return the parts alone. They raise :class:`RouteFormatError` naming the part and the vertex
(``features[0].geometry.coordinates[17]``, ``trk[1] 'A1' trkseg[2] trkpt[18]``) and what is wrong. Nothing is
repaired or dropped silently: repeated consecutive points (a receiver standing still) are dropped
(``RoutePart.vertex_index`` maps each kept vertex back to its position in the source, so curves found on the part
can be mapped back to the file), and what is skipped is listed.

GeoJSON: a ``FeatureCollection`` of ``Feature``s, a ``Feature``, or a bare ``LineString`` /
``MultiLineString`` geometry. Positions are ``[longitude, latitude]`` or ``[longitude, latitude, height]``
(RFC 7946 section 3.1.1; height [m] above the WGS84 ellipsoid, section 4). A ``crs`` member (GeoJSON 2008)
other than CRS84 / EPSG:4326 is refused: only WGS84 longitude/latitude is read. A feature's ``properties``
may carry ``superelevation_percent`` ([-20, 20]), ``posted_speed_kmh`` ((0, 200]), ``name`` and ``id``; an OSM
``maxspeed`` is read as the posted speed where it is a speed (:func:`maxspeed_kmh`). In a collection, a feature
that is not a line (an export's nodes and areas) is skipped and listed; OSM ways (features with ``highway``) that
meet end to end are joined into one road (:func:`join_ways`).

GPX: every ``trk/trkseg`` (points ``trkpt``) and every ``rte`` (points ``rtept``), attributes ``lat`` and ``lon`` in
decimal degrees (WGS84, the GPX schema's datum) and an optional ``<ele>`` [m]. The part's properties hold its ``name``.
By default the tracks are read and the routes skipped when the file has a track (a router writes its turn points
as ``<rte>`` beside the geometry as ``<trk>``); ``parts`` (:data:`PARTS`) chooses. Tracks, segments and routes with
fewer than 2 distinct points are skipped and listed (GPSBabel's empty ``ACTIVE LOG``); a file with nothing else is
refused. Parsing refuses what defusedxml refuses (no external entities, no entity expansion;
:mod:`app.formats.xmlsafe`).

Limits (module constants, refused beyond them with the part named):

* ``MIN_VERTICES`` distinct vertices per part (2: a part with one point has no direction);
* ``MAX_SEGMENT_M`` between consecutive vertices (10 km): longer jumps are what swapped or corrupted
  coordinates produce, and they also bound the error of the engine's plane frame
  (:mod:`engine.route.geodesy`: below 1e-7 relative);
* ``MAX_VERTICES`` vertices (100,000: a job's; a reader's caller may set fewer, ``max_vertices``, as the
  synchronous request does) and ``MAX_PARTS`` parts (1,000) in one document, and ``MAX_LENGTH_M`` of route in all
  (1,000 km): they bound the work of one request (a 500 km route at 10 m spacing is 50,000 vertices). Beyond the
  vertices, :class:`RouteTooLarge` (a :class:`RouteFormatError`), so a caller can say where larger work goes.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field

import numpy as np

from app.formats import xmlsafe
from engine.route import segment_lengths_m

MIN_VERTICES = 2
MAX_SEGMENT_M = 10_000.0
MAX_VERTICES = 100_000
MAX_PARTS = 1_000
MAX_LENGTH_M = 1_000_000.0
#: property bounds (those of :func:`engine.road.curves.check_curve`)
SUPERELEVATION_LIMIT_PERCENT = 20.0
POSTED_SPEED_LIMIT_KMH = 200.0
_CRS84 = ("urn:ogc:def:crs:OGC:1.3:CRS84", "urn:ogc:def:crs:OGC::CRS84", "urn:ogc:def:crs:EPSG::4326", "EPSG:4326")


class RouteFormatError(ValueError):
    """Geometry that cannot be read as a route; ``location`` says where, ``field`` which member."""

    def __init__(self, message: str, location: str | None = None, field: str | None = None) -> None:
        super().__init__(f"{location}: {message}" if location else message)
        self.location = location
        self.field = field


@dataclass(frozen=True)
class RoutePart:
    """One polyline of a route document, repeated points dropped."""

    source: str  # "features[2]", "features[2] part 1", "trk[1] 'A1' trkseg[1]", "rte[1] 'Detour'"
    location: str  # path of its vertex list: "features[2].geometry.coordinates", "trk[1] 'A1' trkseg[1]"
    properties: dict = field(repr=False)
    lon_deg: np.ndarray = field(repr=False)
    lat_deg: np.ndarray = field(repr=False)
    ele_m: np.ndarray | None = field(repr=False)  # NaN where a vertex has none; None when none has one
    vertex_index: np.ndarray = field(repr=False)  # index of each kept vertex in the source list
    length_m: float = 0.0
    #: an OSM road joined from several ways: each way's (first vertex, last vertex, properties) in the part's vertex
    #: list (a curve takes its posted speed and superelevation from the ways it lies on), and the ways' sources in
    #: travel order (" reversed" where a way is drawn against it); None for a single line
    spans: tuple[tuple[int, int, dict], ...] | None = field(default=None, repr=False)
    ways: tuple[str, ...] | None = None


@dataclass(frozen=True)
class RouteRead:
    """What a reader made of a route document: the parts read and the facts the answer's ``reading`` reports
    (``format`` such as ``"GPX 1.1"`` or ``"GeoJSON"``; ``writer``: the GPX ``creator`` or the GeoJSON
    ``generator``; ``elements``: what the document holds, by type; ``skipped``: (what, why) for everything read but
    not used)."""

    format: str
    writer: str | None
    parts: list[RoutePart]
    elements: dict[str, int]
    skipped: list[tuple[str, str]]


class RouteTooLarge(RouteFormatError):
    """More vertices than the reader was allowed (``max_vertices``)."""


@dataclass
class _Budget:
    max_vertices: int = MAX_VERTICES
    vertices: int = 0
    length_m: float = 0.0

    def check_part(self, n: int, location: str, what: str = "vertices") -> None:
        """Refuse a part longer than the whole budget before reading it point by point."""
        if n > self.max_vertices:
            raise RouteTooLarge(f"more than {self.max_vertices:,} {what}", location)


def _vertex(location: str, i: int, style: str) -> str:
    return f"{location}[{i}]" if style == "json" else f"{location} {style}[{i + 1}]"


def _check_coordinates(location: str, style: str, lon: np.ndarray, lat: np.ndarray) -> None:
    """Refuse the first vertex whose coordinates are not finite WGS84 longitude/latitude, naming it."""
    for i in range(lon.size):  # a plain loop: the first bad vertex is the one to name
        lo, la = lon[i], lat[i]
        where = _vertex(location, i, style)
        if not (math.isfinite(lo) and math.isfinite(la)):
            raise RouteFormatError(f"coordinates must be finite numbers, got ({lo}, {la})", where, "coordinates")
        if abs(la) > 90.0:
            hint = " (longitude and latitude look swapped)" if abs(lo) <= 90.0 else ""
            raise RouteFormatError(f"latitude {la} is outside [-90, 90]{hint}", where, "latitude")
        if abs(lo) > 180.0:
            raise RouteFormatError(f"longitude {lo} is outside [-180, 180]", where, "longitude")


def _distinct(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """Indices of the vertices kept: repeated consecutive points dropped (a GPS standing still)."""
    keep = np.ones(lon.size, dtype=bool)
    keep[1:] = (lon[1:] != lon[:-1]) | (lat[1:] != lat[:-1])
    return np.flatnonzero(keep)


def _too_few(n: int, distinct: int) -> str:
    """Why a list of ``n`` points with ``distinct`` distinct ones is no line."""
    if n == 0:
        return "has no points"
    what = f"all {n} vertices are the same point" if n > 1 and distinct == 1 else f"has {n} vertex"
    return f"{what}; a route part needs at least {MIN_VERTICES} distinct vertices"


def _part(source, location, style, lon, lat, ele, properties, budget: _Budget, idx=None) -> RoutePart:
    """Checks shared by both formats; ``lon``/``lat``/``ele`` are float arrays (NaN ele: none); ``idx``: the distinct
    vertices when the caller has checked the coordinates already."""
    n = lon.size
    if idx is None:
        _check_coordinates(location, style, lon, lat)
        idx = _distinct(lon, lat)
    if idx.size < MIN_VERTICES:
        raise RouteFormatError(_too_few(n, idx.size), location)
    lon, lat = lon[idx], lat[idx]
    seg = segment_lengths_m(lon, lat)
    jumps = np.flatnonzero(seg > MAX_SEGMENT_M)
    if jumps.size:
        j = int(jumps[0])
        raise RouteFormatError(
            f"jumps {seg[j] / 1000:.1f} km from the previous vertex (at most {MAX_SEGMENT_M / 1000:g} km): "
            "corrupt or swapped coordinates?",
            _vertex(location, int(idx[j + 1]), style),
            "coordinates",
        )
    budget.vertices += idx.size
    budget.length_m += float(seg.sum())
    if budget.vertices > budget.max_vertices:
        raise RouteTooLarge(f"more than {budget.max_vertices:,} vertices in the document", location)
    if budget.length_m > MAX_LENGTH_M:
        raise RouteFormatError(f"the route is longer than {MAX_LENGTH_M / 1000:g} km", location)
    e = None
    if ele is not None and np.any(np.isfinite(ele)):
        e = ele[idx]
    return RoutePart(source, location, properties, lon, lat, e, idx, float(seg.sum()))


# ----------------------------------------------------------------------------------------- GeoJSON


def _number(v) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def _positions(coords, location: str, budget: _Budget) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    if not isinstance(coords, list):
        raise RouteFormatError("coordinates must be an array of positions", location, "coordinates")
    n = len(coords)
    budget.check_part(n, location)
    lon, lat, ele = np.empty(n), np.empty(n), np.full(n, np.nan)
    for i, pos in enumerate(coords):
        if not isinstance(pos, list) or not 2 <= len(pos) <= 3 or not all(_number(v) for v in pos):
            raise RouteFormatError(
                f"a position is [longitude, latitude] or [longitude, latitude, height] in numbers, got {pos!r}"[:200],
                f"{location}[{i}]",
                "coordinates",
            )
        lon[i], lat[i] = pos[0], pos[1]
        if len(pos) == 3:
            if not math.isfinite(pos[2]):
                raise RouteFormatError(f"height must be finite, got {pos[2]}", f"{location}[{i}]", "coordinates")
            ele[i] = pos[2]
    return lon, lat, ele


#: the international mile and nautical mile [m] (the international yard and pound agreement, 1959: 1 yd = 0.9144 m
#: exactly, so 1 mi = 1760 yd = 1609.344 m; the International Hydrographic Conference, 1929: 1 nmi = 1852 m)
MILE_M = 1609.344
NAUTICAL_MILE_M = 1852.0
#: OSM ``maxspeed`` units (wiki Key:maxspeed: a bare number is km/h; "mph" and "knots" follow the number)
_SPEED_UNITS = {"": 1.0, "km/h": 1.0, "kmh": 1.0, "kph": 1.0, "mph": MILE_M / 1000.0, "knots": NAUTICAL_MILE_M / 1000.0}
_MAXSPEED = re.compile(r"^\s*(\d+(?:\.\d+)?)\s*(km/h|kmh|kph|mph|knots)?\s*$")
_COUNTRY_CODE = re.compile(r"^[A-Z]{2}(-[A-Z0-9]{1,3})?:\S+$")
_WORDS = {
    "none": "no numeric limit (maxspeed=none)",
    "walk": "walking speed, no number (maxspeed=walk)",
    "signals": "a variable limit shown on signs (maxspeed=signals)",
    "variable": "a variable limit (maxspeed=variable)",
}


def maxspeed_kmh(value) -> tuple[float | None, str | None]:
    """An OSM ``maxspeed`` tag as a posted speed [km/h], or None and why it is not one.

    A bare number is km/h, ``"50 mph"`` 50 international miles an hour (1.609344 km), ``"10 knots"`` nautical miles
    (1.852 km) (OSM wiki, Key:maxspeed). ``none``, ``walk``, ``signals``, a country's implicit code (``DE:urban``,
    ``RO:rural``), several values (``50;30``) and anything else are not a number of km/h: None, with the reason; so is
    a speed outside (0, 200] km/h.
    """
    text = str(value).strip()
    m = _MAXSPEED.match(text)
    if m is None:
        low = text.lower()
        if low in _WORDS:
            return None, _WORDS[low]
        if _COUNTRY_CODE.match(text):
            return None, "a country's implicit limit code, not a number (it depends on the vehicle and road class)"
        if ";" in text:
            return None, "several values (by lane, time or direction): no single posted speed"
        return None, "not a number of km/h, mph or knots"
    kmh = float(m.group(1)) * _SPEED_UNITS[m.group(2) or ""]
    if not 0.0 < kmh <= POSTED_SPEED_LIMIT_KMH:
        return None, f"{kmh:g} km/h is outside (0, {POSTED_SPEED_LIMIT_KMH:g}] km/h"
    return kmh, None


def _properties(props, where: str, skipped: list[tuple[str, str]]) -> dict:
    if props is None:
        return {}
    if not isinstance(props, dict):
        raise RouteFormatError("properties must be an object or null", where, "properties")
    out = dict(props)
    for key, lo, hi, open_lo in (
        ("superelevation_percent", -SUPERELEVATION_LIMIT_PERCENT, SUPERELEVATION_LIMIT_PERCENT, False),
        ("posted_speed_kmh", 0.0, POSTED_SPEED_LIMIT_KMH, True),
    ):
        v = props.get(key)
        if v is None:
            continue
        ok = _number(v) and math.isfinite(v) and (lo < v if open_lo else lo <= v) and v <= hi
        if not ok:
            bounds = f"({lo:g}, {hi:g}]" if open_lo else f"[{lo:g}, {hi:g}]"
            raise RouteFormatError(f"{key} must be a number in {bounds} or null, got {v!r}", f"{where}.{key}", key)
    for key in ("name", "id"):
        v = props.get(key)
        if v is not None and not isinstance(v, str | int | float):
            raise RouteFormatError(f"{key} must be a string or a number, got {type(v).__name__}", f"{where}.{key}", key)
    if out.get("posted_speed_kmh") is None and out.get("maxspeed") is not None:
        kmh, why = maxspeed_kmh(out["maxspeed"])
        if kmh is None:
            what = f"{where}.maxspeed {str(out['maxspeed'])[:40]!r}"
            skipped.append((what, f"{why}: the request's posted speed applies"))
        else:
            out["posted_speed_kmh"] = kmh
    return out


def _listed(skipped: list[tuple[str, str]], at_most: int = 5) -> str:
    """What was skipped, for a refusal's message: the first ``at_most`` and how many more."""
    text = "; ".join(f"{w}: {y}" for w, y in skipped[:at_most])
    return text + (f"; and {len(skipped) - at_most} more" if len(skipped) > at_most else "")


def _at(where: str, name: str) -> str:
    """The JSON path of ``name`` inside the object at ``where`` ("" is the document itself)."""
    return f"{where}.{name}" if where else name


_LINES = ("LineString", "MultiLineString")


def _geometry(geom, where: str, source: str, props: dict, budget: _Budget) -> list[RoutePart]:
    if not isinstance(geom, dict):
        raise RouteFormatError("the geometry must be a LineString or MultiLineString object", where, "geometry")
    kind = geom.get("type")
    loc = _at(where, "coordinates")
    if kind == "LineString":
        lon, lat, ele = _positions(geom.get("coordinates"), loc, budget)
        return [_part(source, loc, "json", lon, lat, ele, props, budget)]
    if kind == "MultiLineString":
        lines = geom.get("coordinates")
        if not isinstance(lines, list) or not lines:
            raise RouteFormatError("coordinates must be a non-empty array of lines", loc, "coordinates")
        out = []
        for j, line in enumerate(lines):
            lon, lat, ele = _positions(line, f"{loc}[{j}]", budget)
            out.append(_part(f"{source} part {j}", f"{loc}[{j}]", "json", lon, lat, ele, props, budget))
        return out
    raise RouteFormatError(
        f"geometry type {kind!r} is not a line; a route is a LineString or MultiLineString", _at(where, "type"), "type"
    )


def read_geojson_document(doc, *, max_vertices: int = MAX_VERTICES) -> RouteRead:
    """Route parts from a GeoJSON object (parsed, or as JSON text), at most ``max_vertices`` vertices in all, and what
    was skipped: in a ``FeatureCollection`` a feature without a line (an OSM export's nodes and areas) is skipped and
    listed; OSM ways (features with a ``highway`` property) that meet end to end are joined into one road
    (:func:`join_ways`); see the module docstring."""
    if isinstance(doc, str | bytes):
        try:
            doc = json.loads(doc)
        except ValueError as exc:
            raise RouteFormatError(f"not JSON: {exc}", "geojson") from None
    if not isinstance(doc, dict):
        raise RouteFormatError("a GeoJSON object is expected", "geojson")
    crs = doc.get("crs")
    if crs is not None:
        name = (crs.get("properties") or {}).get("name") if isinstance(crs, dict) else None
        if name not in _CRS84:
            raise RouteFormatError(f"crs {name!r} is not WGS84 longitude/latitude (CRS84)", "crs", "crs")
    generator = doc.get("generator")
    writer = generator.strip()[:200] if isinstance(generator, str) and generator.strip() else None
    budget, skipped = _Budget(max_vertices=max_vertices), []
    kind = doc.get("type")
    if kind == "FeatureCollection":
        feats = doc.get("features")
        if not isinstance(feats, list) or not feats:
            raise RouteFormatError("features must be a non-empty array", "features", "features")
        if len(feats) > MAX_PARTS:
            raise RouteFormatError(f"more than {MAX_PARTS} features", "features")
        items = [(f, f"features[{i}]") for i, f in enumerate(feats)]
    elif kind == "Feature":
        items = [(doc, "")]  # the document itself: its paths start at its members
    elif kind in _LINES:
        parts = _geometry(doc, "", "geometry", {}, budget)
        return RouteRead("GeoJSON", writer, parts, {kind: 1}, skipped)
    else:
        raise RouteFormatError(
            f"type {kind!r}: expected FeatureCollection, Feature, LineString or MultiLineString", "type", "type"
        )
    parts: list[RoutePart] = []
    elements: dict[str, int] = {}
    collection = kind == "FeatureCollection"
    for feat, where in items:
        if not isinstance(feat, dict) or feat.get("type") != "Feature":
            raise RouteFormatError("must be a Feature object", where, "type")
        geom = feat.get("geometry")
        gtype = geom.get("type") if isinstance(geom, dict) else None
        label = gtype if isinstance(gtype, str) else "no geometry"
        elements[label] = elements.get(label, 0) + 1
        if collection and gtype not in _LINES and (geom is None or isinstance(gtype, str)):
            # an export's points (an OSM node with tags) and areas: not a road's line
            skipped.append((where, f"{'a ' + gtype if gtype else 'a null geometry'} is not a line"))
            continue
        props = _properties(feat.get("properties"), _at(where, "properties"), skipped)
        if "id" in feat and "id" not in props:
            props["id"] = feat["id"]
        parts.extend(_geometry(geom, _at(where, "geometry"), where or "feature", props, budget))
    if len(parts) > MAX_PARTS:
        raise RouteFormatError(f"more than {MAX_PARTS} line parts", "features")
    if not parts:
        raise RouteFormatError(f"no LineString or MultiLineString feature ({_listed(skipped)})", "features", "features")
    joined = join_ways(parts)
    if len(joined) < len(parts):
        elements["roads joined from OSM ways"] = sum(1 for p in joined if p.ways is not None)
    return RouteRead("GeoJSON", writer, joined, elements, skipped)


def read_geojson(doc, *, max_vertices: int = MAX_VERTICES) -> list[RoutePart]:
    """The parts of :func:`read_geojson_document`."""
    return read_geojson_document(doc, max_vertices=max_vertices).parts


# ------------------------------------------------------------------------------------------ OSM ways


def _is_way(p: RoutePart) -> bool:
    """An OSM way as Overpass and osmtogeojson export it: a line feature with a ``highway`` tag."""
    return p.properties.get("highway") is not None and p.ways is None and " part " not in p.source


def _oneway(p: RoutePart) -> bool:
    return str(p.properties.get("oneway", "")).lower() in ("yes", "true", "1", "-1", "reversible")


def _names(p: RoutePart) -> set[tuple[str, str]]:
    """What names the road a way belongs to: its ``ref`` and its ``name``."""
    return {(k, str(p.properties[k]).strip()) for k in ("ref", "name") if str(p.properties.get(k) or "").strip()}


def _pair(ends: list[tuple[int, int]], parts: list[RoutePart]) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """The two way ends at one node that continue each other, or None. Ends of two different ways continue when one
    ends where the other starts (or both end or both start there and neither is one-way: one is drawn the other way
    round), and they are the same road: at a node where only those two ways end, when their ref and name do not
    contradict; at a junction (three ends or more), the one such pair with the same ref or name."""
    candidates = []
    for a in range(len(ends)):
        for b in range(a + 1, len(ends)):
            (i, si), (j, sj) = ends[a], ends[b]
            if i == j:
                continue
            if si == sj and (_oneway(parts[i]) or _oneway(parts[j])):
                continue
            candidates.append((ends[a], ends[b]))
    if len(ends) == 2 and len(candidates) == 1:
        (i, _), (j, _) = candidates[0]
        ni, nj = _names(parts[i]), _names(parts[j])
        return candidates[0] if not (ni and nj and not ni & nj) else None
    same = [c for c in candidates if _names(parts[c[0][0]]) & _names(parts[c[1][0]])]
    return same[0] if len(same) == 1 else None


def _chains(links: dict[tuple[int, int], tuple[int, int]], ways: list[int]) -> list[list[tuple[int, bool]]]:
    """The joined roads: each a list of (way, reversed) in travel order; a closed loop is opened at its first way."""
    seen: set[int] = set()
    out = []
    starts = [(i, s) for i in ways for s in (0, 1) if (i, s) not in links]
    starts += [(i, 0) for i in ways]  # loops: every end linked
    for i, side in starts:
        if i in seen:
            continue
        chain = []
        while i not in seen:
            seen.add(i)
            chain.append((i, side == 1))  # entered at its end: travelled from its last vertex to its first
            nxt = links.get((i, 1 - side))
            if nxt is None:
                break
            i, side = nxt
        out.append(chain)
    return out


def _joined(parts: list[RoutePart], chain: list[tuple[int, bool]]) -> RoutePart:
    """One road from its ways in travel order: vertices concatenated (each shared node once)."""
    # travel along the one-way ways' own direction (else along most of the ways' drawn direction)
    judged = [(parts[i].length_m, rev) for i, rev in chain if _oneway(parts[i])] or [
        (parts[i].length_m, rev) for i, rev in chain
    ]
    if sum(n for n, rev in judged if rev) > sum(n for n, rev in judged if not rev):
        chain = [(i, not rev) for i, rev in reversed(chain)]
    lons, lats, eles, spans, ways = [], [], [], [], []
    n = 0
    has_ele = any(parts[i].ele_m is not None for i, _ in chain)
    for k, (i, rev) in enumerate(chain):
        p = parts[i]
        order = slice(None, None, -1) if rev else slice(None)
        lo, la = p.lon_deg[order], p.lat_deg[order]
        e = p.ele_m[order] if p.ele_m is not None else np.full(lo.size, np.nan)
        skip = 1 if k else 0  # the node shared with the previous way
        lons.append(lo[skip:])
        lats.append(la[skip:])
        eles.append(e[skip:])
        first = max(n - 1, 0)
        n += lo.size - skip
        spans.append((first, n - 1, p.properties))
        ways.append(p.source + (" reversed" if rev else ""))
    first = parts[chain[0][0]]
    names = {k: v for k, v in first.properties.items() if k in ("name", "ref", "highway")}
    lon, lat = np.concatenate(lons), np.concatenate(lats)
    ele = np.concatenate(eles) if has_ele else None
    source = f"{first.source} +{len(chain) - 1} way{'s' if len(chain) > 2 else ''}"
    length = float(sum(parts[i].length_m for i, _ in chain))
    index = np.arange(lon.size)
    return RoutePart(source, first.location, names, lon, lat, ele, index, length, tuple(spans), tuple(ways))


def join_ways(parts: list[RoutePart]) -> list[RoutePart]:
    """OSM ways that meet end to end joined into one road, so that a bend is not cut where a way ends.

    An OSM export splits a road into ways wherever a tag changes (a bridge, a speed limit, a lane count); two ways
    of one road share their end node, whose coordinates are written identically in both. Ways are joined at a node
    where they continue each other (:func:`_pair`); everything else (a single line, a feature without ``highway``,
    a way meeting no continuation) is left as it is. The joined road keeps each way's properties over its own
    vertices (``RoutePart.spans``) and lists its ways (``RoutePart.ways``); it lies where its first way lay in the
    document's order."""
    ways = [i for i, p in enumerate(parts) if _is_way(p)]
    if len(ways) < 2:
        return parts
    nodes: dict[tuple[float, float], list[tuple[int, int]]] = {}
    for i in ways:
        p = parts[i]
        for side, k in ((0, 0), (1, -1)):
            nodes.setdefault((float(p.lon_deg[k]), float(p.lat_deg[k])), []).append((i, side))
    links: dict[tuple[int, int], tuple[int, int]] = {}
    for ends in nodes.values():
        pair = _pair(ends, parts) if len(ends) >= 2 else None
        if pair is not None:
            a, b = pair
            links[a], links[b] = b, a
    if not links:
        return parts
    road_of: dict[int, RoutePart | None] = {}
    for chain in _chains(links, ways):
        if len(chain) == 1:
            continue
        road_of[min(i for i, _ in chain)] = _joined(parts, chain)
        for i, _ in chain:
            road_of.setdefault(i, None)
    out = []
    for i, p in enumerate(parts):
        if i not in road_of:
            out.append(p)
        elif road_of[i] is not None:
            out.append(road_of[i])
    return out


# --------------------------------------------------------------------------------------------- GPX


def _child_text(el, name: str) -> str | None:
    for c in el:
        if xmlsafe.local(c.tag) == name:
            return (c.text or "").strip()
    return None


def _gpx_points(points: list, label: str, tag: str, budget: _Budget) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = len(points)
    budget.check_part(n, label, "points")
    lon, lat, ele = np.empty(n), np.empty(n), np.full(n, np.nan)
    for i, pt in enumerate(points):
        where = f"{label} {tag}[{i + 1}]"
        for attr, arr in (("lat", lat), ("lon", lon)):
            text = pt.get(attr)
            if text is None:
                raise RouteFormatError(f"has no {attr} attribute", where, attr)
            try:
                arr[i] = float(text)
            except ValueError:
                raise RouteFormatError(f"{attr} is not a number: {text!r}", where, attr) from None
        e = _child_text(pt, "ele")
        if e:
            try:
                ele[i] = float(e)
            except ValueError:
                raise RouteFormatError(f"ele is not a number: {e!r}", where, "ele") from None
            if not math.isfinite(ele[i]):
                raise RouteFormatError(f"ele must be finite, got {e!r}", where, "ele")
    return lon, lat, ele


#: which GPX parts are read: ``trk`` (track segments: the geometry a device logged or a router drew), ``rte`` (routes:
#: a plan's or a router's turn points), ``all``; None: the tracks when the file has any, else its routes
PARTS = ("trk", "rte", "all")

_WHY_RTE = (
    "the file also has a track: a router writes the turn points as <rte> beside the geometry as <trk>, and turn "
    "points joined by straight lines make up curves that are not on the road (parts=rte or parts=all reads it)"
)


@dataclass
class _Candidate:
    kind: str  # "trk" or "rte"
    label: str
    tag: str
    lon: np.ndarray
    lat: np.ndarray
    ele: np.ndarray
    props: dict
    idx: np.ndarray


def read_gpx_document(text: str | bytes, *, parts: str | None = None, max_vertices: int = MAX_VERTICES) -> RouteRead:
    """Route parts from a GPX document (1.1, or 1.0: the same elements), at most ``max_vertices`` vertices in the parts
    read, and what was skipped.

    ``parts`` (:data:`PARTS`): which of the tracks and routes are read; by default the tracks, and the routes only
    when the file has no track with points. A track with no segment, a segment or route with fewer than 2 distinct
    points (GPSBabel writes an empty ``ACTIVE LOG`` track in every Garmin download) is skipped and listed; a file
    with nothing else is refused, naming what it holds.
    """
    if parts is not None and parts not in PARTS:
        raise RouteFormatError(f"parts must be one of {', '.join(PARTS)}, got {parts!r}", "parts", "parts")
    with xmlsafe.collection_paused():  # the tree's million elements: no collector passes, freed in slices
        root = xmlsafe.document(text, "gpx", "GPX", RouteFormatError)
        try:
            return _gpx_read(root, parts, max_vertices)
        finally:
            xmlsafe.free(root)


def _gpx_read(root, parts: str | None, max_vertices: int) -> RouteRead:
    version = (root.get("version") or "").strip()
    fmt = f"GPX {version}" if version in ("1.0", "1.1") else "GPX"
    creator = (root.get("creator") or "").strip()
    budget, skipped = _Budget(max_vertices=max_vertices), []
    elements = {"trk": 0, "trkseg": 0, "trkpt": 0, "rte": 0, "rtept": 0, "wpt": 0}
    found: list[_Candidate] = []
    for el in root:
        kind = xmlsafe.local(el.tag)
        if kind == "wpt":
            elements["wpt"] += 1
        if kind not in ("trk", "rte"):
            continue
        elements[kind] += 1
        name = _child_text(el, "name")
        named = f" {name!r}" if name else ""
        props = {"name": name} if name else {}
        if kind == "trk":
            label = f"trk[{elements['trk']}]{named}"
            segs = [s for s in el if xmlsafe.local(s.tag) == "trkseg"]
            if not segs:
                skipped.append((label, "has no trkseg (an empty track)"))
            pieces = [(f"{label} trkseg[{j}]", "trkpt", seg) for j, seg in enumerate(segs, start=1)]
        else:
            label = f"rte[{elements['rte']}]{named}"
            pieces = [(label, "rtept", el)]
        for where, tag, holder in pieces:
            if tag == "trkpt":
                elements["trkseg"] += 1
            points = [p for p in holder if xmlsafe.local(p.tag) == tag]
            elements[tag] += len(points)
            lon, lat, ele = _gpx_points(points, where, tag, budget)
            _check_coordinates(where, tag, lon, lat)
            idx = _distinct(lon, lat)
            if idx.size < MIN_VERTICES:
                empty = "an empty segment" if tag == "trkpt" else "an empty route"
                skipped.append((where, f"{_too_few(len(points), idx.size)} ({empty})"))
                continue
            found.append(_Candidate(kind, where, tag, lon, lat, ele, props, idx))
        if len(found) > MAX_PARTS:
            raise RouteFormatError(f"more than {MAX_PARTS} tracks, segments and routes", "GPX")
    if elements["wpt"]:
        skipped.append((f"wpt ({elements['wpt']})", "waypoints are single points, not a line to find curves on"))
    if not elements["trk"] and not elements["rte"]:
        raise RouteFormatError("no trk or rte element", "GPX")
    has = {k: any(c.kind == k for c in found) for k in ("trk", "rte")}
    if not found:
        raise RouteFormatError(
            f"no track or route with at least {MIN_VERTICES} distinct points ({_listed(skipped)})", "GPX"
        )
    wanted = parts or ("trk" if has["trk"] else "rte")
    if wanted != "all" and not has[wanted]:
        what = "track (trk) segment" if wanted == "trk" else "route (rte)"
        other = "parts=rte reads its routes" if wanted == "trk" else "parts=trk reads its tracks"
        raise RouteFormatError(f"parts={wanted}: the file has no {what} with points; {other}", "parts", "parts")
    out = []
    for c in found:
        if wanted in ("all", c.kind):
            out.append(_part(c.label, c.label, c.tag, c.lon, c.lat, c.ele, c.props, budget, c.idx))
        elif c.kind == "rte":
            skipped.append((c.label, _WHY_RTE if parts is None else "parts=trk"))
        else:
            skipped.append((c.label, "parts=rte"))
    return RouteRead(fmt, creator[:200] or None, out, elements, skipped)


def read_gpx(text: str | bytes, *, parts: str | None = None, max_vertices: int = MAX_VERTICES) -> list[RoutePart]:
    """The parts of :func:`read_gpx_document`."""
    return read_gpx_document(text, parts=parts, max_vertices=max_vertices).parts
