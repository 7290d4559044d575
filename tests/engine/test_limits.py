"""Closed-form limits, equilibrium invariants and monotonic trends of the 2D and 3D models."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from engine.case import Case, LoadCase, Road
from engine.errors import ConvergenceError, InvalidVehicle
from engine.models import trailer3d
from engine.models.stepping import stage_model
from engine.models.threshold import rollover_threshold
from engine.vehicle.presets import PRESETS
from engine.vehicle.record import static_axle_loads

BTRAIN = PRESETS["table16-btrain"]
TABLE14 = PRESETS["table14-semitrailer"]
STIFF = dict(suspension_stiffness_kn_per_m=1e12, tire_stiffness_kn_per_m=1e12, fifth_wheel_stiffness_kn_per_m=1e12)


def rigid(v):
    return (v.rear_track_m / 2) / (v.rolling_radius_m + v.suspension_height_m + v.cg_height_above_chassis_m)


def test_infinitely_stiff_2d_model_is_the_rigid_model():
    # Eq. 2.6: SRT = t / 2h
    for v in (TABLE14, BTRAIN):
        assert rollover_threshold(Case(v.replace(**STIFF), "2d")).srt == pytest.approx(rigid(v), rel=1e-8)


def test_infinitely_stiff_3d_model():
    stiff = BTRAIN.replace(**STIFF)
    r = rollover_threshold(Case(stiff))
    # stage 1 (LLTf = LLTr): the rigid t/2h
    assert r.stage_values["srt_ts"] == pytest.approx(rigid(BTRAIN), rel=1e-8)
    # full stage, rigid: Eq. 6.18 with Fz19 = 0, Fz3 = Ff (1 - 0.7)/2 and the rest geometry
    ff, _ = static_axle_loads(BTRAIN)
    h = BTRAIN.rolling_radius_m + BTRAIN.suspension_height_m + BTRAIN.cg_height_above_chassis_m
    expected = (0.93 - 1.86 * (ff / BTRAIN.weight_kn) * (1 - 0.7) / 2) / h
    assert r.srt == pytest.approx(expected, rel=1e-8)


def test_tire_and_spring_roll_compliance_alone_matches_rill():
    # the limit: the 2D model with only tire and spring roll compliance agrees with Eq. 2.20 to ~2 %
    for v in (TABLE14, BTRAIN):
        r2d = rollover_threshold(Case(v, "2d")).srt
        assert r2d == pytest.approx(rollover_threshold(Case(v, "rill")).srt, rel=0.02)


def test_rigid_3d_on_a_bank_is_eq_2_8():
    stiff = BTRAIN.replace(**STIFF, front_llt_ratio=1.0)
    for e in (0.04, 0.10):
        # moment balance about the outer contact with the CG at (t/2, h) on a bank: (h1 + h2 e)/(h2 - h1 e)
        h, half = 2.06, 0.93
        srt = rollover_threshold(Case(stiff, road=Road(bank_percent=100 * e))).srt
        assert srt == pytest.approx((half + h * e) / (h - half * e), rel=1e-8)


@settings(max_examples=25, deadline=None)
@given(
    bank=st.floats(-8, 12),
    slope=st.floats(-12, 10),
    psi=st.floats(0, 30),
    d1=st.floats(-0.15, 0.15),
    d2=st.floats(-1.2, 1.5),
    d3=st.floats(-0.2, 0.2),
    ow=st.floats(0, 15),
    lim=st.floats(0.5, 1.0),
)
def test_force_balance_and_eq_6_17_hold_for_any_case(bank, slope, psi, d1, d2, d3, ow, lim):
    m = stage_model(Case(BTRAIN), "full")
    case = trailer3d.SolverCase(
        weight=BTRAIN.weight_kn * (1 + ow / 100),
        bank=math.atan(bank / 100),
        slope=math.atan(slope / 100),
        psi=math.radians(psi),
        d1=d1,
        d2=d2,
        d3=d3,
        llt_limit=lim,
    )
    s = trailer3d.solve(m, case)
    fz = (s.front.fz_outer, s.front.fz_inner, s.rear.fz_outer, s.rear.fz_inner)
    # the tire normal loads carry the weight's normal component (Eq. 4.26)
    assert sum(fz) == pytest.approx(s.loads.pz, rel=1e-10)
    assert s.rear.fz_outer + s.rear.fz_inner == pytest.approx(s.loads.fr, rel=1e-10)  # Eq. 4.27
    assert (s.rear.fz_outer - s.rear.fz_inner) / s.loads.fr == pytest.approx(lim, rel=1e-9)
    # the outer tires carry the lateral force (the inner ones slide, Sec. 4.1.1): along the trailer's y axis,
    # Fy17 + Fy1 cos(psi) + (front unit's longitudinal ground force) sin(psi) = Py
    x_front = np.array([math.cos(case.psi), math.sin(case.psi), 0.0])
    front_long = float(np.array(s.loads.f28) @ x_front)  # what the kingpin passes to the front unit's tires
    lateral = s.rear.fy_outer + s.front.fy_outer * math.cos(case.psi) + front_long * math.sin(case.psi)
    assert lateral == pytest.approx(s.loads.py, rel=1e-9, abs=1e-9)
    # moments about the trailer's x axis through the rear outer contact (Eq. 6.15), plus the roll share of
    # the front unit's pitch reaction when it is articulated (see docs/model.md)
    g = s.geometry
    t2, l13 = m.front.axle_width, m.kingpin_to_front_axle
    p1 = (2 * l13 * math.sin(case.psi) + t2 * (math.cos(case.psi) - 1)) / 2
    lhs = (
        s.front.fz_inner * (g.front.track * math.cos(case.psi) - p1)
        - p1 * s.front.fz_outer
        + s.rear.fz_inner * g.rear.track
    )
    rhs = s.loads.pz * g.cg[1] - s.loads.py * g.cg[2] + _front_pitch_roll_share(s, m, case)
    assert lhs == pytest.approx(rhs, rel=1e-9, abs=1e-9)


def _front_pitch_roll_share(s, m, case):
    """Trailer-x component of the ground's pitch reaction on the front unit (zero at psi = 0)."""
    cp, sp = math.cos(case.psi), math.sin(case.psi)
    f28 = np.array(s.loads.f28)
    load = -f28  # on the front unit, at the kingpin (x' = 0, height z28)
    fx_p = load[0] * cp + load[1] * sp
    z28 = s.geometry.p28[2]
    # pitch moment about y' through the front contact line (x' = -l13, z = 0): load at x' = 0, z = z28
    m_pitch = z28 * fx_p - m.kingpin_to_front_axle * load[2]
    # the ground reacts -m_pitch about y' = (-sin psi, cos psi, 0); its x component is m_pitch sin psi
    return -m_pitch * sp


def test_srt_rises_with_bank_and_falls_with_cg_height():
    banks = [rollover_threshold(Case(BTRAIN, road=Road(bank_percent=b))).srt for b in (-4, 0, 4, 8, 12)]
    assert np.all(np.diff(banks) > 0)
    heights = [rollover_threshold(Case(BTRAIN.replace(cg_height_above_chassis_m=h))).srt for h in (1.0, 1.2, 1.4, 1.6)]
    assert np.all(np.diff(heights) < 0)
    heights2d = [
        rollover_threshold(Case(TABLE14.replace(cg_height_above_chassis_m=h), "2d")).srt for h in (1.0, 1.3, 1.6)
    ]
    assert np.all(np.diff(heights2d) < 0)


def test_srt_falls_with_outward_offset_overweight_and_softer_suspension():
    d1 = [rollover_threshold(Case(BTRAIN, load=LoadCase(lateral_offset_m=x))).srt for x in (-0.1, 0.0, 0.1)]
    assert d1[0] > d1[1] > d1[2]
    ow = [rollover_threshold(Case(BTRAIN, load=LoadCase(overweight_percent=x))).srt for x in (0, 5, 10)]
    assert ow[0] > ow[1] > ow[2]
    k = [rollover_threshold(Case(BTRAIN.replace(suspension_stiffness_kn_per_m=x))).srt for x in (1500, 1800, 2400)]
    assert k[0] < k[1] < k[2]


def test_roll_angle_grows_along_the_curves_and_ends_at_the_limit():
    r = rollover_threshold(Case(BTRAIN), include_curves=True, curve_points=11)
    c = r.curves
    assert c.ay_g[0] == 0.0 and c.ay_g[-1] == pytest.approx(r.srt)
    assert np.all(np.diff(c.roll_angle_deg) > 0)
    assert np.all(np.diff(c.fz_rear_inner_kn) < 0) and c.fz_rear_inner_kn[-1] == pytest.approx(0.0, abs=1e-9)
    assert c.llt_front[-1] == pytest.approx(0.7 * c.llt_rear[-1], rel=1e-6)
    assert np.all(np.diff(c.cg_lateral_m) < 0)  # h1 moves toward the outer tires (Fig. 96)
    assert c.llt_rear[0] == pytest.approx(0.0, abs=1e-9)  # centred load on a flat road


def test_non_convergence_is_reported_not_hidden():
    m = stage_model(Case(BTRAIN), "full")
    case = trailer3d.SolverCase(
        weight=BTRAIN.weight_kn, bank=0.0, slope=0.0, psi=0.0, d1=0.0, d2=0.0, d3=0.0, llt_limit=1.0
    )
    with pytest.raises(ConvergenceError, match="did not converge") as exc:
        trailer3d.solve(m, case, max_iter=3)
    assert exc.value.iterations == 3 and exc.value.residual > 0


def test_a_suspension_at_rills_stability_bound_is_refused_and_just_above_it_is_still_consistent():
    # Eq. 2.17: the body falls over at rest unless k_theta = kLs_side b^2 / 2 > W_rear l12
    w_rear = BTRAIN.weight_kn * 3.0 / 4.26
    k_axle_limit = w_rear * 1.356 * 2 / 0.95**2 / 3  # per axle and side
    with pytest.raises(InvalidVehicle, match="fall over at rest") as exc:
        rollover_threshold(Case(BTRAIN.replace(suspension_stiffness_kn_per_m=0.99 * k_axle_limit)))
    assert exc.value.field == "suspension_stiffness_kn_per_m"
    soft = rollover_threshold(Case(BTRAIN.replace(suspension_stiffness_kn_per_m=1.3 * k_axle_limit)))
    assert 0 < soft.srt < rollover_threshold(Case(BTRAIN)).srt
    assert soft.llt_rear == pytest.approx(1.0, abs=1e-9)
