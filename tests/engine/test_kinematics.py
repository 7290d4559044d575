"""Closed-form kinematics of the sub-mechanisms (Eqs. 4.2-4.5, 4.8-4.12) against direct vector geometry,
and the compliance laws (Eqs. 4.1, 4.6-4.7, 4.20-4.21)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.models import springs as compliance
from engine.models.groups import ARRAY, four_bar, tire_system


def _circle_intersection_upper(c1, r1, c2, r2):
    d = np.subtract(c2, c1)
    dist = np.linalg.norm(d)
    a = (r1**2 - r2**2 + dist**2) / (2 * dist)
    h = math.sqrt(r1**2 - a**2)
    u = d / dist
    p = np.asarray(c1) + a * u
    cands = [p + h * np.array([-u[1], u[0]]), p - h * np.array([-u[1], u[0]])]
    return max(cands, key=lambda q: q[1])


@pytest.mark.parametrize("l_out,l_in,width", [(0.47, 0.52, 1.86), (0.499, 0.499, 1.86), (0.53, 0.49, 1.815)])
def test_tire_system_keeps_both_tires_perpendicular_to_the_axle(l_out, l_in, width):
    theta, track = tire_system(l_out, l_in, width)  # Eqs. 4.2-4.5
    # the axle of length `width` rotated by theta, columns perpendicular to it, both feet on the road
    assert math.tan(theta) == pytest.approx((l_in - l_out) / width, rel=1e-12, abs=1e-15)
    axle_start = np.array([-l_out * math.sin(theta), l_out * math.cos(theta)])
    axle_end = axle_start + width * np.array([math.cos(theta), math.sin(theta)])
    inner_foot = axle_end - l_in * np.array([-math.sin(theta), math.cos(theta)])
    assert inner_foot[1] == pytest.approx(0.0, abs=1e-12)
    assert inner_foot[0] == pytest.approx(track, rel=1e-12)
    assert track >= width - 1e-12  # Eq. 4.3: the sliding inner tire widens the track


@pytest.mark.parametrize(
    "l_a,l_b,theta_a,sep",
    [(0.17, 0.24, 0.01, 0.95), (0.2, 0.21, -0.03, 0.95), (0.12, 0.08, 0.02, 0.6), (0.205, 0.205, 0.0, 0.95)],
)
def test_four_bar_angles_match_vector_geometry(l_a, l_b, theta_a, sep):
    top_a, base_b, top_b = four_bar(l_a, l_b, theta_a, sep)  # Eqs. 4.8-4.12
    pa, pb = np.array([0.0, 0.0]), np.array([sep, 0.0])
    ta = pa + l_a * np.array([-math.sin(theta_a), math.cos(theta_a)])
    tb = _circle_intersection_upper(ta, sep, pb, l_b)
    body = math.atan2(tb[1] - ta[1], tb[0] - ta[0])
    leg_b = math.atan2(-(tb[0] - pb[0]), tb[1] - pb[1])
    assert top_a == pytest.approx(body - theta_a, abs=1e-12)
    assert base_b == pytest.approx(leg_b, abs=1e-12)
    assert top_b == pytest.approx(body - leg_b, abs=1e-12)
    assert theta_a + top_a == pytest.approx(base_b + top_b, abs=1e-12)  # loop closure


def test_kinematics_work_on_arrays_like_on_floats():
    l_out = np.array([0.47, 0.5])
    th, tr = tire_system(l_out, np.array([0.52, 0.49]), 1.86, ARRAY)
    assert th[0] == pytest.approx(tire_system(0.47, 0.52, 1.86)[0])
    assert tr[1] == pytest.approx(tire_system(0.5, 0.49, 1.86)[1])


def test_compliance_laws():
    # Eq. 4.1: a tire loaded 100 kN above its start load shortens by 100 / kT
    assert compliance.tire_radius(225.0, 125.0, 5040.0, 0.499) == pytest.approx(0.499 - 100 / 5040)
    assert compliance.leaf_spring_height(25.0, 125.0, 5400.0, 0.205) == pytest.approx(0.205 + 100 / 5400)
    assert compliance.fifth_wheel_height(52.5, 52.5, 7500.0, 0.1) == pytest.approx(0.1)
    # Eq. 4.6: the leg rotates against the moment its base applies to it
    assert compliance.torsion_angle(-20.0, 4000.0) == pytest.approx(0.005)
    assert compliance.torsion_angle(-20.0, math.inf) == 0.0
    # Table 2: a graduated multi-leaf spring is a beam of uniform strength, which deflects 3/2 as much as the
    # prismatic beam of the same section (Shigley): its rate is 2/3 of 48 E I / l^3 for the stack loaded at mid-span
    e, n, b, t, span = 206e6, 10, 0.09, 0.012, 1.2
    prismatic = 48 * e * (n * b * t**3 / 12) / span**3
    assert compliance.leaf_spring_rate(span, n, b, t, e) == pytest.approx(2 / 3 * prismatic)
    # chosen leaf-spring torsion coefficient: 10 x the two springs' vertical rate, at the spring top
    assert compliance.shear_torsion_coefficient(5400.0, 0.205) == pytest.approx(10 * 2 * 5400 * 0.205**2)


def test_chassis_torsion_relations():
    # Eq. 4.20/4.21: equal twist of the CG section from both ends of a shaft built in at both ends
    # a uniform shaft (x = Jr/Jf = 1) built in at both ends with a torque T at a from the front end: the reactions
    # are T (L - a)/L at the front and T a/L at the rear (mechanics of materials, statically indeterminate shaft)
    torque, a, big_l = 100.0, 3.0, 4.26
    tr = torque * a / big_l
    assert compliance.chassis_torque_split(tr, a, big_l, 1.0) == pytest.approx(torque * (big_l - a) / big_l)
    # a rear section twice as stiff (x = 2) takes twice the share it would
    assert compliance.chassis_torque_split(tr, a, big_l, 2.0) == pytest.approx(torque * (big_l - a) / big_l / 2)

    # Eqs. 4.22-4.23: straight, the front torque is all roll; at right angles all pitch; at 30 deg, tan 30 of it
    def components(torque, psi):
        return compliance.chassis_torque_components(torque, math.cos(psi), math.sin(psi))

    assert components(10.0, 0.0) == pytest.approx((10.0, 0.0))
    assert components(10.0, math.pi / 2) == pytest.approx((0.0, 10.0), abs=1e-12)
    tfx, tfy = components(10.0, math.radians(30))
    assert tfy / tfx == pytest.approx(0.5773502692)
    assert compliance.chassis_twist(-100.0, 1.26, None) == 0.0
    assert compliance.chassis_twist(-100.0, 1.26, 50000.0) == pytest.approx(100 * 1.26 / 50000)
