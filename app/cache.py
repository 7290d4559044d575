"""Result cache: an in-process LRU, optionally in front of a shared Redis.

Keys are ``<engine version>:<operation>:<sha256 of the canonical JSON of the resolved request>``
(:func:`cache_key`): the preset expanded to its full record, every default filled, keys sorted by orjson's
``OPT_SORT_KEYS``. Values are the JSON bytes of the response body, the same bytes in both tiers (never
pickle), so a hit returns exactly what the miss returned.

Redis is optional at run time: when a call fails (connection refused, timeout, any ``RedisError``) the
cache logs ``redis_unavailable`` once, answers from the local LRU (and the caller computes), and does not
try Redis again for ``redis_retry_seconds``; the first call that succeeds afterwards logs ``redis_recovered``.

The in-process LRU is bounded by entries and by total bytes; a body larger than ``cache_max_entry_bytes`` is not
cached in either tier (it is computed again on the next request and answered with ``X-Cache: miss``).
"""

from __future__ import annotations

import hashlib
import math
import time
from dataclasses import dataclass
from typing import Any

import orjson
from cachetools import LRUCache

from engine import ENGINE_VERSION

from .logs import get_logger
from .metrics import REDIS_FAILURES

REDIS_PREFIX = "rollover:"


def _normalise(value: Any) -> Any:
    """-0.0 -> 0.0 so that two equal requests cannot differ only in the sign of a zero."""
    if isinstance(value, float):
        return value + 0.0 if math.isfinite(value) else value
    if isinstance(value, dict):
        return {k: _normalise(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_normalise(v) for v in value]
    return value


def canonical_json(resolved: dict[str, Any]) -> bytes:
    return orjson.dumps(_normalise(resolved), option=orjson.OPT_SORT_KEYS)


def cache_key(operation: str, resolved: dict[str, Any]) -> str:
    """``<engine version>:<operation>:<sha256 hex>`` of the canonical JSON of the resolved request."""
    digest = hashlib.sha256(canonical_json({"engine_version": ENGINE_VERSION, "op": operation, **resolved}))
    return f"{ENGINE_VERSION}:{operation}:{digest.hexdigest()}"


class SizedLRU(LRUCache):
    """An LRU bounded both by its number of entries and by the total bytes of its values (a batch answer of
    100,000 curve rows is tens of MB: an entry bound alone would let a few thousand of them exhaust memory)."""

    def __init__(self, max_entries: int, max_bytes: int) -> None:
        super().__init__(maxsize=max_bytes, getsizeof=len)
        self.max_entries = max_entries

    def __setitem__(self, key: str, value: bytes) -> None:
        if key not in self:
            while len(self) >= self.max_entries:
                self.popitem()
        super().__setitem__(key, value)


@dataclass(frozen=True)
class Lookup:
    value: bytes | None
    tier: str | None  # "local", "redis" or None (miss)


class ResultCache:
    """Two-tier cache of response bodies (JSON bytes)."""

    def __init__(
        self,
        max_entries: int,
        redis: Any | None = None,
        *,
        ttl_seconds: int = 0,
        retry_seconds: float = 15.0,
        max_bytes: int = 512 * 2**20,
        max_entry_bytes: int = 32 * 2**20,
    ) -> None:
        self.local: SizedLRU = SizedLRU(max_entries, max_bytes)
        self.max_entry_bytes = min(max_entry_bytes, max_bytes)
        self.redis = redis
        self.ttl_seconds = ttl_seconds
        self.retry_seconds = retry_seconds
        self._down_until = 0.0
        self._down = False
        self._log = get_logger("rollover.cache")

    @property
    def backend(self) -> str:
        return "redis" if self.redis is not None else "memory"

    @property
    def redis_available(self) -> bool | None:
        """None without Redis; False while the last call failed (and the retry delay runs)."""
        return None if self.redis is None else not self._down

    # ---------------------------------------------------------------------------------- redis guard
    def _redis_usable(self) -> bool:
        return self.redis is not None and time.monotonic() >= self._down_until

    def _redis_failed(self, exc: BaseException) -> None:
        REDIS_FAILURES.inc()
        self._down_until = time.monotonic() + self.retry_seconds
        if not self._down:
            self._down = True
            self._log.warning(
                "redis_unavailable",
                error=f"{type(exc).__name__}: {exc}",
                action="serving from the in-process cache and computing; Redis is retried later",
                retry_seconds=self.retry_seconds,
            )

    def _redis_ok(self) -> None:
        if self._down:
            self._down = False
            self._log.info("redis_recovered")

    # ---------------------------------------------------------------------------------------- API
    async def get(self, key: str) -> Lookup:
        value = self.local.get(key)
        if value is not None:
            return Lookup(value, "local")
        if self._redis_usable():
            try:
                value = await self.redis.get(REDIS_PREFIX + key)
            except Exception as exc:  # any client/transport error: go on without Redis
                self._redis_failed(exc)
            else:
                self._redis_ok()
                if value is not None:
                    self.local[key] = value
                    return Lookup(value, "redis")
        return Lookup(None, None)

    async def set(self, key: str, value: bytes) -> None:
        if len(value) > self.max_entry_bytes:  # too big to keep: computed again on the next request
            return
        self.local[key] = value
        if self._redis_usable():
            try:
                await self.redis.set(REDIS_PREFIX + key, value, ex=self.ttl_seconds or None)
            except Exception as exc:
                self._redis_failed(exc)
            else:
                self._redis_ok()

    async def ping(self) -> bool | None:
        """Health probe of the shared tier: None without Redis, else whether it answers."""
        if self.redis is None:
            return None
        try:
            await self.redis.ping()
        except Exception as exc:
            self._redis_failed(exc)
            return False
        self._redis_ok()
        self._down_until = 0.0
        return True

    async def aclose(self) -> None:
        if self.redis is not None:
            await self.redis.aclose()


def make_cache(settings) -> ResultCache:
    """The cache the settings ask for; the Redis client is created here and closed in the lifespan."""
    redis = None
    if settings.cache_backend == "redis":
        import redis.asyncio as aioredis
        from redis.asyncio.retry import Retry
        from redis.backoff import NoBackoff

        # no client-side retries: a cache that is down must cost one timeout, not a backoff schedule
        redis = aioredis.Redis.from_url(
            settings.redis_url,
            socket_timeout=settings.redis_timeout_seconds,
            socket_connect_timeout=settings.redis_timeout_seconds,
            retry=Retry(NoBackoff(), 0),
        )
    return ResultCache(
        settings.cache_max_entries,
        redis,
        ttl_seconds=settings.redis_ttl_seconds,
        retry_seconds=settings.redis_retry_seconds,
        max_bytes=settings.cache_max_bytes,
        max_entry_bytes=settings.cache_max_entry_bytes,
    )
