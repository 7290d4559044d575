"""Component library: each value against the cell it was read from, the conversions, the sources, the trends.

Expected numbers are the cells of the cited documents (quoted per test), closed forms worked in the test, or
engine results compared with each other (trends) -- never the library's own values restated.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import replace

import pytest

from engine.builder.build import build_vehicle
from engine.builder.spec import AxleGroupSpec, SuspensionSpec, TyreSpec
from engine.case import Case
from engine.errors import InvalidVehicle
from engine.models.threshold import rollover_threshold
from engine.vehicle.components import (
    LOAD_INDEX_KG,
    NOT_FOUND,
    SUSPENSIONS,
    TYRES,
    library_sources,
    parse_load_index,
    parse_tyre_size,
    rated_load_from_load_index_kg,
    roll_stiffness_from_spring_rate,
    static_loaded_radius_m,
)
from tests.engine.test_builder import semitrailer

GOODYEAR = "goodyear-g275msa-335-65r22.5-6.5bar"

#: cells of the Goodyear MF-Tyre 5.0 file 335_65R22_5_G275MSA_95psi.tir (Calspan, 10-JUN-2010), as distributed
#: with Project Chrono (data/vehicle/feda/tires/): [DIMENSION] UNLOADED_RADIUS, WIDTH, ASPECT_RATIO, RIM_RADIUS;
#: [VERTICAL] VERTICAL_STIFFNESS [N/m], FNOMIN [N]
TIR = {
    "UNLOADED_RADIUS": 0.4990,
    "WIDTH": 0.3350,
    "ASPECT_RATIO": 0.6500,
    "RIM_RADIUS": 0.2858,
    "VERTICAL_STIFFNESS": 8.4855e005,
    "FNOMIN": 29912.0,
}


def srt(vehicle) -> float:
    return rollover_threshold(Case(vehicle, "3d")).srt


# ------------------------------------------------------------------------------------------ tyre entries


def test_goodyear_tyre_values_are_the_property_file_cells():
    tyre = TYRES[GOODYEAR]
    # kT: VERTICAL_STIFFNESS = 8.4855e+005 N/m, per tyre, in kN/m
    assert tyre.stiffness_kn_per_m.value == pytest.approx(TIR["VERTICAL_STIFFNESS"] / 1000.0, rel=1e-12)
    assert tyre.stiffness_kn_per_m.unit == "kN/m"
    # lr, converted: the static loaded radius at FNOMIN of the file's linear vertical model Fz = Cz (R0 - r),
    # worked here in SI from the cells: 0.4990 - 29912 / 848550 = 0.4990 - 0.0352507 = 0.4637493 m
    assert tyre.loaded_radius_m.value == pytest.approx(
        TIR["UNLOADED_RADIUS"] - TIR["FNOMIN"] / TIR["VERTICAL_STIFFNESS"]
    )
    assert tyre.loaded_radius_m.value == pytest.approx(0.4637493, abs=1e-7)
    for cell in ("VERTICAL_STIFFNESS", "FNOMIN", "UNLOADED_RADIUS", "CALSPAN"):
        assert cell in tyre.loaded_radius_m.source + tyre.stiffness_kn_per_m.source, cell
    # the size the entry names agrees with the file's own dimension cells (11.25 in rim radius = 0.28575 m,
    # printed 0.2858): the designation and the measurement are one tyre
    size = parse_tyre_size(tyre.size)
    assert size.section_width_m == pytest.approx(TIR["WIDTH"], rel=1e-12)
    assert size.aspect_ratio == pytest.approx(TIR["ASPECT_RATIO"], rel=1e-12)
    assert size.rim_radius_m == pytest.approx(TIR["RIM_RADIUS"], abs=5e-5)
    # and the loaded tyre is deflected: rim < r < R0 < the size's nominal free radius rim/2 + 0.335 x 0.65
    assert size.rim_radius_m < tyre.loaded_radius_m.value < TIR["UNLOADED_RADIUS"] < size.nominal_free_radius_m


def test_static_loaded_radius_is_the_linear_deflection_closed_form():
    # R0 0.5 m, 30 kN on a 1000 kN/m tyre: deflection 0.03 m
    assert static_loaded_radius_m(0.5, 30.0, 1000.0) == pytest.approx(0.47, rel=1e-12)
    assert static_loaded_radius_m(0.5, 0.0, 1000.0) == 0.5
    # more load sinks the axle; a stiffer tyre sinks it less
    assert static_loaded_radius_m(0.5, 40.0, 1000.0) < static_loaded_radius_m(0.5, 30.0, 1000.0)
    assert static_loaded_radius_m(0.5, 30.0, 1200.0) > static_loaded_radius_m(0.5, 30.0, 1000.0)


def test_thesis_tyre_and_suspension_cells_are_unchanged():
    # Table 16 (and 22, 23): lr 0.499 m, kT 840 kN/m, kLs 1800 kN/m, ls 0.205 m, b 0.95 m; Table 15: lr 0.51 m,
    # kT 980 kN/m, kLs 2500 kN/m; Ch. 9: Harwood et al. (2003) range kLs = 1500-2400 kN/m
    assert (
        TYRES["thesis-michelin-xza"].loaded_radius_m.value,
        TYRES["thesis-michelin-xza"].stiffness_kn_per_m.value,
    ) == (
        0.499,
        840.0,
    )
    t15 = TYRES["thesis-trucksim-semitrailer"]
    assert (t15.loaded_radius_m.value, t15.stiffness_kn_per_m.value) == (0.51, 980.0)
    rates = {k: s.stiffness_kn_per_m.value for k, s in SUSPENSIONS.items()}
    assert rates == {
        "thesis-steel-leaf": 1800.0,
        "thesis-trucksim-semitrailer": 2500.0,
        "harwood-2003-soft": 1500.0,
        "harwood-2003-stiff": 2400.0,
    }


# --------------------------------------------------------------------------------------------- load index

#: cells of the load-index tables read from a second source, each against LOAD_INDEX_KG (transcribed from Project
#: Chrono's ChTMeasyTire::GetTireMaxLoad):
PIRELLI = {  # Pirelli, "Tyre load index & chart" (pirelli.com/tyres/en-gb/car/...), rows 140-150
    140: 2500, 141: 2575, 142: 2650, 143: 2725, 144: 2800, 145: 2900, 146: 3000, 147: 3075, 148: 3150, 149: 3250,
    150: 3350,
}  # fmt: skip
MCCORMICK = {142: 2650, 165: 5150, 168: 5600}  # McCormick MTX operator's manual p. 166: "142 = 2650 kg" etc.
HEUVER = {150: 3350, 154: 3750, 164: 5000}  # heuver.com, "Single or dual air mounting on trucks"
COMMERCIAL_GUIDE = {148: 3150, 150: 3350, 152: 3550}  # "Understanding tyre load ratings..." (295/80 R22.5 152/148M)


@pytest.mark.parametrize("source", [PIRELLI, MCCORMICK, HEUVER, COMMERCIAL_GUIDE])
def test_load_index_table_matches_second_sources_cell_by_cell(source):
    for index, kg in source.items():
        assert LOAD_INDEX_KG[index] == kg, index


def test_load_index_table_is_the_truck_range_and_smooth():
    assert sorted(LOAD_INDEX_KG) == list(range(140, 169))
    # a transcription slip (a dropped or swapped digit) would break the progression: every step is 2-4 %
    for a, b in itertools.pairwise(sorted(LOAD_INDEX_KG)):
        assert 1.02 < LOAD_INDEX_KG[b] / LOAD_INDEX_KG[a] < 1.04, (a, b)


def test_rated_load_by_fitment():
    # 295/80 R22.5 152/148M: 3550 kg single, 3150 kg in a dual pair (commercial-tyre guide, cells 152 and 148)
    assert rated_load_from_load_index_kg("152/148", 2) == 3550.0
    assert rated_load_from_load_index_kg("152/148", 4) == 3150.0
    assert rated_load_from_load_index_kg(" 154 / 149 ", 4) == LOAD_INDEX_KG[149]
    assert rated_load_from_load_index_kg(160, 2) == 4500.0  # a super single marked 160K (Heuver)
    assert parse_load_index("160") == (160, None)
    with pytest.raises(InvalidVehicle, match="no dual-fitment index") as e:
        rated_load_from_load_index_kg("160", 4, field="spec.rear.tyre.load_index")
    assert e.value.field == "spec.rear.tyre.load_index"
    for bad, why in (
        ("148/152", "above the single-fitment index"),
        ("139/136", "outside the table's truck range 140-168"),
        ("295/80", "outside"),
        ("152-148", "not a load-index marking"),
        (True, "not a load-index marking"),
    ):
        with pytest.raises(InvalidVehicle, match=why):
            parse_load_index(bad)


# ---------------------------------------------------------------------------------------------- sources

_LOCATOR = re.compile(r"\b(?:Tables?|p\.|pp\.|page|Eq\.|Sec\.|Ch\.|Appendix)\s*\d|\.tir\b|\.cpp\b")
_DOCUMENT = re.compile(r"\b(?:19|20)\d\d\b|thesis")


def test_every_library_value_cites_a_document_and_a_place_in_it_or_says_assumed():
    values = library_sources()
    assert {entry for entry, _, _ in values} == set(TYRES) | set(SUSPENSIONS)
    for entry, name, v in values:
        source = v.source.strip()
        if source.startswith("assumed:"):
            assert len(source) > len("assumed:") + 10, (entry, name)  # and says why
        else:
            assert _LOCATOR.search(source) and _DOCUMENT.search(source), (entry, name, source)
    assert all(why.strip() for why in NOT_FOUND.values())


def test_converted_quantities_say_so():
    # a value that is not the cell itself says it was converted and by which formula
    assert "converted" in TYRES[GOODYEAR].loaded_radius_m.source
    assert "UNLOADED_RADIUS - FNOMIN / VERTICAL_STIFFNESS" in TYRES[GOODYEAR].loaded_radius_m.source


# ----------------------------------------------------------------------------------------- builder, trends


def with_rear(spec, **changes):
    return replace(spec, rear=replace(spec.rear, **changes))


def test_builder_takes_the_new_tyre_from_the_library():
    built = build_vehicle(with_rear(semitrailer(), tyre=TyreSpec(id=GOODYEAR)))
    tyre = TYRES[GOODYEAR]
    assert built.vehicle.rolling_radius_m == tyre.loaded_radius_m.value
    assert built.vehicle.tire_stiffness_kn_per_m == tyre.stiffness_kn_per_m.value
    for name in ("rolling_radius_m", "tire_stiffness_kn_per_m"):
        d = built.derivation[name]
        assert d.method == "library" and "Calspan".upper() in d.source.upper() and d.spec_path == "spec.rear.tyre.id"
    # the 335 mm section width enters the spring-clearance check: duals on a 1.86 m track leave 1.19 m > b 0.95 m
    narrow = AxleGroupSpec(**{**semitrailer().rear.__dict__, "track_m": 1.60, "tyre": TyreSpec(id=GOODYEAR)})
    with pytest.raises(InvalidVehicle, match="inboard of the tyres"):
        build_vehicle(replace(semitrailer(), rear=narrow))  # 1.60 - 2 x 0.335 = 0.93 m < 0.95 m


def test_load_index_sets_the_rating_of_the_fitment():
    # single tyres on the tri-axle: 6 tyres share the rear group's 32000 x 5.625 / 8.7 = 20690 kg -> 3448 kg each
    single = with_rear(semitrailer(), tyres_per_axle=2)
    load_each = 32000 * 5.625 / 8.7 / 6
    assert LOAD_INDEX_KG[150] < load_each < LOAD_INDEX_KG[152]
    build_vehicle(with_rear(single, tyre=replace(single.rear.tyre, load_index="152/148")))  # 3550 kg single: ok
    with pytest.raises(InvalidVehicle, match=r"3448 kg .* tyre rating of 3350 kg") as e:
        build_vehicle(with_rear(single, tyre=replace(single.rear.tyre, load_index="150/146")))  # 3350 kg: over
    assert e.value.field == "spec.payloads[0].mass_kg"
    # the same marking in dual pairs rates each tyre at the dual index, 146 -> 3000 kg, above 20690 / 12 = 1724 kg
    dual = semitrailer()
    build_vehicle(with_rear(dual, tyre=replace(dual.rear.tyre, load_index="150/146")))
    with pytest.raises(InvalidVehicle, match="no dual-fitment index") as e:
        build_vehicle(with_rear(dual, tyre=replace(dual.rear.tyre, load_index="160")))
    assert e.value.field == "spec.rear.tyre.load_index"
    with pytest.raises(InvalidVehicle, match="not both") as e:
        build_vehicle(with_rear(dual, tyre=replace(dual.rear.tyre, load_index="150/146", rated_load_kg=3000.0)))
    assert e.value.field == "spec.rear.tyre.load_index"


def raised(spec, dz):
    """The same vehicle on taller tyres: every height above the ground raised by dz [m]."""
    payloads = tuple(
        replace(p, deck_height_m=p.deck_height_m + dz, load_height_m=p.load_height_m + dz) for p in spec.payloads
    )
    return replace(spec, payloads=payloads, tare=replace(spec.tare, cg_height_m=spec.tare.cg_height_m + dz))


def test_larger_loaded_radius_raises_the_cg_and_lowers_the_srt():
    # each library tyre at one stiffness (840 kN/m), the body riding on it: heights rise with lr
    base = semitrailer()
    lowest = min(t.loaded_radius_m.value for t in TYRES.values())
    results = []
    for tyre in sorted(TYRES.values(), key=lambda t: t.loaded_radius_m.value):
        dz = tyre.loaded_radius_m.value - lowest
        spec = with_rear(raised(base, dz), tyre=TyreSpec(id=tyre.id, stiffness_kn_per_m=840.0))
        built = build_vehicle(spec)
        results.append((tyre.loaded_radius_m.value, built.cg_height_m, srt(built.vehicle)))
    assert len({lr for lr, _, _ in results}) == len(results) >= 3
    for (lr_a, h_a, srt_a), (lr_b, h_b, srt_b) in itertools.pairwise(results):
        assert h_b - h_a == pytest.approx(lr_b - lr_a, abs=1e-12)  # the CG rises with the axle
        assert srt_b < srt_a  # and the engine's threshold falls


def test_softer_tyre_lowers_the_srt():
    # each library tyre's own kT at one loaded radius (0.499 m): SRT rises with the tyre's radial stiffness
    base = semitrailer()
    results = sorted(
        (
            t.stiffness_kn_per_m.value,
            srt(build_vehicle(with_rear(base, tyre=TyreSpec(id=t.id, loaded_radius_m=0.499))).vehicle),
        )
        for t in TYRES.values()
    )
    assert len(results) >= 3
    for (k_a, srt_a), (k_b, srt_b) in itertools.pairwise(results):
        assert k_a < k_b and srt_a < srt_b, results


def test_stiffer_suspension_type_raises_the_srt_across_the_library():
    # library suspensions that share a geometry (ls, b), ordered by roll stiffness k_theta = kLs b^2 / 2 (Eq. 2.11)
    base = semitrailer()
    groups: dict[tuple[float, float], list] = {}
    for s in SUSPENSIONS.values():
        groups.setdefault((s.height_m.value, s.spring_separation_m.value), []).append(s)
    compared = 0
    for (_, b), members in groups.items():
        members.sort(key=lambda s: s.roll_stiffness_knm_per_rad)
        values = [srt(build_vehicle(with_rear(base, suspension=SuspensionSpec(type=s.id))).vehicle) for s in members]
        for s, (srt_a, srt_b) in zip(members[1:], itertools.pairwise(values), strict=True):
            assert s.roll_stiffness_knm_per_rad == pytest.approx(
                roll_stiffness_from_spring_rate(s.stiffness_kn_per_m.value, b)
            )
            assert srt_b > srt_a, s.id
            compared += 1
    assert compared >= 3
