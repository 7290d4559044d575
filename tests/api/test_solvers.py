"""app.compute.solvers: the threads that run a large batch's blocks (ROLLOVER_SOLVE_THREADS)."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from pydantic import ValidationError

from app.compute import solvers
from app.settings import Settings
from engine.case import Case
from engine.models.threshold import BATCH_ROWS
from engine.road.curves import solve_bank_grade_pairs
from engine.vehicle.presets import PRESETS

from .conftest import make_client


@pytest.fixture(autouse=True)
def _restore():
    yield
    solvers.configure(solvers.default_threads())


def _where(threads: int) -> set[str]:
    solvers.configure(threads)
    return set(solvers.block_map(lambda _: threading.current_thread().name, range(8)))


def test_blocks_run_on_the_solver_threads_or_in_the_caller():
    assert all(name.startswith("rollover-solve") for name in _where(3))
    assert len(_where(3)) <= 3
    assert _where(1) == {threading.current_thread().name}  # one thread: block after block, no pool


def test_the_app_sets_the_threads_from_its_settings():
    with make_client(Settings(cache_backend="memory", solve_threads=3)):
        assert solvers._threads == 3
    with make_client(Settings(cache_backend="memory", solve_threads=1)):
        assert solvers._threads == 1


def test_the_setting_is_bounded():
    assert 1 <= Settings().solve_threads <= 4
    for bad in (0, 65):
        with pytest.raises(ValidationError, match="solve_threads"):
            Settings(solve_threads=bad)


def test_pairs_solved_on_threads_are_the_pairs_solved_alone():
    """Two blocks of pairs (one is refused: outside the bank bound) on three threads: the same bits and refusals."""
    rng = np.random.default_rng(11)
    pairs = np.stack([rng.uniform(0, 10, BATCH_ROWS + 50), rng.uniform(-8, 8, BATCH_ROWS + 50)], axis=1)
    pairs[7, 0] = 99.0
    case = Case(PRESETS["table16-btrain"])
    solvers.configure(3)
    srt, errors = solve_bank_grade_pairs(case, pairs, block_map=solvers.block_map)
    alone, alone_errors = solve_bank_grade_pairs(case, pairs)
    assert srt.tobytes() == alone.tobytes()
    assert errors == alone_errors and list(errors) == [7]


def test_free_memory_is_given_back_after_a_threaded_batch(monkeypatch):
    """After the blocks of a threaded batch (not after a batch solved in the caller), the arenas are trimmed once,
    when every block is done; glibc's malloc_trim is found on this (Linux, glibc) machine."""
    assert solvers._malloc_trim() is not None
    calls: list[tuple[int, int]] = []
    done: list[int] = []
    monkeypatch.setattr(solvers, "_TRIM", lambda pad: calls.append((pad, len(done))) or 1)
    solvers.configure(2)
    assert list(solvers.block_map(done.append, range(5))) == [None] * 5
    assert calls == [(0, 5)]
    solvers.configure(1)
    list(solvers.block_map(done.append, range(5)))
    assert calls == [(0, 5)]
