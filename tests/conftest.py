"""Fixtures shared by every test directory: a real PostgreSQL server (one per session, started on first use)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from .pg import PostgresServer, require_postgres_bindir


@pytest.fixture(scope="session")
def postgres_server() -> Iterator[PostgresServer]:
    """A real PostgreSQL server for the session; skipped locally without the binaries, failed under CI."""
    server = PostgresServer(require_postgres_bindir())
    try:
        yield server
    finally:
        server.stop()


@pytest.fixture(params=["sqlite", "postgresql"])
def database_url(request, tmp_path) -> str:
    """A fresh empty database: a SQLite file in a temporary directory, or a new database on the PostgreSQL
    server."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'rollover.db'}"
    request.applymarker(pytest.mark.postgres)
    return request.getfixturevalue("postgres_server").create_database()
