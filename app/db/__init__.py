"""The catalog database (saved vehicles and fleets): SQLAlchemy 2 models, sessions, Alembic migrations.

``ROLLOVER_DATABASE_URL`` chooses it: ``sqlite:///./rollover.db`` (default, a file in the working directory, WAL)
or ``postgresql+psycopg://user:pass@host:5432/db`` (shared by replicas). Migrate with ``python -m app.db upgrade``
(the app also does it at start-up).
"""

from __future__ import annotations

from .migrate import current_revision, head_revision, upgrade
from .session import Database

__all__ = ["Database", "current_revision", "head_revision", "upgrade"]
