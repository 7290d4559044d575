"""The linear yaw-roll model (engine.dynamics): independent checks, each of which fails on a wrong model."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from engine.dynamics import DynamicsData, GroupData, UnitData, build
from engine.dynamics.manoeuvres import (
    Unstable,
    damping_from_peaks,
    lane_change,
    pulse_steer,
    rearward_amplification_spectrum,
    stability,
    steady_turn,
)
from engine.dynamics.reference import chain_matrices, state_matrix
from engine.dynamics.response import (
    damping_ratio,
    eigen,
    frequency_response,
    least_damped_oscillatory,
    simulate,
    steady_state,
)
from engine.errors import InvalidVehicle
from engine.models.combination import build_systems, solve_unit
from engine.vehicle.combination import G_M_PER_S2, Combination, UnitLoad, static_loads
from engine.vehicle.combination_presets import COMBINATIONS

G = G_M_PER_S2


def no_lash(c: Combination) -> Combination:
    units = tuple(replace(u, groups=tuple(replace(g, lash_deg=0.0) for g in u.groups)) for u in c.units)
    return replace(c, units=units, couplings=tuple(replace(k, lash_deg=0.0) for k in c.couplings))


def rigid_truck(front_cc: float, rear_cc: float) -> tuple[Combination, DynamicsData]:
    """The truck-trailer preset's truck alone, with one rear axle (a two-axle bicycle)."""
    tt = COMBINATIONS["truck-trailer"]
    truck = tt.units[0]
    rear = replace(truck.groups[1], axles=1)
    c = Combination((replace(truck, groups=(truck.groups[0], rear)),), ())
    data = DynamicsData(groups={("truck", "steer"): GroupData(front_cc), ("truck", "drive"): GroupData(rear_cc)})
    return c, data


def bicycle(c: Combination, data: DynamicsData):
    """Gillespie (1992) ch. 6: wheelbase L, understeer gradient K = Wf/Cf - Wr/Cr [rad per g]."""
    st = static_loads(c)
    wf, wr = st.normal_kn[(0, 0)], st.normal_kn[(0, 1)]
    cf = data.groups[("truck", "steer")].cornering_coefficient_per_rad * wf
    cr = data.groups[("truck", "drive")].cornering_coefficient_per_rad * wr
    return c.units[0].groups[1].position_m, wf / cf - wr / cr


@pytest.mark.parametrize("cc", [(6.0, 4.5), (4.5, 6.5)])
def test_rigid_truck_is_the_bicycle_model(cc):
    """Yaw-rate and lateral-acceleration gains, Gillespie (1992) Eqs. 6-15 and 6-19:
    r/delta = (u/L) / (1 + K u^2/(g L)), ay/delta = (u^2/(g L)) / (1 + K u^2/(g L)) [g/rad]."""
    c, data = rigid_truck(*cc)
    length, k = bicycle(c, data)
    m = build(c, data)
    for kmh in (30.0, 60.0, 90.0):
        u = kmh / 3.6
        if k < 0 and u > math.sqrt(-G * length / k):
            continue
        ss = m.state_space(u)
        z, _ = steady_state(ss)
        n = m.n
        r = z[n - 1]  # (q[2:], v, r, ...): r is the (n-1)-th
        expected = (u / length) / (1 + k * u * u / (G * length))
        assert r == pytest.approx(expected, rel=1e-9)
        assert u * r / G == pytest.approx((u * u / (G * length)) / (1 + k * u * u / (G * length)), rel=1e-9)


def test_characteristic_and_critical_speed():
    """Gillespie (1992) ch. 6: the characteristic speed sqrt(g L / K) (understeer) halves the neutral yaw gain; the
    critical speed sqrt(-g L / K) (oversteer) is where a real eigenvalue crosses zero."""
    c, data = rigid_truck(4.5, 6.5)
    length, k = bicycle(c, data)
    assert k > 0
    uch = math.sqrt(G * length / k)
    z, _ = steady_state(build(c, data).state_space(uch))
    assert z[build(c, data).n - 1] == pytest.approx(0.5 * uch / length, rel=1e-9)
    c, data = rigid_truck(6.0, 4.5)
    length, k = bicycle(c, data)
    assert k < 0
    ucrit_kmh = math.sqrt(-G * length / k) * 3.6
    st = stability(build(c, data))
    assert st.divergence_speed_kmh == pytest.approx(ucrit_kmh, abs=0.06)
    assert st.sway_critical_speed_kmh is None
    with pytest.raises(Unstable) as err:
        lane_change(build(c, data), ucrit_kmh + 5.0)
    assert err.value.limit_kmh == pytest.approx(ucrit_kmh, abs=0.06)


def test_assembly_equals_hand_derived_equations_on_random_tractor_semitrailers():
    """The constrained multibody assembly and the hand-derived Newton-Euler equations (engine.dynamics.reference)
    have the same eigenvalues (yaw plane) on random tractor-semitrailers at random speeds."""
    rng = np.random.default_rng(7)
    base = COMBINATIONS["tractor-semitrailer-table15"]
    for _ in range(12):
        tractor, trailer = base.units
        trailer = replace(trailer, sprung_mass_kg=float(rng.uniform(4000, 30000)),
                          cg_position_m=float(rng.uniform(3.0, 7.0)),
                          groups=(replace(trailer.groups[0], position_m=float(rng.uniform(7.5, 11.0)),
                                          axles=int(rng.integers(1, 4))),))  # fmt: skip
        cp = replace(base.couplings[0], position_m=float(rng.uniform(2.0, 3.4)))
        c = replace(base, units=(tractor, trailer), couplings=(cp,))
        data = DynamicsData(
            units={"trailer": UnitData(yaw_inertia_kgm2=None, front_overhang_m=float(rng.uniform(0.5, 1.5)))},
            groups={("tractor", "steer"): GroupData(float(rng.uniform(4, 8))),
                    ("trailer", "trailer"): GroupData(float(rng.uniform(4, 8)), float(rng.uniform(1.2, 1.5)))},
        )  # fmt: skip
        m = build(c, data, roll=False)
        u = float(rng.uniform(10, 35))
        w1 = np.sort_complex(np.linalg.eigvals(m.state_space(u).A))
        M, C, K, _ = chain_matrices(c, m.parameters, u)
        w2 = np.sort_complex(np.linalg.eigvals(state_matrix(M, C, K)))
        big = np.abs(w1) > 1e-6
        np.testing.assert_allclose(w1[big], np.sort_complex(w2[np.abs(w2) > 1e-6]), rtol=1e-8)


def _random_chain(rng: np.random.Generator, cid: str) -> tuple[Combination, DynamicsData]:
    """A preset chain with its masses, CGs, couplings, group positions, axle counts and coefficients drawn anew."""
    base = COMBINATIONS[cid]
    units = []
    for u in base.units:
        groups = tuple(
            replace(g, axles=int(rng.integers(1, 4)) if not g.steer else 1,
                    position_m=g.position_m * float(rng.uniform(0.9, 1.1)) if g.position_m else 0.0)
            for g in u.groups
        )  # fmt: skip
        if len(groups) == 2 and groups[1].position_m <= groups[0].position_m + 1.0:
            groups = (groups[0], replace(groups[1], position_m=groups[0].position_m + 3.0))
        xs = [g.position_m for g in groups]
        units.append(replace(u, groups=groups, sprung_mass_kg=u.sprung_mass_kg * float(rng.uniform(0.5, 1.5)),
                             cg_position_m=float(rng.uniform(0.3, 0.9)) * max(xs)))  # fmt: skip
    couplings = []
    for i, cp in enumerate(base.couplings):
        rear = units[i].groups[-1].position_m
        x = rear * float(rng.uniform(0.6, 0.95)) if cp.kind == "fifth-wheel" else rear + float(rng.uniform(0.5, 2.0))
        if cp.kind == "b-coupling":
            x = rear * float(rng.uniform(0.8, 1.0))
        couplings.append(replace(cp, position_m=x))
    groups = {(u.id, g.id): GroupData(float(rng.uniform(4, 8))) for u in units for g in u.groups}
    return replace(base, units=tuple(units), couplings=tuple(couplings)), DynamicsData(groups=groups)


@pytest.mark.parametrize("cid", ["tractor-semitrailer-table15", "btrain-table16", "adouble"])
def test_assembly_equals_hand_derived_equations_on_random_chains(cid):
    """The same on random B-doubles and A-doubles (dolly and pintle included): the eigenvalues of the null-space
    assembly equal those of the recursive Newton-Euler equations."""
    rng = np.random.default_rng(11)
    for _ in range(8):
        c, data = _random_chain(rng, cid)
        m = build(c, data, roll=False)
        u = float(rng.uniform(10, 35))
        w1 = np.sort_complex(np.linalg.eigvals(m.state_space(u).A))
        M, C, K, _ = chain_matrices(c, m.parameters, u)
        w2 = np.sort_complex(np.linalg.eigvals(state_matrix(M, C, K)))
        np.testing.assert_allclose(w1[np.abs(w1) > 1e-6], w2[np.abs(w2) > 1e-6], rtol=1e-7)


@pytest.mark.parametrize("cid", sorted(COMBINATIONS))
def test_steady_turn_roll_equals_static_combination_model(cid):
    """Per unit and axle by axle, the steady turn's roll per g equals the lash-free static combination model's on
    its first (linear) segment (engine.models.combination.solve_unit, before any lift-off)."""
    c = no_lash(COMBINATIONS[cid])
    m = build(c)
    ss = m.state_space(70 / 3.6)
    z, red = steady_state(ss)
    x = red.L @ z
    n = m.n
    ay_g = ss.speed_mps * z[n - 1] / G
    for s in build_systems(c, 0.0, 0.0, UnitLoad()):
        zz = solve_unit(s, 1.0, None).vertices[1].z
        for u in s.units:  # the static model's roll is + outward, the dynamic model's + left
            assert -(m.phi_unit_rows[u] @ x[:n]) / ay_g == pytest.approx(zz[s.body[u]] / zz[s.n], rel=1e-9)
        for key, dof in s.axle.items():
            cc, dd = ss.group_roll(key)
            assert -(cc @ x + dd) / ay_g == pytest.approx(zz[dof] / zz[s.n], rel=1e-9)


@pytest.mark.parametrize("cid", sorted(COMBINATIONS))
def test_rearward_amplification_tends_to_one_at_low_frequency(cid):
    """At a vanishing frequency every unit follows the steer axle's path: RA -> 1."""
    ra = rearward_amplification_spectrum(build(COMBINATIONS[cid]), 88.0, np.array([0.002]))
    assert ra[0] == pytest.approx(1.0, abs=2e-3)


def test_lane_change_moves_the_steer_axle_by_a_over_2_pi_f_squared():
    """One sine period of lateral acceleration A at f displaces by A/(2 pi f^2): 1.463 m at 0.15 g and 0.4 Hz."""
    lc = lane_change(build(COMBINATIONS["adouble"]), 88.0, frequency_hz=0.4, amplitude_g=0.15, dt=0.002)
    assert 0.15 * G / (2 * math.pi * 0.4**2) == pytest.approx(1.4637, abs=1e-4)
    # the first-order hold's error on a sampled sine is (w dt)^2 / 12 = 2.1e-5 at this step
    assert lc.steer_axle_lateral_offset_m == pytest.approx(0.15 * G / (2 * math.pi * 0.4**2), rel=4e-5)


def test_time_response_to_a_long_sine_equals_the_frequency_response():
    """After the transient decays, the rear unit's acceleration amplitude under a sine steer equals |H(j w)|."""
    m = build(COMBINATIONS["btrain-table16"])
    ss = m.state_space(80 / 3.6)
    f, dt = 0.5, 0.01
    t = np.arange(0.0, 40.0, dt)
    steer = np.sin(2 * np.pi * f * t)
    x = simulate(ss.A, ss.B, steer, dt)
    c, d = ss.acceleration(m.point_row(m.main_body[2], m.combination.units[2].cg_position_m))
    y = x @ c + d * steer
    h = frequency_response(ss, [(c, d)], np.array([f]))[0, 0]
    assert np.max(np.abs(y[t > 30.0])) == pytest.approx(abs(h), rel=2e-3)


def test_log_decrement_equals_the_eigenvalue_on_a_single_articulation():
    """Yaw plane tractor-semitrailer: the articulation's free decay after a pulse is the least-damped mode; its
    same-sign log decrement gives that eigenvalue's damping ratio."""
    base = COMBINATIONS["tractor-semitrailer-table15"]
    c = replace(base, units=(base.units[0], replace(base.units[1], cg_position_m=8.0)))
    data = DynamicsData(units={"trailer": UnitData(yaw_inertia_kgm2=3e5)},
                        groups={("tractor", "steer"): GroupData(8.0), ("tractor", "drive"): GroupData(8.0),
                                ("trailer", "trailer"): GroupData(4.0)})  # fmt: skip
    m = build(c, data, roll=False)
    ps = pulse_steer(m, 120.0, duration_s=30.0, dt=0.005)
    w, _, _ = eigen(m.state_space(120 / 3.6))
    k = least_damped_oscillatory(w)
    assert 0.05 < damping_ratio(w[k]) < 0.2  # a lightly damped sway, well apart from the real modes
    assert ps.yaw_damping_ratio == pytest.approx(damping_ratio(w[k]), rel=0.01)


def test_half_cycle_peaks_in_the_full_cycle_formula_halve_the_damping():
    """A decaying sine with zeta = 0.15: same-sign peaks give 0.15; every extremum in the full-cycle formula gives
    about half (0.076, the value the PBS sources note for the open implementation's mistake)."""
    zeta, wn = 0.15, 2 * math.pi
    t = np.arange(0, 20, 1e-4)
    y = np.exp(-zeta * wn * t) * np.sin(wn * math.sqrt(1 - zeta**2) * t)
    assert damping_from_peaks(y) == pytest.approx(0.15, rel=1e-3)
    assert damping_from_peaks(y, same_sign=False) == pytest.approx(0.076, abs=1e-3)


def test_sense_on_presets():
    """RA: A-double > B-double > tractor-semitrailer; over the highway speeds the yaw damping of every preset that
    sways falls as speed rises (the tractor-semitrailer's articulation does not sway: no peaks)."""
    ra = {cid: lane_change(build(COMBINATIONS[cid]), 88.0).rearward_amplification
          for cid in ("adouble", "btrain-table16", "tractor-semitrailer-table15")}  # fmt: skip
    assert ra["adouble"] > ra["btrain-table16"] > ra["tractor-semitrailer-table15"]
    for cid in ("adouble", "btrain-table16", "truck-trailer"):
        m = build(COMBINATIONS[cid])
        zetas = [pulse_steer(m, v).yaw_damping_ratio for v in (80.0, 100.0, 120.0)]
        assert zetas[0] > zetas[1] > zetas[2], cid
    assert pulse_steer(build(COMBINATIONS["tractor-semitrailer-table15"]), 100.0).yaw_damping_ratio is None


def test_low_speed_steady_turn_gives_the_equivalent_axle_its_sum_of_squares_radius():
    """At crawl speed the trailer's tandem centre runs at sqrt(R_h^2 - L_eq^2 + (L_eq - L)^2) with the equivalent
    wheelbase L_eq = L + sum(d_i^2)/(n L) (moment balance of n equal axles about the kingpin), R_h the kingpin's."""
    c = COMBINATIONS["tractor-semitrailer-table15"]
    m = build(c)
    st = steady_turn(m, 200.0, 0.5)
    assert len(m.parameters.groups[(1, 0)].axle_positions_m) == 3
    trailer = c.units[1]
    xs = m.parameters.groups[(1, 0)].axle_positions_m
    big_l = trailer.groups[0].position_m
    l_eq = big_l + sum((x - big_l) ** 2 for x in xs) / (len(xs) * big_l)
    # the kingpin's own radius from the model (the tandem's scrub pushes the tractor, so it is not kinematic)
    r_king = st.couplings[0]["path_radius_m"]
    expected = math.sqrt(r_king**2 - l_eq**2 + (l_eq - big_l) ** 2)
    got = next(a["path_radius_m"] for a in st.axles if a["unit"] == "trailer")
    assert r_king - got == pytest.approx(r_king - expected, rel=2e-3)


def test_preset_inertias_are_sourced_and_a_changed_vehicle_is_estimated():
    """The A-double's sprung inertias are TruckSim's (body and payload combined about their common CG, Izz adding
    as both CGs lie at LX 3500 mm: 40672.8 + 21750); a unit changed in any field is estimated, the others keep
    theirs."""
    from engine.dynamics.parameters import resolve

    c = COMBINATIONS["adouble"]
    p = resolve(c)
    assert p.units[1].yaw_inertia_kgm2.value == pytest.approx(40672.8 + 21750.0)
    hc = (2116 * 1.935 + 9000 * 2.3) / 11116
    ixx = 5592.5 + 6000 + 2116 * (1.935 - hc) ** 2 + 9000 * (2.3 - hc) ** 2
    assert p.units[1].roll_inertia_kgm2.value == pytest.approx(ixx)
    assert p.units[2].yaw_inertia_kgm2.value == 290.0 and "TrlSprM_1399a1df" in p.units[2].yaw_inertia_kgm2.source
    changed = replace(c, units=(c.units[0], replace(c.units[1], sprung_mass_kg=8000.0), *c.units[2:]))
    q = resolve(changed)
    assert q.units[1].yaw_inertia_kgm2.source.startswith("estimated")
    assert q.units[0].yaw_inertia_kgm2.value == 34802.6  # the unchanged tractor keeps its own


def test_impossible_dynamics_data_is_refused_naming_unit_and_field():
    c = COMBINATIONS["adouble"]
    u, g = "dynamics.units", "dynamics.groups"
    cases = [
        (DynamicsData(units={"trailer1": UnitData(front_overhang_m=-0.5)}), f"{u}[trailer1].front_overhang_m"),
        (DynamicsData(units={"trailer2": UnitData(yaw_inertia_kgm2=1000.0)}), f"{u}[trailer2].yaw_inertia_kgm2"),
        (DynamicsData(groups={("dolly", "dolly"): GroupData(30.0)}), f"{g}[dolly/dolly].cornering_coefficient_per_rad"),
        (DynamicsData(units={"trailer1": UnitData(rear_extent_m=6.0)}), f"{u}[trailer1].rear_extent_m"),
        (DynamicsData(units={"nope": UnitData()}), f"{u}[nope]"),
    ]
    for data, fieldname in cases:
        with pytest.raises(InvalidVehicle) as err:
            build(c, data)
        assert err.value.field == fieldname


def test_the_inertia_bound_message_quotes_the_unit_once():
    """The unit's id is quoted by its repr; a possessive after it read ``unit 'trailer2''s``."""
    with pytest.raises(InvalidVehicle) as err:
        build(COMBINATIONS["adouble"], DynamicsData(units={"trailer2": UnitData(yaw_inertia_kgm2=1000.0)}))
    message = str(err.value)
    assert "''" not in message
    assert "the own masses of unit 'trailer2' about its CG" in message
