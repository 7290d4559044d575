"""The hand-reduced fast path against the full Davies solution, and what the Davies statics determine."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.case import Case
from engine.errors import MechanismSingular
from engine.mechanics.davies import solve_statics
from engine.models import trailer2d, trailer3d, trailer3d_davies
from engine.models.stepping import stage_model
from engine.vehicle.presets import PRESETS

BTRAIN = PRESETS["table16-btrain"]
TRUCK = PRESETS["table22-truck"]

CASES_3D = [
    # (vehicle id, stage, bank %, slope %, psi deg, d1, d2, d3, overweight %, llt limit)
    ("table16-btrain", "full", 0, 0, 0, 0, 0, 0, 0, 1.0),
    ("table16-btrain", "full", 6, -8, 30, 0.08, 0.5, 0.1, 10, 0.6),
    ("table16-btrain", "tires-suspension", 12, 9, 10, -0.12, -1.0, -0.2, 0, 1.0),
    ("table15-semitrailer", "full", 10, 0, 0, 0, 0, 0, 0, 1.0),
    ("table23-semitrailer", "full", 2, 4, 20, 0.1, 0, 0, 5, 0.8),
    ("table22-truck", "full", 4, -6, 0, -0.1, 0.3, 0.05, 0, 1.0),
]


def _case(vid, bank, slope, psi, d1, d2, d3, ow, lim):
    v = PRESETS[vid]
    return trailer3d.SolverCase(
        weight=v.weight_kn * (1 + ow / 100),
        bank=math.atan(bank / 100),
        slope=math.atan(slope / 100),
        psi=math.radians(psi),
        d1=d1,
        d2=d2,
        d3=d3,
        llt_limit=lim,
    )


def _perturbed_state(m, rng):
    """A deformed state away from rest (so every joint angle and length is exercised)."""
    rear = tuple(v + rng.uniform(-0.02, 0.02) for v in m.rear.rest_state())
    front = tuple(v + rng.uniform(-0.01, 0.01) for v in m.front.rest_state())
    return trailer3d.State(rear, front, rng.uniform(-0.01, 0.01))


@pytest.mark.parametrize("params", CASES_3D, ids=lambda p: f"{p[0]}-{p[1]}-b{p[2]}-s{p[3]}-psi{p[4]}")
def test_reduced_statics_equal_davies_solution_at_a_deformed_state(params):
    vid, stage, *rest = params
    m = stage_model(Case(PRESETS[vid]), stage)
    case = _case(vid, *rest)
    state = _perturbed_state(m, np.random.default_rng(7))
    for ay in (None, 0.21):  # at the limit (ay unknown) and at a given ay
        a_fast, geo_f, cl_f, rf, ff = trailer3d.forces_at(m, case, state, ay)
        a_dav, geo_d, cl_d, rd, fd = trailer3d_davies.davies_forces_at(m, case, state, ay)
        assert a_dav == pytest.approx(a_fast, rel=1e-9)
        # positions by successive screws (Table 9) equal the planar chain of the fast path
        for p, q in ((geo_f.p27, geo_d.p27), (geo_f.p28, geo_d.p28), (geo_f.cg, geo_d.cg)):
            assert np.array(q) == pytest.approx(np.array(p), abs=1e-12)
        fast = [
            rf.fz_outer,
            rf.fz_inner,
            rf.fy_outer,
            rf.tire_outer,
            rf.tire_inner,
            *rf.suspension,
            ff.fz_outer,
            ff.fz_inner,
            ff.fy_outer,
            ff.tire_outer,
            ff.tire_inner,
            *ff.suspension,
            cl_f.tx27,
            cl_f.t28,
            cl_f.fr,
            *cl_f.f28,
        ]
        dav = [
            rd.fz_outer,
            rd.fz_inner,
            rd.fy_outer,
            rd.tire_outer,
            rd.tire_inner,
            *rd.suspension,
            fd.fz_outer,
            fd.fz_inner,
            fd.fy_outer,
            fd.tire_outer,
            fd.tire_inner,
            *fd.suspension,
            cl_d.tx27,
            cl_d.t28,
            cl_d.fr,
            *cl_d.f28,
        ]
        if ff.fifth_wheel is not None:
            fast += list(ff.fifth_wheel)
            dav += list(fd.fifth_wheel)
        scale = max(abs(x) for x in fast)
        assert np.array(dav) == pytest.approx(np.array(fast), rel=1e-9, abs=1e-9 * scale)


@pytest.mark.parametrize(
    "vid,stage", [("table16-btrain", "full"), ("table16-btrain", "tires-suspension"), ("table22-truck", "full")]
)
def test_srt_by_fast_path_equals_srt_by_davies_path(vid, stage):
    m = stage_model(Case(PRESETS[vid]), stage)
    case = _case(vid, 4, -4, 10, 0.04, 0.2, 0.05, 5, 1.0)
    fast = trailer3d.solve(m, case)
    dav = trailer3d.solve(m, case, forces=trailer3d_davies.davies_forces_at)
    assert dav.ay == pytest.approx(fast.ay, rel=1e-9)
    assert float(dav.geometry.roll) == pytest.approx(float(fast.geometry.roll), rel=1e-9)


def test_davies_system_size_rank_and_null_space_of_the_btrain():
    """22 cuts x 6 = 132 cut-set equations; the closures determine every reported quantity and no more."""
    m = stage_model(Case(BTRAIN), "full")
    case = _case("table16-btrain", 0, 0, 0, 0, 0, 0, 0, 1.0)
    state = trailer3d.solve(m, case).state
    mech, geo = trailer3d_davies.build_mechanism(m, case, state)
    n, j, f = mech.mobility_counts
    assert (n, j, f) == (23, 28, 3)  # Fig. 43: 23 links, 28 joints, Px Py Pz
    closures, primary, _extra = trailer3d_davies.davies_closures(m, case, geo, ay=0.3)
    bare = solve_statics(mech, primary, [])  # the cut-set law alone
    assert bare.n_equations == 22 * 6
    assert bare.n_unknowns == len(mech.variable_names) - 3
    assert bare.nullity > 0
    assert not {"Fz1", "Fz3", "Fz17", "Fz19"} & bare.determined  # the four-legged table (Fig. 60)
    sol = solve_statics(mech, primary, closures, require=trailer3d_davies.REPORTED + trailer3d_davies.REPORTED_FW)
    assert sol.residual < 1e-12
    assert sol.nullity > 0  # still underdetermined, as Eq. 6.19 ...
    free = set(sol.values) - sol.determined
    assert "My1" in free  # ... e.g. the pitch moments the front tires share
    with pytest.raises(MechanismSingular, match="My1"):
        sol["My1"]
    # without the roll-moment closure the tire loads are left in the null space
    partial = solve_statics(mech, primary, closures[:-1])
    assert "Fz3" not in partial.determined


def test_tire_loads_sum_to_the_normal_weight_component_in_the_davies_solution():
    m = stage_model(Case(BTRAIN), "full")
    case = _case("table16-btrain", 8, -6, 20, 0.05, 0.0, 0.0, 0, 1.0)
    sol = trailer3d.solve(m, case, forces=trailer3d_davies.davies_forces_at)
    total = sol.front.fz_outer + sol.front.fz_inner + sol.rear.fz_outer + sol.rear.fz_inner
    assert total == pytest.approx(sol.loads.pz, rel=1e-12)  # Pz, Eq. 4.26 at the limit
    assert sol.rear.fz_inner == pytest.approx(0.0, abs=1e-9)  # the limit: Fz19 = 0


def test_planar_model_fast_path_equals_davies_eq_5_14():
    v = PRESETS["table14-semitrailer"]
    m = trailer2d.build_model(v)
    rng = np.random.default_rng(3)
    state = tuple(x + rng.uniform(-0.02, 0.02) for x in m.group.rest_state())
    case = trailer2d.Case2D(weight=250.0, bank=math.atan(0.06), d1=0.05, d3=0.1, llt_limit=0.7)
    for ay in (None, 0.3):
        a1, _g1, cg1, _py1, _pz1, f1 = trailer2d.forces_at(m, case, state, ay)
        a2, _g2, cg2, _py2, _pz2, f2 = trailer2d.davies_forces_at(m, case, state, ay)
        assert a2 == pytest.approx(a1, rel=1e-10)
        assert np.array(cg2) == pytest.approx(np.array(cg1), abs=1e-12)
        fast = [f1.fz_outer, f1.fz_inner, f1.fy_outer, f1.tire_outer, f1.tire_inner, *f1.suspension]
        dav = [f2.fz_outer, f2.fz_inner, f2.fy_outer, f2.tire_outer, f2.tire_inner, *f2.suspension]
        assert np.array(dav) == pytest.approx(np.array(fast), rel=1e-9, abs=1e-9)


def test_planar_davies_system_is_square_and_determinate():
    """Eq. 5.11: 27 equations (9 cuts x 3) for 27 secondary variables; rank 27."""
    v = PRESETS["table14-semitrailer"]
    m = trailer2d.build_model(v)
    case = trailer2d.Case2D(weight=250.0, bank=0.0, d1=0.0, d3=0.0, llt_limit=1.0)
    mech, _ = trailer2d.build_mechanism(m, case, m.group.rest_state())
    from engine.mechanics.davies import PLANAR_YZ

    sol = solve_statics(mech, {"Py": 90.0, "Pz": 250.0}, space=PLANAR_YZ)
    assert (sol.n_equations, sol.n_unknowns, sol.rank, sol.nullity) == (27, 27, 27, 0)
    # Eq. 5.21 at rest geometry: Fz3 = (h1 Pz - h2 Py)/t
    h1, h2, t = 0.93, 0.499 + 0.205 + 1.346, 1.86
    assert sol["Fz3"] == pytest.approx((h1 * 250.0 - h2 * 90.0) / t, rel=1e-12)


def test_batched_fast_path_equals_one_case_at_a_time():
    m = stage_model(Case(BTRAIN), "full")
    banks = np.array([0.0, 0.04, 0.12])
    psis = np.radians([0.0, 20.0, 30.0])
    case = trailer3d.SolverCase(
        weight=np.full(3, BTRAIN.weight_kn),
        bank=np.arctan(banks),
        slope=np.array([0.0, -0.06, 0.09]),
        psi=psis,
        d1=np.array([0.0, 0.04, -0.08]),
        d2=np.zeros(3),
        d3=np.zeros(3),
        llt_limit=np.array([1.0, 0.6, 0.6]),
    )
    batch = trailer3d.solve(m, case, xp=np)
    for i in range(3):
        one = trailer3d.SolverCase(
            weight=BTRAIN.weight_kn,
            bank=float(case.bank[i]),
            slope=float(case.slope[i]),
            psi=float(psis[i]),
            d1=float(case.d1[i]),
            d2=0.0,
            d3=0.0,
            llt_limit=float(case.llt_limit[i]),
        )
        # a converged case stops where it would alone: the batch gives its answer to rounding
        assert batch.ay[i] == pytest.approx(trailer3d.solve(m, one).ay, rel=1e-13)


@pytest.mark.parametrize("bank,slope,psi", [(0, 0, 0), (8, -10, 0), (4, 6, 30)])
def test_eq_6_39_from_the_davies_coefficients_gives_the_same_srt(bank, slope, psi):
    """Eq. 6.37 read off the Davies solution at the limit geometry, then Eq. 6.39, equals the stepped SRT."""
    m = stage_model(Case(BTRAIN), "full")
    case = _case("table16-btrain", bank, slope, psi, 0.0, 0.0, 0.0, 0, 1.0)
    sol = trailer3d.solve(m, case)
    c52, c53, c54 = trailer3d_davies.eq_6_37_coefficients(m, case, sol.state)
    assert trailer3d_davies.srt_eq_6_39(c52, c53, c54, case.bank, case.slope) == pytest.approx(sol.ay, rel=1e-9)
    # a forward (downhill) force unloads the rear group (Eq. 4.27), so C52 > 0 and uphill raises the SRT
    assert c52 > 0 and c53 > 0


@pytest.mark.parametrize("row", CASES_3D)
def test_the_fixed_point_tolerance_leaves_the_srt_exact_to_1e_9_g(row):
    """FIXED_POINT_TOL (1e-10 on the state) is a speed/accuracy choice: the limit it returns agrees with a solve
    iterated to 1e-14 within 1e-9 g (the thesis quotes four digits), in the 3D model and in the 2D one."""
    vid, stage, *rest = row
    case = _case(vid, *rest)
    m = stage_model(Case(PRESETS[vid]), stage)
    default, tight = trailer3d.solve(m, case), trailer3d.solve(m, case, tol=1e-14)
    assert tight.iterations > default.iterations
    assert abs(default.ay - tight.ay) < 1e-9
    m2 = trailer2d.build_model(PRESETS[vid])
    case2 = trailer2d.Case2D(case.weight * m2.load_share, case.bank, case.d1, case.d3, case.llt_limit)
    default2, tight2 = trailer2d.solve(m2, case2), trailer2d.solve(m2, case2, tol=1e-14)
    assert tight2.iterations > default2.iterations
    assert abs(default2.ay - tight2.ay) < 1e-9
