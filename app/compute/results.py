"""What a computation answers (:class:`Computed`: a whole body) and :func:`cached`, the cache-or-compute step every
computed endpoint goes through.

A computed answer is keyed by :func:`app.compute.cache.cache_key` of its fully resolved request; the key is its
``ETag``. The body is kept as bytes in the result cache (and so served again by the raw-body fast path,
:mod:`app.http.fastpath`). Every synchronous answer is small enough to be built whole (at most 10,000 rows:
``app.alignments.schemas.MAX_ROWS``, ``app.srt.sweep_schemas.MAX_CASES``); larger work goes to a job, whose result
is streamed from its parts (:mod:`app.jobs`).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from app.compute.cache import ResultCache
from app.compute.resolved import Resolved
from app.metrics import CACHE_LOOKUPS


@dataclass(frozen=True)
class Computed:
    """A response body with its cache key, whether it came from the cache, and its media type."""

    body: bytes
    key: str
    hit: bool
    media_type: str = "application/json"

    @property
    def etag(self) -> str:
        return f'"{self.key}"'


async def _lookup(cache: ResultCache, operation: str, key: str, media_type: str) -> bytes | None:
    lookup = await cache.get(key, media_type)
    CACHE_LOOKUPS.labels(operation, lookup.tier or "miss").inc()
    return lookup.value


async def cached(
    cache: ResultCache,
    operation: str,
    resolved: Resolved,
    produce: Callable[[], Awaitable[bytes]],
    media_type: str = "application/json",
) -> Computed:
    """The body for ``resolved`` (a typed resolved request: :mod:`app.compute.resolved`) from the cache, or from
    ``produce()`` (then stored under the same key: :meth:`~app.compute.resolved.Resolved.key`)."""
    key = resolved.key(operation)
    body = await _lookup(cache, operation, key, media_type)
    if body is not None:
        return Computed(body, key, True, media_type)
    body = await produce()
    await cache.set(key, body, media_type)
    return Computed(body, key, False, media_type)
