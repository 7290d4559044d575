"""Fixtures shared by every test directory (a real PostgreSQL server, one per session, started on first use), and
the markers every test gets from where it is and what it uses.

Markers (registered in pyproject.toml): ``browser`` (tests/browser: the page in a real Chromium), ``server`` (a test
that starts a server process: uvicorn, redis-server, PostgreSQL), ``slow`` (left out of the fast lane,
``python -m pytest -m "not slow"``). Browser and server tests are slow by definition; a test that is slow for its
own reasons (large random samples, schemathesis, the generated client) says so with ``@pytest.mark.slow`` or a
module-level ``pytestmark``.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from .pg import PostgresServer, require_postgres_bindir

#: fixtures that start a server process (a test using one, directly or through another fixture, is a server test)
SERVER_FIXTURES = frozenset({"live_server", "redis_server", "postgres_server", "server"})


#: modules whose every test is slow and whose collection itself costs seconds (schemathesis builds the coverage
#: phase's cases of the whole spec while the module is collected: about 30 s in each test process)
SLOW_TO_COLLECT = frozenset({"test_schemathesis.py"})


def pytest_ignore_collect(collection_path, config: pytest.Config) -> bool | None:
    """The fast lane (``-m "not slow"``) does not collect what it would deselect anyway."""
    if collection_path.name in SLOW_TO_COLLECT and "not slow" in (config.getoption("markexpr") or ""):
        return True
    return None


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        parts = item.path.parts
        if "browser" in parts and "tests" in parts:
            item.add_marker(pytest.mark.browser)
            item.add_marker(pytest.mark.server)
        callspec = getattr(item, "callspec", None)
        on_postgres = callspec is not None and callspec.params.get("database_url") == "postgresql"
        if SERVER_FIXTURES.intersection(getattr(item, "fixturenames", ())) or on_postgres:
            item.add_marker(pytest.mark.server)
        if item.get_closest_marker("server") or item.get_closest_marker("redis"):
            item.add_marker(pytest.mark.slow)


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
