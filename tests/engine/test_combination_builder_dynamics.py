"""A combination spec's data for the yaw-roll model (issue 42, item 2): the builder carries it beside the combination
it builds, the model takes it, the static record and answers do not see it."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest

from engine.builder import CombinationSpec, build_combination
from engine.dynamics import build
from engine.errors import InvalidVehicle
from engine.models import solve_combination
from engine.vehicle.combination import G_M_PER_S2

STEER = {"axles": 1, "tyres_per_axle": 2, "track_m": 2.03, "position_m": 0.0, "tyre": {"size": "295/80R22.5"},
         "suspension": {"type": "trucksim-steer-leaf-5.5t"}}  # fmt: skip
DRIVE = {"axles": 1, "tyres_per_axle": 4, "track_m": 1.863, "position_m": 5.0, "tyre": {"size": "295/80R22.5"},
         "suspension": {"type": "trucksim-trailer-leaf-18t"}}  # fmt: skip
WHEELBASE_M = 5.0


def rigid_truck(iz: float | None, cc_front: float = 6.0, cc_rear: float = 5.0) -> dict:
    """A two-axle rigid truck, its cornering coefficients and (when given) its yaw inertia in the spec."""
    unit = {"kind": "rigid-truck", "axle_groups": [{**STEER, "dynamics": {"cornering_coefficient_per_rad": cc_front}},
                                                   {**DRIVE, "dynamics": {"cornering_coefficient_per_rad": cc_rear}}],
            "tare": {"mass_kg": 14000.0, "cg_height_m": 1.3, "cg_from_kingpin_m": 2.2}}  # fmt: skip
    if iz is not None:
        unit["dynamics"] = {"yaw_inertia_kgm2": iz}
    return {"units": [unit]}


def bicycle_eigenvalues(m: float, a: float, iz: float, cf: float, cr: float, u: float) -> np.ndarray:
    """The two-degree-of-freedom bicycle model in (v, r) (Gillespie 1992, ch. 6, linear tyres; b = L - a):
    m (v' + u r) = -(Cf + Cr) v / u - (a Cf - b Cr) r / u, Iz r' = -(a Cf - b Cr) v / u - (a^2 Cf + b^2 Cr) r / u."""
    b = WHEELBASE_M - a
    A = np.array([[-(cf + cr) / (m * u), -(a * cf - b * cr) / (m * u) - u],
                  [-(a * cf - b * cr) / (iz * u), -(a * a * cf + b * b * cr) / (iz * u)]])  # fmt: skip
    return np.sort_complex(np.linalg.eigvals(A))


@pytest.mark.parametrize("iz", [25_000.0, 60_000.0])
def test_a_yaw_inertia_given_in_the_spec_moves_the_eigenvalues_as_the_bicycle_model_predicts(iz):
    """The yaw-plane model of a spec'd rigid truck (its yaw inertia and cornering coefficients typed in the spec) has
    the bicycle model's two eigenvalues beside the two zeros of its lateral position and heading."""
    built = build_combination(CombinationSpec.from_dict(rigid_truck(iz)))
    unit = built.units[0]
    m, a = unit.mass_kg, unit.cg_position_m  # the whole unit, axles included
    wf, wr = m * G_M_PER_S2 * (WHEELBASE_M - a) / WHEELBASE_M, m * G_M_PER_S2 * a / WHEELBASE_M  # the lever rule
    model = build(built.combination, built.dynamics, roll=False)
    for kmh in (40.0, 80.0):
        u = kmh / 3.6
        lam = np.linalg.eigvals(model.state_space(u).A)
        moving = np.sort_complex(lam[np.abs(lam) > 1e-9])
        np.testing.assert_allclose(moving, bicycle_eigenvalues(m, a, iz, 6.0 * wf, 5.0 * wr, u), rtol=1e-9)


def test_the_yaw_inertia_is_not_the_estimate():
    """The same truck without the given yaw inertia has other eigenvalues: the spec's value is the one used."""
    estimated = build_combination(CombinationSpec.from_dict(rigid_truck(None)))
    given = build_combination(CombinationSpec.from_dict(rigid_truck(60_000.0)))
    lam = [np.linalg.eigvals(build(b.combination, b.dynamics, roll=False).state_space(20.0).A) for b in
           (estimated, given)]  # fmt: skip
    assert not np.allclose(np.sort_complex(lam[0]), np.sort_complex(lam[1]), rtol=1e-3)


def test_the_data_is_carried_beside_the_combination_and_the_static_model_does_not_see_it():
    with_data = rigid_truck(60_000.0)
    with_data["units"][0]["dynamics"]["width_m"] = 2.55
    with_data["units"][0]["axle_groups"][1]["axle_spacing_m"] = 1.3
    without = copy.deepcopy(with_data)
    del without["units"][0]["dynamics"]
    for g in without["units"][0]["axle_groups"]:
        del g["dynamics"]
    del without["units"][0]["axle_groups"][1]["axle_spacing_m"]
    b1 = build_combination(CombinationSpec.from_dict(with_data))
    b0 = build_combination(CombinationSpec.from_dict(without))
    assert b1.combination == b0.combination  # the record (and so the static answers' keys) unchanged
    assert [u.srt for u in solve_combination(b1.combination).roll_coupled_units] == [
        u.srt for u in solve_combination(b0.combination).roll_coupled_units
    ]
    assert not b0.dynamics
    d = b1.dynamics
    assert (d.units["rigid-truck"].yaw_inertia_kgm2, d.units["rigid-truck"].width_m) == (60_000.0, 2.55)
    assert d.groups[("rigid-truck", "steer")].cornering_coefficient_per_rad == 6.0
    # the group's own axle spacing is its spacing for the yaw-roll model: typed once, on the group
    assert d.groups[("rigid-truck", "drive")].axle_spacing_m == 1.3
    assert d.given_at == {
        "units[rigid-truck].yaw_inertia_kgm2": "combination_spec.units[0].dynamics.yaw_inertia_kgm2",
        "units[rigid-truck].width_m": "combination_spec.units[0].dynamics.width_m",
        "groups[rigid-truck/steer].cornering_coefficient_per_rad":
            "combination_spec.units[0].axle_groups[0].dynamics.cornering_coefficient_per_rad",
        "groups[rigid-truck/drive].cornering_coefficient_per_rad":
            "combination_spec.units[0].axle_groups[1].dynamics.cornering_coefficient_per_rad",
        "groups[rigid-truck/drive].axle_spacing_m": "combination_spec.units[0].axle_groups[1].axle_spacing_m",
    }  # fmt: skip
    assert b1.to_dict()["dynamics"] == {
        "units": [{"unit": "rigid-truck", "yaw_inertia_kgm2": 60_000.0, "width_m": 2.55}],
        "groups": [{"unit": "rigid-truck", "group": "steer", "cornering_coefficient_per_rad": 6.0},
                   {"unit": "rigid-truck", "group": "drive", "cornering_coefficient_per_rad": 5.0,
                    "axle_spacing_m": 1.3}],
    }  # fmt: skip


@pytest.mark.parametrize(
    ("change", "field"),
    [
        (lambda s: s["units"][0]["axle_groups"][1]["dynamics"].update(axle_spacing_m=1.3),
         "combination_spec.units[0].axle_groups[1].dynamics.axle_spacing_m"),
        (lambda s: s["units"][0].update(dynamics={"width_m": math.nan}), "combination_spec.units[0].dynamics.width_m"),
        (lambda s: s["units"][0].update(dynamics={"inertia": 1.0}), "combination_spec.units[0].dynamics.inertia"),
    ],
)  # fmt: skip
def test_the_builder_refuses_naming_the_spec_field(change, field):
    spec = rigid_truck(None)
    change(spec)
    with pytest.raises(InvalidVehicle) as err:
        build_combination(CombinationSpec.from_dict(spec))
    assert err.value.field == field
