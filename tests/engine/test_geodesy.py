"""The developed plane frame of a WGS84 route against independent geodesics (Karney 2013, via geographiclib)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from geographiclib.geodesic import Geodesic

from engine.errors import InvalidInput
from engine.route.geodesy import WGS84_A_M, WGS84_F, local_frame, segment_lengths_m, turning_angles_rad

GEOD = Geodesic.WGS84
#: smallest radius of curvature of WGS84, the meridian radius at the equator a (1 - e^2) [m]
M_MIN = WGS84_A_M * (1 - WGS84_F * (2 - WGS84_F))
LATITUDES = (0.0, 45.0, 60.0, -35.0)


def test_ellipsoid_is_geographiclibs():
    # NIMA TR8350.2 defining parameters, cross-checked against GeographicLib's WGS84 (Karney)
    assert GEOD.a == WGS84_A_M
    assert pytest.approx(GEOD.f, rel=1e-15) == WGS84_F


def test_equator_degree_of_longitude():
    # the equator is a geodesic: 1 deg of longitude is a pi / 180 = 111319.4908 m (closed form)
    lon = np.linspace(0.0, 1.0, 1001)
    seg = segment_lengths_m(lon, np.zeros_like(lon))
    exact = WGS84_A_M * math.pi / 180.0
    chord_deficit = 1000 * (exact / 1000) ** 3 / (24 * WGS84_A_M**2)  # 1000 chords of 111 m: 1.4e-6 m
    assert seg.sum() == pytest.approx(exact - chord_deficit, abs=1e-8)


@pytest.mark.parametrize("lat", LATITUDES)
@pytest.mark.parametrize("azimuth", [0.0, 33.0, 90.0, 147.0, -120.0])
@pytest.mark.parametrize("distance", [10.0, 250.0, 10_000.0])
def test_segment_length_is_the_geodesic_distance(lat, azimuth, distance):
    end = GEOD.Direct(lat, 10.0, azimuth, distance)
    seg = segment_lengths_m([10.0, end["lon2"]], [lat, end["lat2"]])[0]
    # the chord is shorter than the arc by s^3 / (24 R^2), R >= M_MIN (the module's stated bound)
    bound = distance**3 / (24.0 * M_MIN**2)
    assert distance - bound - 1e-6 <= seg <= distance + 1e-6


@pytest.mark.parametrize("lat", LATITUDES)
@pytest.mark.parametrize("azimuth", [0.0, 37.0, 90.0, 141.0])
def test_a_geodesic_develops_into_a_straight_line_of_its_length(lat, azimuth):
    line = GEOD.Line(lat, 10.0, azimuth)
    s = np.arange(0.0, 50_001.0, 25.0)
    pos = [line.Position(si) for si in s]
    frame = local_frame([p["lon2"] for p in pos], [p["lat2"] for p in pos])
    end = math.hypot(frame.x_m[-1], frame.y_m[-1])
    assert end == pytest.approx(50_000.0, abs=1e-3)  # the geodesic distance, to 1 mm in 50 km
    ang = math.atan2(frame.y_m[-1], frame.x_m[-1])
    lateral = -math.sin(ang) * frame.x_m + math.cos(ang) * frame.y_m
    assert np.max(np.abs(lateral)) < 1e-3  # no curvature: straight to 1 mm
    # x east, y north at the start: the first segment's direction is the azimuth
    assert math.degrees(ang) == pytest.approx(90.0 - azimuth, abs=1e-6)


@pytest.mark.parametrize("lat", LATITUDES)
def test_turning_angle_sign_and_size(lat):
    # walk 100 m north-east, turn 30 deg left by the geodesic direct problem, walk 100 m
    a = GEOD.Direct(lat, 10.0, 45.0, 100.0)
    b = GEOD.Direct(a["lat2"], a["lon2"], a["azi2"] - 30.0, 100.0)
    c = GEOD.Direct(b["lat2"], b["lon2"], b["azi2"] + 50.0, 100.0)  # then 50 deg right
    lon = [10.0, a["lon2"], b["lon2"], c["lon2"]]
    lat_ = [lat, a["lat2"], b["lat2"], c["lat2"]]
    turns = np.degrees(turning_angles_rad(lon, lat_))
    assert turns == pytest.approx([30.0, -50.0], abs=1e-6)


def test_refusals_name_the_vertex():
    with pytest.raises(InvalidInput) as e:
        local_frame([10.0, 10.1, 10.2], [45.0, 95.0, 45.1])
    assert e.value.field == "coordinates[1]"
    with pytest.raises(InvalidInput) as e:
        local_frame([10.0, 10.0, 10.2], [45.0, 45.0, 45.1])
    assert e.value.field == "coordinates[1]"
    with pytest.raises(InvalidInput):
        local_frame([10.0], [45.0])
