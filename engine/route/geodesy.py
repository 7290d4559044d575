"""WGS84 longitude/latitude of a route to a local metric frame in which its curves keep their size.

Method: the developed (rolling tangent plane) frame
----------------------------------------------------
A single map projection distorts lengths by a factor that grows with the distance from its centre (a
tangent plane by about d^2 / (2 R^2): 0.08 % at 250 km), so a long route would see its radii scaled. Curve
detection needs only the route's *intrinsic* plane geometry: the horizontal length of each segment and the
angle the route turns at each vertex. Both are local, so they are measured where they occur and the route is
then laid out ("developed") in a plane with exactly those lengths and angles:

1. each vertex goes to earth-centred earth-fixed (ECEF) coordinates on the ellipsoid surface (height 0),
   Eq. (1);
2. the length of segment k is the chord |P[k+1] - P[k]| (Eq. 2);
3. at each interior vertex the incoming and outgoing chords are resolved on that vertex's own east and north
   unit vectors (its tangent plane, Eq. 3); the turning angle is the signed angle between the two (Eq. 4,
   + counter-clockwise = a left turn);
4. the plane polyline starts at (0, 0) with the first segment's true azimuth and is rebuilt from the lengths
   and the accumulated turning angles (Eq. 5): x east, y north at the start vertex.

Accuracy. On a sphere each chord lies in the plane of the great circle through its ends, so resolving it on
the tangent plane of either end gives the great circle's direction there exactly; the only approximations
are the chord against the arc, s^3 / (24 R^2) (relative (s / R)^2 / 24 = 1e-7 for s = 10 km) and, on the
ellipsoid, the normal section against the geodesic, whose azimuths differ by a term of order
e^2 (s / R)^2 (below 1e-8 rad for s = 10 km). Neither depends on the extent of the route, only on the
segment length, which the readers bound (``app.route_io.MAX_SEGMENT_M`` = 10 km). The horizontal geometry
is that of the ellipsoid surface: a road at height h is longer by h / R (1.6e-4 at 1000 m), which is not
applied (radii in road design are given on the reference surface or the grid, not at height).

What the frame is not: positions far from the start are not true map positions (the plane carries the
route's geodesic curvature, not the meridians' convergence), so use the vertex indices to map results back
to the source longitude/latitude, never the plane coordinates.

Elevation ``z`` is the given height [m], unchanged; GeoJSON heights are above the WGS84 ellipsoid (RFC 7946
section 4), GPX ``<ele>`` usually above the geoid/sea level: for a grade only differences over a curve
matter, and the geoid undulation changes by far less than 1 m per km.

References
----------
[1] NIMA TR8350.2 (2000), Department of Defense World Geodetic System 1984, 3rd ed.: defining parameters
    a = 6378137 m, 1/f = 298.257223563 (the same values GeographicLib's ``Geodesic.WGS84`` uses).
[2] B. Hofmann-Wellenhof, H. Lichtenegger, E. Wasle (2008), GNSS, Springer: geodetic to ECEF coordinates
    and the local east/north/up frame.
[3] C. F. F. Karney (2013), Algorithms for geodesics, J. Geodesy 87: the geodesic distances the tests
    compare against (through the ``geographiclib`` package).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from engine.errors import InvalidInput

#: WGS84 semi-major axis [m] [1]
WGS84_A_M = 6378137.0
#: WGS84 flattening [-] [1]
WGS84_F = 1.0 / 298.257223563
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)  # first eccentricity squared


def _check_coordinates(lon_deg, lat_deg) -> tuple[np.ndarray, np.ndarray]:
    lon = np.asarray(lon_deg, dtype=float).reshape(-1)
    lat = np.asarray(lat_deg, dtype=float).reshape(-1)
    if lon.shape != lat.shape:
        raise InvalidInput(
            f"lon_deg and lat_deg must have the same length, got {lon.size} and {lat.size}", field="lat_deg"
        )
    bad = ~(np.isfinite(lon) & np.isfinite(lat) & (np.abs(lat) <= 90.0) & (np.abs(lon) <= 180.0))
    if bad.any():
        i = int(np.argmax(bad))
        raise InvalidInput(
            f"vertex {i}: longitude must be in [-180, 180] and latitude in [-90, 90] deg, got ({lon[i]}, {lat[i]})",
            field=f"coordinates[{i}]",
            value=[float(lon[i]), float(lat[i])],
        )
    return lon, lat


def ecef_m(lon_deg, lat_deg, height_m=0.0) -> np.ndarray:
    """Earth-centred earth-fixed coordinates of geodetic positions on WGS84, shape (n, 3) [m].

    Parameters
    ----------
    lon_deg : array_like
        Longitude [deg].
    lat_deg : array_like
        Geodetic latitude [deg].
    height_m : array_like, default 0
        Height above the ellipsoid [m].
    """
    lon, lat = np.radians(lon_deg), np.radians(lat_deg)
    sl, cl = np.sin(lat), np.cos(lat)
    n = WGS84_A_M / np.sqrt(1.0 - WGS84_E2 * sl**2)  # prime-vertical radius of curvature [2]
    h = np.asarray(height_m, dtype=float)
    # Eq. (1): X = (N + h) cos(lat) cos(lon), Y = (N + h) cos(lat) sin(lon), Z = (N (1 - e^2) + h) sin(lat) [2]
    return np.stack(((n + h) * cl * np.cos(lon), (n + h) * cl * np.sin(lon), (n * (1.0 - WGS84_E2) + h) * sl), axis=-1)


def segment_lengths_m(lon_deg, lat_deg) -> np.ndarray:
    """Horizontal length of each segment of a polyline on the WGS84 surface, shape (n - 1,) [m].

    The chord between consecutive vertices (Eq. 2); it is shorter than the geodesic by s^3 / (24 R^2)
    (1e-7 relative at 10 km).

    Parameters
    ----------
    lon_deg, lat_deg : array_like
        Vertices in travel order [deg].
    """
    lon, lat = _check_coordinates(lon_deg, lat_deg)
    p = ecef_m(lon, lat)
    return np.linalg.norm(np.diff(p, axis=0), axis=1)  # Eq. 2


def _east_north(lon: np.ndarray, lat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit east and north vectors of each vertex's tangent plane in ECEF, shape (n, 3) each [2]."""
    lo, la = np.radians(lon), np.radians(lat)
    east = np.stack((-np.sin(lo), np.cos(lo), np.zeros_like(lo)), axis=-1)
    north = np.stack((-np.sin(la) * np.cos(lo), -np.sin(la) * np.sin(lo), np.cos(la)), axis=-1)
    return east, north


def turning_angles_rad(lon_deg, lat_deg) -> np.ndarray:
    """Signed angle the route turns at each interior vertex, shape (n - 2,) [rad] (+ left, - right).

    Both chords at the vertex are resolved on its tangent plane (Eq. 3) and the angle between them is
    atan2(cross, dot) (Eq. 4). The vertices must be distinct from their neighbours.

    Parameters
    ----------
    lon_deg, lat_deg : array_like
        Vertices in travel order [deg].
    """
    lon, lat = _check_coordinates(lon_deg, lat_deg)
    p = ecef_m(lon, lat)
    d = np.diff(p, axis=0)
    east, north = _east_north(lon[1:-1], lat[1:-1])
    # Eq. 3: components of the incoming (d[k-1]) and outgoing (d[k]) chords on vertex k's east and north
    e_in, n_in = np.einsum("ij,ij->i", d[:-1], east), np.einsum("ij,ij->i", d[:-1], north)
    e_out, n_out = np.einsum("ij,ij->i", d[1:], east), np.einsum("ij,ij->i", d[1:], north)
    return np.arctan2(e_in * n_out - n_in * e_out, e_in * e_out + n_in * n_out)  # Eq. 4


@dataclass(frozen=True)
class LocalFrame:
    """A route in the developed plane frame: x east and y north at the first vertex, z the given height."""

    x_m: np.ndarray
    y_m: np.ndarray
    z_m: np.ndarray | None
    segment_m: np.ndarray  # horizontal length of each segment [m]


def local_frame(lon_deg, lat_deg, height_m=None) -> LocalFrame:
    """Develop a WGS84 route into a plane frame that keeps its segment lengths and turning angles.

    Parameters
    ----------
    lon_deg, lat_deg : array_like
        Vertices in travel order, consecutive vertices distinct [deg].
    height_m : array_like or None
        Elevation of each vertex (NaN where unknown) [m]; passed through as ``z_m``.

    Returns
    -------
    LocalFrame
        Plane coordinates [m] in which curve radii, chainages and deflections are those of the route on
        the ellipsoid (see the module docstring for the error bound).
    """
    lon, lat = _check_coordinates(lon_deg, lat_deg)
    if lon.size < 2:
        raise InvalidInput(f"a route needs at least 2 vertices, got {lon.size}", field="coordinates", value=lon.size)
    seg = segment_lengths_m(lon, lat)
    if np.any(seg <= 0.0):
        i = int(np.argmax(seg <= 0.0))
        raise InvalidInput(
            f"vertices {i} and {i + 1} coincide; drop repeated points first", field=f"coordinates[{i + 1}]"
        )
    east, north = _east_north(lon[:1], lat[:1])
    d0 = ecef_m(lon[1], lat[1]) - ecef_m(lon[0], lat[0])
    start = float(np.arctan2(d0 @ north[0], d0 @ east[0]))  # first segment's direction, from east
    heading = start + np.concatenate(([0.0], np.cumsum(turning_angles_rad(lon, lat))))
    x = np.concatenate(([0.0], np.cumsum(seg * np.cos(heading))))  # Eq. 5
    y = np.concatenate(([0.0], np.cumsum(seg * np.sin(heading))))
    z = None
    if height_m is not None:
        z = np.asarray(height_m, dtype=float).reshape(-1)
        if z.shape != lon.shape:
            raise InvalidInput(f"height_m has {z.size} values for {lon.size} vertices", field="height_m")
    return LocalFrame(x, y, z, seg)
