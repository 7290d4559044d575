"""Concurrent one-threshold solves handed to the engine together.

An uncached ``POST /v1/srt`` (and the SRT behind curve-speed, min-radius and the min-radius plot) is one call of
:func:`engine.models.rollover_threshold`, about a millisecond on the event loop. When many arrive at once (a
client firing a batch, a page loading a fleet) they wait on the loop at the same moment; this module hands them to
:func:`engine.models.rollover_thresholds` as one list, which solves the 3D cases of one vehicle and stage together
on numpy arrays when there are enough of them (:data:`engine.models.MIN_ARRAY_CASES`): 32 cases in about half the
time of 32 solves one by one, 64 in about a third (``python bench/bench_engine.py``). A case's result does not
depend on the cases solved with it (a converged case stops where it would alone; tests/api/test_coalesce.py), so an
answer is the same whether its request came alone or in a crowd.

How: the first waiting solve schedules a flush (``loop.call_soon``) and waits on a future; the flush runs once
:data:`QUIET_TURNS` loop turns pass without a new waiting solve, so every solve that arrives meanwhile (the requests
the server read in the same turns) joins it. One waiting solve is solved exactly as before. A flush takes at most
:data:`MAX_FLUSH` cases; the rest go to the next one, so other requests (``/healthz``) get the loop between flushes.
Waiting on the future is also the request's turn for the other connections (without such a turn a saturated worker
stopped answering in arrival order: at 32 connections its p99 was over a second in bench/bench_service.py's uncached
row, where it is now a few tens of milliseconds).
"""

from __future__ import annotations

import asyncio
import time
import weakref

from app.metrics import SOLVE_BATCH_CASES, SOLVE_SECONDS
from engine import Case, RolloverResult
from engine.models import rollover_thresholds

#: loop turns without a new waiting solve before a flush: a request read in one turn reaches this point in the next
QUIET_TURNS = 2

#: most cases one flush solves (about 40-80 ms of event loop at most); the rest wait for the next flush
MAX_FLUSH = 64

_Pending = list[tuple[Case, asyncio.Future]]


class SolveCoalescer:
    """Gathers the threshold solves waiting on one event loop and solves them in one engine call."""

    def __init__(self) -> None:
        # per loop: a test session (or a server with threads running loops) may use more than one
        self._pending: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, _Pending] = weakref.WeakKeyDictionary()

    async def threshold(self, case: Case) -> RolloverResult:
        """``rollover_threshold(case)`` (its result, or the error it raises), solved with the others waiting."""
        loop = asyncio.get_running_loop()
        future: asyncio.Future = loop.create_future()
        pending = self._pending.setdefault(loop, [])
        pending.append((case, future))
        if len(pending) == 1:
            loop.call_soon(self._flush, loop, 1, 0)
        return await future

    def _flush(self, loop: asyncio.AbstractEventLoop, seen: int, quiet: int) -> None:
        pending = self._pending.get(loop, [])
        if len(pending) < MAX_FLUSH and quiet < QUIET_TURNS:  # others may be on their way: a turn more
            loop.call_soon(self._flush, loop, len(pending), 0 if len(pending) > seen else quiet + 1)
            return
        batch, rest = pending[:MAX_FLUSH], pending[MAX_FLUSH:]
        self._pending[loop] = rest
        if rest:
            loop.call_soon(self._flush, loop, len(rest), 0)
        live = [(case, future) for case, future in batch if not future.done()]  # a client that left: not solved
        if not live:
            return
        started = time.perf_counter()
        try:
            results: list = rollover_thresholds([case for case, _ in live])
        except Exception:  # a defect, not a refused case: solved one by one, it fails only the request that has it
            results = [_alone(case) for case, _ in live]
        share = (time.perf_counter() - started) / len(live)
        SOLVE_BATCH_CASES.observe(len(live))
        for (case, future), result in zip(live, results, strict=True):
            SOLVE_SECONDS.labels("srt", case.model).observe(share)
            if isinstance(result, BaseException):
                future.set_exception(result)
            else:
                future.set_result(result)


def _alone(case: Case) -> RolloverResult | Exception:
    try:
        return rollover_thresholds([case])[0]
    except Exception as exc:  # the defect itself: this request's 500; none waits forever
        return exc


#: the process's coalescer (the app layer's; the engine keeps no state)
COALESCER = SolveCoalescer()
