"""saved vehicles may be combinations: kind 'combination', and combination builder specs: 'combination_spec'

Revision ID: 0002
Revises: 0001
Create Date: 2026-12-01
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op

revision: str = "0002"
down_revision: str | None = "0001"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None


def upgrade() -> None:
    # batch mode: SQLite cannot alter a column or a check constraint in place (the table is copied)
    with op.batch_alter_table("vehicles") as batch:
        batch.drop_constraint(op.f("ck_vehicles_kind"), type_="check")
        batch.alter_column(
            "kind", type_=sa.String(length=16), existing_type=sa.String(length=8), existing_nullable=False
        )
        batch.create_check_constraint(
            op.f("ck_vehicles_kind"), "kind IN ('record', 'spec', 'combination', 'combination_spec')"
        )


def downgrade() -> None:
    op.execute(
        "DELETE FROM fleet_members WHERE vehicle_id IN "
        "(SELECT id FROM vehicles WHERE kind IN ('combination', 'combination_spec'))"
    )
    op.execute("DELETE FROM vehicles WHERE kind IN ('combination', 'combination_spec')")
    with op.batch_alter_table("vehicles") as batch:
        batch.drop_constraint(op.f("ck_vehicles_kind"), type_="check")
        batch.alter_column(
            "kind", type_=sa.String(length=8), existing_type=sa.String(length=16), existing_nullable=False
        )
        batch.create_check_constraint(op.f("ck_vehicles_kind"), "kind IN ('record', 'spec')")
