"""PBS screening (engine.dynamics.pbs): what is judged, what is verified, the levels from verified limits only.

The rules' limits by level could not be read (the project's source notes, PBS-AND-ADVISORY-SOURCES.md): the answer
carries no number for them, and no level from them."""

from __future__ import annotations

from dataclasses import replace

import pytest

from engine.dynamics import DynamicsData, GroupData, build, pbs
from engine.dynamics.pbs import LENGTH_LEVELS, NOT_JUDGED, NOT_READ, RULES_VERSION, best_level, screen, vehicle_length_m
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
    for x in s.standards:
        assert [lim["level"] for lim in x.limits] == [1, 2, 3, 4]
        for lim in x.limits:  # no limit was read: no number, said so
            assert lim == {"level": lim["level"], "limit": None, "sense": lim["sense"], "source": NOT_READ,
                           "verified": False}  # fmt: skip
            assert "unverified" in lim["source"] and "could not be read" in lim["source"]
        assert x.level is None  # no verified limit: no level
        assert x.value is not None, x.id
        assert not hasattr(x, "level_unverified")


def test_conditions_say_the_defaults_are_unverified_and_name_those_used():
    """The manoeuvres' defaults were not read in the rules: the answer says so and names the ones left at default."""
    c = build(COMBINATIONS["tractor-semitrailer-table15"])
    default = screen(c).conditions
    assert default["verified"] is False and default["source"].startswith("unverified")
    assert default["unverified_defaults_used"] == [
        "lane_change_speed_kmh", "lane_change_amplitude_g", "pulse_steer_speed_kmh"
    ]  # fmt: skip
    given = screen(c, lane_change_speed_kmh=80.0, pulse_steer_speed_kmh=90.0).conditions
    assert given["lane_change_speed_kmh"] == 80.0 and given["pulse_steer_speed_kmh"] == 90.0
    assert given["unverified_defaults_used"] == ["lane_change_amplitude_g"]


def test_no_sway_is_said_and_gives_no_level_without_a_verified_limit():
    """The tractor-semitrailer's articulation settles without overshoot: no peaks, so no ratio, said in the note;
    with no verified minimum damping there is no level to meet."""
    s = screen(build(COMBINATIONS["tractor-semitrailer-table15"]))
    yd = next(x for x in s.standards if x.id == "yaw_damping")
    assert yd.value is None and yd.note.startswith("no sway")
    assert yd.level is None


def _rows(limits, verified, sense="max"):
    return [{"level": lv, "limit": lim, "sense": sense, "source": "s", "verified": verified}
            for lv, lim in limits.items()]  # fmt: skip


def test_level_is_null_unless_a_verified_limit_exists():
    """best_level reads verified limits only: numbers in unverified rows, or null limits, never give a level."""
    assert best_level(0.5, _rows({1: 1.0, 2: 2.0}, verified=False)) is None
    assert best_level(0.5, _rows({1: None, 2: None}, verified=False)) is None
    assert best_level(0.5, _rows({1: 0.4, 2: 0.6, 3: 0.8}, verified=True)) == 3  # 0.5 <= 0.6 and 0.8, not 0.4
    assert best_level(0.5, _rows({1: 0.4}, verified=True)) is None  # verified but not met
    assert best_level(0.5, _rows({1: 0.4, 2: 0.6}, verified=True, sense="min")) == 1  # 0.5 >= 0.4 only
    assert best_level(None, _rows({1: 1.0}, verified=True)) is None
    # settles without sway: meets any verified minimum, and no level without one
    assert best_level(None, _rows({1: 0.1, 4: 0.1}, verified=True, sense="min"), settles=True) == 4
    assert best_level(None, _rows({1: 0.1}, verified=False, sense="min"), settles=True) is None


def test_a_verified_limit_would_give_its_level_with_its_source(monkeypatch):
    """The screening takes a limit read in a primary text, with that text, and levels from it alone."""
    monkeypatch.setitem(pbs.VERIFIED_LIMITS, "tail_swing", {2: (10.0, "a read text, clause x")})
    monkeypatch.setitem(pbs.VERIFIED_LIMITS, "frontal_swing", {1: (0.0, "a read text, clause y")})
    s = screen(build(COMBINATIONS["adouble"]))
    by_id = {x.id: x for x in s.standards}
    ts = by_id["tail_swing"]
    assert ts.value < 10.0 and ts.level == 2  # the only verified level, met
    assert [(lim["limit"], lim["verified"]) for lim in ts.limits] == [(None, False), (10.0, True), (None, False),
                                                                       (None, False)]  # fmt: skip
    assert ts.limits[1]["source"] == "a read text, clause x"
    assert by_id["frontal_swing"].value > 0.0 and by_id["frontal_swing"].level is None  # verified, not met
    assert by_id["srt"].level is None


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


def test_new_zealands_minimum_srt_is_listed_beside_the_screening_and_judged_on_the_lowest_unit():
    """NZ's 0.35 g (read in the NZ Transport Agency's statement of VDAM 2016, not in the Rule's clause: so
    unverified) is another scheme's limit, not a PBS level: it sits in ``other_limits`` with its source, met exactly
    when the lowest roll-coupled SRT reaches it."""
    for pid in ("tractor-semitrailer-table15", "adouble"):
        c = COMBINATIONS[pid]
        s = screen(build(c))
        (nz,) = [o for o in s.other_limits if o["standard"] == "srt"]
        assert nz["limit"] == 0.35 and nz["verified"] is False and nz["sense"] == "min"
        assert "NZ Transport Agency" in nz["source"] and "Vehicle Dimensions and Mass 2016" in nz["source"]
        lowest = min(r.srt for r in solve_combination(c).roll_coupled_units)
        assert nz["met"] is (lowest >= 0.35)
        assert all(lim["limit"] is None for x in s.standards for lim in x.limits)  # PBS levels stay unread
    assert not screen(build(COMBINATIONS["tractor-semitrailer-table15"])).other_limits[1]["met"]  # SRT 0.30 g
