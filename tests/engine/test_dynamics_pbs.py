"""PBS screening (engine.dynamics.pbs): what is judged, what is verified, the levels from verified limits only."""

from __future__ import annotations

from dataclasses import replace

import pytest

from engine.dynamics import DynamicsData, GroupData, build
from engine.dynamics.pbs import LENGTH_LEVELS, NOT_JUDGED, RULES_VERSION, screen, vehicle_length_m
from engine.models.combination import solve_combination
from engine.vehicle.combination import Combination
from engine.vehicle.combination_presets import COMBINATIONS

IDS = [
    "srt", "rearward_amplification", "high_speed_transient_offtracking", "yaw_damping", "low_speed_swept_path",
    "tail_swing", "frontal_swing",
]  # fmt: skip


def test_adouble_screening_judges_the_contracts_standards_with_unverified_limits():
    c = COMBINATIONS["adouble"]
    s = screen(build(c))
    assert [x.id for x in s.standards] == IDS
    assert s.screening is True and s.note == "indicative screening, not a certification"
    assert s.rules_version == RULES_VERSION
    assert set(NOT_JUDGED) == set(s.not_judged) and "steer-tyre friction demand" in s.not_judged
    srts = [r.srt for r in solve_combination(c).roll_coupled_units]
    by_id = {x.id: x for x in s.standards}
    assert by_id["srt"].value == pytest.approx(min(srts))
    # RA's limit is 5.7 x the rearmost roll-coupled unit's SRT (unverified)
    assert [lim["limit"] for lim in by_id["rearward_amplification"].limits] == pytest.approx([5.7 * srts[-1]] * 4)
    for x in s.standards:
        assert x.limits and all(not lim["verified"] and "unverified" in lim["source"] for lim in x.limits)
        assert x.level is None  # no verified limit: no level
        assert x.value is not None, x.id


def test_no_sway_is_said_and_meets_any_minimum_damping():
    """The tractor-semitrailer's articulation settles without overshoot: no peaks, so no ratio, said in the note."""
    s = screen(build(COMBINATIONS["tractor-semitrailer-table15"]))
    yd = next(x for x in s.standards if x.id == "yaw_damping")
    assert yd.value is None and yd.note.startswith("no sway")
    assert yd.level is None and yd.level_unverified == 4


def test_level_from_unverified_limits_is_the_best_met():
    s = screen(build(COMBINATIONS["tractor-semitrailer-table15"]))
    hsto = next(x for x in s.standards if x.id == "high_speed_transient_offtracking")
    met = [lim["level"] for lim in hsto.limits if hsto.value <= lim["limit"]]
    assert hsto.level_unverified == (max(met) if met else None)


@pytest.mark.parametrize("cid", sorted(COMBINATIONS))
def test_network_level_by_length(cid):
    """NHVR's lengths: the smallest level whose Class A (B) length admits the vehicle."""
    m = build(COMBINATIONS[cid])
    s = screen(m)
    length = vehicle_length_m(m)
    assert s.length_m == length
    assert s.network_level_by_length["class_a"] == min(lv for lv, (a, _) in LENGTH_LEVELS.items() if length <= a)
    assert s.network_level_by_length["verified"] is True


def test_unstable_vehicle_is_answered_unstable_not_with_a_number():
    """An oversteering rigid truck above its critical speed: RA, HSTO and yaw damping say unstable."""
    tt = COMBINATIONS["truck-trailer"]
    truck = tt.units[0]
    c = Combination((replace(truck, groups=(truck.groups[0], replace(truck.groups[1], axles=1))),), ())
    data = DynamicsData(groups={("truck", "steer"): GroupData(9.0), ("truck", "drive"): GroupData(3.0)})
    s = screen(build(c, data))
    by_id = {x.id: x for x in s.standards}
    for sid in ("rearward_amplification", "high_speed_transient_offtracking", "yaw_damping"):
        assert by_id[sid].value is None and by_id[sid].note.startswith("unstable")
