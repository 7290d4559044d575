"""Alembic migrations on both databases: empty -> head, idempotent, concurrent start-ups, down and up again; the
models and the migration agree; SQLite's durability pragmas; the documented ``python -m app.db upgrade``."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from pathlib import Path

from alembic import command
from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from sqlalchemy import inspect

from app.db import Database, current_revision, head_revision, upgrade
from app.db.migrate import alembic_config
from app.db.models import Base

ROOT = Path(__file__).resolve().parents[2]
TABLES = {"vehicles", "fleets", "fleet_members"}


def test_empty_database_migrates_to_head(database_url):
    db = Database(database_url)
    try:
        assert current_revision(db) is None
        assert not TABLES & set(inspect(db.engine).get_table_names())
        assert upgrade(db) == head_revision() == "0002"  # 0002: saved combinations
        names = set(inspect(db.engine).get_table_names())
        assert names >= TABLES | {"alembic_version"}
        columns = {c["name"] for c in inspect(db.engine).get_columns("vehicles")}
        assert columns == {"id", "owner", "title", "kind", "body", "version", "created_at", "updated_at"}
        # the migration creates exactly what the models declare (no drift between the two)
        with db.engine.connect() as connection:
            assert compare_metadata(MigrationContext.configure(connection), Base.metadata) == []
        # a second run (the next start-up) changes nothing
        assert upgrade(db) == head_revision()
    finally:
        db.dispose()


def test_downgrade_to_empty_and_up_again(database_url):
    db = Database(database_url)
    try:
        upgrade(db)
        config = alembic_config(db)
        with db.engine.begin() as connection:
            config.attributes["connection"] = connection
            command.downgrade(config, "base")
        assert not TABLES & set(inspect(db.engine).get_table_names())
        assert upgrade(db) == head_revision()
    finally:
        db.dispose()


def test_workers_starting_at_once_migrate_once(database_url):
    # four workers of one deployment start together on an empty database: each runs the upgrade; the lock
    # makes the first one migrate and the others find the schema at head (none fails on "table exists")
    errors: list[BaseException] = []
    revisions: list[str | None] = []

    def start() -> None:
        db = Database(database_url)
        try:
            revisions.append(upgrade(db))
        except BaseException as exc:
            errors.append(exc)
        finally:
            db.dispose()

    threads = [threading.Thread(target=start) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    assert errors == []
    assert revisions == [head_revision()] * 4


def test_sqlite_connections_are_wal_with_full_sync_and_foreign_keys(tmp_path):
    db = Database(f"sqlite:///{tmp_path / 'r.db'}")
    try:
        with db.engine.connect() as c:
            assert c.exec_driver_sql("PRAGMA journal_mode").scalar() == "wal"
            assert c.exec_driver_sql("PRAGMA synchronous").scalar() == 2  # FULL (0 OFF, 1 NORMAL, 2 FULL)
            assert c.exec_driver_sql("PRAGMA foreign_keys").scalar() == 1
            assert c.exec_driver_sql("PRAGMA busy_timeout").scalar() > 0
    finally:
        db.dispose()


def test_documented_upgrade_command(tmp_path):
    url = f"sqlite:///{tmp_path / 'cli.db'}"
    before = subprocess.run(
        [sys.executable, "-m", "app.db", "current", "--url", url], cwd=ROOT, capture_output=True, text=True
    )
    assert before.returncode == 0 and "at revision None" in before.stdout
    done = subprocess.run(
        [sys.executable, "-m", "app.db", "upgrade"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        env={**os.environ, "ROLLOVER_DATABASE_URL": url},
    )
    assert done.returncode == 0, done.stderr
    assert f"at revision {head_revision()}" in done.stdout
    db = Database(url)
    try:
        assert current_revision(db) == head_revision()
    finally:
        db.dispose()
