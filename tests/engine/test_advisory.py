"""Advisory speeds (engine.road.advisory) against the cited rules, closed forms and a second formulation.

Sources of expected numbers: TxDOT, Procedures for Establishing Speed Zones (Direct Method Step 2: x 0.97, +1 mph,
down to 5 mph; Calculated Speed: f 0.15 / 0.18 / 0.31); the point-mass curve formula in its metric (V^2 = 127 R
(e + f), km/h and m) and US (V^2 = 15 R (e + f), mph and ft) forms; tan of the ball-bank angle when the body does not
roll; MUTCD 11e Table 2C-4 bands as transcribed (5/10/15/20 mph).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.errors import InvalidRoad
from engine.road import advisory as adv

FT = 0.3048
MPH = 1.609344


def test_us_display_follows_txdot_rounding():
    # TxDOT Direct Method Step 2: add 1.0 mph, round down to 5 mph ("curve speeds that end in 4 or 9 up")
    for raw_mph, shown_mph in ((44.0, 45.0), (43.9, 40.0), (39.0, 40.0), (38.99, 35.0), (45.0, 45.0), (30.2, 30.0)):
        got = adv.displayed_speed_kmh(raw_mph * MPH, "us") / MPH
        assert got == pytest.approx(shown_mph, abs=1e-9), raw_mph


def test_display_is_a_multiple_of_the_increment_and_the_rule_bounds_it():
    raw = np.linspace(12.0, 130.0, 4001)
    us = adv.displayed_speed_kmh(raw, "us") / MPH
    assert np.allclose(us / 5.0, np.round(us / 5.0), atol=1e-9)
    # +1 mph then down to 5: the shown speed lies in (raw - 4, raw + 1] mph
    assert np.all(us <= raw / MPH + 1.0 + 1e-9) and np.all(us > raw / MPH - 4.0 - 1e-9)
    metric = adv.displayed_speed_kmh(raw, "metric")
    assert np.allclose(metric / 10.0, np.round(metric / 10.0), atol=1e-9)
    assert np.all(metric <= raw + 1e-9) and np.all(metric > raw - 10.0)


def test_increment_that_is_not_a_sign_increment_is_refused():
    adv.check_increment("us", 5)
    adv.check_increment("metric", 10)
    with pytest.raises(InvalidRoad) as e:
        adv.check_increment("us", 10)
    assert e.value.field == "increment"
    with pytest.raises(InvalidRoad):
        adv.check_increment("metric", 5)
    with pytest.raises(InvalidRoad):
        adv.check_units("imperial")


def test_level_curve_side_friction_method_is_the_point_mass_speed_in_both_unit_systems():
    # TxDOT calculated speed on a level curve fast enough for the 0.15 band: V = sqrt(127 R f) km/h; its US form
    # V = sqrt(15 R_ft f) mph gives the same speed within the rounding of the two constants (127 vs 127.14,
    # 15 vs 14.96: 0.3 % apart in speed at most)
    r = np.array([300.0, 600.0, 1500.0])
    got = adv.criterion_speed_kmh(adv.TXDOT_CALCULATED, r, 0.0)
    assert np.allclose(got, np.sqrt(127.0 * r * 0.15), rtol=1e-12)
    us_mph = np.sqrt(15.0 * (r / FT) * 0.15)
    assert np.allclose(got / MPH, us_mph, rtol=0.005)
    # and with superelevation, e in ft/ft in the US form and in % in the metric one
    got_e = adv.criterion_speed_kmh(adv.TXDOT_CALCULATED, r, 6.0)
    assert np.allclose(got_e / MPH, np.sqrt(15.0 * (r / FT) * (0.06 + 0.15)), rtol=0.005)


def test_ball_bank_conversion_closed_form_and_residual():
    # no body roll: the ball reads atan(f), so f = tan(angle)
    for angle in (10.0, 12.0, 14.0, 16.0):
        assert adv.ball_bank_side_friction(angle, 0.0) == pytest.approx(math.tan(math.radians(angle)), rel=1e-12)
    # with the stated roll allowance: atan(f) + k f = angle
    for angle in (10.0, 16.0):
        f = adv.ball_bank_side_friction(angle, 5.0)
        assert math.degrees(math.atan(f)) + 5.0 * f == pytest.approx(angle, abs=1e-9)
        assert f < math.tan(math.radians(angle))  # roll takes part of the reading


def test_speed_dependent_criterion_is_met_up_to_the_answer_and_not_beyond():
    # the answer V* is the supremum of the speeds that meet the criterion: just below it the curve's demand is within
    # the band's f, just above it the demand exceeds it (at a band's edge V* itself belongs to the failing band)
    r = np.geomspace(15.0, 3000.0, 300)
    e = np.full(r.shape, 4.0)
    for bands in (adv.BALL_BANK_2009, adv.BALL_BANK_TRADITIONAL, adv.TXDOT_CALCULATED):
        f_band = adv.band_values_side_friction(bands)
        edges = np.array(bands.edges_mph) * MPH
        v = adv.criterion_speed_kmh(bands, r, e)

        def allowed(speed, f_band=f_band, edges=edges):
            return f_band[np.searchsorted(edges, speed, side="right") - 1]

        below = v * (1 - 1e-7)
        assert np.all(below**2 / (127.0 * r) - 0.01 * e <= allowed(below) + 1e-9)
        above = v * (1 + 1e-6) + 1e-6
        assert np.all(above**2 / (127.0 * r) - 0.01 * e > allowed(above) - 1e-9)


def test_direct_method_truck_speed_and_display():
    # TxDOT Direct Method: average car speed 45.36 mph -> trucks 44.0 mph -> +1 -> 45 mph shown
    cols = adv.advise_curves([200.0], [6.0], [90.0], measured_car_speed_kmh=[44.0 / 0.97 * MPH])
    assert cols.methods["txdot-direct"][0] / MPH == pytest.approx(44.0, rel=1e-12)
    assert cols.advisory_speed_kmh[0] / MPH == pytest.approx(45.0)
    assert adv.ADVICE_GOVERNED_BY[cols.governed_by[0]] == "txdot-direct"
    # without a measurement the 2009 ball-bank criterion governs, labelled legacy
    cols = adv.advise_curves([200.0], [6.0], [90.0])
    assert adv.ADVICE_GOVERNED_BY[cols.governed_by[0]] == adv.BALL_BANK_2009.id
    assert adv.method_source(adv.BALL_BANK_2009.id)[1] is True
    assert adv.method_source("design-method")[2] is False  # the primary method: unverified here


def test_treatment_by_speed_difference():
    posted = np.array([55, 55, 55, 55, 55, 55]) * MPH
    shown = np.array([55, 50, 45, 40, 35, 25]) * MPH
    codes = adv.treatment_code(posted, shown)
    assert list(codes) == [0, 1, 2, 3, 4, 4]
    assert adv.TREATMENTS[0] == ()
    assert any("chevron" in d for d in adv.TREATMENTS[4])
    assert adv.treatment_code([np.nan], [50.0])[0] == -1


def test_w1_13_rule():
    shown = np.array([45.0, 45.0, 45.0]) * MPH  # 72.4 km/h
    warn = adv.rollover_warning([80.0, 85.0, np.nan], shown, margin_kmh=10.0)
    assert list(warn) == [True, False, False]  # 80 - 10 < 72.4; 85 - 10 > 72.4; unknown: no warning
    with pytest.raises(InvalidRoad):
        adv.rollover_warning([80.0], shown[:1], margin_kmh=-1.0)
    cols = adv.advise_curves([100.0, 100.0], [6.0, 6.0], [90.0, 90.0], [40.0, 200.0], deflection_deg=[30.0, 3.0])
    assert list(cols.truck_rollover_warning) == [True, False]
    assert list(cols.small_deflection) == [False, True]


# ------------------------------------------------------------------------------------------------- alignments


def test_curves_within_600_ft_share_one_sign():
    # TxDOT: curves separated by a tangent of 600 ft (182.88 m) or less get one sign
    start = np.array([0.0, 300.0, 600.0, 1000.0])
    length = np.array([200.0, 200.0, 200.0, 100.0])  # tangents 100, 100, 200 m
    assert list(adv.sign_groups(start, length)) == [0, 0, 0, 3]
    assert list(adv.sign_groups([0.0, 200.0 + 182.88], [200.0, 50.0])) == [0, 0]  # exactly 600 ft: shared
    assert list(adv.sign_groups([0.0, np.nan, 900.0], [200.0, 100.0, 100.0])) == [0, -1, 2]


def _columns():
    from engine.case import Case
    from engine.road.curves import assess_alignment
    from engine.vehicle.presets import PRESETS

    case = Case(PRESETS["table16-btrain"], "3d")
    radius = np.array([120.0, 400.0, 90.0, 800.0])
    e = np.array([6.0, 4.0, 8.0, 2.0])
    grade = np.array([0.0, -3.0, 2.0, 0.0])
    posted = np.array([90.0, 90.0, 90.0, np.nan])
    return assess_alignment(case, radius, e, grade, posted)


def test_advise_alignment_groups_signs_and_carries_the_profile():
    cols = _columns()
    start = np.array([0.0, 250.0, 1500.0, 3000.0])
    length = np.array([150.0, 200.0, 120.0, 150.0])  # tangents 100 m (shared sign), 1050 m, 1380 m
    out = adv.advise_alignment(cols, start, length, desired_speed_kmh=80.0)
    alone = adv.advise_curves(
        cols.radius_m, cols.superelevation_percent, cols.posted_speed_kmh, cols.rollover_speed_kmh
    )
    shown = out.advisory.advisory_speed_kmh
    assert list(out.sign_group) == [0, 0, 2, 3]
    assert shown[0] == shown[1] == min(alone.advisory_speed_kmh[:2])  # the group's lowest
    assert shown[2] == alone.advisory_speed_kmh[2]
    assert list(out.advisory.truck_rollover_warning) == list(
        adv.rollover_warning(cols.rollover_speed_kmh, shown, adv.ROLLOVER_MARGIN_KMH)
    )
    p = out.profile
    assert p.reasons == [None] * 4 and p.station_m.size > 0
    # the tangent speed: posted where given (90), else the desired 80 km/h; never above a curve's safe speed
    assert p.speed_kmh.max() <= 90.0 + 1e-9
    for i in range(4):
        s = np.linspace(start[i], start[i] + length[i], 5)
        v = np.sqrt(np.interp(s, p.station_m, p.speed_kmh**2))
        assert np.all(v <= cols.safe_speed_kmh[i] + 1e-6) and np.all(v <= shown[i] + 1e-6)
    assert np.all(np.isfinite(p.approach_speed_kmh)) and np.all(p.required_deceleration_mps2[1:] >= 0)
    # the first curve's approach length is unknown (no road start given): a rate only where it needs none
    first = p.required_deceleration_mps2[0]
    assert first == 0.0 if p.approach_speed_kmh[0] <= p.curve_speed_kmh[0] else np.isnan(first)


def test_advise_alignment_without_a_tangent_speed_gives_reasons():
    cols = _columns()
    out = adv.advise_alignment(cols, [0.0, 250.0, 1500.0, 3000.0], [150.0, 200.0, 120.0, 150.0])
    assert out.profile.station_m.size == 0
    assert out.profile.reasons[3].startswith("no posted speed") and out.profile.reasons[0].startswith("no profile")
