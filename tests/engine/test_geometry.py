"""Horizontal curves from geometry: synthetic routes of known tangents, arcs and clothoids, laid on WGS84.

Every route is designed in a plane (tests/synthetic_routes.py), laid on the ellipsoid with GeographicLib's
geodesic direct problem (each segment keeps its length, each vertex its turning angle: the route on the
ellipsoid has the designed radii exactly), optionally with white GPS-like noise of sigma 2-3 m added to the
vertices (seeded), then read back through the engine's plane frame (engine.geodesy) and curve finder.

Tolerances (the issue's, not the results'): radius 1 % without noise, 5 % with noise. Chainages without noise:
one vertex spacing (a tangent point lies somewhere between two vertices). Chainages with noise: sqrt(2 R 3
sigma), the distance past a tangent point at which the arc's offset from the tangent, d^2 / (2 R), reaches
three noise standard deviations (the curve cannot be told from the tangent before). Deflection without noise:
0.1 deg where the curve has tangents on both sides (fitted exactly), h / (2 R) rad otherwise (the direction
of a chord of length h against the arc's tangent). Grades: 0.3 percentage points.

Case class of the noisy radius test: arcs whose Cramér-Rao bound for a circle fit through their own vertices
(an independent closed form from the design: sigma^2 [(J^T J)^-1]_RR, J the Jacobian of the distances) is at
most 5 % / 3, so that the 5 % tolerance is three standard deviations of the best unbiased estimate from the
arc alone. Shorter or flatter arcs (fewer vertices, middle ordinate nearer the noise) are outside the
class: docs/routes.md gives the limit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.case import Case
from engine.errors import InvalidInput
from engine.road.curves import assess_curves
from engine.route.detect import find_curves, spiral_length_m
from engine.route.fit import fit_circle
from engine.route.geodesy import local_frame
from engine.route.noise import curvature_noise_per_m, vertex_noise_m
from engine.vehicle.presets import PRESETS
from tests.synthetic_routes import (
    Arc,
    Spiral,
    Tangent,
    curve_spans,
    gauss_markov,
    layout,
    spiral_curve,
    to_lonlat,
)

LATITUDES = (0.0, 45.0, 60.0, -35.0)


def detect(elements, spacing, lat, *, noise=0.0, seed=0, z_of_s=None, z_noise=0.0, corr_m=None, **kwargs):
    """Lay the route on WGS84 at ``lat``, read it back, find its curves; also returns the design chainage. The
    noise is white, or correlated over ``corr_m`` metres along the track (Gauss-Markov, each axis its own)."""
    x, y, s = layout(elements, spacing)
    rng = np.random.default_rng(seed)
    if noise and corr_m:
        rho = math.exp(-spacing / corr_m)
        x = x + gauss_markov(rng, x.size, noise, rho)
        y = y + gauss_markov(rng, y.size, noise, rho)
    elif noise:
        x = x + rng.normal(0.0, noise, x.size)
        y = y + rng.normal(0.0, noise, y.size)
    lon, lat_ = to_lonlat(x, y, lat)
    z = None
    if z_of_s is not None:
        z = z_of_s(s) + (rng.normal(0.0, z_noise, s.size) if z_noise else 0.0)
    frame = local_frame(lon, lat_, z)
    return find_curves(frame.x_m, frame.y_m, frame.z_m, **kwargs), s


def circle_crb(radius, length, spacing, sigma):
    """Cramér-Rao standard deviation of a circle fit's radius through vertices every ``spacing`` on an arc [m]."""
    phi = np.arange(0.0, length + 1e-9, spacing) / radius
    jac = np.column_stack((np.cos(phi), np.sin(phi), np.ones_like(phi)))
    return sigma * math.sqrt(np.linalg.inv(jac.T @ jac)[2, 2])


# a route with a sharp simple curve, a spiralled curve, a flat long curve and a reverse pair without tangent
ROUTE = [
    Tangent(500),
    Arc(60, 120, "left"),
    Tangent(400),
    *spiral_curve(250, 200, 80, "right"),
    Tangent(500),
    Arc(2000, 700, "left"),
    Tangent(400),
    Arc(400, 300, "right"),
    Arc(400, 250, "left"),
    Tangent(500),
]
# designed curves of ROUTE: (radius, direction, start, end, spiral, deflection deg, tangents on both sides)
ROUTE_CURVES = [
    (60, "left", 500, 620, None, math.degrees(120 / 60), True),
    (250, "right", 1020, 1380, 80, math.degrees((200 + 80) / 250), True),
    (2000, "left", 1880, 2580, None, math.degrees(700 / 2000), True),
    (400, "right", 2980, 3280, None, math.degrees(300 / 400), False),
    (400, "left", 3280, 3530, None, math.degrees(250 / 400), False),
]


@pytest.mark.parametrize("lat", LATITUDES)
@pytest.mark.parametrize("spacing", [5.0, 10.0, 20.0])
def test_noiseless_route_radii_chainages_spirals(lat, spacing):
    found, _ = detect(ROUTE, spacing, lat)
    assert len(found.curves) == len(ROUTE_CURVES)
    assert found.noise_m < 0.01
    for c, (r, direction, start, end, spiral, defl, tangents) in zip(found.curves, ROUTE_CURVES, strict=True):
        assert c.direction == direction
        assert c.radius_m == pytest.approx(r, rel=0.01)
        assert c.start_m == pytest.approx(start, abs=spacing)
        assert c.end_m == pytest.approx(end, abs=spacing)
        defl_tol = 0.1 if tangents else math.degrees(spacing / (2 * r))
        assert c.deflection_deg == pytest.approx(defl, abs=defl_tol)
        if spiral is None:
            assert c.spiral_in_m is None and c.spiral_out_m is None
            assert c.arc_start_m == pytest.approx(start, abs=spacing)
        else:
            assert c.spiral_in_m == pytest.approx(spiral, abs=spacing)
            assert c.spiral_out_m == pytest.approx(spiral, abs=spacing)
            assert c.arc_start_m == pytest.approx(start + spiral, abs=spacing)
            assert c.arc_end_m == pytest.approx(end - spiral, abs=spacing)
        assert not c.compound and not c.sparse


def test_reverse_curves_meet_at_the_inflection():
    found, _ = detect(ROUTE, 10.0, 45.0)
    a, b = found.curves[3], found.curves[4]
    assert (a.direction, b.direction) == ("right", "left")
    assert a.end_m == pytest.approx(3280, abs=10) and b.start_m == pytest.approx(a.end_m, abs=1e-6)


def test_vertex_range_covers_the_curve():
    found, s = detect(ROUTE, 10.0, 0.0)
    ch = found.chainage_m
    for c in found.curves:
        assert ch[c.start_index] <= c.start_m + 1e-9 and ch[c.end_index] >= c.end_m - 1e-9
        assert c.end_index - c.start_index <= (c.end_m - c.start_m) / 10 + 2
    # the polyline's chords are shorter than the arcs by (h / R)^2 / 24: at most 0.12 % on the R 60 m arc
    assert found.chainage_m[-1] == pytest.approx(s[-1], rel=1e-4)


NOISY = [
    # radius, arc length, direction, spacing, sigma, latitude
    (60, 180, "left", 5, 2.0, 45.0),
    (150, 300, "right", 5, 2.0, -35.0),
    (300, 500, "left", 10, 3.0, 0.0),
    (800, 800, "right", 5, 3.0, 60.0),
    (2000, 1200, "left", 10, 3.0, 45.0),
]


@pytest.mark.parametrize(("radius", "length", "direction", "spacing", "sigma", "lat"), NOISY)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_noisy_simple_curves(radius, length, direction, spacing, sigma, lat, seed):
    assert 3 * circle_crb(radius, length, spacing, sigma) <= 0.05 * radius  # inside the case class
    route = [Tangent(700), Arc(radius, length, direction), Tangent(700)]
    found, _ = detect(route, spacing, lat, noise=sigma, seed=seed)
    assert len(found.curves) == 1  # no phantom curve on the tangents
    c = found.curves[0]
    assert c.direction == direction
    assert c.radius_m == pytest.approx(radius, rel=0.05)
    tol = math.sqrt(2 * radius * 3 * sigma)
    assert c.start_m == pytest.approx(700, abs=tol)
    assert c.end_m == pytest.approx(700 + length, abs=tol)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_noisy_spiralled_curve(seed):
    # R 1500 m, 100 m clothoids, 1000 m arc, sigma 3 m every 10 m at 60 deg N. The shift p = Ls^2 / (24 R)
    # = 0.28 m is far below the noise: if the spirals are not resolved, the curve is the equivalent simple curve
    # between the spirals' middles, whose best-fit radius exceeds R by about p sec(D/2) / (sec(D/2) - 1) = 4 m
    # (0.3 %, D = 1100 / 1500 rad), inside the class; its ends are then Ls / 2 inside the spirals' ends.
    assert 3 * circle_crb(1500, 1000, 10, 3.0) <= 0.05 * 1500
    route = [Tangent(800), *spiral_curve(1500, 1000, 100, "right"), Tangent(800)]
    found, _ = detect(route, 10.0, 60.0, noise=3.0, seed=seed)
    assert len(found.curves) == 1
    c = found.curves[0]
    assert c.direction == "right" and c.radius_m == pytest.approx(1500, rel=0.05)
    tol = math.sqrt(2 * 1500 * 9.0) + 50.0
    assert c.start_m == pytest.approx(800, abs=tol) and c.end_m == pytest.approx(1900, abs=tol)


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("sigma", [2.0, 3.0])
def test_no_phantom_curves_on_a_long_noisy_tangent(seed, sigma):
    found, _ = detect([Tangent(20_000)], 10.0, 45.0, noise=sigma, seed=seed)
    assert found.curves == ()


def test_no_curves_from_digitising_kinks():
    # a surveyed tangent whose vertices zig-zag by 0.5 deg angle points (below min_deflection_deg = 1)
    s = np.arange(0.0, 5000.0, 50.0)
    y = np.where(np.arange(s.size) % 2 == 0, 0.0, 50.0 * math.tan(math.radians(0.25)))
    assert find_curves(s, y).curves == ()
    assert find_curves(s, np.zeros_like(s)).curves == ()


def test_compound_curve_is_one_curve_with_its_sharpest_radius():
    # R 200 m for 200 m, then R 600 m for 300 m, same direction: one curve over both arcs, compound,
    # radius of the sharper arc (the one that governs the safe speed)
    route = [Tangent(500), Arc(200, 200, "left"), Arc(600, 300, "left"), Tangent(500)]
    found, _ = detect(route, 10.0, 45.0)
    assert len(found.curves) == 1
    c = found.curves[0]
    assert c.compound and c.direction == "left"
    assert c.radius_m == pytest.approx(200, rel=0.01)
    assert c.start_m == pytest.approx(500, abs=10) and c.end_m == pytest.approx(1000, abs=10)
    assert c.deflection_deg == pytest.approx(math.degrees(200 / 200 + 300 / 600), abs=0.1)


def test_broken_back_curves_are_two_curves():
    route = [Tangent(500), Arc(300, 200, "left"), Tangent(150), Arc(300, 200, "left"), Tangent(500)]
    found, _ = detect(route, 10.0, -35.0)
    assert [c.direction for c in found.curves] == ["left", "left"]
    for c, start in zip(found.curves, (500, 850), strict=True):
        assert c.radius_m == pytest.approx(300, rel=0.01)
        assert c.start_m == pytest.approx(start, abs=10)


def test_left_and_right_mirror():
    left, _ = detect([Tangent(400), Arc(120, 150, "left"), Tangent(400)], 5.0, 0.0)
    right, _ = detect([Tangent(400), Arc(120, 150, "right"), Tangent(400)], 5.0, 0.0)
    assert [c.direction for c in left.curves] == ["left"] and [c.direction for c in right.curves] == ["right"]
    assert left.curves[0].radius_m == pytest.approx(right.curves[0].radius_m, rel=1e-9)


GRADE = 5.0  # [%]


@pytest.mark.parametrize("noise", [0.0, 2.0])
def test_straight_grade_uphill_and_downhill(noise):
    route = [Tangent(600), Arc(250, 300, "left"), Tangent(600)]
    found, _ = detect(
        route, 5.0, 45.0, noise=noise, z_of_s=lambda s: 100.0 + GRADE / 100 * s, z_noise=0.5 if noise else 0.0
    )
    assert found.curves[0].grade_percent == pytest.approx(GRADE, abs=0.3)
    down, _ = detect(route, 5.0, 45.0, noise=noise, z_of_s=lambda s: 500.0 - GRADE / 100 * s)
    assert down.curves[0].grade_percent == pytest.approx(-GRADE, abs=0.3)


def test_grade_on_a_vertical_curve_is_the_grade_at_the_curves_middle():
    # sag vertical curve from -4 % to +4 % over 800 m starting at 300 m: z = z0 + g1 s + (g2 - g1) s^2 / (2 L)
    g1, g2, s0, length = -0.04, 0.04, 300.0, 800.0

    def z(s):
        u = np.clip(s - s0, 0.0, length)
        return 200.0 + g1 * s + (g2 - g1) * u**2 / (2 * length)

    route = [Tangent(600), Arc(250, 300, "right"), Tangent(600)]
    found, _ = detect(route, 5.0, 0.0, z_of_s=z)
    middle = 600 + 150
    expected = 100 * (g1 + (g2 - g1) * (middle - s0) / length)  # -4 + 8 x 450 / 800 = 0.5 %
    assert found.curves[0].grade_percent == pytest.approx(expected, abs=0.3)


def test_no_elevation_no_grade():
    found, _ = detect([Tangent(300), Arc(100, 100, "left"), Tangent(300)], 5.0, 0.0)
    assert found.curves[0].grade_percent is None


def test_curves_go_through_the_assessment():
    found, _ = detect(ROUTE, 10.0, 45.0, z_of_s=lambda s: 0.02 * s)
    curves = [c.as_curve(f"C{i}", 6.0, posted_speed_kmh=60.0) for i, c in enumerate(found.curves)]
    out = assess_curves(Case(PRESETS["table16-btrain"]), curves)
    assert len(out.curves) == len(curves)
    # the sharpest curve (R 60 m) has the lowest safe speed
    safe = [a.safe_speed_kmh for a in out.curves]
    assert int(np.argmin(safe)) == 0


# ------------------------------------------------------------------------------------------ parts


def test_noise_model_matches_a_simulation():
    # Eq. 1 against the sample standard deviation of the smoothed curvature of a noisy straight track
    rng = np.random.default_rng(7)
    s = np.arange(0.0, 20_000.0, 10.0)
    y = rng.normal(0.0, 3.0, s.size)
    assert vertex_noise_m(s + rng.normal(0.0, 3.0, s.size), y) == pytest.approx(3.0, rel=0.1)
    assert curvature_noise_per_m(3.0, 10.0, 100.0) == pytest.approx(
        3.0 * math.sqrt(3 * 10.0 / (8 * math.sqrt(math.pi))) * 100.0**-2.5
    )


def test_circle_fit_exact_and_far_from_the_origin():
    t = np.linspace(0.2, 1.1, 9)
    fit = fit_circle(5e5 + 300 * np.cos(t), -3e6 + 300 * np.sin(t))
    assert fit.radius_m == pytest.approx(300, rel=1e-9)
    assert fit.xc_m == pytest.approx(5e5, abs=1e-6)


def test_spiral_length_inverts_the_blurred_ramp():
    # a step (no spiral) blurred by a Gaussian of scale tau crosses 1/4 and 3/4 at -+0.6745 tau
    assert spiral_length_m(2 * 0.6745 * 10.0, 10.0) == pytest.approx(0.0, abs=0.05)
    # a long ramp keeps its shape: the quartiles are L / 2 apart
    assert spiral_length_m(100.0, 5.0) == pytest.approx(200.0, rel=0.01)


def test_spiral_elements_are_clothoids():
    # the curvature of Spiral is linear in chainage: its heading change is k L / 2 (closed form)
    route = [Tangent(100), Spiral(100, 0.0, 1 / 200), Tangent(100)]
    x, y, _ = layout(route, 1.0)
    d0 = math.atan2(y[10] - y[0], x[10] - x[0])
    d1 = math.atan2(y[-1] - y[-11], x[-1] - x[-11])
    assert math.degrees(d1 - d0) == pytest.approx(math.degrees(100 / 200 / 2), abs=1e-6)
    assert curve_spans(route) == [(100, 200)]


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"x_m": [0, 1, float("nan")], "y_m": [0, 0, 0]}, "x_m[2]"),
        ({"x_m": [0, 1, 2], "y_m": [0, 0]}, "y_m"),
        ({"x_m": [0, 1, 2], "y_m": [0, 0, 0], "step_m": 0.0}, "step_m"),
        ({"x_m": [0, 1, 2], "y_m": [0, 0, 0], "noise_m": -1.0}, "noise_m"),
        ({"x_m": [0, 1, 2], "y_m": [0, 0, 0], "max_radius_m": 1.0}, "max_radius_m"),
        ({"x_m": [0, 0, 0], "y_m": [0, 0, 0]}, "x_m"),
        ({"x_m": [0], "y_m": [0]}, "x_m"),
    ],
)
def test_refusals_name_the_field(kwargs, field):
    with pytest.raises(InvalidInput) as e:
        find_curves(**kwargs)
    assert e.value.field == field


def test_repeated_vertices_are_dropped_and_keep_their_chainage():
    x, y, _ = layout([Tangent(300), Arc(100, 100, "left"), Tangent(300)], 5.0)
    xr, yr = np.repeat(x, 2), np.repeat(y, 2)
    a, b = find_curves(x, y), find_curves(xr, yr)
    assert b.curves[0].radius_m == pytest.approx(a.curves[0].radius_m, rel=1e-12)
    assert b.chainage_m[1] == b.chainage_m[0] == 0.0 and b.chainage_m.size == xr.size
    assert b.curves[0].start_index == 2 * a.curves[0].start_index
