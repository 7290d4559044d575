"""Readers for route geometry: GeoJSON (RFC 7946) and GPX 1.1 -> polylines of WGS84 longitude/latitude/elevation.

Both return a list of :class:`RoutePart` (one per GeoJSON ``LineString`` or ``MultiLineString`` part, one per
GPX track segment or route) with the part's source label, its properties and its vertices, or raise
:class:`RouteFormatError` naming the part and the vertex (``features[0].geometry.coordinates[17]``,
``trk[1] 'A1' trkseg[2] trkpt[18]``) and what is wrong. Nothing is repaired silently except repeated
consecutive points (a receiver standing still), which are dropped; ``RoutePart.vertex_index`` maps each kept
vertex back to its position in the source, so curves found on the part can be mapped back to the file.

GeoJSON: a ``FeatureCollection`` of ``Feature``s, a ``Feature``, or a bare ``LineString`` /
``MultiLineString`` geometry. Positions are ``[longitude, latitude]`` or ``[longitude, latitude, height]``
(RFC 7946 section 3.1.1; height [m] above the WGS84 ellipsoid, section 4). A ``crs`` member (GeoJSON 2008)
other than CRS84 / EPSG:4326 is refused: only WGS84 longitude/latitude is read. A feature's ``properties``
may carry ``superelevation_percent`` ([-20, 20]), ``posted_speed_kmh`` ((0, 200]), ``name`` and ``id``.

GPX 1.1: every ``trk/trkseg`` (points ``trkpt``) and every ``rte`` (points ``rtept``), attributes ``lat`` and ``lon`` in
decimal degrees (WGS84, the GPX schema's datum) and an optional ``<ele>`` [m]. The part's properties hold its ``name``.
Parsing refuses what defusedxml refuses (no external entities, no entity expansion; :mod:`app.formats.xmlsafe`).

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


def _part(source, location, style, lon, lat, ele, properties, budget: _Budget) -> RoutePart:
    """Checks shared by both formats; ``lon``/``lat``/``ele`` are float arrays (NaN ele: none)."""
    n = lon.size
    for i in range(n):  # a plain loop: the first bad vertex is the one to name
        lo, la = lon[i], lat[i]
        where = _vertex(location, i, style)
        if not (math.isfinite(lo) and math.isfinite(la)):
            raise RouteFormatError(f"coordinates must be finite numbers, got ({lo}, {la})", where, "coordinates")
        if abs(la) > 90.0:
            hint = " (longitude and latitude look swapped)" if abs(lo) <= 90.0 else ""
            raise RouteFormatError(f"latitude {la} is outside [-90, 90]{hint}", where, "latitude")
        if abs(lo) > 180.0:
            raise RouteFormatError(f"longitude {lo} is outside [-180, 180]", where, "longitude")
    keep = np.ones(n, dtype=bool)
    keep[1:] = (lon[1:] != lon[:-1]) | (lat[1:] != lat[:-1])  # repeated points: dropped (GPS standing still)
    idx = np.flatnonzero(keep)
    if idx.size < MIN_VERTICES:
        what = f"all {n} vertices are the same point" if n > 1 else f"has {n} vertex"
        raise RouteFormatError(f"{what}; a route part needs at least {MIN_VERTICES} distinct vertices", location)
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


def _properties(props, where: str) -> dict:
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
    return out


def _at(where: str, name: str) -> str:
    """The JSON path of ``name`` inside the object at ``where`` ("" is the document itself)."""
    return f"{where}.{name}" if where else name


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


def read_geojson(doc, *, max_vertices: int = MAX_VERTICES) -> list[RoutePart]:
    """Route parts from a GeoJSON object (parsed, or as JSON text), at most ``max_vertices`` vertices in all; see the
    module docstring."""
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
    budget = _Budget(max_vertices=max_vertices)
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
    elif kind in ("LineString", "MultiLineString"):
        return _geometry(doc, "", "geometry", {}, budget)
    else:
        raise RouteFormatError(
            f"type {kind!r}: expected FeatureCollection, Feature, LineString or MultiLineString", "type", "type"
        )
    parts: list[RoutePart] = []
    for feat, where in items:
        if not isinstance(feat, dict) or feat.get("type") != "Feature":
            raise RouteFormatError("must be a Feature object", where, "type")
        props = _properties(feat.get("properties"), _at(where, "properties"))
        if "id" in feat and "id" not in props:
            props["id"] = feat["id"]
        parts.extend(_geometry(feat.get("geometry"), _at(where, "geometry"), where or "feature", props, budget))
    if len(parts) > MAX_PARTS:
        raise RouteFormatError(f"more than {MAX_PARTS} line parts", "features")
    return parts


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


def read_gpx(text: str | bytes, *, max_vertices: int = MAX_VERTICES) -> list[RoutePart]:
    """Route parts from a GPX 1.1 document: each track segment and each route, at most ``max_vertices`` vertices in
    all; see the module docstring."""
    root = xmlsafe.document(text, "gpx", "GPX", RouteFormatError)
    budget, parts = _Budget(max_vertices=max_vertices), []
    t_index = r_index = 0
    for el in root:
        kind = xmlsafe.local(el.tag)
        if kind not in ("trk", "rte"):
            continue
        name = _child_text(el, "name")
        named = f" {name!r}" if name else ""
        props = {"name": name} if name else {}
        if kind == "trk":
            t_index += 1
            segs = [s for s in el if xmlsafe.local(s.tag) == "trkseg"]
            if not segs:
                raise RouteFormatError("has no trkseg", f"trk[{t_index}]{named}")
            for j, seg in enumerate(segs, start=1):
                label = f"trk[{t_index}]{named} trkseg[{j}]"
                lon, lat, ele = _gpx_points([p for p in seg if xmlsafe.local(p.tag) == "trkpt"], label, "trkpt", budget)
                parts.append(_part(label, label, "trkpt", lon, lat, ele, props, budget))
        else:
            r_index += 1
            label = f"rte[{r_index}]{named}"
            lon, lat, ele = _gpx_points([p for p in el if xmlsafe.local(p.tag) == "rtept"], label, "rtept", budget)
            parts.append(_part(label, label, "rtept", lon, lat, ele, props, budget))
        if len(parts) > MAX_PARTS:
            raise RouteFormatError(f"more than {MAX_PARTS} tracks, segments and routes", "GPX")
    if not parts:
        raise RouteFormatError("no trk or rte element", "GPX")
    return parts
