"""The low-speed turn (engine.dynamics.lowspeed): the tractrix reaches the sum-of-squares steady state."""

from __future__ import annotations

import math

import pytest

from engine.dynamics import build
from engine.dynamics.lowspeed import OUTER_RADIUS_M, TYRE_WIDTH_M, equivalent_axle, low_speed_turn
from engine.vehicle.combination import Combination
from engine.vehicle.combination_presets import COMBINATIONS


def test_equivalent_axle_of_a_tridem():
    """Three axles 1.27 m apart centred 8.7 m behind the kingpin: L_eq = L + sum(d^2)/(n L) = 8.7 + 2(1.27^2)/(3 x
    8.7) (the moment balance of equal axles about the kingpin)."""
    assert equivalent_axle((7.43, 8.7, 9.97), 0.0) == pytest.approx(8.7 + 2 * 1.27**2 / (3 * 8.7), rel=1e-12)
    assert equivalent_axle((5.0,), 0.0) == 5.0


def test_rigid_truck_after_two_full_circles_sweeps_the_steady_width():
    """Steady state of a rigid truck on the circle: the body's nearest point to the centre is the foot of the
    perpendicular, at the equivalent axle, sqrt(Rc^2 - L_eq^2) - w/2 from the centre (sum-of-squares rule)."""
    tt = COMBINATIONS["truck-trailer"]
    c = Combination((tt.units[0],), ())
    m = build(c)
    res = low_speed_turn(m, turn_deg=720.0)
    rc = OUTER_RADIUS_M - c.units[0].groups[0].track_m / 2 - TYRE_WIDTH_M / 2
    assert res.steer_axle_radius_m == pytest.approx(rc)
    leq = equivalent_axle(m.parameters.groups[(0, 1)].axle_positions_m, 0.0)
    w = m.parameters.units[0].width_m.value
    assert res.swept_path_width_m == pytest.approx(OUTER_RADIUS_M - (math.sqrt(rc**2 - leq**2) - w / 2), abs=1e-3)


def test_tractor_semitrailer_after_two_full_circles_sweeps_the_steady_width():
    """The kingpin runs at sqrt(R_f1^2 + (x_c - L1)^2) about the tractor's foot R_f1 = sqrt(Rc^2 - L1^2); the
    trailer's foot at sqrt(R_k^2 - L2^2); the trailer's inner side is the innermost."""
    c = COMBINATIONS["tractor-semitrailer-table15"]
    m = build(c)
    res = low_speed_turn(m, turn_deg=720.0)
    rc = res.steer_axle_radius_m
    l1 = equivalent_axle(m.parameters.groups[(0, 1)].axle_positions_m, 0.0)
    l2 = equivalent_axle(m.parameters.groups[(1, 0)].axle_positions_m, 0.0)
    rf1 = math.sqrt(rc**2 - l1**2)
    rk = math.sqrt(rf1**2 + (c.couplings[0].position_m - l1) ** 2)
    rf2 = math.sqrt(rk**2 - l2**2)
    w = m.parameters.units[1].width_m.value
    assert res.swept_path_width_m == pytest.approx(OUTER_RADIUS_M - (rf2 - w / 2), abs=1e-3)


@pytest.mark.parametrize("cid", sorted(COMBINATIONS))
def test_ninety_degree_turn_lies_between_the_straight_and_the_steady_state(cid):
    """A 90 degree turn sweeps more than the straight vehicle and less than the steady state on the same circle;
    its measures converge in the step (0.1 m against 0.05 m)."""
    m = build(COMBINATIONS[cid])
    r90 = low_speed_turn(m)
    rss = low_speed_turn(m, turn_deg=720.0)
    straight = OUTER_RADIUS_M - (r90.steer_axle_radius_m - max(u.width_m.value for u in m.parameters.units) / 2)
    assert straight < r90.swept_path_width_m < rss.swept_path_width_m
    fine = low_speed_turn(m, step_m=0.05)
    assert fine.swept_path_width_m == pytest.approx(r90.swept_path_width_m, abs=2e-3)
    assert fine.tail_swing_m == pytest.approx(r90.tail_swing_m, abs=2e-3)
    assert fine.frontal_swing_m == pytest.approx(r90.frontal_swing_m, abs=2e-3)
    assert {p["corner"] for p in r90.paths} == {"front-left", "front-right", "rear-left", "rear-right"}
