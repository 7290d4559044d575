"""Closed-form models of Ch. 2 and road formulas of Ch. 9 against hand calculations and Tables 18, 20, 21."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine import road
from engine.case import Case, LoadCase, Road
from engine.errors import InvalidRoad
from engine.models import classic
from engine.models.threshold import rollover_threshold
from engine.vehicle.presets import PRESETS

TABLE14 = PRESETS["table14-semitrailer"]
BTRAIN = PRESETS["table16-btrain"]


def test_rigid_and_banked_rigid():
    # Eqs. 2.6 and 2.8 for the B-train: t = 1.86 m, h = 0.499 + 0.205 + 1.356 = 2.06 m
    assert rollover_threshold(Case(BTRAIN, "rigid")).srt == pytest.approx(0.93 / 2.06, rel=1e-12)
    r = rollover_threshold(Case(BTRAIN, "rigid-bank", road=Road(bank_percent=6)))
    assert r.srt == pytest.approx(0.93 / 2.06 + 0.06, rel=1e-12)
    off = rollover_threshold(Case(BTRAIN, "rigid", load=LoadCase(lateral_offset_m=0.1, vertical_offset_m=0.2)))
    assert off.srt == pytest.approx(0.83 / 2.26, rel=1e-12)


def test_rill_by_hand_for_table14():
    # Eq. 2.20 with k_theta = 5400 * 0.95^2 / 2 (Eq. 2.11), kT = 5040 per side, mg = 250 kN, l12 = 1.346
    k_theta_star = 5400 * 0.95**2 / 2 / (250 * 1.346)
    k_t_star = 1.86 * 5040 / 250
    expected = 0.93 / (2.05 + 1.346 / (k_theta_star - 1)) - 1 / k_t_star
    r = rollover_threshold(Case(TABLE14, "rill"))
    assert r.srt == pytest.approx(expected, rel=1e-12)
    assert r.srt == pytest.approx(0.3838, abs=5e-5)
    # Winkler with Delta t from the same roll compliance is the same mechanics (see classic.py)
    assert rollover_threshold(Case(TABLE14, "winkler")).srt == pytest.approx(r.srt, rel=1e-12)


def test_rill_tends_to_rigid_with_stiff_tires_and_suspension():
    assert classic.rill(1.86, 2.05, 1.346, 1e12, 1e12, 250) == pytest.approx(0.93 / 2.05, rel=1e-9)


# the B-train of Table 16 in the symbols of Ch. 2, by hand: rear group 3 axles x 1800 kN/m per side, 6 tires x
# 840 kN/m per side, W_rear = 355.22 x 3.0 / 4.26 (Eq. 4.27 at rest), h0 = lr + ls, h = h0 + l12
W_REAR = 355.22 * 3.0 / 4.26
K_THETA_R = 3 * 1800 * 0.95**2 / 2  # Eq. 2.11
K_T = 3 * 2 * 840.0
H0, H = 0.499 + 0.205, 0.499 + 0.205 + 1.356


def test_chang_by_hand_for_the_btrain_on_an_8_percent_bank():
    # Eq. 2.22 with the suspension roll of Eqs. 2.15, 2.17: theta1 = W/(t kT), theta = A (ay + theta1),
    # A = W l12 / (k_theta - W l12); SRT = t/2h + (1 - h0/h)(phi - theta) is linear in the SRT
    phi = math.atan(0.08)
    a = W_REAR * 1.356 / (K_THETA_R - W_REAR * 1.356)
    theta1 = W_REAR / (1.86 * K_T)
    c = 1 - H0 / H
    expected = (0.93 / H + c * (phi - a * theta1)) / (1 + c * a)
    r = rollover_threshold(Case(BTRAIN, "chang", road=Road(bank_percent=8)))
    assert r.srt == pytest.approx(expected, rel=1e-12)
    assert math.radians(r.roll_angle_deg) == pytest.approx(a * (expected + theta1), rel=1e-12)
    # a bank raises it, less than the rigid model's + e (the body rolls out of the bank)
    flat = rollover_threshold(Case(BTRAIN, "chang")).srt
    assert flat < r.srt < flat + 0.08
    assert classic.chang(1.86, 2.06, 0.704, 0.0, 0.0) == pytest.approx(0.93 / 2.06)  # rigid suspension: t/2h


def test_gillespie_by_hand_for_the_btrain():
    k_f, k_r = 3600 * 0.95**2 / 2, 5400 * 0.95**2 / 2
    m = 355.22 * 1.356
    expected = (1.86 / (2 * 2.06)) / (1 + (1 - 0.704 / 2.06) * m / (k_f + k_r - m))
    assert rollover_threshold(Case(BTRAIN, "gillespie")).srt == pytest.approx(expected, rel=1e-12)


def test_navin_by_hand_for_the_btrain_on_a_4_percent_bank():
    # Eq. 2.30 with theta = B SRT (Eq. 2.27): lre = L - a = 1.26 m, L = 4.26 m, h5 = lr + ls + lf = 0.804 m (kingpin)
    k_theta_f = 2 * 1800 * 0.95**2 / 2
    m = 355.22 * (H - H0)
    b = m / (k_theta_f + K_THETA_R - m)
    phi, r = math.atan(0.04), 1.26 / 4.26
    n0 = 0.93 * (1 - r) + H * phi - 0.804 * r * phi
    d0 = 1.86 * phi / 2 * (r - 1) + H - 0.804 * r
    expected = n0 / (d0 + (H - H0) * b)
    res = rollover_threshold(Case(BTRAIN, "navin", road=Road(bank_percent=4)))
    assert res.srt == pytest.approx(expected, rel=1e-12)
    assert res.parameters["h5"] == pytest.approx(0.804)
    # rigid and flat: (t/2)(1 - lre/L) / (h - h5 lre/L), the moment balance of Eq. 2.29 about the roll axis
    assert classic.navin(1.86, 2.06, 0.704, 0.804, 1.26, 4.26, 0.0, 0.0) == pytest.approx(
        0.93 * (1 - r) / (2.06 - 0.804 * r)
    )


def test_navin_refuses_a_cg_below_its_roll_axis():
    # a CG so low (l12 0.03 m) under a kingpin raised 1 m that it lies below the axis from the fifth wheel to the
    # rear outer tire: Eq. 2.29's moment arm h - h5 lre/L is negative and the formula would give SRT < 0
    from engine.errors import InvalidInput

    low = BTRAIN.replace(cg_height_above_chassis_m=0.03, fifth_wheel_height_m=1.0)
    with pytest.raises(InvalidInput, match="below Navin's roll axis") as exc:
        rollover_threshold(Case(low.replace(wheelbase_m=4.26, front_axle_to_cg_m=0.5), "navin"))
    assert exc.value.field == "cg_height_above_chassis_m"


# the closed forms of Ch. 2 and the equation the thesis gives each (Eqs. 2.6-2.30), and its own two models
THESIS_EQUATIONS = {
    "rigid": "Eq. 2.6",
    "rigid-bank": "Eq. 2.8",
    "winkler": "Eq. 2.10",
    "rill": "Eq. 2.20",
    "chang": "Eq. 2.22",
    "gillespie": "Eq. 2.28",
    "navin": "Eq. 2.30",
}


def test_the_registry_has_every_model_of_the_thesis_with_its_equation():
    from engine.models.registry import MODELS

    assert set(MODELS) == {"3d", "2d", "combination", *THESIS_EQUATIONS}  # and the whole-combination model
    for model_id, equation in THESIS_EQUATIONS.items():
        assert MODELS[model_id].equation == equation
        assert not MODELS[model_id].curves and MODELS[model_id].batch is None
    assert MODELS["3d"].curves and MODELS["2d"].curves


@pytest.mark.parametrize("model_id", ["3d", "2d", *THESIS_EQUATIONS])
def test_each_model_refuses_every_input_it_does_not_account_for(model_id):
    """A non-zero road or load input outside a model's ``takes`` is refused naming the field, never ignored."""
    from engine.errors import InvalidInput
    from engine.models.registry import INPUTS, MODELS

    model = MODELS[model_id]
    nonzero = {
        "bank": {"road": Road(bank_percent=4)},
        "slope": {"road": Road(slope_percent=4)},
        "trailer_angle": {"trailer_angle_deg": 10.0},
        "d1": {"load": LoadCase(lateral_offset_m=0.05)},
        "d2": {"load": LoadCase(longitudinal_offset_m=0.2)},
        "d3": {"load": LoadCase(vertical_offset_m=0.05)},
        "overweight": {"load": LoadCase(overweight_percent=5)},
    }
    for key, field, _get, _exc in INPUTS:
        case = Case(BTRAIN, model_id, **nonzero[key])
        if key in model.takes:
            assert rollover_threshold(case).srt > 0
        else:
            with pytest.raises(InvalidInput) as exc:
                rollover_threshold(case)
            assert exc.value.field == field


# ----------------------------------------------------------------------------------- road formulas


@pytest.mark.parametrize("srt,speed", [(0.4485, 67.5), (0.3364, 58.5), (0.2528, 50.7)])
def test_table18_max_speed_on_80_m(srt, speed):
    assert road.max_curve_speed_kmh(srt, 80.0) == pytest.approx(speed, abs=0.05)  # Eq. 9.1, Table 18


@pytest.mark.parametrize("srt,speed", [(0.23, 59.2), (0.22, 57.9), (0.202, 55.5), (0.172, 51.2)])
def test_table20_max_speed_on_120_m(srt, speed):
    assert road.max_curve_speed_kmh(srt, 120.0) == pytest.approx(speed, abs=0.05)  # Eq. 9.1, Table 20


def test_table21_side_friction_and_interpolation():
    assert road.side_friction_factor("thesis-table21", 60.0) == pytest.approx(0.15)
    assert road.side_friction_factor("thesis-table21", 60.0, "high") == pytest.approx(0.17)
    assert road.side_friction_factor("thesis-table21", 30.0, "mid") == pytest.approx((0.17 + 0.28) / 2)
    assert road.side_friction_factor("thesis-table21", 55.0) == pytest.approx(0.155)  # halfway between 50 and 60 km/h
    assert road.side_friction_factor("thesis-table21", np.array([80.0, 120.0])) == pytest.approx([0.14, 0.09])
    with pytest.raises(InvalidRoad, match="30-120"):
        road.side_friction_factor("thesis-table21", 130.0)
    with pytest.raises(InvalidRoad):
        road.side_friction_factor("thesis-table21", 60.0, "median")


def test_minimum_radius_both_criteria_and_which_governs():
    # 80 km/h, e = 8 %: AASHTO R = 80^2 / (127 (0.08 + 0.14)); rollover R = 80^2 / (127 SRT)
    r = road.min_radius(80.0, 8.0, srt_g=0.285)
    assert r.aashto_min_radius_m == pytest.approx(6400 / (127 * 0.22))
    assert r.rollover_min_radius_m == pytest.approx(6400 / (127 * 0.285))
    assert r.governed_by == "side-friction" and r.governing_min_radius_m == r.aashto_min_radius_m
    tight = road.min_radius(80.0, 8.0, srt_g=0.18)
    assert tight.governed_by == "rollover" and tight.governing_min_radius_m == tight.rollover_min_radius_m
    given = road.min_radius(80.0, 8.0, srt_g=0.3, side_friction=0.1)
    assert given.side_friction == 0.1 and given.aashto_min_radius_m == pytest.approx(6400 / (127 * 0.18))


def test_eq_9_2_has_the_srt_floor_on_e_plus_f():
    # 0.01 e + f = 0.01 is the smallest Eq. 9.2 takes (as srt_g >= 0.01 for Eq. 9.3): 130^2 / (127 * 0.01) m
    assert road.side_friction_min_radius_m(130.0, 0.0, 0.01) == pytest.approx(16900 / 1.27, rel=1e-12)
    assert road.side_friction_min_radius_m(130.0, -9.0, 0.1) == pytest.approx(16900 / 1.27, rel=1e-9)
    for e, f in [(0.0, 5e-324), (-9.5, 0.1), (-20.0, 0.1)]:  # tiny or negative demand: refused, never inf
        with pytest.raises(InvalidRoad) as err:
            road.side_friction_min_radius_m(130.0, e, f)
        assert err.value.field == "superelevation_percent"
    with pytest.raises(InvalidRoad) as err:
        road.min_radius(60.0, 0.0, srt_g=0.3, side_friction=0.005)
    assert err.value.field == "side_friction" and "[0.01, 1]" in str(err.value)


def test_side_friction_speed_solves_the_implicit_equation():
    v = road.side_friction_speed_kmh("thesis-table21", 250.0, 6.0)
    assert v == pytest.approx(math.sqrt(127 * 250 * (0.06 + road.side_friction_factor("thesis-table21", v))), rel=1e-12)
    many = road.side_friction_speed_kmh("thesis-table21", np.array([15.0, 250.0, 5000.0]), np.array([0.0, 6.0, 2.0]))
    assert many[1] == pytest.approx(v)
    assert many[0] == pytest.approx(math.sqrt(127 * 15 * 0.17))  # below 30 km/h: f(30) used
    assert many[2] == pytest.approx(math.sqrt(127 * 5000 * (0.02 + 0.09)))  # above 120 km/h: f(120)
