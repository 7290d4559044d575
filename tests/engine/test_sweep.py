"""Grids of cases (Tables 17 and 19) in one call equal the same cases solved one at a time."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

from engine.case import Case, LoadCase, Road
from engine.models.threshold import BATCH_ROWS, evaluate_arrays, rollover_threshold, sweep
from engine.vehicle.presets import PRESETS

BTRAIN = PRESETS["table16-btrain"]


def test_3d_sweep_equals_single_solves_in_cartesian_order():
    grid = {"trailer_angle_deg": [0, 30], "bank_percent": [0, 6], "slope_percent": [4, -8]}
    res = sweep(Case(BTRAIN, rear_llt_limit=0.6), grid)
    assert res.values.shape == (8, 3)
    for (psi, bank, slope), srt in zip(res.values, res.srt, strict=True):
        one = rollover_threshold(
            Case(BTRAIN, road=Road(bank_percent=bank, slope_percent=slope), trailer_angle_deg=psi, rear_llt_limit=0.6)
        )
        assert srt == pytest.approx(one.srt, rel=1e-13)


@pytest.mark.parametrize("model", ["3d", "2d"])
def test_a_rows_answer_does_not_depend_on_the_rows_solved_with_it(model):
    """evaluate_arrays solves large batches in blocks: any block size gives the same answers (a converged row stops
    where it would alone, so to rounding, far below the fixed-point tolerance of 1e-10), the same refusals, and the
    same bits for the same request (the blocks are fixed by the rows' order)."""
    rng = np.random.default_rng(3)
    arrays = {
        "bank_percent": rng.uniform(-10, 14, 60),
        "lateral_offset_m": np.r_[rng.uniform(-0.2, 0.2, 59), 1.0],  # the last row is refused (outside the track)
    }
    if model == "3d":
        arrays["slope_percent"] = rng.uniform(-9, 9, 60)
    case = Case(BTRAIN, model=model)
    whole = evaluate_arrays(case, arrays, batch_rows=1000)
    assert set(whole[2]) == {59} and np.isfinite(whole[0][:59]).all()
    for rows in (1, 7, 16):
        srt, roll, errors = evaluate_arrays(case, arrays, batch_rows=rows)
        assert errors == whole[2]
        np.testing.assert_allclose(srt, whole[0], rtol=0, atol=1e-14)
        np.testing.assert_allclose(roll, whole[1], rtol=0, atol=1e-12)
        again = evaluate_arrays(case, arrays, batch_rows=rows)
        assert again[0].tobytes() == srt.tobytes()


@pytest.mark.parametrize("model", ["3d", "2d"])
def test_blocks_run_on_threads_give_the_same_bits(model):
    """``block_map``: the blocks solved on a thread pool (in any order it finishes them) give the bits, refusals and
    row order of the blocks solved one after another; each block is solved exactly once."""
    rng = np.random.default_rng(5)
    arrays = {"bank_percent": rng.uniform(-10, 14, 90), "lateral_offset_m": np.r_[rng.uniform(-0.2, 0.2, 89), 1.0]}
    case = Case(BTRAIN, model=model)
    serial = evaluate_arrays(case, arrays, batch_rows=8)
    seen: list[int] = []

    def pool_map(function, blocks):
        blocks = list(blocks)
        seen.extend(len(b) for b in blocks)
        with ThreadPoolExecutor(4) as pool:
            return list(pool.map(function, blocks))

    threaded = evaluate_arrays(case, arrays, batch_rows=8, block_map=pool_map)
    assert sorted(seen) == sorted([8] * 11 + [1])  # 89 rows solved (the refused one is not), in blocks of 8
    assert threaded[0].tobytes() == serial[0].tobytes() and threaded[1].tobytes() == serial[1].tobytes()
    assert threaded[2] == serial[2] == {89: serial[2][89]}
    if model == "3d":  # sweep hands its blocks (of BATCH_ROWS rows) to the same block_map
        seen.clear()
        grid = {"bank_percent": np.linspace(-8, 12, BATCH_ROWS + 1)}
        assert sweep(case, grid, block_map=pool_map).srt.tobytes() == sweep(case, grid).srt.tobytes()
        assert seen == [BATCH_ROWS, 1]


def test_load_grid_like_table19_and_the_2d_and_closed_form_models():
    grid = {"lateral_offset_m": [-0.08, 0.0, 0.08], "longitudinal_offset_m": [-1.0, 0.5], "vertical_offset_m": [0.1]}
    for model in ("3d", "2d"):  # the batched array path against the one-case scalar path
        res = sweep(Case(BTRAIN, model=model), grid)
        assert not res.errors
        for (d1, d2, d3), srt in zip(res.values, res.srt, strict=True):
            one = rollover_threshold(
                Case(BTRAIN, model, load=LoadCase(lateral_offset_m=d1, longitudinal_offset_m=d2, vertical_offset_m=d3))
            )
            assert srt == pytest.approx(one.srt, rel=1e-13)


def test_stage_and_overweight_axes():
    res = sweep(Case(BTRAIN, stage="tires-suspension"), {"overweight_percent": [0, 5, 10]})
    assert res.stage == "tires-suspension"
    assert np.all(np.diff(res.srt) < 0)
    assert res.srt[0] == pytest.approx(rollover_threshold(Case(BTRAIN, stage="tires-suspension")).srt, rel=1e-9)


def test_unknown_axis_is_refused():
    from engine.errors import InvalidInput

    with pytest.raises(InvalidInput, match="wind_speed"):
        sweep(Case(BTRAIN), {"wind_speed": [1, 2]})
