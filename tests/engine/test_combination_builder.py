"""The combination builder (engine.builder.combination) against a preset rebuilt from its sources, force
balance, the rigid closed form and bad input.

Independent numbers used here:
* the preset ``tractor-semitrailer-table15``'s published source values: TruckSim's '2A Day Cab' sprung mass (M_SU
  4455 kg, H_CG_SU 1175 mm, LX_CG_SU 1110 mm) and axles (steer 362 kg at 510 mm, drive 679 kg at 530 mm, LX_AXLE_2
  3500 mm), the thesis's Table 15 (W = 364.147 kN, lr + ls + l12 = 0.51 + 0.205 + 1.285 m, a = 5.0 m, L = 8.7 m,
  kLs = 2500 kN/m, b = 0.95 m, kT = 980 kN/m, l13 = 0.9 m);
* force balance: the groups' static loads sum to the total mass x g (Eq. 4.27 summed over the chain);
* the rigid closed form of a roll-coupled unit on a level road, SRT = sum(N_g T_g/2) / sum(W h) (Eq. 2.6 summed);
* the direction of the SRT with the CG height (Eq. 2.6: the SRT falls as h rises).
"""

from __future__ import annotations

import copy
import dataclasses
import itertools

import pytest

from engine.builder import CombinationSpec, build_combination
from engine.builder.last_unit import last_unit_spec
from engine.case import Case
from engine.errors import InvalidInput, InvalidVehicle
from engine.models import rollover_threshold
from engine.models.combination import rigid_srt, solve_combination
from engine.vehicle import COMBINATIONS, PRESETS
from engine.vehicle.combination import G_M_PER_S2, roll_coupled_units, static_loads

T15 = PRESETS["table15-semitrailer"]
RIGID = 1e12

# TruckSim '2A Day Cab' (the preset's sources): sprung mass and the two axles' unsprung masses at their heights
SPRUNG, Z_SPRUNG, X_SPRUNG = 4455.0, 1.175, 1.11
STEER_KG, STEER_Z, DRIVE_KG, DRIVE_Z, DRIVE_X = 362.0, 0.51, 679.0, 0.53, 3.5
TRACTOR_TARE = SPRUNG + STEER_KG + DRIVE_KG
TRACTOR_Z = (SPRUNG * Z_SPRUNG + STEER_KG * STEER_Z + DRIVE_KG * DRIVE_Z) / TRACTOR_TARE
TRACTOR_X = (SPRUNG * X_SPRUNG + DRIVE_KG * DRIVE_X) / TRACTOR_TARE


def table15_spec() -> dict:
    """The preset tractor-semitrailer-table15 in measurable terms: the tractor from TruckSim's tyre size and
    suspension types, weighed with its axles; the trailer as Table 15 states it (its whole mass and CG)."""
    lr, ls, b = T15.rolling_radius_m, T15.suspension_height_m, T15.spring_separation_m
    return {
        "title": "Table 15 rebuilt",
        "units": [
            {
                "id": "tractor",
                "kind": "tractor",
                "axle_groups": [
                    {"axles": 1, "tyres_per_axle": 2, "track_m": 2.03, "position_m": 0.0, "tyre": {"size": "11R22.5"},
                     "suspension": {"type": "trucksim-steer-leaf-5.5t"}},
                    {"axles": 1, "tyres_per_axle": 4, "track_m": 1.815, "position_m": DRIVE_X,
                     "tyre": {"size": "11R22.5"}, "suspension": {"type": "trucksim-drive-leaf-8.5t"}},
                ],
                "tare": {"mass_kg": TRACTOR_TARE, "cg_height_m": TRACTOR_Z, "cg_from_kingpin_m": TRACTOR_X},
            },
            {
                "id": "trailer",
                "kind": "semitrailer",
                "axle_groups": [
                    {"axles": 3, "tyres_per_axle": 4, "track_m": T15.rear_track_m, "position_m": T15.wheelbase_m,
                     "tyre": {"stiffness_kn_per_m": T15.tire_stiffness_kn_per_m, "loaded_radius_m": lr},
                     "suspension": {"type": "trucksim-trailer-leaf-18t",
                                    "roll_stiffness_knm_per_rad": T15.suspension_stiffness_kn_per_m * b * b / 2,
                                    "roll_centre_height_m": lr + ls, "spring_spacing_m": b, "lash_deg": 0.0,
                                    "unsprung_cg_height_m": lr}},
                ],
                "tare": {"mass_kg": T15.weight_kn * 1000 / G_M_PER_S2,
                         "cg_height_m": lr + ls + T15.cg_height_above_chassis_m,
                         "cg_from_kingpin_m": T15.front_axle_to_cg_m},
            },
        ],
        "couplings": [{"kind": "fifth-wheel", "position_m": DRIVE_X - T15.fifth_wheel_to_front_axle_m,
                       "height_m": 1.07, "fifth_wheel": "trucksim-fifth-wheel"}],
    }  # fmt: skip


def same(a, b) -> bool:
    """Equal, numbers to 1e-12 relative (the builder's arithmetic reorders the preset's sums)."""
    if isinstance(a, bool | str | None) or isinstance(b, bool | str | None):
        return a == b
    return a == pytest.approx(b, rel=1e-12, abs=1e-12)


def build(data: dict):
    return build_combination(CombinationSpec.from_dict(data))


def test_the_table15_preset_is_rebuilt_from_its_measurable_data():
    preset = COMBINATIONS["tractor-semitrailer-table15"]
    built = build(table15_spec()).combination
    for u, p in zip(built.units, preset.units, strict=True):
        for name in ("id", "kind", "sprung_mass_kg", "cg_height_m", "cg_position_m"):
            assert same(getattr(u, name), getattr(p, name)), (u.id, name)
        assert len(u.groups) == len(p.groups)
        for g, pg in zip(u.groups, p.groups, strict=True):
            for f in dataclasses.fields(g):
                assert same(getattr(g, f.name), getattr(pg, f.name)), (u.id, g.id, f.name)
    assert built.couplings == preset.couplings
    # the titles differ; the last unit's record for the 3D model, built from the same measurable data
    # (engine/builder/last_unit.py), is Table 15's record (the preset's) field by field, with no LLTf/LLTr of
    # its own (the combination computes it)
    assert built.title == "Table 15 rebuilt"
    derived, table15 = built.last_unit_record.to_dict(), preset.last_unit_record.to_dict()
    assert derived["front_llt_ratio"] is None and table15["front_llt_ratio"] is None
    for name, value in table15.items():
        assert same(derived[name], value), name
    # Table 15's trailer: W = 364.147 kN less 3 axles of 445 kg is the sprung weight
    assert built.units[1].sprung_mass_kg == pytest.approx(364.147e3 / 9.81 - 3 * 445.0, rel=1e-12)
    # same SRT as the preset
    assert solve_combination(built).roll_coupled_units[0].srt == pytest.approx(
        solve_combination(preset).roll_coupled_units[0].srt, rel=1e-12
    )


def test_every_component_value_keeps_its_source():
    b = build(table15_spec())
    d = b.derivation
    kt = d["units[0].groups[0].tyre_stiffness_kn_per_m"]
    assert kt.method == "library" and "TruckSim" in kt.source and kt.value == 980.0
    assert kt.spec_path == "combination_spec.units[0].axle_groups[0].tyre.size"
    roll = d["units[1].groups[0].roll_stiffness_knm_per_rad"]
    assert roll.method == "given" and roll.value == pytest.approx(2500 * 0.95**2 / 2)  # Eq. 2.11, Table 15
    mu = d["units[1].groups[0].unsprung_mass_kg"]
    assert mu.method == "library" and mu.value == 445.0 and "M_US 445" in mu.source
    fw = d["couplings[0].roll_stiffness_knm_per_rad"]
    assert fw.method == "library" and fw.value == pytest.approx(100_000 * 180 / 3.141592653589793 / 1000)
    # the 3000 kg class's loaded radius R0 - Fz/Cz = 0.520 - 3000 x 9.81 / 1000 / 980 (TruckSim's tyre)
    assert d["units[0].groups[0].tyre_loaded_radius_m"].value == pytest.approx(0.520 - 29.43 / 980.0)


def test_the_axle_loads_balance_the_total_mass():
    spec = table15_spec()
    spec["units"][1]["tare"] = {"mass_kg": 9000.0, "cg_height_m": 1.3, "cg_from_kingpin_m": 5.5}
    spec["units"][1]["deck"] = {"front_from_kingpin_m": 0.5, "length_m": 12.0}
    spec["units"][1]["payloads"] = [{"mass_kg": 21000.0, "deck_height_m": 1.3, "load_height_m": 2.7}]
    b = build(spec)
    total_kg = TRACTOR_TARE + 9000.0 + 21000.0
    assert b.gross_mass_kg == pytest.approx(total_kg, rel=1e-12)
    assert sum(a.load_kn for a in b.axle_loads) == pytest.approx(total_kg * G_M_PER_S2 / 1000.0, rel=1e-12)
    assert sum(a.load_kg for a in b.axle_loads) == pytest.approx(total_kg, rel=1e-12)
    # the payload's CG, uniform between deck and top (TERNZ), and centred on the deck: 1.3 + 1.4 / 2, 0.5 + 6
    pay = b.units[1].masses[1]
    assert (pay.cg_height_m, pay.cg_from_kingpin_m) == pytest.approx((2.0, 6.5))


def _with_payload_height(h: float):
    spec = table15_spec()
    spec["units"][1]["tare"] = {"mass_kg": 9000.0, "cg_height_m": 1.3, "cg_from_kingpin_m": 5.5}
    spec["units"][1]["payloads"] = [{"mass_kg": 21000.0, "cg_height_m": h, "cg_from_kingpin_m": 5.0}]
    return build(spec).combination


def test_the_srt_falls_as_the_payload_cg_rises():
    srts = [solve_combination(_with_payload_height(h)).roll_coupled_units[0].srt for h in (1.6, 1.9, 2.2, 2.5)]
    assert all(a > b for a, b in itertools.pairwise(srts)), srts


def stiffened(c):
    units = tuple(
        dataclasses.replace(u, groups=tuple(dataclasses.replace(g, tyre_stiffness_kn_per_m=RIGID,
                            roll_stiffness_knm_per_rad=RIGID, lash_deg=0.0) for g in u.groups))
        for u in c.units
    )  # fmt: skip
    cps = tuple(dataclasses.replace(cp, roll_stiffness_knm_per_rad=RIGID, lash_deg=0.0) for cp in c.couplings)
    return dataclasses.replace(c, units=units, couplings=cps)


@pytest.mark.parametrize("h", [1.6, 2.2])
def test_the_rigid_limit_of_a_built_tractor_semitrailer_is_the_closed_form(h):
    c = _with_payload_height(h)
    loads = static_loads(c).normal_kn  # the record's statics (force balance checked above)
    (members,) = roll_coupled_units(c)
    moment = sum(loads[(i, j)] * g.track_m / 2 for i in members for j, g in enumerate(c.units[i].groups))
    wh = sum(
        c.units[i].sprung_weight_kn * c.units[i].cg_height_m
        + sum(g.unsprung_weight_kn * g.unsprung_cg_height_m for g in c.units[i].groups)
        for i in members
    )
    closed = moment / wh  # sum(W_j b_j) / sum(W h), Eq. 2.6 summed over the roll-coupled unit
    assert rigid_srt(c)[0] == pytest.approx(closed, rel=1e-12)
    assert solve_combination(stiffened(c)).roll_coupled_units[0].srt == pytest.approx(closed, rel=1e-6)
    assert solve_combination(c).roll_coupled_units[0].srt < closed  # compliance only lowers it


# ------------------------------------------------------------------------------------------- bad input


def _dolly_last():
    spec = table15_spec()
    spec["units"].append({
        "kind": "dolly", "axle_groups": [{"axles": 1, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 1.98,
                                          "tyre": {"size": "11R22.5"},
                                          "suspension": {"type": "trucksim-dolly-leaf-22.5kip"}}],
        "tare": {"mass_kg": 1760.0, "cg_height_m": 0.9, "cg_from_kingpin_m": 1.9},
    })  # fmt: skip
    spec["couplings"].append({"kind": "pintle", "position_m": 9.5, "height_m": 0.82})
    return spec


def _edit(path: list, value):
    def change():
        spec = table15_spec()
        node = spec
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
        return spec

    return change


def _payload_in_grams():
    spec = table15_spec()
    spec["units"][1]["payloads"] = [{"mass_kg": 22_000_000.0, "cg_height_m": 2.0, "cg_from_kingpin_m": 5.0}]
    return spec


BAD = [
    (_payload_in_grams, "combination_spec.units[1].payloads[0].mass_kg", "not plausible for a payload"),
    (_dolly_last, "combination_spec.units[2].kind", "tows nothing"),
    (_edit(["couplings", 0, "position_m"], 4.0), "combination_spec.couplings[0].position_m", "behind the group"),
    (
        _edit(["units", 1, "axle_groups", 0, "suspension", "roll_centre_height_m"], 2.2),
        "combination_spec.units[1].axle_groups[0].suspension.roll_centre_height_m",
        "below the sprung CG",
    ),
    (_edit(["units", 1, "tare", "mass_kg"], 31.5), "combination_spec.units[1].tare.mass_kg", "tonnes"),
    (_edit(["units", 0, "tare", "cg_height_m"], 1100.0), "combination_spec.units[0].tare.cg_height_m", "millimetres"),
    (
        _edit(["units", 0, "axle_groups", 1, "tyre", "size"], "9.00R20"),
        "combination_spec.units[0].axle_groups[1].tyre.size",
        "no sourced data",
    ),
    (
        _edit(["units", 0, "axle_groups", 0, "suspension", "type"], "walking-beam"),
        "combination_spec.units[0].axle_groups[0].suspension.type",
        "unknown suspension",
    ),
    (_edit(["units", 1, "axle_groups", 0, "track_m"], 1815.0), "combination_spec.units[1].axle_groups[0].track_m",
     "millimetres"),
    (_edit(["couplings", 0, "fifth_wheel"], "jost"), "combination_spec.couplings[0].fifth_wheel", "unknown fifth"),
    (_edit(["units", 1, "tare", "colour"], "red"), "combination_spec.units[1].tare.colour", "unknown field"),
    (_edit(["units", 1, "axle_groups", 0, "suspension", "lash_deg"], 5.0),
     "combination_spec.units[1].axle_groups[0].suspension.lash_deg", "only sourced lash"),
]  # fmt: skip


@pytest.mark.parametrize(("make", "field", "words"), BAD, ids=[b[1].split(".", 1)[1] for b in BAD])
def test_bad_input_is_refused_naming_the_field(make, field, words):
    with pytest.raises(InvalidVehicle) as e:
        build(make())
    assert e.value.field == field
    assert words in str(e.value)


#: the library suspension of each group of the TruckSim-sourced presets, and their couplings, as their sources say
WEIGHED = {
    "truck-trailer": (
        {"truck": ("trucksim-steer-leaf-5.5t", "trucksim-air-high-roll-10t"),
         "trailer": ("trucksim-dolly-leaf-22.5kip", "trucksim-tandem-leaf-15.5t")},
        [{"kind": "pintle", "position_m": 7.4, "height_m": 0.82}],
    ),
    "adouble": (
        {"tractor": ("trucksim-steer-leaf-5.5t", "trucksim-drive-leaf-8.5t"),
         "trailer1": ("trucksim-tandem-leaf-15.5t",), "dolly": ("trucksim-dolly-leaf-22.5kip",),
         "trailer2": ("trucksim-tandem-leaf-15.5t",)},
        [{"kind": "fifth-wheel", "position_m": 2.9, "height_m": 1.07, "fifth_wheel": "trucksim-fifth-wheel"},
         {"kind": "ball", "position_m": 8.5, "height_m": 0.82},
         {"kind": "fifth-wheel", "position_m": 1.98, "height_m": 1.065, "fifth_wheel": "trucksim-fifth-wheel"}],
    ),
}  # fmt: skip


def weighed_spec(cid: str) -> dict:
    """A TruckSim-sourced preset in measurable terms: each unit weighed with its axles (the sources' sprung mass
    plus the axles' unsprung masses, at their composite CG), tyre size 11R22.5, the sources' suspension types."""
    types, couplings = WEIGHED[cid]
    spec = {"units": [], "couplings": copy.deepcopy(couplings)}
    for p in COMBINATIONS[cid].units:
        m_u = sum(g.axles * g.unsprung_mass_kg for g in p.groups)
        mass = p.sprung_mass_kg + m_u
        z = (p.sprung_mass_kg * p.cg_height_m + sum(g.axles * g.unsprung_mass_kg * g.unsprung_cg_height_m
                                                     for g in p.groups)) / mass  # fmt: skip
        x = p.sprung_mass_kg * p.cg_position_m + sum(g.axles * g.unsprung_mass_kg * g.position_m for g in p.groups)
        groups = [
            {"axles": g.axles, "tyres_per_axle": g.tyres_per_axle, "track_m": g.track_m, "position_m": g.position_m,
             "tyre": {"size": "11R22.5"}, "suspension": {"type": t}}
            for g, t in zip(p.groups, types[p.id], strict=True)
        ]  # fmt: skip
        spec["units"].append(
            {"id": p.id, "kind": p.kind, "axle_groups": groups,
             "tare": {"mass_kg": mass, "cg_height_m": z, "cg_from_kingpin_m": x / mass}}
        )  # fmt: skip
    return spec


@pytest.mark.parametrize("cid", sorted(WEIGHED))
def test_the_trucksim_presets_are_rebuilt_unit_by_unit(cid):
    preset = COMBINATIONS[cid]
    built = build(weighed_spec(cid)).combination
    for u, p in zip(built.units, preset.units, strict=True):
        assert (u.id, u.kind) == (p.id, p.kind)
        assert (u.sprung_mass_kg, u.cg_height_m, u.cg_position_m) == pytest.approx(
            (p.sprung_mass_kg, p.cg_height_m, p.cg_position_m), rel=1e-12
        )
        for g, pg in zip(u.groups, p.groups, strict=True):
            for f in dataclasses.fields(g):
                assert same(getattr(g, f.name), getattr(pg, f.name)), (u.id, g.id, f.name)
    assert built.couplings == preset.couplings  # a ball coupling is the record's pintle
    assert roll_coupled_units(built) == roll_coupled_units(preset)
    assert [r.srt for r in solve_combination(built).roll_coupled_units] == pytest.approx(
        [r.srt for r in solve_combination(preset).roll_coupled_units], rel=1e-12
    )


def test_a_full_trailers_rear_group_load_is_levered_from_its_front_group():
    spec = weighed_spec("truck-trailer")
    # the rear-group-load lever rule of a full trailer is measured from its front group (its drawbar is hinged)
    spec["units"][1]["tare"] = {"mass_kg": 8548.0, "cg_height_m": 2.0, "rear_group_load_kg": 4274.0}
    b = build(spec)
    loads = {(a.unit, a.group): a.load_kg for a in b.axle_loads}
    assert loads[("trailer", "rear")] == pytest.approx(4274.0, rel=1e-12)
    assert loads[("trailer", "front")] == pytest.approx(4274.0, rel=1e-12)
    assert [g.id for u in b.combination.units for g in u.groups] == ["steer", "drive", "front", "rear"]


def every_value_given(preset) -> dict:
    """A preset's spec with each unit weighed with its axles and every group and coupling value given explicitly."""
    spec = {"units": [], "couplings": []}
    for p in preset.units:
        m_u = sum(g.axles * g.unsprung_mass_kg for g in p.groups)
        mass = p.sprung_mass_kg + m_u
        z = (p.sprung_mass_kg * p.cg_height_m + sum(g.axles * g.unsprung_mass_kg * g.unsprung_cg_height_m
                                                     for g in p.groups)) / mass  # fmt: skip
        x = (p.sprung_mass_kg * p.cg_position_m + sum(g.axles * g.unsprung_mass_kg * g.position_m
                                                       for g in p.groups)) / mass  # fmt: skip
        groups = [
            {"id": g.id, "axles": g.axles, "tyres_per_axle": g.tyres_per_axle, "track_m": g.track_m,
             "position_m": g.position_m, "tyre": {"stiffness_kn_per_m": g.tyre_stiffness_kn_per_m},
             "suspension": {"roll_stiffness_knm_per_rad": g.roll_stiffness_knm_per_rad,
                            "roll_centre_height_m": g.roll_centre_height_m, "spring_spacing_m": g.spring_spacing_m,
                            "lash_deg": g.lash_deg, "unsprung_mass_kg": g.unsprung_mass_kg,
                            "unsprung_cg_height_m": g.unsprung_cg_height_m}}
            for g in p.groups
        ]  # fmt: skip
        spec["units"].append({"id": p.id, "kind": p.kind, "axle_groups": groups,
                              "tare": {"mass_kg": mass, "cg_height_m": z, "cg_from_kingpin_m": x}})  # fmt: skip
    for cp in preset.couplings:
        spec["couplings"].append({"kind": cp.kind, "position_m": cp.position_m, "height_m": cp.height_m,
                                  "roll_stiffness_knm_per_rad": cp.roll_stiffness_knm_per_rad,
                                  "lash_deg": cp.lash_deg})  # fmt: skip
    return spec


def test_the_b_double_is_rebuilt_with_every_group_value_given():
    """btrain-table16 (lead trailer and B-coupling kinds): each unit weighed with its axles, every group and coupling
    value given explicitly (Table 16's derived values and the lead trailer's assumed ones): the same record and SRT."""
    preset = COMBINATIONS["btrain-table16"]
    spec = every_value_given(preset)
    b = build(spec)
    built = b.combination
    assert [u.kind for u in built.units] == ["tractor", "btrain-lead", "semitrailer"]
    for u, p in zip(built.units, preset.units, strict=True):
        assert (u.sprung_mass_kg, u.cg_height_m, u.cg_position_m) == pytest.approx(
            (p.sprung_mass_kg, p.cg_height_m, p.cg_position_m), rel=1e-12
        )
        for g, pg in zip(u.groups, p.groups, strict=True):
            for f in dataclasses.fields(g):
                assert same(getattr(g, f.name), getattr(pg, f.name)), (u.id, g.id, f.name)
    assert built.couplings == preset.couplings
    assert solve_combination(built).roll_coupled_units[0].srt == pytest.approx(
        solve_combination(preset).roll_coupled_units[0].srt, rel=1e-12
    )
    # Table 16's rear trailer: W = 355.22 kN; the lead trailer's assumed 20,000 kg laden (the preset's sources)
    assert [u.mass_kg for u in b.units[1:]] == pytest.approx([20000.0, 355.22e3 / 9.81], rel=1e-12)
    assert all(d.method == "given" for k, d in b.derivation.items() if ".groups[" in k)


def test_payload_table_of_a_combination_finds_the_governing_srt_at_the_target_and_falls_with_height():
    """The payload table of a combination (the semitrailer's payload varied): each found limit, rebuilt and solved
    independently with the whole-combination model, is the target; the largest mass falls as the load rises."""
    from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC
    from engine import Case, rollover_threshold
    from engine.builder import CombinationSpec, build_combination
    from engine.builder.payload_table import payload_table

    spec = CombinationSpec.from_dict(EXAMPLE_COMBINATION_SPEC)
    table = payload_table(spec, 0.55, load_heights_m=[2.0, 2.3, 2.6], payload_masses_kg=[20000.0], rows=3)
    assert table.unit_index == 1  # the last unit that carries a payload: the semitrailer
    masses = [r.limit.value for r in table.by_load_height]
    assert masses == sorted(masses, reverse=True) and masses[0] > masses[-1]
    for row in (*table.by_load_height, *table.by_payload_mass):
        if row.limit.status != "found":
            continue
        payload = spec.units[1].payloads[0]
        mass = row.limit.value if row.payload_mass_kg is None else row.payload_mass_kg
        height = row.load_height_m if row.load_height_m is not None else row.limit.value
        units = list(spec.units)
        units[1] = dataclasses.replace(
            units[1], payloads=(dataclasses.replace(payload, mass_kg=mass, load_height_m=height),)
        )
        rebuilt = build_combination(dataclasses.replace(spec, units=tuple(units))).combination
        assert rollover_threshold(Case(rebuilt)).srt == pytest.approx(0.55, abs=2e-4)  # the limits' tolerances
    with pytest.raises(InvalidInput) as err:
        payload_table(spec, 0.55, unit_index=0)  # the tractor carries nothing
    assert err.value.field == "payload_index"


# ------------------------------------------------------------------ the last unit's record for the 3D model


def test_a_built_combination_runs_the_3d_model_of_its_last_unit_as_its_preset_does():
    """The Table 15 rebuilt: its last unit's record is Table 15's, so the 3D model of the last unit, with LLTf/LLTr
    from the combination, gives the preset's SRT (to 1e-9: the builder's arithmetic reorders sums)."""
    built = build(table15_spec()).combination
    preset = COMBINATIONS["tractor-semitrailer-table15"]
    ours, theirs = rollover_threshold(Case(built, model="3d")), rollover_threshold(Case(preset, model="3d"))
    assert ours.srt == pytest.approx(theirs.srt, rel=1e-9)


@pytest.mark.parametrize(
    "cid, unit_type", [("btrain-table16", "btrain-rear"), ("adouble", "semitrailer"), ("truck-trailer", None)]
)
def test_the_last_units_record_is_made_where_the_3d_model_has_one(cid, unit_type):
    """A semitrailer behind a B-coupling is a B-train's rear trailer, behind a dolly's fifth wheel a semitrailer; a
    full trailer (a turntable, a pintle) has no 3D model: no record, and the build's notes say why."""
    if cid in WEIGHED:
        data = weighed_spec(cid)
    else:  # every value given, and Table 16's loaded radius (lr) on the trailers' tyres: ls = roll centre - lr
        data = every_value_given(COMBINATIONS[cid])
        for unit in data["units"][1:]:
            for g in unit["axle_groups"]:
                g["tyre"]["loaded_radius_m"] = PRESETS["table16-btrain"].rolling_radius_m
    spec = CombinationSpec.from_dict(data)
    built = build_combination(spec)
    note = next(n for n in built.notes if "3D model" in n)
    if unit_type is None:
        assert built.combination.last_unit_record is None and "full-trailer" in note
        return
    assert built.combination.last_unit_record is not None and unit_type in note
    vspec = last_unit_spec(spec, built.combination, built.derivation)
    last, towing = spec.units[-1], spec.units[-2]
    assert vspec.unit_type == unit_type
    assert vspec.rear.centre_from_kingpin_m == last.axle_groups[0].position_m
    # the front group: the towing unit's group under the coupling, l13 from the coupling's position
    near = min(towing.axle_groups, key=lambda g: abs(g.position_m - spec.couplings[-1].position_m))
    assert vspec.front.centre_from_kingpin_m == pytest.approx(near.position_m - spec.couplings[-1].position_m)
    record = built.combination.last_unit_record
    assert record.weight_kn == pytest.approx(built.units[-1].mass_kg * G_M_PER_S2 / 1000.0, rel=1e-12)
    three_d = rollover_threshold(Case(built.combination, model="3d"))
    assert 0.2 < three_d.srt < 0.7
    if cid == "btrain-table16":  # every value given: Table 16's own record (the preset's), field by field
        for name, value in COMBINATIONS[cid].last_unit_record.to_dict().items():
            assert same(getattr(record, name), value), name
        preset_3d = rollover_threshold(Case(COMBINATIONS[cid], model="3d"))
        assert three_d.srt == pytest.approx(preset_3d.srt, rel=1e-9)  # and so the preset's 3D SRT
