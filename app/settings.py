"""Service settings (pydantic-settings), read from the environment with the ``ROLLOVER_`` prefix.

:func:`get_settings` reads the environment once per process; :func:`app.main.create_app` takes it, or a
:class:`Settings` given to it (tests), and keeps it on ``app.state``.
"""

from __future__ import annotations

import secrets
from functools import cached_property, lru_cache
from typing import Literal

from pydantic import Field, SecretStr, field_validator, model_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from app.compute.solvers import default_threads
from engine.road import DEFAULT_TARGETS

#: shortest bearer key accepted in ROLLOVER_API_KEYS [characters]
MIN_API_KEY_LENGTH = 16


def split_api_keys(text: str) -> list[str]:
    """``"a, b,,c"`` -> ``["a", "b", "c"]``."""
    return [k.strip() for k in text.split(",") if k.strip()]


class Settings(BaseSettings):
    # hide_input_in_errors: a refused setting (an API key, a database URL with its password) is never echoed
    model_config = SettingsConfigDict(env_prefix="ROLLOVER_", extra="ignore", hide_input_in_errors=True)

    cache_backend: Literal["memory", "redis"] = Field(
        "memory",
        description="memory: in-process LRU only (one worker). redis: in-process LRU in front of a shared Redis.",
    )
    cache_max_entries: int = Field(4096, ge=1, description="Size bound of the in-process LRU cache [entries].")
    cache_max_bytes: int = Field(
        512 * 2**20, ge=1, description="Size bound of the in-process LRU: total bytes of the cached bodies [bytes]."
    )
    cache_max_entry_bytes: int = Field(
        32 * 2**20, ge=1, description="Bodies larger than this are not cached in either tier [bytes]."
    )
    redis_url: str = Field("redis://127.0.0.1:6379/0", description="Redis URL (used when cache_backend=redis).")
    cache_secret: SecretStr | None = Field(
        None,
        min_length=16,
        description="Secret of the HMAC that seals every Redis entry (required with cache_backend=redis; the same on "
        "every replica; e.g. `openssl rand -hex 32`). An entry that does not verify is never served.",
    )
    redis_ttl_seconds: int = Field(
        7 * 24 * 3600, ge=0, description="Expiry of the entries written to Redis [s]; 0 keeps them until evicted."
    )
    redis_timeout_seconds: float = Field(
        0.25, gt=0, description="Connect and read timeout of each Redis call [s]; past it the call counts as down."
    )
    redis_retry_seconds: float = Field(
        5.0, ge=0, description="After a Redis failure, serve from the local cache without Redis for this long [s]."
    )
    log_level: Literal["DEBUG", "INFO", "WARNING", "ERROR"] = Field("INFO", description="Lowest level logged.")
    metrics: bool = Field(
        True,
        description="Per-request HTTP metrics (http_requests_total, http_request_duration_seconds); false "
        "leaves them out (GET /metrics still serves the service's own solve-time and cache counters).",
    )
    srt_target_general_g: float = Field(
        DEFAULT_TARGETS["general"],
        gt=0,
        lt=2,
        description="SRT target every result is checked against, general freight (PBS / NZ rule: 0.35) [g].",
    )
    srt_target_dangerous_goods_g: float = Field(
        DEFAULT_TARGETS["dangerous_goods"],
        gt=0,
        lt=2,
        description="SRT target for dangerous goods, e.g. tankers (PBS / NZ rule: 0.40) [g].",
    )

    @model_validator(mode="after")
    def _redis_needs_a_secret(self) -> Settings:
        if self.cache_backend == "redis" and self.cache_secret is None:
            raise ValueError(
                "ROLLOVER_CACHE_SECRET is required with ROLLOVER_CACHE_BACKEND=redis: every replica seals and "
                "verifies the shared entries with it (generate one with `openssl rand -hex 32`)"
            )
        return self

    @cached_property
    def _process_secret(self) -> bytes:
        return secrets.token_bytes(32)

    def cache_secret_bytes(self) -> bytes:
        """The HMAC key of the shared cache (a random one per process without Redis, where nothing is shared)."""
        if self.cache_secret is None:
            return self._process_secret
        return self.cache_secret.get_secret_value().encode()

    # ------------------------------------------------------------------ saved vehicles and fleets (catalog)
    database_url: str = Field(
        "sqlite:///./rollover.db",
        repr=False,  # may carry a password
        description="SQLAlchemy URL of the catalog database: `sqlite:///path` (embedded, one host) or "
        "`postgresql+psycopg://user:pass@host/db` (shared by several replicas).",
    )
    api_keys: SecretStr = Field(
        SecretStr(""),
        description="Comma-separated bearer keys allowed to save vehicles and fleets (each at least "
        f"{MIN_API_KEY_LENGTH} characters); empty disables the catalog. Never logged or stored.",
    )
    catalog_max_vehicles: int = Field(1000, ge=1, description="Saved vehicles per key [vehicles].")
    catalog_max_fleets: int = Field(100, ge=1, description="Fleets per key [fleets].")
    catalog_max_vehicle_bytes: int = Field(
        32 * 2**10, ge=256, description="Size of one saved vehicle body as stored (canonical JSON) [bytes]."
    )
    catalog_max_fleet_members: int = Field(100, ge=1, description="Vehicles in one fleet [vehicles].")

    # ------------------------------------------------------------------------------------------- jobs
    jobs_backend: Literal["inprocess", "redis"] = Field(
        "inprocess",
        description="inprocess: jobs run in threads of the API process, stored in its memory (nothing else to run). "
        "redis: jobs stored in Redis (ROLLOVER_REDIS_URL) and run by `python -m app.jobs.worker` processes.",
    )
    jobs_result_ttl_s: int = Field(
        24 * 3600, ge=1, description="How long a finished job and its result are kept (and an unfinished one) [s]."
    )
    jobs_workers: int = Field(1, ge=1, le=64, description="Worker threads of the inprocess backend [threads].")
    solve_threads: int = Field(
        default_factory=default_threads,
        ge=1,
        le=64,
        description="Threads that solve the blocks of one large batch (alignment, route, sweep, job part) in parallel; "
        "1 solves them one after another. Default: the process's cores, at most 4 [threads].",
    )
    jobs_max_bytes: int = Field(
        1024 * 2**20,
        ge=2**20,
        description="Bound of the inprocess backend's store: all jobs' inputs and compressed results [bytes].",
    )
    jobs_part_size: int | None = Field(
        None,
        ge=1,
        description="Units of work per part (rows, cases); default: the operation's (50,000 rows, 20,000 cases).",
    )
    jobs_lease_s: float = Field(
        60.0,
        gt=0,
        description="A running part that has not reported for this long is taken to have lost its worker and is "
        "queued again [s].",
    )
    jobs_max_attempts: int = Field(3, ge=1, le=20, description="Runs of one part before the job fails [runs].")
    jobs_part_timeout_s: float = Field(1800.0, gt=0, description="Longest run of one part [s].")
    jobs_queue: str = Field("rollover-jobs", pattern=r"^[A-Za-z0-9_.-]{1,64}$", description="RQ queue name.")

    @model_validator(mode="after")
    def _redis_jobs_need_a_secret(self) -> Settings:
        if self.jobs_backend == "redis" and self.cache_secret is None:
            raise ValueError(
                "ROLLOVER_CACHE_SECRET is required with ROLLOVER_JOBS_BACKEND=redis: the API and every worker seal "
                "and verify the stored jobs with it (generate one with `openssl rand -hex 32`)"
            )
        return self

    @field_validator("api_keys")
    @classmethod
    def _check_api_keys(cls, value: SecretStr) -> SecretStr:
        for i, key in enumerate(split_api_keys(value.get_secret_value())):
            if len(key) < MIN_API_KEY_LENGTH or any(c.isspace() for c in key):
                # the message names the key's position, never the key
                raise ValueError(
                    f"ROLLOVER_API_KEYS key #{i + 1} is shorter than {MIN_API_KEY_LENGTH} characters or contains "
                    "whitespace: use long random keys (python -c 'import secrets; print(secrets.token_urlsafe(32))')"
                )
        return value

    def api_key_list(self) -> list[str]:
        """The configured bearer keys (empty: the catalog is disabled)."""
        return split_api_keys(self.api_keys.get_secret_value())

    def default_targets(self) -> dict[str, float]:
        """The SRT targets checked when a request gives none: name -> minimum SRT [g]."""
        return {"general": self.srt_target_general_g, "dangerous_goods": self.srt_target_dangerous_goods_g}


@lru_cache
def get_settings() -> Settings:
    return Settings()
