"""Grids of cases (Tables 17 and 19) in one call equal the same cases solved one at a time."""

from __future__ import annotations

import numpy as np
import pytest

from engine.case import Case
from engine.loads import LoadCase, Road
from engine.threshold import rollover_threshold, sweep
from engine.vehicles import PRESETS

BTRAIN = PRESETS["table16-btrain"]


def test_3d_sweep_equals_single_solves_in_cartesian_order():
    grid = {"trailer_angle_deg": [0, 30], "bank_percent": [0, 6], "slope_percent": [4, -8]}
    res = sweep(Case(BTRAIN, rear_llt_limit=0.6), grid)
    assert res.values.shape == (8, 3)
    for (psi, bank, slope), srt in zip(res.values, res.srt, strict=True):
        one = rollover_threshold(
            Case(BTRAIN, road=Road(bank_percent=bank, slope_percent=slope), trailer_angle_deg=psi, rear_llt_limit=0.6)
        )
        assert srt == pytest.approx(one.srt, rel=1e-9)


def test_load_grid_like_table19_and_the_2d_and_closed_form_models():
    grid = {"lateral_offset_m": [-0.08, 0.0, 0.08], "longitudinal_offset_m": [-1.0, 0.5], "vertical_offset_m": [0.1]}
    for model in ("3d", "2d"):  # the batched array path against the one-case scalar path
        res = sweep(Case(BTRAIN, model=model), grid)
        assert not res.errors
        for (d1, d2, d3), srt in zip(res.values, res.srt, strict=True):
            one = rollover_threshold(
                Case(BTRAIN, model, load=LoadCase(lateral_offset_m=d1, longitudinal_offset_m=d2, vertical_offset_m=d3))
            )
            assert srt == pytest.approx(one.srt, rel=1e-9)


def test_stage_and_overweight_axes():
    res = sweep(Case(BTRAIN, stage="tires-suspension"), {"overweight_percent": [0, 5, 10]})
    assert res.stage == "tires-suspension"
    assert np.all(np.diff(res.srt) < 0)
    assert res.srt[0] == pytest.approx(rollover_threshold(Case(BTRAIN, stage="tires-suspension")).srt, rel=1e-9)


def test_unknown_axis_is_refused():
    from engine.errors import InvalidInput

    with pytest.raises(InvalidInput, match="wind_speed"):
        sweep(Case(BTRAIN), {"wind_speed": [1, 2]})
