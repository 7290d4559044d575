"""Alembic migration scripts of the catalog database (configured in code by ``app.db.migrate``)."""
