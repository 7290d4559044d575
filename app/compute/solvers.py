"""The threads that solve the blocks of one large batch in parallel (``ROLLOVER_SOLVE_THREADS``).

The engine's batch solve (:func:`engine.models.evaluate_arrays`) cuts a large batch into blocks of
:data:`engine.models.BATCH_ROWS` rows and runs them through the ``block_map`` it is given. It spends its time in
numpy, which releases the GIL on arrays this large, so blocks run in threads really run in parallel: a
100,000-curve alignment's solve takes about half as long on two cores (``bench/bench_engine.py``). The blocks are the
same whichever runs them, so the answer is bit for bit the one solved block after block.

One pool per process, shared by every request, route and job of the process: a burst of large batches queues here
for the cores instead of each taking its own threads. Set by :func:`configure` when the app starts.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import threading
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

_lock = threading.Lock()
_pool: ThreadPoolExecutor | None = None
_threads = 1


def _malloc_trim() -> Callable[[int], int] | None:
    """glibc's ``malloc_trim`` (None elsewhere, e.g. musl): gives the free memory of every malloc arena back."""
    try:
        return ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").malloc_trim
    except (OSError, AttributeError):
        return None


_TRIM = _malloc_trim()


def default_threads() -> int:
    """The cores this process may run on, at most 4 (a block is ~16,000 rows: more threads rarely have work)."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(4, cores))


def configure(threads: int) -> None:
    """Solve with ``threads`` threads from now on (1: block after block in the calling thread)."""
    global _pool, _threads
    with _lock:
        if threads == _threads:
            return
        old, _pool, _threads = _pool, None, threads
    if old is not None:
        old.shutdown(wait=False)


def _executor() -> ThreadPoolExecutor | None:
    global _pool
    with _lock:
        if _pool is None and _threads > 1:
            _pool = ThreadPoolExecutor(max_workers=_threads, thread_name_prefix="rollover-solve")
        return _pool


def block_map(function: Callable[[Any], Any], blocks: Iterable[Any]) -> Iterator[Any]:
    """``map(function, blocks)`` on the solver threads (:data:`engine.models.BlockMap`): results in the blocks'
    order. Never called from a solver thread itself (a block does not solve batches), so it cannot wait on itself.

    Each thread allocates its blocks' temporaries in a malloc arena of its own, and glibc keeps what they free: a
    100,000-curve alignment left the process ~70 MB larger with two threads than with one. So the arenas' free memory
    is given back once the blocks are done (``malloc_trim``, a few milliseconds)."""
    pool = _executor()
    if pool is None:
        return map(function, blocks)
    results = list(pool.map(function, blocks))
    if _TRIM is not None:
        _TRIM(0)
    return iter(results)


__all__ = ["block_map", "configure", "default_threads"]
