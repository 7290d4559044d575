"""The whole-combination static roll model (engine.models.combination) against closed forms, invariants and a
second, independent formulation (engine.models.combination_reference).

Independent numbers used here:
* the rigid limit: every group lifts at once with no roll, SRT = sum(N_g T_g/2) / sum(W h) (Eq. 2.6 summed over
  the roll-coupled unit; on a bank Eq. 2.8's exact form);
* Rill's closed form (thesis Eq. 2.20, Rill 2011) and Gillespie's (Eq. 2.28) for one unit whose groups share one
  roll centre and have stiffnesses in proportion to their loads (both lift together);
* force and moment balance of the loads (Eq. 4.27 generalised);
* the scipy equilibrium of every roll degree of freedom (no events, no regimes) on random vehicles.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import pytest

from engine.errors import InvalidVehicle
from engine.models.classic import gillespie, rill
from engine.models.combination import rigid_srt, solve_combination
from engine.models.combination_reference import reference_srt
from engine.vehicle.combination import (
    G_M_PER_S2,
    AxleGroup,
    Combination,
    Coupling,
    Unit,
    UnitLoad,
    roll_coupled_units,
    static_loads,
    validate_combination,
)

RIGID = 1e12  # kN/m and kN m/rad: effectively rigid (the record's MAX_STIFFNESS_KN_PER_M)


def group(gid, axles, tyres, track, x, *, kt=900.0, kroll=600.0, hr=0.7, mu=450.0, hu=0.5, lash=0.0, steer=False):
    return AxleGroup(gid, axles, tyres, track, x, kt, kroll, hr, mu, hu, lash_deg=lash, steer=steer)


def tractor(**kw):
    return Unit(
        "tractor",
        "tractor",
        kw.get("mass", 5000.0),
        kw.get("h", 1.1),
        kw.get("x", 1.3),
        (
            group("steer", 1, 2, 2.03, 0.0, kroll=kw.get("ks", 550.0), hr=0.55, mu=362.0, steer=True),
            group("drive", kw.get("drive_axles", 2), 4, 1.86, kw.get("wb", 4.1), kroll=kw.get("kd", 500.0), hr=0.72),
        ),
    )


def semitrailer(uid="trailer", kind="semitrailer", mass=30000.0, h=2.0, x=6.0, axles=3, L=8.5, **kw):
    return Unit(
        uid, kind, mass, h, x, (group(uid, axles, 4, 1.86, L, kroll=kw.get("kr", 900.0), lash=kw.get("lash", 0.0)),)
    )


FIFTH = Coupling("fifth-wheel", 3.7, 1.1, 5730.0, 1.0)


def tractor_semitrailer(**kw):
    return Combination((tractor(**kw), semitrailer(**kw)), (FIFTH,))


def b_double():
    lead = semitrailer("lead", "btrain-lead", mass=22000.0, h=1.9, x=4.0, axles=3, L=6.5)
    rear = semitrailer("rear", mass=24000.0, h=2.0, x=4.5, axles=3, L=6.0)
    b = Coupling("b-coupling", 7.8, 1.2, 5730.0, 1.0)
    return Combination((tractor(), lead, rear), (FIFTH, b))


def a_double(**kw):
    dolly = Unit("dolly", "dolly", 1300.0, 0.95, 1.9, (group("dolly", 2, 4, 1.86, 1.9, kroll=650.0),))
    semi1 = semitrailer("trailer1", mass=kw.get("m1", 20000.0), L=7.0, x=5.0)
    semi2 = semitrailer("trailer2", mass=kw.get("m2", 20000.0), L=7.0, x=5.0)
    pintle = Coupling("pintle", 7.9, 0.9)
    dolly_fw = Coupling("fifth-wheel", 1.9, 1.15, 5730.0, 1.0)
    return Combination((tractor(**kw), semi1, dolly, semi2), (FIFTH, pintle, dolly_fw))


def stiffened(c: Combination, k: float = RIGID) -> Combination:
    units = tuple(
        dataclasses.replace(
            u,
            groups=tuple(
                dataclasses.replace(g, tyre_stiffness_kn_per_m=k, roll_stiffness_knm_per_rad=k, lash_deg=0.0)
                for g in u.groups
            ),
        )
        for u in c.units
    )
    cps = tuple(
        dataclasses.replace(cp, roll_stiffness_knm_per_rad=k, lash_deg=0.0) if cp.transmits_roll else cp
        for cp in c.couplings
    )
    return dataclasses.replace(c, units=units, couplings=cps)


def srts(c, **kw):
    return [r.srt for r in solve_combination(c, **kw).roll_coupled_units]


# ------------------------------------------------------------------------------------------ statics


@pytest.mark.parametrize("build", [tractor_semitrailer, b_double, a_double])
@pytest.mark.parametrize("slope", [0.0, 8.0, -10.0])
def test_static_loads_balance_the_weight_and_the_pitch_moment(build, slope):
    c = build()
    validate_combination(c)
    st = static_loads(c)
    s = math.sin(math.atan(slope / 100.0))
    n = math.cos(math.atan(slope / 100.0))
    total_w = sum(u.sprung_weight_kn + sum(g.unsprung_weight_kn for g in u.groups) for u in c.units)
    normal = sum(n * st.normal_kn[k] + s * st.grade_kn[k] for k in st.normal_kn)
    assert normal == pytest.approx(n * total_w, rel=1e-12)  # the road carries the weight's normal component
    # each towed unit's pitch balance about its own coupling, with free-rolling tyres (Eq. 4.27 generalised)
    for i in range(1, len(c.units)):
        u = c.units[i]
        if len(u.groups) != 1:
            continue
        behind = 0.0
        if i < len(c.couplings):
            cp = c.couplings[i]
            behind = cp.position_m * (n * st.coupling_kn[i] + s * st.coupling_grade_kn[i])
        g = u.groups[0]
        moment = u.cg_position_m * n * u.sprung_weight_kn + g.position_m * n * g.unsprung_weight_kn + behind
        held = g.position_m * (n * st.normal_kn[(i, 0)] + s * st.grade_kn[(i, 0)])
        rear_weights = sum(
            w.sprung_weight_kn + sum(gg.unsprung_weight_kn for gg in w.groups) for w in c.units[i:]
        )  # the grade's pull on everything from here back, at the heights below
        long_moment = (
            s * (u.sprung_weight_kn * u.cg_height_m + g.unsprung_weight_kn * g.unsprung_cg_height_m)
            - s * rear_weights * c.couplings[i - 1].height_m
        )
        if i < len(c.couplings):
            long_moment += (
                s
                * sum(w.sprung_weight_kn + sum(gg.unsprung_weight_kn for gg in w.groups) for w in c.units[i + 1 :])
                * c.couplings[i].height_m
            )
        assert held == pytest.approx(moment + long_moment, rel=1e-10, abs=1e-9)


def test_roll_coupled_units_are_cut_at_the_pintle_only():
    assert roll_coupled_units(tractor_semitrailer()) == [(0, 1)]
    assert roll_coupled_units(b_double()) == [(0, 1, 2)]
    assert roll_coupled_units(a_double()) == [(0, 1), (2, 3)]


# -------------------------------------------------------------------------------------- closed forms


@pytest.mark.parametrize("build", [tractor_semitrailer, b_double, a_double])
def test_the_rigid_closed_form_is_sum_of_half_track_loads_over_sum_of_weight_heights(build):
    c = build()
    st = static_loads(c)
    for members, value in zip(roll_coupled_units(c), rigid_srt(c), strict=True):
        restoring = sum(
            st.normal_kn[(u, j)] * g.track_m / 2.0 for u in members for j, g in enumerate(c.units[u].groups)
        )
        overturning = sum(
            c.units[u].sprung_weight_kn * c.units[u].cg_height_m
            + sum(g.unsprung_weight_kn * g.unsprung_cg_height_m for g in c.units[u].groups)
            for u in members
        )
        for i, cp in enumerate(c.couplings):  # a pintle's load acts from outside the roll-coupled unit
            if not cp.transmits_roll:
                if i in members:
                    overturning += st.coupling_kn[i] * cp.height_m
                if i + 1 in members:
                    overturning -= st.coupling_kn[i] * cp.height_m
        assert value == pytest.approx(restoring / overturning, rel=1e-12)


@pytest.mark.parametrize("build", [tractor_semitrailer, b_double, a_double])
@pytest.mark.parametrize("bank", [0.0, 6.0])
def test_the_rigid_limit_of_the_stepped_solution_is_the_rigid_closed_form(build, bank):
    c = stiffened(build())
    rigid = rigid_srt(c, bank_percent=bank)
    if bank:  # Eq. 2.8 exactly: tan(atan(SRT_level) + bank angle) on the level-road form
        level = rigid_srt(c)
        assert rigid == pytest.approx([math.tan(math.atan(r) + math.atan(bank / 100)) for r in level], rel=1e-12)
    # compliance of 1e-12 rad per kN m leaves the rigid value to within (sum W h) / k, about 1e-9 g
    assert srts(c, bank_percent=bank) == pytest.approx(rigid, rel=1e-8)


def _one_unit(track=1.86, h=1.5, hr=0.7, k_per_kn=3.0, kt_per_kn=12.0):
    """A rigid truck whose two groups share a roll centre and have roll and tyre stiffnesses in proportion to their
    loads, with no unsprung mass (the assumptions of Eqs. 2.20 and 2.28)."""
    steer = group("front", 1, 2, track, 0.0, hr=hr, mu=0.0 + 1e-9, hu=0.5, steer=True)
    rear = group("rear", 2, 4, track, 5.0, hr=hr, mu=1e-9, hu=0.5)
    truck = Unit("truck", "rigid-truck", 20000.0, h, 3.0, (steer, rear))
    c = Combination((truck,))
    st = static_loads(c)
    groups = []
    for j, g in enumerate(truck.groups):
        n = st.normal_kn[(0, j)]
        groups.append(
            dataclasses.replace(
                g,
                roll_stiffness_knm_per_rad=k_per_kn * n * 100 / g.axles,
                tyre_stiffness_kn_per_m=kt_per_kn * n / (g.axles * g.tyres_per_axle / 2),
            )
        )
    return Combination((dataclasses.replace(truck, groups=tuple(groups)),))


def test_one_unit_with_proportional_groups_is_rills_closed_form_eq_2_20():
    c = _one_unit()
    u = c.units[0]
    w = u.sprung_weight_kn + sum(g.unsprung_weight_kn for g in u.groups)
    k_theta = sum(g.suspension_roll_stiffness_knm_per_rad for g in u.groups)
    k_side = sum(g.tyre_side_stiffness_kn_per_m for g in u.groups)
    expected = rill(1.86, u.cg_height_m, u.cg_height_m - 0.7, k_theta, k_side, w)  # Eq. 2.20
    result = solve_combination(c).roll_coupled_units[0]
    assert result.srt == pytest.approx(expected, rel=1e-6)  # the unsprung mass of 1e-9 kg is the only difference
    assert {e.group for e in result.lift_sequence} == {"front", "rear"}  # both lift together


def test_one_unit_on_rigid_tyres_is_gillespies_closed_form_eq_2_28():
    c = _one_unit(kt_per_kn=1e9)
    u = c.units[0]
    w = u.sprung_weight_kn
    k = [g.suspension_roll_stiffness_knm_per_rad for g in u.groups]
    expected = gillespie(1.86, u.cg_height_m, 0.7, w, k[0], k[1])  # Eq. 2.28, roll about the roll axis
    assert solve_combination(c).roll_coupled_units[0].srt == pytest.approx(expected, rel=1e-6)


# ------------------------------------------------------------------------------------------ invariants


@pytest.mark.parametrize("build", [tractor_semitrailer, b_double, a_double])
def test_compliance_and_lash_only_lower_the_srt(build):
    c = build()
    base = srts(c)
    assert all(s < r for s, r in zip(base, rigid_srt(c), strict=True))
    softer = dataclasses.replace(
        c,
        units=tuple(
            dataclasses.replace(
                u,
                groups=tuple(
                    dataclasses.replace(g, roll_stiffness_knm_per_rad=0.7 * g.roll_stiffness_knm_per_rad)
                    for g in u.groups
                ),
            )
            for u in c.units
        ),
    )
    assert all(s < b for s, b in zip(srts(softer), base, strict=True))
    lashed = dataclasses.replace(
        c,
        units=tuple(
            dataclasses.replace(u, groups=tuple(dataclasses.replace(g, lash_deg=1.0) for g in u.groups))
            for u in c.units
        ),
    )
    assert all(s < b for s, b in zip(srts(lashed), base, strict=True))
    no_fifth_lash = dataclasses.replace(c, couplings=tuple(dataclasses.replace(cp, lash_deg=0.0) for cp in c.couplings))
    assert all(s >= b for s, b in zip(srts(no_fifth_lash), base, strict=True))


def test_a_pintle_passes_no_roll_moment_so_each_roll_coupled_unit_is_its_own():
    base = a_double()
    rear_alone = srts(base)[1]
    # everything ahead of the pintle changed, the pintle's load kept: the rear unit's SRT does not move
    changed = a_double(mass=9000.0, kd=300.0, ks=900.0)
    assert srts(changed)[0] != pytest.approx(srts(base)[0], rel=1e-3)
    assert srts(changed)[1] == pytest.approx(rear_alone, rel=1e-12)
    detail = solve_combination(base)
    assert [r.units for r in detail.roll_coupled_units] == [("tractor", "trailer1"), ("dolly", "trailer2")]
    assert detail.governing == int(np.argmin(srts(base)))
    pintle = [cs for r in detail.roll_coupled_units for cs in r.couplings if cs.kind == "pintle"]
    assert pintle and all(cs.roll_moment_knm == 0.0 for cs in pintle)


def test_the_group_stiffer_for_its_load_lifts_first():
    # two groups of one unit, same roll centre and track: the load transfer divides as the roll stiffness, so the
    # one with the larger stiffness per unit of load lifts first
    for k_front, k_rear, first in ((3000.0, 300.0, "front"), (200.0, 900.0, "rear")):
        steer = group("front", 1, 2, 1.86, 0.0, kroll=k_front, kt=5000.0, hr=0.7, steer=True)
        rear = group("rear", 2, 4, 1.86, 5.0, kroll=k_rear, kt=5000.0, hr=0.7)
        c = Combination((Unit("truck", "rigid-truck", 16000.0, 1.6, 3.0, (steer, rear)),))
        st = static_loads(c)
        predicted = "front" if k_front / st.normal_kn[(0, 0)] > 2 * k_rear / st.normal_kn[(0, 1)] else "rear"
        assert predicted == first
        assert solve_combination(c).roll_coupled_units[0].lift_sequence[0].group == first


def test_a_bank_raises_and_an_offset_outward_lowers_the_srt():
    c = tractor_semitrailer()
    level = srts(c)[0]
    assert srts(c, bank_percent=6.0)[0] > level
    assert srts(c, load=UnitLoad(lateral_offset_m=0.1))[0] < level < srts(c, load=UnitLoad(lateral_offset_m=-0.1))[0]
    assert srts(c, load=UnitLoad(vertical_offset_m=0.2))[0] < level
    assert srts(c, load=UnitLoad(overweight_percent=20.0))[0] < level


def test_the_limit_state_is_in_moment_balance():
    c = b_double()
    r = solve_combination(c, bank_percent=0.0).roll_coupled_units[0]
    # the road's moment about the centre line: the tyre lines' loads at +-T/2
    by = {(g.unit, g.group): g for g in r.groups}
    restoring = sum((by[(u.id, g.id)].outer_kn - by[(u.id, g.id)].inner_kn) * g.track_m / 2 for u in c.units
                    for g in u.groups)  # fmt: skip
    # the overturning moment: ay W h of every mass, and its weight times its lateral shift from the roll angles
    ay = r.srt
    over = 0.0
    st = static_loads(c)
    for i, u in enumerate(c.units):
        phi = math.radians(r.roll_angle_deg[u.id])
        over += u.sprung_weight_kn * u.cg_height_m * (ay + phi)
        for j, g in enumerate(u.groups):
            pa = math.radians(by[(u.id, g.id)].axle_roll_deg)
            s = st.normal_kn[(i, j)] - g.unsprung_weight_kn
            over += g.unsprung_weight_kn * g.unsprung_cg_height_m * (ay + pa) + s * g.roll_centre_height_m * (pa - phi)
    for i, cp in enumerate(c.couplings):
        v = st.coupling_kn[i]
        over += v * cp.height_m * (math.radians(r.roll_angle_deg[c.units[i].id]) -
                                   math.radians(r.roll_angle_deg[c.units[i + 1].id]))  # fmt: skip
    assert restoring == pytest.approx(over, rel=1e-9)


# -------------------------------------------------------------------------------------- two methods


def random_combination(rng: np.random.Generator) -> Combination:
    """A tractor-semitrailer, B-double, A-double or truck and full trailer with random values inside the plausible
    ranges. Coupling lash is drawn up to 1 deg each way, the one sourced value (TruckSim's default fifth wheel):
    with more, two trailers snap through each other's lash in ways the reference's continuation cannot follow."""
    kind = rng.integers(4)

    def u(lo, hi):
        return float(rng.uniform(lo, hi))

    t = Unit(
        "tractor",
        "tractor" if kind != 3 else "rigid-truck",
        u(4000, 9000),
        u(0.9, 1.4),
        u(0.8, 1.8),
        (
            group("steer", 1, 2, u(1.9, 2.1), 0.0, kroll=u(300, 900), kt=u(700, 1100), hr=u(0.45, 0.6),
                  mu=u(300, 500), lash=u(0, 0.5) * rng.integers(2), steer=True),
            group("drive", int(rng.integers(1, 3)), 4, u(1.8, 1.9), u(3.4, 4.2), kroll=u(300, 900),
                  kt=u(700, 1100), hr=u(0.6, 0.8), mu=u(500, 700), lash=u(0, 1.0) * rng.integers(2)),
        ),
    )  # fmt: skip
    if kind == 3:  # truck + full trailer
        t = dataclasses.replace(t, sprung_mass_kg=u(12000, 18000), cg_height_m=u(1.6, 2.1), cg_position_m=u(2.5, 3.2))
        ft = Unit("full", "full-trailer", u(10000, 18000), u(1.6, 2.1), u(3.5, 4.5),
                  (group("front", 2, 4, 1.86, 1.5, kroll=u(400, 1000), lash=u(0, 1)),
                   group("rear", 2, 4, 1.86, 6.5, kroll=u(400, 1000), lash=u(0, 1))))  # fmt: skip
        return Combination((t, ft), (Coupling("pintle", u(5.0, 5.5), u(0.8, 1.0)),))
    fifth = Coupling("fifth-wheel", u(3.0, 3.4), u(1.0, 1.3), u(2000, 9000), u(0, 1.0))
    first = semitrailer("trailer", mass=u(15000, 32000), h=u(1.6, 2.3), x=u(4.5, 6.5), L=u(7.5, 9.0),
                        kr=u(500, 1500), lash=u(0, 1.0) * rng.integers(2))  # fmt: skip
    if kind == 0:
        return Combination((t, first), (fifth,))
    if kind == 1:
        lead = dataclasses.replace(first, id="lead", kind="btrain-lead")
        rear = semitrailer("rear", mass=u(15000, 25000), h=u(1.6, 2.3), x=u(3.5, 5.0), L=u(5.5, 7.0), kr=u(500, 1500))
        b = Coupling("b-coupling", u(8.0, 8.4), u(1.1, 1.3), u(2000, 9000), u(0, 1.0))
        return Combination((t, lead, rear), (fifth, b))
    dolly = Unit(
        "dolly", "dolly", u(1000, 2000), u(0.8, 1.1), 1.9, (group("dolly", 2, 4, 1.86, 1.9, kroll=u(400, 900)),)
    )
    second = semitrailer("trailer2", mass=u(12000, 25000), h=u(1.6, 2.2), x=u(4.0, 6.0), L=u(7.0, 8.5))
    return Combination(
        (t, first, dolly, second),
        (fifth, Coupling("pintle", first.groups[0].position_m + u(0.8, 1.5), u(0.8, 1.0)),
         Coupling("fifth-wheel", 1.9, u(1.1, 1.2), u(2000, 9000), u(0, 1.0))),
    )  # fmt: skip


def _agree(seed: int) -> None:
    rng = np.random.default_rng(seed)
    c = random_combination(rng)
    validate_combination(c)
    bank, slope = float(rng.uniform(-4, 10)), float(rng.uniform(-8, 8))
    load = UnitLoad(lateral_offset_m=float(rng.uniform(-0.1, 0.15)), overweight_percent=float(rng.uniform(0, 15)))
    stepped = srts(c, bank_percent=bank, slope_percent=slope, load=load)
    reference = reference_srt(c, bank_percent=bank, slope_percent=slope, load=load)
    assert stepped == pytest.approx(reference, abs=1e-9)  # the reference maximises to about 1e-12 g


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_stepped_and_nonlinear_equilibrium_agree(seed):
    _agree(seed)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 28))
def test_stepped_and_nonlinear_equilibrium_agree_on_many_random_vehicles(seed):
    _agree(seed)


# ------------------------------------------------------------------------------------------ bad input


def test_a_31_5_kg_semitrailer_is_refused_as_tonnes():
    c = tractor_semitrailer()
    bad = dataclasses.replace(c, units=(c.units[0], dataclasses.replace(c.units[1], sprung_mass_kg=31.5)))
    with pytest.raises(InvalidVehicle, match="tonnes") as e:
        validate_combination(bad)
    assert e.value.field == "combination.units[1].sprung_mass_kg"


@pytest.mark.parametrize(
    "change, field, words",
    [
        (lambda c: _unit(c, 1, cg_height_m=1850.0), "combination.units[1].cg_height_m", "millimetres"),
        (lambda c: _group(c, 1, 0, roll_centre_height_m=2.1), "combination.units[1].groups[0].roll_centre_height_m",
         "below the sprung CG"),
        (lambda c: _group(c, 1, 0, lash_deg=5.0), "combination.units[1].groups[0].lash_deg", "not plausible"),
        (lambda c: dataclasses.replace(c, couplings=(dataclasses.replace(FIFTH, position_m=4.5),)),
         "combination.couplings[0].position_m", "behind the group it sits on"),
        (lambda c: dataclasses.replace(c, units=(c.units[0], dataclasses.replace(c.units[1], kind="dolly"))),
         "combination.couplings[0].kind", "joins"),
    ],
)  # fmt: skip
def test_impossible_combinations_are_refused_naming_the_field(change, field, words):
    with pytest.raises(InvalidVehicle, match=words) as e:
        validate_combination(change(tractor_semitrailer()))
    assert e.value.field == field


def test_a_dolly_carrying_nothing_is_refused():
    c = a_double()
    with pytest.raises(InvalidVehicle, match="dolly carrying nothing") as e:
        validate_combination(Combination(c.units[:3], c.couplings[:2]))
    assert e.value.field == "combination.units[2].kind"


def _unit(c, i, **changes):
    units = list(c.units)
    units[i] = dataclasses.replace(units[i], **changes)
    return dataclasses.replace(c, units=tuple(units))


def _group(c, i, j, **changes):
    groups = list(c.units[i].groups)
    groups[j] = dataclasses.replace(groups[j], **changes)
    return _unit(c, i, groups=tuple(groups))


def test_weights_are_the_masses_times_g():
    c = tractor_semitrailer()
    assert c.units[1].sprung_weight_kn == pytest.approx(30000.0 * G_M_PER_S2 / 1000.0)


def test_solves_of_one_vehicle_on_several_threads_are_the_solves_one_after_another():
    """The per-regime tables a vehicle's solves share (engine.models.combination._shared_regimes) are built on
    whichever thread needs them first (the service's solver threads): solved on four threads at once from an empty
    memo, with the interpreter switching threads as often as it can, every bank gives the bits it gives solved
    alone (an invariant of the shared memo; a race that changed a result would break it)."""
    from concurrent.futures import ThreadPoolExecutor

    from engine.models import combination as model
    from engine.vehicle import COMBINATIONS

    c = COMBINATIONS["adouble"]
    banks = [b / 4 for b in range(-8, 41)]
    model._shared_regimes.cache_clear()
    alone = [[r.srt for r in solve_combination(c, bank_percent=b).roll_coupled_units] for b in banks]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # threads switched as often as possible: a half-built entry would be seen
    try:
        for _ in range(3):
            model._shared_regimes.cache_clear()
            with ThreadPoolExecutor(max_workers=4) as pool:
                together = list(
                    pool.map(lambda b: [r.srt for r in solve_combination(c, bank_percent=b).roll_coupled_units], banks)
                )
            assert together == alone
    finally:
        sys.setswitchinterval(interval)
