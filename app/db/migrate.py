"""Alembic, configured in code (no ``alembic.ini``): the scripts live in ``app/db/migrations/``.

``upgrade(db)`` brings the schema to the newest revision; the app's lifespan calls it at start-up and
``python -m app.db upgrade`` runs it by hand. Several workers or replicas starting at once are safe: the whole
upgrade is one transaction that first takes the database's write lock (SQLite ``BEGIN IMMEDIATE``) or a
PostgreSQL advisory lock, so the first one migrates and the others find the schema at head.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from sqlalchemy import text

from .session import Database, lock_key

if TYPE_CHECKING:
    from alembic.config import Config

# Alembic is imported inside the functions: the app imports this module at start-up whether or not the catalog is
# enabled, and Alembic (with Mako) adds about half a second to that.

MIGRATIONS = Path(__file__).resolve().parent / "migrations"
_MIGRATION_LOCK = "rollover:migrations"


def alembic_config(db: Database | None = None) -> Config:
    """An Alembic configuration pointing at the packaged migration scripts (and at ``db``'s URL)."""
    from alembic.config import Config

    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS))
    if db is not None:
        # ConfigParser interpolation: a literal % in a password must be doubled
        config.set_main_option("sqlalchemy.url", db.url.render_as_string(hide_password=False).replace("%", "%%"))
    return config


def head_revision() -> str:
    """The newest revision of the packaged scripts."""
    from alembic.script import ScriptDirectory

    head = ScriptDirectory.from_config(alembic_config()).get_current_head()
    assert head is not None
    return head


def current_revision(db: Database) -> str | None:
    """The revision the database is at (None for an empty database)."""
    from alembic.runtime.migration import MigrationContext

    with db.engine.connect() as connection:
        return MigrationContext.configure(connection).get_current_revision()


def upgrade(db: Database, revision: str = "head") -> str | None:
    """Migrate ``db`` to ``revision`` (default: the newest) in one locked transaction; returns the revision."""
    from alembic import command

    config = alembic_config(db)
    with db._writer.begin() as connection:  # BEGIN IMMEDIATE on SQLite
        if db.dialect == "postgresql":
            connection.execute(text("SELECT pg_advisory_xact_lock(:k)"), {"k": lock_key(_MIGRATION_LOCK)})
        config.attributes["connection"] = connection
        command.upgrade(config, revision)
    return current_revision(db)
