"""The roll component library's suspensions from the UMTRI Factbook's springs (as TruckSim's datasets cite them):
their roll stiffness derived here by hand from the datasets' numbers, a builder spec that uses them, and the
ordering a stiffer suspension must keep (it does not lower the SRT)."""

from __future__ import annotations

import dataclasses
import itertools

import pytest

from engine.builder import CombinationSpec, build_combination
from engine.models.combination import solve_combination
from engine.models.combination_reference import reference_srt
from engine.vehicle import SUSPENSIONS_IN_ROLL
from engine.vehicle.roll_components import (
    _FACTBOOK_SINGLE_SPRING,
    _FACTBOOK_TANDEM_SPRING,
    NOT_FOUND_IN_ROLL,
    leaf_table_rate,
)

IN_LB = 4.4482216152605 * 0.0254  # N m
PER_DEG = 180.0 / 3.141592653589793  # N m/deg -> N m/rad


def test_the_factbook_steer_axle_is_k_s2_over_2_plus_its_auxiliary_roll_stiffness():
    # '5.5t Leaf, Steer: Compliance': 580 N/mm per side, 813 mm apart (32 in), 1500 in-lb/deg (Factbook p. 200)
    s = SUSPENSIONS_IN_ROLL["factbook-steer-leaf-5.5t"]
    hand = (580e3 * 0.813**2 / 2 + 1500 * IN_LB * PER_DEG) / 1000
    assert s.roll_stiffness_knm_per_rad.value == pytest.approx(hand, rel=1e-12)
    assert s.roll_stiffness_knm_per_rad.value == pytest.approx(201.4, abs=0.05)
    assert "UMTRI-86-12" in s.roll_stiffness_knm_per_rad.source and "p. 200" in s.roll_stiffness_knm_per_rad.source


def test_the_factbook_trailer_tandem_rate_is_the_mid_line_of_its_spring_table_at_the_rated_load():
    # 'Tandem Axle Trailer, 8t / 17.6 kip': at 8 t per axle each spring carries 8000 x 9.81 / 2 = 39.24 kN, between
    # the mid-line's 28771.9 N (25.4 mm) and 48787.9 N (38.1 mm)
    lo, hi = (32523.776 + 25020.0) / 2, (52539.776 + 45036.0) / 2
    assert lo < 8000 * 9.81 / 2 < hi
    rate = (hi - lo) / 12.7
    assert leaf_table_rate(_FACTBOOK_TANDEM_SPRING, 8000 * 9.81 / 2) == pytest.approx(rate, rel=1e-12)
    assert rate == pytest.approx(1576.1, abs=0.05)
    s = SUSPENSIONS_IN_ROLL["factbook-trailer-tandem-leaf-8t"]
    hand = (rate * 1000 * 0.965**2 / 2 + 1000 * IN_LB * PER_DEG) / 1000  # 38 in spread, 1000 in-lb/deg (p. 199)
    assert s.roll_stiffness_knm_per_rad.value == pytest.approx(hand, rel=1e-12)
    assert s.spring_spacing_m.value == 0.965 and s.rated_axle_load_kg.value == 8000.0


def test_the_factbook_single_trailer_axle_rate_is_the_mid_line_of_its_spring_table_at_the_rated_load():
    lo, hi = (36140.0 + 27800.0) / 2, (58268.8 + 50040.0) / 2  # 25.4 and 38.1 mm; 6800 x 9.81 / 2 = 33.35 kN
    assert lo < 6800 * 9.81 / 2 < hi
    rate = (hi - lo) / 12.7
    assert leaf_table_rate(_FACTBOOK_SINGLE_SPRING, 6800 * 9.81 / 2) == pytest.approx(rate, rel=1e-12)
    s = SUSPENSIONS_IN_ROLL["factbook-trailer-single-leaf-6.8t"]
    hand = (rate * 1000 * 0.965**2 / 2 + 1500 * PER_DEG) / 1000  # aux 'Linear: 1500 N-m/deg'
    assert s.roll_stiffness_knm_per_rad.value == pytest.approx(hand, rel=1e-12)
    assert s.roll_stiffness_knm_per_rad.value == pytest.approx(899.3, abs=0.05)


def test_a_spring_table_is_not_extrapolated():
    with pytest.raises(ValueError, match="beyond the table"):
        leaf_table_rate(_FACTBOOK_TANDEM_SPRING, 300e3)
    # each segment's mid-line slope lies between its loading and unloading branches' slopes
    x, comp, ext = _FACTBOOK_SINGLE_SPRING
    for i in range(len(x) - 1):
        slopes = sorted(((comp[i + 1] - comp[i]) / 12.7, (ext[i + 1] - ext[i]) / 12.7))
        mid = leaf_table_rate(_FACTBOOK_SINGLE_SPRING, (comp[i] + ext[i] + comp[i + 1] + ext[i + 1]) / 4)
        assert slopes[0] - 1e-9 <= mid <= slopes[1] + 1e-9


def test_every_library_suspension_names_its_source_and_the_old_ids_remain():
    for sid in ("trucksim-steer-leaf-5.5t", "trucksim-drive-leaf-8.5t", "trucksim-tandem-leaf-15.5t",
                "trucksim-trailer-leaf-18t", "trucksim-dolly-leaf-22.5kip", "trucksim-air-high-roll-8.5t",
                "trucksim-air-high-roll-10t", "trucksim-air-low-roll-6t"):  # fmt: skip
        assert sid in SUSPENSIONS_IN_ROLL
    for s in SUSPENSIONS_IN_ROLL.values():
        for f in ("roll_stiffness_knm_per_rad", "roll_centre_height_m", "lash_deg", "unsprung_mass_kg"):
            assert getattr(s, f).source, (s.id, f)
    assert "walking-beam, trunnion / bogie and four-spring tandems" in NOT_FOUND_IN_ROLL
    assert "suspension lash (any type)" in NOT_FOUND_IN_ROLL


def spec(steer: str, trailer: str) -> dict:
    """A tractor (two axles) and a tandem semitrailer, every group's suspension from the library."""
    return {
        "title": "Factbook suspensions",
        "units": [
            {
                "id": "tractor",
                "kind": "tractor",
                "axle_groups": [
                    {"axles": 1, "tyres_per_axle": 2, "track_m": 2.03, "position_m": 0.0, "tyre": {"size": "11R22.5"},
                     "suspension": {"type": steer}},
                    {"axles": 1, "tyres_per_axle": 4, "track_m": 1.815, "position_m": 3.5,
                     "tyre": {"size": "11R22.5"}, "suspension": {"type": "trucksim-drive-leaf-8.5t"}},
                ],
                "tare": {"mass_kg": 5496.0, "cg_height_m": 1.07, "cg_from_kingpin_m": 1.33},
            },
            {
                "id": "trailer",
                "kind": "semitrailer",
                "axle_groups": [
                    {"axles": 2, "tyres_per_axle": 4, "track_m": 1.82, "position_m": 10.5, "axle_spacing_m": 1.3,
                     "tyre": {"size": "11R22.5"}, "suspension": {"type": trailer}},
                ],
                "tare": {"mass_kg": 6500.0, "cg_height_m": 1.2, "cg_from_kingpin_m": 6.0},
                "payloads": [{"mass_kg": 16000.0, "cg_height_m": 2.0, "cg_from_kingpin_m": 6.0}],
            },
        ],
        "couplings": [{"kind": "fifth-wheel", "position_m": 3.2, "height_m": 1.1,
                       "fifth_wheel": "trucksim-fifth-wheel"}],
    }  # fmt: skip


def governing(steer: str, trailer: str) -> float:
    d = solve_combination(build_combination(CombinationSpec.from_dict(spec(steer, trailer))).combination)
    return d.roll_coupled_units[d.governing].srt


def test_a_builder_spec_takes_the_factbook_suspensions_with_their_sources():
    b = build_combination(
        CombinationSpec.from_dict(spec("factbook-steer-leaf-5.5t", "factbook-trailer-tandem-leaf-8t"))
    )
    d = b.derivation
    roll = d["units[1].groups[0].roll_stiffness_knm_per_rad"]
    assert roll.method == "library" and "Factbook" in roll.source
    assert roll.value == SUSPENSIONS_IN_ROLL["factbook-trailer-tandem-leaf-8t"].roll_stiffness_knm_per_rad.value
    assert d["units[0].groups[0].roll_stiffness_knm_per_rad"].value == pytest.approx(201.4, abs=0.05)
    d = solve_combination(b.combination)
    assert 0.2 < d.roll_coupled_units[d.governing].srt < 0.6


def _scaled(c, factor: float):
    return dataclasses.replace(c, units=tuple(
        dataclasses.replace(u, groups=tuple(
            dataclasses.replace(g, roll_stiffness_knm_per_rad=factor * g.roll_stiffness_knm_per_rad) for g in u.groups))
        for u in c.units))  # fmt: skip


@pytest.mark.parametrize("trailer", ["factbook-trailer-tandem-leaf-8t", "trucksim-trailer-leaf-18t"])
def test_stiffer_suspensions_throughout_do_not_lower_the_srt(trailer):
    c = build_combination(CombinationSpec.from_dict(spec("factbook-steer-leaf-5.5t", trailer))).combination
    srts = []
    for factor in (0.7, 1.0, 1.5, 3.0):
        d = solve_combination(_scaled(c, factor))
        srts.append(d.roll_coupled_units[d.governing].srt)
    assert all(a <= b + 1e-12 for a, b in itertools.pairwise(srts)), srts


def test_a_stiffer_steer_suspension_does_not_lower_the_srt():
    soft, stiff = "factbook-steer-leaf-5.5t", "trucksim-steer-leaf-5.5t"
    assert (SUSPENSIONS_IN_ROLL[soft].roll_stiffness_knm_per_rad.value
            < SUSPENSIONS_IN_ROLL[stiff].roll_stiffness_knm_per_rad.value)  # fmt: skip
    for trailer in ("factbook-trailer-tandem-leaf-8t", "trucksim-trailer-leaf-18t"):
        assert governing(soft, trailer) < governing(stiff, trailer)


def test_a_stiffer_trailer_suspension_alone_can_lower_the_srt_and_the_reference_solution_agrees():
    """Not every stiffer suspension raises the SRT. Three trailer suspensions with the same roll centre and axle,
    in order of roll stiffness: the trailer group lifts off first, and past its lift-off the stiffer suspension ties
    the lifted axle (its roll centre and unsprung mass) to the rolling body, so the roll-coupled unit's CG moves
    further outward by its limit and the governing SRT is lower. The independent nonlinear solution finds the same
    numbers, so this is the statics, not the stepped solution."""
    ids = ["factbook-trailer-tandem-leaf-8t", "factbook-trailer-single-leaf-6.8t", "trucksim-trailer-leaf-18t"]
    ks = [SUSPENSIONS_IN_ROLL[i].roll_stiffness_knm_per_rad.value for i in ids]
    assert ks == sorted(ks)
    for i in ids:
        s = SUSPENSIONS_IN_ROLL[i]
        assert (s.roll_centre_height_m.value, s.unsprung_mass_kg.value) == (0.725, 445.0)
    srts = []
    for i in ids:
        c = build_combination(CombinationSpec.from_dict(spec("trucksim-steer-leaf-5.5t", i))).combination
        d = solve_combination(c)
        assert d.roll_coupled_units[0].lift_sequence[0].unit == "trailer"
        srts.append(d.roll_coupled_units[d.governing].srt)
        assert reference_srt(c) == pytest.approx([u.srt for u in d.roll_coupled_units], abs=1e-9)
    assert all(a > b for a, b in itertools.pairwise(srts)), srts
    assert srts[0] - srts[-1] < 0.01  # a few thousandths of a g
