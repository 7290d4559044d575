"""The generic Davies core on mechanisms whose statics can be written by hand (App. A, Sec. 3.1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.errors import MechanismSingular
from engine.mechanics.davies import PLANAR_YZ, SPATIAL, Closure, cutset_matrix, incidence_matrix, solve_statics
from engine.mechanics.mechanism import Mechanism, custom_joint, external, joint
from engine.mechanics.screw import rot_x, screw_matrix, successive, unit_couple, unit_force

X = np.array([1.0, 0.0, 0.0])


# ------------------------------------------------------------------------------------ screw theory


def test_screw_matrix_rotation_about_offset_axis_matches_rotation_formula():
    # Eqs. A.3-A.4: rotating the point (0, 2, 0) by 90 deg about x through (0, 1, 0) gives (0, 1, 1)
    a = screw_matrix((1, 0, 0), (0, 1, 0), math.pi / 2, 0.0)
    p = a @ np.array([0.0, 2.0, 0.0, 1.0])
    assert p[:3] == pytest.approx([0.0, 1.0, 1.0], abs=1e-12)
    # a pure translation d along an arbitrary unit axis
    s = np.array([1.0, 2.0, 2.0]) / 3.0
    t = screw_matrix(s, (5, -1, 3), 0.0, 0.6)
    assert t[:3, 3] == pytest.approx(0.6 * s, abs=1e-12)
    assert t[:3, :3] == pytest.approx(np.eye(3), abs=1e-12)


def test_screw_matrix_is_a_rigid_motion_for_arbitrary_axis():
    rng = np.random.default_rng(1)
    for _ in range(20):
        s = rng.normal(size=3)
        s /= np.linalg.norm(s)
        a = screw_matrix(s, rng.normal(size=3), rng.uniform(-3, 3), rng.uniform(-1, 1))
        r = a[:3, :3]
        assert r.T @ r == pytest.approx(np.eye(3), abs=1e-12)
        assert np.linalg.det(r) == pytest.approx(1.0, abs=1e-12)
        assert r @ s == pytest.approx(s, abs=1e-12)  # the screw axis is invariant


def test_successive_screws_compose_like_planar_rotations():
    # two revolutes about parallel x axes: the end of a 2-link planar arm (lengths 1 and 0.5)
    t1, t2 = 0.3, -0.7
    a1 = screw_matrix((1, 0, 0), (0, 0, 0), t1)
    a2 = screw_matrix((1, 0, 0), (0, 1.0, 0), t2)
    p = successive(a1, a2) @ np.array([0.0, 1.5, 0.0, 1.0])
    expected = rot_x(t1) @ np.array([0, 1.0, 0]) + rot_x(t1 + t2) @ np.array([0, 0.5, 0])
    assert p[:3] == pytest.approx(expected, abs=1e-12)


def test_unit_wrench_moment_is_position_cross_direction():
    w = unit_force((0, 0, 2.0), (0, 3.0, 0))  # Eq. 3.4: Fz at y = 3 -> Mx = y Fz
    assert w == pytest.approx([3.0, 0, 0, 0, 0, 1.0])
    assert unit_couple((0, 0, -5.0)) == pytest.approx([0, 0, -1.0, 0, 0, 0])


# --------------------------------------------------------------------------------- four-bar (App. A)


def four_bar(theta2: float):
    """Crank-rocker in the y-z plane; returns joint points for crank angle theta2 (ground pivots a, d)."""
    a = np.array([0.0, 0.0, 0.0])
    d = np.array([0.0, 4.0, 0.0])
    r2, r3, r4 = 1.0, 4.5, 3.0
    b = a + r2 * np.array([0.0, math.cos(theta2), math.sin(theta2)])
    # c: intersection of circle (b, r3) and circle (d, r4), upper branch
    bd = d - b
    dist = np.linalg.norm(bd)
    along = (r3**2 - r4**2 + dist**2) / (2 * dist)
    h = math.sqrt(r3**2 - along**2)
    u = bd / dist
    perp = np.array([0.0, -u[2], u[1]])
    c = b + along * u + h * perp
    return a, b, c, d


def build_four_bar(theta2: float) -> Mechanism:
    a, b, c, d = four_bar(theta2)
    m = Mechanism(["1", "2", "3", "4"])
    eye = np.eye(3)
    joint(m, "a", "1", "2", a, eye, "planar-revolute", actuator="Ta")
    joint(m, "b", "2", "3", b, eye, "planar-revolute")
    joint(m, "c", "3", "4", c, eye, "planar-revolute")
    joint(m, "d", "1", "4", d, eye, "planar-revolute", actuator="Td")
    return m


def test_incidence_and_cutset_match_appendix_a():
    m = build_four_bar(0.8)
    inc = incidence_matrix(m)
    assert inc.tolist() == [[1, 0, 0, 1], [-1, 1, 0, 0], [0, -1, 1, 0], [0, 0, -1, -1]]  # Eq. A.9
    cs = cutset_matrix(inc)
    assert cs.q.tolist() == [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]]  # Eq. A.10
    assert cs.branches == (0, 1, 2) and cs.chords == (3,)


def test_four_bar_output_torque_obeys_virtual_work_and_coupler_is_two_force_member():
    theta2, ta = 0.8, 10.0
    m = build_four_bar(theta2)
    sol = solve_statics(m, {"Ta": ta}, space=PLANAR_YZ)
    assert sol.nullity == 0 and sol.rank == 9  # 3 cuts x 3 equations, 9 unknowns (Eq. A.11)
    # virtual work: Ta w2 + Td w4 = 0, with w4/w2 from the loop closure by central differences
    eps = 1e-6

    def rocker(t):
        _, _, c, d = four_bar(t)
        return math.atan2(c[2] - d[2], c[1] - d[1])

    ratio = (rocker(theta2 + eps) - rocker(theta2 - eps)) / (2 * eps)
    assert sol["Td"] == pytest.approx(-ta / ratio, rel=1e-7)
    # the coupler carries no moment: the force at b is along b-c
    _, b, c, _ = four_bar(theta2)
    fb = np.array([sol["Fyb"], sol["Fzb"]])
    bc = (c - b)[1:]
    assert abs(fb[0] * bc[1] - fb[1] * bc[0]) == pytest.approx(0.0, abs=1e-9 * np.linalg.norm(fb))


def test_underdetermined_mechanism_reports_which_quantities_are_free():
    # a rigid bar on two ground pins (one redundant horizontal reaction): the vertical reactions are
    # determined by statics, the horizontal ones only in sum.
    m = Mechanism(["ground", "bar"])
    custom_joint(
        m, "1", "ground", "bar", [("Fy1", unit_force((0, 1, 0), (0, 0, 0))), ("Fz1", unit_force((0, 0, 1), (0, 0, 0)))]
    )
    custom_joint(
        m,
        "2",
        "ground",
        "bar",
        [("Fy2", unit_force((0, 1, 0), (0, 2.0, 0))), ("Fz2", unit_force((0, 0, 1), (0, 2.0, 0)))],
    )
    external(m, "P", "bar", unit_force((0, -0.6, -0.8), (0, 0.5, 1.0)))
    sol = solve_statics(m, {"P": 10.0}, space=PLANAR_YZ)
    assert sol.nullity == 1
    assert {"Fz1", "Fz2"} <= sol.determined
    assert "Fy1" not in sol.determined
    with pytest.raises(MechanismSingular, match="Fy1"):
        sol["Fy1"]
    # moments about pin 1: 2 Fz2 = 0.5 (8) - 1.0 (6)  (force (0, -6, -8) at (0.5, 1.0))
    assert sol["Fz2"] == pytest.approx((0.5 * 8 - 1.0 * 6) / 2.0)
    assert sol["Fz1"] + sol["Fz2"] == pytest.approx(8.0)
    # a closure that fixes the split makes everything determined
    closed = solve_statics(m, {"P": 10.0}, [Closure({"Fy1": 1.0, "Fy2": -1.0})], space=PLANAR_YZ)
    assert closed.nullity == 0
    assert closed["Fy1"] == pytest.approx(3.0) and closed["Fy2"] == pytest.approx(3.0)
    # a contradictory closure is refused
    with pytest.raises(MechanismSingular, match="inconsistent"):
        solve_statics(m, {"P": 10.0}, [Closure({"Fz1": 1.0}, constant=-1.0)], space=PLANAR_YZ)


# ------------------------------------------------------------------------- buckling column (Sec. 3.1)


@pytest.mark.parametrize("theta", [0.0, 0.05, -0.2])
def test_buckling_column_spring_and_torsion_carry_axial_and_bending(theta):
    """Fig. 20: base revolute with torsion spring T, prismatic with axial spring Fn, tip load (Fy, Fz)."""
    length, fy, fz = 1.2, 3.0, -50.0
    axis = rot_x(theta) @ np.array([0.0, 0.0, 1.0])
    tip = length * axis
    frame = rot_x(theta)  # e1 = x, e3 along the bar
    m = Mechanism(["A", "B", "C"])
    joint(m, "1", "A", "B", (0, 0, 0), frame, "planar-revolute", actuator="T")
    joint(m, "2", "B", "C", 0.5 * tip, frame, "planar-prismatic", actuator="Fn")
    external(m, "Fy", "C", unit_force((0, 1, 0), tip))
    external(m, "Fz", "C", unit_force((0, 0, 1), tip))
    sol = solve_statics(m, {"Fy": fy, "Fz": fz}, space=PLANAR_YZ)
    assert sol.nullity == 0
    load = np.array([0.0, fy, fz])
    # the spring carries the axial component: the base pushes the tip up the bar
    assert sol["Fn"] == pytest.approx(-load @ axis, rel=1e-12)
    # the torsion spring carries the moment of the tip load about the base
    assert sol["T"] == pytest.approx(-np.cross(tip, load)[0], rel=1e-12, abs=1e-12)


def test_spatial_rigid_table_reactions_need_a_closure():
    """Four-legged table (Fig. 60): 4 vertical legs under a point load are once indeterminate."""
    m = Mechanism(["ground", "top"])
    legs = {"1": (0, 0), "2": (2, 0), "3": (2, 1), "4": (0, 1)}
    for name, (x, y) in legs.items():
        custom_joint(m, name, "ground", "top", [(f"Fz{name}", unit_force((0, 0, 1), (x, y, 0)))])
    # the table top is otherwise held in its plane by an ideal guide (x, y forces, z moment)
    custom_joint(
        m,
        "g",
        "ground",
        "top",
        [("Gx", unit_force(X, (0, 0, 0))), ("Gy", unit_force((0, 1, 0), (0, 0, 0))), ("Gz", unit_couple((0, 0, 1)))],
    )
    external(m, "W", "top", unit_force((0, 0, -1), (0.8, 0.4, 0.5)))
    sol = solve_statics(m, {"W": 100.0}, space=SPATIAL)
    assert sol.nullity == 1
    assert not {"Fz1", "Fz2", "Fz3", "Fz4"} & sol.determined
    # the classic closure: diagonal sums equal (elastic floor) -> unique answer, total = W
    closed = solve_statics(m, {"W": 100.0}, [Closure({"Fz1": 1, "Fz3": 1, "Fz2": -1, "Fz4": -1})], space=SPATIAL)
    total = sum(closed[f"Fz{i}"] for i in "1234")
    assert total == pytest.approx(100.0)
    mx = sum(closed[f"Fz{i}"] * legs[i][1] for i in "1234")
    assert mx == pytest.approx(100.0 * 0.4)
