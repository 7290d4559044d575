"""Synthetic routes for the geometry tests: tangents, circular arcs and clothoids laid out exactly.

A route is a list of elements; its heading theta(s) is piecewise linear in curvature (constant on tangents
and arcs, linear on clothoids), and positions are the integral of (cos theta, sin theta) by the midpoint rule
on 0.05 m steps (error below 1e-6 m per km for radii over 20 m). ``to_lonlat`` lays the same polyline on the
WGS84 ellipsoid with GeographicLib's geodesic direct problem (Karney 2013): each segment keeps its length and
each vertex its turning angle, so the route on the ellipsoid has exactly the designed radii. This is independent
of the engine's projection, which the tests then check against it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from geographiclib.geodesic import Geodesic


@dataclass(frozen=True)
class Tangent:
    length_m: float


@dataclass(frozen=True)
class Arc:
    radius_m: float
    length_m: float
    direction: str  # "left" / "right"

    @property
    def curvature(self) -> float:
        return (1.0 if self.direction == "left" else -1.0) / self.radius_m


@dataclass(frozen=True)
class Spiral:
    """Clothoid whose curvature goes linearly from ``k0`` to ``k1`` [1/m] over ``length_m``."""

    length_m: float
    k0: float
    k1: float


def spiral_curve(radius_m: float, arc_m: float, spiral_m: float, direction: str) -> list:
    """Tangent-spiral-arc-spiral-tangent elements of one curve (without the tangents)."""
    k = (1.0 if direction == "left" else -1.0) / radius_m
    return [Spiral(spiral_m, 0.0, k), Arc(radius_m, arc_m, direction), Spiral(spiral_m, k, 0.0)]


def curvature_profile(elements: list, ds: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """Chainage and curvature [1/m] sampled every ds along the route."""
    ks = []
    for el in elements:
        n = max(1, round(el.length_m / ds))
        u = (np.arange(n) + 0.5) / n
        if isinstance(el, Tangent):
            ks.append(np.zeros(n))
        elif isinstance(el, Arc):
            ks.append(np.full(n, el.curvature))
        else:
            ks.append(el.k0 + (el.k1 - el.k0) * u)
    k = np.concatenate(ks)
    total = sum(el.length_m for el in elements)
    return np.linspace(0.0, total, k.size + 1), k


def layout(elements: list, spacing_m: float, ds: float = 0.05, heading_deg: float = 30.0):
    """Vertices every ``spacing_m`` along the route: (x, y, chainage) in a plane, x east, y north."""
    s_edges, k = curvature_profile(elements, ds)
    step = np.diff(s_edges)
    theta_edges = math.radians(heading_deg) + np.concatenate(([0.0], np.cumsum(k * step)))
    theta_mid = 0.5 * (theta_edges[1:] + theta_edges[:-1])
    x = np.concatenate(([0.0], np.cumsum(step * np.cos(theta_mid))))
    y = np.concatenate(([0.0], np.cumsum(step * np.sin(theta_mid))))
    total = s_edges[-1]
    s = np.arange(0.0, total + 1e-9, spacing_m)
    return np.interp(s, s_edges, x), np.interp(s, s_edges, y), s


def curve_spans(elements: list) -> list[tuple[float, float]]:
    """(start, end) chainage of each run of non-tangent elements."""
    spans, s, start = [], 0.0, None
    for el in elements:
        if isinstance(el, Tangent):
            if start is not None:
                spans.append((start, s))
                start = None
        elif start is None:
            start = s
        s += el.length_m
    if start is not None:
        spans.append((start, s))
    return spans


def gauss_markov(rng, n: int, sigma: float, rho: float) -> np.ndarray:
    """n values of a stationary AR(1) (Gauss-Markov) sequence of standard deviation ``sigma`` and lag-one
    correlation ``rho``: a receiver's error that drifts rather than jumping fix to fix."""
    out = np.empty(n)
    out[0] = rng.normal(0.0, sigma)
    kick = rng.normal(0.0, sigma * math.sqrt(1.0 - rho * rho), n)
    for k in range(1, n):
        out[k] = rho * out[k - 1] + kick[k]
    return out


def to_lonlat(x, y, lat0: float, lon0: float = 10.0) -> tuple[np.ndarray, np.ndarray]:
    """Lay a plane polyline on WGS84 keeping segment lengths and turning angles (geodesic direct problem)."""
    geod = Geodesic.WGS84
    dx, dy = np.diff(x), np.diff(y)
    lengths = np.hypot(dx, dy)
    headings = np.arctan2(dy, dx)  # from east, counter-clockwise
    turns = np.diff(headings)
    turns = (turns + np.pi) % (2 * np.pi) - np.pi
    lat, lon = [lat0], [lon0]
    azi = 90.0 - math.degrees(headings[0])  # azimuth: clockwise from north
    for i, length in enumerate(lengths):
        if i > 0:
            azi -= math.degrees(turns[i - 1])  # a left turn (counter-clockwise) lowers the azimuth
        g = geod.Direct(lat[-1], lon[-1], azi, float(length))
        lat.append(g["lat2"])
        lon.append(g["lon2"])
        azi = g["azi2"]
    return np.array(lon), np.array(lat)
