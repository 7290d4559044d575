"""The combination model's batch solve (engine.models.combination_batch) against its scalar solve, row by row.

The batch follows the scalar's arithmetic on stacked rows, so every row must give the scalar
``rollover_threshold(case).srt`` and ``.roll_angle_deg`` bit for bit, on the presets and on random vehicles, over
banks, grades, load cases and LLT limits; a row the lockstep cannot follow is solved alone, and a row that fails
fails alone.
"""

from __future__ import annotations

import numpy as np
import pytest

from engine import Case, LoadCase, Road, sweep
from engine.errors import RolloverError
from engine.models import combination as whole
from engine.models import combination_batch
from engine.models.registry import get_model
from engine.models.threshold import _columns, case_at, evaluate_arrays, rollover_threshold
from engine.vehicle.combination_presets import COMBINATIONS
from tests.engine.test_combination import random_combination

BANKS = (-8.0, -3.0, 0.0, 2.5, 6.0, 10.0, 12.0)
GRADES = (-8.0, -2.0, 0.0, 4.0, 8.0)
LOADS = ({}, {"lateral_offset_m": 0.1}, {"lateral_offset_m": -0.08, "vertical_offset_m": 0.2, "overweight_percent": 10})


def grid(loads=LOADS, banks=BANKS, grades=GRADES, limits=(1.0,)) -> dict[str, np.ndarray]:
    rows = [(b, s, L, ld) for ld in loads for L in limits for b in banks for s in grades]
    out = {"bank_percent": np.array([r[0] for r in rows]), "slope_percent": np.array([r[1] for r in rows])}
    out["rear_llt_limit"] = np.array([r[2] for r in rows])
    for k in ("lateral_offset_m", "vertical_offset_m", "overweight_percent"):
        out[k] = np.array([r[3].get(k, 0.0) for r in rows])
    return out


def scalar(case: Case, col, i: int):
    try:
        r = rollover_threshold(case_at(case, col, i))
    except RolloverError as exc:
        return None, None, str(exc)
    return r.srt, r.roll_angle_deg, None


def assert_batch_is_scalar(case: Case, arrays) -> None:
    srt, roll, errors = evaluate_arrays(case, arrays)
    col = _columns(case, len(srt), arrays)
    for i in range(len(srt)):
        s, r, err = scalar(case, col, i)
        if err is not None:
            assert i in errors, (i, err)
            continue
        assert i not in errors, (i, errors.get(i))
        # the same arithmetic row by row: the same bits (a route's curve answers what /v1/srt answers there)
        assert srt[i] == s
        assert roll[i] == r


@pytest.mark.parametrize("cid", list(COMBINATIONS))
def test_the_batch_is_the_scalar_solve_on_every_preset(cid):
    assert_batch_is_scalar(Case(COMBINATIONS[cid], model="combination"), grid())


@pytest.mark.parametrize("cid", ["tractor-semitrailer-table15", "adouble"])
def test_the_batch_is_the_scalar_solve_at_an_llt_limit(cid):
    arrays = grid(loads=LOADS[:2], banks=(-4.0, 0.0, 6.0, 12.0), grades=(-8.0, 0.0, 8.0), limits=(0.7, 0.9, 1.0))
    assert_batch_is_scalar(Case(COMBINATIONS[cid], model="combination"), arrays)


@pytest.mark.parametrize("seed", range(1, 13))
def test_the_batch_is_the_scalar_solve_on_random_vehicles(seed):
    c = random_combination(np.random.default_rng(seed))
    arrays = grid(loads=LOADS[:2], banks=(-8.0, 0.0, 4.0, 12.0), grades=(-8.0, 0.0, 8.0), limits=(0.8, 1.0))
    assert_batch_is_scalar(Case(c, model="combination"), arrays)


def test_evaluate_arrays_and_sweeps_use_the_batch(monkeypatch):
    assert get_model("combination").batch is combination_batch.batch
    calls = []
    real = whole.solve_combination
    monkeypatch.setattr(whole, "solve_combination", lambda *a, **k: calls.append(1) or real(*a, **k))
    case = Case(COMBINATIONS["btrain-table16"], model="combination")
    result = sweep(case, {"bank_percent": [0.0, 4.0, 8.0], "slope_percent": [-5.0, 0.0, 5.0]})
    assert not calls  # no row was solved one by one
    one = rollover_threshold(case.replace(road=Road(bank_percent=8.0, slope_percent=5.0)))
    assert result.srt[-1] == pytest.approx(one.srt, rel=1e-12)
    assert result.roll_angle_deg[-1] == pytest.approx(one.roll_angle_deg, rel=1e-12)


def test_a_row_the_lockstep_cannot_follow_is_solved_alone(monkeypatch):
    real = combination_batch._stable

    def first_row_unstable(*args):
        out = real(*args)
        out[0] = False
        return out

    monkeypatch.setattr(combination_batch, "_stable", first_row_unstable)
    case = Case(COMBINATIONS["adouble"], model="combination")
    assert_batch_is_scalar(case, grid(loads=LOADS[:1], banks=(0.0, 6.0), grades=(0.0, 4.0)))


def test_a_row_that_fails_fails_alone():
    case = Case(COMBINATIONS["tractor-semitrailer-table15"], model="combination")
    arrays = {"bank_percent": np.array([0.0, 6.0, 6.0, 10.0]), "lateral_offset_m": np.array([0.0, 0.0, 1.2, 0.05])}
    srt, roll, errors = evaluate_arrays(case, arrays)
    assert list(errors) == [2]  # its CG is outside the track
    for i in (0, 1, 3):
        one = rollover_threshold(
            case.replace(
                road=Road(bank_percent=float(arrays["bank_percent"][i])),
                load=LoadCase(lateral_offset_m=float(arrays["lateral_offset_m"][i])),
            )
        )
        assert srt[i] == pytest.approx(one.srt, rel=1e-12)
        assert roll[i] == pytest.approx(one.roll_angle_deg, rel=1e-12)


def test_a_refused_row_gets_the_scalar_message():
    # a row the batch refuses is solved alone by evaluate_arrays, for the scalar's own message
    case = Case(COMBINATIONS["tractor-semitrailer-table15"], model="combination")
    _srt, _roll, errors = evaluate_arrays(case, {"lateral_offset_m": np.array([0.0, 1.2])})
    with pytest.raises(RolloverError) as exc:
        rollover_threshold(case.replace(load=LoadCase(lateral_offset_m=1.2)))
    assert errors[1] == str(exc.value)


def test_the_stability_test_is_cholesky_on_the_rows():
    # _stable's pivots on the tree must answer what each row's dense Cholesky factor answers, on the presets' own
    # pieces with P-Delta diagonals from clearly stable to unstable, through the edge
    rng = np.random.default_rng(3)
    for cid in COMBINATIONS:
        for s in whole.build_systems(COMBINATIONS[cid], 0.0, 0.0, whole.UnitLoad()):
            e = whole._elements(s)
            T, Z = len(s.tyres), len(s.zones)
            for tyre in [(whole.LINEAR,) * T, (whole.LIFTED,) + (whole.LINEAR,) * (T - 1)]:
                zone = (whole.PLUS,) * Z
                K = e.piece(tyre, zone)[0]
                lam = np.linalg.eigvalsh(K)[0]
                scale = rng.choice([0.5, 0.99, 1.0, 1.01, 2.0], size=(40, 1))
                pd = rng.uniform(0.0, 1.0, (40, s.n)) * abs(lam) * scale * s.n
                expect = [_cholesky_exists(K - np.diag(p)) for p in pd]
                got = combination_batch._stable(e, tyre, zone, np.ascontiguousarray(pd.T))  # DOF by row
                assert got.tolist() == expect, cid
                assert 0 < sum(expect) < len(expect), cid  # both answers seen


def _cholesky_exists(J) -> bool:
    try:
        np.linalg.cholesky(0.5 * (J + J.T))
    except np.linalg.LinAlgError:
        return False
    return True


def test_a_singular_vertex_stops_its_own_newton_steps_only():
    # the batch's Newton start on many rows must give each row what it gives the row alone (the scalar's call): a
    # row whose vertex system is singular stops where it is, and the others go on
    s = whole.build_systems(COMBINATIONS["btrain-table16"], 0.0, 0.0, whole.UnitLoad())[0]
    e = whole._elements(s)
    T, Z = len(s.tyres), len(s.zones)
    kd, ke = e.tree_piece((whole.LINEAR,) * T, (whole.BAND,) * Z)
    rng = np.random.default_rng(0)
    m, n = 6, s.n
    jp, k = rng.standard_normal((m, n)) * 100.0, rng.standard_normal((m, n)) * 100.0
    c1, c2, b = rng.standard_normal(m), rng.standard_normal(m), rng.standard_normal(m)
    c1[2] = c2[2] = 0.0  # row 2's constraint row is zero: its system is singular
    i1, i2 = np.full(m, 1), np.full(m, n)
    pn, pg = np.diagonal(s.P_normal).tolist(), np.diagonal(s.P_grade).tolist()
    n0, n1, grade = rng.uniform(0.9, 1.0, m), rng.uniform(0.0, 0.1, m), rng.uniform(-0.05, 0.05, m)
    a = rng.uniform(0.3, 0.5, m)
    cols = lambda x: [x[:, v] for v in range(n)]  # noqa: E731
    many = whole._vertex_fixed_point(e.tree, kd, ke, cols(jp), cols(k), c1, c2, b, i1, i2, pn, pg, n0, n1, grade, a)
    for i in range(m):
        one = whole._vertex_fixed_point(
            e.tree, kd, ke, jp[i].tolist(), k[i].tolist(), float(c1[i]), float(c2[i]), float(b[i]), 1, n, pn, pg,
            float(n0[i]), float(n1[i]), float(grade[i]), float(a[i]),
        )  # fmt: skip
        assert many[i] == one, i
    assert many[2] == a[2]  # the singular row did not move
    assert np.all(many[[0, 1, 3, 4, 5]] != a[[0, 1, 3, 4, 5]])


def test_the_vertex_fixed_point_is_the_dense_bordered_solve():
    # the Newton steps on the tree (a bordered elimination) against the same fixed point written densely: the vertex
    # system [[K - P(n0 + n1 a), jp], [c]] (z) = (-k, -b) solved with LAPACK until z[n] = a
    s = whole.build_systems(COMBINATIONS["adouble"], 6.0, 2.0, whole.UnitLoad())[1]
    e = whole._elements(s)
    T, Z = len(s.tyres), len(s.zones)
    tyre, zone = (whole.LIFTED,) + (whole.LINEAR,) * (T - 1), (whole.PLUS,) * Z
    K = e.piece(tyre, zone)[0]
    kd, ke = e.tree_piece(tyre, zone)
    jp, k = whole._assemble(s, whole.Regime(list(tyre), list(zone)), 2)
    n, r = s.n, s.road
    for i1, i2, c1, c2, b in ((1, n, 2000.0, -30.0, -5.0), (0, 2, 1.0, -1.0, 0.01)):
        got = whole._vertex_fixed_point(
            e.tree, kd, ke, jp.tolist(), k.tolist(), c1, c2, b, i1, i2, np.diagonal(s.P_normal).tolist(),
            np.diagonal(s.P_grade).tolist(), r.n0, r.n1, r.grade, 0.3,
        )  # fmt: skip
        a = 0.3
        for _ in range(50):
            M = np.zeros((n + 1, n + 1))
            M[:n, :n] = K - ((r.n0 + r.n1 * a) * s.P_normal + r.grade * s.P_grade)
            M[:n, n] = jp
            M[n, i1] += c1
            M[n, i2] += c2
            a = float(np.linalg.solve(M, np.append(-k, -b))[n])
        assert got == pytest.approx(a, rel=1e-12, abs=1e-14)
