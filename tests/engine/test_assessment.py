"""Targets, inverse limits and curve assessment (engine side of the road-design tools)."""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import fields

import numpy as np
import pytest

from engine.case import Case, LoadCase, Road
from engine.errors import InvalidInput, InvalidRoad
from engine.models.threshold import BATCH_ROWS, rollover_threshold
from engine.road.curves import Curve, assess_alignment, assess_curves
from engine.road.formulas import max_curve_speed_kmh
from engine.road.limits import limit_table, parameter_limit
from engine.road.standards import side_friction_speed_kmh
from engine.road.targets import check_targets, tilt_table_angle_deg
from engine.vehicle.presets import PRESETS

BTRAIN = PRESETS["table16-btrain"]


def test_targets_and_tilt_angle():
    checks = {c.name: c for c in check_targets(0.3364)}
    assert checks["general"].target_g == 0.35 and not checks["general"].meets
    assert checks["general"].margin_g == pytest.approx(-0.0136)
    assert not checks["dangerous_goods"].meets
    assert check_targets(0.45, {"custom": 0.42})[0].meets
    assert tilt_table_angle_deg(1.0) == pytest.approx(45.0)
    assert tilt_table_angle_deg(0.3364) == pytest.approx(math.degrees(math.atan(0.3364)))
    with pytest.raises(InvalidInput, match="custom"):
        check_targets(0.3, {"custom": -1})


@pytest.mark.parametrize(
    "parameter", ["cg_height_above_chassis_m", "overweight_percent", "lateral_offset_m", "spring_separation_m"]
)
def test_inverse_limit_lands_on_the_target(parameter):
    target = 0.32
    lim = parameter_limit(Case(BTRAIN), target, parameter)
    assert lim.status == "found"
    # solving forward at the limit gives the target back
    v, load = BTRAIN, LoadCase()
    if parameter in ("cg_height_above_chassis_m", "spring_separation_m"):
        v = BTRAIN.replace(**{parameter: lim.value})
    else:
        load = LoadCase(**{parameter: lim.value})
    assert rollover_threshold(Case(v, load=load)).srt == pytest.approx(target, abs=1e-5)
    # and the side of the limit that is allowed meets it
    step = 1e-3 * (1 if lim.kind == "min" else -1)
    if parameter in ("cg_height_above_chassis_m", "spring_separation_m"):
        ok = rollover_threshold(Case(BTRAIN.replace(**{parameter: lim.value + step}))).srt
    else:
        ok = rollover_threshold(Case(BTRAIN, load=LoadCase(**{parameter: lim.value + 100 * step}))).srt
    assert ok > target


def test_limits_that_the_range_cannot_reach():
    # even the lowest CG (l12 = 0.05 m, rigid t/2h = 0.93/0.754 = 1.23) cannot reach 1.5 g
    never = parameter_limit(Case(BTRAIN), 1.5, "cg_height_above_chassis_m")
    assert never.status == "never-met" and never.value is None
    # 50 % overweight (the largest accepted) still leaves the B-train above 0.2 g
    always = parameter_limit(Case(BTRAIN), 0.2, "overweight_percent")
    assert always.status == "always-met" and always.value == pytest.approx(always.range[1])
    assert always.srt_at_limit > 0.2


def test_limit_table_falls_with_overweight():
    rows = limit_table(Case(BTRAIN), 0.33, "cg_height_above_chassis_m", [0, 10, 20])
    values = [r.limit.value for r in rows]
    assert all(r.limit.status == "found" for r in rows)
    assert values[0] > values[1] > values[2]
    with pytest.raises(InvalidInput):
        limit_table(Case(BTRAIN), 0.33, "overweight_percent", [0])


def test_curve_assessment_shares_solves_and_picks_the_governing_speed():
    curves = [
        Curve("tight", 60.0, 6.0, -4.0, 60.0),
        Curve("wide", 900.0, 6.0, -4.0, 100.0),  # same bank and grade as "tight": one solve
        Curve("flat", 250.0, 0.0, 0.0, None),
    ]
    res = assess_curves(Case(BTRAIN), curves, design_standard="thesis-table21")
    assert res.distinct_cases == 2
    tight, wide, flat = res.curves
    srt = rollover_threshold(Case(BTRAIN, road=Road(bank_percent=6.0, slope_percent=-4.0))).srt
    assert tight.srt_g == pytest.approx(srt, rel=1e-9) and wide.srt_g == tight.srt_g
    assert tight.rollover_speed_kmh == pytest.approx(float(max_curve_speed_kmh(srt, 60.0)))  # Eq. 9.1
    assert tight.side_friction_speed_kmh == pytest.approx(side_friction_speed_kmh("thesis-table21", 60.0, 6.0))
    for c in res.curves:
        assert c.safe_speed_kmh == min(c.rollover_speed_kmh, c.side_friction_speed_kmh)
        assert c.governed_by == ("rollover" if c.rollover_speed_kmh < c.side_friction_speed_kmh else "side-friction")
    assert tight.margin_kmh == pytest.approx(tight.safe_speed_kmh - 60.0)
    assert tight.flagged == (tight.margin_kmh < 0)
    assert flat.margin_kmh is None and not flat.flagged


def test_rollover_governs_where_the_srt_is_below_the_side_friction_demand():
    # flat road: the side-friction speed uses e + f <= 0.17 while the B-train's SRT is ~0.34: friction governs;
    # with an LLT limit of 0.6 and a 10 % downhill the SRT (~0.18) drops near f and rollover can govern
    res = assess_curves(
        Case(BTRAIN, rear_llt_limit=0.6, trailer_angle_deg=30),
        [Curve("a", 100.0, 0.0, -10.0)],
        design_standard="thesis-table21",
    )
    c = res.curves[0]
    assert c.srt_g < 0.2
    assert c.governed_by == ("rollover" if c.srt_g < 0.16 else "side-friction")


def test_bad_curves_are_refused_with_their_row():
    with pytest.raises(InvalidRoad, match=r"curves\[1\]") as exc:
        assess_curves(Case(BTRAIN), [Curve("ok", 100.0, 4.0), Curve("zero", 0.0, 4.0)])
    assert exc.value.field == "curves[1].radius_m"
    with pytest.raises(InvalidRoad, match="superelevation"):
        assess_curves(Case(BTRAIN), [Curve("x", 100.0, 40.0)])


def test_many_curves_come_back_with_as_many_rows():
    rng = np.random.default_rng(1)
    curves = [
        Curve(str(i), float(rng.uniform(50, 600)), float(rng.integers(0, 9)), float(rng.integers(-6, 7)))
        for i in range(500)
    ]
    res = assess_curves(Case(BTRAIN), curves)
    assert len(res.curves) == 500 and res.distinct_cases <= 9 * 13
    assert all(c.error is None for c in res.curves)


def test_limit_search_steps_off_an_unsolvable_good_end():
    # Table 15 at l12 = 0.05 m would need ~1.2 g, beyond the mechanism's valid geometry; the search moves
    # to the first solvable CG height and still finds the limit (bounded by the weaker front group, 1 axle)
    v = PRESETS["table15-semitrailer"]
    lim = parameter_limit(Case(v), 0.35, "cg_height_above_chassis_m")
    assert lim.status == "found"
    assert rollover_threshold(Case(v.replace(cg_height_above_chassis_m=lim.value))).srt == pytest.approx(0.35, abs=1e-5)
    front_bound = 1 * 2500 * 0.95**2 / 2 / (364.147 * 3.7 / 8.7)  # k_theta_front / W_front (Eq. 2.17)
    assert lim.range[1] == pytest.approx(0.98 * front_bound)


def test_limit_search_lets_configuration_errors_through():
    from engine.errors import MissingParameter

    with pytest.raises(MissingParameter) as exc:
        parameter_limit(Case(PRESETS["table14-semitrailer"]), 0.35, "cg_height_above_chassis_m")  # 3d needs a front
    assert exc.value.field == "front_track_m"
    assert parameter_limit(
        Case(PRESETS["table14-semitrailer"], model="2d"), 0.35, "cg_height_above_chassis_m"
    ).status == ("found")


def test_a_curve_without_an_srt_is_flagged_with_its_reason():
    # 20 % adverse crossfall with the load 0.45 m toward the outside: the vehicle tips at rest on that curve
    res = assess_curves(
        Case(BTRAIN, load=LoadCase(lateral_offset_m=0.3), rear_llt_limit=0.6),
        [Curve("bad", 100.0, -20.0, 0.0, 40.0), Curve("ok", 100.0, 6.0)],
    )
    bad, ok = res.curves
    assert bad.srt_g is None and bad.error and bad.flagged
    assert ok.error is None


def test_an_alignment_assessed_on_threads_is_the_same_bits():
    """block_map: the side-friction speeds of blocks of BATCH_ROWS curves (and the pairs' solve) on a thread pool give
    every column of the curves assessed in the calling thread, bit for bit."""
    rng = np.random.default_rng(21)
    n = BATCH_ROWS + 700
    radius = rng.uniform(15, 3000, n)
    e = rng.choice([2.0, 4.0, 6.0, 8.0, np.nan], n)  # nan: derived from the distribution at the posted speed
    grade = rng.choice([-4.0, 0.0, 3.0], n)
    posted = rng.choice([40.0, 60.0, 90.0], n)
    case = Case(PRESETS["table16-btrain"])
    blocks: list[int] = []

    def pool_map(function, items):
        items = list(items)
        blocks.append(len(items))
        with ThreadPoolExecutor(3) as pool:
            return list(pool.map(function, items))

    kwargs = {"design_standard": "aashto-2018", "max_superelevation_percent": 8.0}
    alone = assess_alignment(case, radius, e, grade, posted, **kwargs)
    threaded = assess_alignment(case, radius, e, grade, posted, block_map=pool_map, **kwargs)
    assert blocks == [2]  # the side friction's two blocks (fewer distinct pairs than BATCH_ROWS: one block, no map)
    pairs = np.stack([rng.uniform(0, 10, n), grade], axis=1)  # distinct superelevations: two blocks of pairs too
    blocks.clear()
    distinct = assess_alignment(case, radius, pairs[:, 0], grade, posted, block_map=pool_map)
    assert blocks == [2, 2]
    assert distinct.srt_g.tobytes() == assess_alignment(case, radius, pairs[:, 0], grade, posted).srt_g.tobytes()
    for f in fields(alone):
        a, b = getattr(alone, f.name), getattr(threaded, f.name)
        assert (a.tobytes() == b.tobytes()) if isinstance(a, np.ndarray) else a == b, f.name
