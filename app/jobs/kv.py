"""The key-value layer under the job store: Redis (shared by the API and the workers) or process memory (embedded).

Both hold bytes under string keys with an expiry, an atomic read-modify-write (:meth:`KV.update`) and a set of the
active job ids. Nothing here trusts or interprets a value: the job store seals what it writes and verifies what it
reads (:func:`app.compute.cache.seal` / :func:`app.compute.cache.unseal`).

:class:`MemoryKV` bounds the total bytes it holds (``max_bytes``): a write past the bound raises :class:`StorageFull`
(the job store turns it into a refused submission or a failed part). Expired entries are dropped when read and by
:meth:`MemoryKV.purge`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable
from typing import Protocol

#: every job key starts with this (the cache's keys start with ``rollover:`` + the engine version)
PREFIX = "rollover:job:"
ACTIVE_SET = "rollover:jobs:active"
#: a Redis call of the job store may move a result fragment of several MB: its own, longer timeout [s]
REDIS_TIMEOUT_S = 30.0


class StorageFull(Exception):
    """The embedded store would exceed its byte bound (ROLLOVER_JOBS_MAX_BYTES)."""


class KV(Protocol):
    def get(self, key: str) -> bytes | None: ...
    def head(self, key: str, length: int) -> bytes | None: ...
    def mget(self, keys: list[str]) -> list[bytes | None]: ...
    def set(self, key: str, value: bytes, ttl_s: int) -> None: ...
    def set_many(self, items: dict[str, bytes], ttl_s: int) -> None: ...
    def exists(self, keys: list[str]) -> int: ...
    def delete(self, keys: Iterable[str]) -> None: ...
    def expire(self, keys: Iterable[str], ttl_s: int) -> None: ...
    def update(self, key: str, fn: Callable[[bytes | None], bytes | None], ttl_s: int) -> bytes | None: ...
    def add_active(self, job_id: str) -> None: ...
    def remove_active(self, job_id: str) -> None: ...
    def active(self) -> list[str]: ...
    def close(self) -> None: ...


class MemoryKV:
    """Process memory, bounded by the total bytes of the values, with expiries; thread-safe."""

    def __init__(self, max_bytes: int) -> None:
        self.max_bytes = max_bytes
        self._data: dict[str, tuple[bytes, float]] = {}
        self._bytes = 0
        self._active: set[str] = set()
        self._lock = threading.RLock()

    @property
    def used_bytes(self) -> int:
        return self._bytes

    def _live(self, key: str, now: float) -> bytes | None:
        item = self._data.get(key)
        if item is None:
            return None
        if item[1] <= now:
            self._drop(key)
            return None
        return item[0]

    def _drop(self, key: str) -> None:
        item = self._data.pop(key, None)
        if item is not None:
            self._bytes -= len(item[0])

    def _put(self, key: str, value: bytes, ttl_s: int, now: float) -> None:
        old = self._data.get(key)
        grow = len(value) - (len(old[0]) if old else 0)
        if grow > 0 and self._bytes + grow > self.max_bytes:
            self.purge()
            if self._bytes + grow > self.max_bytes:
                raise StorageFull(
                    f"the embedded job store holds {self._bytes} bytes; {len(value)} more would exceed "
                    f"ROLLOVER_JOBS_MAX_BYTES ({self.max_bytes})"
                )
        self._drop(key)
        self._data[key] = (value, now + ttl_s)
        self._bytes += len(value)

    def get(self, key: str) -> bytes | None:
        with self._lock:
            return self._live(key, time.time())

    def head(self, key: str, length: int) -> bytes | None:
        """The value's first ``length`` bytes (all of a shorter one); None when absent."""
        value = self.get(key)
        return None if value is None else value[:length]

    def mget(self, keys: list[str]) -> list[bytes | None]:
        with self._lock:
            now = time.time()
            return [self._live(k, now) for k in keys]

    def set(self, key: str, value: bytes, ttl_s: int) -> None:
        with self._lock:
            self._put(key, value, ttl_s, time.time())

    def set_many(self, items: dict[str, bytes], ttl_s: int) -> None:
        with self._lock:
            now = time.time()
            grow = sum(len(v) for v in items.values())
            if self._bytes + grow > self.max_bytes:
                self.purge()
                if self._bytes + grow > self.max_bytes:
                    raise StorageFull(
                        f"the embedded job store holds {self._bytes} bytes; {grow} more would exceed "
                        f"ROLLOVER_JOBS_MAX_BYTES ({self.max_bytes})"
                    )
            for k, v in items.items():
                self._put(k, v, ttl_s, now)

    def exists(self, keys: list[str]) -> int:
        with self._lock:
            now = time.time()
            return sum(self._live(k, now) is not None for k in keys)

    def delete(self, keys: Iterable[str]) -> None:
        with self._lock:
            for k in keys:
                self._drop(k)

    def expire(self, keys: Iterable[str], ttl_s: int) -> None:
        with self._lock:
            now = time.time()
            for k in keys:
                value = self._live(k, now)
                if value is not None:
                    self._data[k] = (value, now + ttl_s)

    def update(self, key: str, fn: Callable[[bytes | None], bytes | None], ttl_s: int) -> bytes | None:
        with self._lock:
            now = time.time()
            old = self._live(key, now)
            new = fn(old)
            if new is None:
                return old
            self._put(key, new, ttl_s, now)
            return new

    def add_active(self, job_id: str) -> None:
        with self._lock:
            self._active.add(job_id)

    def remove_active(self, job_id: str) -> None:
        with self._lock:
            self._active.discard(job_id)

    def active(self) -> list[str]:
        with self._lock:
            return sorted(self._active)

    def purge(self) -> None:
        """Drop every expired entry (and forget active jobs whose record has expired)."""
        with self._lock:
            now = time.time()
            for k in [k for k, (_, exp) in self._data.items() if exp <= now]:
                self._drop(k)
            self._active = {j for j in self._active if PREFIX + j in self._data}

    def close(self) -> None:
        with self._lock:
            self._data.clear()
            self._bytes = 0
            self._active.clear()


class RedisKV:
    """A Redis database (redis-py, synchronous: the API calls it from worker threads, the workers directly)."""

    def __init__(self, url: str, client=None) -> None:
        import redis

        self.redis = client or redis.Redis.from_url(
            url, socket_timeout=REDIS_TIMEOUT_S, socket_connect_timeout=REDIS_TIMEOUT_S
        )

    def get(self, key: str) -> bytes | None:
        return self.redis.get(key)

    def head(self, key: str, length: int) -> bytes | None:
        """The value's first ``length`` bytes (GETRANGE: the rest does not cross the network); None when absent
        (GETRANGE answers an empty string for a missing key: EXISTS tells them apart)."""
        with self.redis.pipeline(transaction=False) as p:
            p.exists(key)
            p.getrange(key, 0, max(length, 1) - 1)
            found, value = p.execute()
        return value[:length] if found else None

    def mget(self, keys: list[str]) -> list[bytes | None]:
        return list(self.redis.mget(keys)) if keys else []

    def set(self, key: str, value: bytes, ttl_s: int) -> None:
        self.redis.set(key, value, ex=ttl_s)

    def set_many(self, items: dict[str, bytes], ttl_s: int) -> None:
        with self.redis.pipeline(transaction=False) as p:
            for k, v in items.items():
                p.set(k, v, ex=ttl_s)
            p.execute()

    def exists(self, keys: list[str]) -> int:
        return int(self.redis.exists(*keys)) if keys else 0

    def delete(self, keys: Iterable[str]) -> None:
        keys = list(keys)
        if keys:
            self.redis.delete(*keys)

    def expire(self, keys: Iterable[str], ttl_s: int) -> None:
        with self.redis.pipeline(transaction=False) as p:
            for k in keys:
                p.expire(k, ttl_s)
            p.execute()

    def update(self, key: str, fn: Callable[[bytes | None], bytes | None], ttl_s: int) -> bytes | None:
        from redis.exceptions import WatchError

        with self.redis.pipeline() as p:
            while True:
                try:
                    p.watch(key)
                    old = p.get(key)
                    new = fn(old)
                    if new is None:
                        p.unwatch()
                        return old
                    p.multi()
                    p.set(key, new, ex=ttl_s)
                    p.execute()
                    return new
                except WatchError:  # another process changed it in between: read it again
                    continue

    def add_active(self, job_id: str) -> None:
        self.redis.sadd(ACTIVE_SET, job_id)

    def remove_active(self, job_id: str) -> None:
        self.redis.srem(ACTIVE_SET, job_id)

    def active(self) -> list[str]:
        out = []
        for j in self.redis.smembers(ACTIVE_SET):
            try:
                out.append(j.decode("ascii"))
            except (UnicodeDecodeError, AttributeError):
                self.redis.srem(ACTIVE_SET, j)  # not an id this service wrote
        return sorted(out)

    def close(self) -> None:
        self.redis.close()
