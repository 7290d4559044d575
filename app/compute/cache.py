"""Result cache: an in-process LRU, optionally in front of a shared Redis, and a memo of engine results.

Keys are ``<engine version>:<operation>:<sha256 of the canonical JSON of the resolved request>``
(:func:`cache_key`): the case's every input explicit, the preset expanded to its full record, keys sorted by
orjson's ``OPT_SORT_KEYS`` (the batch features' requests are typed, :mod:`app.compute.resolved`, and hash their
JSON form here). Values are the response bodies, the same bytes in both tiers (never pickle), so a hit
returns exactly what the miss returned.

**The shared tier is not trusted.** Whatever another process (or an attacker with access to Redis) left under a key
is served only if it proves to be ours and whole: each Redis value is an envelope ``ROLLOVER1`` + HMAC-SHA256 (with
the deployment's ``ROLLOVER_CACHE_SECRET``, over the key, the media type and the body) + the media type + the body
(:func:`seal` / :func:`unseal`). A value that fails the check, a key holding another Redis type, or a value of
another media type than the route answers, is a *bad entry*: logged once with its key (``cache_entry_rejected``),
deleted, recomputed and rewritten; it never switches Redis off and never reaches a client.

Redis is optional at run time: when a call fails (connection refused, timeout, any connection error) the cache logs
``redis_unavailable`` once, drops its pooled connections (they are stale), answers from the local LRU (and the caller
computes), and does not try Redis again for ``redis_retry_seconds``; the first call that succeeds afterwards logs
``redis_recovered``.

The in-process LRU is bounded by entries and by total bytes; a body larger than ``cache_max_entry_bytes`` is not
cached in either tier (it is computed again on the next request and answered with ``X-Cache: miss``).
"""

from __future__ import annotations

import asyncio
import contextlib
import hashlib
import hmac
import math
import time
from dataclasses import dataclass
from typing import Any

import orjson
from cachetools import LRUCache

from app.logs import get_logger
from app.metrics import CACHE_REJECTED, REDIS_FAILURES
from engine import ENGINE_VERSION

REDIS_PREFIX = "rollover:"
ENVELOPE_MAGIC = b"ROLLOVER1"
_MAC_SIZE = hashlib.sha256().digest_size
#: engine result objects memoised per process (a nested SRT, the curves of a plot)
MEMO_ENTRIES = 1024
#: keys already logged as bad: each is logged once (bounded, so a flood of bad keys cannot grow memory)
_LOGGED_BAD_KEYS = 10_000


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


# ----------------------------------------------------------------------------------- the envelope


def _mac(secret: bytes, key: str, media_type: str, body: bytes | memoryview) -> bytes:
    """HMAC-SHA256 over key NUL media type NUL body, fed in pieces (a job's result part is megabytes: not copied
    into one message first)."""
    mac = hmac.new(secret, key.encode(), hashlib.sha256)
    mac.update(b"\0" + media_type.encode() + b"\0")
    mac.update(body)
    return mac.digest()


def seal(secret: bytes, key: str, media_type: str, body: bytes) -> bytes:
    """The Redis value for a body: magic, HMAC-SHA256 over (key, media type, body), media type, NUL, body."""
    return ENVELOPE_MAGIC + _mac(secret, key, media_type, body) + media_type.encode() + b"\0" + body


def unseal(secret: bytes, key: str, value: Any) -> tuple[str, bytes] | None:
    """(media type, body) of a value this deployment wrote under ``key``; None for anything else (garbage, another
    key's value, a truncated or altered body, a value sealed with another secret)."""
    opened = _envelope(value)
    if opened is None:
        return None
    media_type, body = opened  # the body is checked in place and copied once
    mac = value[len(ENVELOPE_MAGIC) : len(ENVELOPE_MAGIC) + _MAC_SIZE]
    if not hmac.compare_digest(mac, _mac(secret, key, media_type, memoryview(value)[body:])):
        return None
    return media_type, value[body:]


def _envelope(value: Any) -> tuple[str, int] | None:
    """(media type, where the body starts) of an envelope or of its first bytes, unverified; None for anything that
    does not begin as an envelope."""
    if not isinstance(value, bytes) or not value.startswith(ENVELOPE_MAGIC):
        return None
    start = len(ENVELOPE_MAGIC) + _MAC_SIZE
    end = value.find(b"\0", start)
    if end < 0:
        return None
    try:
        return value[start:end].decode("ascii"), end + 1
    except UnicodeDecodeError:
        return None


def envelope_size(media_type: str) -> int:
    """The bytes an envelope of ``media_type`` puts before its body."""
    return len(ENVELOPE_MAGIC) + _MAC_SIZE + len(media_type.encode()) + 1


def peek(value: Any) -> tuple[str, bytes] | None:
    """(media type, the body's bytes present) of an envelope or of its first bytes, NOT verified: a look at a value
    whose body is verified (:func:`unseal`) when it is used; None for anything that does not begin as an envelope."""
    opened = _envelope(value)
    return None if opened is None else (opened[0], value[opened[1] :])


# ------------------------------------------------------------------------------------- the tiers


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
    """Two-tier cache of response bodies and the per-process memo of engine result objects (``objects``)."""

    def __init__(
        self,
        max_entries: int,
        redis: Any | None = None,
        *,
        secret: bytes = b"",
        ttl_seconds: int = 0,
        retry_seconds: float = 5.0,
        max_bytes: int = 512 * 2**20,
        max_entry_bytes: int = 32 * 2**20,
    ) -> None:
        self.local: SizedLRU = SizedLRU(max_entries, max_bytes)
        self.objects: LRUCache = LRUCache(maxsize=MEMO_ENTRIES)
        #: memo keys being solved now -> the task solving them, so concurrent requests that need the same engine
        #: result (every banked request of one vehicle needs its level-road case) wait for one solve
        self.solving: dict[str, asyncio.Future] = {}
        self.max_entry_bytes = min(max_entry_bytes, max_bytes)
        self.redis = redis
        self.secret = secret
        self.ttl_seconds = ttl_seconds
        self.retry_seconds = retry_seconds
        self._down_until = 0.0
        self._down = False
        self._logged_bad: LRUCache = LRUCache(maxsize=_LOGGED_BAD_KEYS)
        self._log = get_logger("rollover.cache")

    @property
    def backend(self) -> str:
        return "redis" if self.redis is not None else "memory"

    # ---------------------------------------------------------------------------------- redis guard
    def _redis_usable(self) -> bool:
        return self.redis is not None and time.monotonic() >= self._down_until

    async def _redis_failed(self, exc: BaseException) -> None:
        REDIS_FAILURES.inc()
        self._down_until = time.monotonic() + self.retry_seconds
        with contextlib.suppress(Exception):  # the pooled connections are stale: the next attempt opens fresh ones
            await self.redis.connection_pool.disconnect()
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

    async def _reject(self, key: str, reason: str) -> None:
        """A bad entry under ``key``: logged once, deleted (it is recomputed and rewritten by the caller)."""
        CACHE_REJECTED.inc()
        if key not in self._logged_bad:
            self._logged_bad[key] = True
            self._log.warning("cache_entry_rejected", key=REDIS_PREFIX + key, reason=reason)
        with contextlib.suppress(Exception):  # the rewrite after the computation replaces it anyway
            await self.redis.delete(REDIS_PREFIX + key)

    # ---------------------------------------------------------------------------------------- API
    async def get(self, key: str, media_type: str | None = None) -> Lookup:
        """The body cached under ``key`` (of ``media_type`` when given), or a miss."""
        value = self.local.get(key)
        if value is not None:
            return Lookup(value, "local")
        if not self._redis_usable():
            return Lookup(None, None)
        from redis.exceptions import ResponseError

        try:
            raw = await self.redis.get(REDIS_PREFIX + key)
        except ResponseError as exc:  # e.g. WRONGTYPE: the server is fine, the entry is not ours
            self._redis_ok()
            await self._reject(key, f"{type(exc).__name__}: {exc}")
            return Lookup(None, None)
        except Exception as exc:  # any client/transport error: go on without Redis
            await self._redis_failed(exc)
            return Lookup(None, None)
        self._redis_ok()
        if raw is None:
            return Lookup(None, None)
        opened = unseal(self.secret, key, raw)
        if opened is None:
            await self._reject(key, "not sealed by this deployment (bad envelope or HMAC)")
            return Lookup(None, None)
        stored_type, body = opened
        if media_type is not None and stored_type != media_type:
            await self._reject(key, f"media type {stored_type!r}, expected {media_type!r}")
            return Lookup(None, None)
        if len(body) <= self.max_entry_bytes:
            self.local[key] = body
        return Lookup(body, "redis")

    async def set(self, key: str, value: bytes, media_type: str = "application/json") -> None:
        if len(value) > self.max_entry_bytes:  # too big to keep: computed again on the next request
            return
        self.local[key] = value
        if self._redis_usable():
            try:
                await self.redis.set(
                    REDIS_PREFIX + key, seal(self.secret, key, media_type, value), ex=self.ttl_seconds or None
                )
            except Exception as exc:
                await self._redis_failed(exc)
            else:
                self._redis_ok()

    async def ping(self) -> bool | None:
        """Health probe of the shared tier: None without Redis, else whether it answers."""
        if self.redis is None:
            return None
        try:
            await self.redis.ping()
        except Exception as exc:
            await self._redis_failed(exc)
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
        secret=settings.cache_secret_bytes(),
        ttl_seconds=settings.redis_ttl_seconds,
        retry_seconds=settings.redis_retry_seconds,
        max_bytes=settings.cache_max_bytes,
        max_entry_bytes=settings.cache_max_entry_bytes,
    )
