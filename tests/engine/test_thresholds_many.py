"""rollover_thresholds: many one-threshold cases handed over together give each case's rollover_threshold answer."""

from __future__ import annotations

import math

import numpy as np

from engine.case import Case, LoadCase, Road
from engine.errors import RolloverError
from engine.models.threshold import MIN_ARRAY_CASES, rollover_threshold, rollover_thresholds
from engine.vehicle.presets import PRESETS
from tests.compare import assert_same_to_rounding

BTRAIN = PRESETS["table16-btrain"]


def _alone(case: Case):
    try:
        return rollover_threshold(case)
    except RolloverError as exc:
        return exc


def _mixed_cases() -> list[Case]:
    rng = np.random.default_rng(11)
    cases = []
    for preset, stage in (("table16-btrain", "full"), ("table15-semitrailer", "full"), ("table16-btrain", None)):
        for _ in range(MIN_ARRAY_CASES + 4):
            case = Case(
                PRESETS[preset],
                road=Road(bank_percent=float(rng.uniform(-10, 10)), slope_percent=float(rng.uniform(-8, 8))),
                trailer_angle_deg=float(rng.uniform(-20, 20)),
                load=LoadCase(
                    lateral_offset_m=float(rng.uniform(-0.2, 0.2)), overweight_percent=float(rng.uniform(0, 20))
                ),
                rear_llt_limit=float(rng.choice([1.0, 0.6])),
            )
            cases.append(case if stage else case.replace(stage="tires-suspension"))
    cases += [
        Case(BTRAIN, road=Road(bank_percent=-60.0)),  # refused before solving (outside the bank's bounds)
        Case(BTRAIN, road=Road(bank_percent=-14.0), load=LoadCase(lateral_offset_m=0.5)),  # tips at rest
        Case(BTRAIN, model="2d"),
        Case(PRESETS["table14-semitrailer"], model="2d"),
        Case(BTRAIN, model="rigid-bank", road=Road(bank_percent=3.0)),
        Case(BTRAIN, stage="nonsense"),
    ]
    return cases


def test_each_case_gets_the_answer_it_gets_alone_results_and_errors():
    cases = _mixed_cases()
    many = rollover_thresholds(cases)
    assert len(many) == len(cases)
    errors = 0
    for case, got in zip(cases, many, strict=True):
        alone = _alone(case)
        if isinstance(alone, RolloverError):
            errors += 1
            assert type(got) is type(alone) and str(got) == str(alone) and got.field == alone.field
        else:
            # the SRT, the state at the limit, the stage values, the iteration count, the notes
            assert_same_to_rounding(got.to_dict(), alone.to_dict())
    assert errors >= 3  # the refused bank, the tip at rest and the unknown stage at least


def test_the_3d_groups_are_solved_on_arrays_and_a_case_does_not_depend_on_its_companions(monkeypatch):
    import engine.models.threshold as threshold

    calls = []
    real = threshold.solve_3d_many
    monkeypatch.setattr(threshold, "solve_3d_many", lambda cases, *a: calls.append(len(cases)) or real(cases, *a))
    banks = np.linspace(-6, 10, 2 * MIN_ARRAY_CASES)
    cases = [Case(BTRAIN, road=Road(bank_percent=float(b))) for b in banks]
    whole = rollover_thresholds(cases)
    half = rollover_thresholds(cases[::2])
    assert calls == [2 * MIN_ARRAY_CASES, MIN_ARRAY_CASES]  # both on arrays
    for a, b in zip(whole[::2], half, strict=True):
        assert_same_to_rounding(a.to_dict(), b.to_dict())
    few = rollover_thresholds(cases[: MIN_ARRAY_CASES - 1])  # below the threshold: one at a time
    assert len(calls) == 2 and [r.srt for r in few] == [rollover_threshold(c).srt for c in cases[: MIN_ARRAY_CASES - 1]]
    assert all(math.isfinite(r.srt) and r.iterations >= 2 for r in whole)


def test_no_case_and_one_case():
    assert rollover_thresholds([]) == []
    (one,) = rollover_thresholds([Case(BTRAIN)])
    assert one == rollover_threshold(Case(BTRAIN))
