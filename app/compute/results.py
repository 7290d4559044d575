"""What a computation answers: a whole body (:class:`Computed`) or a stream of one (:class:`Streamed`), and
:func:`cached`, the cache-or-compute step every computed endpoint goes through.

A computed answer is keyed by :func:`app.compute.cache.cache_key` of its fully resolved request; the key is its
``ETag``. A small answer is a body kept as bytes in the result cache (and so served again by the raw-body fast path,
:mod:`app.http.fastpath`); a large batch answer is streamed, rendered in chunks from arrays kept by reference.
Streamed or whole, the bytes are the same.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Iterator
from dataclasses import dataclass
from typing import Any

from app.compute.cache import ResultCache, cache_key
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


async def _lookup(cache: ResultCache, operation: str, key: str) -> bytes | None:
    lookup = await cache.get(key)
    CACHE_LOOKUPS.labels(operation, lookup.tier or "miss").inc()
    return lookup.value


async def cached(
    cache: ResultCache,
    operation: str,
    resolved: dict[str, Any] | Resolved,
    produce: Callable[[], Awaitable[bytes]],
    media_type: str = "application/json",
) -> Computed:
    """The body for ``resolved`` (a resolved request's dict, or a typed one: :mod:`app.compute.resolved`) from the
    cache, or from ``produce()`` (then stored under the same key)."""
    key = resolved.key(operation) if isinstance(resolved, Resolved) else cache_key(operation, resolved)
    body = await _lookup(cache, operation, key)
    if body is not None:
        return Computed(body, key, True, media_type)
    body = await produce()
    await cache.set(key, body, media_type)
    return Computed(body, key, False, media_type)


@dataclass(frozen=True)
class Streamed:
    """A large answer: its chunks, the key it would have, and its media type (sent as a streamed response)."""

    chunks: Iterator[bytes]
    key: str
    hit: bool
    media_type: str

    @property
    def etag(self) -> str:
        return f'"{self.key}"'
