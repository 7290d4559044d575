"""Tyre types of the yaw-roll model (engine.dynamics.tyres): each type reads its source's cells by its stated rule,
the stiffness rises with load while the coefficient falls, and the option reaches the model and the answer."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.dynamics import DynamicsData, GroupData, build
from engine.dynamics.parameters import as_dict, resolve
from engine.dynamics.response import eigen
from engine.dynamics.tyres import DEFAULT_TYRE_TYPE, TYRE_TYPES
from engine.errors import InvalidVehicle
from engine.vehicle.combination_presets import COMBINATIONS

RAD = 180.0 / math.pi


@pytest.mark.parametrize(
    ("tyre", "load_n", "fy_1deg_n"),
    [  # the 1 deg row of TruckSim's example tables (FY_TIRE_CARPET), first and last load of each
        ("trucksim-3000kg", 7357.5, 1253.8),
        ("trucksim-3000kg", 58860.0, 7612.3),
        ("trucksim-2000kg", 4905.0, 835.9),
        ("trucksim-2000kg", 39240.0, 5074.9),
        ("trucksim-3500kg", 8583.75, 1462.8),
        ("trucksim-3500kg", 68670.0, 8881.1),
    ],
)
def test_trucksim_tables_give_their_1deg_cell_per_degree(tyre, load_n, fy_1deg_n):
    assert TYRE_TYPES[tyre].stiffness_n_per_rad(load_n) == pytest.approx(fy_1deg_n * RAD, rel=1e-12)


def test_sae_steer_tyre_is_the_least_squares_line_over_its_measured_cells():
    # 'Fy; Steer Tire Asymmetric' at 20604 N: the cells of rows -2, -1, 0, 1, 2 deg as printed in the source
    alpha = np.array([-2.0, -1.0, 0.0, 1.0, 2.0])
    fy = np.array([5707.0, 3848.0, 574.0, -2700.0, -4866.0])
    slope, offset = np.polyfit(alpha, fy, 1)  # a second formulation of the fit, with its intercept
    assert offset == pytest.approx(512.6)  # the tyre's offset at zero slip (the cells' mean), fitted out
    assert TYRE_TYPES["sae-steer-295-75r22.5"].stiffness_n_per_rad(20604.0) == pytest.approx(-slope * RAD, rel=1e-12)


def test_sae_drive_tyre_is_the_line_through_the_origin_over_its_cells():
    # 'Fy: Drive Tire Symmetric' at 34336 N: 3905.5 N at 1 deg, 7155 N at 2 deg; its symmetric extension to -2 deg
    alpha = np.array([-2.0, -1.0, 1.0, 2.0])
    fy = np.array([-7155.0, -3905.5, 3905.5, 7155.0])
    slope, offset = np.polyfit(alpha, fy, 1)
    assert offset == pytest.approx(0.0, abs=1e-9)
    assert slope == pytest.approx((3905.5 + 2 * 7155.0) / 5.0)
    assert TYRE_TYPES["sae-drive-295-75r22.5"].stiffness_n_per_rad(34336.0) == pytest.approx(slope * RAD, rel=1e-12)


@pytest.mark.parametrize("tyre", [t for t in TYRE_TYPES if TYRE_TYPES[t].constant_per_rad is None])
def test_stiffness_rises_with_load_and_the_coefficient_falls(tyre):
    t = TYRE_TYPES[tyre]
    loads = np.linspace(2000.0, 1.2 * max(t.loads_n), 400)
    c = np.array([t.stiffness_n_per_rad(n) for n in loads])
    k = c / loads
    assert np.all(np.diff(c) > 0), "cornering stiffness must rise with load"
    lowest = min(n for n in t.loads_n if n > 0)
    above = loads > lowest  # below the table's lowest load the coefficient is held (a line through the origin)
    assert np.all(np.diff(k[above]) < 0), "the cornering coefficient must fall with load"
    assert np.allclose(k[~above], k[~above][0])
    assert np.all((k > 2.0) & (k < 12.0))  # inside the range accepted for a given coefficient


def test_the_three_trucksim_tables_are_one_tyre_scaled_by_its_load_rating():
    # at the same fraction of the load rating every one has the same coefficient (to the cells' rounding)
    for frac in (0.3, 0.7, 1.0, 1.6):
        k = [TYRE_TYPES[f"trucksim-{r}kg"].stiffness_n_per_rad(frac * r * 9.81) / (frac * r * 9.81)
             for r in (2000, 3000, 3500)]  # fmt: skip
        assert max(k) - min(k) < 2e-4 * max(k)


def test_openpbs_constant_type_equals_giving_the_coefficient():
    c = COMBINATIONS["adouble"]
    groups = [(u.id, g.id) for u in c.units for g in u.groups]
    by_type = build(c, DynamicsData(groups={k: GroupData(tyre_type="openpbs-constant") for k in groups}))
    by_value = build(c, DynamicsData(groups={k: GroupData(5.5) for k in groups}))
    for gp in by_type.parameters.groups.values():
        assert gp.cornering_coefficient_per_rad.value == pytest.approx(5.5)
    a = np.sort_complex(eigen(by_type.state_space(88.0 / 3.6))[0])
    b = np.sort_complex(eigen(by_value.state_space(88.0 / 3.6))[0])
    assert np.allclose(a, b, rtol=1e-12, atol=1e-12)


def test_the_default_tyre_type_is_the_presets_and_changes_nothing():
    c = COMBINATIONS["tractor-semitrailer-table15"]
    default = resolve(c)
    explicit = resolve(c, DynamicsData(groups={(u.id, g.id): GroupData(tyre_type=DEFAULT_TYRE_TYPE)
                                              for u in c.units for g in u.groups}))  # fmt: skip
    for key, gp in default.groups.items():
        assert gp.tyre_type == DEFAULT_TYRE_TYPE and gp.tyre_type_source.startswith("default")
        assert gp.cornering_stiffness_kn_per_rad == explicit.groups[key].cornering_stiffness_kn_per_rad
        assert explicit.groups[key].tyre_type_source == "given"
    rows = as_dict(c, default)["groups"]
    assert all(r["tyre_type"]["value"] == DEFAULT_TYRE_TYPE and "TruckSim" in r["tyre_type"]["source"] for r in rows)


def test_a_measured_steer_tyre_changes_the_steer_axle_only():
    c = COMBINATIONS["tractor-semitrailer-table15"]
    steer = (c.units[0].id, c.units[0].groups[0].id)
    base = resolve(c)
    sae = resolve(c, DynamicsData(groups={steer: GroupData(tyre_type="sae-steer-295-75r22.5")}))
    per_tyre = base.groups[(0, 0)].axle_load_kn * 1000.0 / c.units[0].groups[0].tyres_per_axle
    expected = c.units[0].groups[0].tyres_per_axle * TYRE_TYPES["sae-steer-295-75r22.5"].stiffness_n_per_rad(per_tyre)
    assert sae.groups[(0, 0)].cornering_stiffness_kn_per_rad[0] * 1000.0 == pytest.approx(expected, rel=1e-9)
    assert "SAE Steer Tire" in sae.groups[(0, 0)].cornering_coefficient_per_rad.source
    for key in base.groups:
        if key != (0, 0):
            assert sae.groups[key].cornering_stiffness_kn_per_rad == base.groups[key].cornering_stiffness_kn_per_rad


def test_a_tyre_type_with_a_coefficient_or_an_unknown_type_is_refused_naming_the_field():
    c = COMBINATIONS["adouble"]
    for gd in (GroupData(6.0, tyre_type="sae-drive-295-75r22.5"), GroupData(tyre_type="385/65R22.5")):
        with pytest.raises(InvalidVehicle) as err:
            build(c, DynamicsData(groups={("dolly", "dolly"): gd}))
        assert err.value.field == "dynamics.groups[dolly/dolly].tyre_type"
