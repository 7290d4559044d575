"""The catalog database: one SQLAlchemy engine per app, sessions for reads and serialised writes.

A synchronous engine, used from FastAPI's worker threads (``run_in_threadpool``), not SQLAlchemy's asyncio
extension: the embedded default, SQLite, has only a blocking driver (aiosqlite is a thread around it), psycopg 3's
blocking mode is its most used path, and the same engine serves the lifespan's migrations, Alembic and the
``python -m app.db`` command. A catalog request is a handful of indexed statements, so the thread hop is cheap.

SQLite (``sqlite:///path``): every connection sets

* ``journal_mode=WAL``: readers never block the writer and the writer never blocks readers;
* ``synchronous=FULL``: the WAL is fsynced at every commit, so a write the client saw acknowledged survives a
  power loss or an OS crash as well as a killed process (``NORMAL`` in WAL mode is crash-safe against corruption
  but may roll back the last transactions after a power loss; "nothing lost" needs ``FULL``; the cost is one
  fsync per write, negligible at a catalog's write rate);
* ``foreign_keys=ON`` (off by default in SQLite): fleet members cannot point at a deleted vehicle;
* ``busy_timeout``: a writer waits for the lock (several workers on one file) instead of failing at once.

The driver's own transaction handling is switched off and SQLAlchemy emits ``BEGIN`` itself, ``BEGIN IMMEDIATE``
for writes: a write transaction takes the write lock before it reads, so a read-check-write sequence (count
limit, version check, membership check) cannot interleave with another writer, and never fails with
``SQLITE_BUSY_SNAPSHOT`` on lock upgrade.

PostgreSQL (``postgresql+psycopg://...``): writes of one owner are serialised by a transaction-scoped advisory
lock on the owner's hash (count limits and membership checks are exact under concurrency); the version check
itself is a conditional ``UPDATE ... WHERE version = :expected``.
"""

from __future__ import annotations

import hashlib
import sqlite3
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from sqlalchemy import Engine, create_engine, event, text
from sqlalchemy.engine import make_url
from sqlalchemy.orm import Session

#: SQLite waits this long for the write lock before giving up [ms]
SQLITE_BUSY_TIMEOUT_MS = 15_000
#: execution option that marks a write transaction (BEGIN IMMEDIATE on SQLite)
_WRITE = "rollover_write"


def _sqlite_pragmas(dbapi_connection: Any, _record: Any) -> None:
    dbapi_connection.isolation_level = None  # SQLAlchemy emits BEGIN itself (see _sqlite_begin)
    cursor = dbapi_connection.cursor()
    try:
        cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")  # first: the switch to WAL may wait too
        _switch_to_wal(cursor)
        cursor.execute("PRAGMA synchronous=FULL")
        cursor.execute("PRAGMA foreign_keys=ON")
    finally:
        cursor.close()


def _switch_to_wal(cursor: Any) -> None:
    """``PRAGMA journal_mode=WAL``, retried while another connection holds the lock it needs. On a new file, workers
    starting at once each read the header and then want the exclusive lock to switch: SQLite reports that deadlock
    at once as "database is locked" without calling the busy handler (7 of 40 runs of four threads here), so the
    busy timeout alone does not cover it."""
    deadline = time.monotonic() + SQLITE_BUSY_TIMEOUT_MS / 1000
    delay = 0.005
    while True:
        try:
            cursor.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as exc:
            if "locked" not in str(exc) or time.monotonic() + delay > deadline:
                raise
        time.sleep(delay)
        delay = min(2 * delay, 0.2)


def _sqlite_begin(connection: Any) -> None:
    connection.exec_driver_sql("BEGIN IMMEDIATE" if connection.get_execution_options().get(_WRITE) else "BEGIN")


def lock_key(name: str) -> int:
    """A signed 64-bit advisory-lock key for ``name`` (PostgreSQL ``pg_advisory_xact_lock``)."""
    return int.from_bytes(hashlib.sha256(name.encode()).digest()[:8], "big", signed=True)


class Database:
    """The catalog's engine and its two kinds of session.

    Parameters
    ----------
    url : str
        SQLAlchemy URL: ``sqlite:///./rollover.db`` or ``postgresql+psycopg://user:pass@host:5432/db``.
    """

    def __init__(self, url: str) -> None:
        self.url = make_url(url)
        kwargs: dict[str, Any] = {"pool_pre_ping": True}
        if self.url.get_backend_name() == "sqlite":
            kwargs = {}
        self.engine: Engine = create_engine(self.url, **kwargs)
        self.dialect = self.engine.dialect.name
        if self.dialect == "sqlite":
            event.listen(self.engine, "connect", _sqlite_pragmas)
            event.listen(self.engine, "begin", _sqlite_begin)
        self._writer = self.engine.execution_options(**{_WRITE: True})

    @property
    def safe_url(self) -> str:
        """The URL with its password masked (for logs)."""
        return self.url.render_as_string(hide_password=True)

    @contextmanager
    def read(self) -> Iterator[Session]:
        """A session for reads (one transaction, rolled back at the end)."""
        with Session(self.engine, expire_on_commit=False) as session, session.begin():
            yield session

    @contextmanager
    def write(self, lock: str | None = None) -> Iterator[Session]:
        """A session whose work is one transaction, committed at the end or rolled back on any exception.

        ``lock`` (the owner) serialises the writes that share it: SQLite's ``BEGIN IMMEDIATE`` serialises every
        write anyway; on PostgreSQL a transaction-scoped advisory lock on ``lock`` is taken first.
        """
        with Session(self._writer, expire_on_commit=False) as session, session.begin():
            if lock is not None and self.dialect == "postgresql":
                session.execute(text("SELECT pg_advisory_xact_lock(:k)"), {"k": lock_key(lock)})
            yield session

    def dispose(self) -> None:
        self.engine.dispose()
